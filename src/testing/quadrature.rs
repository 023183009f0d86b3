//! Adaptive Gauss-Kronrod quadrature in `f64`, with an error estimate: the independent
//! reference every kernel of the crate is tested against.
//!
//! - [`integrate`]: `integral_a^b f(x) dx` by globally adaptive G7-K15 (QUADPACK's QAG
//!   strategy): the interval with the largest error estimate is bisected until the summed
//!   estimate is below `max(abs_tol, rel_tol |I|)`; [`integrate_estimates`] the same for an
//!   integrand that carries its own error (an inner integral), integrated alongside.
//! - [`integrate_line`]: `integral_-inf^inf f(x) dx` through `x = c + L t / (1 - t^2)`,
//!   `t in (-1, 1)`, with the feature of `f` (its peak) at `c` and its width `L`.
//! - [`integrate_2d`] and [`integrate_plane`]: nested 2D versions, outer integral of inner
//!   integrals, whose error estimates add the outer estimate to the integrated inner ones.
//!
//! The error estimate is QUADPACK's `|K15 - G7|` per interval (not its sharpened form), which
//! over-estimates the true error of a smooth integrand by orders of magnitude; it is a bound
//! in practice, not a proof.

extern crate alloc;
use alloc::vec::Vec;

/// A quadrature result: the value and its estimated absolute error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The integral's estimate.
    pub value: f64,
    /// The estimated absolute error (`>= 0`).
    pub error: f64,
}

/// Tolerances and the budget of an adaptive integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Absolute error goal.
    pub abs: f64,
    /// Relative error goal.
    pub rel: f64,
    /// Maximum number of intervals (each costs 15 evaluations).
    pub max_intervals: usize,
}

impl Default for Tolerance {
    /// `abs = 1e-13`, `rel = 1e-10`, at most 2000 intervals.
    fn default() -> Self {
        Self {
            abs: 1e-13,
            rel: 1e-10,
            max_intervals: 2000,
        }
    }
}

impl Tolerance {
    /// Relative goal `rel` with a tiny absolute floor and the default budget.
    pub fn relative(rel: f64) -> Self {
        Self {
            abs: 1e-300,
            rel,
            ..Self::default()
        }
    }
}

// Gauss-Kronrod 7-15 nodes and weights (QUADPACK qk15).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// One G7-K15 panel over `[a, b]` of an integrand returning `(value, inner_error)`:
/// `(value, |K15 - G7|, the inner errors integrated by K15)`.
fn gk15<G: FnMut(f64) -> (f64, f64)>(g: &mut G, a: f64, b: f64) -> (f64, f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let (fc, ec) = g(c);
    let mut k = fc * WGK[7];
    let mut gs = fc * WG[3];
    let mut inner = ec.abs() * WGK[7];
    for j in 0..7 {
        let x = h * XGK[j];
        let (f1, e1) = g(c - x);
        let (f2, e2) = g(c + x);
        k += WGK[j] * (f1 + f2);
        inner += WGK[j] * (e1.abs() + e2.abs());
        if j % 2 == 1 {
            gs += WG[j / 2] * (f1 + f2);
        }
    }
    (k * h, ((k - gs) * h).abs(), inner * h.abs())
}

/// The adaptive loop. Bisection is driven by the rule's own estimate `|K15 - G7|` alone: the
/// inner errors of a nested integrand do not shrink when the outer interval is split, so they
/// are added to the result's estimate but neither chosen nor waited on.
fn adaptive<G: FnMut(f64) -> (f64, f64)>(mut g: G, a: f64, b: f64, tol: Tolerance) -> Estimate {
    let (v, e, i) = gk15(&mut g, a, b);
    let mut intervals: Vec<(f64, f64, f64, f64, f64)> = alloc::vec![(a, b, v, e, i)];
    let (mut value, mut error) = (v, e);
    while error > tol.abs.max(tol.rel * value.abs()) && intervals.len() < tol.max_intervals {
        let (idx, _) = intervals
            .iter()
            .enumerate()
            .fold(
                (0, -1.0),
                |best, (i, iv)| if iv.3 > best.1 { (i, iv.3) } else { best },
            );
        let (lo, hi, v0, e0, i0) = intervals.swap_remove(idx);
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            // Cannot split further in f64: keep it and stop.
            intervals.push((lo, hi, v0, e0, i0));
            break;
        }
        let (v1, e1, i1) = gk15(&mut g, lo, mid);
        let (v2, e2, i2) = gk15(&mut g, mid, hi);
        intervals.push((lo, mid, v1, e1, i1));
        intervals.push((mid, hi, v2, e2, i2));
        value = intervals.iter().map(|iv| iv.2).sum();
        error = intervals.iter().map(|iv| iv.3).sum();
    }
    let inner: f64 = intervals.iter().map(|iv| iv.4).sum();
    Estimate {
        value,
        error: error + inner,
    }
}

