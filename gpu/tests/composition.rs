//! naga_oil composition of the modules of `shaders/`, as Bevy composes its shaders: every
//! module composes on its own, and a fragment shader in Bevy's style imports and calls them.
//! No GPU needed.

use filtered_ndf_gpu::modules::{compose, load_all};

#[test]
fn every_module_composes_alone() {
    let modules = load_all().expect("modules load");
    assert!(modules.len() >= 10, "found {} modules", modules.len());
    for m in &modules {
        let src = format!(
            "#import {}\n@fragment\nfn main() -> @location(0) vec4<f32> {{\n    return vec4<f32>(0.0);\n}}\n",
            m.path
        );
        compose(&src, "alone.wgsl").unwrap_or_else(|e| panic!("{}: {e}", m.path));
    }
}

/// The README's minimal fragment shader: an isotropic GGX lobe widened by the screen-space
/// footprint of the half vector (TK19 `A + 2 Sigma` with the default clamps).
pub const README_FRAGMENT: &str = r#"#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::ndf::ggx

@fragment
fn main(@location(0) h: vec3<f32>, @location(1) alpha: f32) -> @location(0) vec4<f32> {
    let m = normalize(h);
    let d = ggx::d_isotropic(isotropic::from_alpha(alpha), m);
    return vec4<f32>(d, 0.0, 0.0, 1.0);
}
"#;

#[test]
fn readme_fragment_shader_composes() {
    let module = compose(README_FRAGMENT, "readme.wgsl").expect("composes");
    assert_eq!(module.entry_points.len(), 1);
}
