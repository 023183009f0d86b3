//! The interface shared by every NDF, and the Smith terms derived from `Lambda` once.
//!
//! Conventions (all NDFs, all roughness forms):
//! - Tangent frame with `z` the shading normal; directions are unit vectors in that frame.
//! - Slope of a micronormal `m` (`m_z > 0`): `s = (-m_x / m_z, -m_y / m_z)` (TK19 supplement
//!   eq. 5, Heitz 2014); see [`super::footprint::slope`].
//! - `p22(s)`: slope-domain density, per unit slope area, integrating to 1 over the plane.
//! - `d(m) = p22(s(m)) / m_z^4`: solid-angle density, normalised so that the projected area
//!   is one, `integral of d(m) m_z dm = 1` over the upper hemisphere (KHPL16 eq. 2).
//!
//! NaN policy (every NDF, every roughness form): **a NaN argument contributes nothing.** An
//! argument with a NaN component gives `p22 = d = 0` and `lambda = +inf`, hence
//! `g1 = g2 = 0` (a NaN in `m` as well). A renderer that meets a NaN direction thus adds no
//! light and no pdf, whatever the family; it is the same answer as for a direction beyond
//! the horizon. Decided once, here, and tested for both families (`tests/contract.rs`).

use super::{F, Mat2, Vec2, Vec3};

/// The three checked constructors of an NDF, one per roughness form (`isotropic`,
/// `axis_aligned`, `matrix`), each the form's checked constructor wrapped in `new`.
macro_rules! checked_constructors {
    ($ndf:ident, $name:literal) => {
        impl $ndf<Isotropic> {
            #[doc = concat!("Isotropic ", $name, ", checked (see [`Isotropic::new`]).")]
            #[inline]
            pub fn isotropic(alpha: F) -> Result<Self, RoughnessError> {
                Isotropic::new(alpha).map(Self::new)
            }
        }

        impl $ndf<AxisAligned> {
            #[doc = concat!("Axis-aligned ", $name, ", checked (see [`AxisAligned::new`]).")]
            #[inline]
            pub fn axis_aligned(alpha_x: F, alpha_y: F) -> Result<Self, RoughnessError> {
                AxisAligned::new(alpha_x, alpha_y).map(Self::new)
            }
        }

        impl $ndf<RoughnessMatrix> {
            #[doc = concat!("Full-matrix ", $name, ", checked (see [`RoughnessMatrix::new`]).")]
            #[inline]
            pub fn matrix(a11: F, a12: F, a22: F) -> Result<Self, RoughnessError> {
                RoughnessMatrix::new(a11, a12, a22).map(Self::new)
            }
        }
    };
}

pub mod beckmann;
pub mod ggx;
pub mod roughness;

/// A microfacet normal distribution with Smith masking-shadowing.
pub trait Ndf {
    /// Slope-domain density `P22(s)` (per unit slope area). Finite and `>= 0` for finite `s`;
    /// `0` where `s` is so far in the tail that the density underflows, for an infinite and
    /// for a NaN component (module docs).
    fn p22(&self, s: super::Vec2) -> F;

    /// Solid-angle density `D(m) = P22(s(m)) / m_z^4` (per steradian, KHPL16 eq. 2) for a
    /// unit micronormal `m`. `0` for `m_z <= 0` (the `chi+` factor) and for a non-finite
    /// component (NaN: module docs); finite for finite input.
    fn d(&self, m: Vec3) -> F;

    /// Smith `Lambda(w)` for a direction `w`, using `|w_z|` (TK19 supplement section 1).
    /// `Lambda` is homogeneous of degree 0, so `w` need not be unit: a vector far from unit
    /// length (huge or tiny but finite) is rescaled first. `+inf` at `w_z = 0` (the correct
    /// limit: a grazing direction is fully masked) and for a NaN component (module docs), `0`
    /// for a zero vector.
    fn lambda(&self, w: Vec3) -> F;

    /// Smith masking `G1(w, m) = chi+(w.m) / (1 + Lambda(w))` (TK19 supplement section 1).
    /// In `[0, 1]`; `0` for `w.m <= 0`, for grazing `w` and for a NaN component.
    #[inline]
    fn g1(&self, w: Vec3, m: Vec3) -> F {
        // `>` is false for NaN: a NaN direction masks completely (the NaN policy).
        if w.dot(m) > 0.0 {
            1.0 / (1.0 + self.lambda(w))
        } else {
            0.0
        }
    }

