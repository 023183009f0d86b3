//! The renderer: a G-buffer of pixel-centre hits, GPU-style footprints from 2x2-quad
//! differences, one-sample shading per method, and the supersampled reference.

use crate::camera::{Camera, DiffRay};
use crate::image_out::Image;
use crate::methods::{self, Family, Method, ShadingPoint};
use crate::parallel;
use crate::scene::{Hit, Scene};
use filtered_ndf::f32::Footprint;
use filtered_ndf::f32::footprint::slope::slope_from_sphere;
use filtered_ndf::f32::kernel::Covariance;
use filtered_ndf::testing::rng::SplitMix64;
use glam::{Mat3, Quat, Vec2, Vec3};

/// How footprints are obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FootprintRoute {
    /// ddx/ddy of the half-vector slope between neighbouring pixels (what a GPU does).
    Quad,
    /// Analytic ray differentials and the half-vector Jacobian `M` (the offline route,
    /// KHPL16 eq. 4-6 and section 4.2).
    RayDifferentials,
    /// The false-glint fix: on the water, the kernel is the covariance of the normal's slope
    /// over the pixel's Gaussian window (the waves' exact windowed moments,
    /// [`Scene::gradient_moments`]) plus the first-order parallax of the view and light
    /// directions, centred on the window's mean normal; elsewhere as `RayDifferentials`.
    Moments,
    /// The sub-window fix of the Gaussian shape: on the water, the pixel's Gaussian window
    /// split into [`SUB_GRID`]^2 sub-windows ([`GBuffer::subwindow_mixture`]), each with its
    /// own windowed slope moments and half vector, the method's lobe averaged over them;
    /// elsewhere as `RayDifferentials`. Shaded through [`GBuffer::mixtures`] and
    /// [`shade_mixture`]; as one Gaussian per pixel ([`GBuffer::derivatives`]) it is the
    /// `Moments` route, the mixture's total moments.
    SubWindows,
    /// A cheaper fix of the Gaussian shape, from what a texture lookup of baked moments gives:
    /// on the water, the pixel's window split into 2x2 sub-footprints on its tangent plane
    /// (offsets' share [`SUB_FOOTPRINT_SPREAD`] of the window), each with its own windowed
    /// moments (mean slope and second moments) and half vector, the lobe averaged over the
    /// four ([`GBuffer::subwindow_mixture_with`], untraced); elsewhere as `RayDifferentials`.
    SubFootprints,
    /// A non-Gaussian fit from the window's fourth moment: on the water, where the slopes'
    /// kurtosis along the windowed covariance's principal axis is under 3 (the bounded,
    /// bimodal distribution of a window over about one crest), the windowed Gaussian split
    /// into two with the same mean, covariance and fourth moment there
    /// ([`GBuffer::kurtosis_split`]); elsewhere as `Moments`.
    KurtosisSplit,
}

/// The share of the pixel window's covariance carried by the offsets of the
/// [`FootprintRoute::SubFootprints`] (the rest is each sub-footprint's own).
pub const SUB_FOOTPRINT_SPREAD: f32 = 0.75;
/// Gauss-Hermite nodes per axis of the window quadrature that measures the fourth moment of
/// the slopes ([`GBuffer::kurtosis_split`]).
pub const KURTOSIS_NODES: usize = 8;

/// Gauss-Hermite nodes per axis of the sub-window grid ([`FootprintRoute::SubWindows`]).
pub const SUB_GRID: usize = 4;
/// The fraction of the pixel window's covariance carried by the sub-window offsets (the rest,
/// `1 - SUB_SPREAD`, is each sub-window's own covariance).
pub const SUB_SPREAD: f32 = 0.9;
/// Whether the sub-windows' centres are traced (the sub-pixel ray through each offset meets
/// the water) rather than placed on the pixel's tangent plane.
pub const SUB_TRACED: bool = true;

/// A pixel's filter as a mixture: `(weight, derivatives)` per component, weights summing to 1.
pub type Mixture = Vec<(f32, PixelDerivatives)>;

/// Everything shading needs at one primary hit.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    pub hit: Hit,
    /// Tangent frame: columns tangent, bitangent, normal (world).
    pub frame: Mat3,
    /// Unit directions to the eye and to the light, and the half vector (world).
    pub wo: Vec3,
    pub wi: Vec3,
    pub h: Vec3,
    /// Squared distance to the light.
    pub dist2: f32,
}

impl Surface {
    pub fn new(scene: &Scene, eye: Vec3, hit: Hit) -> Self {
        let wo = (eye - hit.position).normalize();
        let to_light = scene.light_position - hit.position;
        let wi = to_light.normalize();
        Self {
            hit,
            frame: tangent_frame(hit.normal),
            wo,
            wi,
            h: (wi + wo).normalize_or(hit.normal),
            dist2: to_light.length_squared(),
        }
    }

    /// A world vector in this surface's tangent frame.
    fn local(&self, v: Vec3) -> Vec3 {
        self.frame.transpose() * v
    }

    /// Slope `-h_xy / h_z` of a world half vector `h_other` found at a surface with normal
    /// `n_other`, carried to this surface by the rotation taking `n_other` to this normal.
    fn slope_of(&self, h_other: Vec3, n_other: Vec3) -> Vec2 {
        let carried = Quat::from_rotation_arc(n_other, self.hit.normal) * h_other;
        slope_from_sphere(self.local(carried))
    }
}

/// An orthonormal frame around `n` (Duff et al. 2017), columns `(t, b, n)`.
fn tangent_frame(n: Vec3) -> Mat3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    Mat3::from_cols(t, bt, n)
}

/// Outgoing radiance at `s` with the microfacet density `d` (per steradian, evaluated at the
/// local half vector by the caller) and the Smith term of `family` at the base roughness.
#[allow(dead_code)] // the demos shade through `radiance_parts`; the GPU shaders mirror this
pub fn radiance(scene: &Scene, s: &Surface, family: Family, d: impl FnOnce(Vec3) -> f32) -> Vec3 {
    let (rest, specular) = radiance_parts(scene, s, family, d);
    rest + specular
}

