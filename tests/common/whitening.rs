//! The symmetric square root of a roughness matrix and its inverse, by a test-side
//! eigen-decomposition (independent of the library's own), shared by the sampling tests.

use filtered_ndf::f64::Roughness;
use glam::DVec2;

/// `B = A^(1/2)`, `B^-1` (both symmetric) and `sqrt(det A)` of a roughness matrix `A`.
pub struct Whitening {
    pub b: [[f64; 2]; 2],
    pub b_inv: [[f64; 2]; 2],
    pub sqrt_det: f64,
}

impl Whitening {
    pub fn new<R: Roughness>(r: &R) -> Self {
        let (a11, a12, a22) = r.to_matrix().entries();
        let mean = 0.5 * (a11 + a22);
        let rad = (0.5 * (a11 - a22)).hypot(a12);
        let (l1, l2) = (mean + rad, (a11 * a22 - a12 * a12) / (mean + rad));
        let theta = 0.5 * (2.0 * a12).atan2(a11 - a22);
        let (c, s) = (theta.cos(), theta.sin());
        let sq = |f1: f64, f2: f64| {
            [
                [c * c * f1 + s * s * f2, c * s * (f1 - f2)],
                [c * s * (f1 - f2), s * s * f1 + c * c * f2],
            ]
        };
        Self {
            b: sq(l1.sqrt(), l2.sqrt()),
            b_inv: sq(1.0 / l1.sqrt(), 1.0 / l2.sqrt()),
            sqrt_det: (l1 * l2).sqrt(),
        }
    }

    /// `m v` for a 2x2 matrix stored by rows.
    pub fn apply(m: &[[f64; 2]; 2], v: DVec2) -> DVec2 {
        DVec2::new(m[0][0] * v.x + m[0][1] * v.y, m[1][0] * v.x + m[1][1] * v.y)
    }
}
