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
use crate::error::RoughnessError;
use crate::math::{self as m, Real};

/// Smallest supported roughness `alpha` (`A`'s smallest eigenvalue is `ALPHA_MIN^2`).
pub const ALPHA_MIN: F = 1e-8;
/// Largest supported roughness `alpha` (`A`'s largest eigenvalue is `ALPHA_MAX^2`).
pub const ALPHA_MAX: F = 1e4;

mod sealed {
    pub trait Sealed {}
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
fn check_alpha(alpha: F) -> Result<F, RoughnessError> {
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

impl sealed::Sealed for Isotropic {}
impl Roughness for Isotropic {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        s.length_squared() * self.inv_alpha2
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        w.length_squared() * (self.alpha * self.alpha)
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

/// Axis-aligned anisotropic roughness `(alpha_x, alpha_y)` along the tangent and bitangent:
/// `A = diag(alpha_x^2, alpha_y^2)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisAligned {
    alpha: Vec2,
    inv_alpha2: Vec2,
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

    #[inline]
    fn from_valid(alpha: Vec2) -> Self {
        Self {
            alpha,
            inv_alpha2: Vec2::ONE / (alpha * alpha),
        }
    }

    /// `(alpha_x, alpha_y)`.
    #[inline]
    pub fn alpha(&self) -> Vec2 {
        self.alpha
    }
}

impl From<Isotropic> for AxisAligned {
    #[inline]
    fn from(r: Isotropic) -> Self {
        Self::from_valid(Vec2::splat(r.alpha))
    }
}

impl sealed::Sealed for AxisAligned {}
impl Roughness for AxisAligned {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        (s * s).dot(self.inv_alpha2)
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        (w * w).dot(self.alpha * self.alpha)
    }
    #[inline]
    fn sqrt_det(&self) -> F {
        self.alpha.x * self.alpha.y
    }
    #[inline]
    fn to_matrix(&self) -> RoughnessMatrix {
        let a = self.alpha * self.alpha;
        RoughnessMatrix {
            a11: a.x,
            a12: 0.0,
            a22: a.y,
            axis: Vec2::X,
            eig: a,
            inv_eig: self.inv_alpha2,
            sqrt_det: self.alpha.x * self.alpha.y,
            inv_det_wide: 0.0,
            wide: false,
        }
    }
}

/// Full symmetric positive-definite roughness matrix `A = [[a11, a12], [a12, a22]]` (TK19
/// supplement section 1; Heitz 2014 section 5.4). For a Beckmann lobe `A` is twice the slope
/// covariance (KHPL16 eq. 14); rotating the lobe by `R` maps `A` to `R A R^T`.
///
/// With a determinant clamp `tau >= 0` (TK19 supplement, "Practical Implementation") the
/// density uses `sqrt(max(det A, tau))` and `A^-1 = adj(A) / max(det A, tau)`. The clamp
/// protects the inverse of an elongated, filtered matrix whose determinant has lost its
/// precision to cancellation; when filtering, `tau = det(A_unfiltered)` (`alpha_x^2 alpha_y^2`)
/// is exact, since filtering can only grow the determinant. Its bias is zero whenever
/// `det A >= tau` holds in exact arithmetic.
///
/// Precision: the constructor computes `det A` without cancellation error (exactly rounded
/// products) and
/// stores `A` in its eigenbasis `A = R diag(l1, l2) R^T`, so both quadratic forms are sums of
/// two non-negative squares. Evaluating `s^T A^-1 s` from the entries of `A^-1` instead would
/// cancel to a relative error of `cond(A) eps` (6 % in `f32` at an anisotropy ratio of
/// `1e3`); in the eigenbasis it is a few ulps at any condition number.
///
/// In `f32`, a matrix with `cond(A) < 2^24` (every filtered lobe of a realistic material)
/// is instead kept as its entries and `1 / max(det A, tau)` in `f64`, and the quadratic forms
/// are evaluated from the entries in `f64`: the cancellation above then costs a relative
/// `4 eps_f64 cond(A) < 2e-9`, below half an `f32` ulp, and the construction needs one
/// division and one square root instead of an eigen-decomposition (this is what makes a
/// per-pixel filtered lobe cheap). Both representations give the same values to within the
/// stated accuracy; `PartialEq` compares representations, not only the matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughnessMatrix {
    a11: F,
    a12: F,
    a22: F,
    /// Unit eigenvector `(c, s)` of `l1`; `(-s, c)` is the eigenvector of `l2`.
    axis: Vec2,
    /// Eigenvalues `(l1, l2)` of `A` (`l2` may be `<= 0` by rounding when `tau > 0`).
    eig: Vec2,
    /// Eigenvalues of the clamped inverse `adj(A) / max(det A, tau)`: `(l2, l1) / max(det, tau)`.
    inv_eig: Vec2,
    sqrt_det: F,
    /// `1 / max(det A, tau)` in `f64`, for the wide path (`0` on the eigenbasis path).
    inv_det_wide: f64,
    /// Whether the quadratic forms are evaluated from the entries in `f64` (the wide path,
    /// `F = f32` only; see [`RoughnessMatrix::from_entries_clamped`]).
    wide: bool,
}

