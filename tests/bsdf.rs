//! The BSDF layer (`bsdf`): the Fresnel forms against closed forms and published optical
//! constants, the BRDF against a closed-form GGX BRDF written here, the white furnace (the
//! albedo by f64 quadrature against the mean sampled weight), reciprocity, the sampler's
//! random-number dimensions, and bad input. The chi-square test of `sample` against `pdf` is
//! `tests/bsdf_chi2.rs`.

#[path = "common/bsdf_cases.rs"]
mod bsdf_cases;
mod common;

use bsdf_cases::{Grid, cases, cases_with, view};
use filtered_ndf::FresnelError;
use filtered_ndf::f32::bsdf::Bsdf as _;
use filtered_ndf::f32::prelude::Filterable as _;
use filtered_ndf::f64::bsdf::{
    Bsdf, Conductor, Dielectric, Fresnel, FresnelOne, MicrofacetReflection, Schlick,
};
use filtered_ndf::f64::prelude::*;
use filtered_ndf::testing::quadrature::Tolerance;
use filtered_ndf::testing::rng::SplitMix64;
use filtered_ndf::{f32 as s, f64 as d};
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------
// Fresnel: the test side's own formulas.

/// Fresnel's equations for a dielectric, in the textbook form through Snell's law (Hecht,
/// *Optics*, section 4.6): `r_s = (c - eta c_t) / (c + eta c_t)`,
/// `r_p = (eta c - c_t) / (eta c + c_t)`, `c_t = sqrt(1 - (1 - c^2) / eta^2)`; `(R_s, R_p)`,
/// both `1` beyond the critical angle. `c` in `[0, 1]`.
fn textbook_dielectric(eta: f64, c: f64) -> (f64, f64) {
    let sin2_t = (1.0 - c * c) / (eta * eta);
    if sin2_t >= 1.0 {
        return (1.0, 1.0);
    }
    let ct = (1.0 - sin2_t).sqrt();
    let rs = (c - eta * ct) / (c + eta * ct);
    let rp = (eta * c - ct) / (eta * c + ct);
    (rs * rs, rp * rp)
}

/// A conductor's unpolarised reflectance in real arithmetic (the `a^2 + b^2` form of
/// Fresnel's equations with a complex index, as written out in S. Lagarde, "Memo on Fresnel
/// equations", 2013, and pbrt-v3's `FrConductor`): with `t0 = n^2 - k^2 - sin^2`,
/// `a^2 + b^2 = sqrt(t0^2 + 4 n^2 k^2)`, `a = sqrt((a^2 + b^2 + t0) / 2)`,
/// `R_s = (a^2 + b^2 + c^2 - 2 a c) / (a^2 + b^2 + c^2 + 2 a c)`,
/// `R_p = R_s (c^2 (a^2 + b^2) + sin^4 - 2 a c sin^2) / (c^2 (a^2 + b^2) + sin^4 + 2 a c sin^2)`.
fn textbook_conductor(n: f64, k: f64, c: f64) -> f64 {
    let s2 = 1.0 - c * c;
    let t0 = n * n - k * k - s2;
    let ab = (t0 * t0 + 4.0 * n * n * k * k).sqrt();
    let a = (0.5 * (ab + t0)).sqrt();
    let rs = (ab + c * c - 2.0 * a * c) / (ab + c * c + 2.0 * a * c);
    let t3 = c * c * ab + s2 * s2;
    let t4 = 2.0 * a * c * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    0.5 * (rs + rp)
}

/// `cos theta` on a grid of 200 angles from normal incidence to grazing (both included).
fn cosines() -> impl Iterator<Item = f64> {
    (0..=200).map(|i| (i as f64 / 200.0 * 0.5 * PI).cos().max(0.0))
}

#[test]
fn dielectric_at_normal_incidence_is_the_closed_form() {
    // R(0) = ((eta - 1) / (eta + 1))^2 from either side (1e-15 absolute: a few roundings of
    // numbers below 1, squared).
    for eta in [1.0001, 1.33, 1.5, 2.42, 1.0 / 1.5, 0.2] {
        let f = Dielectric::new(eta).unwrap();
        let want = ((eta - 1.0) / (eta + 1.0)).powi(2);
        assert!((f.reflectance(1.0) - want).abs() < 1e-15, "eta {eta}");
        assert!((f.reflectance(-1.0) - want).abs() < 1e-15, "eta {eta}");
        assert!((Schlick::from_ior(eta).unwrap().reflectance(1.0) - want).abs() < 1e-15);
    }
    assert_eq!(Dielectric::new(1.0).unwrap().reflectance(0.3), 0.0);
    assert_eq!(Dielectric::new(1.0).unwrap().reflectance(0.0), 0.0);
}

