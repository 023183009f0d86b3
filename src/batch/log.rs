//! The natural logarithm in lanes (the Beckmann `D(m) m_z` sampler's `ln(1 - u1)`), on the
//! reduction `x = m 2^k`, in `f64` the one shared with [`pow_lane`](super::lane_math::pow_lane)
//! (`lane_math::ln_parts_f64`), in `f32` its `f32` form: plain arithmetic, bit casts and
//! selects, no calls, so the loop over elements vectorises.
//!
//! | function | replaces | bound (relative) | where tested |
//! |---|---|---|---|
//! | [`ln_lane`] | libm `ln` | `4 eps_64` in `f64`, `3 eps_32` in `f32` (each computed in its precision) | unit test below |

use super::super::filter::{LN2_HI_F32, LN2_LO_F32};
use super::F;
use super::lane_math::{LN2_HI, LN2_LO, WIDE, ln_parts_f32, ln_parts_f64};
use crate::math::Real;

/// `ln x` in lanes: `ln x = k ln2_hi + (k ln2_lo + ln m)`, `x = m 2^k` with `m` in
/// `[sqrt(1/2), sqrt(2))` and `ln m = 2 atanh(s)`, `s = (m - 1) / (m + 1)` (`|s| <= 0.1716`),
/// by its series. In `f64` by `lane_math::ln_parts_f64` (series to `s^21`, truncation below
/// `2.3e-17` relative); in `f32` in `f32` arithmetic ([`ln_f32`]: the `f64` form held the
/// `f32` sampler's loop to 4 lanes on AVX2).
///
/// Returns `(value, ok)`: `ok` for `x` positive, finite and normal in `F`; elsewhere (`x <=
/// 0`, NaN, infinite, subnormal) the value is meaningless and the caller's scalar path decides.
///
/// Error where `ok` (relative, against the exact logarithm), in units of `eps` of `F`: `s`
/// carries one rounding of the sum and one of the quotient (`m - 1` is exact, Sterbenz), so
/// `ln m ~ 2 s` is within `(1 + 1/2) eps` of its value with the series' rounding (its terms
/// below `s^2 / 3 < 0.01` of it); `k ln2_hi` is exact (`ln2_hi` has enough trailing zero bits
/// for every `k` of `F`), `k ln2_lo` and the two sums round once each. For `k = 0` the result
/// is `ln m`: `1.5 eps`; for `k != 0`, `|ln x| >= ln(2) / 2 >= |ln m|`, so the absolute errors,
/// at most `1.5 eps |ln m| + eps |ln x|` (the sums; `k ln2_lo` and the truncation of `ln2_lo`
/// below `1e-10` relative), stay below `2.5 eps |ln x|`: stated as `3 eps` in `f32` (series
/// truncation `s^10 / 11 < 2.1e-9` relative, `0.02 eps`) and `4 eps` in `f64`, tested below.
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
pub(crate) fn ln_lane(x: F) -> (F, bool) {
    let ok = (x >= F::MIN_POSITIVE) & (x <= F::MAX);
    if WIDE {
        let xf = x.to_f64();
        let (k, ln_m) = ln_parts_f64(xf);
        (F::from_f64(k * LN2_HI + (k * LN2_LO + ln_m)), ok)
    } else {
        (F::from_f64(ln_f32(x.to_f64() as f32) as f64), ok)
    }
}

/// [`ln_lane`] in `f32` arithmetic, for a positive normal `x` (its docs).
#[inline(always)]
fn ln_f32(x: f32) -> f32 {
    let (k, ln_m) = ln_parts_f32(x);
    k * LN2_HI_F32 + (k * LN2_LO_F32 + ln_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stated bound of [`ln_lane`], in units of `eps` of `F`.
    const ULPS: f64 = if WIDE { 4.0 } else { 3.0 };

    #[test]
    fn ln_lane_against_libm() {
        // Against `f64::ln` (libm: within one ulp of the exact logarithm, so the reference
        // adds `eps_64` relative) over x log-uniform in [MIN_POSITIVE, MAX] of `F` and densely
        // around 1 (where `ln x` is small and the relative bound is the strictest), the
        // sampler's arguments `1 - u1` in (0, 1], and the reduction's boundaries
        // (`sqrt(1/2)`, `sqrt(2)`, powers of two).
        let mut xs: Vec<F> = Vec::new();
        let (lo, hi) = (F::MIN_POSITIVE.to_f64().ln(), F::MAX.to_f64().ln());
        for i in 0..=100_000 {
            let t = i as f64 / 100_000.0;
            xs.push(F::from_f64((lo + (hi - lo) * t).exp()));
            xs.push(F::from_f64(1.0 + (t - 0.5) * 1e-3));
            xs.push(F::from_f64(1.0 - t));
        }
        for b in [
            core::f64::consts::FRAC_1_SQRT_2,
            core::f64::consts::SQRT_2,
            0.5,
            1.0,
            2.0,
            4.0,
        ] {
            let b = F::from_f64(b);
            xs.extend([b, b * (1.0 + F::EPSILON), b * (1.0 - F::EPSILON / 2.0)]);
        }
        xs.extend([F::EPSILON / 2.0, F::MIN_POSITIVE, F::MAX]);
        // The smallest subnormal: flagged (the scalar path decides).
        let tiny = F::MIN_POSITIVE * F::EPSILON;
        assert!(tiny > 0.0 && !ln_lane(tiny).1);
        let f = f64::EPSILON;
        let mut worst = 0.0f64;
        for x in xs {
            if x.is_nan() || x <= 0.0 {
                continue;
            }
            let want = x.to_f64().ln();
            let (got, ok) = ln_lane(x);
            assert!(ok, "x {x}");
            // The stated bound (`4 eps` in `f64`, `3 eps` in `f32`) plus the reference's own
            // error (libm: within an `f64` ulp).
            let err = (got.to_f64() - want).abs();
            let tol = (ULPS * F::EPSILON.to_f64() + f) * want.abs();
            assert!(err <= tol, "x {x}: {got} vs {want}");
            if want != 0.0 {
                worst = worst.max(err / want.abs() / F::EPSILON.to_f64());
            }
        }
        println!("ln_lane worst relative error {worst:.3} eps (stated {ULPS})");
        assert_eq!(ln_lane(1.0), (0.0, true));
        for bad in [0.0, -0.0, -1.0, F::NAN, F::INFINITY, F::NEG_INFINITY] {
            assert!(!ln_lane(bad).1, "{bad}");
        }
    }
}
