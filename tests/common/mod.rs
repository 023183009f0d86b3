//! Test-side helpers shared between test files: moving test scenes with exact, independent
//! ray-surface intersections (analytic roots of quadratics), shared by `tests/implicit.rs`
//! and `tests/temporal.rs`; the roughness-matrix square root of the sampling tests
//! ([`whitening`]).
//!
//! Every scene is a static body (defined in world coordinates at the reference time
//! `t0 = 0`) moved rigidly by `x(t) = c + R(t) (y - c) + v t` with `R(t)` the exact rotation
//! by `omega t`, seen by a camera ray `o(t) = o0 + do t`, `d(t) = R_cam(t) d0` with
//! `R_cam(t)` the exact rotation by `omega_cam t`. Nothing here calls the code under test
//! except to build its inputs (`MovingRay`, `LevelSetSample`).
#![allow(dead_code)]

use filtered_ndf::f64::temporal::implicit::{LevelSetSample, MovingRay, Sym3};
use glam::{DMat3, DQuat, DVec3};

pub mod whitening;

/// Roots of `a s^2 + b s + c = 0` (real, ascending), stable form; linear if `a` ~ 0.
pub fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if a.abs() <= 1e-14 * scale {
        return if b != 0.0 { vec![-c / b] } else { vec![] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut r = if q != 0.0 {
        vec![q / a, c / q]
    } else {
        vec![0.0, 0.0]
    };
    r.sort_by(|x, y| x.partial_cmp(y).unwrap());
    r
}

/// A static body in world coordinates at `t0`: level set, its derivatives, and the exact
/// intersection of a ray `o + s d`.
pub trait Body {
    fn phi(&self, y: DVec3) -> f64;
    fn grad(&self, y: DVec3) -> DVec3;
    fn hess(&self, y: DVec3) -> DMat3;
    /// The root to follow: for closed bodies the smallest positive one, for open ones the
    /// one nearest `hint`.
    fn intersect(&self, o: DVec3, d: DVec3, hint: f64) -> Option<f64>;
}

pub fn sym3(h: DMat3) -> Sym3 {
    Sym3::new(
        h.x_axis.x, h.y_axis.x, h.z_axis.x, h.y_axis.y, h.z_axis.y, h.z_axis.z,
    )
}

/// Ellipsoid `|diag(1/a) R0^T (y - c)|^2 = 1` (a sphere when `a` is constant).
pub struct Ellipsoid {
    pub center: DVec3,
    pub axes: DVec3,
    pub orient: DMat3,
}

impl Ellipsoid {
    fn local(&self, y: DVec3) -> DVec3 {
        self.orient.transpose() * (y - self.center)
    }
}

impl Body for Ellipsoid {
    fn phi(&self, y: DVec3) -> f64 {
        let l = self.local(y) / self.axes;
        l.length_squared() - 1.0
    }
    fn grad(&self, y: DVec3) -> DVec3 {
        let l = self.local(y);
        self.orient * (2.0 * l / (self.axes * self.axes))
    }
    fn hess(&self, _y: DVec3) -> DMat3 {
        let d = DMat3::from_diagonal(2.0 / (self.axes * self.axes));
        self.orient * d * self.orient.transpose()
    }
    fn intersect(&self, o: DVec3, d: DVec3, _hint: f64) -> Option<f64> {
        let lo = self.local(o) / self.axes;
        let ld = (self.orient.transpose() * d) / self.axes;
        let r = quadratic_roots(
            ld.length_squared(),
            2.0 * lo.dot(ld),
            lo.length_squared() - 1.0,
        );
        r.into_iter().find(|&s| s > 0.0)
    }
}

/// Local quadric of eq. 23, written out independently of the library's `LocalQuadric`.
pub struct Quadric {
    pub p: DVec3,
    pub n: DVec3,
    pub e1: DVec3,
    pub e2: DVec3,
    pub k1: f64,
    pub k2: f64,
}

impl Body for Quadric {
    fn phi(&self, y: DVec3) -> f64 {
        let d = y - self.p;
        0.5 * self.k1 * d.dot(self.e1).powi(2)
            + 0.5 * self.k2 * d.dot(self.e2).powi(2)
            + d.dot(self.n)
    }
    fn grad(&self, y: DVec3) -> DVec3 {
        let d = y - self.p;
        self.k1 * d.dot(self.e1) * self.e1 + self.k2 * d.dot(self.e2) * self.e2 + self.n
    }
    fn hess(&self, _y: DVec3) -> DMat3 {
        let o1 = DMat3::from_cols(
            self.e1 * self.e1.x,
            self.e1 * self.e1.y,
            self.e1 * self.e1.z,
        );
        let o2 = DMat3::from_cols(
            self.e2 * self.e2.x,
            self.e2 * self.e2.y,
            self.e2 * self.e2.z,
        );
        o1 * self.k1 + o2 * self.k2
    }
    fn intersect(&self, o: DVec3, d: DVec3, hint: f64) -> Option<f64> {
        let q = o - self.p;
        let (al, be) = (q.dot(self.e1), d.dot(self.e1));
        let (ga, de) = (q.dot(self.e2), d.dot(self.e2));
        let (ep, ze) = (q.dot(self.n), d.dot(self.n));
        let a = 0.5 * (self.k1 * be * be + self.k2 * de * de);
        let b = self.k1 * al * be + self.k2 * ga * de + ze;
        let c = 0.5 * (self.k1 * al * al + self.k2 * ga * ga) + ep;
        quadratic_roots(a, b, c)
            .into_iter()
            .min_by(|x, y| (x - hint).abs().partial_cmp(&(y - hint).abs()).unwrap())
    }
}

/// A rigidly moving body seen by a moving camera ray.
pub struct Scene<B: Body> {
    pub body: B,
    /// Centre of rotation `c`, velocity `v`, angular velocity `omega` of the body.
    pub center: DVec3,
    pub velocity: DVec3,
    pub omega: DVec3,
    /// Camera ray at `t0`, its origin velocity and its angular velocity.
    pub o0: DVec3,
    pub d0: DVec3,
    pub d_o: DVec3,
    pub omega_cam: DVec3,
    /// For open bodies: the `t0` hit distance; the root nearest it is followed in time.
    pub s_hint: f64,
}

/// Exact hit at time `t`: distance `s`, world point, unit normal.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub s: f64,
    pub x: DVec3,
    pub n: DVec3,
}