/// The wide path is compiled in for `f32` only (`f64` has no wider type).
const WIDE: bool = core::mem::size_of::<F>() == 4;
/// The wide path is taken while `tr(A)^2 / det(A) < COND_WIDE` (`>= cond(A)`).
const COND_WIDE: f64 = (1u64 << 24) as f64;

/// `a b - c d` to within about one ulp, whatever the cancellation: in `f32` through `f64`
/// (the products of two `f32` are exact there), in `f64` by Kahan's algorithm with two fused
/// multiply-adds.
#[inline]
fn diff_of_products(a: F, b: F, c: F, d: F) -> F {
    if core::mem::size_of::<F>() == 4 {
        let (a, b, c, d) = (a.to_f64(), b.to_f64(), c.to_f64(), d.to_f64());
        return F::from_f64(a * b - c * d);
    }
    let cd = c * d;
    let err = m::mul_add(-c, d, cd);
    m::mul_add(a, b, -cd) + err
}

impl RoughnessMatrix {
    /// Checked constructor from the three distinct entries, no determinant clamp: entries
    /// finite, `a11 > 0`, `a22 > 0`, `det A > 0`, eigenvalues in `[ALPHA_MIN^2, ALPHA_MAX^2]`.
    #[inline]
    pub fn new(a11: F, a12: F, a22: F) -> Result<Self, RoughnessError> {
        Self::new_with_det_clamp(a11, a12, a22, 0.0)
    }

    /// Checked constructor from a [`Mat2`]: as [`RoughnessMatrix::new`], and the matrix must
    /// be symmetric to within 8 ulps of its largest entry.
    #[inline]
    pub fn from_mat2(a: Mat2) -> Result<Self, RoughnessError> {
        let (a11, a21, a12, a22) = (a.x_axis.x, a.x_axis.y, a.y_axis.x, a.y_axis.y);
        if !(a11.is_finite() && a12.is_finite() && a21.is_finite() && a22.is_finite()) {
            return Err(RoughnessError::NotFinite);
        }
        let scale = a11.abs().max(a22.abs()).max(a12.abs());
        if (a12 - a21).abs() > 8.0 * F::EPSILON * scale {
            return Err(RoughnessError::NotSymmetric);
        }
        Self::new(a11, 0.5 * a12 + 0.5 * a21, a22)
    }

    /// Checked constructor with the TK19 determinant clamp `tau`.
    ///
    /// With `tau > 0` a matrix whose computed determinant is non-positive only by rounding
    /// (`det A >= -8 eps a11 a22`) is accepted and evaluated with `max(det A, tau)`; a clearly
    /// indefinite one is still refused. `tau` itself must be finite and `>= 0` (else
    /// `NotFinite` / `NotPositive`). The range check `[ALPHA_MIN^2, ALPHA_MAX^2]` applies to the
    /// largest eigenvalue and to `max(det A, tau) / l_max` (so `tau <= ALPHA_MAX^2 l_max`).
    pub fn new_with_det_clamp(a11: F, a12: F, a22: F, tau: F) -> Result<Self, RoughnessError> {
        if !(a11.is_finite() && a12.is_finite() && a22.is_finite() && tau.is_finite()) {
            return Err(RoughnessError::NotFinite);
        }
        if a11 <= 0.0 || a22 <= 0.0 || tau < 0.0 {
            return Err(RoughnessError::NotPositive);
        }
        let (lo, hi) = (ALPHA_MIN * ALPHA_MIN, ALPHA_MAX * ALPHA_MAX);
        // Entries beyond the eigenvalue range would overflow the determinant below.
        if a11 > hi || a22 > hi || a12.abs() > hi {
            return Err(RoughnessError::OutOfRange);
        }
        let det = diff_of_products(a11, a22, a12, a12);
        let indefinite = if tau > 0.0 {
            det < -8.0 * F::EPSILON * a11 * a22
        } else {
            det <= 0.0
        };
        if indefinite {
            return Err(RoughnessError::NotPositiveDefinite);
        }
        // |entries| <= ALPHA_MAX^2 = 1e8 (checked above): the squares cannot overflow, so a
        // plain square root replaces `hypot` (a libm call).
        let half_diff = 0.5 * (a11 - a22);
        let lambda_max = 0.5 * (a11 + a22) + m::sqrt(half_diff * half_diff + a12 * a12);
        let lambda_min = det.max(tau) / lambda_max;
        // Both bounds on `max(det A, tau) / l_max`: a huge `tau` (up to `F::MAX`) was accepted
        // and made `sqrt_det` ~ 1e154 against entries ~ 1e-16 (found by fuzzing).
        if lambda_max > hi || !(lo * (1.0 - 16.0 * F::EPSILON)..=hi).contains(&lambda_min) {
            return Err(RoughnessError::OutOfRange);
        }
        Ok(Self::from_entries_clamped(a11, a12, a22, tau))
    }

