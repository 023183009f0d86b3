//! The GGX proxy (KHPL16 section 5.4, eq. 18-19 solved exactly: [`proxy::proxy`]) over slices:
//! one axis-aligned GGX material, a footprint per element through the clamp rules.
//!
//! The lane is the scalar route's steps: the rules' clamped bounding rectangle (the
//! `RectBounds` of the box filter's lanes, the same values bit for bit), then per axis the
//! effective roughness `alpha' = s sqrt(t / atan2(H, s))`, `s = sqrt(alpha^2 + H^2)`,
//! `t = H / s` (the module docs of [`proxy`]: `alpha'^2 = (alpha^2 + H^2) t / atan t`),
//! computed in `f64` with `atan2` by [`atan2_upper_lane`] in place of libm's `hypot` and
//! `atan` (which have no lane form), then [`AxisAligned::new_clamped`] and GGX's lane `D`.

use super::super::super::filter::proxy;
use super::super::super::kernel::{ClampRules, RectBounds};
use super::super::super::ndf::Ndf;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::ndf::roughness::AxisAligned;
use super::super::super::{F, Vec3};
use super::super::columns::{Footprints, footprint, footprint_columns};
use super::super::engine::lane_math::atan2_upper_lane;
use super::super::engine::{Kernel, run};
use super::ndf::LaneD;
use crate::math::{self as m, Real};

/// [`Ndf::d`] of the GGX proxy lobe (KHPL16 section 5.4; the front door's
/// [`Proxy`](super::super::super::filter::Proxy) method with `Proxy { clamps: *rules }`) for each half
/// vector `h_i = (hx[i], hy[i], hz[i])` and footprint `fp_i`: `out[i] = Ggx::new(proxy(*r,
/// H_i)).d(h_i)` per steradian, `H_i = rules.rect(fp_i.bounding_rect(), r.alpha())
/// .half_extent` (the clamped bounding rectangle of KHPL16 section 5.2), [`proxy::proxy`] the
/// effective roughness per axis `alpha' = sqrt(alpha^2 + H^2) sqrt(t / atan t)`, `t = H /
/// sqrt(alpha^2 + H^2)` (eq. 19 solved), clamped by [`AxisAligned::new_clamped`]. `0` for
/// `h_z <= 0` and NaN `h`; a NaN half extent counts as `0` (as [`proxy::effective_alpha`]).
/// Returns the number of elements written (the shortest slice). Allocates nothing.
///
/// **Agreement.** Not bit for bit: libm's `hypot` and `atan` of the scalar path have no lane
/// form. The lane computes `alpha' = s sqrt(t / atan2(H, s))`, `s = sqrt(alpha^2 + H^2)`,
/// `t = H / s`, in `f64` from the same half extents (bit for bit the scalar route's), with
/// `atan2` by the box filter's polynomial (`3 eps_64`). Counting roundings (`u = 2^-53`): `s`
/// within `2 u` (the squares and their sum `2 u`, halved by the root, plus its own `u`),
/// `t = H / s` within `3 u`, `atan2(H, s)` within `8 u` (its `6 u`, and at most `2 u` from
/// `s`), `t / atan2` within `12 u`, its root `7 u`, so `alpha'` is within `10 u` of the exact
/// value (`9 u` in `f32`, whose squares are exact in `f64`).
/// - **`f32`**: `alpha'` is then rounded to `f32`, so each axis's is the correctly rounded
///   value or a neighbour (`10 u` is far below half an `f32` ulp; the scalar `f32` path's,
///   from libm's `f32` functions, is within a few ulps). `D` is GGX's lane `D` of that
///   roughness: the scalar `D` of the same roughness, bit for bit.
/// - **`f64`**: `D` moves by at most `3` times each axis's relative error of `alpha'`
///   (`|d ln D / d ln alpha_x| = |4 X_x / (1 + X) - 1| <= 3`, `X_x = (m_x / (m_z alpha_x))^2`,
///   `X` the sum over the axes), so against the scalar route (its `alpha'` within `8.5 u`:
///   `hypot` `2 u`, `t` `3 u`, `atan t` `5 u`, `t / atan t` `9 u`, the root and product) the
///   relative difference is at most `6 (10 + 8.5) u` plus the two `D`s' own roundings
///   (`2 x 16 u`, GGX's `8 eps`): `143 u = 1.6e-14`.
///
/// Tested in `tests/batch.rs` (every rule set, adversarial footprints and half vectors): in
/// `f32` every element is the scalar `D` of one of the nine pairs of neighbours of the
/// correctly rounded `alpha'`, or the scalar route's value where the lane flags it; in `f64`
/// within `143 u` of the scalar route. Elements the `D` lane flags (a direction to rescale)
/// and, in `f64`, half extents beyond `1e150` (whose squares would overflow) are evaluated by
/// the scalar route.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn ggx_d_filtered_proxy(
    r: &AxisAligned,
    rules: &ClampRules,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let kernel = ProxyD {
        r: *r,
        rules: *rules,
        bounds: rules.rect_bounds(r.alpha()),
    };
    run(&kernel, footprint_columns([hx, hy, hz], fp), [out])
}

