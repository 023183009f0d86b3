//! Jacobians between the half-vector domains (TK19 supplement eq. 1-7) against central finite
//! differences of the actual point maps of `slope`, in f64, plus the determinant and
//! composition identities, the pole and horizon behaviour, f32 vs f64 and bad input.
//!
//! The references are built here from the paper's own parametrisation (eq. 1 and 3: a rotation
//! of `(psi_x, psi_y)` coordinates to `h`), written with the test's own trigonometry; the code
//! under test computes the same frame from `h` alone.

use filtered_ndf::f32::footprint::jacobian as j32;
use filtered_ndf::f64::footprint::jacobian as j64;
use filtered_ndf::f64::footprint::slope;
use glam::{DMat2, DVec2, DVec3, Vec3};
use proptest::prelude::*;

/// `h(theta, phi)` and the spherical basis `e_x`, `e_y` (TK19 supplement eq. 3 columns).
fn frame(theta: f64, phi: f64) -> (DVec3, DVec3, DVec3) {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    (
        DVec3::new(st * cp, st * sp, ct),
        DVec3::new(ct * cp, ct * sp, -st),
        DVec3::new(-sp, cp, 0.0),
    )
}

/// `h` after spherical displacement `(psi_x, psi_y)` (TK19 supplement eq. 1 then eq. 3).
fn displaced(theta: f64, phi: f64, psi_x: f64, psi_y: f64) -> DVec3 {
    let (h, ex, ey) = frame(theta, phi);
    let mx = psi_y.cos() * psi_x.sin();
    let my = psi_y.sin();
    let mz = psi_y.cos() * psi_x.cos();
    ex * mx + ey * my + h * mz
}

/// Central-difference Jacobian of `g: R^2 -> R^2` at `x0` with step `d`, in the paper's
/// layout (column j = derivative along input j).
fn fd2(g: impl Fn(DVec2) -> DVec2, x0: DVec2, d: f64) -> DMat2 {
    let cx = (g(x0 + DVec2::new(d, 0.0)) - g(x0 - DVec2::new(d, 0.0))) / (2.0 * d);
    let cy = (g(x0 + DVec2::new(0.0, d)) - g(x0 - DVec2::new(0.0, d))) / (2.0 * d);
    DMat2::from_cols(cx, cy)
}

/// Relative matrix error `max |a - b| / max |b|` (entry-wise).
fn rel(a: DMat2, b: DMat2) -> f64 {
    let d = (a - b).to_cols_array();
    let s = b.to_cols_array();
    let num = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let den = s.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    num / den
}

/// The four Jacobians against finite differences at `(theta, phi)`; returns the worst
/// relative discrepancy.
fn check_against_fd(theta: f64, phi: f64) -> f64 {
    let (h, _, _) = frame(theta, phi);
    let hz = h.z;
    // Spherical step: the maps vary on the angular scale h_z (slope ~ 1/h_z), so a step of
    // 1e-5 h_z gives truncation ~1e-10 and roundoff ~1e-16 / 1e-5 = 1e-11 relative.
    let dpsi = 1e-5 * hz.min(1.0);
    let sph =
        |map: fn(DVec3) -> DVec2| fd2(|q| map(displaced(theta, phi, q.x, q.y)), DVec2::ZERO, dpsi);
    let e1 = rel(
        j64::sphere_to_projected(h),
        sph(slope::projected_from_sphere),
    );
    let e2 = rel(j64::sphere_to_slope(h), sph(slope::slope_from_sphere));
    // Disk step: the disk map's scale is the distance to the unit circle, 1 - |p| ~ h_z^2 / 2;
    // 1e-4 h_z^2 keeps truncation ~1e-8 and the cancellation in 1 - |p|^2 (~1e-16 / h_z^2)
    // amplified by 1/step at ~1e-8 relative at 89.9 degrees.
    let p = DVec2::new(h.x, h.y);
    let e3 = rel(
        j64::projected_to_slope(h),
        fd2(slope::slope_from_projected, p, 1e-4 * hz * hz),
    );
    // Slope step: the scale of the slope map is 1 + |s|^2 ~ 1 / h_z^2; relative step 1e-5.
    let s = slope::slope_from_sphere(h);
    let e4 = rel(
        j64::slope_to_projected(h),
        fd2(slope::projected_from_slope, s, 1e-5 / hz),
    );
    e1.max(e2).max(e3).max(e4)
}

fn angles() -> Vec<f64> {
    let mut t: Vec<f64> = vec![1e-9, 1e-6, 1e-3, 0.01];
    t.extend((1..=17).map(|k| (5.0 * k as f64).to_radians()));
    t.extend([88.0f64, 89.0, 89.5, 89.9].iter().map(|d| d.to_radians()));
    t
}

