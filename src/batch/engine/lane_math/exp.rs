//! `e^-x k` in lanes (Beckmann's `D`).

use super::super::super::super::F;
use super::super::super::super::filter::{MAGIC_F32, MAGIC_F64, exp_f32_reduced, exp_f64_reduced};
use super::WIDE;
use crate::math::Real;

/// `e^-x k` for `x >= 0` (also `+inf`) and `0 <= k <= 2^126` (`2^1022` in `f64`), without
/// losing the result to an intermediate subnormal `e^-x`: `e^-x = p 2^-n` by the reduction of
/// the shared polynomial exponential (`filter::exp_poly`), and `u = p k` scaled by `2^-n`
/// with one integer subtraction from its exponent field. Returns `(value, ok)`, `ok` when `k`
/// is in the range and `x` is not NaN (else the caller's scalar path decides).
///
/// Error: relative that of `exp_poly` (`2.5e-7` in `f32`, `1.5e-14` in `f64`) plus one
/// rounding (`p k`) for results of at least `F::MIN_POSITIVE`; a result below it is `0`
/// (flushed: absolute error below `F::MIN_POSITIVE`, a density of `1e-38` per steradian in
/// `f32`), so no arithmetic produces a subnormal (each costs a microcode assist). The
/// `Beckmann` `exp_neg_times` in lanes.
#[inline(always)]
pub(crate) fn exp_neg_times(x: F, k: F) -> (F, bool) {
    if WIDE {
        let (v, ok) = exp_neg_times_f64(x.to_f64(), k.to_f64());
        (F::from_f64(v), ok)
    } else {
        let (v, ok) = exp_neg_times_f32(x.to_f64() as f32, k.to_f64() as f32);
        (F::from_f64(v as f64), ok)
    }
}

/// The largest `k` of [`exp_neg_times`]: `2^126` in `f32`, `2^1022` in `f64` (`p k` stays
/// finite for `p < 2`).
pub(crate) const K_MAX: F = if WIDE {
    f64::from_bits((1023 + 1022) << 52) as F
} else {
    f32::from_bits((127 + 126) << 23) as F
};

#[inline(always)]
#[allow(clippy::unnecessary_cast)] // `K_MAX` is `F`: `f64` in the `f64` build.
fn exp_neg_times_f32(x: f32, k: f32) -> (f32, bool) {
    // e^-194 2^126 is below F::MIN_POSITIVE: clamping there changes no result.
    let (p, kk) = exp_f32_reduced(-x.min(194.0));
    // n <= 0: e^-x = p 2^n.
    let n = (kk.to_bits() as i32).wrapping_sub(MAGIC_F32.to_bits() as i32);
    let ub = (p * k).to_bits();
    // The biased exponent of the result: a normal number for t >= 1.
    let t = (ub >> 23) as i32 + n;
    let v = f32::from_bits(ub.wrapping_add((n << 23) as u32));
    (
        if t >= 1 { v } else { 0.0 },
        (k <= K_MAX as f32) & (x >= 0.0),
    )
}

#[inline(always)]
#[allow(clippy::unnecessary_cast)] // `K_MAX` is `F`: `f32` in the `f32` build.
fn exp_neg_times_f64(x: f64, k: f64) -> (f64, bool) {
    // e^-1456 2^1022 is below F::MIN_POSITIVE.
    let (p, kk) = exp_f64_reduced(-x.min(1456.0));
    let n = (kk.to_bits() as i64).wrapping_sub(MAGIC_F64.to_bits() as i64);
    let ub = (p * k).to_bits();
    let t = (ub >> 52) as i64 + n;
    let v = f64::from_bits(ub.wrapping_add((n << 52) as u64));
    (
        if t >= 1 { v } else { 0.0 },
        (k <= K_MAX as f64) & (x >= 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_neg_times_against_libm() {
        // Against the exact value (formed in log space in f64, no underflow), over x in
        // [0, 200] (f32) / [0, 1500] (f64) and k over [F::MIN_POSITIVE, K_MAX]: the relative
        // bound for results of at least F::MIN_POSITIVE, an absolute F::MIN_POSITIVE below.
        let (xmax, bound) = if WIDE {
            (1500.0, 1.6e-14)
        } else {
            (200.0, 2.7e-7)
        };
        let (lo, hi) = (F::MIN_POSITIVE.to_f64().ln(), K_MAX.to_f64().ln());
        let mut worst = 0.0f64;
        for i in 0..20_000 {
            let x = F::from_f64(xmax * (i as f64 / 20_000.0));
            for j in 0..=40 {
                let k = F::from_f64((lo + (hi - lo) * (j as f64 / 40.0)).exp()).min(K_MAX);
                let (v, ok) = exp_neg_times(x, k);
                assert!(ok, "x {x} k {k}");
                let a = -x.to_f64() + k.to_f64().ln();
                let exact = a.exp();
                // The reference's own error: the rounding of `a`, amplified by `|a|`.
                let ref_err = (a.abs() + 2.0) * f64::EPSILON;
                let err = (v.to_f64() - exact).abs();
                if exact >= F::MIN_POSITIVE.to_f64() * (1.0 + 2.0 * bound) {
                    assert!(
                        err <= (bound + ref_err) * exact,
                        "x {x} k {k}: {v} vs {exact}"
                    );
                    worst = worst.max(err / exact - ref_err);
                } else {
                    assert!(
                        err < F::MIN_POSITIVE.to_f64(),
                        "x {x} k {k}: {v} vs {exact}"
                    );
                }
            }
        }
        println!("exp_neg_times worst relative error {worst:e}");
        // Out of domain: flagged.
        assert!(!exp_neg_times(F::NAN, 1.0).1);
        assert!(!exp_neg_times(1.0, F::INFINITY).1);
        assert!(!exp_neg_times(1.0, K_MAX * 2.0).1);
        assert_eq!(exp_neg_times(F::INFINITY, 1.0), (0.0, true));
        assert_eq!(exp_neg_times(1.0, 0.0), (0.0, true));
    }
}
