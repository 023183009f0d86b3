//! The procedural scenes. The water: a tile of wavy water (a sum of sines, as in KHPL16
//! Fig. 2) with a few small glossy spheres floating on it, lit by one small point light low
//! over the horizon so that the water shows a glitter path. The bumpy spheres
//! ([`crate::bumpy`]): glossy spheres whose only detail is their geometry, lit from behind the
//! viewer. World space is `y`-up.

use crate::bumpy::{Bumps, BumpySphere};
use glam::{Mat3, Vec2, Vec3};

/// A ray `origin + t dir`, `dir` unit.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

/// What a ray hit.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub position: Vec3,
    /// Unit shading normal (world).
    pub normal: Vec3,
    /// Shape operator: world normal change per world displacement in the tangent plane.
    pub dn_dp: Mat3,
    /// 0 = water, 1.. = spheres.
    pub object: u32,
    pub albedo: Vec3,
    /// Isotropic roughness at the hit: the scene's `alpha`, plus on the water the slope
    /// variance of the waves the level of detail removed.
    pub alpha: f32,
}

/// One sine wave `a sin(k . (x, z) + phase)`.
#[derive(Clone, Copy, Debug)]
struct Wave {
    wavelength: f32,
    kx: f32,
    kz: f32,
    amplitude: f32,
    phase: f32,
}

/// Level of detail, as a real ocean renderer does it: a wave is faded out where its
/// wavelength covers fewer than [`LOD_PIXELS`] pixels of the (foreshortened) pixel footprint,
/// and its lost slope variance moves into the roughness (LEAN-style, KHPL16 section 5.5).
/// The geometry is then band-limited to the pixel grid, as KHPL16 assume of normals, and the
/// same for every method and for the reference.
#[derive(Clone, Copy, Debug)]
pub struct Lod {
    /// Eye position.
    pub eye: Vec3,
    /// Angle subtended by one pixel (radians).
    pub pixel_angle: f32,
}

/// Wavelength, in pixels of footprint, under which a wave starts to fade (gone at half).
/// (The GPU demo's `scene.wgsl` has the same constant.)
const LOD_PIXELS: f32 = 2.0;

/// The water's albedo.
const WATER_ALBEDO: Vec3 = Vec3::new(0.02, 0.06, 0.08);

/// The height field `y = h(x, z)` on `|x| <= half_width`, `z_far <= z <= z_near`.
pub struct Water {
    lod: Lod,
    waves: Vec<Wave>,
    bound: f32,
    slope_bound: f32,
    half_width: f32,
    z_near: f32,
    z_far: f32,
}

impl Water {
    fn new(lod: Lod) -> Self {
        // Eight octaves: wavelength 2.4 m down to 0.2 m, steepness a k = 0.16 each.
        let waves: Vec<Wave> = (0..8)
            .map(|i| {
                let fi = i as f32;
                let wavelength = 2.4 * 0.7f32.powi(i);
                let k = std::f32::consts::TAU / wavelength;
                let angle = 0.3 + 1.7 * fi;
                Wave {
                    wavelength,
                    kx: k * angle.cos(),
                    kz: k * angle.sin(),
                    amplitude: 0.16 / k / (1.0 + 0.15 * fi),
                    phase: 2.3 * fi,
                }
            })
            .collect();
        let bound = waves.iter().map(|w| w.amplitude).sum();
        let slope_bound = waves.iter().map(|w| w.amplitude * w.kx.hypot(w.kz)).sum();
        Self {
            lod,
            waves,
            bound,
            slope_bound,
            half_width: 120.0,
            z_near: 10.0,
            z_far: -250.0,
        }
    }

    /// Per-wave amplitude factors at `(x, z)`: `smoothstep` of the wavelength measured in
    /// pixel footprints, `len = pixel_angle (d^2 + H^2) / H` (distance `d`, eye height `H`).
    fn fades(&self, x: f32, z: f32) -> impl Iterator<Item = (&Wave, f32)> {
        let e = self.lod.eye;
        let height = e.y.max(0.5);
        let d2 = (x - e.x).powi(2) + (z - e.z).powi(2);
        let len = self.lod.pixel_angle * (d2 + height * height) / height;
        let inv_len = 1.0 / len;
        self.waves.iter().map(move |w| {
            let pixels = w.wavelength * inv_len;
            let t = ((pixels - 0.5 * LOD_PIXELS) / (0.5 * LOD_PIXELS)).clamp(0.0, 1.0);
            (w, t * t * (3.0 - 2.0 * t))
        })
    }

    fn height(&self, x: f32, z: f32) -> f32 {
        self.fades(x, z)
            .map(|(w, f)| f * w.amplitude * fast_sin(w.kx * x + w.kz * z + w.phase))
            .sum()
    }