    /// Height-correlated masking-shadowing
    /// `G2(i, o, m) = chi+(i.m) chi+(o.m) / (1 + Lambda(i) + Lambda(o))` (TK19 supplement
    /// section 1; Heitz 2014 eq. 99). In `[0, 1]`; `0` for a NaN component.
    #[inline]
    fn g2(&self, i: Vec3, o: Vec3, m: Vec3) -> F {
        if i.dot(m) > 0.0 && o.dot(m) > 0.0 {
            1.0 / (1.0 + self.lambda(i) + self.lambda(o))
        } else {
            0.0
        }
    }
}

/// Whether [`rescale_direction`] returns `w` itself: `|w|^2` in `(2^-40, 2^40)` (false for
/// NaN).
#[inline(always)]
pub(crate) fn needs_no_rescale(w: Vec3) -> bool {
    let l2 = w.length_squared();
    const LO: F = 1.0 / (1u64 << 40) as F;
    const HI: F = (1u64 << 40) as F;
    l2 > LO && l2 < HI
}

/// Smith's `Lambda` outside its formula's domain, from `q = w_xy^T A w_xy` and `|w_z|`, for
/// both NDFs (the NaN policy of [`Ndf`]): `+inf` for NaN input and for a grazing `w`
/// (`|w_z| = 0` with `q > 0`), `0` for `q <= 0` (normal incidence, the zero vector); `None`
/// inside the domain (`q > 0`, `|w_z| > 0`).
#[inline(always)]
pub(crate) fn lambda_outside_domain(q: F, abs_wz: F) -> Option<F> {
    if q.is_nan() || abs_wz.is_nan() {
        Some(F::INFINITY)
    } else if q <= 0.0 {
        Some(0.0)
    } else if abs_wz <= 0.0 {
        Some(F::INFINITY)
    } else {
        None
    }
}

/// `w` rescaled by its largest component when `|w|^2` is outside `[2^-40, 2^40]`, so that the
/// quadratic forms of `Lambda` neither overflow nor underflow for huge or tiny finite input.
/// Unit vectors pass through untouched (one compare). Where that would make a normal `w_z`
/// subnormal (a view within `F::MIN_POSITIVE` of grazing relative to `|w|`, whose `Lambda`
/// can still be finite: `alpha |w_xy| / (2 |w_z|)`), `w` is scaled instead so that `|w_z|` is
/// the smallest normal number, keeping its digits (`|w_xy|` then stays below
/// `F::MAX / |w_z| * F::MIN_POSITIVE`, finite): a subnormal `w_z` of `(1e34, 4e-11, 4e-11)`
/// in `f32` had cost GGX's `Lambda` 20 % (found by the box lobe's fuzz contract). A `w_z`
/// subnormal on input is scaled up exactly by `2^(MANTISSA_DIGITS - 1)` instead (all its
/// digits; the division by `mx` would round it to a multiple of the smallest subnormal: `7e-12`
/// in `f64` for `w = (1e-40, 3.9e-11, 5e-324)`, found the same way).
#[inline]
pub(crate) fn rescale_direction(w: Vec3) -> Vec3 {
    if needs_no_rescale(w) {
        return w;
    }
    let mx = w.abs().max_element();
    if !(mx > 0.0 && mx.is_finite()) {
        return w;
    }
    let v = w / mx;
    let az = w.z.abs();
    if v.z.abs() >= F::MIN_POSITIVE || az == 0.0 {
        v
    } else if az >= F::MIN_POSITIVE {
        if v.z == 0.0 {
            // `|w_xy| / |w_z|` beyond `F::MAX`: grazing to every digit `F` has.
            return v;
        }
        // `az < mx F::MIN_POSITIVE <= 4` here, so the divisor is finite and normal.
        w / (az / F::MIN_POSITIVE)
    } else {
        // `w_z` subnormal on input (and `v.z` too, so `mx > az / F::MIN_POSITIVE >=
        // 2^-(MANTISSA_DIGITS - 1)`): scaled up exactly by `2^(MANTISSA_DIGITS - 1)`, which
        // makes every subnormal normal, with its digits; `|w_xy|` lands at least near 1, so
        // nothing underflows. Where that overflows, `|w_xy| / |w_z|` exceeds `F::MAX` and `v`
        // (grazing) is as good.
        let s = w * SUBNORMAL_LIFT;
        if s.is_finite() { s } else { v }
    }
}

/// `2^(MANTISSA_DIGITS - 1)`: times the smallest subnormal, the smallest normal number.
const SUBNORMAL_LIFT: F = (1u64 << (F::MANTISSA_DIGITS - 1)) as F;
