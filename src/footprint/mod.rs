//! Pixel footprints in the slope domain (KHPL16 sections 4.2 and 4.3, TK19 section 2.2) and
//! the maps and Jacobians that carry derivatives into it.
//!
//! A footprint is the pair of slope-domain vectors `(dh_u, dh_v)`: the change of the half
//! vector's slope across one pixel step in `x` and in `y`. A Gaussian pixel filter of standard
//! deviation `sigma` pixels (0.5 in both papers) carried into the slope domain has covariance
//! `Sigma = sigma^2 U^T U` with `U` the matrix whose rows are `dh_u` and `dh_v` (TK19
//! section 2.2; KHPL16 eq. 13 with `sigma` folded into the vectors).
//!
//! - Constructors, one per form a renderer has: slope derivatives
//!   ([`Footprint::from_slope_derivatives`], KHPL16 4.2, 5.1); derivatives of the
//!   tangent-space half vector as 3-D vectors ([`Footprint::from_half_vector_derivatives`],
//!   TK19 supplement eq. 1-7); projected-disk derivatives `ddx(h_xy)`
//!   ([`Footprint::from_projected_derivatives`] as TK19 3.2 uses them,
//!   [`Footprint::from_projected_derivatives_in_slope`] mapped to slope space); normal
//!   differences ([`Footprint::from_normal_differences`], TK19 eq. 3); ray differentials
//!   through the geometry's `M` ([`Footprint::from_ray_differentials`], KHPL16 4.2).
//! - Kernel shapes are the next stage's ([`super::kernel`]), which builds them from a
//!   footprint: the Gaussian `Covariance::from_footprint` (also `footprint.covariance(sigma)`)
//!   and the conservative rectangle of KHPL16 5.3, `BoundingRect::from_footprint` (also
//!   `footprint.bounding_rect()`).
//! - NaN and infinite derivatives (the crate's one policy for footprints and normal
//!   differences, [`crate::contract`]): a NaN entry carries no information and counts as `0`
//!   (no widening from it); a `+-inf` entry saturates: the clamp rules turn it into the widest
//!   kernel they allow. The constructors below drop NaN inputs before mapping them and keep
//!   infinite results infinite ([`Footprint::nan_to_zero`]); the kernel stage applies the same
//!   substitution to a footprint built from raw values.
//! - [`slope`]: the maps between the sphere, the projected disk and the slope plane;
//!   [`jacobian`]: their Jacobians (TK19 supplement); [`geometry`]: the half-vector Jacobian
//!   `M` and ray-differential footprints (KHPL16 section 4).

