//! [`FilteredNdfExtension`]: the per-material knobs of the roughness filter, and
//! [`FilteredNdfMaterial`], `StandardMaterial` extended by them.

use crate::moments::MomentImages;
use crate::plugin::MATERIAL_SHADER;
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{
    ExtendedMaterial, MaterialExtension, MaterialExtensionKey, MaterialExtensionPipeline,
};
use bevy::prelude::*;
use bevy::render::render_resource::{
    AsBindGroup, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError,
};
use bevy::shader::ShaderRef;
use filtered_ndf::f32::filter::deferred::{Combine, Domain, KernelConvention, Norm};
use filtered_ndf::f32::filter::presets;
use filtered_ndf::f32::kernel::SIGMA_PIXEL;

/// The standard deviation of a one-pixel box filter, `1 / sqrt(12)` pixels: the pixel
/// filter of an image supersampled on a regular grid and averaged (Bevy's MSAA resolve, or
/// rendering larger and box-downsampling), as [`FilteredNdfExtension::sigma`].
pub const SIGMA_BOX_PIXEL: f32 = 0.288_675_13;

/// `StandardMaterial` with its roughness filtered before lighting (see
/// [`FilteredNdfExtension`]).
pub type FilteredNdfMaterial = ExtendedMaterial<StandardMaterial, FilteredNdfExtension>;

/// Which published convention widens the roughness (`filtered_ndf::f32::filter::presets`,
/// whose docs give each formula, source and engine default), or none.
///
/// All widen by the screen-space differences `dn_u`, `dn_v` of the normal-mapped shading
/// normal; they differ in the measure of the differences, the factor, the clamp and the
/// roughness domain they add in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Reflect)]
pub enum RoughnessFilter {
    /// No filtering: the material's roughness as given (Bevy's `StandardMaterial`).
    Off,
    /// TK19 eq. 1: `alpha^2 + min(0.5 lambda_max(Gram(dn_u, dn_v)), 0.18)`.
    Tk19Max,
    /// TK19 eq. 4, Listing 2: `alpha^2 + min(0.5 (|dn_u|^2 + |dn_v|^2), 0.18)` (the default).
    #[default]
    Tk19Trace,
    /// TK19 eq. 5: `alpha^2 + min(0.25 (|dn_u|^2 + |dn_v|^2), 0.18)`.
    Tk19Average,
    /// Tokuyoshi and Kaplanyan 2021, Listing 5: `alpha^2 + min((|dn_u|^2 + |dn_v|^2) / (2 pi),
    /// 0.18)`.
    Tk21,
    /// Filament: `alpha^2 + min(0.3 (...), 0.04)`, perceptual roughness floor 0.045.
    Filament,
    /// Unity HDRP: `alpha^2 + min(0.2 (...), 0.04)`.
    UnityHdrp,
    /// Unity HDRP projected space (after TK21): as [`Self::UnityHdrp`] in `alpha^2 / (1 -
    /// alpha^2)`.
    UnityHdrpProjected,
    /// Godot 4: TK19's kernel added to `alpha`.
    Godot,
    /// O3DE: TK19 Listing 2 (the same convention as [`Self::Tk19Trace`]).
    O3de,
    /// Unreal: `max(p, max(|dn_u|^2, |dn_v|^2)^0.333)` on the perceptual roughness `p`.
    Unreal,
    /// Babylon.js (Vlachos 2015): the same convention as [`Self::Unreal`].
    Babylon,
    /// three.js: `max(p, 0.0525) +` the largest absolute component of `dn_u`, `dn_v`.
    ThreeJs,
}

impl RoughnessFilter {
    /// Every filter, [`Self::Off`] first.
    pub const ALL: [Self; 13] = [
        Self::Off,
        Self::Tk19Max,
        Self::Tk19Trace,
        Self::Tk19Average,
        Self::Tk21,
        Self::Filament,
        Self::UnityHdrp,
        Self::UnityHdrpProjected,
        Self::Godot,
        Self::O3de,
        Self::Unreal,
        Self::Babylon,
        Self::ThreeJs,
    ];

