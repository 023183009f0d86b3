//! HDR images, tone mapping, error metrics, and the labelled contact sheet (8-bit images
//! from the `image` crate, labels drawn with `ab_glyph` in the embedded DejaVu Sans).

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use glam::Vec3;
use image::{Rgb, RgbImage};

/// An 8-bit sRGB image.
pub type Rgb8 = RgbImage;

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

    /// RMSE over the pixels where `mask` is true (0 if none).
    #[allow(dead_code)] // used by the GPU demonstration only
    pub fn rmse_where(&self, other: &Image, mask: &[bool]) -> f64 {
        rmse(
            self.data
                .iter()
                .zip(&other.data)
                .zip(mask)
                .filter(|(_, m)| **m)
                .map(|(pair, _)| (*pair.0, *pair.1)),
        )
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

    /// The mean pixel luminance.
    pub fn mean_luminance(&self) -> f64 {
        self.data.iter().map(|&c| luminance(c) as f64).sum::<f64>() / self.data.len() as f64
    }

    /// 8-bit sRGB after tone mapping with `exposure`.
    pub fn to_rgb8(&self, exposure: f32) -> Rgb8 {
        RgbImage::from_fn(self.width as u32, self.height as u32, |x, y| {
            let t = tonemap(self.data[y as usize * self.width + x as usize], exposure);
            Rgb([encode(t.x), encode(t.y), encode(t.z)])
        })
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
pub fn encode(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// The labels' font: DejaVu Sans, embedded by the `dejavu` crate (no system font needed).
pub fn font() -> FontRef<'static> {
    FontRef::try_from_slice(dejavu::sans::regular()).expect("DejaVu Sans parses")
}

/// Draws `text` with its top-left corner at `(x0, y0)`, `px` pixels high, blending the glyph
/// coverage over the image.
pub fn draw_text(img: &mut RgbImage, text: &str, x0: f32, y0: f32, px: f32, color: [u8; 3]) {
    let font = font();
    let scaled = font.as_scaled(PxScale::from(px));
    let mut caret = x0;
    let mut previous = None;
    for ch in text.chars() {
        let id = scaled.glyph_id(ch);
        if let Some(p) = previous {
            caret += scaled.kern(p, id);
        }
        let glyph = id.with_scale_and_position(px, ab_glyph::point(caret, y0 + scaled.ascent()));
        caret += scaled.h_advance(id);
        previous = Some(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue;
        };
        let b = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (x, y) = (b.min.x as i64 + gx as i64, b.min.y as i64 + gy as i64);
            if x < 0 || y < 0 || x >= img.width() as i64 || y >= img.height() as i64 {
                return;
            }
            let p = img.get_pixel_mut(x as u32, y as u32);
            let a = coverage.clamp(0.0, 1.0);
            for (channel, &c) in p.0.iter_mut().zip(&color) {
                *channel = (*channel as f32 * (1.0 - a) + c as f32 * a).round() as u8;
            }
        });
    }
}

/// A grid of labelled tiles, `columns` wide, each image zoomed by `zoom` (nearest pixel).
pub fn contact_sheet(tiles: &[(String, Rgb8)], columns: usize, zoom: u32) -> Rgb8 {
    let (tw, th) = (tiles[0].1.width() * zoom, tiles[0].1.height() * zoom);
    let (pad, label_h) = (6, 24);
    let columns = columns.min(tiles.len()).max(1);
    let rows = tiles.len().div_ceil(columns) as u32;
    let (cw, ch) = (tw + pad, th + label_h + pad);
    let mut sheet = RgbImage::from_pixel(
        pad + columns as u32 * cw,
        pad + rows * ch,
        Rgb([24, 24, 28]),
    );
    for (i, (label, img)) in tiles.iter().enumerate() {
        let (col, row) = ((i % columns) as u32, (i / columns) as u32);
        let (x0, y0) = (pad + col * cw, pad + row * ch);
        let tile = image::imageops::resize(img, tw, th, image::imageops::FilterType::Nearest);
        image::imageops::replace(&mut sheet, &tile, x0 as i64, y0 as i64);
        draw_text(
            &mut sheet,
            label,
            x0 as f32,
            (y0 + th + 3) as f32,
            16.0,
            [235, 235, 235],
        );
    }
    sheet
}

/// Writes `img` as a PNG.
pub fn save(img: &Rgb8, path: &std::path::Path) -> std::io::Result<()> {
    img.save(path).map_err(std::io::Error::other)
}
