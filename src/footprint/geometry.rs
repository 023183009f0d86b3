//! Slope-domain footprints from scene geometry, for ray tracers and offline renderers
//! (KHPL16 sections 3.1, 4.2 and 5.4; TK19 section 3.2).
//!
//! The half vector of a direct-lighting path `eye -> x -> light`, expressed in the shading
//! frame that moves with the shading point `x`, has the slope
//! `sigma(x) = -(H . s, H . t) / (H . n)` with `H = i + o` (KHPL16 eq. 3 in the crate's slope
//! convention `-h_xy / h_z`). [`half_vector_jacobian`] returns its derivative
//! `M = d sigma / dx` along the tangent plane (KHPL16 eq. 4-6), [`footprint`] carries ray
//! differentials through it (KHPL16 section 4.2) and [`footprint_projected`] gives TK19's
//! projected-disk variant.
//!
//! ## Units and layout
//! Positions and displacements are in any one length unit `L` (world space). The shape
//! operator is in `1/L`, the twist in radians per `L`, `M` in slope per `L`. `M` is stored as
//! KHPL16 eq. 4 writes it, `M[i][j] = d sigma_i / d x_j` with `i, j` over `(s, t)`, in glam's
//! column-major `Mat2`: `M.x_axis = d sigma / d x_s`, `M.y_axis = d sigma / d x_t`, so the
//! first-order change is `d sigma = M * (dx . s, dx . t)`. (KHPL16 eq. 5 writes this product
//! with a row vector, `dx M`; with the layout of its eq. 4 it means `M dx`.)
//! The crate's slope sign is opposite to KHPL16's (`h_xy / h_z`), so `M` here is KHPL16's `M`
//! negated.
//!
//! ```
//! use filtered_ndf::f32::footprint::geometry::{
//!     Endpoint, ShadingFrame, footprint, half_vector_jacobian, tangent_plane_differentials,
//!     PinholeRay,
//! };
//! use glam::{Mat2, Vec2, Vec3};
//!
//! // A unit sphere's north pole: shape operator I / R, no twist.
//! let frame = ShadingFrame { s: Vec3::X, t: Vec3::Y, n: Vec3::Z, dn: Mat2::IDENTITY, twist: Vec2::ZERO };
//! let (x, eye) = (Vec3::Z, Vec3::new(0.0, -3.0, 5.0));
//! let m = half_vector_jacobian(x, Endpoint::Point(eye), Endpoint::Direction(Vec3::new(0.0, 0.6, 0.8)), &frame);
//! let ray = PinholeRay { origin: eye, dir: x - eye, ddir_du: Vec3::X * 1e-3, ddir_dv: Vec3::Y * 1e-3 };
//! let (dx_u, dx_v) = tangent_plane_differentials(&ray, x, frame.n).unwrap();
//! let fp = footprint(m, &frame, dx_u, dx_v); // slope change per pixel
//! assert!(fp.dh_u.length() > 0.0 && fp.dh_v.length() > 0.0);
//! ```
//!
//! ## Bad input
//! Nothing here panics or returns NaN. A degenerate configuration (the shading point on the
//! eye or the light, `i + o = 0`, or a non-finite position or direction) gives the zero
//! matrix (no filtering). The footprints follow the NaN policy of footprints (the module docs
//! of [`super`]): a NaN derivative or Jacobian entry counts as `0`, an infinite one saturates.
//! A half vector at or below the shading horizon is clamped to
//! `H . n >= jacobian::HZ_MIN |H|` as in [`super::jacobian`].

use super::super::vector;
use super::Footprint;
use super::jacobian::{self, HZ_MIN};
use super::{F, Mat2, Vec2, Vec3};

