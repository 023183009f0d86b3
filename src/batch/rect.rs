//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::filter::rect::{CLOSED_INDEX, Tier};
use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, RectBounds};
use super::super::ndf::roughness::AxisAligned;
use super::lane_math::{WIDE, atan2_upper_lane};
use super::lanes::Body;
use super::rect_lane;
use super::{F, Footprints, Vec2, Vec3};
use crate::math::Real;

/// Elements sorted by class at a time: the lane loops' padding comes once per class and unit
/// (units of 512 measured 20 % slower than 4096; 2048 as fast as 4096 in `f32`, 1024 10 %
/// slower in `f64`). `class` and `perm` (`u8`, `u16`) and the five columns take
/// `3 + 5 size_of::<F>()` bytes an element on the stack, and the results `1 + size_of::<F>()`.
const UNIT: usize = 2048;
/// The columns the lanes read: `(h_x, h_y, h_z, s_x, s_y)`, or the `f32` lanes' setup.
const NCOL: usize = 5;
/// The multiple of elements a lane loop runs on (the widest vector, 16 `f32`).
const PAD: usize = 16;

/// The exact box-filtered GGX [`rect::d_rect`] (KHPL16 eq. 16: the mean of the GGX slope
/// density over the slope-domain rectangle `s(h_i) +/- (half_x[i], half_y[i])`, divided by
/// `h_z^4`; per steradian) for each half vector `h_i` and half extent:
/// `out[i] = d_rect(*r, h_i, (half_x[i], half_y[i]))` within the bounds below. The half
/// extents are the kernel as given (no clamps: pass rectangles already through
/// `ClampRules::rect` for the clamped route). Out of domain as [`rect::d_rect`] (`0` below the
/// horizon and for NaN, never NaN). Returns the number of elements written. Allocates nothing
/// (buffers on the stack: 60 KiB in `f32`, 108 KiB in `f64`).
///
/// Vectorised where the case analysis integrates both axes by Gauss-Legendre rules (short
/// sides against the distance to the integrand's poles: most pixel footprints) and where it
/// takes the four-edge closed form (a long side, KHPL16 Appendix A rewritten as four `atan2`):
/// per unit of 2048 elements, the elements of each pair of rules and those of the closed form
/// are sorted together and evaluated by one vector loop each. The far field, the 1D closed
/// form and the special cases run the scalar path.
///
/// **Agreement.**
/// - **`f32`, Gauss-Legendre elements** (both sides within `0.5` of their distance from the
///   poles: 89 % of the benchmark's realistic elements): the `f32` lanes of
///   `batch::rect_lane`, in `f32` arithmetic with two more tiers (8 and 10 points) than the
///   scalar `f32` path; not bit for bit: within `78 u |D|` of the exact `D` (`u = 2^-24`,
///   derived there; `4.6e-6` relative) plus the inputs' rounding (`u_c`, `v_c` to `4 u`, the
///   half extents to `2 u`) times `D`'s sensitivity to them. Tested against the `f64` scalar
///   path in `tests/batch_bounds.rs`: worst `0.12` of the bound, `11.4 u` relative, where the
///   scalar `f32` path is within about `2 u`. The price of the speed: the `f64` lanes that
///   matched the scalar path bit for bit ran at 13.4 to 14.0 ns an element, these at 8.5 to
///   9.7 (the benchmark's elements, AVX-512, the two builds alternating; AVX2 18 -> 14 ns,
///   SSE2 29 -> 21 ns).
/// - **`f64`, Gauss-Legendre elements** (and in both builds all those of the scalar path):
///   bit for bit (the pairs of 2- to 10-point rules of the scalar case analysis).
/// - **Four-edge elements**: the lane evaluates the scalar path's formula (`edges_by`) with
///   its four angles by a polynomial `atan2` (relative `3 eps_64`) in place of libm's
///   (`2 eps_64`, with its division and sum); before the rounding to `F`,
///   `|batch - scalar| <= 8 eps_64 M + 4 eps_64 |D|`, `M` the four edge terms' magnitudes
///   `|u / S atan2(..)|` summed and scaled as their sum is into `D` (the form's cancellation:
///   `M / D` up to `900` where the route takes the form, measured, so the bound is below about
///   `2e-12` relative). In `f32` the two `f64` values round to the same `f32` or to neighbours
///   (one ulp apart at most; measured: always the same); in `f64` measured within `7.5e-14`
///   relative. Tested in `tests/batch_bounds.rs`.
pub fn d_rect(
    r: &AxisAligned,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    half_x: &[F],
    half_y: &[F],
    out: &mut [F],
) -> usize {
    rect_loop(r, [hx, hy, hz], Given([half_x, half_y]), out)
}

