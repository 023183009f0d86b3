//! Chi-square goodness of fit of every sampler against its own pdf integrated per cell by
//! adaptive quadrature (the Mitsuba / pbrt test), for GGX and Beckmann in the three roughness
//! forms, roughness 1e-3, 0.1 and 0.8, `D(m) m_z` sampling and visible normals at view
//! angles 0, 15, 30, 80 and 89.9 degrees: 2 x 3 x 3 x 6 = 108 tests; plus 8 tests of the
//! `f32` samplers (full matrix, roughness 0.1) against the `f64` pdf, and 16 with the
//! determinant clamp active (two matrices, both families, `D m_z` and visible normals at 0,
//! 30 and 80 degrees): 132 in all.
//!
//! ## The grid
//! A `(cos theta, phi)` grid on the hemisphere of `m` cannot resolve a lobe of roughness
//! `1e-3` (it covers `1e-6` of the `cos theta` range). The grid is instead a `(cos theta,
//! phi)` grid of the *whitened* normal: the slope `s = -m_xy / m_z` is whitened with this
//! test's own symmetric square root `B = A^{1/2}` (eigen-decomposition, independent of the
//! Cholesky warp of the code under test), `w = B^-1 s`, and the cell coordinates are
//! `r = F(|w|^2)` and `phi = atan2(w_y, w_x)`, with `F(q) = q / (1 + q)` (GGX; this is
//! `sin^2` of the whitened normal, i.e. a `cos theta` grid) or `F(q) = 1 - exp(-q)`
//! (Beckmann), the radial CDFs of the unit-roughness `D(m) m_z`. The grid thus scales with
//! the lobe at every roughness and in every form, and at normal incidence its cells are
//! equiprobable. The density in `(r, phi)` is `pdf(m) m_z^3 sqrt(det A) (dq/dr) / 2`
//! (`d omega = m_z^3 ds`, `ds = sqrt(det A) dw`, `dw = dq dphi / 2`).
//!
//! ## The statistic
//! 40 x 40 cells, 40 000 samples. Cells with expected count below 5 are pooled into one (and
//! that cell into the smallest other if still below 5). A sample in a cell of zero expected
//! count fails outright. The p-value `Q(dof/2, chi2/2)` uses the regularised incomplete
//! gamma function implemented (and tested) below. The significance level is Sidak-corrected
//! for the 132 tests: `1 - (1 - 0.01)^(1/132)`, so the whole suite has a 1% false-alarm rate.

#[path = "common/chi2.rs"]
mod chi2;
mod common;

use chi2::{ALPHA_SUITE, Radial, chi2_sf, chi2_test, gamma_q, ln_gamma};
use filtered_ndf::f64::{
    AxisAligned, Beckmann, Ggx, Isotropic, NdfSampling, Roughness, RoughnessMatrix,
};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------
// The regularised incomplete gamma function of the harness (`tests/common/chi2.rs`), tested
// here against exact values.

#[test]
fn ln_gamma_known_values() {
    // Exact values: Gamma(n) = (n-1)!, Gamma(1/2) = sqrt(pi), Gamma(n + 1/2) from the
    // recurrence. Tolerance 1e-13 absolute: the Lanczos sum is good to ~1e-15 relative.
    let mut fact = 1.0_f64;
    for n in 1..30 {
        assert!((ln_gamma(n as f64) - fact.ln()).abs() < 1e-13 * (1.0 + fact.ln()));
        fact *= n as f64;
    }
    let mut g = PI.sqrt(); // Gamma(1/2)
    for n in 0..30 {
        let a = n as f64 + 0.5;
        assert!(
            (ln_gamma(a) - g.ln()).abs() < 1e-13 * (1.0 + g.ln().abs()),
            "a={a}"
        );
        g *= a;
    }
}

