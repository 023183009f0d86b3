//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::filter::rect::{CLOSED_INDEX, Tier};
use super::super::ndf::roughness::AxisAligned;
use super::lanes::{Body, atan2_upper_lane};

/// Elements sorted by class at a time: the lane loops' scalar remainders come once per class
/// and unit (with ten classes, a sixth of the elements in units of 512; measured 20 % slower
/// than 4096). `perm` (`u16`) and `class` take 3 bytes an element on the stack.
const UNIT: usize = 4096;
/// Elements a lane loop evaluates at a time (the gathered columns and results on the stack).
const CHUNK: usize = 256;
use super::{F, Vec2, Vec3};

/// The exact box-filtered GGX [`rect::d_rect`] (KHPL16 eq. 16: the mean of the GGX slope
/// density over the slope-domain rectangle `s(h_i) +/- (half_x[i], half_y[i])`, divided by
/// `h_z^4`; per steradian) for each half vector `h_i` and half extent:
/// `out[i] = d_rect(*r, h_i, (half_x[i], half_y[i]))`, **bit for bit**. The half extents are
/// the kernel as given (no clamps: pass rectangles already through `ClampRules::rect` for the
/// clamped route). Out of domain as [`rect::d_rect`] (`0` below the horizon and for NaN, never
/// NaN). Returns the number of elements written. Allocates nothing.
///
/// Vectorised where the scalar case analysis integrates both axes by Gauss-Legendre rules of
/// 2, 4 or 6 nodes (short sides against the distance to the integrand's poles: most pixel
/// footprints): per block, the elements of each pair of rules are gathered and evaluated by
/// one vector loop with that pair's rules; the closed form (long sides) runs the scalar path.
#[inline]
pub fn d_rect(
    r: &AxisAligned,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    half_x: &[F],
    half_y: &[F],
    out: &mut [F],
) -> usize {
    let n = out
        .len()
        .min(hx.len())
        .min(hy.len())
        .min(hz.len())
        .min(half_x.len())
        .min(half_y.len());
    super::simd::dispatch(RectLoop {
        r: *r,
        ins: [&hx[..n], &hy[..n], &hz[..n], &half_x[..n], &half_y[..n]],
        out: &mut out[..n],
    });
    n
}

/// The tier pairs with a vector loop, in order: each its own loop with constant tiers.
const PAIRS: [(Tier, Tier); 9] = [
    (Tier::Gl2, Tier::Gl2),
    (Tier::Gl2, Tier::Gl4),
    (Tier::Gl2, Tier::Gl6),
    (Tier::Gl4, Tier::Gl2),
    (Tier::Gl4, Tier::Gl4),
    (Tier::Gl4, Tier::Gl6),
    (Tier::Gl6, Tier::Gl2),
    (Tier::Gl6, Tier::Gl4),
    (Tier::Gl6, Tier::Gl6),
];

/// The class of the elements with a long side (a tier `Closed`): the closed-form lane.
const CLOSED: u8 = PAIRS.len() as u8;
/// The class of the rest (the `f64` 8- and 10-point rules): the scalar path.
const REST: u8 = CLOSED + 1;
/// The number of classes.
const NCLASS: usize = REST as usize + 1;
/// The quarters of a block in the counting sort (independent counters).
const Q: usize = 4;

/// The class of an element from its tiers' indices (`rect`'s `tier_index`: `0`, `1`, `2` for
/// the 2-, 4-, 6-point rules, `CLOSED_INDEX` for the closed form): its index in [`PAIRS`],
/// [`CLOSED`] or [`REST`]. Branch-free (selects on integers): the classification loop
/// vectorises.
#[inline(always)]
fn class_of((a, b): (u8, u8)) -> u8 {
    let closed = (a == CLOSED_INDEX) | (b == CLOSED_INDEX);
    let pair = (a < 3) & (b < 3);
    let other = if closed { CLOSED } else { REST };
    if pair { 3 * a + b } else { other }
}

/// The box filter's loop: per block, each element's tier pair (the scalar case analysis'
/// first step), then per pair the block's elements of that pair gathered into contiguous
/// columns and evaluated by one vector loop whose tiers are constants; the rest (and every
/// flagged element) by [`rect::d_rect`]. Buffers on the stack: allocates nothing.
struct RectLoop<'a> {
    r: AxisAligned,
    ins: [&'a [F]; 5],
    out: &'a mut [F],
}

