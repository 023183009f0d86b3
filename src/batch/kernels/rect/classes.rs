//! The box filter's classes and their counting sort: each element's class is the pair of
//! Gauss-Legendre tiers its case analysis takes (or the closed form), and the elements of a
//! unit are sorted by class so that each class runs one vector loop with its tiers constant.

use super::super::super::super::filter::rect::{CLOSED_INDEX, Tier};
use super::super::super::engine::lane_math::WIDE;
use super::lanes32;

/// Elements sorted by class at a time: the lane loops' padding comes once per class and unit,
/// so smaller units are slower (`docs/batch_measurements.md`). The unit's
/// buffers (`super::Unit`) take `3 + 5 size_of::<F>()` bytes an element for the classes,
/// offsets and columns, and `1 + size_of::<F>()` for the results.
pub(super) const UNIT: usize = 2048;

/// The multiple of elements a class's lane loop runs on (the widest vector, 16 `f32`): the
/// vector loop then leaves no remainder to a scalar loop of the lane.
pub(super) const PAD: usize = 16;

/// The Gauss-Legendre tiers with a vector loop: in `f64` the scalar path's (`filter::rect`'s
/// `tier_index` order: `Gl2`, `Gl4`, `Gl6`, `Gl8`, `Gl10`, then `CLOSED_INDEX`), in `f32` the
/// `f32` lanes' (`lanes32`: 2 to 10 points, then the closed forms).
pub(super) const NT: usize = if WIDE {
    CLOSED_INDEX as usize
} else {
    lanes32::NT
};

/// The `f64` build's tiers (`NT` there).
const NT64: usize = 5;

/// The `f64` build's tier pairs, pair `(i, j)` at `NT64 i + j`: each its own loop with
/// constant tiers.
pub(super) const PAIRS: [(Tier, Tier); NT64 * NT64] = {
    assert!(!WIDE || NT == NT64);
    let tiers = [Tier::Gl2, Tier::Gl4, Tier::Gl6, Tier::Gl8, Tier::Gl10];
    let mut pairs = [(Tier::Gl6, Tier::Gl6); NT64 * NT64];
    let mut k = 0;
    while k < NT64 * NT64 {
        pairs[k] = (tiers[k / NT64], tiers[k % NT64]);
        k += 1;
    }
    pairs
};

/// The class of the elements with a long side (a tier `Closed`): the closed-form lane (after
/// the `NT^2` pairs in `f64`, the `NT (NT + 1) / 2` pairs `i <= j` in `f32`: [`class_of32`]).
pub(super) const CLOSED: u8 = if WIDE { NT * NT } else { NT * (NT + 1) / 2 } as u8;

/// The number of classes.
pub(super) const NCLASS: usize = CLOSED as usize + 1;

/// The parts of a unit in the counting sort, each with its own counters.
const PARTS: usize = 4;

/// The class of an element from its tiers' indices (`rect`'s `tier_index`, at most
/// `CLOSED_INDEX = NT`): its pair's index in [`PAIRS`], or [`CLOSED`]. Branch-free (selects
/// on integers): the classification loop vectorises.
#[inline(always)]
pub(super) fn class_of((a, b): (u8, u8)) -> u8 {
    let closed = (a == CLOSED_INDEX) | (b == CLOSED_INDEX);
    if closed { CLOSED } else { NT as u8 * a + b }
}

/// The class of the pair `(i, j)`, `i <= j < NT`, in `f32`: the pairs numbered row by row,
/// `(0, 0)` to `(0, NT - 1)`, then `(1, 1)`, and so on.
#[inline(always)]
pub(super) const fn tri(i: u8, j: u8) -> u8 {
    i * (2 * NT as u8 - 1 - i) / 2 + j
}

/// The class of an element from its `f32` lane tiers `(min, max)` (`lanes32::Setup::tiers`):
/// [`tri`], or [`CLOSED`]. Branch-free.
#[inline(always)]
pub(super) fn class_of32((a, b): (u8, u8)) -> u8 {
    if b == NT as u8 { CLOSED } else { tri(a, b) }
}

/// The number of bytes of `part` equal to `k`: per lane of 64 a byte counter (at most
/// `UNIT / 64 < 256` increments, no overflow), summed once at the end (a compare and a
/// subtract per 64 bytes with AVX-512).
#[inline(always)]
fn count_eq(part: &[u8], k: u8) -> u16 {
    const L: usize = 64;
    const { assert!(UNIT / L < 256, "a lane's byte counter cannot overflow") };
    let mut acc = [0u8; L];
    let mut chunks = part.chunks_exact(L);
    for chunk in &mut chunks {
        for (a, &x) in acc.iter_mut().zip(chunk) {
            *a += u8::from(x == k);
        }
    }
    let tail: u16 = chunks.remainder().iter().map(|&x| u16::from(x == k)).sum();
    acc.iter().map(|&a| u16::from(a)).sum::<u16>() + tail
}

