//! A Bevy plugin that stops normal-mapped glossy surfaces from sparkling: `StandardMaterial`'s
//! GGX roughness is filtered with `filtered-ndf`'s WGSL modules (naga_oil imports, composed by
//! Bevy's shader pipeline) before Bevy's PBR lighting runs.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use filtered_ndf_bevy::{FilteredNdfExtension, FilteredNdfMaterial, FilteredNdfPlugin};
//!
//! fn main() {
//!     App::new()
//!         .add_plugins((DefaultPlugins, FilteredNdfPlugin))
//!         .add_systems(Startup, setup)
//!         .run();
//! }
//!
//! fn setup(
//!     mut commands: Commands,
//!     mut meshes: ResMut<Assets<Mesh>>,
//!     mut materials: ResMut<Assets<FilteredNdfMaterial>>,
//! ) {
//!     commands.spawn((
//!         Mesh3d(meshes.add(Sphere::new(1.0))),
//!         MeshMaterial3d(materials.add(FilteredNdfMaterial {
//!             base: StandardMaterial {
//!                 perceptual_roughness: 0.1,
//!                 ..default()
//!             },
//!             // TK19's trace kernel, sigma = 0.5 pixel, kappa = 0.18.
//!             extension: FilteredNdfExtension::default(),
//!         })),
//!     ));
//! }
//! ```
//!
//! - [`FilteredNdfPlugin`] adds every WGSL module of `filtered-ndf` as a shader asset under
//!   its import path (`filtered_ndf::filter::deferred`, ...), this crate's own module
//!   `filtered_ndf_bevy::roughness` (see [`ROUGHNESS_IMPORT_PATH`]), and the material.
//! - [`FilteredNdfMaterial`] is `ExtendedMaterial<StandardMaterial, FilteredNdfExtension>`:
//!   every `StandardMaterial` field works as before; [`FilteredNdfExtension`] holds the knobs
//!   (which published kernel convention, the pixel filter's width `sigma`, the clamp
//!   `kappa`) and optionally the normal map's baked LEAN moment chain. Forward and deferred
//!   rendering.
//! - [`moment_images`] bakes a normal map's moment chain in memory (`filtered_ndf::bake`)
//!   into the two textures [`FilteredNdfExtension::with_moments`] takes.
//!
//! The filter is TK19's (Tokuyoshi and Kaplanyan 2019, sect. 4, Listing 2) in each engine's
//! convention (`filtered_ndf::f32::filter::presets`): the roughness widened by the
//! screen-space differences of the normal-mapped shading normal across the pixel quad. With
//! the moment chain, the normal map's detail comes from its LEAN moments instead (KHPL16
//! eq. 21: the lobe widened by the slope covariance of the pixel's texel footprint, the normal
//! of the mean slope), and the differences are the geometric normal's.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod extension;
pub mod moments;
pub mod plugin;

/// The WGSL modules of `filtered-ndf` (the `filtered-ndf-wgsl` crate): [`wgsl::MODULES`], each
/// module's import path, file and source.
pub use filtered_ndf_wgsl as wgsl;

pub use extension::{
    FilteredNdfExtension, FilteredNdfKey, FilteredNdfMaterial, FilteredNdfUniform,
    MOMENTS_SHADER_DEF, RoughnessFilter, SIGMA_BOX_PIXEL,
};
pub use moments::{MomentBakeError, MomentImages, moment_images};
pub use plugin::{
    FilteredNdfPlugin, FilteredNdfShaders, LEAN_IMPORT_PATH, MATERIAL_SHADER, ROUGHNESS_IMPORT_PATH,
};
