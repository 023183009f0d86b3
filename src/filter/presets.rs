//! Published isotropic specular-antialiasing conventions as [`KernelConvention`] values.
//!
//! Each engine ships the same idea (widen the roughness by the screen-space change of the
//! normal) with its own constants and in its own roughness domain. Porting the lines between
//! engines is where they go wrong: a clamp meant for `alpha^2` applied to `alpha`, a variance
//! squared twice. Each preset below states the formula it encodes, the public source file it
//! follows (read for this crate; the code here is written independently), and the engine
//! default it uses. `alpha` is the GGX roughness (`D(0) = 1 / (pi alpha^2)`), `p = sqrt(alpha)`
//! the perceptual roughness, `|dn|` the length of a world-space normal difference per pixel.
//!
//! | preset | domain | kernel | clamp | combine, saturate |
//! |---|---|---|---|---|
//! | [`TK19_TRACE`], [`O3DE`] | `alpha^2` | `0.5 (|dn_u|^2 + |dn_v|^2)` | 0.18 | add, yes |
//! | [`TK19_AVERAGE`] | `alpha^2` | `0.25 (|dn_u|^2 + |dn_v|^2)` | 0.18 | add, yes |
//! | [`TK19_MAX`] | `alpha^2` | `0.5 lambda_max(Gram)` | 0.18 | add, yes |
//! | [`TK21`] | `alpha^2` | `(|dn_u|^2 + |dn_v|^2) / (2 pi)` | 0.18 | add, yes |
//! | [`FILAMENT`] | `alpha^2` | `0.3 (|dn_u|^2 + |dn_v|^2)` | 0.04 | add, yes |
//! | [`UNITY_HDRP`] | `alpha^2` | `0.2 (|dn_u|^2 + |dn_v|^2)` | 0.04 | add, yes |
//! | [`UNITY_HDRP_PROJECTED`] | `alpha^2/(1-alpha^2)` | `0.2 (...)` | 0.04 | add, yes |
//! | [`GODOT`] | `alpha` | `0.5 (|dn_u|^2 + |dn_v|^2)` | 0.18 | add, yes |
//! | [`UNREAL`] | `p` | `max(|dn_u|^2, |dn_v|^2)^0.333` | 1 | max, no |
//! | [`BABYLON`] (Vlachos 2015) | `p` | `max(|dn_u|^2, |dn_v|^2)^0.333` | 1 | max, no |
//! | [`THREE_JS`] | `p` | `max abs component of dn_u, dn_v` | none | add, yes |
//!
//! Where they are wrong against the exact Gaussian filter (measured on a grid with `dn = dh`,
//! `docs/tradeoff.md`, "Where each approximation is wrong"): every preset's `D` errs by more
//! than 10 % once the footprint (the normal's change per pixel) is wider than 0.2 to 0.5 lobe
//! widths, at the peak and in the tails alike (Filament only from 5 lobe widths at the peak;
//! Godot, Unreal and Babylon.js from 0.5 to 1 lobe widths beyond two lobe widths out), by up
//! to 800 % (Godot) to 2900 % (Unreal, Babylon.js, three.js).

use super::super::PI;
use super::F;
use super::deferred::{Bandwidth, Combine, Domain, KernelConvention, Norm};

/// TK19 eq. 4 and Listing 2 (conservative, trace bandwidth):
/// `alpha_bar^2 = saturate(alpha^2 + min(2 sigma^2 (|dn_u|^2 + |dn_v|^2), kappa))` with
/// `sigma^2 = 0.25`, `kappa = 0.18`. Source: Tokuyoshi and Kaplanyan 2019, "Improved
/// Geometric Specular Antialiasing", sect. 4.5.
pub const TK19_TRACE: KernelConvention = Bandwidth::Trace.convention();

/// TK19 eq. 5 (less conservative, average of the eigenvalues): as [`TK19_TRACE`] with
/// kernel `sigma^2 (|dn_u|^2 + |dn_v|^2)` (Listing 2 without the factor 2). TK19 sect. 4.6.
pub const TK19_AVERAGE: KernelConvention = Bandwidth::Average.convention();

/// TK19 eq. 1 (tightest conservative isotropic kernel): kernel `2 lambda_max`, with
/// `lambda_max` the largest eigenvalue of `sigma^2` times the Gram matrix of `dn_u, dn_v`
/// (equal to the footprint covariance's to first order; see
/// [`normal_difference_covariance`](super::deferred::normal_difference_covariance)).
/// TK19 sect. 4.2.
pub const TK19_MAX: KernelConvention = Bandwidth::Max.convention();

