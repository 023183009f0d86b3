//! Gaussian NDF filtering in roughness-matrix form: the Beckmann convolution (KHPL16 eq.
//! 13-15, TK19 section 2.2), the LEAN nested convolution (KHPL16 section 5.5, eq. 21), the
//! TK19 matrix approximation for GGX, and the projected-space filtering of Tokuyoshi and
//! Kaplanyan 2021 (JCGT 10(2)).
//!
//! Every function returns a [`RoughnessMatrix`], which [`super::Beckmann::new`] and
//! [`super::Ggx::new`] evaluate directly. Kernels are slope-domain covariances `Sigma`
//! (slope^2), e.g. [`super::Footprint::covariance`]; each function first applies
//! [`Covariance::sanitized`], so any kernel (NaN, infinite, indefinite) gives a finite,
//! positive-definite result. Clamps (extent, `kappa`) are applied by the caller or by
//! [`super::clamp::ClampRules::filter_gaussian`].
//!
//! ```
//! use filtered_ndf::f32::{filter, Beckmann, ClampRules, Footprint, Ggx, Isotropic, Ndf};
//! use glam::{Vec2, Vec3};
//!
//! let a = Isotropic::new(0.01).unwrap();
//! // ddx / ddy of the half vector's slope (KHPL16) or of h_xy on the disk (TK19).
//! let fp = Footprint::from_slope_derivatives(Vec2::new(0.02, 0.0), Vec2::new(0.0, 0.005));
//! let sigma = fp.covariance(0.5); // SIGMA_PIXEL
//! let beckmann = Beckmann::new(filter::gaussian(a, sigma)); // exact (KHPL16 eq. 15)
//! let ggx = Ggx::new(filter::projected(a, sigma)); // TK21 projected space
//! let clamped = ClampRules::default().filter_gaussian(a, fp, 0.5); // lambda, kappa, tau
//! let h = Vec3::new(0.005, 0.0, 1.0).normalize();
//! assert!(beckmann.d(h) < Beckmann::new(a).d(Vec3::Z));
//! assert!(ggx.d(h).is_finite() && Ggx::new(clamped).d(h).is_finite());
//! ```

use super::footprint::Covariance;
use super::roughness::{Roughness, RoughnessMatrix};
use super::{F, Vec2};

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

/// The largest eigenvalue of `A` that [`projected`] maps to projected space: `0.99`
/// (`alpha <= 0.995`). The map `P = A (I - A)^-1` needs every eigenvalue of `A` below 1.
pub const PROJECTED_EIGEN_MAX: F = 0.99;

/// Projected-space filtering (Tokuyoshi and Kaplanyan 2021, JCGT 10(2), Listing 1):
/// `P = A (I - A)^-1`, `P' = P + 2 Sigma`, `A' = P' (I + P')^-1`.
///
/// **Why.** On the projected disk `p = h_xy` the GGX density is itself a GGX-shaped slope
/// density: with `P^-1 = A^-1 - I`,
/// `D(h) = 1 / (pi sqrt(det A) (1 + p^T P^-1 p)^2) = P22_P(p) / sqrt(det(I - A))`
/// for `|p| < 1` (tested in `tests/filter_projected.rs`). The kernel of TK19 section 3.2 is
/// built from disk derivatives, so it lives in the same space as `P`, and it is added there.
/// **The factor 2** is the same as in the slope domain: the lobe is treated as a Gaussian
/// whose covariance is half its roughness matrix (KHPL16 eq. 14), so a kernel of covariance
/// `Sigma` adds `2 Sigma` to `P` (TK21 Listing 1: `kernelRoughnessMat = 2 SIGMA2 delta^T
/// delta`; TK21 uses `SIGMA2 = 1 / (2 pi)`, which is the caller's `sigma^2` here).
///
/// **Computation.** For 2x2 matrices, by Cayley-Hamilton,
/// `P = (A - det(A) I) / det(I - A)` with `a11 - det A = a11 (1 - a22) + a12^2` (a sum of
/// positive terms) and `A' = (P' + d I) / (1 + tr(P') + d)`, `d = max(det P', det P)` (TK21's
/// `detMin`), every term positive: `A'` is symmetric positive definite by construction. The
/// result is evaluated with `tau = det(A)` (filtering only grows the determinant).
///
/// **Roughness limit.** `I - A` is invertible with `P` positive definite iff both
/// eigenvalues of `A` are `< 1` (`alpha < 1`). Eigenvalues above [`PROJECTED_EIGEN_MAX`]
/// are clamped to it for the projected-space step and the excess is added back unfiltered:
/// `A' = proj(A_c) + (A - A_c)`. This is exact below the limit, continuous across it, and
/// never sharpens (`A' >= A`, as `P -> P (I + P)^-1` is operator monotone); lobes that rough
/// need no filtering (TK19 section 3.2).
#[inline]
pub fn projected<R: Roughness>(roughness: R, kernel: Covariance) -> RoughnessMatrix {
    let k = kernel.sanitized();
    let (a11, a12, a22) = roughness.to_matrix().entries();
    let tau = {
        let s = roughness.sqrt_det();
        s * s
    };
    let a = Covariance::new(a11, a12, a22);
    let ac = a.clamp_eigenvalues(PROJECTED_EIGEN_MAX);
    let excess = Covariance::new(a11 - ac.s11, a12 - ac.s12, a22 - ac.s22);
    let (c11, c12, c22) = (ac.s11, ac.s12, ac.s22);
    // P = (A - det(A) I) / det(I - A).
    let det_ima = ((1.0 - c11) * (1.0 - c22) - c12 * c12).max(F::MIN_POSITIVE);
    let p = Covariance::new(
        (c11 * (1.0 - c22) + c12 * c12) / det_ima,
        c12 / det_ima,
        (c22 * (1.0 - c11) + c12 * c12) / det_ima,
    );
    let det_p = (p.s11 * p.s22 - p.s12 * p.s12).max(0.0);
    let q = p + k * 2.0;
    // det(P + 2K) = det P + 2 tr(adj(P) K) + 4 det K, every term >= 0 for P, K PSD: unlike
    // q11 q22 - q12^2 it does not cancel when a huge, nearly rank-one K meets a tiny P (which
    // sharpened the minor axis by 60x in f32 for alpha = 1e-8, found by fuzzing).
    let det_k = (k.s11 * k.s22 - k.s12 * k.s12).max(0.0);
    let cross = (p.s11 * k.s22 + p.s22 * k.s11 - 2.0 * p.s12 * k.s12).max(0.0);
    let d = (det_p + 2.0 * cross + 4.0 * det_k).max(det_p);
    let den = 1.0 + q.s11 + q.s22 + d;
    // Each part is finite: q's entries are bounded by P (<= 1 / (1 - 0.99)^2 scale) plus the
    // sanitized kernel (<= ALPHA_MAX^2).
    let b11 = (q.s11 + d) / den;
    let b12 = q.s12 / den;
    let b22 = (q.s22 + d) / den;
    // Never below A on the diagonal (exact, by monotonicity): rounding in the excess split
    // otherwise takes a tiny (e.g. subnormal, accepted with a large `tau`) `a11` to `<= 0`.
    let (r11, r12, r22) = (
        (b11 + excess.s11).max(a11),
        b12 + excess.s12,
        (b22 + excess.s22).max(a22),
    );
    let floor = if r11 * r22 - r12 * r12 > 0.0 {
        tau
    } else {
        tau.max(F::MIN_POSITIVE)
    };
    RoughnessMatrix::from_entries_clamped(r11, r12, r22, floor)
}
