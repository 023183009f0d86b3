//! Fresnel reflectance of a microfacet: the fraction of unpolarised light a smooth interface
//! reflects at the angle `theta` between the direction and the microfacet normal `m`
//! (`cos theta = wo.m = wi.m` for a reflection).
//!
//! | type | formula | source |
//! |---|---|---|
//! | [`FresnelOne`] | `1` | a perfect mirror's facets (the white furnace) |
//! | [`Schlick`] | `F0 + (1 - F0) (1 - cos theta)^5` | Schlick 1994 (Computer Graphics Forum 13(3)) |
//! | [`Dielectric`] | exact, unpolarised, real index `eta` (total internal reflection: `1`) | Walter et al. 2007 eq. 22 |
//! | [`Conductor`] | exact, unpolarised, complex index `eta + i k` | Born and Wolf, *Principles of Optics*, the Fresnel formulae with a complex index; pbrt-v4 section 9.3 (`FrComplex`) |
//!
//! A reflectance is a [`Spectrum`]: one value `F` (grey, or one wavelength) or three
//! (`Vec3`, RGB: [`Schlick`] and [`Conductor`] take their parameters per channel).
//!
//! **Indices are relative:** `eta` is the index of the medium behind the interface over the
//! index of the medium the light arrives from (water seen from air: `1.33`; from inside the
//! water: `1 / 1.33`); `k` the extinction coefficient over the same outside index.
//!
//! **Out of domain:** `cos theta` is clamped to `[-1, 1]` and NaN taken as `0` (grazing, where
//! every form but [`FresnelOne`] reflects everything); every reflectance is in `[0, 1]`,
//! never NaN. The checked constructors refuse parameters outside the domain
//! ([`FresnelError`]).

use super::super::{F, Vec3};
use crate::error::FresnelError;
use crate::math as m;
use core::ops::Mul;

/// The reflectance of an interface at `cos theta` (module docs).
pub trait Fresnel {
    /// One value per channel: [`F`] or [`Vec3`] (RGB).
    type Value: Spectrum;

    /// The unpolarised reflectance at the angle `theta` between the direction and the
    /// microfacet normal, `cos theta` in `[-1, 1]` (module docs for negative values and NaN).
    /// In `[0, 1]` per channel.
    fn reflectance(&self, cos_theta: F) -> Self::Value;
}

/// A reflectance per channel: one value ([`F`]) or three ([`Vec3`], RGB). Sealed.
pub trait Spectrum: Copy + core::fmt::Debug + PartialEq + Mul<F, Output = Self> + Sealed {
    /// Every channel `v`.
    fn splat(v: F) -> Self;
    /// `f` per channel.
    fn map(self, f: impl Fn(F) -> F) -> Self;
    /// `f` per channel of `self` and `other`.
    fn zip_map(self, other: Self, f: impl Fn(F, F) -> F) -> Self;
    /// Whether `p` holds for every channel.
    fn all(self, p: impl Fn(F) -> bool) -> bool;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::F {}
    impl Sealed for super::Vec3 {}
}
use sealed::Sealed;

impl Spectrum for F {
    #[inline]
    fn splat(v: F) -> Self {
        v
    }
    #[inline]
    fn map(self, f: impl Fn(F) -> F) -> Self {
        f(self)
    }
    #[inline]
    fn zip_map(self, other: Self, f: impl Fn(F, F) -> F) -> Self {
        f(self, other)
    }
    #[inline]
    fn all(self, p: impl Fn(F) -> bool) -> bool {
        p(self)
    }
}

impl Spectrum for Vec3 {
    #[inline]
    fn splat(v: F) -> Self {
        Vec3::splat(v)
    }
    #[inline]
    fn map(self, f: impl Fn(F) -> F) -> Self {
        Vec3::new(f(self.x), f(self.y), f(self.z))
    }
    #[inline]
    fn zip_map(self, other: Self, f: impl Fn(F, F) -> F) -> Self {
        Vec3::new(f(self.x, other.x), f(self.y, other.y), f(self.z, other.z))
    }
    #[inline]
    fn all(self, p: impl Fn(F) -> bool) -> bool {
        p(self.x) && p(self.y) && p(self.z)
    }
}

/// `cos theta` clamped to `[-1, 1]`, NaN as `0` (module docs).
#[inline]
fn clamp_cos(c: F) -> F {
    if c.is_nan() { 0.0 } else { c.clamp(-1.0, 1.0) }
}

/// `F = 1` at every angle: a surface whose facets reflect everything (the white furnace
/// test's Fresnel, or a BSDF whose caller applies its own Fresnel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FresnelOne;

