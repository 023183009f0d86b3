// The fragment shader of `FilteredNdfMaterial` (`ExtendedMaterial<StandardMaterial,
// FilteredNdfExtension>`), forward and deferred: Bevy's `StandardMaterial` shading with the
// roughness filtered by `filtered_ndf_bevy::roughness` between building the PBR input (normal
// mapping included) and the lighting, or, in the deferred pipeline, writing the G-buffer.

#import bevy_pbr::{
    pbr_fragment::pbr_input_from_standard_material,
    pbr_functions::alpha_discard,
    decal::clustered::apply_decals,
}

#ifdef PREPASS_PIPELINE
#import bevy_pbr::{
    prepass_io::{VertexOutput, FragmentOutput},
    pbr_deferred_functions::deferred_output,
}
#else
#import bevy_pbr::{
    forward_io::{VertexOutput, FragmentOutput},
    pbr_functions::{apply_pbr_lighting, main_pass_post_lighting_processing},
    pbr_types::STANDARD_MATERIAL_FLAGS_UNLIT_BIT,
}
#endif

#ifdef VISIBILITY_RANGE_DITHER
#import bevy_pbr::pbr_functions::visibility_range_dither
#endif

#import filtered_ndf_bevy::roughness

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> filter_settings: roughness::FilterSettings;

@fragment
fn fragment(
    vertex_output: VertexOutput,
    @builtin(front_facing) is_front: bool,
) -> FragmentOutput {
    let in = vertex_output;

#ifdef VISIBILITY_RANGE_DITHER
    visibility_range_dither(in.position, in.visibility_range_dither);
#endif

    var pbr_input = pbr_input_from_standard_material(in, is_front);

    // TK19 Listing 2's ddx, ddy of the shading normal: the normal-mapped world normal's
    // differences to the neighbouring pixels of the quad, taken where every invocation of the
    // quad runs (before any branch).
    let n = pbr_input.N;
    let dn_u = dpdxFine(n);
    let dn_v = dpdyFine(n);
    pbr_input.material.perceptual_roughness = roughness::filter_perceptual_roughness(
        filter_settings,
        pbr_input.material.perceptual_roughness,
        dn_u,
        dn_v,
    );
#ifdef STANDARD_MATERIAL_CLEARCOAT
    // The clear coat is its own GGX lobe over its own normal.
    let c = pbr_input.clearcoat_N;
    let dc_u = dpdxFine(c);
    let dc_v = dpdyFine(c);
    pbr_input.material.clearcoat_perceptual_roughness = roughness::filter_perceptual_roughness(
        filter_settings,
        pbr_input.material.clearcoat_perceptual_roughness,
        dc_u,
        dc_v,
    );
#endif

    pbr_input.material.base_color = alpha_discard(pbr_input.material, pbr_input.material.base_color);
    apply_decals(&pbr_input);

#ifdef PREPASS_PIPELINE
    // Deferred: the G-buffer stores the filtered perceptual roughness; the lighting pass reads it.
    let out = deferred_output(in, pbr_input);
#else
    var out: FragmentOutput;
    if (pbr_input.material.flags & STANDARD_MATERIAL_FLAGS_UNLIT_BIT) == 0u {
        out.color = apply_pbr_lighting(pbr_input);
    } else {
        out.color = pbr_input.material.base_color;
    }
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);
#endif

    return out;
}
