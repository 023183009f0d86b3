//! The seeded domain of the exact Gaussian-filtered GGX's tests (`tests/gaussian_ggx.rs`,
//! `tests/gaussian_ggx_tolerance.rs`): alpha log-uniform in `[1e-4, 1]`, anisotropy up to
//! 100:1, rotated; kernel standard deviations from `1e-3` to `1e3` lobe widths (one case in
//! eight the zero kernel, one in eight rank one), kernel anisotropy up to `1e2`, rotated;
//! slopes `s = rho L u` with `L L^T = A + 2 Sigma`, `rho` uniform in `[0, 50]` for half the
//! cases and log-uniform in `[1e-3, 50]` for the others. Every input is representable in `f32`,
//! so both precisions and the reference see the same numbers. Nothing here calls the code under
//! test except `RoughnessMatrix::new`, to skip matrices the checked constructor refuses.
#![allow(dead_code)]

use filtered_ndf::f32 as s;
use filtered_ndf::testing::rng::SplitMix64 as Rng;

/// One seeded case: the roughness matrix `(a11, a12, a22)`, the kernel `(k11, k12, k22)` and
/// the slope `(sx, sy)`.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// The roughness matrix `A`.
    pub a: (f32, f32, f32),
    /// The kernel covariance `Sigma`.
    pub k: (f32, f32, f32),
    /// The slope.
    pub s: (f32, f32),
}

/// The symmetric matrix with eigenvalues `l1`, `l2`, rotated by `phi`: `(m11, m12, m22)`.
pub fn rotated(l1: f64, l2: f64, phi: f64) -> (f64, f64, f64) {
    let (c, sn) = (phi.cos(), phi.sin());
    (
        c * c * l1 + sn * sn * l2,
        c * sn * (l1 - l2),
        sn * sn * l1 + c * c * l2,
    )
}

/// `n` cases of the domain above from `seed`.
pub fn cases(n: usize, seed: u64) -> Vec<Case> {
    let mut r = Rng(seed);
    let mut out = Vec::new();
    while out.len() < n {
        let i = out.len();
        let alpha = 10f64.powf(r.range(-4.0, 0.0));
        let aniso = 10f64.powf(r.range(0.0, 2.0));
        let (a11, a12, a22) = rotated(alpha * alpha, (alpha / aniso).powi(2), r.range(0.0, 3.2));
        let a = (a11 as f32, a12 as f32, a22 as f32);
        if s::RoughnessMatrix::new(a.0, a.1, a.2).is_err() {
            continue;
        }
        let kw = 10f64.powf(r.range(-3.0, 3.0));
        let k1 = if i % 8 == 0 {
            0.0
        } else {
            (alpha * kw).powi(2)
        };
        let k2 = if i % 8 < 2 {
            0.0
        } else {
            k1 * 10f64.powf(r.range(-4.0, 0.0))
        };
        let (k11, k12, k22) = rotated(k1, k2, r.range(0.0, 3.2));
        // s = rho L u with L the Cholesky factor of A + 2 Sigma.
        let (f11, f12, f22) = (a11 + 2.0 * k11, a12 + 2.0 * k12, a22 + 2.0 * k22);
        let l11 = f11.sqrt();
        let l21 = f12 / l11;
        let l22 = (f22 - l21 * l21).max(0.0).sqrt();
        let rho = if i % 2 == 0 {
            r.range(0.0, 50.0)
        } else {
            10f64.powf(r.range(-3.0, 1.7))
        };
        let th = r.range(0.0, std::f64::consts::TAU);
        let (ux, uy) = (th.cos(), th.sin());
        out.push(Case {
            a,
            k: (k11 as f32, k12 as f32, k22 as f32),
            s: (
                (rho * l11 * ux) as f32,
                (rho * (l21 * ux + l22 * uy)) as f32,
            ),
        });
    }
    out
}
