//! Projected-space filtering (TK21) over slices: one GGX material, a pixel kernel per element.
//!
//! The lane is the scalar route's own steps: the sanitiser's fast path
//! (`Covariance::is_sane`), the lobe's part of [`projected`] computed once per batch and its
//! kernel part per element (`filter::ProjectedBase`, shared with the scalar
//! path), the representation of the filtered matrix where its determinant clamp is inactive
//! (`RoughnessMatrix::from_entries_unclamped`) and GGX's lane `D`. Flagged, and evaluated by
//! the scalar route: a kernel off the sanitiser's fast path (non-finite, indefinite, trace
//! above `KERNEL_MAX`) and a filtered matrix whose determinant clamp acts or whose
//! determinant needs the rescaled evaluation.

use super::super::filter::{ProjectedBase, projected};
use super::super::kernel::Covariance;
use super::super::ndf::Ndf;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::Sealed as _;
use super::lanes::{Kernel, run};
use super::ndf::LaneD;
use super::{Covariances, F, Vec3};

per_form! {
    /// [`Ndf::d`] of GGX filtered in projected space (Tokuyoshi and
    /// Kaplanyan 2021, JCGT 10(2), Listing 1: `P = A (I - A)^-1`, `P' = P + 2 Sigma`, `A' = P'
    /// (I + P')^-1`; [`projected`]) for each half vector `h_i = (hx[i], hy[i], hz[i])` and pixel
    /// kernel `Sigma_i` (slope^2, e.g. [`Footprint::covariance`](super::super::Footprint::covariance)
    /// after the caller's clamp rules): `out[i] = Ggx::new(projected(*r, Sigma_i)).d(h_i)` per
    /// steradian, **bit for bit**. The kernel is sanitised as by [`projected`] (NaN: no
    /// filtering; infinite: the widest kernel; indefinite: the nearest PSD matrix). `0` for
    /// `h_z <= 0` and NaN `h`. Returns the number of elements written (the shortest slice).
    /// Allocates nothing.
    ///
    /// The front door's [`Projected`](super::super::filter::Projected) method applies
    /// [`ClampRules::filter_projected`](super::super::ClampRules::filter_projected) to a
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
        let k = ProjectedD {
            r: *r,
            base: ProjectedBase::new(*r),
            tau: r.lobe_det(),
        };
        run(
            &k,
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
        let (b11, b12, b22) = self.base.entries(k);
        let (a, ok) = RoughnessMatrix::from_entries_unclamped(b11, b12, b22, self.tau);
        let (v, slow) = Ggx::new(a).d_lane(Vec3::new(hx, hy, hz));
        ([v], slow | !ok | !k.is_sane())
    }

    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, s11, s12, s22]: [F; 6]) -> [F; 1] {
        let a = projected(self.r, Covariance::new(s11, s12, s22));
        [Ggx::new(a).d(Vec3::new(hx, hy, hz))]
    }
}
