//! The speed/accuracy trade table: for every kernel, its error against the f64 exact
//! filtered NDF and its cost per evaluation, as a markdown table and
//! an SVG scatter plot (error vs. cost, log-log).
//!
//! `cargo run --release -p filtered-ndf-demo --bin tradeoff [-- --cases N] [--out DIR]`
//!
//! - The exact filtered NDF is the GGX (or Beckmann) slope density convolved with the
//!   Gaussian pixel footprint `Sigma = 0.25 (dh_u dh_u^T + dh_v dh_v^T)` (KHPL16 eq. 12-13,
//!   TK19 section 2.2), per steradian (`/ h_z^4`), in f64: for GGX the crate's exact
//!   Gaussian-filtered GGX (`GaussianFilteredGgx`, the mixture identity with a proven bound of
//!   1.1e-11 relative, tested against 2-D quadrature of the convolution in
//!   `tests/gaussian_ggx.rs`), for Beckmann its closed form `A + 2 Sigma` (KHPL16 eq. 15).
//! - Inputs: the seeded realistic cases of `filtered_ndf::testing::shading` (the benchmarks use the same),
//!   plus extremes (roughness 1e-3 and 1e-4 with tiny footprints, grazing half vectors,
//!   footprints of slope 1).
//! - Kernels run in f32 (the shading precision) with the papers' default clamps. Deferred
//!   (normal-difference) kernels are given `dn = dh`, the near-normal assumption of KHPL16
//!   section 5.4; for an anisotropic material their kernel is added to both axes.
//! - Cost: wall time per evaluation over the whole case set, in one process (ratios between
//!   rows are what matter; `cargo bench` has the criterion figures).
//! - The exact Gaussian filter is measured at each accuracy setting (`Tolerance`), a curve
//!   in the plot; the which-kernel guide's figures (`src/doc/which_kernel.md` and the README's copy, module
//!   `figures`) and the regions where the approximations err by more than 10 % (module
//!   `regions`, appended to `tradeoff.md`) come from the same run.

use filtered_ndf::testing::shading as common;

use filtered_ndf::f32 as p;
use filtered_ndf::f64 as q;
use p::Ndf as _;
use p::filter::{ExactGaussian, Filterable, Gaussian, Projected, Proxy, Rect, Tolerance};

/// The exact Gaussian filter's row name (its reduced settings add the setting's name).
const EXACT: &str = "GGX exact Gaussian (this crate)";
/// The front door's exact Beckmann filter (the which-kernel guide's `forward_beckmann`).
const BECKMANN_FRONT_DOOR: &str = "Beckmann Gaussian::KHPL16 (front door, exact)";
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod figures;
mod regions;

/// One case in both precisions, with its reference.
struct Case {
    alpha: p::AxisAligned,
    h: p::Vec3,
    fp: p::Footprint,
    dn_u: p::Vec3,
    dn_v: p::Vec3,
    /// Exact Gaussian-filtered GGX and Beckmann D(h), per steradian.
    ref_ggx: f64,
    ref_beckmann: f64,
    /// The exact filtered GGX peak (at the lobe centre), per unit slope area / h_z^4.
    ref_ggx_peak: f64,
}

fn cases(n: usize) -> Vec<common::Case> {
    let mut all = common::realistic_cases(n, 0x5EED);
    // Extremes: tiny lobes with tiny and huge footprints, grazing half vectors.
    let mut rng = common::Rng(0xE77E);
    for i in 0..n / 8 {
        let a = [1e-3, 1e-4][i % 2];
        let ext = [1e-6, 1e-3, 1.0][i % 3];
        let t = [0.0f64, 60.0, 85.0][(i / 3) % 3].to_radians();
        let phi = std::f64::consts::TAU * rng.uniform();
        let p1 = std::f64::consts::TAU * rng.uniform();
        all.push(common::Case {
            alpha: [a, a],
            h: [t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos()],
            dh_u: [ext * p1.cos(), ext * p1.sin()],
            dh_v: [-0.3 * ext * p1.sin(), 0.3 * ext * p1.cos()],
        });
    }
    all
}

