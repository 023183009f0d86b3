//! The polynomial exponential that the exact Gaussian filter's quadrature rules
//! (`gaussian_ggx_quad`) and the batch lanes (`batch::lane_math`) share: `e^x` as `2^n e^r` with
//! a relative minimax polynomial for `e^r`, in plain arithmetic and bit casts, so that LLVM
//! vectorises every loop it is in; the reduction alone for callers that scale by `2^n`
//! themselves.

use super::F;
use crate::math::Real;

/// `f64` build: the `f64` polynomial for [`exp_poly`].
const WIDE: bool = F::MANTISSA_DIGITS > 24;

/// `e^x` in `f32` for `x <= 88` (`0` below `-87`): `2^n e^r`, `n = round(x / ln 2)` by the
/// magic-number rounding, `|r| <= ln(2) / 2`, `e^r` by the relative minimax polynomial of
/// degree 6 (error `1.9e-9`, Remez exchange in 50-digit arithmetic) evaluated by Estrin's
/// scheme (depth 5, against 12 for Horner: the node loops are latency-bound); with the
/// rounding of the reduction and of the evaluation, the relative error is below `2.5e-7`
/// (measured over every 64th `f32` in `[-87, 88]`, unit test below). Plain arithmetic and bit
/// casts: LLVM vectorises it.
#[inline(always)]
fn exp_f32(x: f32) -> f32 {
    let (p, k) = exp_f32_reduced(x.clamp(-87.0, 88.0));
    // The low bits of k hold n + 0x400000: (n + 127) << 23 is the bit pattern of 2^n.
    let s = f32::from_bits(k.to_bits().wrapping_add(127) << 23);
    // 0 below the range, by a bit mask (a branch or select here stops the vectoriser).
    let keep = 0u32.wrapping_sub((x >= -87.0) as u32);
    p * s * f32::from_bits(1f32.to_bits() & keep)
}

/// `1.5 * 2^23`: adding it to a float of magnitude below `2^22` rounds it to an integer, held
/// in the low bits of the sum ([`exp_f32_reduced`]).
pub(crate) const MAGIC_F32: f32 = 12_582_912.0;

/// `ln 2` split for the `f32` reductions: `LN2_HI_F32` (`0x3f317200`) has 9 trailing zero
/// bits, so `n LN2_HI_F32` is exact for `|n| < 512`; `LN2_LO_F32` is `ln 2 - LN2_HI_F32`
/// rounded (its own error below `1e-13`). Shared by [`exp_f32_reduced`] and the lanes'
/// logarithm and power (`batch::lane_math`).
pub(crate) const LN2_HI_F32: f32 = 0.693_145_75;
/// See [`LN2_HI_F32`].
pub(crate) const LN2_LO_F32: f32 = 1.428_606_8e-6;

/// The range reduction and polynomial of [`exp_f32`], without its clamp: `(p, k)` with
/// `e^x = p 2^n`, `n = round(x / ln 2)` held in `k = x log2(e) + MAGIC_F32` (its bits are
/// `MAGIC_F32`'s plus `n`) and `p = e^r` by the polynomial, `r = x - n ln 2`. For
/// `|x| <= 350` (`n ln2_hi` is exact for `|n| < 512`); the caller scales by `2^n` (also
/// `batch`'s `exp(-x) k`, whose exponent leaves the normal range).
#[inline(always)]
pub(crate) fn exp_f32_reduced(xc: f32) -> (f32, f32) {
    let k = xc * core::f32::consts::LOG2_E + MAGIC_F32;
    let n = k - MAGIC_F32;
    let r = (xc - n * LN2_HI_F32) - n * LN2_LO_F32;
    (exp_f32_poly(r), k)
}

/// The polynomial of [`exp_f32`]: `e^r` for `|r| <= ln(2) / 2` (a little beyond it too: the
/// callers' rounding of `n`), the relative minimax polynomial of degree 6 (error `1.9e-9`)
/// by Estrin's scheme. With its rounding, for an exact `r`, within `3.5 u` of `e^r` (`u = 2^-24`;
/// measured `2.9 u` over every 16th `f32` of the interval, unit test below).
#[inline(always)]
pub(crate) fn exp_f32_poly(r: f32) -> f32 {
    const C: [f32; 7] = [
        1.0,
        1.0,
        0.499_999_9,
        0.166_664_2,
        0.041_668_225,
        0.008_374_816,
        0.001_383_684_6,
    ];
    let r2 = r * r;
    (C[0] + C[1] * r + (C[2] + C[3] * r) * r2) + (C[4] + C[5] * r + C[6] * r2) * (r2 * r2)
}

