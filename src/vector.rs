//! Lengths and directions of vectors that neither overflow nor underflow for any finite
//! input ("rescale, then normalise"). Every stage that normalises a caller's vector (half
//! vectors, directions, gradients, normal rates) uses these, so the guard exists once.
//!
//! Why: `|v|^2` leaves the float range for components beyond `sqrt(F::MAX)` (`~1.8e19` in
//! `f32`) or below `sqrt(F::MIN_POSITIVE)` (`~1.1e-19`), and glam's `normalize` then returns
//! a non-unit vector, `inf` or NaN. Where `|v|^2` is a normal number at least `1 / eps` times
//! the smallest (an underflowed square then weighs below `eps^2`), `v / |v|` is formed
//! directly (one rounding per component; a unit vector comes back bit for bit); otherwise
//! the largest component is factored out first, after which `|v|^2` lies in `[1, 3]`.

use super::{F, Vec2, Vec3};
use crate::math as m;

/// The squared lengths for which `v / sqrt(|v|^2)` needs no rescaling (module docs).
#[inline(always)]
fn direct(l2: F) -> bool {
    (F::MIN_POSITIVE / F::EPSILON..=F::MAX).contains(&l2)
}

/// `|v|` without overflow or underflow of the squares. `0` for a zero vector; NaN if a
/// component is NaN; `+inf` for an infinite component, or when the length itself exceeds
/// `F::MAX`.
#[inline]
pub fn length(v: Vec3) -> F {
    let l2 = v.length_squared();
    if direct(l2) {
        return m::sqrt(l2);
    }
    // `max_element` skips NaN: test the vector itself.
    if v.is_nan() {
        return F::NAN;
    }
    let big = v.abs().max_element();
    if !(big > 0.0 && big.is_finite()) {
        return big;
    }
    let u = v / big;
    m::sqrt(u.length_squared()) * big
}

/// `(v / |v|, |v|)` without overflow or underflow (module docs). `None` for a zero or
/// non-finite `v`. The direction is a unit vector to rounding for every finite, non-zero `v`
/// (also subnormal or near `F::MAX`); the length may be `+inf` when it exceeds `F::MAX`.
#[inline]
pub fn unit_and_length(v: Vec3) -> Option<(Vec3, F)> {
    let l2 = v.length_squared();
    if direct(l2) {
        let len = m::sqrt(l2);
        return Some((v / len, len));
    }
    let big = v.abs().max_element();
    if !(v.is_finite() && big > 0.0) {
        return None;
    }
    let u = v / big;
    let len = m::sqrt(u.length_squared());
    Some((u / len, len * big))
}

/// `v / |v|` ([`unit_and_length`] without the length). `None` for a zero or non-finite `v`.
#[inline]
pub fn unit(v: Vec3) -> Option<Vec3> {
    unit_and_length(v).map(|(u, _)| u)
}

/// `v / |v|` for a 2-vector, as [`unit()`]. `None` for a zero or non-finite `v`.
#[inline]
pub fn unit2(v: Vec2) -> Option<Vec2> {
    let l2 = v.length_squared();
    if direct(l2) {
        return Some(v / m::sqrt(l2));
    }
    let big = v.abs().max_element();
    if !(v.is_finite() && big > 0.0) {
        return None;
    }
    let u = v / big;
    Some(u / m::sqrt(u.length_squared()))
}
