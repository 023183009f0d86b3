//! Footprint constructors, the bounding rectangle and its Gaussian equivalent, and the
//! clamping rules: each behaves as documented, including on NaN / inf / zero / huge input.

use filtered_ndf::f32 as s;
use filtered_ndf::f64 as d;
use filtered_ndf::f64::Ndf as _;
use filtered_ndf::testing::linalg::Sym2;
use filtered_ndf::testing::quadrature::{Tolerance, integrate_2d};
use glam::{DVec2, DVec3, Vec2, Vec3};
use proptest::prelude::*;

fn min_eig(c: d::Covariance) -> f64 {
    c.eigenvalues().0
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn projected_derivatives_in_slope_match_finite_differences(
        px in -0.6f64..0.6, py in -0.6f64..0.6,
        u in prop::array::uniform2(-1.0f64..1.0), v in prop::array::uniform2(-1.0f64..1.0),
    ) {
        // Central differences of s(p) = slope_from_projected(p) with step 1e-6: truncation
        // O(h^2 |s'''|) ~ 1e-12 and rounding ~ 1e-16 / 1e-6 = 1e-10, relative to |J du|; the
        // bound 1e-7 (relative to the largest |J|) leaves ample room.
        let p = DVec2::new(px, py);
        let h = d::footprint::slope::sphere_from_projected(p);
        let (du, dv) = (DVec2::from(u), DVec2::from(v));
        let fp = d::Footprint::from_projected_derivatives_in_slope(h, du, dv);
        let eps = 1e-6;
        let fd = |dir: DVec2| {
            (d::footprint::slope::slope_from_projected(p + dir * eps) - d::footprint::slope::slope_from_projected(p - dir * eps)) / (2.0 * eps)
        };
        let scale = 1.0 / h.z.powi(3);
        prop_assert!((fp.dh_u - fd(du)).length() <= 1e-7 * scale * (1.0 + du.length()));
        prop_assert!((fp.dh_v - fd(dv)).length() <= 1e-7 * scale * (1.0 + dv.length()));
        // TK19 keeps the disk derivatives themselves.
        let t = d::Footprint::from_projected_derivatives(du, dv);
        prop_assert_eq!((t.dh_u, t.dh_v), (du, dv));
    }

    #[test]
    fn half_vector_derivatives_match_finite_differences_of_the_slope_map(
        theta in 0.0f64..1.4, phi in 0.0f64..6.3,
        a in prop::array::uniform3(-1.0f64..1.0), b in prop::array::uniform3(-1.0f64..1.0),
        scale in prop_oneof![Just(1.0), 1e-3f64..1e3],
    ) {
        // Central differences of s(h) = slope_from_sphere(h) along the tangent derivatives
        // (the unit half vector moved to `(h + t dh) / |h + t dh|`) with step 1e-6:
        // truncation O(t^2 |s'''|) ~ 1e-12 and rounding ~ 1e-16 / 1e-6 = 1e-10, relative to
        // |J| ~ 1 / h_z^2; the bound 1e-7 of the largest |J| leaves ample room.
        let h = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
        let tangent = |w: [f64; 3]| {
            let w = DVec3::from(w);
            w - h * h.dot(w)
        };
        let (dx, dy) = (tangent(a), tangent(b));
        // Only the direction of `h` counts (scaled here by `scale`).
        let fp = d::Footprint::from_half_vector_derivatives(h * scale, dx, dy);
        let t = 1e-6;
        let fd = |d: DVec3| {
            let s = |k: f64| d::footprint::slope::slope_from_sphere((h + d * k).normalize());
            (s(t) - s(-t)) / (2.0 * t)
        };
        let jmax = 1.0 / (h.z * h.z);
        prop_assert!((fp.dh_u - fd(dx)).length() <= 1e-7 * jmax * (1.0 + dx.length()), "{fp:?}");
        prop_assert!((fp.dh_v - fd(dy)).length() <= 1e-7 * jmax * (1.0 + dy.length()), "{fp:?}");
        // The radial part of a derivative is dropped: adding a multiple of h changes nothing
        // (to rounding: 1e-14 of the largest |J|).
        let fr = d::Footprint::from_half_vector_derivatives(h, dx + h * 0.7, dy - h * 0.3);
        let fu = d::Footprint::from_half_vector_derivatives(h, dx, dy);
        prop_assert!((fr.dh_u - fu.dh_u).length() <= 1e-14 * jmax * (1.0 + dx.length()));
        prop_assert!((fr.dh_v - fu.dh_v).length() <= 1e-14 * jmax * (1.0 + dy.length()));
        // The same slope change as the projected-disk derivatives dp = dh_xy through
        // J(perp->par) (a second formula path; 1e-13 of the largest |J| for the rounding of
        // both).
        let fpr = d::Footprint::from_projected_derivatives_in_slope(
            h, DVec2::new(dx.x, dx.y), DVec2::new(dy.x, dy.y),
        );
        prop_assert!((fpr.dh_u - fu.dh_u).length() <= 1e-13 * jmax * (1.0 + dx.length()));
        prop_assert!((fpr.dh_v - fu.dh_v).length() <= 1e-13 * jmax * (1.0 + dy.length()));
    }

    #[test]
    fn normal_differences_have_the_norm_of_tk19_eq3(
        a in prop::array::uniform3(-1.0f64..1.0), b in prop::array::uniform3(-1.0f64..1.0),
        t in 0.0f64..0.8,
    ) {
        // Neighbour normals tilted from n = z; eq. 3: |dn_bar_perp| = |n_u - n|.
        let tilt = |w: [f64; 3]| {
            let w = DVec3::from(w);
            let w = DVec3::new(w.x, w.y, 0.0).normalize_or(DVec3::X);
            (DVec3::Z * (1.0 - t * t).sqrt() + w * t).normalize()
        };
        let (nu, nv) = (tilt(a), tilt(b));
        let (dnu, dnv) = (nu - DVec3::Z, nv - DVec3::Z);
        let fp = d::Footprint::from_normal_differences(dnu, dnv);
        // 1e-12: f64 rounding of a unit-scale computation.
        prop_assert!((fp.dh_u.length() - dnu.length()).abs() <= 1e-12);
        prop_assert!((fp.dh_v.length() - dnv.length()).abs() <= 1e-12);
        // Same direction as the tangential part of the difference.
        prop_assert!(fp.dh_u.perp_dot(DVec2::new(dnu.x, dnu.y)).abs() <= 1e-12);
        prop_assert!(fp.dh_u.dot(DVec2::new(dnu.x, dnu.y)) >= 0.0);
        // Trace identity of TK19 eq. 4.
        let tr = fp.covariance(0.5).trace();
        prop_assert!((tr - 0.25 * (dnu.length_squared() + dnv.length_squared())).abs() <= 1e-12);
        // World-space variant with a rotated frame agrees.
        let (ct, st) = (0.3f64.cos(), 0.3f64.sin());
        let (tw, bw) = (DVec3::new(ct, st, 0.0), DVec3::new(-st, ct, 0.0));
        let world = |v: DVec3| tw * v.x + bw * v.y + DVec3::Z * v.z;
        let fw = d::Footprint::from_world_normal_differences(tw, bw, DVec3::Z, world(dnu), world(dnv));
        prop_assert!((fw.dh_u - fp.dh_u).length() <= 1e-12 && (fw.dh_v - fp.dh_v).length() <= 1e-12);
    }

    #[test]
    fn bounding_rect_contains_the_parallelogram_and_its_gaussian_bounds_half_of_sigma(
        u in prop::array::uniform2(-1.0f64..1.0), v in prop::array::uniform2(-1.0f64..1.0),
    ) {
        let fp = d::Footprint::from_slope_derivatives(DVec2::from(u), DVec2::from(v));
        let r = fp.bounding_rect();
        let mut reach = DVec2::ZERO;
        for (a, b) in [(0.5, 0.5), (0.5, -0.5), (-0.5, 0.5), (-0.5, -0.5)] {
            let vtx = fp.dh_u * a + fp.dh_v * b;
            // The vertices lie inside (1e-15: the vertex sums' rounding, inputs below 1).
            prop_assert!(vtx.abs().cmple(r.half_extent + 1e-15).all());
            prop_assert!(vtx.length() <= fp.max_extent() + 1e-15);
            reach = reach.max(vtx.abs());
        }
        // Tight: on each axis the farthest vertex touches the rectangle.
        prop_assert!((reach - r.half_extent).abs().max_element() <= 1e-15, "{reach} {:?}", r);
        prop_assert!(r.half_extent.max_element() <= fp.max_extent() + 1e-15);
        let sig = fp.covariance(0.5);
        let sr = r.covariance(0.5);
        // Per-axis variance dominates; 2 Sigma_R - Sigma is PSD (documented); Sigma_R - Sigma
        // need not be.
        prop_assert!(sr.s11 >= sig.s11 - 1e-15 && sr.s22 >= sig.s22 - 1e-15);
        prop_assert!(min_eig(sr * 2.0 + sig * -1.0) >= -1e-14);
        // sigma = 1/2 gives diag(h^2) (GDC listing).
        prop_assert!((sr.s11 - r.half_extent.x.powi(2)).abs() <= 1e-15);
    }

    #[test]
    fn clamp_eigenvalues_keeps_eigenvectors_and_clamps_to_zero_and_max(
        l1 in -2.0f64..2.0, l2 in -2.0f64..2.0, phi in 0.0f64..3.2, c in 0.0f64..2.0,
    ) {
        // Any symmetric input, definite or not: the eigenvalues clamped to [0, c] with the
        // eigenvectors kept, against the test side's own decomposition (`testing::linalg`).
        let m = Sym2::from_eigen(l1, l2, phi);
        let k = d::Covariance::new(m.a11, m.a12, m.a22);
        let kc = k.clamp_eigenvalues(c);
        let want = m.eigen().map(|l| l.clamp(0.0, c));
        // 1e-12: rounding of the unit-scale eigen computations (a few ulps of entries <= 2)
        // divided by the eigenvalue gap, which the clamp caps (the result is
        // `c_min I + (c_max - c_min) P_max` and `c_max - c_min <= lambda_max - lambda_min`).
        let err = (kc.s11 - want.a11).abs().max((kc.s12 - want.a12).abs()).max((kc.s22 - want.a22).abs());
        prop_assert!(err <= 1e-12, "{kc:?} vs {want:?}");
        let (a, b) = kc.eigenvalues();
        prop_assert!(a >= 0.0 && b <= c + 1e-12, "{kc:?}");
        // Commutes with the input (same eigenvectors): K Kc - Kc K = 0.
        let comm = k.s11 * kc.s12 + k.s12 * kc.s22 - (kc.s11 * k.s12 + kc.s12 * k.s22);
        prop_assert!(comm.abs() <= 1e-12);
    }
}

