//! `x^e` in lanes (the deferred presets' norm exponent).

use super::super::super::super::F;
use super::super::super::super::filter::{
    LN2_HI_F32, LN2_LO_F32, MAGIC_F32, MAGIC_F64, exp_f32_poly, exp_f64_reduced,
};
use super::WIDE;
use super::log::{LN2_HI, LN2_LO, ln_parts_f32, ln_parts_f64};
use crate::math::Real;

/// The exponent `e` of [`pow_lane`] with `c = e ln 2` split for its `f32` arithmetic: `hi`,
/// `c` rounded to `f32` with its 12 low mantissa bits cleared (12 significant bits, so that
/// `k hi` is exact for every exponent `k` of a normal `f32`, `|k| <= 128`), and `lo = c -
/// hi` rounded to `f32` (`|lo| < 2^-11 |c|`). Built once per batch call (in `f64`), so the
/// lane itself holds no `f64` value.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Power {
    e: F,
    hi: F,
    lo: F,
}

impl Power {
    /// The split of `e`. Any `e`: for a NaN, infinite or huge one, `y` leaves the range of
    /// normal results and [`pow_lane`] flags the element (the caller's scalar path decides),
    /// but for `x = 0` and `e > 0` (value `0`).
    pub(crate) fn new(e: F) -> Self {
        let c = e.to_f64() * core::f64::consts::LN_2;
        let hi = f32::from_bits((c as f32).to_bits() & 0xffff_f000);
        let lo = (c - hi as f64) as f32;
        Self {
            e,
            hi: F::from_f64(hi as f64),
            lo: F::from_f64(lo as f64),
        }
    }
}

/// `x^e` in lanes for the deferred presets' norm exponent ([`KernelConvention`]'s
/// `exponent`), each precision in its own arithmetic, on the reduction `x = m 2^k`, `m` in
/// `[sqrt(1/2), sqrt(2))`, `ln m = 2 atanh(s)`, `s = (m - 1) / (m + 1)` (`|s| <= 0.1716`) by
/// its series:
///
/// - `f64`: the series to `s^21` (truncation below `2.3e-17` relative), `y = e (k ln2_hi +
///   (k ln2_lo + ln m))` (`k ln2_hi` exact) and `e^y` by `filter::exp_poly`'s `f64`
///   reduction. Error (relative, against the exact power): the exponential's `1.5e-14` plus
///   `|y|` times the relative error of `y` (`s` rounded twice, the sums, the product by `e`:
///   at most `3 eps_64`), plus `eps_64`: `1.6e-14 + 3 eps_64 |y|`.
/// - `f32` ([`pow_f32`]): `ln_parts_f32` (series to `s^8`), and `y = e ln x` never rounded
///   as a whole: `y = y_hi + y_lo`, `y_hi = k hi` (exact), `y_lo = k lo + e ln m`
///   ([`Power`]), then `e^y = 2^n e^r`, `n = round(y / ln 2)`, `r = ((y_hi - n ln2_hi) - n
///   ln2_lo) + y_lo` (`n ln2_hi` exact: `filter::LN2_HI_F32`), `e^r` by `exp_f32_poly`. Every
///   rounding then falls on a value of magnitude below `1 + |e|`, not on `y`, so the error
///   does not grow with `|ln x|`. Error (relative, `u = 2^-24`): the polynomial's `3.5 u`;
///   `r`'s roundings (the difference `|D| <= |r| + |y_lo|`, the subtraction of `n ln2_lo`,
///   the sum with `y_lo`), `u (2 (0.347 + |y_lo|) + 0.347)`; `y_lo`'s own: `ln m` within `3 u`
///   relative (`|ln m| <= 0.347`), the product by `e`, `k lo` and the sum, `u (1.04 + 0.35 +
///   0.04 + 0.39) |e|`, with `|y_lo| <= (0.347 + 0.044) |e|` (`|k lo| <= 128 2^-11 ln(2)
///   |e|`); the split's and `ln 2`'s representation below `0.05 u |e|`; `2^n` exact. In all
///   `(4.54 + 2.65 |e|) u`, stated as `(5 + 3 |e|) u`.
///
/// Returns `(value, ok)`: `ok` for `x` a normal positive finite `F` whose `|y|` stays within
/// the range of normal results (`-87 <= y <= 88` in `f32`, `|y| <= 708` in `f64`), or `x = 0`
/// with `e > 0` (value `0`); elsewhere (NaN, infinite, subnormal or negative `x`, overflow,
/// underflow) the value is meaningless and the caller's scalar path decides. Tested below.
///
/// [`KernelConvention`]: super::super::filter::deferred::KernelConvention
#[inline(always)]
pub(crate) fn pow_lane(x: F, p: &Power) -> (F, bool) {
    if WIDE {
        let (v, ok) = pow_f64(x.to_f64(), p.e.to_f64());
        (F::from_f64(v), ok)
    } else {
        let (v, ok) = pow_f32(
            x.to_f64() as f32,
            p.e.to_f64() as f32,
            p.hi.to_f64() as f32,
            p.lo.to_f64() as f32,
        );
        (F::from_f64(v as f64), ok)
    }
}

/// The stated relative bound of [`pow_lane`] in `f32`, in units of `u = 2^-24`, for the
/// exponent `e`: `5 + 3 |e|` (derived in its docs).
#[cfg(test)]
pub(crate) fn pow_f32_ulps(e: f64) -> f64 {
    5.0 + 3.0 * e.abs()
}

