//! The natural logarithm in lanes (the Beckmann `D(m) m_z` sampler's `ln(1 - u1)`), and the
//! reduction `x = m 2^k` it shares with [`pow_lane`](super::pow_lane): plain arithmetic, bit
//! casts and selects, no calls, so the loop over elements vectorises.

use super::super::super::super::F;
use super::super::super::super::filter::{LN2_HI_F32, LN2_LO_F32};
use super::WIDE;
use crate::math::Real;

/// `ln 2` split: the high part has trailing zeros, so `k LN2_HI` is exact for `|k| < 2^11`.
pub(crate) const LN2_HI: f64 = 0.693_147_180_369_123_8; // 0x3fe62e42fee00000.
/// `ln 2 - LN2_HI`.
pub(crate) const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;

/// The logarithm's reduction shared by [`pow_lane`](super::pow_lane) and [`ln_lane`]: `x = m 2^k` with `m` in
/// `[sqrt(1/2), sqrt(2))`, returns `(k, ln m)`, `ln m = 2 atanh(s)`, `s = (m - 1) / (m + 1)`
/// (`|s| <= 0.1716`) by its series to `s^21` (truncation below `2.3e-17` relative). For a
/// normal positive finite `x` (elsewhere garbage: the callers flag it).
#[inline(always)]
pub(crate) fn ln_parts_f64(x: f64) -> (f64, f64) {
    // 1 / (2 j + 1), j = 1..10.
    const C: [f64; 10] = [
        1.0 / 3.0,
        1.0 / 5.0,
        1.0 / 7.0,
        1.0 / 9.0,
        1.0 / 11.0,
        1.0 / 13.0,
        1.0 / 15.0,
        1.0 / 17.0,
        1.0 / 19.0,
        1.0 / 21.0,
    ];
    let b = x.to_bits();
    // The biased exponent field as an `f64` (`2^52 + field`, minus `2^52`: exact), without
    // an integer-to-float conversion (none for 64-bit integers before AVX-512).
    let field =
        f64::from_bits(0x4330_0000_0000_0000 | ((b >> 52) & 0x7ff)) - 4_503_599_627_370_496.0;
    let m1 = f64::from_bits((b & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    // The mantissa in `[1, 2)`, halved above `sqrt 2` (its exponent then one more).
    let halved = m1 > core::f64::consts::SQRT_2;
    let m = if halved { 0.5 * m1 } else { m1 };
    let k = field - 1023.0 + if halved { 1.0 } else { 0.0 };
    // m - 1 is exact (Sterbenz).
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let mut p = C[9];
    for c in C[..9].iter().rev() {
        p = p * s2 + c;
    }
    let ln_m = 2.0 * s + (2.0 * s) * (s2 * p);
    (k, ln_m)
}

/// [`ln_parts_f64`] in `f32` arithmetic ([`ln_lane`] and [`pow_lane`](super::pow_lane) in `f32`): `(k, ln
/// m)`, the series of `atanh(s) / s` through `s^8` (truncation `s^10 / 11 < 2.1e-9`
/// relative); `ln m` within `1.5 eps_32` of its value (`s` rounded twice, the series' terms
/// below `s^2 / 3 < 0.01` of it; `log.rs`). For a normal positive finite `x` (elsewhere
/// garbage: the callers flag it).
#[inline(always)]
pub(crate) fn ln_parts_f32(x: f32) -> (f32, f32) {
    // 1 / (2 j + 1), j = 1..4.
    const C: [f32; 4] = [1.0 / 3.0, 1.0 / 5.0, 1.0 / 7.0, 1.0 / 9.0];
    let b = x.to_bits();
    let field = ((b >> 23) & 0xff) as i32;
    let m1 = f32::from_bits((b & 0x007f_ffff) | 0x3f80_0000);
    let halved = m1 > core::f32::consts::SQRT_2;
    let m = if halved { 0.5 * m1 } else { m1 };
    let k = (field - 127 + i32::from(halved)) as f32;
    // m - 1 is exact (Sterbenz).
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let p = ((C[3] * s2 + C[2]) * s2 + C[1]) * s2 + C[0];
    (k, 2.0 * s + (2.0 * s) * (s2 * p))
}

/// `ln x` in lanes: `ln x = k ln2_hi + (k ln2_lo + ln m)`, `x = m 2^k` with `m` in
/// `[sqrt(1/2), sqrt(2))` and `ln m = 2 atanh(s)`, `s = (m - 1) / (m + 1)` (`|s| <= 0.1716`),
/// by its series. In `f64` by [`ln_parts_f64`] (series to `s^21`, truncation below
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
