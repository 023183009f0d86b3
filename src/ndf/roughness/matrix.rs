//! The full-matrix roughness form: any symmetric positive-definite `A`.

use super::{
    ALPHA_MAX, ALPHA_MIN, AxisAligned, F, Isotropic, Mat2, Roughness, RoughnessError, Vec2,
    over_z2, sealed,
};
use crate::math::{self as m, Real};

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
/// **Representations.** Two, chosen by the constructor, evaluated in `f64` for both
/// precisions; they give the same values to within the stated accuracy (`PartialEq`
/// compares representations, not only the matrix):
/// - **LDL** (`det A > 0`, and in `f64` also `cond(A) < 16`: every filtered lobe of a
///   realistic material): the entries, `det A`, `c = max(det A, tau)`, `1 / (a11 c)` and
///   `c^(3/2)`, with
///   `s^T adj(A) s = ((a11 s_y - a12 s_x)^2 + det(A) s_x^2) / a11` (completing the square, the
///   2x2 `L D L^T`): a sum of two non-negative terms in which only `a11 s_y - a12 s_x` can
///   cancel. For `f32` entries and slopes both products are exact in `f64`, so that term is
///   exactly rounded and the whole form is within a few `eps_f64` at any condition number;
///   for `f64` the cancellation costs about `2 sqrt(cond A) eps_f64`, plus the determinant's
///   10 ulps, hence the `cond < 16` limit. Built with one division and one square root: a
///   lobe built per pixel (a filtered one, or a rotated anisotropic material) stays cheap.
/// - **Eigenbasis** (otherwise: a determinant that is not positive, only possible under the
///   clamp, or an `f64` matrix with `cond(A) >= 16`):
///   `A = R diag(l1, l2) R^T` with `det A` computed without cancellation error, so both
///   quadratic forms are sums of two non-negative squares: a few ulps at any condition number
///   (evaluating from the entries of `A^-1` instead cancels to a relative `cond(A) eps`,
///   6 % in `f32` at an anisotropy ratio of `1e3`). Built with two square roots and two
///   divisions, in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughnessMatrix {
    pub(super) a11: F,
    pub(super) a12: F,
    pub(super) a22: F,
    /// Unit eigenvector `(c, s)` of `l1`; `(-s, c)` is the eigenvector of `l2`.
    pub(super) axis: Vec2,
    /// Eigenvalues `(l1, l2)` of `A` (`l2` may be `<= 0` by rounding when `tau > 0`).
    pub(super) eig: Vec2,
    /// Eigenvalues of the clamped inverse `adj(A) / max(det A, tau)`: `(l2, l1) / max(det, tau)`.
    pub(super) inv_eig: Vec2,
    pub(super) sqrt_det: F,
    /// `1 / sqrt(max(det A, tau))` (eigenbasis path; `0` on the LDL path).
    pub(super) inv_sqrt_det: F,
    /// `det A` in `f64` (LDL path; `0` on the eigenbasis path).
    pub(super) ldl_det: f64,
    /// `1 / (a11 c)` in `f64`, `c = max(det A, tau)` (LDL path; `0` on the eigenbasis path).
    /// Only [`Roughness::inv_quadratic`] reads it: Beckmann's `D` divides once by
    /// `a11 c m_z^2` instead, so a filtered lobe whose matrix is built and evaluated inline
    /// never forms it (the compiler drops the division).
    pub(super) ldl_inv: f64,
    /// `c = max(det A, tau)` in `f64` (LDL path; `0` on the eigenbasis path).
    pub(super) ldl_c: f64,
    /// `c^(3/2)` in `f64` (LDL path; `0` on the eigenbasis path): Beckmann's normalisation
    /// is `(a11 t)^2 c^(3/2)` with `t = 1 / (a11 c m_z^2)`.
    pub(super) ldl_c32: f64,
    /// Whether the LDL representation is used (see the type docs).
    pub(super) ldl: bool,
}

/// `F = f32` (whose products are exact in `f64`).
const WIDE: bool = core::mem::size_of::<F>() == 4;
/// In `f64` the LDL representation is taken while `tr(A)^2 < COND_LDL det(A)`, i.e.
/// `cond(A) < 16` (`(cond + 1)^2 / cond < 18`), where the plain determinant is within 10 ulps
/// and the cancelling term costs at most `8 eps`. `f32` matrices need no limit (type docs).
const COND_LDL: f64 = 18.0;

/// `det A = a11 a22 - a12^2` in `f64` to within about one ulp of `F`'s precision, whatever
/// the cancellation: for `f32` entries the products are exact in `f64` (one rounding); for
/// `f64` entries the plain expression when `a12^2 <= a11 a22 / 2` (at most one bit cancels:
/// within 3 ulps), else Kahan's algorithm with two fused multiply-adds (calls to `fma`
/// without the target feature, so kept off the common path).
#[inline]
fn det_of(a11: F, a12: F, a22: F) -> f64 {
    let (a, b, c) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
    let (ac, bb) = (a * c, b * b);
    if WIDE || bb <= 0.5 * ac {
        return ac - bb;
    }
    let err = m::mul_add(-b, b, bb);
    m::mul_add(a, c, -bb) + err
}

