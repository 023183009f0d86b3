//! What a viewer and a rendering researcher measure (issue 21), shared by the CPU and GPU
//! demonstrations:
//!
//! - **FLIP** (Andersson et al. 2020), NVIDIA's reference C++ implementation through the
//!   `nv-flip` crate: LDR-FLIP of the displayed images (this demo's display transform, then
//!   8-bit sRGB), and HDR-FLIP (Andersson et al. 2021): the per-pixel maximum of LDR-FLIP over
//!   the exposures the reference needs (ACES tone curve, start exposure from the reference's
//!   brightest pixel, stop exposure from its median, one exposure per stop), built here on
//!   the LDR routine, since the crate wraps only that one. 67 pixels per degree (a 0.7 m wide
//!   4K monitor seen from 0.7 m), FLIP's default.
//! - **Flicker energy**: the mean over pixels and frame pairs of the squared frame-to-frame
//!   change of display luminance, divided by the reference sequence's.
//! - **Specular error**: RMSE of the specular term alone, tone mapped (display units).
//! - **False glints / lost highlights**: counts of pixels bright in the frame (display
//!   luminance > 0.8) where the reference is dark (< 0.3), and the reverse.

use crate::image_out::{Image, encode, luminance, tonemap};
use glam::Vec3;

/// FLIP's default pixels per degree: a 0.7 m wide 3840-pixel monitor at 0.7 m.
pub const PIXELS_PER_DEGREE: f32 = 67.0;

/// Display luminance above which a pixel counts as bright: strictly above, so a pixel at
/// exactly `BRIGHT` is not bright (and `BRIGHT.next_up()` is).
pub const BRIGHT: f32 = 0.8;
/// Display luminance below which a pixel counts as dark: strictly below, so a pixel at
/// exactly `DARK` is not dark (and `DARK.next_down()` is).
pub const DARK: f32 = 0.3;

/// A FLIP error map (per pixel, in `[0, 1]`) and its mean.
pub struct FlipMap {
    pub width: usize,
    pub height: usize,
    pub values: Vec<f32>,
}

impl FlipMap {
    /// The mean error (FLIP's single number).
    pub fn mean(&self) -> f64 {
        self.values.iter().map(|&v| v as f64).sum::<f64>() / self.values.len().max(1) as f64
    }

    /// The map through FLIP's magma colour map (8-bit sRGB).
    pub fn to_rgb8(&self) -> crate::image_out::Rgb8 {
        let map =
            nv_flip::FlipImageFloat::with_data(self.width as u32, self.height as u32, &self.values);
        let rgb = map.apply_color_lut(&nv_flip::magma_lut());
        image::RgbImage::from_raw(rgb.width(), rgb.height(), rgb.to_vec())
            .expect("FLIP's colour map has the map's size")
    }
}

/// 8-bit sRGB bytes of linear display values in `[0, 1]`.
fn srgb8(width: usize, height: usize, display: impl Iterator<Item = Vec3>) -> Vec<u8> {
    let bytes: Vec<u8> = display
        .flat_map(|c| [encode(c.x), encode(c.y), encode(c.z)])
        .collect();
    assert_eq!(bytes.len(), 3 * width * height);
    bytes
}

/// LDR-FLIP between two 8-bit sRGB images.
fn ldr_flip_bytes(width: usize, height: usize, test: &[u8], reference: &[u8]) -> Vec<f32> {
    let (w, h) = (width as u32, height as u32);
    let r = nv_flip::FlipImageRgb8::with_data(w, h, reference);
    let t = nv_flip::FlipImageRgb8::with_data(w, h, test);
    nv_flip::flip(r, t, PIXELS_PER_DEGREE).to_vec()
}

/// LDR-FLIP of `test` against `reference` as this demonstration displays them (exposure,
/// per-channel Reinhard, sRGB: [`tonemap`]).
pub fn flip_ldr(test: &Image, reference: &Image, exposure: f32) -> FlipMap {
    let bytes = |img: &Image| {
        srgb8(
            img.width,
            img.height,
            img.data.iter().map(|&c| tonemap(c, exposure)),
        )
    };
    FlipMap {
        width: test.width,
        height: test.height,
        values: ldr_flip_bytes(test.width, test.height, &bytes(test), &bytes(reference)),
    }
}

/// Narkowicz's fit of the ACES curve with FLIP's 0.6 pre-exposure folded in:
/// `(k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5)`.
const ACES: [f32; 6] = [
    0.6 * 0.6 * 2.51,
    0.6 * 0.03,
    0.0,
    0.6 * 0.6 * 2.43,
    0.6 * 0.59,
    0.14,
];

/// The ACES curve of HDR-FLIP, clamped to `[0, 1]`.
pub fn aces(x: f32) -> f32 {
    let [k0, k1, k2, k3, k4, k5] = ACES;
    ((x * (k0 * x + k1) + k2) / (x * (k3 * x + k4) + k5)).clamp(0.0, 1.0)
}

