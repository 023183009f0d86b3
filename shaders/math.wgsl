#define_import_path filtered_ndf::math

// The constants and the driver-independent elementary functions of the shader modules
// (`src/math.rs` is the Rust counterpart: the one switch for the float backend).
//
// WGSL lets a driver evaluate `atan` to 4096 ulp and `sin`/`cos` to an absolute 2^-11
// (WGSL spec, "Floating Point Accuracy"); Mesa's llvmpipe `atan` errs by 2e-5 relative. Where
// a kernel needs better, it calls the functions below, which use only `+`, `-`, `*` (correctly
// rounded in WGSL), `/` (2.5 ulp) and selects. Their bounds are stated in ulp of f32
// (`eps = 2^-23 = 1.19e-7`) and checked on the GPU by the conformance harness
// (`gpu/src/checks/math.rs`).
//
// Infinities and NaN: WGSL allows a driver to assume they never occur at run time, so no
// function here returns them on purpose. Where the Rust crate returns `+inf`, the shader
// returns `F32_MAX` (documented at each function).

/// pi.
const PI: f32 = 3.14159265358979;
/// pi / 2.
const HALF_PI: f32 = 1.57079632679490;
/// pi / 4.
const QUARTER_PI: f32 = 0.785398163397448;
/// 1 / pi.
const INV_PI: f32 = 0.318309886183791;
/// The largest finite f32: the shader's stand-in for the Rust crate's `+inf`.
const F32_MAX: f32 = 3.40282347e38;
/// The smallest positive normal f32, `2^-126` (GPUs may flush smaller results to 0).
const F32_MIN_POSITIVE: f32 = 1.17549435e-38;

/// `tan(pi / 8)`: the reduced argument of [`atan`] stays within `[-TAN_EIGHTH_PI, TAN_EIGHTH_PI]`.
const TAN_EIGHTH_PI: f32 = 0.414213562373095;

/// Arc tangent (radians) with relative error below 8 ulp (`1e-6`) for every finite `x`,
/// whatever the driver's `atan`.
///
/// Reduction: `atan(x) = pi/2 - atan(1/x)` for `|x| > 1`, then
/// `atan(t) = pi/4 + atan((t - 1) / (t + 1))` for `t > tan(pi/8)`, leaving `|u| <= tan(pi/8)`,
/// where `atan(u) = u + u^3 P(u^2)` with a degree-4 polynomial `P` fitted at Chebyshev nodes
/// of `u^2` in `[0, tan^2(pi/8)]` (approximation error `3e-9` relative with the coefficients
/// rounded to f32). Rounding: the reduced argument carries at most 4 ulp, which the
/// reduction maps to at most 2 ulp of the result (`atan u <= 0.39` is added to `pi/4`), the
/// polynomial and the final additions at most 3 ulp more. Odd in `x`; `atan(0) = 0`.
fn atan(x: f32) -> f32 {
    let a = abs(x);
    let inv = a > 1.0;
    var t = select(a, 1.0 / a, inv);
    let shift = t > TAN_EIGHTH_PI;
    t = select(t, (t - 1.0) / (t + 1.0), shift);
    let z = t * t;
    let p = ((((-0.06451927870512009 * z + 0.10743731260299683) * z - 0.14263956248760223) * z
        + 0.19999539852142334) * z - 0.3333333134651184);
    var r = t + t * z * p;
    r = select(r, QUARTER_PI + r, shift);
    r = select(r, HALF_PI - r, inv);
    return select(r, -r, x < 0.0);
}

/// `(cos(2 pi u), sin(2 pi u))` for a turn fraction `u` (an angle of `u` full turns), with
/// absolute error below 3 ulp of 1 (`4e-7`) for `|u| < 2^20`, whatever the driver's
/// `sin`/`cos`. Sampling needs this: WGSL allows `sin`/`cos` an absolute error of `2^-11`.
///
/// Reduction by quarter turns, exact in f32: `q = round(4 u)`, `r = u - q / 4` in
/// `[-1/8, 1/8]`; then `sin(2 pi r) = r S(r^2)`, `cos(2 pi r) = C(r^2)` with degree-4
/// polynomials fitted at Chebyshev nodes of `r^2` in `[0, 1/64]` (approximation error
/// `4e-8` with f32 coefficients, dominated by `2 pi` rounded to f32), and the quadrant
/// applied by exact sign changes and swaps.
fn sincos_turns(u: f32) -> vec2<f32> {
    let q = round(4.0 * u);
    let r = u - 0.25 * q;
    let z = r * r;
    let s = r * ((((41.47283172607422 * z - 76.69786834716797) * z + 81.6052017211914) * z
        - 41.34170150756836) * z + 6.2831854820251465);
    let c = (((59.22016906738281 * z - 85.4428482055664) * z + 64.93931579589844) * z
        - 19.739208221435547) * z + 1.0;
    let k = i32(q) & 3;
    var cs = vec2<f32>(c, s);
    if k == 1 {
        cs = vec2<f32>(-s, c);
    } else if k == 2 {
        cs = vec2<f32>(-c, -s);
    } else if k == 3 {
        cs = vec2<f32>(s, -c);
    }
    return cs;
}

