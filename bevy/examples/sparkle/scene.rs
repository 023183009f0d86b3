//! The scene: a lake of water-like ripples (a tiled normal map of a sum of sines, no mip chain,
//! as a PNG loads in Bevy; [`normal_map_mipmapped`] adds a box-filtered chain) at low roughness under a low point light across the lake, seen from
//! a few metres up: ripples a few pixels wide near the camera, about one pixel where the
//! light's reflection is, a few per pixel at the far shore, so that the highlights sparkle;
//! the camera's short move along the shore. The ripples are at most a few per pixel, so that a
//! supersampled reference resolves them.

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::math::Affine2;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};

/// The normal map's size in texels (square).
pub const NORMAL_MAP_SIZE: usize = 512;
/// The size of one normal-map tile on the water, metres.
pub const TILE_METRES: f32 = 4.0;
/// The lake's half size across (x) and along the view (z), metres.
pub const LAKE_HALF_SIZE: Vec2 = Vec2::new(40.0, 25.0);
/// The lake's centre on the view axis (it spans `z` from 5 m behind the camera to 45 m ahead).
pub const LAKE_CENTRE_Z: f32 = -20.0;
/// The RMS slope of the ripples (both directions together).
pub const SLOPE_RMS: f32 = 0.2;
/// The water's perceptual roughness (Bevy's `perceptual_roughness`; `alpha` = its square).
pub const PERCEPTUAL_ROUGHNESS: f32 = 0.12;

/// The camera's height above the water, metres.
const EYE_HEIGHT: f32 = 6.0;
/// The camera's vertical field of view, radians.
pub const FOV_Y: f32 = 0.7;

/// A small deterministic generator (SplitMix64), so the ripples are the same everywhere.
struct SplitMix(u64);

impl SplitMix {
    fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The ripples' slope field over one tile, `(dh/dx, dh/dy)` per texel (row-major, `y` down
/// the texture): a sum of sines with integer wave numbers (periodic on the tile), amplitudes
/// falling as `k^-2` (slopes as `k^-1`), wavelengths from 0.15 m to 1 m, scaled to
/// [`SLOPE_RMS`].
fn slopes() -> Vec<Vec2> {
    let n = NORMAL_MAP_SIZE;
    let mut rng = SplitMix(0x5eed);
    // (wave vector in cycles per tile, amplitude of the slope, phase)
    let mut waves = Vec::new();
    for _ in 0..48 {
        let k = (TILE_METRES / 1.0) + (TILE_METRES / 0.15 - TILE_METRES / 1.0) * rng.next_f32();
        let theta = std::f32::consts::TAU * rng.next_f32();
        let kv = (Vec2::new(theta.cos(), theta.sin()) * k).round();
        if kv == Vec2::ZERO {
            continue;
        }
        let phase = std::f32::consts::TAU * rng.next_f32();
        waves.push((kv, 1.0 / kv.length(), phase));
    }
    let mut s = vec![Vec2::ZERO; n * n];
    for (i, v) in s.iter_mut().enumerate() {
        let p = Vec2::new((i % n) as f32 + 0.5, (i / n) as f32 + 0.5) / n as f32;
        for &(kv, a, phase) in &waves {
            // h = a / |k| sin(2 pi k.p + phase): grad h = a (k / |k|) cos(...) (per tile,
            // scaled below).
            let c = (std::f32::consts::TAU * kv.dot(p) + phase).cos();
            *v += kv.normalize() * (a * c);
        }
    }
    let rms = (s.iter().map(|v| v.length_squared()).sum::<f32>() / s.len() as f32).sqrt();
    for v in &mut s {
        *v *= SLOPE_RMS / rms;
    }
    s
}

/// The texels of the ripples' tangent-space normal map (`Rgba8Unorm`, `n * 0.5 + 0.5`).
fn normal_map_texels() -> Vec<u8> {
    let n = NORMAL_MAP_SIZE;
    let mut data = Vec::with_capacity(4 * n * n);
    for s in slopes() {
        let normal = Vec3::new(-s.x, -s.y, 1.0).normalize();
        for c in [normal.x, normal.y, normal.z] {
            data.push(((c * 0.5 + 0.5) * 255.0).round() as u8);
        }
        data.push(255);
    }
    data
}

/// A linear `Rgba8Unorm` image of the normal map's size with `levels` mips in `data`,
/// repeating, bilinear within a level and linear between levels.
fn normal_map_image(data: Vec<u8>, levels: u32) -> Image {
    let n = NORMAL_MAP_SIZE as u32;
    let mut image = Image::new_uninit(
        Extent3d {
            width: n,
            height: n,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8Unorm,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.mip_level_count = levels;
    image.data = Some(data);
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::Repeat,
        address_mode_v: ImageAddressMode::Repeat,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        mipmap_filter: ImageFilterMode::Linear,
        ..default()
    });
    image
}

/// The tangent-space normal map of the ripples (`Rgba8Unorm`, linear, `n * 0.5 + 0.5`),
/// repeating, bilinear, without mip levels.
pub fn normal_map() -> Image {
    normal_map_image(normal_map_texels(), 1)
}

/// The normal map with its mip chain as a texture pipeline generates it: each level the 2 x 2
/// box average of the level above, texel values (so the stored vectors, not renormalised:
/// Bevy normalises the normal after its tangent frame), rounded to 8 bits.
pub fn normal_map_mipmapped() -> Image {
    let mut level = normal_map_texels();
    let mut size = NORMAL_MAP_SIZE;
    let mut data = level.clone();
    let mut levels = 1;
    while size > 1 {
        let half = size / 2;
        let mut next = Vec::with_capacity(4 * half * half);
        for y in 0..half {
            for x in 0..half {
                for c in 0..4 {
                    let at = |dx: usize, dy: usize| {
                        u32::from(level[4 * ((2 * y + dy) * size + 2 * x + dx) + c])
                    };
                    let sum = at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1);
                    next.push(((sum + 2) / 4) as u8);
                }
            }
        }
        data.extend_from_slice(&next);
        (level, size) = (next, half);
        levels += 1;
    }
    normal_map_image(data, levels)
}

