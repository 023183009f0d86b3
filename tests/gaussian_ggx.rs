//! The exact Gaussian-filtered GGX (`gaussian_ggx`) against an independent reference: the
//! `f64` 2-D adaptive quadrature of the convolution integral itself
//! (`testing::gaussian_reference::ggx`, which integrates `P22_GGX(s - t) N(t; 0, Sigma)` over
//! the plane and never uses the mixture identity), with its own error estimate.
//!
//! Domain (seeded): alpha log-uniform in `[1e-4, 1]`, anisotropy up to 100:1, rotated; kernel
//! standard deviations from `1e-3` to `1e3` lobe widths (one case in eight the zero kernel,
//! one in eight rank one), kernel anisotropy up to `1e2`, rotated; slopes from the peak to 50
//! widths of the filtered lobe (`s = rho L u`, `L L^T = A + 2 Sigma`, `rho` uniform in
//! `[0, 50]` for half the cases, log-uniform in `[1e-3, 50]` for the others).
//!
//! Tolerances: `1e-10` relative in `f64` and `1e-5` in `f32` (the targets), plus the
//! reference's own error estimate (required below `1e-11` relative, so it never carries a
//! comparison). The rules' own bounds and measured errors are `~1e-11` (`f64`) and `~2e-6`
//! (`f32`, module docs). The switches between the rules (far tail, Gauss-Laguerre, trapezoid;
//! Gauss-Hermite and the sinh rule for `Lambda`) are tested on both sides of each edge.

use filtered_ndf::f32 as s;
use filtered_ndf::f64 as d;
use filtered_ndf::f64::Ndf as _;
use filtered_ndf::f64::Roughness as _;
use filtered_ndf::testing::gaussian_reference as gref;
use filtered_ndf::testing::quadrature::Tolerance;
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use glam::{DVec2, DVec3, Vec2, Vec3};

#[path = "common/gaussian_cases.rs"]
mod gaussian_cases;
use gaussian_cases::{Case, cases, rotated};

fn lobe64(c: &Case) -> (d::RoughnessMatrix, d::Covariance, DVec2) {
    let a = d::RoughnessMatrix::new(c.a.0 as f64, c.a.1 as f64, c.a.2 as f64).unwrap();
    let k = d::Covariance::new(c.k.0 as f64, c.k.1 as f64, c.k.2 as f64);
    (a, k, DVec2::new(c.s.0 as f64, c.s.1 as f64))
}

/// `(worst f64 relative error, worst f32 relative error)` over `cases`, asserting the targets.
fn check_against_reference(cs: &[Case]) -> (f64, f64) {
    let (mut w64, mut w32) = (0.0_f64, 0.0_f64);
    for c in cs {
        let (a, k, sl) = lobe64(c);
        let e = gref::ggx(a, k, sl, Tolerance::relative(1e-12));
        let rel_ref = e.error / e.value;
        assert!(
            e.value > 0.0 && rel_ref < 1e-11,
            "reference not converged: {c:?} {e:?}"
        );
        let v64 = d::GaussianFilteredGgx::new(a, k).p22(sl);
        let r64 = (v64 - e.value).abs() / e.value;
        assert!(
            r64 <= 1e-10 + rel_ref,
            "f64 {c:?}: {v64} vs {e:?} ({r64:.3e})"
        );
        let a32 = s::RoughnessMatrix::new(c.a.0, c.a.1, c.a.2).unwrap();
        let k32 = s::Covariance::new(c.k.0, c.k.1, c.k.2);
        let v32 = s::Ndf::p22(
            &s::GaussianFilteredGgx::new(a32, k32),
            Vec2::new(c.s.0, c.s.1),
        ) as f64;
        let r32 = (v32 - e.value).abs() / e.value;
        assert!(
            r32 <= 1e-5 + rel_ref,
            "f32 {c:?}: {v32} vs {e:?} ({r32:.3e})"
        );
        w64 = w64.max(r64);
        w32 = w32.max(r32);
    }
    (w64, w32)
}

#[test]
fn p22_against_the_2d_reference_over_the_domain() {
    let cs = cases(160, 0x6A55_0017);
    let (w64, w32) = check_against_reference(&cs);
    println!("160 seeded cases: worst relative error f64 {w64:.3e}, f32 {w32:.3e}");
}

