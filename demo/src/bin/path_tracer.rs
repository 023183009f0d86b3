//! A CPU path tracer over the crate's BSDF layer (`filtered_ndf::f32::bsdf`): the water and
//! spheres of the demonstration under a small sphere light, GGX at roughness 0.01, rendered
//! with a few samples per pixel with the unfiltered lobe and with filtered lobes, and scored
//! against a converged unfiltered reference with the demonstration's metrics.
//!
//! Run: `cargo run --release -p filtered-ndf-demo --bin path_tracer -- [--quick] [--width N]
//! [--height N] [--spp N] [--reference-spp N] [--frames N] [--threads N] [--seed N]
//! [--out DIR]`. Defaults: 160x100 pixels, 4 spp, a reference of 256 spp, 4 frames, 2
//! threads, images in `target/path_tracer`; `--quick`: 96x60, a reference of 64 spp, 3
//! frames.
//!
//! ## The path tracer
//! - **Materials.** Every surface is GGX of the hit's roughness (`Hit::alpha`: 0.01, more on
//!   the water where its level of detail moved wave slopes into the roughness) through
//!   `MicrofacetReflection`: the water a dielectric of index 1.33, the second sphere gold (the
//!   exact conductor per RGB channel), the other spheres a dielectric coat of index 1.5 over
//!   their Lambertian albedo. The water and the coated spheres add their albedo's Lambertian
//!   term and the scene's constant ambient (as the demonstration shades them).
//! - **Light.** The scene's point light made a sphere of radius [`LIGHT_RADIUS`] of the same
//!   intensity (radiance `I / (pi r^2)`), invisible to camera rays (the demonstration's point
//!   light is invisible). Each vertex samples it by the cone it subtends (uniform in solid
//!   angle) and samples the BSDF (`Bsdf::sample`); the two are combined by multiple importance
//!   sampling (balance heuristic, Veach 1997) with `Bsdf::pdf`. No shadow rays (the
//!   demonstration's shading has no occlusion either): the light is never occluded, for the
//!   light samples and the sampled reflections alike.
//! - **Paths.** The camera ray's hit, one more vertex where the sampled reflection lands, and
//!   that vertex's sampled reflection to the light or the sky (three segments). The sky is
//!   the scene's sky gradient.
//! - **Footprints.** At the camera ray's hit, the ray differentials (Igehy 1999, the camera's
//!   `DiffRay`) scaled by `1 / sqrt(spp)` (each sample stands for its share of the pixel, as
//!   pbrt-v4 scales its camera differentials) give the slope footprint of the half vector
//!   toward the light through KHPL16's half-vector Jacobian
//!   (`Footprint::from_ray_differentials`, the guide's `path_tracer` row); the filtered lobe
//!   of that footprint is the BSDF's lobe for the light sample and the sampled reflection
//!   alike. Later vertices use the unfiltered lobe (the differentials of a glossy reflection
//!   are not tracked).
//! - **Pixels.** Sub-pixel positions from the Gaussian pixel filter (`sigma` 0.5 pixel) that
//!   the footprint kernels assume: a randomly shifted rank-1 lattice per pixel (stratified),
//!   each sample with its own footprint. The filtered and unfiltered images use the same
//!   random numbers, and every frame the same per-pixel streams (so the flicker columns
//!   measure what the camera's motion changes, not fresh noise). The reference is unfiltered,
//!   with many samples, in two independent halves whose LDR-FLIP against each other is
//!   printed as its noise floor.
//!
//! ## The table
//! Frame 0: FLIP (LDR and HDR), specular error (the light reaching the camera through the
//! first vertex's specular lobe), false glints and lost highlights, HDR RMSE; over the
//! camera's dolly (`camera_at`, `--frames`): the flicker error and energy relative to the
//! reference's and the frame-to-frame variation of the peak; the columns of the
//! demonstration's lead table (`metrics::lead_table`).

