//! Where the false glints come from (issue 21): on the still frame, each candidate cause is
//! measured with a figure, for KHPL16's Beckmann kernel and the exact Gaussian filter of GGX
//! on the ray-differential footprint route, then for the fix (the windowed-moments route).
//!
//! - **the first-order footprint across several wave crests**: the kernel of the first-order
//!   footprint against the covariance of the normal's slope over the pixel's Gaussian window
//!   (the waves' exact windowed moments);
//! - **the Gaussian kernel's infinite tails**: how far out in the kernel (its Mahalanobis
//!   distance) the slope that lights each false glint lies, and the frame with the kernel
//!   truncated at 2 sigma;
//! - **missing clamps**: the same kernel under smaller maximum extents `lambda` and TK19's
//!   `kappa`;
//! - **the reference's Gaussian pixel filter**: the counts against a box-filtered reference.

use crate::camera::Camera;
use crate::image_out::{Image, Rgb8, contact_sheet, draw_text, luminance, tonemap};
use crate::methods::{Family, Method, SIGMA_PIXEL};
use crate::metrics::{BRIGHT, DARK, display_luminance, glint_counts, glint_masks};
use crate::options::Options;
use crate::render::{self, FootprintRoute, GBuffer, PixelDerivatives, Reference};
use crate::scene::Scene;
use crate::{plot, residual};
use filtered_ndf::f32::footprint::slope::slope_from_sphere;
use filtered_ndf::f32::kernel::Covariance;
use filtered_ndf::f32::{Beckmann, ClampRules, ExtentFloor, Isotropic, Ndf};
use glam::Vec2;
use image::Rgb;
use std::fmt::Write as _;

/// The frame in grey with the false glints in red and the lost highlights in blue, labelled.
pub fn glint_map(img: &Image, reference: &Image, exposure: f32) -> Rgb8 {
    let (f, l) = glint_masks(
        &display_luminance(img, exposure),
        &display_luminance(reference, exposure),
    );
    Rgb8::from_fn(img.width as u32, img.height as u32, |x, y| {
        let i = y as usize * img.width + x as usize;
        if f[i] {
            Rgb([255, 30, 30])
        } else if l[i] {
            Rgb([40, 120, 255])
        } else {
            let g = (luminance(tonemap(img.data[i], exposure)) * 140.0) as u8;
            Rgb([g, g, g])
        }
    })
}

/// KHPL16's Beckmann kernel under `rules` at every pixel (`A + 2 Sigma`), its lobe evaluated
/// at `mean_shift * h`; with `truncate`, the kernel is cut at that many standard deviations
/// and renormalised (see [`truncated_fraction`]).
fn beckmann_with(
    scene: &Scene,
    gb: &GBuffer,
    derivs: &[PixelDerivatives],
    rules: ClampRules,
    truncate: Option<f32>,
) -> Image {
    render::shade_with(scene, gb, Family::Beckmann, |i, h, alpha| {
        let dv = derivs[i];
        if dv.support_gap > render::SUPPORT_GAP_ALPHAS {
            return 0.0;
        }
        let h = dv.mean_shift * h;
        let r = Isotropic::new_clamped(alpha);
        let d = Beckmann::new(rules.filter_gaussian(r, dv.footprint, SIGMA_PIXEL)).d(h);
        match truncate {
            None => d,
            Some(radius) => {
                let k = rules.kernel(rules.footprint(dv.footprint).covariance(SIGMA_PIXEL));
                d * truncated_fraction(k, alpha, slope_from_sphere(h), radius)
            }
        }
    })
    .total
}

/// Of the false glints `mask`, those with a reference highlight (display luminance >
/// [`BRIGHT`]) among their 8 neighbours: a highlight moved by one pixel, not one made up.
fn displaced(mask: &[bool], ref_y: &[f32], w: usize, h: usize) -> Vec<bool> {
    (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as i64, (i / w) as i64);
            mask[i]
                && (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        let (nx, ny) = (x + dx, y + dy);
                        (dx, dy) != (0, 0)
                            && (0..w as i64).contains(&nx)
                            && (0..h as i64).contains(&ny)
                            && ref_y[ny as usize * w + nx as usize] > BRIGHT
                    })
                })
        })
        .collect()
}

/// The glint map with the false glints next to a reference highlight in orange, the others
/// in red.
fn displacement_map(img: &Image, reference: &Image, exposure: f32) -> (Rgb8, usize, usize) {
    let ref_y = display_luminance(reference, exposure);
    let (f, l) = glint_masks(&display_luminance(img, exposure), &ref_y);
    let d = displaced(&f, &ref_y, img.width, img.height);
    let n_d = d.iter().filter(|&&b| b).count();
    let n_f = f.iter().filter(|&&b| b).count();
    let map = Rgb8::from_fn(img.width as u32, img.height as u32, |x, y| {
        let i = y as usize * img.width + x as usize;
        if d[i] {
            Rgb([255, 170, 0])
        } else if f[i] {
            Rgb([255, 30, 30])
        } else if l[i] {
            Rgb([40, 120, 255])
        } else {
            let g = (luminance(tonemap(img.data[i], exposure)) * 140.0) as u8;
            Rgb([g, g, g])
        }
    });
    (map, n_f - n_d, n_d)
}

