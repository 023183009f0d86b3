//! The oracle's GPU backend (`--backend gpu`): the same JSON lines answered through the WGSL
//! modules of `shaders/` in f32, so that a shader author can diff a port against ours and ours
//! against the CPU references (`cargo run -p filtered-ndf-gpu --bin oracle-gpu -- --backend gpu`).
//!
//! Design. Every line is first checked by the CPU evaluator in `f32` (the same argument
//! parsing, the same error messages for bad input; `eval::eval_line`); a valid line of an op
//! with a shader becomes a *job*: its arguments encoded as f32 slots of that op's kernel (one
//! WGSL snippet per op, which calls the shader modules as a shader author would). The jobs of
//! a session are batched: one dispatch per kernel (the five NDF ops share one), then the
//! answers are written in input order. So the backend reads its whole input before answering
//! (the CPU backend answers line by line). Ops without a shader (`temporal`) answer an error
//! naming the op; `"precision": "f64"` answers an error (WGSL has no f64); the default and
//! `"f32"` evaluate in f32. The shaders' `F32_MAX` (their stand-in for `+inf`, e.g. `Lambda` at
//! grazing) is written as `"inf"`, as the CPU backend writes infinities.

// The CPU evaluator's argument parsing.
use crate::harness::{self, Kernel};
use filtered_ndf_oracle::args::{
    ClampArg, ClampPreset, Dist, FloorArg, FootprintArg, Point, RoughnessArg, array, clamps_arg,
    dist, footprint_arg, kernel_arg, number, opt_non_negative, opt_number, point, roughness_arg,
    string,
};
use serde_json::{Value, json};

/// The shader modules every kernel may use, and the decoders of the common argument slots.
const IMPORTS: &str = "#import filtered_ndf::math
#import filtered_ndf::ndf::roughness::isotropic
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::footprint
#import filtered_ndf::footprint::jacobian
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::rect
#import filtered_ndf::filter::rect::lambda as box_lambda
#import filtered_ndf::filter::proxy
#import filtered_ndf::filter::deferred
#import filtered_ndf::filter::presets
#import filtered_ndf::filter::rect::lobe
#import filtered_ndf::sampling
#import filtered_ndf::sampling::beckmann as beckmann_sampling

// A roughness in 5 slots: [form, p0, p1, p2, p3], form 0 isotropic (alpha), 1 axis-aligned
// (ax, ay), 2 matrix (a11, a12, a22, det A from the host in f64 of the f32 entries).
fn oracle_matrix(j: u32) -> matrix::RoughnessMatrix {
    let form = x(j);
    if form == 0.0 {
        return isotropic::to_matrix(isotropic::from_alpha(x(j + 1u)));
    }
    if form == 1.0 {
        return axis_aligned::to_matrix(axis_aligned::from_alpha(x2(j + 1u)));
    }
    return matrix::from_entries_det(x(j + 1u), x(j + 2u), x(j + 3u), x(j + 4u), 0.0);
}

fn oracle_axis_aligned(j: u32) -> axis_aligned::AxisAligned {
    if x(j) == 0.0 {
        return axis_aligned::from_alpha(vec2<f32>(x(j + 1u)));
    }
    return axis_aligned::from_alpha(x2(j + 1u));
}

// A footprint in 8 slots: [kind, ...]: 0 slope (u, v), 1 projected (u, v), 2 projected in
// slope (h, u, v), 3 normal differences (du, dv).
fn oracle_footprint(j: u32) -> footprint::Footprint {
    let kind = x(j);
    if kind == 0.0 {
        return footprint::from_slope_derivatives(x2(j + 1u), x2(j + 3u));
    }
    if kind == 1.0 {
        return footprint::from_projected_derivatives(x2(j + 1u), x2(j + 3u));
    }
    if kind == 2.0 {
        return footprint::from_projected_derivatives_in_slope(x3(j + 1u), x2(j + 4u), x2(j + 6u));
    }
    return footprint::from_normal_differences(x3(j + 1u), x3(j + 4u));
}

// Clamp rules in 5 slots: [max_extent, floor kind, floor, kappa, det_clamp] (F32_MAX: off).
fn oracle_rules(j: u32) -> clamp::ClampRules {
    return clamp::ClampRules(x(j), u32(x(j + 1u)), x(j + 2u), x(j + 3u), x(j + 4u) != 0.0);
}

