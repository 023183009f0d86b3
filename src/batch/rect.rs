//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::filter::rect::{CLOSED_INDEX, Tier};
use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, RectBounds};
use super::super::ndf::roughness::AxisAligned;
use super::lanes::{Body, atan2_upper_lane};
use super::{F, Footprints, Vec2, Vec3};

/// Elements sorted by class at a time: the lane loops' padding comes once per class and unit
/// (units of 512 measured 20 % slower than 4096; 2048 as fast as 4096 in `f32` since the
/// gather moves pairs, 1024 10 % slower in `f64`). `class` and `perm` (`u8`, `u16`) and the
/// pairs `(h_x, h_y)` and `(half_x, half_y)` take `3 + 4 size_of::<F>()` bytes an element on
/// the stack.
const UNIT: usize = 2048;
/// Elements a lane loop evaluates at a time (the gathered columns and results on the stack).
const CHUNK: usize = 256;
/// The multiple of elements a lane loop runs on (the widest vector, 16 `f32`; `CHUNK` is a
/// multiple of it).
const PAD: usize = 16;

/// The exact box-filtered GGX [`rect::d_rect`] (KHPL16 eq. 16: the mean of the GGX slope
/// density over the slope-domain rectangle `s(h_i) +/- (half_x[i], half_y[i])`, divided by
/// `h_z^4`; per steradian) for each half vector `h_i` and half extent:
/// `out[i] = d_rect(*r, h_i, (half_x[i], half_y[i]))`, bit for bit except for the four-edge
/// closed form (below). The half extents are the kernel as given (no clamps: pass rectangles
/// already through `ClampRules::rect` for the clamped route). Out of domain as
/// [`rect::d_rect`] (`0` below the horizon and for NaN, never NaN). Returns the number of
/// elements written. Allocates nothing (buffers on the stack: 44 KiB in `f32`, 82 KiB in
/// `f64`).
///
/// Vectorised where the scalar case analysis integrates both axes by Gauss-Legendre rules
/// (short sides against the distance to the integrand's poles: most pixel
/// footprints) and where it takes the four-edge closed form (a long side, KHPL16 Appendix A
/// rewritten as four `atan2`: about a quarter of realistic footprints): per unit of 2048
/// elements, the elements of each pair of rules and those of the closed form are sorted
/// together and evaluated by one vector loop each (the pairs of `f64`'s 8- and 10-point rules
/// too). The far field, the 1D closed form and the special cases run the scalar path.
///
/// **Agreement.** Gauss-Legendre elements (and all those of the scalar path): bit for bit.
/// Four-edge elements: the lane evaluates the scalar path's formula (`edges_by`) with its
/// four angles by a polynomial `atan2` (relative `3 eps_64`) in place of libm's (`2 eps_64`,
/// with its division and sum); before the rounding to `F`,
/// `|batch - scalar| <= 8 eps_64 M + 4 eps_64 |D|`, `M` the four edge terms' magnitudes
/// `|u / S atan2(..)|` summed and scaled as their sum is into `D` (the form's cancellation:
/// `M / D` up to `900` where the route takes the form, measured, so the bound is below about
/// `2e-12` relative). In `f32` the two `f64` values round to the same `f32` or to neighbours
/// (one ulp apart at most; measured: always the same); in `f64` measured within `7.5e-14`
/// relative. Tested in `tests/batch_bounds.rs`.
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

/// The Gauss-Legendre tiers of the precision, in `filter::rect`'s `tier_index` order
/// (`CLOSED_INDEX` of them: `Gl2`, `Gl4`, `Gl6`, and in `f64` `Gl8`, `Gl10`).
const NT: usize = CLOSED_INDEX as usize;

/// The tier pairs with a vector loop, pair `(i, j)` at `NT i + j`: each its own loop with
/// constant tiers (`NT^2` of them: 9 in `f32`, 25 in `f64`; the entries past them repeat
/// `Gl6` and are never used).
const PAIRS: [(Tier, Tier); 25] = {
    let t = [Tier::Gl2, Tier::Gl4, Tier::Gl6, Tier::Gl8, Tier::Gl10];
    let mut a = [(Tier::Gl6, Tier::Gl6); 25];
    let mut k = 0;
    while k < NT * NT {
        a[k] = (t[k / NT], t[k % NT]);
        k += 1;
    }
    a
};

