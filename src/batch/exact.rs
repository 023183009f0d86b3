//! The exact Gaussian-filtered GGX ([`GaussianFilteredGgx`], KHPL16 section 5.2's filter
//! computed by the mixture identity) over slices of micronormals for one lobe.
//!
//! Two lanes ([`super::lanes::Kernel::TIERED`]), each the scalar `D`'s own steps
//! (`GaussianFilteredGgx::d_lane`: the checks as selects, the `f64` whitening, and `J` by the
//! rule the scalar path picks, shared through `gaussian_ggx_quad::rule`): the first holds the
//! far-tail series and the fixed 8-node (`f32`) / 12-node (`f64`) Gauss-Laguerre rule; the
//! elements where the scalar path takes the trapezoid rule in `ln w` (near the peak of a lobe
//! whose kernel widens its variance by more than about `1.8 %` along some axis, `2 l1 >
//! 0.0177 (1 + q)`, `q` the squared whitened slope; `0.01` in `f64`) are gathered and run by
//! the second, the trapezoid rule's first 3 chunks of 8 nodes (`f32`; 9 of 4 in `f64`) as
//! straight-line code with the loop's truncation test as a select. What the trapezoid rule
//! needs longer for (kernels of several lobe variances) is flagged and evaluated by the
//! scalar `D`. On SSE2 the second lane does not pay (0.96 and 0.88 times the scalar loop's
//! speed in `f32` and `f64`) and the driver leaves those elements to the scalar `D` there.

use super::super::filter::GaussianFilteredGgx;
use super::lanes::run;
use super::ndf::{D, LaneD};
use super::{F, Vec3};

/// [`Ndf::d`](super::super::ndf::Ndf::d) of the exact Gaussian-filtered GGX lobe `lobe` for
/// each micronormal `m_i = (mx[i], my[i], mz[i])`: `out[i] = lobe.d(m_i) = P22_Sigma(s(m)) / m_z^4` per steradian,
/// `P22_Sigma = J / (pi sqrt(det A))` the GGX slope density of roughness `A` convolved with
/// the lobe's kernel `N(0, Sigma)` (KHPL16 section 5.2, eq. 15 per mixture component; module
/// docs of [`GaussianFilteredGgx`]), **bit for bit**. `0` for `m_z <= 0` and non-finite `m`,
/// as the scalar function. One lobe for the whole batch (a filtered lobe tabulated or baked
/// over many half vectors); build it once with [`GaussianFilteredGgx::new`]. Returns the
/// number of elements written (the shortest slice). Allocates nothing.
///
/// Speed (`benches/batch.rs`, f32, AVX-512; the README's batch table has the figures): about
/// 6 times the scalar loop for a lightly filtered lobe (every element on the far tail and
/// Gauss-Laguerre), about 4 times for a lobe whose kernel is as wide as the lobe (`2 l1 = 1`:
/// 71 % of the bench's half vectors on the trapezoid rule). The scalar path already runs its
/// nodes as vectors (8 per vector), so the lanes gain the wider vectors, the set-up in lanes
/// and no branches; a kernel of several lobe variances, whose trapezoid rule runs longer than
/// the lane's chunks, falls back to the scalar path for those elements.
#[inline]
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
}
