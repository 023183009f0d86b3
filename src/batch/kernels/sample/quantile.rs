//! The Beckmann visible-slope quantile in lanes (the batch visible-normal sampler's one
//! NDF-specific step): the scalar solve of `sampling::beckmann` with a fixed number of steps
//! and its residual test as the flag.
//!
//! The scalar path solves `K(x) = u K(hi)` (`K(x) = cos theta erfc(-x) / 2 + sin theta
//! exp(-x^2) / (2 sqrt(pi))`, Heitz 2014 eq. 80; `sampling::beckmann`'s module docs) by a
//! safeguarded Newton iteration from a Gaussian guess, with libm's `erfc`: 7.7 evaluations on
//! average, a data-dependent count. The lane:
//!
//! - starts from Jakob's fitted guess (Jakob 2014, "An Improved Visible Normal Sampling
//!   Routine for the Beckmann Distribution", section 3: in the `erf` domain, `b = erf(cot
//!   theta) - (1 + erf(cot theta)) (1 - u)^f(theta)`, `f(theta) = 1 - 0.876 theta + 0.4265
//!   theta^2 - 0.0594 theta^3`, `x_0 = erf^-1(b)` by Giles' guess, the scalar path's
//!   [`ERFINV_CENTRAL`] and [`ERFINV_TAIL`]), a guess only: any value is safe;
//! - takes `STEPS` Halley steps (`K''` costs two products more than `K'`), each kept inside
//!   the bracket of the scalar solve or replaced by bisection, as the scalar rule;
//! - evaluates the residual once more and flags the element unless `|K(x) - u K(hi)|` meets
//!   the scalar solve's goal (`residual_tolerance`, `8 eps_64 u K(hi)`): so what the lane
//!   returns meets the scalar path's guarantee, up to the lane `K`'s error below, however
//!   the steps went, and what it flags goes to the scalar sampler.
//!
//! Measured (prototype of the same steps, 13 view angles, uniform `u`): from this guess three
//! Halley steps meet the goal for every `u` in `[0.01, 1)`; one step at normal incidence (the
//! `y` slope). The far tails (`u < 0.01`, `1 - u < 0.01`) need up to five: a third to a half
//! of those are flagged.
//!
//! `K` in lanes is [`cdf_terms_from`] on [`erfc_neg_lane`] and [`exp_f64`]; its relative
//! error is [`k_lane_error`] (derived there, tested below against libm), so the lane's `x`
//! is the exact quantile of some `u'` with `|u' - u| <= (8.5 eps_64 + k_lane_error(x) +
//! k_lane_error(hi)) u + F::MIN_POSITIVE / K(hi)` (the scalar path's bound has the same form
//! with libm's errors: `(x^2 / 2 + 4) eps_64`).

use super::super::super::super::filter::exp_f64;
use super::super::super::super::sampling::beckmann::{
    ERFINV_CENTRAL, ERFINV_TAIL, INV_SQRT_PI, X_MAX, bracket_top, cdf_terms_from,
    residual_tolerance,
};
use super::super::super::engine::lane_math::{LN2_HI, LN2_LO, atan2_upper_lane, ln_parts_f64};
use crate::math as m;

