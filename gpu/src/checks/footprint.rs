//! `shaders/footprint/` (slope maps, Jacobians, footprint constructors) and
//! `shaders/kernel/` (covariance, rectangle, clamp rules).
//!
//! Cases: half vectors from `strategies::upper_hemisphere(89.9)` plus the pole, the horizon
//! and below it (the Jacobians' clamp `HZ_MIN`); footprints from `strategies::footprint`
//! (extents log-uniform in `[1e-6, 1]`, zero one draw in eight); normal differences with
//! lengths log-uniform in `[1e-6, 1]`; kernels from those footprints and, for the
//! sanitiser, random indefinite matrices.
//!
//! Tolerances (ulp of f32, `EPS`): unit vectors are compared componentwise with an absolute
//! tolerance (6 to 8 `EPS`: a normalisation is a square root, 4.5 ulp, and a division, 2.5,
//! plus the products); matrices whose entries grow like `1 / h_z^k` with an absolute
//! tolerance proportional to their largest entry (`h_z` itself carries 4 ulp from the
//! normalisation, and `1 / h_z^k` multiplies that by `k`); determinants relatively. Sums
//! that may cancel (`s_xy = u_x u_y + v_x v_y`, `dh_u x dh_v`, `dh_u + dh_v`) get an
//! absolute tolerance of a few `EPS` times the sum of the magnitudes of their terms. Where
//! the reference itself cancels in f64 (`Covariance::det`), its own error
//! (`4e-16 s_xx s_yy`) is added.

use super::{Check, EPS, Tol, draw, r32};
use crate::reference::{
    BoundingRect, ClampRules, Covariance, DVec2, DVec3, Footprint, SplitMix64, jacobian, slope,
    strategies, v2, v3,
};

fn f2(d: DVec2) -> [f32; 2] {
    [d.x as f32, d.y as f32]
}

fn f3(d: DVec3) -> [f32; 3] {
    [d.x as f32, d.y as f32, d.z as f32]
}

/// Half vectors: the strategy's, and the special ones of the Jacobians' contract.
fn half_vectors(n: usize) -> Vec<[f32; 3]> {
    let mut v: Vec<[f32; 3]> = vec![
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [0.6, 0.8, 1e-7],
        [0.6, -0.8, -0.3],
        [3.0, 4.0, 5.0],
        [1e-20, 0.0, 1.0],
    ];
    v.extend(
        draw(strategies::upper_hemisphere(89.9), n, "footprint h")
            .into_iter()
            .map(f3),
    );
    v
}

fn footprints(n: usize, label: &str) -> Vec<([f32; 2], [f32; 2])> {
    draw(strategies::footprint(), n, label)
        .into_iter()
        .map(|f| (f2(f.dh_u), f2(f.dh_v)))
        .collect()
}

fn fp64(u: [f32; 2], v: [f32; 2]) -> Footprint {
    Footprint::from_slope_derivatives(v2(u), v2(v))
}

fn dn_vectors(rng: &mut SplitMix64, n: usize) -> Vec<[f32; 3]> {
    (0..n)
        .map(|_| {
            let len = rng.log_uniform(1e-6, 1.0);
            let d = DVec3::new(rng.normal(), rng.normal(), rng.normal()).normalize() * len;
            f3(d)
        })
        .collect()
}

fn mat_out(m: glam::DMat2) -> Vec<f64> {
    vec![m.x_axis.x, m.x_axis.y, m.y_axis.x, m.y_axis.y]
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, b| a.max(b.abs()))
}

