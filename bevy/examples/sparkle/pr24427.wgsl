// The formula of bevyengine/bevy pull request 24427 ("Specular aa", open), written here from
// its description for comparison: Bevy's squared GGX roughness widened by the screen-space
// derivatives of the normal-mapped normal,
//     alpha^2 <- saturate(alpha^2 + min(sigma^2 (|dN/dx|^2 + |dN/dy|^2), kappa)),
// with sigma = 0.5 and kappa = 0.18 by default (Tokuyoshi and Kaplanyan 2019, eq. 5 with
// TK19's kappa). The pull request widens `alpha^2` inside Bevy's lighting, after Bevy's
// roughness clamp; this extension does the same before the lighting, from the clamped
// roughness, and hands Bevy the perceptual roughness of the result.

#import bevy_pbr::{
    pbr_fragment::pbr_input_from_standard_material,
    pbr_functions::{alpha_discard, apply_pbr_lighting, main_pass_post_lighting_processing},
    forward_io::{VertexOutput, FragmentOutput},
}

struct Pr24427Settings {
    /// The screen-space standard deviation `sigma` (the pull request's
    /// `specular_anti_aliasing_screen_space_variance`, 0.5).
    sigma: f32,
    /// The threshold `kappa` (`specular_anti_aliasing_threshold`, 0.18).
    kappa: f32,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> pr_settings: Pr24427Settings;

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);

    let n = pbr_input.N;
    let ddx_n = dpdx(n);
    let ddy_n = dpdy(n);
    let variance = pr_settings.sigma * pr_settings.sigma * (dot(ddx_n, ddx_n) + dot(ddy_n, ddy_n));
    // Bevy's alpha: the square of the clamped perceptual roughness.
    let p = clamp(pbr_input.material.perceptual_roughness, 0.089, 1.0);
    let alpha = p * p;
    let alpha_sq = saturate(alpha * alpha + min(variance, pr_settings.kappa));
    pbr_input.material.perceptual_roughness = sqrt(sqrt(alpha_sq));

    pbr_input.material.base_color = alpha_discard(pbr_input.material, pbr_input.material.base_color);
    var out: FragmentOutput;
    out.color = apply_pbr_lighting(pbr_input);
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);
    return out;
}
