//! Pixel footprints in the slope domain (KHPL16 sections 4.2 and 4.3, TK19 section 2.2) and
//! the maps and Jacobians that carry derivatives into it.
//!
//! A footprint is the pair of slope-domain vectors `(dh_u, dh_v)`: the change of the half
//! vector's slope across one pixel step in `x` and in `y`. A Gaussian pixel filter of standard
//! deviation `sigma` pixels (0.5 in both papers) carried into the slope domain has covariance
//! `Sigma = sigma^2 U^T U` with `U` the matrix whose rows are `dh_u` and `dh_v` (TK19
//! section 2.2; KHPL16 eq. 13 with `sigma` folded into the vectors).
//!
//! - Constructors: from slope derivatives (KHPL16 4.2, 5.1), from projected-disk derivatives
//!   (TK19 3.2, used directly or mapped to slope space), from normal differences (TK19 eq. 3).
//! - Kernel shapes (the next stage, [`super::kernel`]): [`Covariance`] (the Gaussian,
//!   [`Footprint::covariance`]) and [`BoundingRect`] (the conservative rectangle of KHPL16
//!   5.3, [`Footprint::bounding_rect`]).
//! - [`slope`]: the maps between the sphere, the projected disk and the slope plane;
//!   [`jacobian`]: their Jacobians (TK19 supplement); [`geometry`]: the half-vector Jacobian
//!   `M` and ray-differential footprints (KHPL16 section 4).

use super::kernel::{BoundingRect, Covariance};
use super::{F, Mat2, Vec2, Vec3};
use crate::math as m;

pub mod geometry;
pub mod jacobian;
pub mod slope;

/// A slope-domain pixel footprint: the slope change per pixel step in `x` (`dh_u`) and in `y`
/// (`dh_v`) (KHPL16 section 4.2, `Delta h_u = Delta x_u M`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// Slope change per pixel step along the image `x` axis.
    pub dh_u: Vec2,
    /// Slope change per pixel step along the image `y` axis.
    pub dh_v: Vec2,
}

impl Footprint {
    /// A zero footprint (the filtered NDF equals the unfiltered one).
    pub const ZERO: Self = Self {
        dh_u: Vec2::ZERO,
        dh_v: Vec2::ZERO,
    };

    /// From slope-domain derivatives, e.g. `ddx`/`ddy` of the slope of `h` (KHPL16 section
    /// 5.1) or `dx_u M`, `dx_v M` from ray differentials (KHPL16 section 4.2).
    #[inline]
    pub const fn from_slope_derivatives(dh_u: Vec2, dh_v: Vec2) -> Self {
        Self { dh_u, dh_v }
    }

    /// From derivatives of the projected half vector `p = (h_x, h_y)` on the unit disk
    /// (TK19 section 3.2 and Listing 1: `ddx(halfvectorTS.xy)`, `ddy(halfvectorTS.xy)`).
    ///
    /// TK19 builds the kernel from these vectors directly, as if they were slope changes:
    /// the slope-domain change would be `J dp` with the Jacobian of TK19 supplement eq. 6,
    /// whose determinant `1 / h_z^3` blows the footprint (and its estimation error) up at
    /// grazing half vectors. Dropping it shrinks the bandwidth there by `det J_o->perp = h_z`
    /// relative to the sphere (TK19 section 3.2) and equals the slope footprint at `h = n`,
    /// where `J = -I`. Units: disk units per pixel, used as slope units. For the exact slope
    /// change use [`Footprint::from_projected_derivatives_in_slope`].
    #[inline]
    pub const fn from_projected_derivatives(dp_u: Vec2, dp_v: Vec2) -> Self {
        Self {
            dh_u: dp_u,
            dh_v: dp_v,
        }
    }

    /// The slope-domain footprint of disk derivatives at the unit half vector `h`:
    /// `dh = J_perp->par dp` with `J_perp->par = -1/h_z^3 [[1 - h_y^2, h_x h_y],
    /// [h_x h_y, 1 - h_x^2]]` (TK19 supplement eq. 6), i.e. the first-order change of the slope
    /// `s = -p / sqrt(1 - |p|^2)`. `h_z` is clamped to `>= 1e-6` (the footprint of a grazing
    /// half vector is then huge and finite; clamp it with
    /// [`super::ClampRules::footprint`]). `h` is normalised first (a huge non-unit `h`
    /// would overflow `1 - h_y^2` to NaN); a zero or non-finite `h` gives [`Footprint::ZERO`].
    pub fn from_projected_derivatives_in_slope(h: Vec3, dp_u: Vec2, dp_v: Vec2) -> Self {
        let big = h.abs().max_element();
        if !h.is_finite() || big <= 0.0 {
            return Self::ZERO;
        }
        let h = h / big;
        let h = h / m::sqrt(h.length_squared());
        let hz = h.z.max(1e-6);
        let k = -1.0 / (hz * hz * hz);
        let j = |d: Vec2| {
            Vec2::new(
                (1.0 - h.y * h.y) * d.x + h.x * h.y * d.y,
                h.x * h.y * d.x + (1.0 - h.x * h.x) * d.y,
            ) * k
        };
        Self {
            dh_u: j(dp_u),
            dh_v: j(dp_v),
        }
    }

