//! The conformance checks: every WGSL function evaluated on seeded cases and compared with
//! the crate's `f64` references, each output within a stated tolerance.
//!
//! A [`Check`] names the WGSL function, holds the snippet that calls it (see
//! [`crate::harness::Kernel`]) and its cases; each case carries the f32 inputs (what the
//! shader reads), the `f64` reference outputs (computed from exactly those f32 values, by
//! the library's `f64` functions, see [`crate::reference`]) and one [`Tol`] per output.
//!
//! **Tolerances.** Every tolerance is `|gpu - reference| <= rel |reference| + abs` with
//! `rel` a count of f32 ulp (`EPS = 2^-23`) derived from the function's operations (WGSL:
//! `+ - *` correctly rounded, `/` 2.5 ulp, `sqrt` about 3 ulp, `exp` `3 + 2|x|` ulp) and,
//! where the function is ill-conditioned, a condition factor computed per case from the
//! `f64` data (stated in each module). `abs` is the flush-to-zero floor `2^-126` scaled by
//! the output's units where results may be subnormal, else 0. The derivation of each is a
//! comment at the check.

pub mod bake;
pub mod filters;
pub mod footprint;
pub mod gaussian_ggx;
pub mod lean_nested;
pub mod math;
pub mod method;
pub mod nan_policy;
pub mod ndf;
pub mod rect;
pub mod rect_sample;
pub mod sampling;
pub mod sampling_beckmann;

use crate::harness::{self, Kernel};

/// A group's checks, built on call (cases and `f64` references).
pub type Group = fn() -> Vec<Check>;

/// Every group of checks: its name (the test of `gpu/tests/conformance.rs` that runs it, and
/// the report's `target/gpu-conformance/<backend>/<name>.tsv`) and its checks.
/// `gpu/tests/coverage.rs` requires every exported WGSL function to be called by one of them.
pub const GROUPS: &[(&str, Group)] = &[
    ("math", math::all),
    ("ndf", ndf::all),
    ("footprint", footprint::all),
    ("filters", filters::all),
    ("rect", rect::all),
    ("rect_sample", rect_sample::all),
    ("nan_policy", nan_policy::all),
    ("gaussian_ggx", gaussian_ggx::all),
    ("method", method::all),
    ("lean_nested", lean_nested::all),
    ("bake", bake::all),
    ("sampling", sampling::all),
    ("sampling_beckmann", sampling_beckmann::all),
];

/// The checks of the group `name` of [`GROUPS`].
pub fn group(name: &str) -> Vec<Check> {
    let (_, all) = GROUPS
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no check group `{name}`"));
    all()
}
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// f32 machine epsilon `2^-23` (one ulp of 1).
pub const EPS: f64 = f32::EPSILON as f64;
/// The smallest normal f32 `2^-126` (GPUs may flush smaller values to 0).
pub const TINY: f64 = f32::MIN_POSITIVE as f64;

/// `|gpu - reference| <= rel |reference| + abs`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tol {
    /// Relative part.
    pub rel: f64,
    /// Absolute part.
    pub abs: f64,
    /// For an absolute tolerance, the magnitude it is measured against (the largest entry
    /// of a matrix, the length of a vector): the report divides the error by it. 0: none.
    pub scale: f64,
}

impl Tol {
    /// An absolute tolerance of `k` EPS times `scale` (the magnitude the error is measured
    /// against), plus the flush-to-zero floor; reported relative to `scale`.
    pub fn of_scale(k: f64, scale: f64) -> Self {
        Self {
            rel: 0.0,
            abs: k * EPS * scale + TINY,
            scale,
        }
    }
}

impl Tol {
    /// `ulps` ulp of f32, relative, plus the flush-to-zero floor.
    pub fn ulps(ulps: f64) -> Self {
        Self {
            rel: ulps * EPS,
            abs: TINY,
            scale: 0.0,
        }
    }

    /// An absolute tolerance only.
    pub fn abs(abs: f64) -> Self {
        Self {
            rel: 0.0,
            abs,
            scale: 0.0,
        }
    }

    /// A relative and an absolute part.
    pub fn rel_abs(rel: f64, abs: f64) -> Self {
        Self {
            rel,
            abs,
            scale: 0.0,
        }
    }
}

/// One case: f32 inputs, f64 reference outputs and their tolerances.
#[derive(Clone, Debug)]
pub struct Case {
    /// The inputs, as the shader reads them.
    pub input: Vec<f32>,
    /// The reference outputs.
    pub expect: Vec<f64>,
    /// One tolerance per output.
    pub tol: Vec<Tol>,
}

