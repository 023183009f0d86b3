//! The bake's accuracy study: for each map and mip level, the true distribution of normals of
//! a texel (its base texels' GGX lobes averaged, `P22_true(s) = sum_i w_i P22_GGX(s - s_i;
//! alpha)`, evaluated in `f64` lobe by lobe) against the GGX lobe of each roughness bake:
//! Toksvig's factor, Unreal's composite texture, three.js's RoughnessMipmapper, LEAN's
//! Gaussian (KHPL16 eq. 21) and the crate's isotropic and anisotropic fits
//! (`filtered_ndf::bake::fit`). Writes the tables of `docs/bake.md` (between its markers) or
//! prints them.
//!
//! `cargo run --release -p filtered-ndf-demo --bin bake_accuracy [-- --write]`
//!
//! - D error: the total variation `integral |P22_true - P22_bake| ds` (= `integral |D_true -
//!   D_bake| cos(theta_h) d omega_h`), in `[0, 2]`.
//! - Highlight error: the reflected radiance of a small light, integrated over all light
//!   directions above the surface, L1 relative to the true one, for a view 60 degrees from the
//!   normal (azimuths along `+x` and `+y`, averaged); masking and Fresnel left out (both bakes
//!   would share them to first order). For a view along the normal this is the total
//!   variation again.
//! - Quadrature: a midpoint grid about the fitted centre, `s = c + S (tan u, tan v)` (`S` the
//!   texel's spread, `sqrt(alpha^2 + lambda_1 + lambda_2)`), 384 x 384 nodes, every lobe of the
//!   texel summed at every node (identical slopes of 8-bit maps merged, weights added: exact).
//!   The grid's error is reported: the worst `|integral P22_true - 1|` over all texels, and the
//!   total variations recomputed on a grid twice as fine for a few texels.

use filtered_ndf::bake::fit::{self, Spread};
use filtered_ndf::bake::{
    BaseRoughness, ChainLayout, Convention, Kernel, NormalFormat, NormalMap, Settings, SlopeMap,
    SlopeSource, TexelStats, Texels, footprint_row,
};
use filtered_ndf_demo::bake_baselines as base;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::fmt::Write as _;

/// A GGX lobe: centre and `A = [[a11, a12], [a12, a22]]` (`alpha^2 I` for isotropic).
#[derive(Clone, Copy)]
struct Lobe {
    c: DVec2,
    inv: (f64, f64, f64),
    norm: f64,
}

impl Lobe {
    fn new(c: DVec2, (a11, a12, a22): (f64, f64, f64)) -> Self {
        let det = (a11 * a22 - a12 * a12).max(1e-300);
        Self {
            c,
            inv: (a22 / det, -a12 / det, a11 / det),
            norm: 1.0 / (PI * det.sqrt()),
        }
    }
    fn iso(c: DVec2, alpha: f64) -> Self {
        Self::new(c, (alpha * alpha, 0.0, alpha * alpha))
    }
    fn aniso(c: DVec2, a: fit::AnisotropicAlpha) -> Self {
        let (cs, sn) = (a.angle.cos(), a.angle.sin());
        let (x2, y2) = (a.alpha_x * a.alpha_x, a.alpha_y * a.alpha_y);
        Self::new(
            c,
            (
                cs * cs * x2 + sn * sn * y2,
                cs * sn * (x2 - y2),
                sn * sn * x2 + cs * cs * y2,
            ),
        )
    }
    #[inline]
    fn p22(&self, s: DVec2) -> f64 {
        let d = s - self.c;
        let q =
            1.0 + d.x * d.x * self.inv.0 + 2.0 * d.x * d.y * self.inv.1 + d.y * d.y * self.inv.2;
        self.norm / (q * q)
    }
}

/// Nodes per axis of the quadrature grid ([`evaluate`]).
const GRID: usize = 384;

const METHODS: [&str; 6] = [
    "Toksvig",
    "Unreal composite",
    "three.js mipmapper",
    "LEAN (KHPL16 eq. 21)",
    "crate, isotropic",
    "crate, anisotropic",
];

/// One map: its slopes and unit normals, row-major, base roughness `alpha`.
struct Map {
    name: String,
    w: usize,
    h: usize,
    slopes: Vec<DVec2>,
    normals: Vec<DVec3>,
}

