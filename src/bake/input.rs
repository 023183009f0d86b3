//! What the baker reads: tangent-space normal maps and height maps, checked once at
//! construction, then decoded texel by texel into slopes in the bake's tangent frame.
//!
//! # The bake's tangent frame
//! `x` along the texture's `+u` (columns, left to right), `y` along OpenGL's `+v` (up the
//! image: rows are stored top to bottom, so `y` points towards row 0), `z` the surface normal.
//! Slopes are the crate's `s = -n_xy / n_z` (module docs of `ndf`); for a height field
//! `z = h(x, y)` that is `s = grad h`.
//!
//! # Texel formats
//! | [`Texels`] | component value | normal component `c` |
//! |---|---|---|
//! | `Unorm8(v)` | `v / 255` in `[0, 1]` | `2 v / 255 - 1` |
//! | `Unorm16(v)` | `v / 65535` | `2 v / 65535 - 1` |
//! | `F32(v)` | `v` | `v` (signed, stored as is) |
//!
//! Decoding is exact in `f64` (every `Unorm8`/`Unorm16` code and every `f32` is a `f64`; the
//! division by `255` or `65535` rounds once, relative `2^-53`).

use crate::math as m;
use core::fmt;
use glam::{DVec2, DVec3};

/// The green-channel convention of a tangent-space normal map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Convention {
    /// Green is `+y` up the image (OpenGL, glTF, Blender, Unity): the bake's frame.
    OpenGl,
    /// Green is `+y` down the image (DirectX, Unreal, 3ds Max): `n_y` is negated on decode.
    DirectX,
}

/// How a height map's differences treat the border texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Edges {
    /// The map tiles: the neighbour of the last column is the first (periodic differences).
    Wrap,
    /// The map ends: the border texels take the one-sided difference towards the interior.
    Clamp,
}