// The NDF ops on one form: what 0 D(a), 1 P22(a.xy), 2 Lambda(a), 3 G1(a, b), 4 G2(a, b, c).
fn ndf_isotropic(what: u32, ggx_dist: bool, r: isotropic::Isotropic, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>) -> f32 {
    if ggx_dist {
        switch what {
            case 0u: { return ggx::d_isotropic(r, a); }
            case 1u: { return ggx::p22_isotropic(r, a.xy); }
            case 2u: { return ggx::lambda_isotropic(r, a); }
            case 3u: { return ggx::g1_isotropic(r, a, b); }
            default: { return ggx::g2_isotropic(r, a, b, c); }
        }
    }
    switch what {
        case 0u: { return beckmann::d_isotropic(r, a); }
        case 1u: { return beckmann::p22_isotropic(r, a.xy); }
        case 2u: { return beckmann::lambda_isotropic(r, a); }
        case 3u: { return beckmann::g1_isotropic(r, a, b); }
        default: { return beckmann::g2_isotropic(r, a, b, c); }
    }
}

fn ndf_axis_aligned(what: u32, ggx_dist: bool, r: axis_aligned::AxisAligned, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>) -> f32 {
    if ggx_dist {
        switch what {
            case 0u: { return ggx::d_axis_aligned(r, a); }
            case 1u: { return ggx::p22_axis_aligned(r, a.xy); }
            case 2u: { return ggx::lambda_axis_aligned(r, a); }
            case 3u: { return ggx::g1_axis_aligned(r, a, b); }
            default: { return ggx::g2_axis_aligned(r, a, b, c); }
        }
    }
    switch what {
        case 0u: { return beckmann::d_axis_aligned(r, a); }
        case 1u: { return beckmann::p22_axis_aligned(r, a.xy); }
        case 2u: { return beckmann::lambda_axis_aligned(r, a); }
        case 3u: { return beckmann::g1_axis_aligned(r, a, b); }
        default: { return beckmann::g2_axis_aligned(r, a, b, c); }
    }
}

fn ndf_matrix(what: u32, ggx_dist: bool, r: matrix::RoughnessMatrix, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>) -> f32 {
    if ggx_dist {
        switch what {
            case 0u: { return ggx::d_matrix(r, a); }
            case 1u: { return ggx::p22_matrix(r, a.xy); }
            case 2u: { return ggx::lambda_matrix(r, a); }
            case 3u: { return ggx::g1_matrix(r, a, b); }
            default: { return ggx::g2_matrix(r, a, b, c); }
        }
    }
    switch what {
        case 0u: { return beckmann::d_matrix(r, a); }
        case 1u: { return beckmann::p22_matrix(r, a.xy); }
        case 2u: { return beckmann::lambda_matrix(r, a); }
        case 3u: { return beckmann::g1_matrix(r, a, b); }
        default: { return beckmann::g2_matrix(r, a, b, c); }
    }
}

// A point in 4 slots: [kind, p0, p1, p2], kind 0 D(m), 1 P22(slope), 2 Lambda(w), 3 the lobe.
fn point_ggx_matrix(r: matrix::RoughnessMatrix, j: u32) -> f32 {
    let k = x(j);
    if k == 0.0 {
        return ggx::d_matrix(r, x3(j + 1u));
    }
    if k == 1.0 {
        return ggx::p22_matrix(r, x2(j + 1u));
    }
    return ggx::lambda_matrix(r, x3(j + 1u));
}

fn point_beckmann_matrix(r: matrix::RoughnessMatrix, j: u32) -> f32 {
    let k = x(j);
    if k == 0.0 {
        return beckmann::d_matrix(r, x3(j + 1u));
    }
    if k == 1.0 {
        return beckmann::p22_matrix(r, x2(j + 1u));
    }
    return beckmann::lambda_matrix(r, x3(j + 1u));
}

fn point_rect(lobe: lobe::RectFilteredGgx, j: u32) -> f32 {
    let k = x(j);
    if k == 0.0 {
        return lobe::d_rect_filtered(lobe, x3(j + 1u));
    }
    if k == 1.0 {
        return lobe::p22_rect_filtered(lobe, x2(j + 1u));
    }
    return lobe::lambda_rect_filtered(lobe, x3(j + 1u));
}";

/// One kernel: the body of `eval()` and its slots.
struct GpuKernel {
    name: &'static str,
    body: &'static str,
    n_in: usize,
    n_out: usize,
}

const NDF: GpuKernel = GpuKernel {
    name: "ndf",
    body: "let what = u32(x(0u));
let g = x(1u) == 0.0;
let form = x(2u);
let a = x3(7u);
let b = x3(10u);
let c = x3(13u);
var v = 0.0;
if form == 0.0 {
    v = ndf_isotropic(what, g, isotropic::from_alpha(x(3u)), a, b, c);
} else if form == 1.0 {
    v = ndf_axis_aligned(what, g, axis_aligned::from_alpha(x2(3u)), a, b, c);
} else {
    v = ndf_matrix(what, g, oracle_matrix(2u), a, b, c);
}
y(0u, v);",
    n_in: 16,
    n_out: 1,
};

