//! The measurements: the still frame (GPU frames against the CPU reference and the CPU
//! demo's frames, GPU times), the temporal test, and their tables and figures.

use crate::camera::camera_at;
use crate::gpu::{Gpu, Timer};
use crate::image_out::{Image, Rgb8, contact_sheet, save};
use crate::methods::{Family, Method};
use crate::metrics::{
    self, Flicker, LeadRow, Scores, display_luminance, flicker_energy, flicker_error,
};
use crate::passes::{Renderer, Route};
use crate::peaks::{distance, mean, variation};
use crate::plot::{PALETTE, Series, line_plot};
use crate::render::{self, FootprintRoute};
use crate::scene::{Scene, SceneKind};
use crate::{Options, parallel};
use rayon::prelude::*;
use std::fmt::Write as _;

/// Resolution divisor and reference sample divisor of the temporal frames: the CPU demo's
/// (`filtered_ndf_demo::temporal`), so that both temporal tables describe the same frames.
const DOWNSCALE: u32 = 2;
const SPP_DIVISOR: usize = 4;

/// Every route rendered in scene `kind`: each method of the CPU demo in forward shading, on
/// the water each of `moments` (footprint methods) on the forward moments route, then
/// unfiltered GGX and each engine preset in deferred shading, then on the water each of
/// `moments` on the deferred moments route.
pub fn routes(kind: SceneKind, moments: &[Method]) -> Vec<Route> {
    let forward = crate::passes::FORWARD.iter().map(|&m| Route::Forward(m));
    let on_moments: Vec<Method> = crate::passes::FORWARD
        .iter()
        .copied()
        .filter(|m| m.uses_footprint() && moments.contains(m))
        .filter(|_| kind == SceneKind::Water)
        .collect();
    let deferred = std::iter::once(None)
        .chain((0..filtered_ndf::f32::filter::presets::ALL.len()).map(Some))
        .map(Route::Deferred);
    forward
        .chain(on_moments.iter().map(|&m| Route::Moments(m)))
        .chain(deferred)
        .chain(on_moments.iter().map(|&m| Route::DeferredMoments(m)))
        .collect()
}

/// The CPU demo's method that a route renders.
fn cpu_method(route: Route) -> Method {
    match route {
        Route::Forward(m) | Route::Moments(m) | Route::DeferredMoments(m) => m,
        Route::Deferred(None) => Method::Unfiltered(Family::Ggx),
        Route::Deferred(Some(i)) => Method::Preset(i),
    }
}

fn route_name(route: Route) -> &'static str {
    match route {
        Route::Forward(_) => "forward",
        Route::Moments(_) => "forward, moments",
        Route::Deferred(_) => "deferred",
        Route::DeferredMoments(_) => "deferred, moments",
    }
}

/// The route's part of a file name.
fn route_slug(route: Route) -> &'static str {
    match route {
        Route::Forward(_) => "forward",
        Route::Moments(_) => "moments",
        Route::Deferred(_) => "deferred",
        Route::DeferredMoments(_) => "deferred-moments",
    }
}

fn slug(route: Route) -> String {
    format!("gpu-{}-{}", route_slug(route), cpu_method(route).slug())
}

/// The CPU demo's footprint route with the same filter inputs as the GPU route: its
/// moments route for [`Route::Moments`], its 2x2-quad differences for the others.
fn cpu_route(route: Route) -> FootprintRoute {
    match route {
        Route::Moments(_) | Route::DeferredMoments(_) => FootprintRoute::Moments,
        _ => FootprintRoute::Quad,
    }
}

/// The baseline a route's time is divided by: unfiltered GGX on the same route.
fn baseline(route: Route) -> Route {
    match route {
        Route::Forward(_) | Route::Moments(_) => Route::Forward(Method::Unfiltered(Family::Ggx)),
        Route::Deferred(_) | Route::DeferredMoments(_) => Route::Deferred(None),
    }
}

