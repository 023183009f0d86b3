//! The half-vector Jacobian `M = d sigma / dx` (KHPL16 eq. 4-6) against central finite
//! differences of the slope of the half vector in the moving shading frame, with the shading
//! point moved along analytic curved surfaces (sphere, cylinder, saddle quadric), a point light
//! and a pinhole eye; the far-field approximation (eq. 17) against the full `M` as the distances
//! grow; ray differentials and footprints against finite differences of actual ray hits.
//!
//! Surfaces are graphs `z = f(x, y)` with analytic derivatives up to order 2. The frame field is
//! `s = normalize(P_x)`, `n = normalize(P_x x P_y)`, `t = n x s`; its derivatives (the input of
//! the code under test) are computed here analytically from `f`'s second derivatives. The
//! reference is a central difference of the test's own `sigma(x)`.

use filtered_ndf::f32::footprint::geometry as g32;
use filtered_ndf::f64::footprint::geometry::{
    self as g, Endpoint, PinholeRay, ShadingFrame, footprint, footprint_projected, half_vector,
    half_vector_jacobian, half_vector_jacobian_deferred, half_vector_jacobian_far_field,
    tangent_plane_differentials,
};
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use glam::{DMat2, DVec2, DVec3, Mat2, Vec2, Vec3};

/// A graph surface `z = f(x, y)`: value, gradient and Hessian `(f_xx, f_xy, f_yy)`.
#[derive(Clone, Copy)]
struct Graph {
    name: &'static str,
    f: fn(f64, f64) -> (f64, DVec2, DVec3),
}

const R: f64 = 1.0;

fn sphere(x: f64, y: f64) -> (f64, DVec2, DVec3) {
    // Upper cap of the sphere of radius R at the origin (outward normal = up).
    let z = (R * R - x * x - y * y).sqrt();
    let z3 = z * z * z;
    (
        z,
        DVec2::new(-x / z, -y / z),
        DVec3::new(-(R * R - y * y) / z3, -x * y / z3, -(R * R - x * x) / z3),
    )
}

fn cylinder(x: f64, _y: f64) -> (f64, DVec2, DVec3) {
    // Cylinder of radius R around the y axis, upper half.
    let z = (R * R - x * x).sqrt();
    (
        z,
        DVec2::new(-x / z, 0.0),
        DVec3::new(-R * R / (z * z * z), 0.0, 0.0),
    )
}

fn saddle(x: f64, y: f64) -> (f64, DVec2, DVec3) {
    // z = (x^2 - y^2) / 2R.
    (
        (x * x - y * y) / (2.0 * R),
        DVec2::new(x / R, -y / R),
        DVec3::new(1.0 / R, 0.0, -1.0 / R),
    )
}

const SURFACES: [Graph; 3] = [
    Graph {
        name: "sphere",
        f: sphere,
    },
    Graph {
        name: "cylinder",
        f: cylinder,
    },
    Graph {
        name: "saddle",
        f: saddle,
    },
];

struct Sample {
    p: DVec3,
    frame: ShadingFrame,
    /// Columns: `(du, dv)` per unit step along `s` and along `t`.
    ginv: DMat2,
}

fn sample(surf: Graph, u: f64, v: f64) -> Sample {
    let (z, grad, hess) = (surf.f)(u, v);
    let p = DVec3::new(u, v, z);
    let pu = DVec3::new(1.0, 0.0, grad.x);
    let pv = DVec3::new(0.0, 1.0, grad.y);
    let nn = pu.cross(pv); // (-f_x, -f_y, 1)
    let n = nn / nn.length();
    let s = pu / pu.length();
    let t = n.cross(s);
    // Analytic derivatives in the parameters.
    let nn_u = DVec3::new(-hess.x, -hess.y, 0.0);
    let nn_v = DVec3::new(-hess.y, -hess.z, 0.0);
    let n_u = (nn_u - n * n.dot(nn_u)) / nn.length();
    let n_v = (nn_v - n * n.dot(nn_v)) / nn.length();
    let puu = DVec3::new(0.0, 0.0, hess.x);
    let puv = DVec3::new(0.0, 0.0, hess.y);
    let s_u = (puu - s * s.dot(puu)) / pu.length();
    let s_v = (puv - s * s.dot(puv)) / pu.length();
    // (du, dv) -> (x_s, x_t) and its inverse.
    let gm = DMat2::from_cols(
        DVec2::new(pu.dot(s), pu.dot(t)),
        DVec2::new(pv.dot(s), pv.dot(t)),
    );
    let ginv = gm.inverse();
    let along = |a_u: DVec3, a_v: DVec3, k: usize| {
        let c = ginv.col(k);
        a_u * c.x + a_v * c.y
    };
    let frame = ShadingFrame::from_derivatives(
        s,
        t,
        n,
        [along(n_u, n_v, 0), along(n_u, n_v, 1)],
        [along(s_u, s_v, 0), along(s_u, s_v, 1)],
    );
    Sample { p, frame, ginv }
}