    /// `(h, h_x, h_z, h_xx, h_xz, h_zz)` (the fade treated as locally constant) and the
    /// slope variance the fade removed, as an isotropic Beckmann `alpha^2` increment:
    /// each wave's slope `a k cos(.)` along `k` has per-axis `alpha^2 = (a k)^2 / 2`.
    fn derivatives(&self, x: f32, z: f32) -> ([f32; 6], f32) {
        let mut d = [0.0; 6];
        let mut lost = 0.0;
        for (w, f) in self.fades(x, z) {
            let (s, c) = (w.kx * x + w.kz * z + w.phase).sin_cos();
            let a = f * w.amplitude;
            d[0] += a * s;
            d[1] += a * w.kx * c;
            d[2] += a * w.kz * c;
            d[3] -= a * w.kx * w.kx * s;
            d[4] -= a * w.kx * w.kz * s;
            d[5] -= a * w.kz * w.kz * s;
            let slope = w.amplitude * w.kx.hypot(w.kz);
            lost += (1.0 - f * f) * slope * slope * 0.5;
        }
        (d, lost)
    }

    /// The window's gradient distribution as a mixture of Gaussians: the wave whose gradient
    /// varies most over the window (its phase `theta ~ N(theta_0, v)` over the window, its
    /// gradient's variance `(a k)^2 (1/2 (1 + cos 2 theta_0 e^{-2v}) - cos^2 theta_0 e^{-v})`)
    /// is integrated over its phase by 8-point Gauss-Hermite quadrature, the other waves by
    /// their windowed moments (the correlation between the two is neglected). Returns
    /// `(weight, mean, covariance)` per component (weights sum to 1).
    pub fn gradient_mixture(&self, x: f32, z: f32, c: [f32; 3]) -> Vec<(f32, Vec2, [f32; 3])> {
        let quad = |kx: f32, kz: f32| kx * kx * c[0] + 2.0 * kx * kz * c[1] + kz * kz * c[2];
        let var = |a: f32, kx: f32, kz: f32, theta: f32| {
            let v = quad(kx, kz);
            let ct = theta.cos();
            (a * kx.hypot(kz)).powi(2)
                * (0.5 * (1.0 + (2.0 * theta).cos() * (-2.0 * v).exp()) - ct * ct * (-v).exp())
        };
        let Some((i, a, kx, kz, theta)) = self
            .fades(x, z)
            .enumerate()
            .map(|(i, (w, f))| {
                (
                    i,
                    f * w.amplitude,
                    w.kx,
                    w.kz,
                    w.kx * x + w.kz * z + w.phase,
                )
            })
            .max_by(|p, q| var(p.1, p.2, p.3, p.4).total_cmp(&var(q.1, q.2, q.3, q.4)))
        else {
            return Vec::new();
        };
        let (mean, cov) = self.gradient_moments_except(x, z, c, Some(i));
        const X: [f32; 4] = [0.381_187, 1.157_194, 1.981_657, 2.930_637];
        const W: [f32; 4] = [0.661_147, 0.207_802, 0.017_078, 0.000_199_6];
        let sd = (2.0 * quad(kx, kz)).sqrt();
        let norm = std::f32::consts::PI.sqrt().recip();
        X.iter()
            .zip(W)
            .flat_map(|(&xj, wj)| [(xj, wj), (-xj, wj)])
            .map(|(xj, wj)| {
                let g = Vec2::new(kx, kz) * (a * (theta + sd * xj).cos());
                (wj * norm, mean + g, cov)
            })
            .collect()
    }

    /// The height gradients over the Gaussian window `c` centred on `(x, z)` (fades frozen, as
    /// [`Self::gradient_moments`]), at the nodes of an `n`-point Gauss-Hermite rule per
    /// whitened axis of `c`: `(weight, gradient)` per node, weights summing to 1.
    pub fn window_gradients(&self, x: f32, z: f32, c: [f32; 3], n: usize) -> Vec<(f32, Vec2)> {
        let waves: Vec<(f32, Vec2, f32)> = self
            .fades(x, z)
            .map(|(w, f)| (f * w.amplitude, Vec2::new(w.kx, w.kz), w.phase))
            .collect();
        let l11 = c[0].max(0.0).sqrt();
        let l21 = if l11 > 0.0 { c[1] / l11 } else { 0.0 };
        let l22 = (c[2] - l21 * l21).max(0.0).sqrt();
        let (nodes, weights) = crate::render::gauss_hermite(n);
        let mut out = Vec::with_capacity(n * n);
        for (&u, &wu) in nodes.iter().zip(&weights) {
            for (&v, &wv) in nodes.iter().zip(&weights) {
                let p = Vec2::new(x + l11 * u, z + l21 * u + l22 * v);
                let g: Vec2 = waves
                    .iter()
                    .map(|&(a, k, phase)| k * (a * (k.dot(p) + phase).cos()))
                    .sum();
                out.push((wu * wv, g));
            }
        }
        out
    }

