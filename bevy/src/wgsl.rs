//! STAND-IN, TO BE REPLACED by the `filtered-ndf-wgsl` crate (`shaders/Cargo.toml`, being made
//! publishable on another branch): once `main` has it, depend on it and replace this module by
//! `pub use filtered_ndf_wgsl::{MODULES, Module};`. It has the same shape: every WGSL module of
//! the repository's `shaders/` tree with its naga_oil import path, file and source, each after
//! the modules it imports. The sources are `include_str!`ed from outside this package, which
//! `cargo package` does not keep; this crate is not published.

/// One WGSL module.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Module {
    /// Its import path, the argument of its `#define_import_path` (`filtered_ndf::ndf::ggx`).
    pub import_path: &'static str,
    /// Its file, relative to `shaders/` with `/` separators (`ndf/ggx.wgsl`).
    pub file: &'static str,
    /// Its WGSL source.
    pub source: &'static str,
}

/// Declares one [`Module`] of `shaders/`.
macro_rules! module {
    ($path:literal, $file:literal) => {
        Module {
            import_path: $path,
            file: $file,
            source: include_str!(concat!("../../shaders/", $file)),
        }
    };
}

/// Every WGSL module of `shaders/`, each after the modules it imports.
pub const MODULES: &[Module] = &[
    module!("filtered_ndf::math", "math.wgsl"),
    module!("filtered_ndf::ndf::roughness", "ndf/roughness/mod.wgsl"),
    module!("filtered_ndf::kernel::covariance", "kernel/covariance.wgsl"),
    module!("filtered_ndf::filter::deferred", "filter/deferred.wgsl"),
    module!("filtered_ndf::ndf::roughness::matrix", "ndf/roughness/matrix.wgsl"),
    module!("filtered_ndf::filter::gaussian", "filter/gaussian.wgsl"),
    module!("filtered_ndf::ndf", "ndf/mod.wgsl"),
    module!("filtered_ndf::ndf::roughness::isotropic", "ndf/roughness/isotropic.wgsl"),
    module!("filtered_ndf::ndf::roughness::axis_aligned", "ndf/roughness/axis_aligned.wgsl"),
    module!("filtered_ndf::ndf::ggx", "ndf/ggx.wgsl"),
    module!("filtered_ndf::ndf::beckmann", "ndf/beckmann.wgsl"),
    module!("filtered_ndf::filter::gaussian_ggx_quad", "filter/gaussian_ggx_quad.wgsl"),
    module!("filtered_ndf::sampling", "sampling/mod.wgsl"),
    module!("filtered_ndf::filter::gaussian_ggx", "filter/gaussian_ggx.wgsl"),
    module!("filtered_ndf::filter::lean", "filter/lean.wgsl"),
    module!("filtered_ndf::footprint::jacobian", "footprint/jacobian.wgsl"),
    module!("filtered_ndf::kernel::rect", "kernel/rect.wgsl"),
    module!("filtered_ndf::footprint", "footprint/mod.wgsl"),
    module!("filtered_ndf::filter::projected", "filter/projected.wgsl"),
    module!("filtered_ndf::kernel::clamp", "kernel/clamp.wgsl"),
    module!("filtered_ndf::filter::proxy", "filter/proxy.wgsl"),
    module!("filtered_ndf::filter::rect", "filter/rect.wgsl"),
    module!("filtered_ndf::filter::rect::lambda", "filter/rect/lambda.wgsl"),
    module!("filtered_ndf::filter::method", "filter/method.wgsl"),
    module!("filtered_ndf::filter::presets", "filter/presets.wgsl"),
    module!("filtered_ndf::filter::rect::sample", "filter/rect/sample.wgsl"),
    module!("filtered_ndf::footprint::slope", "footprint/slope.wgsl"),
    module!("filtered_ndf::sampling::beckmann", "sampling/beckmann.wgsl"),
];
