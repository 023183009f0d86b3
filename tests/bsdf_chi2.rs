//! Chi-square goodness of fit of `Bsdf::sample` against `Bsdf::pdf` (the Mitsuba / pbrt
//! test) for every lobe type of the front door (`tests/common/bsdf_cases.rs`: GGX and
//! Beckmann unfiltered in the three roughness forms; `Gaussian::TK19` on GGX,
//! `Gaussian::KHPL16` on Beckmann, `ExactGaussian::KHPL16`, `Projected::TK21`,
//! `Rect::KHPL16`, `Proxy::KHPL16`), at roughness `0.02`, `0.2` and `0.7` and views of 0,
//! 40, 80 and 89.5 degrees: 12 x 3 x 4 = 144 tests.
//!
//! ## The statistic
//! 40 000 samples per test. The cells: the whitened half-vector grid of
//! `tests/common/bsdf_cases.rs` (40 x 40 cells in `(r, phi)`, the same partition as
//! `tests/sampling_chi2.rs`, mapped to `wi` through `m = normalize(wo + wi)`), plus one cell
//! for the samples that return `None` (a reflection below the surface). A cell's expected
//! count is `N integral pdf dwi` over its part above the horizon, by nested adaptive
//! Gauss-Kronrod (relative `1e-6`; the expected counts need about `1e-4`); the `None` cell
//! expects `N (1 - sum)`. So the test also checks the pdf's mass: a pdf off by a factor moves
//! samples between the grid and the `None` cell. Cells expecting fewer than 5 are pooled
//! (into the smallest other cell if still below 5); a sample in a cell whose expected count
//! is below `1e-9 N` fails outright. The p-value is `Q(dof / 2, chi2 / 2)`
//! (`tests/common/chi2.rs`, tested in `tests/sampling_chi2.rs`); the level is
//! Sidak-corrected for the 144 tests, `1 - (1 - 0.01)^(1/144)`, so the file has a 1%
//! false-alarm rate. Each sample is also checked: a unit `wi` above the surface whose `pdf`
//! field equals `Bsdf::pdf(wo, wi)` to `1e-8` relative (the pdf recomputed from `wi` through
//! the half vector loses about `eps / (wo.m)` in direction; `1e-8` is far above that for
//! these roughnesses).

#[path = "common/bsdf_cases.rs"]
mod bsdf_cases;
#[path = "common/chi2.rs"]
mod chi2;
mod common;

use bsdf_cases::{Case, Grid, cases, view};
use chi2::{ALPHA_SUITE, MIN_EXPECTED, N_PHI, N_R, N_SAMPLES, chi2_sf};
use filtered_ndf::testing::quadrature::Tolerance;
use filtered_ndf::testing::rng::SplitMix64;
use glam::DVec3;
use std::f64::consts::PI;

const ALPHAS: [f64; 3] = [0.02, 0.2, 0.7];
const VIEW_DEG: [f64; 4] = [0.0, 40.0, 80.0, 89.5];
const N_TESTS: usize = 12 * ALPHAS.len() * VIEW_DEG.len();

fn alpha_test() -> f64 {
    1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64)
}

struct Outcome {
    chi2: f64,
    dof: usize,
    p: f64,
    /// `integral pdf dwi` over the upper hemisphere.
    mass: f64,
    /// The fraction of samples that returned `None`.
    none: f64,
}

