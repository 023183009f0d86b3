//! Importance sampling of the NDFs for path tracers: the distribution of visible normals and
//! `D(m) cos theta_m`, in every roughness form, with the pdfs a renderer needs for multiple
//! importance sampling.
//!
//! ## Densities (per steradian of micronormal `m`, unit vectors in the tangent frame)
//! - `D(m) m_z`: the projected-area-normalised NDF (KHPL16 eq. 2), integrates to 1 over the
//!   upper hemisphere. Sampled by [`NdfSampling::sample_normal`].
//! - Visible normals (Heitz 2014 eq. 16; Heitz and d'Eon 2014 eq. 2):
//!   `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z`, `G1(wo) = 1 / (1 + Lambda(wo))`, integrates
//!   to 1 for every `wo` above the surface. Sampled by [`NdfSampling::sample_visible_normal`].
//! - Reflection: `wi = reflect(wo, m) = 2 (wo.m) m - wo` has the density
//!   `D_wo(m) / (4 |wo.m|) = G1(wo) D(m) / (4 wo_z)` per steradian of `wi` (Walter et al. 2007
//!   eq. 14, the half-vector Jacobian).
//!
//! ## One linear warp for every roughness form
//! With `A = L L^T` (lower Cholesky factor; diagonal for the isotropic and axis-aligned
//! forms), slopes `s = L t` map the unit-roughness NDF of `t` to the NDF of roughness `A`
//! (both depend on the slope only through `s^T A^-1 s = |t|^2`, TK19 supplement section 1).
//! A normal `n` of the unit-roughness space maps to `m ~ (L n_xy, n_z)`, and
//! `wo.m ~ wo_z n_z + (L^T wo_xy).n_xy`, so the visible normals of `A` seen from `wo` are
//! the image of the unit-roughness visible normals seen from the stretched direction
//! `normalize(L^T wo_xy, wo_z)` (Heitz and d'Eon 2014 section 4 for the axis-aligned case;
//! the same algebra holds for any `L`). With the determinant clamp `tau` of
//! [`RoughnessMatrix`](super::RoughnessMatrix), `L` is the Cholesky factor of the clamped
//! matrix `A_c` that the density and `Lambda` evaluate, so the sampled lobe is that one.
//!
//! The unit-roughness samplers are exact: GGX through the spherical caps of Dupuy and
//! Benyoub 2023 ("Sound and Robust Sampling of the Distribution of Visible Normals", listing
//! 3), Beckmann by inverting the visible-slope CDF with a bracketed Newton solve of stated
//! accuracy ([`beckmann`]).
//!
//! ## Out-of-domain input
//! - `wo` at or below the horizon (`wo_z <= 0`), zero or non-finite: no visible normal exists;
//!   the samplers return `None` and the pdfs `0`. The samplers also return `None` where
//!   rounding leaves no certifiable sample: the `m_z` of every candidate (and of the lobe
//!   centre) underflows to `0`. That needs a view within the float range of the stretched
//!   lobe's horizon: `wo_z / |wo|` below about `1e-300` (`f64`) / `1e-37` (`f32`) for
//!   roughness in the checked range. A two-sided material flips `wo` (and the sampled `m`)
//!   itself.
//! - `u` outside `[0, 1)`: each component is clamped to `[0, 1 - eps/2]`, NaN to `0`.
//! - `wo` need not be normalised (every formula is scale-invariant in `wo`); `m` must be a
//!   unit vector for the pdfs.
//!
//! Guarantees for `wo_z > 0`: a sampled `m` is a finite unit vector with `m_z > 0` and
//! `wo.m > 0` (should rounding ever put the mapped sample on or behind the horizon of `m`,
//! which needs `u` within rounding of a boundary of the unit square, the centre of the lobe
//! `m ~ (A wo_xy, wo_z)` is returned instead, which always satisfies both).

use super::ndf::Ndf;
use super::ndf::beckmann::Beckmann;
use super::ndf::ggx::Ggx;
use super::ndf::roughness::Roughness;
use super::{F, PI, Vec2, Vec3};

pub mod beckmann;
mod gaussian_ggx;
pub mod rect;
use crate::math::{self as m, Real};