    /// Builds the matrix without checks, with determinant clamp `tau`. The caller guarantees
    /// `a11 > 0`, `a22 > 0` and `max(det A, tau) > 0` (the filtering kernels, which add a
    /// positive semi-definite kernel to a valid roughness, do).
    #[inline]
    ///
    /// Two representations, one result (to within an `f32` ulp):
    /// - **Wide path** (`F = f32` and `tr(A)^2 < 2^24 det A`, i.e. `cond(A) < 2^24`): only the
    ///   entries and `1 / max(det A, tau)` in `f64` are kept, and the quadratic forms are
    ///   evaluated from the entries in `f64`, `s^T adj(A) s / max(det, tau)`. The `f32`
    ///   inputs' products are exact in `f64`; the one cancellation costs a relative
    ///   `4 eps_f64 cond(A) < 2e-9`, below half an `f32` ulp. One `f64` division and one square
    ///   root build it (the eigenbasis needs three square roots and two divisions): this is
    ///   what makes a filtered lobe, built per pixel, cheap.
    /// - **Eigenbasis path** (`f64`, or `cond(A) >= 2^24`, or a determinant that is not
    ///   positive): `A = R diag(l1, l2) R^T` (see the type docs), accurate at any condition
    ///   number.
    pub(crate) fn from_entries_clamped(a11: F, a12: F, a22: F, tau: F) -> Self {
        if WIDE {
            let (b11, b12, b22) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
            let det = b11 * b22 - b12 * b12;
            let tr = b11 + b22;
            if tr * tr < COND_WIDE * det {
                // det > 0 here; max(det, tau) rounds to the F value the eigenbasis path uses.
                let clamped = det.max(tau.to_f64());
                return Self {
                    a11,
                    a12,
                    a22,
                    axis: Vec2::X,
                    eig: Vec2::ZERO,
                    inv_eig: Vec2::ZERO,
                    sqrt_det: m::sqrt(F::from_f64(clamped)),
                    inv_det_wide: 1.0 / clamped,
                    wide: true,
                };
            }
        }
        let det = diff_of_products(a11, a22, a12, a12);
        let clamped = det.max(tau);
        // Eigen-decomposition: l1 = mean + rad (no cancellation), l2 = det / l1 (accurate
        // because det is), eigenvector of l1 from whichever row avoids cancellation.
        let half_diff = 0.5 * (a11 - a22);
        let rad = m::sqrt(half_diff * half_diff + a12 * a12);
        let rad = if rad.is_finite() {
            rad
        } else {
            m::hypot(half_diff, a12)
        };
        let l1 = 0.5 * (a11 + a22) + rad;
        let l2 = det / l1;
        // Unnormalised eigenvector of l1 (both rows give the same direction; the one with
        // `rad + |half_diff|` avoids cancellation). Written as selects, not a branch: the
        // sign of `half_diff` is data-dependent and mispredicts in a filtering loop.
        let big = rad + half_diff.abs();
        let neg = half_diff < 0.0;
        let v = Vec2::new(if neg { a12 } else { big }, if neg { big } else { a12 });
        let axis = v.try_normalize().unwrap_or(Vec2::X);
        let inv_det = 1.0 / clamped;
        Self {
            a11,
            a12,
            a22,
            axis,
            eig: Vec2::new(l1, l2),
            inv_eig: Vec2::new(l2 * inv_det, l1 * inv_det),
            sqrt_det: m::sqrt(clamped),
            inv_det_wide: 0.0,
            wide: false,
        }
    }

    /// The same matrix evaluated with the determinant clamp `tau` (see the type docs). A
    /// non-finite or negative `tau` is treated as `0` (no clamp).
    #[inline]
    pub fn with_det_clamp(self, tau: F) -> Self {
        let tau = if tau.is_finite() && tau > 0.0 {
            tau
        } else {
            0.0
        };
        Self::from_entries_clamped(self.a11, self.a12, self.a22, tau)
    }

    /// `A` as a [`Mat2`] (columns `(a11, a12)`, `(a12, a22)`).
    #[inline]
    pub fn to_mat2(&self) -> Mat2 {
        Mat2::from_cols(Vec2::new(self.a11, self.a12), Vec2::new(self.a12, self.a22))
    }

