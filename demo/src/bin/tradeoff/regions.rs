//! Where each approximation is wrong: the region of (footprint width / lobe width, distance of
//! the half vector from the peak in lobe widths) where the relative error of `D` against the
//! exact Gaussian filter exceeds 10 %, measured on a grid.
//!
//! - Lobe: GGX, `alpha = 0.1` (isotropic material; the grid is in units of it, and the
//!   approximations' errors depend on the ratios, not on `alpha`, away from the horizon).
//! - Footprint `r` (footprint width / lobe width): the slope change per pixel along `u` is
//!   `r alpha`; the Gaussian pixel kernel is `sigma = 0.5` pixels of it (`Footprint::covariance`).
//!   Four shapes: isotropic (`dh_v` as long as `dh_u`, perpendicular); 4:1 with the half vector
//!   along the long axis; 4:1 along the short axis; and an anisotropic material
//!   (`alpha_y = alpha / 4`) under the isotropic footprint.
//! - Distance `d`: the half vector's slope `d alpha` from the peak along the footprint's
//!   `u` axis (resp. its `v` axis for the third shape, and `x` for the fourth).
//! - Error: `|D_method - D_exact| / D_exact`, `D_exact` the `f64` exact Gaussian-filtered GGX of
//!   the unclamped pixel kernel (the trade table's reference); each method through the front
//!   door with its own clamp rules, in `f32` (what a renderer gets). A cell is the worst of
//!   the four shapes.

use filtered_ndf::f32 as p;
use filtered_ndf::f64 as q;
use p::Ndf as _;
use p::filter::{Filterable, Gaussian, Projected, Proxy};

/// Footprint width / lobe width on the grid.
pub const RATIOS: [f64; 10] = [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 2.0, 5.0, 10.0];
/// Distance from the peak in lobe widths on the grid.
pub const DISTANCES: [f64; 7] = [0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0];
/// The error that marks a cell.
const LIMIT: f64 = 0.1;
const ALPHA: f64 = 0.1;

/// A method under test: `D` of the front door's lobe for (material, footprint, half vector).
type Method = Box<dyn Fn(p::AxisAligned, p::Footprint, p::Vec3) -> f32>;

/// The methods whose regions are measured: TK19, TK21, the proxy and every deferred preset.
fn methods() -> Vec<(String, Method)> {
    let mut v: Vec<(String, Method)> = vec![
        (
            "TK19 `Gaussian::TK19`".into(),
            Box::new(|a, fp, h| p::Ggx::new(a).filtered(fp, Gaussian::TK19).d(h)),
        ),
        (
            "TK21 `Projected::TK21`".into(),
            Box::new(|a, fp, h| p::Ggx::new(a).filtered(fp, Projected::TK21).d(h)),
        ),
        (
            "proxy `Proxy::KHPL16`".into(),
            Box::new(|a, fp, h| p::Ggx::new(a).filtered(fp, Proxy::KHPL16).d(h)),
        ),
    ];
    for (name, conv) in p::filter::presets::ALL {
        v.push((
            format!("deferred `{name}`"),
            Box::new(move |a: p::AxisAligned, fp: p::Footprint, h: p::Vec3| {
                // The deferred kernels take normal differences: `dn = dh` (the trade table's
                // near-normal convention), their increment added to both axes.
                let (du, dv) = (
                    p::Vec3::new(fp.dh_u.x, fp.dh_u.y, 0.0),
                    p::Vec3::new(fp.dh_v.x, fp.dh_v.y, 0.0),
                );
                let al = a.alpha();
                let (ax, ay) = (conv.apply(al.x, du, dv), conv.apply(al.y, du, dv));
                p::Ggx::new(p::AxisAligned::new_clamped(ax, ay)).d(h)
            }),
        ));
    }
    v
}

/// One grid point of one shape: `(material alphas, dh_u, dh_v, slope of h)`.
fn shape(k: usize, r: f64, d: f64) -> ([f64; 2], [f64; 2], [f64; 2], [f64; 2]) {
    let w = r * ALPHA;
    let s = d * ALPHA;
    match k {
        0 => ([ALPHA; 2], [w, 0.0], [0.0, w], [s, 0.0]),
        1 => ([ALPHA; 2], [w, 0.0], [0.0, 0.25 * w], [s, 0.0]),
        2 => ([ALPHA; 2], [w, 0.0], [0.0, 0.25 * w], [0.0, s]),
        _ => ([ALPHA, 0.25 * ALPHA], [w, 0.0], [0.0, w], [s, 0.0]),
    }
}