#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
fn pow_f64(x: f64, e: f64) -> (f64, bool) {
    let (k, ln_m) = ln_parts_f64(x);
    let y = e * (k * LN2_HI + (k * LN2_LO + ln_m));
    let (q, kk) = exp_f64_reduced(y.clamp(-708.0, 708.0));
    let n = (kk.to_bits() as i64).wrapping_sub(MAGIC_F64.to_bits() as i64);
    // 2^n for |n| <= 1022 (|y| <= 708).
    let two_n = f64::from_bits(((n + 1023) as u64) << 52);
    let zero = x == 0.0;
    let ok = ((x >= f64::MIN_POSITIVE) & (x <= f64::MAX) & (y.abs() <= 708.0)) | (zero & (e > 0.0));
    (if zero { 0.0 } else { q * two_n }, ok)
}

/// [`pow_lane`] in `f32` arithmetic, from the split exponent `(e, hi, lo)` of [`Power`].
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
fn pow_f32(x: f32, e: f32, hi: f32, lo: f32) -> (f32, bool) {
    let (k, ln_m) = ln_parts_f32(x);
    let y_hi = k * hi;
    let y_lo = k * lo + e * ln_m;
    let y = y_hi + y_lo;
    let kk = y.clamp(-87.0, 88.0) * core::f32::consts::LOG2_E + MAGIC_F32;
    let n = kk - MAGIC_F32;
    let r = ((y_hi - n * LN2_HI_F32) - n * LN2_LO_F32) + y_lo;
    // The low bits of kk hold n + 0x400000: (n + 127) << 23 is the bit pattern of 2^n.
    let two_n = f32::from_bits(kk.to_bits().wrapping_add(127) << 23);
    let zero = x == 0.0;
    let ok = ((x >= f32::MIN_POSITIVE) & (x <= f32::MAX) & (y >= -87.0) & (y <= 88.0))
        | (zero & (e > 0.0));
    (if zero { 0.0 } else { exp_f32_poly(r) * two_n }, ok)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pow_lane_against_libm() {
        // Against `f64::powf` (libm: within one ulp of the exact power) for x over
        // [1e-30, 1e30], densely around 1 and at the reduction's boundaries, and the
        // presets' exponents and others: the bound of `pow_lane` plus the reference's ulp.
        let mut xs: Vec<F> = (0..=20_000)
            .map(|i| F::from_f64(10f64.powf(-30.0 + 60.0 * (i as f64 / 20_000.0))))
            .collect();
        xs.extend((0..=2_000).map(|i| F::from_f64(1.0 + (i as f64 / 1000.0 - 1.0) * 1e-3)));
        for b in [
            core::f64::consts::FRAC_1_SQRT_2,
            core::f64::consts::SQRT_2,
            0.5,
            2.0,
        ] {
            let b = F::from_f64(b);
            xs.extend([b, b * (1.0 + F::EPSILON), b * (1.0 - F::EPSILON / 2.0)]);
        }
        xs.extend([F::MIN_POSITIVE, F::MAX]);
        let u = F::EPSILON.to_f64() / 2.0;
        let mut worst = 0.0f64;
        for e in [0.333, 0.5, 1.0 / 3.0, 2.0, 0.1, 1.7, 3.0, -0.5, -2.0] {
            let p = Power::new(F::from_f64(e));
            for &x in &xs {
                let (xf, ef) = (x.to_f64(), F::from_f64(e).to_f64());
                let exact = xf.powf(ef);
                let (v, ok) = pow_lane(x, &p);
                let y = ef * xf.ln();
                let in_range = if WIDE {
                    y.abs() <= 700.0
                } else {
                    (-86.9..=87.9).contains(&y)
                };
                if !in_range || exact > F::MAX.to_f64() || exact < F::MIN_POSITIVE.to_f64() {
                    continue;
                }
                assert!(ok, "x {x} e {e}");
                let f = f64::EPSILON;
                let bound = if WIDE {
                    1.6e-14 + 3.0 * f * y.abs() + f
                } else {
                    pow_f32_ulps(ef) * u + f
                };
                let err = (v.to_f64() - exact).abs() / exact;
                assert!(err <= bound, "x {x} e {e}: {v} vs {exact}");
                worst = worst.max(if WIDE {
                    err
                } else {
                    err / u / pow_f32_ulps(ef)
                });
            }
        }
        if WIDE {
            println!("pow_lane worst relative error {worst:e}");
        } else {
            println!("pow_lane worst {worst:.3} of the stated (5 + 3 |e|) u");
        }
        let p = Power::new(0.333);
        assert_eq!(pow_lane(0.0, &p), (0.0, true));
        assert!(!pow_lane(0.0, &Power::new(-1.0)).1);
        for bad in [F::NAN, F::INFINITY, -1.0, F::MIN_POSITIVE / 4.0] {
            assert!(!pow_lane(bad, &p).1, "{bad}");
        }
        // Results past the normal range are flagged.
        assert!(!pow_lane(1e-30, &Power::new(if WIDE { 30.0 } else { 3.0 })).1);
        assert!(!pow_lane(1e30, &Power::new(if WIDE { 30.0 } else { 3.0 })).1);
    }
}
