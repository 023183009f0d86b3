//! The Gaussian kernel of a footprint: a slope-domain covariance `Sigma` (KHPL16 eq. 13-15,
//! TK19 section 2.2), with the eigenvalue clamp of TK19 eq. 1 and the sanitiser every filter
//! applies first.

use super::super::ndf::roughness::ALPHA_MAX;
use super::F;
use crate::math::{self as m, Real};

/// A symmetric positive semi-definite 2x2 covariance `[[s11, s12], [s12, s22]]` in the slope
/// domain (units: slope^2). Covariances of independent kernels add (KHPL16 eq. 15, 21).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Covariance {
    /// Variance along the tangent `x` (slope^2).
    pub s11: F,
    /// Covariance of `x` and `y` (slope^2).
    pub s12: F,
    /// Variance along the bitangent `y` (slope^2).
    pub s22: F,
}

impl Covariance {
    /// The zero kernel (no filtering).
    pub const ZERO: Self = Self {
        s11: 0.0,
        s12: 0.0,
        s22: 0.0,
    };

    /// From the three distinct entries (not checked; see the filtering functions for what
    /// they do with an indefinite or non-finite covariance).
    #[inline]
    pub const fn new(s11: F, s12: F, s22: F) -> Self {
        Self { s11, s12, s22 }
    }

    /// `tr(Sigma) = lambda_min + lambda_max` (TK19 eq. 2).
    #[inline]
    pub fn trace(self) -> F {
        self.s11 + self.s22
    }

    /// `det(Sigma) = lambda_min lambda_max`.
    #[inline]
    pub fn det(self) -> F {
        self.s11 * self.s22 - self.s12 * self.s12
    }

    /// Eigenvalues `(lambda_min, lambda_max)`, computed as `mean +/- hypot(half difference,
    /// s12)` for `lambda_max` and `det / lambda_max` for `lambda_min`, so the small one keeps
    /// its relative accuracy for elongated kernels. Both are clamped to `>= 0`.
    #[inline]
    pub fn eigenvalues(self) -> (F, F) {
        let (min, max, _) = self.eigen_parts();
        (min, max)
    }

    /// [`Covariance::eigenvalues`] and the radius `hypot(half difference, s12)`.
    #[inline]
    fn eigen_parts(self) -> (F, F, F) {
        let mean = 0.5 * (self.s11 + self.s22);
        let rad = radius(0.5 * (self.s11 - self.s22), self.s12);
        let max = (mean + rad).max(0.0);
        let min = if max > 0.0 {
            let det = self.det();
            // `det` overflows (to inf or inf - inf = NaN) for huge finite entries and loses its
            // bits for tiny (subnormal) products: divide first then.
            let min = if det.is_finite() && det.abs() >= F::MIN_POSITIVE {
                det / max
            } else {
                (self.s11 / max) * self.s22 - (self.s12 / max) * self.s12
            };
            min.max(0.0)
        } else {
            0.0
        };
        (min, max, rad)
    }

    /// Clamps both eigenvalues to `<= max` without rotating the eigenvectors:
    /// `Sigma' = V min(Lambda, max) V^T`. This is the matrix form of TK19 eq. 1's
    /// `min(2 lambda, kappa)` (see [`super::clamp::ClampRules::kernel`]).
    ///
    /// Computed as `max P_max + lambda_min P_min` with the spectral projectors
    /// `P_max = (Sigma - lambda_min I) / (lambda_max - lambda_min)`, `P_min = I - P_max` when
    /// only `lambda_max` exceeds `max` (no eigenvector is formed, every term is non-negative),
    /// and `max I` when both do. The matrix is first scaled to unit size (largest entry 1) so
    /// nothing overflows or underflows. A negative or NaN `max` yields [`Covariance::ZERO`], a non-finite
    /// input [`Covariance::ZERO`] (use [`Covariance::sanitized`] for the full contract).
    #[inline]
    pub fn clamp_eigenvalues(self, max: F) -> Self {
        // Fast path: a finite PSD kernel whose trace (lambda_min + lambda_max) is within the
        // bound (`max` is then not NaN and >= 0). Inlined; the rest is out of line, by value
        // (a by-reference call from inlined code measured a store-forwarding stall).
        let (a, b, c) = (self.s11, self.s12, self.s22);
        if a >= 0.0 && c >= 0.0 && a + c <= max && (a + c).is_finite() && b.is_finite() {
            return Self::new(a, b, c);
        }
        // Second fast path: the largest eigenvalue `mean + sqrt(d^2 + b^2)` within the bound,
        // tested without the square root: `d^2 + b^2 <= (max - mean)^2`. The bounds on
        // `h = max - mean` keep `h^2` finite and normal (a square that underflows beside it
        // is negligible; fuzzing found `h = 0` against underflowing squares); NaN fails the
        // comparisons.
        let (mean, d) = (0.5 * (a + c), 0.5 * (a - c));
        let h = max - mean;
        let h_ok = (1.0 / FAST_EIGEN_MAX..=FAST_EIGEN_MAX).contains(&h);
        if a >= 0.0 && c >= 0.0 && h_ok && d * d + b * b <= h * h {
            return Self::new(a, b, c);
        }
        Self::clamp_eigenvalues_slow(a, b, c, max).detached()
    }