/// The input the ACES curve maps to `t` (the positive root of `(k0 - k3 t) x^2 + (k1 - k4
/// t) x + (k2 - k5 t) = 0`).
pub fn aces_inverse(t: f32) -> f32 {
    let [k0, k1, k2, k3, k4, k5] = ACES.map(f64::from);
    let t = t as f64;
    let (a, b, c) = (k0 - k3 * t, k1 - k4 * t, k2 - k5 * t);
    ((-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)).max(0.0) as f32
}

/// HDR-FLIP's exposures for `reference` (log2 scale factors): from the one that maps the
/// brightest luminance to 0.85 through the ACES curve, to the one that maps the median
/// luminance to 0.85, `max(2, ceil(stop - start))` of them, evenly spaced.
pub fn hdr_exposures(reference: &Image) -> Vec<f32> {
    let mut y: Vec<f32> = reference.data.iter().map(|&c| luminance(c)).collect();
    y.sort_by(f32::total_cmp);
    let (median, max) = (y[y.len() / 2], *y.last().unwrap_or(&0.0));
    if max <= 0.0 || median <= 0.0 {
        return vec![0.0];
    }
    let x = aces_inverse(0.85);
    let (start, stop) = ((x / max).log2(), (x / median).log2());
    let n = ((stop - start).ceil() as usize).max(2);
    (0..n)
        .map(|i| start + i as f32 * (stop - start) / (n - 1) as f32)
        .collect()
}

/// HDR-FLIP of `test` against `reference` (linear HDR radiance): the per-pixel maximum of
/// LDR-FLIP over [`hdr_exposures`], each exposure tone mapped by [`aces`] per channel and
/// encoded as 8-bit sRGB (the reference implementation keeps floats there; the 8-bit step is
/// the wrapper's input format).
pub fn flip_hdr(test: &Image, reference: &Image) -> FlipMap {
    let (w, h) = (test.width, test.height);
    let mut values = vec![0.0f32; w * h];
    for e in hdr_exposures(reference) {
        let scale = e.exp2();
        let bytes = |img: &Image| {
            srgb8(
                w,
                h,
                img.data
                    .iter()
                    .map(|&c| (c.max(Vec3::ZERO) * scale).map(aces)),
            )
        };
        let map = ldr_flip_bytes(w, h, &bytes(test), &bytes(reference));
        for (v, m) in values.iter_mut().zip(map) {
            *v = v.max(m);
        }
    }
    FlipMap {
        width: w,
        height: h,
        values,
    }
}

/// Display luminance per pixel: Rec. 709 luminance of the tone-mapped display values.
pub fn display_luminance(img: &Image, exposure: f32) -> Vec<f32> {
    img.data
        .iter()
        .map(|&c| luminance(tonemap(c, exposure)))
        .collect()
}

/// Pixels bright in `test` and dark in `reference` ([`BRIGHT`], [`DARK`], display
/// luminance; both comparisons strict, so a pixel exactly at a threshold is neither bright nor
/// dark), and the reverse: `(false glints, lost highlights)` as masks.
pub fn glint_masks(test: &[f32], reference: &[f32]) -> (Vec<bool>, Vec<bool>) {
    test.iter()
        .zip(reference)
        .map(|(&t, &r)| (t > BRIGHT && r < DARK, r > BRIGHT && t < DARK))
        .unzip()
}

/// `(false glints, lost highlights)` as counts (see [`glint_masks`]).
pub fn glint_counts(test: &[f32], reference: &[f32]) -> (usize, usize) {
    let (f, l) = glint_masks(test, reference);
    let count = |m: Vec<bool>| m.into_iter().filter(|&b| b).count();
    (count(f), count(l))
}

/// RMSE of the tone-mapped specular terms (display units, over all pixels and channels).
pub fn specular_error(test: &Image, reference: &Image, exposure: f32) -> f64 {
    test.rmse_display(reference, exposure)
}

/// Flicker energy of a sequence of display-luminance frames: the mean over pixels and frame
/// pairs of `(Y_t - Y_{t-1})^2` (0 for fewer than two frames).
pub fn flicker_energy(frames: &[Vec<f32>]) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for pair in frames.windows(2) {
        for (a, b) in pair[0].iter().zip(&pair[1]) {
            sum += ((b - a) as f64).powi(2);
            n += 1;
        }
    }
    sum / n.max(1) as f64
}

/// Flicker error of a sequence against the reference sequence: the mean over pixels and frame
/// pairs of `((Y_t - Y_{t-1}) - (R_t - R_{t-1}))^2`, the energy of the frame-to-frame changes
/// the reference does not make (0 for fewer than two frames). Unlike [`flicker_energy`], a
/// sequence that changes as much as the reference but in other pixels scores badly.
pub fn flicker_error(frames: &[Vec<f32>], reference: &[Vec<f32>]) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (pair, rpair) in frames.windows(2).zip(reference.windows(2)) {
        for ((a, b), (ra, rb)) in pair[0]
            .iter()
            .zip(&pair[1])
            .zip(rpair[0].iter().zip(&rpair[1]))
        {
            sum += ((b - a) as f64 - (rb - ra) as f64).powi(2);
            n += 1;
        }
    }
    sum / n.max(1) as f64
}