/// Largest float below 1: the upper clamp of the uniform numbers.
const ONE_MINUS_EPS: F = 1.0 - 0.5 * F::EPSILON;

/// Sampling routines and pdfs of a microfacet NDF (see the module docs for the formulas and
/// the out-of-domain contract).
///
/// ```
/// use filtered_ndf::f32::sampling::reflect;
/// use filtered_ndf::f32::{Ggx, NdfSampling, RoughnessMatrix};
/// use glam::{Vec2, Vec3};
///
/// // A filtered, sheared lobe: A = [[0.04, 0.01], [0.01, 0.09]].
/// let ggx = Ggx::new(RoughnessMatrix::new(0.04, 0.01, 0.09).unwrap());
/// let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
/// let m = ggx.sample_visible_normal(wo, Vec2::new(0.3, 0.7)).unwrap();
/// assert!(m.z > 0.0 && wo.dot(m) > 0.0);
/// let wi = reflect(wo, m);
/// // pdf of the sampled direction, and the same pdf as MIS would evaluate it for a light sample.
/// let pdf = ggx.reflection_pdf_from_normal(wo, m);
/// assert!((ggx.reflection_pdf(wo, wi) - pdf).abs() < 1e-4 * pdf);
/// ```
pub trait NdfSampling: Ndf {
    /// Samples a unit micronormal `m` with density `D(m) m_z` per steradian (the NDF itself,
    /// projected-area normalised, KHPL16 eq. 2) from `u` in `[0, 1)^2`. Always `m_z > 0`.
    fn sample_normal(&self, u: Vec2) -> Vec3;

    /// The density of [`NdfSampling::sample_normal`], `D(m) m_z` per steradian, for a unit
    /// `m`; `0` for `m_z <= 0` and for non-finite `m`.
    #[inline]
    fn normal_pdf(&self, m: Vec3) -> F {
        if !m.is_finite() || m.z <= 0.0 {
            return 0.0;
        }
        normal_pdf_core(self.d(m), m.z)
    }

    /// Samples a visible micronormal `m` with density `D_wo(m)` per steradian from `u` in
    /// `[0, 1)^2` (Heitz 2014 eq. 16). `None` if `wo_z <= 0` or `wo` is not finite (or the
    /// view is grazing to within the float range, module docs); otherwise `m` is a unit vector
    /// with `m_z > 0` and `wo.m > 0`.
    fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Option<Vec3>;

    /// The visible-normal density `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` per steradian
    /// (Heitz 2014 eq. 16) for a unit `m`. `0` for `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0` or
    /// non-finite input.
    #[inline]
    fn visible_normal_pdf(&self, wo: Vec3, m: Vec3) -> F {
        if !(wo.is_finite() && m.is_finite() && positive(wo.z)) {
            return 0.0;
        }
        let wom = wo.dot(m);
        if !positive(wom) {
            return 0.0;
        }
        let v = visible_normal_pdf_core(wom, self.d(m), wo.z, self.lambda(wo));
        if v.is_finite() { v } else { 0.0 }
    }

    /// The density per steradian of `wi = reflect(wo, m)` when `m` is drawn by
    /// [`NdfSampling::sample_visible_normal`]:
    /// `D_wo(m) / (4 wo.m) = G1(wo) D(m) / (4 wo_z)` with `m = normalize(wo + wi)` (Walter et
    /// al. 2007 eq. 14), for multiple importance sampling. `wo` and `wi` need not be unit
    /// vectors. `wi` may lie below the surface (the sampler produces such directions; the
    /// BRDF's `G2` then vanishes). `0` for `wo_z <= 0`, for `wi = -wo` (no half vector), where
    /// `wo.m <= 0`, and for non-finite input.
    ///
    /// Conditioning: the recomputed half vector carries a direction error of about
    /// `eps / (2 wo.m)`; when that exceeds the lobe width (`f32`, roughness near `1e-4`, views
    /// beyond about 89.9 degrees) the value is unreliable (possibly `0`). For the pdf of a
    /// direction this trait sampled, use [`NdfSampling::reflection_pdf_from_normal`] with the
    /// sampled `m`, which has no such loss.
    #[inline]
    fn reflection_pdf(&self, wo: Vec3, wi: Vec3) -> F {
        if !(wo.is_finite() && wi.is_finite() && positive(wo.z)) || wi == Vec3::ZERO {
            return 0.0;
        }
        let h = normalize_scaled(wo) + normalize_scaled(wi);
        let len = m::sqrt(h.length_squared());
        if !positive(len) {
            return 0.0;
        }
        self.reflection_pdf_from_normal(wo, h / len)
    }

