//! The `f64` quadratures of an NDF's normalisation and Smith identity, shared by
//! `tests/ndf_normalization.rs`, `tests/ndf_smith.rs` and `tests/ndf_det_clamp.rs` (included with
//! `#[path = "common/ndf_integrals.rs"] mod ndf_integrals;`). The lobe's frame comes from the
//! caller's own description of the roughness (axes and angle, or the matrix `A`), never from the
//! code under test; tolerances are stated where the results are asserted.
#![allow(dead_code)]

use filtered_ndf::f64::Ndf;
use filtered_ndf::testing::quadrature::{
    Estimate, Tolerance, integrate, integrate_2d, integrate_line, integrate_plane,
};
use glam::{DMat2, DVec2, DVec3};

/// `integral of P22(s) ds` over the slope plane, in the eigen frame of the lobe (a rotation by
/// `phi0`: unit Jacobian) with the widths `(ax, ay)`, asked for `1e-10` relative.
pub fn slope_plane_integral(ndf: &dyn Ndf, ax: f64, ay: f64, phi0: f64) -> Estimate {
    let rot = DVec2::from_angle(phi0);
    integrate_plane(
        |u, v| ndf.p22(rot.rotate(DVec2::new(u, v))),
        (0.0, 0.0),
        (ax, ay),
        Tolerance::relative(1e-10),
    )
}

/// `integral of D(m) cos(theta) sin(theta) dtheta dphi` in spherical coordinates, asked for
/// `1e-10` relative. The peak is resolved by an elliptic substitution: `tan(theta) = rho
/// L(psi)`, `rho = tau / (1 - tau)`, `phi = phi0 + atan2(a_y sin psi, a_x cos psi)`, `L(psi) =
/// |(a_x cos psi, a_y sin psi)|`.
pub fn hemisphere_integral(ndf: &dyn Ndf, ax: f64, ay: f64, phi0: f64) -> Estimate {
    integrate_2d(
        |tau, psi| {
            let (sp, cp) = psi.sin_cos();
            let l2 = ax * ax * cp * cp + ay * ay * sp * sp;
            let l = l2.sqrt();
            let rho = tau / (1.0 - tau);
            let drho = 1.0 / ((1.0 - tau) * (1.0 - tau));
            let t = rho * l; // tan(theta)
            let ct = 1.0 / (1.0 + t * t).sqrt();
            let st = t * ct;
            let dtheta = l * drho / (1.0 + t * t);
            let dphi = ax * ay / l2;
            let phi = phi0 + (ay * sp).atan2(ax * cp);
            let m = DVec3::new(st * phi.cos(), st * phi.sin(), ct);
            ndf.d(m) * ct * st * dtheta * dphi
        },
        (0.0, 1.0),
        (0.0, std::f64::consts::TAU),
        Tolerance::relative(1e-10),
    )
}

/// `integral of max(0, o.m) D(m) dm`, the right side of the Smith identity, by quadrature in the
/// slope plane (`tests/ndf_smith.rs` docs: the frame `(a, b)` with `a` along `o_xy`, the kink an
/// end point of the outer range, the inner integral centred on the conditional peak of the
/// quadratic form of `a`, the lobe's roughness matrix). Asked for `1e-11` relative (inner
/// `1e-12`).
pub fn projected_area(ndf: &dyn Ndf, a: DMat2, o: DVec3) -> f64 {
    let oxy = o.truncate();
    let r = oxy.length();
    let inv = a.inverse();
    let ea = if r > 0.0 { oxy / r } else { DVec2::X };
    let eb = ea.perp();
    let (iab, ibb) = (ea.dot(inv * eb), eb.dot(inv * eb));
    let wb = 1.0 / ibb.sqrt();
    let wa = ea.dot(a * ea).sqrt();
    let inner_tol = Tolerance::relative(1e-12);
    let inner = |x: f64| {
        let c = -x * iab / ibb;
        integrate_line(|y| ndf.p22(ea * x + eb * y), c, wb, inner_tol).value
    };
    let tol = Tolerance::relative(1e-11);
    if r == 0.0 {
        // Normal incidence: max(0, o_z) = o_z everywhere; integrate over the whole line.
        return o.z * integrate_line(inner, 0.0, wa, tol).value;
    }
    let a0 = o.z / r;
    let weight = |x: f64| (o.z - r * x).max(0.0);
    // (-inf, 0]: x = -wa u / (1 - u).
    let left = integrate(
        |u| {
            let x = -wa * u / (1.0 - u);
            let v = weight(x) * inner(x) * wa / ((1.0 - u) * (1.0 - u));
            if v.is_finite() { v } else { 0.0 }
        },
        0.0,
        1.0,
        tol,
    );
    // [0, a0]: x = wa u / (1 - u), u in [0, a0 / (a0 + wa)].
    let u0 = a0 / (a0 + wa);
    let right = integrate(
        |u| {
            let x = wa * u / (1.0 - u);
            weight(x) * inner(x) * wa / ((1.0 - u) * (1.0 - u))
        },
        0.0,
        u0,
        tol,
    );
    left.value + right.value
}