/// Tokuyoshi and Kaplanyan 2021, "Stable Geometric Specular Antialiasing with Projected-Space
/// NDF Filtering" (JCGT 10(2)), Listing 5: `alpha_bar^2 = saturate(alpha^2 + min((|dn_u|^2 +
/// |dn_v|^2) / (2 pi), 0.18))`. The pixel-filter variance is `1 / (2 pi)` and there is no
/// factor 2. The constants follow the listing as public HLSL headers reproduce it with
/// attribution (`IsotropicNDFFiltering`, `SIGMA2 = 0.15915494`, `KAPPA = 0.18`); the values
/// are the paper's `1 / (2 pi)` and TK19's `kappa`.
pub const TK21: KernelConvention = KernelConvention {
    scale: 1.0 / (2.0 * PI),
    ..TK19_TRACE
};

/// Filament (google/filament, `shaders/src/shading_lit.fs`, `normalFiltering`): `alpha_bar^2 =
/// saturate(alpha^2 + min(2 variance (|dn_u|^2 + |dn_v|^2), threshold))` on the geometric
/// normal. Defaults `specularAntiAliasingVariance = 0.15` and `specularAntiAliasingThreshold =
/// 0.2` (`libs/filamat/include/filamat/MaterialBuilder.h`); the material instance squares the
/// threshold before upload (`filament/src/details/MaterialInstance.cpp`,
/// `saturate(threshold * threshold)`), so the clamp is `0.04` on `alpha^2`. The perceptual
/// roughness is first clamped to `MIN_PERCEPTUAL_ROUGHNESS = 0.045` (desktop; 0.089 on mobile,
/// `shaders/src/common_material.fs`).
pub const FILAMENT: KernelConvention = KernelConvention {
    domain: Domain::Alpha2,
    norm: Norm::SumSquared,
    scale: 2.0 * 0.15,
    exponent: 1.0,
    bias: 0.0,
    clamp: 0.2 * 0.2,
    combine: Combine::Add,
    saturate: true,
    perceptual_floor: 0.045,
};

/// Unity HDRP (Unity-Technologies/Graphics,
/// `Packages/com.unity.render-pipelines.core/ShaderLibrary/CommonMaterial.hlsl`,
/// `GeometricNormalFiltering` -> `NormalFiltering`): `alpha_bar^2 = saturate(alpha^2 + min(2
/// variance, threshold^2))`, `variance = screenSpaceVariance (|dn_u|^2 + |dn_v|^2)`. Lit
/// defaults `_SpecularAAScreenSpaceVariance = 0.1`, `_SpecularAAThreshold = 0.2` (HDRP
/// `Lit.shader`). This is the path HDRP's `LitData.hlsl` takes by default
/// (`PROJECTED_SPACE_NDF_FILTERING` is commented out there); see [`UNITY_HDRP_PROJECTED`].
pub const UNITY_HDRP: KernelConvention = KernelConvention {
    domain: Domain::Alpha2,
    norm: Norm::SumSquared,
    scale: 2.0 * 0.1,
    exponent: 1.0,
    bias: 0.0,
    clamp: 0.2 * 0.2,
    combine: Combine::Add,
    saturate: true,
    perceptual_floor: 0.0,
};

/// Unity HDRP's projected-space variant (`ProjectedSpaceNormalFiltering` in the same
/// `CommonMaterial.hlsl`, after TK21): the kernel of [`UNITY_HDRP`] is added to
/// `P = alpha^2 / (1 - alpha^2)`, the sum is saturated in that domain, and
/// `alpha_bar^2 = P' / (1 + P')`. Because the saturate acts on `P'`, the result never exceeds
/// `alpha_bar = sqrt(1/2)`. Compiled in only when `PROJECTED_SPACE_NDF_FILTERING` is defined.
pub const UNITY_HDRP_PROJECTED: KernelConvention = KernelConvention {
    domain: Domain::ProjectedAlpha2,
    ..UNITY_HDRP
};

/// Godot 4 screen-space roughness limiter (godotengine/godot,
/// `servers/rendering/renderer_rd/shaders/forward_clustered/scene_forward_clustered.glsl`):
/// with `r` Godot's roughness (perceptual, `alpha = r^2`), `r'^2 = min(1, r^2 + min(2 amount
/// (|dn_u|^2 + |dn_v|^2), limit))`. The TK19 formula, but added to `r^2 = alpha` instead of
/// `alpha^2`. Defaults `rendering/anti_aliasing/screen_space_roughness_limiter/amount = 0.25`,
/// `limit = 0.18` (`servers/rendering_server.cpp`).
pub const GODOT: KernelConvention = KernelConvention {
    domain: Domain::Alpha,
    norm: Norm::SumSquared,
    scale: 2.0 * 0.25,
    exponent: 1.0,
    bias: 0.0,
    clamp: 0.18,
    combine: Combine::Add,
    saturate: true,
    perceptual_floor: 0.0,
};

