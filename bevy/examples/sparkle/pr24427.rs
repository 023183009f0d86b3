//! The formula of bevyengine/bevy pull request 24427 as a material extension of
//! `StandardMaterial` (forward only), written from the pull request's description for the
//! comparison: `alpha^2 <- saturate(alpha^2 + min(sigma^2 (|dN/dx|^2 + |dN/dy|^2), kappa))`.

use bevy::asset::uuid_handle;
use bevy::pbr::{ExtendedMaterial, MaterialExtension};
use bevy::prelude::*;
use bevy::render::render_resource::AsBindGroup;
use bevy::shader::{Shader, ShaderRef};

/// The extension's fragment shader.
pub const PR24427_SHADER: Handle<Shader> = uuid_handle!("5eca3391-977c-43fa-8603-190dd53713a7");

/// `StandardMaterial` with the pull request's roughness widening.
pub type Pr24427Material = ExtendedMaterial<StandardMaterial, Pr24427Extension>;

/// The pull request's two knobs, at its defaults.
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone, Copy)]
pub struct Pr24427Extension {
    /// `specular_anti_aliasing_screen_space_variance` (`sigma`, 0.5).
    #[uniform(100)]
    pub sigma: f32,
    /// `specular_anti_aliasing_threshold` (`kappa`, 0.18).
    #[uniform(100)]
    pub kappa: f32,
}

impl Default for Pr24427Extension {
    fn default() -> Self {
        Self {
            sigma: 0.5,
            kappa: 0.18,
        }
    }
}

impl MaterialExtension for Pr24427Extension {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(PR24427_SHADER)
    }
}

/// Registers the shader and the material.
pub struct Pr24427Plugin;

impl Plugin for Pr24427Plugin {
    fn build(&self, app: &mut App) {
        let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
        let _ = shaders.insert(
            &PR24427_SHADER,
            Shader::from_wgsl(include_str!("pr24427.wgsl"), "sparkle/pr24427.wgsl"),
        );
        app.add_plugins(MaterialPlugin::<Pr24427Material>::default());
    }
}