#[test]
fn dielectric_is_fresnel_equations_at_every_angle() {
    // Walter et al.'s eq. 22 (the code) against the textbook r_s, r_p (this file): 1e-14
    // absolute (two different roundings of numbers in [0, 1]: the ratios (g - c) / (g + c)
    // and r_s, r_p each cancel where R is small, up to ~30 ulps of R apart).
    for eta in [1.33, 1.5, 2.42, 1.0 / 1.33, 1.0 / 1.5] {
        let f = Dielectric::new(eta).unwrap();
        for c in cosines() {
            let (rs, rp) = textbook_dielectric(eta, c);
            let want = 0.5 * (rs + rp);
            let got = f.reflectance(c);
            assert!(
                (got - want).abs() < 1e-14,
                "eta {eta} cos {c}: {got} vs {want}"
            );
            // From behind: the inverted index.
            let back = Dielectric::new(1.0 / eta).unwrap().reflectance(-c);
            assert!((back - want).abs() < 1e-14, "eta {eta} cos -{c}");
        }
    }
}

#[test]
fn dielectric_at_brewsters_angle_reflects_no_p_light() {
    // At tan theta_B = eta, theta_B + theta_t = 90 degrees: R_p = 0 and
    // R_s = sin^2(theta_B - theta_t) = cos^2(2 theta_B) = ((1 - eta^2) / (1 + eta^2))^2, so
    // R = R_s / 2 (the closed form); 1e-15 absolute. The test's own R_p vanishes there too.
    for eta in [1.33f64, 1.5, 2.42, 1.0 / 1.5] {
        let c = eta.atan().cos();
        let (_, rp) = textbook_dielectric(eta, c);
        assert!(rp < 1e-30, "eta {eta}: R_p = {rp}");
        let want = 0.5 * ((1.0 - eta * eta) / (1.0 + eta * eta)).powi(2);
        let got = Dielectric::new(eta).unwrap().reflectance(c);
        assert!((got - want).abs() < 1e-15, "eta {eta}: {got} vs {want}");
        // Beside it R_p is positive again, and R is still (R_s + R_p) / 2.
        for dc in [-1e-3, 1e-3] {
            let (rs, rp) = textbook_dielectric(eta, c + dc);
            assert!(rp > 0.0);
            let r = Dielectric::new(eta).unwrap().reflectance(c + dc);
            assert!((r - 0.5 * (rs + rp)).abs() < 1e-14);
        }
    }
}

#[test]
fn dielectric_total_internal_reflection_beyond_the_critical_angle() {
    // From glass into air: eta = 1 / 1.5, sin theta_c = eta. Beyond it R = 1 exactly; at it
    // R = 1 (g = 0); just inside it R < 1, matching the textbook form (1e-14).
    let eta = 1.0 / 1.5;
    let f = Dielectric::new(eta).unwrap();
    let theta_c = eta.asin();
    for dt in [1e-9, 1e-3, 0.1, 0.5] {
        let c = (theta_c + dt).cos();
        assert_eq!(f.reflectance(c), 1.0, "theta_c + {dt}");
    }
    assert_eq!(f.reflectance(0.0), 1.0);
    for dt in [1e-3, 1e-2, 0.3] {
        let c = (theta_c - dt).cos();
        let r = f.reflectance(c);
        let (rs, rp) = textbook_dielectric(eta, c);
        assert!(
            r < 1.0 && (r - 0.5 * (rs + rp)).abs() < 1e-14,
            "theta_c - {dt}: {r}"
        );
    }
    // The same interface seen from the air side of an index-1.5 glass, light from inside.
    let glass = Dielectric::new(1.5).unwrap();
    assert_eq!(glass.reflectance(-(theta_c + 0.01).cos()), 1.0);
}

