//! The inspection images: one PNG per level and output, and the contact sheet (every level
//! side by side, one row per output).

use crate::Error;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use std::path::Path;

/// An 8-bit image: `channels` (1 or 3) interleaved components, rows top to bottom.
#[derive(Clone, Debug)]
pub struct Plane {
    /// Texels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// 1 (grey) or 3 (RGB).
    pub channels: usize,
    /// The components.
    pub data: Vec<u8>,
}

/// Writes `p` as a PNG (fast compression: the images are for inspection).
pub fn write_png(path: &Path, p: &Plane) -> Result<(), Error> {
    let file = std::fs::File::create(path)
        .map_err(|e| Error::file(path, format!("cannot be created: {e}")))?;
    let color = if p.channels == 1 {
        ExtendedColorType::L8
    } else {
        ExtendedColorType::Rgb8
    };
    PngEncoder::new_with_quality(
        std::io::BufWriter::new(file),
        CompressionType::Fast,
        FilterType::Adaptive,
    )
    .write_image(&p.data, p.width as u32, p.height as u32, color)
    .map_err(|e| Error::file(path, format!("cannot be written: {e}")))
}

/// Side of a contact sheet's cell.
pub const CELL: usize = 128;
/// Gap between cells.
const GAP: usize = 2;

/// The contact sheet of `rows` (each a list of levels of one output, all with `channels`
/// components, grey rows expanded to RGB): each level point-sampled into a [`CELL`]-sized
/// cell, keeping its aspect (levels larger than a cell are subsampled, smaller ones magnified
/// texel by texel), level 0 on the left.
pub fn contact_sheet(rows: &[Vec<Plane>]) -> Plane {
    let cols = rows.iter().map(Vec::len).max().unwrap_or(0);
    let width = GAP + cols * (CELL + GAP);
    let height = GAP + rows.len() * (CELL + GAP);
    let mut data = vec![96u8; width * height * 3];
    for (r, levels) in rows.iter().enumerate() {
        for (c, p) in levels.iter().enumerate() {
            let scale = CELL as f64 / p.width.max(p.height) as f64;
            let (w, h) = (
                ((p.width as f64 * scale).round() as usize).clamp(1, CELL),
                ((p.height as f64 * scale).round() as usize).clamp(1, CELL),
            );
            let (ox, oy) = (GAP + c * (CELL + GAP), GAP + r * (CELL + GAP));
            for y in 0..h {
                let sy = ((y as f64 + 0.5) / scale) as usize;
                for x in 0..w {
                    let sx = ((x as f64 + 0.5) / scale) as usize;
                    let i = (sy.min(p.height - 1) * p.width + sx.min(p.width - 1)) * p.channels;
                    let o = ((oy + y) * width + ox + x) * 3;
                    for k in 0..3 {
                        data[o + k] = p.data[i + k.min(p.channels - 1)];
                    }
                }
            }
        }
    }
    Plane {
        width,
        height,
        channels: 3,
        data,
    }
}