#[test]
fn every_jacobian_matches_finite_differences_up_to_89_9_degrees() {
    let mut worst = (0.0f64, 0.0, 0.0);
    for theta in angles() {
        for k in 0..12 {
            let phi = -3.0 + 0.53 * k as f64;
            let e = check_against_fd(theta, phi);
            if e > worst.0 {
                worst = (e, theta.to_degrees(), phi);
            }
        }
    }
    println!(
        "worst relative FD discrepancy of the domain Jacobians: {:.3e} at theta = {} deg, phi = {}",
        worst.0, worst.1, worst.2
    );
    // 1e-6: the FD truncation and roundoff budgets in check_against_fd are <= ~1e-8; a wrong
    // sign, transposition or factor h_z would give O(1).
    assert!(worst.0 < 1e-6, "{worst:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_half_vectors_match_finite_differences(
        theta in 0.0f64..89.9f64.to_radians(),
        phi in -3.2f64..3.2,
    ) {
        let theta = theta.max(1e-9);
        // Same budget as the grid test above.
        prop_assert!(check_against_fd(theta, phi) < 1e-6);
    }
}

#[test]
fn determinants_are_positive_and_match_finite_differences() {
    for theta in angles() {
        let phi = 0.7;
        let (h, _, _) = frame(theta, phi);
        let hz = h.z;
        // Closed forms (TK19 sections 3.1, 3.2 and supplement eq. 6); 1e-12 relative: a handful
        // of roundings in products of three or four factors.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(j64::det_sphere_to_projected(h), hz));
        assert!(close(j64::det_projected_to_slope(h), hz.powi(-4)));
        assert!(close(j64::det_sphere_to_slope(h), hz.powi(-3)));
        assert!(close(j64::sphere_to_projected(h).determinant(), hz));
        assert!(close(j64::sphere_to_slope(h).determinant(), hz.powi(-3)));
        // The signs of the determinants from finite differences of the actual maps: all
        // positive despite the leading minus of eq. 6 and 7 (2x2 negation keeps det).
        let dpsi = 1e-5 * hz.min(1.0);
        let fd = fd2(
            |q| slope::slope_from_sphere(displaced(theta, phi, q.x, q.y)),
            DVec2::ZERO,
            dpsi,
        );
        let d = fd.determinant();
        assert!(d > 0.0);
        // 1e-6: FD budget of check_against_fd, doubled by the product of two entries.
        assert!((d - hz.powi(-3)).abs() < 1e-6 * hz.powi(-3), "{theta} {d}");
        // The disk map's angular scale is 1 (not h_z): step 1e-5 keeps roundoff ~1e-11.
        let fdp = fd2(
            |q| slope::projected_from_sphere(displaced(theta, phi, q.x, q.y)),
            DVec2::ZERO,
            1e-5,
        );
        assert!(
            (fdp.determinant() - hz).abs() < 1e-6 * hz,
            "{theta} {} {hz}",
            fdp.determinant()
        );
        assert!(
            (j64::projected_to_slope(h).determinant() - hz.powi(-4)).abs() < 1e-10 * hz.powi(-4)
        );
    }
}

#[test]
fn composition_identity_and_inverse() {
    for theta in angles() {
        for phi in [-2.0, 0.0, 0.4, 2.9] {
            let (h, _, _) = frame(theta, phi);
            // J(o->par) = J(perp->par) J(o->perp) (TK19 supplement eq. 7). 1e-13: a few
            // roundings per entry of a 2-term product, relative to the largest entry.
            let prod = j64::projected_to_slope(h) * j64::sphere_to_projected(h);
            assert!(rel(prod, j64::sphere_to_slope(h)) < 1e-13, "{theta} {phi}");
            // J(par->perp) J(perp->par) = I. Relative to 1 / h_z^3-sized entries, the
            // cancellation in the product costs up to cond ~ 1 / h_z^2 = 3e5 roundings at
            // 89.9 degrees: 1e-10 absolute on the identity.
            let id = j64::slope_to_projected(h) * j64::projected_to_slope(h);
            assert!(rel(id, DMat2::IDENTITY) < 1e-10, "{theta} {phi} {id}");
        }
    }
}