/// The test's own slope of the half vector in the frame at `(u, v)`.
fn sigma(surf: Graph, uv: DVec2, eye: Endpoint, light: Endpoint) -> DVec2 {
    let smp = sample(surf, uv.x, uv.y);
    let dir = |e: Endpoint| match e {
        Endpoint::Point(q) => (q - smp.p).normalize(),
        Endpoint::Direction(d) => d.normalize(),
    };
    let hw = dir(eye) + dir(light);
    let f = smp.frame;
    -DVec2::new(hw.dot(f.s), hw.dot(f.t)) / hw.dot(f.n)
}

/// Central-difference `M`: move along the surface curve whose velocity is `s` (then `t`).
fn fd_m(surf: Graph, uv: DVec2, eye: Endpoint, light: Endpoint, step: f64) -> DMat2 {
    let smp = sample(surf, uv.x, uv.y);
    let col = |k: usize| {
        let d = smp.ginv.col(k) * step;
        (sigma(surf, uv + d, eye, light) - sigma(surf, uv - d, eye, light)) / (2.0 * step)
    };
    DMat2::from_cols(col(0), col(1))
}

fn rel(a: DMat2, b: DMat2) -> f64 {
    let num = (a - b)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let den = b.to_cols_array().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    num / den
}

/// A direction within the cone `{ d . around >= 1 - max_cos }` (rejection sampling).
fn unit_upper(rng: &mut Rng, around: DVec3, max_cos: f64) -> DVec3 {
    loop {
        let d = DVec3::new(
            rng.uniform() - 0.5,
            rng.uniform() - 0.5,
            rng.uniform() - 0.5,
        );
        let l = d.length();
        if l > 0.05 && l < 0.5 && (d / l).dot(around) > 1.0 - max_cos {
            return d / l;
        }
    }
}

#[test]
fn m_matches_finite_differences_on_curved_surfaces() {
    let mut rng = Rng(7);
    let mut worst = (0.0f64, "");
    for surf in SURFACES {
        for _ in 0..200 {
            let uv = DVec2::new(rng.uniform() - 0.5, rng.uniform() - 0.5) * 1.2;
            let smp = sample(surf, uv.x, uv.y);
            let n = smp.frame.n;
            // Eye and light 0.5 .. 5 R away, within 80 degrees of the normal so the half vector
            // stays above the shading horizon.
            let eye = smp.p + unit_upper(&mut rng, n, 0.8) * (0.5 + 4.5 * rng.uniform());
            let light = smp.p + unit_upper(&mut rng, n, 0.8) * (0.5 + 4.5 * rng.uniform());
            let (e, l) = (Endpoint::Point(eye), Endpoint::Point(light));
            let m = half_vector_jacobian(smp.p, e, l, &smp.frame);
            // Step 1e-5 R: truncation ~ (1e-5 / 0.5)^2 = 4e-10 relative, roundoff
            // ~ 1e-16 / 1e-5 = 1e-11 relative (the slope is O(1)).
            let fd = fd_m(surf, uv, e, l, 1e-5);
            let err = rel(m, fd);
            if err > worst.0 {
                worst = (err, surf.name);
            }
            // 1e-7: the FD budget above with a margin of 100 for slopes up to ~5.
            assert!(err < 1e-7, "{} {uv} {eye} {light}: {m} vs {fd}", surf.name);
            // Directional endpoints: the full M equals T'(x) h_w (eq. 17 is exact).
            let (ed, ld) = (
                Endpoint::Direction(eye - smp.p),
                Endpoint::Direction(light - smp.p),
            );
            let md = half_vector_jacobian(smp.p, ed, ld, &smp.frame);
            let ff = half_vector_jacobian_far_field(
                (eye - smp.p).normalize() + (light - smp.p).normalize(),
                &smp.frame,
            );
            assert!(rel(md, ff) < 1e-13);
            assert!(rel(md, fd_m(surf, uv, ed, ld, 1e-5)) < 1e-7);
        }
    }
    println!(
        "worst relative FD discrepancy of M: {:.3e} ({})",
        worst.0, worst.1
    );
}