/// Texel storage, row-major, top row first, `channels` interleaved components per texel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Texels<'a> {
    /// 8-bit unsigned normalised components.
    Unorm8(&'a [u8]),
    /// 16-bit unsigned normalised components.
    Unorm16(&'a [u16]),
    /// 32-bit float components, used as stored (a normal map's components are signed).
    F32(&'a [f32]),
}

impl Texels<'_> {
    /// The number of stored components.
    #[inline]
    pub fn len(&self) -> usize {
        match self {
            Texels::Unorm8(v) => v.len(),
            Texels::Unorm16(v) => v.len(),
            Texels::F32(v) => v.len(),
        }
    }

    /// Whether no component is stored.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Component `i` as stored: `Unorm*` as `v / max` in `[0, 1]`, `F32` as is.
    #[inline(always)]
    fn unit(&self, i: usize) -> f64 {
        match self {
            Texels::Unorm8(v) => v[i] as f64 * (1.0 / 255.0),
            Texels::Unorm16(v) => v[i] as f64 * (1.0 / 65535.0),
            Texels::F32(v) => v[i] as f64,
        }
    }

    /// Component `i` as a signed normal component: `2 u - 1` for `Unorm*`, as is for `F32`.
    #[inline(always)]
    fn signed(&self, i: usize) -> f64 {
        match self {
            Texels::Unorm8(v) => v[i] as f64 * (2.0 / 255.0) - 1.0,
            Texels::Unorm16(v) => v[i] as f64 * (2.0 / 65535.0) - 1.0,
            Texels::F32(v) => v[i] as f64,
        }
    }

    /// The largest quantisation step of a normal component (`2 / 255`, `2 / 65535`; `F32`:
    /// `0`).
    fn step(&self) -> f64 {
        match self {
            Texels::Unorm8(_) => 2.0 / 255.0,
            Texels::Unorm16(_) => 2.0 / 65535.0,
            Texels::F32(_) => 0.0,
        }
    }
}

/// Why a map was refused. Every texel error names the texel (`x` column, `y` row, from the
/// top-left) and the offending value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BakeError {
    /// Width or height is zero.
    ZeroSize,
    /// The number of channels is not supported (normal maps: 2, 3 or 4; height maps: 1 or
    /// more, the first used).
    Channels(usize),
    /// The texel slice does not hold `width * height * channels` components.
    Length {
        /// `width * height * channels`.
        expected: usize,
        /// The slice's length.
        got: usize,
    },
    /// A parameter (tolerance, texel spacing, height scale, roughness) is NaN, infinite or
    /// out of its documented range.
    Parameter(&'static str, f64),
    /// A component is NaN or infinite (`F32` texels).
    NotFinite {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The component.
        value: f32,
    },
    /// A normal's length differs from one by more than the tolerance.
    NotUnit {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The decoded length `|n|`.
        length: f64,
    },
    /// A normal points at or below the surface (`n_z <= 0`; for two-channel maps,
    /// `n_x^2 + n_y^2 >= 1`).
    BelowSurface {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The decoded `n_z` (`0` for a two-channel map whose `x^2 + y^2 >= 1`).
        z: f64,
    },
    /// A slope exceeds [`MAX_SLOPE`] (a normal within `0.06` degrees of the horizon, or a
    /// height difference that steep): its second moments would overflow `f16` storage by far
    /// and no roughness can represent it.
    TooSteep {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// `|s|`.
        slope: f64,
    },
    /// A roughness texel is NaN or outside `[0, 1]`.
    OutOfRange {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The value.
        value: f64,
    },
    /// An output or scratch slice is shorter than the layout needs.
    Output {
        /// Entries needed.
        expected: usize,
        /// The slice's length.
        got: usize,
    },
}

impl fmt::Display for BakeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            BakeError::ZeroSize => write!(f, "the map has zero width or height"),
            BakeError::Channels(c) => write!(f, "{c} channels are not supported"),
            BakeError::Length { expected, got } => {
                write!(f, "{got} components given, {expected} expected")
            }
            BakeError::Parameter(name, v) => write!(f, "{name} = {v} is out of range"),
            BakeError::NotFinite { x, y, value } => {
                write!(f, "texel ({x}, {y}) has the non-finite component {value}")
            }
            BakeError::NotUnit { x, y, length } => {
                write!(f, "texel ({x}, {y}) is not a unit normal: length {length}")
            }
            BakeError::BelowSurface { x, y, z } => {
                write!(f, "texel ({x}, {y}) points below the surface: n_z = {z}")
            }
            BakeError::TooSteep { x, y, slope } => {
                write!(
                    f,
                    "texel ({x}, {y}) has the slope {slope}, steeper than MAX_SLOPE"
                )
            }
            BakeError::OutOfRange { x, y, value } => {
                write!(
                    f,
                    "texel ({x}, {y}) has the roughness {value}, outside [0, 1]"
                )
            }
            BakeError::Output { expected, got } => {
                write!(f, "an output holds {got} entries, {expected} needed")
            }
        }
    }
}

impl core::error::Error for BakeError {}

/// The steepest slope a texel may have, `|s| <= 1000` (a normal `0.057` degrees above the
/// horizon): `|s|^2 <= 1e6` keeps every second moment finite in `f32` storage and within a
/// factor of 16 of `f16`'s largest value (which saturates, [`super::f16`]).
pub const MAX_SLOPE: f64 = 1000.0;

/// A source of slopes over a `width x height` grid of texels: what the bake reads.
/// Implemented by [`NormalMap`] and [`HeightMap`], whose checked constructors make every
/// texel decodable: the methods never fail and never return NaN.
pub trait SlopeSource {
    /// Texels per row.
    fn width(&self) -> usize;
    /// Rows.
    fn height(&self) -> usize;
    /// Texel `(x, y)`'s slope `s` in the bake's frame and its unit normal
    /// `n = (-s, 1) / sqrt(1 + |s|^2)` (column `x < width`, row `y < height`; panics outside).
    fn texel(&self, x: usize, y: usize) -> (DVec2, DVec3);
}

/// The layout and convention of a normal map's texels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalFormat {
    /// Components per texel: 2 (`x, y`, BC5-style: `z = sqrt(1 - x^2 - y^2)`), 3 (`x, y, z`)
    /// or 4 (`x, y, z` and an ignored fourth).
    pub channels: usize,
    /// The green-channel convention.
    pub convention: Convention,
    /// The largest accepted `| |n| - 1 |` (three- and four-channel maps), and for two-channel
    /// maps the largest accepted `x^2 + y^2 - 1` before `z` is taken as `0` (below the
    /// surface). `None`: [`NormalFormat::default_tolerance`] of the texels. Normals are
    /// normalised before use: the slope `-n_xy / n_z` does not depend on `|n|`, and the
    /// tolerance only rejects data that is not a normal map. `f64::INFINITY` accepts any
    /// non-zero vector (maps that were resized without renormalising).
    pub tolerance: Option<f64>,
}