#[test]
fn clamp_eigenvalues_of_an_indefinite_input_drops_its_negative_part() {
    // [[0, 1], [1, 0]] has eigenvalues +1 (along (1, 1)) and -1: clamped to [0, 0.5] it is
    // 0.5 (1, 1)(1, 1)^T / 2 = [[0.25, 0.25], [0.25, 0.25]] (the fast path once returned it
    // unchanged, since its trace 0 is within the bound). Both precisions; 4 ulps of 0.25.
    let c = d::Covariance::new(0.0, 1.0, 0.0).clamp_eigenvalues(0.5);
    for x in [c.s11, c.s12, c.s22] {
        assert!((x - 0.25).abs() <= 4.0 * f64::EPSILON * 0.25, "{c:?}");
    }
    let c = s::Covariance::new(0.0, 1.0, 0.0).clamp_eigenvalues(0.5);
    for x in [c.s11, c.s12, c.s22] {
        assert!((x - 0.25).abs() <= 4.0 * f32::EPSILON * 0.25, "{c:?}");
    }
    // Negative semi-definite: nothing left. A negative variance alone: dropped.
    assert_eq!(
        d::Covariance::new(-1.0, 0.5, -2.0).clamp_eigenvalues(1.0),
        d::Covariance::ZERO
    );
    let c = d::Covariance::new(-1.0, 0.0, 0.3).clamp_eigenvalues(1.0);
    assert!(c.s11 == 0.0 && c.s12 == 0.0 && (c.s22 - 0.3).abs() <= 4.0 * f64::EPSILON * 0.3);
    // A PSD input within the bound is returned bit for bit.
    let k = s::Covariance::new(0.01, 0.003, 0.02);
    assert_eq!(k.clamp_eigenvalues(0.09), k);
}