const PDF: GpuKernel = GpuKernel {
    name: "pdf",
    body: "let r = oracle_matrix(0u);
if x(11u) == 1.0 {
    y(0u, beckmann_sampling::visible_normal_pdf(r, x3(5u), x3(8u)));
} else {
    y(0u, sampling::visible_normal_pdf(r, x3(5u), x3(8u)));
}",
    n_in: 12,
    n_out: 1,
};

const SAMPLE: GpuKernel = GpuKernel {
    name: "sample",
    body: "let r = oracle_matrix(0u);
if x(10u) == 1.0 {
    y3(0u, beckmann_sampling::sample_visible_normal(r, x3(5u), x2(8u)));
} else {
    y3(0u, sampling::sample_visible_normal(r, x3(5u), x2(8u)));
}",
    n_in: 11,
    n_out: 3,
};

const JACOBIAN: GpuKernel = GpuKernel {
    name: "jacobian",
    body: "let k = x(0u);
let h = x3(1u);
var m = jacobian::sphere_to_slope(h);
if k == 1.0 {
    m = jacobian::sphere_to_projected(h);
} else if k == 2.0 {
    m = jacobian::projected_to_slope(h);
}
y2(0u, m[0]);
y2(2u, m[1]);",
    n_in: 4,
    n_out: 4,
};

const ISOTROPIC: GpuKernel = GpuKernel {
    name: "isotropic_roughness",
    body: "let s = deferred::normal_difference_covariance(x3(1u), x3(4u), footprint::SIGMA_PIXEL);
y(0u, deferred::filtered_alpha(x(0u), s, u32(x(7u)), x(8u)));",
    n_in: 9,
    n_out: 1,
};

const PRESET: GpuKernel = GpuKernel {
    name: "preset",
    body: "let v = deferred::apply(presets::preset(u32(x(0u))), x(1u), x3(2u), x3(5u));
y(0u, select(min(max(v, 1e-8), 1e4), v, x(8u) != 0.0));",
    n_in: 9,
    n_out: 1,
};

const FILTER_ROUGHNESS: GpuKernel = GpuKernel {
    name: "filter_roughness",
    body: "let k = covariance::from_footprint(oracle_footprint(5u), x(13u));
var af: matrix::RoughnessMatrix;
if x(14u) == 0.0 {
    af = gaussian::gaussian(oracle_matrix(0u), k);
} else {
    af = projected::projected(oracle_matrix(0u), k);
}
y3(0u, matrix::entries(af));",
    n_in: 15,
    n_out: 3,
};

const GGX_RECT: GpuKernel = GpuKernel {
    name: "ggx_rect",
    body: "y(0u, rect::p22_rect(axis_aligned::from_alpha(x2(0u)), x2(2u), x2(4u)));",
    n_in: 6,
    n_out: 1,
};

const GGX_RECT_FOOTPRINT: GpuKernel = GpuKernel {
    name: "ggx_rect_footprint",
    body: "let r = axis_aligned::from_alpha(x2(0u));
let he = clamp::rect(oracle_rules(10u), bounding::from_footprint(oracle_footprint(2u)), r.alpha).half_extent;
let lobe = lobe::RectFilteredGgx(r, he);
if x(15u) == 3.0 {
    y2(0u, he);
} else {
    y(0u, point_rect(lobe, 15u));
}",
    n_in: 19,
    n_out: 2,
};

const GGX_PROXY: GpuKernel = GpuKernel {
    name: "ggx_proxy",
    body: "y(0u, select(proxy::effective_alpha(x(0u), x(1u)), proxy::effective_alpha_simple(x(0u), x(1u)), x(2u) != 0.0));",
    n_in: 3,
    n_out: 1,
};