impl Map {
    fn from_source<S: SlopeSource>(name: &str, src: &S) -> Self {
        let (w, h) = (src.width(), src.height());
        let mut slopes = Vec::with_capacity(w * h);
        let mut normals = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (s, n) = src.texel(x, y);
                slopes.push(s);
                normals.push(n);
            }
        }
        Self {
            name: name.to_string(),
            w,
            h,
            slopes,
            normals,
        }
    }
}

/// Per level: mean D error and highlight error per method, texels sampled, mean spread.
struct LevelRow {
    level: usize,
    texels: usize,
    spread: f64,
    tv: [f64; 6],
    hl: [f64; 6],
}

struct Texel {
    tv: [f64; 6],
    hl: [f64; 6],
    mass: f64,
    spread: f64,
}

/// The errors of the bakes against the texel's true distribution, on an `n x n` midpoint grid
/// in `(u, v) in (-pi/2, pi/2)^2` mapped by `s = centre + scale (tan u, tan v)`: the core is
/// sampled every `scale pi / n` (a fraction of the base lobe's width for the spreads here),
/// the tails out to infinity.
fn evaluate(
    lobes: &[(DVec2, f64)],
    alpha: f64,
    bakes: &[Lobe; 6],
    centre: DVec2,
    scale: f64,
    n: usize,
) -> Texel {
    let hu = PI / n as f64;
    let (a2, norm) = (alpha * alpha, 1.0 / (PI * alpha * alpha));
    // Views 60 degrees from the normal, azimuths +x and +y.
    let (st, ct) = (60f64.to_radians().sin(), 60f64.to_radians().cos());
    let views = [DVec3::new(st, 0.0, ct), DVec3::new(0.0, st, ct)];
    let axis: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let u = -0.5 * PI + (i as f64 + 0.5) * hu;
            (scale * u.tan(), scale / (u.cos() * u.cos()) * hu)
        })
        .collect();
    let (mut tv, mut hl_num, mut hl_den, mut mass) = ([0.0; 6], [[0.0; 6]; 2], [0.0; 2], 0.0);
    for &(y, dy) in &axis {
        for &(x, dx) in &axis {
            let da = dx * dy;
            let s = centre + DVec2::new(x, y);
            let mut p = 0.0;
            for &(si, wi) in lobes {
                let d = s - si;
                let q = 1.0 + (d.x * d.x + d.y * d.y) / a2;
                p += wi / (q * q);
            }
            p *= norm;
            mass += p * da;
            // Highlight weight: (v_z - v_xy . s) / v_z where v.h > 0 and the light is above.
            let hn = DVec3::new(-s.x, -s.y, 1.0).normalize();
            let mut wv = [0.0; 2];
            for (k, v) in views.iter().enumerate() {
                let vh = v.dot(hn);
                let l = 2.0 * vh * hn - *v;
                if vh > 0.0 && l.z > 0.0 {
                    wv[k] = (v.z - v.x * s.x - v.y * s.y) / v.z;
                    hl_den[k] += p * wv[k] * da;
                }
            }
            for (m, b) in bakes.iter().enumerate() {
                let e = (p - b.p22(s)).abs() * da;
                tv[m] += e;
                for k in 0..2 {
                    hl_num[k][m] += e * wv[k];
                }
            }
        }
    }
    let mut hl = [0.0; 6];
    for m in 0..6 {
        hl[m] = 0.5 * (hl_num[0][m] / hl_den[0] + hl_num[1][m] / hl_den[1]);
    }
    Texel {
        tv,
        hl,
        mass,
        spread: 0.0,
    }
}