/// [`radiance`] in two parts: everything but the point light's specular reflection (ambient
/// and diffuse), and that specular reflection alone (the only part the filters change).
pub fn radiance_parts(
    scene: &Scene,
    s: &Surface,
    family: Family,
    d: impl FnOnce(Vec3) -> f32,
) -> (Vec3, Vec3) {
    let (wi, wo, h) = (s.local(s.wi), s.local(s.wo), s.local(s.h));
    let albedo = s.hit.albedo;
    let ambient = albedo * scene.ambient;
    let cos_i = wi.z;
    if cos_i <= 0.0 {
        return (ambient, Vec3::ZERO);
    }
    let irradiance = scene.light_intensity * (cos_i / s.dist2);
    let cos_o = wo.z.max(1e-4);
    let fresnel = scene.f0 + (1.0 - scene.f0) * (1.0 - wi.dot(h).clamp(0.0, 1.0)).powi(5);
    let spec = fresnel * d(h) * family.g2(s.hit.alpha, wi, wo, h) / (4.0 * cos_i * cos_o);
    (
        ambient + irradiance * albedo * std::f32::consts::FRAC_1_PI,
        irradiance * spec,
    )
}

/// The pixel-centre hits of one frame.
pub struct GBuffer {
    pub width: usize,
    pub height: usize,
    pub eye: Vec3,
    pub pixels: Vec<Option<(Surface, DiffRay)>>,
    /// Background radiance of the pixels that miss.
    pub sky: Vec<Vec3>,
}

pub fn gbuffer(scene: &Scene, cam: &Camera, width: usize, height: usize) -> GBuffer {
    let px = parallel::rows(height, None, |y| {
        (0..width)
            .map(|x| {
                let r = cam.ray(x as f32 + 0.5, y as f32 + 0.5);
                let hit = scene.intersect(&r.ray);
                (
                    hit.map(|h| (Surface::new(scene, cam.eye, h), r)),
                    scene.sky(r.ray.dir),
                )
            })
            .collect()
    });
    let (pixels, sky) = px.into_iter().unzip();
    GBuffer {
        width,
        height,
        eye: cam.eye,
        pixels,
        sky,
    }
}

/// See [`GBuffer::partner`].
const DISCONTINUITY: f32 = 3.0;

/// Per-pixel filtering inputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelDerivatives {
    pub footprint: Footprint,
    pub dn_dx: Vec3,
    pub dn_dy: Vec3,
    /// The rotation (tangent frame) taking the kernel's mean normal to the shading normal:
    /// the half-vector filters evaluate their lobe at `mean_shift * h` (identity but on the
    /// `Moments` route).
    pub mean_shift: Quat,
    /// On the `Moments` route, a support clamp that the false-glint investigation measures
    /// (`glints.rs`; the demo's methods do not use it): how far (in units of the roughness
    /// `alpha`) the gradient whose normal reflects the light to the eye lies outside a bound
    /// of the gradients the water has within [`SUPPORT_SIGMAS`] of the pixel's window
    /// ([`Scene::gradient_gap`]), less the half vector's own change over the window
    /// (parallax); 0 inside, and on the other routes.
    pub support_gap: f32,
}

/// The window, in standard deviations of the pixel filter, that the support clamp covers.
pub const SUPPORT_SIGMAS: f32 = 2.5;
/// Beyond this support gap (in `alpha`) the support clamp answers 0: no normal of the window
/// comes within 4 alpha of reflecting the light (a Beckmann lobe is down by `exp(-16)`
/// there), which a Gaussian kernel, with its unbounded support, cannot know.
pub const SUPPORT_GAP_ALPHAS: f32 = 4.0;

impl GBuffer {
    fn at(&self, x: usize, y: usize) -> Option<&Surface> {
        self.pixels[y * self.width + x].as_ref().map(|(s, _)| s)
    }

    /// The neighbour a 2x2 quad differences against along one axis (`coord ^ 1`), or the
    /// opposite neighbour when the quad partner is off-image or on another object. Returns
    /// the neighbour and the sign of the step (+1 if it is the next pixel).
    ///
    /// A neighbour also counts as another surface when it lies across a depth discontinuity
    /// (a wave crest hiding the water behind it): its distance from this hit is more than
    /// [`DISCONTINUITY`] times the step the ray differentials predict on the tangent plane.
    fn partner(&self, x: usize, y: usize, horizontal: bool) -> Option<(&Surface, f32)> {
        let (c, ray) = self.pixels[y * self.width + x].as_ref()?;
        let (dx_u, dx_v) = ray.footprint_on_plane(&c.hit);
        let predicted = if horizontal { dx_u } else { dx_v }.length();
        let coord = if horizontal { x } else { y };
        let quad = coord ^ 1;
        let other = if quad > coord {
            coord.checked_sub(1)
        } else {
            Some(coord + 1)
        };
        let limit = if horizontal { self.width } else { self.height };
        [Some(quad), other]
            .into_iter()
            .flatten()
            .filter(|&k| k < limit)
            .find_map(|k| {
                let (nx, ny) = if horizontal { (k, y) } else { (x, k) };
                let s = self.at(nx, ny)?;
                let step = s.hit.position.distance(c.hit.position);
                let continuous = step <= DISCONTINUITY * predicted;
                let sign = if k > coord { 1.0 } else { -1.0 };
                (s.hit.object == c.hit.object && continuous).then_some((s, sign))
            })
    }

    /// GPU-style derivatives: `ddx`/`ddy` of the half-vector slope (in this pixel's tangent
    /// frame) and of the world normal, from the quad neighbours.
    pub fn quad_derivatives(&self, x: usize, y: usize) -> PixelDerivatives {
        let Some(c) = self.at(x, y) else {
            return PixelDerivatives::default();
        };
        let s0 = c.slope_of(c.h, c.hit.normal);
        let diff = |horizontal: bool| match self.partner(x, y, horizontal) {
            Some((n, sign)) => (
                (c.slope_of(n.h, n.hit.normal) - s0) * sign,
                (n.hit.normal - c.hit.normal) * sign,
            ),
            None => (Vec2::ZERO, Vec3::ZERO),
        };
        let (dh_u, dn_dx) = diff(true);
        let (dh_v, dn_dy) = diff(false);
        PixelDerivatives {
            footprint: Footprint::from_slope_derivatives(dh_u, dh_v),
            dn_dx,
            dn_dy,
            mean_shift: Quat::IDENTITY,
            support_gap: 0.0,
        }
    }

