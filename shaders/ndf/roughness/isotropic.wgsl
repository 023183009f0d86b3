#define_import_path filtered_ndf::ndf::roughness::isotropic

#import filtered_ndf::ndf::roughness
#import filtered_ndf::ndf::roughness::matrix

/// Isotropic roughness `alpha`: `A = alpha^2 I`.
struct Isotropic {
    /// The roughness `alpha`.
    alpha: f32,
    /// `1 / alpha^2`.
    inv_alpha_sq: f32,
}

/// The isotropic roughness `alpha`, clamped into `[ALPHA_MIN, ALPHA_MAX]` (the Rust
/// `Isotropic::new_clamped`).
fn from_alpha(alpha: f32) -> Isotropic {
    let a = roughness::clamp_alpha(alpha);
    return Isotropic(a, 1.0 / (a * a));
}

/// `s^T A^-1 s = |s|^2 / alpha^2` (dimensionless). Within 4 ulp.
fn inv_quadratic(r: Isotropic, s: vec2<f32>) -> f32 {
    return dot(s, s) * r.inv_alpha_sq;
}

/// `w^T A w = |alpha w|^2` for a tangent-plane `w` (Smith's projected roughness), `w` scaled
/// first as in the axis-aligned form. Within 4 ulp.
fn quadratic(r: Isotropic, w: vec2<f32>) -> f32 {
    let s = w * r.alpha;
    return dot(s, s);
}

/// `sqrt(det A) = alpha^2`. Within 1 ulp.
fn sqrt_det(r: Isotropic) -> f32 {
    return r.alpha * r.alpha;
}

/// This roughness as a [`matrix::RoughnessMatrix`], `alpha^2 I` (no determinant clamp).
fn to_matrix(r: Isotropic) -> matrix::RoughnessMatrix {
    return matrix::from_eigen(vec2<f32>(1.0, 0.0), vec2<f32>(r.alpha));
}
