//! Lane math: transcendental functions in a form LLVM vectorises (plain arithmetic, bit
//! casts and selects; no calls, no branches), each with its stated and tested bound.
//!
//! | function | replaces | bound (relative) | where tested |
//! |---|---|---|---|
//! | [`exp_neg_times`] `e^-x k` | `Beckmann`'s `exp_neg_times` (libm `exp`, `ln`) | `exp_poly`'s (`2.5e-7` in `f32`, `1.5e-14` in `f64`) plus one rounding, for normal results | unit test below |
//! | `filter::exp_poly` (shared with the exact Gaussian filter) | libm `exp` | `2.5e-7` / `1.5e-14`; its `f32` polynomial alone `3.5 u` | `filter/exp_poly.rs` |
//! | [`pow_lane`] `x^e` | libm `powf` (the deferred presets' norm exponent) | in `f64` `1.6e-14 + 3 eps_64 abs(y)` + `eps_64`, `y = e ln x`; in `f32`, computed in `f32` with `e ln 2` split, `(5 + 3 abs(e)) u` (`u = 2^-24`) | unit test below |
//! | [`sincos_2pi`] `(sin 2 pi u, cos 2 pi u)` | libm `sin`, `cos` of `phi = 2 pi u` (the GGX visible-normal sampler's azimuth) | absolute `2e-15` computed in `f64` (in `f32`: plus half an `f32` ulp of the result) | unit test below |
//! | [`atan2_upper_lane`] `atan2(y, x)`, `y > 0` | the box filter's `atan2_upper` (libm `atan`; the closed form's edge angles) | `3 eps_64` (derived `2.1`), in `f64` for both precisions | unit test below |
//! | `filter::beckmann_lambda_fast` (shared with its sampler) | Beckmann `Lambda` in `f64` (libm `erfc`) | `2.1e-7 (1 + Lambda)` / `1.9e-8 (1 + Lambda)` absolute | `gaussian_ggx_quad` |
//! | `quantile::erfc_neg_lane` `(exp(-x^2), erfc(-x))` | libm `exp`, `erfc` (Beckmann's visible-slope quantile) | `1.5e-14 + (x^2 / 2 + 64) eps_64`, in `f64` for both precisions | `quantile.rs` |
//!
//! A lane whose input leaves the range these functions cover (a subnormal result, a
//! non-finite factor) is flagged, and the driver evaluates that element by the scalar
//! function instead: the flags cost nothing where nothing is flagged.

use super::super::filter::{
    LN2_HI_F32, LN2_LO_F32, MAGIC_F32, MAGIC_F64, exp_f32_poly, exp_f32_reduced, exp_f64_reduced,
};
use super::F;
use crate::math::Real;

/// Whether `F` is `f64`.
pub(crate) const WIDE: bool = F::MANTISSA_DIGITS > 24;

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

/// `ln 2` split: the high part has trailing zeros, so `k LN2_HI` is exact for `|k| < 2^11`.
pub(crate) const LN2_HI: f64 = 0.693_147_180_369_123_8; // 0x3fe62e42fee00000.
/// `ln 2 - LN2_HI`.
pub(crate) const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;

/// The logarithm's reduction shared by [`pow_lane`] and `log::ln_lane`: `x = m 2^k` with `m` in
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
    let big = m1 > core::f64::consts::SQRT_2;
    let m = if big { 0.5 * m1 } else { m1 };
    let k = field - 1023.0 + if big { 1.0 } else { 0.0 };
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

/// [`ln_parts_f64`] in `f32` arithmetic (`log::ln_lane` and [`pow_lane`] in `f32`): `(k, ln
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
    let big = m1 > core::f32::consts::SQRT_2;
    let m = if big { 0.5 * m1 } else { m1 };
    let k = (field - 127 + i32::from(big)) as f32;
    // m - 1 is exact (Sterbenz).
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let p = ((C[3] * s2 + C[2]) * s2 + C[1]) * s2 + C[0];
    (k, 2.0 * s + (2.0 * s) * (s2 * p))
}