#[test]
fn half_vector_derivatives_bad_input() {
    // At the pole J(o->par) = -I: the slope moves against the tangential derivative.
    let fp = d::Footprint::from_half_vector_derivatives(DVec3::Z, DVec3::X * 0.1, DVec3::Y);
    assert_eq!(fp.dh_u, DVec2::new(-0.1, 0.0));
    assert_eq!(fp.dh_v, DVec2::new(0.0, -1.0));
    // Zero or non-finite h: no direction, the zero footprint.
    let (x, y) = (Vec3::X * 0.01, Vec3::Y * 0.02);
    for h in [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, f32::INFINITY, 1.0),
    ] {
        assert_eq!(
            s::Footprint::from_half_vector_derivatives(h, x, y),
            s::Footprint::ZERO
        );
    }
    // The NaN policy: a NaN derivative entry counts as 0 (the other entries still count); an
    // infinite one gives an infinite entry, which the clamp rules saturate.
    let fp = s::Footprint::from_half_vector_derivatives(Vec3::Z, Vec3::new(f32::NAN, 0.0, 0.0), y);
    assert_eq!(
        fp,
        s::Footprint::from_half_vector_derivatives(Vec3::Z, Vec3::ZERO, y)
    );
    assert_ne!(fp, s::Footprint::ZERO);
    let fp =
        s::Footprint::from_half_vector_derivatives(Vec3::Z, Vec3::new(f32::INFINITY, 0.0, 0.0), y);
    assert!(
        fp.dh_u.x.is_infinite() && !fp.dh_u.is_nan() && !fp.dh_v.is_nan(),
        "{fp:?}"
    );
    // Zero derivatives: the zero footprint.
    let fp = s::Footprint::from_half_vector_derivatives(
        Vec3::new(0.3, 0.1, 0.9),
        Vec3::ZERO,
        Vec3::ZERO,
    );
    assert_eq!(fp, s::Footprint::ZERO);
    // Grazing and back-facing h: clamped to h_z = 1e-6 at constant azimuth, huge and finite
    // (|J(o->par) e_y| = 1 / h_z there).
    for h in [
        Vec3::new(0.6, 0.8, 0.0),
        Vec3::new(0.6, 0.8, -0.5),
        -Vec3::Z,
    ] {
        let fp = s::Footprint::from_half_vector_derivatives(h, x, y);
        assert!(fp.dh_u.is_finite() && fp.dh_v.is_finite(), "{h}: {fp:?}");
        assert!(fp.dh_u.length().max(fp.dh_v.length()) > 1e3, "{h}: {fp:?}");
    }
    // Huge finite derivatives: never NaN; a product beyond F::MAX is an infinite entry (the
    // NaN policy), which the clamp rules saturate to extent lambda.
    let fp = s::Footprint::from_half_vector_derivatives(
        Vec3::new(0.6, 0.8, 1e-3),
        Vec3::splat(1e30),
        Vec3::new(-1e38, 1e38, 0.0),
    );
    assert!(!fp.dh_u.is_nan() && !fp.dh_v.is_nan(), "{fp:?}");
    assert!(!fp.dh_v.is_finite(), "{fp:?}");
    let c = s::ClampRules::default().footprint(fp);
    assert!((c.max_extent() - 1.0).abs() < 1e-6, "{fp:?} -> {c:?}");
}