    /// Derivatives through the analytic route (ray differentials + half-vector Jacobian).
    pub fn analytic_derivatives(&self, x: usize, y: usize) -> PixelDerivatives {
        let quad = self.quad_derivatives(x, y);
        let Some((s, ray)) = self.pixels[y * self.width + x].as_ref() else {
            return quad;
        };
        let (dx_u, dx_v) = ray.footprint_on_plane(&s.hit);
        let input = methods::AnalyticInput {
            position: s.hit.position,
            eye: self.eye,
            light: s.hit.position + s.wi * s.dist2.sqrt(),
            frame: [s.frame.x_axis, s.frame.y_axis, s.frame.z_axis],
            dn_dt: s.hit.dn_dp * s.frame.x_axis,
            dn_db: s.hit.dn_dp * s.frame.y_axis,
            dx_u,
            dx_v,
        };
        PixelDerivatives {
            footprint: methods::footprint_from_ray_differentials(&input),
            ..quad
        }
    }

    /// The `Moments` route (see [`FootprintRoute::Moments`]).
    pub fn moment_derivatives(&self, scene: &Scene, x: usize, y: usize) -> PixelDerivatives {
        let rays = self.analytic_derivatives(x, y);
        let Some((s, ray)) = self.pixels[y * self.width + x].as_ref() else {
            return rays;
        };
        let (dx_u, dx_v) = ray.footprint_on_plane(&s.hit);
        let window = Self::window(dx_u, dx_v);
        let Some((mean, cov)) = scene.gradient_moments(&s.hit, window) else {
            return rays;
        };
        let from = self.derivatives_of_moments(s, (dx_u, dx_v), rays, mean, cov);
        // The support test: the gradient g* whose normal is the half vector, at the pixel
        // centre and at the window's 2.5-sigma points (the parallax margin).
        let light = s.hit.position + s.wi * s.dist2.sqrt();
        let g_star = |p: Vec3| {
            let h = ((self.eye - p).normalize() + (light - p).normalize()).normalize();
            Vec2::new(-h.x, -h.z) / h.y.max(1e-3)
        };
        let g0 = g_star(s.hit.position);
        let k = SUPPORT_SIGMAS * methods::SIGMA_PIXEL;
        let parallax = [dx_u, -dx_u, dx_v, -dx_v]
            .iter()
            .map(|&d| (g_star(s.hit.position + k * d) - g0).length())
            .fold(0.0, f32::max);
        let gap = scene
            .gradient_gap(&s.hit, window, SUPPORT_SIGMAS, g0)
            .unwrap_or(0.0);
        PixelDerivatives {
            support_gap: ((gap - parallax) / s.hit.alpha).max(0.0),
            ..from
        }
    }

    /// The pixel's Gaussian window on the water, `(dx_u, dx_v)` scaled by the pixel filter,
    /// as a world covariance `(c_xx, c_xz, c_zz)`.
    fn window(dx_u: Vec3, dx_v: Vec3) -> [f32; 3] {
        let sig2 = methods::SIGMA_PIXEL * methods::SIGMA_PIXEL;
        [
            sig2 * (dx_u.x * dx_u.x + dx_v.x * dx_v.x),
            sig2 * (dx_u.x * dx_u.z + dx_v.x * dx_v.z),
            sig2 * (dx_u.z * dx_u.z + dx_v.z * dx_v.z),
        ]
    }

    /// The [`FootprintRoute::SubWindows`] mixture at pixel `(x, y)`. The pixel's Gaussian
    /// window `N(p, C)` on the tangent plane is the mixture over offsets `m ~ N(0, b C)` of
    /// sub-windows `N(p + m, (1 - b) C)` (`b =` [`SUB_SPREAD`]); the offsets are integrated by
    /// a [`SUB_GRID`]-point Gauss-Hermite rule per whitened axis of `C`. Each sub-window gets
    /// the closed-form windowed moments of the waves ([`Scene::gradient_moments`]) over its
    /// own window and centre, the parallax of its own smaller window, and its own half vector
    /// (the eye and light seen from its centre, folded into `mean_shift`: the lobe is read at
    /// `mean_shift * h` for the pixel centre's `h`). The mixture's total mean and covariance
    /// are the whole window's (exactly, up to the rule); what it adds is the shape: a
    /// distribution of slopes bounded where each sub-window sees part of one crest. Off the
    /// water, one component: the `RayDifferentials` route.
    pub fn subwindow_mixture(&self, scene: &Scene, x: usize, y: usize) -> Mixture {
        self.subwindow_mixture_with(scene, (x, y), (SUB_GRID, SUB_SPREAD), SUB_TRACED)
    }

    /// [`Self::subwindow_mixture`] with a `grid`-point rule per axis and the offsets' share
    /// `spread` of the window's covariance (the investigation's variants).
    pub fn subwindow_mixture_with(
        &self,
        scene: &Scene,
        (x, y): (usize, usize),
        (grid, spread): (usize, f32),
        traced: bool,
    ) -> Mixture {
        let rays = self.analytic_derivatives(x, y);
        let Some((s, ray)) = self.pixels[y * self.width + x].as_ref() else {
            return vec![(1.0, rays)];
        };
        if s.hit.object != 0 {
            return vec![(1.0, rays)];
        }
        let (dx_u, dx_v) = ray.footprint_on_plane(&s.hit);
        let (own, spread) = ((1.0 - spread).max(0.0).sqrt(), spread.sqrt());
        let sub = (own * dx_u, own * dx_v);
        let window = Self::window(sub.0, sub.1);
        let light = s.hit.position + s.wi * s.dist2.sqrt();
        let h_local = s.local(s.h);
        let (nodes, weights) = gauss_hermite(grid);
        let mut out = Vec::with_capacity(grid * grid);
        for (&zu, &wu) in nodes.iter().zip(&weights) {
            for (&zv, &wv) in nodes.iter().zip(&weights) {
                let offset = methods::SIGMA_PIXEL * spread * (zu * dx_u + zv * dx_v);
                // The sub-window's centre: on the tangent plane, or where the sub-pixel ray
                // through the offset meets the water (its own tangent plane's window).
                let traced_hit = traced
                    .then(|| {
                        let k = methods::SIGMA_PIXEL * spread;
                        let dir =
                            (ray.ray.dir + k * (zu * ray.d_dir_dx + zv * ray.d_dir_dy)).normalize();
                        let sub_ray = DiffRay {
                            ray: crate::scene::Ray { dir, ..ray.ray },
                            ..*ray
                        };
                        let hit = scene.intersect(&sub_ray.ray)?;
                        (hit.object == 0).then(|| {
                            let (du, dv) = sub_ray.footprint_on_plane(&hit);
                            (hit, Self::window(own * du, own * dv))
                        })
                    })
                    .flatten();
                let (hit, window) = traced_hit.unwrap_or((
                    Hit {
                        position: s.hit.position + offset,
                        ..s.hit
                    },
                    window,
                ));
                let centre = hit.position;
                let Some((mean, cov)) = scene.gradient_moments(&hit, window) else {
                    return vec![(1.0, rays)];
                };
                let d = self.derivatives_of_moments(s, sub, rays, mean, cov);
                let h_k = ((self.eye - centre).normalize() + (light - centre).normalize())
                    .normalize_or(s.h);
                let to_own_h = Quat::from_rotation_arc(h_local, s.local(h_k));
                out.push((
                    wu * wv,
                    PixelDerivatives {
                        mean_shift: d.mean_shift * to_own_h,
                        ..d
                    },
                ));
            }
        }
        out
    }

