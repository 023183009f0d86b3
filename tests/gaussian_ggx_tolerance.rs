//! The accuracy settings of the exact Gaussian-filtered GGX (`Tolerance`) against the
//! independent reference: the `f64` 2-D adaptive quadrature of the convolution integral
//! (`testing::gaussian_reference::ggx`, which never uses the mixture identity), with its own
//! error estimate.
//!
//! Each reduced setting (`Rel1e4`, `Rel1e3`, `Rel1e2`) must be within its proven bound
//! (`Tolerance::bound`) plus the reference's error estimate, over the domain of
//! `tests/gaussian_ggx.rs` (alpha `1e-4..1`, anisotropy to 100:1, rotated; kernels `1e-3..1e3`
//! lobe widths, rank one, rotated; slopes to 50 filtered widths), on both sides of each
//! setting's switch between the far-tail series and the trapezoid rule, and at the rank-one
//! and huge kernels. In `f32` the lobe's input is the `f32` kernel as `Covariance::sanitized`
//! sees it in `f32` (a nearly singular kernel's determinant cancels there, and the sanitiser may
//! move it), the same at every setting: the tolerance is the setting's bound plus the `Full`
//! rule's (`1.8e-6`) plus the `Full` `f32` lobe's own error against the reference on the same
//! case (`f32 - ref = (f32_t - f32_full) + (f32_full - ref)`; the `Full` `f32` lobe is tested
//! against the reference in `tests/gaussian_ggx.rs`).

use filtered_ndf::f32 as s;
use filtered_ndf::f32::Ndf as _;
use filtered_ndf::f64 as d;
use filtered_ndf::f64::Ndf as _;
use filtered_ndf::f64::filter::Tolerance;
use filtered_ndf::testing::gaussian_reference as gref;
use filtered_ndf::testing::quadrature::Tolerance as QuadTolerance;
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use glam::{DVec2, DVec3, Vec2, Vec3};

/// The reduced settings, both precisions.
const REDUCED: [(Tolerance, s::filter::Tolerance); 3] = [
    (Tolerance::Rel1e4, s::filter::Tolerance::Rel1e4),
    (Tolerance::Rel1e3, s::filter::Tolerance::Rel1e3),
    (Tolerance::Rel1e2, s::filter::Tolerance::Rel1e2),
];

/// The far-tail switch constant `K` of each reduced setting (the documented table of
/// `Tolerance`): the series where `2 l1 (K + 12 ln_up(1 + q)) <= 1 + q`.
fn far_k(t: Tolerance) -> f64 {
    match t {
        Tolerance::Rel1e4 => 1500.0,
        Tolerance::Rel1e3 => 500.0,
        Tolerance::Rel1e2 => 160.0,
        Tolerance::Full => unreachable!(),
    }
}

/// The documented upper bound of `ln x` that the switch uses (`e ln 2 + m - 1` for
/// `x = m 2^e`).
fn ln_upper(x: f64) -> f64 {
    let e = x.log2().floor();
    e * std::f64::consts::LN_2 + (x / e.exp2() - 1.0)
}

#[path = "common/gaussian_cases.rs"]
mod gaussian_cases;
use gaussian_cases::{Case, cases, rotated};

/// Worst relative error per reduced setting `(f64, f32)` over `cs`, asserting each bound.
fn check(cs: &[Case]) -> [(f64, f64); 3] {
    let mut worst = [(0.0f64, 0.0f64); 3];
    for c in cs {
        let a = d::RoughnessMatrix::new(c.a.0 as f64, c.a.1 as f64, c.a.2 as f64).unwrap();
        let k = d::Covariance::new(c.k.0 as f64, c.k.1 as f64, c.k.2 as f64);
        let sl = DVec2::new(c.s.0 as f64, c.s.1 as f64);
        let e = gref::ggx(a, k, sl, QuadTolerance::relative(1e-10));
        let rel_ref = e.error / e.value;
        assert!(
            e.value > 0.0 && rel_ref < 1e-8,
            "reference not converged: {c:?} {e:?}"
        );
        let lobe = d::GaussianFilteredGgx::new(a, k);
        let a32 = s::RoughnessMatrix::new(c.a.0, c.a.1, c.a.2).unwrap();
        let lobe32 = s::GaussianFilteredGgx::new(a32, s::Covariance::new(c.k.0, c.k.1, c.k.2));
        let sl32 = Vec2::new(c.s.0, c.s.1);
        let e_full32 = (lobe32.p22(sl32) as f64 - e.value).abs() / e.value;
        for (i, (t, t32)) in REDUCED.iter().enumerate() {
            let v = lobe.with_tolerance(*t).p22(sl);
            let r64 = (v - e.value).abs() / e.value;
            assert!(
                r64 <= t.bound() + rel_ref,
                "{t:?} f64 {c:?}: {v} vs {e:?} ({r64:.3e})"
            );
            let v32 = lobe32.with_tolerance(*t32).p22(sl32) as f64;
            let r32 = (v32 - e.value).abs() / e.value;
            let full = s::filter::Tolerance::Full.bound();
            assert!(
                r32 <= t32.bound() + full + e_full32 + rel_ref,
                "{t:?} f32 {c:?}: {v32} vs {e:?} ({r32:.3e})"
            );
            worst[i].0 = worst[i].0.max(r64);
            worst[i].1 = worst[i].1.max(r32);
        }
    }
    worst
}

