//! Rigidly moving implicit surfaces and the local quadric of a parametric surface (Tessari et
//! al. 2020, section 4.2, eq. 22-24): how any surface whose second fundamental form is known
//! feeds the implicit-surface path of [`super::implicit`].
//!
//! Units as in [`super::implicit`]: lengths `L`, times `T`, the reference time `t0` is where
//! all derivatives are taken.

use super::implicit::{LevelSetSample, Sym3};
use super::{F, Vec3};

/// A rigid motion about the reference time `t0` (section 4.2, the `M` of eq. 24): the body
/// point at `x` (at `t0`) moves with velocity `u(x) = v + omega x (x - c)`.
///
/// Composing a static level set `phi_hat` (the body at `t0`) with the inverse motion,
/// `phi(t, x) = phi_hat(M(t, x))` with `M(t, x) = c + R(t)^T (x - c - v (t - t0))` (eq. 24),
/// gives at `t = t0` (where `M = id`, `D_x M = 1`, `d_t M = -u(x)`,
/// `d_t D_x M = d_t R^T = -[omega]_x`):
/// - `grad phi = grad phi_hat`, `D^2 phi = D^2 phi_hat`;
/// - `d_t phi = -<grad phi_hat, u(x)>`;
/// - `d_t grad phi = omega x grad phi_hat - (D^2 phi_hat) u(x)`.
///
/// Only the first time derivative of the motion enters, so any rotation `R(t)` with angular
/// velocity `omega` at `t0` gives the same result.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RigidMotion {
    /// The centre of rotation `c` at `t0` (units `L`).
    pub center: Vec3,
    /// The translation velocity `v` of the centre (units `L / T`).
    pub velocity: Vec3,
    /// The angular velocity `omega` (axis times rate, radians per `T`).
    pub angular_velocity: Vec3,
}

impl RigidMotion {
    /// No motion.
    pub const STATIC: Self = Self {
        center: Vec3::ZERO,
        velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
    };

    /// A pure translation with velocity `v`.
    #[inline]
    pub const fn translation(velocity: Vec3) -> Self {
        Self {
            center: Vec3::ZERO,
            velocity,
            angular_velocity: Vec3::ZERO,
        }
    }

    /// The velocity `u(x) = v + omega x (x - c)` of the body point at `x` (units `L / T`).
    #[inline]
    pub fn point_velocity(&self, x: Vec3) -> Vec3 {
        self.velocity + self.angular_velocity.cross(x - self.center)
    }

    /// The level set sample at `x`, time `t0`, of the static level set `phi_hat` moved by this
    /// motion (eq. 24; formulas in the type docs), from `phi_hat`'s gradient and Hessian at `x`.
    /// Non-finite input gives a sample whose consumers ([`super::implicit::hit_rates`]) return
    /// zero rates.
    #[inline]
    pub fn level_set_sample(&self, x: Vec3, grad: Vec3, hess: Sym3) -> LevelSetSample {
        let u = self.point_velocity(x);
        LevelSetSample {
            grad,
            hess,
            dphi_dt: -grad.dot(u),
            dgrad_dt: self.angular_velocity.cross(grad) - hess.mul_vec3(u),
        }
    }
}

/// The local quadric of a surface at a point `P` from its normal `N`, principal curvatures
/// `k1, k2` and principal directions `e1, e2 = N x e1` (section 4.2, eq. 22-23), in implicit
/// form
///
/// `phi_hat(x) = k1 <x - P, e1>^2 / 2 + k2 <x - P, e2>^2 / 2 + <x - P, N>` (eq. 23),
///
/// whose zero set is the osculating paraboloid
/// `x(u, v) = P + u e1 + v e2 - (k1 u^2 + k2 v^2) N / 2` (eq. 22 as printed omits the
/// tangent terms `u e1 + v e2` and the normal; this is the surface eq. 23 describes). The
/// curvature sign follows eq. 23: `k > 0` bends the surface away from `N` (a sphere of radius
/// `r` with the outward normal has `k1 = k2 = 1/r`). Curvatures in `1 / L`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalQuadric {
    p: Vec3,
    n: Vec3,
    e1: Vec3,
    e2: Vec3,
    k1: F,
    k2: F,
}

