//! Prefiltered surface detail baked from normal and height maps: the mip chain of LEAN
//! moments (Olano and Baker 2010; KHPL16 section 5.5, eq. 21) and roughness mip chains whose
//! GGX or Beckmann lobe is closest to the true distribution of normals of each mip texel.
//!
//! # The pieces
//! - **Input** ([`input`]): [`NormalMap`] (8-bit, 16-bit or float texels, two channels with
//!   `z` reconstructed or three/four, OpenGL or DirectX green), [`HeightMap`] (central
//!   differences), [`SlopeMap`] (slopes in `f64`), each checked once at construction
//!   ([`BakeError`] names the texel and its value).
//! - **Layout** ([`ChainLayout`]): the GPU rule for level sizes, any base size, and where
//!   each level starts in one flat array that the caller allocates.
//! - **Footprints** ([`footprint_row`]): a mip texel's [`TexelStats`] (`E[s]`, `E[s s^T]`,
//!   the mean unit normal, the mean squared base roughness), averaged in `f64` over its
//!   footprint on the base level by a [`Kernel`]: the GPUs' box or the exact footprint.
//! - **Storage** ([`store_f32`], [`store_f16`]): the five moments per texel.
//! - **Fits** ([`fit`]): the GGX and Beckmann roughness (isotropic, or anisotropic with its
//!   angle) closest to each texel's distribution of normals, by total variation.
//! - **Decoding** ([`decode`]): a stored roughness chain read back as the lobe
//!   (`KHR_materials_anisotropy`'s encoding, the anisotropic matrix, perceptual roughness);
//!   `shaders/bake/roughness.wgsl` mirrors it, `shaders/bake/moments.wgsl` samples the moment
//!   chain on the GPU.
//! - **Bands** ([`bake_rows`]): rows `r0..r1` of one level, every requested output at once;
//!   bands of different rows or levels are independent, so a caller can bake them on as
//!   many threads as it likes (the command-line baker uses rayon across rows).
//!
//! # Conventions
//! The bake's tangent frame is OpenGL's: `x` right along `+u`, `y` up the image along `+v`,
//! `z` the surface normal; slopes `s = -n_xy / n_z` (for a height field `z = h(x, y)`,
//! `s = grad h`). A mip texel's true distribution of normals is its base texels' lobes
//! averaged, each centred on its texel's slope: `P22_true(s) = sum_i w_i P22_base(s - s_i)`
//! (the slope-domain convolution that LEAN mapping and KHPL16 eq. 21 assume; it keeps every
//! moment linear in the texels, which is what makes the chain filterable).
//!
//! # Memory and threads
//! Pure functions over slices: the caller allocates every output and the scratch row
//! ([`ChainLayout::scratch_len`] entries of [`TexelStats`]); nothing here allocates, so the
//! module builds without `std` and without `alloc`. The work per level is one pass over the
//! base texels (each level reads its footprints from the base level, in `f64`).
//!
//! # Moment storage and its error
//! A texel stores `[E[s_x], E[s_y], E[s_x^2], E[s_x s_y], E[s_y^2]]` (the fields of
//! [`crate::f32::LeanMoments`] in order), each rounded to nearest once from `f64`:
//! - `f32`: relative error `2^-24` per moment. The covariance a shader forms from them,
//!   `c = E[s_x^2] - E[s_x]^2`, is then within `2^-24 (E[s_x^2] + 2 E[s_x]^2)` (plus the
//!   shader's own `f32` rounding of the difference): absolute, so a texel whose variance is far
//!   below its squared mean slope (a smooth but tilted region) keeps only the digits above that.
//! - `f16` ([`mod@f16`]): relative `2^-11` (plus the `2^-24` of the intermediate `f32`) for
//!   magnitudes in `[2^-14, 65504]`, absolute `2^-25` below, saturated at `65504` above (a
//!   second moment past that needs `|s| > 256`, a normal within 0.22 degrees of the horizon):
//!   the covariance within `2^-11 (E[s_x^2] + 2 E[s_x]^2) + 3 * 2^-25`.

pub mod decode;
pub mod f16;
pub mod fit;
pub mod footprint;
pub mod input;
pub mod layout;

pub use footprint::{BaseRoughness, Kernel, RoughnessMap, Settings, TexelStats, footprint_row};
pub use input::{
    BakeError, Convention, Edges, HeightFormat, HeightMap, MAX_SLOPE, NormalFormat, NormalMap,
    SlopeMap, SlopeSource, Texels,
};
pub use layout::{ChainLayout, Level};

/// The five moments of a texel rounded to `f32`:
/// `[E[s_x], E[s_y], E[s_x^2], E[s_x s_y], E[s_y^2]]` (module docs: the storage error).
#[inline]
pub fn store_f32(t: &TexelStats) -> [f32; 5] {
    [
        t.mean.x as f32,
        t.mean.y as f32,
        t.second.x as f32,
        t.second.y as f32,
        t.second.z as f32,
    ]
}

/// The five moments of a texel as `f16` bit patterns, in the order of [`store_f32`], each
/// rounded once from `f64` to `f32` and once to `f16` (both to nearest; the double rounding
/// moves a value by at most `2^-24` of it beyond `f16`'s own half ulp), saturated at
/// `±65504` (module docs).
#[inline]
pub fn store_f16(t: &TexelStats) -> [u16; 5] {
    store_f32(t).map(f16::f16_saturating)
}