/// `e^x` in `f64` for `x <= 709` (`0` below `-708`), as [`exp_f32`] with the relative minimax
/// polynomial of degree 9 (error `1.35e-14`; Estrin, depth 7); relative error below `1.5e-14`
/// (unit test below), far inside the `f64` rules' budget.
#[inline(always)]
pub(crate) const fn exp_f64(x: f64) -> f64 {
    let (p, k) = exp_f64_reduced(x.clamp(-708.0, 709.0));
    let s = f64::from_bits(k.to_bits().wrapping_add(1023) << 52);
    let keep = 0u64.wrapping_sub((x >= -708.0) as u64);
    p * s * f64::from_bits(1f64.to_bits() & keep)
}

/// `1.5 * 2^52` ([`exp_f64_reduced`]).
pub(crate) const MAGIC_F64: f64 = 6_755_399_441_055_744.0;

/// [`exp_f32_reduced`] for [`exp_f64`]: `e^x = p 2^n`, `n` held in `k`, for `|x| <= 1e6`
/// (`n ln2_hi` is exact for `|n| < 2^21`).
#[inline(always)]
pub(crate) const fn exp_f64_reduced(xc: f64) -> (f64, f64) {
    const MAGIC: f64 = MAGIC_F64;
    const LN2_HI: f64 = 0.693_147_180_369_123_8; // 0x3fe62e42fee00000.
    const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
    const C: [f64; 10] = [
        1.000_000_000_000_012_7,
        0.999_999_999_999_892_8,
        0.499_999_999_994_579_7,
        0.166_666_666_678_269_54,
        0.041_666_667_032_463_356,
        0.008_333_333_002_822_645,
        0.001_388_880_282_882_159_4,
        0.000_198_415_963_970_344_1,
        2.488_401_001_538_876_4e-5,
        2.748_218_700_193_312e-6,
    ];
    let k = xc * core::f64::consts::LOG2_E + MAGIC;
    let n = k - MAGIC;
    let r = (xc - n * LN2_HI) - n * LN2_LO;
    let r2 = r * r;
    let r4 = r2 * r2;
    let q03 = (C[0] + C[1] * r) + (C[2] + C[3] * r) * r2;
    let q47 = (C[4] + C[5] * r) + (C[6] + C[7] * r) * r2;
    let p = (q03 + q47 * r4) + (C[8] + C[9] * r) * (r4 * r4);
    (p, k)
}

/// `e^x` in the lobe's precision (the polynomial of [`exp_f32`] or [`exp_f64`]).
#[inline(always)]
pub(crate) fn exp_poly(x: F) -> F {
    if WIDE {
        F::from_f64(exp_f64(x.to_f64()))
    } else {
        F::from_f64(exp_f32(x.to_f64() as f32) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`exp_f32_poly`] alone, for exact `r` over every 16th `f32` in `[-0.36, 0.36]`
    /// (`ln(2) / 2 = 0.3466` and the callers' overshoot), against `f64::exp` (within an
    /// `f64` ulp): its stated `3.5 u`.
    #[test]
    fn exp_f32_polynomial_rounding() {
        let u = (f32::EPSILON / 2.0) as f64;
        let mut worst = 0.0f64;
        for sign in [1.0f32, -1.0] {
            let mut bits = 0u32;
            while f32::from_bits(bits) <= 0.36 {
                let r = sign * f32::from_bits(bits);
                let want = (r as f64).exp();
                worst = worst.max((exp_f32_poly(r) as f64 - want).abs() / want / u);
                bits += 16;
            }
        }
        println!("exp_f32_poly worst {worst:.3} u");
        assert!(worst < 3.5, "{worst} u");
    }

    #[test]
    fn polynomial_exp_accuracy() {
        let mut worst = 0.0f64;
        let mut bits = (-87.0f32).to_bits();
        // Every 64th f32 from -87 down to -0 and from +0 up to 88.
        while f32::from_bits(bits) < 0.0 {
            let x = f32::from_bits(bits);
            let e = (exp_f32(x) as f64 - (x as f64).exp()).abs() / (x as f64).exp();
            worst = worst.max(e);
            bits -= 64;
        }
        let mut bits = 0u32;
        while f32::from_bits(bits) <= 88.0 {
            let x = f32::from_bits(bits);
            let e = (exp_f32(x) as f64 - (x as f64).exp()).abs() / (x as f64).exp();
            worst = worst.max(e);
            bits += 64;
        }
        println!("exp_f32 worst {worst:e}");
        assert!(worst < 2.5e-7, "f32 {worst:e}");
        assert_eq!(exp_f32(-87.5), 0.0);
        let mut worst = 0.0f64;
        for i in 0..2_000_000 {
            let x = -708.0 + 1417.0 * (i as f64 / 2e6);
            let e = (exp_f64(x) - x.exp()).abs() / x.exp();
            worst = worst.max(e);
        }
        println!("exp_f64 worst {worst:e}");
        assert!(worst < 1.5e-14, "f64 {worst:e}");
        assert_eq!(exp_f64(-709.0), 0.0);
    }
}
