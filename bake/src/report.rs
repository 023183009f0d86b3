//! The report's figures per level: the slope variance the level adds, the mean fitted
//! roughness, and the fit's error against the true distribution of normals of its texels.
//!
//! **Variance added**: `tr Cov[s]` of each texel from its stored moments
//! ([`crate::encode::variance`]), mean and largest over the level: the variance of the base
//! slopes within the texel's footprint, which the level's lobe has to absorb.
//!
//! **Fit error**: the total variation `integral |P22_true(s) - P22_fit(s)| ds` (in `[0, 2]`,
//! the criterion of `filtered_ndf::bake::fit`), averaged over up to [`SAMPLED`] texels of the
//! level spread evenly over it. `P22_true` is the texel's base lobes (the base roughness at
//! each base texel, centred on its slope) averaged over its footprint; footprints wider than
//! [`SUB`] texels along an axis are represented by [`SUB`] evenly spaced texels along it, with
//! equal weights (exact at the levels whose footprints are at most `SUB x SUB` texels, an
//! estimate above; `docs/bake.md` has the exact study). The fitted lobe is the baked one,
//! centred at the normalised mean normal of the same texels. Quadrature: a [`GRID`] x
//! [`GRID`] midpoint rule in `s = c + S (tan u, tan v)`, `S^2` the mean squared base
//! roughness plus the mean squared slope offset from `c`; its error shows in the mass error,
//! `|integral P22_true - 1|`, reported per level (largest over the sampled texels).

use crate::chain::{Chains, Ndf};
use crate::encode::{self, lobe};
use filtered_ndf::bake::{Kernel, SlopeSource};
use filtered_ndf::f64::prelude::{Beckmann, Ggx, Ndf as _, RoughnessMatrix};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Texels sampled per level for the fit error.
pub const SAMPLED: usize = 8;
/// Base texels per axis representing a footprint.
pub const SUB: usize = 8;
/// Quadrature nodes per axis.
pub const GRID: usize = 64;

/// One level's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelStats {
    /// The level.
    pub level: usize,
    /// Its width.
    pub width: usize,
    /// Its height.
    pub height: usize,
    /// Mean `tr Cov[s]` over the level.
    pub mean_variance: f64,
    /// Largest `tr Cov[s]`.
    pub max_variance: f64,
    /// Mean isotropic `alpha`.
    pub mean_alpha: f64,
    /// Mean anisotropic `(alpha_x, alpha_y)`, when baked.
    pub mean_alpha_xy: Option<(f64, f64)>,
    /// Mean total variation of the isotropic fit over the sampled texels.
    pub error_isotropic: f64,
    /// Mean total variation of the anisotropic fit, when baked.
    pub error_anisotropic: Option<f64>,
    /// The sampled texels.
    pub sampled: usize,
    /// Base texels representing each sampled footprint (the largest).
    pub lobes: usize,
    /// Largest `|integral P22_true - 1|` over the sampled texels.
    pub mass_error: f64,
}

/// The base texels `lo..hi` of texel `i` of a level of `nk` texels along an axis of `n`
/// (the kernels of `filtered_ndf::bake::Kernel`).
fn footprint(kernel: Kernel, n: usize, nk: usize, k: usize, i: usize) -> (usize, usize) {
    match kernel {
        Kernel::GpuBox => {
            let block = 1usize << k.min((usize::BITS - 1 - n.leading_zeros()) as usize);
            (i * block, (i * block + block).min(n))
        }
        Kernel::Area => ((i * n) / nk, ((i + 1) * n).div_ceil(nk)),
    }
}

/// At most [`SUB`] evenly spaced indices of `lo..hi`.
fn sub(lo: usize, hi: usize) -> Vec<usize> {
    let len = hi - lo;
    let m = len.min(SUB);
    (0..m).map(|j| lo + ((2 * j + 1) * len) / (2 * m)).collect()
}

/// A lobe of `ndf` with the roughness matrix `(a11, a12, a22)` (eigenvalues clamped into the
/// crate's range).
fn p22_of(ndf: Ndf, a: (f64, f64, f64)) -> impl Fn(DVec2) -> f64 {
    let floor = 1e-12;
    let m = RoughnessMatrix::new(a.0.max(floor), a.1, a.2.max(floor))
        .or_else(|_| RoughnessMatrix::new(a.0.max(floor), 0.0, a.2.max(floor)))
        .expect("a positive diagonal is a roughness matrix");
    move |s| match ndf {
        Ndf::Ggx => Ggx::new(m).p22(s),
        Ndf::Beckmann => Beckmann::new(m).p22(s),
    }
}

