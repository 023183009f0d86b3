//! Sampling: pdf normalisation by quadrature, closed-form slope statistics of the sampled
//! lobes for full matrices, the accuracy of the Beckmann visible-slope inversion, and the
//! robustness contract at the extremes (both precisions). The chi-square fits are in
//! `tests/sampling_chi2.rs`.

use filtered_ndf::testing::quadrature::{Tolerance, integrate};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------
// Shared helpers (f64).

mod common;

mod f64_helpers {
    use super::*;
    use crate::common::whitening::Whitening;
    use glam::{DVec2, DVec3};

    /// `integral of pdf(m) d omega` over the hemisphere, in the polar coordinates
    /// `(cos theta, phi)` of the whitened normal `n ~ (-w, 1)` (`s = B w`,
    /// `|w|^2 = (1 - c^2) / c^2`, `d omega = m_z^3 ds`, `ds = sqrt(det A) dw`,
    /// `dw = d|w|^2 dphi / 2`), so that the lobe is resolved at every roughness and
    /// condition number, and the grazing tail of the visible pdf (which grows like
    /// `|w|` against the `|w|^-4` of P22) stays bounded near `c = 0`.
    ///
    /// With a view direction the inner integral is split at the visibility cut-off
    /// `wo.m = 0`, which in whitened slopes is the line `w.(B wo_xy) = wo_z`: at low
    /// roughness it lies deep in the tail (`c ~ alpha`), where no quadrature node of an
    /// unsplit rule would land.
    pub fn integrate_hemisphere(
        wh: &Whitening,
        pdf: impl Fn(DVec3) -> f64,
        wo: Option<DVec3>,
        tol: Tolerance,
    ) -> f64 {
        let b = wh.b;
        let f = |phi: f64, c: f64| {
            let q = (1.0 - c * c) / (c * c);
            let w = DVec2::new(phi.cos(), phi.sin()) * q.sqrt();
            let s = Whitening::apply(&b, w);
            let m = DVec3::new(-s.x, -s.y, 1.0).normalize();
            let v = pdf(m) * m.z.powi(3) * wh.sqrt_det / (c * c * c);
            if v.is_finite() { v } else { 0.0 }
        };
        let inner_tol = Tolerance {
            rel: tol.rel * 0.1,
            abs: tol.abs * 0.1,
            ..tol
        };
        integrate(
            |phi| {
                let cut = wo.and_then(|wo| {
                    let wxy = Whitening::apply(&b, DVec2::new(wo.x, wo.y));
                    let d = wxy.dot(DVec2::new(phi.cos(), phi.sin()));
                    (d > 0.0).then(|| {
                        let rho = wo.z / d;
                        1.0 / (1.0 + rho * rho).sqrt()
                    })
                });
                match cut {
                    Some(cc) if cc > 0.0 && cc < 1.0 => {
                        integrate(|c| f(phi, c), 0.0, cc, inner_tol).value
                            + integrate(|c| f(phi, c), cc, 1.0, inner_tol).value
                    }
                    _ => integrate(|c| f(phi, c), 0.0, 1.0, inner_tol).value,
                }
            },
            0.0,
            2.0 * PI,
            tol,
        )
        .value
    }

    pub fn view(theta_deg: f64, phi: f64) -> DVec3 {
        let t = theta_deg.to_radians();
        DVec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
    }
}

use common::whitening::Whitening;
use f64_helpers::{integrate_hemisphere, view};
use filtered_ndf::f64::{
    AxisAligned, Beckmann, Ggx, Isotropic, NdfSampling, Roughness, RoughnessMatrix,
};
use filtered_ndf::testing::rng::SplitMix64;
use glam::{DVec2, DVec3};

/// `diag(a^2, a^2 / cond)` rotated by `angle`.
fn rotated(a: f64, cond: f64, angle: f64) -> RoughnessMatrix {
    let (l1, l2) = (a * a, a * a / cond);
    let (c, s) = (angle.cos(), angle.sin());
    RoughnessMatrix::new(
        c * c * l1 + s * s * l2,
        c * s * (l1 - l2),
        s * s * l1 + c * c * l2,
    )
    .unwrap()
}

