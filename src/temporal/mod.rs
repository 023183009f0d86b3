//! Temporal NDFs for motion blur (Tessari et al. 2020, section 3.2): the normal seen through a
//! pixel sweeps over the shutter; a first-order model of that sweep is folded into an
//! anisotropic roughness along the motion, which widens the NDF `D` but not the masking `G`.
//!
//! Pipeline per shading point:
//! 1. `dN/dt` at the hit from [`implicit::hit_rates`] (eq. 20-21), or from a local
//!    quadric with a rigid motion ([`quadric`], eq. 22-24);
//! 2. [`TemporalRoughness::from_world_rate`]: `alpha_t = |dt dN/dt|` along the direction of
//!    `dN/dt` in the tangent frame, zero across it (section 3.2, "Approximating D^t"),
//!    optionally [`TemporalRoughness::cosine_weighted`] (Fig. 8);
//! 3. [`TemporalLobe::beckmann`] / [`TemporalLobe::ggx`]: `Sigma_conv = Sigma_mu + P`
//!    (eq. 16) for `D`, and `G_conv = G_mu` (eq. 17, Fig. 7) for masking;
//! 4. along a path, [`TemporalRoughness::share`] so that `sum_i alpha_i^2 = alpha_t^2`
//!    (section 3.2, "Indirect rays").
//!
//! ## Conventions (exact)
//! The paper writes Beckmann lobes through their Gaussian slope covariance `Sigma` (eq. 1-2)
//! and notes that the Beckmann roughness factors in the `1/2` of the exponent: `alpha =
//! sqrt(2) sigma` along each axis. That is KHPL16 eq. 14: the crate's roughness matrix is
//! `A = 2 Sigma`. The temporal slope `m = |dt dN/dt|` is mapped "directly to the roughness
//! value", so `alpha_t = m` and its covariance is `P = (alpha_t^2 / 2) a a^T` with `a` the unit
//! direction of `dN/dt` in the tangent plane. Eq. 16 in roughness form is therefore
//! `A_conv = A_mu + 2 P = A_mu + alpha_t^2 a a^T`.
//! (Eq. 2 prints the Gaussian's normalisation as `pi |Sigma|`; the density that integrates to
//! one is `exp(-s^T Sigma^-1 s / 2) / (2 pi sqrt(det Sigma)) = exp(-s^T A^-1 s) / (pi
//! sqrt(det A))`, which is what [`Beckmann`] evaluates.)
//!
//! The paper leaves `dt` as "a subset of the shutter". A box shutter of length `T` sweeps the
//! linearised slope uniformly over `[-T/2, T/2] |dN/dt|`, whose variance `T^2 |dN/dt|^2 / 12`
//! equals `alpha_t^2 / 2` for `dt = T / sqrt(6)` ([`box_shutter_dt`]); the tests measure the
//! first-order model against the true slopes with this choice.
//!
//! Slopes are `s = -h_xy / h_z` in the tangent frame at the reference time (crate
//! convention); for `N(t)` near `N(t0)`, `ds/dt = -(dN/dt)_xy`, and every lobe here is even in
//! `s`, so the sign does not matter.

use super::kernel::Covariance;
use super::ndf::Ndf;
use super::ndf::beckmann::Beckmann;
use super::ndf::ggx::Ggx;
use super::ndf::roughness::{ALPHA_MAX, Roughness, RoughnessMatrix, clamp_alpha};
use super::{F, Vec2, Vec3};

pub mod implicit;
pub mod quadric;
use crate::math as m;

/// `dt = T / sqrt(6)`: the paper's `Delta t` whose Beckmann lobe has the slope variance of a
/// box shutter of length `T` under the first-order model (module docs). Units of `T`.
/// Non-finite or negative `T` gives `0`.
#[inline]
pub fn box_shutter_dt(shutter: F) -> F {
    let inv_sqrt6 = 0.408_248_290_463_863_f64 as F;
    if shutter.is_finite() && shutter > 0.0 {
        shutter * inv_sqrt6
    } else {
        0.0
    }
}

/// The temporal (macro) Beckmann roughness `alpha_t` of section 3.2 along a unit tangent-plane
/// axis `a`; zero roughness across it. Dimensionless (a slope).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TemporalRoughness {
    alpha: F,
    axis: Vec2,
}

impl Default for TemporalRoughness {
    fn default() -> Self {
        Self::ZERO
    }
}

impl TemporalRoughness {
    /// No temporal roughness (a static surface); the axis is `x`.
    pub const ZERO: Self = Self {
        alpha: 0.0,
        axis: Vec2::X,
    };

