//! Projected-space filtering (TK21) over slices: one GGX material, a pixel kernel per element
//! ([`ggx_d_projected`]) or a footprint per element through the clamp rules
//! ([`ggx_d_filtered_projected`], the front door's `Projected` method).
//!
//! The lane is the scalar route's own steps: the sanitiser's fast path
//! (`Covariance::is_sane`), the lobe's part of [`projected`] computed once per batch and its
//! kernel part per element (`filter::ProjectedBase`, shared with the scalar
//! path), the representation of the filtered matrix where its determinant clamp is inactive
//! (`RoughnessMatrix::from_entries_unclamped`) and GGX's lane `D`. Flagged, and evaluated by
//! the scalar route: a kernel off the sanitiser's fast path (non-finite, indefinite, trace
//! above `KERNEL_MAX`) and a filtered matrix whose determinant clamp acts or whose
//! determinant needs the rescaled evaluation.

use super::super::super::filter::{ProjectedBase, projected};
use super::super::super::kernel::{ClampRules, Covariance};
use super::super::super::ndf::Ndf;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::super::super::{F, Vec3};
use super::super::columns::{Covariances, Footprints, footprint, footprint_columns};
use super::super::engine::{Kernel, run};
use super::Sealed as _;
use super::ndf::LaneD;

per_form! {
    /// [`Ndf::d`] of GGX filtered in projected space (Tokuyoshi and
    /// Kaplanyan 2021, JCGT 10(2), Listing 1: `P = A (I - A)^-1`, `P' = P + 2 Sigma`, `A' = P'
    /// (I + P')^-1`; [`projected`]) for each half vector `h_i = (hx[i], hy[i], hz[i])` and pixel
    /// kernel `Sigma_i` (slope^2, e.g. [`Footprint::covariance`](super::super::super::Footprint::covariance)
    /// after the caller's clamp rules): `out[i] = Ggx::new(projected(*r, Sigma_i)).d(h_i)` per
    /// steradian, **bit for bit**. The kernel is sanitised as by [`projected`] (NaN: no
    /// filtering; infinite: the widest kernel; indefinite: the nearest PSD matrix). `0` for
    /// `h_z <= 0` and NaN `h`. Returns the number of elements written (the shortest slice).
    /// Allocates nothing.
    ///
    /// The front door's [`Projected`](super::super::super::filter::Projected) method applies
    /// [`ClampRules::filter_projected`](super::super::super::ClampRules::filter_projected) to a
    /// footprint first (maximum extent, `kappa`): with `rules.kernel(rules.footprint(fp)
    /// .covariance(sigma))` as `Sigma_i` this is that route (the determinant clamp
    /// `tau = det A` is [`projected`]'s).
    pub fn ggx_d_projected(
        r: &R,
        kernels: Covariances<'_>,
        hx: &[F],
        hy: &[F],
        hz: &[F],
        out: &mut [F],
    ) -> usize {
        let kernel = ProjectedD {
            r: *r,
            base: ProjectedBase::new(*r),
            tau: r.lobe_det(),
        };
        run(
            &kernel,
            [hx, hy, hz, kernels.s11, kernels.s12, kernels.s22],
            [out],
        )
    }
}

/// `D` of `Ggx::new(projected(r, Sigma))`.
struct ProjectedD<R> {
    r: R,
    base: ProjectedBase,
    /// The determinant clamp of [`projected`]: `det A`.
    tau: f64,
}

impl<R: Roughness> Kernel<6, 1> for ProjectedD<R> {
    const WIDE_ONLY: bool = true;

    #[inline(always)]
    fn lane(&self, [hx, hy, hz, s11, s12, s22]: [F; 6]) -> ([F; 1], bool) {
        let k = Covariance::new(s11, s12, s22);
        let (v, slow) = ggx_d_of_entries(self.base.entries(k), self.tau, Vec3::new(hx, hy, hz));
        ([v], slow | !k.is_sane())
    }

    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, s11, s12, s22]: [F; 6]) -> [F; 1] {
        let a = projected(self.r, Covariance::new(s11, s12, s22));
        [Ggx::new(a).d(Vec3::new(hx, hy, hz))]
    }
}

