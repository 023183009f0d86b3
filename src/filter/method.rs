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
//! returns for each material NDF ([`Method::Lobe`]). Each method lives beside its math, in the
//! module of its filter (`gaussian`, `gaussian_ggx`, `projected`, `rect::lobe`, `proxy`); this
//! module holds the trait every method implements and the front door's trait:
//!
//! | method | paper | GGX gives | Beckmann gives | exact? |
//! |---|---|---|---|---|
//! | [`Gaussian`](super::Gaussian) | KHPL16 eq. 13-15; TK19 sec. 2.2 | [`Ggx`]`<RoughnessMatrix>` (`A + 2 Sigma`) | [`Beckmann`]`<RoughnessMatrix>` (`A + 2 Sigma`) | Beckmann: the exact Gaussian filter; GGX: an approximation of it |
//! | [`ExactGaussian`](super::ExactGaussian) | this crate (the mixture identity, [`GaussianFilteredGgx`](super::GaussianFilteredGgx)) | [`GaussianFilteredGgx`](super::GaussianFilteredGgx) | [`Beckmann`]`<RoughnessMatrix>` (`A + 2 Sigma`) | exact for both |
//! | [`Projected`](super::Projected) | TK21 | [`Ggx`]`<RoughnessMatrix>` (`A + 2 Sigma` in projected space) | - | an approximation of the Gaussian filter |
//! | [`Rect`](super::Rect) | KHPL16 eq. 16, App. A | [`RectFilteredGgx`](super::RectFilteredGgx) | - | the exact box filter over the footprint's bounding rectangle |
//! | [`Proxy`](super::Proxy) | KHPL16 eq. 18-19 | [`Ggx`]`<AxisAligned>` | - | the GGX whose peak equals the box-filtered peak |
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
//! [`Projected`](super::Projected) adds its kernel in the projected-disk space of TK21: give it the footprint of
//! the projected derivatives ([`Footprint::from_projected_derivatives`], or
//! [`footprint_projected`](super::super::footprint::geometry::footprint_projected) of a slope
//! footprint); a slope footprint is used as it is, which is exact at `h = n` (where both
//! Jacobians are `-I`).
//!
//! **Deferred shading** has no footprint, only G-buffer normal differences and one roughness
//! channel: see [`KernelConvention::filter`](super::deferred::KernelConvention::filter) and
//! the engine [`presets`](super::presets).

use super::super::footprint::Footprint;
use super::super::ndf::Ndf;
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::Roughness;

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
