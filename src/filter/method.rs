//! The front door: one call from what a renderer has (a material NDF and a pixel footprint)
//! to a filtered lobe whose methods all describe one distribution.
//!
//! ```
//! use filtered_ndf::f32::prelude::*;
//! use glam::{Vec2, Vec3};
//!
//! let material = Ggx::isotropic(0.01).unwrap();
//! let footprint = Footprint::from_slope_derivatives(Vec2::new(0.03, 0.0), Vec2::new(0.0, 0.02));
//! let lobe = material.filtered(footprint, Gaussian::TK19); // Ggx<RoughnessMatrix>
//!
//! let h = Vec3::new(0.001, 0.0, 1.0).normalize();
//! assert!(lobe.d(h) < material.d(h)); // the sub-pixel peak is spread over the footprint
//! ```
//!
//! A method is a small value (its clamp rules and pixel filter width) whose type says what it
//! returns for each material NDF ([`Method::Lobe`]):
//!
//! | method | paper | GGX gives | Beckmann gives | exact? |
//! |---|---|---|---|---|
//! | [`Gaussian`] | KHPL16 eq. 13-15; TK19 sec. 2.2 | [`Ggx`]`<RoughnessMatrix>` (`A + 2 Sigma`) | [`Beckmann`]`<RoughnessMatrix>` (`A + 2 Sigma`) | Beckmann: the exact Gaussian filter; GGX: an approximation of it |
//! | [`ExactGaussian`] | this crate (the mixture identity, [`GaussianFilteredGgx`]) | [`GaussianFilteredGgx`] | [`Beckmann`]`<RoughnessMatrix>` (`A + 2 Sigma`) | exact for both |
//! | [`Projected`] | TK21 | [`Ggx`]`<RoughnessMatrix>` (`A + 2 Sigma` in projected space) | - | an approximation of the Gaussian filter |
//! | [`Rect`] | KHPL16 eq. 16, App. A | [`RectFilteredGgx`] | - | the exact box filter over the footprint's bounding rectangle |
//! | [`Proxy`] | KHPL16 eq. 18-19 | [`Ggx`]`<AxisAligned>` | - | the GGX whose peak equals the box-filtered peak |
//!
//! Every lobe implements [`Ndf`] (`p22`, `d`, `lambda`, `g1`, `g2` of one distribution); the
//! lobes that are NDFs of this crate in roughness-matrix or axis-aligned form also implement
//! [`NdfSampling`](super::super::NdfSampling), whose samplers and pdfs describe the same
//! distribution as `d` and `lambda`. A method that is not defined for an NDF (the projected
//! space and the box filter are GGX constructions) does not compile for it.
//!
//! **Footprints.** A [`Footprint`] holds the slope change of the half vector per pixel step,
//! from whichever derivatives the renderer has (see its constructors: ddx/ddy of the slope,
//! of the tangent-space half vector, of the projected `h_xy` (TK19 section 3.2 uses these as
//! they are), normal differences, or ray differentials with the half-vector Jacobian `M`).
//! [`Projected`] adds its kernel in the projected-disk space of TK21: give it the footprint of
//! the projected derivatives ([`Footprint::from_projected_derivatives`], or
//! [`footprint_projected`](super::super::footprint::geometry::footprint_projected) of a slope
//! footprint); a slope footprint is used as it is, which is exact at `h = n` (where both
//! Jacobians are `-I`).
//!
//! **Deferred shading** has no footprint, only G-buffer normal differences and one roughness
//! channel: see [`KernelConvention::filter`](super::deferred::KernelConvention::filter) and
//! the engine [`presets`](super::presets).

use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, SIGMA_PIXEL};
use super::super::ndf::Ndf;
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{AxisAligned, Isotropic, Roughness, RoughnessMatrix};
use super::{F, GaussianFilteredGgx, Vec2, Vec3, proxy, rect};