/// The water plane's mesh: positions, normals and UVs of Bevy's plane, and the constant
/// tangent `+x` the normal map needs.
pub fn water_mesh() -> Mesh {
    let mut mesh = Plane3d::new(Vec3::Y, LAKE_HALF_SIZE).mesh().build();
    let count = mesh.count_vertices();
    mesh.insert_attribute(
        Mesh::ATTRIBUTE_TANGENT,
        vec![[1.0f32, 0.0, 0.0, 1.0]; count],
    );
    mesh
}

/// The water's `StandardMaterial`: dark blue, glossy, dielectric, normal-mapped.
pub fn water_material(normal_map: Handle<Image>) -> StandardMaterial {
    StandardMaterial {
        base_color: Color::srgb(0.02, 0.05, 0.08),
        perceptual_roughness: PERCEPTUAL_ROUGHNESS,
        metallic: 0.0,
        reflectance: 0.5,
        normal_map_texture: Some(normal_map),
        uv_transform: Affine2::from_scale(2.0 * LAKE_HALF_SIZE / TILE_METRES),
        ..default()
    }
}

/// The lake's transform.
pub fn lake_transform() -> Transform {
    Transform::from_xyz(0.0, 0.0, LAKE_CENTRE_Z)
}

/// The point light: across the lake and up, so that its reflection is a glitter path around
/// 18 m from the camera (mirror point `80 * 6 / 26` m), from the resolved ripples to the
/// sub-pixel ones.
pub fn light_transform() -> Transform {
    Transform::from_xyz(0.0, 20.0, -80.0)
}

/// The camera at frame `i` of `frames`: walking 0.5 m along the shore and 0.3 m forward over
/// the move, looking across the water slightly down.
pub fn camera_transform(i: usize, frames: usize) -> Transform {
    let t = if frames > 1 {
        i as f32 / (frames - 1) as f32
    } else {
        0.0
    };
    let eye = Vec3::new(-0.25 + 0.5 * t, EYE_HEIGHT, -0.3 * t);
    Transform::from_translation(eye).looking_at(Vec3::new(0.0, 0.0, -20.0), Vec3::Y)
}