/// `(sin(2 pi u), cos(2 pi u))` for `u` in `[0, 1]` (the batch samplers' azimuth, `u`
/// already clamped by the scalar sampler's `clamp_unit`), branch-free, each precision in its
/// own arithmetic (in `f32` the `f64` form held the samplers' `f32` loops to half width).
///
/// Range reduction `t = 4 u` (exact), `k = round(t)` (by the `1.5 * 2^p` shift, exact), `r =
/// (t - k) pi / 2` in `[-pi/4, pi/4]` (`t - k` exact: both are multiples of `t`'s ulp), then
/// the Taylor polynomials of `sin r` and `cos r` (in `f64` to `r^17` and `r^18`, truncation
/// below `(pi/4)^19 / 19! < 1e-19`; in `f32` to `r^9` and `r^10`, below `(pi/4)^11 / 11! <
/// 1.8e-9`, `0.015 eps_32`), and the quadrant `k mod 4` by selects (`sin(r + k pi/2)`: swaps
/// and signs, exact).
///
/// Error (absolute, `eps` of the precision): `r` carries the rounding of `pi / 2` and of the
/// product (`|r| <= pi/4`: below `eps pi/4`), which the 1-Lipschitz `sin`, `cos` pass on;
/// Horner's rounding: in `f64` below `8 eps_64` over terms of total magnitude below `1.4`, in
/// all `2e-15`; in `f32` the last sum's half ulp (at most `eps / 2`) and the correction
/// term's (`r^2 |p| <= 0.31`: below `0.3 eps`), in all below `1.6 eps_32`, stated as `2
/// eps_32` (`2.4e-7`). Outside `[0, 1]` (the samplers never pass such `u`) the reduction
/// stays exact while `4 u < 2^(p - 1)`, so the bound holds there too; NaN gives NaN. Tested
/// against libm below.
#[inline(always)]
pub(crate) fn sincos_2pi(u: F) -> (F, F) {
    if WIDE {
        let (s, c) = sincos_2pi_f64(u.to_f64());
        (F::from_f64(s), F::from_f64(c))
    } else {
        let (s, c) = sincos_2pi_f32(u.to_f64() as f32);
        (F::from_f64(s as f64), F::from_f64(c as f64))
    }
}

/// `sin(r + q pi/2)`, `cos(r + q pi/2)` from `(sin r, cos r)` and `q = k mod 4`: `(s, c)`,
/// `(c, -s)`, `(-s, -c)`, `(-c, s)`, by selects.
#[inline(always)]
fn quadrant<T: core::ops::Neg<Output = T> + Copy>(sr: T, cr: T, q: u32) -> (T, T) {
    let odd = (q & 1) == 1;
    let (s0, c0) = if odd { (cr, sr) } else { (sr, cr) };
    let sin_neg = q >= 2;
    let cos_neg = (q == 1) | (q == 2);
    (
        if sin_neg { -s0 } else { s0 },
        if cos_neg { -c0 } else { c0 },
    )
}

/// [`sincos_2pi`] in `f64` arithmetic.
#[inline(always)]
fn sincos_2pi_f64(u: f64) -> (f64, f64) {
    const SHIFT: f64 = 6_755_399_441_055_744.0; // 1.5 * 2^52
    const FRAC_PI_2: f64 = core::f64::consts::FRAC_PI_2;
    // 1 / n! for the odd (sin) and even (cos) powers.
    const S: [f64; 8] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 1_307_674_368_000.0,
        1.0 / 355_687_428_096_000.0,
    ];
    const C: [f64; 9] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 20_922_789_888_000.0,
        -1.0 / 6_402_373_705_728_000.0,
    ];
    let t = 4.0 * u;
    let k = (t + SHIFT) - SHIFT;
    let r = (t - k) * FRAC_PI_2;
    let r2 = r * r;
    let mut ps = S[7];
    for c in S[..7].iter().rev() {
        ps = ps * r2 + c;
    }
    let sr = r + r * (r2 * ps);
    let mut pc = C[8];
    for c in C[..8].iter().rev() {
        pc = pc * r2 + c;
    }
    let cr = 1.0 + r2 * pc;
    // k mod 4 from the low bits of k's shifted form (k >= 0 here; any integer works).
    quadrant(sr, cr, ((k + SHIFT).to_bits() & 3) as u32)
}

/// [`sincos_2pi`] in `f32` arithmetic.
#[inline(always)]
fn sincos_2pi_f32(u: f32) -> (f32, f32) {
    const SHIFT: f32 = 12_582_912.0; // 1.5 * 2^23
    const FRAC_PI_2: f32 = core::f32::consts::FRAC_PI_2;
    const S: [f32; 4] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];
    const C: [f32; 5] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
    ];
    let t = 4.0 * u;
    let k = (t + SHIFT) - SHIFT;
    let r = (t - k) * FRAC_PI_2;
    let r2 = r * r;
    let ps = ((S[3] * r2 + S[2]) * r2 + S[1]) * r2 + S[0];
    let sr = r + r * (r2 * ps);
    let pc = (((C[4] * r2 + C[3]) * r2 + C[2]) * r2 + C[1]) * r2 + C[0];
    let cr = 1.0 + r2 * pc;
    quadrant(sr, cr, (k + SHIFT).to_bits() & 3)
}