    /// The entries `(a11, a12, a22)`.
    #[inline]
    pub fn entries(&self) -> (F, F, F) {
        (self.a11, self.a12, self.a22)
    }

    /// `A^-1` as used by the density, i.e. `adj(A) / max(det A, tau)`.
    #[inline]
    pub fn inverse(&self) -> Mat2 {
        if WIDE && self.wide {
            let k = self.inv_det_wide;
            let (a11, a12, a22) = (self.a11.to_f64(), self.a12.to_f64(), self.a22.to_f64());
            let (i11, i12, i22) = (
                F::from_f64(a22 * k),
                F::from_f64(-a12 * k),
                F::from_f64(a11 * k),
            );
            return Mat2::from_cols(Vec2::new(i11, i12), Vec2::new(i12, i22));
        }
        let (c, s) = (self.axis.x, self.axis.y);
        let (w1, w2) = (self.inv_eig.x, self.inv_eig.y);
        let i11 = w1 * c * c + w2 * s * s;
        let i12 = (w1 - w2) * c * s;
        let i22 = w1 * s * s + w2 * c * c;
        Mat2::from_cols(Vec2::new(i11, i12), Vec2::new(i12, i22))
    }

    /// `v` in the eigenbasis of `A`: `(v . e1, v . e2)`.
    #[inline]
    fn rotate(&self, v: Vec2) -> Vec2 {
        let (c, s) = (self.axis.x, self.axis.y);
        Vec2::new(c * v.x + s * v.y, c * v.y - s * v.x)
    }
}

impl From<AxisAligned> for RoughnessMatrix {
    #[inline]
    fn from(r: AxisAligned) -> Self {
        r.to_matrix()
    }
}

impl From<Isotropic> for RoughnessMatrix {
    #[inline]
    fn from(r: Isotropic) -> Self {
        r.to_matrix()
    }
}

/// A quadratic form `q = form(v)` clamped to `>= 0`. A NaN `q` for a finite `v` means that `r * r`
/// overflowed against a zero eigenvalue (`0 * inf`, possible only under the determinant clamp,
/// where the clamped inverse has a null direction): the form is then evaluated on `v / k`,
/// `k = max |v_i|`, and scaled back by `k^2` (`+inf` if that overflows, `0` along the null
/// direction). A NaN component of `v` gives NaN and an infinite one `+inf`, as in the
/// isotropic and axis-aligned forms.
#[inline]
fn scaled_form(q: F, v: Vec2, form: impl Fn(Vec2) -> F) -> F {
    if !q.is_nan() {
        return q.max(0.0);
    }
    if !v.is_finite() {
        return non_finite_form(v);
    }
    let k = v.abs().max_element();
    (form(v / k) * k * k).max(0.0)
}

/// A quadratic form of a vector with a non-finite component, as in the isotropic and
/// axis-aligned forms: NaN for a NaN component, else `+inf`.
#[inline]
fn non_finite_form(v: Vec2) -> F {
    if v.is_nan() { F::NAN } else { F::INFINITY }
}

impl sealed::Sealed for RoughnessMatrix {}
impl Roughness for RoughnessMatrix {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        if WIDE && self.wide {
            // s^T adj(A) s / max(det, tau), in f64 (see `from_entries_clamped`).
            let (a11, a12, a22) = (self.a11.to_f64(), self.a12.to_f64(), self.a22.to_f64());
            let (x, y) = (s.x.to_f64(), s.y.to_f64());
            let q = ((a22 * x) * x + (a11 * y) * y - 2.0 * (a12 * x) * y) * self.inv_det_wide;
            // Finite f32 input cannot overflow in f64: a NaN here means a non-finite input.
            return if q.is_nan() {
                non_finite_form(s)
            } else {
                F::from_f64(q.max(0.0))
            };
        }
        let r = self.rotate(s);
        scaled_form((r * r).dot(self.inv_eig), s, |u| {
            let r = self.rotate(u);
            (r * r).dot(self.inv_eig)
        })
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        if WIDE && self.wide {
            let (a11, a12, a22) = (self.a11.to_f64(), self.a12.to_f64(), self.a22.to_f64());
            let (x, y) = (w.x.to_f64(), w.y.to_f64());
            let q = (a11 * x) * x + (a22 * y) * y + 2.0 * (a12 * x) * y;
            return if q.is_nan() {
                non_finite_form(w)
            } else {
                F::from_f64(q.max(0.0))
            };
        }
        let r = self.rotate(w);
        scaled_form((r * r).dot(self.eig), w, |u| {
            let r = self.rotate(u);
            (r * r).dot(self.eig)
        })
    }
    #[inline]
    fn sqrt_det(&self) -> F {
        self.sqrt_det
    }
    #[inline]
    fn to_matrix(&self) -> RoughnessMatrix {
        *self
    }
}
