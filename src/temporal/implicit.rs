//! Normal derivatives on moving implicit surfaces (Tessari et al. 2020, section 4.1 and
//! Appendix A): the toolbox that turns a time-dependent level set `phi(t, x)` and a
//! time-dependent ray into the temporal derivatives of the hit distance (eq. 20) and of the
//! normal seen by the ray (eq. 21).
//!
//! Conventions: world space, any consistent length unit `L` and time unit `T` (the shutter's).
//! The surface is the zero level set `{phi(t, .) = 0}` and its normal is
//! `N = grad phi / |grad phi|` (eq. 18), so the sign of `phi` picks the side the normal points
//! to. Everything is evaluated at one reference time `t0` (e.g. the shutter centre) at the hit
//! point `x = o + s d`.
//!
//! Bad input: every function returns finite values for finite input and documents a finite
//! answer (zero rates, meaning "no temporal change") for degenerate input (zero gradient, ray
//! tangent to the surface, NaN or infinite input).

use super::super::vector;
use super::{F, Vec3};

/// A symmetric 3x3 matrix, e.g. a Hessian `D^2 phi` (units: `[phi] / L^2`) or a shape
/// operator (units `1 / L`). Stored as its six distinct entries.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sym3 {
    /// Entry `(x, x)`.
    pub xx: F,
    /// Entries `(x, y)` and `(y, x)`.
    pub xy: F,
    /// Entries `(x, z)` and `(z, x)`.
    pub xz: F,
    /// Entry `(y, y)`.
    pub yy: F,
    /// Entries `(y, z)` and `(z, y)`.
    pub yz: F,
    /// Entry `(z, z)`.
    pub zz: F,
}

impl Sym3 {
    /// The zero matrix.
    pub const ZERO: Self = Self::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    /// The identity.
    pub const IDENTITY: Self = Self::new(1.0, 0.0, 0.0, 1.0, 0.0, 1.0);

    /// From the six distinct entries (row-major upper triangle).
    #[inline]
    pub const fn new(xx: F, xy: F, xz: F, yy: F, yz: F, zz: F) -> Self {
        Self {
            xx,
            xy,
            xz,
            yy,
            yz,
            zz,
        }
    }

    /// `diag(d)`.
    #[inline]
    pub const fn from_diagonal(d: Vec3) -> Self {
        Self::new(d.x, 0.0, 0.0, d.y, 0.0, d.z)
    }

    /// The outer product `v v^T` (`v (x) v` of eq. 25).
    #[inline]
    pub fn outer(v: Vec3) -> Self {
        Self::new(
            v.x * v.x,
            v.x * v.y,
            v.x * v.z,
            v.y * v.y,
            v.y * v.z,
            v.z * v.z,
        )
    }

    /// The matrix-vector product `S w`.
    #[inline]
    pub fn mul_vec3(&self, w: Vec3) -> Vec3 {
        Vec3::new(
            self.xx * w.x + self.xy * w.y + self.xz * w.z,
            self.xy * w.x + self.yy * w.y + self.yz * w.z,
            self.xz * w.x + self.yz * w.y + self.zz * w.z,
        )
    }

    /// The bilinear form `a^T S b`.
    #[inline]
    pub fn bilinear(&self, a: Vec3, b: Vec3) -> F {
        a.dot(self.mul_vec3(b))
    }

    /// `k S`.
    #[inline]
    pub fn scale(&self, k: F) -> Self {
        Self::new(
            self.xx * k,
            self.xy * k,
            self.xz * k,
            self.yy * k,
            self.yz * k,
            self.zz * k,
        )
    }

    /// `true` if all six entries are finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.xx.is_finite()
            && self.xy.is_finite()
            && self.xz.is_finite()
            && self.yy.is_finite()
            && self.yz.is_finite()
            && self.zz.is_finite()
    }
}

impl core::ops::Add for Sym3 {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(
            self.xx + o.xx,
            self.xy + o.xy,
            self.xz + o.xz,
            self.yy + o.yy,
            self.yz + o.yz,
            self.zz + o.zz,
        )
    }
}

/// `v` if all its components are finite, else zero.
#[inline]
fn finite_or_zero(v: Vec3) -> Vec3 {
    if v.is_finite() { v } else { Vec3::ZERO }
}

/// The projection `P[v] w = (1 - v/|v| (x) v/|v|) w = w - v_hat (v_hat . w)` on the plane
/// orthogonal to `v` (Appendix A, Definition 1, eq. 25), applied to `w`. Units of `w`.
///
/// `v = 0` or non-finite `v`: the projection is undefined; returns `w` (identity). Non-finite
/// `w`: returns zero.
#[inline]
pub fn project(v: Vec3, w: Vec3) -> Vec3 {
    let n = vector::length(v);
    if !(n > 0.0 && n.is_finite()) {
        return finite_or_zero(w);
    }
    let vh = v / n;
    finite_or_zero(w - vh * vh.dot(w))
}