// ---------------------------------------------------------------------------------------
// Normalisation.

fn check_normalised<N: NdfSampling, R: Roughness>(name: &str, ndf: &N, r: &R) {
    let wh = Whitening::new(r);
    // rel 1e-10 requested, 1e-9 asserted (the nested rule's error adds over the outer nodes).
    let tol = Tolerance {
        abs: 1e-13,
        rel: 1e-10,
        max_intervals: 2000,
    };
    let total = integrate_hemisphere(&wh, |m| ndf.normal_pdf(m), None, tol);
    assert!(
        (total - 1.0).abs() < 1e-9,
        "{name}: D cos integrates to {total}"
    );
    for &deg in &[0.0, 15.0, 30.0, 80.0, 89.9, 89.99] {
        let wo = view(deg, 0.7);
        let total = integrate_hemisphere(&wh, |m| ndf.visible_normal_pdf(wo, m), Some(wo), tol);
        assert!(
            (total - 1.0).abs() < 1e-9,
            "{name} view {deg}: D_wo integrates to {total}"
        );
    }
}

#[test]
fn pdfs_integrate_to_one() {
    for &a in &[1e-4, 1e-3, 0.1, 0.8, 2.0] {
        let iso = Isotropic::new(a).unwrap();
        let axis = AxisAligned::new(a, a / 100.0).unwrap(); // condition number 1e4
        let mat = rotated(a, 1e4, 0.4);
        check_normalised(&format!("ggx iso {a}"), &Ggx::new(iso), &iso);
        check_normalised(&format!("ggx axis {a}"), &Ggx::new(axis), &axis);
        check_normalised(&format!("ggx mat {a}"), &Ggx::new(mat), &mat);
        check_normalised(&format!("beck iso {a}"), &Beckmann::new(iso), &iso);
        check_normalised(&format!("beck axis {a}"), &Beckmann::new(axis), &axis);
        check_normalised(&format!("beck mat {a}"), &Beckmann::new(mat), &mat);
    }
}

type BoxedPdf = Box<dyn Fn(DVec3, DVec3) -> f64>;

#[test]
fn reflection_pdf_integrates_to_one_over_the_sphere() {
    // Every m maps to one wi, so the reflection density integrates to 1 over the whole sphere
    // of wi (including directions below the surface). Integrated to rel 1e-10 per rule;
    // asserted to 1e-9 plus the rules' summed error estimate (the nested rules' estimates
    // are per inner integral, summed over the outer nodes: ten times the goal covers them).
    for &a in &[0.2, 0.8] {
        let ndfs: [(&str, BoxedPdf); 3] = [
            ("ggx iso", {
                let n = Ggx::new(Isotropic::new(a).unwrap());
                Box::new(move |o, i| n.reflection_pdf(o, i))
            }),
            ("ggx mat", {
                let n = Ggx::new(rotated(a, 4.0, 1.1));
                Box::new(move |o, i| n.reflection_pdf(o, i))
            }),
            ("beck mat", {
                let n = Beckmann::new(rotated(a, 4.0, 1.1));
                Box::new(move |o, i| n.reflection_pdf(o, i))
            }),
        ];
        for (name, pdf) in &ndfs {
            for &deg in &[0.0, 30.0, 80.0] {
                let wo = view(deg, 0.3);
                // (cos theta_i, phi_i) with break points: the density jumps across
                // wi_z = -wo_z (where the half vector crosses the horizon and GGX's D(m) stays
                // positive), and the lobe sits at the mirror direction (wi_z = wo_z, phi_i =
                // phi_o + pi), where the outer and inner rules are split as well.
                let tol = Tolerance {
                    abs: 1e-13,
                    rel: 1e-10,
                    max_intervals: 2000,
                };
                let phi_r = 0.3 + PI;
                let inner = |phi: f64| {
                    let mut sum = 0.0;
                    let cuts = [-1.0, -wo.z, wo.z, 1.0];
                    for k in 0..3 {
                        if cuts[k + 1] > cuts[k] {
                            sum += integrate(
                                |ct| {
                                    let st = (1.0 - ct * ct).max(0.0).sqrt();
                                    pdf(wo, DVec3::new(st * phi.cos(), st * phi.sin(), ct))
                                },
                                cuts[k],
                                cuts[k + 1],
                                tol,
                            )
                            .value;
                        }
                    }
                    sum
                };
                let e = integrate(&inner, phi_r - PI, phi_r, tol);
                let e2 = integrate(&inner, phi_r, phi_r + PI, tol);
                let e = filtered_ndf::testing::quadrature::Estimate {
                    value: e.value + e2.value,
                    error: e.error + e2.error,
                };
                assert!(
                    (e.value - 1.0).abs() < 1e-9 + e.error && e.error < 1e-8,
                    "{name} a={a} view {deg}: {e:?}"
                );
            }
        }
    }
}

