#define_import_path filtered_ndf_bevy::lean

#import filtered_ndf::filter::{lean, lean_nested}
#import filtered_ndf::ndf::roughness::{isotropic, matrix}
#import filtered_ndf_bevy::roughness

// The baked LEAN moment chain in Bevy's `StandardMaterial` (Olano and Baker 2010; KHPL16
// section 5.5, eq. 21): the shading normal of the mean slope, and Bevy's isotropic GGX lobe
// widened by the texel's slope covariance. The moments come from
// `filtered_ndf::bake::moments::sample_grad` (the hardware's trilinear filter over the pixel's
// footprint), in the frame of the normal map's channels as stored (`x` red along `+u`, `y`
// green up the image).

/// The normal-map texel of the mean slope, `0.5 n + 0.5` with `n =
/// lean_nested::lean_mean_normal(m) = normalize(-E[s_x], -E[s_y], 1)`, encoded as Bevy's
/// normal maps are, so that `pbr_functions::apply_normal_mapping` applies to it exactly what it
/// applies to a normal-map sample (its TBN, the green flip of `flip_normal_map_y`, the
/// two-component reconstruction of `z`, double-sided back faces).
fn mean_normal_texel(m: lean::LeanMoments) -> vec3<f32> {
    return 0.5 * lean_nested::lean_mean_normal(m) + 0.5;
}

/// The perceptual roughness `sqrt(alpha_L)` of Bevy's lobe widened by the texel's LEAN
/// covariance: `alpha = clamp(p, 0.089, 1)^2` (the lobe Bevy evaluates), `A_L =
/// lean_nested::lean_widened(alpha^2 I, m) = alpha^2 I + 2 Sigma_L` (KHPL16 eq. 21, `Sigma_L =
/// lean::covariance(m)`, PSD-projected), and the isotropic lobe of the same total slope
/// variance, `alpha_L^2 = tr(A_L) / 2 = alpha^2 + tr(Sigma_L)` (Bevy's lobe is isotropic).
/// At least 0.089 and finite for finite moments (`alpha_L >= alpha`: the covariance is PSD;
/// Bevy's lighting clamps the result to at most 1).
fn lean_perceptual_roughness(perceptual_roughness: f32, m: lean::LeanMoments) -> f32 {
    let p = clamp(perceptual_roughness, roughness::BEVY_PERCEPTUAL_ROUGHNESS_MIN, 1.0);
    let a = isotropic::to_matrix(isotropic::from_alpha(p * p));
    let e = matrix::entries(lean_nested::lean_widened(a, m));
    return sqrt(sqrt(0.5 * (e.x + e.z)));
}
