//! LEAN moments nested into every method of the front door (KHPL16 section 5.5, eq. 21).
//!
//! A texel's normals spread the material's lobe by the LEAN kernel `K_L = N(E[s],
//! Sigma_L)`, `Sigma_L = E[s s^T] - E[s] E[s]^T` ([`LeanMoments::covariance`]); the pixel
//! spreads it again by its own kernel. Both are convolutions of the slope density, so
//! `K_P * (K_L * D) = (K_P * K_L) * D` (eq. 21): the material is widened by `K_L` first
//! ([`lean_widened`]: `A_L = A + 2 Sigma_L`, exact for Beckmann, TK19's approximation for
//! GGX), then each method filters the widened lobe over the pixel footprint exactly as it
//! filters a material ([`Lean`]):
//!
//! | method | the nested lobe |
//! |---|---|
//! | [`Gaussian`] | `ClampRules::filter_gaussian(A_L, footprint)` |
//! | [`ExactGaussian`] | GGX: `GaussianFilteredGgx(A, Sigma_L + K_P)` with `K_P` the method's clamped pixel kernel: the exact convolution of the GGX lobe with both Gaussians, no approximation; Beckmann: as [`Gaussian`] |
//! | [`Projected`] | `ClampRules::filter_projected(A_L, footprint)` |
//! | [`Rect`], [`Proxy`] | the method on the axis-aligned lobe [`lean_widened_axis_aligned`] (`alpha_i^2 + 2 (Sigma_L)_ii`: the diagonal of `A_L`, as the box methods reduce the footprint to its axis-aligned bounding rectangle) |
//!
//! The clamp rules apply to the pixel kernel only: `Sigma_L` is the texel's measured
//! distribution, not a first-order estimate, so neither the maximum extent nor `kappa` cuts
//! it. The mean `E[s]` is the lobe's centre: shade with the normal [`lean_mean_normal`]
//! (KHPL16 section 5.5) and compute the footprint in its frame.
//!
//! The WGSL mirror is `shaders/filter/lean_nested.wgsl` (and `shaders/bake/moments.wgsl`
//! samples the baked moment chain of [`crate::bake`]).

use super::super::footprint::Footprint;
use super::super::kernel::Covariance;
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{AxisAligned, Isotropic, Roughness, RoughnessMatrix};
use super::{
    ExactGaussian, Gaussian, GaussianFilteredGgx, LeanMoments, Method, Projected, Proxy, Rect,
    RectFilteredGgx, Vec3, gaussian,
};
use crate::math as m;

/// A method of the front door with the LEAN moments of the shaded texel nested into it
/// (KHPL16 eq. 21): each method filters the material widened by [`lean_widened`] (the box
/// methods: [`lean_widened_axis_aligned`]; the exact Gaussian filter of GGX: one kernel
/// `Sigma_L + K_P`), the clamp rules acting on the pixel kernel only:
/// `material.filtered(footprint, Lean::new(Gaussian::TK19, moments))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lean<M> {
    /// The method that filters the widened lobe over the pixel footprint.
    pub method: M,
    /// The texel's slope moments (sampled from the moment chain).
    pub moments: LeanMoments,
}

impl<M> Lean<M> {
    /// `method` with `moments` nested into it.
    #[inline]
    pub const fn new(method: M, moments: LeanMoments) -> Self {
        Self { method, moments }
    }
}

/// The material widened by the LEAN kernel, `A_L = A + 2 Sigma_L` with `Sigma_L =`
/// [`LeanMoments::covariance`] (PSD-projected), determinant clamp `tau = det A`
/// ([`gaussian`]): the lobe of the texel's normals before the pixel filters it. Exact for
/// Beckmann (a Gaussian of slopes convolved with a Gaussian), TK19's approximation for GGX.
/// Any moments give a valid matrix (the covariance is sanitised).
#[inline]
pub fn lean_widened<R: Roughness>(roughness: R, moments: &LeanMoments) -> RoughnessMatrix {
    gaussian(roughness, moments.covariance())
}