/// The still-frame scores of one method against the reference.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scores {
    pub flip_ldr: f64,
    pub flip_hdr: f64,
    pub specular: f64,
    pub false_glints: usize,
    pub lost_highlights: usize,
    pub rmse_hdr: f64,
}

/// Every still-frame score of `test` (frame and specular term) against the reference, and the
/// LDR-FLIP map.
pub fn score(
    test: (&Image, &Image),
    reference: (&Image, &Image),
    exposure: f32,
) -> (Scores, FlipMap) {
    let ldr = flip_ldr(test.0, reference.0, exposure);
    let (false_glints, lost_highlights) = glint_counts(
        &display_luminance(test.0, exposure),
        &display_luminance(reference.0, exposure),
    );
    let s = Scores {
        flip_ldr: ldr.mean(),
        flip_hdr: flip_hdr(test.0, reference.0).mean(),
        specular: specular_error(test.1, reference.1, exposure),
        false_glints,
        lost_highlights,
        rmse_hdr: test.0.rmse(reference.0),
    };
    (s, ldr)
}

/// The metrics a method must beat unfiltered on (issue 21): FLIP LDR and HDR, flicker,
/// specular error, false glints, lost highlights. Lower is better for each; the flicker is
/// compared as the flicker error over the reference's flicker energy ([`flicker_error`]):
/// the energy ratio alone cannot tell a sequence that changes where the reference does from
/// one that changes as much elsewhere.
/// Returns the names of the metrics on which `m` does not beat `base` (strictly better, or
/// both counts zero): [`not_better_by`] with no reference error.
pub fn not_better(m: (&Scores, f64), base: (&Scores, f64)) -> Vec<&'static str> {
    not_better_by(m, base, (&Scores::default(), 0.0))
}

/// The names of the metrics on which `m` does not beat `base` by more than the reference's
/// own error `err` (each metric of the N-spp reference scored against an independent
/// reference of 4N samples, [`reference_error`]): `m` beats `base` on a metric `M` when
/// `M(base) - M(m) > M(ref_N vs ref_4N)`, the flicker error included (`err.1`); on the glint
/// counts when `base - m > ` the reference's own count of that kind, or when both are zero
/// (nothing to beat).
///
/// Why that margin: each score is taken against the N-spp reference, not the converged
/// image. For a distance `d` obeying the triangle inequality (the RMSE of the specular term;
/// FLIP approximately) `|d(x, ref_N) - d(x, truth)| <= d(ref_N, truth)`, and
/// `d(ref_N, ref_4N)` estimates `d(ref_N, truth)` from above (the two references'
/// independent noises add: `(1 + 1/4)^(1/2)` times it for Monte Carlo noise). Both methods
/// are scored against the same reference, so their scores move together; a margin above
/// that bound is one the reference's noise cannot have made.
pub fn not_better_by(
    m: (&Scores, f64),
    base: (&Scores, f64),
    err: (&Scores, f64),
) -> Vec<&'static str> {
    let ((s, fm), (b, fb), (e, fe)) = (m, base, err);
    let mut out = Vec::new();
    let better = |x: f64, y: f64, margin: f64| y - x > margin;
    let count = |x: usize, y: usize, margin: usize| {
        (x == 0 && y == 0) || y as f64 - x as f64 > margin as f64
    };
    if !better(s.flip_ldr, b.flip_ldr, e.flip_ldr) {
        out.push("FLIP LDR");
    }
    if !better(s.flip_hdr, b.flip_hdr, e.flip_hdr) {
        out.push("FLIP HDR");
    }
    if !better(fm, fb, fe) {
        out.push("flicker");
    }
    if !better(s.specular, b.specular, e.specular) {
        out.push("specular");
    }
    if !count(s.false_glints, b.false_glints, e.false_glints) {
        out.push("false glints");
    }
    if !count(s.lost_highlights, b.lost_highlights, e.lost_highlights) {
        out.push("lost highlights");
    }
    out
}

/// The verdict column: "beats unfiltered on all" or the metrics it does not beat it on.
pub fn verdict(m: (&Scores, f64), base: (&Scores, f64)) -> String {
    verdict_text(not_better(m, base))
}

/// [`verdict`] by more than the reference's own error ([`not_better_by`]).
pub fn verdict_by(m: (&Scores, f64), base: (&Scores, f64), err: (&Scores, f64)) -> String {
    verdict_text(not_better_by(m, base, err))
}

fn verdict_text(missing: Vec<&'static str>) -> String {
    if missing.is_empty() {
        "**beats unfiltered on all**".to_string()
    } else {
        format!("not: {}", missing.join(", "))
    }
}

/// The reference's own error: the still-frame scores of the N-spp reference (frame and
/// specular term) against an independent reference of four times the samples (another seed).
pub fn reference_error(
    reference: (&Image, &Image),
    reference_4n: (&Image, &Image),
    exposure: f32,
) -> Scores {
    score(reference, reference_4n, exposure).0
}