impl<B: Body> Scene<B> {
    pub fn ray_at(&self, t: f64) -> (DVec3, DVec3) {
        let rc = DQuat::from_scaled_axis(self.omega_cam * t);
        (self.o0 + self.d_o * t, rc * self.d0)
    }

    /// The library input: the ray and its rates at `t0 = 0`.
    pub fn moving_ray(&self) -> MovingRay {
        MovingRay {
            origin: self.o0,
            dir: self.d0,
            d_origin: self.d_o,
            d_dir: self.omega_cam.cross(self.d0),
        }
    }

    /// Exact intersection at time `t` (body frame via the inverse motion, root nearest the
    /// `t0` hit for open bodies).
    pub fn hit(&self, t: f64) -> Option<Hit> {
        let (o, d) = self.ray_at(t);
        let r = DQuat::from_scaled_axis(self.omega * t);
        let rt = r.inverse();
        let ob = self.center + rt * (o - self.center - self.velocity * t);
        let db = rt * d;
        let s = self.body.intersect(ob, db, self.s_hint)?;
        let yb = ob + db * s;
        let n = (r * self.body.grad(yb)).normalize();
        Some(Hit { s, x: o + d * s, n })
    }

    /// The level set sample at the `t0` hit, by hand from the body (eq. 24 at `t0`, derived
    /// independently here: `d_t phi = -grad . u`, `d_t grad = omega x grad - H u`).
    pub fn sample_by_hand(&self, x: DVec3) -> LevelSetSample {
        let g = self.body.grad(x);
        let h = self.body.hess(x);
        let u = self.velocity + self.omega.cross(x - self.center);
        LevelSetSample {
            grad: g,
            hess: sym3(h),
            dphi_dt: -g.dot(u),
            dgrad_dt: self.omega.cross(g) - h * u,
        }
    }

    /// Central finite differences of `s(t)` and `N(t)` at `t0 = 0` with step `h`.
    pub fn fd_rates(&self, h: f64) -> Option<(f64, DVec3)> {
        let (a, b) = (self.hit(-h)?, self.hit(h)?);
        Some(((b.s - a.s) / (2.0 * h), (b.n - a.n) / (2.0 * h)))
    }
}

/// Slopes `s = -N_xy / N_z` of a unit normal in the frame `(t, b, n0)`.
pub fn slope_in_frame(n: DVec3, t: DVec3, b: DVec3, n0: DVec3) -> glam::DVec2 {
    let z = n.dot(n0);
    glam::DVec2::new(-n.dot(t) / z, -n.dot(b) / z)
}

pub use filtered_ndf::testing::rng::SplitMix64 as Rng;

