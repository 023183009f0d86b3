//! The exact Gaussian-filtered GGX ([`GaussianFilteredGgx`], KHPL16 section 5.2's filter
//! computed by the mixture identity) over slices of micronormals for one lobe.
//!
//! The lane is the scalar `D`'s own steps (`GaussianFilteredGgx::d_lane`: the checks as
//! selects, the `f64` whitening, and `J` by the rule the scalar path picks, shared through
//! `gaussian_ggx_quad::rule`): the far-tail series or the fixed 8-node (`f32`) / 12-node
//! (`f64`) Gauss-Laguerre rule, both straight-line code. Where the scalar path takes the
//! trapezoid rule in `ln w` (an element-dependent node count, 16 to 64 nodes in `f32`: near
//! the peak of a lobe whose kernel widens its variance by more than about `1.8 %` along some
//! axis, `2 l1 > 0.0177 (1 + q)`, `q` the squared whitened slope; `0.01` in `f64`), the
//! element is flagged and evaluated by the scalar `D`.

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
/// Speed: elements where the scalar path takes the trapezoid rule (near the peak of a lobe
/// whose kernel widens its variance by more than about `1.8 %` along some axis, `2 l1 >
/// 0.0177 (1 + q)` in `f32`, `0.01` in `f64`, `2 l1` of
/// [`GaussianFilteredGgx::kernel_ratio`]) are evaluated by the scalar path after the vector pass;
/// the others (the far tail and Gauss-Laguerre: every element of a lightly filtered lobe,
/// the tails of any) run in vector lanes. The gain is smaller than for the closed-form
/// kernels (about 2 times the scalar loop, `benches/batch.rs`): the scalar path already runs
/// its 8 Gauss-Laguerre nodes as one vector, so the lanes save the per-element set-up and the
/// wider vectors only; a lobe whose elements mostly take the trapezoid rule runs at the
/// scalar loop's speed less the driver's probing of one block in eight (about 5 %).
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
    /// [`GaussianFilteredGgx::d_lane`].
    #[inline(always)]
    fn d_lane(&self, m: Vec3) -> (F, bool) {
        GaussianFilteredGgx::d_lane(self, m)
    }
}
