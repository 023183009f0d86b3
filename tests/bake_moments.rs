//! The moment chain against closed forms: sums of sinusoids sampled at texel centres, whose
//! weighted sums over any footprint are Dirichlet sums (geometric series of complex
//! exponentials), plus the kernels' weights derived here from their definitions (overlap of
//! the base texel with the mip texel's footprint). Nothing here calls the code under test to
//! build an expected value.

use filtered_ndf::bake::f16::f16_to_f32;
use filtered_ndf::bake::{
    Band, BaseRoughness, ChainLayout, Edges, HeightFormat, HeightMap, Kernel, Settings, SlopeMap,
    SlopeSource, TexelStats, Texels, bake_rows, footprint_row, store_f16, store_f32,
};
use glam::DVec2;

const EPS: f64 = f64::EPSILON / 2.0; // unit roundoff 2^-53

/// One axis of the separable test surface: slope `amp k cos(k (t + 1/2))` at texel `t`.
#[derive(Clone, Copy)]
struct Wave {
    amp: f64,
    k: f64,
}

impl Wave {
    fn slope(&self, t: usize) -> f64 {
        self.amp * self.k * (self.k * (t as f64 + 0.5)).cos()
    }
}

/// `sum_{t=p}^{q-1} cos(k (t + 1/2))` in closed form (Dirichlet kernel):
/// `sin(k (q - p) / 2) cos(k (p + q) / 2) / sin(k / 2)`.
fn dirichlet(k: f64, p: usize, q: usize) -> f64 {
    if q <= p {
        return 0.0;
    }
    (k * (q - p) as f64 / 2.0).sin() * (k * (p + q) as f64 / 2.0).cos() / (k / 2.0).sin()
}

/// Base texels and weights of mip texel `i` at level `k` along an axis of `n` texels, from
/// the kernels' definitions: GpuBox averages the aligned block of `2^min(k, floor(log2 n))`
/// texels; Area weights each base texel by its overlap with `[i n / n_k, (i + 1) n / n_k]`
/// divided by the footprint's length `n / n_k`.
fn axis_weights(kernel: Kernel, n: usize, k: usize, i: usize) -> Vec<(usize, f64)> {
    let nk = (n >> k.min(63)).max(1);
    match kernel {
        Kernel::GpuBox => {
            let halvings = k.min(n.ilog2() as usize);
            let b = 1usize << halvings;
            (i * b..(i + 1) * b).map(|t| (t, 1.0 / b as f64)).collect()
        }
        Kernel::Area => {
            // In units of 1 / n_k of a base texel: footprint [i n, (i + 1) n], texel t is
            // [t n_k, (t + 1) n_k]; overlap / n is the weight.
            let (a, b) = (i * n, (i + 1) * n);
            (0..n)
                .filter_map(|t| {
                    let (t0, t1) = (t * nk, (t + 1) * nk);
                    let o = t1.min(b).saturating_sub(t0.max(a));
                    (o > 0).then_some((t, o as f64 / n as f64))
                })
                .collect()
        }
    }
}

/// The exact footprint means of `wave` along one axis: `(E[s], E[s^2], sum w |s|, sum w s^2,
/// the closed form's absolute error bound)`. The interior texels share one weight `c`; the
/// two end texels' weights differ from it by explicit terms, so the sums are `c` times a
/// Dirichlet sum plus two corrections.
fn axis_closed_form(wave: Wave, weights: &[(usize, f64)]) -> (f64, f64, f64, f64, f64) {
    let (p, q) = (weights[0].0, weights.last().unwrap().0 + 1);
    let c = weights[weights.len() / 2].1;
    let Wave { amp, k } = wave;
    let corr = |f: &dyn Fn(usize) -> f64| -> f64 {
        let mut e = (weights[0].1 - c) * f(p);
        if q - p > 1 {
            e += (weights.last().unwrap().1 - c) * f(q - 1);
        }
        e
    };
    let mean = amp * k * c * dirichlet(k, p, q) + corr(&|t| wave.slope(t));
    // s^2 = (amp k)^2 (1 + cos(2 k (t + 1/2))) / 2
    let a2 = (amp * k) * (amp * k);
    let second = a2 / 2.0 * c * ((q - p) as f64 + dirichlet(2.0 * k, p, q))
        + corr(&|t| wave.slope(t) * wave.slope(t));
    let abs1: f64 = weights.iter().map(|&(t, w)| w * wave.slope(t).abs()).sum();
    let abs2: f64 = weights
        .iter()
        .map(|&(t, w)| w * wave.slope(t).powi(2))
        .sum();
    // The closed form's own rounding: the arguments k (p + q) / 2 reach K = 2 k q, so sin and
    // cos carry an absolute error up to (K + 2) eps each; the quotient by sin(k / 2) and the
    // products add a few eps relative. The Dirichlet sum is bounded by 1 / |sin(k / 2)|.
    let big = 2.0 * k * q as f64 + 8.0;
    let err = EPS * big * c * (amp * k + a2) * (1.0 / (k / 2.0).sin().abs() + (q - p) as f64);
    (mean, second, abs1, abs2, err)
}

