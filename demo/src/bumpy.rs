//! The third scene (issue 51): glossy bumpy spheres, the papers' core case. No texture and no
//! level of detail: the only detail is the geometry, a dense field of bumps whose curvature
//! the first-order footprint (KHPL16 section 4: ray differentials and the half-vector
//! Jacobian `M`, eq. 4-6, from the surface's shape operator) is made for. The three spheres
//! stand at 5, 10 and 20 m, so that the same bumps span about four pixels, two, and one at
//! 256x160 (then less towards the rims): from resolved curvature to sub-pixel curvature.
//!
//! Each sphere is the implicit surface `F(p) = |q| - R - sum_i a_i sin(k_i . q + phi_i) = 0`,
//! `q = p - c`: a sphere displaced by eight plane waves of the 3D position (wavelengths 14 cm
//! down to 7 cm, slope amplitude `a_i |k_i| = 0.06` each). `|grad F| >= 1 - sum a_i |k_i| =
//! 0.52 > 0`, so the surface is smooth and star-shaped about `c`, and `F` is Lipschitz with
//! `L = 1 + sum a_i |k_i|` along any ray: the march below steps by `F / L` and can never step
//! over the surface (only its minimum step can, by less than `BUMPY_MIN_STEP t`). Normal and
//! shape operator are closed forms (`grad F / |grad F|`, and `(I - n n^T) Hess F / |grad F|`),
//! ray-traced exactly on the CPU and intersected the same way by the GPU demonstration's
//! fragment shaders (`shaders/scene.wgsl`): no tessellation enters the comparison.

use crate::scene::{Hit, Ray};
use glam::{Mat3, Vec3};

/// One bump wave `a sin(k . q + phase)` of the position `q` relative to the sphere's centre.
#[derive(Clone, Copy, Debug)]
pub struct Bump {
    pub k: Vec3,
    pub amplitude: f32,
    pub phase: f32,
}

/// A bumpy sphere: its base sphere (centre, radius) and albedo; the bumps are the scene's.
#[derive(Clone, Copy, Debug)]
pub struct BumpySphere {
    pub center: Vec3,
    pub radius: f32,
    pub albedo: Vec3,
}

/// The march's minimum step, relative to the ray parameter `t` (the only step that may pass
/// a crossing: a bump clipped over less than this length of the ray, at a grazing view).
/// (The GPU demonstration's `scene.wgsl` has the same constant.)
pub const BUMPY_MIN_STEP: f32 = 4e-4;
/// Each bump wave's slope amplitude `a |k|`.
pub const SLOPE: f32 = 0.06;
/// The march's largest number of steps.
const MAX_STEPS: usize = 400;

/// The scene's bump field, shared by its spheres.
#[derive(Clone, Debug)]
pub struct Bumps {
    pub waves: Vec<Bump>,
    /// `sum a_i`: the bumps lie within `R +- bound` of the centre.
    pub bound: f32,
    /// `L = 1 + sum a_i |k_i|`, the Lipschitz constant of `F`.
    pub lipschitz: f32,
}

impl Bumps {
    /// Eight waves along Fibonacci-sphere directions, wavelengths `0.14 * 0.9^i` m, slope
    /// amplitude [`SLOPE`] each.
    pub fn new() -> Self {
        let waves: Vec<Bump> = (0..8)
            .map(|i| {
                let fi = i as f32;
                let z = 1.0 - (2.0 * fi + 1.0) / 8.0;
                let r = (1.0 - z * z).sqrt();
                let phi = 2.399_963 * fi + 0.4;
                let dir = Vec3::new(r * phi.cos(), z, r * phi.sin());
                let wavelength = 0.14 * 0.9f32.powi(i);
                let k = std::f32::consts::TAU / wavelength;
                Bump {
                    k: dir * k,
                    amplitude: SLOPE / k,
                    phase: 2.3 * fi + 0.7,
                }
            })
            .collect();
        let bound = waves.iter().map(|w| w.amplitude).sum();
        let slopes: f32 = waves.iter().map(|w| w.amplitude * w.k.length()).sum();
        Self {
            waves,
            bound,
            lipschitz: 1.0 + slopes,
        }
    }

    /// `F` at `q` (relative to the centre) for the base radius `radius`, with the march's
    /// sine ([`crate::scene::fast_sin`], the GPU's `fast_sincos`).
    pub fn field(&self, radius: f32, q: Vec3) -> f32 {
        let h: f32 = self
            .waves
            .iter()
            .map(|w| w.amplitude * crate::scene::fast_sin(w.k.dot(q) + w.phase))
            .sum();
        q.length() - radius - h
    }

