//! Chi-square goodness of fit of the exact Gaussian-filtered GGX samplers against the lobe's
//! own pdfs (`normal_pdf = d(m) m_z`, `visible_normal_pdf = (wo.m)+ d(m) / (wo_z (1 +
//! lambda(wo)))`), integrated per cell by adaptive quadrature: the harness of
//! `tests/sampling_chi2.rs` (`tests/common/chi2.rs`), on a grid whitened by the TK19 matrix
//! `A + 2 Sigma` (the filtered lobe's width) with GGX's radial CDF.
//!
//! Three lobes (lobe-dominated, kernel-dominated, rank-one kernel), each `D m_z` sampling and
//! visible normals at 0, 30 and 80 degrees, plus the `f32` samplers against the `f64` pdf:
//! 14 tests, Sidak-corrected to a 1% false-alarm rate for the file.
//!
//! What agreement means: `sample_normal` is exact (a GGX slope plus a kernel slope), so its
//! test is a plain goodness-of-fit test. `sample_visible_normal` draws from the discrete
//! mixture of Beckmann components on a fixed grid, whose density differs from the pdf by the
//! rule's discretisation error (`<= 1.6e-6` relative), the far-tail mass below the grid
//! (`~8e-7`) and the fast Beckmann `Lambda` of its weights (`< 2.1e-7`): far below what 40 000
//! samples resolve (a relative count error of ~`1e-2` per
//! cell), so the test must pass as if the sampler were exact.

#[path = "common/chi2.rs"]
mod chi2;
mod common;

use chi2::{Radial, chi2_test};
use filtered_ndf::f64 as d;
use filtered_ndf::f64::NdfSampling as _;
use glam::{DVec2, DVec3};

const N_TESTS: usize = 14;
const ALPHA_SUITE: f64 = 0.01;

fn rotated(l1: f64, l2: f64, phi: f64) -> (f64, f64, f64) {
    let (c, sn) = (phi.cos(), phi.sin());
    (
        c * c * l1 + sn * sn * l2,
        c * sn * (l1 - l2),
        sn * sn * l1 + c * c * l2,
    )
}

/// The three lobes: `(name, A, Sigma)`.
fn lobes() -> Vec<(&'static str, d::RoughnessMatrix, d::Covariance)> {
    let (a11, a12, a22) = rotated(0.01, 0.01 / 16.0, 0.6);
    let (k11, k12, k22) = rotated(0.01, 0.002, 1.3);
    let (b11, b12, b22) = rotated(1e-4, 1e-4, 0.0);
    let (r11, r12, r22) = rotated(0.3 * 0.3 * 0.09, 0.0, 2.0);
    vec![
        (
            "lobe-dominated",
            d::RoughnessMatrix::new(a11, a12, a22).unwrap(),
            d::Covariance::new(k11 * 0.1, k12 * 0.1, k22 * 0.1),
        ),
        (
            "kernel-dominated",
            d::RoughnessMatrix::new(b11, b12, b22).unwrap(),
            d::Covariance::new(1e-2, 2e-3, 5e-3),
        ),
        (
            "rank-one kernel",
            d::AxisAligned::new(0.3, 0.15).unwrap().to_matrix(),
            d::Covariance::new(r11, r12, r22),
        ),
    ]
}

fn view(deg: f64) -> DVec3 {
    let t = deg.to_radians();
    DVec3::new(t.sin() * 1.0f64.cos(), t.sin() * 1.0f64.sin(), t.cos())
}

use filtered_ndf::f64::Roughness as _;

#[test]
fn chi2_exact_gaussian_filtered_ggx_samplers() {
    let alpha_test = 1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64);
    let mut failures = Vec::new();
    for (i, (name, a, k)) in lobes().into_iter().enumerate() {
        let lobe = d::GaussianFilteredGgx::new(a, k);
        let grid = d::filter::gaussian(a, k);
        for (j, v) in [None, Some(0.0), Some(30.0), Some(80.0)]
            .into_iter()
            .enumerate()
        {
            let seed = 0x6A55_0000 + (10 * i + j) as u64;
            let out = match v {
                None => chi2_test(
                    &grid,
                    Radial::Ggx,
                    seed,
                    |u| lobe.sample_normal(u),
                    |m| lobe.normal_pdf(m),
                ),
                Some(deg) => {
                    let wo = view(deg);
                    chi2_test(
                        &grid,
                        Radial::Ggx,
                        seed,
                        |u| {
                            let m = lobe.sample_visible_normal(wo, u).expect("wo above");
                            assert!(wo.dot(m) > 0.0, "{m} faces away from {wo}");
                            m
                        },
                        |m| lobe.visible_normal_pdf(wo, m),
                    )
                }
            };
            let label = v.map_or("D cos".to_string(), |d| format!("vis {d:>4}"));
            println!(
                "| {name} | {label} | chi2 {:>8.1} | dof {:>4} | p {:>8.4} | mass - 1 {:.1e} |",
                out.chi2,
                out.dof,
                out.p,
                out.expected_total - 1.0
            );
            if (out.expected_total - 1.0).abs() > 1e-5 {
                failures.push(format!("{name} {label}: mass {}", out.expected_total));
            }
            if out.p.is_nan() || out.p <= alpha_test {
                failures.push(format!("{name} {label}: p = {} <= {alpha_test}", out.p));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn chi2_f32_samplers_against_the_f64_pdf() {
    use filtered_ndf::f32 as s;
    use filtered_ndf::f32::NdfSampling as _;
    let alpha_test = 1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64);
    let (_, a, k) = lobes().remove(0);
    let (a11, a12, a22) = a.entries();
    let (a11, a12, a22) = (a11 as f32, a12 as f32, a22 as f32);
    let k32 = s::Covariance::new(k.s11 as f32, k.s12 as f32, k.s22 as f32);
    let a64 = d::RoughnessMatrix::new(a11 as f64, a12 as f64, a22 as f64).unwrap();
    let k64 = d::Covariance::new(k32.s11 as f64, k32.s12 as f64, k32.s22 as f64);
    let l32 = s::GaussianFilteredGgx::new(s::RoughnessMatrix::new(a11, a12, a22).unwrap(), k32);
    let l64 = d::GaussianFilteredGgx::new(a64, k64);
    let grid = d::filter::gaussian(a64, k64);
    let u32of = |u: DVec2| glam::Vec2::new(u.x as f32, u.y as f32);
    let wo = view(30.0);
    let wo32 = wo.as_vec3();
    let o1 = chi2_test(
        &grid,
        Radial::Ggx,
        0x06A5_5F32,
        |u| l32.sample_normal(u32of(u)).as_dvec3(),
        |m| l64.normal_pdf(m),
    );
    let o2 = chi2_test(
        &grid,
        Radial::Ggx,
        0x06A5_5F33,
        |u| {
            l32.sample_visible_normal(wo32, u32of(u))
                .unwrap()
                .as_dvec3()
        },
        |m| l64.visible_normal_pdf(wo, m),
    );
    for (label, o) in [("f32 D cos", o1), ("f32 vis 30", o2)] {
        println!(
            "| {label} | chi2 {:>8.1} | dof {:>4} | p {:>8.4} |",
            o.chi2, o.dof, o.p
        );
        assert!(o.p > alpha_test, "{label}: p = {}", o.p);
    }
}
