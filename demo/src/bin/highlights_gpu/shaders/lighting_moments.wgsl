// The deferred moments route's lighting pass (the host appends `const METHOD: u32 = ...;`, a
// footprint method's index in `passes.rs`'s `FORWARD`): per pixel and per light (one here),
// the moments route's kernel (`highlights::moments`) from the window's slope moments that the
// G-buffer pass stored (`gbuffer.wgsl`'s `fs_moments`) and the light's parallax, the method's
// filtered `D`, the reflectance of `render::radiance`. The same formulas as the forward
// moments route at the same pixel centres, split at the light.

#import highlights::scene
#import highlights::shading
#import highlights::moments
#import highlights::methods

@group(0) @binding(1) var normal_moment: texture_2d<u32>;
@group(0) @binding(2) var position_alpha: texture_2d<u32>;
@group(0) @binding(3) var albedo_object: texture_2d<u32>;
@group(0) @binding(4) var slope_moments: texture_2d<u32>;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return scene::fullscreen(i);
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    let ix = vec2<i32>(floor(frag.xy));
    let nm = bitcast<vec4<f32>>(textureLoad(normal_moment, ix, 0));
    let pa = bitcast<vec4<f32>>(textureLoad(position_alpha, ix, 0));
    let ao = bitcast<vec4<f32>>(textureLoad(albedo_object, ix, 0));
    let wm = bitcast<vec4<f32>>(textureLoad(slope_moments, ix, 0));
    if ao.w == 0.0 {
        return bitcast<vec4<u32>>(vec4<f32>(scene::sky(scene::ray_dir(frag.xy)), 1.0));
    }
    let index = u32(ao.w) - 1u;
    let s = scene::Surface(pa.xyz, nm.xyz, ao.xyz, pa.w);
    let l = shading::light_at(s);
    let g = moments::GradientMoments(wm.xy, vec3<f32>(wm.zw, nm.w));
    let m = moments::filter_input_with(index, s, frag.xy, l.wi, l.dist_sq, l.h, g);
    let dens = methods::filtered_d(METHOD, m.h, s.alpha, m.fp, vec3<f32>(0.0), vec3<f32>(0.0));
    return bitcast<vec4<u32>>(vec4<f32>(shading::radiance(s, l, methods::family(METHOD), dens), 1.0));
}
