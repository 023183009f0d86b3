//! The symmetric square root of a roughness matrix and its inverse, by the test side's own
//! eigen-decomposition (`filtered_ndf::testing::linalg`, independent of the library's),
//! shared by the sampling tests.

use filtered_ndf::f64::Roughness;
use filtered_ndf::testing::linalg::Sym2;
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
        let e = Sym2::new(a11, a12, a22).eigen();
        let rows = |m: Sym2| [[m.a11, m.a12], [m.a12, m.a22]];
        Self {
            b: rows(e.map(f64::sqrt)),
            b_inv: rows(e.map(|l| 1.0 / l.sqrt())),
            sqrt_det: (e.l1 * e.l2).sqrt(),
        }
    }

    /// `m v` for a 2x2 matrix stored by rows.
    pub fn apply(m: &[[f64; 2]; 2], v: DVec2) -> DVec2 {
        DVec2::new(m[0][0] * v.x + m[0][1] * v.y, m[1][0] * v.x + m[1][1] * v.y)
    }
}