impl LocalQuadric {
    /// From the point `P`, the normal `N`, a first principal direction `e1` and the principal
    /// curvatures. `N` is normalised, `e1` is made orthogonal to `N` (Gram-Schmidt) and
    /// normalised, and `e2 = N x e1`.
    ///
    /// Returns `None` if an input is non-finite, `N` or `e1` is zero, or `e1` is within `1e-3`
    /// rad of parallel to `N`. Only directions matter: both are scaled to unit size first.
    pub fn new(p: Vec3, n: Vec3, e1: Vec3, k1: F, k2: F) -> Option<Self> {
        if !(p.is_finite() && n.is_finite() && e1.is_finite() && k1.is_finite() && k2.is_finite()) {
            return None;
        }
        // Scaled by the largest component first: glam's normalisation of a tiny (or huge)
        // vector squares it out of the normal range and returns a non-unit vector or `None`
        // (found by fuzzing).
        let scaled = |v: Vec3| {
            let s = v.abs().max_element();
            (s > 0.0).then(|| v / s)
        };
        let n = scaled(n)?.try_normalize()?;
        let e1 = scaled(e1)?;
        let t = e1 - n * n.dot(e1);
        if t.length_squared() <= 1e-6 * e1.length_squared() {
            return None;
        }
        // A second Gram-Schmidt pass: one pass leaves `N . e1 ~ eps / sin(angle)` (1e-5 in
        // f32 near the 1e-3 rad limit; found by fuzzing), two leave rounding ("twice is
        // enough").
        let t = t - n * n.dot(t);
        let e1 = t.try_normalize()?;
        let e2 = n.cross(e1);
        Some(Self {
            p,
            n,
            e1,
            e2,
            k1,
            k2,
        })
    }

    /// `(P, N, e1, e2)`.
    #[inline]
    pub fn frame(&self) -> (Vec3, Vec3, Vec3, Vec3) {
        (self.p, self.n, self.e1, self.e2)
    }

    /// `(k1, k2)`.
    #[inline]
    pub fn curvatures(&self) -> (F, F) {
        (self.k1, self.k2)
    }

    /// `phi_hat(x)` (eq. 23), units `L`.
    #[inline]
    pub fn value(&self, x: Vec3) -> F {
        let d = x - self.p;
        let (a, b) = (d.dot(self.e1), d.dot(self.e2));
        0.5 * (self.k1 * a * a + self.k2 * b * b) + d.dot(self.n)
    }

    /// `grad phi_hat(x) = k1 <x - P, e1> e1 + k2 <x - P, e2> e2 + N` (dimensionless; equal to
    /// `N` at `P`).
    #[inline]
    pub fn gradient(&self, x: Vec3) -> Vec3 {
        let d = x - self.p;
        self.e1 * (self.k1 * d.dot(self.e1)) + self.e2 * (self.k2 * d.dot(self.e2)) + self.n
    }

    /// `D^2 phi_hat = k1 e1 e1^T + k2 e2 e2^T` (units `1 / L`, constant).
    #[inline]
    pub fn hessian(&self) -> Sym3 {
        Sym3::outer(self.e1).scale(self.k1) + Sym3::outer(self.e2).scale(self.k2)
    }

    /// The point `x(u, v) = P + u e1 + v e2 - (k1 u^2 + k2 v^2) N / 2` of the zero set.
    #[inline]
    pub fn point(&self, u: F, v: F) -> Vec3 {
        self.p + self.e1 * u + self.e2 * v - self.n * (0.5 * (self.k1 * u * u + self.k2 * v * v))
    }

    /// The level set sample at `x` of this quadric moved by `motion` (eq. 24): feed it with a
    /// [`super::implicit::MovingRay`] to [`super::implicit::hit_rates`].
    #[inline]
    pub fn level_set_sample(&self, x: Vec3, motion: &RigidMotion) -> LevelSetSample {
        motion.level_set_sample(x, self.gradient(x), self.hessian())
    }
}