/// O3DE (o3de/o3de,
/// `Gems/Atom/Feature/Common/Assets/ShaderLib/Atom/Features/PBR/SpecularAA.azsli`,
/// `CalculateSpecularAA`): TK19 Listing 2 verbatim on `alpha^2` (`screenVariance = 0.25`,
/// `varianceThresh = 0.18`, factor 2, saturate); identical to [`TK19_TRACE`].
pub const O3DE: KernelConvention = TK19_TRACE;

/// Unreal Engine `NormalCurvatureToRoughness` (material option "Normal Curvature to
/// Roughness"): `k = saturate(scale max(|dn_x|^2, |dn_y|^2)^exponent + bias)` and
/// `GBuffer.Roughness = max(GBuffer.Roughness, k)` on the perceptual roughness. Defaults
/// `r.NormalCurvatureToRoughnessScale = 1`, `...Bias = 0`, `...Exponent = 0.333`, checked in a
/// public UE4 fork (JimmieKJ/unrealTournament,
/// `Engine/Source/Runtime/Renderer/Private/SceneRendering.cpp`). Epic's own repository is not
/// public; the shader body (in `BasePassPixelShader.usf`, later `MaterialTemplate.ush`) is
/// followed as secondary reproductions give it.
pub const UNREAL: KernelConvention = KernelConvention {
    domain: Domain::Perceptual,
    norm: Norm::MaxSquared,
    scale: 1.0,
    exponent: 0.333,
    bias: 0.0,
    clamp: 1.0,
    combine: Combine::Max,
    saturate: false,
    perceptual_floor: 0.0,
};

/// Babylon.js, after Vlachos 2015 ("Advanced VR Rendering", GDC; quoted in the GDC 2016 talk
/// as `r = max(r, cbrt(max(|dn_x|^2, |dn_y|^2)))`): `getAARoughnessFactors` in
/// BabylonJS/Babylon.js `packages/dev/core/src/Shaders/ShadersInclude/pbrHelperFunctions.fx`
/// computes `pow(saturate(max(|dn_x|^2, |dn_y|^2)), 0.333)`, and `computeSpecularLighting`
/// (`pbrDirectLightingFunctions.fx`) takes `max` with the perceptual roughness before
/// `alphaG = r^2 + 0.0005`. This preset is the analytic-light path; the `+0.0005` is not part
/// of the convention and is omitted. Babylon's environment path instead adds `0.75
/// sqrt(max(|dn_x|^2, |dn_y|^2))` to `alphaG`; not a preset here.
pub const BABYLON: KernelConvention = UNREAL;

/// three.js (mrdoob/three.js,
/// `src/renderers/shaders/ShaderChunk/lights_physical_fragment.glsl.js`): `geometryRoughness =
/// max` over components of `max(|dFdx(n)|, |dFdy(n)|)`; `r' = min(max(r, 0.0525) +
/// geometryRoughness, 1)` on the perceptual roughness (`alpha = r'^2`). The floor 0.0525 is
/// "the base mip of a 256 cubemap". The norm is not squared and depends on the world axes.
pub const THREE_JS: KernelConvention = KernelConvention {
    domain: Domain::Perceptual,
    norm: Norm::MaxAbsComponent,
    scale: 1.0,
    exponent: 1.0,
    bias: 0.0,
    clamp: F::INFINITY,
    combine: Combine::Add,
    saturate: true,
    perceptual_floor: 0.0525,
};

/// Every preset with its name, for tables and tests.
pub const ALL: [(&str, KernelConvention); 12] = [
    ("TK19 max (eq. 1)", TK19_MAX),
    ("TK19 trace (eq. 4)", TK19_TRACE),
    ("TK19 average (eq. 5)", TK19_AVERAGE),
    ("TK21 listing 5", TK21),
    ("Filament", FILAMENT),
    ("Unity HDRP", UNITY_HDRP),
    ("Unity HDRP projected", UNITY_HDRP_PROJECTED),
    ("Godot 4", GODOT),
    ("O3DE", O3DE),
    ("Unreal", UNREAL),
    ("Babylon.js (Vlachos 2015)", BABYLON),
    ("three.js", THREE_JS),
];
