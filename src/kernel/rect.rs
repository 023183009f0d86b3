//! The conservative rectangle kernel of KHPL16 section 5.3 and its Gaussian equivalent.

use super::super::footprint::Footprint;
use super::{Covariance, F, Vec2};

/// An axis-aligned slope-domain rectangle centred on the half vector's slope, stored by its
/// half-extents (half the side lengths, slope units): KHPL16 section 5.3's conservative
/// region `R` and the `footprint` argument of the GDC 2016 `GGXRectIntegral`.
///
/// Convention: the rectangle bounds the *one-pixel* parallelogram (`|a|, |b| <= 1/2` pixel
/// steps), so `half_extent = (|dh_u| + |dh_v|) / 2` and the full side `w = |dh_u| + |dh_v|`
/// is TK19 Listing 3's `boundingRectangle`. Half-extents are stored because the rectangle
/// integral takes them and the clamps of the GDC listing act on them.
///
/// Its Gaussian equivalent ([`BoundingRect::covariance`]) treats the full side like the
/// footprint vectors: `Sigma_R = sigma^2 diag(w_x^2, w_y^2) = diag((2 sigma h_x)^2,
/// (2 sigma h_y)^2)`, which is `diag(h_x^2, h_y^2)` for `sigma = 1/2` (GDC 2016 Beckmann
/// listing `rghns_sq += fp * fp * 2`, TK19 Listing 3 `SIGMA2 * maxWidth^2`). It has the same
/// or larger variance than the parallelogram's `Sigma` along each axis, and `2 Sigma_R -
/// Sigma` is positive semi-definite (Cauchy-Schwarz), but `Sigma_R` alone does not dominate
/// `Sigma` along diagonals (a footprint along `(1, 1)` has twice the variance there).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BoundingRect {
    /// Half-extents along the tangent `x` and bitangent `y` (slope units, `>= 0`).
    pub half_extent: Vec2,
}

impl BoundingRect {
    /// From half-extents (not checked; see [`super::clamp::ClampRules::rect`]).
    #[inline]
    pub const fn new(half_extent: Vec2) -> Self {
        Self { half_extent }
    }

    /// The axis-aligned bounding rectangle of the one-pixel parallelogram
    /// `{a dh_u + b dh_v : |a|, |b| <= 1/2}` of a footprint (KHPL16 section 5.3; GDC 2016
    /// listing `fp = (abs(dFdx(hpp)) + abs(dFdy(hpp))) * 0.5`; TK19 Listing 3
    /// `abs(dU) + abs(dV)` is its full side): half-extent `(|dh_u| + |dh_v|) / 2` per axis. A
    /// NaN footprint entry counts as `0` (the NaN policy, [`Footprint::nan_to_zero`]); an
    /// infinite one gives an infinite half extent, which [`ClampRules::rect`] saturates.
    ///
    /// [`ClampRules::rect`]: super::ClampRules::rect
    #[inline]
    pub fn from_footprint(fp: Footprint) -> Self {
        let fp = fp.nan_to_zero();
        Self {
            half_extent: (fp.dh_u.abs() + fp.dh_v.abs()) * 0.5,
        }
    }

    /// The Gaussian-equivalent diagonal covariance `diag((2 sigma h_x)^2, (2 sigma h_y)^2)`
    /// (see the type docs), `sigma` in pixels.
    #[inline]
    pub fn covariance(self, sigma: F) -> Covariance {
        let w = self.half_extent * (2.0 * sigma);
        Covariance::new(w.x * w.x, 0.0, w.y * w.y)
    }
}

impl Footprint {
    /// The axis-aligned bounding rectangle of the one-pixel parallelogram:
    /// [`BoundingRect::from_footprint`].
    #[inline]
    pub fn bounding_rect(self) -> BoundingRect {
        BoundingRect::from_footprint(self)
    }
}
