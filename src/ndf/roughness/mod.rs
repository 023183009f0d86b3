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
//! | [`RoughnessMatrix`] `A` | any symmetric positive definite | 3 mul, 2 mul-adds, in `f64` |
//!
//! Conversions go one way: `Isotropic -> AxisAligned -> RoughnessMatrix`, each equal to the
//! checked constructor of the wider form with the squared roughness rounded to `F`, and each
//! written in the narrower form's file (a form's file knows only the wider forms).
//! Roughness is dimensionless (a slope-domain length: `alpha` is the slope at which the GGX
//! density falls to a quarter of its peak).
//!
//! Domain: every `alpha` (every eigenvalue of `A`, square-rooted) in `[ALPHA_MIN, ALPHA_MAX]`,
//! where all densities and their squares stay inside the `f32` range. Checked constructors
//! return [`RoughnessError`] outside it; `*_clamped` constructors clamp into it (NaN maps to
//! `ALPHA_MIN`).

use super::{F, Mat2, Vec2};
use crate::math::{self as m, Real};

mod axis_aligned;
mod isotropic;
mod matrix;

use crate::error::RoughnessError;
pub use axis_aligned::AxisAligned;
pub use isotropic::Isotropic;
pub use matrix::RoughnessMatrix;
pub(crate) use matrix::det_clamp_tau;

/// Smallest supported roughness `alpha` (`A`'s smallest eigenvalue is `ALPHA_MIN^2`).
pub const ALPHA_MIN: F = 1e-8;
/// Largest supported roughness `alpha` (`A`'s largest eigenvalue is `ALPHA_MAX^2`).
pub const ALPHA_MAX: F = 1e4;

pub(crate) mod sealed {
    use super::{AxisAligned, F, Isotropic, RoughnessMatrix, Vec2};

    /// A roughness form as a value: what `batch`'s entry points match on, so that their loops
    /// are compiled in this crate once per form (`batch::per_form`).
    #[derive(Clone, Copy, Debug)]
    pub enum Form {
        /// [`Isotropic`].
        Isotropic(Isotropic),
        /// [`AxisAligned`].
        AxisAligned(AxisAligned),
        /// [`RoughnessMatrix`].
        Matrix(RoughnessMatrix),
    }

    /// Crate-internal evaluation helpers of the roughness forms (unnameable outside the
    /// crate, which also seals [`super::Roughness`]). Each describes the matrix the form
    /// evaluates: `A`, or for a clamped [`super::RoughnessMatrix`] its `A_c`.
    pub trait Sealed {
        /// `(x, n)` with `x = m^T A^-1 m / z2` and `n = 1 / (sqrt(det A) z2^2)` for a
        /// tangent-plane `m` and `z2 > 0`: the exponent and the normalisation of Beckmann's
        /// `D` (KHPL16 eq. 2 with eq. 14) from one division, shared by both (building a matrix
        /// per pixel, as filtering does, then needs no other division). `x` is `+inf` / NaN as
        /// [`super::Roughness::inv_quadratic`]; `n` overflows to `+inf` for tiny `z2`.
        fn exponent_and_norm(&self, m: Vec2, z2: F) -> (F, F);
        /// `det A` in `f64` from the entries by [`super::det_wide`] (for a clamped matrix
        /// `det A_c = max(det A, tau)`): the one determinant of the crate, which the filters
        /// use as their clamp `tau`, so that a kernel too small to change the entries meets
        /// the clamp with equality.
        fn lobe_det(&self) -> f64;
        /// The lobe's own determinant clamp: `det A_c` for a [`super::RoughnessMatrix`] whose
        /// clamp is active (`det A_c > det A` of its entries), else `0` (every other lobe).
        /// Every filter clamps with at least this, so that filtering never drops the lobe's
        /// own clamp: the entries of a clamped matrix may be far sharper than `A_c`, even
        /// singular, and `A + 2 Sigma` alone could then leave the range where `D` is finite
        /// (found by fuzzing: `f32` entries `1e-40` clamped to `det A_c = 1`, filtered without a
        /// clamp, gave `D(0) = inf`).
        #[inline(always)]
        fn own_det_clamp(&self) -> f64 {
            0.0
        }
        /// The entries `(a11, a12, a22)` of `A` in `F`, as given (for a clamped matrix `A`,
        /// not `A_c`): what a filter adds its kernel to, before clamping the result with
        /// [`Sealed::lobe_det`], so that a zero kernel returns the lobe unchanged.
        fn entries_f(&self) -> (F, F, F);
        /// The lower Cholesky factor `(l11, l21, l22)` of the evaluated matrix,
        /// `A = [[l11, 0], [l21, l22]] [[l11, l21], [0, l22]]` (the samplers' warp).
        fn cholesky(&self) -> (F, F, F);
        /// The form as a [`Form`] value.
        fn form(&self) -> Form;
    }
}