/// `filtered`: [method, dist, roughness (5), footprint (8), clamps (5), sigma, point (4)];
/// method 0 Gaussian, 1 ExactGaussian, 2 Projected, 3 Rect, 4 Proxy.
const FILTERED: GpuKernel = GpuKernel {
    name: "filtered",
    body: "let mth = x(0u);
let g = x(1u) == 0.0;
let fp = oracle_footprint(7u);
let rules = oracle_rules(15u);
let sigma = x(20u);
let pk = x(21u);
if mth == 0.0 || (mth == 1.0 && !g) {
    let lobe = gaussian::gaussian_lobe(gaussian::Gaussian(rules, sigma), oracle_matrix(2u), fp);
    if pk == 3.0 {
        y3(0u, matrix::entries(lobe));
    } else if g {
        y(0u, point_ggx_matrix(lobe, 21u));
    } else {
        y(0u, point_beckmann_matrix(lobe, 21u));
    }
} else if mth == 1.0 {
    let lobe = gaussian_ggx::exact_gaussian_lobe(gaussian_ggx::ExactGaussian(rules, sigma, gaussian_ggx::TOL_FULL), oracle_matrix(2u), fp);
    if pk == 0.0 {
        y(0u, gaussian_ggx::d(lobe, x3(22u)));
    } else if pk == 1.0 {
        y(0u, gaussian_ggx::p22(lobe, x2(22u)));
    } else {
        y(0u, gaussian_ggx::lambda(lobe, x3(22u)));
    }
} else if mth == 2.0 {
    let lobe = projected::projected_lobe(projected::Projected(rules, sigma), oracle_matrix(2u), fp);
    if pk == 3.0 {
        y3(0u, matrix::entries(lobe));
    } else {
        y(0u, point_ggx_matrix(lobe, 21u));
    }
} else if mth == 3.0 {
    let lobe = lobe::rect_lobe(lobe::Rect(rules), oracle_axis_aligned(2u), fp);
    if pk == 3.0 {
        y4(0u, vec4<f32>(lobe.roughness.alpha, lobe.half_extent));
    } else {
        y(0u, point_rect(lobe, 21u));
    }
} else {
    let lobe = proxy::proxy_lobe(proxy::Proxy(rules), oracle_axis_aligned(2u), fp);
    if pk == 3.0 {
        y2(0u, lobe.alpha);
    } else {
        y(0u, point_ggx_matrix(axis_aligned::to_matrix(lobe), 21u));
    }
}",
    n_in: 25,
    n_out: 4,
};

const GAUSSIAN_FILTERED: GpuKernel = GpuKernel {
    name: "gaussian_filtered",
    body: "let a = oracle_matrix(1u);
let k = covariance::Covariance(x(6u), x(7u), x(8u), x(9u));
if x(0u) == 0.0 {
    y(0u, gaussian_ggx::p22(gaussian_ggx::from_kernel(a, k), x2(10u)));
} else {
    y(0u, beckmann::p22_matrix(gaussian::gaussian(a, k), x2(10u)));
}",
    n_in: 12,
    n_out: 1,
};

const KERNELS: &[GpuKernel] = &[
    NDF,
    PDF,
    SAMPLE,
    JACOBIAN,
    ISOTROPIC,
    PRESET,
    FILTER_ROUGHNESS,
    GGX_RECT,
    GGX_RECT_FOOTPRINT,
    GGX_PROXY,
    FILTERED,
    GAUSSIAN_FILTERED,
];

/// How a job's outputs become its JSON answer.
#[derive(Clone, Copy, Debug)]
enum Decode {
    /// One number.
    Scalar,
    /// `n` numbers.
    Array(usize),
    /// `[[a11, a12], [a12, a22]]` from three.
    Matrix,
    /// A 2x2 matrix from its columns (`[[c0.x, c1.x], [c0.y, c1.y]]`).
    Columns,
    /// `{"roughness": [ax, ay], "half_extent": [hx, hy]}`.
    Rect,
    /// A sampled normal, `null` for the zero vector (the shader's `None`).
    Sample,
}

/// A valid line of an op with a shader: its kernel, its input slots, its decoder.
struct Job {
    kernel: usize,
    input: Vec<f32>,
    decode: Decode,
}

/// Rounds to f32 (the slots).
fn f(x: f64) -> f32 {
    x as f32
}

/// The shaders' stand-in for `+inf`.
fn number_out(x: f32) -> Value {
    if x == f32::MAX {
        json!("inf")
    } else if x == -f32::MAX {
        json!("-inf")
    } else {
        json!(f64::from(x))
    }
}

/// The 5 roughness slots (see `IMPORTS`).
fn roughness_slots(r: RoughnessArg) -> Vec<f32> {
    match r {
        RoughnessArg::Iso(a) => vec![0.0, f(a), 0.0, 0.0, 0.0],
        RoughnessArg::Aniso(ax, ay) => vec![1.0, f(ax), f(ay), 0.0, 0.0],
        RoughnessArg::Matrix(m) => {
            // As `RoughnessMatrix::from_mat2` in f32: the mean of the off-diagonal entries;
            // det A in f64 of the f32 entries (exact products, one rounding).
            let (a11, a22) = (f(m[0][0]), f(m[1][1]));
            let a12 = 0.5 * f(m[0][1]) + 0.5 * f(m[1][0]);
            let det = f64::from(a11) * f64::from(a22) - f64::from(a12) * f64::from(a12);
            vec![2.0, a11, a12, a22, det as f32]
        }
    }
}