/// Random directions, vectors and rotations for the scene sweeps, drawn from the crate's
/// shared seeded generator.
pub trait RngExt {
    /// A unit vector, uniform on the sphere (rejection from the cube).
    fn unit(&mut self) -> DVec3;
    /// `unit() * uniform[0, r)`.
    fn vec(&mut self, r: f64) -> DVec3;
    /// A rotation by up to 3 rad about a random axis.
    fn rotation(&mut self) -> DMat3;
    /// A view direction within `acos(0.2)` of `n`: `normalize(1.5 n + r)`, `r` unit.
    fn view_dir(&mut self, n: DVec3) -> DVec3;
}

impl RngExt for Rng {
    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
    fn vec(&mut self, r: f64) -> DVec3 {
        self.unit() * self.range(0.0, r)
    }
    fn rotation(&mut self) -> DMat3 {
        DMat3::from_quat(DQuat::from_scaled_axis(self.unit() * self.range(0.0, 3.0)))
    }
    fn view_dir(&mut self, n: DVec3) -> DVec3 {
        (1.5 * n + self.unit()).normalize()
    }
}

/// Camera motion: origin velocity, angular velocity, direction scale.
fn camera(
    rng: &mut Rng,
    x: DVec3,
    n: DVec3,
    moving_camera: bool,
) -> (DVec3, DVec3, DVec3, DVec3, f64) {
    let w = rng.view_dir(n);
    let l = rng.range(2.0, 6.0);
    let scale = rng.range(0.5, 2.0);
    let (d_o, om) = if moving_camera {
        (rng.vec(1.0), rng.vec(0.3))
    } else {
        (DVec3::ZERO, DVec3::ZERO)
    };
    (x + l * w, -w * scale, d_o, om, l / scale)
}

/// A sphere of radius in `[0.5, 2]` translating with speed up to 2, hit at a random point.
pub fn sphere_scene(rng: &mut Rng, moving_camera: bool) -> Scene<Ellipsoid> {
    let r = rng.range(0.5, 2.0);
    let c = rng.vec(3.0);
    let body = Ellipsoid {
        center: c,
        axes: DVec3::splat(r),
        orient: DMat3::IDENTITY,
    };
    let n = rng.unit();
    let x = c + r * n;
    let (o0, d0, d_o, omega_cam, s0) = camera(rng, x, n, moving_camera);
    Scene {
        body,
        center: c,
        velocity: rng.vec(2.0),
        omega: DVec3::ZERO,
        o0,
        d0,
        d_o,
        omega_cam,
        s_hint: s0,
    }
}

/// An ellipsoid with axes in `[0.3, 1.5]`, random orientation, rotating (up to 2 rad per unit
/// time about a centre near its own) and translating.
pub fn ellipsoid_scene(rng: &mut Rng, moving_camera: bool) -> Scene<Ellipsoid> {
    let axes = DVec3::new(
        rng.range(0.3, 1.5),
        rng.range(0.3, 1.5),
        rng.range(0.3, 1.5),
    );
    let c = rng.vec(3.0);
    let body = Ellipsoid {
        center: c,
        axes,
        orient: rng.rotation(),
    };
    let x = c + body.orient * (axes * rng.unit());
    let n = body.grad(x).normalize();
    let (o0, d0, d_o, omega_cam, s0) = camera(rng, x, n, moving_camera);
    Scene {
        center: c + rng.vec(0.5),
        body,
        velocity: rng.vec(1.0),
        omega: rng.vec(2.0),
        o0,
        d0,
        d_o,
        omega_cam,
        s_hint: s0,
    }
}

/// A local quadric (eq. 23) with curvatures in `[-2, 2]` (saddles included), rotating about a
/// centre up to 1 away from `P` and translating; the `t0` hit is `P`.
pub fn quadric_scene(rng: &mut Rng, moving_camera: bool) -> Scene<Quadric> {
    let p = rng.vec(3.0);
    let n = rng.unit();
    let (e1, e2) = n.any_orthonormal_pair();
    let a = rng.range(0.0, std::f64::consts::TAU);
    let (e1, e2) = (e1 * a.cos() + e2 * a.sin(), -e1 * a.sin() + e2 * a.cos());
    let body = Quadric {
        p,
        n,
        e1,
        e2,
        k1: rng.range(-2.0, 2.0),
        k2: rng.range(-2.0, 2.0),
    };
    let (o0, d0, d_o, omega_cam, s0) = camera(rng, p, n, moving_camera);
    Scene {
        body,
        center: p + rng.vec(1.0),
        velocity: rng.vec(1.0),
        omega: rng.vec(2.0),
        o0,
        d0,
        d_o,
        omega_cam,
        s_hint: s0,
    }
}