/// Cephes `ndtr.c`: `erf(x) = x T(x^2) / U(x^2)` for `|x| < 1` (`U` monic).
const T: [f64; 5] = [
    9.604_973_739_870_516,
    90.026_019_720_384_27,
    2_232.005_345_946_843,
    7_003.325_141_128_051,
    55_592.301_301_039_49,
];
const U: [f64; 5] = [
    33.561_714_164_750_31,
    521.357_949_780_152_7,
    4_594.323_829_709_801,
    22_629.000_061_389_095,
    49_267.394_260_863_59,
];
/// Cephes `ndtr.c`: `erfc(z) = exp(-z^2) P(z) / Q(z)` for `1 <= z < 8` (`Q` monic).
const P: [f64; 9] = [
    2.461_969_814_735_305e-10,
    0.564_189_564_831_068_8,
    7.463_210_564_422_699,
    48.637_197_098_568_14,
    196.520_832_956_077_1,
    526.445_194_995_477_4,
    934.528_527_171_957_6,
    1_027.551_886_895_157_1,
    557.535_335_369_399_3,
];
const Q: [f64; 8] = [
    13.228_195_115_474_499,
    86.707_214_088_598_97,
    354.937_778_887_819_9,
    975.708_501_743_205_5,
    1_823.909_166_879_097_4,
    2_246.337_608_187_109_8,
    1_656.663_091_941_613_5,
    557.535_340_817_727_7,
];
/// Cephes `ndtr.c`: `erfc(z) = exp(-z^2) R(z) / S(z)` for `z >= 8` (`S` monic).
const R: [f64; 6] = [
    0.564_189_583_547_755_1,
    1.275_366_707_599_781,
    5.019_050_422_511_805,
    6.160_210_979_930_536,
    7.409_742_699_504_489,
    2.978_866_653_721_002_4,
];
const S: [f64; 6] = [
    2.260_528_632_201_172_6,
    9.396_035_249_380_015,
    12.048_953_980_809_666,
    17.081_445_074_756_59,
    9.608_968_090_632_859,
    3.369_076_451_000_815,
];

/// Horner's rule from the leading coefficient `lead` through `c[i]` for the listed indices,
/// written out, so that nothing in the lane is left to LLVM to unroll (a loop or call left in
/// the lane keeps LLVM from vectorising the loop over elements).
macro_rules! horner {
    ($z:expr, $lead:expr, $c:expr, [$($i:literal),*]) => {{
        let z = $z;
        let mut p = $lead;
        $(p = p * z + $c[$i];)*
        p
    }};
}

/// `(exp(-x^2), erfc(-x))` in lanes, for `x >= -26.6` (Cephes `ndtr.c`'s rationals, every
/// branch computed and the numerator and denominator selected before one division; below
/// `-26.6` both flush to `0`, an absolute error below `f64::MIN_POSITIVE`, as [`exp_f64`]
/// below `-708`).
///
/// Error (relative, against the exact values), derived: `exp(-x^2)`: [`exp_f64`]'s `1.5e-14`
/// plus the rounding of `x^2` (absolute `x^2 eps / 2` in the exponent); the rationals: their
/// coefficients are positive, so Horner's rule on `z >= 0` errs by at most `n eps` for degree
/// `n`: `P / Q` and `R / S` `16.5 eps`, `x T / U` `10.5 eps`, plus the fits' own error, below
/// `eps` (Cephes' design, confirmed by the test against libm); for `|x| < 1`, `erfc(-x) = 1 +
/// erf(x)` cancels by at most `erf(1) / erfc(1) = 5.4` (`x < 0`), for `x >= 1`, `2 -
/// erfc(x)` shrinks the error (`erfc(1) / (2 - erfc(1)) < 0.09`). In all `erfc(-x)` within
/// `1.5e-14 + (x^2 / 2 + 64) eps_64` ([`k_lane_error`] bounds both).
#[inline(always)]
pub(crate) fn erfc_neg_lane(x: f64) -> (f64, f64) {
    let z = x.abs();
    let z2 = x * x;
    let e = exp_f64(-z2);
    let small = z < 1.0;
    let mid = z < 8.0;
    let (n_t, d_t) = (
        x * horner!(z2, T[0], T, [1, 2, 3, 4]),
        horner!(z2, 1.0, U, [0, 1, 2, 3, 4]),
    );
    let (n_p, d_p) = (
        horner!(z, P[0], P, [1, 2, 3, 4, 5, 6, 7, 8]),
        horner!(z, 1.0, Q, [0, 1, 2, 3, 4, 5, 6, 7]),
    );
    let (n_r, d_r) = (
        horner!(z, R[0], R, [1, 2, 3, 4, 5]),
        horner!(z, 1.0, S, [0, 1, 2, 3, 4, 5]),
    );
    let (n, d) = if small {
        (n_t, d_t)
    } else if mid {
        (n_p, d_p)
    } else {
        (n_r, d_r)
    };
    let q = n / d;
    let erfc_z = e * q;
    let v = if small {
        1.0 + q
    } else if x < 0.0 {
        erfc_z
    } else {
        2.0 - erfc_z
    };
    (e, v)
}