/// Gold at 600 nm: `n = 0.203958032`, `k = 3.16688023` (Yakubovsky et al. 2017, "Optical
/// constants and structural properties of thin gold films", Opt. Express 25, 25574, the
/// 117 nm e-beam film, as tabulated in the refractiveindex.info database); gold at
/// 632.8 nm: `n = 0.18104`, `k = 3.068099` (Filmetrics' refractive index database, from the
/// Sopra material library).
const GOLD: [(f64, f64); 2] = [(0.203_958_032, 3.166_880_23), (0.181_04, 3.068_099)];

#[test]
fn conductor_is_the_complex_fresnel_equations_for_gold() {
    for (n, k) in GOLD {
        let f = Conductor::new(n, k).unwrap();
        // Normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2); 1e-15.
        let r0 = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
        assert!((f.reflectance(1.0) - r0).abs() < 1e-15, "{n} {k}");
        // Gold reflects most of the red: the published constants give R0 in (0.9, 0.95).
        assert!(r0 > 0.9 && r0 < 0.95, "R0 {r0}");
        // Every angle: the real-arithmetic form (this file); 1e-14 absolute (the complex
        // square root and the a, b form round differently, near grazing both go to 1).
        for c in cosines() {
            let want = textbook_conductor(n, k, c);
            let got = f.reflectance(c);
            assert!(
                (got - want).abs() < 1e-14,
                "{n} {k} cos {c}: {got} vs {want}"
            );
            assert_eq!(f.reflectance(-c), got);
        }
        assert_eq!(f.reflectance(0.0), 1.0);
        // RGB: each channel is the scalar conductor.
        let rgb = Conductor::new(DVec3::new(n, 1.0, 0.5), DVec3::new(k, 2.0, 0.0)).unwrap();
        let c = 0.37;
        let v = rgb.reflectance(c);
        assert_eq!(v.x, f.reflectance(c));
        assert_eq!(v.y, Conductor::new(1.0, 2.0).unwrap().reflectance(c));
        assert_eq!(v.z, Conductor::new(0.5, 0.0).unwrap().reflectance(c));
    }
}

#[test]
fn conductor_with_vanishing_extinction_is_the_dielectric() {
    // k = 1e-9 takes the complex path; its difference from the dielectric (Walter et al.'s
    // form) is O(k) (2e-8 allows 20 k) where there is no critical angle (eta > 1): the two
    // formulas of the code agree. (For eta < 1 the difference at the critical angle is
    // O(sqrt(k)): w = sqrt(n^2 - sin^2) ~ sqrt(2 i eta k) there.)
    for eta in [1.33, 1.5, 2.42] {
        let conductor = Conductor::new(eta, 1e-9).unwrap();
        let dielectric = Dielectric::new(eta).unwrap();
        for c in cosines() {
            let (a, b) = (conductor.reflectance(c), dielectric.reflectance(c));
            assert!((a - b).abs() < 2e-8, "eta {eta} cos {c}: {a} vs {b}");
        }
    }
}

#[test]
fn schlick_is_exact_at_the_ends_and_decreasing() {
    for f0 in [0.0, 0.04, 0.5, 1.0] {
        let f = Schlick::new(f0).unwrap();
        assert_eq!(f.reflectance(1.0), f0);
        assert_eq!(f.reflectance(0.0), 1.0);
        assert_eq!(f.reflectance(-0.3), f.reflectance(0.3));
        let mut last = 1.0;
        for c in cosines().collect::<Vec<_>>().into_iter().rev() {
            let r = f.reflectance(c);
            assert!(r <= last && (f0..=1.0).contains(&r), "f0 {f0} cos {c}");
            last = r;
        }
        // The fifth power by hand at one angle.
        let c: f64 = 0.3;
        let want = f0 + (1.0 - f0) * (1.0 - c).powi(5);
        assert!((f.reflectance(c) - want).abs() < 1e-16);
    }
    let rgb = Schlick::new(DVec3::new(0.9, 0.6, 0.2))
        .unwrap()
        .reflectance(0.5);
    assert_eq!(rgb.y, Schlick::new(0.6).unwrap().reflectance(0.5));
}

