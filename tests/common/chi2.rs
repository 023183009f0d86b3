//! The chi-square goodness-of-fit harness of `tests/sampling_chi2.rs` (its regularised
//! incomplete gamma function, whitened `(r, phi)` grid, pooling and statistic), as a module that
//! other sampling tests include with `#[path = "common/chi2.rs"] mod chi2;` next to `mod common;`.
//! The statistics are documented (and the gamma function tested) in `tests/sampling_chi2.rs`,
//! which uses it too.
#![allow(dead_code)]

use crate::common::whitening::Whitening;
use filtered_ndf::f64::Roughness;
use filtered_ndf::testing::quadrature::{Tolerance, integrate_2d};
use filtered_ndf::testing::rng::SplitMix64;
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

// Regularised incomplete gamma function (series + Lentz continued fraction, after Numerical
// Recipes 6.2; written for this test).

/// `ln Gamma(x)` for `x > 0` by the Lanczos approximation (g = 7, 9 terms; relative error
/// about 1e-15).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Gamma(x) Gamma(1 - x) = pi / sin(pi x).
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Upper regularised incomplete gamma `Q(a, x) = Gamma(a, x) / Gamma(a)`, `a > 0`, `x >= 0`.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    assert!(a > 0.0 && x >= 0.0, "gamma_q({a}, {x})");
    if x == 0.0 {
        return 1.0;
    }
    let prefactor = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        // Series for P(a, x): sum x^n / (a (a+1) ... (a+n)).
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        1.0 - sum * prefactor
    } else {
        // Continued fraction for Q(a, x) by the modified Lentz method.
        const TINY: f64 = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        prefactor * h
    }
}

/// Survival function of the chi-square distribution with `dof` degrees of freedom.
pub fn chi2_sf(chi2: f64, dof: usize) -> f64 {
    gamma_q(0.5 * dof as f64, 0.5 * chi2)
}

// ---------------------------------------------------------------------------------------
// The harness.

pub const N_SAMPLES: usize = 40_000;
pub const N_R: usize = 40;
pub const N_PHI: usize = 40;
pub const MIN_EXPECTED: f64 = 5.0;
pub const ALPHA_SUITE: f64 = 0.01;

#[derive(Clone, Copy, PartialEq)]
pub enum Radial {
    /// GGX: `F(q) = q / (1 + q)`.
    Ggx,
    /// Beckmann: `F(q) = 1 - exp(-q)`.
    Beckmann,
}

impl Radial {
    /// `r = F(q)` and `dq/dr` at `r`.
    pub fn r_of_q(self, q: f64) -> f64 {
        match self {
            Radial::Ggx => q / (1.0 + q),
            Radial::Beckmann => -(-q).exp_m1(),
        }
    }
    pub fn q_of_r(self, r: f64) -> (f64, f64) {
        match self {
            Radial::Ggx => (r / (1.0 - r), 1.0 / ((1.0 - r) * (1.0 - r))),
            Radial::Beckmann => (-(-r).ln_1p(), 1.0 / (1.0 - r)),
        }
    }
}

pub struct Outcome {
    pub chi2: f64,
    pub dof: usize,
    pub p: f64,
    pub expected_total: f64,
}