/// The relative error bound of `K(x)` in lanes ([`erfc_neg_lane`]'s, plus the two products
/// and the sum of `K`'s positive terms, `2 eps`): `1.5e-14 + (x^2 / 2 + 66) eps_64`.
#[inline]
#[cfg(test)]
pub(crate) fn k_lane_error(x: f64) -> f64 {
    1.5e-14 + (0.5 * x * x + 66.0) * f64::EPSILON
}

/// `(K, K', K'')` at `x` in lanes.
#[inline(always)]
fn k_terms(x: f64, c: f64, s: f64) -> (f64, f64, f64) {
    let (e, erfc_neg) = erfc_neg_lane(x);
    let (k, dk) = cdf_terms_from(x, c, s, e, erfc_neg);
    // K'' = e (-2 x (c - s x) - s) / sqrt(pi).
    let d2k = INV_SQRT_PI * e * (-2.0 * x * (c - s * x) - s);
    (k, dk, d2k)
}

/// `ln x` for a normal positive `x` (the reduction of `lane_math::ln_parts_f64`; elsewhere a
/// finite value: only the guess uses it).
#[inline(always)]
fn ln_guess(x: f64) -> f64 {
    let (k, ln_m) = ln_parts_f64(x);
    k * LN2_HI + (k * LN2_LO + ln_m)
}

/// Giles' `erf^-1(b)` guess (the scalar path's coefficients) in lanes.
#[inline(always)]
fn erfinv_guess_lane(b: f64) -> f64 {
    let w = -ln_guess((1.0 - b) * (1.0 + b));
    let central = horner!(
        w - 2.5,
        ERFINV_CENTRAL.0,
        ERFINV_CENTRAL.1,
        [0, 1, 2, 3, 4, 5, 6, 7]
    );
    let tail = horner!(
        m::sqrt(w.max(0.0)) - 3.0,
        ERFINV_TAIL.0,
        ERFINV_TAIL.1,
        [0, 1, 2, 3, 4, 5, 6, 7]
    );
    (if w < 5.0 { central } else { tail }) * b
}

/// Jakob's guess of the quantile (module docs), for the view `(c, s)` with `c > 0`.
#[inline(always)]
fn guess(c: f64, s: f64, u: f64) -> f64 {
    let theta = atan2_upper_lane(s, c);
    // `erf(30) = 1` in `f64`; `s = 0` gives `cot = inf`, clamped.
    let cot = (c / s).min(30.0);
    let erf_cot = erfc_neg_lane(cot).1 - 1.0;
    let fit = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    // (1 - u)^fit, 1 - u >= eps / 2 for the clamped u.
    let pw = exp_f64(fit * ln_guess(1.0 - u));
    erfinv_guess_lane(erf_cot - (1.0 + erf_cot) * pw)
}

/// One step of the solve from `x` in the bracket `(lo, hi)`: Halley's `x - 2 f K' / (2 K'^2 -
/// f K'')`, `f = K(x) - target`, or bisection where that leaves the shrunk bracket (or is NaN:
/// `K' = 0` at the bracket's top); `x` kept where it meets the goal `tol`.
#[inline(always)]
fn halley_step(
    (x, lo, hi): (f64, f64, f64),
    c: f64,
    s: f64,
    target: f64,
    tol: f64,
) -> (f64, f64, f64) {
    let (k, dk, d2k) = k_terms(x, c, s);
    let f = k - target;
    let done = f.abs() <= tol;
    let (lo, hi) = if f < 0.0 { (x, hi) } else { (lo, x) };
    let xn = x - 2.0 * f * dk / (2.0 * dk * dk - f * d2k);
    let xn = if (xn > lo) & (xn < hi) {
        xn
    } else {
        0.5 * (lo + hi)
    };
    (if done { x } else { xn }, lo, hi)
}