/// The 8 footprint slots (see `IMPORTS`).
fn footprint_slots(fp: FootprintArg) -> Result<Vec<f32>, String> {
    let v = |k: f32, a: &[f64]| {
        let mut s = vec![k];
        s.extend(a.iter().map(|&x| f(x)));
        s.resize(8, 0.0);
        s
    };
    Ok(match fp {
        FootprintArg::Slope([u, w]) => v(0.0, &[u[0], u[1], w[0], w[1]]),
        FootprintArg::Projected([u, w]) => v(1.0, &[u[0], u[1], w[0], w[1]]),
        FootprintArg::ProjectedInSlope { h, dp: [u, w] } => {
            v(2.0, &[h[0], h[1], h[2], u[0], u[1], w[0], w[1]])
        }
        FootprintArg::NormalDifferences([u, w]) => v(3.0, &[u[0], u[1], u[2], w[0], w[1], w[2]]),
        FootprintArg::HalfVector { .. } => {
            return Err("footprint form \"half_vector\" has no shader".into());
        }
    })
}

/// The rules of a method: `(max_extent, floor kind, floor, kappa, det_clamp)` as the CPU
/// backend composes them (`typed.rs`'s `clamp_rules`), infinities as `F32_MAX`.
#[derive(Clone, Copy)]
struct Rules {
    max_extent: f64,
    floor: FloorArg,
    kappa: f64,
    det_clamp: bool,
}

impl Rules {
    const DEFAULT: Self = Self {
        max_extent: 1.0,
        floor: FloorArg::Constant(1e-3),
        kappa: 0.18,
        det_clamp: true,
    };
    const NONE: Self = Self {
        max_extent: f64::INFINITY,
        floor: FloorArg::None,
        kappa: f64::INFINITY,
        det_clamp: false,
    };
    const GDC2016: Self = Self {
        max_extent: 1.0,
        floor: FloorArg::AlphaCapped(0.1),
        kappa: f64::INFINITY,
        det_clamp: true,
    };
    const KHPL16: Self = Self {
        max_extent: 1.0,
        floor: FloorArg::None,
        kappa: f64::INFINITY,
        det_clamp: true,
    };

    fn with(self, arg: Option<ClampArg>) -> Self {
        let Some(arg) = arg else { return self };
        let mut r = match arg.preset {
            None => self,
            Some(ClampPreset::Default) => Self::DEFAULT,
            Some(ClampPreset::None) => Self::NONE,
            Some(ClampPreset::Gdc2016) => Self::GDC2016,
            Some(ClampPreset::Khpl16) => Self::KHPL16,
        };
        if let Some(l) = arg.max_extent {
            r.max_extent = l;
        }
        if let Some(k) = arg.kappa {
            r.kappa = k;
        }
        if let Some(d) = arg.det_clamp {
            r.det_clamp = d;
        }
        if let Some(fl) = arg.floor {
            r.floor = fl;
        }
        r
    }

    fn slots(self) -> Vec<f32> {
        let bound = |x: f64| if x.is_finite() { f(x) } else { f32::MAX };
        let (kind, floor) = match self.floor {
            FloorArg::None => (0.0, 0.0),
            FloorArg::Constant(e) => (1.0, bound(e)),
            FloorArg::AlphaCapped(c) => (2.0, bound(c)),
        };
        vec![
            bound(self.max_extent),
            kind,
            floor,
            bound(self.kappa),
            if self.det_clamp { 1.0 } else { 0.0 },
        ]
    }
}

/// The 4 point slots: `[kind, p]`, kind 0 D(m), 1 P22(slope), 2 Lambda(w), 3 the lobe.
fn point_slots(p: Point) -> Vec<f32> {
    match p {
        Point::D(m) => vec![0.0, f(m[0]), f(m[1]), f(m[2])],
        Point::P22(s) => vec![1.0, f(s[0]), f(s[1]), 0.0],
        Point::Lambda(w) => vec![2.0, f(w[0]), f(w[1]), f(w[2])],
        Point::Lobe => vec![3.0, 0.0, 0.0, 0.0],
    }
}

fn dist_slot(d: Dist) -> f32 {
    match d {
        Dist::Ggx => 0.0,
        Dist::Beckmann => 1.0,
    }
}

