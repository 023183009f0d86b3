//! The temporal test (KHPL16 Fig. 12): the camera dollies over N frames; per method, the
//! peak HDR intensity of each frame, its frame-to-frame variation and its distance to the
//! reference's peak.

use crate::camera::camera_at;
use crate::methods::Method;
use crate::peaks::{distance, mean, variation};
use crate::plot::{PALETTE, Series, line_plot};
use crate::scene::Scene;
use crate::{Options, render};
use std::fmt::Write as _;

/// Resolution divisor and reference sample divisor of the temporal frames (keeps the default
/// run short; the peaks are compared at the same resolution for every method).
const DOWNSCALE: usize = 2;
const SPP_DIVISOR: usize = 8;

pub fn run(o: &Options) -> std::io::Result<String> {
    let (w, h) = ((o.width / DOWNSCALE).max(2), (o.height / DOWNSCALE).max(2));
    let spp = (o.spp / SPP_DIVISOR).max(2);
    let mut peaks = vec![Vec::new(); o.methods.len()];
    let mut ref_peaks = [Vec::new(), Vec::new()];
    let bar = crate::parallel::bar("temporal frames", o.frames);
    for f in 0..o.frames {
        let cam = camera_at(f, w, h);
        let scene = &Scene::new(cam.lod());
        let reference = render::reference(scene, &cam, w, h, spp, o.seed, None);
        for (k, img) in reference.full.iter().enumerate() {
            ref_peaks[k].push(img.peak());
        }
        let gb = render::gbuffer(scene, &cam, w, h);
        let derivs = gb.derivatives(o.route);
        for (i, &m) in o.methods.iter().enumerate() {
            peaks[i].push(render::shade(scene, &gb, &derivs, m).peak());
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
    writeln!(md, "Peak HDR luminance per frame: mean, mean frame-to-frame change |P(t) - P(t-1)| / mean P, and mean distance |P(t) - P_ref(t)| / mean P_ref.\n").unwrap();
    writeln!(
        md,
        "| method | mean peak | frame-to-frame variation | distance to reference |"
    )
    .unwrap();
    writeln!(md, "|---|---:|---:|---:|").unwrap();
    let mut series = Vec::new();
    for (k, name) in ["Reference Beckmann", "Reference GGX"].iter().enumerate() {
        let p = &ref_peaks[k];
        writeln!(
            md,
            "| {name} | {:.1} | {:.1}% | - |",
            mean(p),
            100.0 * variation(p)
        )
        .unwrap();
        series.push(Series {
            label: name.to_string(),
            color: [[0, 0, 0], [110, 110, 110]][k],
            values: p.clone(),
            dashed: true,
        });
    }
    for (i, &m) in o.methods.iter().enumerate() {
        let p = &peaks[i];
        let r = &ref_peaks[m.family() as usize];
        writeln!(
            md,
            "| {} | {:.1} | {:.1}% | {:.1}% |",
            m.label(),
            mean(p),
            100.0 * variation(p),
            100.0 * distance(p, r)
        )
        .unwrap();
        series.push(Series {
            label: m.label().to_string(),
            color: PALETTE[index_of(m) % PALETTE.len()],
            values: p.clone(),
            dashed: false,
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
    Ok(md)
}

fn index_of(m: Method) -> usize {
    Method::ALL.iter().position(|&x| x == m).unwrap_or(0)
}