/// The axis-aligned lobe of the box methods: `alpha_i' = sqrt(alpha_i^2 + 2 (Sigma_L)_ii)`,
/// the diagonal of [`lean_widened`]'s `A_L` (the off-diagonal `(Sigma_L)_xy` is dropped, as
/// the box methods drop the footprint's orientation in its bounding rectangle), clamped to
/// `[ALPHA_MIN, ALPHA_MAX]` ([`AxisAligned::new_clamped`]).
#[inline]
pub fn lean_widened_axis_aligned(roughness: AxisAligned, moments: &LeanMoments) -> AxisAligned {
    let c = moments.covariance();
    let a = roughness.alpha();
    AxisAligned::new_clamped(
        m::sqrt(a.x * a.x + 2.0 * c.s11),
        m::sqrt(a.y * a.y + 2.0 * c.s22),
    )
}

/// The shading normal of the texel, the unit normal of the mean slope:
/// `normalize(-E[s_x], -E[s_y], 1)` (the crate's slope `s = -n_xy / n_z`; KHPL16 section 5.5
/// perturbs the tangent frame by it). Non-finite means give `+z`.
#[inline]
pub fn lean_mean_normal(moments: &LeanMoments) -> Vec3 {
    let s = moments.mean;
    if !(s.x.is_finite() && s.y.is_finite()) {
        return Vec3::Z;
    }
    Vec3::new(-s.x, -s.y, 1.0).normalize_or(Vec3::Z)
}

impl<R: Roughness> Method<Ggx<R>> for Lean<Gaussian> {
    type Lobe = Ggx<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        let widened = Ggx::new(lean_widened(material.roughness, &self.moments));
        self.method.lobe(&widened, footprint)
    }
}

impl<R: Roughness> Method<Beckmann<R>> for Lean<Gaussian> {
    type Lobe = Beckmann<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Beckmann<R>, footprint: Footprint) -> Self::Lobe {
        let widened = Beckmann::new(lean_widened(material.roughness, &self.moments));
        self.method.lobe(&widened, footprint)
    }
}

impl<R: Roughness> Method<Ggx<R>> for Lean<ExactGaussian> {
    type Lobe = GaussianFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        let e = &self.method;
        let pixel = e
            .clamps
            .kernel(e.clamps.footprint(footprint).covariance(e.sigma));
        let kernel: Covariance = pixel + self.moments.covariance();
        GaussianFilteredGgx::new(material.roughness, kernel).with_tolerance(e.tolerance)
    }
}

impl<R: Roughness> Method<Beckmann<R>> for Lean<ExactGaussian> {
    type Lobe = Beckmann<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Beckmann<R>, footprint: Footprint) -> Self::Lobe {
        let gaussian = Gaussian {
            clamps: self.method.clamps,
            sigma: self.method.sigma,
        };
        Lean::new(gaussian, self.moments).lobe(material, footprint)
    }
}

impl<R: Roughness> Method<Ggx<R>> for Lean<Projected> {
    type Lobe = Ggx<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        let widened = Ggx::new(lean_widened(material.roughness, &self.moments));
        self.method.lobe(&widened, footprint)
    }
}

impl Method<Ggx<AxisAligned>> for Lean<Rect> {
    type Lobe = RectFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<AxisAligned>, footprint: Footprint) -> Self::Lobe {
        let widened = Ggx::new(lean_widened_axis_aligned(material.roughness, &self.moments));
        self.method.lobe(&widened, footprint)
    }
}

impl Method<Ggx<Isotropic>> for Lean<Rect> {
    type Lobe = RectFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe {
        self.lobe(&Ggx::new(AxisAligned::from(material.roughness)), footprint)
    }
}

impl Method<Ggx<AxisAligned>> for Lean<Proxy> {
    type Lobe = Ggx<AxisAligned>;
    #[inline]
    fn lobe(&self, material: &Ggx<AxisAligned>, footprint: Footprint) -> Self::Lobe {
        let widened = Ggx::new(lean_widened_axis_aligned(material.roughness, &self.moments));
        self.method.lobe(&widened, footprint)
    }
}

impl Method<Ggx<Isotropic>> for Lean<Proxy> {
    type Lobe = Ggx<AxisAligned>;
    #[inline]
    fn lobe(&self, material: &Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe {
        self.lobe(&Ggx::new(AxisAligned::from(material.roughness)), footprint)
    }
}
