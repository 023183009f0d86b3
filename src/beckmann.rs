//! Beckmann in any roughness form (Beckmann and Spizzichino 1963; Heitz 2014 section 5.4;
//! KHPL16 eq. 14: `A = 2 B` with `B` the slope covariance).

use super::ndf::Ndf;
use super::roughness::{AxisAligned, Isotropic, Roughness, RoughnessMatrix};
use super::{F, Vec2, Vec3};
use crate::error::RoughnessError;
use crate::math::{self as m, Real};

const PI: F = core::f64::consts::PI as F;

/// The Beckmann distribution with roughness form `R`: a bivariate Gaussian of slopes with
/// covariance `A / 2`.
///
/// - `P22(s) = exp(-s^T A^-1 s) / (pi sqrt(det A))` (slope domain).
/// - `D(m) = exp(-m_xy^T A^-1 m_xy / m_z^2) / (pi sqrt(det A) m_z^4)` for `m_z > 0`, `0`
///   below the horizon and where the exponential underflows.
/// - `Lambda(w) = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2` with
///   `a = |w_z| / sqrt(w_xy^T A w_xy)` (Heitz 2014 eq. 80 with the projected roughness of a
///   matrix lobe). Evaluated in `f64` for both precisions, because the two terms cancel to
///   a relative `1 / (2 a^2)` for large `a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beckmann<R: Roughness> {
    /// The roughness.
    pub roughness: R,
}

impl<R: Roughness> Beckmann<R> {
    /// Beckmann with the given roughness.
    #[inline]
    pub const fn new(roughness: R) -> Self {
        Self { roughness }
    }
}

impl Beckmann<Isotropic> {
    /// Isotropic Beckmann, checked (see [`Isotropic::new`]).
    #[inline]
    pub fn isotropic(alpha: F) -> Result<Self, RoughnessError> {
        Isotropic::new(alpha).map(Self::new)
    }
}

impl Beckmann<AxisAligned> {
    /// Axis-aligned Beckmann, checked (see [`AxisAligned::new`]).
    #[inline]
    pub fn axis_aligned(alpha_x: F, alpha_y: F) -> Result<Self, RoughnessError> {
        AxisAligned::new(alpha_x, alpha_y).map(Self::new)
    }
}

impl Beckmann<RoughnessMatrix> {
    /// Full-matrix Beckmann, checked (see [`RoughnessMatrix::new`]).
    #[inline]
    pub fn matrix(a11: F, a12: F, a22: F) -> Result<Self, RoughnessError> {
        RoughnessMatrix::new(a11, a12, a22).map(Self::new)
    }
}

/// Beckmann Smith `Lambda` from `q = w_xy^T A w_xy` and `|w_z|` (shared with sampling and
/// the temporal module; one source of truth).
#[inline]
pub(crate) fn beckmann_lambda(q: F, abs_wz: F) -> F {
    if q <= 0.0 {
        return 0.0;
    }
    if abs_wz <= 0.0 {
        return F::INFINITY;
    }
    let a = abs_wz.to_f64() / m::sqrt(q.to_f64());
    if a > 26.0 {
        // exp(-a^2) < 1e-293: Lambda is below every representable density scale.
        return 0.0;
    }
    let inv_sqrt_pi = 0.564_189_583_547_756_3_f64;
    let l = 0.5 * (m::exp(-a * a) * inv_sqrt_pi / a - m::erfc(a));
    F::from_f64(l.max(0.0))
}

impl<R: Roughness> Ndf for Beckmann<R> {
    #[inline]
    fn p22(&self, s: Vec2) -> F {
        m::exp(-self.roughness.inv_quadratic(s)) / (PI * self.roughness.sqrt_det())
    }

    #[inline]
    fn d(&self, mn: Vec3) -> F {
        if mn.z <= 0.0 {
            return 0.0;
        }
        let inv_z2 = 1.0 / (mn.z * mn.z);
        let e = m::exp(-self.roughness.inv_quadratic(Vec2::new(mn.x, mn.y)) * inv_z2);
        if e == 0.0 {
            return 0.0;
        }
        let v = e * inv_z2 * inv_z2 / (PI * self.roughness.sqrt_det());
        if v.is_finite() { v } else { 0.0 }
    }

    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        beckmann_lambda(self.roughness.quadratic(Vec2::new(w.x, w.y)), w.z.abs())
    }
}
