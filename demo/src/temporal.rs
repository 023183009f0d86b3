//! The temporal test: the camera dollies over N frames; per method, the flicker energy of
//! the display luminance relative to the reference sequence's ([`metrics::flicker_energy`]),
//! and (KHPL16 Fig. 12) the peak HDR intensity of each frame, its frame-to-frame variation and
//! its distance to the reference's peak.

use crate::camera::camera_at;
use crate::methods::Method;
use crate::metrics::{display_luminance, flicker_energy, flicker_error};
use crate::options::Options;
use crate::peaks::{distance, mean, variation};
use crate::plot::{PALETTE, Series, line_plot};
use crate::render;
use crate::render::FootprintRoute;
use crate::scene::{Scene, SceneKind};
use std::fmt::Write as _;

/// Resolution divisor and reference sample divisor of the temporal frames (keeps the default
/// run short; the peaks are compared at the same resolution for every method).
const DOWNSCALE: usize = 2;
pub const SPP_DIVISOR: usize = 4;

/// What the temporal test measured, per (method, footprint route) of `methods` (in order).
pub struct Temporal {
    pub methods: Vec<(Method, FootprintRoute)>,
    /// Flicker energy divided by the reference's (same family).
    pub flicker: Vec<f64>,
    /// Flicker error ([`flicker_error`]) divided by the reference's flicker energy.
    pub flicker_error: Vec<f64>,
    /// Frame-to-frame variation of the peak.
    pub peak_variation: Vec<f64>,
    /// Per family (Beckmann, GGX): the reference sequence's own flicker error, against an
    /// independent sequence of four times the samples, over its flicker energy (the margin
    /// of the verdict, [`crate::metrics::not_better_by`]).
    pub reference_error: [f64; 2],
    /// The reference sequence's samples per pixel.
    pub spp: usize,
    pub markdown: String,
}

