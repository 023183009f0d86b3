//! Projected-space filtering (Tokuyoshi and Kaplanyan 2021, JCGT 10(2)).

use super::super::kernel::Covariance;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::F;

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