/// The bakes of every level of a power-of-two map.
fn study(map: &Map, alpha: f64, max_level: usize, budget: f64) -> (Vec<LevelRow>, f64, f64) {
    let (w, h) = (map.w, map.h);
    let slope_map = SlopeMap::new(&map.slopes, w, h).unwrap();
    let layout = ChainLayout::new(w, h).unwrap();
    let settings = Settings {
        kernel: Kernel::Area,
        base: BaseRoughness::Constant(alpha),
    };
    // three.js: normal mips (box means of the unit normals, not renormalised) and perceptual
    // roughness, level by level from the one below.
    let mut normal_mips = vec![map.normals.clone()];
    let mut rough_mips = vec![vec![alpha.sqrt(); w * h]];
    let mut rows = Vec::new();
    let (mut worst_mass, mut worst_refine) = (0.0f64, 0.0f64);
    for level in 1..=max_level.min(layout.levels() - 1) {
        let lv = layout.level(level);
        let (pw, pn, pr) = (
            layout.level(level - 1).width,
            &normal_mips[level - 1],
            &rough_mips[level - 1],
        );
        let mut nm = vec![DVec3::ZERO; lv.len()];
        let mut rm = vec![0.0; lv.len()];
        for y in 0..lv.height {
            for x in 0..lv.width {
                let idx = [
                    (2 * x, 2 * y),
                    (2 * x + 1, 2 * y),
                    (2 * x, 2 * y + 1),
                    (2 * x + 1, 2 * y + 1),
                ];
                let n4 = idx.map(|(a, b)| pn[b * pw + a]);
                let r4 = idx.map(|(a, b)| pr[b * pw + a]);
                nm[y * lv.width + x] = 0.25 * n4.iter().sum::<DVec3>();
                rm[y * lv.width + x] = base::three_step(r4, n4);
            }
        }
        normal_mips.push(nm);
        rough_mips.push(rm);
        // Sample texels: every `step`-th in row-major order.
        let block = 1usize << level;
        let per_texel = (block * block) as f64 * (GRID * GRID) as f64;
        let want = ((budget / per_texel) as usize).clamp(1, 32).min(lv.len());
        let step = lv.len() / want;
        let picks: Vec<usize> = (0..want).map(|i| i * step + step / 2).collect();
        let results: Vec<(Texel, Option<[f64; 6]>)> = picks
            .par_iter()
            .enumerate()
            .map(|(pi, &t)| {
                let (tx, ty) = (t % lv.width, t / lv.width);
                let mut scratch = vec![TexelStats::default(); w];
                let mut out = vec![TexelStats::default(); lv.width];
                footprint_row(
                    &slope_map,
                    &settings,
                    &layout,
                    level,
                    ty,
                    &mut scratch,
                    &mut out,
                )
                .unwrap();
                let st = out[tx];
                let spread = Spread::of(&st);
                // The texel's lobes, identical slopes merged.
                let mut merged: HashMap<(u64, u64), f64> = HashMap::new();
                let wgt = 1.0 / (block * block) as f64;
                for y in ty * block..(ty + 1) * block {
                    for x in tx * block..(tx + 1) * block {
                        let s = map.slopes[y * w + x];
                        *merged.entry((s.x.to_bits(), s.y.to_bits())).or_default() += wgt;
                    }
                }
                let lobes: Vec<(DVec2, f64)> = merged
                    .into_iter()
                    .map(|((a, b), wt)| (DVec2::new(f64::from_bits(a), f64::from_bits(b)), wt))
                    .collect();
                let l = st.normal.length();
                let c = spread.centre;
                let (lc, la) =
                    base::lean_lobe(alpha, st.mean, (st.second.x, st.second.y, st.second.z));
                let bakes = [
                    Lobe::iso(c, base::toksvig(alpha, l)),
                    Lobe::iso(c, base::unreal(alpha, l)),
                    Lobe::iso(c, rough_mips[level][t].powi(2)),
                    Lobe::new(lc, la),
                    Lobe::iso(c, fit::ggx_isotropic(&spread)),
                    Lobe::aniso(c, fit::ggx_anisotropic(&spread)),
                ];
                let scale = (alpha * alpha + spread.lambda_1 + spread.lambda_2).sqrt();
                let mut r = evaluate(&lobes, alpha, &bakes, c, scale, GRID);
                r.spread = (spread.lambda_1 + spread.lambda_2).sqrt();
                let fine = (pi < 2 && level <= 3)
                    .then(|| evaluate(&lobes, alpha, &bakes, c, scale, 2 * GRID).tv);
                (r, fine)
            })
            .collect();
        let n = results.len() as f64;
        let mut row = LevelRow {
            level,
            texels: results.len(),
            spread: 0.0,
            tv: [0.0; 6],
            hl: [0.0; 6],
        };
        for (r, fine) in &results {
            row.spread += r.spread / n;
            worst_mass = worst_mass.max((r.mass - 1.0).abs());
            for m in 0..6 {
                row.tv[m] += r.tv[m] / n;
                row.hl[m] += r.hl[m] / n;
                if let Some(f) = fine {
                    worst_refine = worst_refine.max((f[m] - r.tv[m]).abs());
                }
            }
        }
        eprintln!("{} level {level}: {} texels", map.name, results.len());
        rows.push(row);
    }
    (rows, worst_mass, worst_refine)
}

