//! HDR images, tone mapping, error metrics, PNG output and the labelled contact sheet.

use crate::font;
use glam::Vec3;
use std::path::Path;

/// A linear HDR RGB image.
#[derive(Clone, Debug)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub data: Vec<Vec3>,
}

/// Rec. 709 luminance.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

impl Image {
    pub fn new(width: usize, height: usize, data: Vec<Vec3>) -> Self {
        assert_eq!(data.len(), width * height);
        Self {
            width,
            height,
            data,
        }
    }

    /// The largest pixel luminance (the "peak HDR intensity" of KHPL16 Fig. 12).
    pub fn peak(&self) -> f32 {
        self.data.iter().map(|&c| luminance(c)).fold(0.0, f32::max)
    }

    /// RMSE over pixels and channels against `other`, in linear HDR radiance.
    pub fn rmse(&self, other: &Image) -> f64 {
        rmse(self.data.iter().zip(&other.data).map(|(a, b)| (*a, *b)))
    }

    /// RMSE of the tone-mapped display values (in `[0, 1]`) against `other`.
    pub fn rmse_display(&self, other: &Image, exposure: f32) -> f64 {
        let tm = |c: Vec3| tonemap(c, exposure);
        rmse(
            self.data
                .iter()
                .zip(&other.data)
                .map(|(a, b)| (tm(*a), tm(*b))),
        )
    }

    /// 8-bit sRGB after tone mapping with `exposure`.
    pub fn to_rgb8(&self, exposure: f32) -> Rgb8 {
        let mut out = Rgb8::new(self.width, self.height, [0, 0, 0]);
        for (i, &c) in self.data.iter().enumerate() {
            let t = tonemap(c, exposure);
            out.data[i] = [encode(t.x), encode(t.y), encode(t.z)];
        }
        out
    }
}

fn rmse(pairs: impl Iterator<Item = (Vec3, Vec3)>) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (a, b) in pairs {
        let d = (a - b).as_dvec3();
        sum += d.length_squared();
        n += 3;
    }
    (sum / n.max(1) as f64).sqrt()
}

/// Exposure, then a per-channel Reinhard curve `x / (1 + x)`: linear display value in [0, 1].
pub fn tonemap(c: Vec3, exposure: f32) -> Vec3 {
    let x = (c * exposure).max(Vec3::ZERO);
    x / (Vec3::ONE + x)
}

/// Linear `[0, 1]` to 8-bit sRGB.
fn encode(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// An 8-bit RGB canvas.
#[derive(Clone, Debug)]
pub struct Rgb8 {
    pub width: usize,
    pub height: usize,
    pub data: Vec<[u8; 3]>,
}

impl Rgb8 {
    pub fn new(width: usize, height: usize, fill: [u8; 3]) -> Self {
        Self {
            width,
            height,
            data: vec![fill; width * height],
        }
    }

    pub fn set(&mut self, x: i64, y: i64, c: [u8; 3]) {
        if x >= 0 && y >= 0 && (x as usize) < self.width && (y as usize) < self.height {
            self.data[y as usize * self.width + x as usize] = c;
        }
    }

    /// Copies `src` scaled up by the integer factor `zoom` with its top-left at `(x0, y0)`.
    pub fn blit(&mut self, src: &Rgb8, x0: usize, y0: usize, zoom: usize) {
        for y in 0..src.height * zoom {
            for x in 0..src.width * zoom {
                let c = src.data[(y / zoom) * src.width + x / zoom];
                self.set((x0 + x) as i64, (y0 + y) as i64, c);
            }
        }
    }

    /// Draws `text` with the built-in 5x7 font, each font pixel `scale` pixels wide.
    pub fn text(&mut self, text: &str, x0: usize, y0: usize, scale: usize, c: [u8; 3]) {
        for (k, ch) in text.chars().enumerate() {
            let glyph = font::glyph(ch);
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..5 {
                    if bits & (0x10 >> col) != 0 {
                        for dy in 0..scale {
                            for dx in 0..scale {
                                let x = x0 + (k * 6 + col) * scale + dx;
                                let y = y0 + row * scale + dy;
                                self.set(x as i64, y as i64, c);
                            }
                        }
                    }
                }
            }
        }
    }

    pub fn save(&self, path: &Path) -> std::io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let mut enc = png::Encoder::new(file, self.width as u32, self.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(std::io::Error::other)?;
        let bytes: Vec<u8> = self.data.iter().flatten().copied().collect();
        w.write_image_data(&bytes).map_err(std::io::Error::other)?;
        w.finish().map_err(std::io::Error::other)
    }
}

/// A grid of labelled tiles, `columns` wide, each image zoomed by `zoom`.
pub fn contact_sheet(tiles: &[(String, Rgb8)], columns: usize, zoom: usize) -> Rgb8 {
    let (tw, th) = (tiles[0].1.width * zoom, tiles[0].1.height * zoom);
    let (pad, label_h, scale) = (6, 7 * 2 + 8, 2);
    let columns = columns.min(tiles.len()).max(1);
    let rows = tiles.len().div_ceil(columns);
    let (cw, ch) = (tw + pad, th + label_h + pad);
    let mut sheet = Rgb8::new(pad + columns * cw, pad + rows * ch, [24, 24, 28]);
    for (i, (label, img)) in tiles.iter().enumerate() {
        let (x0, y0) = (pad + (i % columns) * cw, pad + (i / columns) * ch);
        sheet.blit(img, x0, y0, zoom);
        sheet.text(
            &label.to_uppercase(),
            x0,
            y0 + th + 4,
            scale,
            [235, 235, 235],
        );
    }
    sheet
}
