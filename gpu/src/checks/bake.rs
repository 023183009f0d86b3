//! `shaders/bake/moments.wgsl` and `shaders/bake/roughness.wgsl`: a moment chain baked by the
//! library (`filtered_ndf::bake`, the GPU box kernel, `f32` storage, and its `f16` rounding)
//! from a procedural slope map, uploaded as the two textures of the moment layout
//! (`rgba = (E[s_x], E[s_y], E[s_x^2], E[s_y^2])`, `r = E[s_x s_y]`, all levels) and sampled by
//! the hardware's filtering; and the roughness decoders on buffer inputs.
//!
//! The map: `32 x 16` texels (six levels, `32 x 16` to `1 x 1`), slopes
//! `s = (0.3 sin(2 pi (2x + y) / 32) + 0.1 cos(2 pi 3y / 16), 0.25 cos(2 pi x / 32) sin(2 pi y /
//! 16) - 0.05)` at texel centres. Power-of-two sizes keep every texture coordinate below
//! exact in f32, so the filter weights are the ones stated.
//!
//! The `rgba32float` checks need `float32-filterable` (an optional WebGPU feature: lavapipe
//! has it, wgpu's GL backend on llvmpipe does not); on an adapter without it they report
//! "not run" with zero cases (`checks::run`), and the `rgba16float` checks, which every
//! adapter filters, cover the same functions.
//!
//! Tolerances (`Tol::of_scale`: absolute, relative to the largest texel the fetch blends):
//! - texel centres at integer levels: the bilinear weights are `1` and `0`, so the fetch is the
//!   stored texel: 2 ulp of it (exact in exact arithmetic; margin for a driver that blends in
//!   another order).
//! - quarter-texel offsets at half levels: every weight is a multiple of `1/8` (bilinear) and
//!   `1/2` (between levels), exact in the 4 bits of sub-texel and mipmap precision Vulkan
//!   requires at least, so the fetch is the closed-form trilinear blend up to the rounding of
//!   at most 8 products and 7 sums: 16 ulp of the largest blended texel.
//! - `textureSampleGrad` with derivatives of `2^(k + 1/2)` base texels per pixel on both axes
//!   (level of detail `k + 1/2`): the same blend, plus the driver's level-of-detail error
//!   (`log2` of the derivatives' length, which drivers approximate): `2^-4` of the difference
//!   between the two levels' values (one step of 4-bit mipmap precision).
//! - the covariance formed from a fetched texel: `delta_ij = EPS (|E[s_i] E[s_j]| +
//!   |Sigma_ij|)` (the product and the difference round once each; `checks/lean_nested.rs`).

use super::{Check, EPS, TINY, Tol};
use crate::harness::{TEXTURE_DECLARATIONS, TextureChain, Textures};
use filtered_ndf::bake::decode::alpha_from_perceptual;
use filtered_ndf::bake::f16::{f16_saturating, f16_to_f32};
use filtered_ndf::bake::fit::{AnisotropicAlpha, KhrAnisotropy};
use filtered_ndf::bake::{self, BaseRoughness, ChainLayout, Kernel, Settings, SlopeMap};
use glam::DVec2;
use std::sync::Arc;

const W: usize = 32;
const H: usize = 16;

/// The procedural map's slopes (module docs).
fn slopes() -> Vec<DVec2> {
    let tau = std::f64::consts::TAU;
    let mut v = Vec::with_capacity(W * H);
    for y in 0..H {
        for x in 0..W {
            let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
            v.push(DVec2::new(
                0.3 * (tau * (2.0 * fx + fy) / 32.0).sin() + 0.1 * (tau * 3.0 * fy / 16.0).cos(),
                0.25 * (tau * fx / 32.0).cos() * (tau * fy / 16.0).sin() - 0.05,
            ));
        }
    }
    v
}