impl Fresnel for FresnelOne {
    type Value = F;
    #[inline]
    fn reflectance(&self, _cos_theta: F) -> F {
        1.0
    }
}

/// Schlick's approximation `F = F0 + (1 - F0) (1 - |cos theta|)^5` (Schlick 1994, "An
/// Inexpensive BRDF Model for Physically-based Rendering"), `F0` the reflectance at normal
/// incidence, per channel. Exact at normal and grazing incidence; between them it follows
/// the dielectric's curve to a few hundredths for `eta` near 1.5 and misses Brewster's
/// minimum. Symmetric in `cos theta` (no total internal reflection).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schlick<S = F> {
    /// The reflectance at normal incidence, per channel, in `[0, 1]`.
    pub f0: S,
}

impl<S: Spectrum> Schlick<S> {
    /// Schlick's approximation with normal-incidence reflectance `f0`; an error for a channel
    /// outside `[0, 1]` or NaN.
    #[inline]
    pub fn new(f0: S) -> Result<Self, FresnelError> {
        if !f0.all(|v| v.is_finite()) {
            Err(FresnelError::NotFinite)
        } else if !f0.all(|v| (0.0..=1.0).contains(&v)) {
            Err(FresnelError::OutOfRange)
        } else {
            Ok(Self { f0 })
        }
    }
}

impl Schlick<F> {
    /// Schlick's approximation of the dielectric of relative index `eta`:
    /// `F0 = ((eta - 1) / (eta + 1))^2`. An error for `eta <= 0` or a non-finite `eta`.
    #[inline]
    pub fn from_ior(eta: F) -> Result<Self, FresnelError> {
        check_ior(eta)?;
        let r = (eta - 1.0) / (eta + 1.0);
        Ok(Self { f0: r * r })
    }
}

impl<S: Spectrum> Fresnel for Schlick<S> {
    type Value = S;
    #[inline]
    fn reflectance(&self, cos_theta: F) -> S {
        let x = 1.0 - clamp_cos(cos_theta).abs();
        let x2 = x * x;
        let w = x2 * x2 * x;
        self.f0.map(|f0| m::mul_add(1.0 - f0, w, f0))
    }
}

/// `Ok` for a finite `eta > 0`.
#[inline]
fn check_ior(eta: F) -> Result<(), FresnelError> {
    if !eta.is_finite() {
        Err(FresnelError::NotFinite)
    } else if eta <= 0.0 {
        Err(FresnelError::OutOfRange)
    } else {
        Ok(())
    }
}

/// The exact unpolarised reflectance of a smooth dielectric interface of relative index
/// `eta` (Walter et al. 2007 eq. 22):
///
/// `F = 1/2 (g - c)^2 / (g + c)^2 (1 + (c (g + c) - 1)^2 / (c (g - c) + 1)^2)`,
/// `c = |cos theta|`, `g = sqrt(eta^2 - 1 + c^2)`,
///
/// the mean of the squared `s` and `p` amplitude ratios of Fresnel's equations. `g^2 <= 0` is
/// total internal reflection (`F = 1`), which happens for `eta < 1` beyond the critical angle
/// `sin theta_c = eta`. A negative `cos theta` is light arriving from behind the interface:
/// the index is inverted (`1 / eta`) and `c = -cos theta`. `eta = 1` reflects nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    /// The relative index of refraction, behind over in front (module docs), `> 0`.
    pub eta: F,
}

impl Dielectric {
    /// The interface of relative index `eta`; an error for `eta <= 0` or a non-finite `eta`.
    #[inline]
    pub fn new(eta: F) -> Result<Self, FresnelError> {
        check_ior(eta).map(|()| Self { eta })
    }
}

impl Fresnel for Dielectric {
    type Value = F;
    #[inline]
    fn reflectance(&self, cos_theta: F) -> F {
        let c = clamp_cos(cos_theta);
        if c < 0.0 {
            dielectric(1.0 / self.eta, -c)
        } else {
            dielectric(self.eta, c)
        }
    }
}

/// Walter et al. 2007 eq. 22 for `c = cos theta` in `[0, 1]` and `eta > 0`.
#[inline]
fn dielectric(eta: F, c: F) -> F {
    if eta == 1.0 {
        // Index matched: no interface (and `g = c = 0` at grazing would be 0 / 0).
        return 0.0;
    }
    let g2 = m::mul_add(eta, eta, -1.0) + c * c;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = m::sqrt(g2);
    let a = (g - c) / (g + c);
    // `c (g - c) + 1 >= 1 - c^2 + c g > 0` for `c` in `[0, 1]` (`= eta` at `c = 1`).
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    (0.5 * a * a * (1.0 + b * b)).clamp(0.0, 1.0)
}