/// `atan2(y, x)` for `y > 0` (an angle in `(0, pi)`), branch-free in `f64`: the lane form of
/// the box filter's `atan2_upper` (`filter::rect`, the closed form's four edge angles).
///
/// Reduction (Cephes `atan`, Moshier): with `t = y / |x|`, `phi = atan t` in `(0, pi/2]` is
/// `pi/2 + atan(-|x| / y)` for `t > tan(3 pi/8)`, `pi/4 + atan((y - |x|) / (y + |x|))` for
/// `t > 0.66`, else `atan(y / |x|)`: one division `r = num / den` of selected operands
/// (`|r| <= 0.66`), without forming `t`; `atan r = r + r z P(z) / Q(z)`, `z = r^2`, Cephes'
/// degree 4 / 5 rational (peak relative error `1.9e-16` on that range); then
/// `theta = phi` for `x >= 0` (`-0` included) and `pi - phi` for `x < 0`, the constants
/// `pi/4`, `pi/2`, `3 pi/4`, `pi` added as `hi + (lo + (+/- atan r))` (their rounding carried).
///
/// Error (relative, against the exact `atan2`; `eps = 2^-52`): `r` carries up to three
/// roundings (the difference, the sum, the quotient: `1.5 eps`; `atan r / r` passes a
/// relative error of `r` on with a factor at most `1`), the rational its `0.86 eps`, so
/// `atan r` is within `2.4 eps` of `|atan r| <= pi/8` in the middle branch (`1.4 eps` in the
/// others, one rounding in `r`); over the angle (at least `atan 0.66 = 0.583` where the
/// base is `pi/4`) plus the final rounding, at most `2.1 eps` relative in all: stated as `3 eps`,
/// tested against libm below (measured: `1.07 eps` against libm, which is itself within half
/// an ulp to one ulp).
///
/// Domain: `y > 0`, `y + |x|` finite (the box filter's edges stay below `1e121`). `x = +/-inf`
/// gives `0` / `pi`, `y = inf` with finite `x` gives `pi/2`; NaN in gives NaN; `y <= 0` or
/// both infinite is outside the domain (`0` for `y = 0, x > 0` and `pi` for `x < 0`; NaN for
/// `0 / 0` and `inf / inf`).
#[inline(always)]
pub(crate) fn atan2_upper_lane(y: f64, x: f64) -> f64 {
    /// `tan(3 pi / 8)`.
    const T3P8: f64 = 2.414_213_562_373_095;
    // Cephes `atan.c` (also Go's `math.xatan`): atan r = r + r z P(z) / Q(z), |r| <= 0.66.
    const P: [f64; 5] = [
        -8.750_608_600_031_904e-1,
        -1.615_753_718_733_365e1,
        -7.500_855_792_314_705e1,
        -1.228_866_684_490_136_2e2,
        -6.485_021_904_942_025e1,
    ];
    const Q: [f64; 5] = [
        2.485_846_490_142_306_3e1,
        1.650_270_098_316_988_5e2,
        4.328_810_604_912_903e2,
        4.853_903_996_359_137e2,
        1.945_506_571_482_614e2,
    ];
    // (hi, lo) of pi/4, pi/2, 3 pi/4, pi: hi the rounded value, lo the rest.
    use core::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI as PI_HI};
    const PI_4: (f64, f64) = (FRAC_PI_4, 3.061_616_997_868_383e-17);
    const PI_2: (f64, f64) = (FRAC_PI_2, 6.123_233_995_736_766e-17);
    const PI3_4: (f64, f64) = (2.356_194_490_192_345, 9.184_850_993_605_148e-17);
    const PI: (f64, f64) = (PI_HI, 1.224_646_799_147_353_2e-16);
    let ax = x.abs();
    let big = y > T3P8 * ax;
    let mid = !big & (y > 0.66 * ax);
    let (num, den) = if big {
        (-ax, y)
    } else if mid {
        (y - ax, y + ax)
    } else {
        (y, ax)
    };
    let r = num / den;
    let z = r * r;
    let p = (((P[0] * z + P[1]) * z + P[2]) * z + P[3]) * z + P[4];
    let q = ((((z + Q[0]) * z + Q[1]) * z + Q[2]) * z + Q[3]) * z + Q[4];
    let a = r + r * (z * p / q);
    // theta = b + a (x >= 0) or (pi - b) - a (x < 0), b the reduction's base.
    let neg = x < 0.0;
    let (bh, bl) = if big {
        PI_2
    } else if mid {
        if neg { PI3_4 } else { PI_4 }
    } else if neg {
        PI
    } else {
        (0.0, 0.0)
    };
    bh + (bl + if neg { -a } else { a })
}