/// One test: `sample` of `case` seen from `wo` against its `pdf`.
fn chi2_bsdf(case: &Case, wo: DVec3, seed: u64) -> Outcome {
    let grid = Grid::new(&case.grid, wo);
    let bsdf = &case.bsdf;
    let n_cells = N_R * N_PHI;
    let cell_of = |wi: DVec3| {
        let (r, phi) = grid.coordinates(wi);
        let ir = ((r * N_R as f64) as usize).min(N_R - 1);
        let ip = ((phi / (2.0 * PI) * N_PHI as f64) as usize).min(N_PHI - 1);
        ir * N_PHI + ip
    };
    let mut observed = vec![0.0f64; n_cells + 1];
    let mut rng = SplitMix64(seed);
    for _ in 0..N_SAMPLES {
        let u = [rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()];
        match bsdf.sample(wo, u) {
            None => observed[n_cells] += 1.0,
            Some(s) => {
                assert!(
                    s.wi.z > 0.0 && (s.wi.length() - 1.0).abs() < 1e-12,
                    "{}: wi {} from {wo}",
                    case.label,
                    s.wi
                );
                let pdf = bsdf.pdf(wo, s.wi);
                assert!(
                    (s.pdf - pdf).abs() <= 1e-8 * pdf,
                    "{}: sampled pdf {} vs pdf {pdf} at {}",
                    case.label,
                    s.pdf,
                    s.wi
                );
                observed[cell_of(s.wi)] += 1.0;
            }
        }
    }
    let tol = Tolerance {
        abs: 1e-12,
        rel: 1e-6,
        max_intervals: 60,
    };
    let pdf = |wi: DVec3| bsdf.pdf(wo, wi);
    let mut expected = vec![0.0f64; n_cells + 1];
    for ir in 0..N_R {
        for ip in 0..N_PHI {
            let r = (ir as f64 / N_R as f64, (ir + 1) as f64 / N_R as f64);
            let p = (
                ip as f64 / N_PHI as f64 * 2.0 * PI,
                (ip + 1) as f64 / N_PHI as f64 * 2.0 * PI,
            );
            expected[ir * N_PHI + ip] = grid.integrate(&pdf, r, p, tol).value;
        }
    }
    let mass: f64 = expected[..n_cells].iter().sum();
    expected[n_cells] = (1.0 - mass).max(0.0);
    let n = N_SAMPLES as f64;
    for e in &mut expected {
        *e *= n;
    }
    let (mut pooled_e, mut pooled_o) = (0.0, 0.0);
    let mut cells: Vec<(f64, f64)> = Vec::new();
    for (&e, &o) in expected.iter().zip(&observed) {
        assert!(
            e >= 1e-9 * n || o == 0.0,
            "{}: {o} samples in a cell of expected count {e}",
            case.label
        );
        if e < MIN_EXPECTED {
            pooled_e += e;
            pooled_o += o;
        } else {
            cells.push((e, o));
        }
    }
    if pooled_e > 0.0 || pooled_o > 0.0 {
        if pooled_e < MIN_EXPECTED && !cells.is_empty() {
            let i = (0..cells.len())
                .min_by(|&a, &b| cells[a].0.total_cmp(&cells[b].0))
                .unwrap();
            cells[i].0 += pooled_e;
            cells[i].1 += pooled_o;
        } else {
            cells.push((pooled_e, pooled_o));
        }
    }
    let chi2: f64 = cells.iter().map(|&(e, o)| (o - e) * (o - e) / e).sum();
    let dof = cells.len() - 1;
    Outcome {
        chi2,
        dof,
        p: chi2_sf(chi2, dof),
        mass,
        none: observed[n_cells] / n,
    }
}

#[test]
fn chi2_sample_against_pdf_for_every_lobe() {
    let mut failures = Vec::new();
    let mut seed = 52_000u64;
    println!("| lobe | view | chi2 | dof | p | mass | None |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for alpha in ALPHAS {
        for case in cases(alpha) {
            for deg in VIEW_DEG {
                seed += 1;
                let wo = view(deg, 0.7);
                let out = chi2_bsdf(&case, wo, seed);
                println!(
                    "| {} | {deg} | {:.1} | {} | {:.4} | {:.6} | {:.4} |",
                    case.label, out.chi2, out.dof, out.p, out.mass, out.none
                );
                // The pdf's mass can only fall short of 1 (the reflections below the
                // surface); the quadrature's relative goal is 1e-6.
                if out.mass > 1.0 + 1e-5 {
                    failures.push(format!("{} at {deg}: mass {}", case.label, out.mass));
                }
                if out.p.is_nan() || out.p <= alpha_test() {
                    failures.push(format!("{} at {deg}: p = {}", case.label, out.p));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
