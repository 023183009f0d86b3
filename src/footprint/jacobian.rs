//! Jacobians between the three half-vector domains (TK19 supplement section 2, eq. 1-7) and
//! the error propagation of TK19 section 3.1.
//!
//! The domains are those of [`super::slope`]: the **sphere** (unit `h`, tangent frame, `z` =
//! shading normal `n`), the **projected disk** `p = h_xy` ("perp", TK19 section 3.2) and the
//! **slope** plane `s = -h_xy / h_z` ("par", TK19 supplement eq. 5). The point maps themselves
//! live in [`super::slope`]; this module holds only their derivatives.
//!
//! ## The spherical coordinates `(psi_x, psi_y)`
//! A spherical-domain change of `h` is measured, as in TK19 supplement eq. 1-3, by two arc
//! lengths (radians): `psi_x` along the great circle through `h` and `n` (positive away from
//! `n`, i.e. along `e_x = (cos theta cos phi, cos theta sin phi, -sin theta)`) and `psi_y` along
//! the great circle through `h` and `n x h / |n x h|` (along `e_y = (-sin phi, cos phi, 0)`),
//! where `h = (sin theta cos phi, sin theta sin phi, cos theta)`. [`spherical_basis`] returns
//! `(e_x, e_y)`.
//!
//! ## Matrix layout
//! Every matrix is the paper's Jacobian `J[i][j] = d out_i / d in_j` (row = output component,
//! column = input component), stored in glam's column-major `Mat2` so that column `j` is
//! `J.col(j) = (d out_x / d in_j, d out_y / d in_j)`: `m.x_axis` is the derivative with respect
//! to the first input, `m.y_axis` with respect to the second, and `m * v` is the paper's
//! column-vector product `J v`. (glam's `Mat2::from_cols_array(&[a, b, c, d])` therefore holds
//! the paper's `[[a, c], [b, d]]`.)
//!
//! ## Signs
//! The crate's slope is `-h_xy / h_z` (TK19), so `J(perp->par)` and `J(o->par)` carry the
//! paper's leading minus sign; KHPL16's slope `+h_xy / h_z` flips the sign of both matrices.
//! A 2x2 matrix's determinant is unchanged by negation, so all three determinants are
//! positive (checked against finite differences in `tests/jacobian.rs`):
//! `det J(o->perp) = h_z`, `det J(perp->par) = 1 / h_z^4`, `det J(o->par) = 1 / h_z^3`
//! (TK19 section 3.1, 3.2). `(psi_x, psi_y)` is a right-handed pair around the outward `h`, and
//! the sign flip of the slope map is a rotation by pi, so no map reverses orientation.
//!
//! ## Pole and horizon
//! At the pole `h = n` the frame `(e_x, e_y)` is undefined (the papers' formulas divide by
//! `sqrt(1 - h_z^2)`). Approaching the pole along the meridian of azimuth `phi`,
//! `J(o->perp) -> R(phi)` (the rotation by `phi`) and `J(o->par) -> -R(phi)`: the matrices have
//! no `phi`-independent limit, only their determinants and `J^T J` do. This module computes
//! `cos phi, sin phi = h_xy / |h_xy|` (with `|h_xy|` by `hypot`, accurate near the pole, never
//! `sqrt(1 - h_z^2)`), so the limit along each meridian is attained continuously, and at the
//! pole itself it chooses `phi = 0`: `e_x = +x`, `e_y = +y`, `J(o->perp) = I`,
//! `J(o->par) = J(perp->par) = -I`. `J(perp->par)` and `J(par->perp)` are smooth at the pole.
//!
//! At the horizon the slope maps blow up like `1 / h_z^2`. Every function clamps `h_z` from
//! below to [`HZ_MIN`] while keeping the azimuth (`h` is replaced by
//! `(sqrt(1 - HZ_MIN^2) cos phi, sqrt(1 - HZ_MIN^2) sin phi, HZ_MIN)`), so results stay finite
//! in `f32` (entries at most `~1e12`, determinants at most `1e24`).
//!
//! ## Input contract
//! `h` is normalised internally (any positive multiple of a direction gives the same result).
//! Below the horizon (`h_z < HZ_MIN`, including `h = -n`, which gets `phi = 0`) the horizon
//! clamp above applies. A zero or non-finite `h` is treated as the pole `h = n`. No function
//! here panics; the matrices and determinants are finite for every input. The products with a
//! vector (`spherical_components`, `spherical_to_slope`, `spherical_to_projected`) are NaN for
//! a NaN vector and, like any matrix product, may overflow (to `inf`, or NaN as `inf - inf`)
//! for finite vectors beyond about `1e26` (`f32`, at the horizon clamp).

