//! The front door's methods over slices: each half vector with its own pixel footprint, one
//! material and one method for the whole batch.

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
    d_filtered(Beckmann::new, r, rules, sigma, [hx, hy, hz], fp, out)
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
    d_filtered(Ggx::new, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// The kernel shared by the Gaussian-filtered batch functions: the clamped pipeline
/// [`ClampRules::filter_gaussian`] evaluated by the NDF `ndf(A')` at `h_i`. Two lanes (a
/// [`Kernel::TIERED`] kernel): the first takes the pipeline's fast path without the `kappa`
/// rule's eigenvalue clamp ([`ClampRules::filter_gaussian_lane`] with `FULL = false`), the
/// second, over what the first flags, with it; then the NDF's lane `D`. An element where a
/// rule leaves the second lane's fast path is flagged and evaluated by the scalar route.
#[inline]
fn d_filtered<R: Roughness, N: LaneNdf, C: Fn(RoughnessMatrix) -> N>(
    ndf: C,
    r: &R,
    rules: &ClampRules,
    sigma: F,
    [hx, hy, hz]: [&[F]; 3],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let k = Filtered {
        ndf,
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

/// `D` of `ndf(rules.filter_gaussian(r, fp, sigma))`.
/// `C` is the NDF's constructor as a function item (zero-sized, inlined into the lane).
struct Filtered<R, C> {
    ndf: C,
    r: R,
    rules: ClampRules,
    sigma: F,
}

impl<R: Roughness, N: LaneNdf, C: Fn(RoughnessMatrix) -> N> Filtered<R, C> {
    /// The lane of [`ClampRules::filter_gaussian_lane`] with or without the eigenvalue clamp
    /// (`FULL`), then the NDF's lane `D`.
    #[inline(always)]
    fn lane_with<const FULL: bool>(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let fp = Footprint::from_slope_derivatives(Vec2::new(ux, uy), Vec2::new(vx, vy));
        let (a, ok) = self
            .rules
            .filter_gaussian_lane::<R, FULL>(self.r, fp, self.sigma);
        let (v, slow) = (self.ndf)(a).d_lane(Vec3::new(hx, hy, hz));
        ([v], slow | !ok)
    }
}

impl<R: Roughness, N: LaneNdf, C: Fn(RoughnessMatrix) -> N> Kernel<7, 1> for Filtered<R, C> {
    // In `f32` the tiered lanes pay on SSE2 too (measured, `FILTERED_NDF_SIMD=sse2-lanes`
    // against the scalar loop on the bench's realistic inputs: 1.3 times as fast for Beckmann,
    // 1.5 for GGX); in `f64` (two lanes) they do not (0.98 and 0.86), so there the baseline
    // runs the scalar path.
    const WIDE_ONLY: bool = WIDE;
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
        let a = self.rules.filter_gaussian(self.r, fp, self.sigma);
        [(self.ndf)(a).d(Vec3::new(hx, hy, hz))]
    }
}
