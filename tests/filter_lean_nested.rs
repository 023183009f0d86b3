//! LEAN moments nested into every method (`filter::Lean`, KHPL16 eq. 21) against independent
//! references: the f64 quadrature of the slope density convolved with the texel's slope
//! distribution and the pixel kernel (`testing::gaussian_reference`), and closed forms
//! computed here from the texel slopes themselves (two-pass covariance, not the library's
//! `E[s s^T] - E[s] E[s]^T`).

use filtered_ndf::f64 as d;
use filtered_ndf::f64::prelude::*;
use filtered_ndf::testing::gaussian_reference as gref;
use filtered_ndf::testing::quadrature::Tolerance as QTol;
use glam::{DVec2, DVec3};

/// A texel's base slopes with weights (summing to 1): its moments as the bake stores them and
/// its covariance by the two-pass formula `sum w (s - mean)(s - mean)^T`.
struct Texel {
    moments: LeanMoments,
    cov: (f64, f64, f64),
    mean: DVec2,
}

fn texel(slopes: &[(f64, DVec2)]) -> Texel {
    let mean: DVec2 = slopes.iter().map(|&(w, s)| w * s).sum();
    let (mut e11, mut e12, mut e22) = (0.0, 0.0, 0.0);
    let (mut c11, mut c12, mut c22) = (0.0, 0.0, 0.0);
    for &(w, s) in slopes {
        e11 += w * s.x * s.x;
        e12 += w * s.x * s.y;
        e22 += w * s.y * s.y;
        let o = s - mean;
        c11 += w * o.x * o.x;
        c12 += w * o.x * o.y;
        c22 += w * o.y * o.y;
    }
    Texel {
        moments: LeanMoments::new(mean, d::Covariance::new(e11, e12, e22)),
        cov: (c11, c12, c22),
        mean,
    }
}

/// Four texels: a 2x2 block of a tilted bump, an elongated ridge, a flat texel and a steep one.
fn texels() -> Vec<Texel> {
    vec![
        texel(&[
            (0.25, DVec2::new(0.02, -0.01)),
            (0.25, DVec2::new(-0.015, 0.03)),
            (0.25, DVec2::new(0.04, 0.02)),
            (0.25, DVec2::new(0.0, -0.025)),
        ]),
        texel(&[(0.5, DVec2::new(0.31, 0.29)), (0.5, DVec2::new(0.35, 0.33))]),
        texel(&[(1.0, DVec2::new(0.1, -0.2))]),
        texel(&[
            (0.1, DVec2::new(1.5, 0.2)),
            (0.6, DVec2::new(1.2, -0.1)),
            (0.3, DVec2::new(0.9, 0.05)),
        ]),
    ]
}

/// The pixel kernel `sigma^2 (u u^T + v v^T)` of a footprint inside every method's extent.
fn pixel(u: DVec2, v: DVec2, sigma: f64) -> (f64, f64, f64) {
    let s2 = sigma * sigma;
    (
        s2 * (u.x * u.x + v.x * v.x),
        s2 * (u.x * u.y + v.x * v.y),
        s2 * (u.y * u.y + v.y * v.y),
    )
}

const U: DVec2 = DVec2::new(0.012, 0.004);
const V: DVec2 = DVec2::new(-0.003, 0.009);

#[test]
fn exact_gaussian_ggx_is_the_triple_convolution() {
    // GGX convolved with the texel's Gaussian and the pixel kernel, by quadrature; the
    // method's footprint is inside lambda = 1, so no clamp acts.
    let material = Ggx::new(d::AxisAligned::new(0.02, 0.05).unwrap());
    let fp = Footprint::from_slope_derivatives(U, V);
    let p = pixel(U, V, 0.5);
    for t in texels() {
        let lobe = material.filtered(fp, Lean::new(ExactGaussian::KHPL16, t.moments));
        let k = d::Covariance::new(p.0 + t.cov.0, p.1 + t.cov.1, p.2 + t.cov.2);
        for s in [DVec2::ZERO, DVec2::new(0.03, -0.02), DVec2::new(-0.1, 0.07)] {
            let e = gref::ggx(material.roughness, k, s, QTol::relative(1e-10));
            let got = lobe.p22(s);
            // The lobe's own bound (Tolerance::Full) plus the reference's estimate, plus the
            // rounding of the one-pass covariance `E[s s^T] - E[s] E[s]^T` (|E[s]|^2 up to
            // 1.6, 1e-16 relative to it, against variances down to 2.5e-4: 1e-12).
            let tol = 1e-9 * got + e.error + 1e-9 * e.value;
            assert!((got - e.value).abs() <= tol, "{s}: {got} vs {e:?}");
        }
    }
}