#[test]
fn each_setting_against_the_2d_reference_over_the_domain() {
    let cs = cases(120, 0x701E_0053);
    let w = check(&cs);
    for ((t, _), (w64, w32)) in REDUCED.iter().zip(w) {
        println!("{t:?}: worst relative error f64 {w64:.3e}, f32 {w32:.3e}");
    }
}

#[test]
fn both_sides_of_the_far_tail_switch() {
    // At kernel ratios 2 l1 from 3e-3 to 1 (isotropic lobe, kernel of anisotropy 0.3
    // along x), the slope `q = |c|^2` where each setting's series takes over, found on the
    // documented condition, and evaluated just below and just above it (relative steps of
    // 1e-6 and 1e-2). Both sides against the reference within the bound.
    let alpha = 0.1f64;
    let mut cs = Vec::new();
    for (t, _) in REDUCED {
        for &tl1 in &[3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0] {
            // beta* solves 2 l1 (K + 12 ln_up(beta)) = beta (the left side grows slower).
            let f = |b: f64| tl1 * (far_k(t) + 12.0 * ln_upper(b)) - b;
            let (mut lo, mut hi) = (1.0f64, 1e12f64);
            if f(lo) <= 0.0 {
                continue; // far tail everywhere, the peak included
            }
            for _ in 0..200 {
                let mid = (lo * hi).sqrt();
                if f(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let l1 = 0.5 * tl1;
            let kxx = (l1 * alpha * alpha) as f32;
            for step in [-1e-2, -1e-6, 1e-6, 1e-2] {
                let beta = hi * (1.0 + step);
                let x = alpha * (beta - 1.0).sqrt();
                cs.push(Case {
                    a: ((alpha * alpha) as f32, 0.0, (alpha * alpha) as f32),
                    k: (kxx, 0.0, 0.3 * kxx),
                    s: (x as f32, 0.0),
                });
            }
        }
    }
    assert!(cs.len() >= 68, "{}", cs.len());
    let w = check(&cs);
    println!("far-tail switch: worst {w:?}");
}

#[test]
fn rank_one_and_huge_kernels_against_the_reference() {
    // The trapezoid rule's longest runs: rank-one kernels along and across the lobe, kernels
    // 1e3 lobe widths wide, from the peak to 50 filtered widths.
    let mut cs = Vec::new();
    for &alpha in &[1e-4f32, 1e-2, 0.5] {
        let a2 = alpha * alpha;
        for (k11, k12, k22) in [
            (a2 * 100.0, 0.0, 0.0),
            (a2 * 0.01, a2 * 0.01, a2 * 0.01),
            (a2 * 1e6, 0.0, a2 * 1e6),
            (a2 * 1e6, a2 * 5e5, a2 * 3e5),
        ] {
            let w = (a2 + 2.0 * k11.max(k22)).sqrt();
            for rho in [0.0f32, 0.5, 3.0, 50.0] {
                cs.push(Case {
                    a: (a2, 0.2 * a2, 0.5 * a2),
                    k: (k11, k12, k22),
                    s: (0.6 * rho * w, 0.8 * rho * w),
                });
            }
        }
    }
    let w = check(&cs);
    println!("rank-one / 1e3-width kernels: worst {w:?}");
}

#[test]
fn d_at_each_setting_to_the_horizon() {
    // d(m) = P22(s(m)) / m_z^4 against the reference at normals from the pole to 89.99 deg,
    // and finite, non-negative, 0 below the horizon and for non-finite input.
    let mut r = Rng(0xD17_0053);
    for i in 0..24 {
        let alpha = 10f64.powf(r.range(-3.0, 0.0));
        let a = d::RoughnessMatrix::new(alpha * alpha, 0.3 * alpha * alpha, 0.5 * alpha * alpha)
            .unwrap();
        let kw = 10f64.powf(r.range(-2.0, 2.0));
        let (k11, k12, k22) = rotated((alpha * kw).powi(2), 0.1 * (alpha * kw).powi(2), 0.4);
        let k = d::Covariance::new(k11, k12, k22);
        let theta = if i % 4 == 3 {
            89.99_f64.to_radians()
        } else {
            r.range(0.0, 1.5)
        };
        let phi = r.range(0.0, std::f64::consts::TAU);
        let mm = DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        );
        let sl = DVec2::new(-mm.x / mm.z, -mm.y / mm.z);
        let e = gref::ggx(a, k, sl, QuadTolerance::relative(1e-10));
        let want = e.value / mm.z.powi(4);
        for (t, _) in REDUCED {
            let got = d::GaussianFilteredGgx::new(a, k).with_tolerance(t).d(mm);
            assert!(
                (got - want).abs() <= (t.bound() + e.error / e.value) * want,
                "{i} {t:?}: {got} vs {want}"
            );
        }
    }
    for (t, t32) in REDUCED {
        let lobe = d::GaussianFilteredGgx::new(
            d::Isotropic::new(0.1).unwrap(),
            d::Covariance::new(1e-2, 0.0, 1e-3),
        )
        .with_tolerance(t);
        for z in [1e-3_f64, 1e-8, 1e-30, 1e-150, 1e-300, 0.0, -1e-3] {
            let mm = DVec3::new((1.0 - z * z).max(0.0).sqrt(), 0.0, z);
            let v = lobe.d(mm);
            assert!(v.is_finite() && v >= 0.0, "{t:?} d({mm}) = {v}");
            if z <= 0.0 {
                assert_eq!(v, 0.0);
            }
        }
        for sl in [
            DVec2::new(f64::NAN, 0.0),
            DVec2::new(f64::INFINITY, 1.0),
            DVec2::splat(f64::MAX),
        ] {
            assert_eq!(lobe.p22(sl), 0.0, "{t:?} {sl}");
        }
        // The widest kernels and the range edges in f32.
        for &alpha in &[1e-8f32, 1e4] {
            for kk in [0.0f32, 1e-30, 1.0, 1e8] {
                let l32 = s::GaussianFilteredGgx::new(
                    s::Isotropic::new(alpha).unwrap(),
                    s::Covariance::new(kk, 0.0, 0.5 * kk),
                )
                .with_tolerance(t32);
                for sl in [Vec2::ZERO, Vec2::new(1e-8, 0.0), Vec2::splat(3e38)] {
                    let v = l32.p22(sl);
                    assert!(v.is_finite() && v >= 0.0, "{t32:?} {alpha} {kk} {sl}: {v}");
                }
                for mm in [
                    Vec3::Z,
                    Vec3::new(0.6, 0.0, 0.8),
                    Vec3::new(1.0, 0.0, 1e-20),
                ] {
                    let v = l32.d(mm);
                    assert!(
                        v.is_finite() && v >= 0.0,
                        "{t32:?} {alpha} {kk} d({mm}): {v}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_setting_and_the_front_door() {
    use d::filter::{ExactGaussian, Filterable};
    // Full is the default, everywhere: the lobe of `new` and of `ExactGaussian::KHPL16`.
    assert_eq!(Tolerance::default(), Tolerance::Full);
    assert_eq!(ExactGaussian::KHPL16.tolerance, Tolerance::Full);
    let r = d::AxisAligned::new(0.05, 0.08).unwrap();
    let fp = d::Footprint::from_slope_derivatives(DVec2::new(0.03, 0.01), DVec2::new(0.0, 0.02));
    let g = d::Ggx::new(r);
    let full = g.filtered(fp, ExactGaussian::KHPL16);
    assert_eq!(full.tolerance(), Tolerance::Full);
    for (t, _) in REDUCED {
        let lobe = g.filtered(fp, ExactGaussian::KHPL16.with_tolerance(t));
        assert_eq!(lobe, full.with_tolerance(t));
        assert_eq!(lobe.tolerance(), t);
        // Lambda is the full rule's at every setting.
        let w = DVec3::new(0.5, 0.1, 0.8);
        assert_eq!(lobe.lambda(w), full.lambda(w));
    }
    // `relative` picks the cheapest setting within the request; the bounds are ordered.
    let pick = [
        (1.0, Tolerance::Rel1e2),
        (1e-2, Tolerance::Rel1e2),
        (5e-3, Tolerance::Rel1e3),
        (1e-3, Tolerance::Rel1e3),
        (1e-4, Tolerance::Rel1e4),
        (9e-5, Tolerance::Full),
        (0.0, Tolerance::Full),
        (-1.0, Tolerance::Full),
        (f64::NAN, Tolerance::Full),
        (f64::INFINITY, Tolerance::Rel1e2),
    ];
    for (eps, want) in pick {
        assert_eq!(Tolerance::relative(eps), want, "{eps}");
        assert!(Tolerance::relative(eps).bound() <= eps.max(Tolerance::Full.bound()));
    }
    let b = Tolerance::ALL.map(Tolerance::bound);
    assert!(b.windows(2).all(|w| w[0] < w[1]), "{b:?}");
    assert!(Tolerance::Full.bound() <= 1.1e-11 && s::filter::Tolerance::Full.bound() <= 1.8e-6);
}
