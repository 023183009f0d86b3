//! Importance sampling over slices: visible normals and `D(m) m_z` of GGX and Beckmann.
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

use super::super::super::ndf::beckmann::Beckmann;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::ndf::roughness::Roughness;
use super::super::super::sampling::{
    NdfSampling, Warp, beckmann_standard_normal, clamp_unit, ggx_cap_point, ggx_standard_normal,
};
use super::super::super::{F, Vec2, Vec3};
use super::super::columns::Vec3s;
use super::super::engine::lane_math::{ln_lane, sincos_2pi};
use super::super::engine::{Kernel, run};
use crate::math::{self as m, Real};
use quantile::visible_slope_quantile_lane;

mod quantile;

per_form! {
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
    /// polynomial `sin`/`cos` of `2 pi u1`, absolute `2 eps_32` in `f32`, `2e-15` in `f64`, replace libm's of
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
    #[allow(clippy::too_many_arguments)]
    pub fn ggx_sample_visible_normal(
        r: &R,
        wo: Vec3s<'_>,
        u1: &[F],
        u2: &[F],
        out_x: &mut [F],
        out_y: &mut [F],
        out_z: &mut [F],
    ) -> usize {
        let kernel = VisibleSampler {
            ndf: Ggx::new(*r),
            warp: Warp::new(r),
        };
        run(&kernel, [wo.x, wo.y, wo.z, u1, u2], [out_x, out_y, out_z])
    }
}

/// The visible-normal sampler of an NDF and its warp.
struct VisibleSampler<N> {
    ndf: N,
    warp: Warp,
}

/// The unit-roughness visible normal of an NDF's sampler in lanes, from the standard view
/// `wi` and the clamped uniforms: `(n, slow)`, `n` unnormalised.
trait StandardVisible {
    fn standard_visible_lane(wi: Vec3, u1: F, u2: F) -> (Vec3, bool);
}

impl<R: Roughness> StandardVisible for Ggx<R> {
    /// A point on the spherical cap plus `wi` (`ggx_cap_point`), the azimuth by
    /// [`sincos_2pi`], the cap height not fused.
    #[inline(always)]
    fn standard_visible_lane(wi: Vec3, u1: F, u2: F) -> (Vec3, bool) {
        let (sin_phi, cos_phi) = sincos_2pi(u1);
        let h = (1.0 - u2) * (1.0 + wi.z) - wi.z;
        (ggx_cap_point(wi, h, cos_phi, sin_phi), false)
    }
}

impl<R: Roughness> StandardVisible for Beckmann<R> {
    /// The scalar sampler's steps in `f64` (the view's azimuth by `sqrt(wx^2 + wy^2)` in
    /// place of `hypot`), the two quantiles by `visible_slope_quantile_lane` (three steps for
    /// `x`, one for the Gaussian `y`), flagged where either misses its goal or the azimuth
    /// is lost to a subnormal `wx^2 + wy^2` (`f64` only).
    #[inline(always)]
    fn standard_visible_lane(wi: Vec3, u1: F, u2: F) -> (Vec3, bool) {
        let (wx, wy, c) = (wi.x.to_f64(), wi.y.to_f64(), wi.z.to_f64());
        let s2 = wx * wx + wy * wy;
        let s = m::sqrt(s2);
        let axis = s > 0.0;
        let ok_az = (s2 >= f64::MIN_POSITIVE / f64::EPSILON) | !axis;
        let (cphi, sphi) = if axis { (wx / s, wy / s) } else { (1.0, 0.0) };
        let (qx, ok_x) = visible_slope_quantile_lane::<3>(c, s, u1.to_f64());
        let (qy, ok_y) = visible_slope_quantile_lane::<1>(1.0, 0.0, u2.to_f64());
        let (tx, ty) = (cphi * qx - sphi * qy, sphi * qx + cphi * qy);
        (
            Vec3::new(F::from_f64(-tx), F::from_f64(-ty), 1.0),
            !(ok_az & ok_x & ok_y),
        )
    }
}

/// `v / sqrt(|v|^2)` where that needs no rescaling (the direct path of
/// [`crate::f32::vector::unit`], the same operations), and whether it applies.
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
pub(super) fn unit_direct(v: Vec3) -> (Vec3, bool) {
    let l2 = v.length_squared();
    let ok = (l2 >= F::MIN_POSITIVE / F::EPSILON) & (l2 <= F::MAX);
    (v / m::sqrt(l2), ok)
}

impl<N: NdfSampling + StandardVisible> Kernel<5, 3> for VisibleSampler<N> {
    /// The scalar sampler's steps: `standard_view`, the NDF's unit-roughness visible normal,
    /// `Warp::unstretch_raw` and the direct normalisation, `visible_result`'s first check.
    #[inline(always)]
    fn lane(&self, [x, y, z, u1, u2]: [F; 5]) -> ([F; 3], bool) {
        let wo = Vec3::new(x, y, z);
        // `standard_view`: `wo` finite with `wo_z > 0` (a NaN or infinite component makes
        // `l2` NaN or infinite: not direct), normalised, stretched, normalised.
        let (o, ok_o) = unit_direct(wo);
        let (wi, ok_s) = unit_direct(self.warp.stretch(o));
        let view = (z > 0.0) & ok_o & ok_s & (wi.z > 0.0);
        let (n, slow) = N::standard_visible_lane(wi, clamp_unit(u1), clamp_unit(u2));
        let (mm, ok_m) = unit_direct(self.warp.unstretch_raw(n));
        // `visible_result`'s first check (a finite `mm`: its squared length was direct).
        let good = ok_m & (mm.z > 0.0) & (wo.dot(mm) > 0.0);
        ([mm.x, mm.y, mm.z], slow | !(view & good))
    }

