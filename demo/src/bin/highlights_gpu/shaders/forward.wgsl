// Forward shading of one object with one filtering method (the host appends
// `const METHOD: u32 = ...;`, the index in `passes.rs`'s `FORWARD`, or 10 + a preset's
// index, and `const MOMENTS: bool = ...;`): per light, the half vector and its quad
// derivatives, or with `MOMENTS` the moments route's inputs (`highlights::moments`: the
// water's windowed slope moments, ray differentials on the spheres), the method's filtered
// `D`, the reflectance of `render::radiance`. One draw per object (the host sets
// `object.index` and a scissor around each sphere); every pixel evaluates the object, visible
// or not, so that the 2x2-quad derivatives of its visible pixels difference that object only
// (as helper lanes do for a rasterised triangle), and the pixels that see something else
// discard at the end.

#import highlights::scene
#import highlights::shading
#import highlights::moments
#import highlights::methods
#import filtered_ndf::footprint
#import filtered_ndf::footprint::slope

struct Object {
    /// 0: the water (and the sky where nothing is hit); `1 + i`: sphere `i`.
    index: u32,
}

@group(0) @binding(1) var visibility: texture_2d<u32>;
@group(1) @binding(0) var<uniform> object: Object;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return scene::fullscreen(i);
}

/// The slope of the half vector `h_other` of a quad neighbour whose normal is `n_other`,
/// carried to this pixel by the rotation taking `n_other` to `n`, in this pixel's frame
/// `f`: `Surface::slope_of`.
fn slope_of(f: mat3x3<f32>, n: vec3<f32>, h_other: vec3<f32>, n_other: vec3<f32>) -> vec2<f32> {
    let carried = scene::rotate_arc(normalize(n_other), n, normalize(h_other));
    return slope::slope_from_sphere(scene::to_local(f, carried));
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    let pixel = frag.xy;
    let vis = bitcast<vec4<f32>>(textureLoad(visibility, vec2<i32>(floor(pixel)), 0));
    let d = scene::ray_dir(pixel);
    let s = scene::object_surface(object.index, d, vis.x);
    // Fine derivatives difference the two pixels of a row (column) of the quad: the
    // neighbour's value is this one plus (even pixel) or minus (odd pixel) the derivative.
    let side = vec2<f32>(select(1.0, -1.0, (u32(pixel.x) & 1u) == 1u), select(1.0, -1.0, (u32(pixel.y) & 1u) == 1u));
    let dn_u = dpdxFine(s.normal);
    let dn_v = dpdyFine(s.normal);
    let f = scene::tangent_frame(s.normal);
    var color = vec3<f32>(0.0);
    // Per light (one here): the half vector and the footprint: its quad neighbours' half
    // vectors, or the moments route's inputs.
    let l = shading::light_at(s);
    var fp = footprint::Footprint(vec2<f32>(0.0), vec2<f32>(0.0));
    var h_lobe = scene::to_local(f, l.h);
    let seen = i32(vis.z);
    if MOMENTS && methods::uses_footprint(METHOD) {
        // No neighbour needed: computed where the object is seen only (the other pixels
        // discard below).
        if seen == i32(object.index) {
            let m = moments::filter_input(object.index, s, pixel, l.wi, l.dist_sq, l.h);
            fp = m.fp;
            h_lobe = m.h;
        }
    } else {
        let dh_x = dpdxFine(l.h);
        let dh_y = dpdyFine(l.h);
        let s_own = slope::slope_from_sphere(h_lobe);
        let dh_u = side.x * (slope_of(f, s.normal, l.h + side.x * dh_x, s.normal + side.x * dn_u) - s_own);
        let dh_v = side.y * (slope_of(f, s.normal, l.h + side.y * dh_y, s.normal + side.y * dn_v) - s_own);
        fp = footprint::from_slope_derivatives(dh_u, dh_v);
    }
    let dens = methods::filtered_d(METHOD, h_lobe, s.alpha, fp, dn_u, dn_v);
    color += shading::radiance(s, l, methods::family(METHOD), dens);

    if object.index == 0u && seen < 0 {
        return bitcast<vec4<u32>>(vec4<f32>(scene::sky(d), 1.0));
    }
    if seen != i32(object.index) {
        discard;
    }
    return bitcast<vec4<u32>>(vec4<f32>(color, 1.0));
}