    /// Per pixel, the filter of `route` as a mixture: the [`Self::subwindow_mixture`] on
    /// the `SubWindows` route, one component of [`Self::derivatives`] on the others.
    pub fn mixtures(&self, scene: &Scene, route: FootprintRoute) -> Vec<Mixture> {
        match route {
            FootprintRoute::SubWindows => parallel::rows(self.height, None, |y| {
                (0..self.width)
                    .map(|x| self.subwindow_mixture(scene, x, y))
                    .collect()
            }),
            FootprintRoute::SubFootprints => parallel::rows(self.height, None, |y| {
                (0..self.width)
                    .map(|x| {
                        self.subwindow_mixture_with(scene, (x, y), (2, SUB_FOOTPRINT_SPREAD), false)
                    })
                    .collect()
            }),
            FootprintRoute::KurtosisSplit => parallel::rows(self.height, None, |y| {
                (0..self.width)
                    .map(|x| self.kurtosis_split(scene, x, y))
                    .collect()
            }),
            _ => self
                .derivatives(scene, route)
                .into_iter()
                .map(|d| vec![(1.0, d)])
                .collect(),
        }
    }

    /// The [`FootprintRoute::KurtosisSplit`] mixture at pixel `(x, y)`. The window's height
    /// gradients `g` have mean `mu` and covariance `C` in closed form
    /// ([`Scene::gradient_moments`]); along `C`'s principal axis `e` the fourth central moment
    /// `m4 = E[(e . (g - mu))^4]` comes from a [`KURTOSIS_NODES`]^2-point Gauss-Hermite
    /// quadrature of the window ([`Scene::window_gradients`]). A Gaussian has `m4 = 3 m2^2`;
    /// a window over about one crest has less (its slopes are bounded, piled at the ends of
    /// their range). There the Gaussian is replaced by the two-component mixture
    /// `1/2 N(mu +- delta e, C - delta^2 e e^T)`, which keeps `mu` and `C` and has the
    /// window's `m4`: `m4 = 3 m2^2 - 2 delta^4`, so `delta^4 = (3 m2^2 - m4) / 2` (capped at
    /// `delta^2 <= 0.95 m2`, where the components would degenerate). Each component becomes a
    /// kernel as the `Moments` route's (its own centre, the window's parallax). Elsewhere,
    /// and off the water, the `Moments` route.
    pub fn kurtosis_split(&self, scene: &Scene, x: usize, y: usize) -> Mixture {
        let single = vec![(1.0, self.moment_derivatives(scene, x, y))];
        let rays = self.analytic_derivatives(x, y);
        let Some((s, ray)) = self.pixels[y * self.width + x].as_ref() else {
            return single;
        };
        let (dx_u, dx_v) = ray.footprint_on_plane(&s.hit);
        let window = Self::window(dx_u, dx_v);
        let (Some((mean, cov)), Some(points)) = (
            scene.gradient_moments(&s.hit, window),
            scene.window_gradients(&s.hit, window, KURTOSIS_NODES),
        ) else {
            return single;
        };
        let c = Covariance::new(cov[0], cov[1], cov[2]);
        let (l1, l2) = c.eigenvalues();
        let m2 = l1.max(l2);
        if m2 <= 1e-12 {
            return single;
        }
        let e = if cov[1].abs() > 1e-12 * m2 {
            Vec2::new(m2 - cov[2], cov[1]).normalize_or(Vec2::X)
        } else if cov[0] >= cov[2] {
            Vec2::X
        } else {
            Vec2::Y
        };
        let m4: f32 = points
            .iter()
            .map(|&(w, g)| w * e.dot(g - mean).powi(4))
            .sum();
        let deficit = 3.0 * m2 * m2 - m4;
        if deficit <= 0.0 {
            return single;
        }
        let delta2 = (0.5 * deficit).sqrt().min(0.95 * m2);
        let delta = delta2.sqrt();
        let own = [
            cov[0] - delta2 * e.x * e.x,
            cov[1] - delta2 * e.x * e.y,
            cov[2] - delta2 * e.y * e.y,
        ];
        [1.0f32, -1.0]
            .into_iter()
            .map(|side| {
                let d = self.derivatives_of_moments(
                    s,
                    (dx_u, dx_v),
                    rays,
                    mean + side * delta * e,
                    own,
                );
                (0.5, d)
            })
            .collect()
    }

    /// The windowed-mixture experiment of `glints.rs` ([`Scene::gradient_mixture`]): per
    /// component its weight and its derivatives (as the `Moments` route's); empty off the
    /// water.
    #[allow(dead_code)] // the false-glint investigation only
    pub fn mixture_derivatives(
        &self,
        scene: &Scene,
        x: usize,
        y: usize,
    ) -> Vec<(f32, PixelDerivatives)> {
        let rays = self.analytic_derivatives(x, y);
        let Some((s, ray)) = self.pixels[y * self.width + x].as_ref() else {
            return Vec::new();
        };
        let (dx_u, dx_v) = ray.footprint_on_plane(&s.hit);
        scene
            .gradient_mixture(&s.hit, Self::window(dx_u, dx_v))
            .unwrap_or_default()
            .into_iter()
            .map(|(w, mean, cov)| {
                (
                    w,
                    self.derivatives_of_moments(s, (dx_u, dx_v), rays, mean, cov),
                )
            })
            .collect()
    }

