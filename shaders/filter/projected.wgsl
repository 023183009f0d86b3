#define_import_path filtered_ndf::filter::projected

#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::ndf::ggx
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::clamp

// Projected-space filtering (Tokuyoshi and Kaplanyan 2021, JCGT 10(2), Listing 1),
// mirroring `src/.../filter/projected.rs`.

/// The largest eigenvalue of `A` mapped to projected space, `0.99` (`alpha <= 0.995`).
const PROJECTED_EIGEN_MAX: f32 = 0.99;

/// `P = A (I - A)^-1`, `P' = P + 2 Sigma`, `A' = P' (I + P')^-1` (TK21 Listing 1): on the
/// projected disk the GGX density is itself a GGX-shaped density of roughness `P`, and TK19's
/// disk-derivative kernel lives in that space. Eigenvalues of `A` above `PROJECTED_EIGEN_MAX`
/// are clamped for the projected step and the excess is added back unfiltered (as in Rust:
/// exact below the limit, continuous, never sharpening). Evaluated with the determinant clamp
/// `tau = det A_c` of the material (the result is the one clamped matrix of `matrix.wgsl`).
///
/// f32 form: in `A`'s eigenbasis `P = R diag(l / (1 - l)) R^T` exactly (no cancellation);
/// `d = det P' = det P + 2 tr(adj(P) K) + 4 det K` as non-negative terms (TK21's `detMin`);
/// `A' = (P' + d I) / (1 + tr P' + d)`, every term positive, with `det A' = d / (1 + tr P' + d)`
/// exactly (so the filtered minor axis keeps its relative accuracy). The kernel is
/// `covariance::sanitized` first.
fn projected(a: matrix::RoughnessMatrix, kernel: covariance::Covariance) -> matrix::RoughnessMatrix {
    return projected_sanitized(a, covariance::sanitized(kernel), matrix::clamped_det(a));
}

/// [`projected`] with an explicit determinant clamp `tau = det_clamp` (`<= 0`: none), at
/// least the material's own clamp ([`matrix::own_det_clamp`]; the Rust
/// `projected_with_det_clamp`).
fn projected_with_det_clamp(
    a: matrix::RoughnessMatrix,
    kernel: covariance::Covariance,
    det_clamp: f32,
) -> matrix::RoughnessMatrix {
    return projected_sanitized(a, covariance::sanitized(kernel), max(det_clamp, matrix::own_det_clamp(a)));
}

/// [`projected`] for a sanitised kernel `k`, with the clamp `tau` (`<= 0`: none). `A` is the
/// material's matrix as given (a clamped material is filtered with its own `tau`, as in Rust).
fn projected_sanitized(
    a: matrix::RoughnessMatrix,
    k: covariance::Covariance,
    tau: f32,
) -> matrix::RoughnessMatrix {
    let lc = min(a.eig, vec2<f32>(PROJECTED_EIGEN_MAX));
    let excess = a.eig - lc;
    let p = lc / (1.0 - lc);
    let c = a.axis.x;
    let s = a.axis.y;
    // P in the tangent frame, and e_i^T K e_i.
    let p11 = p.x * c * c + p.y * s * s;
    let p12 = (p.x - p.y) * c * s;
    let p22 = p.x * s * s + p.y * c * c;
    let k1 = max(c * c * k.s_xx + 2.0 * c * s * k.s_xy + s * s * k.s_yy, 0.0);
    let k2 = max(s * s * k.s_xx - 2.0 * c * s * k.s_xy + c * c * k.s_yy, 0.0);
    let d = p.x * p.y + 2.0 * (p.y * k1 + p.x * k2) + 4.0 * max(k.det, 0.0);
    let q11 = p11 + 2.0 * k.s_xx;
    let q12 = p12 + 2.0 * k.s_xy;
    let q22 = p22 + 2.0 * k.s_yy;
    let den = 1.0 + q11 + q22 + d;
    var b11 = (q11 + d) / den;
    var b12 = q12 / den;
    var b22 = (q22 + d) / den;
    var det = d / den;
    if max(excess.x, excess.y) > 0.0 {
        // A rough lobe (alpha > 0.995): add the excess back; its determinant from the entries
        // (well conditioned there).
        b11 += excess.x * c * c + excess.y * s * s;
        b12 += (excess.x - excess.y) * c * s;
        b22 += excess.x * s * s + excess.y * c * c;
        det = b11 * b22 - b12 * b12;
    }
    // Never below A on the diagonal (exact, by monotonicity), as in Rust.
    let e = matrix::entries(a);
    return matrix::from_entries_det(max(b11, e.x), b12, max(b22, e.z), det, max(tau, 0.0));
}

/// The projected-space pipeline (TK21), the rules as in `gaussian::filter_gaussian`: `clamp::footprint`
/// -> `covariance::from_footprint` (`sigma` pixels; the footprint of the half vector's projected-disk
/// derivatives, TK19 section 3.2) -> `clamp::kernel` -> [`projected_sanitized`] with
/// `tau = det A_c` if `det_clamp` (the Rust `ClampRules::filter_projected`).
fn filter_projected(
    rules: clamp::ClampRules,
    a: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    sigma: f32,
) -> matrix::RoughnessMatrix {
    return projected_sanitized(a, clamp::pixel_kernel(rules, fp, sigma), clamp::det_clamp_for(rules, a));
}

/// Projected-space filtering of GGX (Tokuyoshi and Kaplanyan 2021), the kernel of the
/// footprint after the clamp rules.
struct Projected {
    /// The clamp rules applied to the footprint, the kernel and the filtered matrix.
    clamps: clamp::ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    sigma: f32,
}

/// TK21: the default rules, `sigma = 0.5`.
const TK21_PROJECTED: Projected = Projected(clamp::DEFAULT_RULES, pixel::SIGMA_PIXEL);

/// The GGX lobe of projected-space filtering (the Rust `Projected::lobe`), for `ggx::*_matrix`.
fn projected_lobe(method: Projected, material: matrix::RoughnessMatrix, fp: pixel::Footprint) -> matrix::RoughnessMatrix {
    return filter_projected(method.clamps, material, fp, method.sigma);
}

/// `D(m)` of [`projected_lobe`].
fn d_ggx_projected(method: Projected, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return ggx::d_matrix(projected_lobe(method, material, fp), m);
}
