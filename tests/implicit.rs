//! The implicit-surface derivative toolbox (Tessari et al. 2020, eq. 20-21, 24-29) against
//! central finite differences in time of the exact ray-surface intersection (solved in
//! `common` by the roots of a quadratic, independently of the library).

mod common;

use common::{
    Body, Ellipsoid, Rng, RngExt, Scene, ellipsoid_scene, quadric_scene, sphere_scene, sym3,
};
use filtered_ndf::f64::temporal::implicit::{
    HitRates, LevelSetSample, MovingRay, Sym3, d_normalized, hit_distance_rate, hit_normal_rate,
    hit_rates, project,
};
use filtered_ndf::f64::temporal::quadric::{LocalQuadric, RigidMotion};
use glam::{DMat3, DVec3, Vec3};
use proptest::prelude::*;

/// Central-difference step in time. The scenes move by O(1) per unit time and view the
/// surface no more grazing than cos = 0.2, so the truncation error `h^2 |f'''| / 6` is below
/// ~1e-8 and the rounding error `1e-16 |s| / h` below ~1e-10.
const H: f64 = 1e-5;
/// Tolerance on `|analytic - fd| / (|fd| + 1e-2)`: two orders above the FD error bound above;
/// a wrong term in eq. 20/21/24 (e.g. a missing `s d_t d`, a sign of `omega x grad`) gives
/// errors of order 1.
const TOL: f64 = 1e-6;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / (b.abs() + 1e-2)
}

fn relv(a: DVec3, b: DVec3) -> f64 {
    (a - b).length() / (b.length() + 1e-2)
}

/// Runs `n` seeded scenes, compares the library's rates with FD, returns the worst errors.
fn sweep<B: Body>(
    name: &str,
    n: usize,
    mut make: impl FnMut(&mut Rng, bool) -> Scene<B>,
    sample: impl Fn(&Scene<B>, DVec3) -> LevelSetSample,
) -> (f64, f64) {
    let mut rng = Rng(0x7e55_a121 ^ name.len() as u64);
    let (mut worst_s, mut worst_n) = (0.0f64, 0.0f64);
    for i in 0..n {
        let scene = make(&mut rng, i % 4 != 0);
        let hit = scene.hit(0.0).expect("t0 hit exists by construction");
        assert!(
            (hit.s - scene.s_hint).abs() < 1e-9 * hit.s,
            "{name} #{i}: hit {} != {}",
            hit.s,
            scene.s_hint
        );
        let ray = scene.moving_ray();
        let rates = hit_rates(&sample(&scene, hit.x), &ray, hit.s);
        let (ds_fd, dn_fd) = scene.fd_rates(H).expect("hits near t0");
        let (es, en) = (rel(rates.ds_dt, ds_fd), relv(rates.dn_dt, dn_fd));
        assert!(
            es < TOL && en < TOL,
            "{name} #{i}: ds {} vs fd {ds_fd} ({es:e}); dN {:?} vs fd {dn_fd:?} ({en:e})",
            rates.ds_dt,
            rates.dn_dt
        );
        // The single-quantity entry points agree with the combined one.
        assert_eq!(
            hit_distance_rate(&sample(&scene, hit.x), &ray, hit.s),
            rates.ds_dt
        );
        assert_eq!(
            hit_normal_rate(&sample(&scene, hit.x), &ray, hit.s),
            rates.dn_dt
        );
        // dN/dt is orthogonal to N (eq. 27-28 project out the normal).
        assert!(rates.dn_dt.dot(hit.n).abs() < 1e-12 * (1.0 + rates.dn_dt.length()));
        worst_s = worst_s.max(es);
        worst_n = worst_n.max(en);
    }
    println!("{name}: {n} scenes, worst relative FD gap: ds/dt {worst_s:.2e}, dN/dt {worst_n:.2e}");
    (worst_s, worst_n)
}

#[test]
fn translating_sphere_matches_finite_differences() {
    // The level set sample is written out by hand (phi = |x - c(t)|^2 - r^2):
    // grad = 2 (x - c), H = 2 I, d_t phi = -2 (x - c).v, d_t grad = -2 v.
    sweep("translating sphere", 300, sphere_scene, |s, x| {
        let g = 2.0 * (x - s.body.center);
        LevelSetSample {
            grad: g,
            hess: Sym3::IDENTITY.scale(2.0),
            dphi_dt: -g.dot(s.velocity),
            dgrad_dt: -2.0 * s.velocity,
        }
    });
}

#[test]
fn rotating_ellipsoid_matches_finite_differences() {
    sweep("rotating ellipsoid", 300, ellipsoid_scene, |s, x| {
        let motion = RigidMotion {
            center: s.center,
            velocity: s.velocity,
            angular_velocity: s.omega,
        };
        motion.level_set_sample(x, s.body.grad(x), sym3(s.body.hess(x)))
    });
}