fn separable_slopes(w: usize, h: usize, x: Wave, y: Wave) -> Vec<DVec2> {
    (0..h)
        .flat_map(|r| (0..w).map(move |c| DVec2::new(x.slope(c), y.slope(r))))
        .collect()
}

/// Every level, every texel, both kernels: `E[s]` and `E[s s^T]` against the closed forms.
/// Bound: a texel averaging `p` rows of `q` columns sums each value in `p - 1` additions
/// (column sums) then `q - 1` (the row of column sums), after one weight product each: the
/// computed mean is within `(p + q + 2) u sum w |v|` of the exact weighted mean of the
/// stored samples (Higham, recursive summation). The samples themselves carry the rounding
/// of `cos` of arguments up to `k n`: `(k n + 2) u` absolute per unit amplitude, which the
/// closed form does not have (it assumes exact cosines). Those terms plus the closed form's
/// own rounding ([`axis_closed_form`]) make the tolerance; it is not widened.
#[test]
fn sinusoid_moments_match_closed_forms_at_every_level() {
    let (xw, yw) = (Wave { amp: 0.3, k: 0.83 }, Wave { amp: 0.7, k: 1.91 });
    for &(w, h) in &[(37usize, 23usize), (64, 32), (1, 9), (30, 30), (5, 128)] {
        let slopes = separable_slopes(w, h, xw, yw);
        let map = SlopeMap::new(&slopes, w, h).unwrap();
        let layout = ChainLayout::new(w, h).unwrap();
        for kernel in [Kernel::GpuBox, Kernel::Area] {
            let settings = Settings {
                kernel,
                base: BaseRoughness::Constant(0.1),
            };
            let mut scratch = vec![TexelStats::default(); layout.width()];
            let mut worst = 0.0f64;
            for level in 0..layout.levels() {
                let lv = layout.level(level);
                let mut out = vec![TexelStats::default(); lv.width];
                for row in 0..lv.height {
                    footprint_row(&map, &settings, &layout, level, row, &mut scratch, &mut out)
                        .unwrap();
                    let wy = axis_weights(kernel, h, level, row);
                    let (my, sy, ay, a2y, ey) = axis_closed_form(yw, &wy);
                    for (col, t) in out.iter().enumerate() {
                        let wx = axis_weights(kernel, w, level, col);
                        let (mx, sx, ax, a2x, ex) = axis_closed_form(xw, &wx);
                        let (p, q) = (wy.len() as f64, wx.len() as f64);
                        let sum = (p + q + 2.0) * EPS;
                        let sample_x = EPS * (xw.k * w as f64 + 2.0) * xw.amp * xw.k;
                        let sample_y = EPS * (yw.k * h as f64 + 2.0) * yw.amp * yw.k;
                        let checks = [
                            (t.mean.x, mx, sum * ax + ex + sample_x),
                            (t.mean.y, my, sum * ay + ey + sample_y),
                            (
                                t.second.x,
                                sx,
                                sum * a2x + ex + 2.0 * sample_x * xw.amp * xw.k,
                            ),
                            (
                                t.second.z,
                                sy,
                                sum * a2y + ey + 2.0 * sample_y * yw.amp * yw.k,
                            ),
                            (
                                t.second.y,
                                mx * my,
                                sum * ax * ay + ex * ay + ey * ax + sample_x * ay + sample_y * ax,
                            ),
                        ];
                        for (i, (got, want, tol)) in checks.into_iter().enumerate() {
                            let e = (got - want).abs();
                            assert!(
                                e <= tol,
                                "{w}x{h} {kernel:?} level {level} ({col}, {row}) moment {i}: \
                                 {got} vs {want}, error {e:e} > {tol:e}"
                            );
                            worst = worst.max(e / tol);
                        }
                    }
                }
            }
            eprintln!("{w}x{h} {kernel:?}: worst error / bound {worst:.2e}");
            assert!(
                worst > 0.0 && worst <= 1.0,
                "{w}x{h} {kernel:?}: worst {worst}"
            );
        }
    }
}