/// The front door's `Rect` method over slices: the exact box-filtered GGX over each
/// footprint's bounding rectangle after the clamp rules, `out[i] = d_rect(*r, h_i,
/// rules.rect(fp_i.bounding_rect(), r.alpha()).half_extent)` (KHPL16 eq. 16 over the
/// rectangle of KHPL16 section 5.2; [`ClampRules::rect`]: maximum extent, floor), as
/// [`d_rect`] on those half extents, bit for bit (so its agreement with the scalar path is
/// [`d_rect`]'s). Returns the number of elements written. Allocates nothing (`d_rect`'s
/// loop, each rectangle computed where it classifies the element: the same stack buffers).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn d_rect_filtered(
    r: &AxisAligned,
    rules: &ClampRules,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let ext = Clamped {
        bounds: rules.rect_bounds(r.alpha()),
        fp: [fp.dh_u_x, fp.dh_u_y, fp.dh_v_x, fp.dh_v_y],
    };
    rect_loop(r, [hx, hy, hz], ext, out)
}

/// [`RectLoop`] over the common prefix of the columns, dispatched: the number of elements
/// written.
#[inline(always)]
fn rect_loop<E: Extents>(r: &AxisAligned, h: [&[F]; 3], ext: E, out: &mut [F]) -> usize {
    let n = h
        .iter()
        .fold(out.len().min(ext.len()), |n, s| n.min(s.len()));
    super::simd::dispatch(RectLoop {
        r: *r,
        h: h.map(|s| &s[..n]),
        ext: ext.range(0, n),
        out: &mut out[..n],
    });
    n
}

/// Where [`RectLoop`] takes each element's half extents from.
trait Extents: Copy {
    /// The number of elements (the shortest slice).
    fn len(self) -> usize;
    /// The elements `b..e` (within the slices).
    fn range(self, b: usize, e: usize) -> Self;
    /// The half extents of element `i`.
    fn at(self, i: usize) -> Vec2;
}

/// The half extents given (`d_rect`).
#[derive(Clone, Copy)]
struct Given<'a>([&'a [F]; 2]);

impl Extents for Given<'_> {
    #[inline(always)]
    fn len(self) -> usize {
        self.0[0].len().min(self.0[1].len())
    }
    #[inline(always)]
    fn range(self, b: usize, e: usize) -> Self {
        Self(self.0.map(|s| &s[b..e]))
    }
    #[inline(always)]
    fn at(self, i: usize) -> Vec2 {
        Vec2::new(self.0[0][i], self.0[1][i])
    }
}

/// The half extents of the footprints' bounding rectangles after the rules
/// (`d_rect_filtered`): `bounds.apply(fp_i.bounding_rect())`, as `ClampRules::rect`.
#[derive(Clone, Copy)]
struct Clamped<'a> {
    bounds: RectBounds,
    fp: [&'a [F]; 4],
}

impl Extents for Clamped<'_> {
    #[inline(always)]
    fn len(self) -> usize {
        self.fp.iter().fold(usize::MAX, |n, s| n.min(s.len()))
    }
    #[inline(always)]
    fn range(self, b: usize, e: usize) -> Self {
        Self {
            bounds: self.bounds,
            fp: self.fp.map(|s| &s[b..e]),
        }
    }
    #[inline(always)]
    fn at(self, i: usize) -> Vec2 {
        let [ux, uy, vx, vy] = self.fp;
        let f = Footprint::from_slope_derivatives(Vec2::new(ux[i], uy[i]), Vec2::new(vx[i], vy[i]));
        self.bounds.apply(f.bounding_rect()).half_extent
    }
}