/// The exact unpolarised reflectance of a smooth conductor of relative complex index
/// `eta + i k` (`k >= 0` the extinction coefficient), per channel:
///
/// `R = (|r_s|^2 + |r_p|^2) / 2`, `r_s = (c - w) / (c + w)`,
/// `r_p = (n^2 c - w) / (n^2 c + w)`, `n = eta + i k`, `w = sqrt(n^2 - sin^2 theta)`
/// (`= n cos theta_t`, principal branch), `c = |cos theta|`:
///
/// Fresnel's equations with a complex index (Born and Wolf, *Principles of Optics*, the
/// optics of metals; pbrt-v4 section 9.3, `FrComplex`, is the same formula written through
/// `cos theta_t`). For `k > 0`, `n^2 - sin^2 theta` has a positive imaginary part `2 eta k`,
/// so `w` has positive real and imaginary parts (the refracted wave decays into the metal)
/// and neither denominator vanishes. `k = 0` is the dielectric ([`Dielectric`]'s formula for
/// `c >= 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor<S = F> {
    /// The real part of the relative index, per channel, `> 0`.
    pub eta: S,
    /// The extinction coefficient (imaginary part of the index), per channel, `>= 0`.
    pub k: S,
}

impl<S: Spectrum> Conductor<S> {
    /// The conductor of relative complex index `eta + i k`; an error for a channel with
    /// `eta <= 0`, `k < 0` or a non-finite value.
    #[inline]
    pub fn new(eta: S, k: S) -> Result<Self, FresnelError> {
        if !(eta.all(|v| v.is_finite()) && k.all(|v| v.is_finite())) {
            Err(FresnelError::NotFinite)
        } else if !(eta.all(|v| v > 0.0) && k.all(|v| v >= 0.0)) {
            Err(FresnelError::OutOfRange)
        } else {
            Ok(Self { eta, k })
        }
    }
}

impl<S: Spectrum> Fresnel for Conductor<S> {
    type Value = S;
    #[inline]
    fn reflectance(&self, cos_theta: F) -> S {
        let c = clamp_cos(cos_theta).abs();
        self.eta.zip_map(self.k, |eta, k| conductor(eta, k, c))
    }
}

/// A complex number `re + i im` (the few operations [`conductor`] needs).
#[derive(Clone, Copy)]
struct Complex {
    re: F,
    im: F,
}

impl Complex {
    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
    #[inline]
    fn scale(self, s: F) -> Self {
        Self {
            re: self.re * s,
            im: self.im * s,
        }
    }
    /// `|z|^2`.
    #[inline]
    fn norm2(self) -> F {
        self.re * self.re + self.im * self.im
    }
    /// The principal square root (`re >= 0`), without cancellation: the larger part from
    /// `sqrt((|z| +- re) / 2)`, the other from `im / (2 larger)`.
    #[inline]
    fn sqrt(self) -> Self {
        let r = m::hypot(self.re, self.im);
        if r == 0.0 {
            return Self { re: 0.0, im: 0.0 };
        }
        if self.re >= 0.0 {
            let re = m::sqrt(0.5 * (r + self.re));
            Self {
                re,
                im: self.im / (2.0 * re),
            }
        } else {
            let im = m::sqrt(0.5 * (r - self.re)).copysign(self.im);
            Self {
                re: self.im / (2.0 * im),
                im,
            }
        }
    }
}

/// `|a - b|^2 / |a + b|^2`.
#[inline]
fn ratio2(a: Complex, b: Complex) -> F {
    let den = a.add(b).norm2();
    if den > 0.0 {
        a.sub(b).norm2() / den
    } else {
        1.0
    }
}

/// The conductor's reflectance ([`Conductor`]) for `c = |cos theta|` in `[0, 1]`.
#[inline]
fn conductor(eta: F, k: F, c: F) -> F {
    if k == 0.0 {
        return dielectric(eta, c);
    }
    let sin2 = (1.0 - c * c).max(0.0);
    // n^2 = eta^2 - k^2 + 2 i eta k.
    let n2 = Complex {
        re: (eta - k) * (eta + k),
        im: 2.0 * eta * k,
    };
    let w = Complex {
        re: n2.re - sin2,
        im: n2.im,
    }
    .sqrt();
    let cc = Complex { re: c, im: 0.0 };
    let rs = ratio2(cc, w);
    let rp = ratio2(n2.scale(c), w);
    (0.5 * (rs + rp)).clamp(0.0, 1.0)
}