#[test]
fn moving_quadric_matches_finite_differences() {
    sweep("moving quadric", 300, quadric_scene, |s, x| {
        let q = LocalQuadric::new(s.body.p, s.body.n, s.body.e1, s.body.k1, s.body.k2).unwrap();
        let motion = RigidMotion {
            center: s.center,
            velocity: s.velocity,
            angular_velocity: s.omega,
        };
        q.level_set_sample(x, &motion)
    });
}

#[test]
fn rigid_motion_sample_matches_the_hand_derivation() {
    // The test's own derivation of eq. 24 at t0 (common::Scene::sample_by_hand) and the
    // library's agree to rounding.
    let mut rng = Rng(99);
    for _ in 0..50 {
        let s = ellipsoid_scene(&mut rng, true);
        let x = s.hit(0.0).unwrap().x;
        let m = RigidMotion {
            center: s.center,
            velocity: s.velocity,
            angular_velocity: s.omega,
        };
        let a = m.level_set_sample(x, s.body.grad(x), sym3(s.body.hess(x)));
        let b = s.sample_by_hand(x);
        assert!((a.dphi_dt - b.dphi_dt).abs() < 1e-12 * (1.0 + b.dphi_dt.abs()));
        assert!((a.dgrad_dt - b.dgrad_dt).length() < 1e-12 * (1.0 + b.dgrad_dt.length()));
    }
}

#[test]
fn rotating_sphere_about_its_centre_shows_no_normal_change() {
    // A sphere spinning about its own centre is the same set at every time: eq. 24 must give
    // d_t phi = 0 and d_t grad = 0 exactly in exact arithmetic, so dN/dt = 0 for a fixed ray.
    let c = DVec3::new(0.3, -0.2, 0.1);
    let body = Ellipsoid {
        center: c,
        axes: DVec3::ONE,
        orient: DMat3::IDENTITY,
    };
    let x = c + DVec3::new(0.0, 0.6, 0.8);
    let m = RigidMotion {
        center: c,
        velocity: DVec3::ZERO,
        angular_velocity: DVec3::new(0.5, 2.0, -1.0),
    };
    let smp = m.level_set_sample(x, body.grad(x), sym3(body.hess(x)));
    let ray = MovingRay::fixed(
        x + DVec3::new(0.0, 1.0, 2.0),
        DVec3::new(0.0, -1.0, -2.0) / 2.0,
    );
    let r = hit_rates(&smp, &ray, 2.0);
    assert!(r.ds_dt.abs() < 1e-14 && r.dn_dt.length() < 1e-14, "{r:?}");
}

#[test]
fn shape_operator_is_the_spatial_derivative_of_the_normal() {
    // eq. 29-30: S w = (N(x + h w) - N(x - h w)) / 2h for tangent w, S N = 0; N = grad/|grad|
    // of the static ellipsoid. FD error ~ h^2 |N'''| ~ 1e-10 with h = 1e-5 on axes >= 0.3.
    let mut rng = Rng(7);
    for _ in 0..100 {
        let s = ellipsoid_scene(&mut rng, false);
        let x = s.hit(0.0).unwrap().x;
        let smp = LevelSetSample {
            grad: s.body.grad(x),
            hess: sym3(s.body.hess(x)),
            ..Default::default()
        };
        let n = smp.normal();
        let sop = smp.shape_operator();
        let (t, b) = n.any_orthonormal_pair();
        for w in [t, b, (t + 2.0 * b).normalize()] {
            let nf = |y: DVec3| s.body.grad(y).normalize();
            let fd = (nf(x + H * w) - nf(x - H * w)) / (2.0 * H);
            let e = (sop.mul_vec3(w) - fd).length() / (fd.length() + 1e-2);
            assert!(e < 1e-7, "S w {:?} vs fd {fd:?}", sop.mul_vec3(w));
            // eq. 28 agrees with eq. 29 on tangent vectors.
            assert!(
                (smp.normal_gradient_apply(w) - sop.mul_vec3(w)).length()
                    < 1e-12 * (1.0 + fd.length())
            );
        }
        assert!(
            sop.mul_vec3(n).length() < 1e-12 * (1.0 + sop.xx.abs() + sop.yy.abs() + sop.zz.abs())
        );
    }
    // The local quadric at P: S = k1 e1 e1^T + k2 e2 e2^T exactly (principal curvatures).
    let q = LocalQuadric::new(
        DVec3::ONE,
        DVec3::new(0.0, 0.0, 2.0),
        DVec3::new(1.0, 1.0, 0.3),
        1.5,
        -0.5,
    )
    .unwrap();
    let (p, n, e1, e2) = q.frame();
    let smp = LevelSetSample {
        grad: q.gradient(p),
        hess: q.hessian(),
        ..Default::default()
    };
    let sop = smp.shape_operator();
    assert!((sop.mul_vec3(e1) - 1.5 * e1).length() < 1e-14);
    assert!((sop.mul_vec3(e2) + 0.5 * e2).length() < 1e-14);
    assert!(sop.mul_vec3(n).length() < 1e-14);
    assert!(q.value(q.point(0.3, -0.7)).abs() < 1e-14);
}