/// The total variations of the isotropic and (if given) anisotropic fits of one texel, and
/// the mass error, against `texels` (slope, normal, base alpha).
fn texel_error(
    ndf: Ndf,
    texels: &[(DVec2, DVec3, f64)],
    alpha: f64,
    aniso: Option<[f32; 3]>,
) -> (f64, Option<f64>, f64) {
    let n: DVec3 = texels.iter().map(|t| t.1).sum();
    let c = DVec2::new(-n.x / n.z, -n.y / n.z);
    let count = texels.len() as f64;
    let s2 = texels
        .iter()
        .map(|t| t.2 * t.2 + (t.0 - c).length_squared())
        .sum::<f64>()
        / count;
    let scale = s2.sqrt().max(1e-6);
    let base: Vec<_> = texels
        .iter()
        .map(|t| (t.0, p22_of(ndf, (t.2 * t.2, 0.0, t.2 * t.2))))
        .collect();
    let iso = p22_of(ndf, (alpha * alpha, 0.0, alpha * alpha));
    let an = aniso.map(|a| p22_of(ndf, encode::matrix(&lobe(a))));
    let h = PI / GRID as f64;
    let (mut tv_iso, mut tv_an, mut mass) = (0.0, 0.0, 0.0);
    for j in 0..GRID {
        let v = -0.5 * PI + (j as f64 + 0.5) * h;
        let (tv, cv) = (v.tan(), v.cos());
        for i in 0..GRID {
            let u = -0.5 * PI + (i as f64 + 0.5) * h;
            let (tu, cu) = (u.tan(), u.cos());
            let s = c + scale * DVec2::new(tu, tv);
            let w = h * h * scale * scale / (cu * cu * cv * cv);
            let truth = base.iter().map(|(si, p)| p(s - *si)).sum::<f64>() / count;
            mass += w * truth;
            tv_iso += w * (truth - iso(s - c)).abs();
            if let Some(p) = &an {
                tv_an += w * (truth - p(s - c)).abs();
            }
        }
    }
    (tv_iso, an.map(|_| tv_an), (mass - 1.0).abs())
}

/// The figures of every level. `base_alpha(x, y)` is the base roughness `alpha` of a base
/// texel.
pub fn levels<S: SlopeSource + Sync>(
    source: &S,
    chains: &Chains,
    kernel: Kernel,
    ndf: Ndf,
    base_alpha: &(dyn Fn(usize, usize) -> f64 + Sync),
) -> Vec<LevelStats> {
    let layout = chains.layout;
    (0..layout.levels())
        .into_par_iter()
        .map(|k| {
            let lv = layout.level(k);
            let range = lv.rows(0..lv.height);
            let m = &chains.moments[range.clone()];
            let var: Vec<f64> = m.iter().map(encode::variance).collect();
            let count = lv.len() as f64;
            let mean_alpha = chains.isotropic[range.clone()]
                .iter()
                .map(|&a| f64::from(a))
                .sum::<f64>()
                / count;
            let mean_alpha_xy = chains.anisotropic.as_ref().map(|an| {
                let (sx, sy) = an[range.clone()].iter().fold((0.0, 0.0), |(x, y), a| {
                    (x + f64::from(a[0]), y + f64::from(a[1]))
                });
                (sx / count, sy / count)
            });
            let picks = lv.len().min(SAMPLED);
            let (mut ei, mut ea, mut mass, mut lobes) = (0.0, 0.0, 0.0f64, 0usize);
            for p in 0..picks {
                let t = if picks > 1 {
                    p * (lv.len() - 1) / (picks - 1)
                } else {
                    0
                };
                let (ix, iy) = (t % lv.width, t / lv.width);
                let (x0, x1) = footprint(kernel, layout.width(), lv.width, k, ix);
                let (y0, y1) = footprint(kernel, layout.height(), lv.height, k, iy);
                let texels: Vec<_> = sub(y0, y1)
                    .into_iter()
                    .flat_map(|y| sub(x0, x1).into_iter().map(move |x| (x, y)))
                    .map(|(x, y)| {
                        let (s, n) = source.texel(x, y);
                        (s, n, base_alpha(x, y))
                    })
                    .collect();
                lobes = lobes.max(texels.len());
                let aniso = chains.anisotropic.as_ref().map(|an| an[range.start + t]);
                let alpha = f64::from(chains.isotropic[range.start + t]);
                let (i, a, me) = texel_error(ndf, &texels, alpha, aniso);
                ei += i;
                ea += a.unwrap_or(0.0);
                mass = mass.max(me);
            }
            LevelStats {
                level: k,
                width: lv.width,
                height: lv.height,
                mean_variance: var.iter().sum::<f64>() / count,
                max_variance: var.iter().copied().fold(0.0, f64::max),
                mean_alpha,
                mean_alpha_xy,
                error_isotropic: ei / picks as f64,
                error_anisotropic: chains.anisotropic.as_ref().map(|_| ea / picks as f64),
                sampled: picks,
                lobes,
                mass_error: mass,
            }
        })
        .collect()
}