impl Body for RectLoop<'_> {
    // Measured at 0.7 times the scalar loop on SSE2 (two `f64` lanes, the gather).
    const WIDE_ONLY: bool = true;

    #[inline(always)]
    fn go_scalar(self) {
        let Self { r, ins, out } = self;
        for (i, o) in out.iter_mut().enumerate() {
            *o = rect::d_rect(
                r,
                Vec3::new(ins[0][i], ins[1][i], ins[2][i]),
                Vec2::new(ins[3][i], ins[4][i]),
            );
        }
    }

    #[inline(always)]
    fn go(self) {
        let Self { r, ins, out } = self;
        let n = out.len();
        let ins = ins.map(|s| &s[..n]);
        let at = |i: usize| {
            (
                Vec3::new(ins[0][i], ins[1][i], ins[2][i]),
                Vec2::new(ins[3][i], ins[4][i]),
            )
        };
        let mut class = [0u8; UNIT];
        let mut perm = [0u16; UNIT];
        let mut cols = [[0.0 as F; CHUNK]; 5];
        let mut vals = [0.0 as F; CHUNK];
        let mut slow = [false; CHUNK];
        let mut b = 0;
        while b < n {
            let e = n.min(b + UNIT);
            let len = e - b;
            let blk = ins.map(|s| &s[b..e]);
            // The classes (the scalar case analysis' first step), in a vector loop.
            for (i, c) in class[..len].iter_mut().enumerate() {
                let h = Vec3::new(blk[0][i], blk[1][i], blk[2][i]);
                let s = Vec2::new(blk[3][i], blk[4][i]);
                *c = class_of(rect::RectSetup::new(r, h, s).tier_indices);
            }
            // A counting sort of the unit's offsets by class: `perm[start[k]..start[k + 1]]`
            // are the offsets of class `k`, in order. The unit in `Q` parts with their own
            // counters, interleaved: consecutive elements of one class would otherwise chain
            // every increment through memory (store-to-load forwarding, measured at a third of
            // the loop's time). The counts per part by vectorised compares.
            let q = len.div_ceil(Q);
            let mut next = [[0u16; NCLASS]; Q];
            for (cnt, part) in next.iter_mut().zip(class[..len].chunks(q)) {
                for (k, c) in cnt.iter_mut().enumerate() {
                    *c = part.iter().map(|&x| u16::from(x == k as u8)).sum();
                }
            }
            let mut start = [0u16; NCLASS + 1];
            let mut acc = 0u16;
            for k in 0..NCLASS {
                start[k] = acc;
                for cnt in next.iter_mut() {
                    let c = cnt[k];
                    cnt[k] = acc;
                    acc += c;
                }
            }
            start[NCLASS] = acc;
            for i in 0..q {
                for (s, nx) in next.iter_mut().enumerate() {
                    let j = s * q + i;
                    if j < len {
                        let slot = &mut nx[class[j] as usize];
                        perm[*slot as usize] = j as u16;
                        *slot += 1;
                    }
                }
            }
            // One vector loop per class, over chunks of its offsets: the chunk's elements
            // gathered into contiguous columns, the lane `$lane` (of a `RectSetup`) over them,
            // then the results scattered back, the flagged ones by the scalar path.
            macro_rules! pass {
                ($k:expr, $lane:expr) => {
                    let (lo, hi) = (start[$k as usize] as usize, start[$k as usize + 1] as usize);
                    for idx in perm[lo..hi].chunks(CHUNK) {
                        let m = idx.len();
                        for (c, s) in cols.iter_mut().zip(&blk) {
                            for (d, &i) in c[..m].iter_mut().zip(idx) {
                                *d = s[i as usize];
                            }
                        }
                        for j in 0..m {
                            let h = Vec3::new(cols[0][j], cols[1][j], cols[2][j]);
                            let s = Vec2::new(cols[3][j], cols[4][j]);
                            let (v, sl) = $lane(rect::RectSetup::new(r, h, s));
                            vals[j] = v;
                            slow[j] = sl;
                        }
                        for j in 0..m {
                            let i = b + idx[j] as usize;
                            out[i] = if slow[j] {
                                let (h, s) = at(i);
                                rect::d_rect(r, h, s)
                            } else {
                                vals[j]
                            };
                        }
                    }
                };
            }
            // The Gauss-Legendre pairs, each with its tiers as constants (a macro, not a loop
            // over `PAIRS`: a loop that is not unrolled would leave them variables, and the
            // case analysis in the lane would stop the vectoriser).
            macro_rules! pairs {
                ($($k:literal)*) => {$(
                    pass!($k, |st: rect::RectSetup| st.lane(PAIRS[$k].0, PAIRS[$k].1));
                )*};
            }
            pairs!(0 1 2 3 4 5 6 7 8);
            // The closed form's lane (a long side): the four-edge form with the polynomial
            // `atan2`; the elements it does not take (far field, 1D closed form) flagged.
            pass!(CLOSED, |st: rect::RectSetup| st.closed_lane(atan2_upper_lane));
            // The rest (the `f64` 8- and 10-point rules) by the scalar path.
            for &i in &perm[start[REST as usize] as usize..len] {
                let (h, s) = at(b + i as usize);
                out[b + i as usize] = rect::d_rect(r, h, s);
            }
            b = e;
        }
    }
}