/// Runs the test on the scene `kind`: `o.methods`, then `extra` (the engine presets: their
/// flicker only), on `o.route`, then `fixed` on each route of the false-glint fix
/// ([`crate::options::FIX_ROUTES`]).
pub fn run(
    o: &Options,
    kind: SceneKind,
    extra: &[Method],
    fixed: &[Method],
) -> std::io::Result<Temporal> {
    let (w, h) = ((o.width / DOWNSCALE).max(2), (o.height / DOWNSCALE).max(2));
    let spp = (o.spp / SPP_DIVISOR).max(2);
    let all: Vec<(Method, FootprintRoute)> = o
        .methods
        .iter()
        .chain(extra)
        .map(|&m| (m, o.route))
        .chain(
            crate::options::FIX_ROUTES
                .into_iter()
                .flat_map(|r| fixed.iter().map(move |&m| (m, r))),
        )
        .collect();
    let mut peaks = vec![Vec::new(); all.len()];
    let mut lums = vec![Vec::new(); all.len()];
    let mut ref_peaks = [Vec::new(), Vec::new()];
    let mut ref_lums = [Vec::new(), Vec::new()];
    let mut ref4_lums = [Vec::new(), Vec::new()];
    let bar = crate::parallel::bar("temporal frames", o.frames);
    for f in 0..o.frames {
        let cam = camera_at(f, w, h);
        let scene = &Scene::of(kind, cam.lod());
        let reference = render::reference(scene, &cam, w, h, spp, o.seed, None);
        for (k, img) in reference.full.iter().enumerate() {
            ref_peaks[k].push(img.peak());
            ref_lums[k].push(display_luminance(img, o.exposure));
        }
        let reference_4n =
            render::reference(scene, &cam, w, h, 4 * spp, o.seed ^ render::SEED_4N, None);
        for (k, img) in reference_4n.full.iter().enumerate() {
            ref4_lums[k].push(display_luminance(img, o.exposure));
        }
        let gb = render::gbuffer(scene, &cam, w, h);
        let derivs = gb.derivatives(scene, o.route);
        let fix: Vec<(FootprintRoute, Vec<render::Mixture>)> = crate::options::FIX_ROUTES
            .into_iter()
            .filter(|&r| !fixed.is_empty() && r != o.route)
            .map(|r| (r, gb.mixtures(scene, r)))
            .collect();
        for (i, &(m, route)) in all.iter().enumerate() {
            let img = match fix
                .iter()
                .find(|(r, _)| *r == route && i >= o.methods.len())
            {
                Some((_, mix)) => render::shade_mixture(scene, &gb, mix, m).total,
                None => render::shade(scene, &gb, &derivs, m),
            };
            peaks[i].push(img.peak());
            lums[i].push(display_luminance(&img, o.exposure));
        }
        bar.inc(1);
    }
    bar.finish_and_clear();

    let mut md = String::new();
    writeln!(
        md,
        "\n## Temporal test ({} frames, {}x{}, reference {} spp)\n",
        o.frames, w, h, spp
    )
    .unwrap();
    writeln!(md, "Flicker energy: the mean over pixels and frame pairs of the squared change of display luminance, (Y_t - Y_t-1)^2, divided by the reference sequence's (1 = as much change as the reference; the camera moves, so the reference changes too). Flicker error: the mean of ((Y_t - Y_t-1) - (R_t - R_t-1))^2, the changes the reference R does not make, divided by the same reference energy (0 = changes exactly as the reference). Peak HDR luminance per frame (KHPL16 Fig. 12): mean, mean frame-to-frame change |P(t) - P(t-1)| / mean P, and mean distance |P(t) - P_ref(t)| / mean P_ref.\n").unwrap();
    writeln!(
        md,
        "| method | flicker energy / reference | flicker error / reference | mean peak | peak frame-to-frame variation | peak distance to reference |"
    )
    .unwrap();
    writeln!(md, "|---|---:|---:|---:|---:|---:|").unwrap();
    let reference_flicker = [flicker_energy(&ref_lums[0]), flicker_energy(&ref_lums[1])];
    let reference_error =
        [0, 1].map(|k| flicker_error(&ref_lums[k], &ref4_lums[k]) / reference_flicker[k]);
    let mut series = Vec::new();
    for (k, name) in ["Reference Beckmann", "Reference GGX"].iter().enumerate() {
        let p = &ref_peaks[k];
        writeln!(
            md,
            "| {name} | 1 ({:.2e}) | 0 | {:.1} | {:.1}% | - |",
            reference_flicker[k],
            mean(p),
            100.0 * variation(p)
        )
        .unwrap();
        writeln!(
            md,
            "| {name}, {} spp vs {} spp | {:.2} | {:.2} | - | - | - |",
            spp,
            4 * spp,
            flicker_energy(&ref4_lums[k]) / reference_flicker[k],
            reference_error[k]
        )
        .unwrap();
        series.push(Series {
            label: name.to_string(),
            color: [[0, 0, 0], [110, 110, 110]][k],
            values: p.clone(),
            dashed: true,
        });
    }
    let (mut flicker, mut peak_variation) = (vec![], vec![]);
    let mut flicker_err = vec![];
    for (i, &(m, route)) in all.iter().enumerate() {
        let p = &peaks[i];
        let r = &ref_peaks[m.family() as usize];
        let fam = m.family() as usize;
        flicker.push(flicker_energy(&lums[i]) / reference_flicker[fam]);
        flicker_err.push(flicker_error(&lums[i], &ref_lums[fam]) / reference_flicker[fam]);
        peak_variation.push(variation(p));
        writeln!(
            md,
            "| {} | {:.2} | {:.2} | {:.1} | {:.1}% | {:.1}% |",
            variant_label(m, route),
            flicker[i],
            flicker_err[i],
            mean(p),
            100.0 * variation(p),
            100.0 * distance(p, r)
        )
        .unwrap();
        let fix_route = crate::options::FIX_ROUTES.contains(&route) && route != o.route;
        if i >= o.methods.len() && !fix_route {
            continue;
        }
        series.push(Series {
            label: variant_label(m, route),
            color: PALETTE[index_of(m) % PALETTE.len()],
            values: p.clone(),
            dashed: fix_route,
        });
    }
    let plot = line_plot(
        "Peak HDR luminance per frame",
        "peak luminance",
        &series,
        820,
        400,
    );
    let path = o.out.join("temporal.png");
    crate::image_out::save(&plot, &path)?;
    writeln!(md, "\nPlot: {}", path.display()).unwrap();
    Ok(Temporal {
        methods: all,
        flicker,
        flicker_error: flicker_err,
        peak_variation,
        reference_error,
        spp,
        markdown: md,
    })
}

/// A method's label, with the footprint route when it is one of the false-glint fix's.
pub fn variant_label(m: Method, route: FootprintRoute) -> String {
    match route {
        FootprintRoute::Moments if m.uses_footprint() => format!("{} + moments", m.label()),
        FootprintRoute::SubWindows if m.uses_footprint() => {
            format!("{} + sub-windows", m.label())
        }
        FootprintRoute::SubFootprints if m.uses_footprint() => {
            format!("{} + 2x2 sub-footprints", m.label())
        }
        FootprintRoute::KurtosisSplit if m.uses_footprint() => {
            format!("{} + kurtosis split", m.label())
        }
        _ => m.label().to_string(),
    }
}

fn index_of(m: Method) -> usize {
    Method::ALL.iter().position(|&x| x == m).unwrap_or(0)
}