/// For power-of-two sizes the GPU box and the exact footprint are one kernel.
#[test]
fn gpu_box_equals_area_for_power_of_two_sizes() {
    let (w, h) = (32, 8);
    let slopes = separable_slopes(w, h, Wave { amp: 0.2, k: 0.5 }, Wave { amp: 0.1, k: 2.0 });
    let map = SlopeMap::new(&slopes, w, h).unwrap();
    let layout = ChainLayout::new(w, h).unwrap();
    let mut scratch = vec![TexelStats::default(); w];
    for level in 0..layout.levels() {
        let lv = layout.level(level);
        for row in 0..lv.height {
            let mut a = vec![TexelStats::default(); lv.width];
            let mut b = a.clone();
            for (kernel, out) in [(Kernel::GpuBox, &mut a), (Kernel::Area, &mut b)] {
                let s = Settings {
                    kernel,
                    base: BaseRoughness::Constant(0.2),
                };
                footprint_row(&map, &s, &layout, level, row, &mut scratch, out).unwrap();
            }
            assert_eq!(a, b, "level {level} row {row}");
        }
    }
}

/// The chain's level sizes follow the GPU rule, `max(1, floor(n / 2))` per level, and the
/// levels lie back to back.
#[test]
fn layout_follows_the_gpu_rule() {
    let layout = ChainLayout::new(37, 23).unwrap();
    let sizes: Vec<_> = (0..layout.levels())
        .map(|k| (layout.level(k).width, layout.level(k).height))
        .collect();
    assert_eq!(sizes, [(37, 23), (18, 11), (9, 5), (4, 2), (2, 1), (1, 1)]);
    let mut offset = 0;
    for k in 0..layout.levels() {
        assert_eq!(layout.level(k).offset, offset);
        offset += layout.level(k).len();
    }
    assert_eq!(layout.len(), offset);
    assert_eq!(ChainLayout::new(1, 1).unwrap().levels(), 1);
    assert_eq!(ChainLayout::new(4096, 4096).unwrap().levels(), 13);
    assert_eq!(ChainLayout::new(1, 4096).unwrap().level(12).width, 1);
}

/// Baking a level in bands of rows writes what baking it whole writes.
#[test]
fn bands_are_independent() {
    let (w, h) = (21, 13);
    let slopes = separable_slopes(w, h, Wave { amp: 0.2, k: 0.7 }, Wave { amp: 0.4, k: 1.3 });
    let map = SlopeMap::new(&slopes, w, h).unwrap();
    let layout = ChainLayout::new(w, h).unwrap();
    let settings = Settings {
        kernel: Kernel::Area,
        base: BaseRoughness::Constant(0.05),
    };
    let mut scratch = vec![TexelStats::default(); layout.scratch_len()];
    for level in 0..layout.levels() {
        let lv = layout.level(level);
        let mut whole = vec![[0f32; 5]; lv.len()];
        bake_rows(
            &map,
            &settings,
            &layout,
            level,
            0..lv.height,
            &mut scratch,
            Band {
                moments: Some(&mut whole),
                ..Band::default()
            },
        )
        .unwrap();
        let mut banded = vec![[0f32; 5]; lv.len()];
        for r0 in (0..lv.height).step_by(2) {
            let r1 = (r0 + 2).min(lv.height);
            bake_rows(
                &map,
                &settings,
                &layout,
                level,
                r0..r1,
                &mut scratch,
                Band {
                    moments: Some(&mut banded[r0 * lv.width..r1 * lv.width]),
                    ..Band::default()
                },
            )
            .unwrap();
        }
        assert_eq!(whole, banded, "level {level}");
    }
}

