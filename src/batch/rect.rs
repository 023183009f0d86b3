//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::filter::rect::{CLOSED_INDEX, Tier};
use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, RectBounds};
use super::super::ndf::roughness::AxisAligned;
use super::lanes::{Body, atan2_upper_lane};
use super::{F, Footprints, Vec2, Vec3};

/// Elements sorted by class at a time: the lane loops' scalar remainders come once per class
/// and unit (with ten classes, a sixth of the elements in units of 512; measured 20 % slower
/// than 4096). `perm` (`u16`) and `class` take 3 bytes an element on the stack.
const UNIT: usize = 4096;
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
/// elements written. Allocates nothing (buffers on the stack: 18 KiB in `f32`, 25 KiB in
/// `f64`).
///
/// Vectorised where the scalar case analysis integrates both axes by Gauss-Legendre rules
/// (short sides against the distance to the integrand's poles: most pixel
/// footprints) and where it takes the four-edge closed form (a long side, KHPL16 Appendix A
/// rewritten as four `atan2`: about a quarter of realistic footprints): per unit of 4096
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

/// The front door's `Rect` method over slices: the exact box-filtered GGX over each
/// footprint's bounding rectangle after the clamp rules, `out[i] = d_rect(*r, h_i,
/// rules.rect(fp_i.bounding_rect(), r.alpha()).half_extent)` (KHPL16 eq. 16 over the
/// rectangle of KHPL16 section 5.2; [`ClampRules::rect`]: maximum extent, floor), as
/// [`d_rect`] on those half extents, bit for bit (so its agreement with the scalar path is
/// [`d_rect`]'s). Returns the number of elements written. Allocates nothing (the half
/// extents of 4096 elements at a time on the stack: 32 KiB in `f32`, 64 KiB in `f64`, besides
/// [`d_rect`]'s).
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
    let n = out
        .len()
        .min(hx.len())
        .min(hy.len())
        .min(hz.len())
        .min(fp.len());
    super::simd::dispatch(RectFootprints {
        r: *r,
        bounds: rules.rect_bounds(r.alpha()),
        h: [&hx[..n], &hy[..n], &hz[..n]],
        fp: [
            &fp.dh_u_x[..n],
            &fp.dh_u_y[..n],
            &fp.dh_v_x[..n],
            &fp.dh_v_y[..n],
        ],
        out: &mut out[..n],
    });
    n
}

/// [`d_rect_filtered`]'s loop: per unit of [`UNIT`] elements, the clamped rectangles' half
/// extents into stack arrays, then [`RectLoop`] over the unit, both in the dispatched
/// instruction set (the rectangles computed outside it ran on the SSE2 baseline: 0.4 ns per
/// element, `f32`, against about 0.1 with AVX-512).
struct RectFootprints<'a> {
    r: AxisAligned,
    bounds: RectBounds,
    h: [&'a [F]; 3],
    fp: [&'a [F]; 4],
    out: &'a mut [F],
}

impl RectFootprints<'_> {
    /// The units, each through [`RectLoop::go`] or, with `SCALAR`, [`RectLoop::go_scalar`].
    #[inline(always)]
    fn units<const SCALAR: bool>(self) {
        let Self {
            r,
            bounds,
            h,
            fp,
            out,
        } = self;
        let n = out.len();
        let mut ex = [0.0 as F; UNIT];
        let mut ey = [0.0 as F; UNIT];
        let mut b = 0;
        while b < n {
            let e = n.min(b + UNIT);
            let len = e - b;
            let [ux, uy, vx, vy] = fp.map(|s| &s[b..e]);
            let its = ex[..len].iter_mut().zip(&mut ey[..len]);
            for (((((x, y), &ux), &uy), &vx), &vy) in its.zip(ux).zip(uy).zip(vx).zip(vy) {
                let f = Footprint::from_slope_derivatives(Vec2::new(ux, uy), Vec2::new(vx, vy));
                let he = bounds.apply(f.bounding_rect()).half_extent;
                (*x, *y) = (he.x, he.y);
            }
            let unit = RectLoop {
                r,
                ins: [
                    &h[0][b..e],
                    &h[1][b..e],
                    &h[2][b..e],
                    &ex[..len],
                    &ey[..len],
                ],
                out: &mut out[b..e],
            };
            if SCALAR {
                unit.go_scalar();
            } else {
                unit.go();
            }
            b = e;
        }
    }
}

impl Body for RectFootprints<'_> {
    const WIDE_ONLY: bool = RectLoop::WIDE_ONLY;

    #[inline(always)]
    fn go(self) {
        self.units::<false>();
    }

    #[inline(always)]
    fn go_scalar(self) {
        self.units::<true>();
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

/// The box filter's loop: per unit of [`UNIT`] elements, each element's class (its tier pair
/// or the closed form: the scalar case analysis' first step, vectorised), a counting sort of
/// the unit by class, then per class chunks of its elements gathered into contiguous columns
/// and evaluated by one vector loop whose tiers are constants (or the closed-form lane); the
/// rest (and every flagged element) by [`rect::d_rect`]. Buffers on the stack: allocates
/// nothing.
struct RectLoop<'a> {
    r: AxisAligned,
    ins: [&'a [F]; 5],
    out: &'a mut [F],
}

impl Body for RectLoop<'_> {
    // The lanes pay on SSE2 too since the closed form has one (measured with
    // `FILTERED_NDF_SIMD=sse2-lanes`: 1.3 to 1.8 times the scalar loop in `f32`, 1.1 in `f64`;
    // before, with the closed form scalar and a scan per pair, 0.7).
    const WIDE_ONLY: bool = false;

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
                        for (j, &i) in idx.iter().enumerate() {
                            let i = i as usize;
                            for (c, s) in cols.iter_mut().zip(&blk) {
                                c[j] = s[i];
                            }
                        }
                        // The lane runs over `m` rounded up to a multiple of `PAD` (the
                        // padding repeats the last element, its results unused): the vector
                        // loop then leaves no remainder to a scalar loop of the lane (which
                        // took a sixth of the time: ten classes a unit, each with up to a
                        // vector's worth of elements left over).
                        let padded = m.next_multiple_of(PAD).min(CHUNK);
                        for j in m..padded {
                            for c in cols.iter_mut() {
                                c[j] = c[m - 1];
                            }
                        }
                        for j in 0..padded {
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
