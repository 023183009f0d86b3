//! `A' = A + 2 Sigma`: the Beckmann convolution (KHPL16 eq. 13-15) and the TK19 (section 2.2)
//! matrix approximation for GGX.

use super::super::kernel::Covariance;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::F;

/// `A' = A + 2 Sigma`, evaluated with the determinant clamp `tau = det(A)` (TK19 supplement).
///
/// - **Beckmann: exact.** A Beckmann lobe is a Gaussian of slopes with covariance
///   `B = A / 2` (KHPL16 eq. 14); convolving with the kernel `N(0, Sigma)` adds covariances
///   (eq. 15, `B' = B + Sigma`), and the filtered lobe is Beckmann with `A' = 2 B'`.
/// - **GGX: the TK19 (section 2.2) / KHPL16 approximation.** The GGX lobe is treated as if it
///   were Gaussian; its error against the exact Gaussian-filtered GGX is measured in
///   `tests/filter_ggx_error.rs`.
///
/// `tau = det(A)` has no bias in exact arithmetic since `det(A + 2 Sigma) >= det(A)` for
/// `Sigma >= 0`; it is `det(A)` of the entries as stored (for a clamped [`RoughnessMatrix`],
/// its own `max(det A, tau)`). Units: `A` dimensionless (slope^2), `Sigma` slope^2.
#[inline(always)]
pub fn gaussian<R: Roughness>(roughness: R, kernel: Covariance) -> RoughnessMatrix {
    gaussian_sanitized(roughness, kernel.sanitized())
}

/// [`gaussian`] for a kernel that [`Covariance::sanitized`] (or a clamp applied after it)
/// has already made finite, non-negative on the diagonal and bounded.
#[inline(always)]
pub(crate) fn gaussian_sanitized<R: Roughness>(roughness: R, k: Covariance) -> RoughnessMatrix {
    // tau = det(A) > 0 is valid by construction: no check, no floor (the hot path).
    let (b11, b12, b22) = plus_kernel(roughness, k);
    RoughnessMatrix::from_entries_det_clamped(b11, b12, b22, roughness.det_clamped())
}

/// [`gaussian`] with an explicit determinant clamp `tau` (`0` disables it; NaN, infinite or
/// negative `tau` is treated as `0`). The kernel is [`Covariance::sanitized`] first. Even
/// with `tau = 0`, a filtered determinant that rounds to `<= det(A)` (an extremely elongated
/// kernel, or underflow) is replaced by `det(A)`, its exact lower bound, so the result is
/// always valid.
#[inline]
pub fn gaussian_with_tau<R: Roughness>(
    roughness: R,
    kernel: Covariance,
    tau: F,
) -> RoughnessMatrix {
    gaussian_with_tau_sanitized(roughness, kernel.sanitized(), tau)
}

/// [`gaussian_with_tau`] for a kernel already sanitised (see [`gaussian_sanitized`]).
#[inline]
pub(crate) fn gaussian_with_tau_sanitized<R: Roughness>(
    roughness: R,
    kernel: Covariance,
    tau: F,
) -> RoughnessMatrix {
    let (b11, b12, b22) = plus_kernel(roughness, kernel);
    let tau = if tau.is_finite() && tau > 0.0 {
        tau
    } else {
        // a11, a22 > 0 and det(A + 2K) >= det(A) > 0 for K PSD: without a clamp the result
        // is valid unless the determinant rounded below det(A) (a12 ~ sqrt(a11 a22), an
        // extremely elongated kernel, or underflow; fuzzing): then det(A), its exact lower
        // bound, is the clamp.
        let s = roughness.sqrt_det();
        let floor = s * s;
        if b11 * b22 - b12 * b12 > floor {
            0.0
        } else {
            floor
        }
    };
    RoughnessMatrix::from_entries_clamped(b11, b12, b22, tau)
}

/// The entries of `A + 2 K` for a sanitised kernel `K` (KHPL16 eq. 15 in roughness form).
#[inline(always)]
fn plus_kernel<R: Roughness>(roughness: R, k: Covariance) -> (F, F, F) {
    let (a11, a12, a22) = roughness.to_matrix().entries();
    (a11 + 2.0 * k.s11, a12 + 2.0 * k.s12, a22 + 2.0 * k.s22)
}