    /// `alpha_t = |dt dN/dt|` along `a = dN/dt / |dN/dt|` (section 3.2: `m = tan alpha =
    /// |dt d_t N(t)|`, mapped directly to the Beckmann roughness), from the tangent-frame
    /// components `(dN/dt . t, dN/dt . b)` of the normal's rate (units `1 / T`) and `dt`
    /// (units `T`, e.g. [`box_shutter_dt`]).
    ///
    /// Bad input: non-finite or zero rate, non-finite or non-positive `dt`: [`Self::ZERO`].
    /// `alpha_t` is capped at [`ALPHA_MAX`].
    pub fn from_normal_rate(dn_dt: Vec2, dt: F) -> Self {
        if !(dn_dt.is_finite() && dt.is_finite() && dt > 0.0) {
            return Self::ZERO;
        }
        let scale = dn_dt.abs().max_element();
        if scale == 0.0 {
            return Self::ZERO;
        }
        let u = dn_dt / scale;
        let len_u = m::sqrt(u.length_squared());
        let axis = u / len_u;
        // alpha = dt * scale * len_u, capped without overflow.
        let alpha = if scale > ALPHA_MAX / (dt * len_u) {
            ALPHA_MAX
        } else {
            (dt * scale * len_u).min(ALPHA_MAX)
        };
        if !(alpha > 0.0 && axis.is_finite()) {
            return Self::ZERO;
        }
        Self { alpha, axis }
    }

    /// As [`Self::from_normal_rate`] from the world-space `dN/dt` (e.g.
    /// [`implicit::HitRates::dn_dt`]) and the tangent frame `(t, b)` at the reference
    /// time (unit, orthogonal to the reference normal; not checked). The component of `dN/dt`
    /// along the normal is dropped (it is zero to first order).
    #[inline]
    pub fn from_world_rate(dn_dt: Vec3, tangent: Vec3, bitangent: Vec3, dt: F) -> Self {
        Self::from_normal_rate(Vec2::new(dn_dt.dot(tangent), dn_dt.dot(bitangent)), dt)
    }

    /// The cosine weighting of Fig. 8 (section 3.2): `dt` scaled by `|cos theta|`, the cosine
    /// between the normal and the view direction, which damps the linearisation error of
    /// grazing views. Equivalent to `alpha_t |cos theta|`; `|cos theta|` is clamped to
    /// `[0, 1]` and NaN gives [`Self::ZERO`].
    #[inline]
    pub fn cosine_weighted(self, cos_theta: F) -> Self {
        let c = cos_theta.abs();
        if c.is_nan() || c <= 0.0 {
            return Self::ZERO;
        }
        Self {
            alpha: self.alpha * c.min(1.0),
            ..self
        }
    }

    /// This vertex's share of the temporal roughness along a path (section 3.2, "Indirect
    /// rays"): `alpha_i = alpha_t sqrt(fraction)`, so that shares whose fractions sum to one
    /// satisfy `sum_i alpha_i^2 = alpha_t^2` (variances add under convolution; applying the
    /// full roughness at every vertex would over-blur). `fraction` is clamped to `[0, 1]`; NaN
    /// gives [`Self::ZERO`].
    #[inline]
    pub fn share(self, fraction: F) -> Self {
        if fraction.is_nan() || fraction <= 0.0 {
            return Self::ZERO;
        }
        Self {
            alpha: self.alpha * m::sqrt(fraction.min(1.0)),
            ..self
        }
    }

    /// The even split over `n` path vertices: [`Self::share`] with fraction `1 / n`
    /// (`n = 0` is treated as `1`).
    #[inline]
    pub fn split_even(self, n: u32) -> Self {
        self.share(1.0 / (n.max(1) as F))
    }

    /// `alpha_t` (`>= 0`, `<= ALPHA_MAX`).
    #[inline]
    pub fn alpha(&self) -> F {
        self.alpha
    }

    /// The unit axis `a` of the temporal lobe in the tangent plane (the direction of `dN/dt`;
    /// the slope moves along `-a`). `x` for [`Self::ZERO`].
    #[inline]
    pub fn axis(&self) -> Vec2 {
        self.axis
    }

    /// The slope covariance `P = (alpha_t^2 / 2) a a^T` (slope^2; the `P` of eq. 16, rank one:
    /// the minor axis is zero).
    #[inline]
    pub fn covariance(&self) -> Covariance {
        let v = 0.5 * self.alpha * self.alpha;
        let a = self.axis;
        Covariance::new(v * a.x * a.x, v * a.x * a.y, v * a.y * a.y)
    }

