//! The quadrature rules of the exact Gaussian-filtered GGX ([`super::GaussianFilteredGgx`]):
//! the node loops and their tables (with the polynomial `exp` of `exp_poly.rs`, which LLVM
//! vectorises). The derivations and error bounds are in the module docs of `gaussian_ggx.rs`
//! (items cited as "item N"); this file holds what runs.
//!
//! Every node loop is a fixed-count, branch-free loop over arrays in the lobe's precision `F`
//! (`f32` lanes for the `f32` lobe, `f64` lanes for the `f64` lobe), with all per-evaluation
//! set-up (the exponent's reference, the truncation points, the series corrections) in `f64`.

use super::F;
use super::exp_poly::{exp_f64, exp_poly};
use crate::math::{self as m, Real};

/// `f64` build: the rules' tighter constants.
pub(super) const WIDE: bool = F::MANTISSA_DIGITS > 24;

/// An upper bound of `ln x` for `x >= 1` (exact at powers of two, at most `1 - ln 2` too
/// large): `e ln 2 + (m - 1)` for `x = m 2^e`, `m` in `[1, 2)` (`ln m <= m - 1`).
#[inline(always)]
pub(super) fn ln_upper(x: f64) -> f64 {
    let b = x.to_bits();
    let e = ((b >> 52) & 0x7ff) as f64 - 1023.0;
    let mant = f64::from_bits((b & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    e * core::f64::consts::LN_2 + (mant - 1.0)
}

// ---------------------------------------------------------------------------------------------
// J: the far tail, Gauss-Laguerre, the trapezoid rule in ln w (item numbers of the module docs).
// ---------------------------------------------------------------------------------------------

/// Far-tail switch: the series replaces the quadrature where `1 + q >= FAR 2 l1`.
pub(super) const FAR: f64 = if WIDE { 3.2e7 } else { 3.2e5 };

/// Trapezoid step in `t = ln w`.
pub(super) const H: f64 = if WIDE { 0.3 } else { 0.5 };
/// Relative truncation tolerance at the top of the trapezoid rule.
const EPS_T: f64 = if WIDE { 1e-12 } else { 1e-7 };
/// Number of terms of the series correction below the first trapezoid node.
const N_SER: usize = if WIDE { 8 } else { 4 };
/// The first node lies at or below `w = Y_LO / (1 + q + 2 l1)` (the series' bound).
const Y_LO: f64 = if WIDE { 0.0437 } else { 0.054 };
/// Nodes per chunk of the trapezoid loop (two SIMD vectors).
const CH: usize = if WIDE { 4 } else { 8 };
/// Length of the node tables: `e^(k H)` stays finite in `F` and covers the widest range
/// (`w` from `Y_LO / 1e32` to `~200`).
const NODES: usize = if WIDE { 320 } else { 176 };

/// `e^(k H)`, `k < NODES`, in `F` (the node ratios).
static RATIO: [F; NODES] = {
    let eh = EXP_H;
    let mut r = [0.0; NODES];
    let mut v = 1.0f64;
    let mut k = 0;
    while k < NODES {
        r[k] = v as F;
        v *= eh;
        k += 1;
    }
    r
};

/// `e^(-k H)`, `k < NODES`, in `f64`: [`exp_f64`] at compile time, so the same bits as the
/// batch lane's [`exp_f64`] of the same argument (a table lookup there is a gather, which
/// stopped its loop from vectorising).
static INV_RATIO: [f64; NODES] = {
    let mut r = [0.0; NODES];
    let mut k = 0;
    while k < NODES {
        r[k] = exp_f64(-H * k as f64);
        k += 1;
    }
    r
};

/// `2 k H`, `k < NODES`, in `F` (`ln` of the squared node ratios).
static LOG2RATIO: [F; NODES] = {
    let mut r = [0.0; NODES];
    let mut k = 0;
    while k < NODES {
        r[k] = (2.0 * H * k as f64) as F;
        k += 1;
    }
    r
};

/// Gauss-Laguerre rule for the weight `v e^-v` (generalised Laguerre, `alpha = 1`): 8 nodes
/// in `f32`, 12 in `f64` (nodes and weights to 17 digits, from 60-digit Newton iterations).
const GL_N: usize = if WIDE { 12 } else { 8 };
const GL8_X: [f64; 8] = [
    0.409_383_573_203_185_14,
    1.384_963_184_803_139_8,
    2.956_254_556_168_862,
    5.181_943_101_040_071,
    8.161_709_688_145_818,
    12.070_055_126_837_154,
    17.249_735_526_148_99,
    24.585_955_243_652_784,
];
const GL8_W: [f64; 8] = [
    0.187_632_541_405_723_66,
    0.438_985_360_731_142_36,
    0.289_996_070_781_313_34,
    0.075_141_384_616_697_34,
    0.007_932_646_648_707_345,
    0.000_308_642_136_813_304_2,
    3.348_958_209_797_096e-6,
    4.721_392_823_193_221e-9,
];
const GL12_X: [f64; 12] = [
    0.282_858_348_239_914_1,
    0.952_326_041_364_613_5,
    2.016_492_138_577_681,
    3.492_354_069_778_025,
    5.405_491_020_015_723,
    7.792_813_940_412_415,
    10.707_388_688_989_091,
    14.227_152_363_789_981,
    18.471_996_634_23,
    23.641_783_752_400_894,
    30.120_058_626_106_346,
    38.889_284_376_095_32,
];
const GL12_W: [f64; 12] = [
    0.101_453_765_665_592_26,
    0.317_699_483_362_918_1,
    0.339_986_271_374_452_8,
    0.179_532_599_439_199_83,
    0.052_031_939_035_328_39,
    0.008_491_617_435_768_904,
    0.000_767_135_797_278_598,
    3.636_209_120_384_354_5e-5,
    8.184_567_007_799_461e-7,
    7.323_154_100_403_232e-9,
    1.839_702_434_421_306e-11,
    5.377_628_522_270_37e-15,
];

const fn table<const N: usize>(src: &[f64]) -> [F; N] {
    let mut out = [0.0; N];
    let mut i = 0;
    while i < N {
        out[i] = src[i] as F;
        i += 1;
    }
    out
}
static GL_X: [F; GL_N] = table(if WIDE { &GL12_X } else { &GL8_X });
static GL_W: [F; GL_N] = table(if WIDE { &GL12_W } else { &GL8_W });
/// Gauss-Laguerre applies where `2 l1 <= GL_RATIO (1 + q)` (item 4).
const GL_RATIO: f64 = if WIDE { 0.01 } else { 0.0177 };
/// ... and where the plateau between the two modes is negligible:
/// `2 l1 (GL_PLATEAU + 1.5 ln(1 + q)) <= 1 + q` (item 4).
const GL_PLATEAU: f64 = if WIDE { 31.5 } else { 20.0 };
/// Below `1 + q = GL_WIDE`, `GL_PLATEAU + 1.5 ln(1 + q) <= 1 / GL_RATIO`.
const GL_WIDE: f64 = if WIDE { 7e19 } else { 2.8e10 };

/// The mixture integral `J` (module docs) as `J / z2^2` for `c_i^2 = v_i^2 / z2` from `(v1^2, v2^2)`, `z2 > 0` and
/// `(2 l1, 2 l2)`, `2 l1 >= 2 l2 >= 0`, finite: `J(c)` itself for `z2 = 1` (a slope), `J / m_z^4`
/// for a normal `m` (`z2 = m_z^2`, `v = T m_xy`), without forming the slope. `> 0` unless it
/// underflows.
#[inline]
pub(super) fn mixture_integral(v1s: f64, v2s: f64, z2: f64, tl1: f64, tl2: f64) -> f64 {
    let beta_m = z2 + v1s + v2s;
    let (far, laguerre) = rule(beta_m, z2, tl1);
    if far {
        return far_tail(beta_m, v1s, v2s, tl1, tl2, z2);
    }
    if laguerre {
        return mixture_integral_laguerre::<false>(beta_m, v1s, v2s, z2, tl1, tl2);
    }
    let iz2 = 1.0 / z2;
    mixture_integral_trapezoid(v1s * iz2, v2s * iz2, tl1, tl2) * iz2 * iz2
}

/// The rule [`mixture_integral`] takes for `beta_m = z2 + v1s + v2s`: `(far, laguerre)`, the far tail where
/// `far`, else Gauss-Laguerre where `laguerre`, else the trapezoid rule. Branch-free (`&`,
/// `|` of compares; shared with the batch lane [`mixture_integral_lane`]).
#[inline(always)]
fn rule(beta_m: f64, z2: f64, tl1: f64) -> (bool, bool) {
    let far = beta_m >= FAR * tl1 * z2;
    // beta = 1 + q = beta_m / z2. Gauss-Laguerre where 2 l1 <= GL_RATIO beta and (item 4) the
    // plateau is negligible, 2 l1 (GL_PLATEAU + 1.5 ln beta) <= beta, which the first implies
    // below beta = GL_WIDE.
    let laguerre = (tl1 * z2 <= GL_RATIO * beta_m)
        & ((beta_m <= GL_WIDE * z2)
            | (tl1 * (GL_PLATEAU + 1.5 * ln_upper(beta_m / z2)) * z2 <= beta_m));
    (far, laguerre)
}

/// Whether [`mixture_integral`] takes the trapezoid rule (neither the far tail nor Gauss-Laguerre).
#[inline(always)]
pub(super) fn takes_trapezoid(v1s: f64, v2s: f64, z2: f64, tl1: f64) -> bool {
    let (far, laguerre) = rule(z2 + v1s + v2s, z2, tl1);
    !(far | laguerre)
}

/// [`mixture_integral`] in lanes (`batch`'s exact Gaussian-filtered GGX): the same operations as [`mixture_integral`], so
/// the same value bit for bit where `ok`. Without `TRAPEZOID` the far tail or
/// Gauss-Laguerre, selected by [`rule`], `ok` false where [`mixture_integral`] takes the trapezoid rule;
/// with `TRAPEZOID` the trapezoid rule alone ([`mixture_integral_trapezoid_lane`], its first chunks), `ok`
/// false where [`mixture_integral`] takes another rule or runs it longer. Two lanes, not one: a select
/// computes every rule it holds for every element, and the trapezoid rule's 24 (`f32`) or 36
/// (`f64`) nodes would cost the elements that do not need them 4 times their own rule.
#[inline(always)]
pub(super) fn mixture_integral_lane<const TRAPEZOID: bool>(
    v1s: f64,
    v2s: f64,
    z2: f64,
    tl1: f64,
    tl2: f64,
) -> (f64, bool) {
    let beta_m = z2 + v1s + v2s;
    let (far, laguerre) = rule(beta_m, z2, tl1);
    if TRAPEZOID {
        let iz2 = 1.0 / z2;
        let (t, ok) = mixture_integral_trapezoid_lane(v1s * iz2, v2s * iz2, tl1, tl2);
        (t * iz2 * iz2, ok & !(far | laguerre))
    } else {
        let v = if far {
            far_tail(beta_m, v1s, v2s, tl1, tl2, z2)
        } else {
            mixture_integral_laguerre::<true>(beta_m, v1s, v2s, z2, tl1, tl2)
        };
        (v, far | laguerre)
    }
}

/// The far-tail series of `J` (item 5) in homogeneous form: for a slope argument
/// (`z2 = 1`, `beta = 1 + q`, `c_i^2`) it is `J`; for a normal `m` (`z2 = m_z^2`,
/// `beta = m_z^2 + |T m_xy|^2`, `c_i^2 = (T m_xy)_i^2`) it is `J / m_z^4`, without forming the
/// slope.
#[inline]
pub(super) fn far_tail(beta: f64, c1s: f64, c2s: f64, tl1: f64, tl2: f64, z2: f64) -> f64 {
    // J = beta^-2 (1 + 12 P z2 / beta^2 - 2 (l1 + l2) z2 / beta), P = l1 c1^2 + l2 c2^2.
    // `P / beta` formed first (`c_i^2 <= beta`): `P` alone overflows for a slope near
    // `1e150` lobe widths, and `ib^2` underflows to `0` there, `0 inf = NaN` (found by fuzzing).
    let ib = 1.0 / beta;
    let p_ib = 0.5 * (tl1 * (c1s * ib) + tl2 * (c2s * ib));
    let ls = 0.5 * (tl1 + tl2);
    ib * ib * (1.0 + z2 * ib * (12.0 * p_ib - 2.0 * ls))
}

/// Gauss-Laguerre in `v = (1 + q) w` (item 4): `J = beta^-2 sum W_k F(v_k / beta)`,
/// `F(w) = exp(sum c_i^2 2 l_i w^2 / p_i) / sqrt(p1 p2)`; homogeneous as [`mixture_integral`]
/// (`beta = beta_m / z2`, `c_i^2 = v_i^2 / z2`; the result is `J / z2^2`). `LANE`: the
/// nodes as straight-line code (for a batch lane), else as a loop; the same operations, so
/// the same value bit for bit.
#[inline(always)]
fn mixture_integral_laguerre<const LANE: bool>(
    beta_m: f64,
    v1s: f64,
    v2s: f64,
    z2: f64,
    tl1: f64,
    tl2: f64,
) -> f64 {
    let ib = 1.0 / beta_m;
    // 2 l_i / beta and c_i^2 2 l_i / beta^2.
    let (t1, t2) = (F::from_f64(tl1 * z2 * ib), F::from_f64(tl2 * z2 * ib));
    let (g1, g2) = (
        F::from_f64(v1s * tl1 * z2 * ib * ib),
        F::from_f64(v2s * tl2 * z2 * ib * ib),
    );
    let c = [t1, t2, g1, g2];
    let mut acc = [0.0; GL_N];
    if LANE {
        // Straight-line code, one node after another (see `unrolled`).
        unrolled!(GL_N, k => acc[k] = laguerre_node(GL_X[k], GL_W[k], c));
    } else {
        // A loop, which LLVM vectorises over the nodes (the scalar path's speed: 27 % slower
        // as straight-line code).
        for (a, (&v, &wt)) in acc.iter_mut().zip(GL_X.iter().zip(GL_W.iter())) {
            *a = laguerre_node(v, wt, c);
        }
    }
    sum_tree(acc).to_f64() * ib * ib
}

/// One node of [`mixture_integral_laguerre`]: `W_k F(v_k / beta)` from `[2 l1 / beta, 2 l2 / beta,
/// c1^2 2 l1 / beta^2, c2^2 2 l2 / beta^2]`.
#[inline(always)]
fn laguerre_node(v: F, wt: F, [t1, t2, g1, g2]: [F; 4]) -> F {
    let p1 = 1.0 + t1 * v;
    let p2 = 1.0 + t2 * v;
    let inv = 1.0 / (p1 * p2);
    let e = v * v * ((g1 * p2 + g2 * p1) * inv);
    wt * exp_poly(e) * m::sqrt(inv)
}

/// `$body` for `$k = 0 .. $n` (`$n <= 12`, the rules' node counts) as straight-line code, not
/// a loop: LLVM does not fully unroll a node loop whose body is as large as a node's (an
/// exponential, a division, a square root), and a loop left inside the batch lane's element
/// loop is the one the loop vectoriser takes (8 nodes of one element per vector instead of an
/// element per lane: the exact Gaussian filter's batch ran at half the scalar loop's time
/// instead of a fraction of it).
macro_rules! unrolled {
    ($n:expr, $k:ident => $body:expr) => {
        unrolled!(@ $n, $k => $body; 0 1 2 3 4 5 6 7 8 9 10 11)
    };
    (@ $n:expr, $k:ident => $body:expr; $($i:literal)*) => {{
        const { assert!($n <= 12) };
        $( if $i < $n { let $k: usize = $i; $body; } )*
    }};
}
use unrolled;

/// The sum of an array by pairwise halving (vector adds, not a serial chain).
#[inline(always)]
pub(super) fn sum_tree<const N: usize>(mut a: [F; N]) -> F {
    let mut n = N;
    while n > 1 {
        let h = n / 2;
        for i in 0..h {
            a[i] += a[i + h];
        }
        if n % 2 == 1 {
            a[0] += a[n - 1];
        }
        n = h;
    }
    a[0]
}

/// The trapezoid rule in `t = ln w` (items 1 to 3): nodes `w_k = w_r e^((k - k0) H)` from the
/// first node at or below `Y_LO / (1 + q + 2 l1)`, the nodes below it summed by the series
/// correction, the exponent evaluated against the reference `w_r = 2 / (1 + q)`, the top
/// truncated by the monotone bound.
#[inline]
fn mixture_integral_trapezoid(c1s: f64, c2s: f64, tl1: f64, tl2: f64) -> f64 {
    let t = Trapezoid::new::<false>(c1s, c2s, tl1, tl2);
    let mut tot = [0.0; CH];
    let mut sum: F = 0.0;
    let mut k = 0;
    while let (Some(rk), Some(lk)) = (
        RATIO[k..].first_chunk::<CH>(),
        LOG2RATIO[k..].first_chunk::<CH>(),
    ) {
        let stop;
        (tot, sum, stop) = t.step::<false>(tot, rk, lk);
        k += CH;
        if stop {
            break;
        }
    }
    t.total(sum, c1s, c2s, tl1, tl2)
}

/// [`mixture_integral_trapezoid`] in lanes: the same set-up, chunks and truncation test, the first
/// [`TRAP_CHUNKS`] chunks as straight-line code, the loop's `break` as a select (the chunks
/// after the one that stops it leave the sums as they were), so the same value bit for bit
/// where `ok`; `ok` is false where the scalar loop runs longer (or the sum is NaN).
#[inline(always)]
#[allow(unused_assignments)] // The last chunk's partial sums are not read again.
fn mixture_integral_trapezoid_lane(c1s: f64, c2s: f64, tl1: f64, tl2: f64) -> (f64, bool) {
    const { assert!(TRAP_CHUNKS * CH <= NODES) };
    let t = Trapezoid::new::<true>(c1s, c2s, tl1, tl2);
    let mut tot = [0.0; CH];
    let mut sum: F = 0.0;
    let mut done = false;
    unrolled!(TRAP_CHUNKS, c => {
        let (rk, lk) = (&RATIO, &LOG2RATIO);
        let at = |r: &'static [F; NODES]| r[c * CH..].first_chunk::<CH>().unwrap_or(&[0.0; CH]);
        let (next, s, stop) = t.step::<true>(tot, at(rk), at(lk));
        if !done {
            tot = next;
            sum = s;
        }
        done |= stop;
    });
    (t.total(sum, c1s, c2s, tl1, tl2), done)
}

/// Chunks of the first stage of [`mixture_integral_trapezoid_first`] and [`mixture_integral_trapezoid_rest`]: what most
/// elements of a heavily filtered lobe need (the batch bench's heavy kernel `2 l1 = 1`: 78 %
/// of its trapezoid elements stop after 2 chunks of 8 in `f32`, the others after 3; in `f64`
/// they stop after 7 or 8 chunks of 4 ([`TRAP_CHUNKS`]), and a first stage of 7 is faster
/// than one stage of all of them, `benches/batch.rs`).
const FIRST_CHUNKS: usize = if WIDE { 7 } else { 2 };

/// Values of `F` in a [`TrapezoidState`]: the partial sums after the first chunks (`CH`).
pub(crate) const STATE_F: usize = CH;

/// What the trapezoid lane hands from its first [`FIRST_CHUNKS`] chunks to the rest
/// (`batch`'s staged second lane: the elements that need more chunks are gathered, so that
/// the others do not compute them). The rest recomputes the set-up (`f64`): handing it over
/// too held the first stage's `f32` loop to half its vector width (its widest values are
/// then `f64` stores), which cost more than the set-up of the few elements that continue.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TrapezoidState {
    /// The partial sums.
    pub(crate) f: [F; STATE_F],
}

/// [`mixture_integral_lane`]`::<true>` in two stages, its first: the set-up and the first [`FIRST_CHUNKS`]
/// chunks. Returns `(value, ok, more, state)`: where `more` is false, `(value, ok)` is
/// [`mixture_integral_lane`]`::<true>`'s, bit for bit; where it is true (the trapezoid rule's element, not
/// stopped yet) [`mixture_integral_trapezoid_rest`] finishes from `state`.
#[inline(always)]
pub(super) fn mixture_integral_trapezoid_first(
    v1s: f64,
    v2s: f64,
    z2: f64,
    tl1: f64,
    tl2: f64,
) -> (f64, bool, bool, TrapezoidState) {
    const { assert!(FIRST_CHUNKS < TRAP_CHUNKS) };
    let beta_m = z2 + v1s + v2s;
    let (far, laguerre) = rule(beta_m, z2, tl1);
    let iz2 = 1.0 / z2;
    let (c1s, c2s) = (v1s * iz2, v2s * iz2);
    let t = Trapezoid::new::<true>(c1s, c2s, tl1, tl2);
    let mut tot = [0.0; CH];
    let mut sum: F = 0.0;
    let mut done = false;
    unrolled!(FIRST_CHUNKS, c => {
        let (next, s, stop) = t.step::<true>(tot, chunk(&RATIO, c), chunk(&LOG2RATIO, c));
        if !done {
            tot = next;
            sum = s;
        }
        done |= stop;
    });
    let other = far | laguerre;
    let v = t.total(sum, c1s, c2s, tl1, tl2) * iz2 * iz2;
    (v, done & !other, !(done | other), TrapezoidState { f: tot })
}

/// The second stage of [`mixture_integral_trapezoid_first`] (same arguments, and its state): the set-up
/// again, then the chunks after the first ones from the partial sums, the truncation test's
/// `break` as a select as in [`mixture_integral_trapezoid_lane`]. `(value, ok)` as [`mixture_integral_lane`]`::<true>`'s
/// for an element that [`mixture_integral_trapezoid_first`] did not finish, bit for bit.
#[inline(always)]
#[allow(unused_assignments)] // The last chunk's partial sums are not read again.
pub(super) fn mixture_integral_trapezoid_rest(
    v1s: f64,
    v2s: f64,
    z2: f64,
    tl1: f64,
    tl2: f64,
    st: &TrapezoidState,
) -> (f64, bool) {
    let iz2 = 1.0 / z2;
    let (c1s, c2s) = (v1s * iz2, v2s * iz2);
    let t = Trapezoid::new::<true>(c1s, c2s, tl1, tl2);
    let mut tot = st.f;
    let mut sum: F = 0.0;
    let mut done = false;
    unrolled!(TRAP_CHUNKS, c => {
        if c >= FIRST_CHUNKS {
            let (next, s, stop) = t.step::<true>(tot, chunk(&RATIO, c), chunk(&LOG2RATIO, c));
            if !done {
                tot = next;
                sum = s;
            }
            done |= stop;
        }
    });
    (t.total(sum, c1s, c2s, tl1, tl2) * iz2 * iz2, done)
}

/// Chunk `c` of a node table (zeros past its end, which the lane never reaches).
#[inline(always)]
fn chunk(r: &'static [F; NODES], c: usize) -> &'static [F; CH] {
    r[c * CH..].first_chunk::<CH>().unwrap_or(&[0.0; CH])
}

/// Chunks of [`mixture_integral_trapezoid_lane`]: the longest run of the rule on the lobes a filter meets
/// (measured, the batch bench's heavy kernel `2 l1 = 1` over its realistic half vectors: 2
/// or 3 chunks of 8 in `f32`, 7 or 8 of 4 in `f64`); the lane flags what takes longer.
const TRAP_CHUNKS: usize = if WIDE { 9 } else { 3 };

/// The set-up of [`mixture_integral_trapezoid`] for one argument `(c1^2, c2^2)`: the node constants of
/// [`trapezoid_chunk`], the truncation test's and the series correction's.
struct Trapezoid {
    /// `[v0, 2 l1 w_r, 2 l2 w_r, w_r, k1, k2, l0]` ([`trapezoid_chunk`]).
    c: [F; 7],
    w_r: f64,
    w_first: f64,
    scale: f64,
    stop: f64,
}

impl Trapezoid {
    /// The set-up; `LANE`: without table lookups (the same values).
    #[inline(always)]
    fn new<const LANE: bool>(c1s: f64, c2s: f64, tl1: f64, tl2: f64) -> Self {
        let beta = 1.0 + c1s + c2s;
        let ib = 1.0 / beta;
        let w_r = 2.0 * ib;
        // k0 H >= ln(w_r / w_lo), w_lo = Y_LO / (beta + 2 l1): the first node w_r e^(-k0 H)
        // is at or below w_lo.
        let k0 = ceil_pos(ln_upper(2.0 / Y_LO * (beta + tl1) * ib) * (1.0 / H));
        let k0 = k0.min((NODES - 1) as f64);
        // e^(-k0 H): the table, or in a lane the same polynomial ([`INV_RATIO`]).
        let v0 = if LANE {
            exp_f64(-H * k0)
        } else {
            INV_RATIO[k0 as usize]
        };
        let w_first = w_r * v0;
        // Reference exponent x_r = -w_r - E(w_r) (f64): every node's exponent is taken
        // against it, E(w) - E(w_r) = sum c_i^2 (w - w_r) / (p_i(w) p_i(w_r)), without
        // cancellation.
        let (pr1, pr2) = (1.0 + tl1 * w_r, 1.0 + tl2 * w_r);
        let ipr = w_r / (pr1 * pr2);
        let (k1, k2) = (c1s * pr2 * ipr, c2s * pr1 * ipr);
        let x_r = -w_r - k1 - k2;
        let scale = w_r * w_r * exp_f64(x_r);
        // Per node, with v = w / w_r = e^((k - k0) H):
        // g(t) / scale = exp(2 ln v - (v - 1)(w_r + (k1 p2 + k2 p1) / (p1 p2))) / sqrt(p1 p2),
        // p_i = 1 + (2 l_i w_r) v.
        let c = [
            F::from_f64(v0),
            F::from_f64(tl1 * w_r),
            F::from_f64(tl2 * w_r),
            F::from_f64(w_r),
            F::from_f64(k1),
            F::from_f64(k2),
            F::from_f64(-2.0 * H * k0),
        ];
        Self {
            c,
            w_r,
            w_first,
            scale,
            stop: EPS_T * H * w_r * w_r,
        }
    }

    /// One chunk of nodes (ratios `rk`, their logarithms `lk`) added to the partial sums
    /// `tot`: `(tot, their sum, stop)`, `stop` where the truncation test (item 3: the nodes
    /// above the last sum to at most `g_last b / w_last^2`) ends the rule or the sum is NaN.
    /// `LANE`: the nodes as straight-line code (see [`mixture_integral_laguerre`]).
    #[inline(always)]
    fn step<const LANE: bool>(
        &self,
        mut tot: [F; CH],
        rk: &[F; CH],
        lk: &[F; CH],
    ) -> ([F; CH], F, bool) {
        let acc = trapezoid_chunk::<LANE>(self.c, rk, lk);
        for (t, a) in tot.iter_mut().zip(acc.iter()) {
            *t += *a;
        }
        let sum = sum_tree(tot);
        let last = acc[CH - 1].to_f64();
        let vl = (self.c[0] * rk[CH - 1]).to_f64();
        let wl = vl * self.w_r;
        let b = if wl >= 2.0 { 1.0 + wl } else { 7.47 };
        let s = sum.to_f64();
        (tot, sum, (last * b <= self.stop * s * vl * vl) | s.is_nan())
    }

    /// `J` from the nodes' sum and the series correction below the first node.
    #[inline(always)]
    fn total(&self, sum: F, c1s: f64, c2s: f64, tl1: f64, tl2: f64) -> f64 {
        H * (sum.to_f64() * self.scale + series_below(c1s, c2s, tl1, tl2, self.w_first))
    }
}

/// One chunk of [`mixture_integral_trapezoid`]'s nodes: `g(t) / scale` at `v = v0 r_k` (see there), from the
/// constants `[v0, 2 l1 w_r, 2 l2 w_r, w_r, k1, k2, l0]`. `LANE`: straight-line code.
#[inline(always)]
fn trapezoid_chunk<const LANE: bool>(c: [F; 7], rk: &[F; CH], lk: &[F; CH]) -> [F; CH] {
    let mut acc = [0.0; CH];
    if LANE {
        unrolled!(CH, j => acc[j] = trapezoid_node(c, rk[j], lk[j]));
    } else {
        for j in 0..CH {
            acc[j] = trapezoid_node(c, rk[j], lk[j]);
        }
    }
    acc
}

/// One node of [`trapezoid_chunk`].
#[inline(always)]
fn trapezoid_node(c: [F; 7], rk: F, lk: F) -> F {
    let [v0, t1, t2, fw, fk1, fk2, l0] = c;
    let v = v0 * rk;
    let p1 = 1.0 + t1 * v;
    let p2 = 1.0 + t2 * v;
    let inv = 1.0 / (p1 * p2);
    let a = fw + (fk1 * p2 + fk2 * p1) * inv;
    let x = (l0 + lk) - (v - 1.0) * a;
    exp_poly(x) * m::sqrt(inv)
}

/// `ceil` for the small positive values of the node offset (no `ceil` in `core`).
#[inline(always)]
pub(super) fn ceil_pos(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t < x { t + 1.0 } else { t }
}

/// `e^H`.
const EXP_H: f64 = if WIDE {
    1.349_858_807_576_003_2
} else {
    1.648_721_270_700_128_2
};

/// `1 / (e^(m H) - 1)`, `m = 2 .. N_SER + 1`: the geometric sums of the series correction.
const GEOM: [f64; N_SER] = {
    let mut g = [0.0; N_SER];
    let mut e = EXP_H * EXP_H;
    let mut n = 0;
    while n < N_SER {
        g[n] = 1.0 / (e - 1.0);
        e *= EXP_H;
        n += 1;
    }
    g
};

/// `1 / n`.
const INV_N: [f64; N_SER + 1] = {
    let mut r = [0.0; N_SER + 1];
    let mut n = 1;
    while n <= N_SER {
        r[n] = 1.0 / n as f64;
        n += 1;
    }
    r
};

/// The nodes below `w_first` (item 2): `sum_k w_k^2 phi(w_k)` over `w_k = w_first e^(-k H)`,
/// `k >= 1`, with `phi = exp(-w - E(w)) / sqrt(p1 p2) = sum a_n w^n` truncated after `N_SER`
/// terms: `sum_n a_n w_first^(n + 2) / (e^((n + 2) H) - 1)`.
#[inline(always)]
#[allow(unused_assignments)] // The last term's power of `w_first` and `-2 l_i` are not read.
fn series_below(c1s: f64, c2s: f64, tl1: f64, tl2: f64, w_first: f64) -> f64 {
    // ln phi = sum_n b_n w^n: b_n = -sum_i c_i^2 (-2 l_i)^(n-1) + sum_i (-2 l_i)^n / (2 n)
    // (from -E and -ln(p1 p2) / 2), and b_1 -= 1 (from -w).
    // Straight-line code (`unrolled`): loops here, inside the batch lane's element loop,
    // stopped it from vectorising.
    let mut b = [0.0; N_SER];
    let (mut m1, mut m2) = (1.0, 1.0);
    unrolled!(N_SER, n => {
        b[n] = -(c1s * m1 + c2s * m2) - (tl1 * m1 + tl2 * m2) * (0.5 * INV_N[n + 1]);
        m1 *= -tl1;
        m2 *= -tl2;
    });
    b[0] -= 1.0;
    // phi = exp(sum b_n w^n): a_0 = 1, n a_n = sum_{j=1..n} j b_j a_(n-j).
    let mut a = [0.0; N_SER];
    a[0] = 1.0;
    let mut tail = GEOM[0];
    let mut wp = w_first;
    unrolled!(N_SER, n => if n >= 1 {
        let mut s = 0.0;
        // `saturating_sub`: the indices of the skipped terms (`j = 0`, `j > n`) are never
        // formed as an underflow.
        unrolled!(N_SER, j => if j >= 1 && j <= n {
            s += j as f64 * b[j.saturating_sub(1)] * a[n.saturating_sub(j)];
        });
        a[n] = s * INV_N[n];
        tail += a[n] * wp * GEOM[n];
        wp *= w_first;
    });
    tail * w_first * w_first
}

// ---------------------------------------------------------------------------------------------
// Lambda: Gauss-Hermite for a kernel narrow against the lobe's scale at the view, the
// trapezoid rule in the sinh variable otherwise (item 6 of the module docs).
// ---------------------------------------------------------------------------------------------

/// Gauss-Hermite rule for the standard normal density, full node set (8 nodes in `f32`, 10 in
/// `f64`, to 17 digits from 60-digit Newton iterations).
const GH_N: usize = if WIDE { 10 } else { 8 };
const GH8_X: [f64; 4] = [
    0.539_079_811_351_375_1,
    1.636_519_042_435_108,
    2.802_485_861_287_541_6,
    4.144_547_186_125_894_5,
];
const GH8_W: [f64; 4] = [
    0.373_012_257_679_077_36,
    0.117_239_907_661_759_01,
    0.009_635_220_120_788_266,
    0.000_112_614_538_375_367_77,
];
const GH10_X: [f64; 5] = [
    0.484_935_707_515_497_64,
    1.465_989_094_391_158_2,
    2.484_325_841_638_954_6,
    3.581_823_483_551_927,
    4.859_462_828_332_312,
];
const GH10_W: [f64; 5] = [
    0.344_642_334_932_019_07,
    0.135_483_702_980_267_74,
    0.019_111_580_500_770_286,
    0.000_758_070_934_312_217_7,
    4.310_652_630_718_287e-6,
];
/// The symmetric rule unfolded: `(x, w)` for `-x_k` then `x_k`.
const fn gh_full(x: &[f64], w: &[f64]) -> ([F; GH_N], [F; GH_N]) {
    let (mut xs, mut ws) = ([0.0; GH_N], [0.0; GH_N]);
    let h = GH_N / 2;
    let mut i = 0;
    while i < h {
        xs[i] = -x[i] as F;
        ws[i] = w[i] as F;
        xs[h + i] = x[i] as F;
        ws[h + i] = w[i] as F;
        i += 1;
    }
    (xs, ws)
}
static GH: ([F; GH_N], [F; GH_N]) = if WIDE {
    gh_full(&GH10_X, &GH10_W)
} else {
    gh_full(&GH8_X, &GH8_W)
};
/// Gauss-Hermite applies where `delta_s^2 = qs / (qa + oz^2) <= GH_MAX` (item 6).
const GH_MAX: f64 = 0.01;
/// The sinh rule's step: `min(S_MAX, S_COEF sqrt(delta_s))` (item 6).
const S_MAX: f64 = if WIDE { 0.16 } else { 0.25 };
const S_COEF: f64 = if WIDE { 0.17 } else { 0.25 };
/// The sinh rule's relative truncation tolerance at each end.
const S_EPS: f64 = if WIDE { 1e-13 } else { 1e-8 };
/// Upper bound on the sinh rule's nodes in each direction (never reached: a safety net).
const S_MAX_NODES: usize = 4096;

/// Smith `Lambda` of the filtered lobe (item 6) for `qa = o^T A o > 0`, `qs = o^T Sigma o > 0`
/// and `oz = |o_z| > 0` (unit `o`): `Lambda = E[h(oz - Z)] / (2 oz)`, `Z ~ N(0, qs)`,
/// `h(y) = sqrt(qa + y^2) - y`.
pub(super) fn lambda(qa: f64, qs: f64, oz: f64) -> f64 {
    let ds2 = qs / (qa + oz * oz);
    if ds2 <= GH_MAX {
        lambda_hermite(qa, qs, oz)
    } else {
        lambda_sinh(qa, qs, oz, ds2)
    }
}

/// Gauss-Hermite in units of `sqrt(qa)`: `Lambda = sum W_k h(z0 - sigma x_k) / (2 z0)`,
/// `z0 = oz / sqrt(qa)`, `sigma = sqrt(qs / qa)`, `h(y) = sqrt(1 + y^2) - y`, evaluated as
/// `1 / (sqrt(1 + y^2) + y)` for `y >= 0` (no cancellation; `0` once `y^2` overflows, where
/// `Lambda` is below the smallest positive `F`).
#[inline]
fn lambda_hermite(qa: f64, qs: f64, oz: f64) -> f64 {
    let iq = 1.0 / qa;
    let z0 = oz * m::sqrt(iq);
    let (fz, fs) = (F::from_f64(z0), F::from_f64(m::sqrt(qs * iq)));
    let mut acc = [0.0; GH_N];
    for (a, (&x, &w)) in acc.iter_mut().zip(GH.0.iter().zip(GH.1.iter())) {
        let y = fz - fs * x;
        let t = m::sqrt(1.0 + y * y) + y.abs();
        let pos = (y >= 0.0) as u32 as F;
        *a = w * (pos / t + (1.0 - pos) * t);
    }
    sum_tree(acc).to_f64() / (2.0 * z0)
}

/// The trapezoid rule in `s`, `y = sqrt(qa) sinh s`:
/// `Lambda = qa / (4 oz) integral phi_sigma(oz - sqrt(qa) sinh s) (1 + e^-2s) ds`, nodes
/// `s0 + k h` with `sinh s0 = oz / sqrt(qa)`, `oz - sqrt(qa) sinh(s0 + d) =
/// -sqrt(qa) 2 cosh(s0 + d / 2) sinh(d / 2)` (no cancellation), outward from `s0` in both
/// directions until the truncation bound holds; in `f64` for both lobes.
fn lambda_sinh(qa: f64, qs: f64, oz: f64, ds2: f64) -> f64 {
    let rq = m::sqrt(qa);
    let root = oz + m::sqrt(qa + oz * oz);
    let (e0, ie0) = (root / rq, rq / root);
    let h = S_MAX.min(S_COEF * m::sqrt(m::sqrt(ds2)));
    // The grid ratio: its error compounds over the nodes (`(1 + e^-2s) ~ e^-2s` at the k-th
    // node carries it `4k` times), so to the last bit in `f64` (the library exp); the
    // polynomial's `1.4e-14` is ample for the `f32` rule.
    let t1 = if WIDE {
        m::exp(0.5 * h)
    } else {
        exp_f64(0.5 * h)
    };
    let it1 = 1.0 / t1;
    let i2s2 = 0.5 / qs;
    // |x| sqrt(qa) h / qs beyond which the terms fall by half per node (module docs).
    let c_up = core::f64::consts::LN_2 * qs / (rq * h);
    let c_down = (2.0 * h + core::f64::consts::LN_2) * qs / (rq * h);
    let e2 = ie0 * ie0;
    // One direction: nodes T = e^(d/2) = t0 step^k, with 1 / T by the reciprocal recurrence.
    let run = |t0: f64, it0: f64, step: f64, istep: f64, up: bool, sum: f64| -> f64 {
        const C: usize = SINH_CH;
        let (mut pw, mut ipw) = ([1.0; C], [1.0; C]);
        for i in 1..C {
            pw[i] = pw[i - 1] * step;
            ipw[i] = ipw[i - 1] * istep;
        }
        let (step_c, istep_c) = (pw[C - 1] * step, ipw[C - 1] * istep);
        let (mut t, mut it) = (t0, it0);
        let mut total = sum;
        let mut n = 0;
        loop {
            let (f, xs) = sinh_chunk([t, it, rq, e0, ie0, i2s2, e2], &pw, &ipw);
            total += sum_tree(f).to_f64();
            t *= step_c;
            it *= istep_c;
            n += C;
            let (x, fl) = (xs[C - 1], f[C - 1].to_f64());
            let done = if up { -x >= c_up } else { x >= c_down };
            if (done && fl <= S_EPS * total) || n >= S_MAX_NODES || total.is_nan() {
                return total;
            }
        }
    };
    let up = run(1.0, 1.0, t1, it1, true, 0.0);
    let all = run(it1, t1, it1, t1, false, up);
    let norm = h * qa / (4.0 * oz * m::sqrt(qs * core::f64::consts::TAU));
    all * norm
}

/// Nodes per chunk of the sinh rule.
const SINH_CH: usize = 8;

/// One chunk of [`lambda_sinh`]'s nodes: `(f, x)` at `T = t p_i`, `1 / T = it ip_i`, from the
/// constants `[t, it, sqrt(qa), e^s0, e^-s0, 1 / (2 qs), e^-2s0]`: the grid and the Gaussian's
/// argument in `f64`, its exponential in the lobe's precision (an argument of magnitude `X`
/// rounded to `F` costs `X eps_F` relative, `< 1e-6` where the terms matter).
#[inline(always)]
fn sinh_chunk(
    c: [f64; 7],
    pw: &[f64; SINH_CH],
    ipw: &[f64; SINH_CH],
) -> ([F; SINH_CH], [f64; SINH_CH]) {
    let [t, it, rq, e0, ie0, i2s2, e2] = c;
    let (mut arg, mut fac, mut xs) = ([0.0; SINH_CH], [0.0; SINH_CH], [0.0; SINH_CH]);
    for i in 0..SINH_CH {
        let (tt, itt) = (t * pw[i], it * ipw[i]);
        let x = -0.5 * rq * (e0 * tt + ie0 * itt) * (tt - itt);
        let it2 = itt * itt;
        arg[i] = F::from_f64(-x * x * i2s2);
        fac[i] = F::from_f64(1.0 + e2 * it2 * it2);
        xs[i] = x;
    }
    let mut f = [0.0; SINH_CH];
    for i in 0..SINH_CH {
        f[i] = exp_poly(arg[i]) * fac[i];
    }
    (f, xs)
}

// ---------------------------------------------------------------------------------------------
// The visible-normal sampler's component weights.
// ---------------------------------------------------------------------------------------------

/// Components of the visible-normal sampler: `w_k = exp(SAMPLE_T0 + k / 2)`, `k < SAMPLE_N`,
/// from `w = 8.3e-7` to `w = 39`.
pub(super) const SAMPLE_N: usize = 36;
/// `ln w_0` of the sampler's grid.
pub(crate) const SAMPLE_T0: f64 = -14.0;

/// `(w_k, W_k = w_k e^-w_k / 2)` of the sampler's grid (the trapezoid rule in `ln w`, step
/// `1/2`, of `e^-w dw`), in `F`.
static SAMPLE_GRID: ([F; SAMPLE_N], [F; SAMPLE_N]) = {
    let (mut w, mut wt) = ([0.0; SAMPLE_N], [0.0; SAMPLE_N]);
    // e^-14 and e^(1/2) to 17 digits; e^-w by its Taylor series (const context has no exp).
    let mut x = 8.315_287_191_035_679e-7f64;
    let mut k = 0;
    while k < SAMPLE_N {
        let mut e = 1.0f64;
        let mut term = 1.0f64;
        let mut n = 1;
        // e^-x = 1 / e^x, e^x = sum x^n / n! (x <= 40: 160 terms reach 1e-17 relative).
        while n < 160 {
            term *= x / n as f64;
            e += term;
            n += 1;
        }
        w[k] = x as F;
        wt[k] = (0.5 * x / e) as F;
        x *= 1.648_721_270_700_128_2;
        k += 1;
    }
    (w, wt)
};

/// Beckmann's `Lambda(a) = (e^-a^2 / (a sqrt(pi)) - erfc(a)) / 2` with the Chebyshev fit of
/// `erfc` of Numerical Recipes (section 6.2, `erfcc`: `erfc(a) = t exp(-a^2 + P(t))`,
/// `t = 1 / (1 + a / 2)`, relative error below `1.2e-7` for every `a >= 0`), in `F`: error
/// below `2.1e-7 (1 + Lambda)` in `f32`, `1.9e-8 (1 + Lambda)` in `f64` (unit test below), the
/// relative error of the sampler's weights `1 + Lambda`. For `a > 0`; `a` far below
/// `1 / F::MAX` overflows.
#[inline(always)]
pub(crate) fn beckmann_lambda_fast(a: F) -> F {
    let t = 1.0 / (1.0 + 0.5 * a);
    // P(t) by Estrin's scheme (depth 8 against 18 for Horner).
    const P: [f64; 10] = [
        -1.265_512_23,
        1.000_023_68,
        0.374_091_96,
        0.096_784_18,
        -0.186_288_06,
        0.278_868_07,
        -1.135_203_98,
        1.488_515_87,
        -0.822_152_23,
        0.170_872_77,
    ];
    let c = |i: usize| P[i] as F;
    let (t2, t4) = (t * t, (t * t) * (t * t));
    let p01 = c(0) + t * c(1);
    let p23 = c(2) + t * c(3);
    let p45 = c(4) + t * c(5);
    let p67 = c(6) + t * c(7);
    let p89 = c(8) + t * c(9);
    let p = (p01 + p23 * t2) + (p45 + p67 * t2) * t4 + p89 * (t4 * t4);
    let e = exp_poly(-a * a);
    const INV_SQRT_PI: F = 0.564_189_583_547_756_3_f64 as F;
    (0.5 * e * (INV_SQRT_PI / a - t * exp_poly(p))).max(0.0)
}

/// Draws the sampler's component (module docs, sampling) from the weights
/// `W_k (1 + Lambda_k(o))`, `Lambda_k` the Beckmann `Lambda` of roughness `A / w_k + 2 Sigma`,
/// for `qa = o^T A o`, `qs = o^T Sigma o`, `oz = o_z` of a unit `o` with `oz > 0`, by inverting
/// the cumulative weights at `u` in `[0, 1)`: the index and the remainder rescaled to
/// `[0, 1]`.
pub(crate) fn sample_component(qa: f64, qs: f64, oz: f64, u: f64) -> (usize, f64) {
    // a_k = oz / sqrt(qa / w_k + 2 qs), bounded below (oz ~ 0: Lambda ~ 1 / a; the largest
    // weight then dominates and stays finite).
    let (fqa, fqs, foz) = (F::from_f64(qa), F::from_f64(2.0 * qs), F::from_f64(oz));
    let floor: F = if WIDE { 1e-250 } else { 1e-30 };
    let mut wts = [0.0; SAMPLE_N];
    for (o, (&w, &wt)) in wts
        .iter_mut()
        .zip(SAMPLE_GRID.0.iter().zip(SAMPLE_GRID.1.iter()))
    {
        let a = (foz * m::sqrt(w / (fqa + fqs * w))).max(floor);
        *o = wt * (1.0 + beckmann_lambda_fast(a));
    }
    let target = u * sum_tree(wts).to_f64();
    let mut acc = 0.0;
    for (i, &p) in wts.iter().enumerate() {
        let p = p.to_f64();
        if target < acc + p || i == SAMPLE_N - 1 {
            let ux = if p > 0.0 {
                ((target - acc) / p).clamp(0.0, 1.0)
            } else {
                0.5
            };
            return (i, ux);
        }
        acc += p;
    }
    (SAMPLE_N - 1, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_beckmann_lambda_against_libm() {
        // Absolute error against the f64 formula with libm's erfc, relative to 1 + Lambda.
        let mut worst = 0.0f64;
        for i in 1..200_000 {
            let a = i as f64 * 5e-5;
            let exact = 0.5 * ((-a * a).exp() / (a * core::f64::consts::PI.sqrt()) - libm::erfc(a));
            let got = beckmann_lambda_fast(a as F) as f64;
            worst = worst.max((got - exact.max(0.0)).abs() / (1.0 + exact));
        }
        println!("fast beckmann lambda worst {worst:e}");
        assert!(worst < if WIDE { 2.5e-8 } else { 2.5e-7 }, "{worst:e}");
    }

    /// The trapezoid rule's lane against its loop: the same bits wherever the lane does not
    /// flag; every element of a kernel as wide as the lobe (`2 l1 = 1`, the batch bench's
    /// heavy kernel) taken by the lane up to `1 + q = 10^3`, elements of the widest kernels
    /// (`2 l1 = 100`, more chunks) flagged, and each chunk count up to `TRAP_CHUNKS` met.
    #[test]
    fn trapezoid_lane_matches_loop() {
        let (mut taken, mut flagged) = (0usize, 0usize);
        let mut chunks = [0usize; TRAP_CHUNKS + 1];
        for &tl1 in &[0.02, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0] {
            for &r in &[1.0, 0.5, 0.1, 0.0] {
                let tl2 = tl1 * r;
                for i in 0..200 {
                    let q = 10f64.powf(-4.0 + 7.0 * i as f64 / 199.0);
                    for &split in &[1.0, 0.7, 0.2, 0.0] {
                        let (c1s, c2s) = (q * split, q * (1.0 - split));
                        let want = mixture_integral_trapezoid(c1s, c2s, tl1, tl2);
                        let (got, ok) = mixture_integral_trapezoid_lane(c1s, c2s, tl1, tl2);
                        if ok {
                            assert_eq!(got.to_bits(), want.to_bits(), "{c1s} {c2s} {tl1} {tl2}");
                            taken += 1;
                            // The chunk the loop stops at: the first whose partial sums end it.
                            let t = Trapezoid::new::<false>(c1s, c2s, tl1, tl2);
                            let mut tot = [0.0; CH];
                            for c in 0..TRAP_CHUNKS {
                                let at = |r: &[F; NODES]| *r[c * CH..].first_chunk::<CH>().unwrap();
                                let stop;
                                (tot, _, stop) = t.step::<false>(tot, &at(&RATIO), &at(&LOG2RATIO));
                                if stop {
                                    chunks[c + 1] += 1;
                                    break;
                                }
                            }
                        } else {
                            if tl1 == 1.0 && q <= 1e3 {
                                panic!("flagged {c1s} {c2s} {tl1} {tl2}");
                            }
                            flagged += 1;
                        }
                    }
                }
            }
        }
        println!("trapezoid lane: {taken} taken, {flagged} flagged, stops per chunk {chunks:?}");
        assert!(flagged > 0);
        assert!(chunks[1..].iter().filter(|&&c| c > 0).count() >= TRAP_CHUNKS.min(2));
    }

    /// The trapezoid lane in two stages (`mixture_integral_trapezoid_first`, then `mixture_integral_trapezoid_rest` where
    /// it leaves the element unfinished) equals the one-pass lane `mixture_integral_lane::<true>`, value and
    /// flag, bit for bit, on the arguments of a normal (`z2 < 1`) and a slope (`z2 = 1`),
    /// every rule's region included; both outcomes of the first stage occur.
    #[test]
    fn trapezoid_stages_match_lane() {
        let (mut first, mut rest) = (0usize, 0usize);
        for &tl1 in &[0.02, 0.1, 0.3, 1.0, 3.0, 10.0] {
            for &r in &[1.0, 0.3, 0.0] {
                let tl2 = tl1 * r;
                for i in 0..120 {
                    let q = 10f64.powf(-4.0 + 7.0 * i as f64 / 119.0);
                    for &(split, z2) in &[(1.0, 1.0), (0.6, 0.8), (0.1, 0.3), (0.0, 1.0)] {
                        let (v1s, v2s) = (q * split * z2, q * (1.0 - split) * z2);
                        let (want, want_ok) = mixture_integral_lane::<true>(v1s, v2s, z2, tl1, tl2);
                        let (v, ok, more, st) =
                            mixture_integral_trapezoid_first(v1s, v2s, z2, tl1, tl2);
                        let (got, got_ok) = if more {
                            rest += 1;
                            mixture_integral_trapezoid_rest(v1s, v2s, z2, tl1, tl2, &st)
                        } else {
                            first += 1;
                            (v, ok)
                        };
                        assert_eq!(got_ok, want_ok, "{v1s} {v2s} {z2} {tl1} {tl2}");
                        if want_ok {
                            assert_eq!(got.to_bits(), want.to_bits(), "{v1s} {v2s} {z2} {tl1}");
                        }
                    }
                }
            }
        }
        assert!(first > 0 && rest > 0, "{first} {rest}");
    }

    #[test]
    fn ln_upper_bounds_ln() {
        for i in 0..100_000 {
            let x = 1.0 + (i as f64) * 1.37e-3 * (1.0 + i as f64);
            let (u, l) = (ln_upper(x), x.ln());
            assert!(
                u >= l && u - l <= 1.0 - core::f64::consts::LN_2 + 1e-12,
                "{x}"
            );
        }
    }
}