    /// The kernel convention of the preset (`None` for [`Self::Off`]).
    pub fn convention(self) -> Option<KernelConvention> {
        Some(match self {
            Self::Off => return None,
            Self::Tk19Max => presets::TK19_MAX,
            Self::Tk19Trace => presets::TK19_TRACE,
            Self::Tk19Average => presets::TK19_AVERAGE,
            Self::Tk21 => presets::TK21,
            Self::Filament => presets::FILAMENT,
            Self::UnityHdrp => presets::UNITY_HDRP,
            Self::UnityHdrpProjected => presets::UNITY_HDRP_PROJECTED,
            Self::Godot => presets::GODOT,
            Self::O3de => presets::O3DE,
            Self::Unreal => presets::UNREAL,
            Self::Babylon => presets::BABYLON,
            Self::ThreeJs => presets::THREE_JS,
        })
    }

    /// A short label for tables.
    pub fn label(self) -> &'static str {
        match self {
            Self::Off => "off",
            Self::Tk19Max => "TK19 max (eq. 1)",
            Self::Tk19Trace => "TK19 trace (eq. 4)",
            Self::Tk19Average => "TK19 average (eq. 5)",
            Self::Tk21 => "TK21 listing 5",
            Self::Filament => "Filament",
            Self::UnityHdrp => "Unity HDRP",
            Self::UnityHdrpProjected => "Unity HDRP projected",
            Self::Godot => "Godot 4",
            Self::O3de => "O3DE",
            Self::Unreal => "Unreal",
            Self::Babylon => "Babylon.js",
            Self::ThreeJs => "three.js",
        }
    }
}

/// The knobs of the roughness filter, per material: the extension of
/// [`FilteredNdfMaterial`], and optionally the normal map's baked LEAN moment chain.
///
/// **Without moments** (the default), the fragment shader (`src/shaders/material.wgsl`) takes
/// the screen-space differences `dn_u = dpdxFine(N)`, `dn_v = dpdyFine(N)` of the
/// normal-mapped world normal `N` and replaces the perceptual roughness `p` by
/// `sqrt(alpha_bar)`, `alpha_bar` the [`filter`](Self::filter)'s convention applied to `alpha
/// = clamp(p, 0.089, 1)^2` with the kernel scaled for [`sigma`](Self::sigma) and clamped at
/// [`kappa`](Self::kappa); the clear coat's roughness likewise with its own normal. Bevy's
/// lighting then evaluates its GGX lobe with the filtered roughness (forward), or the G-buffer
/// stores it (deferred).
///
/// **With moments** ([`Self::with_moments`]: both [`moments`](Self::moments) and
/// [`moments_xy`](Self::moments_xy) set, the shader def `FILTERED_NDF_MOMENTS`), for a mesh
/// with UVs and tangents, the normal map's detail comes from the moments instead of from the
/// differences of the normal-mapped normal (LEAN mapping, Olano and Baker 2010; KHPL16 section
/// 5.5, eq. 21):
/// 1. both textures are fetched at the normal map's UV (`uv_transform` applied; `uv_b` where
///    the normal map uses it) with `textureSampleGrad` and the UV's screen derivatives (scaled
///    by the view's mip bias, as Bevy fetches the normal map): the hardware's trilinear
///    filter averages the moments over the pixel's footprint (WGSL `bake::moments`);
/// 2. the shading normal is the mean slope's, `normalize(-E[s_x], -E[s_y], 1)`
///    (`lean_nested::lean_mean_normal`), through Bevy's own normal mapping (its TBN,
///    `flip_normal_map_y`, double-sidedness), in place of the normal-map sample;
/// 3. the material's lobe is widened by the texel's slope covariance `Sigma_L = E[s s^T] -
///    E[s] E[s]^T` (`lean_nested::lean_widened`: `A_L = alpha^2 I + 2 Sigma_L`, KHPL16 eq.
///    21), made isotropic for Bevy's lobe by its trace: `alpha_L^2 = alpha^2 + tr(Sigma_L)`
///    (the mean of `A_L`'s eigenvalues, keeping the lobe's total slope variance);
/// 4. the derivative filter is applied to `alpha_L` with the differences of the *geometric*
///    (interpolated vertex) normal, not of the normal-mapped one: the normal map's detail is
///    already in `Sigma_L`, and counting it again from its differences would widen twice.
///    On a flat surface the derivative term is zero and the lobe is LEAN's alone; on a curved
///    one it adds the curvature's spread across the pixel. `kappa` bounds only this
///    derivative term, never `Sigma_L` (the texel's measured distribution, not an estimate).
///
/// [`RoughnessFilter::Off`] leaves the material as `StandardMaterial` renders it, moments or
/// not. The clear coat is filtered from its own normal's differences in both cases.
///
/// The default is TK19's trace kernel as published, without moments: `alpha_bar^2 =
/// min(alpha^2 + min(0.5 (|dn_u|^2 + |dn_v|^2), 0.18), 1)`.
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone, PartialEq)]
#[uniform(100, FilteredNdfUniform)]
#[bind_group_data(FilteredNdfKey)]
pub struct FilteredNdfExtension {
    /// The convention ([`RoughnessFilter::Off`]: the roughness as the material gives it).
    pub filter: RoughnessFilter,
    /// The standard deviation of the pixel filter the kernel is built for, in pixels. Each
    /// convention's kernel is a variance, proportional to `sigma^2` (TK19 eq. 4's factor `2
    /// sigma^2`), so the kernel is the preset's times `(sigma / 0.5)^2`: the default 0.5
    /// (TK19's `sigma^2 = 1/4`) keeps every preset as its source publishes it. (For Unreal,
    /// Babylon.js and three.js, whose kernels are not variances, the same factor multiplies
    /// their kernel.) A negative or NaN `sigma` counts as 0: no widening from the
    /// derivatives, the preset's roughness floor alone.
    pub sigma: f32,
    /// The clamp of the kernel in the convention's domain units (TK19's `kappa`, 0.18 in
    /// `alpha^2`), bounding the widening where the differences are large (silhouettes,
    /// discontinuities). `None`: the preset's own. A negative value counts as 0 (no
    /// widening), NaN as `None`.
    pub kappa: Option<f32>,
    /// The moment texture `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])` of the normal map
    /// (`Rgba16Float`, or `Rgba32Float` where the device filters it, with its mip chain;
    /// [`crate::moment_images`]). Its sampler samples both moment textures.
    #[texture(101)]
    #[sampler(102)]
    pub moments: Option<Handle<Image>>,
    /// The moment texture `E[s_x s_y]` (`R16Float`, or `R32Float` where the device filters it;
    /// the same size and mips as [`Self::moments`]).
    #[texture(103)]
    pub moments_xy: Option<Handle<Image>>,
}