    /// The density per steradian of `wi = reflect(wo, m)` given the unit half vector `m`
    /// itself: `D_wo(m) / (4 wo.m) = G1(wo) D(m) / (4 wo_z)` (Walter et al. 2007 eq. 14, `wo`
    /// normalised here). `0` for `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0` and non-finite input.
    #[inline]
    fn reflection_pdf_from_normal(&self, wo: Vec3, m: Vec3) -> F {
        if !(wo.is_finite() && m.is_finite() && positive(wo.z)) {
            return 0.0;
        }
        let o = normalize_scaled(wo);
        if !positive(o.dot(m)) {
            return 0.0;
        }
        let v = reflection_pdf_core(self.d(m), o.z, self.lambda(o));
        if v.is_finite() { v } else { 0.0 }
    }
}

/// The formula of [`NdfSampling::normal_pdf`] once its checks passed: `D(m) m_z`. Shared
/// with the batch pdfs' lanes.
#[inline(always)]
pub(crate) fn normal_pdf_core(d: F, m_z: F) -> F {
    d * m_z
}

/// The formula of [`NdfSampling::visible_normal_pdf`] once its checks passed:
/// `(wo.m) D(m) / (wo_z (1 + Lambda(wo)))` (`G1 / wo_z` with the scale of `wo` cancelling
/// in `wo.m / wo_z` and in `Lambda`). Shared with the batch pdfs' lanes.
#[inline(always)]
pub(crate) fn visible_normal_pdf_core(wom: F, d: F, wo_z: F, lambda: F) -> F {
    wom * d / (wo_z * (1.0 + lambda))
}

/// The formula of [`NdfSampling::reflection_pdf_from_normal`] once its checks passed, for
/// the unit view `o`: `D(m) / (4 o_z (1 + Lambda(o)))`. Shared with the batch pdfs' lanes.
#[inline(always)]
pub(crate) fn reflection_pdf_core(d: F, o_z: F, lambda: F) -> F {
    d / (4.0 * o_z * (1.0 + lambda))
}

/// Mirror reflection of `wo` about the unit normal `m`: `2 (wo.m) m - wo` (Walter et al. 2007
/// eq. 13). Keeps the length of `wo`.
#[inline]
pub fn reflect(wo: Vec3, m: Vec3) -> Vec3 {
    2.0 * wo.dot(m) * m - wo
}

/// `x > 0`, false for NaN.
#[inline]
fn positive(x: F) -> bool {
    x > 0.0
}

/// Clamps a uniform number into `[0, 1 - eps/2]`; NaN maps to `0` (shared with the batch
/// sampler's lane, where it compiles to selects).
#[inline(always)]
pub(crate) fn clamp_unit(u: F) -> F {
    if u >= 0.0 { u.min(ONE_MINUS_EPS) } else { 0.0 }
}

/// `v / |v|` for a non-zero, finite `v` (the caller guarantees it) without over- or underflow
/// ([`vector::unit`](super::vector::unit)).
#[inline]
fn normalize_scaled(v: Vec3) -> Vec3 {
    super::vector::unit(v).unwrap_or(Vec3::Z)
}

/// The lower Cholesky factor `L = [[l11, 0], [l21, l22]]` of a roughness, `A = L L^T`.
#[derive(Clone, Copy)]
pub(crate) struct Warp {
    l11: F,
    l21: F,
    l22: F,
}

impl Warp {
    /// The Cholesky factor of the matrix the roughness evaluates (for a clamped
    /// [`RoughnessMatrix`](super::RoughnessMatrix), of its `A_c`): the warp samples the lobe
    /// that `D` and `Lambda` describe.
    #[inline]
    pub(crate) fn new<R: Roughness>(r: &R) -> Self {
        let (l11, l21, l22) = r.cholesky();
        Self { l11, l21, l22 }
    }

