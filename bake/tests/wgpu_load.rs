//! The baker's KTX2 files load into a wgpu texture with every mip level, as an engine's loader
//! uploads them: the file parsed by the `ktx2` crate (the parser of Bevy's KTX2 loader), its
//! `vkFormat` mapped to the wgpu format of the same name, all levels handed to
//! `create_texture_with_data` in mip-major order (one texture, `mip_level_count` = the file's
//! `levelCount`), then every level copied back to a buffer and compared byte for byte with the
//! file's level. The comparison is exact: uploads and copies move bytes, never convert them.
//!
//! The GPU is the conformance harness's (`filtered_ndf_gpu::harness::gpu`), on the backend
//! `FILTERED_NDF_GPU_BACKEND` selects (`vulkan`: Mesa's lavapipe without a GPU). A missing
//! adapter fails the test with the package to install; it never skips.

use filtered_ndf_bake::{Options, Roughness, run};
use filtered_ndf_gpu::harness::{Gpu, gpu};
use image::{ImageBuffer, Rgb};
use std::path::{Path, PathBuf};
use wgpu::util::{DeviceExt, TextureDataOrder};

fn tmp(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("bake-wgpu-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The wgpu format of a `VkFormat` number (Vulkan's `VkFormat` enumeration; the names match
/// wgpu's), with its bytes per texel.
fn format_of(vk_format: u32) -> (wgpu::TextureFormat, u32) {
    match vk_format {
        9 => (wgpu::TextureFormat::R8Unorm, 1),
        37 => (wgpu::TextureFormat::Rgba8Unorm, 4),
        76 => (wgpu::TextureFormat::R16Float, 2),
        97 => (wgpu::TextureFormat::Rgba16Float, 8),
        100 => (wgpu::TextureFormat::R32Float, 4),
        109 => (wgpu::TextureFormat::Rgba32Float, 16),
        other => panic!("VkFormat {other} is not one the baker writes"),
    }
}

/// Loads `path` into a texture with all its levels and reads every level back; returns the
/// file's levels and the read-back ones.
fn load_and_read_back(g: &Gpu, path: &Path) -> (Vec<Vec<u8>>, Vec<Vec<u8>>, u32) {
    let bytes = std::fs::read(path).unwrap();
    let r = ktx2::Reader::new(&bytes[..]).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let h = r.header();
    let (format, texel) = format_of(h.format.expect("a vkFormat").value());
    let levels: Vec<Vec<u8>> = r.levels().map(|l| l.data.to_vec()).collect();
    assert_eq!(levels.len() as u32, h.level_count);
    let size = wgpu::Extent3d {
        width: h.pixel_width,
        height: h.pixel_height,
        depth_or_array_layers: 1,
    };
    let texture = g.device.create_texture_with_data(
        &g.queue,
        &wgpu::TextureDescriptor {
            label: Some("baked chain"),
            size,
            mip_level_count: h.level_count,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        },
        TextureDataOrder::MipMajor,
        &levels.concat(),
    );
    assert_eq!(texture.mip_level_count(), h.level_count);
    let mut back = Vec::new();
    for k in 0..h.level_count {
        let m = size.mip_level_size(k, wgpu::TextureDimension::D2);
        let row = m.width * texel;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = g.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read back"),
            size: u64::from(padded * m.height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = g.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: k,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(m.height),
                },
            },
            m,
        );
        g.queue.submit([enc.finish()]);
        let slice = buffer.slice(..);
        slice.map_async(wgpu::MapMode::Read, |r| r.expect("map"));
        g.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("poll");
        let data = slice.get_mapped_range().expect("a mapped range");
        let level: Vec<u8> = data
            .chunks(padded as usize)
            .flat_map(|r| &r[..row as usize])
            .copied()
            .collect();
        drop(data);
        buffer.unmap();
        back.push(level);
    }
    (levels, back, h.level_count)
}

fn check_dir(g: &Gpu, dir: &Path, names: &[&str], levels: u32) {
    for name in names {
        let path = dir.join(name);
        let (file, back, count) = load_and_read_back(g, &path);
        assert_eq!(count, levels, "{name}: every mip level");
        for (k, (f, b)) in file.iter().zip(&back).enumerate() {
            assert!(f == b, "{name}: level {k} read back differs from the file");
        }
    }
}

#[test]
fn every_file_loads_into_a_texture_with_all_its_mips_and_reads_back_unchanged() {
    let g = gpu().unwrap_or_else(|e| panic!("{e}"));
    let dir = tmp("all");
    // The real map, anisotropic, glTF storage: R8_UNORM, R8G8B8A8_UNORM, RGBA16F, R16F.
    let real =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../demo/data/normal_maps/pmndrs_0011.png");
    let mut o = Options::new(&real, dir.join("real"));
    o.anisotropic = true;
    o.unit_tolerance = Some(f64::INFINITY);
    o.progress = false;
    run(&o).unwrap();
    let (w, h) = image::image_dimensions(&real).unwrap();
    let full = 32 - w.max(h).leading_zeros();
    check_dir(
        g,
        &dir.join("real"),
        &[
            "roughness.ktx2",
            "anisotropy.ktx2",
            "moments.ktx2",
            "moments_xy.ktx2",
        ],
        full,
    );
    // A 37 x 23 map (rows of odd byte lengths: the copies' row padding), alpha storage, f32
    // moments: RGBA16F, RGBA32F, R32F; and isotropic alpha: R16F.
    let input = dir.join("flat.png");
    ImageBuffer::from_fn(37, 23, |x, y| {
        let t = f64::from(x * 7 + y * 3).sin() * 0.3;
        let l = (1.0 + t * t).sqrt();
        let c = |v: f64| ((v * 0.5 + 0.5) * 255.0).round() as u8;
        Rgb([c(-t / l), 128, c(1.0 / l)])
    })
    .save(&input)
    .unwrap();
    for (name, aniso) in [("alpha_aniso", true), ("alpha_iso", false)] {
        let mut o = Options::new(&input, dir.join(name));
        o.anisotropic = aniso;
        o.store = filtered_ndf_bake::encode::Store::Alpha;
        o.moments = filtered_ndf_bake::encode::Precision::F32;
        o.roughness = Roughness::Constant(0.4);
        o.unit_tolerance = Some(f64::INFINITY);
        o.progress = false;
        run(&o).unwrap();
        check_dir(
            g,
            &dir.join(name),
            &["roughness.ktx2", "moments.ktx2", "moments_xy.ktx2"],
            6,
        );
    }
}
