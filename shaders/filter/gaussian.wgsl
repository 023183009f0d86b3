#define_import_path filtered_ndf::filter::gaussian

#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::kernel::covariance

// Gaussian NDF filtering in roughness-matrix form (KHPL16 eq. 13-15, TK19 section 2.2),
// mirroring `src/.../filter/gaussian.rs`. A roughness form converts with its `to_matrix`.

/// The entries of `A + 2 K` and `det(A + 2 K) = det A + 2 tr(adj(A) K) + 4 det K`, every term
/// non-negative for `A` positive definite and `K` PSD, so that the filtered minor axis keeps
/// its relative accuracy (f32 would cancel in `b11 b22 - b12^2`): with `A = R diag(l) R^T`,
/// `tr(adj(A) K) = l2 e1^T K e1 + l1 e2^T K e2`, and `det K` as the kernel carries it.
/// Evaluated with the determinant clamp `tau`.
fn plus_kernel(a: matrix::RoughnessMatrix, k: covariance::Covariance, tau: f32) -> matrix::RoughnessMatrix {
    let e = matrix::entries(a);
    let c = a.axis.x;
    let s = a.axis.y;
    let k1 = max(c * c * k.s_xx + 2.0 * c * s * k.s_xy + s * s * k.s_yy, 0.0);
    let k2 = max(s * s * k.s_xx - 2.0 * c * s * k.s_xy + c * c * k.s_yy, 0.0);
    let det = matrix::determinant(a) + 2.0 * (a.eig.y * k1 + a.eig.x * k2) + 4.0 * max(k.det, 0.0);
    return matrix::from_entries_det(
        e.x + 2.0 * k.s_xx,
        e.y + 2.0 * k.s_xy,
        e.z + 2.0 * k.s_yy,
        det,
        tau,
    );
}

/// `A' = A + 2 Sigma` with the determinant clamp `tau = det A` (TK19 supplement), for a
/// kernel that `covariance::sanitized` (or a clamp after it) has made PSD and bounded.
fn gaussian_sanitized(a: matrix::RoughnessMatrix, k: covariance::Covariance) -> matrix::RoughnessMatrix {
    return plus_kernel(a, k, a.sqrt_det * a.sqrt_det);
}

/// `A' = A + 2 Sigma`, evaluated with `tau = det(A)` (TK19 supplement; no bias in exact
/// arithmetic since `det(A + 2 Sigma) >= det A`). Beckmann: exact (KHPL16 eq. 15, covariances
/// of Gaussians add with `A = 2 B`). GGX: the TK19 section 2.2 / KHPL16 approximation. The
/// kernel is `covariance::sanitized` first. Accuracy: the filtered matrix is evaluated in its
/// eigenbasis with `det` from non-negative terms (`matrix.wgsl`: `s^T A'^-1 s` within
/// `eps (10 + 16 sqrt(cond A'))`, the extra `8 sqrt(cond)` for the rounding of the kernel's
/// entries).
fn gaussian(a: matrix::RoughnessMatrix, kernel: covariance::Covariance) -> matrix::RoughnessMatrix {
    return gaussian_sanitized(a, covariance::sanitized(kernel));
}

/// [`gaussian`] with an explicit determinant clamp `tau` (`<= 0`: none; a filtered
/// determinant that rounds to `<= det A` then gets `det A`, its exact lower bound).
fn gaussian_with_tau(
    a: matrix::RoughnessMatrix,
    kernel: covariance::Covariance,
    tau: f32,
) -> matrix::RoughnessMatrix {
    return gaussian_with_tau_sanitized(a, covariance::sanitized(kernel), tau);
}

/// [`gaussian_with_tau`] for a sanitised kernel.
fn gaussian_with_tau_sanitized(
    a: matrix::RoughnessMatrix,
    k: covariance::Covariance,
    tau: f32,
) -> matrix::RoughnessMatrix {
    let floor = matrix::determinant(a);
    return plus_kernel(a, k, select(floor, tau, tau > 0.0));
}