fn table(out: &mut String, rows: &[LevelRow], hl: bool) {
    let _ = write!(out, "| level | texels | spread |");
    for m in METHODS {
        let _ = write!(out, " {m} |");
    }
    let _ = writeln!(out);
    let _ = writeln!(out, "|---:|---:|---:|{}", "---:|".repeat(METHODS.len()));
    for r in rows {
        let v = if hl { &r.hl } else { &r.tv };
        let best = v.iter().cloned().fold(f64::INFINITY, f64::min);
        let _ = write!(out, "| {} | {} | {:.3} |", r.level, r.texels, r.spread);
        for &x in v {
            if x == best {
                let _ = write!(out, " **{x:.4}** |");
            } else {
                let _ = write!(out, " {x:.4} |");
            }
        }
        let _ = writeln!(out);
    }
}

fn load_png(path: &str) -> (Vec<u8>, usize, usize) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .to_rgb8();
    let (w, h) = img.dimensions();
    (img.into_raw(), w as usize, h as usize)
}

/// The GPU box against the exact footprint on a map of odd size: the largest difference of
/// the covariance's trace per level, relative to the footprint's mean trace.
fn kernels_on_odd_sizes(out: &mut String) {
    let (w, h) = (203usize, 141usize);
    let slopes: Vec<DVec2> = (0..h)
        .flat_map(|y| {
            (0..w).map(move |x| {
                DVec2::new(
                    0.3 * (2.0 * PI * 5.3 * x as f64 / w as f64).cos(),
                    0.2 * (2.0 * PI * 3.7 * y as f64 / h as f64).sin(),
                )
            })
        })
        .collect();
    let map = SlopeMap::new(&slopes, w, h).unwrap();
    let layout = ChainLayout::new(w, h).unwrap();
    let _ = writeln!(
        out,
        "| level | size | max rel. difference of E[s] | of tr Cov[s] |"
    );
    let _ = writeln!(out, "|---:|---:|---:|---:|");
    for level in 1..layout.levels() {
        let lv = layout.level(level);
        let (mut dm, mut dc) = (0.0f64, 0.0f64);
        let mut scratch = vec![TexelStats::default(); w];
        for row in 0..lv.height {
            let mut a = vec![TexelStats::default(); lv.width];
            let mut b = a.clone();
            for (kernel, o) in [(Kernel::GpuBox, &mut a), (Kernel::Area, &mut b)] {
                let s = Settings {
                    kernel,
                    base: BaseRoughness::Constant(0.1),
                };
                footprint_row(&map, &s, &layout, level, row, &mut scratch, o).unwrap();
            }
            for (x, y) in a.iter().zip(&b) {
                let (cx, cy) = (x.covariance(), y.covariance());
                let scale_m = y.second.x.sqrt().max(y.second.z.sqrt());
                dm = dm.max((x.mean - y.mean).length() / scale_m);
                dc = dc.max(((cx.0 + cx.2) - (cy.0 + cy.2)).abs() / (y.second.x + y.second.z));
            }
        }
        let _ = writeln!(
            out,
            "| {level} | {}x{} | {dm:.3} | {dc:.3} |",
            lv.width, lv.height
        );
    }
}