/// A filtering method: turns a material NDF `N` and a pixel footprint into a filtered lobe
/// (see the [module docs](self) for the methods and what each returns).
pub trait Method<N> {
    /// The filtered lobe this method gives for the material NDF `N`.
    type Lobe: Ndf;

    /// The lobe of `material` filtered over `footprint`.
    fn lobe(&self, material: &N, footprint: Footprint) -> Self::Lobe;
}

/// `material.filtered(footprint, method)`: the front door, for every material NDF.
pub trait Filterable: Sized {
    /// The lobe of this material filtered over `footprint` by `method` (see
    /// [`Method`]). Never panics; any footprint (zero, huge, non-finite) gives a lobe whose
    /// evaluations are finite for finite arguments, as the clamp rules of the method make it.
    #[inline]
    fn filtered<M: Method<Self>>(&self, footprint: Footprint, method: M) -> M::Lobe {
        method.lobe(self, footprint)
    }
}

impl<R: Roughness> Filterable for Ggx<R> {}
impl<R: Roughness> Filterable for Beckmann<R> {}

/// `A' = A + 2 Sigma` with the Gaussian pixel kernel `Sigma = sigma^2 (dh_u dh_u^T + dh_v
/// dh_v^T)` (KHPL16 eq. 13-15; TK19 section 2.2), after the clamp rules
/// ([`ClampRules::filter_gaussian`]: maximum extent, `kappa`, determinant clamp).
///
/// For Beckmann this is the exact convolution of the lobe with the kernel (a Beckmann lobe is
/// a Gaussian of slopes with covariance `A / 2`). For GGX it is TK19's approximation: the GGX
/// of roughness `A + 2 Sigma` (its error against the exact Gaussian-filtered GGX is in the
/// trade table, [`crate::tables`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gaussian {
    /// The clamp rules applied to the footprint, the kernel and the filtered matrix.
    pub clamps: ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    pub sigma: F,
}

impl Gaussian {
    /// TK19's configuration: [`ClampRules::default`] (`lambda = 1`, `kappa = 0.18`, the
    /// determinant clamp) and `sigma = 0.5` pixels.
    pub const TK19: Self = Self {
        clamps: ClampRules::DEFAULT,
        sigma: SIGMA_PIXEL,
    };

    /// KHPL16's configuration for the parallelogram kernel: the maximum extent `lambda = 1`
    /// (section 5.2) and the determinant clamp, no `kappa`; `sigma = 0.5` pixels.
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
        sigma: SIGMA_PIXEL,
    };
}

impl Default for Gaussian {
    /// [`Gaussian::TK19`].
    fn default() -> Self {
        Self::TK19
    }
}

impl<R: Roughness> Method<Ggx<R>> for Gaussian {
    type Lobe = Ggx<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        Ggx::new(
            self.clamps
                .filter_gaussian(material.roughness, footprint, self.sigma),
        )
    }
}

impl<R: Roughness> Method<Beckmann<R>> for Gaussian {
    type Lobe = Beckmann<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Beckmann<R>, footprint: Footprint) -> Self::Lobe {
        Beckmann::new(
            self.clamps
                .filter_gaussian(material.roughness, footprint, self.sigma),
        )
    }
}

/// The exact Gaussian filter: the material's slope density convolved with the pixel kernel
/// `N(0, Sigma)`, `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)` after the clamp rules
/// ([`ClampRules::footprint`], [`ClampRules::kernel`]). For GGX the lobe is
/// [`GaussianFilteredGgx`] (what [`Gaussian`] approximates by `A + 2 Sigma`); for Beckmann the
/// exact filter is `A + 2 Sigma` itself, so this gives the same lobe as [`Gaussian`] with the
/// same rules: a renderer switches NDF without switching method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactGaussian {
    /// The clamp rules applied to the footprint and the kernel (for Beckmann also the
    /// determinant clamp of the filtered matrix).
    pub clamps: ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    pub sigma: F,
}

