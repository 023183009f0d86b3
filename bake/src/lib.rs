//! The command-line baker of `filtered-ndf`: a tangent-space normal map (or a height map) in,
//! the roughness mip chain and the LEAN moment chain out, each as a KTX2 texture with every
//! mip level, with a PNG per level, a contact sheet and a report.
//!
//! ```text
//! bake NORMAL.png --out DIR [--height] [--roughness 0.3|ROUGHNESS.png] [--convention gl|dx]
//!      [--anisotropic] [--kernel box|area] [options]
//! ```
//!
//! [`USAGE`] lists every option. The bake is `filtered_ndf::bake::bake_rows` over bands of
//! rows on rayon's pool ([`chain`]); the files are described in [`encode`] and `docs/bake.md`.
//!
//! **Bad input writes nothing.** Every input texel is checked before anything is written
//! (the library's checked constructors: not an image, wrong channel count, zero size, NaN or
//! infinite floats, normals that are not unit or point below the surface, roughness outside
//! `[0, 1]`, sizes that differ); the error names the file and the texel. The outputs are
//! written into a temporary directory beside `DIR` and renamed to `DIR` at the end, so a
//! failure leaves `DIR` as it was (absent, or the previous bake). An existing `DIR` is
//! replaced only if it is empty or holds a previous bake (its `report.md`). A bake killed
//! while writing leaves its temporary directory `.DIR.bake-PID` beside `DIR` (and `DIR` as
//! it was); delete it by hand.
//!
//! # Who loads the files
//! Every chain is a KTX 2.0 file ([`ktx`]) of an uncompressed Vulkan format with all its mip
//! levels, no supercompression, transfer function linear (the chains are data, not colour):
//! - **wgpu**: upload the file's levels with `DeviceExt::create_texture_with_data` in
//!   mip-major order, `mip_level_count` = the file's `levelCount`; tested for every format the
//!   baker writes (`tests/wgpu_load.rs`, on lavapipe).
//! - **Bevy**: its `ktx2` feature (`bevy_image`'s KTX2 loader, built on the `ktx2` crate, the
//!   reader `tests/cli.rs` checks the files with) maps `R8_UNORM`, `R8G8B8A8_UNORM`,
//!   `R16_SFLOAT`, `R16G16B16A16_SFLOAT`, `R32_SFLOAT`, `R32G32B32A32_SFLOAT` to the wgpu
//!   formats of the same names and keeps the levels.
//! - **three.js**: `KTX2Loader` reads these six formats without transcoding (its table of
//!   uncompressed formats, `FORMAT_MAP` in `examples/jsm/loaders/KTX2Loader.js`), levels
//!   included.
//! - **Godot 4** (`modules/ktx/texture_loader_ktx.cpp`, through libktx): `R8_UNORM` (as
//!   `L8`), `R16_SFLOAT`, `R16G16B16A16_SFLOAT`, `R32_SFLOAT`, `R32G32B32A32_SFLOAT` with their
//!   levels; it has no case for `R8G8B8A8_UNORM` (only `_SRGB` and `_UINT`), so the
//!   `anisotropy.ktx2` texture of `--anisotropic` does not load there as written.
//!
//! Only the wgpu path is tested here; the others are read from their loaders' sources.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod chain;
pub mod encode;
pub mod images;
pub mod ktx;
pub mod load;
pub mod report;

use chain::{Chains, Ndf};
use encode::{Precision, Store};
use filtered_ndf::bake::{
    BaseRoughness, Convention, Edges, HeightFormat, HeightMap, Kernel, NormalFormat, NormalMap,
    RoughnessMap, Settings, SlopeSource,
};
use images::Plane;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::fmt;
use std::path::{Path, PathBuf};

/// The command line's help text.
pub const USAGE: &str = "\
bake: roughness and LEAN moment mip chains from a tangent-space normal map or a height map

usage: bake INPUT --out DIR [options]