/// The lobe of `family` replaced, on the water, by the average of the unfiltered lobe over
/// the pixel's Gaussian window on the tangent plane (the surface's exact normal distribution
/// there, the pixel centre's half vector; [`residual::oracle_density`], `n` points);
/// elsewhere `family`'s filter (KHPL16's Beckmann kernel, the exact Gaussian filter of GGX)
/// on the `derivs` route.
fn window_exact(
    scene: &Scene,
    gb: &GBuffer,
    derivs: &[PixelDerivatives],
    family: Family,
    n: usize,
) -> Image {
    let method = match family {
        Family::Beckmann => Method::BeckmannParallelogram,
        Family::Ggx => Method::ExactGaussianGgx,
    };
    let filtered = render::shade_frame(scene, gb, derivs, method).total;
    let exact = render::shade_with(scene, gb, family, |i, _, alpha| {
        residual::oracle_density(scene, gb, i, family, alpha, n).unwrap_or(0.0)
    })
    .total;
    let on_water = |i: usize| {
        gb.pixels[i]
            .as_ref()
            .is_some_and(|(s, _)| s.hit.object == 0)
    };
    Image::new(
        gb.width,
        gb.height,
        (0..gb.width * gb.height)
            .map(|i| {
                if on_water(i) {
                    exact.data[i]
                } else {
                    filtered.data[i]
                }
            })
            .collect(),
    )
}

/// Sub-pixel rays per pixel of the converged reference in [`remaining`].
const CHAIN_SAMPLES: usize = 16384;

/// The false glints that remain (of the Beckmann oracle, the GGX oracle and the exact
/// Gaussian filter of GGX on the windowed-moments route `moments`), each down
/// [`residual::chain`]: a markdown table per pixel and the candidate table's rows.
fn remaining(
    o: &Options,
    scene: &Scene,
    cam: &Camera,
    gb: &GBuffer,
    reference: &Reference,
    moments: &[PixelDerivatives],
    oracle_beckmann: &Image,
) -> (String, Vec<String>) {
    let ggx = render::shade_frame(scene, gb, moments, Method::ExactGaussianGgx).total;
    let oracle_ggx = window_exact(scene, gb, moments, Family::Ggx, 256);
    let cases = [
        (
            "Beckmann oracle (256 points)",
            Family::Beckmann,
            oracle_beckmann,
        ),
        ("GGX oracle (256 points)", Family::Ggx, &oracle_ggx),
        ("Exact Gaussian GGX + moments", Family::Ggx, &ggx),
    ];
    let mut md = String::new();
    let mut rows = Vec::new();
    writeln!(
        md,
        "\n### What remains: each false glint from the method to a converged reference\n"
    )
    .unwrap();
    writeln!(md, "Display luminance at each false glint (> {BRIGHT} in the frame, < {DARK} in the 512-spp reference), down the chain of `residual.rs`: the frame; the oracle (the unfiltered lobe averaged over 4096 points of the pixel's Gaussian window on the tangent plane, the pixel centre's half vector, roughness and shading terms); the same lobe over {CHAIN_SAMPLES} of the reference's own sub-pixel rays (true intersections); with each ray's half vector; with each ray's roughness; the reference at {CHAIN_SAMPLES} spp (each ray's Fresnel, Smith term, cosines; in brackets at -2 and +2 standard errors of its mean radiance); the demonstration's 512-spp reference.\n").unwrap();
    writeln!(md, "| frame | pixel | frame | oracle 4096 | reference rays | + own half vector | + own roughness | reference {CHAIN_SAMPLES} spp (+-2 SE) | reference 512 spp |").unwrap();
    writeln!(md, "|---|---|---:|---:|---:|---:|---:|---:|---:|").unwrap();
    for (name, family, img) in cases {
        let ref_img = reference.full(family);
        let ry = display_luminance(ref_img, o.exposure);
        let (mask, _) = glint_masks(&display_luminance(img, o.exposure), &ry);
        let pixels: Vec<usize> = (0..gb.width * gb.height).filter(|&i| mask[i]).collect();
        let chains: Vec<residual::Chain> = pixels
            .iter()
            .filter_map(|&i| {
                residual::chain(
                    scene,
                    cam,
                    gb,
                    (i % gb.width, i / gb.width),
                    family,
                    (img.data[i], ref_img.data[i]),
                    CHAIN_SAMPLES,
                    o.exposure,
                )
            })
            .collect();
        for c in &chains {
            writeln!(
                md,
                "| {name} | ({}, {}) | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} ({:.2}-{:.2}) | {:.2} |",
                c.x, c.y, c.method, c.oracle, c.rays, c.own_h, c.own_alpha, c.reference,
                c.reference_2se.0, c.reference_2se.1, c.reference_demo
            )
            .unwrap();
        }
        let n = |f: &dyn Fn(&residual::Chain) -> f32| {
            chains
                .iter()
                .filter(|c| c.method > BRIGHT && f(c) < DARK)
                .count()
        };
        rows.push(format!(
            "| 8. what remains | {name}: false glints against the 512-spp reference / of those, still false against a {CHAIN_SAMPLES}-spp reference; still dark (< {DARK}) at the steps oracle 4096 / reference rays / + own half vector / + own roughness | {} / {}; {} / {} / {} / {} | - |",
            pixels.len(),
            n(&|c| c.reference),
            n(&|c| c.oracle),
            n(&|c| c.rays),
            n(&|c| c.own_h),
            n(&|c| c.own_alpha),
        ));
    }
    (md, rows)
}

