//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::super::filter::rect;
use super::super::super::footprint::Footprint;
use super::super::super::kernel::{ClampRules, RectBounds};
use super::super::super::ndf::roughness::AxisAligned;
use super::super::super::{F, Vec2, Vec3};
use super::super::columns::Footprints;
use super::super::engine::lane_math::{WIDE, atan2_upper_lane};
use super::super::engine::{SimdLoop, dispatch};
use crate::math::Real;
use classes::{CLOSED, NCLASS, PAD, PAIRS, UNIT, class_of, class_of32, sort_by_class, tri};

mod classes;
mod lanes32;

/// The columns the lanes read: `(h_x, h_y, h_z, s_x, s_y)`, or the `f32` lanes' setup.
const NCOL: usize = 5;

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
///   `batch::kernels::rect::lanes32`, in `f32` arithmetic with two more tiers (8 and 10 points) than the
///   scalar `f32` path; not bit for bit: within `78 u |D|` of the exact `D` (`u = 2^-24`,
///   derived there; `4.6e-6` relative) plus the inputs' rounding (`u_c`, `v_c` to `4 u`, the
///   half extents to `2 u`) times `D`'s sensitivity to them. Tested against the `f64` scalar
///   path in `tests/batch_bounds.rs`: worst `0.12` of the bound, `11.4 u` relative, where the
///   scalar `f32` path is within about `2 u` (the `f32` lanes run at twice the width of
///   `f64` lanes that would match the scalar path bit for bit).
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
    dispatch(RectLoop {
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
    /// The elements `start..end` (within the slices).
    fn range(self, start: usize, end: usize) -> Self;
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
    fn range(self, start: usize, end: usize) -> Self {
        Self(self.0.map(|s| &s[start..end]))
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
    fn range(self, start: usize, end: usize) -> Self {
        Self {
            bounds: self.bounds,
            fp: self.fp.map(|s| &s[start..end]),
        }
    }
    #[inline(always)]
    fn at(self, i: usize) -> Vec2 {
        let [ux, uy, vx, vy] = self.fp;
        let f = Footprint::from_slope_derivatives(Vec2::new(ux[i], uy[i]), Vec2::new(vx[i], vy[i]));
        self.bounds.apply(f.bounding_rect()).half_extent
    }
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

impl<E: Extents> SimdLoop for RectLoop<'_, E> {
    // The lanes pay on SSE2 too (measured with `FILTERED_NDF_SIMD=sse2-lanes`).
    const WIDE_ONLY: bool = false;

    #[inline(always)]
    fn run_scalar(self) {
        let Self { r, h, ext, out } = self;
        for (i, o) in out.iter_mut().enumerate() {
            *o = rect::d_rect(r, Vec3::new(h[0][i], h[1][i], h[2][i]), ext.at(i));
        }
    }

    #[inline(always)]
    fn run_lanes(self) {
        let Self { r, h, ext, out } = self;
        let n = out.len();
        let consts = lanes32::Consts::new(&r);
        let mut unit = Unit::new();
        let mut start = 0;
        while start < n {
            let end = n.min(start + UNIT);
            let h = h.map(|s| &s[start..end]);
            let ext = ext.range(start, end);
            let len = end - start;
            unit.classify(r, consts, h, ext, len);
            let bounds = sort_by_class(&unit.class, len, &mut unit.perm, &mut unit.inv);
            unit.class_lanes(r, consts, &bounds);
            unit.closed_form_lane(r, h, ext, &bounds);
            unit.results(r, h, ext, len, &mut out[start..end]);
            start = end;
        }
    }
}

/// The buffers of one unit of [`RectLoop`] (on the stack, made once per call).
struct Unit {
    /// Each element's class.
    class: [u8; UNIT],
    /// The offsets sorted by class, with [`PAD`] entries of slack: a class's lane loop runs
    /// over its elements rounded up to a multiple of `PAD`, reading the next class's elements
    /// (or the slack's offset `0`) past its end; those results are never used.
    perm: [u16; UNIT + PAD],
    /// Its inverse: element `j`'s slot in `perm` (the results come back in input order by
    /// gathering through it, a vector loop, rather than scattering through `perm` with a
    /// branch for the flagged elements).
    inv: [u16; UNIT],
    /// What the lanes read, by element: in `f64` the inputs `(h, s)`, in `f32` the `f32`
    /// lanes' setup (`lanes32::Setup::cols`), or the inputs for the closed form's elements.
    cols: [[F; UNIT]; NCOL],
    /// The lanes' results by slot of `perm`.
    vals: [F; UNIT + PAD],
    /// Whether the lane flagged the element of the slot (for the scalar path).
    slow: [bool; UNIT + PAD],
}

/// An element's inputs `(h, s)` as the columns of [`Unit::cols`].
#[inline(always)]
fn inputs<E: Extents>(h: [&[F]; 3], ext: E, i: usize) -> [F; NCOL] {
    let s = ext.at(i);
    [h[0][i], h[1][i], h[2][i], s.x, s.y]
}

/// The half vector and half extents of a column's element.
#[inline(always)]
fn split(x: [F; NCOL]) -> (Vec3, Vec2) {
    (Vec3::new(x[0], x[1], x[2]), Vec2::new(x[3], x[4]))
}

/// The vector path of one class of elements: `(D, flagged)` from the element's columns.
trait ClassLane {
    /// The class whose elements the lane evaluates.
    const CLASS: u8;
    fn lane(&self, x: [F; NCOL]) -> (F, bool);
}

/// The `f64` lane of the tier pair `PAIRS[K]` (the scalar path's rules, bit for bit).
struct Pair64<const K: usize>(AxisAligned);

impl<const K: usize> ClassLane for Pair64<K> {
    const CLASS: u8 = K as u8;
    #[inline(always)]
    fn lane(&self, x: [F; NCOL]) -> (F, bool) {
        let (h, s) = split(x);
        rect::RectSetup::new(self.0, h, s).lane(PAIRS[K].0, PAIRS[K].1)
    }
}

/// The `f32` lane of the tier pair `(I, J)`, `I <= J`, on the setup the classification
/// stored.
struct Pair32<const I: usize, const J: usize>(lanes32::Consts);

impl<const I: usize, const J: usize> ClassLane for Pair32<I, J> {
    const CLASS: u8 = tri(I as u8, J as u8);
    #[inline(always)]
    fn lane(&self, x: [F; NCOL]) -> (F, bool) {
        lanes32::lane::<I, J>(self.0, x.map(|v| v.to_f64() as f32))
    }
}

/// The closed form's lane (a long side): the four-edge form with the polynomial `atan2`; the
/// elements it does not take (far field, 1D closed form) flagged.
struct ClosedForm(AxisAligned);

impl ClassLane for ClosedForm {
    const CLASS: u8 = CLOSED;
    #[inline(always)]
    fn lane(&self, x: [F; NCOL]) -> (F, bool) {
        let (h, s) = split(x);
        rect::RectSetup::new(self.0, h, s).closed_lane(atan2_upper_lane)
    }
}

impl Unit {
    #[inline(always)]
    fn new() -> Self {
        Self {
            class: [0; UNIT],
            perm: [0; UNIT + PAD],
            inv: [0; UNIT],
            cols: [[0.0; UNIT]; NCOL],
            vals: [0.0; UNIT + PAD],
            slow: [false; UNIT + PAD],
        }
    }

    /// The classes (the scalar case analysis' first step) and what the lanes read, in one
    /// vector loop: in `f64` the inputs `(h, s)`, in `f32` the `f32` lanes' setup.
    #[inline(always)]
    fn classify<E: Extents>(
        &mut self,
        r: AxisAligned,
        consts: lanes32::Consts,
        h: [&[F]; 3],
        ext: E,
        len: usize,
    ) {
        let cols = &mut self.cols;
        for (i, c) in self.class[..len].iter_mut().enumerate() {
            let hi = Vec3::new(h[0][i], h[1][i], h[2][i]);
            let s = ext.at(i);
            let x = if WIDE {
                *c = class_of(rect::RectSetup::new(r, hi, s).tier_indices);
                [hi.x, hi.y, hi.z, s.x, s.y]
            } else {
                let setup = lanes32::Setup::new(consts, hi, s);
                *c = class_of32(setup.tiers);
                setup.cols().map(|x| F::from_f64(x.to_f64()))
            };
            for (col, x) in cols.iter_mut().zip(x) {
                col[i] = x;
            }
        }
    }

    /// One vector loop of `lane` over the sorted offsets of its class (`bounds` from
    /// [`sort_by_class`]), its results into `vals` and `slow`.
    #[inline(always)]
    fn class_pass<L: ClassLane>(&mut self, lane: &L, bounds: &[u16; NCLASS + 1]) {
        let k = usize::from(L::CLASS);
        let (lo, hi) = (usize::from(bounds[k]), usize::from(bounds[k + 1]));
        let m = (hi - lo).next_multiple_of(PAD);
        // Slices of one length: the loop has no bounds checks.
        let perm = &self.perm[lo..lo + m];
        let (vals, slow) = (&mut self.vals[lo..lo + m], &mut self.slow[lo..lo + m]);
        for j in 0..m {
            // Gathered in the lane loop (vector gathers with AVX2 and AVX-512).
            let i = perm[j] as usize % UNIT;
            // The lanes' precondition: the class's own elements (not the padding past them)
            // are of its pair.
            debug_assert!(j >= hi - lo || self.class[i] == L::CLASS);
            let x = [
                self.cols[0][i],
                self.cols[1][i],
                self.cols[2][i],
                self.cols[3][i],
                self.cols[4][i],
            ];
            (vals[j], slow[j]) = lane.lane(x);
        }
    }

    /// The Gauss-Legendre pairs, each its own loop with its tiers as constants (a macro, not
    /// a loop over the pairs: a loop that is not unrolled would leave them variables, and the
    /// case analysis in the lane would stop the vectoriser). One build's pairs are not
    /// compiled in the other.
    #[inline(always)]
    fn class_lanes(&mut self, r: AxisAligned, consts: lanes32::Consts, bounds: &[u16; NCLASS + 1]) {
        macro_rules! pairs64 {
            ($($k:literal)*) => {$(
                self.class_pass(&Pair64::<$k>(r), bounds);
            )*};
        }
        macro_rules! pairs32 {
            ($($i:literal $j:literal),*) => {$(
                self.class_pass(&Pair32::<$i, $j>(consts), bounds);
            )*};
        }
        if WIDE {
            pairs64!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24);
        } else {
            // The pairs `(i, j)`, `i <= j` (`class_of32`).
            pairs32!(0 0, 0 1, 0 2, 0 3, 0 4, 1 1, 1 2, 1 3, 1 4, 2 2, 2 3, 2 4, 3 3, 3 4, 4 4);
        }
    }

    /// The closed form's lane over its class. In `f32` it reads the inputs, put in place of
    /// the setup here (a select in the classification kept that loop from vectorising with
    /// AVX2).
    #[inline(always)]
    fn closed_form_lane<E: Extents>(
        &mut self,
        r: AxisAligned,
        h: [&[F]; 3],
        ext: E,
        bounds: &[u16; NCLASS + 1],
    ) {
        if !WIDE {
            let (lo, hi) = (
                usize::from(bounds[CLOSED as usize]),
                usize::from(bounds[NCLASS]),
            );
            for &i in &self.perm[lo..hi] {
                let i = i as usize % UNIT;
                for (col, x) in self.cols.iter_mut().zip(inputs(h, ext, i)) {
                    col[i] = x;
                }
            }
        }
        self.class_pass(&ClosedForm(r), bounds);
    }

    /// The results back in input order (gathered through `inv`: slices of one length, no
    /// bounds checks but the index's), then the flagged ones by the scalar path.
    #[inline(always)]
    fn results<E: Extents>(&self, r: AxisAligned, h: [&[F]; 3], ext: E, len: usize, out: &mut [F]) {
        for (o, &t) in out.iter_mut().zip(&self.inv[..len]) {
            *o = self.vals[t as usize % UNIT];
        }
        // Any flagged, by a reduction that vectorises (`any` stops early: a scalar loop).
        if self.slow[..len].iter().fold(false, |a, &x| a | x) {
            let flagged = self.perm[..len].iter().zip(&self.slow[..len]);
            for (&i, _) in flagged.filter(|(_, slow)| **slow) {
                let i = i as usize;
                let (hi, s) = split(inputs(h, ext, i));
                out[i] = rect::d_rect(r, hi, s);
            }
        }
    }
}