/// The Gauss-Legendre tiers with a vector loop: in `f64` the scalar path's (`filter::rect`'s
/// `tier_index` order: `Gl2`, `Gl4`, `Gl6`, `Gl8`, `Gl10`, then `CLOSED_INDEX`), in `f32` the
/// `f32` lanes' (`rect_lane`: 2 to 10 points, then the closed forms).
const NT: usize = if WIDE {
    CLOSED_INDEX as usize
} else {
    rect_lane::NT
};
/// The `f64` build's tiers (`NT` there).
const NT64: usize = 5;

/// The `f64` build's tier pairs, pair `(i, j)` at `NT64 i + j`: each its own loop with
/// constant tiers.
const PAIRS: [(Tier, Tier); NT64 * NT64] = {
    assert!(!WIDE || NT == NT64);
    let t = [Tier::Gl2, Tier::Gl4, Tier::Gl6, Tier::Gl8, Tier::Gl10];
    let mut a = [(Tier::Gl6, Tier::Gl6); NT64 * NT64];
    let mut k = 0;
    while k < NT64 * NT64 {
        a[k] = (t[k / NT64], t[k % NT64]);
        k += 1;
    }
    a
};

/// The class of the elements with a long side (a tier `Closed`): the closed-form lane (after
/// the `NT^2` pairs in `f64`, the `NT (NT + 1) / 2` pairs `i <= j` in `f32`: `class_of32`).
const CLOSED: u8 = if WIDE { NT * NT } else { NT * (NT + 1) / 2 } as u8;
/// The number of classes.
const NCLASS: usize = CLOSED as usize + 1;
/// The parts of a unit in the counting sort (independent counters).
const Q: usize = 4;

/// The class of an element from its tiers' indices (`rect`'s `tier_index`, at most
/// `CLOSED_INDEX = NT`): its pair's index in [`PAIRS`], or [`CLOSED`]. Branch-free (selects
/// on integers): the classification loop vectorises.
#[inline(always)]
fn class_of((a, b): (u8, u8)) -> u8 {
    let closed = (a == CLOSED_INDEX) | (b == CLOSED_INDEX);
    if closed { CLOSED } else { NT as u8 * a + b }
}

/// The number of bytes of `part` equal to `k`: per lane of 64 a byte counter (at most
/// `UNIT / 64 < 256` increments, no overflow), summed once at the end (a compare and a
/// subtract per 64 bytes with AVX-512).
#[inline(always)]
fn count_eq(part: &[u8], k: u8) -> u16 {
    const L: usize = 64;
    const { assert!(UNIT / L < 256, "a lane's byte counter cannot overflow") };
    let mut acc = [0u8; L];
    let mut it = part.chunks_exact(L);
    for c in &mut it {
        for (a, &x) in acc.iter_mut().zip(c) {
            *a += u8::from(x == k);
        }
    }
    let tail: u16 = it.remainder().iter().map(|&x| u16::from(x == k)).sum();
    acc.iter().map(|&a| u16::from(a)).sum::<u16>() + tail
}

/// The class of the pair `(i, j)`, `i <= j < NT`, in `f32`: the pairs numbered row by row,
/// `(0, 0)` to `(0, NT - 1)`, then `(1, 1)`, and so on.
#[inline(always)]
const fn tri(i: u8, j: u8) -> u8 {
    i * (2 * NT as u8 - 1 - i) / 2 + j
}

/// The class of an element from its `f32` lane tiers `(min, max)` (`rect_lane::Setup::tiers`):
/// [`tri`], or [`CLOSED`]. Branch-free.
#[inline(always)]
fn class_of32((a, b): (u8, u8)) -> u8 {
    if b == NT as u8 { CLOSED } else { tri(a, b) }
}

/// The box filter's loop: per unit of [`UNIT`] elements, each element's half extents (given,
/// or from its footprint by the rules: [`Extents`]) and class (its tier pair or the closed
/// form: the case analysis' first step), in one vector loop that also stores the columns the
/// lanes read (the inputs in `f64`, the `f32` lanes' setup in `f32`); a counting sort of the
/// unit's offsets by class; then per class one vector loop whose tiers are constants (or the
/// closed-form lane), gathering its elements' columns by their offsets; the results back in
/// input order, every flagged element by [`rect::d_rect`]. Buffers on the stack: allocates
/// nothing.
struct RectLoop<'a, E> {
    r: AxisAligned,
    /// The half vectors' columns.
    h: [&'a [F]; 3],
    ext: E,
    out: &'a mut [F],
}