/// The kernel `N(0, k)` cut at `radius` standard deviations (`|L^-1 t| <= radius`, `k = L
/// L^T`) and renormalised, convolved with the Beckmann lobe `N(0, alpha^2 / 2 I)` at slope
/// `s`, over the untruncated convolution: the probability that `u ~ N(mu, S)`, the posterior
/// of the whitened kernel offset given `s`, lies in the disk, over the disk's mass under
/// `N(0, I)` (`1 - exp(-radius^2 / 2)`). The probability by an 8 x 8 Gauss-Hermite grid.
pub fn truncated_fraction(k: Covariance, alpha: f32, s: Vec2, radius: f32) -> f32 {
    let (l1, l2) = k.eigenvalues();
    if l1.max(l2) <= 1e-12 {
        return 1.0;
    }
    // Whiten in k's eigenbasis: t = E diag(sqrt(l)) u.
    let fp = render::footprint_of(k, 1.0);
    let (e1, e2) = (fp.dh_u, fp.dh_v); // columns of L (eigenvectors times sqrt(l))
    let a2 = 0.5 * alpha * alpha;
    // Posterior of u: precision P = I + L^T L / a2, mean P^-1 L^T s / a2.
    let m = glam::Mat2::from_cols(e1, e2);
    let p = glam::Mat2::IDENTITY + m.transpose() * m / a2;
    let cov = p.inverse();
    let mu = cov * (m.transpose() * s) / a2;
    // Cholesky of cov.
    let c11 = cov.x_axis.x.max(0.0).sqrt();
    let c21 = if c11 > 0.0 { cov.x_axis.y / c11 } else { 0.0 };
    let c22 = (cov.y_axis.y - c21 * c21).max(0.0).sqrt();
    // Gauss-Hermite nodes and weights (8 points; the positive half), printed to f64.
    const X: [f64; 4] = [0.381_186_99, 1.157_193_7, 1.981_656_8, 2.930_637_4];
    const W: [f64; 4] = [0.661_147_0, 0.207_802_3, 0.017_077_98, 0.000_199_604_1];
    let (x, wt) = (X.map(|v| v as f32), W.map(|v| v as f32));
    let (mut inside, mut total) = (0.0, 0.0);
    for (i, &xi) in x.iter().chain(x.iter()).enumerate() {
        let zi = if i < 4 { xi } else { -xi } * std::f32::consts::SQRT_2;
        let wi = wt[i % 4];
        for (j, &xj) in x.iter().chain(x.iter()).enumerate() {
            let zj = if j < 4 { xj } else { -xj } * std::f32::consts::SQRT_2;
            let w = wi * wt[j % 4];
            let u = mu + Vec2::new(c11 * zi, c21 * zi + c22 * zj);
            total += w;
            if u.length() <= radius {
                inside += w;
            }
        }
    }
    (inside / total) / (1.0 - (-0.5 * radius * radius).exp())
}

/// The kernel's Mahalanobis distance of the slope `s`: how many standard deviations of the
/// kernel separate the pixel centre's lobe from the slope that lights the pixel.
fn mahalanobis(k: Covariance, s: Vec2) -> f32 {
    let det = k.det().max(1e-20);
    let inv = Covariance::new(k.s22 / det, -k.s12 / det, k.s11 / det);
    (s.x * s.x * inv.s11 + 2.0 * s.x * s.y * inv.s12 + s.y * s.y * inv.s22)
        .max(0.0)
        .sqrt()
}

/// Quantiles (0.1, 0.5, 0.9) of `v` (NaN if empty).
fn quantiles(mut v: Vec<f32>) -> [f32; 3] {
    if v.is_empty() {
        return [f32::NAN; 3];
    }
    v.sort_by(f32::total_cmp);
    [0.1, 0.5, 0.9].map(|q| v[((v.len() - 1) as f32 * q).round() as usize])
}

/// A labelled tile.
fn tile(label: impl Into<String>, img: Rgb8) -> (String, Rgb8) {
    (label.into(), img)
}