#[test]
fn gaussian_beckmann_is_the_exact_nested_convolution() {
    // Beckmann: A + 2 (Sigma_L + Sigma_P) is exact; checked against the quadrature of the
    // material's density with both kernels, without the clamp rules (KHPL16's rules with the
    // footprint inside lambda: the determinant clamp never acts since det grows).
    let material = Beckmann::new(d::Isotropic::new(0.03).unwrap());
    let fp = Footprint::from_slope_derivatives(U, V);
    let p = pixel(U, V, 0.5);
    for t in texels() {
        let k = d::Covariance::new(p.0 + t.cov.0, p.1 + t.cov.1, p.2 + t.cov.2);
        for method in [Gaussian::KHPL16, Gaussian::TK19] {
            let lobe = material.filtered(fp, Lean::new(method, t.moments));
            let exact = material.filtered(fp, Lean::new(ExactGaussian::KHPL16, t.moments));
            for s in [DVec2::ZERO, DVec2::new(0.02, 0.01), DVec2::new(-0.05, 0.04)] {
                let e = gref::beckmann(material.roughness, k, s, QTol::relative(1e-10));
                let got = lobe.p22(s);
                assert!(
                    (got - e.value).abs() <= 1e-9 * e.value + e.error,
                    "{s}: {got} vs {e:?}"
                );
                assert_eq!(exact.p22(s), got);
            }
        }
    }
}

#[test]
fn gaussian_and_projected_ggx_filter_the_widened_matrix() {
    // The widened material in closed form from the two-pass covariance, then the method.
    let a = d::AxisAligned::new(0.04, 0.02).unwrap();
    let material = Ggx::new(a);
    let fp = Footprint::from_slope_derivatives(U, V);
    for t in texels() {
        let widened = d::RoughnessMatrix::new(
            0.04 * 0.04 + 2.0 * t.cov.0,
            2.0 * t.cov.1,
            0.02 * 0.02 + 2.0 * t.cov.2,
        )
        .unwrap();
        let h = DVec3::new(0.01, -0.02, 1.0).normalize();
        for (got, want) in [
            (
                material
                    .filtered(fp, Lean::new(Gaussian::TK19, t.moments))
                    .d(h),
                Ggx::new(widened).filtered(fp, Gaussian::TK19).d(h),
            ),
            (
                material
                    .filtered(fp, Lean::new(Projected::TK21, t.moments))
                    .d(h),
                Ggx::new(widened).filtered(fp, Projected::TK21).d(h),
            ),
        ] {
            // One-pass against two-pass covariance: 1e-12 of the entries (above).
            assert!((got - want).abs() <= 1e-9 * want, "{got} vs {want}");
        }
    }
}

#[test]
fn box_methods_filter_the_widened_diagonal() {
    // alpha_i' = sqrt(alpha_i^2 + 2 (Sigma_L)_ii), then the method's rectangle.
    let a = d::AxisAligned::new(0.05, 0.01).unwrap();
    let fp = Footprint::from_slope_derivatives(U, V);
    for t in texels() {
        let want = d::AxisAligned::new(
            (0.05f64 * 0.05 + 2.0 * t.cov.0).sqrt(),
            (0.01f64 * 0.01 + 2.0 * t.cov.2).sqrt(),
        )
        .unwrap();
        let got = filter_widened(a, &t.moments);
        assert!((got.x - want.alpha().x).abs() <= 1e-12 * want.alpha().x);
        assert!((got.y - want.alpha().y).abs() <= 1e-12 * want.alpha().y);
        let boxed = Ggx::new(a).filtered(fp, Lean::new(Rect::KHPL16, t.moments));
        // The footprint's bounding rectangle, half extents |u_i| + |v_i| / 2 per axis
        // (KHPL16 eq. 16), inside lambda = 1.
        let half = DVec2::new(U.x.abs() + V.x.abs(), U.y.abs() + V.y.abs()) * 0.5;
        assert!((boxed.half_extent - half).abs().max_element() < 1e-15);
        assert!((boxed.roughness.alpha() - want.alpha()).abs().max_element() < 1e-12);
        let proxy = Ggx::new(a).filtered(fp, Lean::new(Proxy::KHPL16, t.moments));
        let want_proxy = Ggx::new(want).filtered(fp, Proxy::KHPL16);
        let (g, w) = (proxy.roughness.alpha(), want_proxy.roughness.alpha());
        assert!((g - w).abs().max_element() <= 1e-9 * w.max_element());
        // Isotropic materials go through the same axis-aligned lobe.
        let iso = Ggx::new(d::Isotropic::new(0.05).unwrap());
        let aa = Ggx::new(d::AxisAligned::new(0.05, 0.05).unwrap());
        let m = Lean::new(Rect::GDC2016, t.moments);
        assert_eq!(iso.filtered(fp, m), aa.filtered(fp, m));
    }
}