fn push3(v: &mut Vec<f32>, a: [f64; 3]) {
    v.extend(a.iter().map(|&x| f(x)));
}

fn kernel_index(name: &str) -> usize {
    KERNELS
        .iter()
        .position(|k| k.name == name)
        .expect("a kernel of that name")
}

/// The error of an op without a shader.
fn no_shader(op: &str, why: &str) -> String {
    format!("op \"{op}\" has no shader ({why}): use the CPU backend")
}

/// The job of a line the CPU evaluator accepted.
fn job(v: &Value) -> Result<Job, String> {
    let op = string(v, "op")?;
    let ndf = |what: f32, slots: &[&str]| -> Result<Job, String> {
        let mut input = vec![what, dist_slot(dist(v)?)];
        input.extend(roughness_slots(roughness_arg(v)?));
        for k in slots {
            match *k {
                "slope" => {
                    let s = array::<2>(v, "slope")?;
                    input.extend([f(s[0]), f(s[1]), 0.0]);
                }
                key => push3(&mut input, array::<3>(v, key)?),
            }
        }
        input.resize(NDF.n_in, 0.0);
        Ok(Job {
            kernel: kernel_index("ndf"),
            input,
            decode: Decode::Scalar,
        })
    };
    match op {
        "ndf" => ndf(0.0, &["m"]),
        "slope_pdf" => ndf(1.0, &["slope"]),
        "lambda" => ndf(2.0, &["w"]),
        "g1" => ndf(3.0, &["w", "m"]),
        "g2" => ndf(4.0, &["i", "o", "m"]),
        "pdf" | "sample" => {
            let d = dist_slot(dist(v)?);
            let mut input = roughness_slots(roughness_arg(v)?);
            push3(&mut input, array::<3>(v, "o")?);
            if op == "pdf" {
                push3(&mut input, array::<3>(v, "m")?);
                input.push(d);
                Ok(Job {
                    kernel: kernel_index("pdf"),
                    input,
                    decode: Decode::Scalar,
                })
            } else {
                let u = array::<2>(v, "u")?;
                input.extend([f(u[0]), f(u[1]), d]);
                Ok(Job {
                    kernel: kernel_index("sample"),
                    input,
                    decode: Decode::Sample,
                })
            }
        }
        "jacobian" => {
            let kind = match string(v, "kind")? {
                "sphere_to_slope" => 0.0,
                "sphere_to_projected" => 1.0,
                _ => 2.0,
            };
            let mut input = vec![kind];
            push3(&mut input, array::<3>(v, "h")?);
            Ok(Job {
                kernel: kernel_index("jacobian"),
                input,
                decode: Decode::Columns,
            })
        }
        "isotropic_roughness" => {
            let bw = match v.get("variant").and_then(Value::as_str) {
                Some("max") => 0.0,
                Some("trace") => 1.0,
                _ => 2.0,
            };
            let mut input = vec![f(number(v, "alpha")?)];
            push3(&mut input, array::<3>(v, "dn_u")?);
            push3(&mut input, array::<3>(v, "dn_v")?);
            input.extend([bw, f(opt_number(v, "kappa")?.unwrap_or(0.18))]);
            Ok(Job {
                kernel: kernel_index("isotropic_roughness"),
                input,
                decode: Decode::Scalar,
            })
        }
        "preset" => {
            let name = string(v, "name")?;
            let index = filtered_ndf::f32::filter::presets::ALL
                .iter()
                .position(|(n, _)| *n == name)
                .ok_or("unknown preset")?;
            let raw = v.get("raw").and_then(Value::as_bool).unwrap_or(false);
            let mut input = vec![index as f32, f(number(v, "alpha")?)];
            push3(&mut input, array::<3>(v, "dn_u")?);
            push3(&mut input, array::<3>(v, "dn_v")?);
            input.push(if raw { 1.0 } else { 0.0 });
            Ok(Job {
                kernel: kernel_index("preset"),
                input,
                decode: Decode::Scalar,
            })
        }
        "filter_roughness" | "projected_roughness" => {
            let mut input = roughness_slots(roughness_arg(v)?);
            input.extend(footprint_slots(footprint_arg(v)?)?);
            input.push(f(opt_non_negative(v, "sigma")?.unwrap_or(0.5)));
            input.push(if op == "filter_roughness" { 0.0 } else { 1.0 });
            Ok(Job {
                kernel: kernel_index("filter_roughness"),
                input,
                decode: Decode::Matrix,
            })
        }
        "ggx_rect" => {
            let (ax, ay) = roughness_arg(v)?.axis_aligned(op)?;
            let (c, h) = (array::<2>(v, "center")?, array::<2>(v, "half_extent")?);
            Ok(Job {
                kernel: kernel_index("ggx_rect"),
                input: vec![f(ax), f(ay), f(c[0]), f(c[1]), f(h[0]), f(h[1])],
                decode: Decode::Scalar,
            })
        }
        "ggx_rect_footprint" => {
            let (ax, ay) = roughness_arg(v)?.axis_aligned(op)?;
            let mut input = vec![f(ax), f(ay)];
            input.extend(footprint_slots(footprint_arg(v)?)?);
            input.extend(Rules::DEFAULT.with(clamps_arg(v)?).slots());
            let p = point(v)?;
            input.extend(point_slots(p));
            let decode = if matches!(p, Point::Lobe) {
                Decode::Array(2)
            } else {
                Decode::Scalar
            };
            Ok(Job {
                kernel: kernel_index("ggx_rect_footprint"),
                input,
                decode,
            })
        }
        "ggx_proxy" => {
            let simple = v.get("variant").and_then(Value::as_str) == Some("simple");
            Ok(Job {
                kernel: kernel_index("ggx_proxy"),
                input: vec![
                    f(number(v, "alpha")?),
                    f(number(v, "half_extent")?),
                    if simple { 1.0 } else { 0.0 },
                ],
                decode: Decode::Scalar,
            })
        }
        "filtered" => filtered_job(v),
        "gaussian_filtered" => {
            let k = kernel_arg(v)?;
            let (s11, s12, s22) = (f(k[0]), f(k[1]), f(k[2]));
            // The kernel's determinant in f64 of its f32 entries (the WGSL `Covariance` carries
            // it, computed where it is accurate).
            let det = f64::from(s11) * f64::from(s22) - f64::from(s12) * f64::from(s12);
            let mut input = vec![dist_slot(dist(v)?)];
            input.extend(roughness_slots(roughness_arg(v)?));
            input.extend([s11, s12, s22, det.max(0.0) as f32]);
            let s = array::<2>(v, "slope")?;
            input.extend([f(s[0]), f(s[1])]);
            Ok(Job {
                kernel: kernel_index("gaussian_filtered"),
                input,
                decode: Decode::Scalar,
            })
        }
        "temporal" => Err(no_shader(
            op,
            "the temporal lobe of Tessari et al. 2020 has no WGSL module yet",
        )),
        other => Err(no_shader(other, "no WGSL function for it")),
    }
}

