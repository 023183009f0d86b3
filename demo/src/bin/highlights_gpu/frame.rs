//! One frame's inputs for the shaders: the shared scene description and camera packed as the
//! `Scene` uniform of `shaders/scene.wgsl`, and the scissor rectangle of each sphere.

use crate::camera::Camera;
use crate::scene::{Scene, SceneKind};
use glam::Vec3;

/// The `Scene` uniform (`shaders/scene.wgsl`), field for field.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SceneUniform {
    eye: [f32; 4],
    corner: [f32; 4],
    step_x: [f32; 4],
    step_y: [f32; 4],
    light_position: [f32; 4],
    light_intensity: [f32; 4],
    ambient: [f32; 4],
    water: [f32; 4],
    water_far_albedo: [f32; 4],
    waves: [[f32; 4]; 8],
    wavelengths: [[f32; 4]; 8],
    spheres: [[f32; 4]; 5],
    sphere_albedo: [[f32; 4]; 5],
    bumpy: [f32; 4],
    bumps: [[f32; 4]; 8],
    bump_phases: [[f32; 4]; 2],
    sky: [[f32; 4]; 2],
}

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

impl SceneUniform {
    /// The uniform of `scene` seen through `cam`.
    pub fn new(scene: &Scene, cam: &Camera) -> Self {
        let p = scene.params();
        assert!(p.waves.len() <= 8, "scene.wgsl: N_WAVES");
        assert!(p.bumps.len() <= 8, "scene.wgsl: N_WAVES");
        assert!(p.spheres.len() <= 5, "scene.wgsl: N_SPHERES");
        let [corner, step_x, step_y] = cam.basis();
        let mut u = Self {
            eye: v4(cam.eye, cam.pixel_angle()),
            corner: v4(corner, 0.0),
            step_x: v4(step_x, 0.0),
            step_y: v4(step_y, 0.0),
            light_position: v4(scene.light_position, scene.f0),
            light_intensity: v4(scene.light_intensity, scene.alpha),
            ambient: v4(scene.ambient, 0.0),
            water: [p.water[0], p.water[1], p.water[2], p.water[3]],
            water_far_albedo: [
                p.water[4],
                p.water_albedo.x,
                p.water_albedo.y,
                p.water_albedo.z,
            ],
            waves: [[0.0; 4]; 8],
            wavelengths: [[0.0; 4]; 8],
            spheres: [[0.0; 4]; 5],
            sphere_albedo: [[0.0; 4]; 5],
            bumpy: [
                f32::from(u8::from(p.kind == SceneKind::Bumpy)),
                p.spheres.len() as f32,
                p.bump_bound,
                p.bump_lipschitz,
            ],
            bumps: [[0.0; 4]; 8],
            bump_phases: [[0.0; 4]; 2],
            sky: [v4(scene.sky[0], 0.0), v4(scene.sky[1], 0.0)],
        };
        for (i, b) in p.bumps.iter().enumerate() {
            u.bumps[i] = [b[0], b[1], b[2], b[3]];
            u.bump_phases[i / 4][i % 4] = b[4];
        }
        for (i, w) in p.waves.iter().enumerate() {
            u.waves[i] = [w[0], w[1], w[2], w[3]];
            u.wavelengths[i] = [w[4], 0.0, 0.0, 0.0];
        }
        for (i, (c, r, albedo)) in p.spheres.iter().enumerate() {
            u.spheres[i] = v4(*c, *r);
            u.sphere_albedo[i] = v4(*albedo, 0.0);
        }
        u
    }
}

/// A pixel rectangle `(x, y, width, height)`.
pub type Rect = (u32, u32, u32, u32);

/// The scissor rectangle of each sphere (in the bumpy scene, of each bumpy sphere's shell,
/// radius `R + sum a_i`): the image rectangle around the projections of the corners of its
/// bounding box (the projection of a convex body in front of the eye lies in
/// the hull of its box's corners), widened by two pixels and to whole 2x2 quads so that every
/// quad with a pixel of the sphere runs whole. The full image where a corner is behind the
/// eye.
pub fn sphere_scissors(scene: &Scene, cam: &Camera, width: u32, height: u32) -> Vec<Rect> {
    let full = (0, 0, width, height);
    let p = scene.params();
    p.spheres
        .iter()
        .map(|&(c, r, _)| {
            let r = r + p.bump_bound;
            let mut lo = (f32::MAX, f32::MAX);
            let mut hi = (f32::MIN, f32::MIN);
            for k in 0..8 {
                let corner = c + Vec3::new(
                    if k & 1 == 0 { -r } else { r },
                    if k & 2 == 0 { -r } else { r },
                    if k & 4 == 0 { -r } else { r },
                );
                let Some((x, y)) = cam.project(corner, 1e-3) else {
                    return full;
                };
                lo = (lo.0.min(x), lo.1.min(y));
                hi = (hi.0.max(x), hi.1.max(y));
            }
            let clamp = |v: f32, max: u32| v.clamp(0.0, max as f32) as u32;
            let x0 = clamp(lo.0 - 2.0, width) & !1;
            let y0 = clamp(lo.1 - 2.0, height) & !1;
            let x1 = (clamp(hi.0 + 3.0, width) + 1).min(width) & !1;
            let y1 = (clamp(hi.1 + 3.0, height) + 1).min(height) & !1;
            if x1 <= x0 || y1 <= y0 {
                (0, 0, 0, 0)
            } else {
                (x0, y0, x1 - x0, y1 - y0)
            }
        })
        .collect()
}