    /// The derivatives of a Gaussian gradient distribution `N(mean, cov)` over the window:
    /// its kernel in this pixel's slope domain plus the parallax, its mean as the lobe's
    /// centre.
    fn derivatives_of_moments(
        &self,
        s: &Surface,
        (dx_u, dx_v): (Vec3, Vec3),
        rays: PixelDerivatives,
        mean: Vec2,
        cov: [f32; 3],
    ) -> PixelDerivatives {
        // The parallax: the ray-differential footprint of a flat surface (zero shape operator).
        let parallax = methods::footprint_from_ray_differentials(&methods::AnalyticInput {
            position: s.hit.position,
            eye: self.eye,
            light: s.hit.position + s.wi * s.dist2.sqrt(),
            frame: [s.frame.x_axis, s.frame.y_axis, s.frame.z_axis],
            dn_dt: Vec3::ZERO,
            dn_db: Vec3::ZERO,
            dx_u,
            dx_v,
        });
        // Height gradient (h_x, h_z) -> slope of the normal in this tangent frame: the normal
        // is (-h_x, 1, -h_z) / L, so d(slope) = (t . e, b . e) / L per unit gradient change.
        let (t, b) = (s.frame.x_axis, s.frame.y_axis);
        let len = 1.0 / s.hit.normal.y.max(1e-3);
        let j = glam::Mat2::from_cols(Vec2::new(t.x, b.x), Vec2::new(t.z, b.z)) / len;
        let g = glam::Mat2::from_cols(Vec2::new(cov[0], cov[1]), Vec2::new(cov[1], cov[2]));
        let k = j * g * j.transpose();
        let total = parallax.covariance(methods::SIGMA_PIXEL)
            + Covariance::new(k.x_axis.x, 0.5 * (k.y_axis.x + k.x_axis.y), k.y_axis.y);
        let mean_normal = Vec3::new(-mean.x, 1.0, -mean.y).normalize();
        PixelDerivatives {
            footprint: footprint_of(total.sanitized(), methods::SIGMA_PIXEL),
            mean_shift: Quat::from_rotation_arc(s.local(mean_normal), Vec3::Z),
            ..rays
        }
    }

    /// Per pixel: whether the quad route differences it with its own 2x2-quad partner on
    /// both axes (`coord ^ 1`: same object, no depth discontinuity), where a GPU's fine
    /// derivatives difference the same two pixels; pixels that see the sky count too (no
    /// derivatives). Elsewhere the quad route takes the opposite neighbour or none.
    #[allow(dead_code)] // used by the GPU demonstration only
    pub fn quad_interior(&self) -> Vec<bool> {
        let own = |coord: usize| if coord & 1 == 0 { 1.0 } else { -1.0 };
        (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .map(|(x, y)| {
                self.at(x, y).is_none()
                    || (self.partner(x, y, true).is_some_and(|(_, s)| s == own(x))
                        && self.partner(x, y, false).is_some_and(|(_, s)| s == own(y)))
            })
            .collect()
    }

    pub fn derivatives(&self, scene: &Scene, route: FootprintRoute) -> Vec<PixelDerivatives> {
        parallel::rows(self.height, None, |y| {
            (0..self.width)
                .map(|x| match route {
                    FootprintRoute::Quad => self.quad_derivatives(x, y),
                    FootprintRoute::RayDifferentials => self.analytic_derivatives(x, y),
                    FootprintRoute::Moments
                    | FootprintRoute::SubWindows
                    | FootprintRoute::SubFootprints
                    | FootprintRoute::KurtosisSplit => self.moment_derivatives(scene, x, y),
                })
                .collect()
        })
    }
}

/// A footprint whose Gaussian kernel at `sigma` is `k`: its eigenvectors scaled by the square
/// roots of its eigenvalues over `sigma`.
pub fn footprint_of(k: Covariance, sigma: f32) -> Footprint {
    let (l1, l2) = k.eigenvalues();
    let (l1, l2) = (l1.max(l2), l1.min(l2));
    let e1 = if k.s12.abs() > 1e-12 * (l1.abs() + 1e-30) {
        Vec2::new(l1 - k.s22, k.s12).normalize_or(Vec2::X)
    } else if k.s11 >= k.s22 {
        Vec2::X
    } else {
        Vec2::Y
    };
    Footprint::from_slope_derivatives(
        e1 * (l1.max(0.0).sqrt() / sigma),
        e1.perp() * (l2.max(0.0).sqrt() / sigma),
    )
}

/// One shading sample per pixel with `method`.
pub fn shade(scene: &Scene, gb: &GBuffer, derivs: &[PixelDerivatives], method: Method) -> Image {
    shade_frame(scene, gb, derivs, method).total
}

/// A shaded frame and its specular term alone (the point light's specular reflection; the
/// rest, ambient, diffuse and sky, is the same for every method).
pub struct Frame {
    pub total: Image,
    pub specular: Image,
}

/// [`shade`], with the specular term kept apart.
pub fn shade_frame(
    scene: &Scene,
    gb: &GBuffer,
    derivs: &[PixelDerivatives],
    method: Method,
) -> Frame {
    shade_with(scene, gb, method.family(), |i, h, alpha| {
        component_d(method, derivs[i], h, alpha)
    })
}

/// The method's density at the pixel's half vector `h` with one set of derivatives `dv`:
/// its footprint, and its `mean_shift` applied to `h` where the method uses a footprint.
fn component_d(method: Method, dv: PixelDerivatives, h: Vec3, alpha: f32) -> f32 {
    let h = if method.uses_footprint() {
        dv.mean_shift * h
    } else {
        h
    };
    methods::filtered_d(
        method,
        &ShadingPoint {
            h,
            alpha,
            footprint: dv.footprint,
            dn_dx: dv.dn_dx,
            dn_dy: dv.dn_dy,
        },
    )
}

/// [`shade_frame`] with a mixture per pixel ([`GBuffer::mixtures`]): the method's density
/// is the weighted sum of its density over the components (each its own footprint and
/// `mean_shift`), the shading terms those of the pixel centre.
pub fn shade_mixture(scene: &Scene, gb: &GBuffer, mixtures: &[Mixture], method: Method) -> Frame {
    shade_with(scene, gb, method.family(), |i, h, alpha| {
        mixtures[i]
            .iter()
            .map(|&(w, dv)| w * component_d(method, dv, h, alpha))
            .sum()
    })
}

/// The `n`-point Gauss-Hermite rule for the standard normal (probabilists'): nodes and
/// weights summing to 1, exact for polynomials of degree `2 n - 1`; `n >= 1` (0 reads as 1).
/// The nodes are the roots of the Hermite polynomial `He_n` (`He_{k+1} = x He_k - k
/// He_{k-1}`), bracketed on a grid of step 1e-3 over `|x| <= 2 sqrt(n) + 2` (which holds
/// them all) and bisected in f64; the weights are `n! / (n^2 He_{n-1}(x_i)^2)`.
pub fn gauss_hermite(n: usize) -> (Vec<f32>, Vec<f32>) {
    let n = n.max(1);
    // (He_n(x), He_{n-1}(x)).
    let he = |x: f64| {
        let (mut prev, mut cur) = (1.0f64, x);
        if n == 1 {
            return (cur, prev);
        }
        for k in 1..n {
            (prev, cur) = (cur, x * cur - k as f64 * prev);
        }
        (cur, prev)
    };
    let reach = 2.0 * (n as f64).sqrt() + 2.0;
    let steps = (2.0 * reach / 1e-3) as usize;
    let mut nodes = Vec::with_capacity(n);
    let mut a = -reach;
    let mut fa = he(a).0;
    for i in 1..=steps {
        let b = -reach + i as f64 * 1e-3;
        let fb = he(b).0;
        if fa == 0.0 || fa * fb < 0.0 {
            let (mut lo, mut hi, mut flo) = (a, b, fa);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let fm = he(mid).0;
                if flo * fm <= 0.0 {
                    hi = mid;
                } else {
                    (lo, flo) = (mid, fm);
                }
            }
            nodes.push(0.5 * (lo + hi));
        }
        (a, fa) = (b, fb);
    }
    let factorial: f64 = (1..=n).map(|k| k as f64).product();
    let weights: Vec<f32> = nodes
        .iter()
        .map(|&x| {
            let p = he(x).1;
            (factorial / ((n * n) as f64 * p * p)) as f32
        })
        .collect();
    (nodes.into_iter().map(|x| x as f32).collect(), weights)
}