/// The orthonormal shading frame at `x` and its first derivative along the surface, per unit
/// length along the frame's own tangents (KHPL16 eq. 6, `T(x)` and `T'(x)`).
///
/// The frame moves as `dn/dx_k = W[0][k] s + W[1][k] t`, `ds/dx_k = twist_k t - W[0][k] n`,
/// `dt/dx_k = -twist_k s - W[1][k] n` for `k` in `(s, t)`: `W` ([`ShadingFrame::dn`]) is the
/// shape operator (Weingarten map) of the shading normal field and `twist` the rotation rate of
/// `(s, t)` about `n`. These are the only degrees of freedom of an orthonormal frame's
/// derivative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingFrame {
    /// Unit tangent `s` (world space).
    pub s: Vec3,
    /// Unit bitangent `t` (world space), `t = n x s` for a right-handed frame.
    pub t: Vec3,
    /// Unit shading normal `n` (world space).
    pub n: Vec3,
    /// Shape operator `W` (`1/L`): column `k` is `(dn/dx_k . s, dn/dx_k . t)`, `k` in `(s, t)`
    /// (`x_axis` along `s`, `y_axis` along `t`). `I / R` for a sphere of radius `R` with an
    /// outward normal; need not be symmetric for interpolated shading normals.
    pub dn: Mat2,
    /// Twist (radians per `L`): `(ds/dx_s . t, ds/dx_t . t)`, the rotation of `(s, t)` about
    /// `n` per unit step along `s` and along `t`.
    pub twist: Vec2,
}

impl ShadingFrame {
    /// A frame on a plane (no curvature, no twist): `M` then comes from the moving directions
    /// alone.
    #[inline]
    pub fn flat(s: Vec3, t: Vec3, n: Vec3) -> Self {
        Self {
            s,
            t,
            n,
            dn: Mat2::ZERO,
            twist: Vec2::ZERO,
        }
    }

    /// From world-space derivatives of the frame along `s` and `t` (per unit length, e.g.
    /// `dndu` of a renderer rescaled to arc length): projects `dn_ds`, `dn_dt` on `(s, t)` for
    /// [`Self::dn`] and `ds_ds . t`, `ds_dt . t` for [`Self::twist`]. Components that an
    /// orthonormal frame cannot have (e.g. `dn . n`) are dropped.
    #[inline]
    pub fn from_derivatives(
        s: Vec3,
        t: Vec3,
        n: Vec3,
        [dn_ds, dn_dt]: [Vec3; 2],
        [ds_ds, ds_dt]: [Vec3; 2],
    ) -> Self {
        Self {
            s,
            t,
            n,
            dn: Mat2::from_cols(
                Vec2::new(dn_ds.dot(s), dn_ds.dot(t)),
                Vec2::new(dn_dt.dot(s), dn_dt.dot(t)),
            ),
            twist: Vec2::new(ds_ds.dot(t), ds_dt.dot(t)),
        }
    }

    /// World vector to frame coordinates `(w . s, w . t, w . n)` (`T(x) w`, KHPL16 eq. 3).
    #[inline]
    pub fn to_local(&self, w: Vec3) -> Vec3 {
        Vec3::new(w.dot(self.s), w.dot(self.t), w.dot(self.n))
    }
}

/// A path end seen from the shading point: a point (eye position, point light) or a direction
/// (directional light, orthographic or far-away eye).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Endpoint {
    /// A position in world space (`L`); the direction from `x` is `(p - x) / |p - x|`.
    Point(Vec3),
    /// A direction from the shading point towards the end (need not be normalised); constant
    /// over the surface (far field).
    Direction(Vec3),
}

impl Endpoint {
    /// Unit direction from `x` and the inverse distance (`0` for a direction); `None` if
    /// degenerate (zero or non-finite).
    #[inline]
    fn direction_from(&self, x: Vec3) -> Option<(Vec3, F)> {
        let (d, is_point) = match *self {
            Endpoint::Point(p) => (p - x, true),
            Endpoint::Direction(d) => (d, false),
        };
        // Scaled first so huge (but finite) vectors normalise without overflow.
        let (d, len) = vector::unit_and_length(d)?;
        let inv_dist = if is_point { 1.0 / len } else { 0.0 };
        Some((d, inv_dist))
    }
}

/// Unit half vector `h = (i + o) / |i + o|` in the shading frame (`T(x) h_w`, KHPL16 eq. 3;
/// normalised rather than divided by `n . h_w`). Returns `n = +z` for a degenerate
/// configuration (module docs). The slope is `slope::slope_from_sphere(h)`.
#[inline]
pub fn half_vector(x: Vec3, eye: Endpoint, light: Endpoint, frame: &ShadingFrame) -> Vec3 {
    match (eye.direction_from(x), light.direction_from(x)) {
        (Some((o, _)), Some((i, _))) => {
            let Some(h) = vector::unit(i + o) else {
                return Vec3::Z;
            };
            let local = frame.to_local(h);
            // A non-finite frame is degenerate input too (module docs): `+z`, not NaN.
            if local.is_finite() { local } else { Vec3::Z }
        }
        _ => Vec3::Z,
    }
}

