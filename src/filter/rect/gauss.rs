//! The Gauss-Legendre rules and their tiers, shared by the rectangle integral
//! ([`super::p22_rect`]) and the box lobe's `Lambda` and samplers: which rule an axis of half
//! length `H` gets at distance `L` from the integrand's nearest complex singularity, per
//! precision (the table and the measured errors are in the module docs of [`super`]).

use super::F;

/// Whether `F` is `f64`: the tiers then aim at `1e-13` instead of `1e-9` (module docs).
pub(crate) const WIDE: bool = F::MANTISSA_DIGITS > 24;
/// Upper ratios `H / L` of the Gauss-Legendre tiers 2, 4, 6, 8 and 10 points, per precision
/// (module docs, "Tiers"); the closed form above the last.
pub(crate) const TAU: [f64; 5] = if WIDE {
    [3e-4, 0.02, 0.08, 0.18, 0.25]
} else {
    [0.01, 0.1, 0.25, 0.25, 0.25]
};
/// 2-point Gauss-Legendre node on `[-1, 1]` (`1 / sqrt 3`); weights `1/2` each for a mean.
pub(crate) const GL2_X: f64 = 0.577_350_269_189_625_8;
/// 4-point Gauss-Legendre nodes on `[-1, 1]` (positive halves).
pub(crate) const GL4_X: [f64; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
/// 4-point Gauss-Legendre weights, halved so that the rule averages over `[-1, 1]`.
pub(crate) const GL4_W: [f64; 2] = [0.326_072_577_431_273_07, 0.173_927_422_568_726_93];
/// 6-point Gauss-Legendre nodes on `[-1, 1]` (positive halves).
pub(crate) const GL6_X: [f64; 3] = [
    0.238_619_186_083_196_9,
    0.661_209_386_466_264_5,
    0.932_469_514_203_152,
];
/// 6-point Gauss-Legendre weights, halved.
pub(crate) const GL6_W: [f64; 3] = [
    0.233_956_967_286_345_5,
    0.180_380_786_524_069_3,
    0.085_662_246_189_585_2,
];
/// 8-point Gauss-Legendre nodes on `[-1, 1]` (positive halves; `f64` tiers only).
pub(crate) const GL8_X: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_2,
];
/// 8-point Gauss-Legendre weights, halved.
pub(crate) const GL8_W: [f64; 4] = [
    0.181_341_891_689_181,
    0.156_853_322_938_943_64,
    0.111_190_517_226_687_24,
    0.050_614_268_145_188_13,
];
/// 10-point Gauss-Legendre nodes on `[-1, 1]` (positive halves; `f64` tiers only).
pub(crate) const GL10_X: [f64; 5] = [
    0.148_874_338_981_631_2,
    0.433_395_394_129_247_2,
    0.679_409_568_299_024_4,
    0.865_063_366_688_984_5,
    0.973_906_528_517_171_7,
];
/// 10-point Gauss-Legendre weights, halved.
pub(crate) const GL10_W: [f64; 5] = [
    0.147_762_112_357_376_44,
    0.134_633_359_654_998_18,
    0.109_543_181_257_991_02,
    0.074_725_674_575_290_3,
    0.033_335_672_154_344_07,
];

/// How an axis of the rectangle is integrated, from `H^2` and `L^2` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Tier {
    /// 2-point Gauss-Legendre (`H < TAU[0] L`).
    Gl2,
    /// 4-point Gauss-Legendre (`H < TAU[1] L`).
    Gl4,
    /// 6-point Gauss-Legendre (`H < TAU[2] L`).
    Gl6,
    /// 8-point Gauss-Legendre (`H < TAU[3] L`, `f64` only).
    Gl8,
    /// 10-point Gauss-Legendre (`H < TAU[4] L`, `f64` only).
    Gl10,
    /// Closed form.
    Closed,
}

/// The tier of an axis of half length `H` at distance `L` from the nearest complex
/// singularity of the integrand, from `H^2` and `L^2`. The thresholds [`TAU`] bound the
/// truncation error of each rule (module docs). The tier of [`tier_index`].
#[inline(always)]
pub(crate) fn tier(h2: f64, l2: f64) -> Tier {
    tier_of_index(tier_index(h2, l2))
}

/// The tier of a [`tier_index`].
#[inline(always)]
pub(crate) fn tier_of_index(k: u8) -> Tier {
    TIERS[k as usize]
}

/// The tiers by [`tier_index`]: `Gl2`, `Gl4`, `Gl6`, then (`f64`) `Gl8`, `Gl10`, and `Closed`.
const TIERS: [Tier; 6] = if WIDE {
    [
        Tier::Gl2,
        Tier::Gl4,
        Tier::Gl6,
        Tier::Gl8,
        Tier::Gl10,
        Tier::Closed,
    ]
} else {
    [
        Tier::Gl2,
        Tier::Gl4,
        Tier::Gl6,
        Tier::Closed,
        Tier::Closed,
        Tier::Closed,
    ]
};

/// The index of an axis's tier in the order `Gl2`, `Gl4`, `Gl6`, (`f64`: `Gl8`, `Gl10`),
/// `Closed` ([`CLOSED_INDEX`]): the number of thresholds [`TAU`] (the first three in `f32`) that `H` does not stay below,
/// `!(H^2 < TAU^2 L^2)` each (a NaN counts as beyond every threshold: the closed form, as
/// before). The thresholds increase, so the count is the first threshold `H` stays below.
/// Branch-free, for `batch`'s classification loop.
#[inline(always)]
pub(crate) fn tier_index(h2: f64, l2: f64) -> u8 {
    let n = if WIDE { 5 } else { 3 };
    let mut k = 0u8;
    for t in &TAU[..n] {
        // Negated: a NaN `h2` counts (the closed form, as the `if` chain had it).
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        let beyond = !(h2 < t * t * l2);
        k += u8::from(beyond);
    }
    k
}

/// [`tier_index`] of the closed form: `3` in `f32`, `5` in `f64`.
pub(crate) const CLOSED_INDEX: u8 = if WIDE { 5 } else { 3 };

/// The positive nodes and halved weights of the Gauss-Legendre rule of tier `t` (`Closed` has
/// no rule and is never passed; it gets the 6-point rule; the 8- and 10-point arms exist in the
/// `f64` build only).
#[inline(always)]
pub(crate) fn rule(t: Tier) -> (&'static [f64], &'static [f64]) {
    match t {
        Tier::Gl2 => (&[GL2_X], &[0.5]),
        Tier::Gl4 => (&GL4_X, &GL4_W),
        Tier::Gl8 if WIDE => (&GL8_X, &GL8_W),
        Tier::Gl10 if WIDE => (&GL10_X, &GL10_W),
        _ => (&GL6_X, &GL6_W),
    }
}

/// The mean of `g` over `[c - h, c + h]` by the Gauss-Legendre rule of tier `t` (one loop, so
/// that `g` is inlined once).
#[inline(always)]
pub(crate) fn gl_of(t: Tier, c: f64, h: f64, mut g: impl FnMut(f64) -> f64) -> f64 {
    let (xs, ws) = rule(t);
    let mut acc = 0.0;
    for (&x, &w) in xs.iter().zip(ws) {
        let a = h * x;
        acc += w * (g(c - a) + g(c + a));
    }
    acc
}