    /// The deferred-rendering footprint from normal differences between neighbouring pixels
    /// (TK19 section 4.4, eq. 3), in the tangent frame of the current normal `n` (`z = n`).
    ///
    /// `dn_u = n_u - n` and `dn_v = n_v - n` are the differences to the unit normals of the
    /// horizontal and vertical neighbours (`ddx(normal)`, `ddy(normal)` expressed in the
    /// tangent frame). TK19 differentiates the half-way normal `n_bar_u = (n + n_u) /
    /// |n + n_u|` on the projected disk over the half-pixel step to it:
    /// `dn_bar_u = 2 (n_bar_u)_xy = 2 (dn_u)_xy / |2 e_z + dn_u|`, whose norm is exactly
    /// `|dn_u|` for unit normals (eq. 3: `|dn_bar_perp| = |dn|`) and whose direction is that of
    /// the tangential part of `dn_u`. Hence `tr(covariance(sigma)) = sigma^2 (|dn_u|^2 +
    /// |dn_v|^2)` (TK19 eq. 4). Near-opposite normals (`n_u ~ -n`) have no half-way normal;
    /// the denominator is clamped to `>= 1e-6` (a huge, finite footprint; zero for exactly
    /// opposite normals, which have no tangential difference). Non-finite input gives
    /// [`Footprint::ZERO`].
    pub fn from_normal_differences(dn_u: Vec3, dn_v: Vec3) -> Self {
        if !(dn_u.is_finite() && dn_v.is_finite()) {
            return Self::ZERO;
        }
        let half = |d: Vec3| {
            let len = (Vec3::new(0.0, 0.0, 2.0) + d).length().max(1e-6);
            Vec2::new(d.x, d.y) * (2.0 / len)
        };
        Self {
            dh_u: half(dn_u),
            dh_v: half(dn_v),
        }
    }

    /// [`Footprint::from_normal_differences`] for world-space differences and a world-space
    /// orthonormal tangent frame `(t, b, n)`: the differences are first expressed in the frame
    /// (`(t.dn, b.dn, n.dn)`).
    pub fn from_world_normal_differences(
        t: Vec3,
        b: Vec3,
        n: Vec3,
        dn_u: Vec3,
        dn_v: Vec3,
    ) -> Self {
        let local = |d: Vec3| Vec3::new(t.dot(d), b.dot(d), n.dot(d));
        Self::from_normal_differences(local(dn_u), local(dn_v))
    }

    /// `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)` (TK19 section 2.2), `sigma` in pixels.
    #[inline]
    pub fn covariance(self, sigma: F) -> Covariance {
        let (u, v) = (self.dh_u, self.dh_v);
        Covariance::new(
            u.x * u.x + v.x * v.x,
            u.x * u.y + v.x * v.y,
            u.y * u.y + v.y * v.y,
        ) * (sigma * sigma)
    }

    /// The axis-aligned bounding rectangle of the one-pixel parallelogram
    /// `{a dh_u + b dh_v : |a|, |b| <= 1/2}` (KHPL16 section 5.3; GDC 2016 listing
    /// `fp = (abs(dFdx(hpp)) + abs(dFdy(hpp))) * 0.5`; TK19 Listing 3 `abs(dU) + abs(dV)`
    /// is its full side): half-extent `(|dh_u| + |dh_v|) / 2` per axis.
    #[inline]
    pub fn bounding_rect(self) -> BoundingRect {
        BoundingRect {
            half_extent: (self.dh_u.abs() + self.dh_v.abs()) * 0.5,
        }
    }

    /// The largest distance from the centre to a vertex of the one-pixel parallelogram,
    /// `max(|dh_u + dh_v|, |dh_u - dh_v|) / 2`: the extent clamped by KHPL16 section 5.2.
    /// It bounds both half-extents of [`Footprint::bounding_rect`] (unless the squares in the
    /// lengths underflow: vectors below about `1e-19` in `f32`, `1e-154` in `f64`, give `0`).
    #[inline]
    pub fn max_extent(self) -> F {
        0.5 * (self.dh_u + self.dh_v)
            .length()
            .max((self.dh_u - self.dh_v).length())
    }
}
