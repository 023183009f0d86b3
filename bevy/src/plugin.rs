//! [`FilteredNdfPlugin`]: the WGSL modules as shader assets and the material.

use crate::extension::FilteredNdfMaterial;
use crate::wgsl;
use bevy::asset::uuid_handle;
use bevy::pbr::MaterialPlugin;
use bevy::prelude::*;
use bevy::shader::Shader;

/// The import path of this crate's WGSL module (`src/shaders/roughness.wgsl`): the settings
/// struct `FilterSettings` and `filter_perceptual_roughness`, for shaders of your own.
pub const ROUGHNESS_IMPORT_PATH: &str = "filtered_ndf_bevy::roughness";

/// The import path of this crate's WGSL module of the moment chain (`src/shaders/lean.wgsl`):
/// the mean slope's normal-map texel and the LEAN-widened perceptual roughness.
pub const LEAN_IMPORT_PATH: &str = "filtered_ndf_bevy::lean";

/// The fragment shader of [`FilteredNdfMaterial`] (forward and deferred).
pub const MATERIAL_SHADER: Handle<Shader> = uuid_handle!("fadec2a8-498d-4925-851e-2881c4ddd6c5");

/// The source of `filtered_ndf_bevy::roughness`.
const ROUGHNESS_WGSL: &str = include_str!("shaders/roughness.wgsl");
/// The source of `filtered_ndf_bevy::lean`.
const LEAN_WGSL: &str = include_str!("shaders/lean.wgsl");
/// The source of [`MATERIAL_SHADER`].
const MATERIAL_WGSL: &str = include_str!("shaders/material.wgsl");

/// Adds every WGSL module of `filtered-ndf` ([`wgsl::MODULES`]), `filtered_ndf_bevy::roughness`
/// and `filtered_ndf_bevy::lean` to `Assets<Shader>` under their import paths (their handles kept in
/// [`FilteredNdfShaders`], so that Bevy's composer finds them for as long as the app runs),
/// the material's shader as [`MATERIAL_SHADER`], and the [`MaterialPlugin`] of
/// [`FilteredNdfMaterial`]. Add it after `DefaultPlugins` (it needs `Assets<Shader>`).
#[derive(Clone, Copy, Debug, Default)]
pub struct FilteredNdfPlugin;

/// The strong handles of the shader modules [`FilteredNdfPlugin`] added, in the order of
/// [`wgsl::MODULES`], then `filtered_ndf_bevy::roughness` and `filtered_ndf_bevy::lean`. Bevy frees an asset whose last
/// strong handle is dropped, and an import whose module is gone fails to compose.
#[derive(Resource, Clone, Debug)]
pub struct FilteredNdfShaders {
    /// One handle per module.
    pub modules: Vec<Handle<Shader>>,
}

impl Plugin for FilteredNdfPlugin {
    fn build(&self, app: &mut App) {
        let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
        let mut modules: Vec<Handle<Shader>> = wgsl::MODULES
            .iter()
            .map(|m| {
                shaders.add(Shader::from_wgsl(
                    m.source,
                    format!("filtered_ndf/{}", m.file),
                ))
            })
            .collect();
        modules.push(shaders.add(Shader::from_wgsl(
            ROUGHNESS_WGSL,
            "filtered_ndf_bevy/roughness.wgsl",
        )));
        modules.push(shaders.add(Shader::from_wgsl(LEAN_WGSL, "filtered_ndf_bevy/lean.wgsl")));
        // A uuid id is not an index id, so `insert` has no generation to reject.
        let _ = shaders.insert(
            &MATERIAL_SHADER,
            Shader::from_wgsl(MATERIAL_WGSL, "filtered_ndf_bevy/material.wgsl"),
        );
        app.insert_resource(FilteredNdfShaders { modules })
            .add_plugins(MaterialPlugin::<FilteredNdfMaterial>::default());
    }
}
