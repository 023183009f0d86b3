//! A baked roughness chain read back as the lobe a renderer evaluates: the inverse of the
//! encodings of [`fit`](super::fit) (`shaders/bake/roughness.wgsl` mirrors it).

use super::fit::{AnisotropicAlpha, KhrAnisotropy};
use crate::math as m;
use glam::DVec2;

/// glTF's perceptual roughness `r` as `alpha = r^2` (the inverse of [`fit::perceptual`](super::fit::perceptual) on
/// `[0, 1]`).
#[inline]
pub fn alpha_from_perceptual(r: f64) -> f64 {
    r * r
}

impl AnisotropicAlpha {
    /// The roughness matrix `A = R diag(alpha_x^2, alpha_y^2) R^T` with `R` the rotation by
    /// `angle`, as its entries `(A11, A12, A22)` (the lobe `Ggx::new(RoughnessMatrix::new(..))`
    /// evaluates).
    pub fn matrix(&self) -> (f64, f64, f64) {
        let (s, c) = (m::sin(self.angle), m::cos(self.angle));
        let (x2, y2) = (self.alpha_x * self.alpha_x, self.alpha_y * self.alpha_y);
        (
            c * c * x2 + s * s * y2,
            c * s * (x2 - y2),
            s * s * x2 + c * c * y2,
        )
    }
}

impl KhrAnisotropy {
    /// The lobe this encoding describes (`KHR_materials_anisotropy`): `alpha_y = r^2` across
    /// the direction, `alpha_x = mix(alpha_y, 1, strength^2)` along it, at the direction's
    /// angle (a zero direction: `0`). The inverse of [`AnisotropicAlpha::khr`] for lobes
    /// with `alpha_y <= alpha_x <= 1`.
    pub fn alpha(&self) -> AnisotropicAlpha {
        let alpha_y = self.roughness * self.roughness;
        let b2 = self.strength * self.strength;
        let d = self.direction;
        AnisotropicAlpha {
            alpha_x: alpha_y + (1.0 - alpha_y) * b2,
            alpha_y,
            angle: if d == DVec2::ZERO {
                0.0
            } else {
                m::atan2(d.y, d.x)
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn khr_round_trip_and_matrix_closed_form() {
        // A lobe along 30 degrees: the encoding's inverse, and the matrix's eigenpairs.
        let lobe = AnisotropicAlpha {
            alpha_x: 0.6,
            alpha_y: 0.2,
            angle: core::f64::consts::FRAC_PI_6,
        };
        let back = lobe.khr().alpha();
        assert!((back.alpha_x - 0.6).abs() < 1e-15 && (back.alpha_y - 0.2).abs() < 1e-15);
        assert!((back.angle - lobe.angle).abs() < 1e-15);
        let (a11, a12, a22) = lobe.matrix();
        // A e1 = alpha_x^2 e1 and A e2 = alpha_y^2 e2 with e1 = (cos 30, sin 30).
        let (c, s) = (0.75f64.sqrt(), 0.5);
        assert!((a11 * c + a12 * s - 0.36 * c).abs() < 1e-15);
        assert!((a12 * c + a22 * s - 0.36 * s).abs() < 1e-15);
        assert!((-a11 * s + a12 * c + 0.04 * s).abs() < 1e-15);
        assert_eq!(alpha_from_perceptual(0.5), 0.25);
    }
}