use filtered_ndf::f32::bsdf::{Bsdf, Conductor, Dielectric, MicrofacetReflection};
use filtered_ndf::f32::filter::Method;
use filtered_ndf::f32::prelude::{
    ExactGaussian, Filterable, Footprint, Gaussian, Ggx, Isotropic, Rect,
};
use filtered_ndf::testing::rng::SplitMix64;
use filtered_ndf_demo::camera::{Camera, camera_at};
use filtered_ndf_demo::image_out::{self, Image, contact_sheet};
use filtered_ndf_demo::methods::{AnalyticInput, SIGMA_PIXEL, footprint_from_ray_differentials};
use filtered_ndf_demo::metrics::{self, Flicker, LeadRow};
use filtered_ndf_demo::render::{Surface, pixel_rng, uniform_f32};
use filtered_ndf_demo::scene::{Hit, Ray, Scene};
use filtered_ndf_demo::{parallel, peaks};
use glam::{Mat3, Vec3};
use std::f32::consts::{PI, TAU};
use std::path::PathBuf;
use std::time::Instant;

/// The light sphere's radius (m), at the scene's point light 90 m away: `0.3` degrees across,
/// narrower than the roughness-0.01 lobe in half-vector slope.
const LIGHT_RADIUS: f32 = 0.25;

/// Gold per RGB channel at 650, 550 and 450 nm: `(n, k)` of Yakubovsky et al. 2017 ("Optical
/// constants and structural properties of thin gold films", Opt. Express 25, 25574; the
/// 117 nm film, as tabulated in the refractiveindex.info database).
const GOLD: ([f32; 3], [f32; 3]) = ([0.143_3, 0.338_2, 1.491_8], [3.703_0, 2.549_0, 1.908_4]);

/// The index of the water and of the spheres' coat.
const WATER_IOR: f32 = 1.33;
const COAT_IOR: f32 = 1.5;

/// Command-line options.
struct Options {
    width: usize,
    height: usize,
    spp: usize,
    reference_spp: usize,
    frames: usize,
    threads: usize,
    seed: u64,
    out: PathBuf,
    exposure: f32,
}

fn usage() -> ! {
    eprintln!(
        "usage: path_tracer [--quick] [--width N] [--height N] [--spp N] [--reference-spp N]\n\
         \x20                  [--frames N] [--threads N] [--seed N] [--out DIR]"
    );
    std::process::exit(2)
}

fn parse_args() -> Options {
    let mut o = Options {
        width: 160,
        height: 100,
        spp: 4,
        reference_spp: 256,
        frames: 4,
        threads: 2,
        seed: 1,
        out: PathBuf::from("target/path_tracer"),
        exposure: 1.0,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        if flag == "--quick" {
            (o.width, o.height, o.reference_spp, o.frames) = (96, 60, 64, 3);
            continue;
        }
        let Some(value) = args.next() else { usage() };
        let num = |v: &str| v.parse::<usize>().unwrap_or_else(|_| usage());
        match flag.as_str() {
            "--width" => o.width = num(&value).max(2),
            "--height" => o.height = num(&value).max(2),
            "--spp" => o.spp = num(&value).max(1),
            "--reference-spp" => o.reference_spp = num(&value).max(2),
            "--frames" => o.frames = num(&value).max(1),
            "--threads" => o.threads = num(&value).max(1),
            "--seed" => o.seed = num(&value) as u64,
            "--out" => o.out = PathBuf::from(value),
            _ => usage(),
        }
    }
    o
}

/// A reflectance as RGB: the grey `f32` of a dielectric, or the conductor's `Vec3`.
trait Rgb: Copy {
    fn rgb(self) -> Vec3;
}

impl Rgb for f32 {
    fn rgb(self) -> Vec3 {
        Vec3::splat(self)
    }
}

impl Rgb for Vec3 {
    fn rgb(self) -> Vec3 {
        self
    }
}