/// A counting sort of the offsets `0..len` of a unit (`1 <= len <= UNIT`) by their class
/// `class[j]`: `perm[start[k]..start[k + 1]]` are the offsets of class `k` in order,
/// `inv[j]` is offset `j`'s slot in `perm`; returns `start`.
///
/// The unit in [`PARTS`] parts with their own counters, interleaved: consecutive elements of
/// one class would otherwise chain every increment through memory (store-to-load
/// forwarding). The counts per part by vectorised compares into byte counters
/// ([`count_eq`]). Only the offsets move: the lanes gather their columns through them.
#[inline(always)]
pub(super) fn sort_by_class(
    class: &[u8; UNIT],
    len: usize,
    perm: &mut [u16; UNIT + PAD],
    inv: &mut [u16; UNIT],
) -> [u16; NCLASS + 1] {
    let part_len = len.div_ceil(PARTS);
    // Each part's next slot per class: first its counts, then its first slots.
    let mut next = [[0u16; NCLASS]; PARTS];
    for (counts, part) in next.iter_mut().zip(class[..len].chunks(part_len)) {
        for (k, c) in counts.iter_mut().enumerate() {
            *c = count_eq(part, k as u8);
        }
    }
    let mut start = [0u16; NCLASS + 1];
    let mut acc = 0u16;
    for k in 0..NCLASS {
        start[k] = acc;
        for counts in next.iter_mut() {
            let c = counts[k];
            counts[k] = acc;
            acc += c;
        }
    }
    start[NCLASS] = acc;
    for i in 0..part_len {
        for (part, slots) in next.iter_mut().enumerate() {
            let j = part * part_len + i;
            if j < len {
                let slot = &mut slots[class[j] as usize];
                let t = *slot as usize % UNIT;
                perm[t] = j as u16;
                inv[j] = t as u16;
                *slot += 1;
            }
        }
    }
    start
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `count_eq` counts as a plain filter does, for every length of a part (whole lanes of
    /// 64 and a remainder) and every class, on bytes where each class is frequent and rare.
    #[test]
    fn count_eq_counts() {
        let mut rng = crate::testing::rng::SplitMix64(0xC0FE);
        let bytes: [u8; UNIT] =
            core::array::from_fn(|_| (rng.uniform() * rng.uniform() * NCLASS as f64) as u8);
        for len in (0..=UNIT).step_by(37).chain([63, 64, 65, UNIT]) {
            for k in 0..=NCLASS as u8 {
                let want = bytes[..len].iter().filter(|&&x| x == k).count();
                assert_eq!(usize::from(count_eq(&bytes[..len], k)), want, "{len} {k}");
            }
        }
    }

    /// `sort_by_class` is a stable sort of the offsets by class, `inv` its inverse, and
    /// `start` the classes' bounds, for lengths that do and do not divide into the parts.
    #[test]
    fn sort_by_class_is_a_stable_sort() {
        let mut rng = crate::testing::rng::SplitMix64(0x50A7);
        let class: [u8; UNIT] =
            core::array::from_fn(|_| (rng.uniform() * rng.uniform() * NCLASS as f64) as u8);
        for len in [1, 2, 3, 5, 37, 1000, UNIT - 1, UNIT] {
            let mut perm = [0u16; UNIT + PAD];
            let mut inv = [0u16; UNIT];
            let start = sort_by_class(&class, len, &mut perm, &mut inv);
            let mut want: Vec<u16> = (0..len as u16).collect();
            want.sort_by_key(|&j| class[j as usize]);
            assert_eq!(&perm[..len], &want[..], "{len}");
            for (t, &j) in perm[..len].iter().enumerate() {
                assert_eq!(usize::from(inv[j as usize]), t, "{len}");
            }
            for k in 0..NCLASS {
                let (lo, hi) = (usize::from(start[k]), usize::from(start[k + 1]));
                assert!(
                    perm[lo..hi]
                        .iter()
                        .all(|&j| usize::from(class[j as usize]) == k)
                );
            }
            assert_eq!(usize::from(start[NCLASS]), len);
        }
    }
}
