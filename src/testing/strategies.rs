//! proptest strategies for downstream property tests (feature `testing`).
//!
//! They draw the inputs this crate's own tests use: roughness log-uniform over the
//! supported working range in all three forms, unit directions in the upper hemisphere with
//! the pole and the horizon weighted in, and slope-domain footprints from zero to large. All
//! values are `f64` (the reference precision); cast for an `f32` port.

use super::linalg::Sym2;
use crate::f64::{AxisAligned, Footprint, Isotropic, RoughnessMatrix};
use glam::{DVec2, DVec3};
use proptest::prelude::*;

/// Log-uniform roughness `alpha` in `[lo, hi]` (both `> 0`).
pub fn alpha_in(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

/// Isotropic roughness, `alpha` log-uniform in `[1e-4, 2]`.
pub fn isotropic() -> impl Strategy<Value = Isotropic> {
    alpha_in(1e-4, 2.0).prop_map(|a| Isotropic::new(a).expect("in range"))
}

/// Axis-aligned roughness: `alpha_x` log-uniform in `[1e-4, 2]`, anisotropy ratio
/// `alpha_y / alpha_x` log-uniform in `[1e-3, 1e3]` (clamped into the supported range).
pub fn axis_aligned() -> impl Strategy<Value = AxisAligned> {
    (alpha_in(1e-4, 2.0), alpha_in(1e-3, 1e3))
        .prop_map(|(a, r)| AxisAligned::new_clamped(a, (a * r).clamp(1e-6, 1e3)))
}

/// Full matrix `A = R diag(ax^2, ay^2) R^T` with `ax`, `ay` as in [`axis_aligned`] and a
/// uniform rotation angle.
pub fn matrix() -> impl Strategy<Value = RoughnessMatrix> {
    (axis_aligned(), 0.0..core::f64::consts::PI).prop_map(|(r, phi)| rotated(r.alpha(), phi))
}

/// `R(phi) diag(alpha_x^2, alpha_y^2) R(phi)^T` as a checked [`RoughnessMatrix`] (clamped
/// into the supported range if rounding pushes an eigenvalue out of it).
pub fn rotated(alpha: DVec2, phi: f64) -> RoughnessMatrix {
    let (a11, a12, a22) = Sym2::from_eigen(alpha.x * alpha.x, alpha.y * alpha.y, phi).entries();
    RoughnessMatrix::new(a11, a12, a22)
        .unwrap_or_else(|_| AxisAligned::new_clamped(alpha.x, alpha.y).into())
}

/// A unit direction in the upper hemisphere (`z > 0`), polar angle up to `max_theta_deg`:
/// one draw in eight exactly at the pole, one in eight within 0.1 degree of
/// `max_theta_deg`, the rest uniform in `cos(theta)`.
pub fn upper_hemisphere(max_theta_deg: f64) -> impl Strategy<Value = DVec3> {
    let t_max = max_theta_deg.to_radians();
    let theta = prop_oneof![
        1 => Just(0.0),
        1 => (t_max - 0.1f64.to_radians()).max(0.0)..=t_max,
        6 => (t_max.cos()..=1.0).prop_map(f64::acos),
    ];
    (theta, 0.0..core::f64::consts::TAU).prop_map(|(t, p)| {
        let (st, ct) = t.sin_cos();
        DVec3::new(st * p.cos(), st * p.sin(), ct)
    })
}

/// A slope-domain footprint with per-axis extents log-uniform in `[1e-6, 1]`, plus exact
/// zero footprints one draw in eight.
pub fn footprint() -> impl Strategy<Value = Footprint> {
    prop_oneof![
        1 => Just(Footprint::ZERO),
        7 => (slope_vector(), slope_vector())
            .prop_map(|(u, w)| Footprint::from_slope_derivatives(u, w)),
    ]
}

/// A slope-domain vector with length log-uniform in `[1e-6, 1]` and uniform direction.
pub fn slope_vector() -> impl Strategy<Value = DVec2> {
    (alpha_in(1e-6, 1.0), 0.0..core::f64::consts::TAU)
        .prop_map(|(r, p)| DVec2::new(r * p.cos(), r * p.sin()))
}