/// A lobe the path tracer can shade with: one `MicrofacetReflection` per Fresnel form of the
/// scene. Every lobe of the front door is one (the bounds are the crate's `Bsdf` impls).
trait Lobe: Copy + Send + Sync {
    fn with_dielectric(self, f: Dielectric) -> impl Bsdf<Value = f32>;
    fn with_conductor(self, f: Conductor<Vec3>) -> impl Bsdf<Value = Vec3>;
}

impl<L: Copy + Send + Sync> Lobe for L
where
    MicrofacetReflection<L, Dielectric>: Bsdf<Value = f32>,
    MicrofacetReflection<L, Conductor<Vec3>>: Bsdf<Value = Vec3>,
{
    fn with_dielectric(self, f: Dielectric) -> impl Bsdf<Value = f32> {
        MicrofacetReflection::new(self, f)
    }
    fn with_conductor(self, f: Conductor<Vec3>) -> impl Bsdf<Value = Vec3> {
        MicrofacetReflection::new(self, f)
    }
}

/// How the first vertex's lobe is made from the material and the sample's footprint.
trait Filter: Sync {
    type Lobe: Lobe;
    fn lobe(&self, material: Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe;
}

/// The material's own lobe.
struct Unfiltered;

impl Filter for Unfiltered {
    type Lobe = Ggx<Isotropic>;
    fn lobe(&self, material: Ggx<Isotropic>, _: Footprint) -> Self::Lobe {
        material
    }
}

/// The front door: `material.filtered(footprint, method)`.
struct Filtered<M>(M);

impl<M> Filter for Filtered<M>
where
    M: Method<Ggx<Isotropic>> + Copy + Sync,
    M::Lobe: Lobe,
{
    type Lobe = M::Lobe;
    fn lobe(&self, material: Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe {
        material.filtered(footprint, self.0)
    }
}

/// The sphere light (module docs).
struct Light {
    center: Vec3,
    radius: f32,
    radiance: Vec3,
}

impl Light {
    fn of(scene: &Scene) -> Self {
        Self {
            center: scene.light_position,
            radius: LIGHT_RADIUS,
            radiance: scene.light_intensity / (PI * LIGHT_RADIUS * LIGHT_RADIUS),
        }
    }

    /// `1 - cos theta_max` of the cone the light subtends from `p` (without cancellation),
    /// and the unit axis; `None` inside the light.
    fn cone(&self, p: Vec3) -> Option<(f32, Vec3)> {
        let to = self.center - p;
        let d2 = to.length_squared();
        let sin2 = self.radius * self.radius / d2;
        if sin2 >= 1.0 {
            return None;
        }
        let one_minus_cos = sin2 / (1.0 + (1.0 - sin2).sqrt());
        Some((one_minus_cos, to / d2.sqrt()))
    }

    /// The solid-angle density of [`Light::sample`] from `p`: `1 / (2 pi (1 - cos theta_max))`.
    fn pdf(&self, p: Vec3) -> f32 {
        self.cone(p).map_or(0.0, |(omc, _)| 1.0 / (TAU * omc))
    }

    /// A direction uniform in the cone of the light seen from `p`, and its density.
    fn sample(&self, p: Vec3, u: [f32; 2]) -> Option<(Vec3, f32)> {
        let (omc, axis) = self.cone(p)?;
        let one_minus_cos = u[0] * omc;
        let cos = 1.0 - one_minus_cos;
        let sin = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
        let phi = TAU * u[1];
        let frame = frame_of(axis);
        let dir = frame * Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
        Some((dir.normalize(), 1.0 / (TAU * omc)))
    }

    /// The distance along `ray` to the light, if it hits it (the discriminant from the
    /// ray's distance to the centre, without the cancellation of `b^2 - c` far away).
    fn hit(&self, ray: &Ray) -> Option<f32> {
        let oc = ray.origin - self.center;
        let b = oc.dot(ray.dir);
        let disc = self.radius * self.radius - (oc - b * ray.dir).length_squared();
        let t = -b - disc.max(0.0).sqrt();
        (disc >= 0.0 && t > 0.0).then_some(t)
    }
}

/// An orthonormal frame with `n` as its third column (Duff et al. 2017).
fn frame_of(n: Vec3) -> Mat3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Mat3::from_cols(
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
        n,
    )
}

/// The surface's specular layer.
#[derive(Clone, Copy)]
enum Coat {
    Dielectric(Dielectric),
    Gold(Conductor<Vec3>),
}

/// The scene, its light and materials.
struct Context {
    scene: Scene,
    light: Light,
    water: Dielectric,
    coat: Dielectric,
    gold: Conductor<Vec3>,
}

impl Context {
    fn new(scene: Scene) -> Self {
        Self {
            light: Light::of(&scene),
            scene,
            water: Dielectric::new(WATER_IOR).expect("a positive index"),
            coat: Dielectric::new(COAT_IOR).expect("a positive index"),
            gold: Conductor::new(Vec3::from(GOLD.0), Vec3::from(GOLD.1))
                .expect("published constants are in the domain"),
        }
    }

