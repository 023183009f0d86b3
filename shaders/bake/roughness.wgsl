#define_import_path filtered_ndf::bake::roughness

#import filtered_ndf::math
#import filtered_ndf::ndf::roughness
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::roughness::matrix

// A baked roughness chain (`src/bake/fit.rs`: the GGX or Beckmann lobe closest to each mip
// texel's distribution of normals) read back as the lobe, mirroring `src/bake/decode.rs`.
// Fetch the texel with the hardware's filtering as any material texture; each function takes
// the fetched value(s) in the encoding the chain was stored in:
//
// | stored | function | lobe |
// |---|---|---|
// | `alpha` (`r16float`) | `isotropic::from_alpha` | `Isotropic` |
// | glTF perceptual roughness `r = sqrt(alpha)` (metallic-roughness G channel) | `from_perceptual` | `Isotropic` |
// | `[alpha_x, alpha_y, angle]` (`fit::AnisotropicAlpha`) | `from_anisotropic` | `RoughnessMatrix` |
// | `KHR_materials_anisotropy`: roughness `r` and the anisotropy texel | `from_khr_anisotropy` | `RoughnessMatrix` |
// | the roughness matrix `(A11, A12, A22, 1)` (`rgba16float`) | `from_matrix_texel` | `RoughnessMatrix` |
//
// Filtering the stored values is the engines' convention (a mip of perceptual roughness is
// not the perceptual roughness of the mip); the chain's fits are per texel, so fetch at texel
// centres of the level for the exact fit.

/// glTF's perceptual roughness `r` as the isotropic lobe `alpha = r^2` (the Rust
/// `bake::decode::alpha_from_perceptual`), clamped as `isotropic::from_alpha`.
fn from_perceptual(r: f32) -> isotropic::Isotropic {
    return isotropic::from_alpha(r * r);
}

/// The anisotropic lobe `[alpha_x, alpha_y, angle]` (`alpha_x` along the direction at `angle`
/// radians from `+x` towards `+y`) as the matrix `A = R diag(alpha_x^2, alpha_y^2) R^T` (the
/// Rust `AnisotropicAlpha::matrix`); the angle's cosine and sine by `math::sincos_turns`
/// (the driver's `cos`, `sin` may err by `2^-11`), the alphas clamped into
/// `[ALPHA_MIN, ALPHA_MAX]`.
fn from_anisotropic(lobe: vec3<f32>) -> matrix::RoughnessMatrix {
    let axis = math::sincos_turns(lobe.z * (0.5 * math::INV_PI));
    let a = vec2<f32>(roughness::clamp_alpha(lobe.x), roughness::clamp_alpha(lobe.y));
    return matrix::from_eigen(axis, a);
}

/// The lobe of `KHR_materials_anisotropy` (the Rust `KhrAnisotropy::alpha`): the
/// metallic-roughness texture's perceptual roughness `r` (`alpha_b = r^2` across the
/// anisotropy direction) and the anisotropy texel as fetched from its unorm texture:
/// direction `(cos, sin) = 2 rg - 1` (normalised: 8-bit channels are not unit), strength `b`,
/// `alpha_t = mix(alpha_b, 1, b^2)` along the direction (the extension's definition).
/// Multiply `b` by the material's `anisotropyStrength` and rotate the direction by its
/// `anisotropyRotation` before calling, as the extension says. A zero direction is `+x`.
fn from_khr_anisotropy(r: f32, anisotropy: vec4<f32>) -> matrix::RoughnessMatrix {
    let d = 2.0 * anisotropy.xy - 1.0;
    let len = length(d);
    let axis = select(vec2<f32>(1.0, 0.0), d / len, len > 0.0);
    let alpha_b = r * r;
    let b = anisotropy.z;
    let alpha_t = mix(alpha_b, 1.0, b * b);
    let a = vec2<f32>(roughness::clamp_alpha(alpha_t), roughness::clamp_alpha(alpha_b));
    return matrix::from_eigen(axis, a);
}

/// The roughness matrix stored as `(A11, A12, A22, 1)` (the baker's `--store alpha
/// --anisotropic`): `matrix::from_entries` (its determinant formed in f32, within
/// `cond(A) eps`).
fn from_matrix_texel(t: vec4<f32>) -> matrix::RoughnessMatrix {
    return matrix::from_entries(t.x, t.y, t.z);
}