    /// `grad F` and `Hess F` at `q`: `grad F = u - sum a_i cos(theta_i) k_i` and
    /// `Hess F = (I - u u^T) / |q| + sum a_i sin(theta_i) k_i k_i^T`, `u = q / |q|`,
    /// `theta_i = k_i . q + phi_i`.
    pub fn derivatives(&self, q: Vec3) -> (Vec3, Mat3) {
        let r = q.length().max(1e-12);
        let u = q / r;
        let mut grad = u;
        let mut hess = (Mat3::IDENTITY - outer(u, u)) * (1.0 / r);
        for w in &self.waves {
            let (s, c) = (w.k.dot(q) + w.phase).sin_cos();
            grad -= w.k * (w.amplitude * c);
            hess += outer(w.k, w.k) * (w.amplitude * s);
        }
        (grad, hess)
    }

    /// The unit normal and the shape operator (world normal change per world displacement
    /// in the tangent plane, `(I - n n^T) Hess F / |grad F|`) at `q`.
    pub fn normal_and_shape(&self, q: Vec3) -> (Vec3, Mat3) {
        let (grad, hess) = self.derivatives(q);
        let len = grad.length().max(1e-12);
        let n = grad / len;
        (n, (Mat3::IDENTITY - outer(n, n)) * hess * (1.0 / len))
    }

    /// The first crossing of `ray` with the bumpy sphere `s` before `t_max`: inside the shell
    /// `|q| <= R + bound`, steps of `max(F / L, BUMPY_MIN_STEP t)` until `F < 0`, then six
    /// bisections of the bracket and a secant step. `None` where the ray starts inside, misses
    /// the shell, or finds no crossing in [`MAX_STEPS`] steps.
    pub fn crossing(&self, s: &BumpySphere, ray: &Ray, t_max: f32) -> Option<f32> {
        let oc = ray.origin - s.center;
        let outer = s.radius + self.bound;
        let b = oc.dot(ray.dir);
        let disc = b * b - (oc.length_squared() - outer * outer);
        if disc < 0.0 {
            return None;
        }
        let sq = disc.sqrt();
        let (mut t, t_end) = ((-b - sq).max(0.0), (-b + sq).min(t_max));
        if t_end <= t {
            return None;
        }
        let f = |t: f32| self.field(s.radius, oc + t * ray.dir);
        let mut f0 = f(t);
        if f0 < 0.0 {
            return None;
        }
        for _ in 0..MAX_STEPS {
            if t >= t_end {
                return None;
            }
            let step = (f0 / self.lipschitz).max(BUMPY_MIN_STEP * t).max(1e-5);
            let t1 = (t + step).min(t_end);
            let f1 = f(t1);
            if f1 < 0.0 {
                let (mut lo, mut hi, mut flo, mut fhi) = (t, t1, f0, f1);
                for _ in 0..6 {
                    let mid = 0.5 * (lo + hi);
                    let fm = f(mid);
                    if fm < 0.0 {
                        (hi, fhi) = (mid, fm);
                    } else {
                        (lo, flo) = (mid, fm);
                    }
                }
                return Some(lo + (hi - lo) * flo / (flo - fhi));
            }
            t = t1;
            f0 = f1;
        }
        None
    }

    /// The shading point of `s` at distance `t` along `ray` (object code `object`).
    pub fn hit_at(&self, s: &BumpySphere, ray: &Ray, t: f32, object: u32, alpha: f32) -> Hit {
        let position = ray.origin + t * ray.dir;
        let (normal, dn_dp) = self.normal_and_shape(position - s.center);
        Hit {
            t,
            position,
            normal,
            dn_dp,
            object,
            albedo: s.albedo,
            alpha,
        }
    }
}

impl Default for Bumps {
    fn default() -> Self {
        Self::new()
    }
}