#[test]
fn incomplete_gamma_known_values() {
    // Integer a: Q(n, x) = exp(-x) sum_{k<n} x^k / k! (the Poisson CDF); half-integer a:
    // Q(1/2, x) = erfc(sqrt x) and Q(a + 1, x) = Q(a, x) + x^a exp(-x) / Gamma(a + 1).
    // Both branches (series below a + 1, continued fraction above) are crossed. Tolerance
    // 1e-12 relative (plus 1e-15 absolute where Q is near 0 or 1 and cancels).
    for &x in &[0.01_f64, 0.3, 1.0, 2.5, 7.0, 15.0, 40.0, 90.0] {
        let mut term = (-x).exp();
        let mut poisson = 0.0;
        for n in 1..60 {
            poisson += term;
            term *= x / n as f64;
            let q = gamma_q(n as f64, x);
            assert!(
                (q - poisson).abs() < 1e-12 * poisson + 1e-15,
                "Q({n},{x})={q} vs {poisson}"
            );
        }
        let mut q_half = filtered_ndf::math::erfc(x.sqrt());
        let mut a = 0.5_f64;
        for _ in 0..40 {
            let q = gamma_q(a, x);
            assert!(
                (q - q_half).abs() < 1e-12 * q_half + 1e-15,
                "Q({a},{x})={q} vs {q_half}"
            );
            q_half += (a * x.ln() - x - ln_gamma(a + 1.0)).exp();
            a += 1.0;
        }
    }
    // Tabulated chi-square critical values (upper 5% and 1% points).
    for &(x, dof, p) in &[
        (3.841_458_820_694_124, 1, 0.05),
        (6.634_896_601_021_214, 1, 0.01),
        (18.307_038_053_275_146, 10, 0.05),
        (124.342_113_404_004_07, 100, 0.05),
    ] {
        let q = chi2_sf(x, dof);
        assert!((q - p).abs() < 1e-9 * p, "dof {dof}: {q} vs {p}");
    }
}

// ---------------------------------------------------------------------------------------
// The harness (`tests/common/chi2.rs`): the grid, pooling and statistic above.

const N_TESTS: usize = 132;

const ROUGHNESS: [f64; 3] = [1e-3, 0.1, 0.8];
const VIEW_DEG: [f64; 5] = [0.0, 15.0, 30.0, 80.0, 89.9];
/// View azimuth: off every axis of the anisotropic forms.
const VIEW_PHI: f64 = 1.0;

fn view(theta_deg: f64) -> DVec3 {
    let t = theta_deg.to_radians();
    DVec3::new(t.sin() * VIEW_PHI.cos(), t.sin() * VIEW_PHI.sin(), t.cos())
}

