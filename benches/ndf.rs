//! `D(m)` of GGX and Beckmann in the three roughness forms, `f32` and `f64`, over a seeded,
//! realistic set of 1024 micronormals (mostly within the lobe, an eighth far in the tail, an
//! eighth grazing), reported per evaluation (`Throughput::Elements`).
//!
//! `cargo bench --bench ndf` (add `-- --quick` for a short run).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
// The crate's seeded SplitMix64, so the input set is identical on every run.
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use std::hint::black_box;

const N: usize = 1024;

/// Micronormals for a lobe of roughness about `alpha`: slopes Gaussian with std `alpha`
/// (3/4), times 10 (tail, 1/8), or polar angles 80..89.9 degrees (grazing, 1/8).
fn micronormals(alpha: f64) -> Vec<[f64; 3]> {
    let mut rng = Rng(0xBE4C);
    (0..N)
        .map(|i| {
            let phi = std::f64::consts::TAU * rng.uniform();
            let tan_theta = match i % 8 {
                6 => 10.0 * alpha * (1.0 + rng.uniform()),
                7 => (80.0 + 9.9 * rng.uniform()).to_radians().tan(),
                _ => alpha * (-2.0 * rng.uniform().max(1e-12).ln()).sqrt(),
            };
            let ct = 1.0 / (1.0 + tan_theta * tan_theta).sqrt();
            let st = tan_theta * ct;
            [st * phi.cos(), st * phi.sin(), ct]
        })
        .collect()
}

macro_rules! bench_precision {
    ($c:expr, $prec:ident, $vec:ident, $t:ty) => {{
        use filtered_ndf::$prec::{AxisAligned, Beckmann, Ggx, Isotropic, Ndf, RoughnessMatrix};
        use glam::$vec;
        let ms: Vec<$vec> = micronormals(0.2)
            .into_iter()
            .map(|[x, y, z]| $vec::new(x as $t, y as $t, z as $t))
            .collect();
        let mut g = $c.benchmark_group(concat!("d_", stringify!($prec)));
        g.throughput(Throughput::Elements(N as u64));
        fn run<N: Ndf>(
            g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
            name: &str,
            ndf: N,
            ms: &[$vec],
        ) {
            g.bench_with_input(BenchmarkId::from_parameter(name), ms, |b, ms| {
                b.iter(|| {
                    let mut acc: $t = 0.0;
                    for &m in ms {
                        acc += black_box(&ndf).d(m);
                    }
                    acc
                })
            });
        }
        let iso = Isotropic::new(0.2).unwrap();
        let aa = AxisAligned::new(0.15, 0.3).unwrap();
        let mx = RoughnessMatrix::new(0.04, 0.015, 0.05).unwrap();
        run(&mut g, "ggx_isotropic", Ggx::new(iso), &ms);
        run(&mut g, "ggx_axis_aligned", Ggx::new(aa), &ms);
        run(&mut g, "ggx_matrix", Ggx::new(mx), &ms);
        run(&mut g, "beckmann_isotropic", Beckmann::new(iso), &ms);
        run(&mut g, "beckmann_axis_aligned", Beckmann::new(aa), &ms);
        run(&mut g, "beckmann_matrix", Beckmann::new(mx), &ms);
        g.finish();
    }};
}

fn bench_d(c: &mut Criterion) {
    bench_precision!(c, f32, Vec3, f32);
    bench_precision!(c, f64, DVec3, f64);
}

criterion_group!(benches, bench_d);
criterion_main!(benches);