#[test]
fn d_is_p22_over_mz4_and_finite_to_the_horizon() {
    // d(m) = P22(s(m)) / m_z^4 against the reference, at normals from the pole to 89.99 deg
    // (the far-tail series takes over towards the horizon). Tolerance as above.
    let mut r = Rng(0xD17);
    for i in 0..40 {
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
        let lobe = d::GaussianFilteredGgx::new(a, k);
        let sl = DVec2::new(-mm.x / mm.z, -mm.y / mm.z);
        let e = gref::ggx(a, k, sl, Tolerance::relative(1e-12));
        let want = e.value / mm.z.powi(4);
        let got = lobe.d(mm);
        assert!(
            (got - want).abs() <= (1e-10 + e.error / e.value) * want,
            "{i}: {got} vs {want}"
        );
    }
    // Grazing and below: finite, non-negative, 0 below the horizon.
    let lobe = d::GaussianFilteredGgx::new(
        d::Isotropic::new(0.1).unwrap(),
        d::Covariance::new(1e-2, 0.0, 1e-3),
    );
    for z in [1e-3_f64, 1e-8, 1e-30, 1e-150, 1e-300, 0.0, -1e-3] {
        let mm = DVec3::new((1.0 - z * z).max(0.0).sqrt(), 0.0, z);
        let v = lobe.d(mm);
        assert!(v.is_finite() && v >= 0.0, "d({mm}) = {v}");
        if z <= 0.0 {
            assert_eq!(v, 0.0);
        }
    }
}