fn filter_widened(a: d::AxisAligned, m: &LeanMoments) -> DVec2 {
    d::filter::lean_widened_axis_aligned(a, m).alpha()
}

#[test]
fn a_texel_of_one_slope_leaves_every_method_unchanged() {
    // Zero spread: Sigma_L = 0, so each nested method is the method itself.
    let t = texel(&[(1.0, DVec2::new(0.2, -0.3))]);
    let (m, fp) = (t.moments, Footprint::from_slope_derivatives(U, V));
    let a = d::AxisAligned::new(0.03, 0.07).unwrap();
    let h = DVec3::new(0.02, 0.01, 1.0).normalize();
    let g = Ggx::new(a);
    let b = Beckmann::new(a);
    let pairs = [
        (
            g.filtered(fp, Lean::new(Gaussian::TK19, m)).d(h),
            g.filtered(fp, Gaussian::TK19).d(h),
        ),
        (
            g.filtered(fp, Lean::new(ExactGaussian::KHPL16, m)).d(h),
            g.filtered(fp, ExactGaussian::KHPL16).d(h),
        ),
        (
            g.filtered(fp, Lean::new(Projected::TK21, m)).d(h),
            g.filtered(fp, Projected::TK21).d(h),
        ),
        (
            g.filtered(fp, Lean::new(Rect::KHPL16, m)).d(h),
            g.filtered(fp, Rect::KHPL16).d(h),
        ),
        (
            g.filtered(fp, Lean::new(Proxy::KHPL16, m)).d(h),
            g.filtered(fp, Proxy::KHPL16).d(h),
        ),
        (
            b.filtered(fp, Lean::new(Gaussian::KHPL16, m)).d(h),
            b.filtered(fp, Gaussian::KHPL16).d(h),
        ),
    ];
    for (got, want) in pairs {
        // E[s s^T] - E[s] E[s]^T of one slope rounds to within 1e-17 of 0 (or is projected
        // to 0 where it rounds negative).
        assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
    }
}

#[test]
fn mean_normal_is_the_normal_of_the_mean_slope() {
    for t in texels() {
        let n = d::filter::lean_mean_normal(&t.moments);
        let want = DVec3::new(-t.mean.x, -t.mean.y, 1.0) / (1.0 + t.mean.length_squared()).sqrt();
        assert!((n - want).abs().max_element() < 1e-15);
    }
    let nan = LeanMoments::new(DVec2::new(f64::NAN, 0.0), d::Covariance::ZERO);
    assert_eq!(d::filter::lean_mean_normal(&nan), DVec3::Z);
}

#[test]
fn any_moments_give_finite_lobes() {
    // Indefinite (second < mean^2), NaN and infinite moments: the covariance is sanitised,
    // every lobe finite.
    let bad = [
        LeanMoments::new(DVec2::new(0.5, 0.5), d::Covariance::new(0.0, 1.0, 0.0)),
        LeanMoments::new(
            DVec2::new(f64::NAN, 0.0),
            d::Covariance::new(f64::NAN, 0.0, 1.0),
        ),
        LeanMoments::new(
            DVec2::ZERO,
            d::Covariance::new(f64::INFINITY, 0.0, f64::INFINITY),
        ),
    ];
    let fp = Footprint::from_slope_derivatives(U, V);
    let a = d::AxisAligned::new(0.1, 0.2).unwrap();
    let h = DVec3::new(0.1, 0.0, 1.0).normalize();
    for m in bad {
        let g = Ggx::new(a);
        let ds = [
            g.filtered(fp, Lean::new(Gaussian::TK19, m)).d(h),
            g.filtered(fp, Lean::new(ExactGaussian::KHPL16, m)).d(h),
            g.filtered(fp, Lean::new(Projected::TK21, m)).d(h),
            g.filtered(fp, Lean::new(Rect::KHPL16, m)).d(h),
            g.filtered(fp, Lean::new(Proxy::KHPL16, m)).d(h),
            Beckmann::new(a)
                .filtered(fp, Lean::new(Gaussian::TK19, m))
                .d(h),
        ];
        for v in ds {
            assert!(v.is_finite() && v >= 0.0, "{m:?}: {v}");
        }
    }
}