impl<E: Extents> Body for RectLoop<'_, E> {
    // The lanes pay on SSE2 too since the closed form has one (measured with
    // `FILTERED_NDF_SIMD=sse2-lanes`: 1.3 to 1.8 times the scalar loop in `f32`, 1.1 in `f64`;
    // before, with the closed form scalar and a scan per pair, 0.7).
    const WIDE_ONLY: bool = false;

    #[inline(always)]
    fn go_scalar(self) {
        let Self { r, h, ext, out } = self;
        for (i, o) in out.iter_mut().enumerate() {
            *o = rect::d_rect(r, Vec3::new(h[0][i], h[1][i], h[2][i]), ext.at(i));
        }
    }

    #[inline(always)]
    fn go(self) {
        let Self { r, h, ext, out } = self;
        let n = out.len();
        let consts = rect_lane::Consts::new(&r);
        let mut class = [0u8; UNIT];
        // The offsets sorted by class, with `PAD` entries of slack: a class's lane loop runs
        // over its elements rounded up to a multiple of `PAD` (the vector loop then leaves no
        // remainder to a scalar loop of the lane, which took a sixth of the time), reading
        // the next class's elements (or the slack's offset `0`) past its end; those results
        // are never used.
        let mut perm = [0u16; UNIT + PAD];
        // Its inverse: element `j`'s slot in `perm` (the results come back in input order by
        // gathering through it, a vector loop; a scatter through `perm`, with its branch for
        // the flagged elements, had taken a fifth of the time).
        let mut inv = [0u16; UNIT];
        let mut cols = [[0.0 as F; UNIT]; NCOL];
        let mut vals = [0.0 as F; UNIT + PAD];
        let mut slow = [false; UNIT + PAD];
        let mut b = 0;
        while b < n {
            let e = n.min(b + UNIT);
            let len = e - b;
            let blk = h.map(|s| &s[b..e]);
            let ext = ext.range(b, e);
            // The classes (the scalar case analysis' first step) and what the lanes read, in a
            // vector loop: in `f64` the inputs `(h, s)`, in `f32` the `f32` lanes' setup
            // (`rect_lane::Setup::cols`).
            for (i, c) in class[..len].iter_mut().enumerate() {
                let h = Vec3::new(blk[0][i], blk[1][i], blk[2][i]);
                let s = ext.at(i);
                let x = if WIDE {
                    *c = class_of(rect::RectSetup::new(r, h, s).tier_indices);
                    [h.x, h.y, h.z, s.x, s.y]
                } else {
                    let st = rect_lane::Setup::new(consts, h, s);
                    *c = class_of32(st.tiers);
                    st.cols().map(|x| F::from_f64(x.to_f64()))
                };
                for (col, x) in cols.iter_mut().zip(x) {
                    col[i] = x;
                }
            }
            // A counting sort of the unit's offsets by class: `perm[start[k]..start[k + 1]]`
            // are the offsets of class `k`, in order. The unit in `Q` parts with their own
            // counters, interleaved: consecutive elements of one class would otherwise chain
            // every increment through memory (store-to-load forwarding, measured at a third of
            // the loop's time). The counts per part by vectorised compares into byte counters
            // (`count_eq`: 8.8 against 9.1 ns an element with `u16` sums, `f32`, AVX-512).
            // Only the offsets move (moving the five columns here took 22 % of the time; the
            // lanes gather them, which measured faster than gathering each class into a buffer
            // first).
            let q = len.div_ceil(Q);
            let mut next = [[0u16; NCLASS]; Q];
            for (cnt, part) in next.iter_mut().zip(class[..len].chunks(q)) {
                for (k, c) in cnt.iter_mut().enumerate() {
                    *c = count_eq(part, k as u8);
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
                        let t = *slot as usize % UNIT;
                        perm[t] = j as u16;
                        inv[j] = t as u16;
                        *slot += 1;
                    }
                }
            }
            // One vector loop per class over its sorted offsets: the lane `$lane` (`$x`: an
            // element's columns) into `vals` and `slow`.
            macro_rules! pass {
                ($k:expr, |$x:ident| $lane:expr) => {
                    let (lo, hi) = (start[$k as usize] as usize, start[$k as usize + 1] as usize);
                    let m = (hi - lo).next_multiple_of(PAD);
                    // Slices of one length: the loop has no bounds checks.
                    let p = &perm[lo..lo + m];
                    let (vs, sls) = (&mut vals[lo..lo + m], &mut slow[lo..lo + m]);
                    for j in 0..m {
                        // Gathered in the lane loop (vector gathers with AVX2 and AVX-512).
                        let i = p[j] as usize % UNIT;
                        // The lanes' precondition: the class's own elements (not the padding
                        // past them) are of its pair.
                        debug_assert!(j >= hi - lo || usize::from(class[i]) == $k as usize);
                        let $x = [cols[0][i], cols[1][i], cols[2][i], cols[3][i], cols[4][i]];
                        let (v, sl) = $lane;
                        vs[j] = v;
                        sls[j] = sl;
                    }
                };
            }
            let split = |x: [F; NCOL]| (Vec3::new(x[0], x[1], x[2]), Vec2::new(x[3], x[4]));
            // An element's inputs `(h, s)` by its offset in the unit.
            let raw = |i: usize| {
                let s = ext.at(i);
                [blk[0][i], blk[1][i], blk[2][i], s.x, s.y]
            };
            // The Gauss-Legendre pairs, each with its tiers as constants (a macro, not a loop
            // over `PAIRS`: a loop that is not unrolled would leave them variables, and the
            // case analysis in the lane would stop the vectoriser).
            macro_rules! pairs64 {
                ($($k:literal)*) => {$(
                    pass!($k, |x| {
                        let (h, s) = split(x);
                        rect::RectSetup::new(r, h, s).lane(PAIRS[$k].0, PAIRS[$k].1)
                    });
                )*};
            }
            macro_rules! pairs32 {
                ($($i:literal $j:literal),*) => {$(
                    pass!(tri($i, $j), |x| {
                        rect_lane::lane::<$i, $j>(consts, x.map(|v| v.to_f64() as f32))
                    });
                )*};
            }
            // Constant conditions: one build's pairs are not compiled in the other.
            if WIDE {
                pairs64!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24);
            } else {
                // The `f32` lanes: the pairs `(i, j)`, `i <= j` (`class_of32`), on the setup
                // that the classification stored.
                pairs32!(0 0, 0 1, 0 2, 0 3, 0 4, 1 1, 1 2, 1 3, 1 4, 2 2, 2 3, 2 4, 3 3, 3 4, 4 4);
            }
            // The closed form's lane (a long side): the four-edge form with the polynomial
            // `atan2`; the elements it does not take (far field, 1D closed form) flagged. In
            // `f32` it reads the inputs, put in place of the setup here (a select in the
            // classification kept that loop from vectorising with AVX2).
            if !WIDE {
                let (lo, hi) = (start[CLOSED as usize] as usize, start[NCLASS] as usize);
                for &i in &perm[lo..hi] {
                    let i = i as usize % UNIT;
                    for (col, x) in cols.iter_mut().zip(raw(i)) {
                        col[i] = x;
                    }
                }
            }
            pass!(CLOSED, |x| {
                let (h, s) = split(x);
                rect::RectSetup::new(r, h, s).closed_lane(atan2_upper_lane)
            });
            // The results back in input order (gathered through `inv`: slices of one length,
            // no bounds checks but the index's), then the flagged ones by the scalar path.
            let o = &mut out[b..e];
            for (o, &t) in o.iter_mut().zip(&inv[..len]) {
                *o = vals[t as usize % UNIT];
            }
            // Any flagged, by a reduction that vectorises (`any` stops early: a scalar loop).
            if slow[..len].iter().fold(false, |a, &x| a | x) {
                for (&i, _) in perm[..len].iter().zip(&slow[..len]).filter(|(_, x)| **x) {
                    let i = i as usize;
                    let (h, s) = split(raw(i));
                    o[i] = rect::d_rect(r, h, s);
                }
            }
            b = e;
        }
    }
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
}