/// A WGSL function under test.
pub struct Check {
    /// The WGSL function, `module::function` (e.g. `ggx::d_isotropic`).
    pub name: String,
    /// The stated tolerance and its derivation, in one line.
    pub tolerance: String,
    /// The `#import` lines of the snippet.
    pub imports: String,
    /// The snippet (body of `eval()`).
    pub body: String,
    /// Input slots per case.
    pub n_in: usize,
    /// Output slots per case.
    pub n_out: usize,
    /// The cases.
    pub cases: Vec<Case>,
    /// Textures bound beside the buffers ([`harness::Textures`]), if the snippet samples any.
    pub textures: Option<std::sync::Arc<harness::Textures>>,
}

impl Check {
    /// A check without cases yet.
    pub fn new(name: &str, imports: &str, body: &str, n_in: usize, n_out: usize) -> Self {
        Self {
            name: name.to_string(),
            tolerance: String::new(),
            imports: imports.to_string(),
            body: body.to_string(),
            n_in,
            n_out,
            cases: Vec::new(),
            textures: None,
        }
    }

    /// Binds `textures` for the snippet (declared by [`harness::TEXTURE_DECLARATIONS`]).
    pub fn with_textures(mut self, textures: std::sync::Arc<harness::Textures>) -> Self {
        self.textures = Some(textures);
        self
    }

    /// Sets the stated tolerance.
    pub fn tolerance(mut self, t: &str) -> Self {
        self.tolerance = t.to_string();
        self
    }

    /// Adds a case (inputs rounded to f32 by the caller).
    pub fn case(&mut self, input: Vec<f32>, expect: Vec<f64>, tol: Vec<Tol>) {
        assert_eq!(input.len(), self.n_in, "{}: inputs", self.name);
        assert_eq!(expect.len(), self.n_out, "{}: outputs", self.name);
        assert_eq!(tol.len(), self.n_out, "{}: tolerances", self.name);
        self.cases.push(Case { input, expect, tol });
    }
}

/// What one check measured.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The WGSL function.
    pub name: String,
    /// The number of cases.
    pub cases: usize,
    /// The worst relative error `|gpu - ref| / |ref|` over outputs with a relative
    /// tolerance and `|ref| > 2^-126`.
    pub worst_rel: f64,
    /// The worst absolute error over outputs with an absolute tolerance only (divided by the
    /// tolerance's scale where it has one).
    pub worst_abs: f64,
    /// The worst error as a fraction of its tolerance (`<= 1` passes).
    pub worst_of_tol: f64,
    /// The stated tolerance.
    pub tolerance: String,
    /// The case closest to (or furthest past) its tolerance, described.
    pub worst_case: String,
    /// The first failing cases, described.
    pub failures: Vec<String>,
    /// The number of failing outputs.
    pub n_failed: usize,
}

impl Outcome {
    /// The worst error, `rel 1.2e-7` or `abs 3.0e-7` (or both).
    pub fn worst(&self) -> String {
        match (self.worst_rel > 0.0, self.worst_abs > 0.0) {
            (_, false) => format!("rel {:8.2e}", self.worst_rel),
            (false, true) => format!("abs {:8.2e}", self.worst_abs),
            (true, true) => format!("rel {:8.2e} abs {:8.2e}", self.worst_rel, self.worst_abs),
        }
    }
}

