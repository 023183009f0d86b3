//! The full-matrix roughness form: any symmetric positive-definite `A`, with the TK19
//! determinant clamp.

use super::{ALPHA_MAX, ALPHA_MIN, F, Mat2, Roughness, RoughnessError, Vec2, det_wide, sealed};
use crate::math::{self as m, Real};

/// Full symmetric positive-definite roughness matrix `A = [[a11, a12], [a12, a22]]` (TK19
/// supplement section 1; Heitz 2014 section 5.4). For a Beckmann lobe `A` is twice the slope
/// covariance (KHPL16 eq. 14); rotating the lobe by `R` maps `A` to `R A R^T`.
///
/// # The determinant clamp
/// A matrix carries a determinant clamp `tau >= 0` (TK19 supplement, "Practical
/// Implementation"; `det_clamp` in the API), which protects a filtered, elongated matrix whose
/// determinant lost its digits when its entries were rounded. Every method (`D`, `P22`,
/// `Lambda`, the samplers' warp, [`RoughnessMatrix::inverse`]) evaluates one matrix:
///
/// - `A_c = A` when `det A >= tau`;
/// - `A_c = A + t I` otherwise, `t > 0` the root of `det(A + t I) = tau`:
///   `t = (tau - det A) / (tr(A) / 2 + sqrt(tr(A)^2 / 4 + tau - det A))`.
///
/// So `det A_c = c = max(det A, tau)`, and `D` is normalised for `A_c`. **Bias:** none when
/// `det A >= tau` (in exact arithmetic filtering never lowers the determinant, so the clamp
/// `tau = det(A_unfiltered)` of the filters is active only where rounding broke that). When
/// active, `A_c - A = t I` is positive semi-definite: for Beckmann exactly the convolution
/// with an isotropic slope kernel of variance `t / 2` (KHPL16 eq. 15), a blur, never a
/// sharpening; for an elongated lobe `t ~ (tau - det A) / lambda_max`, which raises the minor
/// roughness^2 to about `tau / lambda_max` and leaves the major one unchanged to a relative
/// `(tau - det A) / lambda_max^2`. (TK19's literal formula, `sqrt(max(det A, tau))` with
/// `A^-1 = adj(A) / max(det A, tau)`, is not normalised when the clamp is active: its
/// integral is `sqrt(tau / det A)`, unbounded for a singular `A`.)
///
/// # Representation
/// The entries of `A` as given (returned by [`RoughnessMatrix::entries`]), and `A_c` by its
/// `L D L^T` factors: the pivot `p = (A_c)_11` (`a11 + t` rounded to `F`; `a11` when the
/// clamp is inactive) and `c = det A_c` in `f64`. Then
/// `A_c = [[p, a12], [a12, (a12^2 + c) / p]]`, symmetric positive definite with determinant
/// exactly `c` whatever the rounding of `p` (which moves `A_c` off the exact `A + t I` by
/// `eps / 2` of its (1, 1) entry, and its quadratic forms by at most `kappa eps / 2`: the
/// clamped lobe is stored to the precision, as any filtered lobe's entries are), and
///
/// - `s^T A_c^-1 s = ((p s_y - a12 s_x)^2 + c s_x^2) / (p c)`,
/// - `w^T A_c w = ((p w_x + a12 w_y)^2 + c w_y^2) / p`,
///
/// sums of two non-negative terms, evaluated in `f64` for both precisions, in which only
/// `u = p s_y - a12 s_x` can cancel. Accuracy, relative, against the exact forms of the stored
/// matrix at the given (rounded) argument, for any condition number `kappa` of `A_c`:
///
/// - **`f32`**: `p s_y` and `a12 s_x` are exact in `f64` (24 + 24 bits), and `c` is the
///   determinant of the `f32` entries rounded once: each form is within a few `eps_f64` before
///   its one rounding to `f32`, i.e. within `eps_f32 / 2 + 8 eps_f64`.
/// - **`f64`**: `c` within `16 eps` (`roughness::det_wide`); `u`'s cancellation costs at most
///   `sqrt(kappa) eps` of the form `q` (`|u| <= sqrt(p c q)`, its rounding error is at most
///   `eps |s| sqrt(p lambda_max) / 2`, and `q >= |s|^2 / lambda_max`), so each form is within
///   `(sqrt(kappa) + 24) eps` (`tests/matrix_representations.rs`, condition numbers to
///   `1e12`). An eigenbasis representation has the same `sqrt(kappa) eps` loss in the
///   rotation of `s`; removing it needs an error-free product per evaluation, a library `fma`
///   call without the `fma` target feature, which would make every `f64` evaluation slower.
///
/// Building a matrix costs one square root and one division (a lobe built per pixel, as
/// filtering does, stays cheap); the clamp adds a square root where it is active.
///
/// # Equality
/// By value: two matrices are equal when their entries and their clamped determinant
/// `c = max(det A, tau)` are (then `A_c` and every method agree). A clamp at or below `det A`
/// is no clamp: `new_with_det_clamp(a11, a12, a22, tau)` equals `new(a11, a12, a22)` then.
#[derive(Clone, Copy, Debug)]
// Fields in 16-byte groups of what is read together, the groups 16-byte aligned: a copy of
// the matrix through memory (passed by value, or spilled) is written in 16-byte pieces, and a
// vector load of two fields across two pieces cannot be forwarded from those stores (with the
// default field order, GGX `D` of a matrix passed by value stalls on every call;
// `benches/ndf.rs`).
#[repr(C, align(16))]
pub struct RoughnessMatrix {
    /// `c = det A_c = max(det A, tau)`, in `f64`.
    det: f64,
    /// `1 / (p c)` in `f64` (`A_c^-1 = adj(A_c) / c`). Only [`Roughness::inv_quadratic`] reads
    /// it: Beckmann's `D` divides once by `c p m_z^2` instead, so a matrix built and
    /// evaluated inline never forms it (the compiler drops the division).
    inv_pivot_det: f64,
    /// `p = (A_c)_11`: `a11`, or `a11 + t` rounded to `F` when the clamp is active.
    pivot: F,
    /// `A`'s off-diagonal entry (also `A_c`'s).
    a12: F,
    /// `c^(3/2)` in `f64`: Beckmann's normalisation `1 / (sqrt(c) z^4)` is `(p t)^2 c^(3/2)`
    /// with `t = 1 / (c p z^2)`, from that one division.
    det_3_2: f64,
    /// `sqrt(c)`, rounded to `F`.
    sqrt_det: F,
    /// `A`'s diagonal entries as given.
    a11: F,
    a22: F,
}

