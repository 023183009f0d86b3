#define_import_path highlights::shading

#import highlights::scene
#import filtered_ndf::math
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann

// The reflectance model of `render::radiance`, shared by the forward pass and the deferred
// lighting pass: ambient and Lambert terms, and a microfacet lobe whose `D` the caller brings
// (filtered or not) with the unfiltered Smith `G2` of the base roughness.

/// The NDFs of the demonstration.
const BECKMANN: u32 = 0u;
const GGX: u32 = 1u;

/// One point light seen from one shading point: the unit directions to the light and to
/// the eye and the half vector (world), and the squared distance to the light.
struct Light {
    wi: vec3<f32>,
    wo: vec3<f32>,
    h: vec3<f32>,
    dist_sq: f32,
}

/// `Surface::new`: the directions at `s` for the scene's light.
fn light_at(s: scene::Surface) -> Light {
    let to_light = scene::scene.light_position.xyz - s.position;
    let wi = normalize(to_light);
    let wo = normalize(scene::scene.eye.xyz - s.position);
    let sum = wi + wo;
    let h = select(s.normal, normalize(sum), dot(sum, sum) > 1e-30);
    return Light(wi, wo, h, dot(to_light, to_light));
}

/// Unfiltered Smith `G2` (height-correlated) of `family` at roughness `alpha` (tangent frame).
fn smith_g(family: u32, alpha: f32, wi: vec3<f32>, wo: vec3<f32>, h: vec3<f32>) -> f32 {
    let r = isotropic::from_alpha(alpha);
    if family == BECKMANN {
        return beckmann::g2_isotropic(r, wi, wo, h);
    }
    return ggx::g2_isotropic(r, wi, wo, h);
}

/// Outgoing radiance at `s` for the light `l` given the density `d` at the local half
/// vector: `render::radiance`.
fn radiance(s: scene::Surface, l: Light, family: u32, d: f32) -> vec3<f32> {
    let f = scene::tangent_frame(s.normal);
    let wi = scene::to_local(f, l.wi);
    let wo = scene::to_local(f, l.wo);
    let h = scene::to_local(f, l.h);
    var out = s.albedo * scene::scene.ambient.xyz;
    let cos_i = wi.z;
    if cos_i <= 0.0 {
        return out;
    }
    let irradiance = scene::scene.light_intensity.xyz * (cos_i / l.dist_sq);
    let cos_o = max(wo.z, 1e-4);
    let f_normal = scene::scene.light_position.w;
    let m = 1.0 - clamp(dot(wi, h), 0.0, 1.0);
    let fresnel = f_normal + (1.0 - f_normal) * (m * m * m * m * m);
    let spec = fresnel * d * smith_g(family, s.alpha, wi, wo, h) / (4.0 * cos_i * cos_o);
    out += irradiance * (s.albedo * math::INV_PI + vec3<f32>(spec));
    return out;
}