fn main() {
    let write = std::env::args().any(|a| a == "--write");
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let alpha = 0.05;
    let budget = 1e9;
    let mut maps = Vec::new();
    // Procedural: separable sinusoids (anisotropic spread), 128 x 128.
    let n = 128;
    let tau = 2.0 * PI;
    let sines: Vec<DVec2> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64 + 0.5, (i / n) as f64 + 0.5);
            DVec2::new(
                0.3 * (tau * 5.0 * x / n as f64).cos(),
                0.12 * (tau * 13.0 * y / n as f64).cos(),
            )
        })
        .collect();
    maps.push(Map::from_source(
        "sinusoids",
        &SlopeMap::new(&sines, n, n).unwrap(),
    ));
    // Procedural: 300 random Gaussian bumps, periodic, slopes in closed form.
    let mut rng = filtered_ndf::testing::rng::SplitMix64(0xB0B5);
    let bumps: Vec<(f64, f64, f64, f64)> = (0..300)
        .map(|_| {
            (
                rng.uniform() * n as f64,
                rng.uniform() * n as f64,
                2.0 + 4.0 * rng.uniform(),
                (rng.uniform() - 0.5) * 3.0,
            )
        })
        .collect();
    let bump_slopes: Vec<DVec2> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64 + 0.5, (i / n) as f64 + 0.5);
            let mut s = DVec2::ZERO;
            for &(bx, by, r, a) in &bumps {
                for (ox, oy) in [
                    (0.0, 0.0),
                    (n as f64, 0.0),
                    (-(n as f64), 0.0),
                    (0.0, n as f64),
                    (0.0, -(n as f64)),
                ] {
                    let (dx, dy) = (x - bx - ox, y - by - oy);
                    let g = a * (-(dx * dx + dy * dy) / (2.0 * r * r)).exp();
                    // Height a exp(-d^2 / 2r^2) in texel units; slope -d / r^2 times it.
                    s += DVec2::new(-dx, dy) / (r * r) * g;
                }
            }
            s
        })
        .collect();
    maps.push(Map::from_source(
        "Gaussian bumps",
        &SlopeMap::new(&bump_slopes, n, n).unwrap(),
    ));
    for (file, name) in [
        ("pmndrs_0011.png", "real: pmndrs 0011 (wood)"),
        ("pmndrs_0024.png", "real: pmndrs 0024 (cracks)"),
    ] {
        let (texels, w, h) = load_png(&format!("{root}/demo/data/normal_maps/{file}"));
        let nm = NormalMap::new(
            Texels::Unorm8(&texels),
            w,
            h,
            NormalFormat::new(3, Convention::OpenGl).with_tolerance(f64::INFINITY),
        )
        .unwrap_or_else(|e| panic!("{file}: {e}"));
        maps.push(Map::from_source(name, &nm));
    }
    let mut doc = String::new();
    let _ = writeln!(
        doc,
        "Base lobe GGX `alpha = {alpha}` on every texel; levels by the exact-footprint kernel \
         (power-of-two maps: the GPU box is the same kernel). Mean over the sampled texels of \
         each level; best per row in bold. `spread` is `sqrt(lambda_1 + lambda_2)`, the RMS \
         slope deviation of the footprint's normals about the fitted centre.\n"
    );
    let (mut worst_mass, mut worst_refine) = (0.0f64, 0.0f64);
    for map in &maps {
        let (rows, wm, wr) = study(map, alpha, 7, budget);
        worst_mass = worst_mass.max(wm);
        worst_refine = worst_refine.max(wr);
        let _ = writeln!(doc, "#### {}: D error (total variation)\n", map.name);
        table(&mut doc, &rows, false);
        let _ = writeln!(
            doc,
            "\n#### {}: highlight error (view at 60 degrees)\n",
            map.name
        );
        table(&mut doc, &rows, true);
        let _ = writeln!(doc);
    }
    let _ = writeln!(
        doc,
        "Quadrature: worst `|integral P22_true - 1|` over all sampled texels {worst_mass:.1e}; \
         worst change of a total variation on a grid twice as fine (two texels per level, levels 1 to 3) \
         {worst_refine:.1e}.\n"
    );
    let _ = writeln!(doc, "#### Mip kernels on a 203 x 141 map (sinusoids)\n");
    kernels_on_odd_sizes(&mut doc);
    if write {
        let path = format!("{root}/docs/bake.md");
        let text = std::fs::read_to_string(&path).expect("docs/bake.md");
        let (a, b) = (
            "<!-- bake_accuracy: begin -->",
            "<!-- bake_accuracy: end -->",
        );
        let (i, j) = (
            text.find(a).expect("begin marker"),
            text.find(b).expect("end marker"),
        );
        let new = format!("{}{a}\n{doc}{}", &text[..i], &text[j..]);
        std::fs::write(&path, new).expect("write docs/bake.md");
        eprintln!("wrote {path}");
    } else {
        print!("{doc}");
    }
}