#[test]
fn fresnel_bad_input_is_refused_or_clamped() {
    assert_eq!(Dielectric::new(0.0), Err(FresnelError::OutOfRange));
    assert_eq!(Dielectric::new(-1.5), Err(FresnelError::OutOfRange));
    assert_eq!(Dielectric::new(f64::NAN), Err(FresnelError::NotFinite));
    assert_eq!(Dielectric::new(f64::INFINITY), Err(FresnelError::NotFinite));
    assert_eq!(Conductor::new(0.2, -1.0), Err(FresnelError::OutOfRange));
    assert_eq!(Conductor::new(0.0, 1.0), Err(FresnelError::OutOfRange));
    assert_eq!(Conductor::new(0.2, f64::NAN), Err(FresnelError::NotFinite));
    assert_eq!(
        Conductor::new(DVec3::new(0.2, 0.3, f64::INFINITY), DVec3::ONE),
        Err(FresnelError::NotFinite)
    );
    assert_eq!(Schlick::new(1.5), Err(FresnelError::OutOfRange));
    assert_eq!(Schlick::new(-0.1), Err(FresnelError::OutOfRange));
    assert_eq!(Schlick::new(f64::NAN), Err(FresnelError::NotFinite));
    assert_eq!(Schlick::from_ior(0.0), Err(FresnelError::OutOfRange));
    // cos theta: NaN is grazing, beyond +-1 clamped; always in [0, 1].
    let d = Dielectric::new(1.5).unwrap();
    let c = Conductor::new(GOLD[0].0, GOLD[0].1).unwrap();
    let s = Schlick::new(0.04).unwrap();
    for x in [f64::NAN, f64::INFINITY, -f64::INFINITY, 3.0, -3.0, 1e-300] {
        for r in [d.reflectance(x), c.reflectance(x), s.reflectance(x)] {
            assert!((0.0..=1.0).contains(&r), "cos {x}: {r}");
        }
    }
    assert_eq!(d.reflectance(f64::NAN), 1.0);
    assert_eq!(d.reflectance(3.0), d.reflectance(1.0));
    assert_eq!(FresnelOne.reflectance(f64::NAN), 1.0);
}

// ---------------------------------------------------------------------------------------
// The BRDF.

/// A random unit direction above the surface, cosine-distributed, kept off grazing by 1e-3.
fn random_upper(rng: &mut SplitMix64) -> DVec3 {
    let (u1, u2) = (rng.uniform(), rng.uniform());
    let r = u1.sqrt().min(0.999_999);
    let phi = 2.0 * PI * u2;
    DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - r * r).sqrt())
}

#[test]
fn ggx_brdf_is_the_closed_form() {
    // f = F D G2 / (4 cos_o cos_i) written out here for isotropic GGX: D (Walter et al. 2007
    // eq. 33) = alpha^2 / (pi (m_z^2 (alpha^2 - 1) + 1)^2), Lambda (Heitz 2014 eq. 72) =
    // (sqrt(1 + alpha^2 tan^2) - 1) / 2, height-correlated G2 = 1 / (1 + Lambda_o +
    // Lambda_i), F the textbook dielectric (this file). 1e-12 relative: a few dozen
    // roundings, D's peak is not cancelling at these roughnesses.
    let eta = 1.5;
    let mut rng = SplitMix64(52);
    for alpha in [0.05, 0.3, 0.9] {
        let bsdf = MicrofacetReflection::new(
            Ggx::isotropic(alpha).unwrap(),
            Dielectric::new(eta).unwrap(),
        );
        let lambda = |w: DVec3| {
            let tan2 = (1.0 - w.z * w.z) / (w.z * w.z);
            0.5 * ((1.0 + alpha * alpha * tan2).sqrt() - 1.0)
        };
        for _ in 0..500 {
            let (wo, wi) = (random_upper(&mut rng), random_upper(&mut rng));
            let m = (wo + wi).normalize();
            let a2 = alpha * alpha;
            let d = a2 / (PI * (m.z * m.z * (a2 - 1.0) + 1.0).powi(2));
            let g2 = 1.0 / (1.0 + lambda(wo) + lambda(wi));
            let (rs, rp) = textbook_dielectric(eta, wo.dot(m));
            let want = 0.5 * (rs + rp) * d * g2 / (4.0 * wo.z * wi.z);
            let got = bsdf.f(wo, wi);
            assert!(
                (got - want).abs() <= 1e-12 * want,
                "alpha {alpha} {wo} {wi}: {got} vs {want}"
            );
            // Scale invariance: directions need not be unit.
            let scaled = bsdf.f(wo * 1e200, wi * 3e-200);
            assert!((scaled - got).abs() <= 1e-12 * got);
        }
    }
}