    /// The specular layer and Lambertian albedo of a hit.
    fn material(&self, hit: &Hit) -> (Coat, Vec3) {
        match hit.object {
            0 => (Coat::Dielectric(self.water), hit.albedo),
            2 => (Coat::Gold(self.gold), Vec3::ZERO),
            _ => (Coat::Dielectric(self.coat), hit.albedo),
        }
    }
}

/// A sampled reflection leaving a vertex.
struct Bounce {
    ray: Ray,
    /// `f cos / pdf` (RGB).
    weight: Vec3,
    pdf: f32,
}

/// What one vertex gathers: its Lambertian and ambient terms, its specular light sample, and
/// the sampled reflection (followed by the caller).
struct Vertex {
    diffuse: Vec3,
    specular: Vec3,
    bounce: Option<Bounce>,
}

/// `N` uniform numbers in `[0, 1)`.
fn uniforms<const N: usize>(rng: &mut SplitMix64) -> [f32; N] {
    std::array::from_fn(|_| 1.0 - uniform_f32(rng))
}

/// One vertex with the lobe `lobe` (module docs: light sample with MIS, BSDF sample).
fn vertex<L: Lobe>(
    ctx: &Context,
    lobe: L,
    hit: &Hit,
    frame: Mat3,
    wo: Vec3,
    rng: &mut SplitMix64,
) -> Vertex {
    let (coat, albedo) = ctx.material(hit);
    match coat {
        Coat::Dielectric(f) => {
            vertex_with(ctx, &lobe.with_dielectric(f), albedo, hit, frame, wo, rng)
        }
        Coat::Gold(f) => vertex_with(ctx, &lobe.with_conductor(f), albedo, hit, frame, wo, rng),
    }
}

fn vertex_with<B: Bsdf>(
    ctx: &Context,
    bsdf: &B,
    albedo: Vec3,
    hit: &Hit,
    frame: Mat3,
    wo_world: Vec3,
    rng: &mut SplitMix64,
) -> Vertex
where
    B::Value: Rgb,
{
    let to_local = frame.transpose();
    let wo = to_local * wo_world;
    let mut v = Vertex {
        diffuse: albedo * ctx.scene.ambient,
        specular: Vec3::ZERO,
        bounce: None,
    };
    let u_light: [f32; 2] = uniforms(rng);
    let u_bsdf: [f32; 4] = uniforms(rng);
    if wo.z <= 0.0 {
        // Seen from below its shading normal (a wave's back at grazing): no reflection.
        return v;
    }
    let le = ctx.light.radiance;
    if let Some((dir, pdf_light)) = ctx.light.sample(hit.position, u_light) {
        let wi = to_local * dir;
        if wi.z > 0.0 {
            v.diffuse += le * albedo * (wi.z / (PI * pdf_light));
            let f = bsdf.f(wo, wi).rgb();
            // Balance heuristic: f cos / pdf_light * pdf_light / (pdf_light + pdf_bsdf).
            v.specular += le * f * (wi.z / (pdf_light + bsdf.pdf(wo, wi)));
        }
    }
    if let Some(s) = bsdf.sample(wo, u_bsdf) {
        v.bounce = Some(Bounce {
            ray: Ray {
                origin: hit.position + hit.normal * 1e-3,
                dir: (frame * s.wi).normalize(),
            },
            weight: s.weight.rgb(),
            pdf: s.pdf,
        });
    }
    v
}

/// The radiance arriving along a sampled reflection: the light (MIS-weighted against its
/// light sample), or the surface it meets, a further vertex (unfiltered) while
/// `vertices > 0`, or the sky. The light is never occluded (the light samples cast no shadow
/// rays, so a reflection that meets the light counts it whatever lies in front: both
/// strategies estimate the same integrand).
fn follow(ctx: &Context, b: &Bounce, vertices: usize, rng: &mut SplitMix64) -> Vec3 {
    if ctx.light.hit(&b.ray).is_some() {
        let pdf_light = ctx.light.pdf(b.ray.origin);
        return ctx.light.radiance * (b.pdf / (b.pdf + pdf_light));
    }
    match ctx.scene.intersect(&b.ray) {
        Some(h) => {
            if vertices == 0 {
                return Vec3::ZERO;
            }
            let s = Surface::new(&ctx.scene, b.ray.origin, h);
            let lobe = Ggx::new(Isotropic::new_clamped(h.alpha));
            let v = vertex(ctx, lobe, &h, s.frame, -b.ray.dir, rng);
            let mut l = v.diffuse + v.specular;
            if let Some(next) = v.bounce {
                l += next.weight * follow(ctx, &next, vertices - 1, rng);
            }
            l
        }
        None => ctx.scene.sky(b.ray.dir),
    }
}

/// One camera path through the image point `(x, y)`: `(radiance, its specular part)`.
fn path<F: Filter>(
    ctx: &Context,
    filter: &F,
    cam: &Camera,
    (x, y): (f32, f32),
    scale: f32,
    rng: &mut SplitMix64,
) -> (Vec3, Vec3) {
    let r = cam.ray(x, y);
    let Some(hit) = ctx.scene.intersect(&r.ray) else {
        return (ctx.scene.sky(r.ray.dir), Vec3::ZERO);
    };
    let s = Surface::new(&ctx.scene, cam.eye, hit);
    let (dx_u, dx_v) = r.footprint_on_plane(&hit);
    let footprint = footprint_from_ray_differentials(&AnalyticInput {
        position: hit.position,
        eye: cam.eye,
        light: ctx.light.center,
        frame: [s.frame.x_axis, s.frame.y_axis, s.frame.z_axis],
        dn_dt: hit.dn_dp * s.frame.x_axis,
        dn_db: hit.dn_dp * s.frame.y_axis,
        dx_u: dx_u * scale,
        dx_v: dx_v * scale,
    });
    let material = Ggx::new(Isotropic::new_clamped(hit.alpha));
    let v = vertex(
        ctx,
        filter.lobe(material, footprint),
        &hit,
        s.frame,
        s.wo,
        rng,
    );
    let mut specular = v.specular;
    if let Some(b) = v.bounce {
        specular += b.weight * follow(ctx, &b, 1, rng);
    }
    (v.diffuse + specular, specular)
}

/// A rank-1 lattice of `n` points `(j / n, {j g / n})` in the unit square, `g` coprime to `n`
/// near `n / phi` (the golden ratio): stratified for every `n` (Korobov lattices; the
/// Fibonacci lattice where `n` is a Fibonacci number).
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