/// All 18 cases of one NDF and form: `D m_z` sampling, then visible normals per view angle.
/// Prints one table row per case (`cargo test --release --test sampling_chi2 -- --nocapture`).
fn run_suite<R: Roughness, N: NdfSampling>(
    name: &str,
    radial: Radial,
    seed_base: u64,
    make: impl Fn(f64) -> (N, R),
) {
    let alpha_test = 1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64);
    let mut failures = Vec::new();
    let mut case = 0u64;
    for &a in &ROUGHNESS {
        let (ndf, rough) = make(a);
        let views: Vec<Option<f64>> = std::iter::once(None)
            .chain(VIEW_DEG.iter().map(|&d| Some(d)))
            .collect();
        for v in views {
            case += 1;
            let seed = seed_base.wrapping_mul(1000).wrapping_add(case);
            let start = std::time::Instant::now();
            let out = match v {
                None => chi2_test(
                    &rough,
                    radial,
                    seed,
                    |u| ndf.sample_normal(u),
                    |m| ndf.normal_pdf(m),
                ),
                Some(deg) => {
                    let wo = view(deg);
                    chi2_test(
                        &rough,
                        radial,
                        seed,
                        |u| {
                            let m = ndf.sample_visible_normal(wo, u).expect("wo above surface");
                            assert!(wo.dot(m) > 0.0, "sample {m} faces away from {wo}");
                            m
                        },
                        |m| ndf.visible_normal_pdf(wo, m),
                    )
                }
            };
            let label = match v {
                None => "D cos".to_string(),
                Some(d) => format!("vis {d:>4}"),
            };
            println!(
                "| {name} | {a:>6} | {label} | {:>8.1} | {:>4} | {:>8.4} | {:>6.0} ms | sum {:.2e} |",
                out.chi2,
                out.dof,
                out.p,
                start.elapsed().as_secs_f64() * 1e3,
                out.expected_total - 1.0
            );
            // The cell integrals must add up to the pdf's total mass, 1 (tolerance 1e-5:
            // 1600 cells, each to ~1e-7 relative, plus the mass beyond the last radial cell,
            // which is inside it by construction: r < 1 covers the whole hemisphere).
            if (out.expected_total - 1.0).abs() > 1e-5 {
                failures.push(format!("{name} a={a} {label}: mass {}", out.expected_total));
            }
            if out.p.is_nan() || out.p <= alpha_test {
                failures.push(format!(
                    "{name} a={a} {label}: p = {} < {alpha_test}",
                    out.p
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

fn matrix(a: f64) -> RoughnessMatrix {
    // diag(a^2, (a/4)^2) rotated by 0.6 rad: condition number 16, all entries non-zero.
    let (l1, l2) = (a * a, a * a / 16.0);
    let (c, s) = (0.6_f64.cos(), 0.6_f64.sin());
    RoughnessMatrix::new(
        c * c * l1 + s * s * l2,
        c * s * (l1 - l2),
        s * s * l1 + c * c * l2,
    )
    .unwrap()
}

#[test]
fn chi2_ggx_isotropic() {
    run_suite("ggx iso", Radial::Ggx, 1, |a| {
        let r = Isotropic::new(a).unwrap();
        (Ggx::new(r), r)
    });
}

#[test]
fn chi2_ggx_axis_aligned() {
    run_suite("ggx axis", Radial::Ggx, 2, |a| {
        let r = AxisAligned::new(a, 0.5 * a).unwrap();
        (Ggx::new(r), r)
    });
}

#[test]
fn chi2_ggx_matrix() {
    run_suite("ggx mat", Radial::Ggx, 3, |a| {
        let r = matrix(a);
        (Ggx::new(r), r)
    });
}

#[test]
fn chi2_beckmann_isotropic() {
    run_suite("beck iso", Radial::Beckmann, 4, |a| {
        let r = Isotropic::new(a).unwrap();
        (Beckmann::new(r), r)
    });
}

#[test]
fn chi2_beckmann_axis_aligned() {
    run_suite("beck axis", Radial::Beckmann, 5, |a| {
        let r = AxisAligned::new(a, 0.5 * a).unwrap();
        (Beckmann::new(r), r)
    });
}

#[test]
fn chi2_beckmann_matrix() {
    run_suite("beck mat", Radial::Beckmann, 6, |a| {
        let r = matrix(a);
        (Beckmann::new(r), r)
    });
}

#[test]
fn chi2_f32_samplers_against_the_f64_pdf() {
    // The f32 samplers, fed with f32-rounded uniform numbers, against the f64 pdf of the same
    // (f32-representable) matrix: D m_z and visible normals at 0, 80 and 89.9 degrees.
    use filtered_ndf::f32 as s32;
    use filtered_ndf::f32::NdfSampling as _;
    let alpha_test = 1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64);
    let (a11, a12, a22) = matrix(0.1).entries();
    let (a11, a12, a22) = (a11 as f32, a12 as f32, a22 as f32);
    let r64 = RoughnessMatrix::new(a11 as f64, a12 as f64, a22 as f64).unwrap();
    let r32 = s32::RoughnessMatrix::new(a11, a12, a22).unwrap();
    let u32of = |u: DVec2| glam::Vec2::new(u.x as f32, u.y as f32);
    let mut failures = Vec::new();
    for (k, view_deg) in [None, Some(0.0), Some(80.0), Some(89.9)]
        .into_iter()
        .enumerate()
    {
        let wo = view_deg.map(view).unwrap_or(DVec3::Z);
        let wo32 = wo.as_vec3();
        let (g32, b32) = (s32::Ggx::new(r32), s32::Beckmann::new(r32));
        let (g64, b64) = (Ggx::new(r64), Beckmann::new(r64));
        let seed = 9000 + k as u64;
        let (og, ob) = match view_deg {
            None => (
                chi2_test(
                    &r64,
                    Radial::Ggx,
                    seed,
                    |u| g32.sample_normal(u32of(u)).as_dvec3(),
                    |m| g64.normal_pdf(m),
                ),
                chi2_test(
                    &r64,
                    Radial::Beckmann,
                    seed + 100,
                    |u| b32.sample_normal(u32of(u)).as_dvec3(),
                    |m| b64.normal_pdf(m),
                ),
            ),
            Some(_) => (
                chi2_test(
                    &r64,
                    Radial::Ggx,
                    seed,
                    |u| {
                        g32.sample_visible_normal(wo32, u32of(u))
                            .unwrap()
                            .as_dvec3()
                    },
                    |m| g64.visible_normal_pdf(wo, m),
                ),
                chi2_test(
                    &r64,
                    Radial::Beckmann,
                    seed + 100,
                    |u| {
                        b32.sample_visible_normal(wo32, u32of(u))
                            .unwrap()
                            .as_dvec3()
                    },
                    |m| b64.visible_normal_pdf(wo, m),
                ),
            ),
        };
        for (name, o) in [("ggx f32", og), ("beck f32", ob)] {
            let label = view_deg.map_or("D cos".to_string(), |d| format!("vis {d:>4}"));
            println!(
                "| {name} | 0.1 mat | {label} | {:>8.1} | {:>4} | {:>8.4} |",
                o.chi2, o.dof, o.p
            );
            if o.p.is_nan() || o.p <= alpha_test {
                failures.push(format!("{name} {label}: p = {}", o.p));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn chi2_det_clamp_active() {
    // tau far above det A: D and Lambda evaluate A_c = A + t I with det(A_c) = tau
    // (RoughnessMatrix docs; tests/ndf_det_clamp.rs checks D's normalisation and the Smith
    // identity), and the samplers must warp by the Cholesky factor of that same matrix. The
    // cells are whitened by this test's own A_c (any partition is valid; this one makes the
    // cells equiprobable at normal incidence). A rotated lobe with tau = 100 det A, and an
    // exactly singular one (rank one) with tau = (alpha^2 / 10)^2.
    let alpha_test = 1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64);
    let rotated = |l1: f64, l2: f64, phi: f64| {
        let (c, s) = (phi.cos(), phi.sin());
        (
            c * c * l1 + s * s * l2,
            c * s * (l1 - l2),
            s * s * l1 + c * c * l2,
        )
    };
    let (a11, a12, a22) = rotated(0.04, 4e-4, 0.7);
    let det = a11 * a22 - a12 * a12;
    let cases = [
        ("rotated", (a11, a12, a22), 100.0 * det),
        ("singular", (0.0324, 0.0432, 0.0576), 0.0009f64.powi(2)),
    ];
    let mut failures = Vec::new();
    for (k, (name, (a11, a12, a22), tau)) in cases.into_iter().enumerate() {
        let r = RoughnessMatrix::new_with_det_clamp(a11, a12, a22, tau).unwrap();
        let h = 0.5 * (a11 + a22);
        let d = a11 * a22 - a12 * a12;
        let t = (tau - d) / (h + (h * h + tau - d).sqrt());
        let whiten = RoughnessMatrix::new(a11 + t, a12, a22 + t).unwrap();
        let ndfs: [(&str, Radial, Box<dyn NdfSampling>); 2] = [
            ("ggx", Radial::Ggx, Box::new(Ggx::new(r))),
            ("beck", Radial::Beckmann, Box::new(Beckmann::new(r))),
        ];
        for (j, (family, radial, ndf)) in ndfs.iter().enumerate() {
            for (i, v) in [None, Some(0.0), Some(30.0), Some(80.0)]
                .into_iter()
                .enumerate()
            {
                let seed = 7000 + 100 * k as u64 + 10 * j as u64 + i as u64;
                let out = match v {
                    None => chi2_test(
                        &whiten,
                        *radial,
                        seed,
                        |u| ndf.sample_normal(u),
                        |m| ndf.normal_pdf(m),
                    ),
                    Some(deg) => {
                        let wo = view(deg);
                        chi2_test(
                            &whiten,
                            *radial,
                            seed,
                            |u| ndf.sample_visible_normal(wo, u).expect("wo above surface"),
                            |m| ndf.visible_normal_pdf(wo, m),
                        )
                    }
                };
                let label = v.map_or("D cos".to_string(), |d| format!("vis {d:>4}"));
                println!(
                    "| {family} clamped | {name} | {label} | {:>8.1} | {:>4} | {:>8.4} | sum {:.2e} |",
                    out.chi2,
                    out.dof,
                    out.p,
                    out.expected_total - 1.0
                );
                if (out.expected_total - 1.0).abs() > 1e-5 {
                    failures.push(format!(
                        "{family} {name} {label}: mass {}",
                        out.expected_total
                    ));
                }
                if out.p.is_nan() || out.p <= alpha_test {
                    failures.push(format!("{family} {name} {label}: p = {}", out.p));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
