//! Batch evaluation over slices (structure of arrays), for baking and offline use.
//!
//! Each function evaluates one scalar function of the crate element by element and writes
//! `out[i]`; the result is **bit for bit** the scalar function's (the loop body calls it,
//! inlined, so there is one source of truth per formula). The filtered functions take the
//! same [`ClampRules`] and pixel `sigma` as the scalar route [`ClampRules::filter_gaussian`]
//! and answer exactly what it answers. Inputs are separate slices per component (`mx`, `my`,
//! `mz`, ...), so that a loop over them can be vectorised. Nothing allocates.
//!
//! **Lengths.** Every function processes the common prefix `n = min` of all slice lengths
//! (including `out`), leaves `out[n..]` untouched and returns `n`. It never panics.
//!
//! **Bad input.** As the scalar functions: NaN, infinite or back-facing (`m_z <= 0`)
//! elements give `0` (never NaN), without affecting the other elements.
//!
//! **Vectorisation** (stable Rust, `std` feature, x86-64 baseline SSE2; checked by
//! disassembling the `batch` benchmark, see its header): [`ggx_d`] compiles to packed
//! `mulps`/`divps`/`addps` (4 lanes in `f32`, 2 in `f64`) for all three roughness forms
//! (the matrix form's two representations are loop-invariant, and the loop is unswitched),
//! because its body is GGX's `D` with its checks written as one select. The
//! others call `exp`, branch on data (the filtered matrix's representation, the Beckmann
//! tail) or run the rectangle integral's case analysis per element: they compile to scalar
//! loops (with a few two-lane SLP ops inside an element) and exist for the convenience of a
//! uniform slice API; they run 1.1 to 1.3 times as fast as a hand-written scalar loop (no
//! bounds checks; `beckmann_d` 1.3). Measured per core (`benches/batch.rs`, `f32`): `ggx_d`
//! about 4.4 times the scalar loop for `Isotropic` and `AxisAligned`, 2.5 times for
//! `RoughnessMatrix`; `f64` about 2.2 times.

use super::filter::rect;
use super::footprint::Footprint;
use super::kernel::ClampRules;
use super::ndf::Ndf;
use super::ndf::beckmann::Beckmann;
use super::ndf::ggx::Ggx;
use super::ndf::roughness::{AxisAligned, Roughness, RoughnessMatrix};
use super::{F, Vec2, Vec3};

/// Footprints in structure-of-arrays form: element `i` is the [`Footprint`] with
/// `dh_u = (dh_u_x[i], dh_u_y[i])`, `dh_v = (dh_v_x[i], dh_v_y[i])` (slope change per pixel).
#[derive(Clone, Copy, Debug)]
pub struct Footprints<'a> {
    /// `dh_u.x` per element.
    pub dh_u_x: &'a [F],
    /// `dh_u.y` per element.
    pub dh_u_y: &'a [F],
    /// `dh_v.x` per element.
    pub dh_v_x: &'a [F],
    /// `dh_v.y` per element.
    pub dh_v_y: &'a [F],
}

impl Footprints<'_> {
    /// The shortest of the four slices.
    #[inline]
    pub fn len(&self) -> usize {
        self.dh_u_x
            .len()
            .min(self.dh_u_y.len())
            .min(self.dh_v_x.len())
            .min(self.dh_v_y.len())
    }

    /// Whether [`Footprints::len`] is `0`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// [`Ndf::d`] of GGX (per steradian, TK19 supplement) for each micronormal
/// `m_i = (mx[i], my[i], mz[i])`: `out[i] = Ggx::new(*r).d(m_i)`. Returns the number of
/// elements written (the shortest slice length). Vectorises for `Isotropic` and
/// `AxisAligned` and `RoughnessMatrix` (module docs).
#[inline]
pub fn ggx_d<R: Roughness>(r: &R, mx: &[F], my: &[F], mz: &[F], out: &mut [F]) -> usize {
    let n = out.len().min(mx.len()).min(my.len()).min(mz.len());
    let ggx = Ggx::new(*r);
    // Re-slicing to `n` lets the compiler drop the bounds checks and vectorise.
    let (mx, my, mz, out) = (&mx[..n], &my[..n], &mz[..n], &mut out[..n]);
    for i in 0..n {
        // Ndf::d's checks as one select (`&`, and `abs() < inf` rather than `is_finite`,
        // which compiles to integer bit tests): the same value, bit for bit, without a
        // branch in the loop body.
        let v = ggx.d_unchecked(Vec3::new(mx[i], my[i], mz[i]));
        let keep = (mz[i] > 0.0) & (v.abs() < F::INFINITY);
        out[i] = if keep { v } else { 0.0 };
    }
    n
}

