//! Batch (structure-of-arrays) evaluation against the scalar loop a caller would write, per
//! core, on the seeded realistic inputs of `common`. Each iteration evaluates `N` elements;
//! criterion reports the throughput in elements per second. Every kernel is one group
//! `batch_<kernel>/<precision>` with the pair `scalar_loop` and `batch`.
//!
//! Vectorisation check (see `filtered_ndf::f32::batch`): disassemble this binary
//! (`objdump -d --no-show-raw-insn target/release/deps/batch-*`) and look for packed
//! single-precision ops (`mulps`, `divps`, `sqrtps`, `addps`) in the kernels' loops.

use filtered_ndf::testing::shading as common;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;

const N: usize = 4096;

macro_rules! family {
    ($c:expr, $prec:ident, $t:ty) => {{
        use filtered_ndf::$prec::{
            AxisAligned, Beckmann, ClampRules, Footprint, GaussianFilteredGgx, Ggx, Isotropic, Ndf,
            RoughnessMatrix, Vec2, Vec3, batch, filter::presets, filter::proxy, filter::rect,
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
        // Views for Lambda and G2: the light direction of each case (its half vector
        // reflected about a view direction seeded per case), in the upper hemisphere.
        let mut rng = common::Rng(0x5EED);
        let views: Vec<[f64; 3]> = (0..N)
            .map(|_| {
                let t = (89.0 * rng.uniform()).to_radians();
                let p = std::f64::consts::TAU * rng.uniform();
                [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
            })
            .collect();
        let (ox, oy, oz) = (
            views.iter().map(|v| v[0] as $t).collect::<Vec<_>>(),
            views.iter().map(|v| v[1] as $t).collect::<Vec<_>>(),
            views.iter().map(|v| v[2] as $t).collect::<Vec<_>>(),
        );
        // i = reflect(o, h), flipped into the upper hemisphere.
        let refl: Vec<[$t; 3]> = (0..N)
            .map(|k| {
                let (o, h) = (
                    Vec3::new(ox[k], oy[k], oz[k]),
                    Vec3::new(hx[k], hy[k], hz[k]),
                );
                let i = 2.0 * o.dot(h) * h - o;
                let i = Vec3::new(i.x, i.y, i.z.abs()).normalize();
                [i.x, i.y, i.z]
            })
            .collect();
        let (ix, iy, iz) = (
            refl.iter().map(|v| v[0]).collect::<Vec<_>>(),
            refl.iter().map(|v| v[1]).collect::<Vec<_>>(),
            refl.iter().map(|v| v[2]).collect::<Vec<_>>(),
        );
        let (vi, vo, vh) = (
            batch::Vec3s::new(&ix, &iy, &iz),
            batch::Vec3s::new(&ox, &oy, &oz),
            batch::Vec3s::new(&hx, &hy, &hz),
        );
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
            g.warm_up_time(Duration::from_millis(500));
            g.measurement_time(Duration::from_secs(2));
            g
        }
        let h = |i: usize| Vec3::new(hx[i], hy[i], hz[i]);
        let o = |i: usize| Vec3::new(ox[i], oy[i], oz[i]);
        let li = |i: usize| Vec3::new(ix[i], iy[i], iz[i]);

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
        macro_rules! forms {
            ($ndf:ident, $form:expr, $r:expr) => {{
                let r = $r;
                let lobe = $ndf::new(r);
                let name = stringify!($ndf).to_lowercase();
                pair!(
                    &format!("{name}_d_{}", $form),
                    |i| lobe.d(h(i)),
                    |o: &mut [$t]| batch_fn!($ndf, d)(&r, &hx, &hy, &hz, o)
                );
                pair!(
                    &format!("{name}_lambda_{}", $form),
                    |i| lobe.lambda(o(i)),
                    |out: &mut [$t]| batch_fn!($ndf, lambda)(&r, &ox, &oy, &oz, out)
                );
                pair!(
                    &format!("{name}_g2_{}", $form),
                    |i| lobe.g2(li(i), o(i), h(i)),
                    |out: &mut [$t]| batch_fn!($ndf, g2)(&r, vi, vo, vh, out)
                );
            }};
        }
        macro_rules! batch_fn {
            (Ggx, d) => {
                batch::ggx_d
            };
            (Ggx, lambda) => {
                batch::ggx_lambda
            };
            (Ggx, g2) => {
                batch::ggx_g2
            };
            (Beckmann, d) => {
                batch::beckmann_d
            };
            (Beckmann, lambda) => {
                batch::beckmann_lambda
            };
            (Beckmann, g2) => {
                batch::beckmann_g2
            };
        }
        forms!(Ggx, "isotropic", iso);
        forms!(Ggx, "axis_aligned", aa);
        forms!(Ggx, "matrix", mat);
        forms!(Beckmann, "isotropic", iso);
        forms!(Beckmann, "axis_aligned", aa);
        forms!(Beckmann, "matrix", mat);
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
            "ggx_d_filtered_projected",
            |i: usize| Ggx::new(rules.filter_projected(aa, fps[i], 0.5)).d(h(i)),
            |o: &mut [$t]| batch::ggx_d_filtered_projected(&aa, &rules, 0.5, &hx, &hy, &hz, soa, o)
        );
        pair!(
            "ggx_d_filtered_exact",
            |i: usize| {
                let k = rules.kernel(rules.footprint(fps[i]).covariance(0.5));
                GaussianFilteredGgx::new(aa, k).d(h(i))
            },
            |o: &mut [$t]| batch::ggx_d_filtered_exact(&aa, &rules, 0.5, &hx, &hy, &hz, soa, o)
        );
        pair!(
            "d_rect_filtered",
            |i: usize| {
                let half = rules.rect(fps[i].bounding_rect(), aa.alpha()).half_extent;
                rect::d_rect(aa, h(i), half)
            },
            |o: &mut [$t]| batch::d_rect_filtered(&aa, &rules, &hx, &hy, &hz, soa, o)
        );
        pair!(
            "ggx_d_filtered_proxy",
            |i: usize| {
                let half = rules.rect(fps[i].bounding_rect(), aa.alpha()).half_extent;
                Ggx::new(proxy::proxy(aa, half)).d(h(i))
            },
            |o: &mut [$t]| batch::ggx_d_filtered_proxy(&aa, &rules, &hx, &hy, &hz, soa, o)
        );
        // Deferred presets: per-element material roughness and world-space normal
        // differences (the cases' slope derivatives as the tangential part of the normal's
        // change per pixel, the footprint's cross term as its normal part).
        let alpha_col = col(&|k| 0.02 + 0.5 * k.h[0].abs());
        let (nz_u, nz_v) = (
            col(&|k| k.dh_u[0] * k.dh_v[1]),
            col(&|k| k.dh_u[1] * k.dh_v[0]),
        );
        let (dn_u, dn_v) = (
            batch::Vec3s::new(&ux, &uy, &nz_u),
            batch::Vec3s::new(&vx, &vy, &nz_v),
        );
        let dn = |i: usize| {
            (
                Vec3::new(ux[i], uy[i], nz_u[i]),
                Vec3::new(vx[i], vy[i], nz_v[i]),
            )
        };
        for (name, conv) in [
            ("deferred_tk19_trace", presets::TK19_TRACE),
            ("deferred_tk19_max", presets::TK19_MAX),
            ("deferred_unreal", presets::UNREAL),
        ] {
            pair!(
                name,
                |i: usize| {
                    let (u, v) = dn(i);
                    conv.filter(alpha_col[i], u, v).alpha()
                },
                |o: &mut [$t]| batch::deferred_filter(&conv, &alpha_col, dn_u, dn_v, o)
            );
        }
        pair!(
            "d_rect",
            |i: usize| rect::d_rect(aa, h(i), Vec2::new(rx[i], ry[i])),
            |o: &mut [$t]| batch::d_rect(&aa, &hx, &hy, &hz, &rx, &ry, o)
        );
        // The exact Gaussian-filtered GGX, one lobe over the cases' half vectors: a light
        // kernel (`2 l1 = 0.01`: Gauss-Laguerre and the far tail, the first lane) and a heavy
        // one (`2 l1 = 1`: the trapezoid rule where `1 + q < 56`, 71 % of these half vectors,
        // the second lane).
        {
            use filtered_ndf::$prec::Covariance;
            for (name, k) in [
                (
                    "gaussian_filtered_ggx_d_light",
                    Covariance::new(5e-5, 0.0, 5e-5),
                ),
                (
                    "gaussian_filtered_ggx_d_heavy",
                    Covariance::new(5e-3, 0.0, 5e-3),
                ),
            ] {
                let lobe = GaussianFilteredGgx::new(aa, k);
                pair!(name, |i: usize| lobe.d(h(i)), |o: &mut [$t]| {
                    batch::gaussian_filtered_ggx_d(&lobe, &hx, &hy, &hz, o)
                });
            }
        }
        // Projected-space filtering (TK21) with the cases' clamped kernels (the papers' rules),
        // one per element.
        {
            use filtered_ndf::$prec::filter::projected;
            let ks: Vec<_> = fps
                .iter()
                .map(|&f| rules.kernel(rules.footprint(f).covariance(0.5)))
                .collect();
            let (k11, k12, k22): (Vec<$t>, Vec<$t>, Vec<$t>) = (
                ks.iter().map(|k| k.s11).collect(),
                ks.iter().map(|k| k.s12).collect(),
                ks.iter().map(|k| k.s22).collect(),
            );
            let kernels = batch::Covariances {
                s11: &k11,
                s12: &k12,
                s22: &k22,
            };
            pair!(
                "ggx_d_projected",
                |i: usize| Ggx::new(projected(aa, ks[i])).d(h(i)),
                |o: &mut [$t]| batch::ggx_d_projected(&aa, kernels, &hx, &hy, &hz, o)
            );
        }
        // The samplers' pdfs (matrix form): the views and the cases' half vectors.
        {
            use filtered_ndf::$prec::NdfSampling;
            let (g, b) = (Ggx::new(mat), Beckmann::new(mat));
            pair!(
                "ggx_normal_pdf",
                |i: usize| g.normal_pdf(h(i)),
                |out: &mut [$t]| batch::ggx_normal_pdf(&mat, &hx, &hy, &hz, out)
            );
            pair!(
                "beckmann_normal_pdf",
                |i: usize| b.normal_pdf(h(i)),
                |out: &mut [$t]| batch::beckmann_normal_pdf(&mat, &hx, &hy, &hz, out)
            );
            pair!(
                "ggx_visible_normal_pdf",
                |i: usize| g.visible_normal_pdf(o(i), h(i)),
                |out: &mut [$t]| batch::ggx_visible_normal_pdf(&mat, vo, vh, out)
            );
            pair!(
                "beckmann_visible_normal_pdf",
                |i: usize| b.visible_normal_pdf(o(i), h(i)),
                |out: &mut [$t]| batch::beckmann_visible_normal_pdf(&mat, vo, vh, out)
            );
            pair!(
                "ggx_reflection_pdf",
                |i: usize| g.reflection_pdf_from_normal(o(i), h(i)),
                |out: &mut [$t]| batch::ggx_reflection_pdf_from_normal(&mat, vo, vh, out)
            );
            pair!(
                "beckmann_reflection_pdf",
                |i: usize| b.reflection_pdf_from_normal(o(i), h(i)),
                |out: &mut [$t]| batch::beckmann_reflection_pdf_from_normal(&mat, vo, vh, out)
            );
        }
        // Visible normals (matrix form) from the views and uniform pairs: three outputs, so
        // their own groups rather than `pair!`.
        {
            use filtered_ndf::$prec::NdfSampling;
            let (u1, u2): (Vec<$t>, Vec<$t>) = (0..N)
                .map(|_| (rng.uniform() as $t, rng.uniform() as $t))
                .unzip();
            let (mut o2, mut o3) = (out.clone(), out.clone());
            macro_rules! visible_sampler {
                ($name:expr, $lobe:expr, $batch:path) => {{
                    let lobe = $lobe;
                    let mut g = group($c, $name);
                    g.bench_function("scalar_loop", |b| {
                        b.iter(|| {
                            for i in 0..N {
                                let m = lobe
                                    .sample_visible_normal(o(black_box(i)), Vec2::new(u1[i], u2[i]))
                                    .unwrap_or(Vec3::ZERO);
                                (out[i], o2[i], o3[i]) = (m.x, m.y, m.z);
                            }
                            black_box((&mut out, &mut o2, &mut o3));
                        })
                    });
                    g.bench_function("batch", |b| {
                        b.iter(|| {
                            black_box($batch(&mat, vo, &u1, &u2, &mut out, &mut o2, &mut o3));
                            black_box((&mut out, &mut o2, &mut o3));
                        })
                    });
                    g.finish();
                }};
            }
            visible_sampler!(
                "ggx_sample_visible_normal",
                Ggx::new(mat),
                batch::ggx_sample_visible_normal
            );
            visible_sampler!(
                "beckmann_sample_visible_normal",
                Beckmann::new(mat),
                batch::beckmann_sample_visible_normal
            );
            // `D(m) m_z` sampling (matrix form) from the same uniform pairs.
            macro_rules! normal_sampler {
                ($name:expr, $lobe:expr, $batch:path) => {{
                    let lobe = $lobe;
                    let mut g = group($c, $name);
                    g.bench_function("scalar_loop", |b| {
                        b.iter(|| {
                            for i in 0..N {
                                let m = lobe.sample_normal(Vec2::new(u1[black_box(i)], u2[i]));
                                (out[i], o2[i], o3[i]) = (m.x, m.y, m.z);
                            }
                            black_box((&mut out, &mut o2, &mut o3));
                        })
                    });
                    g.bench_function("batch", |b| {
                        b.iter(|| {
                            black_box($batch(&mat, &u1, &u2, &mut out, &mut o2, &mut o3));
                            black_box((&mut out, &mut o2, &mut o3));
                        })
                    });
                    g.finish();
                }};
            }
            normal_sampler!("ggx_sample_normal", Ggx::new(mat), batch::ggx_sample_normal);
            normal_sampler!(
                "beckmann_sample_normal",
                Beckmann::new(mat),
                batch::beckmann_sample_normal
            );
        }
    }};
}

