//! GGX (Trowbridge-Reitz) in any roughness form (TK19 supplement section 1; Heitz 2014).

use super::super::PI;
use super::roughness::{AxisAligned, Isotropic, Roughness, RoughnessMatrix};
use super::{F, Vec2, Vec3};
use super::{Ndf, lambda_outside_domain, rescale_direction};
use crate::error::RoughnessError;
use crate::math as m;

/// The GGX / Trowbridge-Reitz distribution with roughness form `R`.
///
/// - `P22(s) = 1 / (pi sqrt(det A) (1 + s^T A^-1 s)^2)` (slope domain).
/// - `D(m) = 1 / (pi sqrt(det A) (m_xy^T A^-1 m_xy + m_z^2)^2)` for `m_z > 0` (TK19
///   supplement, non-axis-aligned GGX), computed in this homogeneous form so that it stays
///   finite and accurate up to the horizon.
/// - `Lambda(w) = (sqrt(1 + w_xy^T A w_xy / w_z^2) - 1) / 2` (TK19 supplement), evaluated as
///   `q / (2 |w_z| (sqrt(w_z^2 + q) + |w_z|))` without cancellation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx<R: Roughness> {
    /// The roughness.
    pub roughness: R,
}

impl<R: Roughness> Ggx<R> {
    /// GGX with the given roughness.
    #[inline]
    pub const fn new(roughness: R) -> Self {
        Self { roughness }
    }
}

checked_constructors!(Ggx, "GGX");

impl<R: Roughness> Ggx<R> {
    /// The formula of [`Ndf::d`] without its two checks (`m_z > 0`, finite result): the one
    /// source of `D` for the scalar path (which branches on the checks, cheapest for a single
    /// evaluation) and for `batch::ggx_d` (which selects, so that the loop vectorises).
    #[inline(always)]
    pub(crate) fn d_unchecked(&self, mn: Vec3) -> F {
        let t = self.roughness.inv_quadratic(Vec2::new(mn.x, mn.y)) + mn.z * mn.z;
        1.0 / (PI * self.roughness.sqrt_det() * t * t)
    }
}

/// GGX Smith `Lambda` from `q = w_xy^T A w_xy` and `|w_z|` (shared with the sampling and
/// temporal modules; one source of truth). NaN in either: `+inf` (the NaN policy of
/// [`Ndf`]).
#[inline]
pub(crate) fn ggx_lambda(q: F, abs_wz: F) -> F {
    if let Some(v) = lambda_outside_domain(q, abs_wz) {
        return v;
    }
    let r = m::sqrt(abs_wz * abs_wz + q);
    if !r.is_finite() {
        // An infinite w_z with a finite q is the pole (Lambda = 0); otherwise grazing.
        return if abs_wz.is_infinite() && q.is_finite() {
            0.0
        } else {
            F::INFINITY
        };
    }
    let (lambda, normal) = ggx_lambda_core(q, abs_wz);
    if normal {
        lambda
    } else {
        // The denominator 2 |w_z| (r + |w_z|) is subnormal (a grazing |w_z| near 1e-308 with
        // r near 1e-8 kept 8 digits; found by the box lobe's fuzz contract) or 0:
        // q / (r + |w_z|) <= sqrt(q) first, then the exact 2 |w_z|.
        q / (r + abs_wz) / (2.0 * abs_wz)
    }
}

/// The formula of [`ggx_lambda`] without its checks, `q / (2 |w_z| (sqrt(w_z^2 + q) + |w_z|))`
/// (no cancellation; one division), for `q >= 0`, `|w_z| > 0` and a finite `w_z^2 + q`, and
/// whether its denominator is a normal number (else the value may have lost digits and
/// [`ggx_lambda`] divides twice): the one source of GGX's `Lambda` for the scalar path and for
/// `batch` (whose lanes take it where those hold and flag the rest).
#[inline(always)]
pub(crate) fn ggx_lambda_core(q: F, abs_wz: F) -> (F, bool) {
    let r = m::sqrt(abs_wz * abs_wz + q);
    let den = 2.0 * abs_wz * (r + abs_wz);
    (q / den, den >= F::MIN_POSITIVE)
}

impl<R: Roughness> Ndf for Ggx<R> {
    #[inline]
    fn p22(&self, s: Vec2) -> F {
        let t = 1.0 + self.roughness.inv_quadratic(s);
        let v = 1.0 / (PI * self.roughness.sqrt_det() * t * t);
        // NaN slope: 0 (the NaN policy of `Ndf`); an infinite one already gives 0.
        if v.is_nan() { 0.0 } else { v }
    }

    #[inline]
    fn d(&self, mn: Vec3) -> F {
        if mn.z <= 0.0 {
            return 0.0;
        }
        let v = self.d_unchecked(mn);
        if v.is_finite() { v } else { 0.0 }
    }

    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        let w = rescale_direction(w);
        ggx_lambda(self.roughness.quadratic(Vec2::new(w.x, w.y)), w.z.abs())
    }
}
