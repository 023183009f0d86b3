#define_import_path filtered_ndf::sampling::rect

#import filtered_ndf::math
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::filter::rect as boxed
#import filtered_ndf::filter::rect::lambda
#import filtered_ndf::sampling

// Importance sampling of the box-filtered GGX lobe (`boxed::d_rect`, `lambda::lambda_rect`)
// and its pdfs, mirroring `src/.../sampling/rect.rs`.
//
// `D(m) m_z`: the lobe's slope is `s = g + delta` with `g` axis-aligned GGX and `delta`
// uniform on the box `[-H_x, H_x] x [-H_y, H_y]` (its density is the box mean of `P22`,
// `boxed::p22_rect`, KHPL16 eq. 16), so a GGX slope plus a uniform offset is an exact sample:
// four uniform numbers, `u` for the GGX slope and `u_box` for the offset (the lobe's
// conditional CDFs have no closed form, so two numbers would need a root find per
// dimension). Visible normals: `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` (Heitz 2014
// eq. 16) with the box lobe's own `Lambda`; its density is here, its sampler (an offset drawn
// by its projected-area weight, two Newton solves over `Psi_1` means) is not yet.
//
// Out of domain: `u` components clamped to `[0, 1 - 2^-24]`; half extents by magnitude, at
// most `1e18 alpha` (`boxed::BIG`; the Rust crate `1e60 alpha`); a sampled `m` is a unit
// vector with `m_z > 0` (a slope beyond the f32 range keeps `m_z` at the smallest normal).

/// A half extent as `boxed::p22_rect` reads it, in slope units: `|h|`, at most `BIG alpha`
/// (NaN as 0 where the driver keeps the comparison).
fn sanitized_half_extent(h: f32, alpha: f32) -> f32 {
    let v = abs(h);
    return select(0.0, min(v, boxed::BIG * alpha), v >= 0.0);
}

/// The unit normal `normalize(-s, 1)` of the slope `s` (scaled first: no square overflows),
/// `m_z` kept at the smallest normal f32 where it underflows.
fn normal_of_slope(s: vec2<f32>) -> vec3<f32> {
    let n = sampling::normalize_scaled(vec3<f32>(-s, 1.0));
    return vec3<f32>(n.xy, max(n.z, math::F32_MIN_POSITIVE));
}

/// Samples a unit micronormal `m` of the box-filtered GGX lobe (roughness `r`, slope-domain
/// half extents `half_extent`) with density `D(m) m_z` per steradian, `D` = `boxed::d_rect`
/// (KHPL16 eq. 16 per steradian): the axis-aligned GGX slope
/// `g = -alpha sqrt(u1 / (1 - u1)) (cos phi, sin phi)`, `phi = 2 pi u2` (the GGX sampler's
/// `D(m) m_z`, Walter et al. 2007 eq. 35-36 with the anisotropic stretch), plus the offset
/// `(2 u_box - 1) H` uniform in the box. Exact; four uniform numbers in `[0, 1)`. Zero half
/// extents: the GGX sample (the same direction as `sampling::sample_normal`).
fn sample_normal_rect(r: axis_aligned::AxisAligned, half_extent: vec2<f32>, u: vec2<f32>, u_box: vec2<f32>) -> vec3<f32> {
    let a = r.alpha;
    let h = vec2<f32>(sanitized_half_extent(half_extent.x, a.x), sanitized_half_extent(half_extent.y, a.y));
    let u1 = sampling::clamp_unit(u.x);
    let cs = math::sincos_turns(sampling::clamp_unit(u.y));
    let rad = sqrt(u1 / (1.0 - u1));
    let g = -a * (rad * cs);
    let b = vec2<f32>(sampling::clamp_unit(u_box.x), sampling::clamp_unit(u_box.y));
    let d = (2.0 * b - 1.0) * h;
    return normal_of_slope(g + d);
}

/// The density of [`sample_normal_rect`], `D(m) m_z` per steradian with `D` =
/// `boxed::d_rect`, for a unit `m`; 0 for `m_z <= 0`.
fn normal_pdf_rect(r: axis_aligned::AxisAligned, half_extent: vec2<f32>, m: vec3<f32>) -> f32 {
    return select(0.0, boxed::d_rect(r, m, half_extent) * m.z, m.z > 0.0);
}

/// The visible-normal density of the box lobe,
/// `D_wo(m) = max(0, wo.m) D(m) / (wo_z (1 + Lambda(wo)))` per steradian (Heitz 2014 eq. 16)
/// for a unit `m`, `D` = `boxed::d_rect`, `Lambda` = `lambda::lambda_rect`. 0 for
/// `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0`; `wo` need not be normalised.
fn visible_normal_pdf_rect(r: axis_aligned::AxisAligned, half_extent: vec2<f32>, wo: vec3<f32>, m: vec3<f32>) -> f32 {
    let wom = dot(wo, m);
    if !(wo.z > 0.0) || !(m.z > 0.0) || !(wom > 0.0) {
        return 0.0;
    }
    let v = wom * boxed::d_rect(r, m, half_extent) / (wo.z * (1.0 + lambda::lambda_rect(r, half_extent, wo)));
    return select(0.0, v, v <= math::F32_MAX);
}
