//! The exact Gaussian-filtered GGX ([`GaussianFilteredGgx`], KHPL16 section 5.2's filter
//! computed by the mixture identity) over slices of micronormals for one lobe.
//!
//! Two lanes (a tiered kernel of the engine), each the scalar `D`'s own steps
//! (`GaussianFilteredGgx::d_lane`: the checks as selects, the `f64` whitening, and `J` by the
//! rule the scalar path picks, shared through `gaussian_ggx_quad::rule`): the first holds the
//! far-tail series and the fixed 8-node (`f32`) / 12-node (`f64`) Gauss-Laguerre rule; the
//! elements where the scalar path takes the trapezoid rule in `ln w` (near the peak of a lobe
//! whose kernel widens its variance by more than about `1.8 %` along some axis, `2 l1 >
//! 0.0177 (1 + q)`, `q` the squared whitened slope; `0.01` in `f64`) are gathered and run by
//! the second, the trapezoid rule's first 3 chunks of 8 nodes (`f32`; 9 of 4 in `f64`) as
//! straight-line code with the loop's truncation test as a select. For one lobe the second
//! lane runs in two stages (the engine's staged second lane): the set-up and the first 2
//! chunks (`f32`; 7 in `f64`) for every element, then the set-up again and the last chunk for
//! those not stopped by then, gathered, so that the elements that stop early do not compute
//! the longest chunk count. With the lobe built per element ([`ggx_d_filtered_exact`]) the
//! second stage would build it again, which costs more than it saves: that lane stays in one
//! stage. What the trapezoid rule needs longer for (kernels of several lobe variances) is
//! flagged and evaluated by the scalar `D`. On SSE2 the second lane does not pay and the
//! driver leaves those elements to the scalar `D` there (`docs/batch_measurements.md`).

use super::super::super::filter::{GaussianFilteredGgx, TrapezoidState};
use super::super::super::kernel::ClampRules;
use super::super::super::ndf::Ndf;
use super::super::super::ndf::roughness::Roughness;
use super::super::super::{F, Vec3};
use super::super::columns::{Footprints, footprint, footprint_columns};
use super::super::engine::{Carry, Kernel, run};
use super::ndf::{D, LaneD};

/// [`Ndf::d`](super::super::super::ndf::Ndf::d) of the exact Gaussian-filtered GGX lobe `lobe` for
/// each micronormal `m_i = (mx[i], my[i], mz[i])`: `out[i] = lobe.d(m_i) = P22_Sigma(s(m)) / m_z^4` per steradian,
/// `P22_Sigma = J / (pi sqrt(det A))` the GGX slope density of roughness `A` convolved with
/// the lobe's kernel `N(0, Sigma)` (KHPL16 section 5.2, eq. 15 per mixture component; module
/// docs of [`GaussianFilteredGgx`]), **bit for bit**. `0` for `m_z <= 0` and non-finite `m`,
/// as the scalar function. One lobe for the whole batch (a filtered lobe tabulated or baked
/// over many half vectors); build it once with [`GaussianFilteredGgx::new`]. Returns the
/// number of elements written (the shortest slice). Allocates nothing.
///
/// The scalar path already runs its nodes as vectors (a loop over 8 nodes), so the lanes gain
/// the wider vectors, the set-up in lanes and no branches; a kernel of several lobe
/// variances, whose trapezoid rule runs longer than the lane's chunks, falls back to the
/// scalar path for those elements (speed: `docs/batch_measurements.md`).
pub fn gaussian_filtered_ggx_d(
    lobe: &GaussianFilteredGgx,
    mx: &[F],
    my: &[F],
    mz: &[F],
    out: &mut [F],
) -> usize {
    run(&D(*lobe), [mx, my, mz], [out])
}

impl LaneD for GaussianFilteredGgx {
    /// The far tail and Gauss-Laguerre (every element of a lightly filtered lobe, the tails
    /// of any); the trapezoid rule's elements, flagged, go to the second lane.
    #[inline(always)]
    fn d_lane(&self, m: Vec3) -> (F, bool) {
        GaussianFilteredGgx::d_lane::<false>(self, m)
    }
    const TIERED: bool = true;
    const FULL_COVERS: bool = false;
    const FULL_WIDE_ONLY: bool = true;
    /// Where the scalar path takes the trapezoid rule.
    #[inline(always)]
    fn d_second(&self, m: Vec3) -> bool {
        GaussianFilteredGgx::takes_trapezoid(self, m)
    }
    /// The trapezoid rule's first chunks (the elements the first lane flags).
    #[inline(always)]
    fn d_lane_full(&self, m: Vec3) -> (F, bool) {
        GaussianFilteredGgx::d_lane::<true>(self, m)
    }
    /// The trapezoid lane in two stages: its first chunks for every element, the rest for
    /// those not stopped by then.
    const FULL_STAGED: bool = true;
    #[inline(always)]
    fn d_full_one(&self, m: Vec3) -> ((F, bool), bool, Carry) {
        // The trapezoid rule's partial sums are one `Carry` (`STATE_F = CARRY` values).
        let (v, slow, more, state) = self.d_trapezoid_first(m);
        ((v, slow), more, state.f)
    }
    #[inline(always)]
    fn d_full_two(&self, m: Vec3, carry: Carry) -> (F, bool) {
        self.d_trapezoid_rest(m, &TrapezoidState { f: carry })
    }
}

