//! Microfacet reflection over any lobe of the front door, for path tracers: the BRDF, its
//! importance sampling by visible normals and its pdf, with a Fresnel term ([`fresnel`]).
//!
//! ```
//! use filtered_ndf::f32::prelude::*;
//! use filtered_ndf::f32::bsdf::{Bsdf, Dielectric, MicrofacetReflection};
//! use glam::{Vec2, Vec3};
//!
//! let material = Ggx::isotropic(0.01).unwrap();
//! let footprint = Footprint::from_slope_derivatives(Vec2::new(0.03, 0.0), Vec2::new(0.0, 0.02));
//! let lobe = material.filtered(footprint, Gaussian::TK19);
//! let water = MicrofacetReflection::new(lobe, Dielectric::new(1.33).unwrap());
//!
//! let wo = Vec3::new(0.3, 0.0, 0.95).normalize();
//! if let Some(s) = water.sample(wo, [0.3, 0.7, 0.1, 0.9]) {
//!     // s.weight = f cos / pdf: multiply the path throughput by it; s.pdf for MIS.
//!     assert!(s.wi.z > 0.0 && s.weight <= 1.0 && s.pdf > 0.0);
//!     let f = water.f(wo, s.wi);
//!     assert!((f * s.wi.z / s.pdf - s.weight).abs() < 1e-3 * s.weight);
//! }
//! ```
//!
//! ## The BRDF (Walter et al. 2007 eq. 20, reflection)
//! In the tangent frame (`z` the shading normal), for `wo`, `wi` above the surface and
//! `m = normalize(wo + wi)` the half vector:
//!
//! `f(wo, wi) = F(wo.m) D(m) G2(wo, wi, m) / (4 wo_z wi_z)`,
//!
//! with `D` the lobe's density ([`Ndf::d`]), `G2` its own height-correlated Smith
//! masking-shadowing `1 / (1 + Lambda(wo) + Lambda(wi))` ([`Ndf::g2`], TK19 supplement
//! section 1; Heitz 2014 eq. 99) and `F` the Fresnel reflectance ([`Fresnel`]). A filtered
//! lobe brings its own `D` and `Lambda` (for the exactly filtered lobes, the `Lambda` of the
//! filtered distribution), so the BRDF is that of the filtered surface.
//!
//! ## Sampling (Heitz and d'Eon 2014; Walter et al. 2007 eq. 14)
//! `m` is drawn from the visible normals `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` (the
//! lobe's own sampler, [`NdfSampling::sample_visible_normal`] or the box lobe's), and
//! `wi = reflect(wo, m)`. Its density per steradian of `wi` is
//!
//! `pdf(wo, wi) = D_wo(m) / (4 wo.m) = D(m) / (4 wo_z (1 + Lambda(wo)))`,
//!
//! and the sample's weight `f cos / pdf` simplifies to
//!
//! `weight = F(wo.m) G2(wo, wi, m) / G1(wo) = F(wo.m) (1 + Lambda(wo)) / (1 + Lambda(wo) + Lambda(wi))`,
//!
//! in `[0, 1]` per channel, computed in that form (no `D` in it, no cancellation).
//!
//! **Reflection only.** A sampled `wi` below the surface (`wi_z <= 0`: the visible normal
//! reflects the view into the surface, which happens more the rougher the lobe and the more
//! grazing the view) is not a reflection: `sample` returns `None`, and `pdf` is `0` there, so
//! `pdf` integrates over the upper hemisphere to the probability that `sample` returns a
//! direction (`1` minus that loss). Transmission (the refraction of
//! [`Dielectric`]'s remainder `1 - F`) is not modelled: a renderer adds its own refracted or
//! diffuse layer with weight `1 - F` if it wants one.
//!
//! **Energy.** A single-scattering microfacet BRDF loses the light that scatters more than
//! once between facets, and the reflections below the surface: with `F = 1` the albedo
//! `E(wo) = integral f wi_z dwi` is below `1`. For isotropic GGX (f64 quadrature,
//! `tests/bsdf.rs`; `docs/bsdf.md` tabulates every lobe): `E = 0.9996` at roughness `0.02`
//! seen from above and `0.894` from 89 degrees; `0.948` and `0.971` at roughness `0.2`;
//! `0.504` and `0.948` at roughness `0.7`. A filtered lobe has the albedo of its own, wider
//! distribution (`docs/bsdf.md`).
//!
//! ## Random numbers: [`Bsdf::sample_dimension`]
//! `sample` takes four uniform numbers `u: [F; 4]` for every lobe, so code generic over
//! [`Bsdf`] takes every lobe; [`Bsdf::sample_dimension`] says how many of them the lobe
//! reads (the rest are ignored): `2` (`u[0]`, `u[1]`) for the NDFs and
//! [`GaussianFilteredGgx`](super::GaussianFilteredGgx), `4` for the box-filtered lobe
//! [`RectFilteredGgx`] (`u[0..2]` for the GGX visible normal, `u[2..4]` for the offset in the
//! box: its conditional CDFs have no closed form, so an exact sample takes two more numbers,
//! [`sampling::rect::sample_visible_normal_rect`](super::sampling::rect::sample_visible_normal_rect)). A
//! quasi-Monte Carlo renderer draws `sample_dimension()` dimensions per bounce.
//!
//! ## The lobes
//! [`MicrofacetReflection`]`<L, Fr>` implements [`Bsdf`] for every lobe of the front door:
//! every `L` with [`NdfSampling`] (`Ggx<R>` and `Beckmann<R>` in each roughness form: the
//! unfiltered NDFs and the lobes of `Gaussian`, `Projected`, `Proxy`;
//! [`GaussianFilteredGgx`](super::GaussianFilteredGgx) of `ExactGaussian`, whose
//! visible-normal sampler draws the density of its pdf to `1.6e-6` relative, see its docs)
//! and [`RectFilteredGgx`] of `Rect`. Every one samples its own visible normals exactly; none
//! falls back to `D(m) m_z` sampling.
//!
//! **Reciprocity.** `f(wo, wi) = f(wi, wo)` for every lobe: `m`, `D(m)`, `G2` (symmetric in
//! `Lambda(wo)`, `Lambda(wi)`), `F(wo.m) = F(wi.m)` and `wo_z wi_z` are all symmetric. The pdf
//! is not (it is `wo`'s visible-normal density).
//!
//! ## Out-of-domain input
//! One-sided: directions are in the tangent frame and must be above the surface. A two-sided
//! material flips `wo` and `wi` (negates both) itself.
//! - `f`, `pdf`: `0` for `wo_z <= 0` or `wi_z <= 0`, a zero, NaN or infinite direction.
//!   Directions need not be unit vectors (they are normalised first).
//! - `sample`: `None` for the same `wo`, for a `wi` below the surface, and where the lobe's
//!   sampler gives none (a view within the float range of grazing, [`NdfSampling`]) or the
//!   pdf underflows to `0` at the sampled normal (a normal in the far tail). `u` components
//!   outside `[0, 1)` are clamped to `[0, 1 - eps/2]` and NaN to `0`, as the lobes' samplers
//!   do.
//! - Nothing returns NaN for any input; `f` is `0` where its product overflows (directions
//!   within about `1e-38` (`f32`) of grazing).