/// The label of the reference-error row: `reference (N spp) vs (4N spp)`, with the temporal
/// test's samples where they differ (`; temporal M vs 4M spp`).
pub fn reference_error_label(spp: usize, temporal_spp: Option<usize>) -> String {
    let mut label = format!("reference ({spp} spp) vs ({} spp)", 4 * spp);
    if let Some(t) = temporal_spp.filter(|&t| t != spp) {
        label.push_str(&format!("; temporal {t} vs {} spp", 4 * t));
    }
    label
}

/// A method's temporal scores ([`flicker_error`] and [`flicker_energy`] over the reference's
/// energy, and KHPL16 Fig. 12's frame-to-frame variation of the peak).
#[derive(Clone, Copy, Debug)]
pub struct Flicker {
    pub error: f64,
    pub energy: f64,
    pub peak_variation: f64,
}

/// One row of the lead table.
pub struct LeadRow {
    pub label: String,
    /// The NDF's name; the verdict compares each row with the baseline row of its NDF.
    pub ndf: &'static str,
    /// Unfiltered (the row the others are compared with).
    pub baseline: bool,
    pub scores: Scores,
    pub flicker: Option<Flicker>,
}

/// Issue 21's table, shared by the CPU and GPU demonstrations: per row FLIP, flicker,
/// specular error, false glints and lost highlights, the HDR RMSE, and where it stands
/// against the unfiltered row of its NDF ([`verdict`]). A missing score prints as `-`.
pub fn lead_table(rows: &[LeadRow]) -> String {
    lead_table_with(rows, &[])
}

/// [`lead_table`] with the references' own errors: `references` holds, per NDF, the row of
/// the N-spp reference scored against the 4N-spp one (its label from
/// [`reference_error_label`]), printed first; each verdict then counts only the margins
/// above that NDF's reference error ([`verdict_by`]). An NDF without such a row is judged by
/// [`verdict`].
pub fn lead_table_with(rows: &[LeadRow], references: &[LeadRow]) -> String {
    use std::fmt::Write as _;
    let mut t = String::new();
    writeln!(t, "| method | NDF | FLIP LDR | FLIP HDR | flicker error / ref. | flicker energy / ref. | peak flicker | specular error | false glints | lost highlights | RMSE (HDR) | against unfiltered |").unwrap();
    writeln!(
        t,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    )
    .unwrap();
    let num = |v: f64, digits: usize| {
        if v.is_finite() {
            format!("{v:.digits$}")
        } else {
            "-".to_string()
        }
    };
    let line = |t: &mut String, r: &LeadRow, verdict: String| {
        let f = r.flicker.unwrap_or(Flicker {
            error: f64::NAN,
            energy: f64::NAN,
            peak_variation: f64::NAN,
        });
        let s = &r.scores;
        writeln!(
            t,
            "| {} | {} | {:.4} | {:.4} | {} | {} | {}% | {} | {} | {} | {:.4} | {} |",
            r.label,
            r.ndf,
            s.flip_ldr,
            s.flip_hdr,
            num(f.error, 2),
            num(f.energy, 2),
            num(100.0 * f.peak_variation, 1),
            num(s.specular, 4),
            s.false_glints,
            s.lost_highlights,
            s.rmse_hdr,
            verdict
        )
        .unwrap();
    };
    for r in references {
        line(
            &mut t,
            r,
            "(the reference's own error: the margins)".to_string(),
        );
    }
    for r in rows {
        let verdict = if r.baseline {
            "(baseline)".to_string()
        } else {
            missing(r, rows, references).map_or("-".to_string(), verdict_text)
        };
        line(&mut t, r, verdict);
    }
    t
}

/// The metrics on which row `r` does not beat the baseline row of its NDF in `rows`, by more
/// than its NDF's reference error in `references` where there is one ([`not_better_by`]);
/// `None` without a baseline or flicker scores.
pub fn missing(r: &LeadRow, rows: &[LeadRow], references: &[LeadRow]) -> Option<Vec<&'static str>> {
    let b = rows.iter().find(|b| b.baseline && b.ndf == r.ndf)?;
    let (f, bf) = (r.flicker?, b.flicker?);
    let zero = (Scores::default(), 0.0);
    let err = references
        .iter()
        .find(|e| e.ndf == r.ndf)
        .map_or(zero, |e| (e.scores, e.flicker.map_or(0.0, |x| x.error)));
    Some(not_better_by(
        (&r.scores, f.error),
        (&b.scores, bf.error),
        (&err.0, err.1),
    ))
}

