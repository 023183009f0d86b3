// The deferred route's lighting pass: per pixel and per light (one here), GGX with the
// G-buffer's filtered roughness, the reflectance of `render::radiance`.

#import highlights::scene
#import highlights::shading
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::ggx

@group(0) @binding(1) var normal_alpha: texture_2d<u32>;
@group(0) @binding(2) var position_alpha: texture_2d<u32>;
@group(0) @binding(3) var albedo: texture_2d<u32>;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return scene::fullscreen(i);
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    let ix = vec2<i32>(floor(frag.xy));
    let na = bitcast<vec4<f32>>(textureLoad(normal_alpha, ix, 0));
    let pa = bitcast<vec4<f32>>(textureLoad(position_alpha, ix, 0));
    let al = bitcast<vec4<f32>>(textureLoad(albedo, ix, 0));
    if al.w == 0.0 {
        return bitcast<vec4<u32>>(vec4<f32>(scene::sky(scene::ray_dir(frag.xy)), 1.0));
    }
    let s = scene::Surface(pa.xyz, na.xyz, al.xyz, pa.w);
    let l = shading::light_at(s);
    let h = scene::to_local(scene::tangent_frame(s.normal), l.h);
    let dens = ggx::d_isotropic(isotropic::from_alpha(na.w), h);
    return bitcast<vec4<u32>>(vec4<f32>(shading::radiance(s, l, shading::GGX, dens), 1.0));
}
