//! The baked LEAN moment chain of a normal map as two Bevy [`Image`]s: [`moment_images`].
//!
//! A texel of mip level `k` holds the moments of the normal map's slopes over its footprint
//! on the base level (`filtered_ndf::bake`, Olano and Baker 2010; KHPL16 section 5.5):
//!
//! | image | format | channels |
//! |---|---|---|
//! | [`MomentImages::moments`] | `Rgba16Float` | `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])` |
//! | [`MomentImages::moments_xy`] | `R16Float` | `E[s_x s_y]` |
//!
//! the layout of the command-line baker's `moments.ktx2` and `moments_xy.ktx2`, which the WGSL
//! module `filtered_ndf::bake::moments` samples. Every moment is linear in the texels, so the
//! hardware's trilinear fetch of both images is the moments of the filter's footprint on the
//! base level (to the `f16` rounding); the shader forms the covariance after filtering,
//! `Sigma_L = E[s s^T] - E[s] E[s]^T` (LEAN eq. 5).
//!
//! **Slopes and frame.** `s = -n_xy / n_z` (dimensionless, the crate's slope: for a height
//! field `z = h(x, y)`, `s = grad h`), with `n` the normal-map texel decoded as Bevy decodes it
//! (`2 c - 1` per unorm channel; for a two-channel map `n_z = sqrt(1 - n_x^2 - n_y^2)`) and
//! its channels taken as stored: `x` the red channel, along `+u`; `y` the green channel, up
//! the image (OpenGL's and glTF's convention, the bake's frame, and Bevy's default). A map
//! authored for DirectX (`StandardMaterial::flip_normal_map_y`) has the sign of `s_y` flipped
//! by the same flag in the shader, where Bevy flips the normal map's green channel: the
//! moments stay those of the channels as stored (`E[s_y]` and `E[s_x s_y]` change sign,
//! `E[s_y^2]` and the trace of `Sigma_L` do not).

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use filtered_ndf::bake::{
    self, BakeError, Band, BaseRoughness, ChainLayout, Convention, Kernel, NormalFormat, NormalMap,
    Settings, TexelStats, Texels,
};
use std::fmt;

/// The two textures of a moment chain, each with its full mip chain (`1 + floor(log2(max(w,
/// h)))` levels by the GPU rule, the base level the normal map's size), linear (not sRGB),
/// with a trilinear sampler (linear minification, magnification and mip filtering) whose
/// address modes are the normal map's.
#[derive(Clone, Debug)]
pub struct MomentImages {
    /// `Rgba16Float`: `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])`.
    pub moments: Image,
    /// `R16Float`: `E[s_x s_y]`.
    pub moments_xy: Image,
}

/// Why [`moment_images`] refused a normal map.
#[derive(Clone, Debug, PartialEq)]
pub enum MomentBakeError {
    /// The texture format is not one Bevy decodes as a linear tangent-space normal map that
    /// this helper reads (`Rgba8Unorm`, `Rg8Unorm`, `Rgba16Unorm`, `Rg16Unorm`,
    /// `Rgba32Float`); an sRGB format is refused (Bevy would decode its texels through the
    /// sRGB curve, so they are not normals).
    Format(TextureFormat),
    /// The image has no CPU data (a render target or a GPU-only asset).
    NoData,
    /// The image is not a single 2-D layer (its dimension and layer count).
    NotSingle2d(TextureDimension, u32),
    /// The data is shorter than the base level (bytes expected, bytes held).
    Length(usize, usize),
    /// The bake refused a texel or a size (`filtered_ndf::bake::BakeError`: the texel and
    /// its value).
    Bake(BakeError),
}

impl fmt::Display for MomentBakeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Format(t) => write!(f, "the normal map's format {t:?} is not supported"),
            Self::NoData => write!(f, "the normal map has no CPU data"),
            Self::NotSingle2d(d, n) => {
                write!(
                    f,
                    "the normal map is {d:?} with {n} layers, not one 2-D layer"
                )
            }
            Self::Length(e, g) => write!(f, "the normal map holds {g} bytes, {e} expected"),
            Self::Bake(e) => write!(f, "the normal map cannot be baked: {e}"),
        }
    }
}

impl std::error::Error for MomentBakeError {}