/// The baked chain: every level's texels `[E[s_x], E[s_y], E[s_x^2], E[s_x s_y], E[s_y^2]]`
/// (`f32`, or rounded to `f16` and back).
struct Chain {
    layout: ChainLayout,
    texels: Vec<[f32; 5]>,
}

impl Chain {
    fn bake(half: bool) -> Self {
        let s = slopes();
        let map = SlopeMap::new(&s, W, H).expect("valid slopes");
        let layout = ChainLayout::new(W, H).expect("valid size");
        let settings = Settings {
            kernel: Kernel::GpuBox,
            base: BaseRoughness::Constant(0.1),
        };
        let mut texels = vec![[0f32; 5]; layout.len()];
        let mut scratch = vec![bake::TexelStats::default(); layout.scratch_len()];
        for k in 0..layout.levels() {
            let lv = layout.level(k);
            let band = bake::Band {
                moments: Some(&mut texels[lv.offset..lv.offset + lv.len()]),
                ..Default::default()
            };
            bake::bake_rows(
                &map,
                &settings,
                &layout,
                k,
                0..lv.height,
                &mut scratch,
                band,
            )
            .expect("bakes");
        }
        if half {
            for t in &mut texels {
                *t = t.map(|v| f16_to_f32(f16_saturating(v)));
            }
        }
        Self { layout, texels }
    }

    fn textures(&self, half: bool) -> Arc<Textures> {
        let rgba = self
            .texels
            .iter()
            .flat_map(|t| [t[0], t[1], t[2], t[4]])
            .collect();
        let r = self.texels.iter().map(|t| t[3]).collect();
        let chain = |channels, texels| TextureChain {
            width: W as u32,
            height: H as u32,
            channels,
            texels,
        };
        Arc::new(Textures {
            rgba: chain(4, rgba),
            r: chain(1, r),
            half,
        })
    }

    /// Texel `(i, j)` of level `k`, clamped to the edge, in f64.
    fn texel(&self, k: usize, i: i64, j: i64) -> [f64; 5] {
        let lv = self.layout.level(k);
        let i = i.clamp(0, lv.width as i64 - 1) as usize;
        let j = j.clamp(0, lv.height as i64 - 1) as usize;
        self.texels[lv.offset + j * lv.width + i].map(f64::from)
    }

    /// The bilinear fetch of level `k` at `uv` (clamp to edge): each output and the largest
    /// magnitude it blends.
    fn bilinear(&self, k: usize, uv: DVec2) -> [(f64, f64); 5] {
        let lv = self.layout.level(k);
        let x = uv.x * lv.width as f64 - 0.5;
        let y = uv.y * lv.height as f64 - 0.5;
        let (i, j) = (x.floor() as i64, y.floor() as i64);
        let (fx, fy) = (x - x.floor(), y - y.floor());
        let mut out = [(0.0, 0.0); 5];
        for (di, dj, w) in [
            (0, 0, (1.0 - fx) * (1.0 - fy)),
            (1, 0, fx * (1.0 - fy)),
            (0, 1, (1.0 - fx) * fy),
            (1, 1, fx * fy),
        ] {
            let t = self.texel(k, i + di, j + dj);
            for c in 0..5 {
                out[c].0 += w * t[c];
                if w > 0.0 {
                    out[c].1 = f64::max(out[c].1, t[c].abs());
                }
            }
        }
        out
    }
}

/// The snippet's outputs: the moments in the order of the chain's texels.
const OUT: &str = "y2(0u, m.mean);\ny(2u, m.second.x);\ny(3u, m.second.y);\ny(4u, m.second.z);";

fn imports() -> String {
    format!(
        "#import filtered_ndf::filter::lean\n#import filtered_ndf::bake::moments\n{TEXTURE_DECLARATIONS}"
    )
}

