#define_import_path filtered_ndf::filter::proxy

#import filtered_ndf::math
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::ggx
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp

// The GGX proxy of KHPL16 section 5.4 (eq. 18-20), mirroring `src/.../filter/proxy.rs`: an
// effective roughness whose unfiltered GGX has the peak of the box-filtered GGX. Eq. 19
// solved: `alpha'^2 = (alpha^2 + H^2) t / atan(t)`, `t = H / sqrt(alpha^2 + H^2)`, with `H`
// the half extent (eq. 20 as printed is inconsistent with eq. 19; see the Rust docs).

/// The exact effective roughness of one axis (KHPL16 eq. 19 solved):
/// `alpha' = sqrt(alpha^2 + H^2) sqrt(t / atan t)`, `t = H / sqrt(alpha^2 + H^2)`, with the
/// driver-independent `math::atan` (8 ulp): within 12 ulp. `alpha' = alpha` at `H = 0`;
/// `H` is used by magnitude. Domain: `alpha > 0`.
fn effective_alpha(alpha: f32, half_extent: f32) -> f32 {
    let h = abs(half_extent);
    let s = math::hypot(alpha, h);
    let t = select(0.0, h / s, s > 0.0);
    let ratio = select(1.0, t / math::atan(t), t > 0.0);
    return s * sqrt(ratio);
}

/// The simple form of KHPL16 eq. 20 for one axis, `sqrt(alpha^2 + H^2)` with `H` the half
/// extent (within 11.4 % below [`effective_alpha`]). Within 8 ulp.
fn effective_alpha_simple(alpha: f32, half_extent: f32) -> f32 {
    return math::hypot(alpha, abs(half_extent));
}

/// The exact GGX proxy roughness per axis, clamped into the supported range
/// (`axis_aligned::from_alpha`). `half_extent` is the filtering rectangle's.
fn proxy(r: axis_aligned::AxisAligned, half_extent: vec2<f32>) -> axis_aligned::AxisAligned {
    return axis_aligned::from_alpha(vec2<f32>(
        effective_alpha(r.alpha.x, half_extent.x),
        effective_alpha(r.alpha.y, half_extent.y),
    ));
}

/// The simple GGX proxy roughness per axis, clamped.
fn proxy_simple(r: axis_aligned::AxisAligned, half_extent: vec2<f32>) -> axis_aligned::AxisAligned {
    return axis_aligned::from_alpha(vec2<f32>(
        effective_alpha_simple(r.alpha.x, half_extent.x),
        effective_alpha_simple(r.alpha.y, half_extent.y),
    ));
}

/// The GGX proxy of KHPL16 section 5.4 (eq. 18-19, solved exactly): the axis-aligned GGX whose
/// peak is the box-filtered peak over the clamped bounding rectangle, per axis.
struct Proxy {
    /// The clamp rules applied to the rectangle's half extents.
    clamps: clamp::ClampRules,
}

/// KHPL16: half extents clamped to `lambda = 1`, no floor.
const KHPL16_PROXY: Proxy = Proxy(clamp::KHPL16_RULES);

/// The proxy roughness (the Rust `Proxy::lobe`), for `ggx::*_axis_aligned`.
fn proxy_lobe(method: Proxy, material: axis_aligned::AxisAligned, fp: pixel::Footprint) -> axis_aligned::AxisAligned {
    let h = clamp::rect(method.clamps, bounding::from_footprint(fp), material.alpha).half_extent;
    return proxy(material, h);
}

/// `D(m)` of [`proxy_lobe`].
fn d_ggx_proxy(method: Proxy, material: axis_aligned::AxisAligned, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return ggx::d_axis_aligned(proxy_lobe(method, material, fp), m);
}