/// One shading sample per pixel with the density `d(pixel index, local h, alpha)`.
pub fn shade_with(
    scene: &Scene,
    gb: &GBuffer,
    family: Family,
    d: impl Fn(usize, Vec3, f32) -> f32 + Sync + Send,
) -> Frame {
    let data: Vec<(Vec3, Vec3)> = parallel::rows(gb.height, None, |y| {
        (0..gb.width)
            .map(|x| {
                let i = y * gb.width + x;
                match &gb.pixels[i] {
                    None => (gb.sky[i], Vec3::ZERO),
                    Some((s, _)) => {
                        let (rest, spec) =
                            radiance_parts(scene, s, family, |h| d(i, h, s.hit.alpha));
                        (rest + spec, spec)
                    }
                }
            })
            .collect()
    });
    let (total, specular): (Vec<Vec3>, Vec<Vec3>) = data.into_iter().unzip();
    Frame {
        total: Image::new(gb.width, gb.height, total),
        specular: Image::new(gb.width, gb.height, specular),
    }
}

/// The supersampled references of one frame: for each family, the average over the first
/// half of the samples and over all of them (nested, so the convergence check is free).
pub struct Reference {
    pub half: [Image; 2],
    pub full: [Image; 2],
    /// The specular term alone, all samples.
    pub specular: [Image; 2],
}

impl Reference {
    pub fn full(&self, family: Family) -> &Image {
        &self.full[family as usize]
    }
    pub fn half(&self, family: Family) -> &Image {
        &self.half[family as usize]
    }
    pub fn specular(&self, family: Family) -> &Image {
        &self.specular[family as usize]
    }
}

/// The seed offset of the references of four times the samples that measure a reference's
/// own error ([`crate::metrics::reference_error`]): `seed ^ SEED_4N` draws other streams per
/// pixel, independent of `seed`'s.
pub const SEED_4N: u64 = 0x4A4A_5EED;

/// Renders the reference with `spp` sub-pixel samples drawn from the same Gaussian pixel
/// filter (sigma = 0.5 pixel) the footprint kernels assume, unfiltered NDFs. Each half of the
/// samples is a randomly shifted rank-1 lattice (stratified for any count, unbiased thanks to
/// the per-pixel random shift) mapped to the Gaussian by Box-Muller.
pub fn reference(
    scene: &Scene,
    cam: &Camera,
    width: usize,
    height: usize,
    spp: usize,
    seed: u64,
    progress: Option<&str>,
) -> Reference {
    reference_with(
        scene,
        cam,
        (width, height),
        spp,
        seed,
        progress,
        methods::SIGMA_PIXEL,
    )
}