/// The derivative of a normalised vector (Appendix A, Remark 1, eq. 26):
/// `D(v / |v|) = P[v] Dv / |v|`, for any first-order derivative `Dv` of `v` (a time
/// derivative, a directional derivative, ...). Units: those of `Dv / v`.
///
/// `v = 0` (no direction to differentiate) or non-finite input: returns zero.
#[inline]
pub fn d_normalized(v: Vec3, dv: Vec3) -> Vec3 {
    let n = vector::length(v);
    if !(n > 0.0 && n.is_finite()) {
        return Vec3::ZERO;
    }
    let vh = v / n;
    finite_or_zero((dv - vh * vh.dot(dv)) / n)
}

/// The first- and second-order data of a time-dependent level set `phi(t, x)` at one point
/// `x` and the reference time `t0`: everything eq. 20, 21, 27-29 need.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LevelSetSample {
    /// `grad_x phi` (units `[phi] / L`); its direction is the surface normal (eq. 18).
    pub grad: Vec3,
    /// The spatial Hessian `D^2 phi` (units `[phi] / L^2`).
    pub hess: Sym3,
    /// `d phi / dt` at fixed `x` (units `[phi] / T`).
    pub dphi_dt: F,
    /// `d (grad_x phi) / dt` at fixed `x` (units `[phi] / (L T)`).
    pub dgrad_dt: Vec3,
}

impl LevelSetSample {
    /// The unit normal `N_phi = grad phi / |grad phi|` (eq. 18). Zero for a zero or
    /// non-finite gradient.
    #[inline]
    pub fn normal(&self) -> Vec3 {
        // `grad / |grad|` is not unit for a subnormal gradient (`|grad|` rounds to a few
        // significant bits there; found by fuzzing): `vector::unit` scales first.
        match vector::unit_and_length(self.grad) {
            Some((u, n)) if n.is_finite() => finite_or_zero(u),
            _ => Vec3::ZERO,
        }
    }

    /// The partial time derivative of the normal at fixed `x` (Appendix A, eq. 27):
    /// `d_t N_phi = P[grad phi] d_t grad phi / |grad phi|`. Units `1 / T`; orthogonal to
    /// `N`. Zero for a zero gradient or non-finite input.
    #[inline]
    pub fn normal_partial_t(&self) -> Vec3 {
        d_normalized(self.grad, self.dgrad_dt)
    }

    /// The spatial gradient of the normal applied to a displacement `w` (Appendix A, eq. 28):
    /// `(grad_x N_phi) w = P[grad phi] (D^2 phi) w / |grad phi|`. Units: `1 / L` times those
    /// of `w`. Zero for a zero gradient or non-finite input.
    #[inline]
    pub fn normal_gradient_apply(&self, w: Vec3) -> Vec3 {
        d_normalized(self.grad, self.hess.mul_vec3(w))
    }

    /// The shape operator (Weingarten map, Appendix A, Remark 2, eq. 29):
    /// `S = P[grad phi] (D^2 phi) P[grad phi] / |grad phi|` (units `1 / L`), symmetric, with
    /// `S N = 0`; on tangent vectors it equals `grad_x N_phi` (eq. 30: `dN/du = S dx/du`). Its
    /// nonzero eigenvalues are the principal curvatures (positive where the surface bends
    /// away from its normal, e.g. `1 / r` on a sphere with the outward normal).
    ///
    /// Zero for a zero gradient or non-finite input.
    pub fn shape_operator(&self) -> Sym3 {
        let g = vector::length(self.grad);
        if !(g > 0.0 && g.is_finite() && self.hess.is_finite()) {
            return Sym3::ZERO;
        }
        let n = self.grad / g;
        // P H P = H - n (H n)^T - (H n) n^T + (n^T H n) n n^T.
        let hn = self.hess.mul_vec3(n);
        let nhn = n.dot(hn);
        let sym = |a: F, b: F, c: F, d: F| a * b + c * d;
        let s = Sym3::new(
            self.hess.xx - 2.0 * n.x * hn.x + nhn * n.x * n.x,
            self.hess.xy - sym(n.x, hn.y, hn.x, n.y) + nhn * n.x * n.y,
            self.hess.xz - sym(n.x, hn.z, hn.x, n.z) + nhn * n.x * n.z,
            self.hess.yy - 2.0 * n.y * hn.y + nhn * n.y * n.y,
            self.hess.yz - sym(n.y, hn.z, hn.y, n.z) + nhn * n.y * n.z,
            self.hess.zz - 2.0 * n.z * hn.z + nhn * n.z * n.z,
        )
        .scale(1.0 / g);
        if s.is_finite() { s } else { Sym3::ZERO }
    }
}