impl PartialEq for RoughnessMatrix {
    /// By value: the entries and `c = max(det A, tau)` (see the type docs).
    #[inline]
    fn eq(&self, o: &Self) -> bool {
        self.a11 == o.a11 && self.a12 == o.a12 && self.a22 == o.a22 && self.det == o.det
    }
}

/// `t` with `det(A + t I) = tau` for `det < tau` and `tr > 0`:
/// `t^2 + tr t + det - tau = 0`, the positive root in the form without cancellation (and
/// without overflow for `tau` up to `f64::MAX`).
#[inline]
fn clamp_shift(a11: f64, a22: f64, det: f64, tau: f64) -> f64 {
    let (h, gap) = (0.5 * (a11 + a22), tau - det);
    gap / (h + m::sqrt(h * h + gap))
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

    /// Checked constructor with the TK19 determinant clamp `tau = det_clamp` (see the type
    /// docs for the matrix `A_c` it evaluates).
    ///
    /// With `det_clamp > 0` a matrix whose determinant is non-positive only by rounding
    /// (`det A >= -8 eps a11 a22`) is accepted; a clearly indefinite one is refused.
    /// `det_clamp` must be finite and `>= 0` (else `NotFinite` / `NotPositive`). The range
    /// check `[ALPHA_MIN^2, ALPHA_MAX^2]` applies to the eigenvalues of `A_c`.
    #[inline]
    pub fn new_with_det_clamp(
        a11: F,
        a12: F,
        a22: F,
        det_clamp: F,
    ) -> Result<Self, RoughnessError> {
        if !(a11.is_finite() && a12.is_finite() && a22.is_finite() && det_clamp.is_finite()) {
            return Err(RoughnessError::NotFinite);
        }
        if a11 <= 0.0 || a22 <= 0.0 || det_clamp < 0.0 {
            return Err(RoughnessError::NotPositive);
        }
        let (lo, hi) = (
            (ALPHA_MIN * ALPHA_MIN).to_f64(),
            (ALPHA_MAX * ALPHA_MAX).to_f64(),
        );
        // Entries beyond the eigenvalue range would overflow the determinant below.
        if a11.to_f64() > hi || a22.to_f64() > hi || a12.abs().to_f64() > hi {
            return Err(RoughnessError::OutOfRange);
        }
        let det = det_wide(a11, a12, a22);
        let tau = det_clamp.to_f64();
        let indefinite = if tau > 0.0 {
            det < -8.0 * F::EPSILON.to_f64() * a11.to_f64() * a22.to_f64()
        } else {
            det <= 0.0
        };
        if indefinite {
            return Err(RoughnessError::NotPositiveDefinite);
        }
        let r = Self::from_entries(a11, a12, a22, tau);
        // The eigenvalues of A_c = A + t I (t as applied to the pivot, 0 without the clamp):
        // lambda_max = mean + radius + t, lambda_min = c / lambda_max.
        let (b11, b12, b22) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
        let t = r.pivot.to_f64() - b11;
        let half_diff = 0.5 * (b11 - b22);
        let l_max = 0.5 * (b11 + b22) + m::sqrt(half_diff * half_diff + b12 * b12) + t;
        let l_min = r.det / l_max;
        // `lo (1 - 16 eps)`: an isotropic ALPHA_MIN rounds its square by up to an ulp.
        let lo = lo * (1.0 - 16.0 * F::EPSILON.to_f64());
        if !(l_max <= hi && l_min >= lo) {
            return Err(RoughnessError::OutOfRange);
        }
        Ok(r)
    }

    /// Builds the matrix without checks, with the determinant clamp `tau` (`<= 0`: none).
    /// The caller guarantees `a11 > 0`, `a22 > 0` and `max(det A, tau) > 0` (the filters,
    /// which add a positive semi-definite kernel to a valid roughness and clamp with its
    /// determinant, do).
    #[inline(always)]
    pub(crate) fn from_entries(a11: F, a12: F, a22: F, tau: f64) -> Self {
        let det = det_wide(a11, a12, a22);
        // Inactive clamp (every lobe but those whose determinant rounding broke): A_c = A.
        let (pivot, c) = if det >= tau {
            (a11, det)
        } else {
            let t = clamp_shift(a11.to_f64(), a22.to_f64(), det, tau);
            (F::from_f64(a11.to_f64() + t), tau)
        };
        Self::from_pivot(a11, a12, a22, pivot, c)
    }

    /// [`RoughnessMatrix::from_entries`] where the clamp is inactive, without a branch (for
    /// `batch`'s lanes): `(matrix, ok)`, the same matrix bit for bit where `ok`, i.e. where
    /// [`det_wide`]'s direct branch applies and `det A >= tau`, `det A > 0` (so that the
    /// filters' `valid_clamp` keeps `tau` too). Elsewhere the matrix is garbage, not used.
    #[inline(always)]
    pub(crate) fn from_entries_unclamped(a11: F, a12: F, a22: F, tau: f64) -> (Self, bool) {
        let (det, direct) = super::det_wide_direct(a11, a12, a22);
        let ok = direct & (det >= tau) & (det > 0.0);
        (Self::from_pivot(a11, a12, a22, a11, det), ok)
    }

    /// The representation from its pivot `p` and determinant `c = det A_c`.
    #[inline(always)]
    fn from_pivot(a11: F, a12: F, a22: F, pivot: F, c: f64) -> Self {
        let p = pivot.to_f64();
        let sqrt_c = m::sqrt(c);
        Self {
            a11,
            a12,
            a22,
            pivot,
            det: c,
            inv_pivot_det: 1.0 / (p * c),
            det_3_2: c * sqrt_c,
            sqrt_det: F::from_f64(sqrt_c),
        }
    }

    /// [`RoughnessMatrix::from_entries`] with the clamp in `F` (the temporal lobe's).
    #[inline(always)]
    pub(crate) fn from_entries_clamped(a11: F, a12: F, a22: F, tau: F) -> Self {
        Self::from_entries(a11, a12, a22, tau.to_f64())
    }

    /// The same matrix `A` evaluated with the determinant clamp `tau = det_clamp` (see the type
    /// docs). A non-finite or negative `det_clamp` is treated as `0` (no clamp). A clamp that
    /// would leave no positive determinant (only a matrix accepted with `det A <= 0` under a
    /// clamp can meet one) keeps the current clamp.
    #[inline]
    pub fn with_det_clamp(self, det_clamp: F) -> Self {
        let tau = det_clamp_tau(det_clamp);
        let tau = if tau > 0.0 || det_wide(self.a11, self.a12, self.a22) > 0.0 {
            tau
        } else {
            self.det
        };
        Self::from_entries(self.a11, self.a12, self.a22, tau)
    }

    /// `A` as a [`Mat2`] (columns `(a11, a12)`, `(a12, a22)`), as given.
    #[inline]
    pub fn to_mat2(&self) -> Mat2 {
        Mat2::from_cols(Vec2::new(self.a11, self.a12), Vec2::new(self.a12, self.a22))
    }

    /// The entries `(a11, a12, a22)` of `A`, as given.
    #[inline]
    pub fn entries(&self) -> (F, F, F) {
        (self.a11, self.a12, self.a22)
    }

    /// The entries `(a11, a12, a22)` of `A_c`, the matrix every method evaluates (type docs),
    /// rounded to `F`: `A`'s own when the clamp is inactive, else `A + t I` with `t` as
    /// applied to the pivot.
    #[inline]
    pub fn clamped_entries(&self) -> (F, F, F) {
        let t = self.pivot - self.a11;
        (self.pivot, self.a12, self.a22 + t)
    }

    /// `det A_c = max(det A, tau)` in `f64`, with `det A` from `roughness::det_wide` (the determinant
    /// the filters clamp with).
    #[inline]
    pub fn clamped_det(&self) -> f64 {
        self.det
    }

    /// `A_c^-1 = adj(A_c) / c`, the inverse the density uses, rounded to `F`.
    #[inline]
    pub fn inverse(&self) -> Mat2 {
        let (p, b) = (self.pivot.to_f64(), self.a12.to_f64());
        let k = self.inv_pivot_det;
        let (i11, i12, i22) = (
            F::from_f64((b * b + self.det) * k),
            F::from_f64(-b * p * k),
            F::from_f64(p * p * k),
        );
        Mat2::from_cols(Vec2::new(i11, i12), Vec2::new(i12, i22))
    }

    /// `(p s_y - a12 s_x)^2 + c s_x^2 = p c s^T A_c^-1 s`, in `f64`.
    #[inline(always)]
    fn adj_form(&self, x: f64, y: f64) -> f64 {
        let u = self.pivot.to_f64() * y - self.a12.to_f64() * x;
        u * u + self.det * (x * x)
    }

    /// Beckmann's exponent and norm (`exponent_and_norm`'s formula: `x = ((p s_y - a12
    /// s_x)^2 + c s_x^2) t`, `n = (p t)^2 c^(3/2)`, `t = 1 / (c p z2)`, `p = a11`,
    /// `c = a11 a22 - a12^2`) of the unclamped matrix with these entries, in `F`'s own
    /// precision: no `f64` and one vector width for `batch`'s `f32` lanes (the filtered
    /// Beckmann's first tier; `f64` arithmetic there halves the lanes per instruction).
    /// Returns `(x, n, matrix_ok, eval_ok)`:
    ///
    /// - `matrix_ok`: `a12^2 <= 3 a11 a22 / 4` as rounded (the correlation `rho^2 <= 3/4`, on
    ///   which the bound rests), `c >= tau (1 + 8 eps)` rounded to `F` and `c >= 2^-100`: then
    ///   `det A >= tau` exactly, so the determinant clamp of the scalar path is inactive and
    ///   it evaluates the same matrix;
    /// - `eval_ok`: `c p z2` in `[2^-100, F::MAX]` and the numerator finite (no subnormal or
    ///   overflowing step that matters).
    ///
    /// **Bound** (first order in `u = eps / 2`, where both flags hold), relative to the exact
    /// forms of the given entries at the given `(s, z2)`: `c` within `(1 + K) u <= 8 u`
    /// (`K = (a11 a22 + a12^2) / c = (1 + rho^2) / (1 - rho^2) <= 7`); in the numerator
    /// `N = p R`, `R = s^T adj(A) s`, the rounding of `u_s = p s_y - a12 s_x` costs
    /// `2 u sqrt(N) (|p s_y| + |a12 s_x|) <= 2 S u N` with `S^2 = 2 / (1 - |rho|) <= 14.9`
    /// (since `N >= p (1 - |rho|) (p s_y^2 + a22 s_x^2)`), the other steps `11 u`: `N` within
    /// `18.7 u`; `t` within `11 u`; so `x` within `30.7 u`, and `n` within `16 u` (`p t c =
    /// 1 / z2` and `p t sqrt(c) = 1 / (sqrt(c) z2)` are formed apart, so `c`'s error enters
    /// `n` only through its square root). Tested against `f64` below. (At `rho^2 <= 1/2` the
    /// bound on `x` would be `20 u`, but twice the elements of a smooth lobe under an elongated
    /// footprint would leave the `f32` lane: 15 % against 7 % at `alpha = 0.01`.)
    #[inline(always)]
    #[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
    pub(crate) fn exponent_and_norm_narrow(
        a11: F,
        a12: F,
        a22: F,
        tau: f64,
        s: Vec2,
        z2: F,
    ) -> (F, F, bool, bool) {
        // 2^-100: far above the subnormals, so no step below loses relative accuracy.
        const LOW: F = 7.888_609e-31;
        let (pr, bb) = (a11 * a22, a12 * a12);
        let c = pr - bb;
        let den = c * (a11 * z2);
        let t = 1.0 / den;
        let us = a11 * s.y - a12 * s.x;
        let num = us * us + c * (s.x * s.x);
        let w = a11 * t;
        let n = (w * c) * (w * m::sqrt(c));
        let c_min = F::from_f64(tau * (1.0 + 8.0 * F::EPSILON.to_f64())).max(LOW);
        let matrix_ok = (4.0 * bb <= 3.0 * pr) & (c >= c_min);
        let eval_ok = (den >= LOW) & (den <= F::MAX) & (num <= F::MAX);
        (num * t, n, matrix_ok, eval_ok)
    }
}