impl NormalFormat {
    /// `channels` components per texel in `convention`, the default tolerance.
    pub const fn new(channels: usize, convention: Convention) -> Self {
        Self {
            channels,
            convention,
            tolerance: None,
        }
    }

    /// The same format with the tolerance `tolerance`.
    pub const fn with_tolerance(self, tolerance: f64) -> Self {
        Self {
            tolerance: Some(tolerance),
            ..self
        }
    }

    /// The default tolerance of a normal's length: `1e-3` for `F32` texels (data that went
    /// through `f16` still passes), and for `Unorm` texels twice the largest length error
    /// that rounding a unit normal to the grid can cause, `2 * sqrt(3) * step / 2`
    /// (`step = 2 / 255`: `0.0136`; `2 / 65535`: `5.3e-5`), plus `1e-6`.
    pub fn default_tolerance(texels: &Texels<'_>) -> f64 {
        match texels {
            Texels::F32(_) => 1e-3,
            t => m::sqrt(3.0) * t.step() + 1e-6,
        }
    }
}

/// A checked tangent-space normal map.
#[derive(Clone, Copy, Debug)]
pub struct NormalMap<'a> {
    texels: Texels<'a>,
    width: usize,
    height: usize,
    channels: usize,
    flip_y: bool,
}

/// The length of `texels` must be `width * height * channels`, without overflow.
fn check_len(texels: &Texels<'_>, width: usize, height: usize, ch: usize) -> Result<(), BakeError> {
    if width == 0 || height == 0 {
        return Err(BakeError::ZeroSize);
    }
    let expected = width
        .checked_mul(height)
        .and_then(|n| n.checked_mul(ch))
        .ok_or(BakeError::Length {
            expected: usize::MAX,
            got: texels.len(),
        })?;
    if texels.len() != expected {
        return Err(BakeError::Length {
            expected,
            got: texels.len(),
        });
    }
    Ok(())
}

/// The first non-finite component of an `F32` slice, as a texel error.
fn check_finite(texels: &Texels<'_>, width: usize, ch: usize) -> Result<(), BakeError> {
    if let Texels::F32(v) = texels
        && let Some(i) = v.iter().position(|c| !c.is_finite())
    {
        let t = i / ch;
        return Err(BakeError::NotFinite {
            x: t % width,
            y: t / width,
            value: v[i],
        });
    }
    Ok(())
}

impl<'a> NormalMap<'a> {
    /// Checks every texel: the slice's length, finite components, `| |n| - 1 |` within the
    /// tolerance (three or four channels) or `x^2 + y^2 - 1` within it (two channels),
    /// `n_z > 0`, and `|s| <= MAX_SLOPE`. The first failing texel in row-major order is
    /// reported ([`BakeError`]).
    pub fn new(
        texels: Texels<'a>,
        width: usize,
        height: usize,
        format: NormalFormat,
    ) -> Result<Self, BakeError> {
        let ch = format.channels;
        if !(2..=4).contains(&ch) {
            return Err(BakeError::Channels(ch));
        }
        check_len(&texels, width, height, ch)?;
        check_finite(&texels, width, ch)?;
        let tol = format
            .tolerance
            .unwrap_or_else(|| NormalFormat::default_tolerance(&texels));
        if tol.is_nan() || tol < 0.0 {
            return Err(BakeError::Parameter("tolerance", tol));
        }
        let map = Self {
            texels,
            width,
            height,
            channels: ch,
            flip_y: format.convention == Convention::DirectX,
        };
        for y in 0..height {
            for x in 0..width {
                let i = (y * width + x) * ch;
                let (nx, ny) = (texels.signed(i), texels.signed(i + 1));
                let r2 = nx * nx + ny * ny;
                let nz = if ch == 2 {
                    if r2 - 1.0 > tol {
                        return Err(BakeError::NotUnit {
                            x,
                            y,
                            length: m::sqrt(r2),
                        });
                    }
                    m::sqrt((1.0 - r2).max(0.0))
                } else {
                    let nz = texels.signed(i + 2);
                    let len = m::sqrt(r2 + nz * nz);
                    if len.is_nan() || (len - 1.0).abs() > tol {
                        return Err(BakeError::NotUnit { x, y, length: len });
                    }
                    nz
                };
                if nz.is_nan() || nz <= 0.0 {
                    return Err(BakeError::BelowSurface { x, y, z: nz });
                }
                let slope = m::sqrt(r2) / nz;
                if slope.is_nan() || slope > MAX_SLOPE {
                    return Err(BakeError::TooSteep { x, y, slope });
                }
            }
        }
        Ok(map)
    }
}

