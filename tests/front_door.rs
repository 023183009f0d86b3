//! Value tests of the front door (`material.filtered(footprint, method)`) against independent
//! references: f64 quadrature of the filtered density where the method is an exact filter
//! (Beckmann `Gaussian`, `Rect`), the published closed forms written out here where it is an
//! approximation (GGX `Gaussian` = TK19's `A + 2 Sigma`, `Projected` = TK21), and eq. 19's
//! peak identity for `Proxy`. Footprints are chosen both with every clamp inactive (so the
//! comparison is with the unclamped filter) and with one clamp active at a time (so the
//! reference uses the clamped kernel, computed here from the rule's definition).

use filtered_ndf::f32 as s;
use filtered_ndf::f32::{Ndf as _, filter::Filterable as _};
use filtered_ndf::f64::prelude::*;
use filtered_ndf::f64::{Covariance, Vec2, Vec3};
use filtered_ndf::testing::box_reference::ggx_box;
use filtered_ndf::testing::gaussian_reference;
use filtered_ndf::testing::quadrature::Tolerance;
use glam::DMat2;
use std::f64::consts::PI;

/// A rotated anisotropic roughness matrix `R diag(ax^2, ay^2) R^T`.
fn rotated(ax: f64, ay: f64, phi: f64) -> RoughnessMatrix {
    let (c, s) = (phi.cos(), phi.sin());
    let (l1, l2) = (ax * ax, ay * ay);
    RoughnessMatrix::new(
        c * c * l1 + s * s * l2,
        c * s * (l1 - l2),
        s * s * l1 + c * c * l2,
    )
    .unwrap()
}

/// `Sigma = sigma^2 (u u^T + v v^T)` (TK19 section 2.2), written out.
fn kernel_of(u: Vec2, v: Vec2, sigma: f64) -> Covariance {
    let k = sigma * sigma;
    Covariance::new(
        k * (u.x * u.x + v.x * v.x),
        k * (u.x * u.y + v.x * v.y),
        k * (u.y * u.y + v.y * v.y),
    )
}

fn mat(r: &RoughnessMatrix) -> DMat2 {
    r.to_mat2()
}

fn unit(x: f64, y: f64) -> Vec3 {
    Vec3::new(x, y, 1.0).normalize()
}

/// A small footprint: extent 0.015 < lambda = 1 and kernel roughness^2 2 lambda_max < 4e-4,
/// far below kappa = 0.18, so every clamp of `Gaussian::TK19` is inactive.
fn small_footprint() -> (Vec2, Vec2) {
    (Vec2::new(0.012, 0.004), Vec2::new(-0.003, 0.009))
}

#[test]
fn gaussian_beckmann_is_the_convolution_of_the_lobe_with_the_pixel_kernel() {
    let a = rotated(0.02, 0.008, 0.7);
    let (u, v) = small_footprint();
    let lobe = Beckmann::new(a).filtered(Footprint::from_slope_derivatives(u, v), Gaussian::TK19);
    let kernel = kernel_of(u, v, 0.5);
    // Slopes from the peak to about three filtered widths out along both axes.
    for (x, y) in [
        (0.0, 0.0),
        (0.01, 0.0),
        (0.0, -0.012),
        (0.02, 0.015),
        (-0.03, 0.01),
    ] {
        let sl = Vec2::new(x, y);
        let r = gaussian_reference::beckmann(a, kernel, sl, Tolerance::relative(1e-11));
        let got = lobe.p22(sl);
        // The reference's own error estimate plus the f64 evaluation of the closed form:
        // A + 2 Sigma and its LDL form to a few ulps (relative 1e-15 each), amplified by the
        // exponent x <= 12 here: 1e-13 relative bounds it.
        let tol = r.error + 1e-13 * r.value;
        assert!(
            (got - r.value).abs() <= tol,
            "s = {sl}: {got} vs {} +- {tol}",
            r.value
        );
    }
}