#[test]
fn derivative_of_a_normalised_vector_matches_finite_differences() {
    // eq. 26 against d/dt normalize(v + t dv); FD error ~ h^2 |v|^-3 |dv|^3 ~ 1e-10.
    let mut rng = Rng(11);
    for _ in 0..200 {
        let v = rng.unit() * rng.range(0.2, 5.0);
        let dv = rng.vec(3.0);
        let fd = ((v + H * dv).normalize() - (v - H * dv).normalize()) / (2.0 * H);
        let a = d_normalized(v, dv);
        assert!(
            (a - fd).length() < 1e-8 * (1.0 + fd.length()),
            "{a:?} vs {fd:?}"
        );
        // Projection (eq. 25): kills v, keeps the orthogonal part, idempotent.
        let w = rng.vec(2.0);
        let pw = project(v, w);
        assert!(pw.dot(v).abs() < 1e-12 * v.length() * (1.0 + w.length()));
        assert!((project(v, pw) - pw).length() < 1e-14 * (1.0 + w.length()));
    }
}

#[test]
fn static_scene_has_zero_rates() {
    let mut rng = Rng(5);
    for _ in 0..20 {
        let s = ellipsoid_scene(&mut rng, false);
        let x = s.hit(0.0).unwrap().x;
        let smp = RigidMotion::STATIC.level_set_sample(x, s.body.grad(x), sym3(s.body.hess(x)));
        let r = hit_rates(&smp, &MovingRay::fixed(s.o0, s.d0), s.s_hint);
        assert_eq!(r.ds_dt, 0.0);
        assert_eq!(r.dn_dt, DVec3::ZERO);
    }
}

#[test]
fn degenerate_inputs_give_zero_rates() {
    let good = LevelSetSample {
        grad: DVec3::new(0.0, 0.0, 2.0),
        hess: Sym3::IDENTITY.scale(2.0),
        dphi_dt: 0.5,
        dgrad_dt: DVec3::new(0.1, 0.2, 0.0),
    };
    let ray = MovingRay {
        origin: DVec3::new(0.0, 0.0, 3.0),
        dir: DVec3::new(0.0, 0.0, -1.0),
        d_origin: DVec3::X,
        d_dir: DVec3::Y * 0.1,
    };
    assert_ne!(hit_rates(&good, &ray, 2.0), HitRates::ZERO);
    // Zero gradient.
    let zero_grad = LevelSetSample {
        grad: DVec3::ZERO,
        ..good
    };
    assert_eq!(hit_rates(&zero_grad, &ray, 2.0), HitRates::ZERO);
    assert_eq!(zero_grad.normal(), DVec3::ZERO);
    assert_eq!(zero_grad.normal_partial_t(), DVec3::ZERO);
    assert_eq!(zero_grad.shape_operator(), Sym3::ZERO);
    assert_eq!(d_normalized(DVec3::ZERO, DVec3::ONE), DVec3::ZERO);
    assert_eq!(project(DVec3::ZERO, DVec3::ONE), DVec3::ONE);
    // Ray tangent to the surface, zero direction.
    let grazing = MovingRay {
        dir: DVec3::X,
        ..ray
    };
    assert_eq!(hit_rates(&good, &grazing, 2.0), HitRates::ZERO);
    let zero_dir = MovingRay {
        dir: DVec3::ZERO,
        ..ray
    };
    assert_eq!(hit_rates(&good, &zero_dir, 2.0), HitRates::ZERO);
    // NaN / inf anywhere.
    for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
        let v = DVec3::new(bad, 0.0, 1.0);
        let cases = [
            hit_rates(&LevelSetSample { grad: v, ..good }, &ray, 2.0),
            hit_rates(
                &LevelSetSample {
                    dgrad_dt: v,
                    ..good
                },
                &ray,
                2.0,
            ),
            hit_rates(
                &LevelSetSample {
                    dphi_dt: bad,
                    ..good
                },
                &ray,
                2.0,
            ),
            hit_rates(
                &LevelSetSample {
                    hess: Sym3 {
                        xy: bad,
                        ..good.hess
                    },
                    ..good
                },
                &ray,
                2.0,
            ),
            hit_rates(&good, &MovingRay { origin: v, ..ray }, 2.0),
            hit_rates(&good, &MovingRay { dir: v, ..ray }, 2.0),
            hit_rates(&good, &MovingRay { d_origin: v, ..ray }, 2.0),
            hit_rates(&good, &MovingRay { d_dir: v, ..ray }, 2.0),
            hit_rates(&good, &ray, bad),
        ];
        for c in cases {
            assert_eq!(c, HitRates::ZERO);
        }
        assert!(d_normalized(v, DVec3::ONE).is_finite());
        assert!(d_normalized(DVec3::ONE, v).is_finite());
        assert!(project(v, DVec3::ONE).is_finite());
        assert!(project(DVec3::ONE, v).is_finite());
        assert!(LevelSetSample { grad: v, ..good }.normal().is_finite());
        let s = LevelSetSample {
            hess: Sym3 {
                zz: bad,
                ..good.hess
            },
            ..good
        }
        .shape_operator();
        assert!(s.is_finite());
    }
    // Huge but finite gradients do not overflow the norm.
    let huge = LevelSetSample {
        grad: DVec3::splat(1e300),
        hess: Sym3::IDENTITY,
        ..good
    };
    assert!((huge.normal().length() - 1.0).abs() < 1e-15);
    let r = hit_rates(&huge, &ray, 2.0);
    assert!(r.ds_dt.is_finite() && r.dn_dt.is_finite());
    // Local quadric: bad frames are refused.
    assert!(LocalQuadric::new(DVec3::ZERO, DVec3::Z, DVec3::Z, 1.0, 1.0).is_none());
    assert!(LocalQuadric::new(DVec3::ZERO, DVec3::ZERO, DVec3::X, 1.0, 1.0).is_none());
    assert!(LocalQuadric::new(DVec3::ZERO, DVec3::Z, DVec3::X, f64::NAN, 1.0).is_none());
}

