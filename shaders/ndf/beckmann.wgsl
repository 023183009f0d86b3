#define_import_path filtered_ndf::ndf::beckmann

#import filtered_ndf::math
#import filtered_ndf::ndf
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix

// Beckmann in any roughness form (Beckmann and Spizzichino 1963; Heitz 2014 section 5.4;
// KHPL16 eq. 14: `A = 2 B` with `B` the slope covariance), mirroring
// `src/.../ndf/beckmann.rs`. The first three functions take what a roughness form reduces
// to; the rest are the entry points per form.
//
// Accuracy: `exp(-x)` amplifies the relative error of its argument `x` by `x` (a property
// of the function, not of the evaluation), and WGSL allows the driver's `exp` `3 + 2|x|`
// ulp, the same order: the densities are within `eps (8 + 4 x)` plus the error of `x`
// itself (`x` ulp more per ulp of `q`), and results below `2^-126` may flush to 0.

/// `exp(x < EXP_SPLIT)` keeps `exp(-x)` a normal f32; beyond it the normalisation moves
/// into the exponent.
const EXP_SPLIT: f32 = 80.0;

/// `sqrt(pi)`.
const SQRT_PI: f32 = 1.77245385090552;

/// `exp(-x) k` for `x >= 0`, `k = exp(ln_k)`: past `EXP_SPLIT` as `exp(ln_k - x)`, so that a
/// density that is a normal f32 is not lost to an intermediate `exp(-x)` that is not (the
/// Rust `exp_neg_times`).
fn exp_neg_times(x: f32, k: f32, ln_k: f32) -> f32 {
    return select(exp(-x) * k, exp(ln_k - x), x > EXP_SPLIT);
}

/// Slope-domain density `P22(s) = exp(-q) / (pi sqrt(det A))` from `q = s^T A^-1 s` and
/// `sqrt(det A)`. `0` where the density underflows.
fn p22_of(q: f32, sqrt_det: f32) -> f32 {
    let den = math::PI * sqrt_det;
    return select(0.0, exp_neg_times(q, 1.0 / den, -log(den)), q >= 0.0);
}

/// Solid-angle density `D(m) = exp(-q_xy / m_z^2) / (pi sqrt(det A) m_z^4)` for a unit
/// micronormal `m` from `q_xy = m_xy^T A^-1 m_xy`, `m_z` and `sqrt(det A)` (KHPL16 eq. 2
/// with eq. 14). `0` for `m_z <= 0`, where the density underflows, and where it exceeds the
/// f32 range.
fn d_of(q_xy: f32, m_z: f32, sqrt_det: f32) -> f32 {
    let z2 = m_z * m_z;
    let x = q_xy / z2;
    let k = 1.0 / (math::PI * sqrt_det * z2 * z2);
    let ln_k = -(log(math::PI * sqrt_det) + 4.0 * log(max(m_z, math::F32_MIN_POSITIVE)));
    let v = exp_neg_times(x, k, ln_k);
    return select(0.0, v, m_z > 0.0 && v <= math::F32_MAX);
}

/// Smith `Lambda(w) = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2` with
/// `a = |w_z| / sqrt(q)`, `q = w_xy^T A w_xy` (Heitz 2014 eq. 80 with the projected
/// roughness of a matrix lobe).
///
/// The two terms cancel (to a relative `1 / (2 a^2)` for large `a`); the Rust crate takes
/// them in f64. Here, with `sqrt(pi) erfcx(a) = 1 / (a + K(a))`,
/// `Lambda = exp(-a^2) K / (2 sqrt(pi) a (a + K))`, a product of positive factors for every
/// `a > 0`, and `K(a) (2a + 1)` is a degree-14 polynomial in `t = (a - 3) / (a + 3)` (all of
/// `a >= 0` maps to `t` in `[-1, 1)`; fitted at Chebyshev nodes, approximation error
/// `4.4e-8` relative with the coefficients rounded to f32). The result is within
/// `eps (32 + 16 a^2)`: `Lambda` amplifies the error of `a` (6 ulp) by `2 a^2 + 3`, and `exp`
/// adds its `3 + 2 a^2` ulp. `0` for `q <= 0` and for `a > 9.5` (below the f32 range);
/// `F32_MAX` at `w_z = 0` (the Rust `+inf`).
fn lambda_of(q: f32, abs_wz: f32) -> f32 {
    if q <= 0.0 && abs_wz >= 0.0 {
        return 0.0;
    }
    // Grazing, or NaN in either (the NaN policy of `ndf`): fully masked.
    if !(abs_wz > 0.0) || !(q > 0.0) {
        return math::F32_MAX;
    }
    let a = abs_wz / sqrt(q);
    if a > 9.5 {
        return 0.0;
    }
    let t = (a - 3.0) / (a + 3.0);
    var p = -3.849171844194643e-05;
    p = p * t + 0.00028491427656263113;
    p = p * t + 1.8268152416567318e-05;
    p = p * t - 0.0018242653459310532;
    p = p * t + 0.0013654069043695927;
    p = p * t + 0.005581194534897804;
    p = p * t - 0.009357542730867863;
    p = p * t - 0.007657155394554138;
    p = p * t + 0.036274611949920654;
    p = p * t - 0.0232936330139637;
    p = p * t - 0.07646358013153076;
    p = p * t + 0.21173490583896637;
    p = p * t - 0.23284178972244263;
    p = p * t + 0.033079251646995544;
    p = p * t + 1.0631378889083862;
    let k = p / (2.0 * a + 1.0);
    return min(exp(-a * a) * k / (2.0 * SQRT_PI * a * (a + k)), math::F32_MAX);
}