    /// Point `j` shifted by `shift` (modulo 1): in `[0, 1)^2`.
    fn point(&self, j: usize, shift: (f32, f32)) -> (f32, f32) {
        let u = (j as f32 / self.n as f32 + shift.0).fract();
        let v = (((j * self.g) % self.n) as f32 / self.n as f32 + shift.1).fract();
        (u, v)
    }
}

/// An image of `spp` paths per pixel, the ray differentials scaled by `1 / sqrt(spp)`:
/// `(radiance, specular part)`. The sub-pixel positions are a randomly shifted rank-1
/// lattice (stratified, unbiased by the per-pixel shift) mapped to the Gaussian pixel filter
/// by Box-Muller; the other random numbers are independent. `seed` picks the pixels' random
/// streams.
fn render<F: Filter>(
    ctx: &Context,
    filter: &F,
    cam: &Camera,
    (w, h): (usize, usize),
    spp: usize,
    seed: u64,
) -> (Image, Image) {
    let scale = 1.0 / (spp as f32).sqrt();
    let lattice = Lattice::new(spp);
    let px: Vec<(Vec3, Vec3)> = parallel::rows(h, None, |y| {
        (0..w)
            .map(|x| {
                let mut rng = pixel_rng(seed, (y * w + x) as u64);
                let [s0, s1] = uniforms(&mut rng);
                let (mut total, mut spec) = (Vec3::ZERO, Vec3::ZERO);
                for j in 0..spp {
                    let (u, v) = lattice.point(j, (s0, s1));
                    // 1 - u in (0, 1]: the logarithm is finite.
                    let r = SIGMA_PIXEL * (-2.0 * (1.0 - u).ln()).sqrt();
                    let (ox, oy) = (r * (TAU * v).cos(), r * (TAU * v).sin());
                    let p = (x as f32 + 0.5 + ox, y as f32 + 0.5 + oy);
                    let (l, s) = path(ctx, filter, cam, p, scale, &mut rng);
                    total += l;
                    spec += s;
                }
                (total / spp as f32, spec / spp as f32)
            })
            .collect()
    });
    let (total, spec): (Vec<Vec3>, Vec<Vec3>) = px.into_iter().unzip();
    (Image::new(w, h, total), Image::new(w, h, spec))
}

