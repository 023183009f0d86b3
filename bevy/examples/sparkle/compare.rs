//! The comparison: each method's frames against the supersampled reference's, with the
//! demonstration's metrics (`filtered_ndf_demo::metrics`: FLIP LDR and HDR, flicker over the
//! camera move, false glints, lost highlights), as a markdown table.

use filtered_ndf_demo::image_out::Image;
use filtered_ndf_demo::metrics;
use std::fmt::Write as _;

/// One method's scores over the frames of the move.
#[derive(Clone, Debug)]
pub struct Row {
    /// The method.
    pub label: String,
    /// Mean LDR-FLIP over the frames.
    pub flip_ldr: f64,
    /// Mean HDR-FLIP over the frames.
    pub flip_hdr: f64,
    /// Flicker error over the reference's flicker energy (`metrics::flicker_error`).
    pub flicker_error: f64,
    /// Flicker energy over the reference's.
    pub flicker_energy: f64,
    /// False glints summed over the frames.
    pub false_glints: usize,
    /// Lost highlights summed over the frames.
    pub lost_highlights: usize,
    /// Mean RMSE of linear radiance over the frames.
    pub rmse_hdr: f64,
}

/// The scores of `frames` against `reference` (the same number of frames, the same size),
/// displayed at `exposure` for the LDR metrics.
pub fn evaluate(label: &str, frames: &[Image], reference: &[Image], exposure: f32) -> Row {
    let n = frames.len().max(1) as f64;
    let (mut flip_ldr, mut flip_hdr, mut rmse) = (0.0, 0.0, 0.0);
    let (mut false_glints, mut lost_highlights) = (0, 0);
    let mut lum = Vec::new();
    let mut ref_lum = Vec::new();
    for (f, r) in frames.iter().zip(reference) {
        flip_ldr += metrics::flip_ldr(f, r, exposure).mean() / n;
        flip_hdr += metrics::flip_hdr(f, r).mean() / n;
        rmse += f.rmse(r) / n;
        let (y, yr) = (
            metrics::display_luminance(f, exposure),
            metrics::display_luminance(r, exposure),
        );
        let (g, l) = metrics::glint_counts(&y, &yr);
        false_glints += g;
        lost_highlights += l;
        lum.push(y);
        ref_lum.push(yr);
    }
    let energy = metrics::flicker_energy(&ref_lum);
    Row {
        label: label.to_string(),
        flip_ldr,
        flip_hdr,
        flicker_error: metrics::flicker_error(&lum, &ref_lum) / energy,
        flicker_energy: metrics::flicker_energy(&lum) / energy,
        false_glints,
        lost_highlights,
        rmse_hdr: rmse,
    }
}

/// The metrics a viewer sees on which `row` is not better than `base`: FLIP LDR, FLIP HDR
/// and flicker error strictly lower; false glints and lost highlights fewer, or both none.
pub fn not_better(row: &Row, base: &Row) -> Vec<&'static str> {
    let mut out = Vec::new();
    if row.flip_ldr >= base.flip_ldr {
        out.push("FLIP LDR");
    }
    if row.flip_hdr >= base.flip_hdr {
        out.push("FLIP HDR");
    }
    if row.flicker_error >= base.flicker_error {
        out.push("flicker");
    }
    let fewer = |a: usize, b: usize| a < b || (a == 0 && b == 0);
    if !fewer(row.false_glints, base.false_glints) {
        out.push("false glints");
    }
    if !fewer(row.lost_highlights, base.lost_highlights) {
        out.push("lost highlights");
    }
    out
}

/// The markdown table of `rows` (the first is the baseline, unfiltered Bevy), and below a
/// rule the rows that are not methods (`extra`: the reference's own error).
pub fn table(rows: &[Row], extra: &[Row]) -> String {
    let mut t = String::new();
    t.push_str("| method | FLIP LDR | FLIP HDR | flicker error / ref. | flicker energy / ref. | false glints | lost highlights | RMSE (HDR) | against unfiltered |\n");
    t.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
    let base = rows.first();
    for (i, r) in rows.iter().chain(extra).enumerate() {
        let verdict = match base {
            _ if i == 0 => "(baseline)".to_string(),
            _ if i >= rows.len() => "(reference check)".to_string(),
            Some(b) => {
                let missing = not_better(r, b);
                if missing.is_empty() {
                    "**better on all**".to_string()
                } else {
                    format!("not: {}", missing.join(", "))
                }
            }
            None => String::new(),
        };
        writeln!(
            t,
            "| {} | {:.4} | {:.4} | {:.3} | {:.3} | {} | {} | {:.4} | {} |",
            r.label,
            r.flip_ldr,
            r.flip_hdr,
            r.flicker_error,
            r.flicker_energy,
            r.false_glints,
            r.lost_highlights,
            r.rmse_hdr,
            verdict
        )
        .expect("writing to a String");
    }
    t
}