use super::filter::RectFilteredGgx;
use super::ndf::Ndf;
use super::sampling::{NdfSampling, reflect, reflection_pdf_core};
use super::vector::unit;
use super::{F, Vec2, Vec3};

pub mod fresnel;

pub use fresnel::{Conductor, Dielectric, Fresnel, FresnelOne, Schlick, Spectrum};

/// A sampled direction ([`Bsdf::sample`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample<S = F> {
    /// The incident direction (unit, tangent frame, `wi_z > 0`).
    pub wi: Vec3,
    /// `f(wo, wi) wi_z / pdf`, per channel: what the path's throughput is multiplied by.
    pub weight: S,
    /// The density of `wi` per steradian (`> 0`, finite), as [`Bsdf::pdf`] gives it.
    pub pdf: F,
}

/// A BSDF in the tangent frame (`z` the shading normal), in the style of pbrt's `BxDF`:
/// the value, importance sampling and the pdf of one scattering function (see the
/// [module docs](self) for the formulas and the out-of-domain contract).
pub trait Bsdf {
    /// The value's type per channel: [`F`] or [`Vec3`] (RGB), as the Fresnel term's.
    type Value: Spectrum;

    /// How many of the four uniform numbers of [`Bsdf::sample`] are read (the first ones;
    /// the others are ignored): `2` or `4`. A method rather than a constant, so that the
    /// trait stays dyn-compatible (a renderer with mixed materials holds
    /// `&dyn Bsdf<Value = Vec3>`).
    fn sample_dimension(&self) -> usize;

    /// The BSDF `f(wo, wi)` per steradian (for reflection
    /// `F D G2 / (4 |wo_z| |wi_z|)`), `>= 0`.
    fn f(&self, wo: Vec3, wi: Vec3) -> Self::Value;

    /// A direction `wi` drawn with density [`Bsdf::pdf`]`(wo, .)` from the uniform numbers
    /// `u` (the first [`Bsdf::sample_dimension`] of them), with its weight `f wi_z / pdf` and
    /// pdf; `None` where no direction is drawn (module docs).
    fn sample(&self, wo: Vec3, u: [F; 4]) -> Option<BsdfSample<Self::Value>>;

    /// The density per steradian of the directions [`Bsdf::sample`] draws, at `wi`.
    fn pdf(&self, wo: Vec3, wi: Vec3) -> F;
}

/// Microfacet reflection: the lobe `L` (any lobe of the front door) with the Fresnel term
/// `Fr` ([`fresnel`]). Implements [`Bsdf`] (module docs: formulas, sampling, domain).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MicrofacetReflection<L, Fr> {
    /// The microfacet lobe: its `D`, `Lambda` and visible-normal sampler.
    pub lobe: L,
    /// The facets' reflectance.
    pub fresnel: Fr,
}