/// For each metric of `failed` (names as [`not_better_by`] gives them): row `r`'s value less
/// its baseline's, and the reference's error in parentheses; `r` beats the baseline on that
/// metric only where the difference is below minus the error (lower is better on all six).
pub fn shortfalls(
    r: &LeadRow,
    rows: &[LeadRow],
    references: &[LeadRow],
    failed: &[&str],
) -> Vec<String> {
    let Some(b) = rows.iter().find(|b| b.baseline && b.ndf == r.ndf) else {
        return Vec::new();
    };
    let e = references.iter().find(|e| e.ndf == r.ndf);
    let flicker = |x: &LeadRow| x.flicker.map_or(f64::NAN, |f| f.error);
    let value = |x: &LeadRow, name: &str| match name {
        "FLIP LDR" => x.scores.flip_ldr,
        "FLIP HDR" => x.scores.flip_hdr,
        "flicker" => flicker(x),
        "specular" => x.scores.specular,
        "false glints" => x.scores.false_glints as f64,
        _ => x.scores.lost_highlights as f64,
    };
    failed
        .iter()
        .map(|&name| {
            let d = value(r, name) - value(b, name);
            let err = e.map_or(0.0, |e| value(e, name));
            if matches!(name, "false glints" | "lost highlights") {
                format!("{name} {d:+.0} ({err:.0})")
            } else if name == "flicker" {
                format!("{name} {d:+.2} ({err:.2})")
            } else {
                format!("{name} {d:+.4} ({err:.4})")
            }
        })
        .collect()
}

/// One route of the "where each route stands" table: its name, the indices of its rows in
/// the lead table's `rows`, and what it costs (free text: measured times).
pub struct RouteGroup {
    pub name: String,
    pub rows: Vec<usize>,
    pub cost: String,
}