fn level_check(chain: &Chain, half: bool) -> Check {
    let fmt = if half { "16" } else { "32" };
    let body = format!(
        "let m = moments::sample_level(harness_moments, harness_moments_xy, harness_sampler, x2(0u), x(2u));\n{OUT}"
    );
    let mut c = Check::new(
        &format!("moments::sample_level (texel centres, every level, rgba{fmt}float)"),
        &imports(),
        &body,
        3,
        5,
    )
    .tolerance("2 ulp of the texel (weights 1 and 0: the stored value)")
    .with_textures(chain.textures(half));
    for k in 0..chain.layout.levels() {
        let lv = chain.layout.level(k);
        for j in 0..lv.height {
            for i in 0..lv.width {
                let uv = [
                    ((i as f64 + 0.5) / lv.width as f64) as f32,
                    ((j as f64 + 0.5) / lv.height as f64) as f32,
                ];
                let t = chain.texel(k, i as i64, j as i64);
                let tol = t.iter().map(|v| Tol::of_scale(2.0, v.abs())).collect();
                c.case(vec![uv[0], uv[1], k as f32], t.to_vec(), tol);
            }
        }
    }
    c
}

fn blend_check(chain: &Chain, half: bool) -> Check {
    let fmt = if half { "16" } else { "32" };
    let body = format!(
        "let m = moments::sample_level(harness_moments, harness_moments_xy, harness_sampler, x2(0u), x(2u));\n{OUT}"
    );
    let mut c = Check::new(
        &format!("moments::sample_level (bilinear and trilinear blends, rgba{fmt}float)"),
        &imports(),
        &body,
        3,
        5,
    )
    .tolerance("16 ulp of the largest blended texel (weights multiples of 1/8 and 1/2: exact)")
    .with_textures(chain.textures(half));
    for k in 0..chain.layout.levels() - 1 {
        let lv = chain.layout.level(k);
        for j in 0..lv.height {
            for i in 0..lv.width {
                let uv = DVec2::new(
                    (i as f64 + 0.75) / lv.width as f64,
                    (j as f64 + 0.25) / lv.height as f64,
                );
                let (a, b) = (chain.bilinear(k, uv), chain.bilinear(k + 1, uv));
                let expect = (0..5).map(|c| 0.5 * (a[c].0 + b[c].0)).collect();
                let tol = (0..5)
                    .map(|c| Tol::of_scale(16.0, a[c].1.max(b[c].1)))
                    .collect();
                c.case(vec![uv.x as f32, uv.y as f32, k as f32 + 0.5], expect, tol);
            }
        }
    }
    c
}

fn grad_check(chain: &Chain, half: bool) -> Check {
    let fmt = if half { "16" } else { "32" };
    let body = format!(
        "let m = moments::sample_grad(harness_moments, harness_moments_xy, harness_sampler, x2(0u), x2(2u), x2(4u));\n{OUT}"
    );
    let mut c = Check::new(
        &format!("moments::sample_grad (level of detail k + 1/2, rgba{fmt}float)"),
        &imports(),
        &body,
        6,
        5,
    )
    .tolerance("16 ulp of the largest blended texel, plus 2^-4 of the two levels' difference (the driver's level of detail)")
    .with_textures(chain.textures(half));
    for k in 0..chain.layout.levels() - 1 {
        let lv = chain.layout.level(k);
        let rho = 2f64.powf(k as f64 + 0.5);
        let ddx = [(rho / W as f64) as f32, 0.0];
        let ddy = [0.0, (rho / H as f64) as f32];
        for j in 0..lv.height {
            for i in 0..lv.width {
                let uv = DVec2::new(
                    (i as f64 + 0.5) / lv.width as f64,
                    (j as f64 + 0.5) / lv.height as f64,
                );
                let (a, b) = (chain.bilinear(k, uv), chain.bilinear(k + 1, uv));
                let expect = (0..5).map(|c| 0.5 * (a[c].0 + b[c].0)).collect();
                let tol = (0..5)
                    .map(|c| {
                        let t = Tol::of_scale(16.0, a[c].1.max(b[c].1));
                        Tol {
                            abs: t.abs + (a[c].0 - b[c].0).abs() / 16.0,
                            ..t
                        }
                    })
                    .collect();
                c.case(
                    vec![uv.x as f32, uv.y as f32, ddx[0], ddx[1], ddy[0], ddy[1]],
                    expect,
                    tol,
                );
            }
        }
    }
    c
}