/// A time-dependent ray `r(t) = (o(t), d(t))` at the reference time (section 4.1): the point
/// at parameter `s` is `o + s d`. `d` need not be unit length; `s` is then in units of `|d|`.
/// The rates are the temporal ray differentials (e.g. a moving, rotating camera).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MovingRay {
    /// Origin `o` (units `L`).
    pub origin: Vec3,
    /// Direction `d` (units `L` per unit of `s`).
    pub dir: Vec3,
    /// `d o / dt` (units `L / T`).
    pub d_origin: Vec3,
    /// `d d / dt` (units `L / T` per unit of `s`).
    pub d_dir: Vec3,
}

impl MovingRay {
    /// A ray fixed in time.
    #[inline]
    pub const fn fixed(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            dir,
            d_origin: Vec3::ZERO,
            d_dir: Vec3::ZERO,
        }
    }

    /// The point `o + s d`.
    #[inline]
    pub fn at(&self, s: F) -> Vec3 {
        self.origin + self.dir * s
    }
}

/// The temporal derivatives at a ray hit (eq. 20 and 21).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HitRates {
    /// `d s / dt`, the rate of the hit distance (eq. 20), units of `s` per `T`.
    pub ds_dt: F,
    /// `d N / dt` of the normal seen by the ray (eq. 21), units `1 / T`, orthogonal to `N`.
    pub dn_dt: Vec3,
    /// The velocity of the hit point `d x / dt = d_t o + (d_t s) d + s d_t d` (units `L / T`).
    pub dx_dt: Vec3,
}

impl HitRates {
    /// No temporal change (what degenerate input returns).
    pub const ZERO: Self = Self {
        ds_dt: 0.0,
        dn_dt: Vec3::ZERO,
        dx_dt: Vec3::ZERO,
    };
}

/// The temporal derivative of the ray-hit distance (section 4.1, eq. 20):
/// `d_t s = -(d_t phi + <grad phi, d_t o + s d_t d>) / <grad phi, d>`, from the implicit
/// function theorem on `f(t, s) = phi(t, o(t) + s d(t)) = 0` (eq. 19). `sample` is the level
/// set at the hit `x = o + s d`, `s` the hit distance at `t0`. Units of `s` per `T`.
///
/// Domain: `<grad phi, d> != 0`. A ray tangent to the surface (threshold in [`hit_rates`]), a
/// zero gradient or non-finite input returns `0` (the derivative is unbounded or undefined
/// there).
#[inline]
pub fn hit_distance_rate(sample: &LevelSetSample, ray: &MovingRay, s: F) -> F {
    hit_rates(sample, ray, s).ds_dt
}

/// The temporal derivative of the normal seen by a moving ray (section 4.1, eq. 21):
/// `d_t N = d_t N_phi + (grad_x N_phi) (d_t o + (d_t s) d + s d_t d)`, with `d_t N_phi` from
/// eq. 27, `grad_x N_phi` from eq. 28 and `d_t s` from eq. 20. Units `1 / T`; the result is
/// orthogonal to the normal.
///
/// Degenerate input as in [`hit_distance_rate`]: returns zero.
#[inline]
pub fn hit_normal_rate(sample: &LevelSetSample, ray: &MovingRay, s: F) -> Vec3 {
    hit_rates(sample, ray, s).dn_dt
}

/// Eq. 20 and 21 in one pass (see [`hit_distance_rate`], [`hit_normal_rate`]).
///
/// Degenerate input returns [`HitRates::ZERO`]: a zero or non-finite gradient, non-finite
/// ray, `s` or sample, or a ray tangent to the surface, `|<grad phi, d>| <= 8 eps |grad phi|
/// |d|` with `eps` the precision's machine epsilon (a grazing hit, where `d_t s` diverges).
pub fn hit_rates(sample: &LevelSetSample, ray: &MovingRay, s: F) -> HitRates {
    let g = sample.grad;
    let gn = vector::length(g);
    let dn = vector::length(ray.dir);
    let finite_input = s.is_finite()
        && sample.dphi_dt.is_finite()
        && sample.dgrad_dt.is_finite()
        && sample.hess.is_finite()
        && ray.origin.is_finite()
        && ray.d_origin.is_finite()
        && ray.d_dir.is_finite();
    if !(finite_input && gn > 0.0 && gn.is_finite() && dn > 0.0 && dn.is_finite()) {
        return HitRates::ZERO;
    }
    // Work with the unit gradient: eq. 20 is homogeneous of degree 0 in phi.
    let gh = g / gn;
    let denom = gh.dot(ray.dir);
    if denom.is_nan() || denom.abs() <= 8.0 * F::EPSILON * dn {
        return HitRates::ZERO;
    }
    let fixed_rate = ray.d_origin + ray.d_dir * s;
    let ds_dt = -(sample.dphi_dt / gn + gh.dot(fixed_rate)) / denom;
    let dx_dt = fixed_rate + ray.dir * ds_dt;
    let dn_dt = sample.normal_partial_t() + sample.normal_gradient_apply(dx_dt);
    let r = HitRates {
        ds_dt,
        dn_dt,
        dx_dt,
    };
    if ds_dt.is_finite() && dn_dt.is_finite() && dx_dt.is_finite() {
        r
    } else {
        HitRates::ZERO
    }
}