/// Where each route stands: per route, its best row (the fewest metrics on which it does not
/// beat unfiltered by more than the reference's error, [`missing`]; ties to the lower FLIP
/// LDR), what that row fails, its FLIP LDR, flicker error and glint counts, and the route's
/// cost.
pub fn standing_table(groups: &[RouteGroup], rows: &[LeadRow], references: &[LeadRow]) -> String {
    use std::fmt::Write as _;
    let mut t = String::new();
    writeln!(t, "| route | best method | beats unfiltered (by more than the reference's error) | short by: method - unfiltered (reference's error) | FLIP LDR | flicker error / ref. | false glints / lost highlights | cost |").unwrap();
    writeln!(t, "|---|---|---|---|---:|---:|---:|---|").unwrap();
    for g in groups {
        let best = g
            .rows
            .iter()
            .filter_map(|&i| {
                let r = rows.get(i)?;
                let m = if r.baseline {
                    None
                } else {
                    missing(r, rows, references)
                };
                Some((r, m))
            })
            .min_by(|(a, ma), (b, mb)| {
                let n = |m: &Option<Vec<&str>>| m.as_ref().map_or(usize::MAX, Vec::len);
                n(ma)
                    .cmp(&n(mb))
                    .then(a.scores.flip_ldr.total_cmp(&b.scores.flip_ldr))
            });
        let Some((r, m)) = best else { continue };
        let stands = match (&m, r.baseline) {
            (_, true) => "(baseline)".to_string(),
            (Some(m), _) if m.is_empty() => "**on all six**".to_string(),
            (Some(m), _) => format!("all but {}", m.join(", ")),
            (None, _) => "-".to_string(),
        };
        let flicker = r
            .flicker
            .map_or("-".to_string(), |f| format!("{:.2}", f.error));
        let short = match (&m, r.baseline) {
            (Some(m), false) if !m.is_empty() => shortfalls(r, rows, references, m).join("; "),
            _ => "-".to_string(),
        };
        writeln!(
            t,
            "| {} | {} | {} | {} | {:.4} | {} | {} / {} | {} |",
            g.name,
            r.label,
            stands,
            short,
            r.scores.flip_ldr,
            flicker,
            r.scores.false_glints,
            r.scores.lost_highlights,
            g.cost
        )
        .unwrap();
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> Vec3) -> Image {
        Image::new(
            w,
            h,
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect(),
        )
    }

    /// A row that wins FLIP LDR by more than the reference's error, wins FLIP HDR by less
    /// than it, and loses on false glints: the verdict names the last two, and the shortfalls
    /// are the differences written by hand from the scores below, with the errors beside.
    #[test]
    fn shortfalls_are_the_differences_beside_the_reference_error() {
        let row = |label: &str, baseline, s: Scores, flicker| LeadRow {
            label: label.to_string(),
            ndf: "GGX",
            baseline,
            scores: s,
            flicker: Some(Flicker {
                error: flicker,
                energy: 1.0,
                peak_variation: 0.0,
            }),
        };
        let base = Scores {
            flip_ldr: 0.05,
            flip_hdr: 0.08,
            specular: 0.06,
            false_glints: 0,
            lost_highlights: 40,
            rmse_hdr: 1.0,
        };
        let method = Scores {
            flip_ldr: 0.04,
            flip_hdr: 0.079,
            specular: 0.05,
            false_glints: 3,
            lost_highlights: 10,
            rmse_hdr: 0.5,
        };
        let error = Scores {
            flip_ldr: 0.002,
            flip_hdr: 0.004,
            specular: 0.001,
            false_glints: 1,
            lost_highlights: 2,
            rmse_hdr: 0.1,
        };
        let rows = [row("u", true, base, 2.0), row("m", false, method, 1.5)];
        let refs = [row("r", false, error, 0.25)];
        let failed = missing(&rows[1], &rows, &refs).unwrap();
        assert_eq!(failed, ["FLIP HDR", "false glints"]);
        assert_eq!(
            shortfalls(&rows[1], &rows, &refs, &failed),
            ["FLIP HDR -0.0010 (0.0040)", "false glints +3 (1)"]
        );
    }

    #[test]
    fn aces_inverse_inverts_the_curve() {
        for t in [0.1f32, 0.5, 0.85] {
            assert!((aces(aces_inverse(t)) - t).abs() < 1e-5, "t = {t}");
        }
    }

    #[test]
    fn hdr_exposures_span_max_to_median() {
        // Luminances 1 (median) and 64 (max): 6 stops apart, so 6 exposures, the first
        // mapping 64 and the last mapping 1 to 0.85.
        let img = image(4, 4, |x, y| {
            Vec3::splat(if x + y == 0 { 64.0 } else { 1.0 })
        });
        let e = hdr_exposures(&img);
        assert_eq!(e.len(), 6);
        let x = aces_inverse(0.85);
        assert!((e[0] - (x / 64.0).log2()).abs() < 1e-5);
        assert!((e[5] - x.log2()).abs() < 1e-5);
    }

    #[test]
    fn flip_is_zero_for_equal_images_and_grows_with_the_difference() {
        let a = image(32, 32, |x, y| Vec3::splat(0.05 * ((x + y) % 7) as f32));
        assert_eq!(flip_ldr(&a, &a, 1.0).mean(), 0.0);
        assert_eq!(flip_hdr(&a, &a).mean(), 0.0);
        let small = image(32, 32, |x, y| a.data[y * 32 + x] * 1.1);
        let large = image(32, 32, |x, y| a.data[y * 32 + x] * 3.0);
        let (s, l) = (
            flip_ldr(&small, &a, 1.0).mean(),
            flip_ldr(&large, &a, 1.0).mean(),
        );
        assert!(0.0 < s && s < l && l <= 1.0, "{s} {l}");
    }

    #[test]
    fn glints_count_bright_over_dark_and_the_reverse() {
        let reference = [0.1, 0.9, 0.5, 0.1];
        let test = [0.9, 0.1, 0.9, 0.2];
        assert_eq!(glint_counts(&test, &reference), (1, 1));
    }

    /// Glints only the method has and highlights only the reference has, at different pixels
    /// and in different numbers: each lands in its own count, and swapping the images swaps
    /// the counts.
    #[test]
    fn glints_on_asymmetric_inputs() {
        // 12 pixels: three false glints (0, 4, 9), one lost highlight (6), and pixels that
        // count as neither: both bright (2), both dark (3), bright over mid-grey (5), mid-grey
        // over dark (7), dark under mid-grey (8), bright under bright (10), dark over dark (11).
        let reference = [
            0.0, 0.5, 0.95, 0.1, 0.29, 0.4, 1.0, 0.1, 0.6, 0.2, 0.85, 0.0,
        ];
        let test = [
            0.9, 0.5, 0.99, 0.2, 1.0, 0.9, 0.1, 0.6, 0.1, 0.81, 0.95, 0.05,
        ];
        let (glints, lost) = glint_masks(&test, &reference);
        let at = |m: &[bool]| (0..m.len()).filter(|&i| m[i]).collect::<Vec<_>>();
        assert_eq!(at(&glints), [0, 4, 9]);
        assert_eq!(at(&lost), [6]);
        assert_eq!(glint_counts(&test, &reference), (3, 1));
        assert_eq!(glint_counts(&reference, &test), (1, 3));
        // Only glints, no highlight in the reference; only lost highlights, none in the test.
        assert_eq!(glint_counts(&[0.9; 5], &[0.0; 5]), (5, 0));
        assert_eq!(glint_counts(&[0.0; 5], &[0.9; 5]), (0, 5));
        assert_eq!(glint_counts(&[], &[]), (0, 0));
    }

    /// A pixel exactly at a threshold is neither bright nor dark (both comparisons are
    /// strict); one f32 ulp past it, it is.
    #[test]
    fn glints_at_the_thresholds() {
        let (b, d) = (BRIGHT, DARK);
        // The test pixel at `BRIGHT`, one ulp below and above it, over a black reference.
        assert_eq!(glint_counts(&[b], &[0.0]), (0, 0));
        assert_eq!(glint_counts(&[b.next_down()], &[0.0]), (0, 0));
        assert_eq!(glint_counts(&[b.next_up()], &[0.0]), (1, 0));
        // The reference pixel at `DARK`, one ulp above and below it, under a white test.
        assert_eq!(glint_counts(&[1.0], &[d]), (0, 0));
        assert_eq!(glint_counts(&[1.0], &[d.next_up()]), (0, 0));
        assert_eq!(glint_counts(&[1.0], &[d.next_down()]), (1, 0));
        // The same for lost highlights, the roles swapped.
        assert_eq!(glint_counts(&[0.0], &[b]), (0, 0));
        assert_eq!(glint_counts(&[0.0], &[b.next_up()]), (0, 1));
        assert_eq!(glint_counts(&[d], &[1.0]), (0, 0));
        assert_eq!(glint_counts(&[d.next_down()], &[1.0]), (0, 1));
        // Both at once, each one ulp past its threshold: counted; at the thresholds: not.
        assert_eq!(glint_counts(&[b.next_up()], &[d.next_down()]), (1, 0));
        assert_eq!(glint_counts(&[b], &[d]), (0, 0));
    }

    // Reference values from NVIDIA's own implementation: `flip-evaluator` 1.7 from PyPI
    // (pybind11 over NVIDIA's C++ `FLIP.h`), printed by `tests/data/flip_reference.py`. The
    // `nv-flip` crate wraps NVIDIA's C++ too, but an older release (the 2022 `CPP/` sources,
    // before 1.3 reordered some transforms and 1.4 changed the median): on the LDR pair the
    // two give different values in every pixel (up to 2.2e-4, median 1.9e-4 relative, of
    // mixed sign), `mean |difference| = 3.33e-5`, measured once by dumping this crate's map
    // beside the package's. That mean absolute difference bounds the difference of the mean
    // FLIPs, and is the tolerance `VERSION_TOL` below (rounded up). It still fails a wrong
    // pixels-per-degree (67 -> 60 or 70 moves the mean by 9e-4, 7e-4), swapped channels
    // (1e-2) or sRGB bytes taken as linear (1.8e-2).

    /// The mean absolute per-pixel difference of the two NVIDIA versions, rounded up.
    const VERSION_TOL: f64 = 3.4e-5;
    /// Mean LDR-FLIP of the PNG pair of `tests/data/`, 67 pixels per degree.
    const FLIP_LDR_NVIDIA: f64 = 0.205_382_138;
    /// HDR-FLIP's exposures for the HDR pair's reference: start, stop, count (printed
    /// -4.916702747, 4.110420704; to f32 precision here).
    const FLIP_HDR_EXPOSURES_NVIDIA: (f32, f32, usize) = (-4.916_703, 4.110_421, 10);
    /// Mean HDR-FLIP of the HDR pair (the package's float pipeline).
    const FLIP_HDR_NVIDIA: f64 = 0.152_552_187;
    /// Mean HDR-FLIP of the HDR pair with each exposure's tone-mapped images quantised to
    /// 8-bit sRGB before the package's LDR-FLIP, as [`flip_hdr`] does (the `nv-flip` input is
    /// 8-bit): the package at the crate's quantisation.
    const FLIP_HDR_8BIT_NVIDIA: f64 = 0.152_731_185;
    /// The mean absolute per-pixel effect of that quantisation on this pair, as the script
    /// prints it (the package alone): it bounds the difference of the two HDR means.
    const QUANTISATION_TOL: f64 = 8.41e-4;

    /// The LDR pair of `tests/data/` (8-bit sRGB PNGs written by
    /// `tests/data/flip_reference.py`).
    fn ldr_pair() -> (usize, usize, Vec<u8>, Vec<u8>) {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
        let load = |name: &str| {
            let p = dir.join(name);
            image::open(&p)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
                .to_rgb8()
        };
        let (r, t) = (load("flip_ldr_reference.png"), load("flip_ldr_test.png"));
        assert_eq!(r.dimensions(), t.dimensions());
        let (w, h) = r.dimensions();
        (w as usize, h as usize, t.into_raw(), r.into_raw())
    }

    /// The HDR pair of `tests/data/flip_reference.py` (`hdr_pair`), built from the same
    /// formulas: every value a dyadic rational, exact in f32 in both languages.
    fn hdr_pair() -> (Image, Image) {
        let n = 32;
        let reference = image(n, n, |x, y| {
            if (x as i32 - 25, y as i32 - 6) == (0, 0) {
                return Vec3::splat(64.0);
            }
            if (x as i32 - 12).pow(2) + (y as i32 - 20).pow(2) < 9 {
                return Vec3::splat(16.0);
            }
            let r = (1 + (x + y) % 8) as f32 / 32.0;
            Vec3::new(r, r * 0.75, r * 0.5)
        });
        let test = image(n, n, |x, y| {
            let c = reference.data[y * n + x];
            match (x, y) {
                (25, 6) => Vec3::splat(0.5),
                (5, 5) => Vec3::splat(32.0),
                _ if c == Vec3::splat(16.0) => Vec3::splat(8.0),
                _ if (3 * x + 5 * y) % 7 == 0 => c * 1.5,
                _ => c,
            }
        });
        (test, reference)
    }

    #[test]
    fn flip_ldr_matches_nvidia_reference_implementation() {
        let (w, h, test, reference) = ldr_pair();
        let map = ldr_flip_bytes(w, h, &test, &reference);
        let got = map.iter().map(|&x| f64::from(x)).sum::<f64>() / map.len() as f64;
        assert!(
            (got - FLIP_LDR_NVIDIA).abs() <= VERSION_TOL,
            "LDR-FLIP mean {got:.9}, NVIDIA {FLIP_LDR_NVIDIA}"
        );
    }

    #[test]
    fn flip_hdr_matches_nvidia_reference_implementation() {
        let (test, reference) = hdr_pair();
        // The exposures, within 4 ulp of their magnitude (`log2` of f32 ratios).
        let e = hdr_exposures(&reference);
        let (start, stop, count) = FLIP_HDR_EXPOSURES_NVIDIA;
        assert_eq!(e.len(), count, "{e:?}");
        let ulps4 = |x: f32| 4.0 * f32::EPSILON * x.abs();
        assert!((e[0] - start).abs() <= ulps4(start), "{e:?}");
        assert!((e[count - 1] - stop).abs() <= ulps4(stop), "{e:?}");
        let got = flip_hdr(&test, &reference).mean();
        // The same quantisation as the package run at it: the versions' difference only.
        assert!(
            (got - FLIP_HDR_8BIT_NVIDIA).abs() <= VERSION_TOL,
            "HDR-FLIP mean {got:.9}, NVIDIA at 8 bits {FLIP_HDR_8BIT_NVIDIA}"
        );
        // The package's own float HDR-FLIP: plus the quantisation's effect.
        assert!(
            (got - FLIP_HDR_NVIDIA).abs() <= QUANTISATION_TOL + VERSION_TOL,
            "HDR-FLIP mean {got:.9}, NVIDIA {FLIP_HDR_NVIDIA}"
        );
    }

    #[test]
    fn flicker_energy_is_the_mean_squared_change() {
        assert_eq!(flicker_energy(&vec![vec![0.5; 4]; 3]), 0.0);
        // Two pixels, one switching by 1 each frame: 2 pairs x 2 pixels, sum 2.
        let frames = vec![vec![0.0, 0.2], vec![1.0, 0.2], vec![0.0, 0.2]];
        assert!((flicker_energy(&frames) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn flicker_error_counts_changes_the_reference_does_not_make() {
        let reference = vec![vec![0.0, 0.2], vec![1.0, 0.2], vec![0.0, 0.2]];
        assert_eq!(flicker_error(&reference, &reference), 0.0);
        // The same energy, in the other pixel: each pair differs by (-1, +1).
        let moved = vec![vec![0.2, 0.0], vec![0.2, 1.0], vec![0.2, 0.0]];
        assert_eq!(flicker_energy(&moved), flicker_energy(&reference));
        assert!((flicker_error(&moved, &reference) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn verdict_needs_every_metric() {
        let base = Scores {
            flip_ldr: 0.2,
            flip_hdr: 0.3,
            specular: 0.1,
            false_glints: 5,
            lost_highlights: 0,
            rmse_hdr: 1.0,
        };
        let good = Scores {
            flip_ldr: 0.1,
            flip_hdr: 0.2,
            specular: 0.05,
            false_glints: 1,
            ..base
        };
        assert!(not_better((&good, 1.1), (&base, 4.0)).is_empty());
        assert_eq!(not_better((&good, 5.0), (&base, 4.0)), ["flicker"]);
        assert_eq!(not_better((&good, 4.0), (&base, 4.0)), ["flicker"]);
        let glinty = Scores {
            false_glints: 9,
            ..good
        };
        assert_eq!(not_better((&glinty, 1.0), (&base, 4.0)), ["false glints"]);
    }

    /// The verdict with the reference's own error: a margin counts only above it, on every
    /// metric (strictly: a margin equal to the error does not), and two zero counts pass.
    #[test]
    fn verdict_by_needs_each_margin_above_the_reference_error() {
        let base = Scores {
            flip_ldr: 0.20,
            flip_hdr: 0.30,
            specular: 0.10,
            false_glints: 0,
            lost_highlights: 10,
            rmse_hdr: 1.0,
        };
        let m = Scores {
            flip_ldr: 0.15,
            flip_hdr: 0.25,
            specular: 0.08,
            false_glints: 0,
            lost_highlights: 5,
            rmse_hdr: 0.5,
        };
        let small = Scores {
            flip_ldr: 0.01,
            flip_hdr: 0.01,
            specular: 0.01,
            false_glints: 3,
            lost_highlights: 4,
            rmse_hdr: 0.0,
        };
        assert!(not_better_by((&m, 1.0), (&base, 2.0), (&small, 0.5)).is_empty());
        // A margin under its error, or equal to it (the counts: 10 - 5 = 5), fails that
        // metric alone.
        let big = Scores {
            flip_ldr: 0.06,
            flip_hdr: 0.04,
            specular: 0.01,
            false_glints: 3,
            lost_highlights: 5,
            rmse_hdr: 0.0,
        };
        assert_eq!(
            not_better_by((&m, 1.0), (&base, 2.0), (&big, 1.5)),
            ["FLIP LDR", "flicker", "lost highlights"]
        );
        // A false glint where unfiltered has none fails whatever the error.
        let glinty = Scores {
            false_glints: 1,
            ..m
        };
        assert_eq!(
            not_better_by((&glinty, 1.0), (&base, 2.0), (&small, 0.5)),
            ["false glints"]
        );
        // With zero error it is the plain verdict.
        assert_eq!(
            not_better_by((&m, 1.0), (&base, 2.0), (&Scores::default(), 0.0)),
            not_better((&m, 1.0), (&base, 2.0))
        );
    }
}
