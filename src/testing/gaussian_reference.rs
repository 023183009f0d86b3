//! The exact Gaussian-filtered slope density, by f64 quadrature: the reference that the
//! filtering kernels (and anything built on them) are measured against.
//!
//! `P22_Sigma(s) = (P22 * N_Sigma)(s) = integral P22(s - t) N(t; 0, Sigma) dt` over the slope
//! plane, with `N(t; 0, Sigma)` the bivariate normal density of covariance `Sigma` (KHPL16
//! eq. 12 with a Gaussian kernel; TK19 section 2.2).
//!
//! Method: `t = x e1 + y e2` in the eigenbasis of `Sigma`, so the kernel factorises into two
//! 1D normals. Each 1D integral is split at breakpoints around both features (the kernel at
//! `0` with its standard deviation, and the density's peak along the line with its conditional
//! width, from `0.5` to `128` widths), integrated piecewise by adaptive Gauss-Kronrod
//! ([`super::quadrature::integrate`]) and closed by two mapped tails, so a lobe far narrower
//! than the kernel (or the reverse) is never stepped over.
//!
//! Degenerate kernels: a zero kernel (`lambda_max <= 0`) returns the unfiltered density with
//! zero error; a singular one (`sqrt(lambda_min) < 1e-12` times the smallest other width)
//! reduces to the 1D integral along its range (the neglected variance changes the result by a
//! relative `O(1e-24)`).
//!
//! Error estimate: the sum of the piecewise estimates, plus, in 2D, the inner integrals'
//! error estimates integrated with the outer rule's weights
//! ([`super::quadrature::integrate_estimates`]).

extern crate alloc;
use alloc::vec::Vec;

use super::linalg::Sym2;
use super::quadrature::{Estimate, Tolerance, integrate_estimates};
use crate::f64::{Beckmann, Covariance, Ggx, Ndf, Roughness, RoughnessMatrix, Vec2};

const INV_SQRT_2PI: f64 = 0.398_942_280_401_432_7;

/// `(f * N_Sigma)(s)` for a unimodal density `f` peaked at `center` whose spread is described
/// by the SPD matrix `spread` (widths `sqrt(e^T M e)`, conditional widths
/// `1 / sqrt(e^T M^-1 e)`; for GGX and Beckmann the roughness matrix). `kernel` is
/// sanitized first ([`Covariance::sanitized`]).
pub fn gaussian_convolution<Fd: FnMut(Vec2) -> f64>(
    mut density: Fd,
    center: Vec2,
    spread: RoughnessMatrix,
    kernel: Covariance,
    s: Vec2,
    tol: Tolerance,
) -> Estimate {
    let k = kernel.sanitized();
    // The kernel's eigenbasis from the test side's own decomposition (not the library's).
    let eig = Sym2::new(k.s11, k.s12, k.s22).eigen();
    let (lmin, lmax) = (eig.l2.max(0.0), eig.l1.max(0.0));
    if lmax <= 0.0 {
        return Estimate {
            value: density(s),
            error: 0.0,
        };
    }
    let e1 = Vec2::new(eig.theta.cos(), eig.theta.sin());
    let e2 = Vec2::new(-e1.y, e1.x);
    let m = spread.to_mat2();
    let minv = spread.inverse();
    let width = |e: Vec2| e.dot(m * e).max(0.0).sqrt();
    let cond_width = |e: Vec2| 1.0 / e.dot(minv * e).max(1e-300).sqrt();
    let (sd1, sd2) = (lmax.sqrt(), lmin.sqrt());
    let w_min = width(e1).min(width(e2)).min(cond_width(e1)).min(sd1);

    // Inner integral along e1 at fixed offset `y` along e2.
    let inner = |y: f64, density: &mut Fd, tol: Tolerance| -> Estimate {
        let d = s - y * e2 - center;
        // Along r(x) = s - y e2 - x e1 the density peaks at x* = e1^T M^-1 d / e1^T M^-1 e1.
        let q = e1.dot(minv * e1).max(1e-300);
        let x_star = e1.dot(minv * d) / q;
        let wx = cond_width(e1);
        let mut g = |x: f64| {
            let v = density(s - y * e2 - x * e1) * normal(x, sd1);
            (if v.is_finite() { v } else { 0.0 }, 0.0)
        };
        line(&mut g, &[(0.0, sd1, false), (x_star, wx, true)], tol)
    };

    if sd2 < 1e-12 * w_min {
        return inner(0.0, &mut density, tol);
    }

    let inner_tol = Tolerance {
        rel: tol.rel * 0.1,
        abs: tol.abs * 0.1,
        ..tol
    };
    let y_star = e2.dot(s - center);
    let wy = width(e2);
    // The inner integrals' errors are integrated with the outer rule's weights (the estimate
    // adds them to the outer one).
    let mut g = |y: f64| {
        let e = inner(y, &mut density, inner_tol);
        let n = normal(y, sd2);
        let (v, err) = (e.value * n, e.error * n);
        if v.is_finite() && err.is_finite() {
            (v, err)
        } else {
            (0.0, 0.0)
        }
    };
    line(&mut g, &[(0.0, sd2, false), (y_star, wy, true)], tol)
}