#[test]
fn reflection_pdf_is_the_half_vector_jacobian_of_the_visible_pdf() {
    // pdf(wi) = D_wo(m) / (4 wo.m) with m the half vector: checked pointwise against the
    // visible pdf (1e-12 relative: the two paths round differently).
    let ndf = Beckmann::new(rotated(0.3, 20.0, 0.5));
    let wo = view(50.0, 2.0);
    let mut rng = SplitMix64(7);
    for _ in 0..200 {
        let m = ndf
            .sample_visible_normal(wo, DVec2::new(rng.uniform(), rng.uniform()))
            .unwrap();
        let wi = filtered_ndf::f64::sampling::reflect(wo, m);
        let expect = ndf.visible_normal_pdf(wo, m) / (4.0 * wo.dot(m));
        let got = ndf.reflection_pdf(wo, wi);
        assert!((got - expect).abs() <= 1e-12 * expect, "{got} vs {expect}");
        let from_m = ndf.reflection_pdf_from_normal(wo, m);
        assert!(
            (from_m - expect).abs() <= 1e-12 * expect,
            "{from_m} vs {expect}"
        );
        assert!((wi.length() - 1.0).abs() < 1e-14);
    }
}

// ---------------------------------------------------------------------------------------
// Closed-form slope statistics of the full-matrix lobes.

const N_MOMENTS: usize = 200_000;
/// Kolmogorov-Smirnov critical value at a per-test level of about 1e-4
/// (`sqrt(ln(2 / 1e-4) / 2) = 2.23`), so that the ~50 KS tests of this file have a combined
/// false-alarm rate below 1%.
const KS_C: f64 = 2.23;

fn ks_statistic(mut xs: Vec<f64>, cdf: impl Fn(f64) -> f64) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len() as f64;
    xs.iter()
        .enumerate()
        .map(|(i, &x)| {
            let c = cdf(x);
            (c - i as f64 / n).abs().max((c - (i + 1) as f64 / n).abs())
        })
        .fold(0.0, f64::max)
}

fn slopes(mut sample: impl FnMut(DVec2) -> DVec3, seed: u64) -> Vec<DVec2> {
    let mut rng = SplitMix64(seed);
    (0..N_MOMENTS)
        .map(|_| {
            let m = sample(DVec2::new(rng.uniform(), rng.uniform()));
            DVec2::new(-m.x / m.z, -m.y / m.z)
        })
        .collect()
}

