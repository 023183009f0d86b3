//! LEAN moments nested into the pixel kernel (KHPL16 section 5.5, eq. 21).

use super::super::kernel::Covariance;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::Vec2;
use super::gaussian;

/// First and second moments of normal-map slopes over a texel footprint, as stored by LEAN
/// mapping (Olano and Baker 2010): `mean = E[s]`, `second = E[s s^T]` (both linearly
/// filterable, so they survive mip-mapping). LEAN's slope `b = n_xy / n_z` is the crate's
/// `-s`; the covariance does not depend on that sign.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LeanMoments {
    /// First moments `(E[s_x], E[s_y])`: KHPL16 section 5.5 uses them as the shading normal
    /// (perturb the tangent frame with them before computing the footprint).
    pub mean: Vec2,
    /// Second moments `(E[s_x^2], E[s_x s_y], E[s_y^2])`, stored in a [`Covariance`].
    pub second: Covariance,
}

impl LeanMoments {
    /// From the two moment sets.
    #[inline]
    pub const fn new(mean: Vec2, second: Covariance) -> Self {
        Self { mean, second }
    }

    /// The covariance of the normal-map slopes, `E[s s^T] - E[s] E[s]^T` (LEAN eq. 5; the
    /// kernel `K_L` of KHPL16 section 5.5), [`Covariance::sanitized`]: mip filtering or low
    /// precision can make the difference slightly indefinite, which is projected back to PSD.
    /// If the stored second moments include the base lobe's covariance (as LEAN's `1 / 2s`
    /// term does), filter a minimal base roughness instead of adding the lobe twice.
    #[inline]
    pub fn covariance(&self) -> Covariance {
        let m = self.mean;
        Covariance::new(
            self.second.s11 - m.x * m.x,
            self.second.s12 - m.x * m.y,
            self.second.s22 - m.y * m.y,
        )
        .sanitized()
    }
}

/// The nested convolution `K_L * K_P * D = (K_L * K_P) * D` (KHPL16 eq. 21): the LEAN kernel
/// and the pixel kernel are independent Gaussians, so their covariances add, and the result
/// is filtered by [`gaussian`]: `A' = A + 2 (Sigma_L + Sigma_P)`, `tau = det(A)`.
#[inline]
pub fn lean<R: Roughness>(
    roughness: R,
    pixel: Covariance,
    moments: &LeanMoments,
) -> RoughnessMatrix {
    gaussian(roughness, pixel.sanitized() + moments.covariance())
}
