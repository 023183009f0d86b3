//! IEEE 754 binary16 (`f16`) encoding and decoding, for the moment chain's half-precision
//! storage (the GPU formats `R16F` .. `RGBA16F`).
//!
//! binary16: 1 sign bit, 5 exponent bits (bias 15), 10 fraction bits. Normal numbers
//! `[2^-14, 65504]` carry a relative rounding error of at most `2^-11`; subnormals are
//! multiples of `2^-24` (absolute error at most `2^-25`).

/// The largest finite `f16`, `65504`.
pub const F16_MAX: f32 = 65504.0;

/// `x` rounded to the nearest `f16`, ties to even (IEEE 754's default rounding), as its bit
/// pattern. Values of magnitude `65520` or more (the midpoint between `F16_MAX` and `2^16`)
/// round to infinity, as IEEE 754 requires; NaN stays a (quiet) NaN with its sign; `-0`
/// stays `-0`. [`f16_to_f32`] of the result is exact.
pub const fn f16_from_f32(x: f32) -> u16 {
    let b = x.to_bits();
    let sign = ((b >> 16) & 0x8000) as u16;
    let exp = ((b >> 23) & 0xff) as i32;
    let man = b & 0x007f_ffff;
    if exp == 0xff {
        // Infinity, or a NaN kept quiet with the top fraction bits it had.
        let nan = if man != 0 {
            0x0200 | (man >> 13) as u16
        } else {
            0
        };
        return sign | 0x7c00 | nan;
    }
    // The f16 biased exponent of x's leading bit.
    let e = exp - 127 + 15;
    if e >= 0x1f {
        return sign | 0x7c00;
    }
    if e <= 0 {
        // Subnormal in f16 (or zero): the value in units of 2^-24 is the 24-bit significand
        // shifted right by 14 - e; below 2^-25 it rounds to zero.
        if e < -10 {
            return sign;
        }
        let m = man | 0x0080_0000;
        let shift = (14 - e) as u32;
        let half = 1u32 << (shift - 1);
        let rem = m & ((1u32 << shift) - 1);
        let mut r = m >> shift;
        if rem > half || (rem == half && (r & 1) == 1) {
            // A carry into bit 10 gives the smallest normal number's pattern: correct.
            r += 1;
        }
        return sign | r as u16;
    }
    let mut r = ((e as u32) << 10) | (man >> 13);
    let rem = man & 0x1fff;
    if rem > 0x1000 || (rem == 0x1000 && (r & 1) == 1) {
        // A carry into the exponent is correct, up to infinity (0x7c00).
        r += 1;
    }
    sign | r as u16
}

/// The `f16` bit pattern `h` as an `f32` (exact: every `f16` is an `f32`).
pub const fn f16_to_f32(h: u16) -> f32 {
    let sign = ((h & 0x8000) as u32) << 16;
    let exp = ((h >> 10) & 0x1f) as u32;
    let man = (h & 0x03ff) as u32;
    if exp == 0 {
        // Zero or subnormal: man * 2^-24, exact in f32.
        let v = man as f32 * (1.0 / 16_777_216.0);
        return if sign != 0 { -v } else { v };
    }
    let bits = if exp == 0x1f {
        sign | 0x7f80_0000 | (man << 13)
    } else {
        sign | ((exp + 112) << 23) | (man << 13)
    };
    f32::from_bits(bits)
}

/// `x` as a finite `f16`: clamped to `[-F16_MAX, F16_MAX]`, then [`f16_from_f32`] (the
/// moment chain's storage: a texel never holds an infinity).
#[inline]
pub fn f16_saturating(x: f32) -> u16 {
    f16_from_f32(x.clamp(-F16_MAX, F16_MAX))
}