/// `sqrt(x^2 + y^2)` without overflow or underflow of the squares (both scaled by the larger
/// magnitude first): within 5 ulp. `0` for `x = y = 0`.
fn hypot(x: f32, y: f32) -> f32 {
    let m = max(abs(x), abs(y));
    if m <= 0.0 {
        return 0.0;
    }
    let a = x / m;
    let b = y / m;
    return m * sqrt(a * a + b * b);
}

/// `ln 2` split for an exact `n ln 2` (`n` integer, `|n| <= 256`): `LN2_HI` has 16 significant
/// bits, `LN2_LO` the rest.
const LN2_HI: f32 = 0.693145751953125;
const LN2_LO: f32 = 1.428606765330187e-6;
/// `ln 2`.
const LN_2: f32 = 0.693147180559945;
/// `sqrt(2 pi)`.
const SQRT_TAU: f32 = 2.50662827463100;
/// `log2(e)`.
const LOG2_E: f32 = 1.44269504088896;

/// `e^x` within 3 ulp (`2.5e-7` measured, `gpu/src/checks/math.rs`) for `x <= 88`, `0` below
/// `-87`, whatever the driver's `exp` (WGSL allows `3 + 2|x|` ulp): the Rust crate's `f32`
/// polynomial exponential (`gaussian_ggx_quad.rs`). `2^n e^r` with `n = round(x / ln 2)`,
/// `r = (x - n LN2_HI) - n LN2_LO` exact to the rounding of the last step, `|r| <= ln(2) / 2`,
/// `e^r` by the relative minimax polynomial of degree 6 (error `1.9e-9`) in Estrin's form,
/// `2^n` by its bit pattern (GLSL 330 has no `ldexp`).
fn exp(x: f32) -> f32 {
    let xc = clamp(x, -87.0, 88.0);
    let n = round(xc * LOG2_E);
    let r = (xc - n * LN2_HI) - n * LN2_LO;
    let r2 = r * r;
    let p = (1.0 + r + (0.4999999 + 0.1666642 * r) * r2)
        + (0.041668225 + 0.008374816 * r + 0.0013836846 * r2) * (r2 * r2);
    let s = bitcast<f32>(u32(i32(n) + 127) << 23u);
    return select(0.0, p * s, x >= -87.0);
}

/// `sqrt(2)`.
const SQRT_2: f32 = 1.41421356237310;

/// `2 atanh(z) = ln((1 + z) / (1 - z))` for `|z| <= 0.2`: its odd series through `z^11 / 11`
/// (next term below `1e-9` relative).
fn atanh2(z: f32) -> f32 {
    let z2 = z * z;
    let s = ((((z2 * (1.0 / 11.0) + 1.0 / 9.0) * z2 + 1.0 / 7.0) * z2 + 0.2) * z2 + 1.0 / 3.0) * z2;
    return 2.0 * z + 2.0 * z * s;
}

/// Natural logarithm of a positive normal `x` within 4 ulp relative, also near `x = 1` (WGSL
/// allows the driver's `log` an absolute `2^-21` on `[0.5, 2]`, no relative accuracy near its
/// zero). `x = f 2^e` with `f` in `[sqrt(1/2), sqrt 2)` from the bit pattern, then
/// `ln f = 2 atanh(z)`, `z = (f - 1) / (f + 1)` (`f - 1` exact, `|z| <= 0.1716`, [`atanh2`]),
/// and `e ln 2` with the split constant.
fn ln(x: f32) -> f32 {
    let b = bitcast<u32>(x);
    var e = f32(i32((b >> 23u) & 0xffu) - 127);
    var f = bitcast<f32>((b & 0x007fffffu) | 0x3f800000u);
    if f > SQRT_2 {
        f = 0.5 * f;
        e = e + 1.0;
    }
    let p = atanh2((f - 1.0) / (f + 1.0));
    return e * LN2_HI + (e * LN2_LO + p);
}

/// `ln(1 + x)` for `x >= 0` within 6 ulp relative, also for tiny `x`: `2 atanh(x / (2 + x))`
/// below `x = 0.5` ([`atanh2`]; no `1 + x` is formed, whose rounding would cost `eps / x`),
/// [`ln`] of `1 + x` above (its rounding then costs under 2 ulp of the result). Kahan's
/// `ln(u) x / (u - 1)` is not used: a driver may simplify `(1 + x) - 1` to `x` (Mesa does).
fn ln_1p(x: f32) -> f32 {
    if x < 0.5 {
        return atanh2(x / (2.0 + x));
    }
    return ln(1.0 + x);
}

/// Whether `x` is NaN, decided on its bits (exponent all ones, mantissa non-zero): integer
/// arithmetic, which no driver folds away under a no-NaN assumption (a float comparison such
/// as `x != x` may be). The Rust `is_nan`.
fn is_nan(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) > 0x7f800000u;
}

/// `x` with NaN replaced by `0`: the NaN policy of footprints and normal differences (the Rust
/// `vector::nan_to_zero`): a NaN entry carries no information and widens nothing.
fn nan_to_zero(x: f32) -> f32 {
    return select(x, 0.0, is_nan(x));
}

/// [`nan_to_zero`] per component of a 2-vector.
fn nan_to_zero2(v: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(nan_to_zero(v.x), nan_to_zero(v.y));
}

/// [`nan_to_zero`] per component of a 3-vector.
fn nan_to_zero3(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(nan_to_zero(v.x), nan_to_zero(v.y), nan_to_zero(v.z));
}
