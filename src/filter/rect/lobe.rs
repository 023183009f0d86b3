//! The box-filter method and its lobe: [`Rect`] (KHPL16 section 5.3, the footprint's bounding
//! rectangle after the clamp rules) gives [`RectFilteredGgx`], the axis-aligned GGX averaged
//! over that rectangle, with its own Smith `Lambda` ([`lambda_rect`]). Its exact samplers are
//! the sampling stage's (`sampling::rect`).

use super::super::super::footprint::Footprint;
use super::super::super::kernel::ClampRules;
use super::super::super::ndf::Ndf;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::ndf::roughness::{AxisAligned, Isotropic};
use super::super::method::Method;
use super::{F, Vec2, Vec3, d_rect, lambda_rect, p22_rect};

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
    pub(crate) fn half_extent(&self, r: AxisAligned, footprint: Footprint) -> Vec2 {
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

/// The exactly box-filtered GGX lobe ([`Rect`]): the axis-aligned GGX slope density averaged
/// over the slope-domain rectangle `[-H_x, H_x] x [-H_y, H_y]` around each slope (KHPL16
/// eq. 16).
///
/// - `p22(s)` = [`p22_rect`], `d(m)` = [`d_rect`] (exact to about one ulp).
/// - `lambda(w)` = [`lambda_rect`]: Smith's `Lambda` of this distribution itself, so
///   that `g1` and `g2` are those of the filtered surface and the Smith normalisation
///   `integral G1(w, m) max(0, w.m) D(m) dm = w_z` holds.
/// - Sampling is exact but takes four uniform numbers (a GGX sample and an offset in the box:
///   the conditional CDFs of the box-filtered density have no closed form), so this lobe does
///   not implement the two-number [`NdfSampling`](super::super::super::NdfSampling); its samplers
///   and their pdfs are its inherent methods `sample_normal`, `sample_visible_normal`,
///   `normal_pdf`, `visible_normal_pdf` (`sampling::rect`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectFilteredGgx {
    /// The material's roughness.
    pub roughness: AxisAligned,
    /// The rectangle's half extents (slope units, `>= 0`).
    pub half_extent: Vec2,
}

impl RectFilteredGgx {
    /// The box-filtered lobe of `roughness` over half extents `half_extent` (taken by
    /// magnitude, NaN as `0`, as [`p22_rect`] does).
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
        p22_rect(self.roughness, s, self.half_extent)
    }
    #[inline]
    fn d(&self, m: Vec3) -> F {
        d_rect(self.roughness, m, self.half_extent)
    }
    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        lambda_rect(self.roughness, self.half_extent, w)
    }
}