/// The class of the elements with a long side (a tier `Closed`): the closed-form lane.
const CLOSED: u8 = (NT * NT) as u8;
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

/// The box filter's loop: per unit of [`UNIT`] elements, each element's half extents (given,
/// or from its footprint by the rules: [`Extents`]) and class (its tier pair or the closed
/// form: the scalar case analysis' first step), in one vector loop that also stores the
/// element's `(h_x, h_y)` and half extents as pairs; a counting sort of the unit by class;
/// then per class chunks of its elements gathered (`h_z` and the two pairs) into contiguous
/// columns and evaluated by one vector loop whose tiers are constants (or the closed-form
/// lane); the rest (and every flagged element) by [`rect::d_rect`]. Buffers on the stack:
/// allocates nothing.
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
        let mut class = [0u8; UNIT];
        let mut perm = [0u16; UNIT];
        let mut pairs = [[[0.0 as F; 2]; UNIT]; 2];
        let mut z = [0.0 as F; CHUNK];
        let mut cpairs = [[[0.0 as F; 2]; CHUNK]; 2];
        let mut vals = [0.0 as F; CHUNK];
        let mut slow = [false; CHUNK];
        let mut b = 0;
        while b < n {
            let e = n.min(b + UNIT);
            let len = e - b;
            let blk = h.map(|s| &s[b..e]);
            let ext = ext.range(b, e);
            // The classes (the scalar case analysis' first step), in a vector loop; the
            // half vectors' `(x, y)` and the half extents stored as pairs (gathered below
            // with three moves an element instead of five: 9 % of the time).
            for (i, c) in class[..len].iter_mut().enumerate() {
                let h = Vec3::new(blk[0][i], blk[1][i], blk[2][i]);
                let s = ext.at(i);
                *c = class_of(rect::RectSetup::new(r, h, s).tier_indices);
                pairs[0][i] = [h.x, h.y];
                pairs[1][i] = [s.x, s.y];
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
                        for (j, &i) in idx.iter().enumerate() {
                            let i = i as usize;
                            z[j] = blk[2][i];
                            cpairs[0][j] = pairs[0][i];
                            cpairs[1][j] = pairs[1][i];
                        }
                        // The lane runs over `m` rounded up to a multiple of `PAD` (the
                        // padding repeats the last element, its results unused): the vector
                        // loop then leaves no remainder to a scalar loop of the lane (which
                        // took a sixth of the time: ten classes a unit, each with up to a
                        // vector's worth of elements left over).
                        let padded = m.next_multiple_of(PAD).min(CHUNK);
                        for j in m..padded {
                            z[j] = z[m - 1];
                            cpairs[0][j] = cpairs[0][m - 1];
                            cpairs[1][j] = cpairs[1][m - 1];
                        }
                        let at = |j: usize| {
                            let (p, q) = (cpairs[0][j], cpairs[1][j]);
                            (Vec3::new(p[0], p[1], z[j]), Vec2::new(q[0], q[1]))
                        };
                        for j in 0..padded {
                            let (h, s) = at(j);
                            let (v, sl) = $lane(rect::RectSetup::new(r, h, s));
                            vals[j] = v;
                            slow[j] = sl;
                        }
                        for j in 0..m {
                            out[b + idx[j] as usize] = if slow[j] {
                                let (h, s) = at(j);
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
                    // A constant condition: the `f64` pairs are not compiled in `f32`.
                    if $k < NT * NT {
                        pass!($k, |st: rect::RectSetup| st.lane(PAIRS[$k].0, PAIRS[$k].1));
                    }
                )*};
            }
            pairs!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24);
            // The closed form's lane (a long side): the four-edge form with the polynomial
            // `atan2`; the elements it does not take (far field, 1D closed form) flagged.
            pass!(CLOSED, |st: rect::RectSetup| st
                .closed_lane(atan2_upper_lane));
            b = e;
        }
    }
}