#[test]
fn gaussian_applies_kappa_to_the_kernel_before_filtering() {
    // An isotropic footprint of 0.8 slope units per pixel: Sigma = 0.25 * 0.64 I = 0.16 I, so
    // 2 lambda = 0.32 > kappa = 0.18 and TK19 eq. 1 clamps the kernel to Sigma' = 0.09 I
    // (extent 0.8 / sqrt(2) * ... < lambda = 1: the extent rule is inactive).
    let a = Isotropic::new(0.05).unwrap();
    let fp = Footprint::from_slope_derivatives(Vec2::new(0.8, 0.0), Vec2::new(0.0, 0.8));
    assert!(fp.max_extent() < 1.0);
    let lobe = Beckmann::new(a).filtered(fp, Gaussian::TK19);
    let clamped = Covariance::new(0.09, 0.0, 0.09);
    for sl in [Vec2::ZERO, Vec2::new(0.2, 0.1), Vec2::new(-0.5, 0.3)] {
        let r = gaussian_reference::beckmann(a, clamped, sl, Tolerance::relative(1e-11));
        let got = lobe.p22(sl);
        assert!(
            (got - r.value).abs() <= r.error + 1e-13 * r.value,
            "s = {sl}: {got} vs {}",
            r.value
        );
    }
    // Without kappa (KHPL16) the full kernel is used.
    let full = Beckmann::new(a).filtered(fp, Gaussian::KHPL16);
    let r = gaussian_reference::beckmann(
        a,
        Covariance::new(0.16, 0.0, 0.16),
        Vec2::ZERO,
        Tolerance::relative(1e-11),
    );
    assert!((full.p22(Vec2::ZERO) - r.value).abs() <= r.error + 1e-13 * r.value);
}

#[test]
fn gaussian_ggx_is_tk19_a_plus_two_sigma() {
    let a = rotated(0.03, 0.01, -0.4);
    let (u, v) = small_footprint();
    let lobe = Ggx::new(a).filtered(Footprint::from_slope_derivatives(u, v), Gaussian::TK19);
    let k = kernel_of(u, v, 0.5);
    let ap = mat(&a) + 2.0 * DMat2::from_cols_array(&[k.s11, k.s12, k.s12, k.s22]);
    let det = ap.determinant();
    let inv = ap.inverse();
    for h in [
        unit(0.0, 0.0),
        unit(0.02, -0.01),
        unit(-0.05, 0.04),
        unit(0.3, 0.2),
    ] {
        // D(m) = 1 / (pi sqrt(det A') (m_xy^T A'^-1 m_xy + m_z^2)^2) (TK19 supplement).
        let mxy = Vec2::new(h.x, h.y);
        let t = mxy.dot(inv * mxy) + h.z * h.z;
        let want = 1.0 / (PI * det.sqrt() * t * t);
        let got = lobe.d(h);
        // Two f64 evaluations of the same closed form: a few ulps each, times the
        // condition of the quadratic form (cond A' < 10 here): 1e-13.
        assert!(
            (got - want).abs() <= 1e-13 * want,
            "h = {h}: {got} vs {want}"
        );
    }
}

#[test]
fn projected_is_tk21_in_projected_space() {
    let a = rotated(0.2, 0.05, 0.9);
    let (u, v) = (Vec2::new(0.05, 0.01), Vec2::new(-0.02, 0.04));
    let lobe = Ggx::new(a).filtered(Footprint::from_slope_derivatives(u, v), Projected::TK21);
    // TK21 Listing 1, with explicit 2x2 inverses: P = A (I - A)^-1, P' = P + 2 Sigma,
    // A' = P' (I + P')^-1.
    let k = kernel_of(u, v, 0.5);
    let am = mat(&a);
    let p = am * (DMat2::IDENTITY - am).inverse();
    let pp = p + 2.0 * DMat2::from_cols_array(&[k.s11, k.s12, k.s12, k.s22]);
    let want = pp * (DMat2::IDENTITY + pp).inverse();
    let got = lobe.roughness.to_mat2();
    for (g, w) in got.to_cols_array().iter().zip(want.to_cols_array()) {
        // Both are rational functions of the entries evaluated in f64 (cond(I - A) < 1.1):
        // a few ulps of the largest entry.
        assert!((g - w).abs() <= 1e-14 * want.x_axis.x.abs().max(want.y_axis.y.abs()));
    }
}

