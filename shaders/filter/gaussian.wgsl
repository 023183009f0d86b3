#define_import_path filtered_ndf::filter::gaussian

#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::clamp

// Gaussian NDF filtering in roughness-matrix form (KHPL16 eq. 13-15, TK19 section 2.2),
// mirroring `src/.../filter/gaussian.rs`. A roughness form converts with its `to_matrix`.
//
// The determinant clamp: the result is evaluated as the one clamped matrix `A'_c` of
// `matrix.wgsl` (`A' + t I` where `det A' < tau`). In exact arithmetic
// `det(A + 2 Sigma) >= det A`, and here the filtered determinant is a sum of non-negative
// terms that contains `det A` itself, so with `tau = det A_c` of an unclamped material the
// clamp is inactive (equality for a zero kernel); it acts for a material that is itself
// clamped (`tau = det A_c > det A`) and for an explicit `tau` above the filtered determinant.

/// `A + 2 K` for a sanitised kernel `K`, with its determinant
/// `det(A + 2 K) = det A + 2 tr(adj(A) K) + 4 det K`, every term non-negative for `A` positive
/// definite and `K` PSD, so that the filtered minor axis keeps its relative accuracy (f32
/// would cancel in `b11 b22 - b12^2`): with `A = R diag(l) R^T`,
/// `tr(adj(A) K) = l2 e1^T K e1 + l1 e2^T K e2`, and `det K` as the kernel carries it.
/// Evaluated with the determinant clamp `tau` (`<= 0`: none). `A` is the material's matrix as
/// given ([`matrix::entries`]; a clamped material is filtered as `A + 2 K` with its own `tau`,
/// as in Rust).
fn gaussian_sanitized(a: matrix::RoughnessMatrix, k: covariance::Covariance, tau: f32) -> matrix::RoughnessMatrix {
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
        max(tau, 0.0),
    );
}

/// `A' = A + 2 Sigma`, evaluated with the determinant clamp `tau = det A_c` of the material
/// (TK19 supplement; no bias in exact arithmetic since `det(A + 2 Sigma) >= det A`). Beckmann:
/// exact (KHPL16 eq. 15, covariances of Gaussians add with `A = 2 B`). GGX: the TK19 section
/// 2.2 / KHPL16 approximation. The kernel is `covariance::sanitized` first. Accuracy: the
/// filtered matrix is evaluated in its eigenbasis with `det` from non-negative terms
/// (`matrix.wgsl`: `s^T A'^-1 s` within `eps (10 + 16 sqrt(cond A'))`, the extra
/// `8 sqrt(cond)` for the rounding of the kernel's entries).
fn gaussian(a: matrix::RoughnessMatrix, kernel: covariance::Covariance) -> matrix::RoughnessMatrix {
    return gaussian_sanitized(a, covariance::sanitized(kernel), matrix::clamped_det(a));
}

/// [`gaussian`] with an explicit determinant clamp `tau = det_clamp` (`<= 0`: none; the
/// filtered determinant here is never below `det A`, so no fallback is needed), at least the
/// material's own clamp ([`matrix::own_det_clamp`]): the Rust `gaussian_with_det_clamp`.
fn gaussian_with_det_clamp(
    a: matrix::RoughnessMatrix,
    kernel: covariance::Covariance,
    det_clamp: f32,
) -> matrix::RoughnessMatrix {
    return gaussian_sanitized(a, covariance::sanitized(kernel), max(det_clamp, matrix::own_det_clamp(a)));
}

/// The whole Gaussian pipeline: `clamp::footprint` -> `covariance::from_footprint` (`sigma` pixels)
/// -> `clamp::kernel` -> `A' = A + 2 Sigma` with `tau = det A_c` if `det_clamp` (the TK19 matrix
/// filter; exact for Beckmann). The result is the one clamped matrix of `matrix.wgsl`. The
/// Rust `ClampRules::filter_gaussian`: the rules are the kernel stage's data, applied here.
fn filter_gaussian(
    rules: clamp::ClampRules,
    a: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    sigma: f32,
) -> matrix::RoughnessMatrix {
    return gaussian_sanitized(a, clamp::pixel_kernel(rules, fp, sigma), clamp::det_clamp_for(rules, a));
}

/// `A' = A + 2 Sigma` with the clamped Gaussian pixel kernel (KHPL16 eq. 13-15; TK19 section
/// 2.2): exact for Beckmann, TK19's approximation for GGX.
struct Gaussian {
    /// The clamp rules applied to the footprint, the kernel and the filtered matrix.
    clamps: clamp::ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    sigma: f32,
}

/// TK19: the default rules (`lambda = 1`, `kappa = 0.18`, the determinant clamp), `sigma = 0.5`.
const TK19_GAUSSIAN: Gaussian = Gaussian(clamp::DEFAULT_RULES, pixel::SIGMA_PIXEL);
/// KHPL16's parallelogram kernel: `lambda = 1` and the determinant clamp, no `kappa`.
const KHPL16_GAUSSIAN: Gaussian = Gaussian(clamp::KHPL16_RULES, pixel::SIGMA_PIXEL);

/// The lobe of `material` filtered by `method` over `fp` (the Rust `Gaussian::lobe`): the
/// filtered roughness matrix, for `ggx::*_matrix` or `beckmann::*_matrix`.
fn gaussian_lobe(method: Gaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint) -> matrix::RoughnessMatrix {
    return filter_gaussian(method.clamps, material, fp, method.sigma);
}

/// `D(m)` of the GGX lobe of [`gaussian_lobe`].
fn d_ggx_gaussian(method: Gaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return ggx::d_matrix(gaussian_lobe(method, material, fp), m);
}

/// `D(m)` of the Beckmann lobe of [`gaussian_lobe`] (the exact Gaussian filter of Beckmann).
fn d_beckmann_gaussian(method: Gaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return beckmann::d_matrix(gaussian_lobe(method, material, fp), m);
}