INPUT is a PNG (8 or 16 bits) or OpenEXR (float) image: a tangent-space normal map (RGB or
RGBA; values 2v-1, or as stored for floats), or with --height a height map (first channel).

  --out DIR              output directory (written whole or not at all)
  --height               INPUT is a height map; slopes by central differences
  --height-scale H       world height of a texel value of 1 (height maps; default 1)
  --texel-size D         world size of a texel (height maps; default 1/width)
  --edges wrap|clamp     height-map borders (default wrap)
  --convention gl|dx     normal map green channel: OpenGL/glTF (+y up) or DirectX (default gl)
  --xy                   use only R and G of the normal map, z = sqrt(1 - x^2 - y^2) (BC5)
  --unit-tolerance T|any largest accepted | |n| - 1 | of a normal (default: sqrt(3)
                         quantisation steps; 1e-3 for floats); any: renormalise every
                         non-zero normal (lossy or resized maps)
  --roughness R|FILE     base roughness: a number, or a texture of the map's size (default 0.3)
  --roughness-channel C  r, g, b or a of the roughness texture (default g, glTF's channel;
                         r for a grey texture)
  --roughness-is perceptual|alpha
                         how the base roughness is given (default perceptual: alpha = r^2)
  --ndf ggx|beckmann     the NDF the roughness chain is fitted for (default ggx)
  --anisotropic          also fit anisotropic lobes (KHR_materials_anisotropy texture)
  --kernel box|area      mip kernel: the GPUs' 2x2 box or the exact footprint (default area)
  --store perceptual|alpha
                         roughness chain storage: glTF perceptual roughness in R8 (default) or
                         alpha in R16F (with --anisotropic: the matrix A in RGBA16F)
  --moments f16|f32      moment chain precision (default f16: filterable everywhere)
  --threads N            worker threads (default: all cores)
  --quiet                no progress bar
  --help                 this text
";

/// What went wrong, and with which file.
#[derive(Clone, Debug, PartialEq)]
pub struct Error {
    /// The file the error is about, if any.
    pub path: Option<PathBuf>,
    /// What is wrong (for texel errors: the texel and its value).
    pub message: String,
}

impl Error {
    /// An error about `path`.
    pub fn file(path: &Path, message: impl Into<String>) -> Self {
        Self {
            path: Some(path.to_path_buf()),
            message: message.into(),
        }
    }