#[test]
fn max_extent_rescales_the_parallelogram_and_clamps_the_rectangle() {
    let rules = s::ClampRules::default();
    assert_eq!(rules.max_extent, 1.0);
    // Inside: unchanged (bit-exact).
    let fp = s::Footprint::from_slope_derivatives(Vec2::new(0.3, 0.1), Vec2::new(-0.2, 0.4));
    assert_eq!(rules.footprint(fp), fp);
    // Outside: same shape, extent exactly lambda (to f32 rounding).
    let big = s::Footprint::from_slope_derivatives(Vec2::new(30.0, 10.0), Vec2::new(-20.0, 40.0));
    let c = rules.footprint(big);
    assert!((c.max_extent() - 1.0).abs() < 1e-6);
    assert!((c.dh_u.perp_dot(big.dh_u)).abs() < 1e-5 * big.dh_u.length());
    // Huge (1e3, 1e30) and infinite footprints, NaN, zero.
    for fp in [
        s::Footprint::from_slope_derivatives(Vec2::splat(1e3), Vec2::new(1e3, -1e3)),
        s::Footprint::from_slope_derivatives(Vec2::splat(1e30), Vec2::new(1e30, -1e30)),
        s::Footprint::from_slope_derivatives(
            Vec2::new(f32::INFINITY, 0.0),
            Vec2::new(1.0, f32::NEG_INFINITY),
        ),
    ] {
        let c = rules.footprint(fp);
        assert!((c.max_extent() - 1.0).abs() < 1e-6, "{fp:?} -> {c:?}");
    }
    // The NaN policy: a NaN entry counts as 0.
    let nan = s::Footprint::from_slope_derivatives(Vec2::new(f32::NAN, 0.0), Vec2::ONE);
    assert_eq!(rules.footprint(nan), rules.footprint(nan.nan_to_zero()));
    assert_eq!(rules.footprint(nan).dh_u, Vec2::ZERO);
    assert_eq!(rules.footprint(s::Footprint::ZERO), s::Footprint::ZERO);
    // Rectangle: per-axis clamp to [floor, lambda].
    let r = rules.rect(
        s::BoundingRect::new(Vec2::new(5.0, 1e-5)),
        Vec2::splat(0.01),
    );
    assert_eq!(r.half_extent, Vec2::new(1.0, 1e-3));
    let r = rules.rect(
        s::BoundingRect::new(Vec2::new(f32::NAN, f32::INFINITY)),
        Vec2::splat(0.01),
    );
    assert_eq!(r.half_extent, Vec2::new(1e-3, 1.0));
    // GDC floor: min(alpha, 0.1) per axis.
    let g = s::ClampRules::GDC2016;
    let r = g.rect(s::BoundingRect::new(Vec2::ZERO), Vec2::new(0.02, 0.5));
    assert_eq!(r.half_extent, Vec2::new(0.02, 0.1));
    // NONE leaves everything.
    let n = s::ClampRules::NONE;
    assert_eq!(n.footprint(big), big);
    assert_eq!(
        n.rect(s::BoundingRect::new(Vec2::new(5.0, 0.0)), Vec2::ONE)
            .half_extent,
        Vec2::new(5.0, 0.0)
    );
}