fn check_slope_statistics(name: &str, s: &[DVec2], a: RoughnessMatrix, beckmann: bool) {
    let (a11, a12, a22) = a.entries();
    let det = a11 * a22 - a12 * a12;
    let ks_max = KS_C / (N_MOMENTS as f64).sqrt();
    // The quadratic form q = s^T A^-1 s: P(q <= x) = 1 - exp(-x) (Beckmann: chi-square with 2
    // dof of the whitened Gaussian / 2) or x / (1 + x) (GGX: the radial CDF of P22).
    let q: Vec<f64> = s
        .iter()
        .map(|s| (a22 * s.x * s.x - 2.0 * a12 * s.x * s.y + a11 * s.y * s.y) / det)
        .collect();
    let d = if beckmann {
        ks_statistic(q, |x| -(-x).exp_m1())
    } else {
        ks_statistic(q, |x| x / (1.0 + x))
    };
    assert!(d < ks_max, "{name}: KS of s^T A^-1 s = {d} > {ks_max}");
    // Projections v.s: Beckmann N(0, v^T A v / 2); GGX Student-t with 2 dof and scale
    // sqrt(v^T A v / 2) (P22 is the bivariate t_2 with scale matrix A / 2), CDF
    // 1/2 + z / (2 sqrt(2 + z^2)). These see the orientation of A, which q does not.
    for v in [
        DVec2::X,
        DVec2::Y,
        DVec2::new(1.0, 1.0),
        DVec2::new(1.0, -2.0),
    ] {
        let v = v.normalize();
        let sigma = (0.5 * (a11 * v.x * v.x + 2.0 * a12 * v.x * v.y + a22 * v.y * v.y)).sqrt();
        let proj: Vec<f64> = s.iter().map(|s| s.dot(v) / sigma).collect();
        let d = if beckmann {
            ks_statistic(proj, |z| 0.5 * filtered_ndf::math::erfc(-z / 2f64.sqrt()))
        } else {
            ks_statistic(proj, |z| 0.5 + z / (2.0 * (2.0 + z * z).sqrt()))
        };
        assert!(
            d < ks_max,
            "{name}: KS of the projection on {v} = {d} > {ks_max}"
        );
    }
    if beckmann {
        // Mean 0 and covariance A / 2 (KHPL16 eq. 14), each within 5 standard errors:
        // se(mean_i) = sqrt(S_ii / N), se(S_ij) = sqrt((S_ii S_jj + S_ij^2) / N).
        let n = s.len() as f64;
        let mean = s.iter().fold(DVec2::ZERO, |acc, s| acc + *s) / n;
        let (mut c11, mut c12, mut c22) = (0.0, 0.0, 0.0);
        for s in s {
            let d = *s - mean;
            c11 += d.x * d.x;
            c12 += d.x * d.y;
            c22 += d.y * d.y;
        }
        let (c11, c12, c22) = (c11 / n, c12 / n, c22 / n);
        let (s11, s12, s22) = (a11 / 2.0, a12 / 2.0, a22 / 2.0);
        assert!(mean.x.abs() < 5.0 * (s11 / n).sqrt(), "{name}: mean {mean}");
        assert!(mean.y.abs() < 5.0 * (s22 / n).sqrt(), "{name}: mean {mean}");
        assert!(
            (c11 - s11).abs() < 5.0 * (2.0 * s11 * s11 / n).sqrt(),
            "{name}: c11 {c11} vs {s11}"
        );
        assert!(
            (c22 - s22).abs() < 5.0 * (2.0 * s22 * s22 / n).sqrt(),
            "{name}: c22 {c22} vs {s22}"
        );
        assert!(
            (c12 - s12).abs() < 5.0 * ((s11 * s22 + s12 * s12) / n).sqrt(),
            "{name}: c12 {c12} vs {s12}"
        );
    }
}

#[test]
fn full_matrix_slope_statistics_match_closed_forms() {
    // D cos sampling and, at normal incidence (where D_wo(m) = D(m) m_z), visible-normal
    // sampling, for a moderate and a condition-1e4 matrix.
    for (k, a) in [rotated(0.5, 6.0, 0.7), rotated(0.05, 1e4, -1.2)]
        .into_iter()
        .enumerate()
    {
        let seed = 100 * k as u64;
        let g = Ggx::new(a);
        let b = Beckmann::new(a);
        check_slope_statistics(
            "ggx D cos",
            &slopes(|u| g.sample_normal(u), seed + 1),
            a,
            false,
        );
        check_slope_statistics(
            "ggx visible 0",
            &slopes(|u| g.sample_visible_normal(DVec3::Z, u).unwrap(), seed + 2),
            a,
            false,
        );
        check_slope_statistics(
            "beck D cos",
            &slopes(|u| b.sample_normal(u), seed + 3),
            a,
            true,
        );
        check_slope_statistics(
            "beck visible 0",
            &slopes(|u| b.sample_visible_normal(DVec3::Z, u).unwrap(), seed + 4),
            a,
            true,
        );
    }
}

