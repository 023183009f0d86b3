#define_import_path filtered_ndf::filter::lean

#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::kernel::covariance as cov
#import filtered_ndf::filter::gaussian

// LEAN mapping's moments and the nested convolution of KHPL16 section 5.5, eq. 21,
// mirroring `src/.../filter/lean.rs`.

/// First and second moments of normal-map slopes (Olano and Baker 2010), linearly
/// filterable: `mean = E[s]`, `second = (E[s_x^2], E[s_x s_y], E[s_y^2])`.
struct LeanMoments {
    /// `(E[s_x], E[s_y])`.
    mean: vec2<f32>,
    /// `(E[s_x^2], E[s_x s_y], E[s_y^2])`.
    second: vec3<f32>,
}

/// The covariance of the normal-map slopes, `E[s s^T] - E[s] E[s]^T` (LEAN eq. 5; KHPL16's
/// `K_L`), `cov::sanitized` (mip filtering can make it slightly indefinite). Its
/// determinant is formed from the differences (cancelling for elongated moments).
fn covariance(m: LeanMoments) -> cov::Covariance {
    let c = cov::from_entries(
        m.second.x - m.mean.x * m.mean.x,
        m.second.y - m.mean.x * m.mean.y,
        m.second.z - m.mean.y * m.mean.y,
    );
    return cov::sanitized(c);
}

/// `K_L * K_P * D = (K_L * K_P) * D` (KHPL16 eq. 21): the covariances add and the sum is
/// filtered by `gaussian::gaussian` (`A' = A + 2 (Sigma_L + Sigma_P)`, `tau = det A`).
fn lean(
    a: matrix::RoughnessMatrix,
    pixel: cov::Covariance,
    moments: LeanMoments,
) -> matrix::RoughnessMatrix {
    return gaussian::gaussian(a, cov::add(cov::sanitized(pixel), covariance(moments)));
}