use super::super::vector;
use super::{F, Mat2, Vec2, Vec3};
use crate::math as m;

/// Smallest `h_z` the Jacobians use (`h` is at most `89.99994` degrees from the normal): below
/// it `h_z` is clamped to this value, keeping the azimuth. Chosen so `1 / HZ_MIN^4 = 1e24` and
/// the squares of the largest entries (`1e24`) stay finite in `f32`.
pub const HZ_MIN: F = 1e-6;

/// A half vector reduced to what the Jacobians need: the sanitised unit `h`, `(cos phi, sin phi)`
/// and `sin theta`.
#[derive(Clone, Copy)]
struct Polar {
    h: Vec3,
    cos_phi: F,
    sin_phi: F,
}

/// Normalise, apply the pole choice and the horizon clamp (module docs).
#[inline]
fn polar(h: Vec3) -> Polar {
    let Some(h) = vector::unit(h) else {
        return Polar {
            h: Vec3::Z,
            cos_phi: 1.0,
            sin_phi: 0.0,
        };
    };
    // The azimuth from `h_xy` scaled to unit size: `h_x / hypot(h_x, h_y)` is not a unit
    // pair for subnormal components (fuzzing).
    let (cos_phi, sin_phi) = match vector::unit2(Vec2::new(h.x, h.y)) {
        Some(q) => (q.x, q.y),
        None => (1.0, 0.0),
    };
    if h.z >= HZ_MIN {
        Polar {
            h,
            cos_phi,
            sin_phi,
        }
    } else {
        let st = m::sqrt(1.0 - HZ_MIN * HZ_MIN);
        Polar {
            h: Vec3::new(st * cos_phi, st * sin_phi, HZ_MIN),
            cos_phi,
            sin_phi,
        }
    }
}

/// The unit half vector the Jacobians actually use for input `h`: `h` normalised, a zero or
/// non-finite `h` replaced by `n = +z`, and `h_z` clamped to [`HZ_MIN`] at constant azimuth.
#[inline]
pub fn sanitize(h: Vec3) -> Vec3 {
    polar(h).h
}

/// The spherical-domain basis `(e_x, e_y)` at `h` (TK19 supplement eq. 3, columns 1 and 2):
/// `e_x = (cos theta cos phi, cos theta sin phi, -sin theta)` is the unit tangent of the great
/// circle through `h` and `n` (pointing away from `n`), `e_y = (-sin phi, cos phi, 0)` =
/// `n x h / |n x h|` the unit tangent of the great circle through `h` and `n x h`. With `h` they
/// form a right-handed orthonormal frame. At the pole `phi = 0`: `(+x, +y)`. Input as in the
/// module docs.
#[inline]
pub fn spherical_basis(h: Vec3) -> (Vec3, Vec3) {
    basis(&polar(h))
}

/// [`spherical_basis`] of a sanitised half vector.
#[inline]
fn basis(p: &Polar) -> (Vec3, Vec3) {
    let st = m::hypot(p.h.x, p.h.y);
    (
        Vec3::new(p.h.z * p.cos_phi, p.h.z * p.sin_phi, -st),
        Vec3::new(-p.sin_phi, p.cos_phi, 0.0),
    )
}

