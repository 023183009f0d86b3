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
fn in_direct_range(l2: F) -> bool {
    (F::MIN_POSITIVE / F::EPSILON..=F::MAX).contains(&l2)
}

/// `|v|` without overflow or underflow of the squares. `0` for a zero vector; NaN if a
/// component is NaN; `+inf` for an infinite component, or when the length itself exceeds
/// `F::MAX`.
#[inline]
pub fn length(v: Vec3) -> F {
    let l2 = v.length_squared();
    if in_direct_range(l2) {
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

/// `(v / |v|, |v|)` without overflow or underflow for a vector type (module docs): the one body
/// of [`unit_and_length`] and [`unit2_and_length`].
macro_rules! unit_and_length_of {
    ($v:expr) => {{
        let v = $v;
        let l2 = v.length_squared();
        if in_direct_range(l2) {
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
    }};
}

/// `(v / |v|, |v|)` without overflow or underflow (module docs). `None` for a zero or
/// non-finite `v`. The direction is a unit vector to rounding for every finite, non-zero `v`
/// (also subnormal or near `F::MAX`); the length may be `+inf` when it exceeds `F::MAX`.
#[inline]
pub fn unit_and_length(v: Vec3) -> Option<(Vec3, F)> {
    unit_and_length_of!(v)
}

/// `v / |v|` ([`unit_and_length`] without the length). `None` for a zero or non-finite `v`.
#[inline]
pub fn unit(v: Vec3) -> Option<Vec3> {
    unit_and_length(v).map(|(u, _)| u)
}

/// `(v / |v|, |v|)` for a 2-vector, as [`unit_and_length`]. `None` for a zero or non-finite
/// `v`.
#[inline]
pub fn unit2_and_length(v: Vec2) -> Option<(Vec2, F)> {
    unit_and_length_of!(v)
}

/// `v / |v|` for a 2-vector, as [`unit()`]. `None` for a zero or non-finite `v`.
#[inline]
pub fn unit2(v: Vec2) -> Option<Vec2> {
    unit2_and_length(v).map(|(u, _)| u)
}

/// `v` with each NaN component replaced by `0`, infinite components kept: the crate's policy
/// for derivative inputs (footprints and normal differences, [`crate::contract`]): a NaN
/// carries no information, so it contributes no widening.
#[inline(always)]
pub fn nan_to_zero(v: Vec3) -> Vec3 {
    Vec3::select(v.is_nan_mask(), Vec3::ZERO, v)
}

/// [`nan_to_zero`] for a 2-vector.
#[inline(always)]
pub fn nan_to_zero2(v: Vec2) -> Vec2 {
    Vec2::select(v.is_nan_mask(), Vec2::ZERO, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Real;

    /// `|len(v) - 1| <= 4 eps`: a division per component and a square root.
    fn is_unit(v: Vec3) -> bool {
        let l = (v.x.to_f64().powi(2) + v.y.to_f64().powi(2) + v.z.to_f64().powi(2)).sqrt();
        (l - 1.0).abs() <= 4.0 * F::EPSILON.to_f64()
    }

    #[test]
    fn unit_and_length_over_the_whole_range() {
        let tiny = F::MIN_POSITIVE * F::EPSILON; // the smallest subnormal
        for k in [1.0, 1e-30, tiny, 3.0 * tiny, F::MAX, F::MAX / 3.0, 1e30] {
            let v = Vec3::new(0.36, -0.48, 0.8) * k;
            let (u, len) = unit_and_length(v).unwrap_or_else(|| panic!("{k}: {v}"));
            assert!(is_unit(u), "{k}: {u}");
            // The length against f64 (exact enough for both precisions' inputs), where it is
            // representable and normal (a subnormal length has only a few bits): 4 eps.
            let want = (v.x.to_f64().powi(2) + v.y.to_f64().powi(2) + v.z.to_f64().powi(2)).sqrt();
            if want.is_finite() && want >= F::MIN_POSITIVE.to_f64() {
                let rel = (len.to_f64() - want).abs() / want;
                assert!(rel <= 4.0 * F::EPSILON.to_f64(), "{k}: {len} vs {want}");
                assert_eq!(length(v), len);
            }
            let u2 = unit2(Vec2::new(0.6, -0.8) * k).unwrap_or_else(|| panic!("{k}"));
            assert!(is_unit(Vec3::new(u2.x, u2.y, 0.0)), "{k}: {u2}");
        }
        // A unit vector comes back bit for bit (the direct path).
        assert_eq!(unit(Vec3::Z), Some(Vec3::Z));
        // No direction: zero, NaN, infinite.
        for v in [
            Vec3::ZERO,
            Vec3::new(F::NAN, 0.0, 1.0),
            Vec3::new(F::INFINITY, 0.0, 0.0),
        ] {
            assert_eq!(unit(v), None);
            assert_eq!(unit2(Vec2::new(v.x, v.y)), None);
        }
        assert!(length(Vec3::new(F::NAN, 1.0, 0.0)).is_nan());
        assert_eq!(length(Vec3::new(F::NEG_INFINITY, 1.0, 0.0)), F::INFINITY);
        assert_eq!(length(Vec3::ZERO), 0.0);
        // Beyond F::MAX: the direction is still unit, the length +inf.
        let (u, len) = unit_and_length(Vec3::splat(F::MAX)).unwrap();
        assert!(is_unit(u) && len == F::INFINITY);
    }
}
