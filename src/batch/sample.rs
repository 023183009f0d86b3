//! Importance sampling over slices: GGX visible normals.
//!
//! The lane is the scalar sampler's own steps ([`NdfSampling::sample_visible_normal`] of
//! [`Ggx`]: the view normalised and stretched by the Cholesky factor `L` of the roughness, a
//! point on the spherical cap of Dupuy and Benyoub 2023, listing 3, mapped back by `L`), with
//! the shared cores `Warp::stretch`, `Warp::unstretch_raw`, `ggx_cap_point` and `clamp_unit`;
//! its checks become selects. It differs from the scalar path in two operations only: the
//! azimuth's `(cos, sin)` is [`sincos_2pi`] (the scalar path: libm of `phi = 2 pi u1` rounded
//! in `F`) and the cap height `z = (1 - u2) (1 + wi_z) - wi_z` is not fused (the scalar path:
//! `mul_add`). Flagged, and sampled by the scalar function: non-finite `wo`, `wo_z <= 0`, a
//! `wo`, stretched view or mapped normal whose squared length needs the rescaling of
//! [`crate::f32::vector::unit`], a stretched view with `wi_z <= 0`, and a mapped normal that
//! fails the sampler's final check (`m_z > 0`, `wo.m > 0`: the scalar path then returns the
//! lobe centre).

use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::Roughness;
use super::super::sampling::{NdfSampling, Warp, clamp_unit, ggx_cap_point};
use super::lanes::{Kernel, run, sincos_2pi};
use super::{F, Vec2, Vec3, Vec3s};
use crate::math as m;

/// [`NdfSampling::sample_visible_normal`] of GGX for each view `wo_i = (wo.x[i], wo.y[i],
/// wo.z[i])` and uniform pair `(u1[i], u2[i])`: writes the unit micronormal `m_i` with
/// density `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` per steradian (Heitz 2018, "Sampling
/// the GGX Distribution of Visible Normals"; spherical caps of Dupuy and Benyoub 2023,
/// listing 3; warped by the Cholesky factor of the roughness, TK19 supplement section 1, as
/// the scalar sampler) to `(out_x[i], out_y[i], out_z[i])`.
///
/// Where the scalar sampler returns `None` (`wo_z <= 0`, non-finite `wo`, a view grazing to
/// within the float range): `(0, 0, 0)`. `u` outside `[0, 1)` is clamped as by the scalar
/// sampler (NaN to `0`).
///
/// Agreement: not bit for bit with the scalar sampler of the same precision (the lane's
/// polynomial `sin`/`cos` of `2 pi u1`, absolute `2e-15` computed in `f64`, replace libm's of
/// the rounded `phi`, and the cap height is not fused); against the `f64` scalar sampler on
/// the same inputs, the angle between the samples pulled back to the unit-roughness space
/// is within the bound `B` stated and derived in `tests/batch_bounds.rs`: `(9 kappa + 1) E`
/// plus `(d_c + d_wi + E) / |n|`, where `d_wi = (8.5 kappa + 1) E` and `d_c` (the cap
/// point's error) is about `(17 kappa + 8) E / sin theta + S E`, `E` the precision's
/// epsilon, `kappa` the condition number of the warp `diag(L, 1)`, `sin theta` the radius
/// of the cap point, `|n|` the length of the unit-roughness normal before normalisation,
/// `S = 8` (`f32`) / `9` (`f64`) the azimuth's error in `E`. The scalar `f32` sampler's own
/// error has the same form. Every output is a unit vector with `m_z > 0` and `wo.m > 0` (those
/// checks are the lane's or, flagged, the scalar path's).
///
/// Returns the number of elements written (the shortest of the eight slices); leaves the
/// rest untouched. Allocates nothing.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn ggx_sample_visible_normal<R: Roughness>(
    r: &R,
    wo: Vec3s<'_>,
    u1: &[F],
    u2: &[F],
    out_x: &mut [F],
    out_y: &mut [F],
    out_z: &mut [F],
) -> usize {
    let k = Vndf {
        ggx: Ggx::new(*r),
        warp: Warp::new(r),
    };
    run(&k, [wo.x, wo.y, wo.z, u1, u2], [out_x, out_y, out_z])
}

/// The kernel: the NDF and its warp.
struct Vndf<R: Roughness> {
    ggx: Ggx<R>,
    warp: Warp,
}

/// `v / sqrt(|v|^2)` where that needs no rescaling (the direct path of
/// [`crate::f32::vector::unit`], the same operations), and whether it applies.
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
fn unit_direct(v: Vec3) -> (Vec3, bool) {
    let l2 = v.length_squared();
    let ok = (l2 >= F::MIN_POSITIVE / F::EPSILON) & (l2 <= F::MAX);
    (v / m::sqrt(l2), ok)
}

impl<R: Roughness> Kernel<5, 3> for Vndf<R> {
    #[inline(always)]
    fn lane(&self, [x, y, z, u1, u2]: [F; 5]) -> ([F; 3], bool) {
        let wo = Vec3::new(x, y, z);
        // `standard_view`: `wo` finite with `wo_z > 0` (a NaN or infinite component makes
        // `l2` NaN or infinite: not direct), normalised, stretched, normalised.
        let (o, ok_o) = unit_direct(wo);
        let (wi, ok_s) = unit_direct(self.warp.stretch(o));
        let view = (z > 0.0) & ok_o & ok_s & (wi.z > 0.0);
        let (u1, u2) = (clamp_unit(u1), clamp_unit(u2));
        let (sin_phi, cos_phi) = sincos_2pi(u1);
        let h = (1.0 - u2) * (1.0 + wi.z) - wi.z;
        let n = ggx_cap_point(wi, h, cos_phi, sin_phi);
        let (mm, ok_m) = unit_direct(self.warp.unstretch_raw(n));
        // `visible_result`'s first check (a finite `mm`: its squared length was direct).
        let good = ok_m & (mm.z > 0.0) & (wo.dot(mm) > 0.0);
        ([mm.x, mm.y, mm.z], !(view & good))
    }

    #[inline]
    fn scalar(&self, [x, y, z, u1, u2]: [F; 5]) -> [F; 3] {
        let m = self
            .ggx
            .sample_visible_normal(Vec3::new(x, y, z), Vec2::new(u1, u2))
            .unwrap_or(Vec3::ZERO);
        [m.x, m.y, m.z]
    }
}
