#define_import_path filtered_ndf::filter::presets

#import filtered_ndf::math
#import filtered_ndf::filter::deferred

// The published isotropic specular-antialiasing conventions as `deferred::KernelConvention`
// values, mirroring `src/.../filter/presets.rs` (whose docs give each source, formula and
// engine default). `alpha` is the GGX roughness, `p = sqrt(alpha)` the perceptual one.
// Names that would end in a digit carry a suffix (naga renames such identifiers).
//
// | preset | domain | kernel | clamp | combine, saturate |
// |---|---|---|---|---|
// | TK19_TRACE, O3DE | alpha^2 | 0.5 (|dn_u|^2 + |dn_v|^2) | 0.18 | add, yes |
// | TK19_AVERAGE | alpha^2 | 0.25 (...) | 0.18 | add, yes |
// | TK19_MAX | alpha^2 | 0.5 lambda_max(Gram) | 0.18 | add, yes |
// | TK21_LISTING | alpha^2 | (...) / (2 pi) | 0.18 | add, yes |
// | FILAMENT | alpha^2 | 0.3 (...), perceptual floor 0.045 | 0.04 | add, yes |
// | UNITY_HDRP | alpha^2 | 0.2 (...) | 0.04 | add, yes |
// | UNITY_HDRP_PROJECTED | alpha^2 / (1 - alpha^2) | 0.2 (...) | 0.04 | add, yes |
// | GODOT | alpha | 0.5 (...) | 0.18 | add, yes |
// | UNREAL, BABYLON | p | max(|dn_u|^2, |dn_v|^2)^0.333 | 1 | max, no |
// | THREE_JS | p | max abs component, floor 0.0525 | none | add, yes |

/// TK19 eq. 4 and Listing 2 (trace bandwidth): `saturate(alpha^2 + min(0.5 (|dn_u|^2 +
/// |dn_v|^2), 0.18))`.
const TK19_TRACE: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.5,
    1.0,
    0.0,
    0.18,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// TK19 eq. 5 (average of the eigenvalues): kernel `0.25 (|dn_u|^2 + |dn_v|^2)`.
const TK19_AVERAGE: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.25,
    1.0,
    0.0,
    0.18,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// TK19 eq. 1 (tightest conservative isotropic kernel): `0.5 lambda_max` of the Gram matrix.
const TK19_MAX: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_MAX_EIGENVALUE,
    0.5,
    1.0,
    0.0,
    0.18,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// Tokuyoshi and Kaplanyan 2021, Listing 5: `saturate(alpha^2 + min((|dn_u|^2 +
/// |dn_v|^2) / (2 pi), 0.18))`.
const TK21_LISTING: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.159154943091895,
    1.0,
    0.0,
    0.18,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// Filament `normalFiltering`: variance 0.15 (kernel `0.3 (...)`), threshold `0.2^2`,
/// perceptual roughness floor 0.045.
const FILAMENT: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.3,
    1.0,
    0.0,
    0.04,
    deferred::COMBINE_ADD,
    true,
    0.045,
);
/// Unity HDRP `NormalFiltering`: screen-space variance 0.1 (kernel `0.2 (...)`),
/// threshold `0.2^2`.
const UNITY_HDRP: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.2,
    1.0,
    0.0,
    0.04,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// Unity HDRP `ProjectedSpaceNormalFiltering` (after TK21): [`UNITY_HDRP`] in the domain
/// `alpha^2 / (1 - alpha^2)`.
const UNITY_HDRP_PROJECTED: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_PROJECTED_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.2,
    1.0,
    0.0,
    0.04,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// Godot 4 screen-space roughness limiter: TK19's formula on `alpha` (amount 0.25, limit
/// 0.18).
const GODOT: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA,
    deferred::NORM_SUM_SQUARED,
    0.5,
    1.0,
    0.0,
    0.18,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// O3DE `CalculateSpecularAA`: TK19 Listing 2 verbatim, identical to [`TK19_TRACE`].
const O3DE: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_ALPHA_SQ,
    deferred::NORM_SUM_SQUARED,
    0.5,
    1.0,
    0.0,
    0.18,
    deferred::COMBINE_ADD,
    true,
    0.0,
);
/// Unreal `NormalCurvatureToRoughness`: `max(p, max(|dn_x|^2, |dn_y|^2)^0.333)`.
const UNREAL: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_PERCEPTUAL,
    deferred::NORM_MAX_SQUARED,
    1.0,
    0.333,
    0.0,
    1.0,
    deferred::COMBINE_MAX,
    false,
    0.0,
);
/// Babylon.js (Vlachos 2015), the analytic-light path: as [`UNREAL`].
const BABYLON: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_PERCEPTUAL,
    deferred::NORM_MAX_SQUARED,
    1.0,
    0.333,
    0.0,
    1.0,
    deferred::COMBINE_MAX,
    false,
    0.0,
);
/// three.js: `min(max(p, 0.0525) + max abs component of dn, 1)` on the perceptual roughness.
const THREE_JS: deferred::KernelConvention = deferred::KernelConvention(
    deferred::DOMAIN_PERCEPTUAL,
    deferred::NORM_MAX_ABS_COMPONENT,
    1.0,
    1.0,
    0.0,
    math::F32_MAX,
    deferred::COMBINE_ADD,
    true,
    0.0525,
);

/// Every preset, in the order of the Rust `presets::ALL`: TK19 max, trace, average, TK21,
/// Filament, Unity HDRP, Unity HDRP projected, Godot, O3DE, Unreal, Babylon.js, three.js.
fn preset(i: u32) -> deferred::KernelConvention {
    switch i {
        case 0u: { return TK19_MAX; }
        case 1u: { return TK19_TRACE; }
        case 2u: { return TK19_AVERAGE; }
        case 3u: { return TK21_LISTING; }
        case 4u: { return FILAMENT; }
        case 5u: { return UNITY_HDRP; }
        case 6u: { return UNITY_HDRP_PROJECTED; }
        case 7u: { return GODOT; }
        case 8u: { return O3DE; }
        case 9u: { return UNREAL; }
        case 10u: { return BABYLON; }
        default: { return THREE_JS; }
    }
}
