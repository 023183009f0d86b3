//! The samplers' densities over slices: the `D(m) m_z` pdf, the visible-normal pdf `D_wo(m)`
//! and the reflection pdf `D_wo(m) / (4 wo.m)` of GGX and Beckmann, in every roughness form (multiple importance
//! sampling over a batch of paths, baking).
//!
//! Each lane is the scalar function's own formula core (`normal_pdf_core`,
//! `visible_normal_pdf_core`, `reflection_pdf_core` of the sampling module) on the NDF's lane `D` and `Lambda`
//! ([`LaneNdf`]), its checks as selects. Flagged, and evaluated by the scalar function: an
//! element whose `D` or `Lambda` lane is flagged (a `Lambda` direction that needs rescaling,
//! a grazing view, a Beckmann result out of the polynomial exponential's range) and, for the
//! reflection pdf, a view whose normalisation needs the rescaling of
//! [`crate::f32::vector::unit`]. GGX's pdfs are therefore the scalar values bit for bit;
//! Beckmann's carry the lane `D` and `Lambda` bounds (module docs of [`batch`](super::super)).

use super::super::super::ndf::beckmann::Beckmann;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::sampling::{
    NdfSampling, normal_pdf_core, reflection_pdf_core, visible_normal_pdf_core,
};
use super::super::super::{F, Vec3};
use super::super::columns::Vec3s;
use super::super::engine::{Kernel, run};
use super::ndf::LaneNdf;
use super::sample::unit_direct;

per_form! {
    /// [`NdfSampling::normal_pdf`] of GGX (the density of [`super::ggx_sample_normal`]) for each
    /// unit micronormal `m_i = (mx[i], my[i], mz[i])`: `out[i] = Ggx::new(*r).normal_pdf(m_i) =
    /// D(m) m_z` per steradian (KHPL16 eq. 2), **bit for bit**. `0` for `m_z <= 0` and non-finite
    /// `m`, as the scalar function. Returns the number of elements written (the shortest slice).
    /// Allocates nothing.
    pub fn ggx_normal_pdf(r: &R, mx: &[F], my: &[F], mz: &[F], out: &mut [F]) -> usize {
        run(&NormalPdf(Ggx::new(*r)), [mx, my, mz], [out])
    }
}

per_form! {
    /// [`NdfSampling::normal_pdf`] of Beckmann (the density of [`super::beckmann_sample_normal`]):
    /// `out[i] = Beckmann::new(*r).normal_pdf(m_i) = D(m) m_z` within Beckmann `D`'s lane bound
    /// plus the product's rounding in each path (relative `E + 4 eps`, plus `x eps` where the
    /// scalar `D` takes its far-tail branch; in `f32` against the `f64` scalar path `(12 + 4 x)
    /// eps`, `tests/batch_bounds.rs`); where the lane `D` flushes below `F::MIN_POSITIVE`, `0`
    /// (absolute error below `F::MIN_POSITIVE m_z`). `0` for `m_z <= 0` and non-finite `m`.
    /// Returns the number of elements written. Allocates nothing.
    pub fn beckmann_normal_pdf(
        r: &R,
        mx: &[F],
        my: &[F],
        mz: &[F],
        out: &mut [F],
    ) -> usize {
        run(&NormalPdf(Beckmann::new(*r)), [mx, my, mz], [out])
    }
}

per_form! {
    /// [`NdfSampling::visible_normal_pdf`] of GGX for each view `wo_i` and unit micronormal
    /// `m_i`: `out[i] = Ggx::new(*r).visible_normal_pdf(wo_i, m_i) = G1(wo) max(0, wo.m) D(m) /
    /// wo_z` per steradian of `m`, `G1 = 1 / (1 + Lambda(wo))` (Heitz 2014 eq. 16; Heitz and
    /// d'Eon 2014 eq. 2), **bit for bit**. `0` for `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0`,
    /// non-finite input or a non-finite value, as the scalar function (never NaN). `wo` need not
    /// be normalised. Returns the number of elements written (the shortest of the seven
    /// slices). Allocates nothing.
    pub fn ggx_visible_normal_pdf(
        r: &R,
        wo: Vec3s<'_>,
        m: Vec3s<'_>,
        out: &mut [F],
    ) -> usize {
        run(&VisiblePdf(Ggx::new(*r)), six(wo, m), [out])
    }
}

