//! Frames from Bevy's render targets: `Rgba16Float` images read back to the CPU
//! (`bevy::render::gpu_readback`), decoded to the demonstration's linear `Image`, and box
//! filtered down from a supersampled target.

use filtered_ndf_demo::image_out::Image;

/// The bytes per texel of `Rgba16Float`.
pub const TEXEL_BYTES: usize = 8;

/// IEEE 754 binary16 to `f32` (exact: every half is a float).
pub fn half_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0f32 } else { 1.0 };
    let exponent = i32::from((h >> 10) & 0x1f);
    let mantissa = f32::from(h & 0x3ff);
    match exponent {
        0 => sign * mantissa * (-24f32).exp2(),
        31 if mantissa == 0.0 => sign * f32::INFINITY,
        31 => f32::NAN,
        e => sign * (1.0 + mantissa / 1024.0) * ((e - 15) as f32).exp2(),
    }
}

/// The linear RGB image in the bytes of a read-back `Rgba16Float` texture of `width` x
/// `height`, whose rows are padded to `bytes_per_row` (wgpu's copy alignment). `None` if
/// the data is too short.
pub fn decode_rgba16f(data: &[u8], width: usize, height: usize) -> Option<Image> {
    if height == 0 {
        return Some(Image::new(width, 0, Vec::new()));
    }
    let bytes_per_row = data.len() / height;
    if bytes_per_row < width * TEXEL_BYTES {
        return None;
    }
    let mut out = Vec::with_capacity(width * height);
    for y in 0..height {
        let row = &data[y * bytes_per_row..][..width * TEXEL_BYTES];
        for t in row.chunks_exact(TEXEL_BYTES) {
            let c = |i: usize| half_to_f32(u16::from_le_bytes([t[2 * i], t[2 * i + 1]]));
            out.push(glam::Vec3::new(c(0), c(1), c(2)));
        }
    }
    Some(Image::new(width, height, out))
}

/// The mean over each `factor` x `factor` block (the box filter of the pixel: a supersampled
/// frame down to the frame's resolution).
pub fn box_downsample(img: &Image, factor: usize) -> Image {
    let (w, h) = (img.width / factor, img.height / factor);
    let mut out = Vec::with_capacity(w * h);
    let norm = 1.0 / (factor * factor) as f32;
    for y in 0..h {
        for x in 0..w {
            let mut sum = glam::Vec3::ZERO;
            for j in 0..factor {
                let row = &img.data[(y * factor + j) * img.width + x * factor..][..factor];
                for &c in row {
                    sum += c;
                }
            }
            out.push(sum * norm);
        }
    }
    Image::new(w, h, out)
}