fn covariance_check(chain: &Chain, half: bool) -> Check {
    let fmt = if half { "16" } else { "32" };
    let body = "let m = moments::sample_level(harness_moments, harness_moments_xy, harness_sampler, x2(0u), x(2u));\nlet c = lean::covariance(m);\ny(0u, c.s_xx);\ny(1u, c.s_xy);\ny(2u, c.s_yy);";
    let mut c = Check::new(
        &format!("lean::covariance of moments::sample_level (texel centres, rgba{fmt}float)"),
        &imports(),
        body,
        3,
        3,
    )
    .tolerance("EPS (|E[s_i] E[s_j]| + |Sigma_ij|) absolute per entry (f32 moments' cancellation)")
    .with_textures(chain.textures(half));
    for k in 0..chain.layout.levels() {
        let lv = chain.layout.level(k);
        for j in 0..lv.height {
            for i in 0..lv.width {
                let uv = [
                    ((i as f64 + 0.5) / lv.width as f64) as f32,
                    ((j as f64 + 0.5) / lv.height as f64) as f32,
                ];
                let t = chain.texel(k, i as i64, j as i64);
                let m = crate::reference::LeanMoments::new(
                    DVec2::new(t[0], t[1]),
                    crate::reference::Covariance::new(t[2], t[3], t[4]),
                );
                let cv = m.covariance();
                let d = |a: f64, b: f64, s: f64| Tol::abs(EPS * ((a * b).abs() + s.abs()) + TINY);
                c.case(
                    vec![uv[0], uv[1], k as f32],
                    vec![cv.s11, cv.s12, cv.s22],
                    vec![
                        d(t[0], t[0], cv.s11),
                        d(t[0], t[1], cv.s12),
                        d(t[1], t[1], cv.s22),
                    ],
                );
            }
        }
    }
    c
}

const ROUGHNESS_IMPORTS: &str = "#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::bake::roughness";