/// Spherical-domain components `(eps_x, eps_y) = (dh . e_x, dh . e_y)` (radians) of a tangent
/// change `dh` of the unit half vector (TK19 section 3.1); the radial part `dh . h` (zero for
/// the derivative of a unit vector) is dropped. Basis as in [`spherical_basis`].
#[inline]
pub fn spherical_components(h: Vec3, dh: Vec3) -> Vec2 {
    let (ex, ey) = spherical_basis(h);
    Vec2::new(dh.dot(ex), dh.dot(ey))
}

/// `J(o->perp)`: spherical `(psi_x, psi_y)` (radians) to projected disk `p = h_xy` (TK19
/// supplement eq. 4; TK19 section 3.2):
/// `1 / sqrt(1 - h_z^2) [[h_x h_z, -h_y], [h_y h_z, h_x]] = [[h_z cos phi, -sin phi],
/// [h_z sin phi, cos phi]]`, evaluated in the second form (no division by `sqrt(1 - h_z^2)`).
/// Determinant `h_z` ([`det_sphere_to_projected`]). Pole and horizon as in the module docs
/// (`I` at the pole).
#[inline]
pub fn sphere_to_projected(h: Vec3) -> Mat2 {
    let p = polar(h);
    Mat2::from_cols(
        Vec2::new(p.h.z * p.cos_phi, p.h.z * p.sin_phi),
        Vec2::new(-p.sin_phi, p.cos_phi),
    )
}

/// `J(perp->par)`: projected disk `p = h_xy` to slope `s = -p / sqrt(1 - |p|^2)` (TK19
/// supplement eq. 6): `-1 / h_z^3 [[1 - h_y^2, h_x h_y], [h_x h_y, 1 - h_x^2]]` (symmetric),
/// with `1 - h_y^2` evaluated as `h_x^2 + h_z^2` for accuracy at the horizon. Determinant
/// `1 / h_z^4` ([`det_projected_to_slope`]); `-I` at the pole. Horizon clamp as in the module
/// docs. Units: slope per unit disk length. For a disk point `p`, pass
/// `slope::sphere_from_projected(p)`.
#[inline]
pub fn projected_to_slope(h: Vec3) -> Mat2 {
    let h = polar(h).h;
    let k = -1.0 / (h.z * h.z * h.z);
    let xy = h.x * h.y;
    Mat2::from_cols(
        Vec2::new(h.x * h.x + h.z * h.z, xy) * k,
        Vec2::new(xy, h.y * h.y + h.z * h.z) * k,
    )
}

/// `J(par->perp) = J(perp->par)^-1`: slope to projected disk, `dp/ds = -h_z (I - p p^T)` with
/// `p = h_xy`, i.e. `-h_z [[1 - h_x^2, -h_x h_y], [-h_x h_y, 1 - h_y^2]]` (derived from
/// `p = -s / sqrt(1 + |s|^2)`; the inverse of TK19 supplement eq. 6). Determinant `h_z^4`.
/// Used for TK19's projected-space footprint (section 3.2). Finite everywhere; `-I` at the
/// pole; horizon clamp as in the module docs.
#[inline]
pub fn slope_to_projected(h: Vec3) -> Mat2 {
    let h = polar(h).h;
    let xy = h.x * h.y;
    Mat2::from_cols(
        Vec2::new(h.y * h.y + h.z * h.z, -xy) * -h.z,
        Vec2::new(-xy, h.x * h.x + h.z * h.z) * -h.z,
    )
}

/// `J(o->par)`: spherical `(psi_x, psi_y)` (radians) to slope (TK19 supplement eq. 7; TK19
/// section 3.1): `-1 / (h_z^2 sqrt(1 - h_z^2)) [[h_x, -h_y h_z], [h_y, h_x h_z]]
/// = -1 / h_z^2 [[cos phi, -h_z sin phi], [sin phi, h_z cos phi]]`, evaluated in the second
/// form. Equals `projected_to_slope(h) * sphere_to_projected(h)` (the composition identity of
/// the supplement). Determinant `1 / h_z^3` ([`det_sphere_to_slope`]); `-I` at the pole.
/// Horizon clamp as in the module docs. Units: slope per radian.
#[inline]
pub fn sphere_to_slope(h: Vec3) -> Mat2 {
    sphere_to_slope_of(&polar(h))
}

