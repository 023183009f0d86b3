//! The test side's one symmetric 2x2 eigen-decomposition, in `f64` and written independently
//! of the library's ([`Covariance::eigenvalues`](crate::f64::Covariance::eigenvalues),
//! the roughness matrix's eigenbasis), so that references built on it do not share the code
//! under test.
//!
//! ```
//! use filtered_ndf::testing::linalg::Sym2;
//!
//! let e = Sym2::new(2.0, 1.0, 2.0).eigen(); // eigenvalues 3 and 1, axes at 45 degrees
//! assert!((e.l1 - 3.0).abs() < 1e-15 && (e.l2 - 1.0).abs() < 1e-15);
//! assert!((e.theta - core::f64::consts::FRAC_PI_4).abs() < 1e-15);
//! // V f(Lambda) V^T: the symmetric square root.
//! let r = e.map(f64::sqrt);
//! let back = r.mul(&r);
//! assert!((back.a11 - 2.0).abs() < 1e-14 && (back.a12 - 1.0).abs() < 1e-14);
//! ```

/// A symmetric 2x2 matrix `[[a11, a12], [a12, a22]]` in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sym2 {
    /// Upper-left entry.
    pub a11: f64,
    /// Off-diagonal entry.
    pub a12: f64,
    /// Lower-right entry.
    pub a22: f64,
}

/// The eigen-decomposition `A = l1 v1 v1^T + l2 v2 v2^T` of a [`Sym2`], with
/// `v1 = (cos theta, sin theta)` and `v2 = (-sin theta, cos theta)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eigen2 {
    /// The larger eigenvalue (signed).
    pub l1: f64,
    /// The smaller eigenvalue (signed).
    pub l2: f64,
    /// Angle of the eigenvector of `l1` from the `x` axis, in `(-pi/2, pi/2]`.
    pub theta: f64,
}

impl Sym2 {
    /// From the three distinct entries.
    pub const fn new(a11: f64, a12: f64, a22: f64) -> Self {
        Self { a11, a12, a22 }
    }

    /// `R(theta) diag(l1, l2) R(theta)^T`: the matrix with eigenvalues `l1` (along
    /// `(cos theta, sin theta)`) and `l2`, e.g. a rotated roughness `l = alpha^2`.
    pub fn from_eigen(l1: f64, l2: f64, theta: f64) -> Self {
        Eigen2 { l1, l2, theta }.rebuild(l1, l2)
    }

    /// The entries `(a11, a12, a22)`.
    pub fn entries(&self) -> (f64, f64, f64) {
        (self.a11, self.a12, self.a22)
    }

    /// `det A`.
    pub fn det(&self) -> f64 {
        self.a11 * self.a22 - self.a12 * self.a12
    }

    /// The eigen-decomposition. The matrix is scaled by its largest entry first (no overflow
    /// or underflow of the squares for finite entries); the eigenvalue of larger magnitude is
    /// `mean +/- hypot(half difference, a12)` with the sign of `mean`, the other `det` divided
    /// by it, from the unscaled entries (no cancellation for either sign). Non-finite entries
    /// give NaN.
    pub fn eigen(&self) -> Eigen2 {
        let scale = self.a11.abs().max(self.a12.abs()).max(self.a22.abs());
        if !scale.is_finite() || scale.is_nan() {
            return Eigen2 {
                l1: f64::NAN,
                l2: f64::NAN,
                theta: f64::NAN,
            };
        }
        if scale == 0.0 {
            return Eigen2 {
                l1: 0.0,
                l2: 0.0,
                theta: 0.0,
            };
        }
        let (a, b, c) = (self.a11 / scale, self.a12 / scale, self.a22 / scale);
        let mean = 0.5 * (a + c);
        let rad = (0.5 * (a - c)).hypot(b);
        // The eigenvalue of larger magnitude without cancellation; the other is `det / big`,
        // formed from the unscaled entries divided first, so it keeps its relative accuracy
        // for both signs even where the scaled entries underflow.
        let big_s = if mean >= 0.0 { mean + rad } else { mean - rad };
        let big = big_s * scale;
        let other = if big != 0.0 && big.is_finite() {
            // |big| bounds every entry: divide the larger diagonal entry (its quotient cannot
            // underflow where the product matters).
            let (lo, hi) = if self.a11.abs() <= self.a22.abs() {
                (self.a11, self.a22)
            } else {
                (self.a22, self.a11)
            };
            (hi / big) * lo - (self.a12 / big) * self.a12
        } else if big_s != 0.0 {
            (a * c - b * b) / big_s * scale
        } else {
            0.0
        };
        let (l1, l2) = if mean >= 0.0 {
            (big, other)
        } else {
            (other, big)
        };
        Eigen2 {
            l1,
            l2,
            theta: 0.5 * (2.0 * b).atan2(a - c),
        }
    }

    /// `A B` for symmetric `A`, `B` that commute (e.g. functions of the same matrix), as a
    /// [`Sym2`] (the symmetric part of the product).
    pub fn mul(&self, o: &Self) -> Self {
        let a12 = self.a11 * o.a12 + self.a12 * o.a22;
        let a21 = self.a12 * o.a11 + self.a22 * o.a12;
        Self::new(
            self.a11 * o.a11 + self.a12 * o.a12,
            0.5 * (a12 + a21),
            self.a12 * o.a12 + self.a22 * o.a22,
        )
    }

    /// `A v`.
    pub fn apply(&self, v: [f64; 2]) -> [f64; 2] {
        [
            self.a11 * v[0] + self.a12 * v[1],
            self.a12 * v[0] + self.a22 * v[1],
        ]
    }
}

impl Eigen2 {
    /// `V f(Lambda) V^T`: the matrix function `f(A)` (e.g. `sqrt`, a clamp of the
    /// eigenvalues, `1 / sqrt`).
    pub fn map(&self, f: impl Fn(f64) -> f64) -> Sym2 {
        self.rebuild(f(self.l1), f(self.l2))
    }

    /// `V diag(f1, f2) V^T` with this decomposition's eigenvectors.
    pub fn rebuild(&self, f1: f64, f2: f64) -> Sym2 {
        let (c, s) = (self.theta.cos(), self.theta.sin());
        Sym2::new(
            c * c * f1 + s * s * f2,
            c * s * (f1 - f2),
            s * s * f1 + c * c * f2,
        )
    }
}