fn reference(k: &common::Case) -> (f64, f64, f64) {
    use q::Ndf as _;
    let r = q::AxisAligned::new(k.alpha[0], k.alpha[1]).expect("valid");
    let fp = q::Footprint::from_slope_derivatives(k.dh_u.into(), k.dh_v.into());
    let kernel = fp.covariance(0.5);
    let h: q::Vec3 = k.h.into();
    let exact = q::GaussianFilteredGgx::new(r, kernel);
    let g = exact.d(h);
    let b = q::Beckmann::new(q::filter::gaussian(r, kernel)).d(h);
    let peak = exact.p22(q::Vec2::ZERO) / k.h[2].powi(4);
    (g, b, peak)
}

fn build(n: usize) -> Vec<Case> {
    let raw = cases(n);
    let chunks: Vec<&[common::Case]> = raw.chunks(raw.len().div_ceil(2)).collect();
    let refs: Vec<(f64, f64, f64)> = std::thread::scope(|s| {
        let hs: Vec<_> = chunks
            .iter()
            .map(|c| s.spawn(move || c.iter().map(reference).collect::<Vec<_>>()))
            .collect();
        hs.into_iter()
            .flat_map(|h| h.join().expect("reference thread"))
            .collect()
    });
    raw.iter()
        .zip(refs)
        .map(|(k, (g, b, pk))| Case {
            alpha: p::AxisAligned::new(k.alpha[0] as f32, k.alpha[1] as f32).expect("valid"),
            h: p::Vec3::new(k.h[0] as f32, k.h[1] as f32, k.h[2] as f32),
            fp: p::Footprint::from_slope_derivatives(
                p::Vec2::new(k.dh_u[0] as f32, k.dh_u[1] as f32),
                p::Vec2::new(k.dh_v[0] as f32, k.dh_v[1] as f32),
            ),
            dn_u: p::Vec3::new(k.dh_u[0] as f32, k.dh_u[1] as f32, 0.0),
            dn_v: p::Vec3::new(k.dh_v[0] as f32, k.dh_v[1] as f32, 0.0),
            ref_ggx: g,
            ref_beckmann: b,
            ref_ggx_peak: pk,
        })
        .collect()
}

/// A kernel under test: the filtered D(h) of one case, in f32.
type Kernel = Box<dyn Fn(&Case) -> f32>;

fn sigma() -> f32 {
    p::kernel::SIGMA_PIXEL
}

/// The deferred kernels: one isotropic increment added to both axes of the material.
fn deferred(c: &Case, conv: p::KernelConvention) -> f32 {
    let a = c.alpha.alpha();
    let ax = conv.apply(a.x, c.dn_u, c.dn_v);
    let ay = conv.apply(a.y, c.dn_u, c.dn_v);
    p::Ggx::new(p::AxisAligned::new_clamped(ax, ay)).d(c.h)
}

fn rect_half_extent(c: &Case, rules: p::ClampRules) -> p::Vec2 {
    rules
        .rect(c.fp.bounding_rect(), c.alpha.alpha())
        .half_extent
}