    /// The general case of [`Covariance::clamp_eigenvalues`].
    #[cold]
    #[inline(never)]
    fn clamp_eigenvalues_slow(s11: F, s12: F, s22: F, max: F) -> Self {
        // Non-finite entries are caught here: `F::max` below would pass a NaN through.
        let finite = s11.is_finite() && s12.is_finite() && s22.is_finite();
        if max.is_nan() || max < 0.0 || !finite {
            return Self::ZERO;
        }
        let this = Self::new(s11, s12, s22);
        let scale = s11.abs().max(s22.abs()).max(s12.abs());
        if scale <= 0.0 {
            return this;
        }
        // Unless every square below is a finite normal number (the entries within the fast
        // range and `r^2 = d^2 + s12^2` well above the subnormals: fuzzing found `s12^2`
        // underflowing beside normal diagonal entries), work on Sigma / scale (largest entry
        // 1). Tiny (subnormal) entries are scaled up too: `1 / (2 r)` below would overflow to
        // inf (0 * inf = NaN); dividing (not multiplying by `1 / k`, which overflows for a
        // subnormal `k`).
        let d0 = 0.5 * (s11 - s22);
        let r2 = d0 * d0 + s12 * s12;
        let unscaled = (1.0 / FAST_EIGEN_MAX..=FAST_EIGEN_MAX).contains(&scale)
            && r2 >= F::MIN_POSITIVE / F::EPSILON;
        let (k, s) = if unscaled {
            (1.0, this)
        } else {
            (scale, Self::new(s11 / scale, s12 / scale, s22 / scale))
        };
        let (lmin, lmax, r) = s.eigen_parts();
        // Compared and rebuilt in the caller's units (`lambda * k` against `max`): `max / k`
        // is subnormal when `max << scale` and carries only a few bits (fuzzing found 40 %
        // overshoots in f32).
        if lmax * k <= max {
            return this;
        }
        if lmin * k >= max {
            return Self::new(max, 0.0, max);
        }
        // lmin < c < lmax, so lmax - lmin > 0.
        let d = 0.5 * (s.s11 - s.s22);
        let p = r + d.abs();
        let q = if p > 0.0 { s.s12 * s.s12 / p } else { 0.0 };
        let (e11, e22) = if d >= 0.0 { (p, q) } else { (q, p) };
        // Sigma' = max P_max + lambda_min P_min with the (scale-free) spectral projectors
        // P_max = [[e11, s12], [s12, e22]] / 2r and P_min = [[e22, -s12], [-s12, e11]] / 2r:
        // sums of non-negative terms, no cancellation.
        let inv = 1.0 / (2.0 * r);
        if !inv.is_finite() {
            // lmax - lmin = 2 r below the normal range: isotropic to rounding, with `max`
            // between its eigenvalues.
            return Self::new(max, 0.0, max);
        }
        let (p11, p12, p22) = (e11 * inv, s.s12 * inv, e22 * inv);
        let lm = lmin * k;
        Self::new(max * p11 + lm * p22, (max - lm) * p12, max * p22 + lm * p11)
    }