/// Storage: each moment rounded once to nearest, `f32` within `2^-24` relative, `f16` within
/// `2^-11` relative in its normal range (`2^-14 .. 65504`) and `2^-25` absolute below, plus the
/// `2^-24` relative of the intermediate `f32` (the module's stated bounds).
#[test]
fn storage_error_is_within_the_stated_bounds() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..100_000 {
        // Magnitudes log-uniform over 1e-6 .. 1e2, signs mixed.
        let mut v = [0.0f64; 5];
        for x in v.iter_mut() {
            let (a, b) = (next(), next());
            *x = (a - 0.5) * 10f64.powf(8.0 * b - 6.0);
        }
        let t = TexelStats {
            mean: DVec2::new(v[0], v[1]),
            second: glam::DVec3::new(v[2].abs(), v[3], v[4].abs()),
            ..TexelStats::default()
        };
        let exact = [t.mean.x, t.mean.y, t.second.x, t.second.y, t.second.z];
        let a = store_f32(&t);
        let b = store_f16(&t);
        for i in 0..5 {
            let v = exact[i];
            assert!(
                (a[i] as f64 - v).abs() <= v.abs() * 2f64.powi(-24),
                "{v} -> {}",
                a[i]
            );
            let h = f16_to_f32(b[i]) as f64;
            let bound = if v.abs() >= 2f64.powi(-14) {
                v.abs() * (2f64.powi(-11) + 2f64.powi(-24))
            } else {
                2f64.powi(-25) + v.abs() * 2f64.powi(-24)
            };
            assert!((h - v).abs() <= bound, "{v} -> {h}");
        }
    }
}

/// Central differences of `h = a sin(kx x) + b sin(ky y)` sampled at texel centres with
/// periodic edges are `a kx cos(kx x) sin(kx d) / (kx d)` (and likewise in `y`, with `y` up
/// the image): exact identities of the sine. The heights are stored in `f32`, rounding each
/// by at most `2^-24 |h|`, so a difference over `2d` is off by at most
/// `2^-24 (|h+| + |h-|) / (2d)` plus a few `f64` ulps of the closed form.
#[test]
fn height_map_central_differences_match_the_sine_identity() {
    let (w, h) = (48usize, 20usize);
    let (d, scale) = (0.5, 2.0);
    let (a, kx) = (0.3, 2.0 * std::f64::consts::PI * 3.0 / (w as f64 * d));
    let (b, ky) = (0.2, 2.0 * std::f64::consts::PI * 2.0 / (h as f64 * d));
    // Height at texel (x, row): world y runs up the image, y = (h - 1 - row) d.
    let height = |x: usize, row: usize| {
        let (px, py) = (x as f64 * d, (h - 1 - row) as f64 * d);
        (a * (kx * px).sin() + b * (ky * py).sin()) / scale
    };
    let texels: Vec<f32> = (0..h)
        .flat_map(|r| (0..w).map(move |x| height(x, r) as f32))
        .collect();
    let format = HeightFormat {
        channels: 1,
        texel_spacing: d,
        height_scale: scale,
        edges: Edges::Wrap,
    };
    let map = HeightMap::new(Texels::F32(&texels), w, h, format).unwrap();
    let hmax = (a + b) / scale;
    let tol = 2f64.powi(-24) * 2.0 * hmax * scale / (2.0 * d) + 64.0 * EPS;
    for r in 0..h {
        for x in 0..w {
            let (px, py) = (x as f64 * d, (h - 1 - r) as f64 * d);
            let sx = a * kx * (kx * px).cos() * (kx * d).sin() / (kx * d);
            let sy = b * ky * (ky * py).cos() * (ky * d).sin() / (ky * d);
            let (s, n) = map.texel(x, r);
            assert!((s.x - sx).abs() <= tol, "({x}, {r}) s_x {} vs {sx}", s.x);
            assert!((s.y - sy).abs() <= tol, "({x}, {r}) s_y {} vs {sy}", s.y);
            assert!((n.length() - 1.0).abs() <= 4.0 * EPS);
            assert!((n.x + s.x * n.z).abs() <= 4.0 * EPS && (n.y + s.y * n.z).abs() <= 4.0 * EPS);
        }
    }
    // Clamped edges: the border takes the one-sided difference over d.
    let clamp = HeightMap::new(
        Texels::F32(&texels),
        w,
        h,
        HeightFormat {
            edges: Edges::Clamp,
            ..format
        },
    )
    .unwrap();
    let (s, _) = clamp.texel(0, 5);
    let want = (texels[5 * w + 1] as f64 - texels[5 * w] as f64) * scale / d;
    assert!((s.x - want).abs() <= 4.0 * EPS * want.abs().max(1.0));
    let (s, _) = clamp.texel(3, 0);
    let want = (texels[3] as f64 - texels[w + 3] as f64) * scale / d;
    assert!((s.y - want).abs() <= 4.0 * EPS * want.abs().max(1.0));
}