// ---------------------------------------------------------------------------------------
// The Beckmann visible-slope inversion.

#[test]
fn beckmann_visible_slope_quantile_matches_the_quadrature_cdf() {
    use filtered_ndf::f64::sampling::beckmann::visible_slope_quantile;
    let tol = Tolerance {
        abs: 1e-300,
        rel: 1e-14,
        max_intervals: 2000,
    };
    for &deg in &[0.0, 15.0, 45.0, 80.0, 89.0, 89.9, 89.999, 90.0] {
        let t: f64 = f64::to_radians(deg);
        let (c, s) = if deg == 90.0 {
            (0.0, 1.0)
        } else {
            (t.cos(), t.sin())
        };
        let mu = if s > 0.0 { (c / s).min(30.0) } else { 30.0 };
        let density = |x: f64| (-x * x).exp() * (c - s * x).max(0.0);
        let total = integrate(density, -30.0, mu, tol);
        let mut prev = f64::NEG_INFINITY;
        for &u in &[1e-12, 1e-6, 0.01, 0.3, 0.5, 0.9, 0.999_999, 1.0 - 1e-12] {
            let x = visible_slope_quantile(c, s, u);
            assert!(x > prev, "view {deg}: not increasing in u at {u}");
            assert!(
                s * x < c || (deg == 90.0 && x <= 0.0),
                "view {deg} u {u}: x={x} >= cot"
            );
            prev = x;
            // The smaller tail of the distribution at x, by quadrature of that side (the
            // other side's 1 - C would lose the tail's digits near u = 1), against u or 1 - u.
            let (side, tail) = if u <= 0.5 {
                (integrate(density, -30.0, x, tol), u)
            } else {
                (integrate(density, x, mu, tol), 1.0 - u)
            };
            let got = side.value / total.value;
            // The solver's residual bound is 8 ulps of u (relative to u, not to the tail: near
            // u = 1 that is 16 eps absolute, all the digits u itself has there), plus the
            // rounding of erfc and exp, 1e-12 relative to the tail; plus four times the
            // quadrature's own estimate (both integrals, relative), required to meet 1e-12.
            // Or (the solver's other documented exit) x within 1e-13 (1 + |x|) of the exact
            // quantile: that times the density at x in u (dominant in the far tails, where
            // the residual sits at erfc's rounding).
            let bracket = density(x) / total.value * 1e-13 * (1.0 + x.abs());
            let qerr = side.error / side.value + total.error / total.value;
            assert!(
                qerr <= 1e-12,
                "view {deg} u {u}: quadrature {side:?} {total:?}"
            );
            assert!(
                (got - tail).abs()
                    <= (1e-12 + 4.0 * qerr) * tail + 16.0 * f64::EPSILON * u + bracket,
                "view {deg}: tail of x({u}) = {got}, error {:e}",
                (got - tail) / tail
            );
        }
    }
    // Grazing limit in closed form: density -x exp(-x^2) on x < 0, C(x) = exp(-x^2).
    for &u in &[1e-9, 0.2, 0.7] {
        let x = visible_slope_quantile(0.0, 1.0, u);
        assert!((x + (-u.ln()).sqrt()).abs() < 1e-12, "{u}: {x}");
    }
}

// ---------------------------------------------------------------------------------------
// Robustness at the extremes, both precisions.

