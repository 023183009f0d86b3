//! The exact GGX box filter against its baselines, f32, on seeded realistic inputs: the
//! printed GDC eight-term formula, filtered Beckmann with a full roughness matrix, and
//! unfiltered GGX; and the box lobe's `Lambda` and samplers against GGX's. Each iteration
//! evaluates all `N` inputs; time per evaluation is the reported time divided by `N`
//! (criterion prints it as throughput).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use filtered_ndf::f32::{
    AxisAligned, Beckmann, Covariance, Ggx, Ndf, NdfSampling, RoughnessMatrix, filter,
    filter::rect, footprint::slope, sampling,
};
use filtered_ndf::testing::rng::SplitMix64;
use glam::{Vec2, Vec3};
use std::hint::black_box;

const N: usize = 1024;

struct Input {
    r: AxisAligned,
    m: RoughnessMatrix,
    h: Vec3,
    hpp: Vec2,
    half: Vec2,
    /// Filtered-matrix entries `A + 2 Sigma` and the clamp `tau`, for building the Beckmann
    /// matrix per evaluation.
    entries: (f32, f32, f32, f32),
    /// The same kernel `Sigma`, for the filtering path `filter::gaussian`.
    cov: Covariance,
    /// A view direction (0 to 85 degrees) and four uniform numbers, for `Lambda` and the
    /// samplers (drawn from a second stream, so the inputs above are those of earlier runs).
    wo: Vec3,
    u: Vec2,
    u_box: Vec2,
}

/// Realistic inputs: roughness 0.02..0.6 (log), anisotropy up to 4, half vectors within a few
/// roughness widths of the normal (and some far), footprints 1e-3..0.1 per axis (log).
fn inputs() -> Vec<Input> {
    let mut st = SplitMix64(0x5eed);
    let mut st2 = SplitMix64(0x5eed ^ 0xb0c5);
    let next = |st: &mut SplitMix64| st.uniform() as f32;
    let log = |lo: f32, hi: f32, st: &mut SplitMix64| st.log_uniform(lo as f64, hi as f64) as f32;
    (0..N)
        .map(|_| {
            let a = log(0.02, 0.6, &mut st);
            let k = log(1.0, 4.0, &mut st);
            let b = (a * k).min(1.0);
            let r = AxisAligned::new(a, b).unwrap();
            let spread = if next(&mut st) < 0.8 { 3.0 } else { 30.0 };
            let s = Vec2::new(
                (next(&mut st) - 0.5) * 2.0 * spread * a,
                (next(&mut st) - 0.5) * 2.0 * spread * b,
            );
            let h = slope::sphere_from_slope(s);
            let half = Vec2::new(log(1e-3, 0.1, &mut st), log(1e-3, 0.1, &mut st));
            // Beckmann: A + 2 Sigma with a box-equivalent covariance (H^2 / 3) and a small
            // correlation, tau = det A (TK19).
            let (s11, s22) = (half.x * half.x / 3.0, half.y * half.y / 3.0);
            let s12 = 0.3 * (s11 * s22).sqrt();
            let entries = (
                a * a + 2.0 * s11,
                2.0 * s12,
                b * b + 2.0 * s22,
                a * a * b * b,
            );
            let m = RoughnessMatrix::new_with_det_clamp(entries.0, entries.1, entries.2, entries.3)
                .unwrap();
            let theta = (st2.uniform() * 85f64.to_radians()) as f32;
            let phi = (st2.uniform() * std::f64::consts::TAU) as f32;
            let wo = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            let mut uni = || st2.uniform() as f32;
            let (u, u_box) = (Vec2::new(uni(), uni()), Vec2::new(uni(), uni()));
            Input {
                r,
                m,
                h,
                hpp: Vec2::new(h.x / h.z, h.y / h.z),
                half,
                entries,
                cov: Covariance::new(s11, s12, s22),
                wo,
                u,
                u_box,
            }
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let xs = inputs();
    let mut g = c.benchmark_group("ggx_rect_f32");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("exact_rect_d", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += rect::d_rect(x.r, x.h, x.half);
            }
            acc
        })
    });
    g.bench_function("printed_gdc_d", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += rect::d_rect_printed(x.r, x.hpp, x.h, x.half);
            }
            acc
        })
    });
    g.bench_function("beckmann_matrix_d", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += Beckmann::new(x.m).d(x.h);
            }
            acc
        })
    });
    g.bench_function("beckmann_matrix_build_and_d", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                let (a11, a12, a22, tau) = x.entries;
                if let Ok(m) = RoughnessMatrix::new_with_det_clamp(a11, a12, a22, tau) {
                    acc += Beckmann::new(m).d(x.h);
                }
            }
            acc
        })
    });
    g.bench_function("beckmann_filtered_d", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += Beckmann::new(filter::gaussian(x.r, x.cov)).d(x.h);
            }
            acc
        })
    });
    g.bench_function("ggx_unfiltered_d", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += Ggx::new(x.r).d(x.h);
            }
            acc
        })
    });
    g.bench_function("exact_rect_lambda", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += rect::lambda_rect(x.r, x.half, x.wo);
            }
            acc
        })
    });
    g.bench_function("ggx_unfiltered_lambda", |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for x in black_box(&xs) {
                acc += Ggx::new(x.r).lambda(x.wo);
            }
            acc
        })
    });
    g.bench_function("exact_rect_sample_normal", |bch| {
        bch.iter(|| {
            let mut acc = Vec3::ZERO;
            for x in black_box(&xs) {
                acc += sampling::rect::sample_normal_rect(x.r, x.half, x.u, x.u_box);
            }
            acc
        })
    });
    g.bench_function("ggx_sample_normal", |bch| {
        bch.iter(|| {
            let mut acc = Vec3::ZERO;
            for x in black_box(&xs) {
                acc += Ggx::new(x.r).sample_normal(x.u);
            }
            acc
        })
    });
    g.bench_function("exact_rect_sample_visible", |bch| {
        bch.iter(|| {
            let mut acc = Vec3::ZERO;
            for x in black_box(&xs) {
                acc += sampling::rect::sample_visible_normal_rect(x.r, x.half, x.wo, x.u, x.u_box)
                    .unwrap_or(Vec3::ZERO);
            }
            acc
        })
    });
    g.bench_function("ggx_sample_visible", |bch| {
        bch.iter(|| {
            let mut acc = Vec3::ZERO;
            for x in black_box(&xs) {
                acc += Ggx::new(x.r)
                    .sample_visible_normal(x.wo, x.u)
                    .unwrap_or(Vec3::ZERO);
            }
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