#[test]
fn far_field_and_deferred_approximations_converge_like_one_over_distance() {
    println!(
        "relative error of KHPL16 eq. 17 against the full M (R = 1, point eye and light at distance D)"
    );
    println!(
        "{:>9} {:>8} {:>12} {:>12}",
        "surface", "D / R", "far field", "deferred"
    );
    for surf in SURFACES {
        let uv = DVec2::new(0.3, -0.2);
        let smp = sample(surf, uv.x, uv.y);
        let n = smp.frame.n;
        let o = (n + smp.frame.s * 0.6 + smp.frame.t * 0.2).normalize();
        // Deferred (h_w = n) assumes the light near the mirror direction: use the exact mirror.
        let i_mirror = n * (2.0 * n.dot(o)) - o;
        let i_other = (n - smp.frame.s * 0.3 + smp.frame.t * 0.5).normalize();
        let mut prev: Option<(f64, f64)> = None;
        for d in [1.0, 10.0, 100.0, 1e3, 1e4, 1e5] {
            let e = Endpoint::Point(smp.p + o * d);
            let full_other =
                half_vector_jacobian(smp.p, e, Endpoint::Point(smp.p + i_other * d), &smp.frame);
            let ff = half_vector_jacobian_far_field(o + i_other, &smp.frame);
            let full_mirror =
                half_vector_jacobian(smp.p, e, Endpoint::Point(smp.p + i_mirror * d), &smp.frame);
            let def = half_vector_jacobian_deferred(&smp.frame);
            let (e_ff, e_def) = (rel(ff, full_other), rel(def, full_mirror));
            println!(
                "{:>9} {:>8.0e} {:>12.3e} {:>12.3e}",
                surf.name, d, e_ff, e_def
            );
            if let (Some((p_ff, p_def)), true) = (prev, d >= 100.0) {
                // First order in 1/D once D >> R: each tenfold distance cuts the error by 10
                // (7..13 allows for the O(1/D^2) remainder from D = 10 to 100; at D = R the
                // expansion has not started).
                assert!(
                    (7.0..13.0).contains(&(p_ff / e_ff)),
                    "{} {d} {p_ff} {e_ff}",
                    surf.name
                );
                assert!(
                    (7.0..13.0).contains(&(p_def / e_def)),
                    "{} {d} {p_def} {e_def}",
                    surf.name
                );
            }
            prev = Some((e_ff, e_def));
        }
        // The deferred M is the shape operator itself.
        assert_eq!(half_vector_jacobian_deferred(&smp.frame), smp.frame.dn);
    }
}

#[test]
fn sphere_and_flat_closed_forms() {
    // On a sphere of radius R with an outward normal, the shape operator is I / R whatever the
    // frame; a flat frame with the eye and light straight above at distances a, b gives
    // M = (1/a + 1/b) / 2 I (half the sum of the direction rates, h_z = 1).
    for (u, v) in [(0.0, 0.0), (0.4, -0.3), (-0.6, 0.5)] {
        let smp = sample(SURFACES[0], u, v);
        assert!(rel(smp.frame.dn, DMat2::IDENTITY / R) < 1e-12);
    }
    let flat = ShadingFrame::flat(DVec3::X, DVec3::Y, DVec3::Z);
    let m = half_vector_jacobian(
        DVec3::ZERO,
        Endpoint::Point(DVec3::Z * 2.0),
        Endpoint::Point(DVec3::Z * 8.0),
        &flat,
    );
    // sigma = -h_xy / h_z: moving x by +dx tilts both directions towards -x, so the slope
    // grows: +(1/2 + 1/8) / 2.
    assert!(rel(m, DMat2::IDENTITY * (0.5 + 0.125) / 2.0) < 1e-14, "{m}");
}