macro_rules! robustness {
    ($modname:ident, $prec:ident, $F:ty, $V2:ty, $V3:ty, $len_tol:expr) => {
        mod $modname {
            use filtered_ndf::$prec::{
                AxisAligned, Beckmann, Ggx, Isotropic, NdfSampling, Roughness, RoughnessMatrix,
                sampling::reflect,
            };

            type F = $F;
            type V2 = $V2;
            type V3 = $V3;

            const US: [F; 11] = [
                0.0,
                1e-7,
                0.25,
                0.5,
                0.999,
                1.0 - <$F>::EPSILON / 2.0,
                1.0,
                1.5,
                -0.5,
                <$F>::NAN,
                <$F>::INFINITY,
            ];

            fn interior(u: F) -> bool {
                (1e-3..=0.999).contains(&u)
            }

            fn check<N: NdfSampling>(name: &str, ndf: &N) {
                for &deg in &[0.0 as F, 1e-6, 45.0, 89.0, 89.9, 89.99] {
                    for &phi in &[0.0 as F, 0.4, 2.5] {
                        let t = deg.to_radians();
                        let wo = V3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos());
                        for &u1 in &US {
                            for &u2 in &US {
                                let u = V2::new(u1, u2);
                                let ctx = || format!("{name} view {deg} phi {phi} u {u}");
                                let m = ndf.sample_visible_normal(wo, u).expect("wo above");
                                assert!(m.is_finite(), "{}: {m}", ctx());
                                assert!((m.length() - 1.0).abs() < $len_tol, "{}: {m}", ctx());
                                assert!(m.z > 0.0, "{}: m = {m} below the horizon", ctx());
                                assert!(wo.dot(m) > 0.0, "{}: m = {m} faces away", ctx());
                                let p = ndf.visible_normal_pdf(wo, m);
                                assert!(p.is_finite() && p >= 0.0, "{}: pdf {p}", ctx());
                                let wi = reflect(wo, m);
                                let pr = ndf.reflection_pdf(wo, wi);
                                assert!(pr.is_finite() && pr >= 0.0, "{}: {pr}", ctx());
                                let pm = ndf.reflection_pdf_from_normal(wo, m);
                                assert!(pm.is_finite() && pm >= 0.0, "{}: {pm}", ctx());
                                if interior(u1) && interior(u2) {
                                    assert!(p > 0.0 && pm > 0.0, "{}: pdf {p} {pm}", ctx());
                                    // The recomputed half vector resolves the lobe in f64
                                    // (see the conditioning note of reflection_pdf).
                                    assert!(pr > 0.0 || $len_tol > 1e-6, "{}: {pr}", ctx());
                                }
                                let n = ndf.sample_normal(u);
                                assert!(n.is_finite() && n.z > 0.0, "{}: {n}", ctx());
                                assert!((n.length() - 1.0).abs() < $len_tol, "{}: {n}", ctx());
                                let pn = ndf.normal_pdf(n);
                                assert!(pn.is_finite() && pn >= 0.0, "{}: {pn}", ctx());
                                if interior(u1) && interior(u2) {
                                    assert!(pn > 0.0, "{}: normal pdf {pn}", ctx());
                                }
                            }
                        }
                    }
                }
                // Below, on the horizon, degenerate and non-finite view directions.
                let u = V2::new(0.3, 0.6);
                let m = V3::new(0.1, 0.0, 1.0).normalize();
                for wo in [
                    V3::new(0.0, 0.6, -0.8),
                    V3::new(0.0, 0.0, -1.0),
                    V3::new(1.0, 0.0, 0.0),
                    V3::ZERO,
                    V3::new(F::NAN, 0.0, 1.0),
                    V3::new(0.0, F::INFINITY, 1.0),
                ] {
                    assert!(ndf.sample_visible_normal(wo, u).is_none(), "{name}: {wo}");
                    assert_eq!(ndf.visible_normal_pdf(wo, m), 0.0, "{name}: {wo}");
                    assert_eq!(ndf.reflection_pdf(wo, V3::Z), 0.0, "{name}: {wo}");
                    assert_eq!(ndf.reflection_pdf_from_normal(wo, m), 0.0, "{name}: {wo}");
                }
                // Bad m / wi for the pdfs: 0, never NaN.
                let wo = V3::new(0.3, 0.0, 0.9).normalize();
                for bad in [V3::ZERO, V3::NEG_Z, V3::new(F::NAN, 0.0, 1.0), -wo] {
                    assert_eq!(ndf.visible_normal_pdf(wo, bad), 0.0, "{name}: {bad}");
                    assert_eq!(ndf.normal_pdf(bad), 0.0, "{name}: {bad}");
                    assert_eq!(
                        ndf.reflection_pdf_from_normal(wo, bad),
                        0.0,
                        "{name}: {bad}"
                    );
                }
                assert_eq!(ndf.reflection_pdf(wo, -wo), 0.0, "{name}: wi = -wo");
                assert_eq!(ndf.reflection_pdf(wo, V3::new(F::NAN, 0.0, 1.0)), 0.0);
                // Unnormalised wo: same pdfs.
                let mm = ndf.sample_visible_normal(wo, u).unwrap();
                let p1 = ndf.visible_normal_pdf(wo, mm);
                let p2 = ndf.visible_normal_pdf(wo * 3.0, mm);
                // `wo` enters through `wo.m / wo_z` and `Lambda(wo)` (rescaled, homogeneous):
                // a few roundings each; 64 eps of `F` covers them with margin.
                assert!(
                    (p1 - p2).abs() <= 64.0 * F::EPSILON * p1,
                    "{name}: {p1} vs {p2}"
                );
            }

            fn rotated(a: F, cond: F, angle: F) -> RoughnessMatrix {
                let (l1, l2) = (a * a, a * a / cond);
                let (c, s) = (angle.cos(), angle.sin());
                RoughnessMatrix::new(
                    c * c * l1 + s * s * l2,
                    c * s * (l1 - l2),
                    s * s * l1 + c * c * l2,
                )
                .unwrap()
            }

            fn both<R: Roughness>(name: &str, r: R) {
                check(&format!("ggx {name}"), &Ggx::new(r));
                check(&format!("beckmann {name}"), &Beckmann::new(r));
            }

            #[test]
            fn extremes_never_nan_never_behind_the_horizon() {
                for &a in &[1e-4, 1e-3, 0.5, 1.0, 10.0, 1e3] {
                    both(&format!("iso {a}"), Isotropic::new(a).unwrap());
                    both(
                        &format!("axis {a}"),
                        AxisAligned::new(a, (a * 0.01).max(1e-4)).unwrap(),
                    );
                }
                // Condition number 1e4 (eigenvalues a^2 and a^2 / 1e4), smallest alpha 1e-4.
                for &a in &[1e-2, 1.0, 100.0] {
                    for &ang in &[0.3, 1.3, -2.0] {
                        both(&format!("mat {a} {ang}"), rotated(a, 1e4, ang));
                    }
                }
            }
        }
    };
}