/// `det A = a11 a22 - a12^2` in `f64`: the one determinant of every roughness form (their
/// densities, the range checks, the filters' clamp `tau`).
///
/// - `f32` entries: both products are exact in `f64`; the difference is rounded once
///   (relative error `<= eps_f64 / 2`, whatever the cancellation).
/// - `f64` entries: the plain formula while `a12^2 <= (15/16) a11 a22` (then
///   `det >= a11 a22 / 16` and the error is at most `(31 + 1) eps / 2 = 16 eps` relative);
///   beyond, Kahan's algorithm with two fused multiply-adds (within `2 eps`, Jeannerod, Louvet
///   and Muller 2013). The threshold keeps the fused multiply-adds, library calls without the
///   `fma` target feature, off every lobe of condition number below about 60 (a lower
///   threshold, `a12^2 <= a11 a22 / 2`, would bound the plain formula's error by 3 ulps but
///   send the realistic filtered lobes of `benches/filtered.rs` to the slower branch).
#[inline]
pub(crate) fn det_wide(a11: F, a12: F, a22: F) -> f64 {
    let (d, direct) = det_wide_direct(a11, a12, a22);
    if direct {
        return d;
    }
    let (a, b, c) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
    let bb = b * b;
    let err = m::mul_add(-b, b, bb);
    m::mul_add(a, c, -bb) + err
}

/// The direct branch of [`det_wide`]: `(a11 a22 - a12^2, direct)` in `f64`, `direct` when
/// [`det_wide`] returns that value (always in `f32`; in `f64` for `a12^2 <= 0.9375 a11 a22`).
/// Branch-free, for `batch`'s lanes.
#[inline(always)]
pub(crate) fn det_wide_direct(a11: F, a12: F, a22: F) -> (f64, bool) {
    let (a, b, c) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
    let (ac, bb) = (a * c, b * b);
    (ac - bb, core::mem::size_of::<F>() == 4 || bb <= 0.9375 * ac)
}

/// A roughness form: what the NDFs need of a roughness matrix `A`.
///
/// Sealed; implemented by [`Isotropic`], [`AxisAligned`] and [`RoughnessMatrix`]. Each method
/// is exact for its form (no conversion to the matrix form happens at evaluation time).
pub trait Roughness: Copy + sealed::Sealed {
    /// `s^T A^-1 s` for a slope `s` (dimensionless, `>= 0`; for a clamped matrix `A_c^-1`,
    /// see [`RoughnessMatrix`]). Every form returns `+inf` when the form overflows or `s` has
    /// an infinite component, and NaN for a NaN component (the NDFs turn that into their NaN
    /// policy, [`super::Ndf`]).
    fn inv_quadratic(&self, s: Vec2) -> F;
    /// `w^T A w` for a tangent-plane vector `w` (the projected roughness of Smith's
    /// `Lambda`, TK19 supplement section 1; `A_c` for a clamped matrix), `>= 0`. Overflow
    /// and non-finite input as [`Roughness::inv_quadratic`].
    fn quadratic(&self, w: Vec2) -> F;
    /// `sqrt(det A)` (for a clamped matrix `sqrt(det A_c) = sqrt(max(det A, tau))`):
    /// `alpha^2` isotropic, `alpha_x alpha_y` axis-aligned. Strictly positive.
    fn sqrt_det(&self) -> F;
    /// This roughness as a full [`RoughnessMatrix`]: for the isotropic and axis-aligned forms
    /// equal to `RoughnessMatrix::new(alpha_x^2, 0, alpha_y^2)` (squares rounded to `F`); a
    /// matrix returns itself (with its clamp).
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