/// The checks of `shaders/footprint/` and `shaders/kernel/`.
pub fn all() -> Vec<Check> {
    let mut rng = SplitMix64(0x666f_6f74);
    let hs = half_vectors(1500);
    let mut checks = Vec::new();
    let slope_imports = "#import filtered_ndf::footprint::slope";

    // slope_from_sphere: one division per component (2.5 ulp) -> 3 ulp.
    let mut c = Check::new(
        "slope::slope_from_sphere",
        slope_imports,
        "y2(0u, slope::slope_from_sphere(x3(0u)));",
        3,
        2,
    )
    .tolerance("3 ulp per component (one division)");
    for h in hs.iter().filter(|h| h[2] > 0.0) {
        let s = slope::slope_from_sphere(v3(*h));
        c.case(h.to_vec(), vec![s.x, s.y], vec![Tol::ulps(3.0); 2]);
    }
    checks.push(c);

    // sphere_from_slope: scaling, a length and a division: 6 EPS per component.
    let mut c = Check::new(
        "slope::sphere_from_slope",
        slope_imports,
        "y3(0u, slope::sphere_from_slope(x2(0u)));",
        2,
        3,
    )
    .tolerance("6 EPS absolute per component (scaling 2.5 ulp, length 4.5, division 2.5, of a unit vector)");
    let mut c2 = Check::new(
        "slope::projected_from_slope",
        slope_imports,
        "y2(0u, slope::projected_from_slope(x2(0u)));",
        2,
        2,
    )
    .tolerance("6 EPS absolute per component (as sphere_from_slope)");
    for h in hs.iter().filter(|h| h[2] > 0.0) {
        let sd = slope::slope_from_sphere(v3(*h));
        let s = [sd.x as f32, sd.y as f32];
        let r = slope::sphere_from_slope(v2(s));
        c.case(
            s.to_vec(),
            vec![r.x, r.y, r.z],
            vec![Tol::abs(6.0 * EPS); 3],
        );
        let p = slope::projected_from_slope(v2(s));
        c2.case(s.to_vec(), vec![p.x, p.y], vec![Tol::abs(6.0 * EPS); 2]);
    }
    checks.push(c);
    checks.push(c2);

    // sphere_from_projected / slope_from_projected: h_z = sqrt(1 - |p|^2) carries the
    // absolute error of |p|^2 (1.5 EPS) divided by 2 h_z, plus its own 4.5 ulp.
    let mut c = Check::new(
        "slope::sphere_from_projected",
        slope_imports,
        "y3(0u, slope::sphere_from_projected(x2(0u)));",
        2,
        3,
    )
    .tolerance("x, y exact inside the disk (6 EPS outside, rescaled); z within EPS / z + 5 EPS (1 - |p|^2 carries 1.5 EPS)");
    let mut c2 = Check::new(
        "slope::slope_from_projected",
        slope_imports,
        "y2(0u, slope::slope_from_projected(x2(0u)));",
        2,
        2,
    )
    .tolerance(
        "relative (EPS / z + 5 EPS) / z + 3 EPS per component (the error of z, then a division)",
    );
    let mut c3 = Check::new(
        "slope::projected_from_sphere",
        slope_imports,
        "y2(0u, slope::projected_from_sphere(x3(0u)));",
        3,
        2,
    )
    .tolerance("exact");
    for h in hs.iter().filter(|h| h[2] > 1e-3) {
        let p = [h[0], h[1]];
        let r = slope::sphere_from_projected(v2(p));
        let dz = EPS / r.z + 5.0 * EPS;
        // Outside the disk `p` is rescaled to unit length (6 EPS), inside it is kept.
        let xy = if v2(p).length() < 1.0 { 0.0 } else { 6.0 * EPS };
        c.case(
            p.to_vec(),
            vec![r.x, r.y, r.z],
            vec![Tol::abs(xy), Tol::abs(xy), Tol::abs(dz)],
        );
        let s = slope::slope_from_projected(v2(p));
        // Inside the disk only: outside it the slope saturates (at `F32_MAX` in f32, at
        // `f64::MAX` in the reference), as documented.
        if v2(p).length() >= 1.0 {
            continue;
        }
        c2.case(
            p.to_vec(),
            vec![s.x, s.y],
            vec![Tol::ulps(dz / r.z / EPS + 3.0); 2],
        );
        let q = slope::projected_from_sphere(v3(*h));
        c3.case(h.to_vec(), vec![q.x, q.y], vec![Tol::abs(0.0); 2]);
    }
    checks.push(c);
    checks.push(c2);
    checks.push(c3);

    // Jacobians.
    let jac = "#import filtered_ndf::footprint::jacobian";
    type MatFn = fn(DVec3) -> glam::DMat2;
    let mats: [(&str, MatFn, f64, &str); 4] = [
        (
            "sphere_to_projected",
            jacobian::sphere_to_projected,
            8.0,
            "8 EPS of the largest entry (normalisation, azimuth by hypot)",
        ),
        (
            "projected_to_slope",
            jacobian::projected_to_slope,
            20.0,
            "20 EPS of the largest entry (h_z's 4 ulp times 3 for 1/h_z^3, products)",
        ),
        (
            "slope_to_projected",
            jacobian::slope_to_projected,
            10.0,
            "10 EPS of the largest entry (h_z's 4 ulp, products)",
        ),
        (
            "sphere_to_slope",
            jacobian::sphere_to_slope,
            16.0,
            "16 EPS of the largest entry (h_z's 4 ulp times 2 for 1/h_z^2, azimuth)",
        ),
    ];
    for (name, f, k, why) in mats {
        let mut c = Check::new(
            &format!("jacobian::{name}"),
            jac,
            &format!("let m = jacobian::{name}(x3(0u)); y2(0u, m[0]); y2(2u, m[1]);"),
            3,
            4,
        )
        .tolerance(why);
        for h in &hs {
            let out = mat_out(f(v3(*h)));
            let tol = Tol::of_scale(k, max_abs(&out));
            c.case(h.to_vec(), out, vec![tol; 4]);
        }
        checks.push(c);
    }
    type DetFn = fn(DVec3) -> f64;
    let dets: [(&str, DetFn, f64); 3] = [
        (
            "det_sphere_to_projected",
            jacobian::det_sphere_to_projected,
            4.0,
        ),
        (
            "det_projected_to_slope",
            jacobian::det_projected_to_slope,
            20.0,
        ),
        ("det_sphere_to_slope", jacobian::det_sphere_to_slope, 16.0),
    ];
    for (name, f, k) in dets {
        let mut c = Check::new(
            &format!("jacobian::{name}"),
            jac,
            &format!("y(0u, jacobian::{name}(x3(0u)));"),
            3,
            1,
        )
        .tolerance(&format!(
            "{k} ulp relative (h_z's 4 ulp times the power, a division)"
        ));
        for h in &hs {
            c.case(h.to_vec(), vec![f(v3(*h))], vec![Tol::ulps(k)]);
        }
        checks.push(c);
    }
    let mut c = Check::new(
        "jacobian::sanitize",
        jac,
        "y3(0u, jacobian::sanitize(x3(0u)));",
        3,
        3,
    )
    .tolerance("6 EPS absolute per component (a normalisation)");
    let mut cb = Check::new(
        "jacobian::spherical_basis",
        jac,
        "let b = jacobian::spherical_basis(x3(0u)); y3(0u, b.e_x); y3(3u, b.e_y);",
        3,
        6,
    )
    .tolerance("8 EPS absolute per component (normalisation, azimuth)");
    let mut cc = Check::new(
        "jacobian::spherical_components",
        jac,
        "y2(0u, jacobian::spherical_components(x3(0u), x3(3u)));",
        6,
        2,
    )
    .tolerance("10 EPS |dh| absolute (the basis' 8 EPS, dot products)");
    let mut cs = Check::new(
        "jacobian::spherical_to_slope",
        jac,
        "y2(0u, jacobian::spherical_to_slope(x3(0u), x2(3u)));",
        5,
        2,
    )
    .tolerance("18 EPS |J|max |eps| absolute (sphere_to_slope's 16, the product)");
    let mut cp = Check::new(
        "jacobian::spherical_to_projected",
        jac,
        "y2(0u, jacobian::spherical_to_projected(x3(0u), x2(3u)));",
        5,
        2,
    )
    .tolerance("10 EPS |eps| absolute (sphere_to_projected's 8, the product)");
    for h in &hs {
        let hd = v3(*h);
        let s = jacobian::sanitize(hd);
        c.case(
            h.to_vec(),
            vec![s.x, s.y, s.z],
            vec![Tol::abs(6.0 * EPS); 3],
        );
        let (ex, ey) = jacobian::spherical_basis(hd);
        cb.case(
            h.to_vec(),
            vec![ex.x, ex.y, ex.z, ey.x, ey.y, ey.z],
            vec![Tol::abs(8.0 * EPS); 6],
        );
        let dh = f3(DVec3::new(rng.normal(), rng.normal(), rng.normal()) * 1e-2);
        let comp = jacobian::spherical_components(hd, v3(dh));
        let mut input = h.to_vec();
        input.extend(dh);
        cc.case(
            input,
            vec![comp.x, comp.y],
            vec![Tol::of_scale(10.0, v3(dh).length()); 2],
        );
        let e = [
            r32(rng.normal() * 1e-2) as f32,
            r32(rng.normal() * 1e-2) as f32,
        ];
        let mut input = h.to_vec();
        input.extend(e);
        let jmax = max_abs(&mat_out(jacobian::sphere_to_slope(hd)));
        let o = jacobian::spherical_to_slope(hd, v2(e));
        cs.case(
            input.clone(),
            vec![o.x, o.y],
            vec![Tol::of_scale(18.0, jmax * v2(e).length()); 2],
        );
        let o = jacobian::spherical_to_projected(hd, v2(e));
        cp.case(
            input,
            vec![o.x, o.y],
            vec![Tol::of_scale(10.0, v2(e).length()); 2],
        );
    }
    checks.extend([c, cb, cc, cs, cp]);

    // Footprint constructors and shapes.
    let fpi = "#import filtered_ndf::footprint";
    let fps = footprints(2000, "footprint fp");
    let mut c = Check::new(
        "covariance::from_footprint",
        "#import filtered_ndf::footprint\n#import filtered_ndf::kernel::covariance",
        "let c = covariance::from_footprint(footprint::from_slope_derivatives(x2(0u), x2(2u)), x(4u)); y4(0u, vec4<f32>(c.s_xx, c.s_xy, c.s_yy, c.det));",
        5,
        4,
    )
    .tolerance("s_xx, s_yy 3 ulp (sums of squares); s_xy 3 EPS (|u_x u_y| + |v_x v_y|) sigma^2; det 6 ulp + 3 EPS |cross| (|u_x v_y| + |u_y v_x|) sigma^4 + the f64 reference's 4e-16 s_xx s_yy");
    let mut cr = Check::new(
        "rect::from_footprint (kernel)",
        "#import filtered_ndf::footprint\n#import filtered_ndf::kernel::rect",
        "y2(0u, rect::from_footprint(footprint::from_slope_derivatives(x2(0u), x2(2u))).half_extent);",
        4,
        2,
    )
    .tolerance("1 ulp (a sum of magnitudes, halved)");
    let mut ce = Check::new(
        "footprint::max_extent",
        fpi,
        "y(0u, footprint::max_extent(footprint::from_slope_derivatives(x2(0u), x2(2u))));",
        4,
        1,
    )
    .tolerance(
        "5 ulp + 2 EPS (|dh_u| + |dh_v|) (the sums dh_u +- dh_v may cancel; length 4.5 ulp)",
    );
    for (u, v) in &fps {
        let sigma = 0.5f32;
        let f = fp64(*u, *v);
        let cov = f.covariance(0.5);
        let (ud, vd) = (v2(*u), v2(*v));
        let s2 = 0.25;
        let cross = ud.x * vd.y - ud.y * vd.x;
        let cross_terms = (ud.x * vd.y).abs() + (ud.y * vd.x).abs();
        let det_tol = Tol::rel_abs(
            6.0 * EPS,
            3.0 * EPS * cross.abs() * cross_terms * s2 * s2
                + 4e-16 * cov.s11 * cov.s22
                + super::TINY,
        );
        let xy_tol = Tol::rel_abs(
            0.0,
            3.0 * EPS * ((ud.x * ud.y).abs() + (vd.x * vd.y).abs()) * s2 + super::TINY,
        );
        let mut input = u.to_vec();
        input.extend(v);
        let mut ic = input.clone();
        ic.push(sigma);
        c.case(
            ic,
            vec![cov.s11, cov.s12, cov.s22, cov.det()],
            vec![Tol::ulps(3.0), xy_tol, Tol::ulps(3.0), det_tol],
        );
        let r = f.bounding_rect();
        cr.case(
            input.clone(),
            vec![r.half_extent.x, r.half_extent.y],
            vec![Tol::ulps(1.0); 2],
        );
        let mag = ud.length() + vd.length();
        ce.case(
            input,
            vec![f.max_extent()],
            vec![Tol::rel_abs(5.0 * EPS, 2.0 * EPS * mag + super::TINY)],
        );
    }
    checks.extend([c, cr, ce]);

    let mut c = Check::new(
        "footprint::from_projected_derivatives_in_slope",
        fpi,
        "let f = footprint::from_projected_derivatives_in_slope(x3(0u), x2(3u), x2(5u)); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        7,
        4,
    )
    .tolerance("20 EPS |J|max |dp| absolute (projected_to_slope's bound times the vector)");
    let mut cn = Check::new(
        "footprint::from_normal_differences",
        fpi,
        "let f = footprint::from_normal_differences(x3(0u), x3(3u)); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        6,
        4,
    )
    .tolerance("8 EPS |dn| absolute per component (a length and a division)");
    let mut cd = Check::new(
        "footprint::from_slope_derivatives",
        fpi,
        "let f = footprint::from_slope_derivatives(x2(0u), x2(2u)); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        4,
        4,
    )
    .tolerance("exact");
    let mut cq = Check::new(
        "footprint::from_projected_derivatives",
        fpi,
        "let f = footprint::from_projected_derivatives(x2(0u), x2(2u)); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        4,
        4,
    )
    .tolerance("exact");
    let dns = dn_vectors(&mut rng, 2 * hs.len());
    for (k, h) in hs.iter().enumerate() {
        let (u, v) = fps[k % fps.len()];
        let hd = v3(*h);
        let f = Footprint::from_projected_derivatives_in_slope(hd, v2(u), v2(v));
        let j = max_abs(&mat_out(jacobian::projected_to_slope(hd)));
        let mag = v2(u).length().max(v2(v).length());
        let mut input = h.to_vec();
        input.extend(u);
        input.extend(v);
        c.case(
            input,
            vec![f.dh_u.x, f.dh_u.y, f.dh_v.x, f.dh_v.y],
            vec![Tol::of_scale(20.0, j * mag); 4],
        );
        let (a, b) = (dns[2 * k], dns[2 * k + 1]);
        let f = Footprint::from_normal_differences(v3(a), v3(b));
        let mut input = a.to_vec();
        input.extend(b);
        let m = v3(a).length().max(v3(b).length());
        cn.case(
            input,
            vec![f.dh_u.x, f.dh_u.y, f.dh_v.x, f.dh_v.y],
            vec![Tol::of_scale(8.0, m); 4],
        );
        let mut input = u.to_vec();
        input.extend(v);
        let exact = vec![u[0].into(), u[1].into(), v[0].into(), v[1].into()];
        cd.case(input.clone(), exact.clone(), vec![Tol::abs(0.0); 4]);
        cq.case(input, exact, vec![Tol::abs(0.0); 4]);
    }
    checks.extend([c, cn, cd, cq]);

    checks.extend(kernel_checks(&fps, &mut rng));
    checks
}