robustness!(robust_f32, f32, f32, glam::Vec2, glam::Vec3, 1e-5);
robustness!(robust_f64, f64, f64, glam::DVec2, glam::DVec3, 1e-12);

#[test]
fn f32_and_f64_samplers_agree() {
    // Same u, same roughness: the f32 sample is the f64 one up to f32 rounding through the
    // warp (1e-4 absolute on a unit vector for moderate roughness and views).
    use filtered_ndf::f32 as s;
    use filtered_ndf::f32::NdfSampling as _;
    let mut rng = SplitMix64(42);
    let a64 = rotated(0.3, 10.0, 0.8);
    let (a11, a12, a22) = a64.entries();
    let a32 = s::RoughnessMatrix::new(a11 as f32, a12 as f32, a22 as f32).unwrap();
    let wo = view(60.0, 1.0);
    let wo32 = glam::Vec3::new(wo.x as f32, wo.y as f32, wo.z as f32);
    for _ in 0..1000 {
        // u below 0.99: near u = 1 the GGX tail amplifies the f32 rounding of u itself.
        let u = DVec2::new(rng.uniform(), 0.99 * rng.uniform());
        let u32 = glam::Vec2::new(u.x as f32, u.y as f32);
        let m64 = Beckmann::new(a64).sample_visible_normal(wo, u).unwrap();
        let m32 = s::Beckmann::new(a32)
            .sample_visible_normal(wo32, u32)
            .unwrap();
        assert!((m64.as_vec3() - m32).length() < 1e-4, "{m64} vs {m32}");
        let g64 = Ggx::new(a64).sample_visible_normal(wo, u).unwrap();
        let g32 = s::Ggx::new(a32).sample_visible_normal(wo32, u32).unwrap();
        assert!((g64.as_vec3() - g32).length() < 1e-4, "{g64} vs {g32}");
    }
}
