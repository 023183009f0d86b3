//! The exact Gaussian-filtered GGX against the filters a renderer would otherwise use, in one
//! run, f32 and f64, on the seeded realistic cases of `filtered_ndf::testing::shading` (the trade table's
//! cases): unfiltered GGX, the TK19 matrix approximation `Ggx::new(filter::gaussian(A, Sigma))`
//! (building the lobe included), the exact box filter `rect::d_rect` over the footprint's
//! bounding rectangle (the speed bar of issue 17), and the exact Gaussian filter, once with the
//! lobe built per evaluation and once with prebuilt lobes (`d` alone); then Smith `Lambda` and
//! visible-normal sampling of the exact lobe beside the TK19 lobe's (prebuilt lobes, seeded
//! views: three in four up to 80 degrees, one in four from 80 to 89.9).
//!
//! The front door's rows (`front_door_*`) compare TK19 (`Gaussian::TK19`) with the exact
//! filter (`ExactGaussian::KHPL16`) at each [`Tolerance`](filtered_ndf::f32::filter::Tolerance)
//! setting, both with their clamp rules and the lobe built per evaluation.
//!
//! `cargo bench --bench gaussian_ggx -- --quick`. Figures are per evaluation
//! (`Throughput::Elements`); compare ratios within one run.

use filtered_ndf::testing::shading as common;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

const N: usize = 1024;

macro_rules! group {
    ($c:expr, $prec:ident, $t:ty) => {{
        use filtered_ndf::math::Real;
        use filtered_ndf::$prec::{
            AxisAligned, Footprint, GaussianFilteredGgx, Ggx, Ndf, NdfSampling, Vec2, Vec3, filter,
            filter::rect,
            filter::{ExactGaussian, Filterable, Gaussian, Tolerance},
        };
        type Wall<'a> = BenchmarkGroup<'a, criterion::measurement::WallTime>;
        let c = |x: f64| <$t as Real>::from_f64(x);
        let cases = common::realistic_cases(N, 0x5EED);
        let r: Vec<AxisAligned> = cases
            .iter()
            .map(|k| AxisAligned::new_clamped(c(k.alpha[0]), c(k.alpha[1])))
            .collect();
        let h: Vec<Vec3> = cases
            .iter()
            .map(|k| Vec3::new(c(k.h[0]), c(k.h[1]), c(k.h[2])))
            .collect();
        let fp: Vec<Footprint> = cases
            .iter()
            .map(|k| {
                Footprint::from_slope_derivatives(
                    Vec2::new(c(k.dh_u[0]), c(k.dh_u[1])),
                    Vec2::new(c(k.dh_v[0]), c(k.dh_v[1])),
                )
            })
            .collect();
        let lobes: Vec<GaussianFilteredGgx> = (0..N)
            .map(|i| GaussianFilteredGgx::new(r[i], fp[i].covariance(0.5)))
            .collect();
        let tk19: Vec<_> = (0..N)
            .map(|i| Ggx::new(filter::gaussian(r[i], fp[i].covariance(0.5))))
            .collect();
        let mut rng = common::Rng(0x5EED_0017);
        let views: Vec<Vec3> = (0..N)
            .map(|i| {
                let deg = if i % 4 == 3 {
                    rng.range(80.0, 89.9)
                } else {
                    rng.range(0.0, 80.0)
                };
                let (t, p) = (deg.to_radians(), rng.range(0.0, std::f64::consts::TAU));
                Vec3::new(c(t.sin() * p.cos()), c(t.sin() * p.sin()), c(t.cos()))
            })
            .collect();
        let us: Vec<Vec2> = (0..N)
            .map(|_| Vec2::new(c(rng.uniform()), c(rng.uniform())))
            .collect();
        fn run<T>(g: &mut Wall<'_>, name: &str, mut f: impl FnMut(usize) -> T) {
            g.bench_function(name, |b| {
                b.iter(|| {
                    for i in 0..N {
                        black_box(f(black_box(i)));
                    }
                })
            });
        }
        let mut g = $c.benchmark_group(format!("gaussian_ggx/{}", stringify!($prec)));
        g.throughput(Throughput::Elements(N as u64));
        run(&mut g, "unfiltered_d", |i| Ggx::new(r[i]).d(h[i]));
        run(&mut g, "tk19_matrix_build_and_d", |i| {
            Ggx::new(filter::gaussian(r[i], fp[i].covariance(0.5))).d(h[i])
        });
        run(&mut g, "exact_box_d_rect", |i| {
            rect::d_rect(r[i], h[i], fp[i].bounding_rect().half_extent)
        });
        run(&mut g, "exact_gaussian_build_and_d", |i| {
            GaussianFilteredGgx::new(r[i], fp[i].covariance(0.5)).d(h[i])
        });
        run(&mut g, "exact_gaussian_d", |i| lobes[i].d(h[i]));
        // Through the front door, with the clamp rules: TK19 against the exact Gaussian filter
        // at each tolerance setting (the trade inside the exact filter).
        run(&mut g, "front_door_tk19", |i| {
            Ggx::new(r[i]).filtered(fp[i], Gaussian::TK19).d(h[i])
        });
        for t in Tolerance::ALL {
            let m = ExactGaussian::KHPL16.with_tolerance(t);
            run(&mut g, &format!("front_door_exact_{t:?}"), |i| {
                Ggx::new(r[i]).filtered(fp[i], m).d(h[i])
            });
        }
        run(&mut g, "tk19_lambda", |i| tk19[i].lambda(views[i]));
        run(&mut g, "exact_gaussian_lambda", |i| {
            lobes[i].lambda(views[i])
        });
        run(&mut g, "tk19_sample_visible_normal", |i| {
            tk19[i].sample_visible_normal(views[i], us[i])
        });
        run(&mut g, "exact_gaussian_sample_visible_normal", |i| {
            lobes[i].sample_visible_normal(views[i], us[i])
        });
        g.finish();
    }};
}

fn benches(c: &mut Criterion) {
    group!(c, f32, f32);
    group!(c, f64, f64);
}

criterion_group!(gaussian_ggx, benches);
criterion_main!(gaussian_ggx);