#[test]
fn zero_kernel_is_ggx_at_the_range_edges() {
    // The zero kernel takes the far-tail branch, where the series is exact: J = (1 + q)^-2.
    // Against GGX's own p22 and d: 64 ulps (the two evaluate the same quadratic form by
    // different roundings).
    for &alpha in &[1e-8, 1e-4, 0.1, 1.0, 1e2, 1e4] {
        let ratio = if alpha < 1.0 { 2.0 } else { 0.5 };
        {
            let r = d::AxisAligned::new(alpha, alpha * ratio)
                .unwrap()
                .to_matrix();
            let lobe = d::GaussianFilteredGgx::new(r, d::Covariance::ZERO);
            let g = d::Ggx::new(r);
            for &x in &[0.0, 1e-9, 1e-3, 0.5, 3.0, 1e3, 1e8] {
                let sl = DVec2::new(x * alpha, 0.7 * x * alpha);
                let (a, b) = (lobe.p22(sl), g.p22(sl));
                assert!(
                    (a - b).abs() <= 64.0 * f64::EPSILON * b,
                    "{alpha} {x}: {a} vs {b}"
                );
                let mm = d::footprint::slope::sphere_from_slope(sl);
                let (a, b) = (lobe.d(mm), g.d(mm));
                assert!(
                    (a - b).abs() <= 64.0 * f64::EPSILON * b,
                    "d {alpha} {x}: {a} vs {b}"
                );
            }
            let w = DVec3::new(0.6, 0.0, 0.8);
            let (a, b) = (lobe.lambda(w), g.lambda(w));
            assert!(
                (a - b).abs() <= 64.0 * f64::EPSILON * b,
                "lambda {alpha}: {a} vs {b}"
            );
        }
        let r32 = s::Isotropic::new(alpha as f32).unwrap();
        let lobe = s::GaussianFilteredGgx::new(r32, s::Covariance::ZERO);
        let g = s::Ggx::new(r32);
        for &x in &[0.0f32, 1e-3, 0.5, 3.0, 1e3] {
            let sl = Vec2::new(x * alpha as f32, 0.0);
            let (a, b) = (s::Ndf::p22(&lobe, sl), s::Ndf::p22(&g, sl));
            assert!(
                (a - b).abs() <= 8.0 * f32::EPSILON * b,
                "f32 {alpha} {x}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn rank_one_and_huge_kernels_against_the_reference() {
    // Rank-one kernels along and across the lobe, and kernels 1e3 lobe widths wide, at the
    // peak and out to 50 filtered widths.
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
    let (w64, w32) = check_against_reference(&cs);
    println!("rank-one / 1e3-width kernels: worst f64 {w64:.3e}, f32 {w32:.3e}");
}

#[test]
fn bad_kernels_give_the_sanitised_lobe_and_never_nan() {
    let a = d::Isotropic::new(0.05).unwrap();
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    for k in [
        d::Covariance::new(nan, 0.0, 1.0),
        d::Covariance::new(inf, 0.0, 1.0),
        d::Covariance::new(-inf, 0.0, 1.0),
        d::Covariance::new(1e-3, 5e-3, 1e-3), // indefinite
        d::Covariance::new(-1e-3, 0.0, 1e-3),
        d::Covariance::new(1e300, 0.0, 1e300),
    ] {
        let lobe = d::GaussianFilteredGgx::new(a, k);
        // Documented: the lobe of the sanitised kernel.
        assert_eq!(lobe, d::GaussianFilteredGgx::new(a, k.sanitized()), "{k:?}");
        for sl in [DVec2::ZERO, DVec2::new(0.1, -0.3), DVec2::new(1e10, 1.0)] {
            let v = lobe.p22(sl);
            assert!(v.is_finite() && v >= 0.0, "{k:?} {sl}: {v}");
        }
        for sl in [
            DVec2::new(nan, 0.0),
            DVec2::new(inf, 1.0),
            DVec2::splat(f64::MAX),
        ] {
            assert_eq!(lobe.p22(sl), 0.0, "{k:?} {sl}");
        }
        let l = lobe.lambda(DVec3::new(0.3, 0.2, 0.5));
        assert!(l.is_finite() && l >= 0.0, "{k:?}: lambda {l}");
    }
    // Roughness range edges with the widest kernel: finite everywhere, both precisions.
    for &alpha in &[1e-8f32, 1e4] {
        for kk in [0.0f32, 1e-30, 1.0, 1e8] {
            let lobe = s::GaussianFilteredGgx::new(
                s::Isotropic::new(alpha).unwrap(),
                s::Covariance::new(kk, 0.0, 0.5 * kk),
            );
            for sl in [
                Vec2::ZERO,
                Vec2::new(1e-8, 0.0),
                Vec2::new(1.0, 1.0),
                Vec2::splat(3e38),
            ] {
                let v = s::Ndf::p22(&lobe, sl);
                assert!(v.is_finite() && v >= 0.0, "{alpha} {kk} {sl}: {v}");
            }
            for mm in [
                Vec3::Z,
                Vec3::new(0.6, 0.0, 0.8),
                Vec3::new(1.0, 0.0, 1e-20),
            ] {
                let v = s::Ndf::d(&lobe, mm);
                assert!(v.is_finite() && v >= 0.0, "{alpha} {kk} d({mm}): {v}");
                let l = s::Ndf::lambda(&lobe, mm);
                assert!(l >= 0.0, "{alpha} {kk} lambda({mm}): {l}");
            }
        }
    }
}

#[test]
fn normalised_and_smith_identity_with_the_filtered_lambda() {
    // In the frame (e, e_perp) of the view's azimuth, the marginal slope density
    // P2(x) = integral P22(x e + y e_perp) dy (of the code's own p22) must integrate to one,
    // and the Smith identity integral (o.m)+ D(m) dm = o_z (1 + Lambda(o)) (Heitz 2014 eq. 19)
    // reduces to Lambda(o) = (1 / mu) integral_mu^inf (x - mu) P2(x) dx, mu = cot theta_o
    // (Heitz 2014 eq. 72; the slope mean is zero). Both by f64 adaptive quadrature (inner
    // 1e-11, outer 1e-9 relative). Tolerance 1e-7 relative: the quadratures' goals with room.
    use filtered_ndf::testing::quadrature::{integrate, integrate_line};
    for (alpha, kw) in [(0.05, 0.3), (0.2, 3.0), (0.01, 20.0)] {
        let a = d::RoughnessMatrix::new(alpha * alpha, 0.2 * alpha * alpha, 0.6 * alpha * alpha)
            .unwrap();
        let (k11, k12, k22) = rotated((kw * alpha).powi(2), 0.2 * (kw * alpha).powi(2), 1.0);
        let lobe = d::GaussianFilteredGgx::new(a, d::Covariance::new(k11, k12, k22));
        let w = (alpha * alpha + 2.0 * k11.max(k22)).sqrt();
        let inner = Tolerance::relative(1e-11);
        let outer = Tolerance::relative(1e-9);
        let e = DVec2::new(0.8, 0.6);
        let ep = DVec2::new(-0.6, 0.8);
        let p2 = |x: f64| integrate_line(|y| lobe.p22(x * e + y * ep), 0.0, w, inner).value;
        let mass = integrate_line(p2, 0.0, w, outer).value;
        assert!((mass - 1.0).abs() < 1e-7, "{alpha} {kw}: mass {mass}");
        for deg in [20.0f64, 60.0, 85.0] {
            let t = deg.to_radians();
            let o = DVec3::new(t.sin() * e.x, t.sin() * e.y, t.cos());
            let mu = 1.0 / t.tan();
            // x = mu + w u / (1 - u), u in [0, 1).
            let v = integrate(
                |u| {
                    let den = 1.0 - u;
                    let x = mu + w * u / den;
                    let r = (x - mu) * p2(x) * w / (den * den);
                    if r.is_finite() { r } else { 0.0 }
                },
                0.0,
                1.0,
                outer,
            );
            let want = v.value / mu;
            let got = lobe.lambda(o);
            assert!(
                (got - want).abs() < 1e-7 * want + 1e-12,
                "{alpha} {kw} {deg}: lambda {got} vs {want}"
            );
        }
    }
}

#[test]
fn beckmann_through_the_same_entry_is_its_exact_filter() {
    use filtered_ndf::f64::filter::{ExactGaussian, Filterable};
    let r = d::RoughnessMatrix::new(0.01, 0.002, 0.004).unwrap();
    // A footprint well inside lambda = 1: the kernel is sigma^2 (u u^T + v v^T), unclamped.
    let (u, v) = (DVec2::new(0.08, 0.03), DVec2::new(-0.02, 0.09));
    let fp = d::Footprint::from_slope_derivatives(u, v);
    let k = d::Covariance::new(
        0.25 * (u.x * u.x + v.x * v.x),
        0.25 * (u.x * u.y + v.x * v.y),
        0.25 * (u.y * u.y + v.y * v.y),
    );
    let b = d::Beckmann::new(r).filtered(fp, ExactGaussian::KHPL16);
    for sl in [DVec2::ZERO, DVec2::new(0.1, 0.05), DVec2::new(-0.2, 0.3)] {
        let e = gref::beckmann(r, k, sl, Tolerance::relative(1e-12));
        assert!(
            (b.p22(sl) - e.value).abs() <= 1e-10 * e.value + e.error,
            "{sl}"
        );
    }
    let g = d::Ggx::new(r).filtered(fp, ExactGaussian::KHPL16);
    for sl in [DVec2::ZERO, DVec2::new(0.1, 0.05)] {
        let e = gref::ggx(r, k, sl, Tolerance::relative(1e-12));
        assert!(
            (g.p22(sl) - e.value).abs() <= 1e-10 * e.value + e.error,
            "{sl}"
        );
    }
}

/// Beckmann's `Lambda` for `a = cot(theta) / alpha`, `(e^-a^2 / (a sqrt(pi)) - erfc(a)) / 2`
/// with libm's `erfc` (the cancellation loses `log10(2 a^2)` digits: `< 2` for `a < 6`, and the
/// components beyond are `< 1e-17` of the total in the cases below).
fn beckmann_lambda_ref(a: f64) -> f64 {
    if a <= 0.0 {
        return f64::INFINITY;
    }
    let v = 0.5 * ((-a * a).exp() / (a * std::f64::consts::PI.sqrt()) - libm::erfc(a));
    v.max(0.0)
}

/// The filtered `Lambda` as the mixture of Beckmann components (module docs: `Lambda(o) =
/// integral e^-w Lambda_B(o; A / w + 2 Sigma) dw`), by adaptive quadrature in `w = u^2`
/// (smooth at `u = 0`), for `qa = o^T A o`, `qs = o^T Sigma o`, `oz` of a unit `o`: an
/// evaluation independent of the code under test (which uses a Gaussian expectation of GGX's
/// closed form).
fn lambda_ref(qa: f64, qs: f64, oz: f64) -> filtered_ndf::testing::quadrature::Estimate {
    use filtered_ndf::testing::quadrature::{Estimate, integrate};
    let f = |u: f64| {
        let w = u * u;
        if w == 0.0 {
            // u Lambda_B(a(u^2)) -> sqrt(qa) / (2 sqrt(pi) oz) as u -> 0.
            return 2.0 * qa.sqrt() / (2.0 * std::f64::consts::PI.sqrt() * oz);
        }
        let a = oz / (qa / w + 2.0 * qs).sqrt();
        2.0 * u * (-w).exp() * beckmann_lambda_ref(a)
    };
    // The features sit at u ~ sqrt(qa) / oz (the lobe's components seen at the view's
    // slope) and u ~ 1 (the mixing density): doubling intervals from 1e-2 of the first to 8.
    let mut lo = 0.0;
    let mut hi = 1e-2 * (qa.sqrt() / oz).min(1.0);
    let mut total = Estimate {
        value: 0.0,
        error: 0.0,
    };
    while lo < 8.0 {
        let e = integrate(f, lo, hi.min(8.0), Tolerance::relative(1e-14));
        total.value += e.value;
        total.error += e.error;
        lo = hi;
        hi *= 2.0;
    }
    total
}

#[test]
fn lambda_against_the_mixture_reference() {
    // The seeded lobes of the p22 test, views from the pole to 89.9 degrees (one in four
    // beyond 80), azimuth random. Targets as for p22: 1e-10 (f64) and 1e-5 (f32) relative,
    // plus the reference's estimate. Cases with Lambda < 1e-30 are compared absolutely
    // (their G1 is 1 in both precisions).
    let cs = cases(120, 0x1A3B_0017);
    let mut r = Rng(0x1A3B);
    let (mut w64, mut w32) = (0.0_f64, 0.0_f64);
    for (i, c) in cs.iter().enumerate() {
        let (a, k, _) = lobe64(c);
        let lobe = d::GaussianFilteredGgx::new(a, k);
        let a32 = s::RoughnessMatrix::new(c.a.0, c.a.1, c.a.2).unwrap();
        let lobe32 = s::GaussianFilteredGgx::new(a32, s::Covariance::new(c.k.0, c.k.1, c.k.2));
        for _ in 0..4 {
            let deg = if i % 4 == 3 {
                r.range(80.0, 89.9)
            } else {
                r.range(0.0, 80.0)
            };
            let t = (deg as f32).to_radians();
            let phi = r.range(0.0, std::f64::consts::TAU) as f32;
            let o32 = Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos());
            // The reference sees the f32 direction exactly, normalised in f64 as the code does.
            let o = DVec3::new(o32.x as f64, o32.y as f64, o32.z as f64).normalize();
            let qa = a.quadratic(DVec2::new(o.x, o.y));
            // Each lobe filters with its sanitised kernel (rank-one kernels are indefinite by
            // rounding in one precision or the other): the reference takes the same one.
            let k64 = k.sanitized();
            let k32 = s::Covariance::new(c.k.0, c.k.1, c.k.2).sanitized();
            let qs = |k: (f64, f64, f64)| k.0 * o.x * o.x + 2.0 * k.1 * o.x * o.y + k.2 * o.y * o.y;
            for (wide, qs) in [
                (true, qs((k64.s11, k64.s12, k64.s22))),
                (false, qs((k32.s11 as f64, k32.s12 as f64, k32.s22 as f64))),
            ] {
                let e = lambda_ref(qa, qs, o.z);
                let rel_ref = e.error / e.value;
                assert!(rel_ref < 1e-11, "reference not converged: {c:?} {o}: {e:?}");
                let v = if wide {
                    lobe.lambda(o)
                } else {
                    s::Ndf::lambda(&lobe32, o32) as f64
                };
                if e.value < 1e-30 {
                    assert!(v < 1e-29, "{c:?} {o}: {v} vs {e:?}");
                    continue;
                }
                let r = (v - e.value).abs() / e.value;
                let (tol, worst) = if wide {
                    (1e-10, &mut w64)
                } else {
                    (1e-5, &mut w32)
                };
                assert!(
                    r <= tol + rel_ref,
                    "{wide} {c:?} {o}: {v} vs {e:?} ({r:.3e})"
                );
                *worst = worst.max(r);
            }
        }
    }
    println!("lambda: worst relative error f64 {w64:.3e}, f32 {w32:.3e}");
}

#[test]
fn p22_on_both_sides_of_the_rule_switches() {
    // Isotropic lobe, kernel along x (rank one or isotropic), slope along x: 2 l1 = 2 k / a2 and
    // q = s_x^2 / a2, placed at 0.9, 1 and 1.1 times the Gauss-Laguerre edge of each precision
    // (2 l1 = r (1 + q), r = 0.0177 in f32, 0.01 in f64) and of the far tail (1 + q = K 2 l1), q
    // from 0 to 3e7 (where the plateau condition moves the edge).
    let alpha = 0.01f64;
    let a2 = alpha * alpha;
    let mut cs = Vec::new();
    for edge in [0.0177, 0.01, 1.0 / 3.2e5, 1.0 / 3.2e7] {
        for f in [0.9, 1.0, 1.1] {
            for q in [0.0, 30.0, 3e3, 3e5, 3e7] {
                for iso in [false, true] {
                    let tl1 = edge * f * (1.0 + q);
                    let k = 0.5 * tl1 * a2;
                    cs.push(Case {
                        a: (a2 as f32, 0.0, a2 as f32),
                        k: (k as f32, 0.0, if iso { k as f32 } else { 0.0 }),
                        s: ((alpha * q.sqrt()) as f32, 0.0),
                    });
                }
            }
        }
    }
    let (w64, w32) = check_against_reference(&cs);
    println!("rule switches: worst f64 {w64:.3e}, f32 {w32:.3e}");
}

#[test]
fn p22_on_both_sides_of_the_plateau_edge() {
    // Beyond 1 + q = GL_WIDE (2.8e10 in f32, 7e19 in f64) Gauss-Laguerre's edge is no longer
    // 2 l1 = r (1 + q) but the plateau condition 2 l1 (P + 1.5 ln(1 + q)) = 1 + q (P = 20 in
    // f32, 31.5 in f64; module docs of the quadrature, item 4): the kernel at 0.9, 1 and 1.1
    // times that edge, 1 + q at half and twice GL_WIDE of each precision, rank-one and
    // isotropic kernels; both precisions against the 2D reference at every case.
    let alpha = 0.01f64;
    let a2 = alpha * alpha;
    let mut cs = Vec::new();
    for (wide, plateau) in [(2.8e10, 20.0), (7e19, 31.5)] {
        for beta in [0.5 * wide, 2.0 * wide] {
            let edge = beta / (plateau + 1.5 * f64::ln(beta));
            for f in [0.9, 1.0, 1.1] {
                for iso in [false, true] {
                    let k = 0.5 * edge * f * a2;
                    cs.push(Case {
                        a: (a2 as f32, 0.0, a2 as f32),
                        k: (k as f32, 0.0, if iso { k as f32 } else { 0.0 }),
                        s: ((alpha * (beta - 1.0).sqrt()) as f32, 0.0),
                    });
                }
            }
        }
    }
    let (w64, w32) = check_against_reference(&cs);
    println!("plateau edge: worst f64 {w64:.3e}, f32 {w32:.3e}");
}

#[test]
fn lambda_on_both_sides_of_the_rule_switch() {
    // delta_s^2 = qs / (qa + o_z^2) at 0.9, 1 and 1.1 times the Gauss-Hermite edge (0.01), for
    // lobe-dominated, balanced and kernel-dominated views.
    let a = d::Isotropic::new(0.1).unwrap();
    let (mut w64, mut w32) = (0.0_f64, 0.0_f64);
    for deg in [30.0f64, 70.0, 85.0] {
        let t = deg.to_radians();
        let o = DVec3::new(t.sin(), 0.0, t.cos());
        let qa = 0.01 * t.sin() * t.sin();
        for f in [0.9, 1.0, 1.1] {
            let qs = 0.01 * f * (qa + o.z * o.z);
            // Sigma = diag(k, 0): o^T Sigma o = k sin^2 t.
            let k = qs / (t.sin() * t.sin());
            let kf = k as f32;
            let lobe = d::GaussianFilteredGgx::new(a, d::Covariance::new(kf as f64, 0.0, 0.0));
            let lobe32 = s::GaussianFilteredGgx::new(
                s::Isotropic::new(0.1).unwrap(),
                s::Covariance::new(kf, 0.0, 0.0),
            );
            let o32 = Vec3::new(o.x as f32, 0.0, o.z as f32);
            let o64 = DVec3::new(o32.x as f64, 0.0, o32.z as f64).normalize();
            let qa = a.quadratic(DVec2::new(o64.x, o64.y));
            let e = lambda_ref(qa, kf as f64 * o64.x * o64.x, o64.z);
            let rel_ref = e.error / e.value;
            let (v64, v32) = (lobe.lambda(o64), s::Ndf::lambda(&lobe32, o32) as f64);
            let (r64, r32) = (
                (v64 - e.value).abs() / e.value,
                (v32 - e.value).abs() / e.value,
            );
            assert!(r64 <= 1e-10 + rel_ref, "f64 {deg} {f}: {v64} vs {e:?}");
            assert!(r32 <= 1e-5 + rel_ref, "f32 {deg} {f}: {v32} vs {e:?}");
            w64 = w64.max(r64);
            w32 = w32.max(r32);
        }
    }
    println!("lambda switch: worst f64 {w64:.3e}, f32 {w32:.3e}");
}
