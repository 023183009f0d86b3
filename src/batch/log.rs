//! The natural logarithm in lanes (the Beckmann `D(m) m_z` sampler's `ln(1 - u1)`), on the
//! reduction `x = m 2^k` shared with [`pow_lane`](super::lanes::pow_lane)
//! (`lanes::ln_parts_f64`): plain arithmetic, bit casts and selects, no calls, so the loop
//! over elements vectorises.
//!
//! | function | replaces | bound (relative) | where tested |
//! |---|---|---|---|
//! | [`ln_lane`] | libm `ln` | `4 eps_64` computed in `f64` (in `f32`: plus half an `f32` ulp) | unit test below |

use super::F;
use super::lanes::{LN2_HI, LN2_LO, ln_parts_f64};
use crate::math::Real;

/// `ln x` in lanes, computed in `f64` at either precision: `ln x = k ln2_hi + (k ln2_lo +
/// ln m)`, `(k, ln m)` by `lanes::ln_parts_f64` (`m` in `[sqrt(1/2), sqrt(2))`, `ln m = 2
/// atanh((m - 1) / (m + 1))` by its series, truncation below `2.3e-17` relative).
///
/// Returns `(value, ok)`: `ok` for `x` positive, finite and normal as an `f64` (every
/// positive finite `f32`, subnormals included); elsewhere (`x <= 0`, NaN, infinite) the value
/// is meaningless and the caller's scalar path decides.
///
/// Error where `ok` (relative, against the exact logarithm): `s = (m - 1) / (m + 1)` carries
/// one rounding of the sum and one of the quotient (`m - 1` is exact, Sterbenz), so `ln m ~
/// 2 s` is within `(1 + 1/2) eps_64` of its value plus the series' rounding (terms below
/// `s^2 / 3 < 0.01` of it: `eps_64 / 2`); `k ln2_hi` is exact (`|k| <= 1075`, `LN2_HI` has 21
/// trailing zero bits), `k ln2_lo` and the two sums round once each. For `k = 0` the result
/// is `ln m`: `2 eps_64`; for `k != 0`, `|ln x| >= ln(2) / 2 >= |ln m|`, so the absolute
/// errors, at most `2 eps_64 |ln m| + eps_64 |k ln 2| / 2 + eps_64 |ln x|`, stay below `4 eps_64
/// |ln x|`. In `f32` the result is rounded to `f32` once more (half an `f32` ulp).
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
pub(crate) fn ln_lane(x: F) -> (F, bool) {
    let xf = x.to_f64();
    let (k, ln_m) = ln_parts_f64(xf);
    let v = k * LN2_HI + (k * LN2_LO + ln_m);
    (F::from_f64(v), (xf >= f64::MIN_POSITIVE) & (xf <= f64::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

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
        // The smallest subnormal: a normal `f64` in the `f32` build (`ok`), flagged in `f64`.
        let tiny = F::MIN_POSITIVE * F::EPSILON;
        assert_eq!(ln_lane(tiny).1, tiny.to_f64() >= f64::MIN_POSITIVE);
        let f = f64::EPSILON;
        let mut worst = 0.0f64;
        for x in xs {
            if x.is_nan() || x <= 0.0 {
                continue;
            }
            let want = x.to_f64().ln();
            let (got, ok) = ln_lane(x);
            assert!(ok, "x {x}");
            let half_ulp = if F::MANTISSA_DIGITS > 24 {
                0.0
            } else {
                f32::EPSILON as f64 / 2.0
            };
            let err = (got.to_f64() - want).abs();
            let tol = (4.0 * f + f + half_ulp) * want.abs();
            assert!(err <= tol, "x {x}: {got} vs {want}");
            if want != 0.0 {
                worst = worst.max(err / want.abs() - half_ulp);
            }
        }
        println!("ln_lane worst relative error {worst:e} (eps_64 {f:e})");
        assert_eq!(ln_lane(1.0), (0.0, true));
        for bad in [0.0, -0.0, -1.0, F::NAN, F::INFINITY, F::NEG_INFINITY] {
            assert!(!ln_lane(bad).1, "{bad}");
        }
    }
}