/// [`sphere_to_slope`] of a sanitised half vector.
#[inline]
fn sphere_to_slope_of(p: &Polar) -> Mat2 {
    let k = -1.0 / (p.h.z * p.h.z);
    Mat2::from_cols(
        Vec2::new(p.cos_phi, p.sin_phi) * k,
        Vec2::new(-p.h.z * p.sin_phi, p.h.z * p.cos_phi) * k,
    )
}

/// `J(o->par)` in Cartesian form: the rows `(ds_x/dh, ds_y/dh)` of the derivative of the slope
/// with respect to the unit half vector, restricted to its tangent plane:
/// `[ds_x/dh; ds_y/dh] = J(o->par) [e_x; e_y]` ([`sphere_to_slope`] composed with the basis of
/// [`spherical_basis`]; TK19 supplement eq. 1-3 and 7). A change `dh` of the unit half vector
/// moves the slope by `(ds_x/dh . dh, ds_y/dh . dh)`; the radial part of `dh` (along `h`) has
/// no effect. Equals `(-e_x + h_x/h_z e_z, -e_y + h_y/h_z e_z) / h_z` (the gradient of
/// `s = -h_xy / h_z`) on the tangent plane. Input as in the module docs.
#[inline]
pub fn unit_vector_to_slope(h: Vec3) -> [Vec3; 2] {
    let p = polar(h);
    let j = sphere_to_slope_of(&p);
    let (e_x, e_y) = basis(&p);
    [
        e_x * j.x_axis.x + e_y * j.y_axis.x,
        e_x * j.x_axis.y + e_y * j.y_axis.y,
    ]
}

/// `det J(o->perp) = h_z` (TK19 section 3.2; `<= 1`: the projected disk shrinks errors).
/// `h_z` after the input sanitising of the module docs, so in `[HZ_MIN, 1]`.
#[inline]
pub fn det_sphere_to_projected(h: Vec3) -> F {
    polar(h).h.z
}

/// `det J(perp->par) = 1 / h_z^4` (from TK19 supplement eq. 6). In `[1, 1e24]`.
#[inline]
pub fn det_projected_to_slope(h: Vec3) -> F {
    let z = polar(h).h.z;
    let z2 = z * z;
    1.0 / (z2 * z2)
}

/// `det J(o->par) = 1 / h_z^3` (TK19 section 3.1; `>= 1`: the slope domain amplifies
/// spherical errors, without bound at grazing angles). In `[1, 1e18]`.
#[inline]
pub fn det_sphere_to_slope(h: Vec3) -> F {
    let z = polar(h).h.z;
    1.0 / (z * z * z)
}

/// Error propagation of TK19 section 3.1: a spherical-domain error or derivative
/// `(eps_x, eps_y)` (radians along `e_x`, `e_y`, see [`spherical_basis`]) mapped to the slope
/// domain, `eps_par = J(o->par) eps` ([`sphere_to_slope`]). Its size grows like `1 / h_z^2`
/// towards the horizon, which is the paper's explanation of grazing-angle artifacts.
#[inline]
pub fn spherical_to_slope(h: Vec3, eps: Vec2) -> Vec2 {
    sphere_to_slope(h) * eps
}

/// The same error mapped to the projected disk, `eps_perp = J(o->perp) eps`
/// ([`sphere_to_projected`]; TK19 section 3.2): no larger than `|eps|`.
#[inline]
pub fn spherical_to_projected(h: Vec3, eps: Vec2) -> Vec2 {
    sphere_to_projected(h) * eps
}
