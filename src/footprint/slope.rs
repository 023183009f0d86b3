//! The three half-vector domains and the maps between them (TK19 supplement eq. 1-5).
//!
//! - **Sphere**: a unit vector `h` in the tangent frame (`z` = shading normal).
//! - **Projected disk**: `p = (h_x, h_y)`, the orthographic projection on the unit disk
//!   (TK19 section 3.2).
//! - **Slope**: `s = (-h_x / h_z, -h_y / h_z)` (TK19 supplement eq. 5; Heitz 2014). KHPL16
//!   writes `h_xy / h_z`; the NDFs are even in `s`, so only signs of derivatives differ.
//!
//! Every map is defined on the upper hemisphere `h_z > 0` (open disk `|p| < 1`, whole slope
//! plane). Outside it the functions document a finite answer instead of a NaN.

use super::super::vector;
use super::{F, Vec2, Vec3};
use crate::math as m;

/// Slope of a unit vector: `s = -h_xy / h_z` (TK19 supplement eq. 5).
///
/// For `h_z <= 0` (horizon or below) there is no finite slope: returns the slope of the
/// direction clamped to `h_z = F::MIN_POSITIVE`, which is finite for a unit `h` and far in every
/// NDF's tail (densities there evaluate to 0).
#[inline]
pub fn slope_from_sphere(h: Vec3) -> Vec2 {
    let z = h.z.max(F::MIN_POSITIVE);
    let s = Vec2::new(-h.x / z, -h.y / z);
    if s.is_finite() {
        s
    } else {
        s.clamp(Vec2::splat(-F::MAX), Vec2::splat(F::MAX))
    }
}

/// Unit vector of a slope: `h = (-s_x, -s_y, 1) / sqrt(1 + |s|^2)` (inverse of
/// [`slope_from_sphere`]). For huge `|s|` the result tends to the horizon direction `-s/|s|`;
/// an infinite component gives the horizon direction of the infinite components' signs, a NaN
/// component a NaN result.
#[inline]
pub fn sphere_from_slope(s: Vec2) -> Vec3 {
    let v = Vec3::new(-s.x, -s.y, 1.0);
    let len = m::sqrt(v.length_squared());
    if len.is_finite() {
        return v / len;
    }
    // `1 + |s|^2` overflowed (huge or infinite `s`) or is NaN: the horizon direction of `s`,
    // or of the signs of its infinite components.
    let inf = |x: F| if x.is_infinite() { x.signum() } else { 0.0 };
    let d = if s.is_finite() {
        s
    } else {
        Vec2::new(inf(s.x), inf(s.y))
    };
    match vector::unit2(d) {
        Some(d) if !s.is_nan() => Vec3::new(-d.x, -d.y, 0.0),
        _ => Vec3::new(F::NAN, F::NAN, 0.0),
    }
}

/// Projection on the unit disk: `p = (h_x, h_y)` (TK19 section 3.2).
#[inline]
pub fn projected_from_sphere(h: Vec3) -> Vec2 {
    Vec2::new(h.x, h.y)
}

/// Upper-hemisphere unit vector over a disk point: `h = (p_x, p_y, sqrt(1 - |p|^2))`. Points
/// outside the disk map to the horizon (`h_z = 0`, `p` rescaled to unit length).
#[inline]
pub fn sphere_from_projected(p: Vec2) -> Vec3 {
    let r2 = p.length_squared();
    if r2 < 1.0 {
        Vec3::new(p.x, p.y, m::sqrt(1.0 - r2))
    } else {
        // Rescaled first so that a huge `p` does not overflow the length; NaN or infinite
        // `p`: the zero direction at the horizon.
        let q = vector::unit2(p).unwrap_or(Vec2::ZERO);
        Vec3::new(q.x, q.y, 0.0)
    }
}

/// Slope of a disk point: `s = -p / sqrt(1 - |p|^2)` (TK19 supplement eq. 5). Points on or
/// outside the unit circle are treated as in [`slope_from_sphere`].
#[inline]
pub fn slope_from_projected(p: Vec2) -> Vec2 {
    slope_from_sphere(sphere_from_projected(p))
}

/// Disk point of a slope: `p = -s / sqrt(1 + |s|^2)`.
#[inline]
pub fn projected_from_slope(s: Vec2) -> Vec2 {
    projected_from_sphere(sphere_from_slope(s))
}
