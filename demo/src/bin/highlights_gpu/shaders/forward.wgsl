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
#import filtered_ndf::footprint
#import filtered_ndf::footprint::slope
#import filtered_ndf::footprint::jacobian
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::rect
#import filtered_ndf::filter::proxy
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::deferred
#import filtered_ndf::filter::presets

struct Object {
    /// 0: the water (and the sky where nothing is hit); `1 + i`: sphere `i`.
    index: u32,
}

@group(0) @binding(1) var visibility: texture_2d<u32>;
@group(1) @binding(0) var<uniform> object: Object;

/// KHPL16's clamps for the parallelogram kernels (`methods.rs`): `lambda = 1` and the
/// determinant clamp, no rectangle floor, no `kappa`.
const KHPL16_RULES: clamp::ClampRules = clamp::ClampRules(1.0, clamp::FLOOR_NONE, 0.0, 3.40282347e38, true);

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return scene::fullscreen(i);
}

/// The NDF a method filters (its G2 and its reference).
fn family() -> u32 {
    if METHOD == 0u || METHOD == 2u {
        return shading::BECKMANN;
    }
    return shading::GGX;
}

/// Whether the method filters over the half vector's footprint (`Method::uses_footprint`;
/// the others read the normal differences, or nothing).
fn uses_footprint() -> bool {
    return METHOD >= 2u && METHOD <= 6u;
}

/// The method's (filtered) `D` at the local half vector `h`: `methods::filtered_d`.
/// `fp`: the slope footprint; `dn_u`, `dn_v`: world normal differences.
fn filtered_d(h: vec3<f32>, alpha: f32, fp: footprint::Footprint, dn_u: vec3<f32>, dn_v: vec3<f32>) -> f32 {
    let r = isotropic::from_alpha(alpha);
    let aa = axis_aligned::from_alpha(vec2<f32>(alpha));
    switch METHOD {
        case 0u: {
            return beckmann::d_isotropic(r, h);
        }
        case 1u: {
            return ggx::d_isotropic(r, h);
        }
        case 2u: {
            // KHPL16 eq. 13-15: A' = A + 2 Sigma on Beckmann.
            let a = gaussian::filter_gaussian(KHPL16_RULES, isotropic::to_matrix(r), fp, footprint::SIGMA_PIXEL);
            return beckmann::d_matrix(a, h);
        }
        case 3u, 4u: {
            // KHPL16 section 5.3: the bounding rectangle, half-extents clamped to lambda = 1.
            let half = clamp::rect(KHPL16_RULES, bounding::from_footprint(fp), vec2<f32>(alpha)).half_extent;
            if METHOD == 3u {
                return rect::d_rect(aa, h, half);
            }
            return ggx::d_axis_aligned(proxy::proxy(aa, half), h);
        }
        case 5u, 6u: {
            // TK19 section 3.2: the kernel of the projected half vector's derivatives.
            let j = jacobian::slope_to_projected(h);
            let fp_p = footprint::Footprint(j * fp.dh_u, j * fp.dh_v);
            let a = isotropic::to_matrix(r);
            if METHOD == 5u {
                return ggx::d_matrix(gaussian::filter_gaussian(clamp::DEFAULT_RULES, a, fp_p, footprint::SIGMA_PIXEL), h);
            }
            // TK21: the same kernel added in projected space.
            let rules = clamp::DEFAULT_RULES;
            let k = clamp::kernel(rules, covariance::from_footprint(clamp::footprint(rules, fp_p), footprint::SIGMA_PIXEL));
            return ggx::d_matrix(projected::projected(a, k), h);
        }
        default: {
            // TK19 eq. 1 / 4 / 5 (methods 7, 8, 9 = presets 0, 1, 2) and the engine presets.
            let i = select(METHOD - 10u, METHOD - 7u, METHOD < 10u);
            let alpha_bar = deferred::apply(presets::preset(i), alpha, dn_u, dn_v);
            return ggx::d_isotropic(isotropic::from_alpha(alpha_bar), h);
        }
    }
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
    // Per light (one here): the half vector, its quad neighbours' half vectors, the footprint.
    let l = shading::light_at(s);
    let dh_x = dpdxFine(l.h);
    let dh_y = dpdyFine(l.h);
    let s_own = slope::slope_from_sphere(scene::to_local(f, l.h));
    let dh_u = side.x * (slope_of(f, s.normal, l.h + side.x * dh_x, s.normal + side.x * dn_u) - s_own);
    let dh_v = side.y * (slope_of(f, s.normal, l.h + side.y * dh_y, s.normal + side.y * dn_v) - s_own);
    var fp = footprint::from_slope_derivatives(dh_u, dh_v);
    var h_lobe = scene::to_local(f, l.h);
    let seen = i32(vis.z);
    // The moments route's inputs need no neighbour: computed where the object is seen only.
    if MOMENTS && uses_footprint() && seen == i32(object.index) {
        let m = moments::filter_input(object.index, s, pixel, l.wi, l.dist_sq, l.h);
        fp = m.fp;
        h_lobe = m.h;
    }
    let dens = filtered_d(h_lobe, s.alpha, fp, dn_u, dn_v);
    color += shading::radiance(s, l, family(), dens);

    if object.index == 0u && seen < 0 {
        return bitcast<vec4<u32>>(vec4<f32>(scene::sky(d), 1.0));
    }
    if seen != i32(object.index) {
        discard;
    }
    return bitcast<vec4<u32>>(vec4<f32>(color, 1.0));
}
