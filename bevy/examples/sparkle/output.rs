//! What the example writes besides its table: the middle frame of the move side by side, the
//! change from the frame before (what flickers), and the generated part of the docs page.

use crate::{Options, View};
use filtered_ndf_demo::image_out::{self, Image};
use std::path::{Path, PathBuf};

/// The frame in the middle of the move of the unfiltered, PR, plugin and plugin-with-moments
/// rows (trilinear, and anisotropic without `--quick`) and the reference, side by side; and the frame-to-frame change of display luminance at the same
/// frame (what flickers). Returns the folder.
pub fn write_images(
    o: &Options,
    views: &[View],
    frames: &[Vec<Image>],
    methods: usize,
    exposure: f32,
    dir: &Path,
) -> Result<PathBuf, String> {
    let find = |label: &str| views[..methods].iter().position(|v| v.label == label);
    let lean = [crate::PLUGIN_LEAN, crate::PLUGIN_LEAN_ANISOTROPIC].map(find);
    let shown: Vec<usize> = (0..3)
        .chain(lean.into_iter().flatten())
        .chain([methods])
        .collect();
    let columns = if shown.len() > 4 { 3 } else { 2 };
    let mid = o.frames / 2;
    let zoom = if o.quick { 2 } else { 1 };
    let tiles: Vec<(String, image_out::Rgb8)> = shown
        .iter()
        .map(|&i| (views[i].label.clone(), frames[i][mid].to_rgb8(exposure)))
        .collect();
    let sheet = image_out::contact_sheet(&tiles, columns, zoom);
    let path = dir.join("sparkle_frame.png");
    image_out::save(&sheet, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    if mid > 0 {
        let diff_tiles: Vec<(String, image_out::Rgb8)> = shown
            .iter()
            .map(|&i| {
                let (a, b) = (&frames[i][mid - 1], &frames[i][mid]);
                let data = a
                    .data
                    .iter()
                    .zip(&b.data)
                    .map(|(&p, &q)| {
                        let d = (image_out::luminance(image_out::tonemap(q, exposure))
                            - image_out::luminance(image_out::tonemap(p, exposure)))
                        .abs();
                        glam::Vec3::splat(d)
                    })
                    .collect();
                let d = Image::new(a.width, a.height, data);
                // A change of 1/4 of the display range shows white.
                (
                    format!("{}: change", views[i].label),
                    d.to_rgb8(FLICKER_GAIN),
                )
            })
            .collect();
        let sheet = image_out::contact_sheet(&diff_tiles, columns, zoom);
        let path = dir.join("sparkle_flicker.png");
        image_out::save(&sheet, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(dir.to_path_buf())
}

/// The gain of the frame-to-frame change images: a change of display luminance of `1 /
/// FLICKER_GAIN` (before the image's tone map) shows near white.
const FLICKER_GAIN: f32 = 4.0;

/// Rewrites the generated part of the docs page and writes its images.
#[allow(clippy::too_many_arguments)]
pub fn write_docs(
    o: &Options,
    docs: &Path,
    header: &str,
    table: &str,
    views: &[View],
    frames: &[Vec<Image>],
    methods: usize,
    exposure: f32,
) -> Result<(), String> {
    const BEGIN: &str =
        "<!-- sparkle:begin (written by `cargo run --example sparkle -- --docs ...`) -->";
    const END: &str = "<!-- sparkle:end -->";
    let text = std::fs::read_to_string(docs).map_err(|e| format!("{}: {e}", docs.display()))?;
    let (Some(a), Some(b)) = (text.find(BEGIN), text.find(END)) else {
        return Err(format!("{}: no {BEGIN} ... {END} marks", docs.display()));
    };
    let stem = docs
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or(format!("{}: no file name", docs.display()))?;
    let dir = docs.with_file_name(stem);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    write_images(o, views, frames, methods, exposure, &dir)?;
    let body = format!(
        "{BEGIN}\n\n{header}.\n\n{table}\n![The middle frame](sparkle/sparkle_frame.png)\n\n![Its change from the frame before](sparkle/sparkle_flicker.png)\n\n{END}"
    )
    .replace("sparkle/", &format!("{stem}/"));
    let out = format!("{}{}{}", &text[..a], body, &text[b + END.len()..]);
    std::fs::write(docs, out).map_err(|e| format!("{}: {e}", docs.display()))
}