/// The relative error bound of [`atan2_upper_lane`], in units of `eps_64` (its docs).
#[cfg(test)]
const ATAN2_LANE_ULPS: f64 = 3.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sincos_2pi_against_libm() {
        // Against libm's `sin`, `cos` in `f64` of `2 pi u` (the reference's own error: the
        // rounding of `2 pi u`, below `2 pi eps_64`, plus libm's ulp): the bound of
        // `sincos_2pi` plus the reference's, over [0, 1] densely, the quadrant boundaries,
        // and the clamp's top `1 - eps/2`.
        let mut us: Vec<F> = (0..=200_000)
            .map(|i| F::from_f64(i as f64 / 200_000.0))
            .collect();
        for k in 0..=4 {
            let b = F::from_f64(k as f64 / 4.0);
            us.extend([b, b + F::EPSILON, b - F::EPSILON / 2.0, b + 1e-3, b - 1e-3]);
        }
        us.extend([1.0 - F::EPSILON / 2.0, F::MIN_POSITIVE, 1e-30]);
        // The stated bound (`2e-15` in `f64`, `2 eps_32` in `f32`) and the reference's error.
        let lane = if WIDE {
            2e-15
        } else {
            2.0 * f32::EPSILON as f64
        };
        let reference = lane + 2.0 * core::f64::consts::PI * f64::EPSILON + f64::EPSILON;
        let mut worst = 0.0f64;
        for u in us {
            if !(0.0..=1.0).contains(&u) {
                continue;
            }
            let phi = 2.0 * core::f64::consts::PI * u.to_f64();
            let (s, c) = sincos_2pi(u);
            for (got, want) in [(s, phi.sin()), (c, phi.cos())] {
                let err = (got.to_f64() - want).abs();
                assert!(err <= reference, "u {u}: {got} vs {want}");
                worst = worst.max(err);
            }
        }
        println!("sincos_2pi worst absolute error {worst:e}");
        assert!(sincos_2pi(F::NAN).0.is_nan());
    }

    #[test]
    fn atan2_upper_lane_against_libm() {
        // Against libm's `f64::atan2` (within one ulp of the exact angle, so at most `eps_64`
        // relative): the lane's bound `ATAN2_LANE_ULPS eps_64` plus the reference's `eps_64`,
        // over angles densely in (0, pi) (both sides of the reduction's switches at
        // `atan 0.66` and `3 pi / 8` and their mirrors), radii from `1e-300` to `1e300`, the
        // axes (`x = +/-0`), tiny and huge ratios, infinities and NaN.
        let bound = (ATAN2_LANE_ULPS + 1.0) * f64::EPSILON;
        let mut worst = 0.0f64;
        let mut check = |y: f64, x: f64| {
            let want = y.atan2(x);
            let got = atan2_upper_lane(y, x);
            let err = (got - want).abs() / want;
            assert!(err <= bound, "atan2({y:e}, {x:e}): {got:e} vs {want:e}");
            worst = worst.max(err);
        };
        let n = 400_000;
        for i in 1..n {
            let th = core::f64::consts::PI * (i as f64 / n as f64);
            for rad in [1.0, 1e-300, 3.7e-5, 1e5, 1e300] {
                check(rad * th.sin(), rad * th.cos());
            }
        }
        for &t in &[0.66f64, 2.414_213_562_373_095, 1.0] {
            for k in -50..=50 {
                let tt = t * (1.0 + k as f64 * f64::EPSILON);
                check(tt, 1.0);
                check(tt, -1.0);
                check(1.0, 1.0 / tt);
                check(1.0, -1.0 / tt);
            }
        }
        for e in -300..=300 {
            let v = 10f64.powi(e);
            for (y, x) in [(v, 1.0), (v, -1.0), (1.0, v), (1.0, -v), (v, 0.5 * v)] {
                check(y, x);
            }
        }
        for (y, x) in [
            (1.0, 0.0),
            (1.0, -0.0),
            (f64::MIN_POSITIVE, 1.0),
            (5e-324, 1.0),
            (5e-324, -1.0),
            (1.0, f64::INFINITY),
            (1.0, f64::NEG_INFINITY),
            (f64::INFINITY, 1.0),
            (f64::INFINITY, -1e300),
            (f64::MAX / 4.0, f64::MAX / 4.0),
        ] {
            if y.atan2(x) > 0.0 && y.atan2(x) < core::f64::consts::PI {
                check(y, x);
            }
        }
        assert_eq!(atan2_upper_lane(1.0, f64::INFINITY), 0.0);
        assert_eq!(
            atan2_upper_lane(1.0, f64::NEG_INFINITY),
            core::f64::consts::PI
        );
        assert_eq!(atan2_upper_lane(1.0, 0.0), core::f64::consts::FRAC_PI_2);
        assert_eq!(atan2_upper_lane(1.0, -0.0), core::f64::consts::FRAC_PI_2);
        assert!(atan2_upper_lane(f64::NAN, 1.0).is_nan());
        assert!(atan2_upper_lane(1.0, f64::NAN).is_nan());
        println!(
            "atan2_upper_lane worst relative error {:.3} eps",
            worst / f64::EPSILON
        );
    }

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