per_form! {
    /// The exact Gaussian-filtered GGX with a footprint per element through the clamp rules (the
    /// front door's `ExactGaussian` method for GGX): `out[i] = GaussianFilteredGgx::new(*r,
    /// rules.kernel(rules.footprint(fp_i).covariance(sigma))).d(h_i)` per steradian, **bit for
    /// bit**, `sigma` the pixel filter's standard deviation in pixels. Returns the number of
    /// elements written. Allocates nothing.
    ///
    /// The lanes of [`gaussian_filtered_ggx_d`] with the lobe built per element in the lane (the
    /// rules' kernel by `ClampRules::kernel_lane`, the kernel's sanity decided exactly, then
    /// [`GaussianFilteredGgx::new`]'s steps without its sanitiser, where the kernel is sane); an element whose footprint or kernel leaves the
    /// rules' fast paths or the eigenvalue clamp's common case is flagged and evaluated by the
    /// scalar route.
    #[allow(clippy::too_many_arguments)]
    pub fn ggx_d_filtered_exact(
        r: &R,
        rules: &ClampRules,
        sigma: F,
        hx: &[F],
        hy: &[F],
        hz: &[F],
        fp: Footprints<'_>,
        out: &mut [F],
    ) -> usize {
        let kernel = ExactFiltered {
            r: *r,
            rules: *rules,
            sigma,
        };
        run(&kernel, footprint_columns([hx, hy, hz], fp), [out])
    }
}

/// `D` of `GaussianFilteredGgx::new(r, rules.kernel(rules.footprint(fp).covariance(sigma)))`.
struct ExactFiltered<R> {
    r: R,
    rules: ClampRules,
    sigma: F,
}

impl<R: Roughness> ExactFiltered<R> {
    /// The element's lobe in the lane, and whether its kernel is the scalar route's.
    #[inline(always)]
    fn lobe(&self, ux: F, uy: F, vx: F, vy: F) -> (GaussianFilteredGgx, bool) {
        let fp = footprint(ux, uy, vx, vy);
        let (k, ok) = self.rules.kernel_lane::<true>(fp, self.sigma);
        // `new` sanitises the rules' kernel again: the eigenvalue clamp can leave a nearly
        // singular kernel within rounding of indefinite (found by the tiers test's rank-one
        // footprints), which the sanitiser then changes; such elements are flagged.
        (
            GaussianFilteredGgx::of_sanitized(self.r, k),
            ok & k.is_sane(),
        )
    }
}

impl<R: Roughness> Kernel<7, 1> for ExactFiltered<R> {
    // The tiers of `gaussian_filtered_ggx_d` (its `LaneD` constants). On SSE2 the first lane,
    // with the lobe built per element in `f64`, is at par with the scalar route.
    const TIERED: bool = true;
    const FULL_COVERS: bool = false;
    const FULL_WIDE_ONLY: bool = true;

    #[inline(always)]
    fn lane(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let (lobe, ok) = self.lobe(ux, uy, vx, vy);
        let (v, slow) = lobe.d_lane::<false>(Vec3::new(hx, hy, hz));
        ([v], slow | !ok)
    }
    #[inline(always)]
    fn lane_full(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let (lobe, ok) = self.lobe(ux, uy, vx, vy);
        let (v, slow) = lobe.d_lane::<true>(Vec3::new(hx, hy, hz));
        ([v], slow | !ok)
    }
    // Not `FULL_STAGED`: its second stage would build the element's lobe again, which costs
    // more than the chunks it saves.
    #[inline(always)]
    fn second(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> bool {
        self.lobe(ux, uy, vx, vy)
            .0
            .takes_trapezoid(Vec3::new(hx, hy, hz))
    }
    // Always inlined, as `Filtered::scalar` (the footprint through memory stalls).
    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> [F; 1] {
        let fp = footprint(ux, uy, vx, vy);
        let rules = self.rules;
        let k = rules.kernel(rules.footprint(fp).covariance(self.sigma));
        [GaussianFilteredGgx::new(self.r, k).d(Vec3::new(hx, hy, hz))]
    }
}
