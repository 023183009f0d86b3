// The fragment shader of `FilteredNdfMaterial` (`ExtendedMaterial<StandardMaterial,
// FilteredNdfExtension>`), forward and deferred: Bevy's `StandardMaterial` shading with the
// roughness filtered by `filtered_ndf_bevy::roughness` between building the PBR input (normal
// mapping included) and the lighting, or, in the deferred pipeline, writing the G-buffer.
// With `FILTERED_NDF_MOMENTS` (the material's baked moment chain is bound) and a mesh with
// UVs and tangents, the normal and the lobe come from the moments (`filtered_ndf_bevy::lean`)
// and the derivative filter sees the geometric normal.

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

#ifdef FILTERED_NDF_MOMENTS
#import bevy_pbr::{
    mesh_view_bindings::view,
    pbr_functions::{apply_normal_mapping, calculate_tbn_mikktspace},
    pbr_types::STANDARD_MATERIAL_FLAGS_DOUBLE_SIDED_BIT,
}
#import filtered_ndf::bake::moments
#import filtered_ndf_bevy::lean
#endif

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> filter_settings: roughness::FilterSettings;

#ifdef FILTERED_NDF_MOMENTS
// The normal map's moment chain (`FilteredNdfExtension::moments`, `moments_xy`); the first
// texture's sampler samples both.
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var moments_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(102) var moments_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var moments_xy_texture: texture_2d<f32>;
#endif

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

    // The normal whose differences widen the lobe (TK19 Listing 2's ddx, ddy of the shading
    // normal): the normal-mapped world normal, or with the moment chain the geometric one.
    var n_filtered = pbr_input.N;
    var perceptual_roughness = pbr_input.material.perceptual_roughness;
#ifdef FILTERED_NDF_MOMENTS
#ifdef VERTEX_UVS_A
#ifdef VERTEX_TANGENTS
    // The moments over the pixel's footprint, fetched as Bevy fetches the normal map: at its
    // UV (transformed; `uv_b` where the normal map uses it) and its level of detail (the
    // UV's screen derivatives, scaled by the view's mip bias: `textureSampleBias`'s level).
#ifdef STANDARD_MATERIAL_NORMAL_MAP_UV_B
#ifdef VERTEX_UVS_B
    let mesh_uv = in.uv_b;
#else
    let mesh_uv = in.uv;
#endif
#else
    let mesh_uv = in.uv;
#endif
    let uv = (pbr_input.material.uv_transform * vec3<f32>(mesh_uv, 1.0)).xy;
    let lod_scale = exp2(view.mip_bias);
    let m = moments::sample_grad(
        moments_texture,
        moments_xy_texture,
        moments_sampler,
        uv,
        dpdx(uv) * lod_scale,
        dpdy(uv) * lod_scale,
    );
    // The geometric normal (interpolated, flipped on back faces as Bevy flips it): the normal
    // map's detail is in the moments, so only the surface's own curvature is left to the
    // derivative filter.
    n_filtered = normalize(pbr_input.world_normal);
    if filter_settings.enabled != 0u {
        // The mean slope's normal through Bevy's normal mapping, and the lobe widened by the
        // texel's covariance (KHPL16 eq. 21).
        let flags = pbr_input.material.flags;
        let double_sided = (flags & STANDARD_MATERIAL_FLAGS_DOUBLE_SIDED_BIT) != 0u;
        let tbn = calculate_tbn_mikktspace(pbr_input.world_normal, in.world_tangent);
        pbr_input.N = apply_normal_mapping(
            flags,
            tbn,
            double_sided,
            is_front,
            lean::mean_normal_texel(m),
        );
        perceptual_roughness = lean::lean_perceptual_roughness(perceptual_roughness, m);
    }
#endif
#endif
#endif
    // Taken where every invocation of the quad runs (before any branch).
    let dn_u = dpdxFine(n_filtered);
    let dn_v = dpdyFine(n_filtered);
    pbr_input.material.perceptual_roughness = roughness::filter_perceptual_roughness(
        filter_settings,
        perceptual_roughness,
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