    /// The temporal lobe alone as a roughness matrix, for a perfectly specular base:
    /// `A = alpha_t^2 a a^T + alpha_minor^2 (1 - a a^T)`, with both roughnesses passed through
    /// [`clamp_alpha`] (section 3.2: "the roughness in the minor axis [is set] to 0, or to a
    /// small value in case the base NDF is perfectly specular"; `alpha_minor = ALPHA_MIN` is
    /// the smallest this crate represents). The determinant is exact
    /// (`alpha_t^2 alpha_minor^2`, used as the TK19 clamp).
    pub fn roughness_matrix(&self, alpha_minor: F) -> RoughnessMatrix {
        let (big, small) = (clamp_alpha(self.alpha), clamp_alpha(alpha_minor));
        let (b2, s2) = (big * big, small * small);
        let a = self.axis;
        // `1 - a a^T = a_perp a_perp^T` for the unit axis: the diagonal as two non-negative
        // terms (`s2 + (b2 - s2) a_x^2` loses `b2` entirely when `alpha_minor >> alpha_t`,
        // which gave a zero diagonal entry; found by fuzzing).
        RoughnessMatrix::from_entries_clamped(
            b2 * a.x * a.x + s2 * a.y * a.y,
            (b2 - s2) * a.x * a.y,
            b2 * a.y * a.y + s2 * a.x * a.x,
            b2 * s2,
        )
    }
}

/// Eq. 16 in roughness form: `A_conv = A_mu + 2 P` (the Gaussian convolution
/// `Sigma_conv = Sigma_mu + P` with `A = 2 Sigma`, KHPL16 eq. 14), evaluated with the TK19
/// determinant clamp `tau = det A_mu` (the convolution can only grow the determinant, so the
/// clamp is exact and protects elongated lobes from cancellation).
///
/// Exact for Beckmann in the slope domain (Gaussians convolve to Gaussians); for GGX the same
/// matrix is the usual "roughness-matrix route" approximation (KHPL16, TK19). `p` is any slope
/// covariance: temporal ([`TemporalRoughness::covariance`]), spatial
/// ([`super::footprint::Footprint::covariance`]) or their sum. An invalid `p` is made usable
/// by [`Covariance::sanitized`](super::kernel::Covariance::sanitized) (NaN: no widening;
/// infinite: the largest kernel; indefinite: projected to positive semi-definite).
pub fn widen<R: Roughness>(base: R, p: Covariance) -> RoughnessMatrix {
    // One source of truth for A + 2 Sigma with tau = det A: the spatial Gaussian filter.
    super::filter::gaussian(base, p)
}

/// A microfacet lobe whose distribution is widened by the temporal roughness but whose
/// masking-shadowing is that of the base roughness (section 3.2, eq. 17, Fig. 6-7:
/// `G_conv = G_mu`, since microfacets at different instants do not shadow each other).
///
/// - [`Ndf::p22`], [`Ndf::d`]: those of `widened` (`W`, eq. 16).
/// - [`Ndf::lambda`], [`Ndf::g1`], [`Ndf::g2`]: those of `base` (`B`), evaluated by the base
///   NDF itself in its own roughness form, so they are bit-identical to the base lobe's.
///
/// `base` is the roughness the masking should see: the BSDF roughness, or the spatially
/// filtered one (KHPL16 curvature) when both filters are used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TemporalLobe<W, B = W> {
    /// The NDF for `D`: base convolved with the temporal kernel (eq. 16).
    pub widened: W,
    /// The NDF for `Lambda`, `G1`, `G2`: the base roughness only (eq. 17).
    pub base: B,
}

impl<W: Ndf, B: Ndf> TemporalLobe<W, B> {
    /// From the two NDFs (not checked to be related).
    #[inline]
    pub const fn new(widened: W, base: B) -> Self {
        Self { widened, base }
    }
}

impl<R: Roughness> TemporalLobe<Beckmann<RoughnessMatrix>, Beckmann<R>> {
    /// Beckmann: `D` from `A_mu + 2 P` ([`widen`], exact Gaussian convolution in the slope
    /// domain), `G` from `A_mu`.
    #[inline]
    pub fn beckmann(base: R, p: Covariance) -> Self {
        Self::new(Beckmann::new(widen(base, p)), Beckmann::new(base))
    }
}

impl<R: Roughness> TemporalLobe<Ggx<RoughnessMatrix>, Ggx<R>> {
    /// GGX: `D` from `A_mu + 2 P` ([`widen`], the roughness-matrix approximation of the
    /// convolution), `G` from `A_mu`.
    #[inline]
    pub fn ggx(base: R, p: Covariance) -> Self {
        Self::new(Ggx::new(widen(base, p)), Ggx::new(base))
    }
}

impl<W: Ndf, B: Ndf> Ndf for TemporalLobe<W, B> {
    #[inline]
    fn p22(&self, s: Vec2) -> F {
        self.widened.p22(s)
    }

    #[inline]
    fn d(&self, mn: Vec3) -> F {
        self.widened.d(mn)
    }

    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        self.base.lambda(w)
    }

    #[inline]
    fn g1(&self, w: Vec3, mn: Vec3) -> F {
        self.base.g1(w, mn)
    }

    #[inline]
    fn g2(&self, i: Vec3, o: Vec3, mn: Vec3) -> F {
        self.base.g2(i, o, mn)
    }
}