/// The roughness decoders against `bake::decode` in `f64`.
fn roughness_checks() -> Vec<Check> {
    let mut rng = crate::reference::SplitMix64(0xba4e_0051);
    let mut perceptual = Check::new(
        "roughness::from_perceptual",
        ROUGHNESS_IMPORTS,
        "y(0u, roughness::from_perceptual(x(0u)).alpha);",
        1,
        1,
    )
    .tolerance("1 ulp (one rounded product)");
    for k in 1..=255 {
        let r = k as f32 / 255.0;
        perceptual.case(
            vec![r],
            vec![alpha_from_perceptual(r.into())],
            vec![Tol::ulps(1.0)],
        );
    }
    // Entries of the matrix: from_eigen's eigenbasis reconstructed by `matrix::entries`
    // (4 ulp of the largest entry, `checks/filters.rs`), the axis from `sincos_turns` (3 ulp
    // of 1 absolute) after the angle's conversion to turns (2 ulp of it): each entry moves by
    // `2 alpha_x^2` times the axis error, 16 ulp of `alpha_x^2` with margin.
    let mut aniso = Check::new(
        "roughness::from_anisotropic",
        ROUGHNESS_IMPORTS,
        "y3(0u, matrix::entries(roughness::from_anisotropic(x3(0u))));",
        3,
        3,
    )
    .tolerance("16 ulp of alpha_x^2 per entry (sincos_turns' axis, matrix::entries)");
    for _ in 0..500 {
        let ay = rng.range(0.01, 1.0);
        let ax = ay * rng.range(1.0, 10.0);
        let angle = rng.range(-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2);
        let lobe = [ax as f32, ay as f32, angle as f32];
        let l = AnisotropicAlpha {
            alpha_x: lobe[0].into(),
            alpha_y: lobe[1].into(),
            angle: lobe[2].into(),
        };
        let m = l.matrix();
        let s = l.alpha_x * l.alpha_x;
        aniso.case(
            lobe.to_vec(),
            vec![m.0, m.1, m.2],
            vec![Tol::of_scale(16.0, s); 3],
        );
    }
    // KHR: the direction normalised (3 ulp), alpha_t = mix(alpha_b, 1, b^2) (4 roundings):
    // 24 ulp of alpha_t^2 per entry with the axis' and entries' share.
    let mut khr = Check::new(
        "roughness::from_khr_anisotropy",
        ROUGHNESS_IMPORTS,
        "y3(0u, matrix::entries(roughness::from_khr_anisotropy(x(0u), x4(1u))));",
        5,
        3,
    )
    .tolerance("24 ulp of alpha_t^2 per entry (normalised direction, the mix, matrix::entries)");
    for _ in 0..500 {
        let r = (rng.range(0.1, 1.0) * 255.0).round() as f32 / 255.0;
        let texel = [
            (rng.range(0.0, 1.0) * 255.0).round() as f32 / 255.0,
            (rng.range(0.0, 1.0) * 255.0).round() as f32 / 255.0,
            (rng.range(0.0, 1.0) * 255.0).round() as f32 / 255.0,
            1.0,
        ];
        let dir = DVec2::new(
            2.0 * f64::from(texel[0]) - 1.0,
            2.0 * f64::from(texel[1]) - 1.0,
        );
        if dir.length() < 0.05 {
            continue;
        }
        let k = KhrAnisotropy {
            roughness: r.into(),
            strength: texel[2].into(),
            direction: dir,
        };
        let l = k.alpha();
        let m = l.matrix();
        let s = l.alpha_x * l.alpha_x;
        let mut input = vec![r];
        input.extend(texel);
        khr.case(input, vec![m.0, m.1, m.2], vec![Tol::of_scale(24.0, s); 3]);
    }
    // The stored matrix read back: from_entries' eigen-decomposition and `entries`'
    // reconstruction (4 ulp of the largest entry each, `checks/filters.rs`; the f32
    // determinant's cancellation is `cond(A) eps`, cond <= 100 here): 8 ulp plus `cond A` ulp.
    let mut texel = Check::new(
        "roughness::from_matrix_texel",
        ROUGHNESS_IMPORTS,
        "y3(0u, matrix::entries(roughness::from_matrix_texel(x4(0u))));",
        4,
        3,
    )
    .tolerance("(8 + cond A) ulp of the largest entry (eigen-decomposition and reconstruction)");
    for _ in 0..500 {
        let ay = rng.range(0.01, 1.0);
        let ax = ay * rng.range(1.0, 10.0);
        let l = AnisotropicAlpha {
            alpha_x: ax,
            alpha_y: ay,
            angle: rng.range(-1.5, 1.5),
        };
        let m = l.matrix();
        let t = [m.0 as f32, m.1 as f32, m.2 as f32, 1.0];
        let cond = (ax / ay).powi(2);
        let big = f64::from(t[0].abs().max(t[1].abs()).max(t[2].abs()));
        texel.case(
            t.to_vec(),
            vec![t[0].into(), t[1].into(), t[2].into()],
            vec![Tol::of_scale(8.0 + cond, big); 3],
        );
    }
    vec![perceptual, aniso, khr, texel]
}

/// The checks of `shaders/bake/`.
pub fn all() -> Vec<Check> {
    let (f32_chain, f16_chain) = (Chain::bake(false), Chain::bake(true));
    let mut checks = vec![
        level_check(&f32_chain, false),
        level_check(&f16_chain, true),
        blend_check(&f32_chain, false),
        blend_check(&f16_chain, true),
        grad_check(&f32_chain, false),
        grad_check(&f16_chain, true),
        covariance_check(&f32_chain, false),
        covariance_check(&f16_chain, true),
    ];
    checks.extend(roughness_checks());
    checks
}