/// `d sigma / dx_k` for a unit half vector `h` (world) changing at `dh` (world) along tangent
/// `k`, with the frame moving as described by `frame` (KHPL16 eq. 6, both terms).
#[inline]
fn slope_derivative(frame: &ShadingFrame, h: Vec3, dh: Vec3, k: usize) -> Vec2 {
    let a = h.dot(frame.s);
    let b = h.dot(frame.t);
    let c = h.dot(frame.n).max(HZ_MIN);
    let w = frame.dn.col(k);
    let tw = frame.twist[k];
    // T'(x) h_w: the frame rotates under the fixed vector; T(x) h_w': the vector moves.
    let da = dh.dot(frame.s) + b * tw - c * w.x;
    let db = dh.dot(frame.t) - a * tw - c * w.y;
    let dc = dh.dot(frame.n) + a * w.x + b * w.y;
    // sigma = -(a, b) / c.
    (Vec2::new(a, b) * (dc / c) - Vec2::new(da, db)) / c
}

/// The half-vector Jacobian `M = d sigma / dx` with respect to the shading point on its tangent
/// plane (KHPL16 eq. 4 and 6): `M = T(x) h_w'(x) + T'(x) h_w(x)`, exact to first order for a
/// point (or directional) eye and light, with `h_w' = (I - h h^T)(i' + o') / |i + o|` and
/// `i' = -(I - i i^T) / |l - x|` (zero for a direction), likewise `o'`.
///
/// `x` is the shading point (on the surface, `L`), `frame` its shading frame and frame
/// derivative. Output layout, units and sign in the module docs; degenerate input gives
/// `Mat2::ZERO`. Compare [`half_vector_jacobian_far_field`] (eq. 17), which drops the first
/// term.
pub fn half_vector_jacobian(x: Vec3, eye: Endpoint, light: Endpoint, frame: &ShadingFrame) -> Mat2 {
    let (Some((o, ko)), Some((i, ki))) = (eye.direction_from(x), light.direction_from(x)) else {
        return Mat2::ZERO;
    };
    let Some((h, len)) = vector::unit_and_length(i + o) else {
        return Mat2::ZERO;
    };
    let col = |k: usize| {
        let u = if k == 0 { frame.s } else { frame.t };
        let di: Vec3 = (u - i * i.dot(u)) * -ki;
        let do_: Vec3 = (u - o * o.dot(u)) * -ko;
        let dhw = di + do_;
        let dh = (dhw - h * h.dot(dhw)) / len;
        slope_derivative(frame, h, dh, k)
    };
    finite_or_zero(Mat2::from_cols(col(0), col(1)))
}

/// KHPL16 eq. 17, the far-field (deferred-shading) approximation `M ~ T'(x) h_w`: the half
/// vector `h_w` (world, any positive length) is held fixed and only the shading frame moves.
/// Exact when eye and light are directions; the error of a point eye / light falls like
/// `1 / distance` (measured in `tests/geometry.rs`). Degenerate input gives `Mat2::ZERO`.
#[inline]
pub fn half_vector_jacobian_far_field(h_w: Vec3, frame: &ShadingFrame) -> Mat2 {
    let Some(h) = vector::unit(h_w) else {
        return Mat2::ZERO;
    };
    finite_or_zero(Mat2::from_cols(
        slope_derivative(frame, h, Vec3::ZERO, 0),
        slope_derivative(frame, h, Vec3::ZERO, 1),
    ))
}

/// KHPL16 section 5.4: eq. 17 with the glossy assumption `h_w ~ n`, which reduces `M` to the
/// shape operator `frame.dn` (in the crate's slope sign). The deferred G-buffer pass uses it
/// with `n` averaged over the quad.
#[inline]
pub fn half_vector_jacobian_deferred(frame: &ShadingFrame) -> Mat2 {
    half_vector_jacobian_far_field(frame.n, frame)
}

