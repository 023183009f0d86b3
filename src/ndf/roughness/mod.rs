//! The three roughness forms and the one trait every NDF accepts them through.
//!
//! A roughness is the matrix `A` of TK19 supplement section 1 (Heitz 2014 section 5.4): the
//! slope-domain density of both Beckmann and GGX depends on the slope `s` only through the
//! quadratic form `s^T A^-1 s` and on `sqrt(det A)`, and Smith's `Lambda(w)` only through
//! `w_xy^T A w_xy`. The three forms compute those three numbers at three costs:
//!
//! | form | `A` | `s^T A^-1 s` costs |
//! |---|---|---|
//! | [`Isotropic`] `alpha` | `alpha^2 I` | 1 dot, 1 mul |
//! | [`AxisAligned`] `(alpha_x, alpha_y)` | `diag(alpha_x^2, alpha_y^2)` | 2 mul-adds |
//! | [`RoughnessMatrix`] `A` | any symmetric positive definite | 1 rotation, 2 mul-adds |
//!
//! Conversions go one way, for free: `Isotropic -> AxisAligned -> RoughnessMatrix`.
//! Roughness is dimensionless (a slope-domain length: `alpha` is the slope at which the GGX
//! density falls to a quarter of its peak).
//!
//! Domain: every `alpha` (every eigenvalue of `A`, square-rooted) in `[ALPHA_MIN, ALPHA_MAX]`,
//! where all densities and their squares stay inside the `f32` range. Checked constructors
//! return [`RoughnessError`] outside it; `*_clamped` constructors clamp into it (NaN maps to
//! `ALPHA_MIN`).

use super::{F, Mat2, Vec2};

mod axis_aligned;
mod isotropic;
mod matrix;

use crate::error::RoughnessError;
pub use axis_aligned::AxisAligned;
pub use isotropic::Isotropic;
pub use matrix::RoughnessMatrix;

/// Smallest supported roughness `alpha` (`A`'s smallest eigenvalue is `ALPHA_MIN^2`).
pub const ALPHA_MIN: F = 1e-8;
/// Largest supported roughness `alpha` (`A`'s largest eigenvalue is `ALPHA_MAX^2`).
pub const ALPHA_MAX: F = 1e4;

pub(crate) mod sealed {
    use super::{F, Vec2};

    /// Crate-internal evaluation helpers of the roughness forms (unnameable outside the
    /// crate, which also seals [`super::Roughness`]).
    pub trait Sealed {
        /// `(x, n)` with `x = m^T A^-1 m / z2` and `n = 1 / (sqrt(det A) z2^2)` for a
        /// tangent-plane `m` and `z2 > 0`: the exponent and the normalisation of Beckmann's
        /// `D` (KHPL16 eq. 2 with eq. 14) from one division, shared by both (the matrix form
        /// merges its `1 / max(det A, tau)` into it, so building a matrix per pixel, as
        /// filtering does, needs no division). `x` is `+inf` / NaN as
        /// [`super::Roughness::inv_quadratic`]; `n` overflows to `+inf` for tiny `z2`.
        fn exponent_and_norm(&self, m: Vec2, z2: F) -> (F, F);
        /// `max(det A, tau)` in `f64` (`det A` for the forms without a clamp), with `det A`
        /// computed from the entries of [`super::Roughness::to_matrix`] exactly as the matrix
        /// constructor computes it (`a11 a22 - a12^2` in `f64`, exact for `f32` entries; a
        /// matrix in the eigenbasis representation keeps only its square root, in `F`): the
        /// filtering clamp `tau`, which a kernel too small to change the entries then meets
        /// with equality.
        fn det_clamped(&self) -> f64;
    }
}

/// A roughness form: what the NDFs need of a roughness matrix `A`.
///
/// Sealed; implemented by [`Isotropic`], [`AxisAligned`] and [`RoughnessMatrix`]. Each method
/// is exact for its form (no conversion to the matrix form happens at evaluation time).
pub trait Roughness: Copy + sealed::Sealed {
    /// `s^T A^-1 s` for a slope `s` (dimensionless, `>= 0`). For the matrix form `A^-1` is
    /// `adj(A) / max(det A, tau)` (TK19 supplement, "Practical Implementation") and the result
    /// is clamped to `>= 0`. Every form returns `+inf` when the form overflows (also against
    /// the null direction of a clamped singular matrix) or `s` has an infinite component, and
    /// NaN for a NaN component.
    fn inv_quadratic(&self, s: Vec2) -> F;
    /// `w^T A w` for a tangent-plane vector `w` (the projected roughness of Smith's
    /// `Lambda`, TK19 supplement section 1), `>= 0`. Overflow and non-finite input as
    /// [`Roughness::inv_quadratic`].
    fn quadratic(&self, w: Vec2) -> F;
    /// `sqrt(det A)` (for the matrix form `sqrt(max(det A, tau))`): `alpha^2` isotropic,
    /// `alpha_x alpha_y` axis-aligned. Strictly positive.
    fn sqrt_det(&self) -> F;
    /// This roughness as a full [`RoughnessMatrix`] (no determinant clamp).
    fn to_matrix(&self) -> RoughnessMatrix;
}

#[inline]
pub(super) fn check_alpha(alpha: F) -> Result<F, RoughnessError> {
    if !alpha.is_finite() {
        Err(RoughnessError::NotFinite)
    } else if alpha <= 0.0 {
        Err(RoughnessError::NotPositive)
    } else if !(ALPHA_MIN..=ALPHA_MAX).contains(&alpha) {
        Err(RoughnessError::OutOfRange)
    } else {
        Ok(alpha)
    }
}

/// `(q / z2, inv_sqrt_det / z2^2)` from one division: [`sealed::Sealed::exponent_and_norm`]
/// for the forms that store `A^-1` and `1 / sqrt(det A)`.
#[inline(always)]
pub(super) fn over_z2(q: F, inv_sqrt_det: F, z2: F) -> (F, F) {
    let inv_z2 = 1.0 / z2;
    (q * inv_z2, inv_z2 * inv_z2 * inv_sqrt_det)
}

/// Clamps `alpha` into `[ALPHA_MIN, ALPHA_MAX]`; NaN and non-positive values map to
/// `ALPHA_MIN`, `+inf` to `ALPHA_MAX`.
#[inline]
pub fn clamp_alpha(alpha: F) -> F {
    if alpha >= ALPHA_MIN {
        if alpha <= ALPHA_MAX { alpha } else { ALPHA_MAX }
    } else {
        ALPHA_MIN
    }
}
