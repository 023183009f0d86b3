#define_import_path highlights::methods

#import highlights::shading
#import filtered_ndf::footprint
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

// The demonstration's methods on the GPU, `demo/src/methods.rs`: `method` is the index in
// `passes.rs`'s `FORWARD` (0-9), or 10 + an engine preset's index. The shaders pass it as a
// constant (`METHOD`), so that the driver keeps the one case a pipeline shades.

/// KHPL16's clamps for the parallelogram kernels (`methods.rs`): `lambda = 1` and the
/// determinant clamp, no rectangle floor, no `kappa`.
const KHPL16_RULES: clamp::ClampRules = clamp::ClampRules(1.0, clamp::FLOOR_NONE, 0.0, 3.40282347e38, true);

/// The NDF a method filters (its G2 and its reference).
fn family(method: u32) -> u32 {
    if method == 0u || method == 2u {
        return shading::BECKMANN;
    }
    return shading::GGX;
}

/// Whether the method filters over the half vector's footprint (`Method::uses_footprint`;
/// the others read the normal differences, or nothing).
fn uses_footprint(method: u32) -> bool {
    return method >= 2u && method <= 6u;
}

/// Method `method`'s (filtered) `D` at the local half vector `h`: `methods::filtered_d`.
/// `fp`: the slope footprint; `dn_u`, `dn_v`: world normal differences.
fn filtered_d(method: u32, h: vec3<f32>, alpha: f32, fp: footprint::Footprint, dn_u: vec3<f32>, dn_v: vec3<f32>) -> f32 {
    let r = isotropic::from_alpha(alpha);
    let aa = axis_aligned::from_alpha(vec2<f32>(alpha));
    switch method {
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
            if method == 3u {
                return rect::d_rect(aa, h, half);
            }
            return ggx::d_axis_aligned(proxy::proxy(aa, half), h);
        }
        case 5u, 6u: {
            // TK19 section 3.2: the kernel of the projected half vector's derivatives.
            let j = jacobian::slope_to_projected(h);
            let fp_p = footprint::Footprint(j * fp.dh_u, j * fp.dh_v);
            let a = isotropic::to_matrix(r);
            if method == 5u {
                return ggx::d_matrix(gaussian::filter_gaussian(clamp::DEFAULT_RULES, a, fp_p, footprint::SIGMA_PIXEL), h);
            }
            // TK21: the same kernel added in projected space.
            let rules = clamp::DEFAULT_RULES;
            let k = clamp::kernel(rules, covariance::from_footprint(clamp::footprint(rules, fp_p), footprint::SIGMA_PIXEL));
            return ggx::d_matrix(projected::projected(a, k), h);
        }
        default: {
            // TK19 eq. 1 / 4 / 5 (methods 7, 8, 9 = presets 0, 1, 2) and the engine presets.
            let i = select(method - 10u, method - 7u, method < 10u);
            let alpha_bar = deferred::apply(presets::preset(i), alpha, dn_u, dn_v);
            return ggx::d_isotropic(isotropic::from_alpha(alpha_bar), h);
        }
    }
}