/// [`reference`] with the pixel filter's standard deviation `sigma` (in pixels); `sigma <= 0`
/// draws the samples uniformly over the pixel's square instead (a box pixel filter).
pub fn reference_with(
    scene: &Scene,
    cam: &Camera,
    (width, height): (usize, usize),
    spp: usize,
    seed: u64,
    progress: Option<&str>,
    sigma: f32,
) -> Reference {
    let n = (spp / 2).max(1);
    let lattice = Lattice::new(n);
    let families = [Family::Beckmann, Family::Ggx];
    let px: Vec<[Vec3; 6]> = parallel::rows(height, progress, |y| {
        (0..width)
            .map(|x| {
                let mut rng = pixel_rng(seed, (y * width + x) as u64);
                let mut sums = [[Vec3::ZERO; 2]; 2];
                let mut spec = [Vec3::ZERO; 2];
                for sum in &mut sums {
                    let shift = (uniform_f32(&mut rng), uniform_f32(&mut rng));
                    for j in 0..n {
                        let (ox, oy) = if sigma > 0.0 {
                            lattice.gaussian(j, shift, sigma)
                        } else {
                            lattice.uniform(j, shift)
                        };
                        let r = cam.ray(x as f32 + 0.5 + ox, y as f32 + 0.5 + oy);
                        let hit = scene
                            .intersect(&r.ray)
                            .map(|h| Surface::new(scene, cam.eye, h));
                        for (f, family) in families.iter().enumerate() {
                            sum[f] += match &hit {
                                None => scene.sky(r.ray.dir),
                                Some(s) => {
                                    let (rest, sp) = radiance_parts(scene, s, *family, |h| {
                                        family.d(s.hit.alpha, h)
                                    });
                                    spec[f] += sp;
                                    rest + sp
                                }
                            };
                        }
                    }
                }
                let n = n as f32;
                let [a, b] = sums;
                [
                    a[0] / n,
                    a[1] / n,
                    (a[0] + b[0]) / (2.0 * n),
                    (a[1] + b[1]) / (2.0 * n),
                    spec[0] / (2.0 * n),
                    spec[1] / (2.0 * n),
                ]
            })
            .collect()
    });
    let img = |k: usize| Image::new(width, height, px.iter().map(|p| p[k]).collect());
    Reference {
        half: [img(0), img(1)],
        full: [img(2), img(3)],
        specular: [img(4), img(5)],
    }
}

/// How many samples a reference draws per pixel.
#[derive(Clone, Debug)]
pub enum Samples {
    /// Rounds of [`ROUND`] samples (each round the rank-1 lattice under its own random
    /// shift: independent randomised quasi-Monte Carlo replicates of the pixel's mean), at
    /// least `min` samples, until the standard error of the pixel's display luminance (the
    /// spread of the rounds' display luminances over the square root of their number) is at
    /// most `target`, or `max` samples are drawn. Stopping on the estimate biases the mean by
    /// about one standard error at most, where the target is met.
    Adaptive { min: usize, max: usize, target: f32 },
    /// Exactly this many samples at each pixel (rounded up to whole rounds): the counts of an
    /// adaptive reference times four, for its error.
    Counts(Vec<usize>),
    /// This many samples at every pixel (rounded up to whole rounds).
    Each(usize),
}

/// The samples per round of an adaptive reference ([`Samples::Adaptive`]).
pub const ROUND: usize = 128;

/// One pixel's mean of `K` radiance sums under `samples` (`index`: the pixel's index, for
/// [`Samples::Counts`]), drawn by `sample(offset)` at sub-pixel offsets from the pixel
/// centre (the Gaussian pixel filter of standard deviation `sigma` pixels, Box-Muller over
/// the shifted lattice), shifts from `rng`. The stopping rule reads component 0 as the
/// pixel's radiance. Returns the means and the samples drawn.
pub fn sample_pixel<const K: usize>(
    samples: &Samples,
    index: usize,
    rng: &mut SplitMix64,
    (sigma, exposure): (f32, f32),
    mut sample: impl FnMut((f32, f32)) -> [Vec3; K],
) -> ([Vec3; K], usize) {
    let lattice = Lattice::new(ROUND);
    let (min_rounds, max_rounds, target) = match samples {
        Samples::Adaptive { min, max, target } => (
            min.div_ceil(ROUND).max(2),
            max.div_ceil(ROUND).max(2),
            *target,
        ),
        Samples::Counts(c) => {
            let r = c[index].div_ceil(ROUND).max(1);
            (r, r, f32::INFINITY)
        }
        Samples::Each(n) => {
            let r = n.div_ceil(ROUND).max(1);
            (r, r, f32::INFINITY)
        }
    };
    let mut sums = [Vec3::ZERO; K];
    let mut display: Vec<f32> = Vec::new();
    for round in 0..max_rounds {
        let shift = (uniform_f32(rng), uniform_f32(rng));
        let mut part = [Vec3::ZERO; K];
        for j in 0..ROUND {
            let v = sample(lattice.gaussian(j, shift, sigma));
            for (p, x) in part.iter_mut().zip(v) {
                *p += x;
            }
        }
        for (s, p) in sums.iter_mut().zip(part) {
            *s += p;
        }
        display.push(crate::image_out::luminance(crate::image_out::tonemap(
            part[0] / ROUND as f32,
            exposure,
        )));
        let r = round + 1;
        if r >= min_rounds {
            let mean = display.iter().sum::<f32>() / r as f32;
            let var = display.iter().map(|y| (y - mean).powi(2)).sum::<f32>() / (r - 1) as f32;
            if (var / r as f32).sqrt() <= target {
                break;
            }
        }
    }
    let n = display.len() * ROUND;
    (sums.map(|s| s / n as f32), n)
}

/// A rank-1 lattice of `n` points `(j / n, j g / n)`, `g` coprime to `n` near `n / phi`.
struct Lattice {
    n: usize,
    g: usize,
}

impl Lattice {
    fn new(n: usize) -> Self {
        let gcd = |mut a: usize, mut b: usize| {
            while b != 0 {
                (a, b) = (b, a % b);
            }
            a
        };
        let mut g = ((n as f64 * 0.618_034).round() as usize).max(1);
        while gcd(g, n) != 1 {
            g += 1;
        }
        Self { n, g }
    }

    /// Point `j` shifted by `shift` (mod 1), in `[0, 1)^2`.
    fn point(&self, j: usize, shift: (f32, f32)) -> (f32, f32) {
        let u = ((j as f32 / self.n as f32) + shift.0).fract();
        let v = (((j * self.g) % self.n) as f32 / self.n as f32 + shift.1).fract();
        (u, v)
    }

    /// Point `j` as an offset from the pixel centre, uniform over the pixel (a box filter).
    fn uniform(&self, j: usize, shift: (f32, f32)) -> (f32, f32) {
        let (u, v) = self.point(j, shift);
        (u - 0.5, v - 0.5)
    }

    /// Point `j` shifted by `shift` (mod 1), mapped to a 2D normal deviate of std `sigma`.
    fn gaussian(&self, j: usize, shift: (f32, f32), sigma: f32) -> (f32, f32) {
        let (u, v) = self.point(j, shift);
        let r = sigma * (-2.0 * (1.0 - u).max(1e-12).ln()).sqrt();
        let (s, c) = (std::f32::consts::TAU * v).sin_cos();
        (r * c, r * s)
    }
}