/// The LEAN moments of a stored texel, for [`crate::f32::filter::lean`].
#[inline]
pub fn lean_moments(t: &[f32; 5]) -> crate::f32::LeanMoments {
    crate::f32::LeanMoments::new(
        glam::Vec2::new(t[0], t[1]),
        crate::f32::Covariance::new(t[2], t[3], t[4]),
    )
}

/// What [`bake_rows`] writes: each present slice holds the band's texels row-major
/// (`rows.len() * level width` entries at least). Roughnesses are `alpha` ([`fit`]; glTF's
/// perceptual roughness is [`fit::perceptual`] of it); anisotropic lobes are
/// `[alpha_x, alpha_y, angle]` ([`fit::AnisotropicAlpha`], whose
/// [`khr`](fit::AnisotropicAlpha::khr) gives `KHR_materials_anisotropy`'s encoding).
#[derive(Debug, Default)]
pub struct Band<'o> {
    /// The moments in `f32` ([`store_f32`]).
    pub moments: Option<&'o mut [[f32; 5]]>,
    /// The moments in `f16` ([`store_f16`]).
    pub moments_f16: Option<&'o mut [[u16; 5]]>,
    /// The isotropic GGX fit ([`fit::ggx_isotropic`]).
    pub ggx: Option<&'o mut [f32]>,
    /// The anisotropic GGX fit ([`fit::ggx_anisotropic`]).
    pub ggx_anisotropic: Option<&'o mut [[f32; 3]]>,
    /// The isotropic Beckmann fit ([`fit::beckmann_isotropic`]).
    pub beckmann: Option<&'o mut [f32]>,
    /// The anisotropic Beckmann fit ([`fit::beckmann_anisotropic`]).
    pub beckmann_anisotropic: Option<&'o mut [[f32; 3]]>,
}

fn lobe_f32(a: fit::AnisotropicAlpha) -> [f32; 3] {
    [a.alpha_x as f32, a.alpha_y as f32, a.angle as f32]
}

fn check_out<T>(out: &Option<&mut [T]>, n: usize) -> Result<(), BakeError> {
    match out {
        Some(o) if o.len() < n => Err(BakeError::Output {
            expected: n,
            got: o.len(),
        }),
        _ => Ok(()),
    }
}

/// Rows `rows` of level `level`: every output of `band`, texel by texel, from each texel's
/// [`TexelStats`] ([`footprint_row`]). `scratch` holds [`ChainLayout::scratch_len`] entries.
/// Errors (nothing is written past the first failing check, and every check precedes the
/// first write): the source's size differs from the layout's, the base roughness fails its
/// check, `rows` leaves the level, or a slice is too short.
pub fn bake_rows<S: SlopeSource>(
    source: &S,
    settings: &Settings<'_>,
    layout: &ChainLayout,
    level: usize,
    rows: core::ops::Range<usize>,
    scratch: &mut [TexelStats],
    mut band: Band<'_>,
) -> Result<(), BakeError> {
    settings.base.check(layout.width(), layout.height())?;
    let lv = layout.level(level);
    if level >= layout.levels() || rows.end > lv.height || rows.start > rows.end {
        return Err(BakeError::Output {
            expected: rows.end,
            got: lv.height,
        });
    }
    let n = rows.len() * lv.width;
    check_out(&band.moments, n)?;
    check_out(&band.moments_f16, n)?;
    check_out(&band.ggx, n)?;
    check_out(&band.ggx_anisotropic, n)?;
    check_out(&band.beckmann, n)?;
    check_out(&band.beckmann_anisotropic, n)?;
    let fits = band.ggx.is_some()
        || band.ggx_anisotropic.is_some()
        || band.beckmann.is_some()
        || band.beckmann_anisotropic.is_some();
    if scratch.len() < layout.scratch_len() {
        return Err(BakeError::Output {
            expected: layout.scratch_len(),
            got: scratch.len(),
        });
    }
    let (acc, out) = scratch.split_at_mut(layout.width());
    for (r, row) in rows.enumerate() {
        footprint_row(source, settings, layout, level, row, acc, out)?;
        let at = r * lv.width;
        for (i, t) in out[..lv.width].iter().enumerate() {
            if let Some(m) = band.moments.as_deref_mut() {
                m[at + i] = store_f32(t);
            }
            if let Some(m) = band.moments_f16.as_deref_mut() {
                m[at + i] = store_f16(t);
            }
            if !fits {
                continue;
            }
            let spread = fit::Spread::of(t);
            if let Some(m) = band.ggx.as_deref_mut() {
                m[at + i] = fit::ggx_isotropic(&spread) as f32;
            }
            if let Some(m) = band.ggx_anisotropic.as_deref_mut() {
                m[at + i] = lobe_f32(fit::ggx_anisotropic(&spread));
            }
            if let Some(m) = band.beckmann.as_deref_mut() {
                m[at + i] = fit::beckmann_isotropic(&spread) as f32;
            }
            if let Some(m) = band.beckmann_anisotropic.as_deref_mut() {
                m[at + i] = lobe_f32(fit::beckmann_anisotropic(&spread));
            }
        }
    }
    Ok(())
}