/// The pipeline key of [`FilteredNdfExtension`]: whether its moment chain is bound (both
/// textures set), which defines `FILTERED_NDF_MOMENTS` in the fragment shader.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FilteredNdfKey {
    /// Both moment textures are set.
    pub moments: bool,
}

impl From<&FilteredNdfExtension> for FilteredNdfKey {
    fn from(e: &FilteredNdfExtension) -> Self {
        Self {
            moments: e.moments.is_some() && e.moments_xy.is_some(),
        }
    }
}

/// The shader def of a material with its moment chain bound.
pub const MOMENTS_SHADER_DEF: &str = "FILTERED_NDF_MOMENTS";

impl Default for FilteredNdfExtension {
    fn default() -> Self {
        Self::new(RoughnessFilter::default())
    }
}

impl FilteredNdfExtension {
    /// `filter` as published: `sigma = 0.5`, the preset's `kappa`.
    pub fn new(filter: RoughnessFilter) -> Self {
        Self {
            filter,
            sigma: SIGMA_PIXEL,
            kappa: None,
            moments: None,
            moments_xy: None,
        }
    }

    /// With the pixel filter's standard deviation `sigma` (see [`Self::sigma`]).
    pub fn with_sigma(self, sigma: f32) -> Self {
        Self { sigma, ..self }
    }

    /// With the clamp `kappa` (see [`Self::kappa`]).
    pub fn with_kappa(self, kappa: f32) -> Self {
        Self {
            kappa: Some(kappa),
            ..self
        }
    }

    /// With the normal map's moment chain: `moments` and `moments_xy` the handles of a
    /// [`MomentImages`]' two images added to `Assets<Image>` (see the type docs for what the
    /// shader does with them). The chain must be the moments of the material's
    /// `normal_map_texture`, sampled at its UV.
    pub fn with_moments(self, moments: Handle<Image>, moments_xy: Handle<Image>) -> Self {
        Self {
            moments: Some(moments),
            moments_xy: Some(moments_xy),
            ..self
        }
    }

    /// With the moment chain `images`, added to `assets` ([`Self::with_moments`]).
    pub fn with_moment_images(self, images: MomentImages, assets: &mut Assets<Image>) -> Self {
        let moments = assets.add(images.moments);
        let moments_xy = assets.add(images.moments_xy);
        self.with_moments(moments, moments_xy)
    }
}

