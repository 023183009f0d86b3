//! `sin` and `cos` of `2 pi u`, and `atan2` on the upper half plane, in lanes.

use super::super::super::super::F;
use super::WIDE;
use crate::math::Real;

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
    // The reduction's branch: `t = y / |x|` above `tan(3 pi / 8)`, or above `0.66`.
    let steep = y > T3P8 * ax;
    let diagonal = !steep & (y > 0.66 * ax);
    let (num, den) = if steep {
        (-ax, y)
    } else if diagonal {
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
    let (bh, bl) = if steep {
        PI_2
    } else if diagonal {
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
}