/// One method's frames: the still frame (total and specular) and every frame's display
/// luminance and peak.
struct Run {
    label: String,
    /// File name stem.
    slug: String,
    still: Option<(Image, Image)>,
    luminance: Vec<Vec<f32>>,
    peaks: Vec<f32>,
    seconds: f64,
}

impl Run {
    fn new(label: &str) -> Self {
        Self {
            label: label.to_string(),
            slug: label
                .split(' ')
                .next()
                .unwrap_or(label)
                .to_lowercase()
                .replace("::", "-"),
            still: None,
            luminance: Vec::new(),
            peaks: Vec::new(),
            seconds: 0.0,
        }
    }

    fn push(&mut self, frame: (Image, Image), exposure: f32, seconds: f64) {
        self.luminance
            .push(metrics::display_luminance(&frame.0, exposure));
        self.peaks.push(frame.0.peak());
        self.seconds += seconds;
        if self.still.is_none() {
            self.still = Some(frame);
        }
    }
}

/// One frame's setting: the scene, the camera, the image size, the samples per pixel, the
/// seed and the display exposure.
struct Shot<'a> {
    ctx: &'a Context,
    cam: &'a Camera,
    size: (usize, usize),
    spp: usize,
    seed: u64,
    exposure: f32,
}

impl Shot<'_> {
    /// Renders this frame with `filter` into `run`, timed.
    fn render_into<F: Filter>(&self, run: &mut Run, filter: &F) {
        let t = Instant::now();
        let img = render(self.ctx, filter, self.cam, self.size, self.spp, self.seed);
        run.push(img, self.exposure, t.elapsed().as_secs_f64());
    }
}