    /// An error about the command line.
    pub fn usage(message: impl Into<String>) -> Self {
        Self {
            path: None,
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.path {
            Some(p) => write!(f, "{}: {}", p.display(), self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

impl std::error::Error for Error {}

/// The base roughness as given on the command line.
#[derive(Clone, Debug, PartialEq)]
pub enum Roughness {
    /// One value for every texel.
    Constant(f64),
    /// A texture.
    Texture(PathBuf),
}

/// Everything the command line sets.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The normal or height map.
    pub input: PathBuf,
    /// The output directory.
    pub out: PathBuf,
    /// The input is a height map.
    pub height: bool,
    /// Height maps: world height of a value of 1.
    pub height_scale: f64,
    /// Height maps: world size of a texel (`None`: `1 / width`).
    pub texel_size: Option<f64>,
    /// Height maps: border rule.
    pub edges: Edges,
    /// Normal maps: green convention.
    pub convention: Convention,
    /// Normal maps: R and G only, `z` reconstructed.
    pub xy: bool,
    /// Normal maps: the largest accepted `| |n| - 1 |` (`None`: the library's default;
    /// `f64::INFINITY`: any non-zero normal).
    pub unit_tolerance: Option<f64>,
    /// The base roughness.
    pub roughness: Roughness,
    /// The roughness texture's channel (`None`: G, or R for a grey texture).
    pub roughness_channel: Option<usize>,
    /// The base roughness is perceptual (`alpha = r^2`), else `alpha`.
    pub roughness_perceptual: bool,
    /// The NDF of the fits.
    pub ndf: Ndf,
    /// Fit anisotropic lobes too.
    pub anisotropic: bool,
    /// The mip kernel.
    pub kernel: Kernel,
    /// The roughness chain's storage.
    pub store: Store,
    /// The moment chain's precision.
    pub moments: Precision,
    /// Worker threads (`None`: rayon's default).
    pub threads: Option<usize>,
    /// Draw a progress bar (on a terminal, for maps of a million texels or more).
    pub progress: bool,
}

impl Options {
    /// The defaults for `input` and `out`.
    pub fn new(input: impl Into<PathBuf>, out: impl Into<PathBuf>) -> Self {
        Self {
            input: input.into(),
            out: out.into(),
            height: false,
            height_scale: 1.0,
            texel_size: None,
            edges: Edges::Wrap,
            convention: Convention::OpenGl,
            xy: false,
            unit_tolerance: None,
            roughness: Roughness::Constant(0.3),
            roughness_channel: None,
            roughness_perceptual: true,
            ndf: Ndf::Ggx,
            anisotropic: false,
            kernel: Kernel::Area,
            store: Store::Perceptual,
            moments: Precision::F16,
            threads: None,
            progress: true,
        }
    }

    /// Parses the arguments after the program's name. `Ok(None)`: `--help` was asked for.
    pub fn parse<I: IntoIterator<Item = String>>(args: I) -> Result<Option<Self>, Error> {
        let mut it = args.into_iter();
        let mut input = None;
        let mut out = None;
        let mut o = Options::new("", "");
        let value = |it: &mut I::IntoIter, flag: &str| {
            it.next()
                .ok_or_else(|| Error::usage(format!("{flag} needs a value")))
        };
        let number = |v: String, flag: &str| {
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| Error::usage(format!("{flag} {v}: not a finite number")))
        };
        let choice = |v: String, flag: &str, options: &[&str]| {
            options.iter().position(|o| *o == v).ok_or_else(|| {
                Error::usage(format!("{flag} {v}: expected {}", options.join(" or ")))
            })
        };
        while let Some(a) = it.next() {
            match a.as_str() {
                "--help" | "-h" => return Ok(None),
                "--out" => out = Some(PathBuf::from(value(&mut it, &a)?)),
                "--height" => o.height = true,
                "--height-scale" => o.height_scale = number(value(&mut it, &a)?, &a)?,
                "--texel-size" => o.texel_size = Some(number(value(&mut it, &a)?, &a)?),
                "--edges" => {
                    o.edges = [Edges::Wrap, Edges::Clamp]
                        [choice(value(&mut it, &a)?, &a, &["wrap", "clamp"])?]
                }
                "--convention" => {
                    o.convention = [Convention::OpenGl, Convention::DirectX]
                        [choice(value(&mut it, &a)?, &a, &["gl", "dx"])?]
                }
                "--xy" => o.xy = true,
                "--unit-tolerance" => {
                    let v = value(&mut it, &a)?;
                    o.unit_tolerance = Some(if v == "any" {
                        f64::INFINITY
                    } else {
                        number(v, &a).and_then(|t| {
                            if t >= 0.0 {
                                Ok(t)
                            } else {
                                Err(Error::usage(format!("--unit-tolerance {t}: must be >= 0")))
                            }
                        })?
                    });
                }
                "--roughness" => {
                    let v = value(&mut it, &a)?;
                    o.roughness = match v.parse::<f64>() {
                        Ok(x) => Roughness::Constant(x),
                        Err(_) => Roughness::Texture(PathBuf::from(v)),
                    };
                }
                "--roughness-channel" => {
                    o.roughness_channel =
                        Some(choice(value(&mut it, &a)?, &a, &["r", "g", "b", "a"])?)
                }
                "--roughness-is" => {
                    o.roughness_perceptual =
                        choice(value(&mut it, &a)?, &a, &["perceptual", "alpha"])? == 0
                }
                "--ndf" => {
                    o.ndf = [Ndf::Ggx, Ndf::Beckmann]
                        [choice(value(&mut it, &a)?, &a, &["ggx", "beckmann"])?]
                }
                "--anisotropic" => o.anisotropic = true,
                "--kernel" => {
                    o.kernel = [Kernel::GpuBox, Kernel::Area]
                        [choice(value(&mut it, &a)?, &a, &["box", "area"])?]
                }
                "--store" => {
                    o.store = [Store::Perceptual, Store::Alpha]
                        [choice(value(&mut it, &a)?, &a, &["perceptual", "alpha"])?]
                }
                "--moments" => {
                    o.moments = [Precision::F16, Precision::F32]
                        [choice(value(&mut it, &a)?, &a, &["f16", "f32"])?]
                }
                "--threads" => {
                    let v = value(&mut it, &a)?;
                    o.threads =
                        Some(v.parse::<usize>().ok().filter(|&n| n > 0).ok_or_else(|| {
                            Error::usage(format!("--threads {v}: expected a positive integer"))
                        })?);
                }
                "--quiet" => o.progress = false,
                s if s.starts_with('-') && s.len() > 1 => {
                    return Err(Error::usage(format!("unknown option {s} (see --help)")));
                }
                _ if input.is_none() => input = Some(PathBuf::from(a)),
                _ => {
                    return Err(Error::usage(format!(
                        "a second input {a}: one map at a time"
                    )));
                }
            }
        }
        o.input = input.ok_or_else(|| Error::usage("no input map (see --help)"))?;
        o.out = out.ok_or_else(|| Error::usage("no --out DIR (see --help)"))?;
        Ok(Some(o))
    }
}

/// What a bake wrote.
#[derive(Clone, Debug)]
pub struct Summary {
    /// The output directory.
    pub out: PathBuf,
    /// The files in it, relative to it.
    pub files: Vec<PathBuf>,
    /// The figures per level.
    pub levels: Vec<report::LevelStats>,
}

/// The base roughness after loading: per texel `alpha` for the report, and the library's
/// form.
struct Base {
    image: Option<(PathBuf, load::Image, usize)>,
    constant_alpha: f64,
    perceptual: bool,
}

impl Base {
    fn alpha(&self, x: usize, y: usize) -> f64 {
        match &self.image {
            None => self.constant_alpha,
            Some((_, img, c)) => {
                let v = img.value(x, y, *c);
                if self.perceptual { v * v } else { v }
            }
        }
    }

    fn library(&self) -> Result<BaseRoughness<'_>, Error> {
        Ok(match &self.image {
            None => BaseRoughness::Constant(self.constant_alpha),
            Some((path, img, c)) => BaseRoughness::Texture(
                RoughnessMap::new(
                    img.texels(),
                    img.width,
                    img.height,
                    img.channels,
                    *c,
                    self.perceptual,
                )
                .map_err(|e| Error::file(path, e.to_string()))?,
            ),
        })
    }
}

fn load_base(o: &Options, width: usize, height: usize) -> Result<Base, Error> {
    match &o.roughness {
        Roughness::Constant(r) => {
            let ok = r.is_finite() && *r > 0.0 && (!o.roughness_perceptual || *r <= 1.0);
            if !ok {
                return Err(Error::usage(format!(
                    "--roughness {r}: a base roughness must be in (0, 1] (perceptual) or positive (alpha)"
                )));
            }
            let alpha = if o.roughness_perceptual { r * r } else { *r };
            Ok(Base {
                image: None,
                constant_alpha: alpha,
                perceptual: o.roughness_perceptual,
            })
        }
        Roughness::Texture(path) => {
            let img = load::read(path)?;
            if (img.width, img.height) != (width, height) {
                return Err(Error::file(
                    path,
                    format!(
                        "is {}x{}; the roughness texture must have the map's size, {width}x{height}",
                        img.width, img.height
                    ),
                ));
            }
            let c = o
                .roughness_channel
                .unwrap_or(if img.channels >= 3 { 1 } else { 0 });
            if c >= img.channels {
                return Err(Error::file(
                    path,
                    format!(
                        "has {} channels; channel {} asked for",
                        img.channels,
                        ["r", "g", "b", "a"][c]
                    ),
                ));
            }
            Ok(Base {
                image: Some((path.clone(), img, c)),
                constant_alpha: 0.0,
                perceptual: o.roughness_perceptual,
            })
        }
    }
}

/// Runs a bake: reads and checks every input, bakes, writes the directory whole.
pub fn run(o: &Options) -> Result<Summary, Error> {
    let pool = {
        let mut b = rayon::ThreadPoolBuilder::new();
        if let Some(n) = o.threads {
            b = b.num_threads(n);
        }
        b.build()
            .map_err(|e| Error::usage(format!("thread pool: {e}")))?
    };
    pool.install(|| run_in_pool(o))
}

fn run_in_pool(o: &Options) -> Result<Summary, Error> {
    let img = load::read(&o.input)?;
    check_destination(&o.out)?;
    let base = load_base(o, img.width, img.height)?;
    let bad = |e: filtered_ndf::bake::BakeError| Error::file(&o.input, e.to_string());
    if o.height {
        let format = HeightFormat {
            channels: img.channels,
            texel_spacing: o.texel_size.unwrap_or(1.0 / img.width as f64),
            height_scale: o.height_scale,
            edges: o.edges,
        };
        let map = HeightMap::new(img.texels(), img.width, img.height, format).map_err(bad)?;
        finish(o, &map, &base)
    } else {
        let img = if o.xy {
            if img.channels < 2 {
                return Err(Error::file(
                    &o.input,
                    format!("has {} channel; --xy needs R and G", img.channels),
                ));
            }
            img.select(&[0, 1])
        } else {
            if img.channels < 3 {
                return Err(Error::file(
                    &o.input,
                    format!(
                        "has {} channel(s); a normal map needs 3 or 4 (RGB, RGBA), or R and G with --xy; a height map needs --height",
                        img.channels
                    ),
                ));
            }
            img
        };
        let mut format = NormalFormat::new(img.channels, o.convention);
        if let Some(t) = o.unit_tolerance {
            format = format.with_tolerance(t);
        }
        let map = NormalMap::new(img.texels(), img.width, img.height, format).map_err(|e| {
            let hint = if matches!(e, filtered_ndf::bake::BakeError::NotUnit { .. }) {
                " (a lossy or resized map: --unit-tolerance any renormalises every normal)"
            } else {
                ""
            };
            Error::file(&o.input, format!("{e}{hint}"))
        })?;
        finish(o, &map, &base)
    }
}

fn finish<S: SlopeSource + Sync>(o: &Options, source: &S, base: &Base) -> Result<Summary, Error> {
    let settings = Settings {
        kernel: o.kernel,
        base: base.library()?,
    };
    let texels = source.width() * source.height();
    let levels = filtered_ndf::bake::ChainLayout::new(source.width(), source.height())
        .map_err(|e| Error::file(&o.input, e.to_string()))?
        .levels();
    let bar = if o.progress && texels >= 1 << 20 {
        let b = ProgressBar::with_draw_target(
            Some((levels * source.height()) as u64),
            ProgressDrawTarget::stderr(),
        );
        if let Ok(s) =
            ProgressStyle::with_template("baking {bar:40} {percent:>3}% {elapsed} (eta {eta})")
        {
            b.set_style(s);
        }
        b
    } else {
        ProgressBar::hidden()
    };
    let chains = chain::bake(source, &settings, o.ndf, o.anisotropic, &bar)
        .map_err(|e| Error::file(&o.input, e.to_string()))?;
    bar.finish_and_clear();
    let stats = report::levels(source, &chains, o.kernel, o.ndf, &|x, y| base.alpha(x, y));
    let tmp = temporary_beside(&o.out)?;
    let written = write_all(o, &chains, &stats, base, &tmp);
    match written {
        Ok(files) => {
            replace(&tmp, &o.out)?;
            Ok(Summary {
                out: o.out.clone(),
                files,
                levels: stats,
            })
        }
        Err(e) => {
            let _ = std::fs::remove_dir_all(&tmp);
            Err(e)
        }
    }
}

/// `DIR` may be replaced: absent, an empty directory, or a previous bake (it holds
/// `report.md`).
fn check_destination(out: &Path) -> Result<(), Error> {
    match std::fs::read_dir(out) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(Error::file(
            out,
            format!("is not a directory the baker can replace: {e}"),
        )),
        Ok(mut entries) => {
            if entries.next().is_none() || out.join("report.md").is_file() {
                Ok(())
            } else {
                Err(Error::file(
                    out,
                    "exists and is not a previous bake (no report.md): choose another --out",
                ))
            }
        }
    }
}

fn parent_and_name(out: &Path) -> Result<(PathBuf, String), Error> {
    let name = out
        .file_name()
        .ok_or_else(|| Error::file(out, "names no directory"))?
        .to_string_lossy()
        .into_owned();
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

/// A new directory beside `out` for the bake's files.
fn temporary_beside(out: &Path) -> Result<PathBuf, Error> {
    let (parent, name) = parent_and_name(out)?;
    std::fs::create_dir_all(&parent)
        .map_err(|e| Error::file(&parent, format!("cannot be created: {e}")))?;
    let tmp = parent.join(format!(".{name}.bake-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir(&tmp).map_err(|e| Error::file(&tmp, format!("cannot be created: {e}")))?;
    Ok(tmp)
}

/// Moves the finished `tmp` to `out`, replacing a previous bake there.
fn replace(tmp: &Path, out: &Path) -> Result<(), Error> {
    let (parent, name) = parent_and_name(out)?;
    let old = parent.join(format!(".{name}.old-{}", std::process::id()));
    let had = out.exists();
    if had {
        std::fs::rename(out, &old)
            .map_err(|e| Error::file(out, format!("cannot be replaced: {e}")))?;
    }
    if let Err(e) = std::fs::rename(tmp, out) {
        if had {
            let _ = std::fs::rename(&old, out);
        }
        let _ = std::fs::remove_dir_all(tmp);
        return Err(Error::file(out, format!("cannot be written: {e}")));
    }
    if had {
        let _ = std::fs::remove_dir_all(&old);
    }
    Ok(())
}

/// The `KTXwriter` value.
pub const WRITER: &str = concat!("filtered-ndf-bake ", env!("CARGO_PKG_VERSION"));

fn write_file(dir: &Path, name: &str, bytes: &[u8], files: &mut Vec<PathBuf>) -> Result<(), Error> {
    let path = dir.join(name);
    std::fs::write(&path, bytes)
        .map_err(|e| Error::file(&path, format!("cannot be written: {e}")))?;
    files.push(PathBuf::from(name));
    Ok(())
}

fn ktx_file(
    c: &Chains,
    format: ktx::Format,
    level: impl Fn(std::ops::Range<usize>) -> Vec<u8> + Sync,
) -> Result<Vec<u8>, Error> {
    let l = c.layout;
    let levels: Vec<Vec<u8>> = (0..l.levels())
        .into_par_iter()
        .map(|k| {
            let lv = l.level(k);
            level(lv.rows(0..lv.height))
        })
        .collect();
    let refs: Vec<&[u8]> = levels.iter().map(Vec::as_slice).collect();
    ktx::encode(format, l.width() as u32, l.height() as u32, &refs, WRITER).map_err(Error::usage)
}

/// The KTX2 files' names, formats and level encoders of a bake.
fn ktx_outputs(o: &Options, c: &Chains) -> Result<Vec<(&'static str, Vec<u8>)>, Error> {
    let mut out = Vec::new();
    let rough_format = match (o.store, c.anisotropic.is_some()) {
        (Store::Perceptual, _) => ktx::Format::R8Unorm,
        (Store::Alpha, false) => ktx::Format::R16Float,
        (Store::Alpha, true) => ktx::Format::Rgba16Float,
    };
    out.push((
        "roughness.ktx2",
        ktx_file(c, rough_format, |r| encode::roughness(c, r, o.store))?,
    ));
    if let (Store::Perceptual, Some(an)) = (o.store, &c.anisotropic) {
        out.push((
            "anisotropy.ktx2",
            ktx_file(c, ktx::Format::Rgba8Unorm, |r| encode::anisotropy(an, r))?,
        ));
    }
    let (rgba, r) = match o.moments {
        Precision::F16 => (ktx::Format::Rgba16Float, ktx::Format::R16Float),
        Precision::F32 => (ktx::Format::Rgba32Float, ktx::Format::R32Float),
    };
    out.push((
        "moments.ktx2",
        ktx_file(c, rgba, |range| {
            encode::moments_rgba(&c.moments, range, o.moments)
        })?,
    ));
    out.push((
        "moments_xy.ktx2",
        ktx_file(c, r, |range| {
            encode::moments_xy(&c.moments, range, o.moments)
        })?,
    ));
    Ok(out)
}

/// The variance image's white: twice the RMS slope deviation of the level whose mean
/// `tr Cov[s]` is the largest (a few steep texels do not darken the rest).
fn variance_scale(stats: &[report::LevelStats]) -> f64 {
    let v = stats.iter().map(|s| s.mean_variance).fold(0.0, f64::max);
    (2.0 * v.sqrt()).max(f64::MIN_POSITIVE)
}

/// The inspection planes of one level: roughness (grey), mean normal (RGB), variance
/// (grey, `sqrt(tr Cov[s]) / max_sqrt`), anisotropy (RGB, when baked).
fn planes(c: &Chains, k: usize, max_sqrt: f64) -> Vec<(&'static str, Plane)> {
    let lv = c.layout.level(k);
    let range = lv.rows(0..lv.height);
    let plane = |channels, data| Plane {
        width: lv.width,
        height: lv.height,
        channels,
        data,
    };
    let rough: Vec<u8> = match &c.anisotropic {
        None => c.isotropic[range.clone()]
            .iter()
            .map(|&a| encode::unorm8(filtered_ndf::bake::fit::perceptual(f64::from(a))))
            .collect(),
        Some(an) => an[range.clone()]
            .iter()
            .map(|&a| encode::unorm8(encode::lobe(a).khr().roughness))
            .collect(),
    };
    let m = &c.moments[range.clone()];
    let mut out = vec![
        ("roughness", plane(1, rough)),
        (
            "normal",
            plane(3, m.iter().flat_map(encode::mean_normal).collect()),
        ),
        (
            "variance",
            plane(
                1,
                m.iter()
                    .map(|t| encode::unorm8(encode::variance(t).sqrt() / max_sqrt))
                    .collect(),
            ),
        ),
    ];
    if let Some(an) = &c.anisotropic {
        out.push((
            "anisotropy",
            plane(
                3,
                an[range]
                    .iter()
                    .flat_map(|&a| {
                        let t = encode::khr_texel(a);
                        [t[0], t[1], t[2]]
                    })
                    .collect(),
            ),
        ));
    }
    out
}

fn write_all(
    o: &Options,
    c: &Chains,
    stats: &[report::LevelStats],
    base: &Base,
    dir: &Path,
) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    for (name, bytes) in ktx_outputs(o, c)? {
        write_file(dir, name, &bytes, &mut files)?;
    }
    let levels_dir = dir.join("levels");
    std::fs::create_dir(&levels_dir)
        .map_err(|e| Error::file(&levels_dir, format!("cannot be created: {e}")))?;
    let max_sqrt = variance_scale(stats);
    let per_level: Vec<Vec<(&str, Plane)>> = (0..c.layout.levels())
        .into_par_iter()
        .map(|k| planes(c, k, max_sqrt))
        .collect();
    let names: Vec<(usize, &str)> = per_level
        .iter()
        .enumerate()
        .flat_map(|(k, ps)| ps.iter().map(move |(n, _)| (k, *n)))
        .collect();
    names.par_iter().try_for_each(|&(k, n)| {
        let p = &per_level[k].iter().find(|(m, _)| *m == n).expect("named").1;
        images::write_png(&levels_dir.join(format!("{n}_{k}.png")), p)
    })?;
    for &(k, n) in &names {
        files.push(PathBuf::from(format!("levels/{n}_{k}.png")));
    }
    let rows: Vec<Vec<Plane>> = per_level[0]
        .iter()
        .map(|(n, _)| {
            per_level
                .iter()
                .map(|ps| {
                    ps.iter()
                        .find(|(m, _)| m == n)
                        .expect("every level")
                        .1
                        .clone()
                })
                .collect()
        })
        .collect();
    let sheet = images::contact_sheet(&rows);
    images::write_png(&dir.join("contact_sheet.png"), &sheet)?;
    files.push(PathBuf::from("contact_sheet.png"));
    let md = report_markdown(
        o,
        c,
        stats,
        base,
        &per_level[0].iter().map(|(n, _)| *n).collect::<Vec<_>>(),
    );
    write_file(dir, "report.md", md.as_bytes(), &mut files)?;
    Ok(files)
}

fn report_markdown(
    o: &Options,
    c: &Chains,
    stats: &[report::LevelStats],
    base: &Base,
    rows: &[&str],
) -> String {
    use std::fmt::Write as _;
    let l = c.layout;
    let mut md = String::new();
    let ndf = match o.ndf {
        Ndf::Ggx => "GGX",
        Ndf::Beckmann => "Beckmann",
    };
    let _ = writeln!(md, "# Bake of `{}`\n", o.input.display());
    let _ = writeln!(
        md,
        "{}x{} texels, {} levels; {} map{}; mip kernel {}; base roughness {}; {ndf} fits{}.\n",
        l.width(),
        l.height(),
        l.levels(),
        if o.height { "height" } else { "normal" },
        if o.height {
            String::new()
        } else {
            format!(
                " ({} green{})",
                if o.convention == Convention::OpenGl {
                    "OpenGL"
                } else {
                    "DirectX"
                },
                if o.xy {
                    ", z reconstructed from x, y"
                } else {
                    ""
                }
            )
        },
        if o.kernel == Kernel::Area {
            "exact footprint (area)"
        } else {
            "GPU 2x2 box"
        },
        match &base.image {
            None => format!("alpha = {:.6}", base.constant_alpha),
            Some((p, _, ch)) => format!(
                "texture `{}` channel {} ({})",
                p.display(),
                ["r", "g", "b", "a"][*ch],
                if base.perceptual {
                    "perceptual"
                } else {
                    "alpha"
                }
            ),
        },
        if o.anisotropic {
            ", isotropic and anisotropic"
        } else {
            ", isotropic"
        },
    );
    let _ = writeln!(md, "## Files\n");
    let _ = writeln!(md, "| file | contents |\n|---|---|");
    let rough = match (o.store, o.anisotropic) {
        (Store::Perceptual, false) => {
            "KTX2 `R8_UNORM`, every level: perceptual roughness `sqrt(alpha)` of the isotropic fit (glTF's metallic-roughness G value)"
        }
        (Store::Perceptual, true) => {
            "KTX2 `R8_UNORM`, every level: `KHR_materials_anisotropy`'s roughness `sqrt(alpha_y)` (the minor axis)"
        }
        (Store::Alpha, false) => "KTX2 `R16_SFLOAT`, every level: `alpha` of the isotropic fit",
        (Store::Alpha, true) => {
            "KTX2 `R16G16B16A16_SFLOAT`, every level: the roughness matrix `(A11, A12, A22, 1)` of the anisotropic fit"
        }
    };
    let _ = writeln!(md, "| `roughness.ktx2` | {rough} |");
    if o.anisotropic && o.store == Store::Perceptual {
        let _ = writeln!(
            md,
            "| `anisotropy.ktx2` | KTX2 `R8G8B8A8_UNORM`: `KHR_materials_anisotropy`'s texture (direction `(cos, sin)` as `(v + 1) / 2`, strength, 1) |"
        );
    }
    let p = if o.moments == Precision::F16 {
        "16"
    } else {
        "32"
    };
    let _ = writeln!(
        md,
        "| `moments.ktx2` | KTX2 `R{p}G{p}B{p}A{p}_SFLOAT`: `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])` |"
    );
    let _ = writeln!(
        md,
        "| `moments_xy.ktx2` | KTX2 `R{p}_SFLOAT`: `E[s_x s_y]` |"
    );
    let _ = writeln!(
        md,
        "| `levels/<name>_<level>.png` | per level: {} |",
        rows.join(", ")
    );
    let _ = writeln!(
        md,
        "| `contact_sheet.png` | every level side by side (level 0 left), one row each: {} |\n",
        rows.join(", ")
    );
    let _ = writeln!(
        md,
        "Slopes `s = -n_xy / n_z` in OpenGL's tangent frame (`x` along `+u`, `y` up the image). The variance image shows `sqrt(tr Cov[s])` from black (0) to white ({:.4}, twice the RMS slope deviation of the level with the largest mean variance).\n",
        variance_scale(stats)
    );
    let _ = writeln!(md, "## Levels\n");
    let _ = writeln!(
        md,
        "Variance added: `tr Cov[s] = Var[s_x] + Var[s_y]` of each texel, from its stored moments. Fit error: total variation `integral |P22_true - P22_fit| ds` (0 to 2) of the baked lobe against the texel's true distribution of normals (its base lobes averaged), mean over the sampled texels; footprints wider than {} texels along an axis are represented by {} evenly spaced ones (an estimate there); quadrature {}x{} nodes, its mass error in the last column.\n",
        report::SUB,
        report::SUB,
        report::GRID,
        report::GRID
    );
    let _ = write!(
        md,
        "| level | size | mean var added | max var added | mean alpha (iso) | fit error (iso) |"
    );
    if o.anisotropic {
        let _ = write!(md, " mean alpha_x, alpha_y | fit error (aniso) |");
    }
    let _ = writeln!(
        md,
        " texels sampled | base texels per sample | mass error |"
    );
    let _ = write!(md, "|---:|---:|---:|---:|---:|---:|");
    if o.anisotropic {
        let _ = write!(md, "---:|---:|");
    }
    let _ = writeln!(md, "---:|---:|---:|");
    for s in stats {
        let _ = write!(
            md,
            "| {} | {}x{} | {:.3e} | {:.3e} | {:.4} | {:.4} |",
            s.level,
            s.width,
            s.height,
            s.mean_variance,
            s.max_variance,
            s.mean_alpha,
            s.error_isotropic
        );
        if let (Some((ax, ay)), Some(e)) = (s.mean_alpha_xy, s.error_anisotropic) {
            let _ = write!(md, " {ax:.4}, {ay:.4} | {e:.4} |");
        }
        let _ = writeln!(md, " {} | {} | {:.1e} |", s.sampled, s.lobes, s.mass_error);
    }
    md
}