fn ggx_kernels() -> Vec<(String, Kernel)> {
    let mut k: Vec<(String, Kernel)> = vec![
        (
            "GGX unfiltered".into(),
            Box::new(|c: &Case| p::Ggx::new(c.alpha).d(c.h)),
        ),
        (
            EXACT.into(),
            Box::new(|c: &Case| {
                p::Ggx::new(c.alpha)
                    .filtered(c.fp, ExactGaussian::KHPL16)
                    .d(c.h)
            }),
        ),
    ];
    // The trade inside the exact filter: each reduced accuracy setting (a point of its curve).
    for t in &Tolerance::ALL[1..] {
        let m = ExactGaussian::KHPL16.with_tolerance(*t);
        k.push((
            format!("{EXACT} {t:?}"),
            Box::new(move |c: &Case| p::Ggx::new(c.alpha).filtered(c.fp, m).d(c.h)),
        ));
    }
    k.extend::<[(String, Kernel); 7]>([
        (
            "GGX TK19 A+2Sigma (matrix)".into(),
            Box::new(|c: &Case| p::Ggx::new(c.alpha).filtered(c.fp, Gaussian::TK19).d(c.h)),
        ),
        (
            "GGX TK19 A+2Sigma, no clamps".into(),
            Box::new(|c: &Case| {
                let none = Gaussian {
                    clamps: p::ClampRules::NONE,
                    ..Gaussian::TK19
                };
                p::Ggx::new(c.alpha).filtered(c.fp, none).d(c.h)
            }),
        ),
        (
            "GGX TK21 projected".into(),
            Box::new(|c: &Case| p::Ggx::new(c.alpha).filtered(c.fp, Projected::TK21).d(c.h)),
        ),
        (
            "GGX exact rect (bounding box)".into(),
            Box::new(|c: &Case| p::Ggx::new(c.alpha).filtered(c.fp, Rect::KHPL16).d(c.h)),
        ),
        (
            "GGX printed 8-term rect (GDC, eps floor)".into(),
            Box::new(|c: &Case| {
                let he = rect_half_extent(c, p::ClampRules::default());
                let hpp = p::footprint::slope::slope_from_sphere(c.h);
                p::filter::rect::d_rect_printed(c.alpha, hpp, c.h, he)
            }),
        ),
        (
            "GGX proxy exact (eq. 19)".into(),
            Box::new(|c: &Case| p::Ggx::new(c.alpha).filtered(c.fp, Proxy::KHPL16).d(c.h)),
        ),
        (
            "GGX proxy simple (eq. 20)".into(),
            Box::new(|c: &Case| {
                let he = rect_half_extent(c, p::ClampRules::default());
                p::Ggx::new(p::filter::proxy::proxy_simple(c.alpha, he)).d(c.h)
            }),
        ),
    ]);
    for (name, conv) in p::filter::presets::ALL {
        k.push((
            format!("GGX deferred: {name}"),
            Box::new(move |c: &Case| deferred(c, conv)),
        ));
    }
    k
}

fn beckmann_kernels() -> Vec<(String, Kernel)> {
    vec![
        (
            "Beckmann unfiltered".into(),
            Box::new(|c: &Case| p::Beckmann::new(c.alpha).d(c.h)),
        ),
        (
            "Beckmann KHPL16 A+2Sigma (exact)".into(),
            Box::new(|c: &Case| {
                let a = p::filter::gaussian(c.alpha, c.fp.covariance(sigma()));
                p::Beckmann::new(a).d(c.h)
            }),
        ),
        (
            BECKMANN_FRONT_DOOR.into(),
            Box::new(|c: &Case| {
                p::Beckmann::new(c.alpha)
                    .filtered(c.fp, Gaussian::KHPL16)
                    .d(c.h)
            }),
        ),
        (
            "Beckmann A+2Sigma, default clamps".into(),
            Box::new(|c: &Case| {
                p::Beckmann::new(c.alpha)
                    .filtered(c.fp, Gaussian::TK19)
                    .d(c.h)
            }),
        ),
    ]
}

/// Supersampling: the unfiltered NDF averaged over `n` points of the Gaussian footprint
/// (seeded standard-normal jitter), which is what a renderer does without this crate.
fn supersampled(c: &Case, jitter: &[(f32, f32)], beckmann: bool) -> f32 {
    let s0 = p::footprint::slope::slope_from_sphere(c.h);
    let mut acc = 0.0f32;
    for &(a, b) in jitter {
        let m = p::footprint::slope::sphere_from_slope(
            s0 + c.fp.dh_u * (a * sigma()) + c.fp.dh_v * (b * sigma()),
        );
        acc += if beckmann {
            p::Beckmann::new(c.alpha).d(m)
        } else {
            p::Ggx::new(c.alpha).d(m)
        };
    }
    acc / jitter.len() as f32
}