#[test]
fn kappa_caps_the_kernel_roughness_per_direction() {
    let rules = s::ClampRules::default();
    // Isotropic kernel: exactly TK19 eq. 1, 2 Sigma' = min(2 lambda, kappa).
    let k = rules.kernel(s::Covariance::new(0.5, 0.0, 0.5));
    assert!((k.s11 - 0.09).abs() < 1e-7 && (k.s22 - 0.09).abs() < 1e-7 && k.s12 == 0.0);
    let small = s::Covariance::new(0.01, 0.003, 0.02);
    assert_eq!(rules.kernel(small), small);
    // Elongated: the long axis is capped, the short one kept.
    let k = rules.kernel(s::Covariance::new(10.0, 0.0, 0.001));
    assert!((k.s11 - 0.09).abs() < 1e-7 && (k.s22 - 0.001).abs() < 1e-9);
    // The whole pipeline: the filtered roughness^2 never exceeds alpha^2 + kappa.
    let a = s::Isotropic::new(0.1).unwrap();
    for fp in [
        s::Footprint::from_slope_derivatives(Vec2::new(1e3, 0.0), Vec2::new(0.0, 1e3)),
        s::Footprint::from_slope_derivatives(Vec2::new(0.3, 0.2), Vec2::new(-0.1, 0.5)),
        s::Footprint::from_slope_derivatives(Vec2::splat(f32::NAN), Vec2::ZERO),
        s::Footprint::ZERO,
    ] {
        let f = rules.filter_gaussian(a, fp, 0.5);
        let (a11, a12, a22) = f.entries();
        let lmax = s::Covariance::new(a11, a12, a22).eigenvalues().1;
        assert!(lmax <= 0.01 + 0.18 + 1e-6, "{fp:?}: {f:?}");
        assert!(a11.is_finite() && a12.is_finite() && a22.is_finite());
    }
    // Tau: det(A) or 0.
    assert!((rules.det_clamp_for(s::AxisAligned::new(0.1, 0.2).unwrap()) - 4e-4).abs() < 1e-10);
    assert_eq!(s::ClampRules::NONE.det_clamp_for(a), 0.0);
}