fn main() -> std::io::Result<()> {
    let o = parse_args();
    parallel::init_threads(o.threads);
    let start = Instant::now();
    let size = (o.width, o.height);
    eprintln!(
        "path_tracer: {}x{}, {} spp against an unfiltered reference of {} spp, {} frames, {} threads",
        o.width, o.height, o.spp, o.reference_spp, o.frames, o.threads
    );
    let spp_label = |name: &str| format!("{name} ({} spp)", o.spp);
    let mut reference = Run::new("reference");
    let mut halves = (Vec::new(), Vec::new());
    let mut runs = [
        Run::new(&spp_label("unfiltered GGX")),
        Run::new(&spp_label("Gaussian::TK19")),
        Run::new(&spp_label("ExactGaussian::KHPL16")),
        Run::new(&spp_label("Rect::KHPL16")),
    ];
    for f in 0..o.frames {
        let cam = camera_at(f, o.width, o.height);
        let ctx = Context::new(Scene::new(cam.lod()));
        // The reference in two independent halves (their difference is its noise floor).
        let t = Instant::now();
        let half = (o.reference_spp / 2).max(1);
        let a = render(&ctx, &Unfiltered, &cam, size, half, o.seed ^ 0xa11ce);
        let b = render(&ctx, &Unfiltered, &cam, size, half, o.seed ^ 0xb0b);
        let mean = |p: &Image, q: &Image| {
            Image::new(
                p.width,
                p.height,
                p.data
                    .iter()
                    .zip(&q.data)
                    .map(|(x, y)| 0.5 * (*x + *y))
                    .collect(),
            )
        };
        let full = (mean(&a.0, &b.0), mean(&a.1, &b.1));
        if f == 0 {
            halves = (vec![a.0], vec![b.0]);
        }
        reference.push(full, o.exposure, t.elapsed().as_secs_f64());
        let shot = Shot {
            ctx: &ctx,
            cam: &cam,
            size,
            spp: o.spp,
            seed: o.seed,
            exposure: o.exposure,
        };
        let [u, g, e, r] = &mut runs;
        shot.render_into(u, &Unfiltered);
        shot.render_into(g, &Filtered(Gaussian::TK19));
        shot.render_into(e, &Filtered(ExactGaussian::KHPL16));
        shot.render_into(r, &Filtered(Rect::KHPL16));
        eprintln!("frame {f} done ({:.1} s)", start.elapsed().as_secs_f64());
    }

    let (ref_total, ref_spec) = reference.still.as_ref().expect("one frame at least");
    let ref_energy = metrics::flicker_energy(&reference.luminance);
    let mut rows = Vec::new();
    for (i, run) in runs.iter().enumerate() {
        let (total, spec) = run.still.as_ref().expect("one frame at least");
        let (scores, _) = metrics::score((total, spec), (ref_total, ref_spec), o.exposure);
        let flicker = (o.frames > 1).then(|| Flicker {
            error: metrics::flicker_error(&run.luminance, &reference.luminance) / ref_energy,
            energy: metrics::flicker_energy(&run.luminance) / ref_energy,
            peak_variation: peaks::variation(&run.peaks),
        });
        rows.push(LeadRow {
            label: run.label.clone(),
            ndf: "GGX",
            baseline: i == 0,
            scores,
            flicker,
        });
    }
    let noise_floor = metrics::flip_ldr(&halves.0[0], &halves.1[0], o.exposure).mean();
    println!(
        "\n## Path tracer: {}x{}, {} spp against an unfiltered reference of {} spp, {} frames\n",
        o.width, o.height, o.spp, o.reference_spp, o.frames
    );
    print!("{}", metrics::lead_table(&rows));
    println!(
        "\nReference noise floor: LDR-FLIP {noise_floor:.4} between its two halves of {} spp; \
         reference flicker energy {ref_energy:.2e}.",
        (o.reference_spp / 2).max(1)
    );
    println!("\n| render | seconds (all frames) |\n|---|---:|");
    println!("| reference | {:.1} |", reference.seconds);
    for run in &runs {
        println!("| {} | {:.1} |", run.label, run.seconds);
    }

    std::fs::create_dir_all(&o.out)?;
    let mut tiles = vec![("reference".to_string(), ref_total.to_rgb8(o.exposure))];
    image_out::save(&tiles[0].1, &o.out.join("reference.png"))?;
    for run in &runs {
        let (total, _) = run.still.as_ref().expect("one frame at least");
        let img = total.to_rgb8(o.exposure);
        let flip = metrics::flip_ldr(total, ref_total, o.exposure).to_rgb8();
        image_out::save(&img, &o.out.join(format!("{}.png", run.slug)))?;
        image_out::save(&flip, &o.out.join(format!("flip-{}.png", run.slug)))?;
        tiles.push((run.label.clone(), img));
    }
    let sheet_path = o.out.join("path_tracer.png");
    image_out::save(&contact_sheet(&tiles, 3, 2), &sheet_path)?;
    println!(
        "\nImages: {}\nTotal {:.1} s.",
        sheet_path.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A light of radius `0.5` at `center`, radiance 1.
    fn light(center: Vec3) -> Light {
        Light {
            center,
            radius: 0.5,
            radiance: Vec3::ONE,
        }
    }

    /// Every light sample is a unit direction that meets the light, with the density
    /// `1 / (2 pi (1 - cos theta_max))`, `sin theta_max = r / d` (the cone's solid angle in
    /// closed form, in f64; 1e-4 relative: f32 rounding of `1 - cos theta_max` computed
    /// without cancellation).
    #[test]
    fn light_samples_meet_the_light_with_the_cone_density() {
        let l = light(Vec3::new(1.0, 2.0, 8.0));
        let p = Vec3::new(0.2, -0.1, 0.0);
        let d = (l.center - p).length() as f64;
        let sin = 0.5 / d;
        let want = 1.0 / (std::f64::consts::TAU * (1.0 - (1.0 - sin * sin).sqrt()));
        let mut rng = pixel_rng(5, 2);
        for _ in 0..1000 {
            let (dir, pdf) = l.sample(p, uniforms(&mut rng)).unwrap();
            assert!((dir.length() - 1.0).abs() < 1e-6);
            assert!(l.hit(&Ray { origin: p, dir }).is_some(), "{dir} misses");
            assert!(((pdf as f64) - want).abs() < 1e-4 * want, "{pdf} vs {want}");
            assert_eq!(l.pdf(p), pdf);
        }
    }

    /// The multiple-importance estimate of one vertex's specular light (light sample plus
    /// BSDF sample, balance heuristic) against light sampling alone, both unbiased for the
    /// same integral: their means over 200 000 samples agree within 5 standard errors of the
    /// difference (a light as wide as the lobe, so that both strategies carry weight). Checks
    /// that `Bsdf::pdf` is the density `Bsdf::sample` draws, as MIS needs.
    #[test]
    fn mis_agrees_with_light_sampling() {
        let wo = Vec3::new(-0.5, 0.0, 0.8).normalize();
        let mirror = Vec3::new(0.5, 0.0, 0.8).normalize();
        let l = light(mirror * 10.0);
        let lobe = Ggx::new(Isotropic::new(0.05).unwrap());
        let bsdf = lobe.with_dielectric(Dielectric::new(1.33).unwrap());
        let p = Vec3::ZERO;
        let mut rng = pixel_rng(7, 3);
        let n = 200_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        let mut strategies = [0.0f64; 2];
        for _ in 0..n {
            let (dir, pdf_l) = l.sample(p, uniforms(&mut rng)).unwrap();
            let (f, cos) = (bsdf.f(wo, dir), dir.z);
            let light_only = (f * cos / pdf_l) as f64;
            let mut mis = (f * cos / (pdf_l + bsdf.pdf(wo, dir))) as f64;
            strategies[0] += mis;
            if let Some(s) = bsdf.sample(wo, uniforms(&mut rng)) {
                if l.hit(&Ray {
                    origin: p,
                    dir: s.wi,
                })
                .is_some()
                {
                    let b = (s.weight * s.pdf / (s.pdf + l.pdf(p))) as f64;
                    mis += b;
                    strategies[1] += b;
                }
            }
            let diff = mis - light_only;
            sum += diff;
            sum2 += diff * diff;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!(
            strategies
                .iter()
                .all(|&s| s > 0.1 * (strategies[0] + strategies[1])),
            "both strategies carry weight: {strategies:?}"
        );
        assert!(
            mean.abs() <= 5.0 * se,
            "MIS - light only = {mean} (se {se})"
        );
    }
}