impl<L, Fr> MicrofacetReflection<L, Fr> {
    /// Reflection from the facets of `lobe` with the reflectance `fresnel`.
    #[inline]
    pub const fn new(lobe: L, fresnel: Fr) -> Self {
        Self { lobe, fresnel }
    }
}

impl<L: Ndf, Fr: Fresnel> MicrofacetReflection<L, Fr> {
    /// `F D G2 / (4 wo_z wi_z)` (module docs).
    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Fr::Value {
        let zero = <Fr::Value as Spectrum>::splat(0.0);
        let (Some(o), Some(i)) = (upper_unit(wo), upper_unit(wi)) else {
            return zero;
        };
        // Both above the surface: `o + i` is not zero.
        let Some(h) = unit(o + i) else {
            return zero;
        };
        let d = self.lobe.d(h);
        if !positive(d) {
            return zero;
        }
        let scale = d * self.lobe.g2(i, o, h) / (4.0 * o.z * i.z);
        if !scale.is_finite() {
            return zero;
        }
        self.fresnel.reflectance(o.dot(h)) * scale
    }

    /// `D(m) / (4 wo_z (1 + Lambda(wo)))` at `m = normalize(wo + wi)` (module docs).
    #[inline]
    fn density(&self, wo: Vec3, wi: Vec3) -> F {
        let (Some(o), Some(i)) = (upper_unit(wo), upper_unit(wi)) else {
            return 0.0;
        };
        let Some(h) = unit(o + i) else {
            return 0.0;
        };
        let v = reflection_pdf_core(self.lobe.d(h), o.z, self.lobe.lambda(o));
        if v.is_finite() { v } else { 0.0 }
    }

    /// The sample of the visible normal `visible(o)` drawn for the unit view `o` (module
    /// docs): `wi = reflect(o, m)`, its pdf and weight.
    #[inline]
    fn sample_with(
        &self,
        wo: Vec3,
        visible: impl FnOnce(Vec3) -> Option<Vec3>,
    ) -> Option<BsdfSample<Fr::Value>> {
        let o = upper_unit(wo)?;
        let mn = visible(o)?;
        let wi = unit(reflect(o, mn))?;
        if !positive(wi.z) {
            return None;
        }
        let lambda_o = self.lobe.lambda(o);
        let pdf = reflection_pdf_core(self.lobe.d(mn), o.z, lambda_o);
        if !(positive(pdf) && pdf.is_finite()) {
            return None;
        }
        let g = (1.0 + lambda_o) / (1.0 + lambda_o + self.lobe.lambda(wi));
        // `Lambda(wi) = +inf` (a `wi` within rounding of grazing) gives `g = 0`; NaN cannot
        // arise (`Lambda` is never NaN and `>= 0`), `1 + Lambda(wo)` is finite for `o_z > 0`
        // up to overflow, which leaves `inf / inf`: no weight then.
        let g = if g.is_nan() { 0.0 } else { g };
        Some(BsdfSample {
            wi,
            weight: self.fresnel.reflectance(o.dot(mn)) * g,
            pdf,
        })
    }
}

/// `x > 0`, false for NaN.
#[inline]
fn positive(x: F) -> bool {
    x > 0.0
}

/// `w / |w|` for a finite, non-zero `w` with `w_z > 0`; `None` otherwise.
#[inline]
fn upper_unit(w: Vec3) -> Option<Vec3> {
    if !positive(w.z) {
        return None;
    }
    unit(w).filter(|u| u.z > 0.0)
}

impl<L: NdfSampling, Fr: Fresnel> Bsdf for MicrofacetReflection<L, Fr> {
    type Value = Fr::Value;
    /// `2`: `u[0]`, `u[1]` for the lobe's visible-normal sampler.
    #[inline]
    fn sample_dimension(&self) -> usize {
        2
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Fr::Value {
        self.eval(wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u: [F; 4]) -> Option<BsdfSample<Fr::Value>> {
        self.sample_with(wo, |o| {
            self.lobe.sample_visible_normal(o, Vec2::new(u[0], u[1]))
        })
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> F {
        self.density(wo, wi)
    }
}

impl<Fr: Fresnel> Bsdf for MicrofacetReflection<RectFilteredGgx, Fr> {
    type Value = Fr::Value;
    /// `4`: `u[0]`, `u[1]` for the GGX visible normal, `u[2]`, `u[3]` for the offset in the
    /// box ([`RectFilteredGgx::sample_visible_normal`]).
    #[inline]
    fn sample_dimension(&self) -> usize {
        4
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Fr::Value {
        self.eval(wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u: [F; 4]) -> Option<BsdfSample<Fr::Value>> {
        self.sample_with(wo, |o| {
            self.lobe
                .sample_visible_normal(o, Vec2::new(u[0], u[1]), Vec2::new(u[2], u[3]))
        })
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> F {
        self.density(wo, wi)
    }
}