    /// A zonotope holding every height gradient within `k` standard deviations of the
    /// Gaussian window `c` centred on `(x, z)` (fades frozen, as [`Self::gradient_moments`]):
    /// wave `i` contributes `a_i k_i cos(theta_i)` with the phase `theta_i` within `k sqrt(v_i)`
    /// of its value at the centre (`v_i = k_i^T c k_i`), so its gradient lies on a segment
    /// along `k_i` (the exact range of the cosine over that phase interval). Returns the
    /// centre and the half-generators: the gradients are `centre + sum t_i g_i`, `|t_i| <= 1`.
    pub fn gradient_support(&self, x: f32, z: f32, c: [f32; 3], k: f32) -> (Vec2, Vec<Vec2>) {
        let mut centre = Vec2::ZERO;
        let mut generators = Vec::new();
        for (w, f) in self.fades(x, z) {
            let v = w.kx * w.kx * c[0] + 2.0 * w.kx * w.kz * c[1] + w.kz * w.kz * c[2];
            let half = k * v.max(0.0).sqrt();
            let theta = w.kx * x + w.kz * z + w.phase;
            let (lo, hi) = cos_range(theta - half, theta + half);
            let dir = Vec2::new(w.kx, w.kz) * (f * w.amplitude);
            centre += dir * (0.5 * (lo + hi));
            generators.push(dir * (0.5 * (hi - lo)));
        }
        (centre, generators)
    }

    /// The moments of the height gradient `g = (h_x, h_z)` over a Gaussian window of world
    /// covariance `c = (c_xx, c_xz, c_zz)` centred on `(x, z)` (the pixel filter carried onto
    /// the water by the ray differentials), each wave's fade taken as constant over the
    /// window: with the phase `theta_i = k_i . p + phase_i` Gaussian of variance `k_i^T c k_i`,
    /// `E[cos theta_i] = cos(theta_i) exp(-v_i / 2)` and `E[cos theta_i cos theta_j] =
    /// (cos(theta_i + theta_j) exp(-v_{i+j} / 2) + cos(theta_i - theta_j) exp(-v_{i-j} / 2)) / 2`
    /// with `v_{i+-j} = (k_i +- k_j)^T c (k_i +- k_j)`. Returns `(E[g], Cov[g])`: unlike the
    /// first-order footprint, the covariance of one wave saturates at its slope variance
    /// `(a k)^2 / 2` when the window spans many of its crests.
    pub fn gradient_moments(&self, x: f32, z: f32, c: [f32; 3]) -> (Vec2, [f32; 3]) {
        self.gradient_moments_except(x, z, c, None)
    }

    /// [`Self::gradient_moments`] of every wave but `skip`.
    fn gradient_moments_except(
        &self,
        x: f32,
        z: f32,
        c: [f32; 3],
        skip: Option<usize>,
    ) -> (Vec2, [f32; 3]) {
        let quad = |kx: f32, kz: f32| kx * kx * c[0] + 2.0 * kx * kz * c[1] + kz * kz * c[2];
        let waves: Vec<(f32, f32, f32, f32)> = self
            .fades(x, z)
            .enumerate()
            .filter(|&(i, _)| Some(i) != skip)
            .map(|(_, (w, f))| (f * w.amplitude, w.kx, w.kz, w.kx * x + w.kz * z + w.phase))
            .collect();
        let mut mean = Vec2::ZERO;
        let mut second = [0.0f32; 3];
        for &(ai, kxi, kzi, ti) in &waves {
            mean += Vec2::new(kxi, kzi) * (ai * ti.cos() * (-0.5 * quad(kxi, kzi)).exp());
            for &(aj, kxj, kzj, tj) in &waves {
                let plus = (ti + tj).cos() * (-0.5 * quad(kxi + kxj, kzi + kzj)).exp();
                let minus = (ti - tj).cos() * (-0.5 * quad(kxi - kxj, kzi - kzj)).exp();
                let e = 0.5 * ai * aj * (plus + minus);
                second[0] += e * kxi * kxj;
                second[1] += e * kxi * kzj;
                second[2] += e * kzi * kzj;
            }
        }
        let cov = [
            second[0] - mean.x * mean.x,
            second[1] - mean.x * mean.y,
            second[2] - mean.y * mean.y,
        ];
        (mean, cov)
    }

    fn inside(&self, p: Vec3) -> bool {
        p.x.abs() <= self.half_width && p.z <= self.z_near && p.z >= self.z_far
    }