/// The slope-domain footprint `(dh_u, dh_v) = (M dx_u, M dx_v)` (KHPL16 section 4.2, eq. 5)
/// from tangent-plane ray differentials `dx_u`, `dx_v` (world vectors, `L` per pixel, e.g.
/// from [`tangent_plane_differentials`]); their normal components are ignored. Slope per
/// pixel. NaN entries of `jac`, `dx_u`, `dx_v` and of the frame's `s`, `t` count as `0`;
/// infinite ones (or products beyond `F::MAX`) give infinite entries, which the clamp rules
/// saturate.
#[inline]
pub fn footprint(jac: Mat2, frame: &ShadingFrame, dx_u: Vec3, dx_v: Vec3) -> Footprint {
    let (s, t) = (vector::nan_to_zero(frame.s), vector::nan_to_zero(frame.t));
    let local = |d: Vec3| {
        let d = vector::nan_to_zero(d);
        Vec2::new(d.dot(s), d.dot(t))
    };
    let jac = Mat2::from_cols(
        vector::nan_to_zero2(jac.x_axis),
        vector::nan_to_zero2(jac.y_axis),
    );
    saturated(jac * local(dx_u), jac * local(dx_v))
}

/// A footprint mapped from NaN-free inputs: a NaN entry there comes from an infinite input
/// (`inf * 0`, `inf - inf`) and becomes `+inf`, which the clamp rules saturate (the policy of
/// the module docs of [`super`]).
fn saturated(dh_u: Vec2, dh_v: Vec2) -> Footprint {
    let sat = |v: Vec2| Vec2::select(v.is_nan_mask(), Vec2::splat(F::INFINITY), v);
    Footprint::from_slope_derivatives(sat(dh_u), sat(dh_v))
}

/// TK19 section 3.2: the same footprint for the projected half vector `p = h_xy` (the disk
/// domain), `dp = J(par->perp) d sigma` ([`jacobian::slope_to_projected`] at the local unit
/// half vector `h`, e.g. from [`half_vector`]). Returned in a [`Footprint`] whose vectors are
/// projected-disk (not slope) changes per pixel, the quantities TK19 feeds to its covariance
/// `sigma^2 [dp_u; dp_v]^T [dp_u; dp_v]`. NaN footprint entries count as `0`; infinite ones (or
/// products beyond `F::MAX`) give infinite entries, which the clamp rules saturate.
#[inline]
pub fn footprint_projected(slope_footprint: Footprint, h: Vec3) -> Footprint {
    let j = jacobian::slope_to_projected(h);
    let f = slope_footprint.nan_to_zero();
    saturated(j * f.dh_u, j * f.dh_v)
}

/// A pinhole camera ray and its derivatives with respect to the image coordinates `(u, v)`
/// (pixels): the input of Igehy's (1999) ray differentials.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PinholeRay {
    /// The pinhole (eye position, `L`); fixed, so the origin differentials are zero.
    pub origin: Vec3,
    /// Ray direction `d(u, v)`; need not be normalised, but the derivatives must be those of
    /// this same (e.g. unnormalised `forward + u right + v up`) direction.
    pub dir: Vec3,
    /// `dd/du`, per pixel.
    pub ddir_du: Vec3,
    /// `dd/dv`, per pixel.
    pub ddir_dv: Vec3,
}

/// Ray differentials transferred onto the tangent plane at `x` with normal `n` (Igehy 1999,
/// transfer equation with a fixed origin; KHPL16 section 4.2): with `t = (x - o) . n / (d . n)`,
/// `dx_u = t dd/du + dt/du d`, `dt/du = -t (dd/du . n) / (d . n)`, likewise for `v`. Both lie
/// in the plane (`dx . n = 0`) and are in `L` per pixel. Returns `None` if the ray is parallel
/// to the plane or any result is non-finite.
#[inline]
pub fn tangent_plane_differentials(ray: &PinholeRay, x: Vec3, n: Vec3) -> Option<(Vec3, Vec3)> {
    let dn = ray.dir.dot(n);
    let t = (x - ray.origin).dot(n) / dn;
    let transfer = |dd: Vec3| dd * t + ray.dir * (-t * dd.dot(n) / dn);
    let (du, dv) = (transfer(ray.ddir_du), transfer(ray.ddir_dv));
    (du.is_finite() && dv.is_finite()).then_some((du, dv))
}

#[inline]
fn finite_or_zero(jac: Mat2) -> Mat2 {
    if jac.is_finite() { jac } else { Mat2::ZERO }
}