/// Runs a check on the GPU and compares.
pub fn run(check: &Check) -> Result<Outcome, String> {
    let input: Vec<f32> = check.cases.iter().flat_map(|c| c.input.clone()).collect();
    let kernel = Kernel {
        imports: &check.imports,
        body: &check.body,
        n_in: check.n_in,
        n_out: check.n_out,
    };
    if let Some(t) = &check.textures
        && !t.half
        && !harness::float32_filterable()?
    {
        return Ok(Outcome {
            name: check.name.clone(),
            cases: 0,
            worst_rel: 0.0,
            worst_abs: 0.0,
            worst_of_tol: 0.0,
            tolerance: "not run: the adapter lacks float32-filterable".into(),
            worst_case: String::new(),
            failures: Vec::new(),
            n_failed: 0,
        });
    }
    let out = match &check.textures {
        Some(t) => harness::run_textured(&kernel, &input, t),
        None => harness::run(&kernel, &input),
    }
    .map_err(|e| format!("{}: {e}", check.name))?;
    let mut o = Outcome {
        name: check.name.clone(),
        cases: check.cases.len(),
        worst_rel: 0.0,
        worst_abs: 0.0,
        worst_of_tol: 0.0,
        tolerance: check.tolerance.clone(),
        worst_case: String::new(),
        failures: Vec::new(),
        n_failed: 0,
    };
    for (i, c) in check.cases.iter().enumerate() {
        for j in 0..check.n_out {
            let g = f64::from(out[i * check.n_out + j]);
            let r = c.expect[j];
            let t = c.tol[j];
            // Equal values (the same infinity included) differ by 0, not by `inf - inf`, and
            // an absolute tolerance stays absolute at an infinite reference (not `0 inf`).
            let err = if g == r { 0.0 } else { (g - r).abs() };
            let allowed = if t.rel == 0.0 {
                t.abs
            } else {
                t.rel * r.abs() + t.abs
            };
            let ok = err <= allowed;
            // Reported errors: relative where the relative part of the tolerance dominates
            // (`|ref|` well above the absolute part, which is the flush-to-zero floor or a
            // cancellation allowance), absolute for absolute tolerances.
            if t.rel == 0.0 {
                let e = if t.scale > 0.0 { err / t.scale } else { err };
                o.worst_abs = o.worst_abs.max(e);
            } else if r.abs() > TINY && t.rel * r.abs() > 1e3 * t.abs && err.is_finite() {
                o.worst_rel = o.worst_rel.max(err / r.abs());
            }
            let frac = if allowed > 0.0 {
                err / allowed
            } else if err == 0.0 {
                0.0
            } else {
                f64::INFINITY
            };
            let frac = if frac.is_nan() { f64::INFINITY } else { frac };
            if frac > o.worst_of_tol || o.worst_case.is_empty() {
                o.worst_of_tol = o.worst_of_tol.max(frac);
                o.worst_case = format!(
                    "case {i} output {j}: input {:?}, gpu {g:e}, reference {r:e}",
                    c.input
                );
            }
            if !ok {
                o.n_failed += 1;
                if o.failures.len() < 8 {
                    o.failures.push(format!(
                        "case {i} output {j}: input {:?}, gpu {g:e}, reference {r:e}, error {err:.3e} > allowed {allowed:.3e} (rel {:.1e}, abs {:.1e})",
                        c.input, t.rel, t.abs
                    ));
                }
            }
        }
    }
    Ok(o)
}

/// Runs every check of a group, returns the outcomes and a table; the outcomes are also
/// written to `target/gpu-conformance/<backend>/<group>.tsv` for the report.
pub fn run_group(group: &str, checks: &[Check]) -> Result<(Vec<Outcome>, String), String> {
    let gpu = harness::gpu()?;
    let mut outcomes = Vec::new();
    for c in checks {
        outcomes.push(run(c)?);
    }
    let mut table = format!("{group} on {}\n", gpu.label());
    let mut tsv = String::from("function\tcases\tworst\tworst_of_tol\ttolerance\n");
    for o in &outcomes {
        table.push_str(&format!(
            "  {:<44} {:>6} cases  worst {}  {:>6.3} of tol  {}\n",
            o.name,
            o.cases,
            o.worst(),
            o.worst_of_tol,
            if o.n_failed == 0 { "ok" } else { "FAILED" }
        ));
        tsv.push_str(&format!(
            "{}\t{}\t{}\t{:.3}\t{}\n",
            o.name,
            o.cases,
            o.worst(),
            o.worst_of_tol,
            o.tolerance
        ));
        if std::env::var_os("FILTERED_NDF_GPU_VERBOSE").is_some() {
            table.push_str(&format!("      worst: {}\n", o.worst_case));
        }
        for f in &o.failures {
            table.push_str(&format!("      {f}\n"));
        }
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../target/gpu-conformance")
        .join(gpu.backend_name());
    let _ = std::fs::create_dir_all(&dir);
    let _ = std::fs::write(dir.join(format!("{group}.tsv")), tsv);
    Ok((outcomes, table))
}

/// Runs a group and panics with the table if any output is out of tolerance (for tests).
pub fn assert_group(group: &str, checks: &[Check]) {
    let (outcomes, table) = match run_group(group, checks) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    eprintln!("{table}");
    let failed: Vec<&str> = outcomes
        .iter()
        .filter(|o| o.n_failed > 0)
        .map(|o| o.name.as_str())
        .collect();
    assert!(failed.is_empty(), "out of tolerance: {failed:?}\n{table}");
}

/// `n` values drawn from a proptest strategy of the crate's `testing` feature, with a fixed
/// seed derived from `label` (the same values on every run and machine).
pub fn draw<S: Strategy>(strategy: S, n: usize, label: &str) -> Vec<S::Value> {
    let mut seed = [0u8; 32];
    for (i, b) in label.bytes().enumerate() {
        seed[i % 32] ^= b;
    }
    seed[31] ^= 0x5a;
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    (0..n)
        .map(|_| {
            strategy
                .new_tree(&mut runner)
                .expect("strategy draws")
                .current()
        })
        .collect()
}

/// A value rounded to f32 and back (the exact input the shader sees).
pub fn r32(x: f64) -> f64 {
    f64::from(x as f32)
}
