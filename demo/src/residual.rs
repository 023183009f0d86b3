//! What the windowed moments leave (issue 21): for each false glint that remains, the pixel's
//! display luminance down a chain of approximations from the method to a converged reference,
//! so that each candidate cause gets its own figure:
//!
//! 1. the method (a Gaussian kernel from the window's slope moments);
//! 2. the oracle: the unfiltered lobe averaged over the window's exact normals on the tangent
//!    plane (`n` points of the pixel's Gaussian window carried by the ray differentials), the
//!    pixel centre's half vector, roughness and shading terms: the Gaussian fit removed;
//! 3. the same over the reference's own rays (the true intersections of Gaussian sub-pixel
//!    rays with the height field): the tangent-plane window removed;
//! 4. each ray's own half vector (the view and light parallax over the window);
//! 5. each ray's own roughness (the level of detail's lost slope variance);
//! 6. each ray's own Fresnel, Smith term, cosines and light distance: the reference itself,
//!    at many samples, with its standard error;
//! 7. the reference of the demonstration (512 spp), which the counts use.

use crate::camera::Camera;
use crate::image_out::{luminance, tonemap};
use crate::methods::{Family, SIGMA_PIXEL};
use crate::render::{self, GBuffer, Surface, radiance_parts};
use crate::scene::Scene;
use glam::Vec3;

/// One pixel's chain (display luminance at each step; see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct Chain {
    pub x: usize,
    pub y: usize,
    /// Step 1, the method.
    pub method: f32,
    /// Step 2, the tangent-plane oracle.
    pub oracle: f32,
    /// Step 3, the reference's rays, the pixel centre's half vector, roughness and terms.
    pub rays: f32,
    /// Step 4, plus each ray's half vector.
    pub own_h: f32,
    /// Step 5, plus each ray's roughness.
    pub own_alpha: f32,
    /// Step 6, the reference at `samples` samples, and its value at the mean radiance minus
    /// and plus two standard errors.
    pub reference: f32,
    pub reference_2se: (f32, f32),
    /// Step 7, the demonstration's reference.
    pub reference_demo: f32,
}

/// Display luminance of a linear radiance.
fn display(c: Vec3, exposure: f32) -> f32 {
    luminance(tonemap(c, exposure))
}

/// The tangent-plane oracle's mean density at pixel `i`: the unfiltered lobe (roughness
/// `alpha`) at the pixel centre's half vector, averaged over `n` points of the pixel's
/// Gaussian window on the tangent plane (a rank-1 lattice through Box-Muller, as the
/// reference's samples), each with the water's exact normal there. `None` off the water.
pub fn oracle_density(
    scene: &Scene,
    gb: &GBuffer,
    i: usize,
    family: Family,
    alpha: f32,
    n: usize,
) -> Option<f32> {
    let (s, ray) = gb.pixels[i].as_ref()?;
    if s.hit.object != 0 {
        return None;
    }
    let (dx_u, dx_v) = ray.footprint_on_plane(&s.hit);
    // The lattice generator: coprime to n, near n / phi (153 for 256).
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let mut g = ((n as f64 * 0.598).round() as usize).max(1);
    while gcd(g, n) != 1 {
        g += 1;
    }
    let mut sum = 0.0;
    for j in 0..n {
        let a = (j as f32 + 0.5) / n as f32;
        let b = ((j * g) % n) as f32 / n as f32 + 0.5 / n as f32;
        let rad = (-2.0 * a.ln()).sqrt();
        let (sn, cs) = (std::f32::consts::TAU * b).sin_cos();
        let p = s.hit.position + SIGMA_PIXEL * (rad * cs * dx_u + rad * sn * dx_v);
        let c = s.h.dot(scene.water_normal(p.x, p.z)).clamp(-1.0, 1.0);
        sum += family.d(alpha, Vec3::new((1.0 - c * c).max(0.0).sqrt(), 0.0, c));
    }
    Some(sum / n as f32)
}

/// The chain at pixel `(x, y)` of `family`, given the method's and the demonstration
/// reference's radiance there; `samples` Gaussian sub-pixel rays (independent of the
/// demonstration reference's) for steps 3-6. `None` off the water.
#[allow(clippy::too_many_arguments)]
pub fn chain(
    scene: &Scene,
    cam: &Camera,
    gb: &GBuffer,
    (x, y): (usize, usize),
    family: Family,
    (method, reference_demo): (Vec3, Vec3),
    samples: usize,
    exposure: f32,
) -> Option<Chain> {
    let i = y * gb.width + x;
    let (c, _) = gb.pixels[i].as_ref()?;
    let alpha = c.hit.alpha;
    let oracle = oracle_density(scene, gb, i, family, alpha, 4096)?;
    let shade = |d: f32| {
        let (rest, spec) = radiance_parts(scene, c, family, |_| d);
        display(rest + spec, exposure)
    };
    let mut rng = render::pixel_rng(0x005E_ED0F_C4A1, i as u64);
    let (mut d_rays, mut d_h, mut d_alpha) = (0.0f64, 0.0f64, 0.0f64);
    let (mut sum, mut sum_y2) = (Vec3::ZERO.as_dvec3(), 0.0f64);
    for _ in 0..samples {
        let (u, v) = (render::uniform_f32(&mut rng), render::uniform_f32(&mut rng));
        let r = SIGMA_PIXEL * (-2.0 * u.ln()).sqrt();
        let (sn, cs) = (std::f32::consts::TAU * v).sin_cos();
        let ray = cam.ray(x as f32 + 0.5 + r * cs, y as f32 + 0.5 + r * sn);
        let radiance = match scene.intersect(&ray.ray) {
            None => scene.sky(ray.ray.dir),
            Some(hit) => {
                let s = Surface::new(scene, cam.eye, hit);
                let local = |h: Vec3| s.frame.transpose() * h;
                d_rays += f64::from(family.d(alpha, local(c.h)));
                d_h += f64::from(family.d(alpha, local(s.h)));
                d_alpha += f64::from(family.d(s.hit.alpha, local(s.h)));
                let (rest, spec) = radiance_parts(scene, &s, family, |h| family.d(s.hit.alpha, h));
                rest + spec
            }
        };
        sum += radiance.as_dvec3();
        sum_y2 += f64::from(luminance(radiance)).powi(2);
    }
    let n = samples as f64;
    let mean = sum / n;
    let y_mean = luminance(mean.as_vec3());
    let var = (sum_y2 / n - f64::from(y_mean).powi(2)).max(0.0);
    let se = (var / (n - 1.0)).sqrt() as f32;
    let scaled = |k: f32| {
        let f = if y_mean > 0.0 {
            (1.0 + k * se / y_mean).max(0.0)
        } else {
            1.0
        };
        display(mean.as_vec3() * f, exposure)
    };
    Some(Chain {
        x,
        y,
        method: display(method, exposure),
        oracle: shade(oracle),
        rays: shade((d_rays / n) as f32),
        own_h: shade((d_h / n) as f32),
        own_alpha: shade((d_alpha / n) as f32),
        reference: display(mean.as_vec3(), exposure),
        reference_2se: (scaled(-2.0), scaled(2.0)),
        reference_demo: display(reference_demo, exposure),
    })
}
