//! Beckmann in any roughness form (Beckmann and Spizzichino 1963; Heitz 2014 section 5.4;
//! KHPL16 eq. 14: `A = 2 B` with `B` the slope covariance).

use super::super::PI;
use super::roughness::{AxisAligned, Isotropic, Roughness, RoughnessMatrix};
use super::{F, Vec2, Vec3};
use super::{Ndf, lambda_outside_domain, rescale_direction};
use crate::error::RoughnessError;
use crate::math::{self as m, Real};

/// `exp(-x)` is a normal float for `x` below this (`-ln(F::MIN_POSITIVE)` less one binade).
const EXP_NORMAL_LIMIT: F = -(F::MIN_EXP as F) * core::f64::consts::LN_2 as F;

/// `exp(-e)` rounds to `0` in `F` (below half the smallest subnormal) for `e` above this.
const EXP_ZERO_LIMIT: F =
    (-(F::MIN_EXP as F) + F::MANTISSA_DIGITS as F + 1.0) * core::f64::consts::LN_2 as F;

/// `ln(F::MAX)`, rounded up.
const LN_MAX: F = (F::MAX_EXP as F) * core::f64::consts::LN_2 as F;

/// `exp(-x) k` for `x >= 0` and `k = exp(ln_k)`, without losing the result to an
/// intermediate subnormal `exp(-x)`: past [`EXP_NORMAL_LIMIT`] the factor moves into the
/// exponent, `exp(-(x - ln k))`, with `ln k` taken directly when `k` is a normal number and
/// from `ln_k` (the logarithms of its factors) when it is not. A result below the subnormal
/// range is `0` without calling `exp` (whose underflow path is slow).
#[inline]
fn exp_neg_times(x: F, k: F, ln_k: impl FnOnce() -> F) -> F {
    if x < EXP_NORMAL_LIMIT {
        return m::exp(-x) * k;
    }
    // A normal k has ln k <= ln F::MAX: beyond this the result is 0 without a logarithm.
    if x > EXP_ZERO_LIMIT + LN_MAX && k <= F::MAX {
        return 0.0;
    }
    let l = if (F::MIN_POSITIVE..=F::MAX).contains(&k) {
        m::ln(k)
    } else {
        ln_k()
    };
    let e = x - l;
    if e > EXP_ZERO_LIMIT { 0.0 } else { m::exp(-e) }
}

/// The Beckmann distribution with roughness form `R`: a bivariate Gaussian of slopes with
/// covariance `A / 2`.
///
/// - `P22(s) = exp(-s^T A^-1 s) / (pi sqrt(det A))` (slope domain).
/// - `D(m) = exp(-m_xy^T A^-1 m_xy / m_z^2) / (pi sqrt(det A) m_z^4)` for `m_z > 0`, `0`
///   below the horizon and where the result underflows. Far in the tail (exponent past the
///   normal range of `F`) the normalisation moves into the exponent, so a density that is
///   representable is returned to full relative precision even when `exp(-x)` alone is not.
/// - `Lambda(w) = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2` with
///   `a = |w_z| / sqrt(w_xy^T A w_xy)` (Heitz 2014 eq. 80 with the projected roughness of a
///   matrix lobe). Evaluated in `f64` for both precisions, because the two terms cancel to
///   a relative `1 / (2 a^2)` for large `a`; `exp(-a^2)` uses the exact split of `a^2`, so the
///   result carries a relative error of about `2 a^2 eps_f64` (`< 1e-12` wherever `Lambda`
///   is a normal `f64`), plus `2 a^2` times the relative error of the inputs `q`, `w_z`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beckmann<R: Roughness> {
    /// The roughness.
    pub roughness: R,
}

impl<R: Roughness> Beckmann<R> {
    /// Beckmann with the given roughness.
    #[inline]
    pub const fn new(roughness: R) -> Self {
        Self { roughness }
    }
}

checked_constructors!(Beckmann, "Beckmann");

/// Beckmann Smith `Lambda` from `q = w_xy^T A w_xy` and `|w_z|` (shared with sampling and
/// the temporal module; one source of truth). NaN in either: `+inf` (the NaN policy of
/// [`Ndf`]).
#[inline]
pub(crate) fn beckmann_lambda(q: F, abs_wz: F) -> F {
    if let Some(v) = lambda_outside_domain(q, abs_wz) {
        return v;
    }
    let a = abs_wz.to_f64() / m::sqrt(q.to_f64());
    if a > 26.0 {
        // exp(-a^2) < 1e-293: Lambda is below every representable density scale.
        return 0.0;
    }
    let inv_sqrt_pi = 0.564_189_583_547_756_3_f64;
    // exp(-a^2) with a^2 split exactly into a2 + a2_lo: the rounding of a * a alone would
    // cost a relative a^2 eps, which the cancellation below amplifies by another 2 a^2.
    let a2 = a * a;
    let a2_lo = m::mul_add(a, a, -a2);
    let e = m::exp(-a2) * (1.0 - a2_lo);
    let l = 0.5 * (e * inv_sqrt_pi / a - m::erfc(a));
    F::from_f64(l.max(0.0))
}

impl<R: Roughness> Ndf for Beckmann<R> {
    #[inline]
    fn p22(&self, s: Vec2) -> F {
        let den = PI * self.roughness.sqrt_det();
        let v = exp_neg_times(self.roughness.inv_quadratic(s), 1.0 / den, || -m::ln(den));
        // A NaN slope gives NaN here: 0 (the NaN policy of `Ndf`).
        if v.is_finite() { v } else { 0.0 }
    }

    #[inline(always)]
    fn d(&self, mn: Vec3) -> F {
        if mn.z <= 0.0 {
            return 0.0;
        }
        // x = m_xy^T A^-1 m_xy / m_z^2 and n = 1 / (sqrt(det A) m_z^4) from one division.
        let (x, n) = self
            .roughness
            .exponent_and_norm(Vec2::new(mn.x, mn.y), mn.z * mn.z);
        let v = exp_neg_times(x, n * (1.0 / PI), || {
            -(m::ln(PI * self.roughness.sqrt_det()) + 4.0 * m::ln(mn.z))
        });
        if v.is_finite() { v } else { 0.0 }
    }

    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        let w = rescale_direction(w);
        beckmann_lambda(self.roughness.quadratic(Vec2::new(w.x, w.y)), w.z.abs())
    }
}