impl SlopeSource for NormalMap<'_> {
    #[inline]
    fn width(&self) -> usize {
        self.width
    }
    #[inline]
    fn height(&self) -> usize {
        self.height
    }
    #[inline(always)]
    fn texel(&self, x: usize, y: usize) -> (DVec2, DVec3) {
        assert!(x < self.width && y < self.height);
        let i = (y * self.width + x) * self.channels;
        let t = &self.texels;
        let nx = t.signed(i);
        let ny = if self.flip_y {
            -t.signed(i + 1)
        } else {
            t.signed(i + 1)
        };
        let nz = if self.channels == 2 {
            m::sqrt((1.0 - nx * nx - ny * ny).max(0.0))
        } else {
            t.signed(i + 2)
        };
        let inv = 1.0 / nz;
        let n = DVec3::new(nx, ny, nz);
        (DVec2::new(-nx * inv, -ny * inv), n * (1.0 / n.length()))
    }
}

/// How a height map's texel values become heights and slopes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightFormat {
    /// Components per texel (the first is the height; 1 or more).
    pub channels: usize,
    /// World units per texel step (`> 0`, finite), the same along rows and columns.
    pub texel_spacing: f64,
    /// World height of a texel value of one (`Unorm`: the full code range; `F32`: the value
    /// as stored), finite; negative inverts the relief.
    pub height_scale: f64,
    /// The border rule of the differences.
    pub edges: Edges,
}

/// A checked height map. Slopes by central differences of the heights
/// `h = height_scale * value` over `2 * texel_spacing`:
///
/// `s_x(x, y) = (h(x + 1, y) - h(x - 1, y)) / (2 d)`,
/// `s_y(x, y) = (h(x, y - 1) - h(x, y + 1)) / (2 d)` (rows go down, `y` up),
///
/// periodic with [`Edges::Wrap`]; with [`Edges::Clamp`] the first and last texel of a row or
/// column take the one-sided difference over `d` (a map one texel wide has zero slope along
/// that axis). For `h = a sin(k x)` sampled at texel centres the central difference is
/// `a k cos(k x) sin(k d) / (k d)`: the slope of the sampled height field, attenuated by
/// `sinc(k d)` at frequencies near the texel rate.
#[derive(Clone, Copy, Debug)]
pub struct HeightMap<'a> {
    texels: Texels<'a>,
    width: usize,
    height: usize,
    channels: usize,
    /// `height_scale / (2 d)`.
    scale: f64,
    edges: Edges,
}

impl<'a> HeightMap<'a> {
    /// Checks the slice's length, finite components, the parameters, and that every slope
    /// is within [`MAX_SLOPE`].
    pub fn new(
        texels: Texels<'a>,
        width: usize,
        height: usize,
        format: HeightFormat,
    ) -> Result<Self, BakeError> {
        let ch = format.channels;
        if ch == 0 {
            return Err(BakeError::Channels(0));
        }
        check_len(&texels, width, height, ch)?;
        check_finite(&texels, width, ch)?;
        let d = format.texel_spacing;
        if !(d > 0.0 && d.is_finite()) {
            return Err(BakeError::Parameter("texel_spacing", d));
        }
        let hs = format.height_scale;
        if !hs.is_finite() {
            return Err(BakeError::Parameter("height_scale", hs));
        }
        let scale = hs / (2.0 * d);
        if !scale.is_finite() {
            return Err(BakeError::Parameter("height_scale / texel_spacing", scale));
        }
        let map = Self {
            texels,
            width,
            height,
            channels: ch,
            scale,
            edges: format.edges,
        };
        for y in 0..height {
            for x in 0..width {
                let s = map.slope(x, y);
                let slope = s.length();
                if slope.is_nan() || slope > MAX_SLOPE {
                    return Err(BakeError::TooSteep { x, y, slope });
                }
            }
        }
        Ok(map)
    }