    /// A finite, symmetric positive semi-definite covariance whose eigenvalues are at most
    /// [`KERNEL_MAX`] (`ALPHA_MAX^2`, a kernel already wider than the widest supported lobe):
    ///
    /// - any NaN entry: [`Covariance::ZERO`] (no information, no filtering);
    /// - any infinite entry: `KERNEL_MAX * I` (the widest kernel, direction unknown);
    /// - negative variances are raised to `0` and `|s12|` lowered to `sqrt(s11 s22)` (the
    ///   nearest PSD matrix with the same diagonal; only rounding produces these from
    ///   [`Footprint::covariance`](super::super::Footprint::covariance));
    /// - then [`Covariance::clamp_eigenvalues`] with `KERNEL_MAX`.
    ///
    /// Every filtering function applies this first, so their results are NaN-free for any
    /// input.
    #[inline]
    pub fn sanitized(self) -> Self {
        let (a, b, c) = (self.s11, self.s12, self.s22);
        // Fast path (every footprint covariance): finite, positive semi-definite and with
        // trace <= KERNEL_MAX, which bounds both eigenvalues: `a, c >= 0`, `b^2 <= a c` and
        // `a + c <= KERNEL_MAX` (which excludes infinities); NaN fails every comparison. The
        // signs are tested explicitly: `a c` can underflow to -0 in `f64` (fuzzing found
        // `a = -1e-231, c = 2e-197, b = 0` passing `b^2 <= a c` otherwise). In `f32` the
        // products are formed in `f64`, where they are exact: `b^2 <= a c` is decided exactly.
        // In `f64`, if `a c` underflows to 0, `b^2 <= a c` may hold by underflow for a nonzero
        // `b`: the slow path decides. Inlined into the filtering kernels; the rest is out of
        // line.
        let psd = if core::mem::size_of::<F>() == 4 {
            let (a, b, c) = (a.to_f64(), b.to_f64(), c.to_f64());
            b * b <= a * c
        } else {
            b * b <= a * c && (a * c > 0.0 || b == 0.0)
        };
        if psd && a >= 0.0 && c >= 0.0 && a + c <= KERNEL_MAX {
            return Self::new(a, b, c);
        }
        Self::sanitized_slow(self.s11, self.s12, self.s22).detached()
    }

    /// The general case of [`Covariance::sanitized`].
    #[cold]
    #[inline(never)]
    fn sanitized_slow(a: F, b: F, c: F) -> Self {
        let e = [a, b, c];
        if e.iter().any(|x| x.is_nan()) {
            return Self::ZERO;
        }
        if e.iter().any(|x| x.is_infinite()) {
            return Self::new(KERNEL_MAX, 0.0, KERNEL_MAX);
        }
        let s11 = a.max(0.0);
        let s22 = c.max(0.0);
        let bound = m::sqrt(s11) * m::sqrt(s22);
        let s12 = b.clamp(-bound, bound);
        Self::new(s11, s12, s22).clamp_eigenvalues(KERNEL_MAX)
    }
}

impl Covariance {
    /// The same covariance as fresh values (`x + 0`, which only turns `-0` into `+0`), for
    /// the result of an out-of-line slow path. An aggregate comes back from a call through
    /// memory; returned as is, the compiler wrote the inlined fast path's value into that
    /// memory too (it saw a plain copy) and read it back with loads straddling the stores: a
    /// store-forwarding stall that made every filtered evaluation three times slower.
    #[inline(always)]
    fn detached(self) -> Self {
        Self::new(self.s11 + 0.0, self.s12 + 0.0, self.s22 + 0.0)
    }
}

/// Bounds `[1 / FAST_EIGEN_MAX, FAST_EIGEN_MAX]` on `max - mean` in
/// [`Covariance::clamp_eigenvalues`]'s second fast path: its square is a finite normal number
/// (`sqrt(F::MAX) / 2`, rounded down to a power of ten; its reciprocal is above
/// `sqrt(F::MIN_POSITIVE)`).
const FAST_EIGEN_MAX: F = (if core::mem::size_of::<F>() == 4 {
    1e18
} else {
    1e153
}) as F;

/// `hypot(d, b)`: a plain square root where `d^2 + b^2` is a normal number at least
/// `1 / eps` times the smallest (an underflowed square then weighs below `eps^2`), the
/// library's `hypot` (a call) otherwise.
#[inline]
fn radius(d: F, b: F) -> F {
    let r2 = d * d + b * b;
    if (F::MIN_POSITIVE / F::EPSILON..=F::MAX).contains(&r2) {
        m::sqrt(r2)
    } else {
        m::hypot(d, b)
    }
}

/// The largest kernel eigenvalue kept by [`Covariance::sanitized`] (slope^2): `ALPHA_MAX^2`.
pub const KERNEL_MAX: F = ALPHA_MAX * ALPHA_MAX;

impl core::ops::Add for Covariance {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.s11 + o.s11, self.s12 + o.s12, self.s22 + o.s22)
    }
}

impl core::ops::Mul<F> for Covariance {
    type Output = Self;
    #[inline]
    fn mul(self, k: F) -> Self {
        Self::new(self.s11 * k, self.s12 * k, self.s22 * k)
    }
}