#[test]
fn brdf_is_reciprocal_for_every_lobe() {
    // f(wo, wi) = f(wi, wo) for every lobe (all use the symmetric height-correlated G2 of
    // their own Lambda, and F(wo.m) = F(wi.m)), with the dielectric Fresnel. 1e-13 relative:
    // the two orders differ by the rounding of 1 + Lambda_o + Lambda_i and of wo.m against
    // wi.m (a few ulps).
    let mut rng = SplitMix64(5252);
    let fresnel = Dielectric::new(1.33).unwrap();
    for alpha in [0.02, 0.2, 0.7] {
        for case in cases_with(alpha, fresnel) {
            let mut nonzero = 0;
            for k in 0..200 {
                // Half the pairs independent, half a sampled reflection (inside the lobe,
                // where a narrow lobe's f is not 0).
                let wo = random_upper(&mut rng);
                let u = [rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()];
                let wi = match case.bsdf.sample(wo, u) {
                    Some(s) if k % 2 == 0 => s.wi,
                    _ => random_upper(&mut rng),
                };
                let (a, b) = (case.bsdf.f(wo, wi), case.bsdf.f(wi, wo));
                assert!(
                    (a - b).abs() <= 1e-13 * a.max(b),
                    "{}: f({wo}, {wi}) = {a}, reversed {b}",
                    case.label
                );
                nonzero += usize::from(a > 0.0);
            }
            assert!(nonzero >= 90, "{}: {nonzero} non-zero values", case.label);
        }
    }
    // f32, two lobes (TK19 and the box): 1e-5 relative (wo.m and wi.m round an f32 ulp
    // apart, which the dielectric's F amplifies by its logarithmic slope, below 10 here).
    let material = s::Ggx::axis_aligned(0.05, 0.02).unwrap();
    let fp = s::Footprint::from_slope_derivatives(Vec2::new(0.05, 0.01), Vec2::new(-0.01, 0.03));
    let fresnel = s::bsdf::Dielectric::new(1.33).unwrap();
    let tk19 = s::bsdf::MicrofacetReflection::new(
        material.filtered(fp, s::filter::Gaussian::TK19),
        fresnel,
    );
    let rect =
        s::bsdf::MicrofacetReflection::new(material.filtered(fp, s::filter::Rect::KHPL16), fresnel);
    for _ in 0..200 {
        let (wo, wi) = (
            random_upper(&mut rng).as_vec3(),
            random_upper(&mut rng).as_vec3(),
        );
        for (a, b) in [
            (tk19.f(wo, wi), tk19.f(wi, wo)),
            (rect.f(wo, wi), rect.f(wi, wo)),
        ] {
            assert!((a - b).abs() <= 1e-5 * a.max(b), "{wo} {wi}: {a} vs {b}");
        }
    }
}

