//! The front door's methods over slices: each half vector with its own pixel footprint, one
//! material and one method for the whole batch.

use super::super::filter::ProjectedBase;
use super::super::footprint::Footprint;
use super::super::kernel::ClampRules;
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::lanes::{Kernel, WIDE, run};
use super::ndf::LaneNdf;
use super::{F, Footprints, Vec2, Vec3};

/// Filtered Beckmann (exact Gaussian filtering, KHPL16 eq. 15) through the clamped pipeline
/// for each half vector and footprint: `out[i] = Beckmann::new(rules.filter_gaussian(*r,
/// fp_i, sigma)).d(h_i)` ([`ClampRules::filter_gaussian`]: footprint extent, kernel
/// roughness `kappa`, determinant clamp; [`ClampRules::NONE`] for none), `sigma` the pixel
/// filter's standard deviation in pixels (e.g. [`super::super::kernel::SIGMA_PIXEL`]).
/// Returns the number of elements written. Allocates nothing.
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
    d_filtered(
        Beckmann::new,
        Gaussian,
        r,
        rules,
        sigma,
        [hx, hy, hz],
        fp,
        out,
    )
}

/// Filtered GGX with the TK19 (section 2.2) matrix approximation `A' = A + 2 Sigma` through
/// the clamped pipeline for each half vector and footprint: `out[i] =
/// Ggx::new(rules.filter_gaussian(*r, fp_i, sigma)).d(h_i)` (see [`beckmann_d_filtered`]).
/// Returns the number of elements written. Allocates nothing.
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
    d_filtered(Ggx::new, Gaussian, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// GGX filtered in projected space (TK21 Listing 1, [`super::ggx_d_projected`]) through the
/// clamped pipeline for each half vector and footprint: `out[i] =
/// Ggx::new(rules.filter_projected(*r, fp_i, sigma)).d(h_i)` ([`ClampRules::filter_projected`]:
/// footprint extent, kernel roughness `kappa`, determinant clamp; the front door's
/// `Projected` method), **bit for bit**, in the two lane tiers of [`ggx_d_filtered`]. Returns
/// the number of elements written. Allocates nothing.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn ggx_d_filtered_projected<R: Roughness>(
    r: &R,
    rules: &ClampRules,
    sigma: F,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let route = Projected(ProjectedBase::new(*r));
    d_filtered(Ggx::new, route, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// A clamped filter pipeline of [`ClampRules`] in its lane and scalar forms.
trait Route: Copy {
    /// Whether its lanes pay only with 256-bit vectors or wider ([`Kernel::WIDE_ONLY`]).
    const WIDE_ONLY: bool;
    /// The lane form (`(A', ok)`).
    fn lane<R: Roughness, const FULL: bool>(
        &self,
        rules: &ClampRules,
        r: R,
        fp: Footprint,
        sigma: F,
    ) -> (RoughnessMatrix, bool);
    /// The scalar route.
    fn scalar<R: Roughness>(
        &self,
        rules: &ClampRules,
        r: R,
        fp: Footprint,
        sigma: F,
    ) -> RoughnessMatrix;
}

/// [`ClampRules::filter_gaussian`].
#[derive(Clone, Copy)]
struct Gaussian;

impl Route for Gaussian {
    // In `f32` the tiered lanes pay on SSE2 too (measured, `FILTERED_NDF_SIMD=sse2-lanes`
    // against the scalar loop on the bench's realistic inputs: 1.3 times as fast for Beckmann,
    // 1.5 for GGX); in `f64` (two lanes) they do not (0.98 and 0.86), so there the baseline
    // runs the scalar path.
    const WIDE_ONLY: bool = WIDE;
    #[inline(always)]
    fn lane<R: Roughness, const FULL: bool>(
        &self,
        rules: &ClampRules,
        r: R,
        fp: Footprint,
        sigma: F,
    ) -> (RoughnessMatrix, bool) {
        rules.filter_gaussian_lane::<R, FULL>(r, fp, sigma)
    }
    #[inline(always)]
    fn scalar<R: Roughness>(
        &self,
        rules: &ClampRules,
        r: R,
        fp: Footprint,
        sigma: F,
    ) -> RoughnessMatrix {
        rules.filter_gaussian(r, fp, sigma)
    }
}

/// [`ClampRules::filter_projected`], with the lobe's part computed once.
#[derive(Clone, Copy)]
struct Projected(ProjectedBase);

impl Route for Projected {
    // As `ggx_d_projected`'s lanes: only with wider vectors.
    const WIDE_ONLY: bool = true;
    #[inline(always)]
    fn lane<R: Roughness, const FULL: bool>(
        &self,
        rules: &ClampRules,
        r: R,
        fp: Footprint,
        sigma: F,
    ) -> (RoughnessMatrix, bool) {
        rules.filter_projected_lane::<R, FULL>(r, &self.0, fp, sigma)
    }
    #[inline(always)]
    fn scalar<R: Roughness>(
        &self,
        rules: &ClampRules,
        r: R,
        fp: Footprint,
        sigma: F,
    ) -> RoughnessMatrix {
        rules.filter_projected(r, fp, sigma)
    }
}

/// The kernel shared by the filtered batch functions: the clamped pipeline of `route`
/// ([`ClampRules::filter_gaussian`] or [`ClampRules::filter_projected`]) evaluated by the NDF
/// `ndf(A')` at `h_i`. Two lanes (a
/// [`Kernel::TIERED`] kernel): the first takes the pipeline's fast path without the `kappa`
/// rule's eigenvalue clamp ([`ClampRules::filter_gaussian_lane`] with `FULL = false`), the
/// second, over what the first flags, with it; then the NDF's lane `D`. An element where a
/// rule leaves the second lane's fast path is flagged and evaluated by the scalar route.
#[inline]
#[allow(clippy::too_many_arguments)]
fn d_filtered<R: Roughness, N: LaneNdf, C: Fn(RoughnessMatrix) -> N, M: Route>(
    ndf: C,
    route: M,
    r: &R,
    rules: &ClampRules,
    sigma: F,
    [hx, hy, hz]: [&[F]; 3],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let k = Filtered {
        ndf,
        route,
        r: *r,
        rules: *rules,
        sigma,
    };
    run(
        &k,
        [hx, hy, hz, fp.dh_u_x, fp.dh_u_y, fp.dh_v_x, fp.dh_v_y],
        [out],
    )
}

/// `D` of `ndf(A')`, `A'` the route `M`'s clamped pipeline (`rules.filter_gaussian(r, fp,
/// sigma)` or `rules.filter_projected(..)`). `C` is the NDF's constructor as a function item
/// (zero-sized, inlined into the lane).
struct Filtered<R, C, M> {
    ndf: C,
    route: M,
    r: R,
    rules: ClampRules,
    sigma: F,
}

impl<R: Roughness, N: LaneNdf, C: Fn(RoughnessMatrix) -> N, M: Route> Filtered<R, C, M> {
    /// The lane of [`ClampRules::filter_gaussian_lane`] with or without the eigenvalue clamp
    /// (`FULL`), then the NDF's lane `D`.
    #[inline(always)]
    fn lane_with<const FULL: bool>(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let fp = Footprint::from_slope_derivatives(Vec2::new(ux, uy), Vec2::new(vx, vy));
        let (a, ok) = self
            .route
            .lane::<R, FULL>(&self.rules, self.r, fp, self.sigma);
        let (v, slow) = (self.ndf)(a).d_lane(Vec3::new(hx, hy, hz));
        ([v], slow | !ok)
    }
}

impl<R: Roughness, N: LaneNdf, C: Fn(RoughnessMatrix) -> N, M: Route> Kernel<7, 1>
    for Filtered<R, C, M>
{
    const WIDE_ONLY: bool = M::WIDE_ONLY;
    // The first lane leaves the kappa rule's eigenvalue clamp (a square root and two
    // divisions, once four, which a branch-free lane computes for every element: with four,
    // half of the lane's time) to the second: on the realistic footprints of `benches/batch.rs` 15 % of the
    // elements need it (`tests/batch.rs` checks both tiers).
    const TIERED: bool = true;

    #[inline(always)]
    fn lane(&self, x: [F; 7]) -> ([F; 1], bool) {
        self.lane_with::<false>(x)
    }
    #[inline(always)]
    fn lane_full(&self, x: [F; 7]) -> ([F; 1], bool) {
        self.lane_with::<true>(x)
    }
    // Always inlined: out of line, the footprint travels through memory and is read back
    // with wider loads than it was stored with (a store-forwarding stall, see
    // `ClampRules::filter_gaussian`): 2.3 times the scalar loop's time on SSE2.
    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> [F; 1] {
        let fp = Footprint::from_slope_derivatives(Vec2::new(ux, uy), Vec2::new(vx, vy));
        let a = self.route.scalar(&self.rules, self.r, fp, self.sigma);
        [(self.ndf)(a).d(Vec3::new(hx, hy, hz))]
    }
}