#[test]
fn sanitized_covariance_contract() {
    // A NaN entry counts as 0 (the NaN policy).
    assert_eq!(
        s::Covariance::new(f32::NAN, 0.0, 1.0).sanitized(),
        s::Covariance::new(0.0, 0.0, 1.0)
    );
    let inf = s::Covariance::new(f32::INFINITY, 0.0, 1.0).sanitized();
    assert_eq!(inf, s::Covariance::new(1e8, 0.0, 1e8));
    // Negative variances and an over-large correlation are projected to PSD.
    let c = s::Covariance::new(-1.0, 3.0, 4.0).sanitized();
    assert_eq!(c, s::Covariance::new(0.0, 0.0, 4.0));
    let c = s::Covariance::new(1.0, 3.0, 4.0).sanitized();
    assert!(c.det() >= -1e-6 && c.s12 == 2.0);
    // Huge finite entries keep their shape and are capped at KERNEL_MAX.
    let c = s::Covariance::new(1e30, 0.0, 1.0).sanitized();
    assert!((c.s11 - 1e8).abs() <= 1.0 && c.s22 == 1.0);
}

#[test]
fn clamp_bias_statements() {
    // epsilon floor: with alpha << epsilon the filtered peak is the box average of the lobe,
    // ~ 1 / (4 eps^2) (all the mass is inside the box) instead of 1 / (pi alpha^2).
    let tol = Tolerance::relative(1e-9);
    let box_mean = |alpha: f64, h: f64| {
        let g = d::Ggx::new(d::Isotropic::new(alpha).unwrap());
        integrate_2d(|x, y| g.p22(DVec2::new(x, y)), (-h, h), (-h, h), tol).value / (4.0 * h * h)
    };
    let eps = 1e-3;
    let capped = box_mean(1e-5, eps);
    // Mass outside the box is ~ alpha^2 / eps^2 = 1e-4 of the total.
    assert!((capped * 4.0 * eps * eps - 1.0).abs() < 2e-4, "{capped}");
    // GDC floor min(alpha, 0.1): at zero footprint the peak drops to the average of the lobe
    // over [-alpha, alpha]^2, a fixed fraction for every alpha <= 0.1 (the lobe is
    // self-similar). Measured and pinned:
    let frac = box_mean(0.05, 0.05) * std::f64::consts::PI * 0.05 * 0.05;
    println!("GDC floor at zero footprint: filtered peak / unfiltered peak = {frac:.6}");
    let frac2 = box_mean(0.001, 0.001) * std::f64::consts::PI * 1e-6;
    assert!((frac - frac2).abs() < 1e-8);
    // Closed form: integral over [0,1]^2 of (1 + x^2 + y^2)^-2 is atan(1/sqrt 2) / sqrt 2
    // (each of the two symmetric terms a/(2 sqrt(1+a^2)) atan(b/sqrt(1+a^2)) at a = b = 1),
    // so the peak ratio (4/pi of that, over 4, times pi) is atan(1/sqrt 2)/sqrt 2 = 0.435210:
    // the GDC floor costs 56% of the peak of every lobe with alpha <= 0.1 at zero footprint.
    let exact = (1.0 / 2f64.sqrt()).atan() / 2f64.sqrt();
    assert!((frac - exact).abs() < 1e-8, "{frac} vs {exact}");
}