/// The Gaussian-filtered GGX slope density `(P22_GGX * N_Sigma)(s)` (per unit slope area).
pub fn ggx<R: Roughness>(roughness: R, kernel: Covariance, s: Vec2, tol: Tolerance) -> Estimate {
    filtered_p22(Ggx::new(roughness), roughness, kernel, s, tol)
}

/// The Gaussian-filtered Beckmann slope density `(P22_Beckmann * N_Sigma)(s)`; in closed form
/// it is the Beckmann density of `A + 2 Sigma` (KHPL16 eq. 15), which this does not use.
pub fn beckmann<R: Roughness>(
    roughness: R,
    kernel: Covariance,
    s: Vec2,
    tol: Tolerance,
) -> Estimate {
    filtered_p22(Beckmann::new(roughness), roughness, kernel, s, tol)
}

/// `(P22 * N_Sigma)(s)` of a centred lobe `ndf` of roughness `roughness`.
fn filtered_p22<N: Ndf, R: Roughness>(
    ndf: N,
    roughness: R,
    kernel: Covariance,
    s: Vec2,
    tol: Tolerance,
) -> Estimate {
    gaussian_convolution(
        |r| ndf.p22(r),
        Vec2::ZERO,
        roughness.to_matrix(),
        kernel,
        s,
        tol,
    )
}

/// The 1D normal density of standard deviation `sd > 0` at `x`.
#[inline]
fn normal(x: f64, sd: f64) -> f64 {
    let u = x / sd;
    INV_SQRT_2PI / sd * (-0.5 * u * u).exp()
}

/// `integral_R g(x) dx` split at breakpoints around features `(centre, width, heavy_tail)`.
/// `g` returns a value and its own absolute error (`0` for a plain integrand).
fn line(
    g: &mut dyn FnMut(f64) -> (f64, f64),
    features: &[(f64, f64, bool)],
    tol: Tolerance,
) -> Estimate {
    const GAUSS: [f64; 5] = [0.0, 1.0, 3.0, 6.0, 10.0];
    const HEAVY: [f64; 7] = [0.0, 0.5, 2.0, 8.0, 32.0, 128.0, 512.0];
    let mut pts: Vec<f64> = Vec::new();
    let mut big = 0.0_f64;
    for &(c, w, heavy) in features {
        if !(c.is_finite() && w.is_finite() && w > 0.0) {
            continue;
        }
        big = big.max(w);
        let steps: &[f64] = if heavy { &HEAVY } else { &GAUSS };
        for &k in steps {
            pts.push(c + k * w);
            pts.push(c - k * w);
        }
    }
    if pts.is_empty() {
        pts.push(0.0);
        big = 1.0;
    }
    pts.sort_by(|a, b| a.total_cmp(b));
    pts.dedup_by(|a, b| (*a - *b).abs() <= 1e-15 * a.abs().max(b.abs()));
    let piece_tol = Tolerance {
        abs: tol.abs / (pts.len() as f64 + 1.0),
        ..tol
    };
    let mut value = 0.0;
    let mut error = 0.0;
    for w in pts.windows(2) {
        let e = integrate_estimates(&mut *g, w[0], w[1], piece_tol);
        value += e.value;
        error += e.error;
    }
    // Tails: x = b +/- L t / (1 - t), t in [0, 1).
    let (lo, hi) = (pts[0], pts[pts.len() - 1]);
    for (b, sign) in [(hi, 1.0), (lo, -1.0)] {
        let e = integrate_estimates(
            |t| {
                let d = 1.0 - t;
                let j = big / (d * d);
                let (v, err) = g(b + sign * big * t / d);
                let (v, err) = (v * j, err * j);
                if v.is_finite() && err.is_finite() {
                    (v, err)
                } else {
                    (0.0, 0.0)
                }
            },
            0.0,
            1.0,
            piece_tol,
        );
        value += e.value;
        error += e.error;
    }
    Estimate { value, error }
}