/// A quadratic form `q = form(v)` evaluated in `f64` (a sum of non-negative terms times a
/// positive factor, so `>= 0` without a clamp) and rounded to `F`.
/// A NaN `q` for a finite `v` can only come from overflow (`inf - inf`, for `f64` input;
/// never for `f32`, whose squares fit in `f64`): the form is then evaluated on `v / k`,
/// `k = max |v_i|`, and scaled back by `k^2` (`+inf` if that overflows). A non-finite `v`
/// gives NaN for a NaN component, else `+inf` (as the isotropic and axis-aligned forms).
#[inline]
fn wide_form(q: f64, v: Vec2, form: impl Fn(f64, f64) -> f64) -> F {
    if !q.is_nan() {
        return F::from_f64(q);
    }
    // `f32` input cannot overflow in `f64`: a NaN means a non-finite input (decided without
    // the rescaling branch, which keeps `batch` loops vectorised).
    if core::mem::size_of::<F>() == 4 || !v.is_finite() {
        return if v.is_nan() { F::NAN } else { F::INFINITY };
    }
    let k = v.abs().max_element().to_f64();
    F::from_f64(form(v.x.to_f64() / k, v.y.to_f64() / k) * k * k)
}

impl sealed::Sealed for RoughnessMatrix {
    #[inline(always)]
    fn form(&self) -> sealed::Form {
        sealed::Form::Matrix(*self)
    }
    #[inline(always)]
    fn exponent_and_norm(&self, mxy: Vec2, z2: F) -> (F, F) {
        // t = 1 / (c p z2), the one division; x = adj_form t and n = 1 / (sqrt(c) z2^2) =
        // (p t)^2 c^(3/2), all in f64. `c (p z2)`: a matrix built inline (filtering) reaches
        // the division one product after `c`.
        let p = self.pivot.to_f64();
        let t = 1.0 / (self.det * (p * z2.to_f64()));
        let form = |x: f64, y: f64| self.adj_form(x, y) * t;
        let x = wide_form(form(mxy.x.to_f64(), mxy.y.to_f64()), mxy, form);
        let pt = p * t;
        (x, F::from_f64(pt * pt * self.det_3_2))
    }
    #[inline(always)]
    fn lobe_det(&self) -> f64 {
        self.det
    }
    #[inline(always)]
    fn own_det_clamp(&self) -> f64 {
        if self.det > det_wide(self.a11, self.a12, self.a22) {
            self.det
        } else {
            0.0
        }
    }
    #[inline(always)]
    fn entries_f(&self) -> (F, F, F) {
        self.entries()
    }
    #[inline(always)]
    fn cholesky(&self) -> (F, F, F) {
        // A_c = L L^T: l11 = sqrt(p), l21 = a12 / l11, l22 = sqrt(c / p) = sqrt(c) / l11.
        let l11 = m::sqrt(self.pivot.to_f64());
        (
            F::from_f64(l11),
            F::from_f64(self.a12.to_f64() / l11),
            F::from_f64(m::sqrt(self.det) / l11),
        )
    }
}

