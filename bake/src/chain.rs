//! The whole chain on rayon's thread pool: every level in bands of rows, each band one call of
//! [`bake_rows`] with its own scratch row (bands of different rows are independent: the
//! library's contract), the moments and the fits in one pass.

use filtered_ndf::bake::{
    BakeError, Band, ChainLayout, Settings, SlopeSource, TexelStats, bake_rows,
};
use indicatif::ProgressBar;
use rayon::prelude::*;

/// Which NDF the roughness chain is fitted for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ndf {
    /// GGX (Trowbridge-Reitz): `fit::ggx_isotropic`, `fit::ggx_anisotropic`.
    Ggx,
    /// Beckmann: `fit::beckmann_isotropic`, `fit::beckmann_anisotropic`.
    Beckmann,
}

/// The baked chains, each level after level in the flat layout of [`ChainLayout`].
#[derive(Clone, Debug)]
pub struct Chains {
    /// The level sizes and offsets.
    pub layout: ChainLayout,
    /// The five moments per texel, `bake::store_f32`.
    pub moments: Vec<[f32; 5]>,
    /// The isotropic fit's `alpha` per texel.
    pub isotropic: Vec<f32>,
    /// The anisotropic fit, `[alpha_x, alpha_y, angle]`, when asked for.
    pub anisotropic: Option<Vec<[f32; 3]>>,
}

/// Bands per thread and level: enough for rayon to balance the rows' unequal costs.
const BANDS_PER_THREAD: usize = 8;

/// Bakes every level of `source`. `progress` advances by one per base row read (a level
/// reads every base row once: the bar's length is `levels * height`).
pub fn bake<S: SlopeSource + Sync>(
    source: &S,
    settings: &Settings<'_>,
    ndf: Ndf,
    anisotropic: bool,
    progress: &ProgressBar,
) -> Result<Chains, BakeError> {
    let layout = ChainLayout::new(source.width(), source.height())?;
    settings.base.check(layout.width(), layout.height())?;
    let n = layout.len();
    let mut moments = vec![[0.0f32; 5]; n];
    let mut isotropic = vec![0.0f32; n];
    let mut aniso = anisotropic.then(|| vec![[0.0f32; 3]; n]);
    let threads = rayon::current_num_threads().max(1);
    for level in 0..layout.levels() {
        let lv = layout.level(level);
        let band_rows = lv.height.div_ceil(BANDS_PER_THREAD * threads).max(1);
        let per = band_rows * lv.width;
        let range = lv.rows(0..lv.height);
        // Base rows per level row, for the progress bar.
        let weight = layout.height() as f64 / lv.height as f64;
        let a_chunks: Box<dyn Iterator<Item = Option<&mut [[f32; 3]]>>> = match aniso.as_mut() {
            Some(a) => Box::new(a[range.clone()].chunks_mut(per).map(Some)),
            None => Box::new(std::iter::repeat_with(|| None)),
        };
        let jobs: Vec<_> = moments[range.clone()]
            .chunks_mut(per)
            .zip(isotropic[range.clone()].chunks_mut(per))
            .zip(a_chunks)
            .enumerate()
            .collect();
        jobs.into_par_iter().try_for_each_init(
            || vec![TexelStats::default(); layout.scratch_len()],
            |scratch, (i, ((m, iso), a))| {
                let rows = i * band_rows..((i + 1) * band_rows).min(lv.height);
                let mut band = Band {
                    moments: Some(m),
                    ..Band::default()
                };
                match ndf {
                    Ndf::Ggx => {
                        band.ggx = Some(iso);
                        band.ggx_anisotropic = a;
                    }
                    Ndf::Beckmann => {
                        band.beckmann = Some(iso);
                        band.beckmann_anisotropic = a;
                    }
                }
                let done = (rows.len() as f64 * weight).round() as u64;
                bake_rows(source, settings, &layout, level, rows, scratch, band)?;
                progress.inc(done);
                Ok(())
            },
        )?;
    }
    Ok(Chains {
        layout,
        moments,
        isotropic,
        anisotropic: aniso,
    })
}