/// [`Ndf::d`] of Beckmann (per steradian) for each micronormal:
/// `out[i] = Beckmann::new(*r).d(m_i)`. Returns the number of elements written. Scalar loop
/// (one `exp` per element).
#[inline]
pub fn beckmann_d<R: Roughness>(r: &R, mx: &[F], my: &[F], mz: &[F], out: &mut [F]) -> usize {
    let n = out.len().min(mx.len()).min(my.len()).min(mz.len());
    let beckmann = Beckmann::new(*r);
    let (mx, my, mz, out) = (&mx[..n], &my[..n], &mz[..n], &mut out[..n]);
    for i in 0..n {
        out[i] = beckmann.d(Vec3::new(mx[i], my[i], mz[i]));
    }
    n
}

/// Filtered Beckmann (exact Gaussian filtering, KHPL16 eq. 15) through the clamped pipeline
/// for each half vector and footprint: `out[i] = Beckmann::new(rules.filter_gaussian(*r,
/// fp_i, sigma)).d(h_i)` ([`ClampRules::filter_gaussian`]: footprint extent, kernel
/// roughness `kappa`, determinant clamp; [`ClampRules::NONE`] for none), `sigma` the pixel
/// filter's standard deviation in pixels (e.g. [`super::kernel::SIGMA_PIXEL`]). Bit for bit
/// the scalar route's value. Returns the number of elements written. Scalar loop.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn beckmann_d_filtered<R: Roughness>(
    r: &R,
    rules: &ClampRules,
    sigma: F,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    d_filtered(Beckmann::new, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// Filtered GGX with the TK19 (section 2.2) matrix approximation `A' = A + 2 Sigma` through
/// the clamped pipeline for each half vector and footprint: `out[i] =
/// Ggx::new(rules.filter_gaussian(*r, fp_i, sigma)).d(h_i)` (see [`beckmann_d_filtered`]).
/// Bit for bit the scalar route's value. Returns the number of elements written. Scalar loop.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn ggx_d_filtered<R: Roughness>(
    r: &R,
    rules: &ClampRules,
    sigma: F,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    d_filtered(Ggx::new, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// The loop shared by the Gaussian-filtered batch functions: the clamped pipeline
/// [`ClampRules::filter_gaussian`] (the one scalar route, inlined) evaluated by the NDF
/// `ndf(A')` at `h_i`.
#[inline]
fn d_filtered<R: Roughness, N: Ndf>(
    ndf: impl Fn(RoughnessMatrix) -> N,
    r: &R,
    rules: &ClampRules,
    sigma: F,
    [hx, hy, hz]: [&[F]; 3],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let n = out
        .len()
        .min(hx.len())
        .min(hy.len())
        .min(hz.len())
        .min(fp.len());
    let (hx, hy, hz, out) = (&hx[..n], &hy[..n], &hz[..n], &mut out[..n]);
    let (ux, uy, vx, vy) = (
        &fp.dh_u_x[..n],
        &fp.dh_u_y[..n],
        &fp.dh_v_x[..n],
        &fp.dh_v_y[..n],
    );
    for i in 0..n {
        let f = Footprint::from_slope_derivatives(Vec2::new(ux[i], uy[i]), Vec2::new(vx[i], vy[i]));
        let a = rules.filter_gaussian(*r, f, sigma);
        out[i] = ndf(a).d(Vec3::new(hx[i], hy[i], hz[i]));
    }
    n
}

/// The exact box-filtered GGX [`rect::d_rect`] (KHPL16 eq. 16) for each half vector
/// `h_i` and slope-domain half extent `(half_x[i], half_y[i])`:
/// `out[i] = d_rect(*r, h_i, (half_x[i], half_y[i]))`. The half extents are the kernel as
/// given (no clamps: pass rectangles already through [`ClampRules::rect`] for the clamped
/// route). Returns the number of elements written. Scalar loop.
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
    let (hx, hy, hz) = (&hx[..n], &hy[..n], &hz[..n]);
    let (half_x, half_y, out) = (&half_x[..n], &half_y[..n], &mut out[..n]);
    for i in 0..n {
        out[i] = rect::d_rect(
            *r,
            Vec3::new(hx[i], hy[i], hz[i]),
            Vec2::new(half_x[i], half_y[i]),
        );
    }
    n
}