impl MaterialExtension for FilteredNdfExtension {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(MATERIAL_SHADER)
    }

    fn deferred_fragment_shader() -> ShaderRef {
        ShaderRef::Handle(MATERIAL_SHADER)
    }

    fn specialize(
        _pipeline: &MaterialExtensionPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        _layout: &MeshVertexBufferLayoutRef,
        key: MaterialExtensionKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        if key.bind_group_data.moments
            && let Some(fragment) = descriptor.fragment.as_mut()
        {
            fragment.shader_defs.push(MOMENTS_SHADER_DEF.into());
        }
        Ok(())
    }
}

/// The uniform the fragment shader reads (`FilterSettings` in `filtered_ndf_bevy::roughness`):
/// a `KernelConvention` with its enumerations as the WGSL module `filter::deferred`'s `u32`
/// constants, `clamp` finite (`f32::MAX` for none), and `enabled` 0 for
/// [`RoughnessFilter::Off`].
#[derive(Clone, Copy, Debug, Default, PartialEq, ShaderType)]
pub struct FilteredNdfUniform {
    /// 1: filter; 0: leave the roughness.
    pub enabled: u32,
    /// `DOMAIN_ALPHA_SQ` 0, `DOMAIN_ALPHA` 1, `DOMAIN_PERCEPTUAL` 2,
    /// `DOMAIN_PROJECTED_ALPHA_SQ` 3.
    pub domain: u32,
    /// `NORM_SUM_SQUARED` 0, `NORM_MAX_SQUARED` 1, `NORM_MAX_EIGENVALUE` 2,
    /// `NORM_MAX_ABS_COMPONENT` 3.
    pub norm: u32,
    /// `COMBINE_ADD` 0, `COMBINE_MAX` 1.
    pub combine: u32,
    /// The factor on `norm^exponent`, `sigma` included (finite, `>= 0`).
    pub scale: f32,
    /// The exponent on the norm.
    pub exponent: f32,
    /// Added after scaling.
    pub bias: f32,
    /// The kernel's clamp in domain units (finite, `>= 0`).
    pub clamp: f32,
    /// The minimum perceptual roughness enforced first.
    pub perceptual_floor: f32,
    /// 1: `min(v', 1)` after combining.
    pub saturate: u32,
}

/// The WGSL `deferred::DOMAIN_*` value of `d`.
fn domain_index(d: Domain) -> u32 {
    match d {
        Domain::Alpha2 => 0,
        Domain::Alpha => 1,
        Domain::Perceptual => 2,
        Domain::ProjectedAlpha2 => 3,
    }
}

/// The WGSL `deferred::NORM_*` value of `n`.
fn norm_index(n: Norm) -> u32 {
    match n {
        Norm::SumSquared => 0,
        Norm::MaxSquared => 1,
        Norm::MaxEigenvalue => 2,
        Norm::MaxAbsComponent => 3,
    }
}

/// The WGSL `deferred::COMBINE_*` value of `c`.
fn combine_index(c: Combine) -> u32 {
    match c {
        Combine::Add => 0,
        Combine::Max => 1,
    }
}

/// `x` if finite, else `f32::MAX` (WGSL has no infinity to compare with reliably).
fn finite_or_max(x: f32) -> f32 {
    if x.is_finite() { x } else { f32::MAX }
}