#[test]
fn error_propagation_of_tk19_section_3_1() {
    for theta in angles() {
        let phi = -1.3;
        let (h, ex, ey) = frame(theta, phi);
        // The basis: matches eq. 3 columns, orthonormal, right-handed, e_y = n x h / |n x h|.
        let (bx, by) = j64::spherical_basis(h);
        // 1e-12: the code derives (cos phi, sin phi) from h by a hypot and a division.
        assert!(
            (bx - ex).length() < 1e-12 && (by - ey).length() < 1e-12,
            "{theta}"
        );
        assert!((bx.cross(by) - h).length() < 1e-12);
        let nxh = DVec3::Z.cross(h);
        assert!((nxh / nxh.length() - by).length() < 1e-12);
        // An error eps on the sphere becomes J eps in the slope domain, to first order: check
        // against the actual slope change of a small displacement along eps.
        let eps = DVec2::new(0.8, -0.6) * 1e-6 * h.z;
        let ds = slope::slope_from_sphere(displaced(theta, phi, eps.x, eps.y))
            - slope::slope_from_sphere(displaced(theta, phi, -eps.x, -eps.y));
        let pred = j64::spherical_to_slope(h, eps) * 2.0;
        // 1e-6: second-order terms of a step 1e-6 h_z relative to the map's scale h_z.
        assert!((ds - pred).length() < 1e-6 * pred.length(), "{theta}");
        let dp = slope::projected_from_sphere(displaced(theta, phi, eps.x, eps.y))
            - slope::projected_from_sphere(displaced(theta, phi, -eps.x, -eps.y));
        let pred_p = j64::spherical_to_projected(h, eps) * 2.0;
        assert!((dp - pred_p).length() < 1e-6 * pred_p.length());
        // The projected domain never amplifies (|J(o->perp) e| <= |e|); the slope domain
        // always does (|J(o->par) e| >= |e|).
        assert!(pred_p.length() <= 2.0 * eps.length() * (1.0 + 1e-12));
        assert!(pred.length() >= 2.0 * eps.length() * (1.0 - 1e-12));
        // spherical_components inverts the basis expansion of a tangent change.
        let dh = ex * 0.3 - ey * 0.7 + h * 0.25;
        let c = j64::spherical_components(h, dh);
        assert!((c - DVec2::new(0.3, -0.7)).length() < 1e-12);
    }
}

#[test]
fn pole_limit_along_each_meridian_and_the_phi_zero_choice() {
    // Exactly at the pole: phi = 0, J(o->perp) = I, J(o->par) = J(perp->par) = -I.
    assert_eq!(j64::sphere_to_projected(DVec3::Z), DMat2::IDENTITY);
    assert_eq!(j64::sphere_to_slope(DVec3::Z), -DMat2::IDENTITY);
    assert_eq!(j64::projected_to_slope(DVec3::Z), -DMat2::IDENTITY);
    assert_eq!(j64::slope_to_projected(DVec3::Z), -DMat2::IDENTITY);
    assert_eq!(j64::spherical_basis(DVec3::Z), (DVec3::X, DVec3::Y));
    assert_eq!(j32::sphere_to_slope(Vec3::Z), -glam::Mat2::IDENTITY);
    // Along the meridian phi, J(o->perp) -> R(phi) and J(o->par) -> -R(phi) continuously:
    // the deviation is O(theta^2) (h_z = cos theta), 0.6 theta^2 bounds (1 - cos) and the
    // 1/h_z^2 factor's 2 theta^2.
    for phi in [-2.5, 0.0, 1.0, 3.0] {
        let r = DMat2::from_angle(phi);
        for theta in [1e-300, 1e-100, 1e-12, 1e-8, 1e-4, 1e-2] {
            let (h, _, _) = frame(theta, phi);
            let tol = 3.0 * theta * theta + 1e-15;
            assert!(rel(j64::sphere_to_projected(h), r) < tol, "{phi} {theta}");
            assert!(rel(j64::sphere_to_slope(h), -r) < tol, "{phi} {theta}");
            // The phi-independent quantities are continuous through the pole.
            let jtj = j64::sphere_to_projected(h).transpose() * j64::sphere_to_projected(h);
            assert!(rel(jtj, DMat2::IDENTITY) < tol);
        }
    }
    // f32 near the pole: h_z rounds to 1 but the azimuth survives (hypot of the tiny h_xy).
    for h in [
        Vec3::new(1e-20, 1e-20, 1.0),
        Vec3::new(1e-45, 0.0, 1.0),
        Vec3::new(-1e-38, 3e-38, 1.0),
    ] {
        let m = j32::sphere_to_slope(h);
        assert!(m.is_finite(), "{h}");
        let phi = (h.y as f64).atan2(h.x as f64);
        let r = DMat2::from_angle(phi);
        // 1e-6: f32 rounding of cos/sin phi.
        assert!(rel(m.as_dmat2(), -r) < 1e-6, "{h} {m}");
    }
}