fn benches(c: &mut Criterion) {
    family!(c, f32, f32);
    family!(c, f64, f64);
    #[cfg(feature = "rayon")]
    parallel(c);
}

/// `batch::par_chunks` (feature `rayon`): filtered Beckmann over 65536 elements in chunks of
/// 4096 on pools of 1 and 2 threads (`batch_par/f32/threads_1`, `threads_2`), or of the sizes
/// listed in `FILTERED_NDF_BENCH_THREADS`.
#[cfg(feature = "rayon")]
fn parallel(c: &mut Criterion) {
    use filtered_ndf::f32::{AxisAligned, ClampRules, batch};
    const M: usize = 65536;
    let cases = common::realistic_cases(M, 0x9A7C);
    let col = |f: &dyn Fn(&common::Case) -> f64| -> Vec<f32> {
        cases.iter().map(|k| f(k) as f32).collect()
    };
    let (hx, hy, hz) = (col(&|k| k.h[0]), col(&|k| k.h[1]), col(&|k| k.h[2]));
    let (ux, uy) = (col(&|k| k.dh_u[0]), col(&|k| k.dh_u[1]));
    let (vx, vy) = (col(&|k| k.dh_v[0]), col(&|k| k.dh_v[1]));
    let aa = AxisAligned::new(0.1, 0.3).unwrap();
    let rules = ClampRules::default();
    let mut g = c.benchmark_group("batch_par/f32");
    g.throughput(Throughput::Elements(M as u64));
    let mut out = vec![0.0f32; M];
    // `FILTERED_NDF_BENCH_THREADS=1,2,4,8,16` measures larger pools (default: 1 and 2).
    let pools: Vec<usize> = std::env::var("FILTERED_NDF_BENCH_THREADS")
        .ok()
        .map(|v| v.split(',').filter_map(|t| t.trim().parse().ok()).collect())
        .filter(|v: &Vec<usize>| !v.is_empty())
        .unwrap_or_else(|| vec![1, 2]);
    for threads in pools {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        g.bench_function(format!("threads_{threads}"), |b| {
            b.iter(|| {
                pool.install(|| {
                    batch::par_chunks(&mut out, 4096, |s, o| {
                        let e = s + o.len();
                        let fp = batch::Footprints {
                            dh_u_x: &ux[s..e],
                            dh_u_y: &uy[s..e],
                            dh_v_x: &vx[s..e],
                            dh_v_y: &vy[s..e],
                        };
                        batch::beckmann_d_filtered(
                            &aa,
                            &rules,
                            0.5,
                            &hx[s..e],
                            &hy[s..e],
                            &hz[s..e],
                            fp,
                            o,
                        );
                    })
                });
                black_box(&out);
            })
        });
    }
    g.finish();
}

criterion_group!(batch_benches, benches);
criterion_main!(batch_benches);
