//! One benchmark group per kernel family, each in f32 and f64, over the seeded realistic
//! cases of `filtered_ndf::testing::shading` (the trade table measures error on the same cases):
//! filtered Beckmann vs unfiltered Beckmann, filtered GGX (TK19 matrix, TK21 projected) vs
//! unfiltered GGX, the GGX proxy (exact and simple), the isotropic deferred variants and engine presets, the Jacobians, the
//! footprint-to-kernel conversions, and the supersampling baseline (unfiltered GGX averaged
//! over N = 1..256 jittered points of the same Gaussian footprint).
//!
//! `cargo bench --bench filtered` (add `-- --quick` for a short run). Figures are per
//! evaluation (`Throughput::Elements`); compare ratios within one run.

use filtered_ndf::testing::shading as common;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

const N: usize = 1024;

macro_rules! families {
    ($c:expr, $prec:ident, $t:ty) => {{
        use filtered_ndf::math::Real;
        use filtered_ndf::$prec::{
            AxisAligned, Beckmann, ClampRules, Footprint, Ggx, Ndf, RoughnessMatrix, Vec2, Vec3,
            filter, filter::deferred, filter::presets, filter::proxy, footprint::jacobian,
            footprint::slope,
        };
        type Wall<'a> = BenchmarkGroup<'a, criterion::measurement::WallTime>;
        let c = |x: f64| <$t as Real>::from_f64(x);
        let cases = common::realistic_cases(N, 0x5EED);
        struct In {
            r: AxisAligned,
            h: Vec3,
            fp: Footprint,
            dn_u: Vec3,
            dn_v: Vec3,
        }
        let ins: Vec<In> = cases
            .iter()
            .map(|k| In {
                r: AxisAligned::new_clamped(c(k.alpha[0]), c(k.alpha[1])),
                h: Vec3::new(c(k.h[0]), c(k.h[1]), c(k.h[2])),
                fp: Footprint::from_slope_derivatives(
                    Vec2::new(c(k.dh_u[0]), c(k.dh_u[1])),
                    Vec2::new(c(k.dh_v[0]), c(k.dh_v[1])),
                ),
                dn_u: Vec3::new(c(k.dh_u[0]), c(k.dh_u[1]), 0.0),
                dn_v: Vec3::new(c(k.dh_v[0]), c(k.dh_v[1]), 0.0),
            })
            .collect();
        // The unfiltered matrix form: the material's lobe rotated by a seeded angle (a
        // rotated anisotropic material, the general case of the form, as the filtered lobe
        // is), and the diagonal matrix of `From<AxisAligned>` (its cheapest case).
        let mut rot = common::Rng(0x707);
        let mats: Vec<RoughnessMatrix> = ins
            .iter()
            .map(|i| {
                let a = i.r.alpha();
                let (l1, l2) = (a.x * a.x, a.y * a.y);
                let t = std::f64::consts::TAU * rot.uniform();
                let (c, s) = (c(t.cos()), c(t.sin()));
                RoughnessMatrix::new(
                    c * c * l1 + s * s * l2,
                    c * s * (l1 - l2),
                    s * s * l1 + c * c * l2,
                )
                .unwrap()
            })
            .collect();
        let diags: Vec<RoughnessMatrix> = ins.iter().map(|i| i.r.into()).collect();
        let kernels: Vec<_> = ins.iter().map(|i| i.fp.covariance(0.5)).collect();
        fn group<'a>(c: &'a mut Criterion, name: &str) -> Wall<'a> {
            let mut g = c.benchmark_group(format!("{}/{}", name, stringify!($prec)));
            g.throughput(Throughput::Elements(N as u64));
            g
        }
        fn run<T>(g: &mut Wall<'_>, name: &str, mut f: impl FnMut(usize) -> T) {
            g.bench_function(name, |b| {
                b.iter(|| {
                    for i in 0..N {
                        black_box(f(black_box(i)));
                    }
                })
            });
        }

        let mut g = group($c, "beckmann");
        run(&mut g, "unfiltered_axis_aligned", |i| {
            Beckmann::new(ins[i].r).d(ins[i].h)
        });
        run(&mut g, "unfiltered_matrix", |i| {
            Beckmann::new(mats[i]).d(ins[i].h)
        });
        run(&mut g, "unfiltered_matrix_diagonal", |i| {
            Beckmann::new(diags[i]).d(ins[i].h)
        });
        // The filtered lobe from the material and the pixel kernel (KHPL16 eq. 15, TK19 tau).
        run(&mut g, "filtered_matrix", |i| {
            Beckmann::new(filter::gaussian(ins[i].r, kernels[i])).d(ins[i].h)
        });
        // The same with the kernel formed from the footprint (+ `Footprint::covariance`).
        run(&mut g, "filtered_matrix_from_footprint", |i| {
            let a = filter::gaussian(ins[i].r, ins[i].fp.covariance(0.5));
            Beckmann::new(a).d(ins[i].h)
        });
        g.finish();

        let mut g = group($c, "ggx_matrix");
        run(&mut g, "unfiltered_axis_aligned", |i| {
            Ggx::new(ins[i].r).d(ins[i].h)
        });
        run(&mut g, "unfiltered_matrix", |i| {
            Ggx::new(mats[i]).d(ins[i].h)
        });
        run(&mut g, "tk19_a_plus_2sigma", |i| {
            let a = filter::gaussian(ins[i].r, ins[i].fp.covariance(0.5));
            Ggx::new(a).d(ins[i].h)
        });
        run(&mut g, "tk21_projected", |i| {
            let a = filter::projected(ins[i].r, ins[i].fp.covariance(0.5));
            Ggx::new(a).d(ins[i].h)
        });
        g.finish();

        let mut g = group($c, "ggx_proxy");
        run(&mut g, "exact_eq19", |i| {
            let he = ins[i].fp.bounding_rect().half_extent;
            Ggx::new(proxy::proxy(ins[i].r, he)).d(ins[i].h)
        });
        run(&mut g, "simple_eq20", |i| {
            let he = ins[i].fp.bounding_rect().half_extent;
            Ggx::new(proxy::proxy_simple(ins[i].r, he)).d(ins[i].h)
        });
        g.finish();

        let mut g = group($c, "isotropic");
        for (name, bw) in [
            ("tk19_max", deferred::Bandwidth::Max),
            ("tk19_trace", deferred::Bandwidth::Trace),
            ("tk19_average", deferred::Bandwidth::Average),
        ] {
            run(&mut g, name, |i| {
                let s = deferred::normal_difference_covariance(
                    ins[i].dn_u,
                    ins[i].dn_v,
                    filtered_ndf::$prec::kernel::SIGMA_PIXEL,
                );
                deferred::filtered_alpha(ins[i].r.alpha().x, &s, bw, deferred::KAPPA)
            });
        }
        for (name, p) in presets::ALL {
            run(&mut g, &format!("preset_{name}"), |i| {
                p.apply(ins[i].r.alpha().x, ins[i].dn_u, ins[i].dn_v)
            });
        }
        g.finish();

        let mut g = group($c, "jacobians");
        run(&mut g, "sphere_to_slope", |i| {
            jacobian::sphere_to_slope(ins[i].h)
        });
        run(&mut g, "sphere_to_projected", |i| {
            jacobian::sphere_to_projected(ins[i].h)
        });
        run(&mut g, "projected_to_slope", |i| {
            jacobian::projected_to_slope(ins[i].h)
        });
        g.finish();

        let mut g = group($c, "footprint_kernel");
        let rules = ClampRules::default();
        run(&mut g, "covariance", |i| ins[i].fp.covariance(0.5));
        run(&mut g, "bounding_rect", |i| ins[i].fp.bounding_rect());
        run(&mut g, "clamped_kernel", |i| {
            rules.kernel(rules.footprint(ins[i].fp).covariance(0.5))
        });
        g.finish();

        // What a user does without this crate: average the unfiltered NDF over N jittered
        // points of the same Gaussian footprint (standard normal jitter, seeded).
        let mut g = group($c, "supersampling_ggx");
        let mut rng = common::Rng(0x1177);
        let jitter: Vec<($t, $t)> = (0..256)
            .map(|_| (c(0.5 * rng.normal()), c(0.5 * rng.normal())))
            .collect();
        for n in [1usize, 4, 16, 64, 256] {
            let js = &jitter[..n];
            run(&mut g, &format!("n{n}"), |i| {
                let s0 = slope::slope_from_sphere(ins[i].h);
                let ggx = Ggx::new(ins[i].r);
                let mut acc: $t = 0.0;
                for &(a, b) in js {
                    let s = s0 + ins[i].fp.dh_u * a + ins[i].fp.dh_v * b;
                    acc += ggx.d(slope::sphere_from_slope(s));
                }
                acc / c(n as f64)
            });
        }
        g.finish();
    }};
}

fn benches(c: &mut Criterion) {
    families!(c, f32, f32);
    families!(c, f64, f64);
}

criterion_group!(filtered, benches);
criterion_main!(filtered);