    /// Marches the ray through the slab `|y| <= bound` with half-Lipschitz steps, then
    /// bisects the bracketed crossing.
    fn intersect(&self, ray: &Ray, t_max: f32, alpha: f32) -> Option<Hit> {
        let d = ray.dir;
        if d.y.abs() < 1e-6 {
            return None;
        }
        let t_top = (self.bound - ray.origin.y) / d.y;
        let t_bottom = (-self.bound - ray.origin.y) / d.y;
        let (mut t, t_end) = (t_top.min(t_bottom).max(0.0), t_top.max(t_bottom).min(t_max));
        let lip = d.y.abs() + 0.5 * self.slope_bound * (d.x * d.x + d.z * d.z).sqrt();
        let f = |t: f32| {
            let p = ray.origin + t * d;
            p.y - self.height(p.x, p.z)
        };
        let mut f0 = f(t);
        if f0 < 0.0 {
            return None; // starts below the water
        }
        for _ in 0..400 {
            if t >= t_end {
                return None;
            }
            let step = (f0 / lip).max(2e-3 * t).max(1e-4);
            let t1 = (t + step).min(t_end);
            let f1 = f(t1);
            if f1 < 0.0 {
                // Bisect [t, t1].
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
                // Final secant step inside the bracket.
                return self.hit_at(ray, lo + (hi - lo) * flo / (flo - fhi), alpha);
            }
            t = t1;
            f0 = f1;
        }
        None
    }

    fn hit_at(&self, ray: &Ray, t: f32, alpha: f32) -> Option<Hit> {
        let p = ray.origin + t * ray.dir;
        if !self.inside(p) {
            return None;
        }
        let ([_, hx, hz, hxx, hxz, hzz], lost) = self.derivatives(p.x, p.z);
        // n = g / |g|, g = (-h_x, 1, -h_z); dn = (I - n n^T) dg / |g|.
        let g = Vec3::new(-hx, 1.0, -hz);
        let len = g.length();
        let n = g / len;
        let proj = (Mat3::IDENTITY - outer(n, n)) * (1.0 / len);
        let dg = Mat3::from_cols(
            Vec3::new(-hxx, 0.0, -hxz),
            Vec3::ZERO,
            Vec3::new(-hxz, 0.0, -hzz),
        );
        Some(Hit {
            t,
            position: p,
            normal: n,
            dn_dp: proj * dg,
            object: 0,
            albedo: WATER_ALBEDO,
            alpha: (alpha * alpha + lost).sqrt(),
        })
    }
}

/// The range `(min, max)` of `cos` over `[a, b]` (`a <= b`).
fn cos_range(a: f32, b: f32) -> (f32, f32) {
    use std::f32::consts::{PI, TAU};
    if b - a >= TAU {
        return (-1.0, 1.0);
    }
    let (ca, cb) = (a.cos(), b.cos());
    let (mut lo, mut hi) = (ca.min(cb), ca.max(cb));
    // A maximum at 2 pi n, a minimum at pi + 2 pi n, inside [a, b].
    if (a / TAU).ceil() * TAU <= b {
        hi = 1.0;
    }
    if ((a - PI) / TAU).ceil() * TAU + PI <= b {
        lo = -1.0;
    }
    (lo, hi)
}

/// How far `p` lies outside the zonotope `centre + sum t_i g_i` (`|t_i| <= 1`): the largest
/// excess over the slabs normal to each generator and to the axes (each slab holds the
/// zonotope; in 2D those normal to the generators intersect to it exactly), 0 inside.
pub fn zonotope_gap(centre: Vec2, generators: &[Vec2], p: Vec2) -> f32 {
    let d = p - centre;
    let normals = generators
        .iter()
        .filter(|g| g.length_squared() > 1e-20)
        .map(|g| g.perp().normalize())
        .chain([Vec2::X, Vec2::Y]);
    normals
        .map(|n| {
            let reach: f32 = generators.iter().map(|g| n.dot(*g).abs()).sum();
            n.dot(d).abs() - reach
        })
        .fold(0.0, f32::max)
}

/// `sin(x)` to about 1e-7 absolute for moderate `|x|` (the march evaluates millions of
/// sines): Cody-Waite reduction by `pi`, then the odd Taylor polynomial to `x^11` on
/// `[-pi/2, pi/2]`.
pub(crate) fn fast_sin(x: f32) -> f32 {
    const PI_HI: f32 = 3.140_625;
    const PI_LO: f32 = 9.676_536e-4;
    let k = (x * std::f32::consts::FRAC_1_PI).round();
    let r = (x - k * PI_HI) - k * PI_LO;
    let r2 = r * r;
    let p = -1.0 / 39_916_800.0;
    let p = p * r2 + 1.0 / 362_880.0;
    let p = p * r2 - 1.0 / 5040.0;
    let p = p * r2 + 1.0 / 120.0;
    let p = p * r2 - 1.0 / 6.0;
    let s = r + r * r2 * p;
    if (k as i64) & 1 == 0 { s } else { -s }
}