/// `shaders/kernel/`: covariance, rect, clamp.
fn kernel_checks(fps: &[([f32; 2], [f32; 2])], rng: &mut SplitMix64) -> Vec<Check> {
    let mut checks = Vec::new();
    let imports = "#import filtered_ndf::footprint\n#import filtered_ndf::kernel::covariance\n#import filtered_ndf::kernel::rect\n#import filtered_ndf::kernel::clamp";
    let from_fp = "let c = covariance::from_footprint(footprint::from_slope_derivatives(x2(0u), x2(2u)), 0.5);";

    // eigenvalues: lambda_max = mean + hypot (8 ulp on top of the entries' 3), lambda_min =
    // det / lambda_max (the carried det's tolerance plus 3 ulp).
    let mut ce = Check::new(
        "covariance::eigenvalues",
        imports,
        &format!("{from_fp} y2(0u, covariance::eigenvalues(c));"),
        4,
        2,
    )
    .tolerance("lambda_max 12 ulp (entries 3, hypot 8, sum 1); lambda_min: det's tolerance / lambda_max + 12 ulp");
    // clamp_eigenvalues with TK19's kappa / 2 = 0.09 and sanitized (identity on PSD
    // footprint kernels): entries within 24 EPS of the largest eigenvalue involved (scaling,
    // the radius, the projectors: a few divisions, each 2.5 ulp, on entries of 3 ulp).
    let mut cc = Check::new(
        "covariance::clamp_eigenvalues",
        imports,
        &format!(
            "{from_fp} let k = covariance::clamp_eigenvalues(c, x(4u)); y4(0u, vec4<f32>(k.s_xx, k.s_xy, k.s_yy, k.det));"
        ),
        5,
        4,
    )
    .tolerance("entries 24 EPS min(lambda_max, bound) absolute; det 24 ulp + the covariance's det tolerance");
    let mut ck = Check::new(
        "clamp::kernel",
        imports,
        &format!(
            "{from_fp} let k = clamp::kernel(clamp::DEFAULT_RULES, c); y3(0u, vec3<f32>(k.s_xx, k.s_xy, k.s_yy));"
        ),
        4,
        3,
    )
    .tolerance("as clamp_eigenvalues, with kappa / 2 = 0.09 (sanitized is the identity on footprint kernels)");
    for (u, v) in fps {
        let f = fp64(*u, *v);
        let cov = f.covariance(0.5);
        let (ud, vd) = (v2(*u), v2(*v));
        let cross = ud.x * vd.y - ud.y * vd.x;
        let cross_terms = (ud.x * vd.y).abs() + (ud.y * vd.x).abs();
        let det_abs =
            3.0 * EPS * cross.abs() * cross_terms / 16.0 + 4e-16 * cov.s11 * cov.s22 + super::TINY;
        let (lmin, lmax) = cov.eigenvalues();
        let mut input = u.to_vec();
        input.extend(v);
        ce.case(
            input.clone(),
            vec![lmin, lmax],
            vec![
                Tol::rel_abs(12.0 * EPS, det_abs / lmax.max(1e-300) + super::TINY),
                Tol::ulps(12.0),
            ],
        );
        let bound = r32(if rng.uniform() < 0.5 {
            0.09
        } else {
            rng.log_uniform(1e-12, 1.0)
        });
        let k = cov.clamp_eigenvalues(bound);
        let scale = lmax.min(bound);
        let e = Tol::of_scale(24.0, scale);
        let kdet = k.s11 * k.s22 - k.s12 * k.s12;
        let mut ib = input.clone();
        ib.push(bound as f32);
        cc.case(
            ib,
            vec![k.s11, k.s12, k.s22, kdet],
            vec![
                e,
                e,
                e,
                Tol::rel_abs(24.0 * EPS, det_abs + 8e-16 * scale * scale + super::TINY),
            ],
        );
        let k = ClampRules::default().kernel(cov);
        let e = Tol::of_scale(24.0, lmax.min(0.09));
        ck.case(input, vec![k.s11, k.s12, k.s22], vec![e; 3]);
    }
    checks.extend([ce, cc, ck]);

    // The zero kernel: constant, exactly zero (one case; its entries are multiplied by the
    // input 1, exactly, so that the shader reads its input buffer).
    let mut z = Check::new(
        "covariance::zero",
        imports,
        "let k = covariance::zero(); y4(0u, vec4<f32>(k.s_xx, k.s_xy, k.s_yy, k.det) * x(0u));",
        1,
        4,
    )
    .tolerance("exact (every entry and the determinant 0)");
    let k = Covariance::ZERO;
    z.case(
        vec![1.0],
        vec![k.s11, k.s12, k.s22, k.s11 * k.s22 - k.s12 * k.s12],
        vec![Tol::abs(0.0); 4],
    );
    checks.push(z);

    // sanitized on arbitrary (indefinite, negative, huge) entries.
    let mut cs = Check::new(
        "covariance::sanitized",
        imports,
        "let k = covariance::sanitized(covariance::from_entries(x(0u), x(1u), x(2u))); y3(0u, vec3<f32>(k.s_xx, k.s_xy, k.s_yy));",
        3,
        3,
    )
    .tolerance("24 EPS of the largest entry (the PSD projection is exact up to sqrt s_xx sqrt s_yy, 9 ulp; then clamp_eigenvalues)");
    for _ in 0..2000 {
        let mut e = || {
            let m = rng.log_uniform(1e-8, 1e9);
            r32(if rng.uniform() < 0.3 { -m } else { m })
        };
        let (a, b, c) = (e(), e(), e());
        let k = Covariance::new(a, b, c).sanitized();
        let m = max_abs(&[k.s11, k.s12, k.s22]);
        cs.case(
            vec![a as f32, b as f32, c as f32],
            vec![k.s11, k.s12, k.s22],
            vec![Tol::of_scale(24.0, m); 3],
        );
    }
    checks.push(cs);

    // Covariance arithmetic and the rectangle's covariance.
    let mut ct = Check::new(
        "covariance::trace",
        imports,
        &format!("{from_fp} y(0u, covariance::trace(c));"),
        4,
        1,
    )
    .tolerance("4 ulp (entries 3, one sum)");
    let mut ca = Check::new(
        "covariance::add",
        imports,
        &format!(
            "{from_fp} let s = covariance::add(c, covariance::scaled(c, 0.5)); y4(0u, vec4<f32>(s.s_xx, s.s_xy, s.s_yy, s.det));"
        ),
        4,
        4,
    )
    .tolerance("entries as covariance::from_footprint plus 2 ulp; det 12 ulp, the carried determinants' tolerance, and 4 EPS (|a_xx b_yy| + |a_yy b_xx| + 2 |a_xy b_xy|) for the cross term, which cancels for kernels elongated along one direction");
    let mut crc = Check::new(
        "rect::covariance",
        imports,
        "let k = rect::covariance(rect::BoundingRect(x2(0u)), 0.5); y4(0u, vec4<f32>(k.s_xx, k.s_xy, k.s_yy, k.det));",
        2,
        4,
    )
    .tolerance("2 ulp entries (two products), 3 ulp det");
    for (u, v) in fps {
        let f = fp64(*u, *v);
        let cov = f.covariance(0.5);
        let mut input = u.to_vec();
        input.extend(v);
        ct.case(input.clone(), vec![cov.trace()], vec![Tol::ulps(4.0)]);
        let s = cov + cov * 0.5;
        let (ud, vd) = (v2(*u), v2(*v));
        let cross = ud.x * vd.y - ud.y * vd.x;
        let cross_terms = (ud.x * vd.y).abs() + (ud.y * vd.x).abs();
        let det_abs =
            3.0 * EPS * cross.abs() * cross_terms / 16.0 + 4e-16 * cov.s11 * cov.s22 + super::TINY;
        let xy = Tol::abs(
            5.0 * EPS * ((ud.x * ud.y).abs() + (vd.x * vd.y).abs()) * 0.25 * 1.5 + super::TINY,
        );
        ca.case(
            input,
            vec![s.s11, s.s12, s.s22, s.det()],
            vec![
                Tol::ulps(5.0),
                xy,
                Tol::ulps(5.0),
                // The carried determinants' errors, and the cross term
                // a_xx b_yy + a_yy b_xx - 2 a_xy b_xy, which cancels when both kernels are
                // elongated along one direction (here b = a / 2).
                Tol::rel_abs(
                    12.0 * EPS,
                    2.0 * det_abs
                        + 4.0 * EPS * 0.5 * (2.0 * cov.s11 * cov.s22 + 2.0 * cov.s12 * cov.s12)
                        + 4e-16 * s.s11 * s.s22,
                ),
            ],
        );
        let r = f.bounding_rect();
        let k = r.covariance(0.5);
        crc.case(
            vec![r.half_extent.x as f32, r.half_extent.y as f32],
            vec![k.s11, k.s12, k.s22, k.det()],
            vec![
                Tol::ulps(2.0),
                Tol::abs(0.0),
                Tol::ulps(2.0),
                Tol::ulps(3.0),
            ],
        );
    }
    checks.extend([ct, ca, crc]);

    // Clamp rules: footprint (max extent), rect (floors), tau.
    let mut cf = Check::new(
        "clamp::footprint",
        imports,
        "let f = clamp::footprint(clamp::DEFAULT_RULES, footprint::from_slope_derivatives(x2(0u), x2(2u))); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        4,
        4,
    )
    .tolerance("exact when not clamped; else 12 EPS lambda absolute (scaling, the extent's 5 ulp, two divisions)");
    let mut crd = Check::new(
        "clamp::rect",
        imports,
        "let d = clamp::rect(clamp::DEFAULT_RULES, rect::BoundingRect(x2(0u)), x2(2u)); let g = clamp::rect(clamp::GDC2016_RULES, rect::BoundingRect(x2(0u)), x2(2u)); y2(0u, d.half_extent); y2(2u, g.half_extent);",
        4,
        4,
    )
    .tolerance("exact (min and max of the inputs and the rules' constants)");
    let big = footprints(1500, "clamp fp big");
    for (k, (u, v)) in fps.iter().chain(big.iter()).enumerate() {
        // Half of the second set scaled past lambda = 1.
        let s = if k >= fps.len() && k % 2 == 0 {
            rng.log_uniform(1.0, 1e6) as f32
        } else {
            1.0
        };
        let (u, v) = ([u[0] * s, u[1] * s], [v[0] * s, v[1] * s]);
        let f = ClampRules::default().footprint(fp64(u, v));
        let mut input = u.to_vec();
        input.extend(v);
        let clamped = f != fp64(u, v);
        let t = if clamped {
            Tol::abs(12.0 * EPS)
        } else {
            Tol::abs(0.0)
        };
        cf.case(
            input.clone(),
            vec![f.dh_u.x, f.dh_u.y, f.dh_v.x, f.dh_v.y],
            vec![t; 4],
        );
        let he = [
            (u[0].abs() + v[0].abs()) * 0.5,
            (u[1].abs() + v[1].abs()) * 0.5,
        ];
        let alpha = [
            rng.log_uniform(1e-4, 2.0) as f32,
            rng.log_uniform(1e-4, 2.0) as f32,
        ];
        let r = BoundingRect::new(v2(he));
        let d = ClampRules::default().rect(r, v2(alpha));
        let g = ClampRules::GDC2016.rect(r, v2(alpha));
        let mut input = he.to_vec();
        input.extend(alpha);
        crd.case(
            input,
            vec![
                d.half_extent.x,
                d.half_extent.y,
                g.half_extent.x,
                g.half_extent.y,
            ],
            vec![Tol::ulps(0.5); 4],
        );
    }
    checks.extend([cf, crd]);
    checks
}