per_form! {
    /// [`NdfSampling::visible_normal_pdf`] of Beckmann for each view and unit micronormal (as
    /// [`ggx_visible_normal_pdf`]): `out[i] = Beckmann::new(*r).visible_normal_pdf(wo_i, m_i)`
    /// within the bound of the module docs of [`batch`](super::super) (the lane `D`'s relative `E + 2 eps`
    /// and the lane `Lambda`'s absolute `L (1 + Lambda)` over `1 + Lambda`, plus the formula's
    /// sum's and three operations' roundings in each path: first order `E + L + 10 eps + (5 + 3
    /// a^2) eps Lambda / (1 + Lambda)`; in `f32` against the `f64` scalar path: `(15 + 4 x) eps +
    /// L + (13 + 7 a^2) eps Lambda / (1 + Lambda) + 3 eps sum|wo_k m_k| / wo.m`, derived in
    /// `tests/batch_bounds.rs`); where the lane `D` flushes below `F::MIN_POSITIVE`, an absolute
    /// `F::MIN_POSITIVE wo.m / (wo_z (1 + Lambda))`. `0` exactly where the scalar function gives
    /// `0`. Returns the number of elements written. Allocates nothing.
    pub fn beckmann_visible_normal_pdf(
        r: &R,
        wo: Vec3s<'_>,
        m: Vec3s<'_>,
        out: &mut [F],
    ) -> usize {
        run(&VisiblePdf(Beckmann::new(*r)), six(wo, m), [out])
    }
}

per_form! {
    /// [`NdfSampling::reflection_pdf_from_normal`] of GGX for each view `wo_i` and unit half
    /// vector `m_i`: `out[i] = Ggx::new(*r).reflection_pdf_from_normal(wo_i, m_i) = G1(wo) D(m) /
    /// (4 wo_z)` per steradian of `wi = reflect(wo, m)` (Walter et al. 2007 eq. 14, `wo`
    /// normalised), **bit for bit**. `0` for `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0`, non-finite
    /// input or a non-finite value, as the scalar function. Returns the number of elements
    /// written. Allocates nothing.
    pub fn ggx_reflection_pdf_from_normal(
        r: &R,
        wo: Vec3s<'_>,
        m: Vec3s<'_>,
        out: &mut [F],
    ) -> usize {
        run(&ReflectionPdf(Ggx::new(*r)), six(wo, m), [out])
    }
}

per_form! {
    /// [`NdfSampling::reflection_pdf_from_normal`] of Beckmann (as
    /// [`ggx_reflection_pdf_from_normal`]) within the bound of the module docs of [`batch`](super::super) (as
    /// [`beckmann_visible_normal_pdf`], less the `wo.m` factor; against `f64` plus the
    /// normalisation of `wo`: `o_z` within `3 eps`, its direction moving `Lambda` by `(4 a^2 + 6)
    /// eps Lambda`, `tests/batch_bounds.rs`).
    /// Returns the number of elements written. Allocates nothing.
    pub fn beckmann_reflection_pdf_from_normal(
        r: &R,
        wo: Vec3s<'_>,
        m: Vec3s<'_>,
        out: &mut [F],
    ) -> usize {
        run(&ReflectionPdf(Beckmann::new(*r)), six(wo, m), [out])
    }
}

/// The six columns of two vectors.
#[inline(always)]
fn six<'a>(a: Vec3s<'a>, b: Vec3s<'a>) -> [&'a [F]; 6] {
    [a.x, a.y, a.z, b.x, b.y, b.z]
}