fn outer(a: Vec3, b: Vec3) -> Mat3 {
    Mat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// A sphere.
#[derive(Clone, Copy, Debug)]
struct Sphere {
    center: Vec3,
    radius: f32,
    albedo: Vec3,
}

impl Sphere {
    fn intersect(&self, ray: &Ray, object: u32, alpha: f32) -> Option<Hit> {
        let oc = ray.origin - self.center;
        let b = oc.dot(ray.dir);
        let c = oc.length_squared() - self.radius * self.radius;
        let disc = b * b - c;
        if disc < 0.0 {
            return None;
        }
        let sq = disc.sqrt();
        let t = if -b - sq > 1e-4 { -b - sq } else { -b + sq };
        if t <= 1e-4 {
            return None;
        }
        let p = ray.origin + t * ray.dir;
        let n = (p - self.center) / self.radius;
        Some(Hit {
            t,
            position: p,
            normal: n,
            dn_dp: (Mat3::IDENTITY - outer(n, n)) * (1.0 / self.radius),
            object,
            albedo: self.albedo,
            alpha,
        })
    }
}

/// The scene's parameters as plain numbers: what the GPU demonstration uploads to its shaders
/// (`demo/src/bin/highlights_gpu/shaders/scene.wgsl` evaluates the same surfaces from them).
#[derive(Clone, Debug)]
#[allow(dead_code)] // read by the GPU demonstration only
pub struct Params {
    pub kind: SceneKind,
    /// Per wave: `k_x`, `k_z`, amplitude, phase, wavelength (empty without water).
    pub waves: Vec<[f32; 5]>,
    /// The water's slab half-height and slope bound (the march's), half width, `z_near`,
    /// `z_far` (zeros without water).
    pub water: [f32; 5],
    pub water_albedo: Vec3,
    /// Per sphere: centre, radius, albedo; in the bumpy scene, the bumpy spheres' base
    /// spheres.
    pub spheres: Vec<(Vec3, f32, Vec3)>,
    /// Per bump wave of the bumpy scene: `k` (xyz), amplitude, phase (empty in the water
    /// scene).
    pub bumps: Vec<[f32; 5]>,
    /// The bumps' `sum a_i` (the shell's half-thickness) and the field's Lipschitz constant
    /// (zeros in the water scene).
    pub bump_bound: f32,
    pub bump_lipschitz: f32,
}

/// Which scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneKind {
    /// The wavy water with its glossy spheres (KHPL16 Fig. 2).
    Water,
    /// Glossy bumpy spheres, geometric curvature only ([`crate::bumpy`]).
    Bumpy,
}

impl SceneKind {
    /// The command-line and file name.
    pub fn slug(self) -> &'static str {
        match self {
            SceneKind::Water => "water",
            SceneKind::Bumpy => "bumpy",
        }
    }

    /// The tables' name.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Water => "the water",
            SceneKind::Bumpy => "the bumpy spheres",
        }
    }
}

/// The whole scene.
pub struct Scene {
    pub kind: SceneKind,
    /// The water (the water scene only).
    water: Option<Water>,
    spheres: Vec<Sphere>,
    /// The bumpy spheres and their bumps (the bumpy scene only).
    bumpy: Vec<BumpySphere>,
    bumps: Bumps,
    /// Point light position (world) and radiant intensity (RGB, per steradian).
    pub light_position: Vec3,
    pub light_intensity: Vec3,
    /// Constant ambient radiance (lets the diffuse term show the shapes).
    pub ambient: Vec3,
    /// Base GGX / Beckmann roughness of every surface (see [`Hit::alpha`]).
    pub alpha: f32,
    /// Normal-incidence Fresnel reflectance.
    pub f0: f32,
    /// The background's horizon and zenith radiance (see [`Scene::sky`]).
    pub sky: [Vec3; 2],
}

impl Scene {
    /// The scene as seen from `lod.eye` (the water's level of detail follows the eye).
    pub fn new(lod: Lod) -> Self {
        let sphere = |x: f32, z: f32, r: f32, albedo: [f32; 3]| Sphere {
            center: Vec3::new(x, 0.35 * r, z),
            radius: r,
            albedo: Vec3::from(albedo),
        };
        Self {
            kind: SceneKind::Water,
            water: Some(Water::new(lod)),
            bumpy: Vec::new(),
            bumps: Bumps::new(),
            spheres: vec![
                sphere(-1.6, -3.0, 0.45, [0.5, 0.08, 0.05]),
                sphere(-0.5, -5.0, 0.35, [0.6, 0.45, 0.05]),
                sphere(0.9, -3.6, 0.4, [0.05, 0.3, 0.5]),
                sphere(2.1, -6.0, 0.5, [0.3, 0.3, 0.32]),
                sphere(-2.8, -7.5, 0.55, [0.1, 0.4, 0.1]),
            ],
            light_position: Vec3::new(0.0, 9.0, -90.0),
            light_intensity: Vec3::new(1.0, 0.9, 0.75) * 6.0e3,
            ambient: Vec3::new(0.35, 0.45, 0.6),
            alpha: 0.01,
            f0: 0.04,
            sky: [Vec3::new(0.25, 0.3, 0.42), Vec3::new(0.05, 0.09, 0.2)],
        }
    }