/// The investigation: figures in `o.out` (`glints-*.png`) and a markdown section.
pub fn investigate(
    o: &Options,
    scene: &Scene,
    cam: &Camera,
    gb: &GBuffer,
    reference: &Reference,
) -> std::io::Result<String> {
    let mut md = String::new();
    let (w, h) = (gb.width, gb.height);
    let rays = gb.derivatives(scene, FootprintRoute::RayDifferentials);
    let moments = gb.derivatives(scene, FootprintRoute::Moments);
    let ref_b = reference.full(Family::Beckmann);
    let ref_y = display_luminance(ref_b, o.exposure);
    let khpl = ClampRules::KHPL16;
    let before = beckmann_with(scene, gb, &rays, khpl, None);
    // The windowed moments with the support clamp (experiment 7), and without (the fix).
    let clamped = beckmann_with(scene, gb, &moments, khpl, None);
    let moments_ns: Vec<PixelDerivatives> = moments
        .iter()
        .map(|d| PixelDerivatives {
            support_gap: 0.0,
            ..*d
        })
        .collect();
    let after = beckmann_with(scene, gb, &moments_ns, khpl, None);
    let after_ns = &after;
    let counts = |img: &Image| glint_counts(&display_luminance(img, o.exposure), &ref_y);
    let (f_before, mask_before) = {
        let y = display_luminance(&before, o.exposure);
        (glint_counts(&y, &ref_y), glint_masks(&y, &ref_y).0)
    };
    writeln!(
        md,
        "\n## Where the false glints come from (KHPL16 Beckmann A+2S, still frame, {w}x{h})\n"
    )
    .unwrap();
    writeln!(md, "A false glint: display luminance > {BRIGHT} in the frame where the reference's is < {DARK}; a lost highlight: the reverse. Counts as (false glints, lost highlights). Ray-differential footprints (KHPL16's first-order route) unless stated.\n").unwrap();
    writeln!(
        md,
        "| candidate | experiment | false glints | lost highlights |"
    )
    .unwrap();
    writeln!(md, "|---|---|---:|---:|").unwrap();
    // Rows, sorted by candidate before they are written (stable: experiments in order).
    let mut rows: Vec<String> = Vec::new();
    let mut row = |cand: &str, exp: &str, c: (usize, usize)| {
        rows.push(format!("| {cand} | {exp} | {} | {} |", c.0, c.1));
    };
    row(
        "-",
        "unfiltered",
        counts(&render::shade(
            scene,
            gb,
            &rays,
            Method::Unfiltered(Family::Beckmann),
        )),
    );
    row("-", "KHPL16 A+2S, first-order footprint (before)", f_before);

    // Candidate 1: the first-order footprint against the windowed moments.
    let ratio: Vec<Option<f32>> = (0..w * h)
        .map(|i| {
            let on_water = gb.pixels[i]
                .as_ref()
                .is_some_and(|(s, _)| s.hit.object == 0);
            on_water.then(|| {
                let a = rays[i].footprint.covariance(SIGMA_PIXEL).trace();
                let b = moments[i].footprint.covariance(SIGMA_PIXEL).trace();
                (a / b.max(1e-12)).max(1e-6)
            })
        })
        .collect();
    let at_glints: Vec<f32> = (0..w * h)
        .filter(|&i| mask_before[i])
        .filter_map(|i| ratio[i])
        .collect();
    let all_water: Vec<f32> = ratio.iter().flatten().copied().collect();
    let (qg, qa) = (quantiles(at_glints.clone()), quantiles(all_water));
    row(
        "1. first-order footprint across crests",
        "kernel = windowed slope moments (the fix's kernel), centred on the pixel centre",
        counts(&beckmann_with(
            scene,
            gb,
            &moments_ns
                .iter()
                .map(|d| PixelDerivatives {
                    mean_shift: glam::Quat::IDENTITY,
                    ..*d
                })
                .collect::<Vec<_>>(),
            khpl,
            None,
        )),
    );
    row(
        "1. first-order footprint across crests",
        "kernel and centre from the windowed moments",
        counts(after_ns),
    );
    let ratio_map = Rgb8::from_fn(w as u32, h as u32, |x, y| {
        let i = y as usize * w + x as usize;
        if mask_before[i] {
            return Rgb([255, 30, 30]);
        }
        match ratio[i] {
            None => Rgb([20, 20, 20]),
            Some(r) => {
                // log2 ratio in [-2, 6] -> blue..white..orange.
                let t = ((r.log2() + 2.0) / 8.0).clamp(0.0, 1.0);
                let c = |a: f32, b: f32| (a + (b - a) * t) as u8;
                Rgb([c(30.0, 255.0), c(60.0, 190.0), c(200.0, 60.0)])
            }
        }
    });

    // Candidate 2: the Gaussian tails.
    let kernels: Vec<Covariance> = rays
        .iter()
        .map(|d| khpl.kernel(khpl.footprint(d.footprint).covariance(SIGMA_PIXEL)))
        .collect();
    let dist: Vec<f32> = (0..w * h)
        .filter(|&i| mask_before[i])
        .filter_map(|i| {
            let (s, _) = gb.pixels[i].as_ref()?;
            let hl = s.frame.transpose() * s.h;
            Some(mahalanobis(kernels[i], slope_from_sphere(hl)))
        })
        .collect();
    let beyond2 = dist.iter().filter(|&&d| d > 2.0).count();
    let qd = quantiles(dist.clone());
    let truncated = beckmann_with(scene, gb, &rays, khpl, Some(2.0));
    row(
        "2. Gaussian tails",
        "first-order kernel cut at 2 sigma",
        counts(&truncated),
    );

    // The same two candidates on the windowed-moments route (what remains after the fix).
    let (mask_after, _) = glint_masks(&display_luminance(after_ns, o.exposure), &ref_y);
    let moment_kernels: Vec<Covariance> = moments
        .iter()
        .map(|d| khpl.kernel(khpl.footprint(d.footprint).covariance(SIGMA_PIXEL)))
        .collect();
    let dist_after: Vec<f32> = (0..w * h)
        .filter(|&i| mask_after[i])
        .filter_map(|i| {
            let (s, _) = gb.pixels[i].as_ref()?;
            let hl = moments[i].mean_shift * (s.frame.transpose() * s.h);
            Some(mahalanobis(moment_kernels[i], slope_from_sphere(hl)))
        })
        .collect();
    let qd_after = quantiles(dist_after.clone());
    let clamped_at_glints = (0..w * h)
        .filter(|&i| mask_after[i] && moments[i].support_gap > render::SUPPORT_GAP_ALPHAS)
        .count();
    let water: Vec<usize> = (0..w * h)
        .filter(|&i| {
            gb.pixels[i]
                .as_ref()
                .is_some_and(|(s, _)| s.hit.object == 0)
        })
        .collect();
    let clamped_water = water
        .iter()
        .filter(|&&i| moments[i].support_gap > render::SUPPORT_GAP_ALPHAS)
        .count();
    let beyond2_after = dist_after.iter().filter(|&&d| d > 2.0).count();
    let truncated_after = beckmann_with(scene, gb, &moments_ns, khpl, Some(2.0));
    row(
        "2. Gaussian tails",
        "windowed-moments kernel cut at 2 sigma",
        counts(&truncated_after),
    );
    for lambda in [0.25f32, 0.06] {
        let rules = ClampRules {
            max_extent: lambda,
            ..khpl
        };
        row(
            "3. clamps",
            &format!("windowed moments, maximum extent lambda = {lambda}"),
            counts(&beckmann_with(scene, gb, &moments_ns, rules, None)),
        );
    }

    // Candidate 6: the Gaussian shape itself. The exact distribution of the normal over the
    // pixel's Gaussian window on the tangent plane (no Gaussian fit): the unfiltered lobe
    // averaged over 256 points of the window (a rank-1 lattice through Box-Muller), the
    // pixel centre's half vector; spheres as the windowed-moments route.
    let window = window_exact(scene, gb, &moments_ns, Family::Beckmann, 256);
    row(
        "6. the Gaussian shape of the kernel",
        "the window's exact normal distribution (256 points on the tangent plane), no Gaussian",
        counts(&window),
    );

    // What remains: each remaining false glint down the chain from the method to a converged
    // reference (residual.rs), for the oracle and the exact Gaussian filter of GGX.
    let (remaining_md, remaining_rows) =
        remaining(o, scene, cam, gb, reference, &moments_ns, &window);
    // The fix of the Gaussian shape: sub-windows, each with its own windowed moments and
    // half vector (render::FootprintRoute::SubWindows), KHPL16 Beckmann and the exact
    // Gaussian filter of GGX, against the 512-spp reference of their NDF.
    let mut sub_rows = Vec::new();
    for (grid, spread, traced) in [
        (3, 0.75f32, false),
        (4, 0.9, false),
        (2, 0.75, true),
        (3, 0.9, true),
        (4, 0.9, true),
        (4, 1.0, true),
    ] {
        let mix: Vec<render::Mixture> = crate::parallel::rows(h, None, |y| {
            (0..w)
                .map(|x| gb.subwindow_mixture_with(scene, (x, y), (grid, spread), traced))
                .collect()
        });
        for (method, fam) in [
            (Method::BeckmannParallelogram, Family::Beckmann),
            (Method::ExactGaussianGgx, Family::Ggx),
        ] {
            let f = render::shade_mixture(scene, gb, &mix, method);
            let (sc, _) = crate::metrics::score(
                (&f.total, &f.specular),
                (reference.full(fam), reference.specular(fam)),
                o.exposure,
            );
            let centres = if traced {
                "traced centres"
            } else {
                "centres on the tangent plane"
            };
            let what = if spread >= 1.0 {
                format!(
                    "control, no filtering: {} traced sub-pixel rays, the unfiltered lobe at each",
                    grid * grid
                )
            } else {
                format!(
                    "{grid}x{grid} sub-windows, {centres}, offsets' share of the window b = {spread}"
                )
            };
            sub_rows.push(format!(
                "| 9. sub-windows (the fix) | {}: {what}; FLIP {:.4} / {:.4}, specular error {:.4} | {} | {} |",
                method.label(), sc.flip_ldr, sc.flip_hdr, sc.specular, sc.false_glints, sc.lost_highlights
            ));
        }
    }

    // Candidate 6, a method: the window's most varying wave integrated over its phase.
    let mixtures: Vec<Vec<(f32, PixelDerivatives)>> = crate::parallel::rows(h, None, |y| {
        (0..w)
            .map(|x| gb.mixture_derivatives(scene, x, y))
            .collect()
    })
    .into_iter()
    .collect();
    let mixture = render::shade_with(scene, gb, Family::Beckmann, |i, hl, alpha| {
        let r = Isotropic::new_clamped(alpha);
        let lobe = |dv: &PixelDerivatives| {
            Beckmann::new(khpl.filter_gaussian(r, dv.footprint, SIGMA_PIXEL)).d(dv.mean_shift * hl)
        };
        if mixtures[i].is_empty() {
            return lobe(&moments_ns[i]);
        }
        mixtures[i].iter().map(|(wt, dv)| wt * lobe(dv)).sum()
    })
    .total;
    row(
        "6. the Gaussian shape of the kernel",
        "a mixture: the window's most varying wave over its phase (8-point Gauss-Hermite), the others by their windowed moments",
        counts(&mixture),
    );

    // A missing clamp: the kernel's support.
    row(
        "7. a support clamp (a missing clamp)",
        &format!(
            "windowed moments, 0 where no gradient within {} sigma of the window comes within {} alpha of reflecting (the parallax subtracted)",
            render::SUPPORT_SIGMAS,
            render::SUPPORT_GAP_ALPHAS
        ),
        counts(&clamped),
    );

    // Candidate 3: clamps.
    let mut clamp_series = [Vec::new(), Vec::new()];
    let lambdas = [1.0f32, 0.5, 0.25, 0.12, 0.06];
    for &lambda in &lambdas {
        let rules = ClampRules {
            max_extent: lambda,
            ..khpl
        };
        let c = counts(&beckmann_with(scene, gb, &rays, rules, None));
        clamp_series[0].push(c.0 as f32);
        clamp_series[1].push(c.1 as f32);
        row("3. clamps", &format!("maximum extent lambda = {lambda}"), c);
    }
    let tk19 = ClampRules {
        floor: ExtentFloor::None,
        ..ClampRules::DEFAULT
    };
    row(
        "3. clamps",
        "TK19's kappa = 0.18 and lambda = 1",
        counts(&beckmann_with(scene, gb, &rays, tk19, None)),
    );

    // Candidate 4: the reference's pixel filter (both references at a quarter of the
    // samples, so that they differ by the filter only).
    let spp = (o.spp / 4).max(2);
    let gauss = render::reference(scene, cam, w, h, spp, o.seed, None);
    let boxed = render::reference_with(scene, cam, (w, h), spp, o.seed, None, 0.0);
    let vs = |r: &Image| {
        glint_counts(
            &display_luminance(&before, o.exposure),
            &display_luminance(r, o.exposure),
        )
    };
    let (c_gauss, c_box) = (
        vs(gauss.full(Family::Beckmann)),
        vs(boxed.full(Family::Beckmann)),
    );
    row(
        "4. the reference's pixel filter",
        &format!("against a Gaussian-filtered reference, {spp} spp"),
        c_gauss,
    );
    row(
        "4. the reference's pixel filter",
        &format!("against a box-filtered reference, {spp} spp"),
        c_box,
    );

    // Candidate 5: a highlight moved by a pixel (false glint and lost highlight side by side).
    let (disp_before, iso_b, adj_b) = displacement_map(&before, ref_b, o.exposure);
    let (disp_after, iso_a, adj_a) = displacement_map(after_ns, ref_b, o.exposure);
    rows.push(format!("| 5. a highlight moved by one pixel | first-order footprint: false glints next to a reference highlight / isolated | {adj_b} / {iso_b} | - |"));
    rows.push(format!("| 5. a highlight moved by one pixel | windowed moments: false glints next to a reference highlight / isolated | {adj_a} / {iso_a} | - |"));
    rows.extend(remaining_rows);
    rows.extend(sub_rows);
    rows.sort_by_key(|r| {
        r.chars()
            .nth(2)
            .filter(|c| c.is_ascii_digit())
            .map_or(0, |c| c as u32)
    });
    for r in &rows {
        writeln!(md, "{r}").unwrap();
    }

    writeln!(md, "\n1. **First-order footprint.** On the water, the first-order kernel's trace over the windowed moments' (the covariance of the normal's slope over the pixel's Gaussian window, exact for the sum of sines): median {:.2} over all water pixels (10-90 %: {:.2}-{:.2}), median {:.2} at the false glints (10-90 %: {:.2}-{:.2}). Figure `glints-footprint.png`: log2 of that ratio from -2 (blue) to 6 (orange), false glints in red.", qa[1], qa[0], qa[2], qg[1], qg[0], qg[2]).unwrap();
    writeln!(md, "2. **Gaussian tails.** The slope that lights each false glint lies at a Mahalanobis distance of the first-order kernel of median {:.2} (10-90 %: {:.2}-{:.2}); {} of {} false glints lie beyond 2 sigma; on the windowed moments, median {:.2} (10-90 %: {:.2}-{:.2}), {} of {} beyond 2 sigma. Figure `glints-tails.png`: the frames with the kernel cut at 2 sigma, both routes.", qd[1], qd[0], qd[2], beyond2, dist.len(), qd_after[1], qd_after[0], qd_after[2], beyond2_after, dist_after.len()).unwrap();
    writeln!(md, "3. **Clamps.** Figure `glints-clamps.png`: false glints and lost highlights against the maximum extent lambda (index: lambda = {lambdas:?}).").unwrap();
    writeln!(md, "4. **The reference's pixel filter.** Figure `glints-reference.png`: the Gaussian- and the box-filtered references and the false glints against each.").unwrap();
    writeln!(md, "5. **A highlight moved by one pixel.** A false glint with a reference highlight (display > {BRIGHT}) among its 8 neighbours is the same highlight one pixel off (FLIP scores it; the counts score it twice, once false and once lost). Figure `glints-displaced.png`: those in orange, isolated false glints in red, lost highlights in blue, first-order and windowed moments.").unwrap();
    writeln!(md, "6. **The Gaussian shape.** With the window's exact normals instead of any Gaussian (an oracle: 256 normal evaluations per pixel, not a method), the false glints of the windowed-moments route fall from {} to {}: what remains is the Gaussian fit of a slope distribution that, where the window spans about one short wave (the near glitter path), is bounded and far from Gaussian.", counts(after_ns).0, counts(&window).0).unwrap();
    writeln!(md, "7. **A support clamp.** The gradients within {} sigma of the window lie in a zonotope (each wave's gradient on a segment, the exact range of its cosine over the window's phases; `Scene::gradient_gap`, tested against 4000 points of a window); 0 where the reflecting gradient lies more than {} alpha outside it, the parallax subtracted: {} of {} water pixels are clamped, {} of the {} false glints of the windowed-moments route, so the bound (independent phases) is too loose where it matters.", render::SUPPORT_SIGMAS, render::SUPPORT_GAP_ALPHAS, clamped_water, water.len(), clamped_at_glints, mask_after.iter().filter(|&&b| b).count()).unwrap();

    writeln!(md, "8. **What remains, pixel by pixel.** The table below follows each remaining false glint from the frame to a converged reference (`residual.rs`); a step that takes the pixel from above {BRIGHT} to below {DARK} is its cause: the oracle at 4096 points (the 256-point oracle's own convergence), the reference's own rays instead of the tangent-plane window (where the sub-pixel rays really meet the waves: occlusion and the heights' parallax at grazing view), each ray's half vector (the parallax of the eye and light), each ray's roughness (the level of detail), each ray's Fresnel, Smith term and cosines (the reference at {CHAIN_SAMPLES} spp, with its standard error), and the 512-spp reference itself (its convergence). Both the window's sigma (0.5 pixel) and its untruncated Gaussian are the same in the moments, the oracle and the reference; the step from the oracle to the reference's rays measures the rest of the window's mismatch.").unwrap();
    writeln!(md, "9. **The fix: sub-windows.** The pixel's Gaussian window `N(p, C)` is the mixture over offsets `m ~ N(0, b C)` of the windows `N(p + m, (1 - b) C)`: a Gauss-Hermite grid of offsets, each sub-window with its own closed-form windowed moments and half vector, bounds the slope distribution the way the oracle does; traced centres (the sub-pixel ray through each offset meets the water) also take the window off the tangent plane. The control (b = 1) is plain supersampling with the same rays and the unfiltered lobe.").unwrap();
    md.push_str(&remaining_md);

    // Figures.
    let ex = o.exposure;
    let save = |name: &str, img: &Rgb8| crate::image_out::save(img, &o.out.join(name));
    let zoom = if w <= 320 { 2 } else { 1 };
    save(
        "glints-before-after.png",
        &contact_sheet(
            &[
                tile("Reference Beckmann", ref_b.to_rgb8(ex)),
                tile("KHPL16 first-order (before)", before.to_rgb8(ex)),
                tile("KHPL16 windowed moments (after)", after.to_rgb8(ex)),
                tile(
                    "Unfiltered: false red, lost blue",
                    glint_map(
                        &render::shade(scene, gb, &rays, Method::Unfiltered(Family::Beckmann)),
                        ref_b,
                        ex,
                    ),
                ),
                tile(
                    format!("Before: {} false, {} lost", f_before.0, f_before.1),
                    glint_map(&before, ref_b, ex),
                ),
                tile(
                    {
                        let c = counts(&after);
                        format!("After: {} false, {} lost", c.0, c.1)
                    },
                    glint_map(&after, ref_b, ex),
                ),
            ],
            3,
            zoom,
        ),
    )?;
    save(
        "glints-footprint.png",
        &contact_sheet(
            &[
                tile("first-order / windowed kernel (log2)", ratio_map),
                tile("false glints (before)", glint_map(&before, ref_b, ex)),
            ],
            2,
            zoom,
        ),
    )?;
    save(
        "glints-tails.png",
        &contact_sheet(
            &[
                tile("first-order Gaussian kernel", glint_map(&before, ref_b, ex)),
                tile(
                    "first-order, cut at 2 sigma",
                    glint_map(&truncated, ref_b, ex),
                ),
                tile("windowed moments", glint_map(after_ns, ref_b, ex)),
                tile(
                    "windowed moments, cut at 2 sigma",
                    glint_map(&truncated_after, ref_b, ex),
                ),
                tile("the window's exact normals", glint_map(&window, ref_b, ex)),
            ],
            2,
            zoom,
        ),
    )?;
    let series = [
        plot::Series {
            label: "false glints".into(),
            color: [220, 40, 40],
            values: clamp_series[0].clone(),
            dashed: false,
        },
        plot::Series {
            label: "lost highlights".into(),
            color: [40, 100, 220],
            values: clamp_series[1].clone(),
            dashed: false,
        },
    ];
    let mut p = plot::line_plot(
        "KHPL16 Beckmann: counts against the maximum extent lambda",
        "pixels",
        &series,
        720,
        360,
    );
    let label = format!("x: lambda index, lambda = {lambdas:?}");
    draw_text(&mut p, &label, 80.0, 340.0, 13.0, [0, 0, 0]);
    save("glints-clamps.png", &p)?;
    save(
        "glints-reference.png",
        &contact_sheet(
            &[
                tile(
                    "Gaussian pixel filter reference",
                    gauss.full(Family::Beckmann).to_rgb8(ex),
                ),
                tile(
                    "box pixel filter reference",
                    boxed.full(Family::Beckmann).to_rgb8(ex),
                ),
                tile(
                    format!("vs Gaussian: {} false, {} lost", c_gauss.0, c_gauss.1),
                    glint_map(&before, gauss.full(Family::Beckmann), ex),
                ),
                tile(
                    format!("vs box: {} false, {} lost", c_box.0, c_box.1),
                    glint_map(&before, boxed.full(Family::Beckmann), ex),
                ),
            ],
            2,
            zoom,
        ),
    )?;
    save(
        "glints-displaced.png",
        &contact_sheet(
            &[
                tile(
                    format!("first-order: {adj_b} moved, {iso_b} isolated"),
                    disp_before,
                ),
                tile(
                    format!("windowed moments: {adj_a} moved, {iso_a} isolated"),
                    disp_after,
                ),
            ],
            2,
            zoom,
        ),
    )?;
    Ok(md)
}