/// GGX's lane `D(m)` of the filtered matrix with entries `(a11, a12, a22)` where its
/// determinant clamp `tau` is inactive (`RoughnessMatrix::from_entries_unclamped`, the scalar
/// path's matrix): `(D, flagged)`, flagged where the clamp would act.
#[inline(always)]
fn ggx_d_of_entries((a11, a12, a22): (F, F, F), tau: f64, m: Vec3) -> (F, bool) {
    let (a, ok) = RoughnessMatrix::from_entries_unclamped(a11, a12, a22, tau);
    let (v, slow) = Ggx::new(a).d_lane(m);
    (v, slow | !ok)
}

per_form! {
    /// GGX filtered in projected space (TK21 Listing 1, [`ggx_d_projected`]) through the
    /// clamped pipeline for each half vector and footprint: `out[i] =
    /// Ggx::new(rules.filter_projected(*r, fp_i, sigma)).d(h_i)`
    /// ([`ClampRules::filter_projected`]: footprint extent, kernel roughness `kappa`,
    /// determinant clamp; the front door's `Projected` method), **bit for bit**. Returns the
    /// number of elements written. Allocates nothing.
    ///
    /// One lane (the projected filter's kernel part runs in `f64` in both precisions, so an `f32`
    /// first tier would gain nothing): the rules' fast paths and the eigenvalue clamp's common
    /// case (`ClampRules::filter_projected_entries_lane`, the kernel's sanity decided exactly),
    /// the kernel part on the lobe's part computed once per batch (`filter::ProjectedBase`,
    /// shared with the scalar path), the matrix where its determinant clamp is inactive and GGX's
    /// lane `D`; every other element flagged and evaluated by the scalar route. As
    /// [`ggx_d_projected`], it runs its lanes with 256-bit vectors or wider only (the
    /// scalar route on the SSE2 baseline).
    #[allow(clippy::too_many_arguments)]
    pub fn ggx_d_filtered_projected(
        r: &R,
        rules: &ClampRules,
        sigma: F,
        hx: &[F],
        hy: &[F],
        hz: &[F],
        fp: Footprints<'_>,
        out: &mut [F],
    ) -> usize {
        let kernel = FilteredProjected {
            r: *r,
            base: ProjectedBase::new(*r),
            rules: *rules,
            sigma,
        };
        run(&kernel, footprint_columns([hx, hy, hz], fp), [out])
    }
}

/// `D` of `Ggx::new(rules.filter_projected(r, fp, sigma))`.
struct FilteredProjected<R> {
    r: R,
    base: ProjectedBase,
    rules: ClampRules,
    sigma: F,
}

impl<R: Roughness> Kernel<7, 1> for FilteredProjected<R> {
    // As `ggx_d_projected`'s lane: both branches of the projected filter's clamps in `f64`.
    const WIDE_ONLY: bool = true;

    #[inline(always)]
    fn lane(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let fp = footprint(ux, uy, vx, vy);
        let (e, tau, ok) = self
            .rules
            .filter_projected_entries_lane(self.r, &self.base, fp, self.sigma);
        let (v, slow) = ggx_d_of_entries(e, tau, Vec3::new(hx, hy, hz));
        ([v], slow | !ok)
    }

    // Always inlined: out of line, the footprint travels through memory and is read back
    // with wider loads than it was stored with (a store-forwarding stall).
    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> [F; 1] {
        let fp = footprint(ux, uy, vx, vy);
        let a = self.rules.filter_projected(self.r, fp, self.sigma);
        [Ggx::new(a).d(Vec3::new(hx, hy, hz))]
    }
}
