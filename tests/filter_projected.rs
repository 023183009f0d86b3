//! Projected-space filtering (Tokuyoshi and Kaplanyan 2021): the identity behind it, the
//! round trip, positive definiteness, monotonicity, and the roughness limit.

use filtered_ndf::f32 as s;
use filtered_ndf::f64 as d;
use filtered_ndf::f64::Ndf as _;
use glam::{DMat2, DVec2, Vec2};
use proptest::prelude::*;

fn mat(r: d::RoughnessMatrix) -> DMat2 {
    r.to_mat2()
}

fn rotated(a1: f64, a2: f64, phi: f64) -> (f64, f64, f64) {
    let (c, sn) = (phi.cos(), phi.sin());
    (
        c * c * a1 + sn * sn * a2,
        c * sn * (a1 - a2),
        sn * sn * a1 + c * c * a2,
    )
}

/// Smallest eigenvalue of a symmetric 2x2.
fn min_eig(m: DMat2) -> f64 {
    let (a, b, c) = (m.x_axis.x, m.x_axis.y, m.y_axis.y);
    0.5 * (a + c) - (0.25 * (a - c) * (a - c) + b * b).sqrt()
}

#[test]
fn ggx_on_the_projected_disk_is_ggx_with_matrix_p() {
    // D(h) = P22_P(p) / sqrt(det(I - A)) with P = A (I - A)^-1 (glam inverse here, not the
    // crate's Cayley-Hamilton form): the reason the kernel is added to P.
    for &(a1, a2, phi) in &[(0.01, 0.04, 0.3), (0.25, 0.5, -1.0), (1e-6, 1e-4, 2.0)] {
        let (a11, a12, a22) = rotated(a1, a2, phi);
        let a = d::RoughnessMatrix::new(a11, a12, a22).unwrap();
        let am = mat(a);
        let pm = am * (DMat2::IDENTITY - am).inverse();
        let p = d::RoughnessMatrix::from_mat2(DMat2::from_cols(
            pm.x_axis,
            DVec2::new(pm.x_axis.y, pm.y_axis.y),
        ))
        .unwrap();
        let jac = (DMat2::IDENTITY - am).determinant().sqrt();
        for &(x, y) in &[(0.0, 0.0), (0.05, -0.02), (0.3, 0.4), (-0.7, 0.1)] {
            let pp = DVec2::new(x, y) * a1.sqrt().max(0.01);
            let h = d::footprint::slope::sphere_from_projected(pp);
            let lhs = d::Ggx::new(a).d(h);
            let rhs = d::Ggx::new(p).p22(pp) / jac;
            // 1e-9: f64 rounding amplified by the 1/alpha^2-scaled quadratic forms.
            assert!(
                (lhs - rhs).abs() <= 1e-9 * lhs,
                "{a:?} p={pp}: {lhs} vs {rhs}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn matches_the_matrix_formula_and_is_spd_and_monotone(
        l1 in -8.0f64..-0.01, l2 in -8.0f64..-0.01, phi in 0.0f64..3.2,
        u in prop::array::uniform2(-0.3f64..0.3), v in prop::array::uniform2(-0.3f64..0.3),
    ) {
        // Eigenvalues of A log-uniform in [1e-8, 0.977].
        let (a11, a12, a22) = rotated(10f64.powf(l1 / 2.0).powi(2).min(0.98), 10f64.powf(l2 / 2.0).powi(2).min(0.98), phi);
        let a = d::RoughnessMatrix::new(a11, a12, a22).unwrap();
        let k = d::Footprint::from_slope_derivatives(DVec2::from(u), DVec2::from(v)).covariance(0.5);
        let f = d::filter::projected(a, k);
        // Independent evaluation: P = A (I-A)^-1, P' = P + 2 Sigma, A' = P' (I + P')^-1.
        let am = mat(a);
        let pm = am * (DMat2::IDENTITY - am).inverse();
        let km = DMat2::from_cols(DVec2::new(k.s11, k.s12), DVec2::new(k.s12, k.s22));
        let qm = pm + km * 2.0;
        let expect = qm * (DMat2::IDENTITY + qm).inverse();
        let got = mat(f);
        let scale = expect.x_axis.x.abs().max(expect.y_axis.y.abs());
        // 1e-9 of the largest entry: the explicit inverse of I - A loses ~1/(1 - lambda) <= 50
        // in relative accuracy; the Cayley-Hamilton form does not.
        let diff = (got - expect).abs();
        prop_assert!(diff.x_axis.max_element().max(diff.y_axis.max_element()) <= 1e-9 * scale,
            "{got:?} vs {expect:?}");
        // Symmetric by construction, positive definite, and A' - A >= 0 (operator monotone;
        // -1e-12 of the scale for rounding).
        prop_assert!(f.entries().0 > 0.0 && min_eig(got) > 0.0);
        prop_assert!(min_eig(got - am) >= -1e-12 * scale);
    }
}

#[test]
fn zero_kernel_round_trips_in_f32() {
    // Sigma = 0 gives A back. Over alpha in [1e-4, 0.99]: relative error of each entry against
    // A, in f32. `projected` computes in f64 and rounds once (its docs): the f64 round trip is
    // within a handful of f64 roundings times its condition 1 / (1 - lambda_max) (at most
    // 100), 64 eps_64 cond, and the rounding to f32 adds at most half an ulp, 2^-24, so A
    // (exact in f32) comes back unless the f64 error crosses a rounding boundary.
    let mut worst = 0.0f64;
    for i in 0..=40 {
        let alpha = 10f32.powf(-4.0 + 4.0 * i as f32 / 40.0).min(0.99);
        for &(ratio, phi) in &[(1.0f32, 0.0f32), (0.3, 0.7), (0.01, -1.2)] {
            let (a1, a2) = (alpha * alpha, (alpha * ratio).powi(2));
            let (c, sn) = (phi.cos(), phi.sin());
            let (a11, a12, a22) = (
                c * c * a1 + sn * sn * a2,
                c * sn * (a1 - a2),
                sn * sn * a1 + c * c * a2,
            );
            let Ok(a) = s::RoughnessMatrix::new(a11, a12, a22) else {
                continue;
            };
            let f = s::filter::projected(a, s::Covariance::ZERO);
            let (b11, b12, b22) = f.entries();
            let cond = 1.0 / (1.0 - a1 as f64);
            let rel = ((b11 - a11).abs() as f64 / a11 as f64)
                .max((b22 - a22).abs() as f64 / a22 as f64)
                .max((b12 - a12).abs() as f64 / (a11 * a22).sqrt() as f64);
            worst = worst.max(rel / cond);
            let bound = 64.0 * f64::EPSILON * cond + (0.5f64).powi(24);
            assert!(rel <= bound, "alpha={alpha} ratio={ratio}: {rel}");
        }
    }
    println!("projected round trip, f32: worst relative error / condition = {worst:.2e}");
}

#[test]
fn beyond_the_roughness_limit() {
    // Eigenvalues at and above PROJECTED_EIGEN_MAX = 0.99: the clamped part is filtered, the
    // excess is added back. Continuous across the limit, never sharper than A, finite.
    let k = d::Covariance::new(1e-3, 2e-4, 5e-4);
    let at = |l: f64| d::filter::projected(d::RoughnessMatrix::new(l, 0.0, 0.01).unwrap(), k);
    let below = mat(at(0.99 - 1e-9));
    let above = mat(at(0.99 + 1e-9));
    // Lipschitz across the limit: a 2e-9 step of A moves A' by at most ~2e-9 (x some O(1)).
    assert!((below - above).abs().x_axis.max_element() < 1e-7);
    assert!((below - above).abs().y_axis.max_element() < 1e-7);
    for l in [0.995, 1.0, 1.5, 100.0, 1e8] {
        let a = d::RoughnessMatrix::new(l, 0.0, 0.01).unwrap();
        let f = d::filter::projected(a, k);
        let g = mat(f);
        assert!(g.is_finite());
        assert!(min_eig(g - mat(a)) >= -1e-12 * l, "l={l}: {g:?}");
        // The rough direction keeps exactly its excess over the limit plus a filtered 0.99.
        assert!(g.x_axis.x >= l, "l={l}");
        // The smooth direction is filtered as below the limit.
        assert!(g.y_axis.y > 0.01);
    }
    // Isotropic alpha >= 1 (both eigenvalues above the limit).
    let f = d::filter::projected(d::Isotropic::new(1.2).unwrap(), k);
    assert!(min_eig(mat(f) - DMat2::from_diagonal(DVec2::splat(1.44))) >= -1e-12);
}

#[test]
fn bad_kernels_give_finite_spd_results() {
    let a = s::AxisAligned::new(0.01, 0.02).unwrap();
    let peak = s::Ggx::new(a).d(glam::Vec3::Z);
    for k in [
        s::Covariance::new(f32::NAN, 0.0, 0.0),
        s::Covariance::new(f32::INFINITY, 0.0, 1.0),
        s::Covariance::new(-1.0, 5.0, -2.0),
        s::Covariance::new(1e30, 1e30, 1e30),
        s::Covariance::ZERO,
        s::Footprint::from_slope_derivatives(Vec2::splat(1e3), Vec2::new(-1e3, 1e3))
            .covariance(0.5),
    ] {
        for f in [s::filter::projected(a, k), s::filter::gaussian(a, k)] {
            let (a11, a12, a22) = f.entries();
            assert!(
                a11.is_finite() && a12.is_finite() && a22.is_finite(),
                "{k:?}: {f:?}"
            );
            let g = s::Ggx::new(f);
            for h in [glam::Vec3::Z, glam::Vec3::new(0.6, 0.0, 0.8), glam::Vec3::X] {
                let v = g.d(h);
                assert!(v.is_finite() && v >= 0.0 && v <= peak, "{k:?} h={h}: {v}");
            }
        }
    }
}

use filtered_ndf::f32::{Ndf as _, Roughness as _};

/// Whether an `f32` kernel is positive semi-definite exactly (products of `f32` numbers are
/// exact in `f64`): then `Covariance::sanitized` keeps it unchanged in both precisions.
fn psd32(k: (f32, f32, f32)) -> bool {
    let (a, b, c) = (f64::from(k.0), f64::from(k.1), f64::from(k.2));
    a >= 0.0 && c >= 0.0 && b * b <= a * c
}

/// One case of the f32-against-f64 tests: a lobe of roughness `alpha` in [1e-4, 0.99] with
/// anisotropy up to 100 at a seeded angle and a kernel 1e-2 to 1e2 alpha wide, rounded to f32
/// and given to both precisions identically (`None` where the f32 matrix is rejected or the
/// rounded kernel is not exactly positive semi-definite).
#[allow(clippy::type_complexity)]
fn f32_case(
    next: &mut impl FnMut() -> f64,
) -> Option<(
    d::RoughnessMatrix,
    s::RoughnessMatrix,
    d::Covariance,
    s::Covariance,
)> {
    let alpha = 10f64.powf(-4.0 + 3.998 * next());
    let aniso = 10f64.powf(2.0 * next());
    let (a11, a12, a22) = rotated(alpha * alpha, (alpha / aniso).powi(2), 3.2 * next());
    let kk = (alpha * 10f64.powf(-2.0 + 4.0 * next())).powi(2);
    let (k11, k12, k22) = rotated(kk, kk * next(), 3.2 * next());
    let (a11, a12, a22) = (a11 as f32, a12 as f32, a22 as f32);
    let kf = (k11 as f32, k12 as f32, k22 as f32);
    let ad = d::RoughnessMatrix::new(a11.into(), a12.into(), a22.into()).ok()?;
    let af = s::RoughnessMatrix::new(a11, a12, a22).ok()?;
    if !psd32(kf) {
        return None;
    }
    let kd = d::Covariance::new(kf.0.into(), kf.1.into(), kf.2.into());
    let ks = s::Covariance::new(kf.0, kf.1, kf.2);
    Some((ad, af, kd, ks))
}

#[test]
fn f32_entries_are_the_f64_entries_rounded_once() {
    // Both filters in f32 against the same filters in f64 on identical inputs (entries and
    // kernels rounded to f32 first), over a seeded log-uniform sample of alpha in
    // [1e-4, 0.99], anisotropy up to 100 and kernels from 1e-2 to 1e2 alpha wide.
    //
    // Tolerance, per entry and relative to the entry itself: gaussian's `a + 2 k` is one f32
    // rounding of a sum that f64 forms exactly or within one f64 rounding; projected computes
    // in f64 in both precisions and rounds each entry once: `eps_f32 / 2 + eps_f64` for both
    // (the clamps `max(a11)` commute with the rounding). Computing the projected map in f32
    // instead (`(I - A)^-1` amplifies rounding by up to `1 / (1 - lambda_max) = 100`) misses
    // this by orders of magnitude.
    let mut rng = filtered_ndf::testing::rng::SplitMix64(0x1234_5678);
    let mut next = || rng.uniform();
    let tol = 0.5 * f64::from(f32::EPSILON) + f64::EPSILON;
    let (mut worst_g, mut worst_p, mut n) = (0.0f64, 0.0f64, 0);
    for _ in 0..4000 {
        let Some((ad, af, kd, ks)) = f32_case(&mut next) else {
            continue;
        };
        n += 1;
        for (fd, ff, worst, what) in [
            (
                d::filter::gaussian(ad, kd),
                s::filter::gaussian(af, ks),
                &mut worst_g,
                "gaussian",
            ),
            (
                d::filter::projected(ad, kd),
                s::filter::projected(af, ks),
                &mut worst_p,
                "projected",
            ),
        ] {
            let (x, y) = (fd.entries(), ff.entries());
            for (u, v) in [(x.0, y.0), (x.1, y.1), (x.2, y.2)] {
                let e = (u - f64::from(v)).abs() / u.abs().max(f64::from(f32::MIN_POSITIVE));
                assert!(e <= tol, "{what}: {x:?} vs {y:?} ({e:.2e} > {tol:.2e})");
                *worst = worst.max(e / tol);
            }
        }
    }
    assert!(n > 3000, "{n}");
    println!(
        "f32 entries vs f64 (fraction of eps / 2 + eps_f64): gaussian {worst_g:.3}, \
         projected {worst_p:.3} ({n} cases)"
    );
}

#[test]
fn f32_densities_are_as_accurate_as_gaussian() {
    // GGX D of the filtered lobe, f32 against f64 on identical inputs, with one tolerance for
    // both filters, derived from their entries' one rounding (previous test):
    // a relative perturbation `e = eps / 2` of each entry of `A'` moves `q = s^T A'^-1 s` by at
    // most `e |v|^T |A'| |v|` (`v = A'^-1 s`, first order) and `det A'` by at most
    // `e (a11 a22 + a12^2)`; `D = 1 / (pi sqrt(det) (q + z^2)^2)` follows with the factors 2
    // (times `q / (q + z^2)`) and 1/2; plus `8 eps` for the f32 evaluation of `D` itself
    // (`tests/ndf_precision.rs`).
    let mut rng = filtered_ndf::testing::rng::SplitMix64(0xD15C);
    let mut next = || rng.uniform();
    let eps = f64::from(f32::EPSILON);
    let (mut worst_g, mut worst_p) = (0.0f64, 0.0f64);
    for _ in 0..2000 {
        let Some((ad, af, kd, ks)) = f32_case(&mut next) else {
            continue;
        };
        for (fd, ff, worst) in [
            (
                d::filter::gaussian(ad, kd),
                s::filter::gaussian(af, ks),
                &mut worst_g,
            ),
            (
                d::filter::projected(ad, kd),
                s::filter::projected(af, ks),
                &mut worst_p,
            ),
        ] {
            let am = fd.to_mat2();
            let det = am.determinant();
            let (b11, b12, b22) = fd.entries();
            let width = (b11 + b22).sqrt();
            for _ in 0..4 {
                let sl = DVec2::new(next() - 0.5, next() - 0.5) * 4.0 * width;
                let h = glam::DVec3::new(-sl.x, -sl.y, 1.0).normalize().as_vec3();
                let hd = h.as_dvec3();
                let sx = DVec2::new(-hd.x / hd.z, -hd.y / hd.z);
                let v = am.inverse() * sx;
                let (va, q) = (v.abs(), sx.dot(am.inverse() * sx));
                let gamma = (b11 * va.x * va.x + 2.0 * b12.abs() * va.x * va.y + b22 * va.y * va.y)
                    / v.dot(am * v).max(f64::MIN_POSITIVE);
                let det_rel = (b11 * b22 + b12 * b12) / det;
                let tol = 0.5 * eps * (2.0 * gamma * q / (q + 1.0) + 0.5 * det_rel) + 8.0 * eps;
                let (want, got) = (d::Ggx::new(fd).d(hd), f64::from(s::Ggx::new(ff).d(h)));
                let e = (got - want).abs() / want.max(f64::from(f32::MIN_POSITIVE));
                assert!(
                    e <= tol,
                    "{fd:?} at {h}: {got} vs {want} ({e:.2e} > {tol:.2e})"
                );
                *worst = worst.max(e / tol);
            }
        }
    }
    println!(
        "f32 GGX D vs f64 (fraction of tolerance): gaussian {worst_g:.3}, projected {worst_p:.3}"
    );
}

#[test]
fn clamp_rules_route_projected_like_gaussian() {
    // ClampRules::filter_projected: footprint rule -> covariance -> kernel rule -> projected,
    // with tau = det A under `det_clamp` and none without: bit for bit the public pieces.
    let a = s::RoughnessMatrix::new(0.02, 0.004, 0.01).unwrap();
    let fp = s::Footprint::from_slope_derivatives(Vec2::new(0.3, 0.05), Vec2::new(-0.02, 0.2));
    for rules in [
        s::ClampRules::default(),
        s::ClampRules::GDC2016,
        s::ClampRules::NONE,
    ] {
        let k = rules.kernel(rules.footprint(fp).covariance(0.5));
        let want = if rules.det_clamp {
            s::filter::projected(a, k)
        } else {
            s::filter::projected_with_det_clamp(a, k, 0.0)
        };
        assert_eq!(rules.filter_projected(a, fp, 0.5), want);
        // The one determinant, in f64 from the f32 entries (exact products), rounded once.
        let (a11, a12, a22) = a.entries();
        let det = (f64::from(a11) * f64::from(a22) - f64::from(a12) * f64::from(a12)) as f32;
        let tau = rules.det_clamp_for(a);
        assert_eq!(tau, if rules.det_clamp { det } else { 0.0 });
    }
    // The maximum-extent rule shrinks this footprint, kappa caps the kernel: both visible.
    let big = s::Footprint::from_slope_derivatives(Vec2::new(3.0, 0.5), Vec2::new(-0.2, 2.0));
    let wide = s::ClampRules::default().filter_projected(a, big, 0.5);
    let free = s::ClampRules::NONE.filter_projected(a, big, 0.5);
    assert!(wide.sqrt_det() < free.sqrt_det());
}