/// `abs() < inf` per component: `is_finite` as compares (no branch, no integer bit tests).
#[inline(always)]
fn finite(v: Vec3) -> bool {
    (v.x.abs() < F::INFINITY) & (v.y.abs() < F::INFINITY) & (v.z.abs() < F::INFINITY)
}

/// The `D(m) m_z` pdf of an NDF.
struct NormalPdf<N>(N);

impl<N: LaneNdf + NdfSampling> Kernel<3, 1> for NormalPdf<N> {
    /// [`NdfSampling::normal_pdf`]'s checks as one select around its core.
    #[inline(always)]
    fn lane(&self, [x, y, z]: [F; 3]) -> ([F; 1], bool) {
        let m = Vec3::new(x, y, z);
        let (d, slow) = self.0.d_lane(m);
        let live = finite(m) & (z > 0.0);
        (
            [if live { normal_pdf_core(d, z) } else { 0.0 }],
            live & slow,
        )
    }

    #[inline]
    fn scalar(&self, [x, y, z]: [F; 3]) -> [F; 1] {
        [self.0.normal_pdf(Vec3::new(x, y, z))]
    }
}

/// The visible-normal pdf of an NDF.
struct VisiblePdf<N>(N);

impl<N: LaneNdf + NdfSampling> Kernel<6, 1> for VisiblePdf<N> {
    /// [`NdfSampling::visible_normal_pdf`]'s checks as one select around its core.
    #[inline(always)]
    fn lane(&self, [ox, oy, oz, mx, my, mz]: [F; 6]) -> ([F; 1], bool) {
        let (wo, m) = (Vec3::new(ox, oy, oz), Vec3::new(mx, my, mz));
        let wom = wo.dot(m);
        let (d, slow_d) = self.0.d_lane(m);
        let (lambda, slow_l) = self.0.lambda_lane(wo);
        let v = visible_normal_pdf_core(wom, d, wo.z, lambda);
        let live = finite(wo) & finite(m) & (wo.z > 0.0) & (wom > 0.0);
        let keep = live & (v.abs() < F::INFINITY);
        ([if keep { v } else { 0.0 }], live & (slow_d | slow_l))
    }

    #[inline]
    fn scalar(&self, [ox, oy, oz, mx, my, mz]: [F; 6]) -> [F; 1] {
        [self
            .0
            .visible_normal_pdf(Vec3::new(ox, oy, oz), Vec3::new(mx, my, mz))]
    }
}

/// The reflection pdf (from the half vector) of an NDF.
struct ReflectionPdf<N>(N);

impl<N: LaneNdf + NdfSampling> Kernel<6, 1> for ReflectionPdf<N> {
    /// [`NdfSampling::reflection_pdf_from_normal`]'s checks as one select around its core;
    /// `wo` normalised by the direct path of `vector::unit` (flagged where that rescales).
    #[inline(always)]
    fn lane(&self, [ox, oy, oz, mx, my, mz]: [F; 6]) -> ([F; 1], bool) {
        let (wo, m) = (Vec3::new(ox, oy, oz), Vec3::new(mx, my, mz));
        let (o, direct) = unit_direct(wo);
        let (d, slow_d) = self.0.d_lane(m);
        let (lambda, slow_l) = self.0.lambda_lane(o);
        let v = reflection_pdf_core(d, o.z, lambda);
        let live = finite(wo) & finite(m) & (wo.z > 0.0);
        let keep = live & (o.dot(m) > 0.0) & (v.abs() < F::INFINITY);
        (
            [if keep { v } else { 0.0 }],
            live & (!direct | slow_d | slow_l),
        )
    }

    #[inline]
    fn scalar(&self, [ox, oy, oz, mx, my, mz]: [F; 6]) -> [F; 1] {
        [self
            .0
            .reflection_pdf_from_normal(Vec3::new(ox, oy, oz), Vec3::new(mx, my, mz))]
    }
}