/// The worst relative error over the four shapes at `(r, d)` for `method`.
fn worst(method: &Method, r: f64, d: f64) -> f64 {
    let mut e = 0.0f64;
    for k in 0..4 {
        let (al, du, dv, s) = shape(k, r, d);
        let n = 1.0 / (1.0 + s[0] * s[0] + s[1] * s[1]).sqrt();
        let h64 = q::Vec3::new(-s[0] * n, -s[1] * n, n);
        let a64 = q::AxisAligned::new(al[0], al[1]).expect("valid");
        let fp64 = q::Footprint::from_slope_derivatives(du.into(), dv.into());
        let exact = q::GaussianFilteredGgx::new(a64, fp64.covariance(0.5));
        let want = q::Ndf::d(&exact, h64);
        let a = p::AxisAligned::new(al[0] as f32, al[1] as f32).expect("valid");
        let fp = p::Footprint::from_slope_derivatives(
            p::Vec2::new(du[0] as f32, du[1] as f32),
            p::Vec2::new(dv[0] as f32, dv[1] as f32),
        );
        let h = p::Vec3::new(h64.x as f32, h64.y as f32, h64.z as f32);
        let got = method(a, fp, h) as f64;
        e = e.max((got - want).abs() / want);
    }
    e
}

/// The regions as markdown: a summary table (per method and distance, the smallest footprint
/// ratio of the grid from which on every larger one errs by more than 10 %), then the full
/// map of the first method.
pub fn markdown() -> String {
    let ms = methods();
    let maps: Vec<Vec<Vec<f64>>> = ms
        .iter()
        .map(|(_, m)| {
            RATIOS
                .iter()
                .map(|&r| DISTANCES.iter().map(|&d| worst(m, r, d)).collect())
                .collect()
        })
        .collect();
    let mut md = String::new();
    md += "## Where each approximation is wrong\n\n";
    md += "The smallest footprint width / lobe width (of the grid ";
    md += &list(&RATIOS);
    md += ") from which on the relative error of `D` against the exact Gaussian filter exceeds \
           10 % at every larger footprint, per distance of the half vector from the peak in \
           lobe widths; `-`: nowhere on the grid. GGX `alpha = 0.1`; the worst of four shapes \
           (isotropic footprint; 4:1 footprint with the half vector along its long, then its \
           short axis; anisotropic material `alpha_y = alpha / 4`); each method through the \
           front door with its clamp rules, in `f32`; footprint width = slope change per pixel, \
           kernel `sigma = 0.5` pixel of it (`demo/src/bin/tradeoff/regions.rs`).\n\n";
    md += "| method |";
    for d in DISTANCES {
        md += &format!(" d = {d} |");
    }
    md += " worst on the grid |\n|---|";
    md += &"---:|".repeat(DISTANCES.len() + 1);
    md += "\n";
    for ((name, _), map) in ms.iter().zip(&maps) {
        md += &format!("| {name} |");
        for j in 0..DISTANCES.len() {
            md += &format!(" {} |", onset(map, j));
        }
        let w = map.iter().flatten().fold(0.0f64, |a, &b| a.max(b));
        md += &format!(" {:.0} % |\n", 100.0 * w);
    }
    md += &format!(
        "\nThe map of {} (relative error in %, `.` at or below 10 %; rows: footprint width / \
         lobe width, columns: distance from the peak in lobe widths):\n\n",
        ms[0].0
    );
    md += "| r \\ d |";
    for d in DISTANCES {
        md += &format!(" {d} |");
    }
    md += "\n|---|";
    md += &"---:|".repeat(DISTANCES.len());
    md += "\n";
    for (r, row) in RATIOS.iter().zip(&maps[0]) {
        md += &format!("| {r} |");
        for &e in row {
            if e > LIMIT {
                md += &format!(" {:.0} |", 100.0 * e);
            } else {
                md += " . |";
            }
        }
        md += "\n";
    }
    md
}

/// The smallest ratio of the grid from which on every larger ratio errs by more than 10 % at
/// distance column `j` (`-` if the largest does not).
fn onset(map: &[Vec<f64>], j: usize) -> String {
    let mut first = None;
    for i in (0..RATIOS.len()).rev() {
        if map[i][j] > LIMIT {
            first = Some(i);
        } else {
            break;
        }
    }
    first.map_or("-".into(), |i| format!("{}", RATIOS[i]))
}

fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
