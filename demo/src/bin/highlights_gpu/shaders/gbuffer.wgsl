// The deferred route's G-buffer pass (the host appends `const PRESET: u32 = ...;`, an index
// of `presets::ALL`, or 12 for none): per object, as the forward pass draws it, the normal
// and its quad derivatives, the roughness filtered from the normal differences by the
// engine convention (TK19 Listing 2), stored for the lighting pass (`fs`). No light is known
// here. The deferred moments route's entry point `fs_moments` stores the water's windowed
// slope moments instead (`highlights::moments`, independent of the light), for
// `lighting_moments.wgsl` to filter each light with.

#import highlights::scene
#import highlights::moments
#import filtered_ndf::filter::deferred
#import filtered_ndf::filter::presets

struct Object {
    index: u32,
}

@group(0) @binding(1) var visibility: texture_2d<u32>;
@group(1) @binding(0) var<uniform> object: Object;

/// The G-buffer (f32 values as their bits, as every target here).
struct GBuffer {
    /// World normal, filtered roughness `alpha_bar`.
    @location(0) normal_alpha: vec4<u32>,
    /// World position, base roughness (for `G2`).
    @location(1) position_alpha: vec4<u32>,
    /// Albedo, coverage (0: sky).
    @location(2) albedo: vec4<u32>,
}

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return scene::fullscreen(i);
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> GBuffer {
    let pixel = frag.xy;
    let vis = bitcast<vec4<f32>>(textureLoad(visibility, vec2<i32>(floor(pixel)), 0));
    let d = scene::ray_dir(pixel);
    let s = scene::object_surface(object.index, d, vis.x);
    // TK19 Listing 2: ddx / ddy of the world normal (fine: the quad's row / column pair).
    let dn_u = dpdxFine(s.normal);
    let dn_v = dpdyFine(s.normal);
    var alpha_bar = s.alpha;
    if PRESET < 12u {
        alpha_bar = deferred::apply(presets::preset(PRESET), s.alpha, dn_u, dn_v);
    }
    let seen = i32(vis.z);
    if object.index == 0u && seen < 0 {
        return GBuffer(vec4<u32>(0u), vec4<u32>(0u), vec4<u32>(0u));
    }
    if seen != i32(object.index) {
        discard;
    }
    return GBuffer(
        bitcast<vec4<u32>>(vec4<f32>(s.normal, alpha_bar)),
        bitcast<vec4<u32>>(vec4<f32>(s.position, s.alpha)),
        bitcast<vec4<u32>>(vec4<f32>(s.albedo, 1.0)),
    );
}

/// The G-buffer of the deferred moments route (f32 values as their bits).
struct GBufferMoments {
    /// World normal, the window's `Cov[h_z, h_z]` (the height gradient's covariance).
    @location(0) normal_moment: vec4<u32>,
    /// World position, base roughness (for `G2` and the lobe).
    @location(1) position_alpha: vec4<u32>,
    /// Albedo, `1 + object index` (0: sky).
    @location(2) albedo_object: vec4<u32>,
    /// The window's `E[h_x]`, `E[h_z]`, `Cov[h_x, h_x]`, `Cov[h_x, h_z]`.
    @location(3) slope_moments: vec4<u32>,
}

@fragment
fn fs_moments(@builtin(position) frag: vec4<f32>) -> GBufferMoments {
    let pixel = frag.xy;
    let vis = bitcast<vec4<f32>>(textureLoad(visibility, vec2<i32>(floor(pixel)), 0));
    let seen = i32(vis.z);
    if object.index == 0u && seen < 0 {
        return GBufferMoments(vec4<u32>(0u), vec4<u32>(0u), vec4<u32>(0u), vec4<u32>(0u));
    }
    if seen != i32(object.index) {
        discard;
    }
    let s = scene::object_surface(object.index, scene::ray_dir(pixel), vis.x);
    let g = moments::window_moments(object.index, s, pixel);
    return GBufferMoments(
        bitcast<vec4<u32>>(vec4<f32>(s.normal, g.cov.z)),
        bitcast<vec4<u32>>(vec4<f32>(s.position, s.alpha)),
        bitcast<vec4<u32>>(vec4<f32>(s.albedo, f32(object.index + 1u))),
        bitcast<vec4<u32>>(vec4<f32>(g.mean, g.cov.xy)),
    );
}