    #[inline]
    fn scalar(&self, [x, y, z, u1, u2]: [F; 5]) -> [F; 3] {
        let m = self
            .ndf
            .sample_visible_normal(Vec3::new(x, y, z), Vec2::new(u1, u2))
            .unwrap_or(Vec3::ZERO);
        [m.x, m.y, m.z]
    }
}

per_form! {
    /// [`NdfSampling::sample_normal`] of GGX for each uniform pair `(u1[i], u2[i])`: writes the
    /// unit micronormal `m_i` with density `D(m) m_z` per steradian (KHPL16 eq. 2; in the
    /// unit-roughness space `n = (sqrt(u1) cos phi, sqrt(u1) sin phi, sqrt(1 - u1))`, `phi = 2 pi
    /// u2`, warped by the Cholesky factor of the roughness, TK19 supplement section 1, as the
    /// scalar sampler) to `(out_x[i], out_y[i], out_z[i])`. `u` outside `[0, 1)` is clamped as by
    /// the scalar sampler (NaN to `0`); every output is a unit vector with `m_z > 0`.
    ///
    /// Agreement: not bit for bit with the scalar sampler of the same precision (the azimuth's
    /// `(cos, sin)` by the lane polynomial `sincos_2pi`, absolute `2 eps_32` in `f32`, `2e-15` in `f64`, in
    /// place of libm's of the rounded `phi`); against the `f64` scalar sampler on the same
    /// inputs, the angle between the samples pulled back to the unit-roughness space is within
    /// `(S + 3) E + 9 kappa E + E` (`E` the precision's epsilon, `S = 8` in `f32`, `9` in `f64`,
    /// `kappa` the condition number of the warp `diag(L, 1)`), derived in
    /// `tests/batch_bounds.rs`; the scalar sampler is within the same bound. Returns the number
    /// of elements written (the shortest of the five slices). Allocates nothing.
    pub fn ggx_sample_normal(
        r: &R,
        u1: &[F],
        u2: &[F],
        out_x: &mut [F],
        out_y: &mut [F],
        out_z: &mut [F],
    ) -> usize {
        let kernel = NormalSampler {
            ndf: Ggx::new(*r),
            warp: Warp::new(r),
        };
        run(&kernel, [u1, u2], [out_x, out_y, out_z])
    }
}

per_form! {
    /// [`NdfSampling::sample_normal`] of Beckmann for each uniform pair: the unit micronormal
    /// with density `D(m) m_z` per steradian (KHPL16 eq. 2; in the unit-roughness space the slope
    /// of squared length `-ln(1 - u1)` at the azimuth `phi = 2 pi u2`, a Gaussian of covariance
    /// `I / 2`, warped by the Cholesky factor of the roughness, as the scalar sampler). `u`
    /// clamped as by the scalar sampler; every output is a unit vector with `m_z > 0`.
    ///
    /// Agreement: not bit for bit (`ln(1 - u1)` by the lane logarithm `log::ln_lane`, relative
    /// `3 eps` computed in `f32` in the `f32` build, `4 eps` in `f64`, and the azimuth by
    /// `sincos_2pi`, in place of libm's); against the `f64` scalar sampler, the pulled-back angle
    /// is within the bound derived in `tests/batch_bounds.rs`: `dr / (1 + r^2) + (S + 1) E r /
    /// sqrt(1 + r^2) + 9 kappa E + E`, `r = sqrt(-ln(1 - u1))`, `dr = min(dl / r, sqrt(dl)) + E r
    /// / 2` the error of `r` from the error `dl = E / 2 + c E |ln(1 - u1)|` of the logarithm (the
    /// rounding of `1 - u1` in `F`, and the logarithm's `c E`: `c = 3` in `f32`, `4` in `f64`, `1`
    /// for libm's). The scalar sampler is within the same bound with `c = 1`.
    ///
    /// Returns the number of elements written. Allocates nothing.
    pub fn beckmann_sample_normal(
        r: &R,
        u1: &[F],
        u2: &[F],
        out_x: &mut [F],
        out_y: &mut [F],
        out_z: &mut [F],
    ) -> usize {
        let kernel = NormalSampler {
            ndf: Beckmann::new(*r),
            warp: Warp::new(r),
        };
        run(&kernel, [u1, u2], [out_x, out_y, out_z])
    }
}

/// The `D(m) m_z` sampler of an NDF and its warp.
struct NormalSampler<N> {
    ndf: N,
    warp: Warp,
}

