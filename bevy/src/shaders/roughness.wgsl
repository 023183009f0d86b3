#define_import_path filtered_ndf_bevy::roughness

#import filtered_ndf::filter::deferred

// Roughness filtering for Bevy's `StandardMaterial`: the material's GGX roughness widened by
// the screen-space change of the shading normal across the pixel (TK19 sect. 4, Listing 2;
// KHPL16 sect. 5.4), in one of the published conventions of `filter::presets`, before Bevy's
// PBR lighting evaluates its GGX lobe. Bevy's convention: `alpha = perceptual_roughness^2`
// (`pbr_lighting::perceptualRoughnessToRoughness`).
//
// With the normal map's baked moment chain (`filtered_ndf_bevy::lean`), the lobe this module
// filters is the material's widened by the texel's LEAN covariance (KHPL16 eq. 21), and the
// differences are those of the geometric normal: the normal map's detail is in the moments.
// The derivative kernel's clamp `kappa` bounds only its own estimate, not the baked variance.

/// The per-material settings: a `deferred::KernelConvention` as uniform data (the Rust
/// `FilteredNdfUniform`; the enumerations as `u32`, `saturate` as 0 or 1), and `enabled`
/// (0: the roughness is left as the material gives it).
struct FilterSettings {
    enabled: u32,
    /// `deferred::DOMAIN_*`.
    domain: u32,
    /// `deferred::NORM_*`.
    norm: u32,
    /// `deferred::COMBINE_*`.
    combine: u32,
    scale: f32,
    exponent: f32,
    bias: f32,
    /// The kernel's clamp in `domain` units (`math::F32_MAX`: none).
    clamp: f32,
    perceptual_floor: f32,
    saturate: u32,
}

/// Bevy's smallest perceptual roughness: its lighting clamps `perceptual_roughness` to
/// `[0.089, 1]` after the material's fragment shader (`perceptualRoughnessToRoughness`).
const BEVY_PERCEPTUAL_ROUGHNESS_MIN: f32 = 0.089;

/// The settings as the kernel convention they encode.
fn convention(s: FilterSettings) -> deferred::KernelConvention {
    return deferred::KernelConvention(
        s.domain,
        s.norm,
        s.scale,
        s.exponent,
        s.bias,
        s.clamp,
        s.combine,
        s.saturate != 0u,
        s.perceptual_floor,
    );
}

/// The filtered perceptual roughness `sqrt(alpha_bar)` of Bevy's lobe: `alpha =
/// clamp(perceptual_roughness, 0.089, 1)^2` (the lobe Bevy evaluates), `alpha_bar =
/// deferred::apply(convention(s), alpha, dn_u, dn_v)`, with `dn_u`, `dn_v` the world-space
/// differences of the unit shading normal to the next pixel in x and y (`dpdx`, `dpdy`).
/// Returns `perceptual_roughness` unchanged when `s.enabled == 0`. In `[0, 1]` for finite
/// input (`deferred::apply` keeps `alpha_bar` in `[0, ALPHA_MAX]`).
fn filter_perceptual_roughness(
    s: FilterSettings,
    perceptual_roughness: f32,
    dn_u: vec3<f32>,
    dn_v: vec3<f32>,
) -> f32 {
    if s.enabled == 0u {
        return perceptual_roughness;
    }
    let p = clamp(perceptual_roughness, BEVY_PERCEPTUAL_ROUGHNESS_MIN, 1.0);
    let alpha_bar = deferred::apply(convention(s), p * p, dn_u, dn_v);
    return sqrt(alpha_bar);
}