impl From<BakeError> for MomentBakeError {
    fn from(e: BakeError) -> Self {
        Self::Bake(e)
    }
}

/// The base level of a normal map's data, decoded to what the bake reads.
enum Base<'a> {
    /// 8-bit unorm channels, as stored.
    Unorm8(&'a [u8]),
    /// 16-bit unorm channels (little-endian bytes decoded).
    Unorm16(Vec<u16>),
    /// 32-bit float channels (little-endian bytes decoded).
    F32(Vec<f32>),
}

impl Base<'_> {
    fn texels(&self) -> Texels<'_> {
        match self {
            Base::Unorm8(v) => Texels::Unorm8(v),
            Base::Unorm16(v) => Texels::Unorm16(v),
            Base::F32(v) => Texels::F32(v),
        }
    }
}

/// The base level of `image` and its channel count, checked for format, layers and length.
fn base_level(image: &Image) -> Result<(Base<'_>, usize), MomentBakeError> {
    let d = &image.texture_descriptor;
    if d.dimension != TextureDimension::D2 || d.size.depth_or_array_layers != 1 {
        return Err(MomentBakeError::NotSingle2d(
            d.dimension,
            d.size.depth_or_array_layers,
        ));
    }
    let (bytes_per_channel, channels) = match d.format {
        TextureFormat::Rgba8Unorm => (1, 4),
        TextureFormat::Rg8Unorm => (1, 2),
        TextureFormat::Rgba16Unorm => (2, 4),
        TextureFormat::Rg16Unorm => (2, 2),
        TextureFormat::Rgba32Float => (4, 4),
        other => return Err(MomentBakeError::Format(other)),
    };
    let data = image.data.as_deref().ok_or(MomentBakeError::NoData)?;
    let bytes = d.size.width as usize * d.size.height as usize * channels * bytes_per_channel;
    // A chain's further levels follow the base level; only the base is read.
    let base = data
        .get(..bytes)
        .ok_or(MomentBakeError::Length(bytes, data.len()))?;
    let decoded = match bytes_per_channel {
        1 => Base::Unorm8(base),
        2 => Base::Unorm16(
            base.chunks_exact(2)
                .map(|b| u16::from_le_bytes([b[0], b[1]]))
                .collect(),
        ),
        _ => Base::F32(
            base.chunks_exact(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect(),
        ),
    };
    Ok((decoded, channels))
}

/// The bake's moments of every level of `layout`, `f16` bit patterns, level after level.
fn bake_chain(map: &NormalMap<'_>, layout: &ChainLayout) -> Result<Vec<[u16; 5]>, BakeError> {
    let settings = Settings {
        kernel: Kernel::Area,
        // The moments do not depend on the base roughness (only the fits read it).
        base: BaseRoughness::Constant(1.0),
    };
    let mut out = vec![[0u16; 5]; layout.len()];
    let mut scratch = vec![TexelStats::default(); layout.scratch_len()];
    for k in 0..layout.levels() {
        let lv = layout.level(k);
        bake::bake_rows(
            map,
            &settings,
            layout,
            k,
            0..lv.height,
            &mut scratch,
            Band {
                moments_f16: Some(&mut out[lv.rows(0..lv.height)]),
                ..Band::default()
            },
        )?;
    }
    Ok(out)
}

/// A trilinear sampler with `normal_map`'s address modes (Bevy's default descriptor's
/// clamp-to-edge where the normal map uses the app's default sampler, which this function
/// cannot see).
fn trilinear_like(normal_map: &Image) -> ImageSamplerDescriptor {
    let base = match &normal_map.sampler {
        ImageSampler::Descriptor(d) => d.clone(),
        ImageSampler::Default => ImageSamplerDescriptor::default(),
    };
    ImageSamplerDescriptor {
        address_mode_u: base.address_mode_u,
        address_mode_v: base.address_mode_v,
        address_mode_w: ImageAddressMode::ClampToEdge,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        mipmap_filter: ImageFilterMode::Linear,
        ..ImageSamplerDescriptor::default()
    }
}

/// A 2-D `format` image of `width x height` with `levels` mips, `data` level after level.
fn chain_image(
    width: u32,
    height: u32,
    levels: usize,
    format: TextureFormat,
    data: Vec<u8>,
    sampler: ImageSamplerDescriptor,
) -> Image {
    let mut image = Image::new_uninit(
        Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        format,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.mip_level_count = levels as u32;
    image.data = Some(data);
    image.sampler = ImageSampler::Descriptor(sampler);
    image
}

/// The LEAN moment chain of the tangent-space normal map `normal_map` (the image Bevy
/// samples as `StandardMaterial::normal_map_texture`), baked in memory by
/// `filtered_ndf::bake` and packed for [`crate::FilteredNdfExtension::with_moments`]: level
/// `k` texel `(i, j)` holds the moments of the slopes `s = -n_xy / n_z` of the base texels
/// under its footprint, each base texel weighted by its overlap with the texel's exact
/// footprint (`bake::Kernel::Area`; for power-of-two sizes the aligned `2^k x 2^k` block that
/// GPU mip generators average), accumulated in `f64` from the base level and rounded once to
/// `f16` (`bake::store_f16`: relative error `2^-11`, so the covariance a shader forms is
/// within `2^-11 (E[s_x^2] + 2 E[s_x]^2)` plus `f32` rounding; module docs of
/// `filtered_ndf::bake`). Slopes are dimensionless, in the frame of the map's channels as
/// stored (module docs: `+v` up the image, Bevy's default; `flip_normal_map_y` is applied by
/// the shader). Only the base level of `normal_map` is read (a map with its own mip chain
/// keeps it; the moments come from its base).
///
/// Formats: `Rgba8Unorm`, `Rgba16Unorm`, `Rgba32Float` (`x, y, z` in the first three
/// channels, the fourth ignored), `Rg8Unorm`, `Rg16Unorm` (`z` reconstructed, as Bevy's
/// two-component normal maps). Errors: another format, no CPU data, not one 2-D layer, data
/// shorter than the base level, or a texel the bake refuses (not unit to within its
/// quantisation, at or below the surface, or steeper than `bake::MAX_SLOPE`; the error
/// names the texel, column and row from the top-left). Nothing is returned on error.
///
/// Cost: one pass over the base texels per level (`O(w h log2 max(w, h))`, in `f64`), and
/// `8 + 2` bytes per texel for `4/3` of the base level on the GPU.
pub fn moment_images(normal_map: &Image) -> Result<MomentImages, MomentBakeError> {
    let (base, channels) = base_level(normal_map)?;
    let size = normal_map.texture_descriptor.size;
    let (w, h) = (size.width as usize, size.height as usize);
    let format = NormalFormat::new(channels, Convention::OpenGl);
    let map = NormalMap::new(base.texels(), w, h, format)?;
    let layout = ChainLayout::new(w, h)?;
    let chain = bake_chain(&map, &layout)?;
    let rgba: Vec<u8> = chain
        .iter()
        .flat_map(|t| [t[0], t[1], t[2], t[4]])
        .flat_map(u16::to_le_bytes)
        .collect();
    let xy: Vec<u8> = chain.iter().flat_map(|t| t[3].to_le_bytes()).collect();
    let sampler = trilinear_like(normal_map);
    Ok(MomentImages {
        moments: chain_image(
            size.width,
            size.height,
            layout.levels(),
            TextureFormat::Rgba16Float,
            rgba,
            sampler.clone(),
        ),
        moments_xy: chain_image(
            size.width,
            size.height,
            layout.levels(),
            TextureFormat::R16Float,
            xy,
            sampler,
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use filtered_ndf::bake::f16::f16_to_f32;

    /// A `width x height` image of `format` holding `data`, repeating, with no mips.
    fn image(width: u32, height: u32, format: TextureFormat, data: Vec<u8>) -> Image {
        let mut i = Image::new(
            Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            data,
            format,
            RenderAssetUsages::RENDER_WORLD,
        );
        i.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
            address_mode_u: ImageAddressMode::Repeat,
            address_mode_v: ImageAddressMode::MirrorRepeat,
            ..ImageSamplerDescriptor::nearest()
        });
        i
    }

    /// Unit normals of slopes up to about 0.6 in each direction, from a small LCG, as
    /// `Rgba8Unorm` texels (`round(255 (0.5 n + 0.5))`).
    fn random_rgba8(n: usize, seed: u32) -> Vec<u8> {
        let mut state = seed;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f64 / f64::from(1u32 << 24) - 0.5
        };
        let mut out = Vec::with_capacity(4 * n);
        for _ in 0..n {
            let (sx, sy) = (1.2 * next(), 1.2 * next());
            let l = (sx * sx + sy * sy + 1.0).sqrt();
            for c in [-sx / l, -sy / l, 1.0 / l] {
                out.push(((0.5 * c + 0.5) * 255.0).round() as u8);
            }
            out.push(255);
        }
        out
    }

    /// The slope of an `Rgba8Unorm` texel, in `f64` from its bytes: `-n_xy / n_z` with `n =
    /// 2 c / 255 - 1` per channel, red `x`, green `y` (Bevy's decode; no flip).
    fn slope_rgba8(t: &[u8]) -> [f64; 2] {
        let c = |i: usize| 2.0 * f64::from(t[i]) / 255.0 - 1.0;
        [-c(0) / c(2), -c(1) / c(2)]
    }

    /// The `f16` at `i` of little-endian `bytes`.
    fn half(bytes: &[u8], i: usize) -> f64 {
        f64::from(f16_to_f32(u16::from_le_bytes([
            bytes[2 * i],
            bytes[2 * i + 1],
        ])))
    }

    /// `|got - want|` within one rounding to `f16` (relative `2^-11` in the normal range,
    /// absolute `2^-25` below it) after one to `f32` (relative `2^-24`), plus `1e-12` for the
    /// bake's and this reference's `f64` sums (a few ulp of values below 4).
    fn within_f16(got: f64, want: f64) -> bool {
        let tol = want.abs() * (2f64.powi(-11) + 2f64.powi(-24)) + 2f64.powi(-25) + 1e-12;
        (got - want).abs() <= tol
    }

    #[test]
    fn every_level_holds_the_block_moments_in_channel_order() {
        // 8 x 4 (powers of two): texel (i, j) of a `lw x lh` level averages the aligned block
        // of `8 / lw x 4 / lh` base texels, whose moments this test forms in f64 from the
        // texels' bytes, independently of the bake.
        let (w, h) = (8usize, 4usize);
        let bytes = random_rgba8(w * h, 7);
        let img = image(w as u32, h as u32, TextureFormat::Rgba8Unorm, bytes.clone());
        let m = moment_images(&img).expect("a valid normal map");
        let levels = [(8usize, 4usize), (4, 2), (2, 1), (1, 1)];
        assert_eq!(m.moments.texture_descriptor.mip_level_count, 4);
        assert_eq!(m.moments_xy.texture_descriptor.mip_level_count, 4);
        let texels: usize = levels.iter().map(|(a, b)| a * b).sum();
        let rgba = m.moments.data.as_deref().expect("CPU data");
        let xy = m.moments_xy.data.as_deref().expect("CPU data");
        assert_eq!(rgba.len(), 8 * texels);
        assert_eq!(xy.len(), 2 * texels);
        let mut at = 0;
        for (k, &(lw, lh)) in levels.iter().enumerate() {
            let (bw, bh) = (w / lw, h / lh);
            for j in 0..lh {
                for i in 0..lw {
                    let mut e = [0.0f64; 5];
                    for y in j * bh..(j + 1) * bh {
                        for x in i * bw..(i + 1) * bw {
                            let [sx, sy] = slope_rgba8(&bytes[4 * (y * w + x)..]);
                            for (acc, v) in e.iter_mut().zip([sx, sy, sx * sx, sy * sy, sx * sy]) {
                                *acc += v / (bw * bh) as f64;
                            }
                        }
                    }
                    for (c, &want) in e[..4].iter().enumerate() {
                        let got = half(rgba, 4 * at + c);
                        assert!(
                            within_f16(got, want),
                            "level {k} ({i}, {j}) channel {c}: {got} vs {want}"
                        );
                    }
                    let got = half(xy, at);
                    assert!(
                        within_f16(got, e[4]),
                        "level {k} ({i}, {j}) xy: {got} vs {}",
                        e[4]
                    );
                    at += 1;
                }
            }
        }
    }

    #[test]
    fn the_chain_is_the_library_bake_for_any_size() {
        // 6 x 5 (odd sizes: the exact-footprint kernel's partial texels): the images hold
        // `bake_rows`' f16 moments of every level, packed RGBA = [0, 1, 2, 4] and R = [3].
        let (w, h) = (6usize, 5usize);
        let bytes = random_rgba8(w * h, 11);
        let img = image(w as u32, h as u32, TextureFormat::Rgba8Unorm, bytes.clone());
        let m = moment_images(&img).expect("a valid normal map");
        let map = NormalMap::new(
            Texels::Unorm8(&bytes),
            w,
            h,
            NormalFormat::new(4, Convention::OpenGl),
        )
        .expect("a valid normal map");
        let layout = ChainLayout::new(w, h).expect("a valid size");
        assert_eq!(layout.levels(), 3);
        assert_eq!(m.moments.texture_descriptor.mip_level_count, 3);
        assert_eq!(
            m.moments.texture_descriptor.size,
            img.texture_descriptor.size
        );
        let mut want = vec![[0u16; 5]; layout.len()];
        let mut scratch = vec![TexelStats::default(); layout.scratch_len()];
        let settings = Settings {
            kernel: Kernel::Area,
            base: BaseRoughness::Constant(0.5),
        };
        for k in 0..layout.levels() {
            let lv = layout.level(k);
            bake::bake_rows(
                &map,
                &settings,
                &layout,
                k,
                0..lv.height,
                &mut scratch,
                Band {
                    moments_f16: Some(&mut want[lv.rows(0..lv.height)]),
                    ..Band::default()
                },
            )
            .expect("bakes");
        }
        let rgba: Vec<u8> = want
            .iter()
            .flat_map(|t| [t[0], t[1], t[2], t[4]])
            .flat_map(u16::to_le_bytes)
            .collect();
        let xy: Vec<u8> = want.iter().flat_map(|t| t[3].to_le_bytes()).collect();
        assert_eq!(m.moments.data.as_deref(), Some(rgba.as_slice()));
        assert_eq!(m.moments_xy.data.as_deref(), Some(xy.as_slice()));
    }

    #[test]
    fn a_flat_normal_map_has_zero_moments() {
        // (0, 0, 1) in f32: every slope is exactly 0, so every moment and the covariance are.
        let texel = [0.0f32, 0.0, 1.0, 1.0];
        let data: Vec<u8> = (0..16 * 16)
            .flat_map(|_| texel)
            .flat_map(f32::to_le_bytes)
            .collect();
        let m = moment_images(&image(16, 16, TextureFormat::Rgba32Float, data))
            .expect("a valid normal map");
        assert_eq!(m.moments.texture_descriptor.mip_level_count, 5);
        let rgba = m.moments.data.as_deref().expect("CPU data");
        let xy = m.moments_xy.data.as_deref().expect("CPU data");
        assert_eq!(rgba.len(), 8 * (256 + 64 + 16 + 4 + 1));
        assert!(rgba.iter().chain(xy).all(|&b| b == 0));
    }

    #[test]
    fn a_constant_tilted_map_has_no_covariance_beyond_f16_rounding() {
        // Every texel the same tilted normal: E[s s^T] = E[s] E[s]^T exactly, so the covariance
        // the shader forms from the stored moments is their f16 rounding alone, within
        // 2^-11 (E[s_x^2] + 2 E[s_x]^2) per the bake's storage bound.
        let n = [-0.3f64, 0.4, 1.0];
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let b = |c: f64| ((0.5 * c / l + 0.5) * 255.0).round() as u8;
        let t = [b(n[0]), b(n[1]), b(n[2]), 255];
        let [sx, sy] = slope_rgba8(&t);
        let data: Vec<u8> = (0..8 * 8).flat_map(|_| t).collect();
        let m = moment_images(&image(8, 8, TextureFormat::Rgba8Unorm, data))
            .expect("a valid normal map");
        let rgba = m.moments.data.as_deref().expect("CPU data");
        let xy = m.moments_xy.data.as_deref().expect("CPU data");
        // Green above the middle: n_y > 0, so the slope's y (up the image) is negative.
        assert!(sy < 0.0 && sx > 0.0);
        for i in 0..(64 + 16 + 4 + 1) {
            let (mx, my) = (half(rgba, 4 * i), half(rgba, 4 * i + 1));
            assert!(within_f16(mx, sx) && within_f16(my, sy), "texel {i}");
            let c = [
                half(rgba, 4 * i + 2) - mx * mx,
                half(xy, i) - mx * my,
                half(rgba, 4 * i + 3) - my * my,
            ];
            // Each stored moment within (2^-11 + 2^-24) of itself; the squared mean's error
            // twice that of the mean, relative.
            let rel = 3.0 * (2f64.powi(-11) + 2f64.powi(-24));
            let bound = rel * (sx * sx).max(sy * sy) + 3.0 * 2f64.powi(-25);
            assert!(
                c.iter().all(|v| v.abs() <= bound),
                "texel {i}: {c:?} > {bound}"
            );
        }
    }

    #[test]
    fn two_channel_maps_reconstruct_z() {
        // Rg8Unorm: n_z = sqrt(1 - n_x^2 - n_y^2), as Bevy's two-component normal maps.
        let t = [90u8, 150];
        let (nx, ny) = (2.0 * 90.0 / 255.0 - 1.0, 2.0 * 150.0 / 255.0 - 1.0f64);
        let nz = (1.0 - nx * nx - ny * ny).sqrt();
        let data: Vec<u8> = (0..4 * 2).flat_map(|_| t).collect();
        let m =
            moment_images(&image(4, 2, TextureFormat::Rg8Unorm, data)).expect("a valid normal map");
        let rgba = m.moments.data.as_deref().expect("CPU data");
        assert!(within_f16(half(rgba, 0), -nx / nz));
        assert!(within_f16(half(rgba, 1), -ny / nz));
        assert!(within_f16(half(rgba, 2), (nx / nz).powi(2)));
    }

    #[test]
    fn the_images_are_linear_float_chains_with_a_trilinear_sampler() {
        let img = image(4, 4, TextureFormat::Rgba8Unorm, random_rgba8(16, 3));
        let m = moment_images(&img).expect("a valid normal map");
        assert_eq!(
            m.moments.texture_descriptor.format,
            TextureFormat::Rgba16Float
        );
        assert_eq!(
            m.moments_xy.texture_descriptor.format,
            TextureFormat::R16Float
        );
        for i in [&m.moments, &m.moments_xy] {
            let ImageSampler::Descriptor(s) = &i.sampler else {
                panic!("an explicit sampler");
            };
            // The normal map's addressing, every filter linear.
            assert_eq!(s.address_mode_u, ImageAddressMode::Repeat);
            assert_eq!(s.address_mode_v, ImageAddressMode::MirrorRepeat);
            assert_eq!(s.mag_filter, ImageFilterMode::Linear);
            assert_eq!(s.min_filter, ImageFilterMode::Linear);
            assert_eq!(s.mipmap_filter, ImageFilterMode::Linear);
        }
    }

    #[test]
    fn bad_maps_are_refused_with_the_reason() {
        let ok = random_rgba8(4, 5);
        let srgb = image(2, 2, TextureFormat::Rgba8UnormSrgb, ok.clone());
        assert_eq!(
            moment_images(&srgb).err(),
            Some(MomentBakeError::Format(TextureFormat::Rgba8UnormSrgb))
        );
        let mut empty = image(2, 2, TextureFormat::Rgba8Unorm, ok.clone());
        empty.data = None;
        assert_eq!(moment_images(&empty).err(), Some(MomentBakeError::NoData));
        let mut short = image(2, 2, TextureFormat::Rgba8Unorm, ok.clone());
        short.data = Some(ok[..12].to_vec());
        assert_eq!(
            moment_images(&short).err(),
            Some(MomentBakeError::Length(16, 12))
        );
        // Texel (1, 1) points into the surface: (0, 0, -1).
        let mut below = ok.clone();
        below[12..16].copy_from_slice(&[128, 128, 0, 255]);
        let err = moment_images(&image(2, 2, TextureFormat::Rgba8Unorm, below)).err();
        assert!(
            matches!(
                err,
                Some(MomentBakeError::Bake(BakeError::BelowSurface {
                    x: 1,
                    y: 1,
                    ..
                }))
            ),
            "{err:?}"
        );
    }
}
