//! The bake of a whole chain: an 8-bit RGB tangent-space normal map (a procedural height field
//! of sinusoids and hashed noise, encoded once outside the timing), every level, both chains
//! (the `f32` moment chain and the GGX roughness chains, isotropic and anisotropic), the
//! levels baked in two bands of rows on two threads (`std::thread::scope`), as a caller of
//! [`bake_rows`] would with rayon. The target: 4096 x 4096 in under 10 s on 2 cores.
//!
//! Two groups: `bake_chain` is wall-clock time; `bake_chain_cpu` is the process's CPU time
//! (user + system, from `/proc/self/stat`, in clock ticks of 10 ms), which a shared machine's
//! load inflates far less: on two idle cores the two-thread bake's wall time is about half of
//! it. (Linux only; elsewhere that group is skipped.)
//!
//! `cargo bench --bench bake` (add `-- --quick` for a short run).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use filtered_ndf::bake::{
    Band, BaseRoughness, ChainLayout, Convention, Kernel, NormalFormat, NormalMap, Settings,
    TexelStats, Texels, bake_rows,
};
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use std::time::Duration;

/// An 8-bit RGB normal map of a height field `h = sum of sinusoids + hashed noise`.
fn normal_map(n: usize) -> Vec<u8> {
    let mut rng = Rng(0xBA4E);
    let noise: Vec<f64> = (0..n * n).map(|_| rng.uniform() - 0.5).collect();
    let mut out = Vec::with_capacity(3 * n * n);
    for y in 0..n {
        for x in 0..n {
            let (fx, fy) = (x as f64 / n as f64, y as f64 / n as f64);
            let tau = std::f64::consts::TAU;
            let sx = 0.4 * (tau * 37.0 * fx).cos() + 0.2 * noise[y * n + x];
            let sy = 0.3 * (tau * 53.0 * fy + 1.0).cos() + 0.2 * noise[(y * n + x) ^ 1];
            let len = (1.0 + sx * sx + sy * sy).sqrt();
            for c in [-sx / len, -sy / len, 1.0 / len] {
                out.push(((c * 0.5 + 0.5) * 255.0).round() as u8);
            }
        }
    }
    out
}

/// Every level of the chain, each in `threads` bands of rows.
fn bake_chain(map: &NormalMap<'_>, layout: &ChainLayout, out: &mut Outputs, threads: usize) {
    let settings = Settings {
        kernel: Kernel::Area,
        base: BaseRoughness::Constant(0.05),
    };
    let Outputs {
        moments,
        ggx,
        aniso,
        scratch,
    } = out;
    for level in 0..layout.levels() {
        let lv = layout.level(level);
        let range = lv.rows(0..lv.height);
        let band_rows = lv.height.div_ceil(threads);
        let per = band_rows * lv.width;
        std::thread::scope(|s| {
            let parts = moments[range.clone()]
                .chunks_mut(per)
                .zip(ggx[range.clone()].chunks_mut(per))
                .zip(aniso[range.clone()].chunks_mut(per))
                .zip(scratch.iter_mut())
                .enumerate();
            for (i, (((m, g), a), sc)) in parts {
                let rows = i * band_rows..((i + 1) * band_rows).min(lv.height);
                let settings = &settings;
                s.spawn(move || {
                    bake_rows(
                        map,
                        settings,
                        layout,
                        level,
                        rows,
                        sc,
                        Band {
                            moments: Some(m),
                            ggx: Some(g),
                            ggx_anisotropic: Some(a),
                            ..Band::default()
                        },
                    )
                    .unwrap()
                });
            }
        });
    }
}

struct Outputs {
    moments: Vec<[f32; 5]>,
    ggx: Vec<f32>,
    aniso: Vec<[f32; 3]>,
    scratch: Vec<Vec<TexelStats>>,
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("bake_chain");
    g.sample_size(10).warm_up_time(Duration::from_secs(1));
    for &n in &[1024usize, 4096] {
        let texels = normal_map(n);
        let map = NormalMap::new(
            Texels::Unorm8(&texels),
            n,
            n,
            NormalFormat::new(3, Convention::OpenGl),
        )
        .unwrap();
        let layout = ChainLayout::new(n, n).unwrap();
        for threads in [1usize, 2] {
            let mut out = Outputs {
                moments: vec![[0.0; 5]; layout.len()],
                ggx: vec![0.0; layout.len()],
                aniso: vec![[0.0; 3]; layout.len()],
                scratch: vec![vec![TexelStats::default(); layout.scratch_len()]; threads],
            };
            if n == 4096 {
                g.measurement_time(Duration::from_secs(60));
            }
            g.bench_function(BenchmarkId::new(format!("{n}x{n}"), threads), |b| {
                b.iter(|| bake_chain(&map, &layout, &mut out, threads))
            });
        }
    }
    g.finish();
}

/// The process's CPU time (user + system), from `/proc/self/stat` (fields 14 and 15, clock
/// ticks of 10 ms, the Linux default `CLK_TCK = 100`); `None` off Linux.
fn cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (which may hold spaces) in parentheses.
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: u64 = f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?;
    Some(Duration::from_millis(10 * ticks))
}

fn bench_cpu(c: &mut Criterion) {
    if cpu_time().is_none() {
        return;
    }
    let mut g = c.benchmark_group("bake_chain_cpu");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(60));
    let n = 4096;
    let texels = normal_map(n);
    let map = NormalMap::new(
        Texels::Unorm8(&texels),
        n,
        n,
        NormalFormat::new(3, Convention::OpenGl),
    )
    .unwrap();
    let layout = ChainLayout::new(n, n).unwrap();
    for threads in [1usize, 2] {
        let mut out = Outputs {
            moments: vec![[0.0; 5]; layout.len()],
            ggx: vec![0.0; layout.len()],
            aniso: vec![[0.0; 3]; layout.len()],
            scratch: vec![vec![TexelStats::default(); layout.scratch_len()]; threads],
        };
        g.bench_function(BenchmarkId::new(format!("{n}x{n}"), threads), |b| {
            b.iter_custom(|iters| {
                let t0 = cpu_time().unwrap();
                for _ in 0..iters {
                    bake_chain(&map, &layout, &mut out, threads);
                }
                cpu_time().unwrap() - t0
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench, bench_cpu);
criterion_main!(benches);