/// One route's row of the still-frame table.
pub struct Row {
    pub route: Route,
    pub gpu_rmse: f64,
    pub gpu_mean: f64,
    pub gpu_peak: f64,
    /// The CPU demo's frame of the same method: ray differentials (its default) and the
    /// same filter inputs as the GPU's ([`cpu_route`]: its own 2x2-quad differences, or its
    /// moments route).
    pub cpu_rays_rmse: f64,
    pub cpu_same_rmse: f64,
    pub cpu_rays_mean: f64,
    pub cpu_rays_peak: f64,
    /// RMSE of the GPU frame against the CPU demo's frame with the same filter inputs.
    pub gpu_vs_cpu_same: f64,
    /// The same over the pixels the two compute alike (the quad routes: those the CPU
    /// differences with their own quad partners, [`GBuffer::quad_interior`]; the moments
    /// route, which differences nothing: every pixel), relative to the CPU frame's RMSE
    /// against the reference there.
    ///
    /// [`GBuffer::quad_interior`]: crate::render::GBuffer::quad_interior
    pub agreement: f64,
    /// Median GPU time of the route's passes (seconds).
    pub time: f64,
    /// Issue 21's still-frame scores of the GPU frame against the reference; its specular
    /// term is the GPU frame less the CPU frame's ambient, diffuse and sky (the same formulas
    /// at the same pixel centres, whatever the filter).
    pub scores: Scores,
}

/// The still frame's results.
pub struct Still {
    pub kind: SceneKind,
    pub rows: Vec<Row>,
    /// Per family (Beckmann, GGX): the reference's own error, its scores against an
    /// independent reference of four times the samples.
    pub reference_error: [Scores; 2],
    /// The fraction of pixels the CPU quad route differences with their own quad partners.
    pub same_quads: f64,
    pub reference_s: f64,
    pub visibility_time: f64,
    pub timer: &'static str,
}