#[test]
fn constructors_and_filters_never_produce_nan() {
    let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, 1e3, -1e30];
    let a = s::AxisAligned::new(0.01, 0.3).unwrap();
    let rules = s::ClampRules::default();
    for &x in &bad {
        let v2 = Vec2::new(x, 0.5);
        let v3 = Vec3::new(0.1, x, -0.2);
        let fps = [
            s::Footprint::from_slope_derivatives(v2, v2.perp()),
            s::Footprint::from_projected_derivatives(v2, v2),
            s::Footprint::from_projected_derivatives_in_slope(Vec3::new(0.0, 0.6, 0.8), v2, v2),
            s::Footprint::from_projected_derivatives_in_slope(Vec3::new(x, 0.0, 0.0), v2, v2),
            s::Footprint::from_normal_differences(v3, v3),
            s::Footprint::from_normal_differences(Vec3::new(0.0, 0.0, -2.0), v3),
            s::Footprint::from_half_vector_derivatives(Vec3::new(0.0, 0.6, 0.8), v3, v3),
            s::Footprint::from_half_vector_derivatives(Vec3::new(x, 0.0, 0.0), v3, v3),
        ];
        for fp in fps {
            for rm in [
                rules.filter_gaussian(a, fp, 0.5),
                s::ClampRules::NONE.filter_gaussian(a, fp, 0.5),
                s::filter::projected(a, rules.kernel(rules.footprint(fp).covariance(0.5))),
                s::filter::projected(a, fp.covariance(0.5)),
                s::filter::gaussian(a, fp.bounding_rect().covariance(0.5)),
            ] {
                let g = s::Ggx::new(rm);
                let b = s::Beckmann::new(rm);
                for h in [Vec3::Z, Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, -1.0, 0.0)] {
                    use filtered_ndf::f32::Ndf;
                    let (vg, vb) = (g.d(h), b.d(h));
                    assert!(vg.is_finite() && vg >= 0.0, "x={x} {fp:?} {rm:?}: {vg}");
                    assert!(vb.is_finite() && vb >= 0.0, "x={x} {fp:?} {rm:?}: {vb}");
                }
            }
            let r = rules.rect(fp.bounding_rect(), Vec2::new(0.01, 0.3));
            assert!(r.half_extent.is_finite() && r.half_extent.cmpge(Vec2::splat(1e-3)).all());
            assert!(r.half_extent.cmple(Vec2::ONE).all());
        }
    }
}

#[test]
fn clamp_eigenvalues_across_the_reciprocal_threshold_f32() {
    // The general clamp takes `lambda_min` as `(hi / big) lo - (s12 / big) s12` with the
    // quotients as products with `1 / big` where that is a normal number (`|big| <= 1 /
    // F::MIN_POSITIVE = 8.5e37` in f32), with true quotients above. [[a, 0.5], [0.5, 1]]
    // clamped to 10, `a` on both sides of the threshold, against the test side's f64
    // decomposition of the same (f32-exact) entries (`testing::linalg`): lambda_max ~ a is
    // clamped to 10, lambda_min = 1 - 0.25 / a ~ 1 is kept, the eigenvectors are kept.
    // s11 and s22: 8 ulps of the entry: lambda_min's products (3 roundings, 2 ulps), the
    // projectors' reciprocal `1 / 2rp` and products (`p (p w)`: 2.5 ulps), the weighted sum
    // (1 ulp), doubled for the unit-size matrix's rounded entries. s12 = 9 sin cos ~ 4.5 / a
    // comes from the scaled entry `0.5 / a`, subnormal for a > 4.3e37 (2^-20 relative at
    // 3e38): 1e-5 relative.
    for a in [1e37f32, 5e37, 8e37, 8.4e37, 8.6e37, 9e37, 3e38, f32::MAX] {
        let c = s::Covariance::new(a, 0.5, 1.0).clamp_eigenvalues(10.0);
        let want = Sym2::new(a as f64, 0.5, 1.0)
            .eigen()
            .map(|l| l.clamp(0.0, 10.0));
        let (w11, w12, w22) = want.entries();
        let ulp = f32::EPSILON as f64;
        assert!(
            ((c.s11 as f64) - w11).abs() <= 8.0 * ulp * w11,
            "{a}: {c:?} {want:?}"
        );
        assert!(
            ((c.s22 as f64) - w22).abs() <= 8.0 * ulp * w22,
            "{a}: {c:?} {want:?}"
        );
        assert!(
            ((c.s12 as f64) - w12).abs() <= 1e-5 * w12.abs(),
            "{a}: {c:?} {want:?}"
        );
    }
}