#[cfg(test)]
mod tests {
    use crate::camera::camera_at;
    use crate::methods::{Family, Method};
    use crate::metrics::{display_luminance, glint_counts};
    use crate::render::{self, FootprintRoute};
    use crate::scene::Scene;

    /// The false-glint fix, end to end on the still frame (256x160, reference 128 spp with the
    /// Gaussian pixel filter): KHPL16's Beckmann kernel on the windowed-moments route makes
    /// fewer false glints and loses fewer highlights than on the first-order route, and its
    /// specular term is closer to the reference's. Measured: (false glints, lost) (39, 42)
    /// -> (28, 19), specular error 0.0703 -> 0.0585; the assertions keep only the order.
    #[test]
    fn windowed_moments_remove_false_glints() {
        let (w, h) = (256, 160);
        let cam = camera_at(0, w, h);
        let scene = Scene::new(cam.lod());
        let reference = render::reference(&scene, &cam, w, h, 128, 1, None);
        let gb = render::gbuffer(&scene, &cam, w, h);
        let ref_y = display_luminance(reference.full(Family::Beckmann), 1.0);
        let run = |route| {
            let d = gb.derivatives(&scene, route);
            let f = render::shade_frame(&scene, &gb, &d, Method::BeckmannParallelogram);
            let c = glint_counts(&display_luminance(&f.total, 1.0), &ref_y);
            let spec = f
                .specular
                .rmse_display(reference.specular(Family::Beckmann), 1.0);
            (c, spec)
        };
        let (rays, spec_rays) = run(FootprintRoute::RayDifferentials);
        let (moments, spec_moments) = run(FootprintRoute::Moments);
        eprintln!(
            "first order {rays:?} {spec_rays:.4}, windowed moments {moments:?} {spec_moments:.4}"
        );
        assert!(moments.0 < rays.0, "false glints: {moments:?} vs {rays:?}");
        assert!(
            moments.1 <= rays.1,
            "lost highlights: {moments:?} vs {rays:?}"
        );
        assert!(
            spec_moments < spec_rays,
            "specular: {spec_moments} vs {spec_rays}"
        );
    }