/// Runs one chi-square test: `sample(u)` against `pdf(m)` (per steradian).
pub fn chi2_test(
    roughness: &impl Roughness,
    radial: Radial,
    seed: u64,
    sample: impl Fn(DVec2) -> DVec3,
    pdf: impl Fn(DVec3) -> f64,
) -> Outcome {
    let wh = Whitening::new(roughness);
    let cell_of = |m: DVec3| -> usize {
        assert!(m.is_finite() && m.z > 0.0, "sample {m} below the horizon");
        // 1e-6: the f32 samplers are tested here too (f64 ones are checked to 1e-12 in
        // tests/sampling.rs).
        assert!((m.length() - 1.0).abs() < 1e-6, "sample {m} not unit");
        let s = DVec2::new(-m.x / m.z, -m.y / m.z);
        let w = Whitening::apply(&wh.b_inv, s);
        let r = radial.r_of_q(w.length_squared());
        let phi = w.y.atan2(w.x).rem_euclid(2.0 * PI);
        let ir = ((r * N_R as f64) as usize).min(N_R - 1);
        let ip = ((phi / (2.0 * PI) * N_PHI as f64) as usize).min(N_PHI - 1);
        ir * N_PHI + ip
    };
    let mut observed = vec![0.0_f64; N_R * N_PHI];
    let mut rng = SplitMix64(seed);
    for _ in 0..N_SAMPLES {
        let u = DVec2::new(rng.uniform(), rng.uniform());
        observed[cell_of(sample(u))] += 1.0;
    }
    // Density in (r, phi): pdf(m) m_z^3 sqrt(det A) (dq/dr) / 2.
    let density = |r: f64, phi: f64| -> f64 {
        let (q, dq) = radial.q_of_r(r);
        let w = DVec2::new(phi.cos(), phi.sin()) * q.sqrt();
        let s = Whitening::apply(&wh.b, w);
        let m = DVec3::new(-s.x, -s.y, 1.0).normalize();
        let v = pdf(m) * m.z.powi(3) * wh.sqrt_det * dq * 0.5;
        if v.is_finite() { v } else { 0.0 }
    };
    // Cell integrals: relative 1e-7 (the expected counts need ~1e-4 at most; the pdf has a
    // kink at the visibility cut-off, which the adaptive rule resolves).
    let tol = Tolerance {
        abs: 1e-12,
        rel: 1e-7,
        max_intervals: 60,
    };
    let mut expected = vec![0.0_f64; N_R * N_PHI];
    for ir in 0..N_R {
        for ip in 0..N_PHI {
            let r = (ir as f64 / N_R as f64, (ir + 1) as f64 / N_R as f64);
            let p = (
                ip as f64 / N_PHI as f64 * 2.0 * PI,
                (ip + 1) as f64 / N_PHI as f64 * 2.0 * PI,
            );
            let e = integrate_2d(|phi, rr| density(rr, phi), p, r, tol);
            expected[ir * N_PHI + ip] = e.value * N_SAMPLES as f64;
        }
    }
    let expected_total: f64 = expected.iter().sum::<f64>() / N_SAMPLES as f64;
    // Pooling.
    let (mut pooled_e, mut pooled_o) = (0.0, 0.0);
    let mut cells: Vec<(f64, f64)> = Vec::new();
    for (&e, &o) in expected.iter().zip(&observed) {
        if e < 1e-9 * N_SAMPLES as f64 {
            assert!(o == 0.0, "{o} samples in a cell of expected count {e}");
        }
        if e < MIN_EXPECTED {
            pooled_e += e;
            pooled_o += o;
        } else {
            cells.push((e, o));
        }
    }
    if pooled_e > 0.0 {
        if pooled_e < MIN_EXPECTED && !cells.is_empty() {
            let (i, _) = cells
                .iter()
                .enumerate()
                .min_by(|a, b| a.1.0.total_cmp(&b.1.0))
                .unwrap();
            cells[i].0 += pooled_e;
            cells[i].1 += pooled_o;
        } else {
            cells.push((pooled_e, pooled_o));
        }
    }
    // Normalise the expected counts to the number of samples (the cell integrals sum to
    // 1 +- ~1e-7, checked by the caller through expected_total).
    let scale = N_SAMPLES as f64 / cells.iter().map(|c| c.0).sum::<f64>();
    let chi2: f64 = cells
        .iter()
        .map(|&(e, o)| {
            let e = e * scale;
            (o - e) * (o - e) / e
        })
        .sum();
    let dof = cells.len() - 1;
    Outcome {
        chi2,
        dof,
        p: chi2_sf(chi2, dof),
        expected_total,
    }
}