/// The crate's seeded SplitMix64, one stream per pixel.
pub fn pixel_rng(seed: u64, stream: u64) -> SplitMix64 {
    let mut r = SplitMix64(seed ^ stream.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    r.next_u64();
    r
}

/// Uniform in `(0, 1]` as `f32` (24 random bits).
pub fn uniform_f32(r: &mut SplitMix64) -> f32 {
    ((r.next_u64() >> 40) as f32 + 1.0) / (1u64 << 24) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Lod;

    /// The Gauss-Hermite rules against the standard normal's moments `E[z^(2j)] = (2j - 1)!!`
    /// (0 for odd degrees), which an `n`-point rule integrates exactly up to degree `2 n - 1`,
    /// with `n` nodes each. The f32 nodes and weights are summed in f64; their rounding (6e-8
    /// relative, times the degree, at most 15) moves the sum by under 1e-5 of the scale
    /// `sum_i w_i |z_i|^degree`, the tolerance (odd degrees cancel to 0 from terms of that
    /// scale).
    #[test]
    fn gauss_hermite_rules_are_exact_to_their_degree() {
        let double_factorial = [1.0f64, 1.0, 3.0, 15.0, 105.0, 945.0, 10395.0, 135135.0];
        for n in 1..=8 {
            let (z, w) = gauss_hermite(n);
            assert_eq!((z.len(), w.len()), (n, n));
            for degree in 0..2 * n {
                let term = |(z, w): (&f32, &f32)| f64::from(*w) * f64::from(*z).powi(degree as i32);
                let m: f64 = z.iter().zip(&w).map(term).sum();
                let scale: f64 = z.iter().zip(&w).map(|p| term(p).abs()).sum();
                let exact = if degree % 2 == 1 {
                    0.0
                } else {
                    double_factorial[degree / 2]
                };
                assert!(
                    (m - exact).abs() <= 1e-5 * scale.max(1.0),
                    "n = {n}, degree {degree}: {m} vs {exact}"
                );
            }
        }
    }

    /// The identity the sub-window route rests on: the Gaussian window `N(p, C)` is the
    /// mixture over offsets `m ~ N(0, b C)` of the windows `N(p + m, (1 - b) C)`, so the
    /// mixture of the sub-windows' closed-form moments (law of total covariance, offsets by
    /// the route's own [`SUB_GRID`]-point rule and [`SUB_SPREAD`]) has the whole window's mean
    /// and covariance. The window is chosen so that every phase the rule integrates has a
    /// standard deviation of at most 0.5 over the offsets (the sum of two of the shortest
    /// waves' wave vectors): the 4-point rule's error on `E[cos(t + s z)]` is then below
    /// `n! / (2n)! s^8 = 2.3e-6` of the term, and f32 accumulation of 64 wave pairs and the
    /// subtraction of the squared mean add at most 64 f32 epsilons (4e-6), both relative to
    /// `(sum_i a_i k_i)^2`, the scale of every second-moment term: the tolerance is 1e-5 of
    /// it; the window's covariance is over 30 times that tolerance, so a wrong split (`b`
    /// for `sqrt(b)`) fails. The fades are off (eye high, tiny pixels).
    #[test]
    fn subwindow_mixture_keeps_the_window_moments() {
        let scene = Scene::new(Lod {
            eye: Vec3::new(0.0, 2.0, 14.0),
            pixel_angle: 1e-4,
        });
        let p = scene.params();
        let k_max = p.waves.iter().map(|w| w[0].hypot(w[1])).fold(0.0, f32::max);
        let slope_sum: f32 = p.waves.iter().map(|w| w[2] * w[0].hypot(w[1])).sum();
        // Offsets' standard deviation along any direction: sqrt(b) * sigma; 2 k_max of it 0.5.
        let sigma = 0.5 / (2.0 * k_max * SUB_SPREAD.sqrt());
        let c = [sigma * sigma, 0.3 * sigma * sigma, 0.8 * sigma * sigma];
        let hit_at = |x: f32, z: f32| Hit {
            t: 1.0,
            position: Vec3::new(x, 0.0, z),
            normal: Vec3::Y,
            dn_dp: Mat3::ZERO,
            object: 0,
            albedo: Vec3::ZERO,
            alpha: 0.01,
        };
        for (x, z) in [(0.3f32, -8.0f32), (-1.7, -20.0)] {
            let (mean, cov) = scene.gradient_moments(&hit_at(x, z), c).unwrap();
            let l11 = c[0].sqrt();
            let l21 = c[1] / l11;
            let l22 = (c[2] - l21 * l21).sqrt();
            let (nodes, weights) = gauss_hermite(SUB_GRID);
            let own = c.map(|v| v * (1.0 - SUB_SPREAD));
            let (mut m, mut second) = (Vec2::ZERO, [0.0f32; 3]);
            for (&zu, &wu) in nodes.iter().zip(&weights) {
                for (&zv, &wv) in nodes.iter().zip(&weights) {
                    let s = SUB_SPREAD.sqrt();
                    let (ox, oz) = (s * l11 * zu, s * (l21 * zu + l22 * zv));
                    let (mk, ck) = scene
                        .gradient_moments(&hit_at(x + ox, z + oz), own)
                        .unwrap();
                    let w = wu * wv;
                    m += w * mk;
                    second[0] += w * (ck[0] + mk.x * mk.x);
                    second[1] += w * (ck[1] + mk.x * mk.y);
                    second[2] += w * (ck[2] + mk.y * mk.y);
                }
            }
            let total = [
                second[0] - m.x * m.x,
                second[1] - m.x * m.y,
                second[2] - m.y * m.y,
            ];
            let tol = 1e-5 * slope_sum * slope_sum;
            assert!(cov[0] + cov[2] > 30.0 * tol, "window too small: {cov:?}");
            assert!((m - mean).length() <= tol, "mean {m} vs {mean}");
            for k in 0..3 {
                assert!(
                    (total[k] - cov[k]).abs() <= tol,
                    "({x}, {z}) cov[{k}]: mixture {} vs window {} (tol {tol})",
                    total[k],
                    cov[k]
                );
            }
        }
    }
}