    /// The bumpy spheres ([`crate::bumpy`]) against a dark background, under a distant point
    /// light behind and above the viewer (irradiance about 50 at the spheres), so that their
    /// glints lie on the faces the camera sees (object `1 + i`: sphere `i`). No level of
    /// detail: the bumps stay at every distance.
    pub fn bumpy() -> Self {
        Self {
            kind: SceneKind::Bumpy,
            water: None,
            spheres: Vec::new(),
            bumpy: crate::bumpy::spheres(),
            bumps: Bumps::new(),
            light_position: Vec3::new(40.0, 70.0, 90.0),
            light_intensity: Vec3::new(1.0, 0.9, 0.75) * 7.5e5,
            ambient: Vec3::new(0.35, 0.45, 0.6),
            alpha: 0.01,
            f0: 0.04,
            sky: [Vec3::new(0.03, 0.035, 0.045), Vec3::new(0.01, 0.012, 0.02)],
        }
    }

    /// The scene `kind` as seen from `lod.eye`.
    pub fn of(kind: SceneKind, lod: Lod) -> Self {
        match kind {
            SceneKind::Water => Self::new(lod),
            SceneKind::Bumpy => Self::bumpy(),
        }
    }

    /// The nearest hit along `ray`, if any.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for (i, s) in self.spheres.iter().enumerate() {
            if let Some(h) = s.intersect(ray, i as u32 + 1, self.alpha) {
                if best.is_none_or(|b| h.t < b.t) {
                    best = Some(h);
                }
            }
        }
        for (i, s) in self.bumpy.iter().enumerate() {
            let t_max = best.map_or(f32::INFINITY, |b| b.t);
            if let Some(t) = self.bumps.crossing(s, ray, t_max) {
                best = Some(self.bumps.hit_at(s, ray, t, i as u32 + 1, self.alpha));
            }
        }
        let t_max = best.map_or(f32::INFINITY, |b| b.t);
        self.water
            .as_ref()
            .and_then(|w| w.intersect(ray, t_max, self.alpha))
            .or(best)
    }

    /// The water's unit normal at `(x, z)` (the level of detail of this view; up without
    /// water).
    #[allow(dead_code)] // the false-glint investigation only
    pub fn water_normal(&self, x: f32, z: f32) -> Vec3 {
        let Some(water) = &self.water else {
            return Vec3::Y;
        };
        let ([_, hx, hz, ..], _) = water.derivatives(x, z);
        Vec3::new(-hx, 1.0, -hz).normalize()
    }

    /// How far the gradient `g` lies outside the set of gradients the water has within `k`
    /// standard deviations of the Gaussian window `c` at `hit` ([`Water::gradient_support`]),
    /// in gradient units; 0 inside; `None` on the spheres.
    pub fn gradient_gap(&self, hit: &Hit, c: [f32; 3], k: f32, g: Vec2) -> Option<f32> {
        let water = self.water.as_ref().filter(|_| hit.object == 0)?;
        let (center, generators) = water.gradient_support(hit.position.x, hit.position.z, c, k);
        Some(zonotope_gap(center, &generators, g))
    }

    /// [`Water::gradient_mixture`] at `hit`; `None` on the spheres.
    #[allow(dead_code)] // the false-glint investigation only
    pub fn gradient_mixture(&self, hit: &Hit, c: [f32; 3]) -> Option<Vec<(f32, Vec2, [f32; 3])>> {
        let water = self.water.as_ref().filter(|_| hit.object == 0)?;
        Some(water.gradient_mixture(hit.position.x, hit.position.z, c))
    }

    /// [`Water::window_gradients`] at `hit` (`n` nodes per axis); `None` off the water.
    pub fn window_gradients(&self, hit: &Hit, c: [f32; 3], n: usize) -> Option<Vec<(f32, Vec2)>> {
        let water = self.water.as_ref().filter(|_| hit.object == 0)?;
        Some(water.window_gradients(hit.position.x, hit.position.z, c, n))
    }

    /// The moments of the water's height gradient over a Gaussian window at `hit` (see
    /// [`Water::gradient_moments`]); `None` on the spheres.
    pub fn gradient_moments(&self, hit: &Hit, c: [f32; 3]) -> Option<(Vec2, [f32; 3])> {
        let water = self.water.as_ref().filter(|_| hit.object == 0)?;
        Some(water.gradient_moments(hit.position.x, hit.position.z, c))
    }

    /// Background radiance for a ray that hits nothing: a dim sky gradient from [`Self::sky`]'s
    /// horizon colour to its zenith colour.
    pub fn sky(&self, dir: Vec3) -> Vec3 {
        let k = dir.y.clamp(0.0, 1.0);
        let [horizon, zenith] = self.sky;
        horizon.lerp(zenith, k.sqrt())
    }
}