/// `tau`, returned from out of line (see [`RoughnessMatrix::from_entries_det_clamped`]): the
/// opaque `black_box` keeps the compiler from seeing through the call and merging the branch
/// into a select.
#[cold]
#[inline(never)]
fn clamped(tau: f64) -> f64 {
    core::hint::black_box(tau)
}

/// `2^-e` for a positive `x = f 2^e`, `f` in `[1, 2)`: multiplying by it is exact and brings
/// `x` into `[1, 2)`. Subnormal `x` (and `0`) get `2^1022`.
#[inline]
fn inv_binade(x: f64) -> f64 {
    let e = (x.to_bits() >> 52).clamp(1, 2045);
    f64::from_bits((2046 - e) << 52)
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
    #[inline]
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
        let det = F::from_f64(det_of(a11, a12, a22));
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
    ///
    /// Picks the representation (see the type docs): LDL when `det A > 0` (and in `f64`
    /// `cond A < 16`; one division, one square root), else the eigenbasis (two of each).
    #[inline(always)]
    pub(crate) fn from_entries_clamped(a11: F, a12: F, a22: F, tau: F) -> Self {
        Self::from_entries_det_clamped(a11, a12, a22, tau.to_f64())
    }

    /// [`RoughnessMatrix::from_entries_clamped`] with `tau` in `f64`: the filtering kernels
    /// pass `det` of the unfiltered matrix exactly as this function computes `det A`, so a
    /// kernel too small to change the entries meets the clamp with equality.
    #[inline(always)]
    pub(crate) fn from_entries_det_clamped(a11: F, a12: F, a22: F, t: f64) -> Self {
        let (b11, b12, b22) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
        // Exact products for f32 entries (one rounding); in f64 the test admits only
        // `cond < 16`, where this plain determinant is within 10 ulps.
        let det = b11 * b22 - b12 * b12;
        let ldl = det > 0.0
            && (WIDE || {
                let tr = b11 + b22;
                tr * tr < COND_LDL * det
            });
        if ldl {
            // `max(det, tau)` as a branch to an out-of-line function, not a select: a filtered
            // lobe's determinant then reaches its one division directly (the clamp is active
            // only by rounding when filtering).
            let c = if det >= t { det } else { clamped(t) };
            return Self::ldl(a11, a12, a22, det, c);
        }
        // Eigenbasis path, in f64 for both precisions.
        let det = det_of(a11, a12, a22);
        let c = det.max(t);
        // l1 = mean + rad (no cancellation); l2 = det / l1 is never formed (see below).
        let half_diff = 0.5 * (b11 - b22);
        let rad = m::sqrt(half_diff * half_diff + b12 * b12);
        let rad = if rad.is_finite() {
            rad
        } else {
            m::hypot(half_diff, b12)
        };
        let l1 = 0.5 * (b11 + b22) + rad;
        // Eigenvector of l1 from whichever row avoids cancellation (`big >= |b12|`), written
        // as selects (the sign of `half_diff` would mispredict in a filtering loop). It is not
        // normalised (a square root and a division): it is scaled by a power of two to
        // `big` in `[1, 2)` (exact), and its squared length `nv` is folded into the
        // eigenvalues below. `big = 0` (isotropic): any axis.
        let big = rad + half_diff.abs();
        let neg = half_diff < 0.0;
        let k = inv_binade(big);
        let v = if big > 0.0 {
            let (p, q) = (big * k, b12 * k);
            Vec2::new(
                F::from_f64(if neg { q } else { p }),
                F::from_f64(if neg { p } else { q }),
            )
        } else {
            Vec2::X
        };
        let (vx, vy) = (v.x.to_f64(), v.y.to_f64());
        let nv = vx * vx + vy * vy;
        // With the unnormalised rotation r = (v.s, v_perp.s): eig = (l1, l2) / nv and
        // inv_eig = (l2, l1) / (max(det, tau) nv), l2 = det / l1, from two reciprocals that
        // run in parallel (`1 / max(det, tau)` does not wait for the square root). `eig` does
        // not depend on `tau` at all (Smith's Lambda never sees the clamp).
        let (j, ci) = (1.0 / (nv * l1), 1.0 / c);
        let sqrt_c = m::sqrt(c);
        let eig = (l1 * l1 * j, det * j);
        Self {
            a11,
            a12,
            a22,
            axis: v,
            eig: Vec2::new(F::from_f64(eig.0), F::from_f64(eig.1)),
            inv_eig: Vec2::new(F::from_f64(eig.1 * ci), F::from_f64(eig.0 * ci)),
            sqrt_det: F::from_f64(sqrt_c),
            inv_sqrt_det: F::from_f64(sqrt_c * ci),
            ldl_det: 0.0,
            ldl_inv: 0.0,
            ldl_c: 0.0,
            ldl_c32: 0.0,
            ldl: false,
        }
    }

    /// The LDL representation (see the type docs) with `c = max(det A, tau)`.
    #[inline(always)]
    fn ldl(a11: F, a12: F, a22: F, det: f64, c: f64) -> Self {
        // In f64: no conversions on the way to Beckmann's normalisation.
        let sqrt_c = m::sqrt(c);
        Self {
            a11,
            a12,
            a22,
            axis: Vec2::X,
            eig: Vec2::ZERO,
            inv_eig: Vec2::ZERO,
            sqrt_det: F::from_f64(sqrt_c),
            inv_sqrt_det: 0.0,
            ldl_det: det,
            ldl_inv: 1.0 / (a11.to_f64() * c),
            ldl_c: c,
            ldl_c32: c * sqrt_c,
            ldl: true,
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
        if self.ldl {
            // adj(A) / max(det, tau) = adj(A) a11 ldl_inv.
            let (a11, a12, a22) = (self.a11.to_f64(), self.a12.to_f64(), self.a22.to_f64());
            let k = a11 * self.ldl_inv;
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

/// An LDL quadratic form `q = form(v)` evaluated in `f64`, clamped to `>= 0` and rounded to
/// `F`. A NaN `q` for a finite `v` can only come from overflow (`inf - inf`, for `f64` input;
/// never for `f32`, whose squares fit in `f64`): the form is then evaluated on `v / k`, `k = max |v_i|`, and scaled back
/// by `k^2` (`+inf` if that overflows). Non-finite `v` as [`non_finite_form`].
#[inline]
fn wide_form(q: f64, v: Vec2, form: impl Fn(f64, f64) -> f64) -> F {
    if !q.is_nan() {
        return F::from_f64(q.max(0.0));
    }
    // f32 input cannot overflow in f64: a NaN means a non-finite input (a select, which
    // keeps `batch` loops vectorised).
    if WIDE || !v.is_finite() {
        return non_finite_form(v);
    }
    let k = v.abs().max_element().to_f64();
    F::from_f64((form(v.x.to_f64() / k, v.y.to_f64() / k) * k * k).max(0.0))
}

impl sealed::Sealed for RoughnessMatrix {
    #[inline(always)]
    fn exponent_and_norm(&self, m: Vec2, z2: F) -> (F, F) {
        if self.ldl {
            // t = 1 / (a11 c z2), c = max(det, tau), the one division; then
            // x = ((a11 m_y - a12 m_x)^2 + det m_x^2) t and
            // n = 1 / (sqrt(c) z2^2) = (a11 t)^2 c^(3/2), all in f64. `c (a11 z2)`: a matrix
            // built inline (filtering) reaches the division one product after `c`.
            let (a11, a12) = (self.a11.to_f64(), self.a12.to_f64());
            let (det, c) = (self.ldl_det, self.ldl_c);
            let t = 1.0 / (c * (a11 * z2.to_f64()));
            let form = |x: f64, y: f64| {
                let u = a11 * y - a12 * x;
                (u * u + det * (x * x)) * t
            };
            let x = wide_form(form(m.x.to_f64(), m.y.to_f64()), m, form);
            let at = a11 * t;
            return (x, F::from_f64(at * at * self.ldl_c32));
        }
        over_z2(self.inv_quadratic(m), self.inv_sqrt_det, z2)
    }
    #[inline(always)]
    fn det_clamped(&self) -> f64 {
        if self.ldl {
            return self.ldl_c;
        }
        // max(det, tau) is not kept in f64 on this path: its square root, rounded to F.
        let s = self.sqrt_det.to_f64();
        s * s
    }
}
impl Roughness for RoughnessMatrix {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        if self.ldl {
            // ((a11 s_y - a12 s_x)^2 + det s_x^2) / (a11 max(det, tau)), see the type docs.
            let (a11, a12) = (self.a11.to_f64(), self.a12.to_f64());
            let (det, inv) = (self.ldl_det, self.ldl_inv);
            let form = |x: f64, y: f64| {
                let u = a11 * y - a12 * x;
                (u * u + det * (x * x)) * inv
            };
            return wide_form(form(s.x.to_f64(), s.y.to_f64()), s, form);
        }
        let r = self.rotate(s);
        scaled_form((r * r).dot(self.inv_eig), s, |u| {
            let r = self.rotate(u);
            (r * r).dot(self.inv_eig)
        })
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        if self.ldl {
            // ((a11 w_x + a12 w_y)^2 + det w_y^2) / a11: no tau (Lambda never sees the clamp).
            let (a11, a12) = (self.a11.to_f64(), self.a12.to_f64());
            let det = self.ldl_det;
            let form = |x: f64, y: f64| {
                let u = a11 * x + a12 * y;
                (u * u + det * (y * y)) / a11
            };
            return wide_form(form(w.x.to_f64(), w.y.to_f64()), w, form);
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