#[test]
fn rect_is_the_box_average_over_the_bounding_rectangle() {
    let a = AxisAligned::new(0.02, 0.05).unwrap();
    let (u, v) = (Vec2::new(0.03, -0.01), Vec2::new(0.02, 0.04));
    let lobe = Ggx::new(a).filtered(Footprint::from_slope_derivatives(u, v), Rect::KHPL16);
    // KHPL16 section 5.3: half extents (|u| + |v|) / 2 per axis, below lambda = 1.
    let half = (u.abs() + v.abs()) * 0.5;
    assert_eq!(lobe.half_extent, half);
    for sl in [Vec2::ZERO, Vec2::new(0.03, 0.02), Vec2::new(-0.2, 0.1)] {
        let r = ggx_box(a, sl, half, Tolerance::relative(1e-12));
        let got = lobe.p22(sl);
        // d_rect / p22_rect are exact to a few f64 ulps (tests/ggx_rect.rs): 1e-12 relative.
        assert!(
            (got - r.value).abs() <= r.error + 1e-12 * r.value,
            "s = {sl}: {got} vs {}",
            r.value
        );
    }
    // f32 through the same door: within about 4 f32 roundings of the f64 reference (the
    // rounding of the inputs, amplified at most 2x by the average, plus one of the result).
    let a32 = s::AxisAligned::new(0.02, 0.05).unwrap();
    let fp32 = s::Footprint::from_slope_derivatives(u.as_vec2(), v.as_vec2());
    let lobe32 = s::Ggx::new(a32).filtered(fp32, s::filter::Rect::KHPL16);
    let r = ggx_box(a, Vec2::ZERO, half, Tolerance::relative(1e-12));
    let got = lobe32.p22(glam::Vec2::ZERO) as f64;
    assert!((got - r.value).abs() <= 4.0 * f32::EPSILON as f64 * r.value);
}

#[test]
fn proxy_peak_is_the_box_filtered_peak() {
    // Eq. 19 holds exactly for an isotropic lobe and a square rectangle.
    let a = Isotropic::new(0.01).unwrap();
    let (u, v) = (Vec2::new(0.02, 0.0), Vec2::new(0.0, 0.02));
    let fp = Footprint::from_slope_derivatives(u, v);
    let lobe = Ggx::new(a).filtered(fp, Proxy::KHPL16);
    // The bounding rectangle of the one-pixel parallelogram: half extents (|u| + |v|) / 2.
    let half = Vec2::splat(0.01);
    let r = ggx_box(a.into(), Vec2::ZERO, half, Tolerance::relative(1e-12));
    let peak = lobe.d(Vec3::Z);
    assert!(
        (peak - r.value).abs() <= r.error + 1e-12 * r.value,
        "{peak} vs {}",
        r.value
    );
}

#[test]
fn deferred_filter_is_tk19_eq_4_and_always_a_valid_roughness() {
    let (dn_u, dn_v) = (Vec3::new(0.1, 0.2, 0.0), Vec3::new(0.0, 0.05, -0.1));
    let alpha = 0.04;
    // TK19 eq. 4 (Listing 2): alpha_bar^2 = saturate(alpha^2 + min(2 sigma^2 (|dn_u|^2 +
    // |dn_v|^2), kappa)) with sigma^2 = 0.25, kappa = 0.18.
    let want = (alpha * alpha + (0.5 * (dn_u.length_squared() + dn_v.length_squared())).min(0.18))
        .min(1.0)
        .sqrt();
    let got = presets::TK19_TRACE.filter(alpha, dn_u, dn_v).alpha();
    assert!((got - want).abs() <= 1e-15);
    // A zero roughness on a flat G-buffer: the engines' formula gives 0, which no NDF
    // accepts; the front door gives the smallest valid roughness.
    assert_eq!(presets::TK19_TRACE.apply(0.0, Vec3::ZERO, Vec3::ZERO), 0.0);
    for (_, preset) in presets::ALL {
        for alpha in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-30, 0.5] {
            let r = preset.filter(alpha, Vec3::ZERO, Vec3::ZERO);
            assert_eq!(Isotropic::new(r.alpha()), Ok(r));
            assert!(Ggx::new(r).d(Vec3::Z).is_finite());
        }
    }
}