impl ExactGaussian {
    /// The unbiased filter of the footprint: the maximum extent `lambda = 1` of KHPL16
    /// section 5.2 (a first-order footprint wider than that is not trustworthy), no `kappa`;
    /// `sigma = 0.5` pixels.
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
        sigma: SIGMA_PIXEL,
    };

    /// The clamped pixel kernel of `footprint`.
    #[inline]
    fn kernel(&self, footprint: Footprint) -> super::super::kernel::Covariance {
        let rules = self.clamps;
        rules.kernel(rules.footprint(footprint).covariance(self.sigma))
    }
}

impl Default for ExactGaussian {
    /// [`ExactGaussian::KHPL16`].
    fn default() -> Self {
        Self::KHPL16
    }
}

impl<R: Roughness> Method<Ggx<R>> for ExactGaussian {
    type Lobe = GaussianFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        GaussianFilteredGgx::new(material.roughness, self.kernel(footprint))
    }
}

impl<R: Roughness> Method<Beckmann<R>> for ExactGaussian {
    type Lobe = Beckmann<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Beckmann<R>, footprint: Footprint) -> Self::Lobe {
        Gaussian {
            clamps: self.clamps,
            sigma: self.sigma,
        }
        .lobe(material, footprint)
    }
}

/// Projected-space filtering of GGX (Tokuyoshi and Kaplanyan 2021, JCGT 10(2)): `P = A (I -
/// A)^-1`, `P' = P + 2 Sigma`, `A' = P' (I + P')^-1` ([`super::projected`]), with the kernel
/// `Sigma` of the footprint after the clamp rules ([`ClampRules::filter_projected`]: maximum
/// extent, `kappa`, determinant clamp). The footprint should hold projected-disk derivatives (see the
/// [module docs](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    /// The clamp rules applied to the footprint and the kernel.
    pub clamps: ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    pub sigma: F,
}

impl Projected {
    /// TK21's configuration: [`ClampRules::default`] and `sigma = 0.5` pixels (TK21's
    /// `SIGMA2 = 1 / (2 pi)` is a variance of its own pixel filter; set `sigma` to
    /// `sqrt(1 / (2 pi))` to reproduce it).
    pub const TK21: Self = Self {
        clamps: ClampRules::DEFAULT,
        sigma: SIGMA_PIXEL,
    };
}

impl Default for Projected {
    /// [`Projected::TK21`].
    fn default() -> Self {
        Self::TK21
    }
}

impl<R: Roughness> Method<Ggx<R>> for Projected {
    type Lobe = Ggx<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        Ggx::new(
            self.clamps
                .filter_projected(material.roughness, footprint, self.sigma),
        )
    }
}

/// The exact box filter of KHPL16 section 5.3 (eq. 16, Appendix A): the GGX slope density
/// averaged over the footprint's axis-aligned bounding rectangle, its half extents clamped by
/// [`ClampRules::rect`]. Axis-aligned materials only (the rectangle is axis-aligned).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// The clamp rules applied to the rectangle's half extents (maximum extent, floor).
    pub clamps: ClampRules,
}

impl Rect {
    /// KHPL16 with the crate's exact integral: half extents clamped to `lambda = 1`, no floor
    /// (the exact integral needs none).
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
    };

    /// The GDC 2016 listing's clamps: half extents in `[min(alpha, 0.1), 1]`.
    pub const GDC2016: Self = Self {
        clamps: ClampRules::GDC2016,
    };

    /// The clamped half extents of `footprint`'s bounding rectangle for the roughness `r`.
    #[inline]
    fn half_extent(&self, r: AxisAligned, footprint: Footprint) -> Vec2 {
        self.clamps
            .rect(footprint.bounding_rect(), r.alpha())
            .half_extent
    }
}