/// `integral_a^b f(x) dx` by adaptive G7-K15.
pub fn integrate<Fx: FnMut(f64) -> f64>(mut f: Fx, a: f64, b: f64, tol: Tolerance) -> Estimate {
    adaptive(|x| (f(x), 0.0), a, b, tol)
}

/// `integral_a^b g(x) dx` by adaptive G7-K15 for an integrand that is itself an estimate:
/// `g(x) = (value, error)`, its absolute error integrated with the same Kronrod weights and
/// added to the estimate (the inner integrals of a nested quadrature).
pub fn integrate_estimates<G: FnMut(f64) -> (f64, f64)>(
    g: G,
    a: f64,
    b: f64,
    tol: Tolerance,
) -> Estimate {
    adaptive(g, a, b, tol)
}

/// Maps `t in (-1, 1)` to `x = c + L t / (1 - t^2)`; returns `(x, dx/dt)`.
#[inline]
fn line_map(t: f64, center: f64, scale: f64) -> (f64, f64) {
    let d = 1.0 - t * t;
    (center + scale * t / d, scale * (1.0 + t * t) / (d * d))
}

/// `integral_-inf^inf f(x) dx` for an integrand concentrated around `center` with width
/// `scale > 0` (the substitution puts half of the `t` range within `|x - c| < 0.6 L`).
/// `f` must decay at least like `|x|^-1-eps`.
pub fn integrate_line<Fx: FnMut(f64) -> f64>(
    mut f: Fx,
    center: f64,
    scale: f64,
    tol: Tolerance,
) -> Estimate {
    adaptive(
        |t| {
            let (x, j) = line_map(t, center, scale);
            let v = f(x) * j;
            (if v.is_finite() { v } else { 0.0 }, 0.0)
        },
        -1.0,
        1.0,
        tol,
    )
}

/// `integral_{y0}^{y1} integral_{x0}^{x1} f(x, y) dx dy`, nested adaptive. The inner
/// integrals use `tol` with a relative goal ten times tighter.
pub fn integrate_2d<Fxy: FnMut(f64, f64) -> f64>(
    mut f: Fxy,
    x: (f64, f64),
    y: (f64, f64),
    tol: Tolerance,
) -> Estimate {
    let inner_tol = Tolerance {
        rel: tol.rel * 0.1,
        abs: tol.abs * 0.1,
        ..tol
    };
    adaptive(
        |yy| {
            let e = adaptive(|xx| (f(xx, yy), 0.0), x.0, x.1, inner_tol);
            (e.value, e.error)
        },
        y.0,
        y.1,
        tol,
    )
}

/// `integral over R^2 of f(x, y)` for an integrand concentrated around `center` with widths
/// `scale` (see [`integrate_line`]), nested adaptive.
pub fn integrate_plane<Fxy: FnMut(f64, f64) -> f64>(
    mut f: Fxy,
    center: (f64, f64),
    scale: (f64, f64),
    tol: Tolerance,
) -> Estimate {
    integrate_2d(
        |tx, ty| {
            let (x, jx) = line_map(tx, center.0, scale.0);
            let (y, jy) = line_map(ty, center.1, scale.1);
            let v = f(x, y) * jx * jy;
            if v.is_finite() { v } else { 0.0 }
        },
        (-1.0, 1.0),
        (-1.0, 1.0),
        tol,
    )
}