#[test]
fn grazing_and_below_horizon_clamp_to_hz_min() {
    let hz = j64::HZ_MIN;
    let st = (1.0 - hz * hz).sqrt();
    for phi in [0.0, 0.9, -2.0] {
        let (sp, cp) = f64::sin_cos(phi);
        let at_min = DVec3::new(st * cp, st * sp, hz);
        for h in [
            DVec3::new(cp, sp, 0.0),
            DVec3::new(cp, sp, 1e-9),
            DVec3::new(cp, sp, -0.5),
            DVec3::new(cp * 1e-3, sp * 1e-3, -1.0),
        ] {
            // 1e-15 / 1e-14: the azimuth is recomputed from h by hypot and division (an ulp).
            assert!((j64::sanitize(h) - at_min).length() < 1e-15, "{h}");
            assert!(rel(j64::sphere_to_slope(h), j64::sphere_to_slope(at_min)) < 1e-14);
            // Clamped: exactly 1 / HZ_MIN^3. The point at the clamp itself: its
            // normalisation moves h_z by an ulp or two either way, the cube triples that
            // (1e-15 relative).
            assert_eq!(j64::det_sphere_to_slope(h), 1.0 / (hz * hz * hz));
            let at = j64::det_sphere_to_slope(at_min);
            assert!((at * hz * hz * hz - 1.0).abs() < 1e-15, "{at}");
        }
    }
    // The documented finite values at the clamp, in both precisions.
    assert!((j64::det_sphere_to_slope(DVec3::X) - 1e18).abs() < 1e6);
    assert!((j64::det_projected_to_slope(DVec3::X) - 1e24).abs() < 1e12);
    assert!((j64::det_sphere_to_projected(DVec3::X) - 1e-6).abs() < 1e-18);
    let m32 = j32::sphere_to_slope(Vec3::X);
    let p32 = j32::projected_to_slope(Vec3::new(0.6, -0.8, 0.0));
    assert!(m32.is_finite() && p32.is_finite());
    assert!(j32::det_projected_to_slope(Vec3::X).is_finite());
    // Squares of the largest entries (what a covariance computes) stay finite in f32.
    assert!((p32.x_axis.x * p32.x_axis.x).is_finite());
    // -n maps to the horizon at phi = 0.
    assert_eq!(j64::sanitize(-DVec3::Z), DVec3::new(st, 0.0, hz));
    assert!(j32::sphere_to_slope(-Vec3::Z).is_finite());
}

#[test]
fn bad_input_is_the_pole_and_scale_is_ignored() {
    let pole32 = j32::sphere_to_slope(Vec3::Z);
    for h in [
        Vec3::ZERO,
        Vec3::NAN,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(f32::INFINITY, 0.0, 1.0),
        Vec3::new(0.0, f32::NEG_INFINITY, 0.0),
    ] {
        assert_eq!(j32::sanitize(h), Vec3::Z, "{h}");
        assert_eq!(j32::sphere_to_slope(h), pole32);
        assert_eq!(j32::sphere_to_projected(h), glam::Mat2::IDENTITY);
        assert_eq!(j32::det_sphere_to_slope(h), 1.0);
        assert_eq!(
            j32::spherical_to_slope(h, glam::Vec2::new(1.0, 2.0)),
            -glam::Vec2::new(1.0, 2.0)
        );
    }
    // Huge, tiny and unnormalised inputs give the result of the unit vector. 1e-6: f32 ulps.
    let unit = Vec3::new(1.0, 0.5, 2.0).normalize();
    let want = j32::sphere_to_slope(unit);
    for k in [1e-40f32, 1e-20, 3.0, 1e30, 1e38] {
        let got = j32::sphere_to_slope(Vec3::new(1.0, 0.5, 2.0) * k);
        assert!(got.is_finite());
        assert!(rel(got.as_dmat2(), want.as_dmat2()) < 1e-6, "{k} {got}");
    }
}

#[test]
fn f32_agrees_with_f64() {
    let mut worst = 0.0f64;
    for theta in angles() {
        for phi in [-2.9, -0.3, 1.1, 2.2] {
            let (h, _, _) = frame(theta, phi);
            let h32 = h.as_vec3();
            let h64 = h32.as_dvec3();
            for (a, b) in [
                (j32::sphere_to_projected(h32), j64::sphere_to_projected(h64)),
                (j32::sphere_to_slope(h32), j64::sphere_to_slope(h64)),
                (j32::projected_to_slope(h32), j64::projected_to_slope(h64)),
                (j32::slope_to_projected(h32), j64::slope_to_projected(h64)),
            ] {
                worst = worst.max(rel(a.as_dmat2(), b));
            }
            let d =
                (j32::det_sphere_to_slope(h32) as f64 / j64::det_sphere_to_slope(h64) - 1.0).abs();
            worst = worst.max(d);
        }
    }
    println!("worst f32 vs f64 relative difference: {worst:.3e}");
    // 2e-6: the renormalisation of an f32 input and 3-4 f32 roundings (~6e-8 each) amplified
    // at most by the 1/h_z^3 factor's relative condition 3.
    assert!(worst < 2e-6, "{worst}");
}