fn image(o: &Options, data: Vec<glam::Vec3>) -> Image {
    Image::new(o.width as usize, o.height as usize, data)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Frame 0: every route on the GPU, the CPU reference and the CPU demo's frames, the times,
/// the images, the contact sheet and the side-by-side figure.
pub fn still(
    o: &Options,
    kind: SceneKind,
    gpu: &Gpu,
    renderer: &mut Renderer,
) -> Result<Still, String> {
    let (w, h) = (o.width as usize, o.height as usize);
    let cam = camera_at(0, w, h);
    let scene = Scene::of(kind, cam.lod());
    renderer.resize(gpu, o.width, o.height);
    renderer.begin_frame(gpu, &scene, &cam)?;
    let all = routes(kind, &o.moments);
    let mut frames = Vec::new();
    for &route in &all {
        frames.push((route, image(o, renderer.render(gpu, route)?)));
    }
    // Every route once per round, rounds repeated (the first one warms up): a drift of the
    // machine's speed touches every route alike.
    let timer = Timer::new(gpu);
    let bar = parallel::bar("GPU timing", o.repeats + 1);
    let mut samples = vec![Vec::new(); all.len()];
    for round in 0..=o.repeats {
        for (k, &route) in all.iter().enumerate() {
            let s = timer.time(gpu, route.passes(), |enc| {
                renderer.record(enc, route, Some(&timer))
            })?;
            if round > 0 {
                samples[k].push(s);
            }
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    let times: Vec<f64> = samples.into_iter().map(median).collect();
    let visibility_time = median(
        (0..o.repeats)
            .map(|_| renderer.time_visibility(gpu, &timer))
            .collect::<Result<_, _>>()?,
    );

    let t = std::time::Instant::now();
    let reference = render::reference(&scene, &cam, w, h, o.spp, o.seed, Some("CPU reference"));
    let reference_s = t.elapsed().as_secs_f64();
    let reference_4n = render::reference(
        &scene,
        &cam,
        w,
        h,
        4 * o.spp,
        o.seed ^ render::SEED_4N,
        Some("CPU reference x4 (its error)"),
    );
    let reference_error = [Family::Beckmann, Family::Ggx].map(|f| {
        metrics::reference_error(
            (reference.full(f), reference.specular(f)),
            (reference_4n.full(f), reference_4n.specular(f)),
            o.exposure,
        )
    });
    let gb = render::gbuffer(&scene, &cam, w, h);
    let rays = gb.derivatives(&scene, FootprintRoute::RayDifferentials);
    let quad = gb.derivatives(&scene, FootprintRoute::Quad);
    let moments = all
        .iter()
        .any(|&r| cpu_route(r) == FootprintRoute::Moments)
        .then(|| gb.derivatives(&scene, FootprintRoute::Moments));
    let interior = gb.quad_interior();
    let every_pixel = vec![true; interior.len()];
    let same_quads = interior.iter().filter(|&&b| b).count() as f64 / interior.len() as f64;

    let mut rows = Vec::new();
    let mut tiles: Vec<(String, Rgb8)> = Vec::new();
    for family in [Family::Beckmann, Family::Ggx] {
        let img = reference.full(family);
        tiles.push((
            format!("CPU reference, {} ({} spp)", family.name(), o.spp),
            img.to_rgb8(o.exposure),
        ));
        let name = format!("reference-{}.png", family.name().to_lowercase());
        save(&img.to_rgb8(o.exposure), &o.out.join(name)).map_err(|e| e.to_string())?;
    }
    // Each route's CPU frames, metrics and images are independent: computed in parallel
    // (at 1280x800 the loop took minutes on one core: FLIP and the PNG encoders are serial),
    // then laid out in the routes' order.
    let per_route: Vec<(Row, Rgb8, Option<Rgb8>)> = frames
        .par_iter()
        .zip(times)
        .map(|((route, img), time)| -> Result<_, String> {
            let m = cpu_method(*route);
            let full = reference.full(m.family());
            let cpu_rays = render::shade(&scene, &gb, &rays, m);
            let (inputs, mask) = match (cpu_route(*route), &moments) {
                (FootprintRoute::Moments, Some(d)) => (d, &every_pixel),
                _ => (&quad, &interior),
            };
            let cpu_same_frame = render::shade_frame(&scene, &gb, inputs, m);
            let cpu_same = &cpu_same_frame.total;
            let specular = Image::new(
                w,
                h,
                img.data
                    .iter()
                    .zip(&cpu_same_frame.total.data)
                    .zip(&cpu_same_frame.specular.data)
                    .map(|((&g, &t), &sp)| (g - (t - sp)).max(glam::Vec3::ZERO))
                    .collect(),
            );
            let (scores, flip_map) = metrics::score(
                (img, &specular),
                (full, reference.specular(m.family())),
                o.exposure,
            );
            save(
                &flip_map.to_rgb8(),
                &o.out.join(format!("flip-{}.png", slug(*route))),
            )
            .map_err(|e| e.to_string())?;
            let row = Row {
                route: *route,
                gpu_rmse: img.rmse(full),
                gpu_mean: img.mean_luminance() / full.mean_luminance(),
                gpu_peak: img.peak() as f64 / full.peak() as f64,
                cpu_rays_rmse: cpu_rays.rmse(full),
                cpu_same_rmse: cpu_same.rmse(full),
                cpu_rays_mean: cpu_rays.mean_luminance() / full.mean_luminance(),
                cpu_rays_peak: cpu_rays.peak() as f64 / full.peak() as f64,
                gpu_vs_cpu_same: img.rmse(cpu_same),
                agreement: img.rmse_where(cpu_same, mask)
                    / cpu_same.rmse_where(full, mask).max(1e-30),
                time,
                scores,
            };
            let rgb = img.to_rgb8(o.exposure);
            save(&rgb, &o.out.join(format!("{}.png", slug(*route)))).map_err(|e| e.to_string())?;
            let shown = [
                Route::Forward(Method::Unfiltered(Family::Ggx)),
                Route::Forward(Method::Tk19Projected),
                Route::Deferred(Some(2)),
            ];
            let rays = shown.contains(route).then(|| cpu_rays.to_rgb8(o.exposure));
            Ok((row, rgb, rays))
        })
        .collect::<Result<_, String>>()?;
    let mut side_by_side = Vec::new();
    for (row, rgb, rays) in per_route {
        let m = cpu_method(row.route);
        let prefix = match row.route {
            Route::Forward(_) => "GPU fwd",
            Route::Moments(_) => "GPU moments",
            Route::Deferred(_) => "GPU def",
            Route::DeferredMoments(_) => "GPU def moments",
        };
        tiles.push((format!("{prefix}: {}", m.label()), rgb.clone()));
        if let Some(rays) = rays {
            side_by_side.push((
                format!("CPU reference, GGX ({} spp)", o.spp),
                reference.full(m.family()).to_rgb8(o.exposure),
            ));
            side_by_side.push((format!("CPU rays: {}", m.label()), rays));
            side_by_side.push((format!("{prefix}: {}", m.label()), rgb));
        }
        rows.push(row);
    }
    let zoom = if o.width <= 160 { 2 } else { 1 };
    let sheet = contact_sheet(&tiles, 5, zoom);
    save(&sheet, &o.out.join("contact_sheet.png")).map_err(|e| e.to_string())?;
    let figure = contact_sheet(&side_by_side, 3, zoom);
    save(&figure, &o.out.join("gpu_vs_cpu.png")).map_err(|e| e.to_string())?;
    Ok(Still {
        kind,
        rows,
        reference_error,
        same_quads,
        reference_s,
        visibility_time,
        timer: timer.method(),
    })
}

/// Peak luminance per frame of the temporal test, per series.
pub struct Temporal {
    pub width: u32,
    pub height: u32,
    pub spp: usize,
    pub reference: [Vec<f32>; 2],
    /// Per route: peaks of the GPU frames, of the CPU demo's frames with ray differentials
    /// and with the GPU route's filter inputs ([`cpu_route`]).
    pub routes: Vec<(Route, [Vec<f32>; 3])>,
    /// Per route (in `routes`' order): the GPU frames' flicker against the reference's.
    pub flicker: Vec<Flicker>,
    /// Per family: the reference sequence's flicker error against an independent sequence of
    /// four times the samples, over its flicker energy.
    pub reference_error: [f64; 2],
}

/// The temporal test (KHPL16 Fig. 12) on GPU frames: the CPU demo's camera dolly, frames at
/// half resolution, the peak luminance of each frame for every route, beside the CPU
/// reference's and the CPU demo's.
pub fn temporal(
    o: &Options,
    kind: SceneKind,
    gpu: &Gpu,
    renderer: &mut Renderer,
) -> Result<Temporal, String> {
    let (w, h) = (
        (o.width / DOWNSCALE).max(2).div_ceil(2) * 2,
        (o.height / DOWNSCALE).max(2).div_ceil(2) * 2,
    );
    let spp = (o.spp / SPP_DIVISOR).max(2);
    renderer.resize(gpu, w, h);
    let mut out = Temporal {
        width: w,
        height: h,
        spp,
        reference: [Vec::new(), Vec::new()],
        routes: routes(kind, &o.moments)
            .into_iter()
            .map(|r| (r, [Vec::new(), Vec::new(), Vec::new()]))
            .collect(),
        flicker: Vec::new(),
        reference_error: [0.0; 2],
    };
    let mut lums: Vec<Vec<Vec<f32>>> = vec![Vec::new(); out.routes.len()];
    let mut ref_lums = [Vec::new(), Vec::new()];
    let mut ref4_lums = [Vec::new(), Vec::new()];
    let bar = parallel::bar("temporal frames", o.frames);
    for f in 0..o.frames {
        let cam = camera_at(f, w as usize, h as usize);
        let scene = Scene::of(kind, cam.lod());
        renderer.begin_frame(gpu, &scene, &cam)?;
        let reference = render::reference(&scene, &cam, w as usize, h as usize, spp, o.seed, None);
        for (k, img) in reference.full.iter().enumerate() {
            out.reference[k].push(img.peak());
            ref_lums[k].push(display_luminance(img, o.exposure));
        }
        let reference_4n = render::reference(
            &scene,
            &cam,
            w as usize,
            h as usize,
            4 * spp,
            o.seed ^ render::SEED_4N,
            None,
        );
        for (k, img) in reference_4n.full.iter().enumerate() {
            ref4_lums[k].push(display_luminance(img, o.exposure));
        }
        let gb = render::gbuffer(&scene, &cam, w as usize, h as usize);
        let rays = gb.derivatives(&scene, FootprintRoute::RayDifferentials);
        let quad = gb.derivatives(&scene, FootprintRoute::Quad);
        let moments = out
            .routes
            .iter()
            .any(|&(r, _)| cpu_route(r) == FootprintRoute::Moments)
            .then(|| gb.derivatives(&scene, FootprintRoute::Moments));
        for (i, (route, [on_gpu, cpu_rays, cpu_same])) in out.routes.iter_mut().enumerate() {
            let img = Image::new(w as usize, h as usize, renderer.render(gpu, *route)?);
            on_gpu.push(img.peak());
            lums[i].push(display_luminance(&img, o.exposure));
            let m = cpu_method(*route);
            let inputs = match (cpu_route(*route), &moments) {
                (FootprintRoute::Moments, Some(d)) => d,
                _ => &quad,
            };
            cpu_rays.push(render::shade(&scene, &gb, &rays, m).peak());
            cpu_same.push(render::shade(&scene, &gb, inputs, m).peak());
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    let ref_energy = ref_lums.each_ref().map(|l| flicker_energy(l));
    out.reference_error =
        [0, 1].map(|k| flicker_error(&ref_lums[k], &ref4_lums[k]) / ref_energy[k]);
    out.flicker = out
        .routes
        .iter()
        .zip(&lums)
        .map(|((route, [peaks, _, _]), l)| {
            let k = cpu_method(*route).family() as usize;
            Flicker {
                error: flicker_error(l, &ref_lums[k]) / ref_energy[k],
                energy: flicker_energy(l) / ref_energy[k],
                peak_variation: variation(peaks),
            }
        })
        .collect();
    if o.frames >= 2 {
        let mut series = Vec::new();
        for (k, family) in [Family::Beckmann, Family::Ggx].iter().enumerate() {
            series.push(Series {
                label: format!("CPU reference, {}", family.name()),
                color: [[0, 0, 0], [110, 110, 110]][k],
                values: out.reference[k].clone(),
                dashed: true,
            });
        }
        for (i, (route, [peaks, _, _])) in out.routes.iter().enumerate() {
            let name = match route {
                Route::Forward(m) => format!("GPU fwd: {}", m.label()),
                Route::Moments(m) => format!("GPU moments: {}", m.label()),
                Route::Deferred(_) | Route::DeferredMoments(_) => continue,
            };
            series.push(Series {
                label: name,
                color: PALETTE[i % PALETTE.len()],
                values: peaks.clone(),
                dashed: false,
            });
        }
        let plot = line_plot(
            "Peak HDR luminance per frame (GPU forward and moments frames)",
            "peak luminance",
            &series,
            860,
            400,
        );
        save(&plot, &o.out.join("temporal.png")).map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// The largest difference allowed between a GPU frame and the CPU demo's frame with the same
/// filter inputs on the pixels both compute alike (the RMSE between them there, relative to
/// the CPU frame's RMSE against the reference there). Both evaluate the same formulas at the
/// same pixel centres (the quad routes on the same pairs of pixels): what remains is f32
/// rounding on two instruction sets and the GPU's own sine and exponential (the moments
/// route sums 36 pairs of waves' terms with them), which a glint at roughness 0.01 amplifies
/// (measured: see the table's "agreement" column).
const CHECK_TOLERANCE: f64 = 0.005;

/// The routes whose GPU frame is not a faithful fragment-shader version of the CPU demo's
/// frame with the same filter inputs ([`cpu_route`]): a non-finite value, or a difference on
/// the pixels both compute alike above [`CHECK_TOLERANCE`]. (Where a quad straddles an edge
/// the quad routes differ by design: the CPU takes the opposite neighbour, the GPU the
/// object's continuation.)
pub fn check(s: &Still) -> Vec<String> {
    s.rows
        .iter()
        .filter_map(|r| {
            let bad =
                !r.gpu_rmse.is_finite() || r.agreement.is_nan() || r.agreement > CHECK_TOLERANCE;
            bad.then(|| {
                format!(
                    "{} ({}): on the pixels both compute alike the GPU frame differs from the \
                     CPU frame with the same filter inputs by {:.3} % of the latter's RMSE \
                     (allowed {:.1} %)",
                    cpu_method(r.route).label(),
                    route_name(r.route),
                    100.0 * r.agreement,
                    100.0 * CHECK_TOLERANCE
                )
            })
        })
        .collect()
}

/// Row `i`'s GPU time relative to unfiltered GGX's on the same route ([`baseline`]).
fn relative_time(s: &Still, i: usize) -> f64 {
    let r = &s.rows[i];
    let base = s
        .rows
        .iter()
        .find(|b| b.route == baseline(r.route))
        .map_or(r.time, |b| b.time);
    r.time / base
}

/// Issue 51's cost bound: a route may cost at most this many times unfiltered GGX's GPU time.
const GOAL_COST: f64 = 1.5;

/// Issue 51's goal on one scene, from the measured rows: whether a method costing at most
/// [`GOAL_COST`] times unfiltered GGX's GPU time ([`relative_time`]) beats unfiltered on all
/// six metrics by more than the reference's error ([`metrics::missing`]); otherwise the
/// closest such method (fewest metrics short, then lowest FLIP LDR) within the cost and at
/// any cost.
fn goal_verdict(s: &Still, rows: &[LeadRow], references: &[LeadRow]) -> String {
    let candidates: Vec<(usize, Vec<&'static str>, f64)> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| !r.baseline)
        .filter_map(|(i, r)| {
            let m = metrics::missing(r, rows, references)?;
            Some((i, m, relative_time(s, i)))
        })
        .collect();
    let closest = |within: bool| {
        candidates
            .iter()
            .filter(|c| !within || c.2 <= GOAL_COST)
            .min_by(|a, b| {
                a.1.len().cmp(&b.1.len()).then(
                    rows[a.0]
                        .scores
                        .flip_ldr
                        .total_cmp(&rows[b.0].scores.flip_ldr),
                )
            })
    };
    let describe = |c: &(usize, Vec<&'static str>, f64)| {
        let short = if c.1.is_empty() {
            "on all six".to_string()
        } else {
            format!("all but {}", c.1.join(", "))
        };
        format!(
            "{} ({:.2}x unfiltered GGX's GPU time; beats unfiltered on {short})",
            rows[c.0].label, c.2
        )
    };
    let met: Vec<String> = candidates
        .iter()
        .filter(|c| c.1.is_empty() && c.2 <= GOAL_COST)
        .map(|c| format!("{} ({:.2}x)", rows[c.0].label, c.2))
        .collect();
    let goal = format!(
        "**Issue 51's goal** (at most {GOAL_COST}x unfiltered GGX's GPU time, beating unfiltered \
         on all six metrics by more than the reference's error)"
    );
    if !met.is_empty() {
        return format!("{goal}: **met** by {}.", met.join(", "));
    }
    match (closest(true), closest(false)) {
        (Some(a), Some(b)) if a.0 == b.0 => {
            format!("{goal}: not met; the closest: {}.", describe(a))
        }
        (Some(a), Some(b)) => format!(
            "{goal}: not met; the closest within the cost: {}; at any cost: {}.",
            describe(a),
            describe(b)
        ),
        (None, Some(b)) => format!(
            "{goal}: not met; nothing within the cost; the closest at any cost: {}.",
            describe(b)
        ),
        _ => format!("{goal}: not measured (no temporal test)."),
    }
}

/// A route's row label in the metric tables: the CPU demo's label for the method (`+
/// moments` on the moments route, as the CPU demo writes it) and the route.
fn row_label(route: Route) -> String {
    let m = cpu_method(route);
    match route {
        Route::Moments(_) => format!("{} + moments (forward)", m.label()),
        Route::DeferredMoments(_) => format!("{} + moments (deferred)", m.label()),
        _ => format!("{} ({})", m.label(), route_name(route)),
    }
}

/// The results as markdown.
pub fn markdown(o: &Options, gpu: &Gpu, compile_s: f64, s: &Still, t: &Temporal) -> String {
    let mut md = String::new();
    let software = gpu.is_software();
    // The water's sections keep their titles; the other scenes' name themselves.
    let title = match s.kind {
        SceneKind::Water => String::new(),
        k => {
            let name = k.name();
            format!("{}{}: ", name[..1].to_uppercase(), &name[1..])
        }
    };
    writeln!(
        md,
        "## {title}What a viewer sees: GPU frames ({}x{}, temporal test {} frames at {}x{})\n",
        o.width,
        o.height,
        t.reference[0].len(),
        t.width,
        t.height
    )
    .unwrap();
    writeln!(md, "The CPU demo's metrics (`filtered_ndf_demo::metrics`) on the GPU frames, against the CPU reference ({} spp still, {} spp temporal): FLIP LDR / HDR means (maps `flip-gpu-*.png`), flicker error and energy over the reference sequence's energy, the peak's frame-to-frame variation, the specular term's error (the GPU frame less the CPU quad frame's ambient, diffuse and sky), false glints (display > {} where the reference < {}) and lost highlights (the reverse), HDR RMSE; the verdict against unfiltered of the same NDF (forward).\n", o.spp, t.spp, metrics::BRIGHT, metrics::DARK).unwrap();
    let rows: Vec<LeadRow> = s
        .rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let m = cpu_method(r.route);
            LeadRow {
                label: row_label(r.route),
                ndf: m.family().name(),
                baseline: m == Method::Unfiltered(m.family()),
                scores: r.scores,
                flicker: t
                    .flicker
                    .get(i)
                    .copied()
                    .filter(|_| t.reference[0].len() >= 2),
            }
        })
        .collect();
    let temporal = t.reference[0].len() >= 2;
    let references: Vec<LeadRow> = [Family::Beckmann, Family::Ggx]
        .into_iter()
        .map(|f| LeadRow {
            label: format!(
                "{}, {}",
                metrics::reference_error_label(o.spp, temporal.then_some(t.spp)),
                f.name()
            ),
            ndf: f.name(),
            baseline: false,
            scores: s.reference_error[f as usize],
            flicker: temporal.then(|| Flicker {
                error: t.reference_error[f as usize],
                energy: f64::NAN,
                peak_variation: f64::NAN,
            }),
        })
        .collect();
    // Where each route stands: per route its best method, and the GPU time of the route's
    // methods relative to unfiltered GGX on the same route (their range).
    let group = |name: &str, keep: &dyn Fn(Route) -> bool| {
        let idx: Vec<usize> = (0..s.rows.len())
            .filter(|&i| keep(s.rows[i].route))
            .collect();
        let rel: Vec<f64> = idx.iter().map(|&i| relative_time(s, i)).collect();
        let (lo, hi) = rel
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        metrics::RouteGroup {
            name: name.to_string(),
            rows: idx,
            cost: format!("{lo:.2}-{hi:.2}x unfiltered GGX's GPU time"),
        }
    };
    let is_unfiltered = |r: Route| matches!(cpu_method(r), Method::Unfiltered(_));
    let groups = [
        group("unfiltered (forward and deferred)", &is_unfiltered),
        group(
            "forward, half-vector filters on quad derivatives",
            &|r| matches!(r, Route::Forward(m) if m.uses_footprint()),
        ),
        group("forward, TK19's isotropic kernels", &|r| {
            matches!(r, Route::Forward(m) if !m.uses_footprint()) && !is_unfiltered(r)
        }),
        group("deferred conventions", &|r| {
            matches!(r, Route::Deferred(Some(_)))
        }),
        group(
            "forward, windowed slope moments on the water (ray differentials on the spheres)",
            &|r| matches!(r, Route::Moments(_)),
        ),
        group(
            "deferred, windowed slope moments in the G-buffer, kernel per light",
            &|r| matches!(r, Route::DeferredMoments(_)),
        ),
    ];
    writeln!(
        md,
        "### {title}Where each route stands on the GPU\n\n{}\n{}\n\n### {title}Every route on the GPU\n",
        metrics::standing_table(&groups, &rows, &references),
        goal_verdict(s, &rows, &references)
    )
    .unwrap();
    md.push_str(&metrics::lead_table_with(&rows, &references));
    writeln!(md).unwrap();
    writeln!(
        md,
        "## {title}GPU frames against the CPU reference ({}x{}, 1 shading sample per pixel, quad derivatives; the moments route on the water)\n",
        o.width, o.height
    )
    .unwrap();
    writeln!(
        md,
        "Adapter: {}. Reference: the CPU demo's, {} spp with its Gaussian pixel filter ({:.1} s). \
         RMSE in linear HDR radiance; luminance and peak ratios against the reference; \
         \"CPU rays\" is the CPU demo's frame (ray differentials + M, its default), \"CPU same\" \
         the CPU demo's frame with the GPU route's filter inputs: its own 2x2-quad differences \
         for the forward and deferred routes, its moments route (windowed slope moments on the \
         water, ray differentials on the spheres) for the moments route; \"GPU vs CPU same\" is \
         the RMSE between the GPU frame and that CPU frame; \"agreement\" is that RMSE over the \
         pixels both compute alike, relative to the CPU frame's RMSE there: for the quad routes \
         the {:.1} % of pixels that the CPU differences with their own quad partners, as the \
         GPU does (elsewhere a quad straddles an edge: the CPU takes the opposite neighbour, \
         the GPU the object's continuation), for the moments route every pixel (it differences \
         no neighbour).\n",
        gpu.label(),
        o.spp,
        s.reference_s,
        100.0 * s.same_quads
    )
    .unwrap();
    writeln!(
        md,
        "| method | route | RMSE GPU | RMSE CPU rays | GPU / CPU rays | within 10 % | RMSE CPU same | GPU / CPU same | GPU vs CPU same | agreement | mean lum. GPU | mean lum. CPU rays | peak GPU | peak CPU rays |"
    )
    .unwrap();
    writeln!(
        md,
        "|---|---|---:|---:|---:|:-:|---:|---:|---:|---:|---:|---:|---:|---:|"
    )
    .unwrap();
    for r in &s.rows {
        let ratio = r.gpu_rmse / r.cpu_rays_rmse;
        writeln!(
            md,
            "| {} | {} | {:.4} | {:.4} | {:.3} | {} | {:.4} | {:.3} | {:.4} | {:.3}% | {:.3} | {:.3} | {:.3} | {:.3} |",
            cpu_method(r.route).label(),
            route_name(r.route),
            r.gpu_rmse,
            r.cpu_rays_rmse,
            ratio,
            if (ratio - 1.0).abs() <= 0.1 { "yes" } else { "no" },
            r.cpu_same_rmse,
            r.gpu_rmse / r.cpu_same_rmse,
            r.gpu_vs_cpu_same,
            100.0 * r.agreement,
            r.gpu_mean,
            r.cpu_rays_mean,
            r.gpu_peak,
            r.cpu_rays_peak,
        )
        .unwrap();
    }

    writeln!(md, "\n## {title}GPU time per method\n").unwrap();
    writeln!(
        md,
        "{}: {}. Each route's passes (forward: one pass of six draws; deferred: the G-buffer \
         pass and the lighting pass), median of {} runs, relative to unfiltered GGX in the same \
         shading (forward or deferred); the visibility pass that every route reads ({:.3} ms) is \
         not included, but the frame (the visibility pass and the route's passes, relative to \
         the same of unfiltered GGX) includes it. Pipelines compiled in {:.1} s.{}\n",
        gpu.label(),
        s.timer,
        o.repeats,
        s.visibility_time * 1e3,
        compile_s,
        match (software, gpu.info.backend) {
            (true, wgpu::Backend::Vulkan) => {
                " **A software rasteriser, and on lavapipe not even the ratios count**: its \
                 times are mostly the driver's own per-draw work on the submitting thread, \
                 which differs between pipelines whatever their arithmetic (profiled in \
                 docs/gpu_moments.md); the GL run (llvmpipe, the same rasteriser without \
                 lavapipe) times the shaders."
            }
            (true, _) => {
                " **A software rasteriser: only the ratios count**, not the milliseconds (and \
                 its ratios weigh arithmetic as a CPU does, not as a GPU's wide ALUs and \
                 special-function units do)."
            }
            _ => "",
        }
    )
    .unwrap();
    writeln!(
        md,
        "| method | route | ms | relative to unfiltered | frame, relative to unfiltered |"
    )
    .unwrap();
    writeln!(md, "|---|---|---:|---:|---:|").unwrap();
    for r in &s.rows {
        let base = s
            .rows
            .iter()
            .find(|b| b.route == baseline(r.route))
            .map_or(r.time, |b| b.time);
        let vis = s.visibility_time;
        writeln!(
            md,
            "| {} | {} | {:.3} | {:.2} | {:.2} |",
            cpu_method(r.route).label(),
            route_name(r.route),
            r.time * 1e3,
            r.time / base,
            (vis + r.time) / (vis + base)
        )
        .unwrap();
    }

    if !t.reference[0].is_empty() {
        writeln!(
            md,
            "\n## {title}Temporal test on GPU frames ({} frames, {}x{}, reference {} spp)\n",
            t.reference[0].len(),
            t.width,
            t.height,
            t.spp
        )
        .unwrap();
        writeln!(md, "The CPU demo's camera dolly. Peak HDR luminance per frame: mean, mean frame-to-frame change |P(t) - P(t-1)| / mean P (variation), and mean distance |P(t) - P_ref(t)| / mean P_ref, for the GPU frames and the CPU demo's, with its ray differentials and with the GPU route's filter inputs (\"CPU same\": its own quad differences, or its moments route).\n").unwrap();
        writeln!(md, "| method | route | mean peak GPU | variation GPU | distance GPU | variation CPU same | distance CPU same | variation CPU rays | distance CPU rays |").unwrap();
        writeln!(md, "|---|---|---:|---:|---:|---:|---:|---:|---:|").unwrap();
        for (k, name) in ["CPU reference, Beckmann", "CPU reference, GGX"]
            .iter()
            .enumerate()
        {
            let p = &t.reference[k];
            writeln!(
                md,
                "| {name} | - | {:.1} | {:.1}% | - | - | - | - | - |",
                mean(p),
                100.0 * variation(p)
            )
            .unwrap();
        }
        for (route, [g, rays, quad]) in &t.routes {
            let m = cpu_method(*route);
            let r = &t.reference[m.family() as usize];
            writeln!(
                md,
                "| {} | {} | {:.1} | {:.1}% | {:.1}% | {:.1}% | {:.1}% | {:.1}% | {:.1}% |",
                m.label(),
                route_name(*route),
                mean(g),
                100.0 * variation(g),
                100.0 * distance(g, r),
                100.0 * variation(quad),
                100.0 * distance(quad, r),
                100.0 * variation(rays),
                100.0 * distance(rays, r)
            )
            .unwrap();
        }
    }
    md
}