/// The `filtered` op's job (the front door; `shaders/filter/method.wgsl`).
fn filtered_job(v: &Value) -> Result<Job, String> {
    let d = dist(v)?;
    let r = roughness_arg(v)?;
    let name = string(v, "method")?;
    // (kernel code, the method's own rules, its sigma).
    let (code, base) = match name {
        "gaussian_tk19" => (0.0, Rules::DEFAULT),
        "gaussian_khpl16" => (0.0, Rules::KHPL16),
        "gaussian_exact" => (1.0, Rules::KHPL16),
        "projected_tk21" => (2.0, Rules::DEFAULT),
        "rect_khpl16" => (3.0, Rules::KHPL16),
        "rect_gdc2016" => (3.0, Rules::GDC2016),
        _ => (4.0, Rules::KHPL16),
    };
    let p = point(v)?;
    if code == 1.0 && d == Dist::Ggx && matches!(p, Point::Lobe) {
        return Err(
            "the exact Gaussian-filtered GGX is not a roughness: give a point (m, slope or w)"
                .into(),
        );
    }
    let mut input = vec![code, dist_slot(d)];
    input.extend(roughness_slots(r));
    input.extend(footprint_slots(footprint_arg(v)?)?);
    input.extend(base.with(clamps_arg(v)?).slots());
    input.push(f(opt_non_negative(v, "sigma")?.unwrap_or(0.5)));
    input.extend(point_slots(p));
    let decode = match (p, code) {
        (Point::Lobe, 0.0 | 1.0 | 2.0) => Decode::Matrix,
        (Point::Lobe, 3.0) => Decode::Rect,
        (Point::Lobe, _) => Decode::Array(2),
        _ => Decode::Scalar,
    };
    Ok(Job {
        kernel: kernel_index("filtered"),
        input,
        decode,
    })
}