#[test]
fn white_furnace_albedo_by_quadrature_equals_the_mean_weight() {
    // With F = 1: the albedo E(wo) = integral f(wo, wi) wi_z dwi over the upper hemisphere by
    // nested adaptive Gauss-Kronrod (the half-vector grid of tests/common/bsdf_cases.rs cut at
    // the horizon; relative goal 1e-8, 8 x 8 panels) against the mean of the sampled weights
    // (None counts 0) over 40 000 samples: |mean - E| <= 5 standard errors of the mean (the
    // sample standard deviation over sqrt(N); a two-sided 5-sigma band, false-alarm rate
    // 6e-7 per case) + the quadrature's error estimate + 3e-6 (the exact Gaussian filter's
    // sampler draws its pdf's density to 1.6e-6 relative and misses 8e-7 of mass in the far
    // tail, ExactGaussian's docs; the weights are in [0, 1]). And E <= 1 (+ its error): a
    // single-scattering BRDF loses energy, never gains it. Each sample's weight also equals
    // f wi_z / pdf to 1e-9 relative (the closed form F G2 / G1 against the quotient).
    println!("| lobe | view | E (quadrature) | 1 - E | mean weight | std. error |");
    println!("|---|---:|---:|---:|---:|---:|");
    let tol = Tolerance {
        abs: 1e-13,
        rel: 1e-8,
        max_intervals: 200,
    };
    let n = 40_000;
    let mut seed = 77_000u64;
    let mut failures = Vec::new();
    for alpha in [0.02, 0.2, 0.7] {
        for case in cases(alpha) {
            for deg in [0.0, 40.0, 80.0, 89.0] {
                seed += 1;
                let wo = view(deg, 0.7);
                let bsdf = &case.bsdf;
                let grid = Grid::new(&case.grid, wo);
                let e = grid.integrate_hemisphere(&|wi| bsdf.f(wo, wi) * wi.z, 8, tol);
                let mut rng = SplitMix64(seed);
                let (mut sum, mut sum2) = (0.0, 0.0);
                for _ in 0..n {
                    let u = [rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()];
                    if let Some(s) = bsdf.sample(wo, u) {
                        let quotient = bsdf.f(wo, s.wi) * s.wi.z / s.pdf;
                        assert!(
                            (s.weight - quotient).abs() <= 1e-9 * quotient,
                            "{}: weight {} vs f cos / pdf {quotient}",
                            case.label,
                            s.weight
                        );
                        assert!((0.0..=1.0).contains(&s.weight));
                        sum += s.weight;
                        sum2 += s.weight * s.weight;
                    }
                }
                let mean = sum / n as f64;
                let var = (sum2 / n as f64 - mean * mean).max(0.0) * n as f64 / (n - 1) as f64;
                let se = (var / n as f64).sqrt();
                println!(
                    "| {} | {deg} | {:.6} | {:.4} | {:.6} | {:.1e} |",
                    case.label,
                    e.value,
                    1.0 - e.value,
                    mean,
                    se
                );
                if e.value > 1.0 + e.error {
                    failures.push(format!("{} at {deg}: E = {} > 1", case.label, e.value));
                }
                if (mean - e.value).abs() > 5.0 * se + e.error + 3e-6 {
                    failures.push(format!(
                        "{} at {deg}: mean weight {mean} vs E {} (se {se:.1e}, quad. error {:.1e})",
                        case.label, e.value, e.error
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn sample_dimension_is_what_the_sampler_reads() {
    // The box lobe reads four numbers (changing u[2..4] moves the sample), every other lobe
    // two (u[2..4] ignored: the same sample bit for bit).
    let wo = view(35.0, 0.4);
    let u = [0.31, 0.72, 0.13, 0.58];
    let v = [0.31, 0.72, 0.91, 0.04];
    for case in cases(0.05) {
        let (a, b) = (case.bsdf.sample(wo, u), case.bsdf.sample(wo, v));
        let dim = case.bsdf.sample_dimension();
        if case.label.contains("Rect") {
            assert_eq!(dim, 4);
            assert_ne!(a.unwrap().wi, b.unwrap().wi, "{}", case.label);
        } else {
            assert_eq!(dim, 2, "{}", case.label);
            assert_eq!(a, b, "{}", case.label);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Bad input.

/// The directions with no reflection: zero, NaN, infinite, at and below the horizon.
fn bad_directions() -> Vec<DVec3> {
    vec![
        DVec3::ZERO,
        DVec3::new(f64::NAN, 0.0, 1.0),
        DVec3::new(0.0, 0.0, f64::NAN),
        DVec3::new(f64::INFINITY, 0.0, 1.0),
        DVec3::new(0.0, 0.0, f64::INFINITY),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.3, 0.1, -0.9),
        DVec3::new(0.0, 0.0, -1.0),
        DVec3::new(1.0, 0.0, -0.0),
    ]
}

#[test]
fn bad_directions_give_zero_and_none() {
    let good = view(30.0, 0.2);
    for case in cases_with(0.1, Dielectric::new(1.5).unwrap()) {
        let b = &case.bsdf;
        for w in bad_directions() {
            assert_eq!(b.f(w, good), 0.0, "{} f({w}, .)", case.label);
            assert_eq!(b.f(good, w), 0.0, "{} f(., {w})", case.label);
            assert_eq!(b.pdf(w, good), 0.0, "{} pdf({w}, .)", case.label);
            assert_eq!(b.pdf(good, w), 0.0, "{} pdf(., {w})", case.label);
            assert_eq!(
                b.sample(w, [0.3, 0.6, 0.2, 0.8]),
                None,
                "{} {w}",
                case.label
            );
        }
        // Within float range of grazing: finite (0 or positive), never NaN.
        for z in [1e-300, 5e-324, 1e-30] {
            let w = DVec3::new(1.0, 0.2, z);
            for v in [b.f(w, good), b.f(good, w), b.pdf(w, good), b.pdf(good, w)] {
                assert!(v.is_finite() && v >= 0.0, "{} z {z}: {v}", case.label);
            }
            if let Some(s) = b.sample(w, [0.3, 0.6, 0.2, 0.8]) {
                assert!(s.weight.is_finite() && s.pdf.is_finite() && s.pdf > 0.0);
            }
        }
    }
}

#[test]
fn uniform_numbers_outside_the_unit_interval_are_clamped() {
    // [0, 1 - eps/2], NaN to 0: the sample of the clamped numbers, bit for bit.
    let wo = view(50.0, 1.1);
    let top = 1.0 - 0.5 * f64::EPSILON;
    for case in cases_with(0.1, Dielectric::new(1.5).unwrap()) {
        let b = &case.bsdf;
        for (u, clamped) in [
            ([-0.5, 1.5, f64::NAN, 7.0], [0.0, top, 0.0, top]),
            (
                [f64::INFINITY, -f64::INFINITY, 0.5, 1.0],
                [top, 0.0, 0.5, top],
            ),
            ([0.4, f64::NAN, -0.0, 0.9], [0.4, 0.0, 0.0, 0.9]),
        ] {
            let (a, c) = (b.sample(wo, u), b.sample(wo, clamped));
            assert_eq!(a, c, "{} {u:?}", case.label);
            if let Some(s) = a {
                assert!(s.wi.z > 0.0 && s.weight.is_finite() && s.pdf.is_finite());
            }
        }
    }
}

#[test]
fn f32_bsdf_is_finite_on_bad_input_and_agrees_with_f64() {
    // The f32 BSDF (TK19 lobe, RGB gold) at ordinary directions against the f64 one: 1e-4
    // relative (f32 rounding of D near its peak: the lobe is 0.06 wide, directions 1e-7
    // off); and finite, zero or None on the bad directions.
    let mat32 = s::Ggx::isotropic(0.02).unwrap();
    let mat64 = d::Ggx::isotropic(0.02).unwrap();
    let fp32 = s::Footprint::from_slope_derivatives(Vec2::new(0.05, 0.01), Vec2::new(-0.01, 0.03));
    let fp64 = bsdf_cases::footprint();
    let (n, k) = GOLD[0];
    let b32 = s::bsdf::MicrofacetReflection::new(
        mat32.filtered(fp32, s::filter::Gaussian::TK19),
        s::bsdf::Conductor::new(Vec3::new(n as f32, 0.5, 1.2), Vec3::new(k as f32, 2.0, 7.0))
            .unwrap(),
    );
    let b64 = MicrofacetReflection::new(
        mat64.filtered(fp64, d::filter::Gaussian::TK19),
        Conductor::new(DVec3::new(n, 0.5, 1.2), DVec3::new(k, 2.0, 7.0)).unwrap(),
    );
    let mut rng = SplitMix64(99);
    for _ in 0..200 {
        let wo = random_upper(&mut rng);
        let u = [rng.uniform(), rng.uniform(), 0.0, 0.0];
        let Some(s64) = b64.sample(wo, u) else {
            continue;
        };
        let a = b32.f(wo.as_vec3(), s64.wi.as_vec3()).as_dvec3();
        let b = b64.f(wo, s64.wi);
        assert!(
            (a - b).abs().max_element() <= 1e-4 * b.max_element(),
            "{a} vs {b}"
        );
        let (p32, p64) = (b32.pdf(wo.as_vec3(), s64.wi.as_vec3()) as f64, s64.pdf);
        assert!((p32 - p64).abs() <= 1e-4 * p64, "{p32} vs {p64}");
    }
    let good = Vec3::new(0.2, 0.1, 0.9);
    for w in bad_directions() {
        let w = w.as_vec3();
        assert_eq!(b32.f(w, good), Vec3::ZERO);
        assert_eq!(b32.pdf(good, w), 0.0);
        assert_eq!(b32.sample(w, [0.5; 4]), None);
    }
    for z in [1e-38f32, 1e-45, 1e-20] {
        let w = Vec3::new(1.0, 0.2, z);
        assert!(b32.f(w, good).is_finite() && b32.f(good, w).is_finite());
        assert!(b32.pdf(w, good).is_finite() && b32.pdf(good, w).is_finite());
    }
}