impl Roughness for RoughnessMatrix {
    #[inline]
    fn inv_quadratic(&self, s: Vec2) -> F {
        let form = |x: f64, y: f64| self.adj_form(x, y) * self.inv_pivot_det;
        wide_form(form(s.x.to_f64(), s.y.to_f64()), s, form)
    }
    #[inline]
    fn quadratic(&self, w: Vec2) -> F {
        let (p, b) = (self.pivot.to_f64(), self.a12.to_f64());
        let form = |x: f64, y: f64| {
            let u = p * x + b * y;
            (u * u + self.det * (y * y)) / p
        };
        wide_form(form(w.x.to_f64(), w.y.to_f64()), w, form)
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

/// A determinant clamp given as a number, as the `f64` `tau` the clamped matrix takes: the
/// value where finite and positive, else `0` (no clamp). One reading for
/// [`RoughnessMatrix::with_det_clamp`] and the filters' `*_with_det_clamp`.
#[inline(always)]
pub(crate) fn det_clamp_tau(det_clamp: F) -> f64 {
    if det_clamp.is_finite() && det_clamp > 0.0 {
        det_clamp.to_f64()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `exponent_and_norm_narrow` (`f32`) against the `f64` forms of the same entries and
    /// arguments (products of `f32` values exact in `f64`: the reference is good to a few
    /// `eps_64`), on matrices with eigenvalues from `1e-8` to `10`, condition numbers to `1e6`
    /// and every orientation (so that the correlation test flags a share of them), and slopes
    /// out to the far tail (`x` to about `1e6`). Where both flags hold: `x` within the derived
    /// `30.7 u`, `n` within `16 u` (`u = eps / 2`; tested at `32 u` and `17 u`, the second
    /// order terms).
    #[test]
    fn narrow_exponent_and_norm_within_their_bound() {
        if F::MANTISSA_DIGITS > 24 {
            return; // `f32` only: `batch` uses it in `f32`.
        }
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || crate::math::test_uniform(&mut state);
        let u = F::EPSILON.to_f64() / 2.0;
        let (mut worst_x, mut worst_n, mut kept, mut total) = (0.0f64, 0.0f64, 0, 0);
        for _ in 0..200_000 {
            let l1 = 10f64.powf(-8.0 + 9.0 * next());
            let l2 = l1 * 10f64.powf(-6.0 * next());
            let th = core::f64::consts::PI * next();
            let (c, s) = (th.cos(), th.sin());
            let a11 = F::from_f64(l1 * c * c + l2 * s * s);
            let a12 = F::from_f64((l1 - l2) * c * s);
            let a22 = F::from_f64(l1 * s * s + l2 * c * c);
            let k = 10f64.powf(-3.0 + 6.0 * next());
            let phi = core::f64::consts::TAU * next();
            let (sx, sy) = (k * l1.sqrt() * phi.cos(), k * l1.sqrt() * phi.sin());
            let mz = 1.0 / (1.0 + sx * sx + sy * sy).sqrt();
            let (mx, my, mz) = (
                F::from_f64(-sx * mz),
                F::from_f64(-sy * mz),
                F::from_f64(mz),
            );
            let z2 = mz * mz;
            total += 1;
            let (x, n, matrix_ok, eval_ok) = RoughnessMatrix::exponent_and_norm_narrow(
                a11,
                a12,
                a22,
                0.0,
                Vec2::new(mx, my),
                z2,
            );
            if !(matrix_ok && eval_ok) {
                continue;
            }
            kept += 1;
            let (p, b, r) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
            let (xs, ys, z2) = (mx.to_f64(), my.to_f64(), z2.to_f64());
            let det = p * r - b * b;
            let us = p * ys - b * xs;
            let q = (us * us + det * (xs * xs)) / (det * p * z2);
            let norm = 1.0 / (det.sqrt() * z2 * z2);
            if q > 0.0 {
                worst_x = worst_x.max((x.to_f64() - q).abs() / q / u);
            }
            worst_n = worst_n.max((n.to_f64() - norm).abs() / norm / u);
        }
        // The correlation test flags most of the elongated, rotated ones.
        assert!(
            kept > total / 5,
            "only {kept} of {total} on the narrow path"
        );
        assert!(worst_x <= 32.0, "x: {worst_x} u");
        assert!(worst_n <= 17.0, "n: {worst_n} u");
        std::println!("narrow: {kept} of {total}; worst x {worst_x:.2} u, n {worst_n:.2} u");
    }
}
