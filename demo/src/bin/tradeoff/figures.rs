//! The which-kernel guide (README, crate docs), generated from the trade table's rows so that
//! every place shows one measurement: the library's `src/doc/which_kernel.md` (included by the
//! crate docs) and the README's copy between the `which_kernel` markers (compared by the
//! library's `tests/readme.rs`).

use super::{BECKMANN_FRONT_DOOR, EXACT, Row};

/// A cost ratio as the guide writes it: whole numbers from 10, one decimal below.
fn cost(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.0}x")
    } else {
        format!("{x:.1}x")
    }
}

/// The markdown table `| ROW | cost | error |`: cost relative to unfiltered GGX (`f32`, one
/// run), median relative error against the exact Gaussian-filtered NDF. Panics if a row the
/// guide names is missing from the trade table (a renamed row).
pub fn markdown(rows: &[Row], ggx_base: f64, beck_base: f64) -> String {
    let row = |name: &str| -> &Row {
        rows.iter()
            .find(|r| r.name == name)
            .unwrap_or_else(|| panic!("trade table row {name:?} missing"))
    };
    let c = |name: &str| cost(row(name).ns / ggx_base);
    let e = |name: &str| format!("{:.1e}", row(name).median);
    let deferred: Vec<&Row> = rows
        .iter()
        .filter(|r| r.name.starts_with("GGX deferred: TK19"))
        .collect();
    let (dmin, dmax) = deferred.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
        (a.min(r.median), b.max(r.median))
    });
    let fast = format!("{EXACT} Rel1e3");
    let beck = row(BECKMANN_FRONT_DOOR);
    let lines = [
        (
            "forward_ggx",
            c("GGX TK19 A+2Sigma (matrix)"),
            e("GGX TK19 A+2Sigma (matrix)"),
        ),
        (
            "forward_ggx_exact",
            format!(
                "{} / {} (`Tolerance::Rel1e3`) / {} (box)",
                c(EXACT),
                c(&fast),
                c("GGX exact rect (bounding box)")
            ),
            format!(
                "{} / {} / {}",
                e(EXACT),
                e(&fast),
                e("GGX exact rect (bounding box)")
            ),
        ),
        (
            "forward_beckmann",
            format!(
                "{} ({} unfiltered Beckmann)",
                cost(beck.ns / ggx_base),
                cost(beck.ns / beck_base)
            ),
            format!("{:.1e}", beck.median),
        ),
        (
            "projected",
            c("GGX TK21 projected"),
            e("GGX TK21 projected"),
        ),
        (
            "gbuffer_anisotropic",
            c("GGX proxy exact (eq. 19)"),
            e("GGX proxy exact (eq. 19)"),
        ),
        (
            "deferred",
            c("GGX deferred: TK19 trace (eq. 4)"),
            format!("{dmin:.1e} to {dmax:.1e}"),
        ),
    ];
    let mut md = String::from("| scene | call | cost | error | ROW |\n|---|---|---:|---:|---|\n");
    for (id, c, e) in lines {
        let (scene, call) = guide_row(id);
        md += &format!("| {scene} | {call} | {c} | {e} | `{id}` |\n");
    }
    for (id, scene, call, c, e) in STATIC_ROWS {
        md += &format!("| {scene} | {call} | {c} | {e} | `{id}` |\n");
    }
    md
}

/// The scene and the call of a measured guide row.
fn guide_row(id: &str) -> (&'static str, &'static str) {
    match id {
        "forward_ggx" => (
            "forward, GGX, any roughness form, per light (ddx/ddy of the half vector)",
            "`material.filtered(Footprint::from_half_vector_derivatives(h, ddx_h, ddy_h), Gaussian::TK19)`",
        ),
        "forward_ggx_exact" => (
            "forward, GGX, the highlight's shape matters (close-ups, baking, references)",
            "`material.filtered(fp, ExactGaussian::KHPL16)` (exact; `.with_tolerance(Tolerance::Rel1e3)` cheaper), or `Rect::KHPL16` (exact box)",
        ),
        "forward_beckmann" => (
            "forward, Beckmann",
            "`material.filtered(fp, Gaussian::KHPL16)` (exact)",
        ),
        "projected" => (
            "forward, derivatives of the projected `h_xy` (TK19 sec. 3.2)",
            "`material.filtered(Footprint::from_projected_derivatives(..), Projected::TK21)`",
        ),
        "gbuffer_anisotropic" => (
            "G-buffer with an anisotropic roughness",
            "`material.filtered(fp, Proxy::KHPL16)`: a plain `Ggx<AxisAligned>` to store",
        ),
        "deferred" => (
            "deferred, one roughness channel",
            "`Ggx::new(presets::TK19_TRACE.filter(alpha, ddx_n, ddy_n))` (or an engine's preset)",
        ),
        other => panic!("no guide text for row {other:?}"),
    }
}

/// The guide's rows whose cost and error are those of the method they use: `(ROW, scene,
/// call, cost, error)`.
const STATIC_ROWS: [(&str, &str, &str, &str, &str); 3] = [
    (
        "path_tracer",
        "offline path tracer",
        "`Footprint::from_ray_differentials(m, &frame, dx_u, dx_v)`, any method, then `sample_visible_normal`",
        "as the method",
        "as the method",
    ),
    (
        "normal_mapped",
        "normal-mapped (LEAN moments)",
        "`Ggx::new(filter::lean(alpha, pixel_covariance, &moments))`",
        "as `Gaussian`",
        "-",
    ),
    (
        "motion_blur",
        "motion blur",
        "`TemporalLobe::ggx(alpha, TemporalRoughness::from_normal_rate(dn_dt, dt).covariance())`",
        "as `Gaussian`",
        "-",
    ),
];

/// Writes the guide to the library's `src/doc/which_kernel.md` and into the README between
/// its `which_kernel` markers (`root`: the repository).
pub fn write(root: &std::path::Path, table: &str) -> std::io::Result<()> {
    std::fs::write(root.join("src/doc/which_kernel.md"), table)?;
    let readme_path = root.join("README.md");
    let readme = std::fs::read_to_string(&readme_path)?;
    let open = readme
        .find("<!-- which_kernel")
        .and_then(|i| readme[i..].find('\n').map(|j| i + j + 1))
        .ok_or_else(|| std::io::Error::other("README.md lacks the <!-- which_kernel marker"))?;
    let close = readme[open..]
        .find("<!-- /which_kernel -->")
        .map(|j| open + j)
        .ok_or_else(|| {
            std::io::Error::other("README.md lacks the <!-- /which_kernel --> marker")
        })?;
    let updated = format!("{}{}{}", &readme[..open], table, &readme[close..]);
    std::fs::write(readme_path, updated)
}