struct Row {
    name: String,
    family: &'static str,
    median: f64,
    p99: f64,
    max: f64,
    max_peak: f64,
    ns: f64,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i]
}

fn measure(name: String, family: &'static str, cases: &[Case], f: &dyn Fn(&Case) -> f32) -> Row {
    let beck = family == "Beckmann";
    let mut rel: Vec<f64> = Vec::with_capacity(cases.len());
    let mut max_peak = 0.0f64;
    for c in cases {
        let v = f(c) as f64;
        let r = if beck { c.ref_beckmann } else { c.ref_ggx };
        let e = (v - r).abs();
        // Relative error; where the reference underflows f32's normal range, absolute.
        rel.push(if r > 1e-30 { e / r } else { e });
        if !beck && c.ref_ggx_peak > 0.0 {
            max_peak = max_peak.max(e / c.ref_ggx_peak);
        }
    }
    rel.sort_by(f64::total_cmp);
    // Cost: the fastest of five blocks, each repeating the whole set for at least 6 ms of
    // this thread's CPU time (the minimum and the CPU clock filter out interference from other
    // processes on a shared machine: time spent descheduled does not count).
    // The clock is read once per block (a read costs microseconds): the block's pass count
    // doubles until a block takes 6 ms.
    let block = |passes: usize| -> f64 {
        let start = cpu_ns();
        for _ in 0..passes {
            for c in cases {
                black_box(f(black_box(c)));
            }
        }
        cpu_ns() - start
    };
    let mut passes = 1usize;
    while block(passes) < 6e6 {
        passes *= 2;
    }
    let mut ns = f64::INFINITY;
    for _ in 0..5 {
        ns = ns.min(block(passes) / (passes * cases.len()) as f64);
    }
    Row {
        name,
        family,
        median: percentile(&rel, 0.5),
        p99: percentile(&rel, 0.99),
        max: *rel.last().unwrap_or(&0.0),
        max_peak: if beck { f64::NAN } else { max_peak },
        ns,
    }
}

/// One log-log scatter panel (cost on x, an error on y) at `(ox, oy)`, points numbered.
fn panel(s: &mut String, all: &[Row], err: &dyn Fn(&Row) -> Option<f64>, title: &str, ox: f64) {
    let (w, h, m, oy) = (520.0, 440.0, 60.0, 40.0);
    // Keep the legend numbering of `all`; skip rows without this error.
    let shown: Vec<(usize, &Row, f64)> = all
        .iter()
        .enumerate()
        .filter_map(|(i, r)| err(r).map(|e| (i, r, e.clamp(1e-9, 1e9))))
        .collect();
    let rows: Vec<&Row> = shown.iter().map(|t| t.1).collect();
    let pts: Vec<(f64, f64)> = shown.iter().map(|t| (t.1.ns.max(0.5), t.2)).collect();
    let lx = |v: f64| v.log10();
    let x0 = pts
        .iter()
        .map(|p| lx(p.0))
        .fold(f64::INFINITY, f64::min)
        .floor();
    let x1 = pts
        .iter()
        .map(|p| lx(p.0))
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil();
    let y0 = pts
        .iter()
        .map(|p| lx(p.1))
        .fold(f64::INFINITY, f64::min)
        .floor();
    let y1 = pts
        .iter()
        .map(|p| lx(p.1))
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil();
    let sx = |x: f64| ox + m + (lx(x) - x0) / (x1 - x0).max(1.0) * (w - 1.5 * m);
    let sy = |y: f64| oy + h - m - (lx(y) - y0) / (y1 - y0).max(1.0) * (h - 1.5 * m);
    *s += &format!(
        "<text x=\"{}\" y=\"{}\" font-size=\"13\" text-anchor=\"middle\">{title}</text>\n",
        ox + w / 2.0,
        oy + 12.0
    );
    for d in (x0 as i32)..=(x1 as i32) {
        let x = sx(10f64.powi(d));
        *s += &format!(
            "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{d}</text>\n",
            sy(10f64.powi(y1 as i32)),
            oy + h - m,
            oy + h - m + 14.0
        );
    }
    for d in (y0 as i32)..=(y1 as i32) {
        let y = sy(10f64.powi(d));
        *s += &format!(
            "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{d}</text>\n",
            ox + m,
            sx(10f64.powi(x1 as i32)),
            ox + m - 4.0,
            y + 4.0
        );
    }
    *s += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">ns per evaluation (f32)</text>\n",
        ox + w / 2.0,
        oy + h - m + 30.0
    );
    let ss: Vec<String> = rows
        .iter()
        .zip(&pts)
        .filter(|(r, _)| r.name.contains("supersampling"))
        .map(|(_, p)| format!("{},{}", sx(p.0), sy(p.1)))
        .collect();
    *s += &format!(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#c33\" stroke-width=\"1.5\"/>\n",
        ss.join(" ")
    );
    // The exact Gaussian filter's accuracy settings, as a curve.
    let ex: Vec<String> = rows
        .iter()
        .zip(&pts)
        .filter(|(r, _)| r.name.starts_with(EXACT))
        .map(|(_, p)| format!("{},{}", sx(p.0), sy(p.1)))
        .collect();
    *s += &format!(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#33c\" stroke-width=\"1.5\" stroke-dasharray=\"4 3\"/>\n",
        ex.join(" ")
    );
    for ((i, r, _), p) in shown.iter().zip(&pts) {
        let (x, y) = (sx(p.0), sy(p.1));
        *s += &format!(
            "<circle cx=\"{x}\" cy=\"{y}\" r=\"3.5\" fill=\"{}\"/><text x=\"{}\" y=\"{}\" font-size=\"10\">{}</text>\n",
            color(r),
            x + 4.0,
            y - 3.0,
            i + 1
        );
    }
}