/// Ray-sphere hit (sphere of radius R at the origin), nearest positive root.
fn hit_sphere(o: DVec3, d: DVec3) -> DVec3 {
    let (a, b, c) = (d.dot(d), 2.0 * o.dot(d), o.dot(o) - R * R);
    let t = (-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
    o + d * t
}

#[test]
fn ray_differential_footprints_match_finite_differences_of_pixel_rays() {
    // A pinhole above the sphere; pixel (u, v) shoots d = fwd + u right + v up (1 mrad pixels).
    let eye = DVec3::new(0.4, -0.3, 4.0);
    let light = Endpoint::Point(DVec3::new(-2.0, 1.0, 3.0));
    let fwd = (DVec3::new(0.1, 0.2, 0.0) - eye).normalize();
    let right = fwd.cross(DVec3::Y).normalize() * 1e-3;
    let up = right.cross(fwd).normalize() * 1e-3;
    let surf = SURFACES[0];
    let mut worst = 0.0f64;
    for (pu, pv) in [(0.0, 0.0), (60.0, -40.0), (-80.0, 50.0), (30.0, 90.0)] {
        let dir = |du: f64, dv: f64| fwd + right * (pu + du) + up * (pv + dv);
        let x = hit_sphere(eye, dir(0.0, 0.0));
        let smp = sample(surf, x.x, x.y);
        let ray = PinholeRay {
            origin: eye,
            dir: dir(0.0, 0.0),
            ddir_du: right,
            ddir_dv: up,
        };
        let (dx_u, dx_v) = tangent_plane_differentials(&ray, x, smp.frame.n).unwrap();
        assert!(dx_u.dot(smp.frame.n).abs() < 1e-15 && dx_v.dot(smp.frame.n).abs() < 1e-15);
        // To first order the tangent-plane transfer equals the motion of the true hit point.
        // Pixel step 1e-2: the hit moves ~1e-5 R per step, truncation ~1e-4^2 relative.
        let h = 1e-2;
        let fdx = |a: DVec3, b: DVec3| (a - b) / (2.0 * h);
        let fx_u = fdx(hit_sphere(eye, dir(h, 0.0)), hit_sphere(eye, dir(-h, 0.0)));
        let fx_v = fdx(hit_sphere(eye, dir(0.0, h)), hit_sphere(eye, dir(0.0, -h)));
        // 1e-6 relative: FD truncation above plus roundoff 1e-16 / 1e-5.
        assert!(
            (fx_u - dx_u).length() < 1e-6 * dx_u.length(),
            "{fx_u} {dx_u}"
        );
        assert!((fx_v - dx_v).length() < 1e-6 * dx_v.length());
        // The slope footprint M dx against the slope change of neighbouring pixels' hits.
        let e = Endpoint::Point(eye);
        let m = half_vector_jacobian(x, e, light, &smp.frame);
        let fp = footprint(m, &smp.frame, dx_u, dx_v);
        let sig = |du: f64, dv: f64| {
            let q = hit_sphere(eye, dir(du, dv));
            sigma(surf, DVec2::new(q.x, q.y), e, light)
        };
        let fs_u = (sig(h, 0.0) - sig(-h, 0.0)) / (2.0 * h);
        let fs_v = (sig(0.0, h) - sig(0.0, -h)) / (2.0 * h);
        let scale = fp.dh_u.length().max(fp.dh_v.length());
        let err = (fs_u - fp.dh_u).length().max((fs_v - fp.dh_v).length()) / scale;
        worst = worst.max(err);
        assert!(err < 1e-6, "{err}");
        // TK19's projected variant against the change of the projected half vector itself.
        let pp = |du: f64, dv: f64| {
            let q = hit_sphere(eye, dir(du, dv));
            let s = sample(surf, q.x, q.y);
            let hw = (eye - q).normalize() + (DVec3::new(-2.0, 1.0, 3.0) - q).normalize();
            let hl = s.frame.to_local(hw.normalize());
            DVec2::new(hl.x, hl.y)
        };
        let fpp = footprint_projected(fp, half_vector(x, e, light, &smp.frame));
        let fp_u = (pp(h, 0.0) - pp(-h, 0.0)) / (2.0 * h);
        let fp_v = (pp(0.0, h) - pp(0.0, -h)) / (2.0 * h);
        let scale = fpp.dh_u.length().max(fpp.dh_v.length());
        let err = (fp_u - fpp.dh_u).length().max((fp_v - fpp.dh_v).length()) / scale;
        worst = worst.max(err);
        assert!(err < 1e-6, "{err}");
    }
    println!("worst relative FD discrepancy of the pixel footprints: {worst:.3e}");
}

#[test]
fn f32_agrees_with_f64() {
    let surf = SURFACES[2];
    let smp = sample(surf, 0.3, -0.4);
    let f = smp.frame;
    let f32frame = g32::ShadingFrame {
        s: f.s.as_vec3(),
        t: f.t.as_vec3(),
        n: f.n.as_vec3(),
        dn: f.dn.as_mat2(),
        twist: f.twist.as_vec2(),
    };
    let (x, eye, light) = (smp.p, DVec3::new(1.0, 2.0, 3.0), DVec3::new(-1.0, 0.5, 2.0));
    let m64 = half_vector_jacobian(x, Endpoint::Point(eye), Endpoint::Point(light), &f);
    let m32 = g32::half_vector_jacobian(
        x.as_vec3(),
        g32::Endpoint::Point(eye.as_vec3()),
        g32::Endpoint::Point(light.as_vec3()),
        &f32frame,
    );
    // 1e-5: a few dozen f32 roundings (6e-8 each) through normalisations and the quotient rule.
    assert!(rel(m32.as_dmat2(), m64) < 1e-5, "{m32} {m64}");
}

#[test]
fn bad_input_gives_zero_or_none() {
    let flat = g32::ShadingFrame::flat(Vec3::X, Vec3::Y, Vec3::Z);
    let p = |v: Vec3| g32::Endpoint::Point(v);
    let up = Vec3::Z;
    // Shading point on the eye or the light; i + o = 0; NaN and infinite input.
    assert_eq!(
        g32::half_vector_jacobian(Vec3::ZERO, p(Vec3::ZERO), p(up), &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian(Vec3::ZERO, p(up), p(Vec3::ZERO), &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian(Vec3::ZERO, p(Vec3::X), p(-Vec3::X), &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian(Vec3::NAN, p(up), p(up), &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian(Vec3::ZERO, p(Vec3::INFINITY), p(up), &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian(
            Vec3::ZERO,
            g32::Endpoint::Direction(Vec3::ZERO),
            p(up),
            &flat
        ),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian_far_field(Vec3::ZERO, &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector_jacobian_far_field(Vec3::NAN, &flat),
        Mat2::ZERO
    );
    assert_eq!(
        g32::half_vector(Vec3::ZERO, p(Vec3::X), p(-Vec3::X), &flat),
        Vec3::Z
    );
    // Half vector below the shading horizon (eye and light under the surface): finite, from
    // the documented clamp h . n >= HZ_MIN.
    let below = g32::half_vector_jacobian(Vec3::ZERO, p(Vec3::new(1.0, 0.0, -1.0)), p(-up), &flat);
    assert!(below.is_finite() && below != Mat2::ZERO);
    // Grazing: finite at exactly h . n = 0.
    let graze =
        g32::half_vector_jacobian(Vec3::ZERO, p(Vec3::X), p(Vec3::new(1.0, 1.0, 0.0)), &flat);
    assert!(graze.is_finite());
    // Huge frame derivatives overflow to infinity: zero matrix, not inf.
    let wild = g32::ShadingFrame {
        dn: Mat2::from_diagonal(Vec2::splat(f32::MAX)),
        ..flat
    };
    assert_eq!(
        g32::half_vector_jacobian(Vec3::ZERO, p(Vec3::new(3.0, 0.0, 1.0)), p(up), &wild),
        Mat2::ZERO
    );
    // Huge but finite directions normalise without overflow (same M as the unit direction).
    let eye = p(Vec3::new(1.0, -2.0, 4.0));
    let huge = g32::half_vector_jacobian(
        Vec3::ZERO,
        eye,
        g32::Endpoint::Direction(Vec3::new(3e38, 1e38, 3e38)),
        &flat,
    );
    let unit = g32::half_vector_jacobian(
        Vec3::ZERO,
        eye,
        g32::Endpoint::Direction(Vec3::new(3.0, 1.0, 3.0)),
        &flat,
    );
    // 1e-6: f32 rounding of the rescaled direction.
    assert!(
        rel(huge.as_dmat2(), unit.as_dmat2()) < 1e-6,
        "{huge} {unit}"
    );
    // Footprints: a NaN differential counts as 0 (the NaN policy), the other still counts.
    let fp = g32::footprint(Mat2::IDENTITY, &flat, Vec3::NAN, Vec3::X);
    assert_eq!(
        fp,
        g32::footprint(Mat2::IDENTITY, &flat, Vec3::ZERO, Vec3::X)
    );
    assert_eq!(fp.dh_u, Vec2::ZERO);
    // A ray parallel to the plane has no transfer.
    let ray = g32::PinholeRay {
        origin: Vec3::Z,
        dir: Vec3::X,
        ddir_du: Vec3::Y,
        ddir_dv: Vec3::Z,
    };
    assert_eq!(
        g32::tangent_plane_differentials(&ray, Vec3::ZERO, Vec3::Z),
        None
    );
    let nan_ray = g32::PinholeRay {
        dir: Vec3::NAN,
        ..ray
    };
    assert_eq!(
        g32::tangent_plane_differentials(&nan_ray, Vec3::ZERO, Vec3::Z),
        None
    );
    let _ = g::Endpoint::Direction(DVec3::Z);
}