impl Default for Rect {
    /// [`Rect::KHPL16`].
    fn default() -> Self {
        Self::KHPL16
    }
}

impl Method<Ggx<AxisAligned>> for Rect {
    type Lobe = RectFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<AxisAligned>, footprint: Footprint) -> Self::Lobe {
        let r = material.roughness;
        RectFilteredGgx::new(r, self.half_extent(r, footprint))
    }
}

impl Method<Ggx<Isotropic>> for Rect {
    type Lobe = RectFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe {
        self.lobe(&Ggx::new(AxisAligned::from(material.roughness)), footprint)
    }
}

/// The GGX proxy of KHPL16 section 5.4 (eq. 18-19, solved exactly: [`proxy::proxy`]): the
/// axis-aligned GGX whose peak equals the peak of the box-filtered GGX over the clamped
/// bounding rectangle ([`Rect`]), per axis. Axis-aligned materials only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Proxy {
    /// The clamp rules applied to the rectangle's half extents.
    pub clamps: ClampRules,
}

impl Proxy {
    /// KHPL16: half extents clamped to `lambda = 1`, no floor.
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
    };
}

impl Default for Proxy {
    /// [`Proxy::KHPL16`].
    fn default() -> Self {
        Self::KHPL16
    }
}

impl Method<Ggx<AxisAligned>> for Proxy {
    type Lobe = Ggx<AxisAligned>;
    #[inline]
    fn lobe(&self, material: &Ggx<AxisAligned>, footprint: Footprint) -> Self::Lobe {
        let r = material.roughness;
        let half = Rect {
            clamps: self.clamps,
        }
        .half_extent(r, footprint);
        Ggx::new(proxy::proxy(r, half))
    }
}

impl Method<Ggx<Isotropic>> for Proxy {
    type Lobe = Ggx<AxisAligned>;
    #[inline]
    fn lobe(&self, material: &Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe {
        self.lobe(&Ggx::new(AxisAligned::from(material.roughness)), footprint)
    }
}

/// The exactly box-filtered GGX lobe ([`Rect`]): the axis-aligned GGX slope density averaged
/// over the slope-domain rectangle `[-H_x, H_x] x [-H_y, H_y]` around each slope (KHPL16
/// eq. 16).
///
/// - `p22(s)` = [`rect::p22_rect`], `d(m)` = [`rect::d_rect`] (exact to about one ulp).
/// - `lambda(w)` = [`rect::lambda_rect`]: Smith's `Lambda` of this distribution itself, so
///   that `g1` and `g2` are those of the filtered surface and the Smith normalisation
///   `integral G1(w, m) max(0, w.m) D(m) dm = w_z` holds.
/// - Sampling is exact but takes four uniform numbers (a GGX sample and an offset in the box:
///   the conditional CDFs of the box-filtered density have no closed form), so this lobe does
///   not implement the two-number [`NdfSampling`](super::super::NdfSampling); its samplers
///   and their pdfs are the inherent methods below.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectFilteredGgx {
    /// The material's roughness.
    pub roughness: AxisAligned,
    /// The rectangle's half extents (slope units, `>= 0`).
    pub half_extent: Vec2,
}

impl RectFilteredGgx {
    /// The box-filtered lobe of `roughness` over half extents `half_extent` (taken by
    /// magnitude, NaN as `0`, as [`rect::p22_rect`] does).
    #[inline]
    pub const fn new(roughness: AxisAligned, half_extent: Vec2) -> Self {
        Self {
            roughness,
            half_extent,
        }
    }
}

impl Ndf for RectFilteredGgx {
    #[inline]
    fn p22(&self, s: Vec2) -> F {
        rect::p22_rect(self.roughness, s, self.half_extent)
    }
    #[inline]
    fn d(&self, m: Vec3) -> F {
        rect::d_rect(self.roughness, m, self.half_extent)
    }
    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        rect::lambda_rect(self.roughness, self.half_extent, w)
    }
}
