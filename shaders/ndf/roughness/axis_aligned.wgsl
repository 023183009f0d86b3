#define_import_path filtered_ndf::ndf::roughness::axis_aligned

#import filtered_ndf::ndf::roughness
#import filtered_ndf::ndf::roughness::matrix

/// Axis-aligned anisotropic roughness `(alpha_x, alpha_y)` along the tangent and bitangent:
/// `A = diag(alpha_x^2, alpha_y^2)`.
struct AxisAligned {
    /// `(alpha_x, alpha_y)`.
    alpha: vec2<f32>,
    /// `(1 / alpha_x^2, 1 / alpha_y^2)`.
    inv_alpha_sq: vec2<f32>,
}

/// `(alpha_x, alpha_y)`, each clamped into `[ALPHA_MIN, ALPHA_MAX]` (the Rust
/// `AxisAligned::new_clamped`).
fn from_alpha(alpha: vec2<f32>) -> AxisAligned {
    let a = vec2<f32>(roughness::clamp_alpha(alpha.x), roughness::clamp_alpha(alpha.y));
    return AxisAligned(a, 1.0 / (a * a));
}

/// `s^T A^-1 s = s_x^2 / alpha_x^2 + s_y^2 / alpha_y^2`. Within 5 ulp (a sum of two
/// non-negative terms).
fn inv_quadratic(r: AxisAligned, s: vec2<f32>) -> f32 {
    return dot(s * s, r.inv_alpha_sq);
}

/// `w^T A w = (alpha_x w_x)^2 + (alpha_y w_y)^2`, `w` scaled first (no subnormal square of a
/// tiny `w_i` beside a large `alpha_i`). Within 4 ulp.
fn quadratic(r: AxisAligned, w: vec2<f32>) -> f32 {
    let s = w * r.alpha;
    return dot(s, s);
}

/// `sqrt(det A) = alpha_x alpha_y`. Within 1 ulp.
fn sqrt_det(r: AxisAligned) -> f32 {
    return r.alpha.x * r.alpha.y;
}

/// This roughness as a [`matrix::RoughnessMatrix`], `diag(alpha_x^2, alpha_y^2)` (no
/// determinant clamp).
fn to_matrix(r: AxisAligned) -> matrix::RoughnessMatrix {
    return matrix::from_eigen(vec2<f32>(1.0, 0.0), r.alpha);
}