/// A job's answer from its outputs.
fn decode(d: Decode, o: &[f32]) -> Value {
    match d {
        Decode::Scalar => number_out(o[0]),
        Decode::Array(n) => Value::Array(o[..n].iter().map(|&x| number_out(x)).collect()),
        Decode::Matrix => json!([
            [number_out(o[0]), number_out(o[1])],
            [number_out(o[1]), number_out(o[2])]
        ]),
        Decode::Columns => json!([
            [number_out(o[0]), number_out(o[2])],
            [number_out(o[1]), number_out(o[3])]
        ]),
        Decode::Rect => json!({
            "roughness": [number_out(o[0]), number_out(o[1])],
            "half_extent": [number_out(o[2]), number_out(o[3])],
        }),
        Decode::Sample => {
            if o[0] == 0.0 && o[1] == 0.0 && o[2] == 0.0 {
                Value::Null
            } else {
                Value::Array(o[..3].iter().map(|&x| number_out(x)).collect())
            }
        }
    }
}

/// A line prepared: its answer already (an error), or its job.
enum Prepared {
    Answer(Value),
    Job(Job),
}

/// Checks one line with the CPU evaluator in f32 and prepares its job.
fn prepare(line: &str, cpu_eval_line: &dyn Fn(&str) -> String) -> Prepared {
    let err = |e: String| Prepared::Answer(json!({ "error": e }));
    let mut v: Value = match serde_json::from_str(line) {
        Ok(v) => v,
        // The CPU evaluator words the error.
        Err(_) => return Prepared::Answer(parse(&cpu_eval_line(line))),
    };
    if let Some(obj) = v.as_object_mut() {
        match obj.get("precision").and_then(Value::as_str) {
            Some("f64") => {
                return err(
                    "precision \"f64\": the GPU backend evaluates the WGSL modules in f32 (WGSL \
                     has no f64); use the CPU backend"
                        .into(),
                );
            }
            None => {
                obj.insert("precision".into(), json!("f32"));
            }
            _ => {}
        }
    }
    let checked = parse(&cpu_eval_line(&v.to_string()));
    if checked.get("error").is_some() {
        return Prepared::Answer(checked);
    }
    match job(&v) {
        Ok(j) => Prepared::Job(j),
        Err(e) => err(e),
    }
}

fn parse(reply: &str) -> Value {
    serde_json::from_str(reply).unwrap_or_else(|e| json!({ "error": format!("internal: {e}") }))
}

/// Answers the lines of a session through the shaders: one dispatch per kernel (see the
/// module docs), the answers in input order, one JSON line each. `cpu_eval_line` is the CPU
/// evaluator's `eval_line` (the argument checks). A failed dispatch (no adapter, a shader
/// error) answers every line of its kernel with that error.
pub fn answer_session(lines: &[&str], cpu_eval_line: &dyn Fn(&str) -> String) -> Vec<String> {
    let prepared: Vec<Prepared> = lines.iter().map(|l| prepare(l, cpu_eval_line)).collect();
    let mut answers: Vec<Option<Value>> = prepared
        .iter()
        .map(|p| match p {
            Prepared::Answer(a) => Some(a.clone()),
            Prepared::Job(_) => None,
        })
        .collect();
    for (ki, k) in KERNELS.iter().enumerate() {
        let idx: Vec<usize> = prepared
            .iter()
            .enumerate()
            .filter_map(|(i, p)| match p {
                Prepared::Job(j) if j.kernel == ki => Some(i),
                _ => None,
            })
            .collect();
        if idx.is_empty() {
            continue;
        }
        let mut input = Vec::with_capacity(idx.len() * k.n_in);
        for &i in &idx {
            if let Prepared::Job(j) = &prepared[i] {
                let mut slots = j.input.clone();
                slots.resize(k.n_in, 0.0);
                input.extend(slots);
            }
        }
        let kernel = Kernel {
            imports: IMPORTS,
            body: k.body,
            n_in: k.n_in,
            n_out: k.n_out,
        };
        match harness::run(&kernel, &input) {
            Ok(out) => {
                for (n, &i) in idx.iter().enumerate() {
                    if let Prepared::Job(j) = &prepared[i] {
                        let o = &out[n * k.n_out..(n + 1) * k.n_out];
                        answers[i] = Some(json!({ "ok": decode(j.decode, o) }));
                    }
                }
            }
            Err(e) => {
                for &i in &idx {
                    answers[i] = Some(json!({ "error": format!("GPU backend: {e}") }));
                }
            }
        }
    }
    answers
        .into_iter()
        .map(|a| a.expect("every line answered").to_string())
        .collect()
}

/// The kernel names, for `--list`: the ops the GPU backend answers.
pub const GPU_OPS: &str = "ndf slope_pdf lambda g1 g2 pdf (GGX) sample (GGX) jacobian \
isotropic_roughness preset filter_roughness projected_roughness ggx_rect ggx_rect_footprint \
ggx_proxy filtered gaussian_filtered";