/// `D` of `Ggx::new(proxy(r, rules.rect(fp.bounding_rect(), r.alpha()).half_extent))`.
struct ProxyD {
    r: AxisAligned,
    rules: ClampRules,
    /// `rules.rect_bounds(r.alpha())`, once per batch.
    bounds: RectBounds,
}

/// The largest half extent whose square and sum with `alpha^2` stay finite in `f64` (the lane
/// flags larger ones; every `f32` value is below it).
const H_MAX: f64 = 1e150;

/// [`proxy::effective_alpha`] in a lane: `(alpha', ok)`, `alpha' = s sqrt(t / atan2(H, s))`,
/// `s = sqrt(alpha^2 + H^2)`, `t = H / s`, in `f64` (within `10 u` of the exact value,
/// [`ggx_d_filtered_proxy`]); `alpha` at `H = 0` (also for a NaN `H`, as the scalar
/// function). `t` is the quotient that [`atan2_upper_lane`] forms where `t <= 0.66`, so a `t`
/// so small that `atan t` rounds to `t` gives `t / atan t = 1` exactly, as the scalar path.
/// `ok` is false for `H > H_MAX`. `alpha` positive and finite (an [`AxisAligned`]'s).
#[inline(always)]
fn effective_alpha_lane(alpha: F, half_extent: F) -> (F, bool) {
    // The scalar function's sanitiser: |H|, NaN as 0 (its clamp to F::MAX: see H_MAX).
    let h = if half_extent.is_nan() {
        0.0
    } else {
        half_extent.abs().to_f64()
    };
    let a = alpha.to_f64();
    let s = m::sqrt(a * a + h * h);
    // atan2(H, s) needs H > 0: a stand-in of 1 where H = 0, whose result is not used.
    let live = h > 0.0;
    let phi = atan2_upper_lane(if live { h } else { 1.0 }, s);
    let wide = s * m::sqrt(h / s / phi);
    let v = if live { wide } else { a };
    (F::from_f64(v), h <= H_MAX)
}

impl Kernel<7, 1> for ProxyD {
    #[inline(always)]
    fn lane(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let half = self
            .bounds
            .apply(footprint(ux, uy, vx, vy).bounding_rect())
            .half_extent;
        let alpha = self.r.alpha();
        let (ax, okx) = effective_alpha_lane(alpha.x, half.x);
        let (ay, oky) = effective_alpha_lane(alpha.y, half.y);
        let lobe = Ggx::new(AxisAligned::new_clamped(ax, ay));
        let (v, slow) = lobe.d_lane(Vec3::new(hx, hy, hz));
        ([v], slow | !(okx & oky))
    }

    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> [F; 1] {
        let rect = self
            .rules
            .rect(footprint(ux, uy, vx, vy).bounding_rect(), self.r.alpha());
        let lobe = Ggx::new(proxy::proxy(self.r, rect.half_extent));
        [lobe.d(Vec3::new(hx, hy, hz))]
    }
}
