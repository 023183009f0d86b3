//! The axis-aligned roughness form `A = diag(alpha_x^2, alpha_y^2)`.

use super::{
    F, Roughness, RoughnessError, RoughnessMatrix, Vec2, check_alpha, clamp_alpha, det_wide,
    over_z2, sealed,
};

/// Axis-aligned anisotropic roughness `(alpha_x, alpha_y)` along the tangent and bitangent:
/// `A = diag(alpha_x^2, alpha_y^2)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisAligned {
    alpha: Vec2,
    /// `(alpha_x^2, alpha_y^2)`, the diagonal of `A` (a filtered lobe starts from it).
    alpha2: Vec2,
    inv_alpha2: Vec2,
    /// `1 / (alpha_x alpha_y)`.
    inv_sqrt_det: F,
}

impl AxisAligned {
    /// Checked constructor: both values finite and in `[ALPHA_MIN, ALPHA_MAX]`. When both
    /// are invalid, the error describes `alpha_x`.
    #[inline]
    pub fn new(alpha_x: F, alpha_y: F) -> Result<Self, RoughnessError> {
        Ok(Self::from_valid(Vec2::new(
            check_alpha(alpha_x)?,
            check_alpha(alpha_y)?,
        )))
    }

    /// Never fails: each value is first passed through [`clamp_alpha`].
    #[inline]
    pub fn new_clamped(alpha_x: F, alpha_y: F) -> Self {
        Self::from_valid(Vec2::new(clamp_alpha(alpha_x), clamp_alpha(alpha_y)))
    }

    /// From per-axis roughness already in `[ALPHA_MIN, ALPHA_MAX]`.
    #[inline]
    pub(super) fn from_valid(alpha: Vec2) -> Self {
        Self {
            alpha,
            alpha2: alpha * alpha,
            inv_alpha2: Vec2::ONE / (alpha * alpha),
            inv_sqrt_det: 1.0 / (alpha.x * alpha.y),
        }
    }

    /// `(alpha_x, alpha_y)`.
    #[inline]
    pub fn alpha(&self) -> Vec2 {
        self.alpha
    }
}

impl From<AxisAligned> for RoughnessMatrix {
    /// Equal to `RoughnessMatrix::new(alpha_x^2, 0, alpha_y^2)` (squares rounded to `F`).
    #[inline]
    fn from(r: AxisAligned) -> Self {
        r.to_matrix()
    }
}

impl sealed::Sealed for AxisAligned {
    #[inline(always)]
    fn form(&self) -> sealed::Form {
        sealed::Form::AxisAligned(*self)
    }
    #[inline(always)]
    fn exponent_and_norm(&self, m: Vec2, z2: F) -> (F, F) {
        over_z2(self.inv_quadratic(m), self.inv_sqrt_det, z2)
    }
    #[inline(always)]
    fn lobe_det(&self) -> f64 {
        det_wide(self.alpha2.x, 0.0, self.alpha2.y)
    }
    #[inline(always)]
    fn entries_f(&self) -> (F, F, F) {
        (self.alpha2.x, 0.0, self.alpha2.y)
    }
    #[inline(always)]
    fn cholesky(&self) -> (F, F, F) {
        (self.alpha.x, 0.0, self.alpha.y)
    }
}
impl Roughness for AxisAligned {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        (s * s).dot(self.inv_alpha2)
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        // `(alpha_i w_i)^2`, not `w_i^2 alpha_i^2`: a tiny `w_i` beside a large `alpha_i` would
        // square to a subnormal first and lose digits (GGX's `Lambda` 1.3 % off in `f32` at
        // `w_x / |w| = 2e-22`, `alpha = 1e4`; found by fuzzing).
        let s = w * self.alpha;
        s.dot(s)
    }
    #[inline]
    fn sqrt_det(&self) -> F {
        self.alpha.x * self.alpha.y
    }
    #[inline]
    fn to_matrix(&self) -> RoughnessMatrix {
        // What `RoughnessMatrix::new(alpha_x^2, 0, alpha_y^2)` builds (no checks needed).
        RoughnessMatrix::from_entries(self.alpha2.x, 0.0, self.alpha2.y, 0.0)
    }
}