#[test]
fn zero_footprint_gives_the_unfiltered_lobe() {
    let a = AxisAligned::new(0.02, 0.05).unwrap();
    let h = unit(0.01, -0.02);
    let ggx = Ggx::new(a);
    let unfiltered = ggx.d(h);
    let fp = Footprint::ZERO;
    let close = |x: f64| (x - unfiltered).abs() <= 1e-14 * unfiltered;
    assert!(close(ggx.filtered(fp, Gaussian::TK19).d(h)));
    assert!(close(ggx.filtered(fp, Projected::TK21).d(h)));
    assert!(close(ggx.filtered(fp, Rect::KHPL16).d(h)));
    assert!(close(ggx.filtered(fp, Proxy::KHPL16).d(h)));
    let b = Beckmann::new(a);
    let ub = b.d(h);
    assert!((b.filtered(fp, Gaussian::TK19).d(h) - ub).abs() <= 1e-14 * ub);
}

#[test]
fn front_door_never_returns_nan_for_bad_footprints() {
    // The contract (src/contract.rs): whatever the footprint (NaN, infinite, huge, zero,
    // degenerate), every method gives a lobe whose evaluations at finite arguments are finite
    // and non-negative, and whose Lambda is non-negative (possibly +inf at grazing).
    const NAN: f64 = f64::NAN;
    const INF: f64 = f64::INFINITY;
    let footprints = [
        Footprint::ZERO,
        Footprint::from_slope_derivatives(Vec2::new(NAN, 0.0), Vec2::ZERO),
        Footprint::from_slope_derivatives(Vec2::new(INF, 0.0), Vec2::new(0.0, -INF)),
        Footprint::from_slope_derivatives(Vec2::new(1e300, 1e300), Vec2::new(-1e300, 1e300)),
        Footprint::from_slope_derivatives(Vec2::new(1e-300, 0.0), Vec2::new(1e-300, 0.0)),
        Footprint::from_slope_derivatives(Vec2::new(3.0, 1.0), Vec2::new(6.0, 2.0)),
    ];
    let dirs = [
        Vec3::Z,
        unit(0.3, -0.2),
        unit(1e3, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
    ];
    let check = |what: &str, d: f64, l: f64| {
        assert!(d.is_finite() && d >= 0.0, "{what}: d = {d}");
        assert!(!l.is_nan() && l >= 0.0, "{what}: lambda = {l}");
    };
    // A NaN argument contributes nothing (the NaN policy of `Ndf`): d = 0, lambda = +inf.
    let nan_dir = Vec3::new(NAN, 0.0, 1.0);
    let nan_policy = |what: &str, d: f64, l: f64| {
        assert_eq!(d, 0.0, "{what}: d(NaN)");
        assert_eq!(l, f64::INFINITY, "{what}: lambda(NaN)");
    };
    for fp in footprints {
        for alpha in [1e-4, 0.3] {
            let iso = Isotropic::new(alpha).unwrap();
            let ggx = Ggx::new(iso);
            let beck = Beckmann::new(iso);
            let l = ggx.filtered(fp, Gaussian::TK19);
            nan_policy("gaussian ggx", l.d(nan_dir), l.lambda(nan_dir));
            let l = beck.filtered(fp, Gaussian::TK19);
            nan_policy("gaussian beckmann", l.d(nan_dir), l.lambda(nan_dir));
            let l = ggx.filtered(fp, ExactGaussian::KHPL16);
            nan_policy("exact ggx", l.d(nan_dir), l.lambda(nan_dir));
            let l = ggx.filtered(fp, Projected::TK21);
            nan_policy("projected", l.d(nan_dir), l.lambda(nan_dir));
            let l = ggx.filtered(fp, Rect::KHPL16);
            nan_policy("rect", l.d(nan_dir), l.lambda(nan_dir));
            let l = ggx.filtered(fp, Proxy::KHPL16);
            nan_policy("proxy", l.d(nan_dir), l.lambda(nan_dir));
            for h in dirs {
                let l = ggx.filtered(fp, Gaussian::TK19);
                check("gaussian ggx", l.d(h), l.lambda(h));
                let l = beck.filtered(fp, Gaussian::TK19);
                check("gaussian beckmann", l.d(h), l.lambda(h));
                let l = ggx.filtered(fp, ExactGaussian::KHPL16);
                check("exact ggx", l.d(h), l.lambda(h));
                let l = ggx.filtered(fp, Projected::TK21);
                check("projected", l.d(h), l.lambda(h));
                let l = ggx.filtered(fp, Rect::KHPL16);
                check("rect", l.d(h), l.lambda(h));
                let l = ggx.filtered(fp, Proxy::KHPL16);
                check("proxy", l.d(h), l.lambda(h));
            }
        }
    }
}