#[allow(dead_code)] // used by the GPU demonstration only
impl Scene {
    /// The parameters of the surfaces (see [`Params`]).
    pub fn params(&self) -> Params {
        let (waves, water) = match &self.water {
            Some(w) => (
                w.waves
                    .iter()
                    .map(|v| [v.kx, v.kz, v.amplitude, v.phase, v.wavelength])
                    .collect(),
                [w.bound, w.slope_bound, w.half_width, w.z_near, w.z_far],
            ),
            None => (Vec::new(), [0.0; 5]),
        };
        let bumpy = self.kind == SceneKind::Bumpy;
        Params {
            kind: self.kind,
            waves,
            water,
            water_albedo: WATER_ALBEDO,
            spheres: self
                .spheres
                .iter()
                .map(|s| (s.center, s.radius, s.albedo))
                .chain(self.bumpy.iter().map(|s| (s.center, s.radius, s.albedo)))
                .collect(),
            bumps: if bumpy {
                self.bumps
                    .waves
                    .iter()
                    .map(|w| [w.k.x, w.k.y, w.k.z, w.amplitude, w.phase])
                    .collect()
            } else {
                Vec::new()
            },
            bump_bound: if bumpy { self.bumps.bound } else { 0.0 },
            bump_lipschitz: if bumpy { self.bumps.lipschitz } else { 0.0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `E[g]` and `Cov[g]` of the height gradient over the Gaussian window `N((x, z), c)`, by
    /// an independent computation: each wave's gradient summed in f64 from the wave table
    /// (fades frozen at the centre, as [`Water::gradient_moments`] documents), integrated by
    /// the trapezoid rule over +-7 standard deviations of the whitened window (`n x n`
    /// points; spectrally accurate for this smooth, Gaussian-weighted integrand once the grid
    /// resolves the shortest wave).
    fn moments_by_quadrature(
        water: &Water,
        x: f64,
        z: f64,
        c: [f64; 3],
        n: usize,
    ) -> ([f64; 2], [f64; 3]) {
        let waves: Vec<(f64, f64, f64, f64)> = water
            .fades(x as f32, z as f32)
            .map(|(w, f)| {
                (
                    f64::from(f) * f64::from(w.amplitude),
                    f64::from(w.kx),
                    f64::from(w.kz),
                    f64::from(w.phase),
                )
            })
            .collect();
        // Cholesky c = L L^T.
        let l11 = c[0].sqrt();
        let l21 = c[1] / l11;
        let l22 = (c[2] - l21 * l21).sqrt();
        let (mut w_sum, mut m, mut s) = (0.0, [0.0f64; 2], [0.0f64; 3]);
        let step = 14.0 / (n - 1) as f64;
        for i in 0..n {
            let u = -7.0 + i as f64 * step;
            for j in 0..n {
                let v = -7.0 + j as f64 * step;
                let w = (-0.5 * (u * u + v * v)).exp();
                let (px, pz) = (x + l11 * u, z + l21 * u + l22 * v);
                let (mut gx, mut gz) = (0.0, 0.0);
                for &(a, kx, kz, phase) in &waves {
                    let c = a * (kx * px + kz * pz + phase).cos();
                    gx += c * kx;
                    gz += c * kz;
                }
                w_sum += w;
                m[0] += w * gx;
                m[1] += w * gz;
                s[0] += w * gx * gx;
                s[1] += w * gx * gz;
                s[2] += w * gz * gz;
            }
        }
        let m = [m[0] / w_sum, m[1] / w_sum];
        let cov = [
            s[0] / w_sum - m[0] * m[0],
            s[1] / w_sum - m[0] * m[1],
            s[2] / w_sum - m[1] * m[1],
        ];
        (m, cov)
    }

    fn water() -> Water {
        // Eye high above the water: no wave is faded at the points tested.
        Water::new(Lod {
            eye: Vec3::new(0.0, 2.0, 14.0),
            pixel_angle: 1e-4,
        })
    }

    /// The closed-form windowed moments (the false-glint fix's kernel) against quadrature,
    /// for a window far below the shortest wave (first-order regime), one about as wide as
    /// the short waves, and one spanning many crests (anisotropic, sheared). Tolerance:
    /// `1e-3` of the quadrature's total slope variance (trace), and `1e-3` absolute on the
    /// mean gradient (the f32 closed form accumulates 64 wave pairs).
    #[test]
    fn gradient_moments_match_quadrature() {
        let w = water();
        for (p, c, n) in [
            ((0.3, -4.0), [1e-4, 2e-5, 5e-5], 101),
            ((1.7, -9.0), [4e-3, -1e-3, 9e-3], 301),
            ((-2.1, -30.0), [2.0, 0.4, 0.3], 2001),
        ] {
            let (mean, cov) = w.gradient_moments(p.0 as f32, p.1 as f32, c.map(|v| v as f32));
            let (qm, qc) = moments_by_quadrature(&w, p.0, p.1, c, n);
            let scale = qc[0] + qc[2];
            for k in 0..3 {
                let e = (f64::from(cov[k]) - qc[k]).abs() / scale;
                assert!(
                    e < 1e-3,
                    "window {c:?}: cov[{k}] {} vs {} (rel. {e:.2e})",
                    cov[k],
                    qc[k]
                );
            }
            assert!((f64::from(mean.x) - qm[0]).abs() < 1e-3, "{mean} vs {qm:?}");
            assert!((f64::from(mean.y) - qm[1]).abs() < 1e-3, "{mean} vs {qm:?}");
        }
    }

    /// The zonotope holds every gradient of the window within `k` standard deviations: 4000
    /// points of a window spanning a few short crests, drawn within 2.5 sigma (a
    /// deterministic lattice through Box-Muller, radius capped), each at gap 0 (tolerance
    /// 1e-5 for f32 rounding); and a gradient beyond the waves' total slope lies outside.
    #[test]
    fn gradient_support_holds_the_window() {
        let w = water();
        let (x, z) = (0.4f32, -6.0f32);
        let c = [4e-3f32, 1e-3, 2e-3];
        let (centre, generators) = w.gradient_support(x, z, c, 2.5);
        let l11 = c[0].sqrt();
        let l21 = c[1] / l11;
        let l22 = (c[2] - l21 * l21).sqrt();
        let n = 4000;
        for j in 0..n {
            let a = (j as f32 + 0.5) / n as f32;
            let b = ((j * 2473) % n) as f32 / n as f32;
            let r = (-2.0 * a.ln()).sqrt().min(2.5);
            let (u, v) = (
                r * (std::f32::consts::TAU * b).cos(),
                r * (std::f32::consts::TAU * b).sin(),
            );
            let (px, pz) = (x + l11 * u, z + l21 * u + l22 * v);
            let g: Vec2 = w
                .fades(x, z)
                .map(|(wv, f)| {
                    Vec2::new(wv.kx, wv.kz)
                        * (f * wv.amplitude * (wv.kx * px + wv.kz * pz + wv.phase).cos())
                })
                .sum();
            let gap = zonotope_gap(centre, &generators, g);
            assert!(gap < 1e-5, "point {j}: gap {gap}");
        }
        let total: f32 = w.waves.iter().map(|v| v.amplitude * v.kx.hypot(v.kz)).sum();
        assert!(zonotope_gap(centre, &generators, Vec2::new(1.5 * total, 0.0)) > 0.0);
        assert_eq!(cos_range(-0.1, 0.1), ((0.1f32).cos(), 1.0));
        assert_eq!(cos_range(3.0, 3.3).0, -1.0);
    }

    /// Why the windowed moments remove the first-order footprint's false glints: over a
    /// window spanning many crests, the slope covariance saturates at the waves' total slope
    /// variance `sum (a k)^2 / 2` (within 5 %: the cross terms and the windowed mean decay as
    /// `exp(-v / 2)`), while the first-order kernel, the gradient's Jacobian (the Hessian)
    /// times the window, grows with the window without bound and reaches slopes the waves
    /// never have.
    #[test]
    fn gradient_moments_saturate_where_the_first_order_kernel_grows() {
        let w = water();
        let (x, z) = (0.9f32, -12.0f32);
        let total: f32 = w
            .waves
            .iter()
            .map(|v| 0.5 * (v.amplitude * v.kx.hypot(v.kz)).powi(2))
            .sum();
        let (d, _) = w.derivatives(x, z);
        let hessian = glam::Mat2::from_cols(Vec2::new(d[3], d[4]), Vec2::new(d[4], d[5]));
        for s2 in [4.0f32, 16.0, 64.0] {
            let (_, cov) = w.gradient_moments(x, z, [s2, 0.0, s2]);
            let trace = cov[0] + cov[2];
            assert!(
                (trace / total - 1.0).abs() < 0.05,
                "window {s2}: {trace} vs {total}"
            );
            let first_order = (hessian * hessian.transpose() * s2).to_cols_array();
            let fo_trace = first_order[0] + first_order[3];
            assert!(
                fo_trace > 10.0 * total,
                "window {s2}: first order {fo_trace} vs {total}"
            );
        }
    }
}