fn color(r: &Row) -> &'static str {
    if r.name.contains("supersampling") {
        "#c33"
    } else if r.family == "Beckmann" {
        "#393"
    } else if r.name.contains("deferred") {
        "#a6a"
    } else {
        "#33c"
    }
}

fn svg(rows: &[Row], path: &std::path::Path) -> std::io::Result<()> {
    // Beckmann rows have no peak-relative error: the right panel shows GGX rows only.
    let legend_lines = rows.len().div_ceil(2);
    let (w, h) = (1080.0, 500.0 + 16.0 * legend_lines as f64);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"20\" font-size=\"15\" text-anchor=\"middle\">Filtered NDF kernels vs the exact Gaussian-filtered NDF: error against cost (log-log)</text>\n",
        w / 2.0
    );
    panel(
        &mut s,
        rows,
        &|r| Some(r.median),
        "median relative error",
        10.0,
    );
    panel(
        &mut s,
        rows,
        &|r| (!r.max_peak.is_nan()).then_some(r.max_peak),
        "worst error / exact filtered peak (GGX)",
        550.0,
    );
    for (i, r) in rows.iter().enumerate() {
        let (col, line) = (i / legend_lines, i % legend_lines);
        s += &format!(
            "<text x=\"{}\" y=\"{}\" fill=\"{}\">{:>2}. {}</text>\n",
            40.0 + 520.0 * col as f64,
            500.0 + 16.0 * line as f64,
            color(r),
            i + 1,
            r.name.replace('&', "and")
        );
    }
    s += "</svg>\n";
    std::fs::write(path, s)
}

/// This thread's CPU time in nanoseconds (Linux: `/proc/thread-self/schedstat`, the time on
/// the CPU in ns); elsewhere the wall clock since the first call.
fn cpu_ns() -> f64 {
    if let Some(t) = std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
    {
        return t;
    }
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_nanos() as f64
}

/// The CPU model from `/proc/cpuinfo` where there is one, else the architecture.
fn cpu_name() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}