use super::vector;
use super::{F, Mat2, Vec2, Vec3};

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
    /// 5.1) or `dx_u M`, `dx_v M` from ray differentials (KHPL16 section 4.2). Stored as given:
    /// the kernel stage reads a NaN entry as `0` and saturates an infinite one (module docs).
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
    /// change use [`Footprint::from_projected_derivatives_in_slope`]. Stored as given (NaN and
    /// infinite entries: module docs).
    #[inline]
    pub const fn from_projected_derivatives(dp_u: Vec2, dp_v: Vec2) -> Self {
        Self {
            dh_u: dp_u,
            dh_v: dp_v,
        }
    }

    /// The slope-domain footprint of disk derivatives at the half vector `h`:
    /// `dh = J_perp->par dp` with `J_perp->par` of TK19 supplement eq. 6
    /// ([`jacobian::projected_to_slope`]), i.e. the first-order change of the slope
    /// `s = -p / sqrt(1 - |p|^2)`. `h` is normalised and clamped to `h_z >= 1e-6`
    /// ([`jacobian::HZ_MIN`], at constant azimuth) as in [`jacobian`]: the footprint of a grazing
    /// or back-facing half vector is then huge and finite (clamp it with
    /// [`super::ClampRules::footprint`]). A zero or non-finite `h` gives [`Footprint::ZERO`]
    /// (no direction to map along). A NaN derivative entry counts as `0`; an infinite one, or
    /// a product beyond `F::MAX`, gives an infinite entry, which the clamp rules saturate
    /// (module docs).
    pub fn from_projected_derivatives_in_slope(h: Vec3, dp_u: Vec2, dp_v: Vec2) -> Self {
        if vector::unit(h).is_none() {
            return Self::ZERO;
        }
        let j = jacobian::projected_to_slope(h);
        let (dp_u, dp_v) = (vector::nan_to_zero2(dp_u), vector::nan_to_zero2(dp_v));
        Self::saturated(j * dp_u, j * dp_v)
    }

    /// The slope-domain footprint of the screen-space derivatives of the tangent-space half
    /// vector as 3-D vectors (`ddx(h)`, `ddy(h)` of the unit half vector, `z` = shading normal):
    /// `dh_u = J(o->par) (dh_dx . e_x, dh_dx . e_y)`, likewise for `dh_v` (TK19 supplement
    /// eq. 1-3 and 7, in the Cartesian form of [`jacobian::unit_vector_to_slope`]): the
    /// first-order change of the slope `s = -h_xy / h_z` along the derivative.
    ///
    /// - `h` need not be unit: only its direction is used. The derivatives are those of the
    ///   *unit* half vector; their radial part (along `h`) is dropped. With an unnormalised
    ///   `H = L + V` and its derivatives `dH`, pass `dH / |H|`.
    /// - Grazing and back-facing `h` (`h_z < 1e-6`, [`jacobian::HZ_MIN`]): clamped to the
    ///   horizon at constant azimuth; the footprint is huge and finite (clamp it with
    ///   [`super::ClampRules::footprint`]).
    /// - A zero or non-finite `h` and zero derivatives give [`Footprint::ZERO`]. A NaN
    ///   derivative entry counts as `0`; an infinite one, or a product beyond `F::MAX`, gives
    ///   an infinite entry, which the clamp rules saturate (module docs). Never NaN, never
    ///   panics.
    ///
    /// Units: `dh` per pixel (unit-vector change, i.e. radians); the result in slope per pixel.
    pub fn from_half_vector_derivatives(h: Vec3, dh_dx: Vec3, dh_dy: Vec3) -> Self {
        if vector::unit(h).is_none() {
            return Self::ZERO;
        }
        let [ds_x, ds_y] = jacobian::unit_vector_to_slope(h);
        let ds = |d: Vec3| {
            let d = vector::nan_to_zero(d);
            Vec2::new(ds_x.dot(d), ds_y.dot(d))
        };
        Self::saturated(ds(dh_dx), ds(dh_dy))
    }

    /// The footprint of ray differentials through the half-vector Jacobian `M` of the
    /// geometry: [`geometry::footprint`] (KHPL16 section 4.2, eq. 5). `m` from
    /// [`geometry::half_vector_jacobian`] (or its far-field / deferred forms), `dx_u`, `dx_v`
    /// the tangent-plane ray differentials ([`geometry::tangent_plane_differentials`]).
    #[inline]
    pub fn from_ray_differentials(
        m: Mat2,
        frame: &geometry::ShadingFrame,
        dx_u: Vec3,
        dx_v: Vec3,
    ) -> Self {
        geometry::footprint(m, frame, dx_u, dx_v)
    }

    /// `(dh_u, dh_v)` mapped from derivatives without NaN: a NaN entry there can only come
    /// from an infinite input (`inf * 0`, `inf - inf`), so it becomes `+inf` (saturated, its
    /// sign unknown); finite and infinite entries are kept.
    #[inline]
    fn saturated(dh_u: Vec2, dh_v: Vec2) -> Self {
        let sat = |v: Vec2| Vec2::select(v.is_nan_mask(), Vec2::splat(F::INFINITY), v);
        Self {
            dh_u: sat(dh_u),
            dh_v: sat(dh_v),
        }
    }

    /// This footprint with each NaN entry replaced by `0`: the crate's NaN policy for
    /// footprints (module docs; [`crate::contract`]), applied by the kernel stage wherever a
    /// kernel is built from a footprint (`Covariance::from_footprint`,
    /// `BoundingRect::from_footprint`, `ClampRules::footprint`). Infinite entries are kept.
    #[inline(always)]
    pub fn nan_to_zero(self) -> Self {
        Self {
            dh_u: vector::nan_to_zero2(self.dh_u),
            dh_v: vector::nan_to_zero2(self.dh_v),
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
    /// opposite normals, which have no tangential difference). A NaN entry of a difference
    /// counts as `0`; an infinite one gives an infinite entry, which the clamp rules saturate
    /// (module docs).
    pub fn from_normal_differences(dn_u: Vec3, dn_v: Vec3) -> Self {
        let half = |d: Vec3| {
            let d = vector::nan_to_zero(d);
            let len = (Vec3::new(0.0, 0.0, 2.0) + d).length().max(1e-6);
            Vec2::new(d.x, d.y) * (2.0 / len)
        };
        Self::saturated(half(dn_u), half(dn_v))
    }

    /// [`Footprint::from_normal_differences`] for world-space differences and a world-space
    /// orthonormal tangent frame `(t, b, n)`: the differences are first expressed in the frame
    /// (`(t.dn, b.dn, n.dn)`), after their NaN entries are replaced by `0` (module docs).
    pub fn from_world_normal_differences(
        t: Vec3,
        b: Vec3,
        n: Vec3,
        dn_u: Vec3,
        dn_v: Vec3,
    ) -> Self {
        let local = |d: Vec3| {
            let d = vector::nan_to_zero(d);
            Vec3::new(t.dot(d), b.dot(d), n.dot(d))
        };
        Self::from_normal_differences(local(dn_u), local(dn_v))
    }

    /// The largest distance from the centre to a vertex of the one-pixel parallelogram,
    /// `max(|dh_u + dh_v|, |dh_u - dh_v|) / 2`: the extent clamped by KHPL16 section 5.2.
    /// It bounds both half-extents of the footprint's bounding rectangle (unless the squares in the
    /// lengths underflow: vectors below about `1e-19` in `f32`, `1e-154` in `f64`, give `0`).
    #[inline]
    pub fn max_extent(self) -> F {
        0.5 * (self.dh_u + self.dh_v)
            .length()
            .max((self.dh_u - self.dh_v).length())
    }
}