    /// `(L^T w_xy, w_z)`: a view direction into the unit-roughness space (unnormalised).
    #[inline(always)]
    pub(crate) fn stretch(&self, w: Vec3) -> Vec3 {
        Vec3::new(self.l11 * w.x + self.l21 * w.y, self.l22 * w.y, w.z)
    }

    /// `normalize(L n_xy, n_z)`: a unit-roughness normal back to roughness `A`.
    #[inline]
    fn unstretch(&self, n: Vec3) -> Vec3 {
        normalize_scaled(self.unstretch_raw(n))
    }

    /// `(L n_xy, n_z)`: [`Warp::unstretch`] before the normalisation (shared with the batch
    /// sampler's lane).
    #[inline(always)]
    pub(crate) fn unstretch_raw(&self, n: Vec3) -> Vec3 {
        Vec3::new(self.l11 * n.x, self.l21 * n.x + self.l22 * n.y, n.z)
    }

    /// The checked final step of a visible-normal sampler: maps the unit-roughness normal
    /// `n` back and falls back to the lobe centre `unstretch(wi)` (for which
    /// `wo.m ~ wo_xy^T A wo_xy + wo_z^2 > 0`) if rounding broke `m_z > 0` or `wo.m > 0`;
    /// `None` if rounding breaks the centre too (its `m_z` underflows to `0`: found by
    /// fuzzing for views within the float range of the stretched lobe's horizon).
    #[inline]
    fn visible_result(&self, wo: Vec3, wi: Vec3, n: Vec3) -> Option<Vec3> {
        let mm = self.unstretch(n);
        if mm.is_finite() && mm.z > 0.0 && wo.dot(mm) > 0.0 {
            return Some(mm);
        }
        let c = self.unstretch(wi);
        // `wo.m > 0` holds analytically; the scaled `wo` avoids under- and overflow of the dot.
        let ok =
            c.is_finite() && c.z > 0.0 && (wo.dot(c) > 0.0 || normalize_scaled(wo).dot(c) > 0.0);
        ok.then_some(c)
    }
}

/// The view direction in the unit-roughness space, or `None` for `wo_z <= 0` / non-finite.
#[inline]
fn standard_view(warp: &Warp, wo: Vec3) -> Option<Vec3> {
    if !(wo.is_finite() && positive(wo.z)) {
        return None;
    }
    // Normalised first: the stretch of a huge `wo` overflows (inf / inf = NaN; fuzzing).
    let wi = normalize_scaled(warp.stretch(normalize_scaled(wo)));
    positive(wi.z).then_some(wi)
}

/// Unit-roughness GGX visible normal by spherical caps (Dupuy and Benyoub 2023, listing 3):
/// a uniform point `c` on the cap `z >= -wi_z` of the unit sphere, `n = normalize(c + wi)`.
/// Returned unnormalised (`c + wi`, length in `(0, 2]`).
#[inline]
fn ggx_standard_visible(wi: Vec3, u: Vec2) -> Vec3 {
    let phi = 2.0 * PI * u.x;
    let z = m::mul_add(1.0 - u.y, 1.0 + wi.z, -wi.z);
    ggx_cap_point(wi, z, m::cos(phi), m::sin(phi))
}

/// The core of [`ggx_standard_visible`] shared with the batch sampler's lane: the point of
/// the unit sphere at height `z` and azimuth `(cos phi, sin phi)`, plus `wi` (Dupuy and
/// Benyoub 2023, listing 3).
#[inline(always)]
pub(crate) fn ggx_cap_point(wi: Vec3, z: F, cos_phi: F, sin_phi: F) -> Vec3 {
    let sin_theta = m::sqrt((1.0 - z * z).clamp(0.0, 1.0));
    Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, z) + wi
}