fn outer(a: Vec3, b: Vec3) -> Mat3 {
    Mat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The scene's spheres: centres at about 5, 10 and 20 m from the first camera (left,
/// right, and up in the middle of the image), dark glossy colours.
pub fn spheres() -> Vec<BumpySphere> {
    vec![
        BumpySphere {
            center: Vec3::new(-1.3, 0.9, -1.0),
            radius: 0.8,
            albedo: Vec3::new(0.016, 0.005, 0.003),
        },
        BumpySphere {
            center: Vec3::new(1.6, 0.9, -6.0),
            radius: 1.0,
            albedo: Vec3::new(0.014, 0.011, 0.003),
        },
        BumpySphere {
            center: Vec3::new(-0.6, 2.2, -16.0),
            radius: 1.2,
            albedo: Vec3::new(0.003, 0.008, 0.014),
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `F` in f64 from the wave table, independently of the f32 closed forms.
    fn field64(b: &Bumps, radius: f64, q: [f64; 3]) -> f64 {
        let len = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        let h: f64 = b
            .waves
            .iter()
            .map(|w| {
                let k = [w.k.x, w.k.y, w.k.z].map(f64::from);
                f64::from(w.amplitude)
                    * (k[0] * q[0] + k[1] * q[1] + k[2] * q[2] + f64::from(w.phase)).sin()
            })
            .sum();
        len - radius - h
    }

    /// The closed-form gradient and Hessian of `F` against central differences of the f64
    /// field (step 1e-4 m: truncation error `h^2 |F''''| / 12`, under `8 * 1e-8 a |k|^4 / 12 ~
    /// 3e-4` on the Hessian, f64 rounding `1e-16 / h^2 ~ 1e-8`), at points near three spheres.
    /// Tolerance: 1e-4 of `|grad F|` (about 1) on the gradient, and 1e-3 of the Hessian's
    /// scale `sum a_i |k_i|^2` (about 30 m^-1) on each entry: the f32 closed forms sum eight
    /// waves of that scale.
    #[test]
    fn gradient_and_hessian_match_finite_differences() {
        let b = Bumps::new();
        let scale: f32 = b
            .waves
            .iter()
            .map(|w| w.amplitude * w.k.length_squared())
            .sum();
        for (i, dir) in [
            Vec3::new(0.3, 0.8, 0.5),
            Vec3::new(-0.7, 0.1, 0.7),
            Vec3::new(0.2, -0.9, 0.4),
        ]
        .into_iter()
        .enumerate()
        {
            let radius = 0.8 + 0.2 * i as f32;
            let q = dir.normalize() * (radius + 0.003);
            let (grad, hess) = b.derivatives(q);
            let q64 = [q.x, q.y, q.z].map(f64::from);
            let h = 1e-4;
            let f = |d: [f64; 3]| {
                field64(
                    &b,
                    f64::from(radius),
                    [q64[0] + d[0], q64[1] + d[1], q64[2] + d[2]],
                )
            };
            let e = |a: usize| {
                let mut v = [0.0; 3];
                v[a] = h;
                v
            };
            let neg = |v: [f64; 3]| v.map(|x| -x);
            let add = |u: [f64; 3], v: [f64; 3]| [u[0] + v[0], u[1] + v[1], u[2] + v[2]];
            for a in 0..3 {
                let g = (f(e(a)) - f(neg(e(a)))) / (2.0 * h);
                assert!(
                    (f64::from(grad[a]) - g).abs() < 1e-4,
                    "grad[{a}] {} vs {g}",
                    grad[a]
                );
                for c in 0..3 {
                    let fd =
                        (f(add(e(a), e(c))) - f(add(e(a), neg(e(c)))) - f(add(neg(e(a)), e(c)))
                            + f(add(neg(e(a)), neg(e(c)))))
                            / (4.0 * h * h);
                    let v = f64::from(hess.col(c)[a]);
                    assert!(
                        (v - fd).abs() < 1e-3 * f64::from(scale),
                        "hess[{a}][{c}] {v} vs {fd}"
                    );
                }
            }
        }
    }

    /// The march finds the first crossing: the hit lies on the surface (`|F| < 1e-5` m in
    /// f64, the f32 position's rounding at a few metres), and the f64 field, sampled every
    /// 0.1 mm along the ray from the shell up to the hit, stays positive before it (no
    /// earlier crossing that the march stepped over); a ray aimed past the shell misses.
    #[test]
    fn march_finds_the_first_crossing() {
        let b = Bumps::new();
        let s = spheres()[0];
        let eye = Vec3::new(0.0, 1.6, 4.0);
        let mut hits = 0;
        for j in 0..40 {
            let a = j as f32 / 40.0 * std::f32::consts::TAU;
            let target =
                s.center + Vec3::new(a.cos(), a.sin(), 0.3) * (s.radius * (j % 10) as f32 / 10.0);
            let ray = Ray {
                origin: eye,
                dir: (target - eye).normalize(),
            };
            let Some(t) = b.crossing(&s, &ray, f32::INFINITY) else {
                continue;
            };
            hits += 1;
            let at = |t: f64| {
                let p = [0, 1, 2].map(|i| {
                    f64::from(ray.origin[i]) + t * f64::from(ray.dir[i]) - f64::from(s.center[i])
                });
                field64(&b, f64::from(s.radius), p)
            };
            assert!(
                at(f64::from(t)).abs() < 1e-5,
                "ray {j}: F = {}",
                at(f64::from(t))
            );
            let oc = ray.origin - s.center;
            let bb = f64::from(oc.dot(ray.dir));
            let outer = f64::from(s.radius + b.bound);
            let t0 = -bb - (bb * bb - f64::from(oc.length_squared()) + outer * outer).sqrt();
            let mut u = t0;
            while u < f64::from(t) - 1e-4 {
                assert!(at(u) > 0.0, "ray {j}: crossing at {u} before the hit {t}");
                u += 1e-4;
            }
        }
        assert!(hits >= 30, "{hits} of 40 rays hit");
        let away = Ray {
            origin: eye,
            dir: (s.center + Vec3::new(0.0, 2.0 * s.radius, 0.0) - eye).normalize(),
        };
        assert!(b.crossing(&s, &away, f32::INFINITY).is_none());
    }
}
