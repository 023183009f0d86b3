#define_import_path filtered_ndf::ndf::ggx

#import filtered_ndf::math
#import filtered_ndf::ndf
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix

// GGX (Trowbridge-Reitz) in any roughness form (TK19 supplement section 1; Heitz 2014),
// mirroring `src/.../ndf/ggx.rs`. The first three functions take what a roughness form
// reduces to; the rest are the entry points per form.

/// Slope-domain density `P22(s) = 1 / (pi sqrt(det A) (1 + q)^2)` from
/// `q = s^T A^-1 s` and `sqrt(det A)`. Relative error: `2 (error of 1 + q)` plus 5 ulp.
///
/// Far tail: WGSL drivers may reassociate the product (Mesa's lavapipe squares `1 + q`
/// first), so once `1 + q` exceeds `1e18` (the density is then below `1e-36` of its peak)
/// the square may overflow and the result be 0; below that every association stays in
/// range.
fn p22_of(q: f32, sqrt_det: f32) -> f32 {
    let t = 1.0 + q;
    return select(0.0, 1.0 / (math::PI * sqrt_det * t * t), q >= 0.0);
}

/// Solid-angle density `D(m) = 1 / (pi sqrt(det A) (q_xy + m_z^2)^2)` for a unit micronormal
/// `m`, from `q_xy = m_xy^T A^-1 m_xy`, `m_z` and `sqrt(det A)` (TK19 supplement,
/// non-axis-aligned GGX, in the homogeneous form that stays finite up to the horizon;
/// KHPL16 eq. 2). `0` for `m_z <= 0` (the `chi+` factor) and where the density exceeds the
/// f32 range (as the Rust `d`). Relative error: `2 (error of q_xy + m_z^2)` plus 6 ulp.
/// Far tail as [`p22_of`]: possibly 0 once `q_xy + m_z^2 > 1e18` (below `1e-36` of the
/// peak).
fn d_of(q_xy: f32, m_z: f32, sqrt_det: f32) -> f32 {
    let t = q_xy + m_z * m_z;
    let v = 1.0 / (math::PI * sqrt_det * t * t);
    return select(0.0, v, m_z > 0.0 && v <= math::F32_MAX);
}

/// Smith `Lambda(w) = (sqrt(1 + q / w_z^2) - 1) / 2` from `q = w_xy^T A w_xy` and `|w_z|`
/// (TK19 supplement section 1), evaluated as `q / (2 |w_z| (sqrt(w_z^2 + q) + |w_z|))`
/// without cancellation: relative error within 4 ulp plus that of `q`. `0` for `q <= 0`;
/// `F32_MAX` at `w_z = 0` (the Rust crate returns `+inf`, the correct grazing limit).
/// `Lambda` is homogeneous of degree 0 in `w`: `w` need not be unit, but its squared
/// components must stay inside the f32 range.
fn lambda_of(q: f32, abs_wz: f32) -> f32 {
    if q <= 0.0 && abs_wz >= 0.0 {
        return 0.0;
    }
    // Grazing, or NaN in either (the NaN policy of `ndf`): fully masked.
    if !(abs_wz > 0.0) || !(q > 0.0) {
        return math::F32_MAX;
    }
    let r = sqrt(abs_wz * abs_wz + q);
    return q / (2.0 * abs_wz * (r + abs_wz));
}

/// `P22(s)` of isotropic GGX.
fn p22_isotropic(r: isotropic::Isotropic, s: vec2<f32>) -> f32 {
    return p22_of(isotropic::inv_quadratic(r, s), isotropic::sqrt_det(r));
}

/// `D(m)` of isotropic GGX, `alpha^2 / (pi ((m_x^2 + m_y^2) + alpha^2 m_z^2)^2)` in effect.
fn d_isotropic(r: isotropic::Isotropic, m: vec3<f32>) -> f32 {
    return d_of(isotropic::inv_quadratic(r, m.xy), m.z, isotropic::sqrt_det(r));
}

/// `Lambda(w)` of isotropic GGX.
fn lambda_isotropic(r: isotropic::Isotropic, w: vec3<f32>) -> f32 {
    return lambda_of(isotropic::quadratic(r, w.xy), abs(w.z));
}

/// `G1(w, m)` of isotropic GGX.
fn g1_isotropic(r: isotropic::Isotropic, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_isotropic(r, w), dot(w, m));
}

/// `G2(i, o, m)` of isotropic GGX (height-correlated).
fn g2_isotropic(r: isotropic::Isotropic, i: vec3<f32>, o: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g2_of(lambda_isotropic(r, i), lambda_isotropic(r, o), dot(i, m), dot(o, m));
}

/// `P22(s)` of axis-aligned GGX.
fn p22_axis_aligned(r: axis_aligned::AxisAligned, s: vec2<f32>) -> f32 {
    return p22_of(axis_aligned::inv_quadratic(r, s), axis_aligned::sqrt_det(r));
}

/// `D(m)` of axis-aligned GGX.
fn d_axis_aligned(r: axis_aligned::AxisAligned, m: vec3<f32>) -> f32 {
    return d_of(axis_aligned::inv_quadratic(r, m.xy), m.z, axis_aligned::sqrt_det(r));
}

/// `Lambda(w)` of axis-aligned GGX.
fn lambda_axis_aligned(r: axis_aligned::AxisAligned, w: vec3<f32>) -> f32 {
    return lambda_of(axis_aligned::quadratic(r, w.xy), abs(w.z));
}

/// `G1(w, m)` of axis-aligned GGX.
fn g1_axis_aligned(r: axis_aligned::AxisAligned, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_axis_aligned(r, w), dot(w, m));
}

/// `G2(i, o, m)` of axis-aligned GGX (height-correlated).
fn g2_axis_aligned(
    r: axis_aligned::AxisAligned,
    i: vec3<f32>,
    o: vec3<f32>,
    m: vec3<f32>,
) -> f32 {
    return ndf::g2_of(lambda_axis_aligned(r, i), lambda_axis_aligned(r, o), dot(i, m), dot(o, m));
}

/// `P22(s)` of GGX with a roughness matrix.
fn p22_matrix(r: matrix::RoughnessMatrix, s: vec2<f32>) -> f32 {
    return p22_of(matrix::inv_quadratic(r, s), matrix::sqrt_det(r));
}

/// `D(m)` of GGX with a roughness matrix (a filtered or rotated lobe).
fn d_matrix(r: matrix::RoughnessMatrix, m: vec3<f32>) -> f32 {
    return d_of(matrix::inv_quadratic(r, m.xy), m.z, matrix::sqrt_det(r));
}

/// `Lambda(w)` of GGX with a roughness matrix.
fn lambda_matrix(r: matrix::RoughnessMatrix, w: vec3<f32>) -> f32 {
    return lambda_of(matrix::quadratic(r, w.xy), abs(w.z));
}

/// `G1(w, m)` of GGX with a roughness matrix.
fn g1_matrix(r: matrix::RoughnessMatrix, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_matrix(r, w), dot(w, m));
}

/// `G2(i, o, m)` of GGX with a roughness matrix (height-correlated).
fn g2_matrix(r: matrix::RoughnessMatrix, i: vec3<f32>, o: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g2_of(lambda_matrix(r, i), lambda_matrix(r, o), dot(i, m), dot(o, m));
}