    #[inline(always)]
    fn h(&self, x: usize, y: usize) -> f64 {
        self.texels.unit((y * self.width + x) * self.channels)
    }

    /// `(h(after) - h(before)) * factor`, `factor` 1 for a central and 2 for a one-sided
    /// difference, along one axis of length `n` at index `i`.
    #[inline(always)]
    fn neighbours(&self, i: usize, n: usize) -> (usize, usize, f64) {
        match self.edges {
            Edges::Wrap => ((i + n - 1) % n, (i + 1) % n, 1.0),
            Edges::Clamp => {
                if n == 1 {
                    (0, 0, 0.0)
                } else if i == 0 {
                    (0, 1, 2.0)
                } else if i == n - 1 {
                    (n - 2, n - 1, 2.0)
                } else {
                    (i - 1, i + 1, 1.0)
                }
            }
        }
    }

    #[inline(always)]
    fn slope(&self, x: usize, y: usize) -> DVec2 {
        let (x0, x1, fx) = self.neighbours(x, self.width);
        let (y0, y1, fy) = self.neighbours(y, self.height);
        DVec2::new(
            (self.h(x1, y) - self.h(x0, y)) * (fx * self.scale),
            (self.h(x, y0) - self.h(x, y1)) * (fy * self.scale),
        )
    }
}

impl SlopeSource for HeightMap<'_> {
    #[inline]
    fn width(&self) -> usize {
        self.width
    }
    #[inline]
    fn height(&self) -> usize {
        self.height
    }
    #[inline(always)]
    fn texel(&self, x: usize, y: usize) -> (DVec2, DVec3) {
        assert!(x < self.width && y < self.height);
        let s = self.slope(x, y);
        let n = DVec3::new(-s.x, -s.y, 1.0);
        (s, n * (1.0 / n.length()))
    }
}

/// Slopes given directly in `f64` (the bake's frame), for procedural surfaces and tests.
#[derive(Clone, Copy, Debug)]
pub struct SlopeMap<'a> {
    slopes: &'a [DVec2],
    width: usize,
    height: usize,
}

impl<'a> SlopeMap<'a> {
    /// Checks the length, finite components and `|s| <= MAX_SLOPE` (the error's `value` is
    /// the offending component, `NotFinite`, or `|s|`, `TooSteep`).
    pub fn new(slopes: &'a [DVec2], width: usize, height: usize) -> Result<Self, BakeError> {
        if width == 0 || height == 0 {
            return Err(BakeError::ZeroSize);
        }
        let expected = width.saturating_mul(height);
        if slopes.len() != expected {
            return Err(BakeError::Length {
                expected,
                got: slopes.len(),
            });
        }
        for (i, s) in slopes.iter().enumerate() {
            let (x, y) = (i % width, i / width);
            if !s.is_finite() {
                let value = if s.x.is_finite() { s.y } else { s.x };
                return Err(BakeError::NotFinite {
                    x,
                    y,
                    value: value as f32,
                });
            }
            if s.length() > MAX_SLOPE {
                return Err(BakeError::TooSteep {
                    x,
                    y,
                    slope: s.length(),
                });
            }
        }
        Ok(Self {
            slopes,
            width,
            height,
        })
    }
}

impl SlopeSource for SlopeMap<'_> {
    #[inline]
    fn width(&self) -> usize {
        self.width
    }
    #[inline]
    fn height(&self) -> usize {
        self.height
    }
    #[inline(always)]
    fn texel(&self, x: usize, y: usize) -> (DVec2, DVec3) {
        assert!(x < self.width && y < self.height);
        let s = self.slopes[y * self.width + x];
        let n = DVec3::new(-s.x, -s.y, 1.0);
        (s, n * (1.0 / n.length()))
    }
}