/// The visible-slope quantile `C^-1(u)` for the unit view `(c, s) = (cos theta, sin theta)`
/// in the unit-roughness space (`c > 0`, `s >= 0`) and `u` in `[0, 1)` (the scalar sampler's
/// clamp), in lanes: `(x, ok)`. Where `ok`, `x` is in the scalar solve's bracket `[-X_MAX,
/// min(cot theta, X_MAX)]` and meets its residual goal with the lane `K` (module docs: the
/// exact quantile of a `u'` within `(8.5 eps_64 + k_lane_error(x) + k_lane_error(hi)) u` of
/// `u`); elsewhere (`u = 0`, NaN, a far-tail `u` the steps did not reach) the caller's scalar
/// path decides.
#[inline(always)]
pub(crate) fn visible_slope_quantile_lane<const STEPS: usize>(
    c: f64,
    s: f64,
    u: f64,
) -> (f64, bool) {
    let (lo, hi) = (-X_MAX, bracket_top(c, s));
    let norm = k_terms(hi, c, s).0;
    let target = u * norm;
    let tol = residual_tolerance(target);
    let g = guess(c, s, u);
    let x = if (g > lo) & (g < hi) {
        g
    } else {
        0.0_f64.min(0.5 * hi)
    };
    // The steps written out: a loop with a body this large stays a loop, and LLVM then does
    // not vectorise the loop over elements around it (nor does it for a call).
    const { assert!(STEPS <= 3) };
    let mut st = (x, lo, hi);
    if STEPS > 0 {
        st = halley_step(st, c, s, target, tol);
    }
    if STEPS > 1 {
        st = halley_step(st, c, s, target, tol);
    }
    if STEPS > 2 {
        st = halley_step(st, c, s, target, tol);
    }
    let x = st.0;
    let k = k_terms(x, c, s).0;
    let ok = ((k - target).abs() <= tol) & (target > 0.0);
    (x, ok)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `K` with libm's `erfc` and `exp` (the scalar path's), and its relative error bound:
    /// `exp(-x^2)` with the rounding of `x^2` (`x^2 eps / 2`) and libm's ulp, `erfc`'s ulp,
    /// the products and sum (`2 eps`).
    fn k_ref(x: f64, c: f64, s: f64) -> (f64, f64) {
        let k = cdf_terms_from(x, c, s, m::exp(-x * x), m::erfc(-x)).0;
        (k, (0.5 * x * x + 4.0) * f64::EPSILON)
    }

    #[test]
    fn erfc_neg_lane_against_libm() {
        // Against libm's `erfc` (within an ulp), over [-26.5, 27] densely (both sides of the
        // branch points +/-1, +/-8) and 0: the derived bound `k_lane_error(x) - 2 eps` plus
        // libm's `(x^2 / 2 + 1) eps` for `exp(-x^2)` (the reference computes `erfc` itself,
        // so only its ulp: `eps`).
        let mut worst = 0.0f64;
        let mut xs: Vec<f64> = (-265_000..=270_000).map(|i| i as f64 * 1e-4).collect();
        for b in [-8.0f64, -1.0, 1.0, 8.0] {
            xs.extend([b, b + 1e-15, b - 1e-15, b.next_up(), b.next_down()]);
        }
        for x in xs {
            let (e, v) = erfc_neg_lane(x);
            let want = m::erfc(-x);
            // The lane's erfc bound (K's without its products and sum) plus libm's ulp.
            let bound = k_lane_error(x) - 2.0 * f64::EPSILON + f64::EPSILON;
            let err = (v - want).abs() / want;
            assert!(
                err <= bound,
                "x {x}: {v:e} vs {want:e} ({err:e} > {bound:e})"
            );
            worst = worst.max(err / f64::EPSILON);
            let we = m::exp(-x * x);
            let eb = 1.5e-14 + (0.5 * x * x + 1.0) * f64::EPSILON;
            // (Flushed to 0 below `exp(-708)`.)
            assert!(
                (e - we).abs() <= eb * we || (x * x > 708.0 && e == 0.0),
                "x {x}: exp {e:e} vs {we:e}"
            );
        }
        println!("erfc_neg_lane worst relative error {worst:.1} eps");
    }

    #[test]
    fn quantile_lane_meets_its_residual_bound() {
        // For views from normal incidence to 89.99 degrees (and the `y` slope's normal
        // incidence with one step) and `u` over (0, 1) uniformly, in both far tails and at
        // the `f32` clamp: where the lane answers, `K(x)` by libm is within the stated bound
        // of `u K(hi)`, and `x` is in the bracket. Counts what the lane flags: nothing for `u`
        // in [0.01, 0.99] (the module docs' claim), some in the tails.
        // SplitMix64 (the crate's test generator, inlined: `testing` is a feature).
        let mut state = 0x0B5Eu64;
        let mut uniform = || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut flagged = [0usize; 2];
        let mut total = [0usize; 2];
        let mut worst = 0.0f64;
        for deg in [
            0.0f64, 1e-6, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 88.0, 89.9, 89.99,
        ] {
            let th = deg.to_radians();
            let (c, s) = (th.cos(), th.sin());
            for i in 0..6000 {
                let u = match i % 6 {
                    0..=2 => uniform() * 0.98 + 0.01,
                    3 => 10f64.powf(-12.0 * uniform() - 2.0),
                    4 => 1.0 - 10f64.powf(-13.0 * uniform() - 2.0),
                    _ => 1.0 - (1 + (uniform() * 1000.0) as u32) as f64 * 2f64.powi(-24),
                };
                let tail = usize::from(!(0.01..=0.99).contains(&u));
                let (x, ok) = if deg == 0.0 && i % 2 == 0 {
                    visible_slope_quantile_lane::<1>(c, s, u)
                } else {
                    visible_slope_quantile_lane::<3>(c, s, u)
                };
                total[tail] += 1;
                if !ok {
                    flagged[tail] += 1;
                    continue;
                }
                let hi = bracket_top(c, s);
                assert!(
                    x >= -X_MAX && x <= hi,
                    "{deg} u {u}: x {x} outside the bracket"
                );
                let (k, ek) = k_ref(x, c, s);
                let (n, en) = k_ref(hi, c, s);
                let rel = 8.5 * f64::EPSILON + k_lane_error(x) + k_lane_error(hi) + ek + en;
                let bound = rel * u * n + 2.0 * f64::MIN_POSITIVE;
                let err = (k - u * n).abs();
                assert!(err <= bound, "{deg} u {u}: x {x}, {err:e} > {bound:e}");
                worst = worst.max(err / bound);
            }
        }
        println!(
            "quantile lane: worst {worst:.3} of the bound; flagged {} of {} in [0.01, 0.99], {} of {} in the tails",
            flagged[0], total[0], flagged[1], total[1]
        );
        assert_eq!(flagged[0], 0);
        assert!(flagged[1] < total[1] / 2);
        // u = 0 and NaN: flagged (the scalar path returns the bracket's bottom).
        assert!(!visible_slope_quantile_lane::<3>(0.6, 0.8, 0.0).1);
        assert!(!visible_slope_quantile_lane::<3>(0.6, 0.8, f64::NAN).1);
    }
}
