//! The isotropic roughness form `A = alpha^2 I`.

use super::{
    AxisAligned, F, Roughness, RoughnessError, RoughnessMatrix, Vec2, check_alpha, clamp_alpha,
    det_wide, over_z2, sealed,
};

/// Isotropic roughness `alpha`: `A = alpha^2 I`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Isotropic {
    alpha: F,
    inv_alpha2: F,
}

impl Isotropic {
    /// Checked constructor: `alpha` finite and in `[ALPHA_MIN, ALPHA_MAX]`; else
    /// `NotFinite` (NaN, inf), `NotPositive` (`<= 0`, including `-0`) or `OutOfRange`.
    #[inline]
    pub fn new(alpha: F) -> Result<Self, RoughnessError> {
        check_alpha(alpha).map(Self::from_valid)
    }

    /// Never fails: `alpha` is first passed through [`clamp_alpha`].
    #[inline]
    pub fn new_clamped(alpha: F) -> Self {
        Self::from_valid(clamp_alpha(alpha))
    }

    #[inline]
    fn from_valid(alpha: F) -> Self {
        Self {
            alpha,
            inv_alpha2: 1.0 / (alpha * alpha),
        }
    }

    /// The roughness `alpha`.
    #[inline]
    pub fn alpha(&self) -> F {
        self.alpha
    }
}

impl sealed::Sealed for Isotropic {
    #[inline(always)]
    fn form(&self) -> sealed::Form {
        sealed::Form::Isotropic(*self)
    }
    #[inline(always)]
    fn exponent_and_norm(&self, m: Vec2, z2: F) -> (F, F) {
        // sqrt(det A) = alpha^2.
        over_z2(self.inv_quadratic(m), self.inv_alpha2, z2)
    }
    #[inline(always)]
    fn lobe_det(&self) -> f64 {
        let a2 = self.alpha * self.alpha;
        det_wide(a2, 0.0, a2)
    }
    #[inline(always)]
    fn entries_f(&self) -> (F, F, F) {
        let a2 = self.alpha * self.alpha;
        (a2, 0.0, a2)
    }
    #[inline(always)]
    fn cholesky(&self) -> (F, F, F) {
        (self.alpha, 0.0, self.alpha)
    }
}
impl Roughness for Isotropic {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        s.length_squared() * self.inv_alpha2
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        // `|alpha w|^2`: `w` scaled first, as the axis-aligned form (no subnormal square of a
        // tiny `w` beside a large `alpha`; both forms agree bit for bit at equal alphas).
        let s = w * self.alpha;
        s.dot(s)
    }
    #[inline]
    fn sqrt_det(&self) -> F {
        self.alpha * self.alpha
    }
    #[inline]
    fn to_matrix(&self) -> RoughnessMatrix {
        AxisAligned::from(*self).to_matrix()
    }
}

impl From<Isotropic> for AxisAligned {
    /// `(alpha, alpha)`.
    #[inline]
    fn from(r: Isotropic) -> Self {
        Self::from_valid(Vec2::splat(r.alpha()))
    }
}

impl From<Isotropic> for RoughnessMatrix {
    /// Equal to `RoughnessMatrix::new(alpha^2, 0, alpha^2)` (the square rounded to `F`).
    #[inline]
    fn from(r: Isotropic) -> Self {
        r.to_matrix()
    }
}
