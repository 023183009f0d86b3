//! Batch (structure-of-arrays) evaluation against the scalar loop a caller would write, per
//! core, on the seeded realistic inputs of `common`. Each iteration evaluates `N` elements;
//! criterion reports the throughput in elements per second.
//!
//! Vectorisation check (see `filtered_ndf::f32::batch`): disassemble this binary
//! (`objdump -d --no-show-raw-insn target/release/deps/batch-*`) and look for packed
//! single-precision ops (`mulps`, `divps`, `addps`) in the `ggx_d` loops.

#[path = "common/mod.rs"]
mod common;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

const N: usize = 4096;

macro_rules! family {
    ($c:expr, $prec:ident, $t:ty) => {{
        use filtered_ndf::$prec::{
            AxisAligned, Beckmann, ClampRules, Footprint, Ggx, Isotropic, Ndf, RoughnessMatrix,
            Vec2, Vec3, batch, filter::rect,
        };
        type Wall<'a> = BenchmarkGroup<'a, criterion::measurement::WallTime>;
        let cases = common::realistic_cases(N, 0xBA7C);
        let col = |f: &dyn Fn(&common::Case) -> f64| -> Vec<$t> {
            cases.iter().map(|k| f(k) as $t).collect()
        };
        let (hx, hy, hz) = (col(&|k| k.h[0]), col(&|k| k.h[1]), col(&|k| k.h[2]));
        let (ux, uy) = (col(&|k| k.dh_u[0]), col(&|k| k.dh_u[1]));
        let (vx, vy) = (col(&|k| k.dh_v[0]), col(&|k| k.dh_v[1]));
        let fps: Vec<Footprint> = (0..N)
            .map(|i| {
                Footprint::from_slope_derivatives(Vec2::new(ux[i], uy[i]), Vec2::new(vx[i], vy[i]))
            })
            .collect();
        // Bounding-rectangle half extents (KHPL16 5.3): (|dh_u| + |dh_v|) / 2 per axis.
        let (rx, ry) = (
            col(&|k| 0.5 * (k.dh_u[0].abs() + k.dh_v[0].abs())),
            col(&|k| 0.5 * (k.dh_u[1].abs() + k.dh_v[1].abs())),
        );
        let soa = batch::Footprints {
            dh_u_x: &ux,
            dh_u_y: &uy,
            dh_v_x: &vx,
            dh_v_y: &vy,
        };
        // One material for the whole batch (a baking pass over one texture or lobe).
        let iso = Isotropic::new(0.1 as $t).unwrap();
        let aa = AxisAligned::new(0.1 as $t, 0.3 as $t).unwrap();
        let mat = RoughnessMatrix::new(0.02 as $t, 0.005 as $t, 0.05 as $t).unwrap();
        // The papers' clamps (the batch filtered functions take the scalar route's rules).
        let rules = ClampRules::default();
        let mut out = vec![0.0 as $t; N];
        fn group<'a>(c: &'a mut Criterion, name: &str) -> Wall<'a> {
            let mut g = c.benchmark_group(format!("batch_{}/{}", name, stringify!($prec)));
            g.throughput(Throughput::Elements(N as u64));
            g
        }
        let h = |i: usize| Vec3::new(hx[i], hy[i], hz[i]);

        macro_rules! pair {
            ($name:expr, $scalar:expr, $batch:expr) => {{
                let mut g = group($c, $name);
                g.bench_function("scalar_loop", |b| {
                    b.iter(|| {
                        for i in 0..N {
                            out[i] = $scalar(black_box(i));
                        }
                        black_box(&mut out);
                    })
                });
                g.bench_function("batch", |b| {
                    b.iter(|| {
                        black_box($batch(&mut out));
                        black_box(&mut out);
                    })
                });
                g.finish();
            }};
        }
        pair!(
            "ggx_d_isotropic",
            |i| Ggx::new(iso).d(h(i)),
            |o: &mut [$t]| batch::ggx_d(&iso, &hx, &hy, &hz, o)
        );
        pair!(
            "ggx_d_axis_aligned",
            |i| Ggx::new(aa).d(h(i)),
            |o: &mut [$t]| batch::ggx_d(&aa, &hx, &hy, &hz, o)
        );
        pair!(
            "ggx_d_matrix",
            |i| Ggx::new(mat).d(h(i)),
            |o: &mut [$t]| batch::ggx_d(&mat, &hx, &hy, &hz, o)
        );
        pair!(
            "beckmann_d_axis_aligned",
            |i| Beckmann::new(aa).d(h(i)),
            |o: &mut [$t]| batch::beckmann_d(&aa, &hx, &hy, &hz, o)
        );
        pair!(
            "beckmann_d_filtered",
            |i: usize| Beckmann::new(rules.filter_gaussian(aa, fps[i], 0.5)).d(h(i)),
            |o: &mut [$t]| batch::beckmann_d_filtered(&aa, &rules, 0.5, &hx, &hy, &hz, soa, o)
        );
        pair!(
            "ggx_d_filtered_tk19",
            |i: usize| Ggx::new(rules.filter_gaussian(aa, fps[i], 0.5)).d(h(i)),
            |o: &mut [$t]| batch::ggx_d_filtered(&aa, &rules, 0.5, &hx, &hy, &hz, soa, o)
        );
        pair!(
            "d_rect",
            |i: usize| rect::d_rect(aa, h(i), Vec2::new(rx[i], ry[i])),
            |o: &mut [$t]| batch::d_rect(&aa, &hx, &hy, &hz, &rx, &ry, o)
        );
    }};
}

fn benches(c: &mut Criterion) {
    family!(c, f32, f32);
    family!(c, f64, f64);
}

criterion_group!(batch_benches, benches);
criterion_main!(batch_benches);