fn v3(v: DVec3) -> Vec3 {
    v.as_vec3()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The f32 build agrees with f64 on well-conditioned scenes (rel. 1e-3: f32 rounding of
    /// coordinates of size ~5 with intermediate cancellation in eq. 20).
    #[test]
    fn f32_agrees_with_f64(seed in any::<u64>()) {
        use filtered_ndf::f32::temporal::implicit as i32;
        let mut rng = Rng(seed);
        let s = quadric_scene(&mut rng, true);
        let x = s.hit(0.0).unwrap().x;
        let smp = s.sample_by_hand(x);
        let r64 = hit_rates(&smp, &s.moving_ray(), s.s_hint);
        let h = smp.hess;
        let smp32 = i32::LevelSetSample {
            grad: v3(smp.grad),
            hess: i32::Sym3::new(h.xx as f32, h.xy as f32, h.xz as f32, h.yy as f32, h.yz as f32, h.zz as f32),
            dphi_dt: smp.dphi_dt as f32,
            dgrad_dt: v3(smp.dgrad_dt),
        };
        let ray = s.moving_ray();
        let ray32 = i32::MovingRay { origin: v3(ray.origin), dir: v3(ray.dir), d_origin: v3(ray.d_origin), d_dir: v3(ray.d_dir) };
        let r32 = i32::hit_rates(&smp32, &ray32, s.s_hint as f32);
        let scale = 1.0 + r64.dn_dt.length() + r64.ds_dt.abs();
        prop_assert!((r32.ds_dt as f64 - r64.ds_dt).abs() < 1e-3 * scale);
        prop_assert!((r32.dn_dt.as_dvec3() - r64.dn_dt).length() < 1e-3 * scale);
    }

    /// Arbitrary finite input never produces NaN or infinity.
    #[test]
    fn finite_input_gives_finite_output(
        g in prop::array::uniform3(-1e30f32..1e30),
        dg in prop::array::uniform3(-1e30f32..1e30),
        d in prop::array::uniform3(-1e30f32..1e30),
        hs in prop::array::uniform6(-1e30f32..1e30),
        pt in -1e30f32..1e30, s in -1e30f32..1e30,
    ) {
        use filtered_ndf::f32::temporal::implicit as i32;
        let smp = i32::LevelSetSample {
            grad: Vec3::from(g),
            hess: i32::Sym3::new(hs[0], hs[1], hs[2], hs[3], hs[4], hs[5]),
            dphi_dt: pt,
            dgrad_dt: Vec3::from(dg),
        };
        let ray = i32::MovingRay { origin: Vec3::from(dg), dir: Vec3::from(d), d_origin: Vec3::from(g), d_dir: Vec3::from(d) };
        let r = i32::hit_rates(&smp, &ray, s);
        prop_assert!(r.ds_dt.is_finite() && r.dn_dt.is_finite() && r.dx_dt.is_finite());
        prop_assert!(smp.shape_operator().is_finite());
        prop_assert!(smp.normal_partial_t().is_finite());
    }
}