    /// The sub-window fix, end to end on the still frame (256x160, reference 128 spp with the
    /// Gaussian pixel filter): for KHPL16's Beckmann kernel and the exact Gaussian filter of
    /// GGX, the `SubWindows` route makes fewer false glints than the `Moments` route (or
    /// none where it makes none), loses no more highlights, and has a lower FLIP and specular
    /// error. The assertions keep only the order. Measured (false glints, lost), FLIP LDR /
    /// HDR, specular error: KHPL16 Beckmann (28, 19), 0.0365 / 0.0683, 0.0585 -> (2, 5),
    /// 0.0260 / 0.0558, 0.0408; exact Gaussian GGX (7, 12), 0.0318 / 0.0649, 0.0455 -> (0, 2),
    /// 0.0252 / 0.0560, 0.0337 (against this 128-spp reference; 0 and 0 against the demo's
    /// 512-spp one).
    #[test]
    fn subwindows_remove_the_remaining_false_glints() {
        let (w, h) = (256, 160);
        let cam = camera_at(0, w, h);
        let scene = Scene::new(cam.lod());
        let reference = render::reference(&scene, &cam, w, h, 128, 1, None);
        let gb = render::gbuffer(&scene, &cam, w, h);
        for (method, family) in [
            (Method::BeckmannParallelogram, Family::Beckmann),
            (Method::ExactGaussianGgx, Family::Ggx),
        ] {
            let run = |route| {
                let mix = gb.mixtures(&scene, route);
                let f = render::shade_mixture(&scene, &gb, &mix, method);
                crate::metrics::score(
                    (&f.total, &f.specular),
                    (reference.full(family), reference.specular(family)),
                    1.0,
                )
                .0
            };
            let (a, b) = (
                run(FootprintRoute::Moments),
                run(FootprintRoute::SubWindows),
            );
            eprintln!("{}: moments {a:?}, sub-windows {b:?}", method.label());
            assert!(
                b.false_glints < a.false_glints || a.false_glints == 0 && b.false_glints == 0,
                "false glints: {} vs {}",
                b.false_glints,
                a.false_glints
            );
            assert!(b.lost_highlights <= a.lost_highlights, "{b:?} vs {a:?}");
            assert!(
                b.flip_ldr < a.flip_ldr && b.flip_hdr < a.flip_hdr,
                "{b:?} vs {a:?}"
            );
            assert!(b.specular < a.specular, "{b:?} vs {a:?}");
        }
    }
}