/// The unit-roughness normal of an NDF's `D(m) m_z` sampler in lanes, from the clamped `u1`
/// and the azimuth's `(cos, sin)`: `(normal, slow)`.
trait StandardNormal {
    fn standard_normal_lane(u1: F, cos_phi: F, sin_phi: F) -> (Vec3, bool);
}

impl<R: Roughness> StandardNormal for Ggx<R> {
    #[inline(always)]
    fn standard_normal_lane(u1: F, cos_phi: F, sin_phi: F) -> (Vec3, bool) {
        (ggx_standard_normal(u1, cos_phi, sin_phi), false)
    }
}

impl<R: Roughness> StandardNormal for Beckmann<R> {
    /// `ln(1 - u1)` by [`ln_lane`] (`1 - u1 >= eps / 2` for the clamped `u1`: never flagged).
    #[inline(always)]
    fn standard_normal_lane(u1: F, cos_phi: F, sin_phi: F) -> (Vec3, bool) {
        let (l, ok) = ln_lane(1.0 - u1);
        (beckmann_standard_normal(l, cos_phi, sin_phi), !ok)
    }
}

impl<N: NdfSampling + StandardNormal> Kernel<2, 3> for NormalSampler<N> {
    /// The scalar sampler's steps: `clamp_unit`, the standard normal, `Warp::unstretch_raw`
    /// and the direct normalisation (flagged where `vector::unit` rescales).
    #[inline(always)]
    fn lane(&self, [u1, u2]: [F; 2]) -> ([F; 3], bool) {
        let (u1, u2) = (clamp_unit(u1), clamp_unit(u2));
        let (sin_phi, cos_phi) = sincos_2pi(u2);
        let (n, slow) = N::standard_normal_lane(u1, cos_phi, sin_phi);
        let (mm, ok) = unit_direct(self.warp.unstretch_raw(n));
        ([mm.x, mm.y, mm.z], slow | !ok)
    }

    #[inline]
    fn scalar(&self, [u1, u2]: [F; 2]) -> [F; 3] {
        let m = self.ndf.sample_normal(Vec2::new(u1, u2));
        [m.x, m.y, m.z]
    }
}

per_form! {
    /// [`NdfSampling::sample_visible_normal`] of Beckmann for each view `wo_i` and uniform pair
    /// `(u1[i], u2[i])`: writes the unit micronormal `m_i` with density `D_wo(m) = G1(wo) max(0,
    /// wo.m) D(m) / wo_z` per steradian (Heitz and d'Eon 2014, section 4: in the unit-roughness
    /// space with the view's azimuth turned to `x`, the slope `x` is the quantile of the
    /// visible-slope CDF, `y` an independent Gaussian quantile; warped by the Cholesky factor of
    /// the roughness, as the scalar sampler) to `(out_x[i], out_y[i], out_z[i])`.
    ///
    /// Where the scalar sampler returns `None` (`wo_z <= 0`, non-finite `wo`, a view grazing to
    /// within the float range): `(0, 0, 0)`. `u` outside `[0, 1)` is clamped as by the scalar
    /// sampler (NaN to `0`).
    ///
    /// Agreement: not bit for bit. The scalar sampler solves for each quantile by a safeguarded
    /// Newton iteration on libm's `erfc` (7.7 evaluations on average); the lane takes a fitted
    /// guess and a fixed number of Halley steps on a rational `erfc` (three for `x`, one for `y`)
    /// and flags, for the scalar sampler, every element whose residual misses the scalar solve's
    /// goal (`batch::quantile`'s docs; in the far tails of `u`, some elements). So each quantile
    /// is the exact one of a `u'` within `(8.5 eps_64 + d(x) + d(hi)) u` of the clamped `u`, `d(x)
    /// = 1.5e-14 + (x^2 / 2 + 66) eps_64` the lane `K`'s relative error (the scalar path: the
    /// same form with libm's `(x^2 / 2 + 4) eps_64`); the steps after the quantiles (the view's
    /// azimuth `(wx, wy) / sqrt(wx^2 + wy^2)` in place of `hypot`, the rotation, `(-t_x, -t_y,
    /// 1)` rounded to `F`, the warp and the normalisation) are the scalar path's but for that
    /// root. `tests/batch_bounds.rs` checks the samples against the `f64` scalar sampler's
    /// visible-slope CDF (the `u` each sample is the quantile of) within the bound derived
    /// there. Every output is a unit vector with `m_z > 0` and `wo.m > 0`.
    ///
    /// Returns the number of elements written (the shortest of the eight slices); leaves the
    /// rest untouched. Allocates nothing.
    #[allow(clippy::too_many_arguments)]
    pub fn beckmann_sample_visible_normal(
        r: &R,
        wo: Vec3s<'_>,
        u1: &[F],
        u2: &[F],
        out_x: &mut [F],
        out_y: &mut [F],
        out_z: &mut [F],
    ) -> usize {
        let kernel = VisibleSampler {
            ndf: Beckmann::new(*r),
            warp: Warp::new(r),
        };
        run(&kernel, [wo.x, wo.y, wo.z, u1, u2], [out_x, out_y, out_z])
    }
}