impl From<&FilteredNdfExtension> for FilteredNdfUniform {
    fn from(e: &FilteredNdfExtension) -> Self {
        let Some(c) = e.filter.convention() else {
            return Self::default();
        };
        let sigma = if e.sigma.is_nan() {
            0.0
        } else {
            e.sigma.max(0.0)
        };
        let width = sigma / SIGMA_PIXEL;
        let clamp = match e.kappa {
            Some(k) if !k.is_nan() => k.max(0.0),
            _ => c.clamp,
        };
        Self {
            enabled: 1,
            domain: domain_index(c.domain),
            norm: norm_index(c.norm),
            combine: combine_index(c.combine),
            scale: finite_or_max(c.scale * width * width),
            exponent: c.exponent,
            bias: c.bias,
            clamp: finite_or_max(clamp),
            perceptual_floor: c.perceptual_floor,
            saturate: u32::from(c.saturate),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wgsl::MODULES;

    /// The value of `const NAME: u32 = Nu;` in the WGSL module `import_path`.
    fn wgsl_u32(import_path: &str, name: &str) -> u32 {
        let m = MODULES
            .iter()
            .find(|m| m.import_path == import_path)
            .expect("the module is in the list");
        let prefix = format!("const {name}: u32 = ");
        let line = m
            .source
            .lines()
            .find_map(|l| l.trim().strip_prefix(prefix.as_str()))
            .unwrap_or_else(|| panic!("{name} is declared in {import_path}"));
        line.trim_end_matches(';')
            .trim_end_matches('u')
            .parse()
            .expect("a u32 literal")
    }

    #[test]
    fn enumerations_match_the_wgsl_constants() {
        let d = "filtered_ndf::filter::deferred";
        for (v, name) in [
            (Domain::Alpha2, "DOMAIN_ALPHA_SQ"),
            (Domain::Alpha, "DOMAIN_ALPHA"),
            (Domain::Perceptual, "DOMAIN_PERCEPTUAL"),
            (Domain::ProjectedAlpha2, "DOMAIN_PROJECTED_ALPHA_SQ"),
        ] {
            assert_eq!(domain_index(v), wgsl_u32(d, name), "{name}");
        }
        for (v, name) in [
            (Norm::SumSquared, "NORM_SUM_SQUARED"),
            (Norm::MaxSquared, "NORM_MAX_SQUARED"),
            (Norm::MaxEigenvalue, "NORM_MAX_EIGENVALUE"),
            (Norm::MaxAbsComponent, "NORM_MAX_ABS_COMPONENT"),
        ] {
            assert_eq!(norm_index(v), wgsl_u32(d, name), "{name}");
        }
        for (v, name) in [(Combine::Add, "COMBINE_ADD"), (Combine::Max, "COMBINE_MAX")] {
            assert_eq!(combine_index(v), wgsl_u32(d, name), "{name}");
        }
    }

    #[test]
    fn the_uniform_struct_matches_the_wgsl_settings() {
        // The field names of `FilterSettings` in roughness.wgsl, in order, against the Rust
        // struct's (the ShaderType layout follows the declaration order on both sides).
        let src = include_str!("shaders/roughness.wgsl");
        let body = src
            .split("struct FilterSettings {")
            .nth(1)
            .and_then(|s| s.split('}').next())
            .expect("roughness.wgsl declares FilterSettings");
        let wgsl: Vec<&str> = body
            .lines()
            .map(str::trim)
            .filter(|l| !l.starts_with("//") && l.contains(':'))
            .map(|l| l.split(':').next().unwrap_or("").trim())
            .collect();
        let rust = [
            "enabled",
            "domain",
            "norm",
            "combine",
            "scale",
            "exponent",
            "bias",
            "clamp",
            "perceptual_floor",
            "saturate",
        ];
        assert_eq!(wgsl, rust);
        // Every Rust field is named above (a struct literal fails to compile otherwise).
        let FilteredNdfUniform {
            enabled: _,
            domain: _,
            norm: _,
            combine: _,
            scale: _,
            exponent: _,
            bias: _,
            clamp: _,
            perceptual_floor: _,
            saturate: _,
        } = FilteredNdfUniform::default();
    }

    #[test]
    fn presets_as_published_at_the_default_sigma() {
        for f in RoughnessFilter::ALL {
            let u = FilteredNdfUniform::from(&FilteredNdfExtension::new(f));
            let Some(c) = f.convention() else {
                assert_eq!(u, FilteredNdfUniform::default());
                assert_eq!(u.enabled, 0);
                continue;
            };
            assert_eq!(u.enabled, 1);
            // sigma / SIGMA_PIXEL = 1 exactly: the scale is the preset's bit for bit.
            assert_eq!(u.scale, c.scale, "{}", f.label());
            assert_eq!(u.exponent, c.exponent);
            assert_eq!(u.bias, c.bias);
            assert_eq!(u.perceptual_floor, c.perceptual_floor);
            assert_eq!(u.saturate, u32::from(c.saturate));
            let clamp = if c.clamp.is_finite() {
                c.clamp
            } else {
                f32::MAX
            };
            assert_eq!(u.clamp, clamp, "{}", f.label());
        }
        // TK19 Listing 2: 2 sigma^2 = 0.5, kappa = 0.18.
        let u = FilteredNdfUniform::from(&FilteredNdfExtension::default());
        assert_eq!((u.scale, u.clamp, u.domain, u.norm), (0.5, 0.18, 0, 0));
    }

    #[test]
    fn sigma_scales_the_kernel_as_a_variance() {
        let e = FilteredNdfExtension::new(RoughnessFilter::Tk19Trace);
        // (1 / 0.5)^2 = 4 and (0.25 / 0.5)^2 = 1/4, exact in binary.
        assert_eq!(
            FilteredNdfUniform::from(&e.clone().with_sigma(1.0)).scale,
            2.0
        );
        assert_eq!(
            FilteredNdfUniform::from(&e.clone().with_sigma(0.25)).scale,
            0.125
        );
        for bad in [-1.0, f32::NAN, -0.0] {
            assert_eq!(
                FilteredNdfUniform::from(&e.clone().with_sigma(bad)).scale,
                0.0
            );
        }
        // An infinite or overflowing width gives the largest finite scale, not infinity.
        for big in [f32::INFINITY, 1e30] {
            assert_eq!(
                FilteredNdfUniform::from(&e.clone().with_sigma(big)).scale,
                f32::MAX
            );
        }
    }

    #[test]
    fn the_box_filter_sigma_is_one_over_root_twelve() {
        // Closed form: the variance of the uniform distribution on [-1/2, 1/2] is 1/12.
        let exact = (1.0f64 / 12.0).sqrt();
        assert!(
            (f64::from(SIGMA_BOX_PIXEL) - exact).abs() <= 0.5 * f64::from(f32::EPSILON) * exact
        );
    }

    #[test]
    fn the_moment_chain_needs_both_textures() {
        let e = FilteredNdfExtension::default();
        assert_eq!(FilteredNdfKey::from(&e), FilteredNdfKey { moments: false });
        let (a, b) = (Handle::<Image>::default(), Handle::<Image>::default());
        let both = e.clone().with_moments(a.clone(), b);
        assert_eq!(
            FilteredNdfKey::from(&both),
            FilteredNdfKey { moments: true }
        );
        let one = FilteredNdfExtension {
            moments: Some(a),
            ..e
        };
        assert_eq!(
            FilteredNdfKey::from(&one),
            FilteredNdfKey { moments: false }
        );
        // The uniform does not depend on the textures.
        assert_eq!(
            FilteredNdfUniform::from(&both),
            FilteredNdfUniform::from(&FilteredNdfExtension::default())
        );
    }

    #[test]
    fn the_shaders_call_functions_the_crate_exports() {
        // Every `module::function(` the plugin's WGSL calls from the crate's modules exists in
        // that module's source (a renamed or removed function fails here, not at the first
        // pipeline compile).
        let lean_src = include_str!("shaders/lean.wgsl");
        let material_src = include_str!("shaders/material.wgsl");
        for (path, name, caller) in [
            (
                "filtered_ndf::filter::lean_nested",
                "lean_widened",
                lean_src,
            ),
            (
                "filtered_ndf::filter::lean_nested",
                "lean_mean_normal",
                lean_src,
            ),
            (
                "filtered_ndf::ndf::roughness::isotropic",
                "to_matrix",
                lean_src,
            ),
            (
                "filtered_ndf::ndf::roughness::isotropic",
                "from_alpha",
                lean_src,
            ),
            ("filtered_ndf::ndf::roughness::matrix", "entries", lean_src),
            ("filtered_ndf::bake::moments", "sample_grad", material_src),
        ] {
            let module = MODULES
                .iter()
                .find(|m| m.import_path == path)
                .unwrap_or_else(|| panic!("{path} is a module of the crate"));
            let short = path.rsplit("::").next().unwrap_or(path);
            assert!(
                caller.contains(&format!("{short}::{name}(")),
                "the plugin calls {short}::{name}"
            );
            assert!(
                module.source.contains(&format!("fn {name}(")),
                "{path} defines {name}"
            );
        }
    }

    #[test]
    fn kappa_overrides_the_clamp() {
        // Filament's clamp is its `specularAntiAliasingThreshold` 0.2 squared, in f32.
        let filament_clamp = 0.2f32 * 0.2;
        let e = FilteredNdfExtension::new(RoughnessFilter::Filament);
        assert_eq!(FilteredNdfUniform::from(&e).clamp, filament_clamp);
        assert_eq!(
            FilteredNdfUniform::from(&e.clone().with_kappa(0.1)).clamp,
            0.1
        );
        assert_eq!(
            FilteredNdfUniform::from(&e.clone().with_kappa(-3.0)).clamp,
            0.0
        );
        assert_eq!(
            FilteredNdfUniform::from(&e.clone().with_kappa(f32::NAN)).clamp,
            filament_clamp
        );
        assert_eq!(
            FilteredNdfUniform::from(&e.clone().with_kappa(f32::INFINITY)).clamp,
            f32::MAX
        );
        // three.js has no clamp: the largest finite value stands for none.
        let t = FilteredNdfExtension::new(RoughnessFilter::ThreeJs);
        assert_eq!(FilteredNdfUniform::from(&t).clamp, f32::MAX);
    }
}