/// `P22(s)` of isotropic Beckmann.
fn p22_isotropic(r: isotropic::Isotropic, s: vec2<f32>) -> f32 {
    return p22_of(isotropic::inv_quadratic(r, s), isotropic::sqrt_det(r));
}

/// `D(m)` of isotropic Beckmann.
fn d_isotropic(r: isotropic::Isotropic, m: vec3<f32>) -> f32 {
    return d_of(isotropic::inv_quadratic(r, m.xy), m.z, isotropic::sqrt_det(r));
}

/// `Lambda(w)` of isotropic Beckmann.
fn lambda_isotropic(r: isotropic::Isotropic, w: vec3<f32>) -> f32 {
    return lambda_of(isotropic::quadratic(r, w.xy), abs(w.z));
}

/// `G1(w, m)` of isotropic Beckmann.
fn g1_isotropic(r: isotropic::Isotropic, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_isotropic(r, w), dot(w, m));
}

/// `G2(i, o, m)` of isotropic Beckmann (height-correlated).
fn g2_isotropic(r: isotropic::Isotropic, i: vec3<f32>, o: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g2_of(lambda_isotropic(r, i), lambda_isotropic(r, o), dot(i, m), dot(o, m));
}

/// `P22(s)` of axis-aligned Beckmann.
fn p22_axis_aligned(r: axis_aligned::AxisAligned, s: vec2<f32>) -> f32 {
    return p22_of(axis_aligned::inv_quadratic(r, s), axis_aligned::sqrt_det(r));
}

/// `D(m)` of axis-aligned Beckmann.
fn d_axis_aligned(r: axis_aligned::AxisAligned, m: vec3<f32>) -> f32 {
    return d_of(axis_aligned::inv_quadratic(r, m.xy), m.z, axis_aligned::sqrt_det(r));
}

/// `Lambda(w)` of axis-aligned Beckmann.
fn lambda_axis_aligned(r: axis_aligned::AxisAligned, w: vec3<f32>) -> f32 {
    return lambda_of(axis_aligned::quadratic(r, w.xy), abs(w.z));
}

/// `G1(w, m)` of axis-aligned Beckmann.
fn g1_axis_aligned(r: axis_aligned::AxisAligned, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_axis_aligned(r, w), dot(w, m));
}

/// `G2(i, o, m)` of axis-aligned Beckmann (height-correlated).
fn g2_axis_aligned(
    r: axis_aligned::AxisAligned,
    i: vec3<f32>,
    o: vec3<f32>,
    m: vec3<f32>,
) -> f32 {
    return ndf::g2_of(lambda_axis_aligned(r, i), lambda_axis_aligned(r, o), dot(i, m), dot(o, m));
}

/// `P22(s)` of Beckmann with a roughness matrix.
fn p22_matrix(r: matrix::RoughnessMatrix, s: vec2<f32>) -> f32 {
    return p22_of(matrix::inv_quadratic(r, s), matrix::sqrt_det(r));
}

/// `D(m)` of Beckmann with a roughness matrix (a filtered or rotated lobe).
fn d_matrix(r: matrix::RoughnessMatrix, m: vec3<f32>) -> f32 {
    return d_of(matrix::inv_quadratic(r, m.xy), m.z, matrix::sqrt_det(r));
}

/// `Lambda(w)` of Beckmann with a roughness matrix.
fn lambda_matrix(r: matrix::RoughnessMatrix, w: vec3<f32>) -> f32 {
    return lambda_of(matrix::quadratic(r, w.xy), abs(w.z));
}

/// `G1(w, m)` of Beckmann with a roughness matrix.
fn g1_matrix(r: matrix::RoughnessMatrix, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_matrix(r, w), dot(w, m));
}

/// `G2(i, o, m)` of Beckmann with a roughness matrix (height-correlated).
fn g2_matrix(r: matrix::RoughnessMatrix, i: vec3<f32>, o: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g2_of(lambda_matrix(r, i), lambda_matrix(r, o), dot(i, m), dot(o, m));
}
