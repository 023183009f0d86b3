//! Reading the input images: PNG (8 or 16 bits per channel, grey, grey and alpha, RGB, RGBA)
//! and OpenEXR (32-bit float RGB or RGBA; `f16` channels arrive as `f32`), through the `image`
//! crate. Texels stay as stored (no colour conversion: normal, height and roughness maps
//! are data).

use crate::Error;
use filtered_ndf::bake::Texels;
use image::DynamicImage;
use std::path::Path;

/// Texel storage of a decoded image.
#[derive(Clone, Debug, PartialEq)]
pub enum Samples {
    /// 8-bit unsigned normalised components.
    U8(Vec<u8>),
    /// 16-bit unsigned normalised components.
    U16(Vec<u16>),
    /// 32-bit float components.
    F32(Vec<f32>),
}

/// A decoded image: `channels` interleaved components per texel, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Texels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Components per texel (1 to 4).
    pub channels: usize,
    /// The components.
    pub samples: Samples,
}

impl Image {
    /// The components as the library reads them.
    pub fn texels(&self) -> Texels<'_> {
        match &self.samples {
            Samples::U8(v) => Texels::Unorm8(v),
            Samples::U16(v) => Texels::Unorm16(v),
            Samples::F32(v) => Texels::F32(v),
        }
    }

    /// The same texels with only the channels `keep` (in that order).
    pub fn select(&self, keep: &[usize]) -> Image {
        fn pick<T: Copy>(v: &[T], ch: usize, keep: &[usize]) -> Vec<T> {
            v.chunks_exact(ch)
                .flat_map(|px| keep.iter().map(move |&c| px[c]))
                .collect()
        }
        let ch = self.channels;
        let samples = match &self.samples {
            Samples::U8(v) => Samples::U8(pick(v, ch, keep)),
            Samples::U16(v) => Samples::U16(pick(v, ch, keep)),
            Samples::F32(v) => Samples::F32(pick(v, ch, keep)),
        };
        Image {
            width: self.width,
            height: self.height,
            channels: keep.len(),
            samples,
        }
    }

    /// Component `c` of texel `(x, y)` as a value in `[0, 1]` (`Unorm`) or as stored (`F32`).
    pub fn value(&self, x: usize, y: usize, c: usize) -> f64 {
        let i = (y * self.width + x) * self.channels + c;
        match &self.samples {
            Samples::U8(v) => f64::from(v[i]) / 255.0,
            Samples::U16(v) => f64::from(v[i]) / 65535.0,
            Samples::F32(v) => f64::from(v[i]),
        }
    }
}

/// Reads and decodes `path`. Errors name the file: it cannot be read, it is not an image
/// the baker decodes (the format is guessed from the content, not the extension), or its
/// texel layout is one the baker does not take.
pub fn read(path: &Path) -> Result<Image, Error> {
    let reader = image::ImageReader::open(path)
        .map_err(|e| Error::file(path, format!("cannot be read: {e}")))?
        .with_guessed_format()
        .map_err(|e| Error::file(path, format!("cannot be read: {e}")))?;
    if reader.format().is_none() {
        return Err(Error::file(
            path,
            "is not an image the baker reads (PNG or OpenEXR)",
        ));
    }
    let mut reader = reader;
    reader.no_limits();
    let img = reader
        .decode()
        .map_err(|e| Error::file(path, format!("is not a valid image: {e}")))?;
    from_dynamic(img).map_err(|m| Error::file(path, m))
}

/// The texels of a decoded image.
pub fn from_dynamic(img: DynamicImage) -> Result<Image, String> {
    let (width, height) = (img.width() as usize, img.height() as usize);
    let (channels, samples) = match img {
        DynamicImage::ImageLuma8(b) => (1, Samples::U8(b.into_raw())),
        DynamicImage::ImageLumaA8(b) => (2, Samples::U8(b.into_raw())),
        DynamicImage::ImageRgb8(b) => (3, Samples::U8(b.into_raw())),
        DynamicImage::ImageRgba8(b) => (4, Samples::U8(b.into_raw())),
        DynamicImage::ImageLuma16(b) => (1, Samples::U16(b.into_raw())),
        DynamicImage::ImageLumaA16(b) => (2, Samples::U16(b.into_raw())),
        DynamicImage::ImageRgb16(b) => (3, Samples::U16(b.into_raw())),
        DynamicImage::ImageRgba16(b) => (4, Samples::U16(b.into_raw())),
        DynamicImage::ImageRgb32F(b) => (3, Samples::F32(b.into_raw())),
        DynamicImage::ImageRgba32F(b) => (4, Samples::F32(b.into_raw())),
        other => {
            return Err(format!(
                "has an unsupported texel layout {:?}",
                other.color()
            ));
        }
    };
    if width == 0 || height == 0 {
        return Err(format!("has zero size ({width}x{height})"));
    }
    Ok(Image {
        width,
        height,
        channels,
        samples,
    })
}