fn main() -> std::io::Result<()> {
    let mut n = 400;
    let mut out = std::path::PathBuf::from("target/tradeoff");
    let args: Vec<String> = std::env::args().skip(1).collect();
    for w in args.windows(2) {
        match w[0].as_str() {
            "--cases" => n = w[1].parse().expect("--cases N"),
            "--out" => out = w[1].clone().into(),
            _ => {}
        }
    }
    std::fs::create_dir_all(&out)?;
    let t0 = Instant::now();
    let cases = build(n);
    eprintln!(
        "{} cases, f64 references in {:.1} s",
        cases.len(),
        t0.elapsed().as_secs_f64()
    );

    let mut rows: Vec<Row> = Vec::new();
    for (name, k) in ggx_kernels() {
        rows.push(measure(name, "GGX", &cases, &*k));
    }
    for (name, k) in beckmann_kernels() {
        rows.push(measure(name, "Beckmann", &cases, &*k));
    }
    let mut rng = common::Rng(0x1177);
    let jitter: Vec<(f32, f32)> = (0..4096)
        .map(|_| (rng.normal() as f32, rng.normal() as f32))
        .collect();
    let ns_list = [1usize, 4, 16, 64, 256, 1024, 4096];
    let mut ss_rows = Vec::new();
    for &nn in &ns_list {
        let js = jitter[..nn].to_vec();
        let (name, family) = (format!("GGX supersampling N={nn}"), "GGX");
        // The cost loop repeats the set; for large N use a subset to stay within budget.
        ss_rows.push(measure(name, family, &cases, &move |c: &Case| {
            supersampled(c, &js, false)
        }));
    }
    let needed = |err: f64| -> String {
        ns_list
            .iter()
            .zip(&ss_rows)
            .find(|(_, r)| r.median <= err)
            .map(|(nn, _)| nn.to_string())
            .unwrap_or_else(|| format!(">{}", ns_list[ns_list.len() - 1]))
    };

    let ggx_base = rows[0].ns;
    let beck_base = rows
        .iter()
        .find(|r| r.name == "Beckmann unfiltered")
        .map(|r| r.ns)
        .unwrap_or(1.0);
    let mut md = String::new();
    md += &format!(
        "Measured on {} cases ({} realistic + extremes), f32 kernels vs the f64 exact \
         Gaussian-filtered NDF (GGX: `GaussianFilteredGgx`, within 1.1e-11 of the convolution; \
         Beckmann: `A + 2 Sigma`); machine: {}, {} cores. Costs are single-threaded CPU \
         time in one run (the thread's own, so that a busy machine's descheduling does not \
         count): compare ratios.\n\n",
        cases.len(),
        n,
        cpu_name(),
        std::thread::available_parallelism().map_or(1, |n| n.get()),
    );
    md += "| kernel | median rel. err | p99 rel. err | max rel. err | max err / filtered peak | ns / eval | cost vs unfiltered | supersampling N for same median |\n";
    md += "|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for r in rows.iter().chain(&ss_rows) {
        let base = if r.family == "Beckmann" {
            beck_base
        } else {
            ggx_base
        };
        let ss_n = if r.name.contains("supersampling") {
            "-".to_string()
        } else if r.family == "GGX" {
            needed(r.median)
        } else {
            "-".to_string()
        };
        let peak = if r.max_peak.is_nan() {
            "-".to_string()
        } else {
            format!("{:.2e}", r.max_peak)
        };
        md += &format!(
            "| {} | {:.2e} | {:.2e} | {:.2e} | {} | {:.1} | {:.1}x | {} |\n",
            r.name,
            r.median,
            r.p99,
            r.max,
            peak,
            r.ns,
            r.ns / base,
            ss_n
        );
    }
    let fig = figures::markdown(&rows, ggx_base, beck_base);
    md += "\n";
    md += &regions::markdown();
    print!("{md}");
    std::fs::write(out.join("tradeoff.md"), &md)?;
    figures::write(&repository_root(), &fig)?;
    let mut all = rows;
    all.extend(ss_rows);
    svg(&all, &out.join("tradeoff.svg"))?;
    eprintln!(
        "wrote {} and {} in {:.1} s",
        out.join("tradeoff.md").display(),
        out.join("tradeoff.svg").display(),
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The repository's root (this crate is `demo/` in it).
fn repository_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}