/// The unit-roughness GGX normal of `D(m) m_z` sampling: `|t|^2 = u1 / (1 - u1)`, i.e.
/// `n = (sqrt(u1) cos phi, sqrt(u1) sin phi, sqrt(1 - u1))` (a unit vector), for the clamped
/// `u1` and the azimuth's `(cos phi, sin phi)`. Shared with the batch sampler's lane.
#[inline(always)]
pub(crate) fn ggx_standard_normal(u1: F, cos_phi: F, sin_phi: F) -> Vec3 {
    let r = m::sqrt(u1);
    Vec3::new(r * cos_phi, r * sin_phi, m::sqrt(1.0 - u1))
}

/// The unit-roughness Beckmann normal of `D(m) m_z` sampling, unnormalised: the slope of
/// squared length `|t|^2 = -ln(1 - u1)` at the azimuth `(cos phi, sin phi)`,
/// `n = (r cos phi, r sin phi, 1)`, `r = sqrt(-ln_1mu)`, from `ln_1mu = ln(1 - u1)` (`<= 0`).
/// Shared with the batch sampler's lane.
#[inline(always)]
pub(crate) fn beckmann_standard_normal(ln_1mu: F, cos_phi: F, sin_phi: F) -> Vec3 {
    let r = m::sqrt(-ln_1mu);
    Vec3::new(r * cos_phi, r * sin_phi, 1.0)
}

impl<R: Roughness> NdfSampling for Ggx<R> {
    /// GGX `D(m) m_z`: in the unit-roughness space `|t|^2 = u1 / (1 - u1)`, i.e.
    /// `n = (sqrt(u1) cos phi, sqrt(u1) sin phi, sqrt(1 - u1))`, `phi = 2 pi u2`, then warped
    /// by `L`.
    #[inline]
    fn sample_normal(&self, u: Vec2) -> Vec3 {
        let (u1, u2) = (clamp_unit(u.x), clamp_unit(u.y));
        let phi = 2.0 * PI * u2;
        let n = ggx_standard_normal(u1, m::cos(phi), m::sin(phi));
        Warp::new(&self.roughness).unstretch(n)
    }

    #[inline]
    fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let warp = Warp::new(&self.roughness);
        let wi = standard_view(&warp, wo)?;
        let u = Vec2::new(clamp_unit(u.x), clamp_unit(u.y));
        let n = ggx_standard_visible(wi, u);
        warp.visible_result(wo, wi, n)
    }
}

impl<R: Roughness> NdfSampling for Beckmann<R> {
    /// Beckmann `D(m) m_z`: in the unit-roughness space `|t|^2 = -ln(1 - u1)` (a Gaussian of
    /// slopes with covariance `I/2`), `phi = 2 pi u2`, then warped by `L` (slope covariance
    /// `A / 2`, KHPL16 eq. 14).
    #[inline]
    fn sample_normal(&self, u: Vec2) -> Vec3 {
        let (u1, u2) = (clamp_unit(u.x), clamp_unit(u.y));
        let phi = 2.0 * PI * u2;
        let n = beckmann_standard_normal(m::ln(1.0 - u1), m::cos(phi), m::sin(phi));
        Warp::new(&self.roughness).unstretch(n)
    }

    /// Beckmann visible normals: in the unit-roughness space with the view azimuth rotated to
    /// `x`, the slope `x` is the quantile of the visible-slope CDF and `y` an independent
    /// Gaussian quantile ([`beckmann`]), rotated back and warped by `L`.
    #[inline]
    fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        use beckmann::invert_visible_slope_cdf;
        let warp = Warp::new(&self.roughness);
        let wi = standard_view(&warp, wo)?;
        let (wx, wy, c) = (wi.x.to_f64(), wi.y.to_f64(), wi.z.to_f64());
        let s = m::hypot(wx, wy);
        let (cphi, sphi) = if s > 0.0 {
            (wx / s, wy / s)
        } else {
            (1.0, 0.0)
        };
        let x = invert_visible_slope_cdf(c, s, clamp_unit(u.x).to_f64());
        let y = invert_visible_slope_cdf(1.0, 0.0, clamp_unit(u.y).to_f64());
        let (tx, ty) = (cphi * x - sphi * y, sphi * x + cphi * y);
        let n = Vec3::new(F::from_f64(-tx), F::from_f64(-ty), 1.0);
        warp.visible_result(wo, wi, n)
    }
}
