//! `shaders/filter/` and `shaders/kernel/clamp.wgsl`'s pipeline: the rows of the trade table
//! (`filtered-ndf-demo`'s `tradeoff`) as WGSL, end to end (the filtered `D(h)` of one shading point),
//! and the building blocks (proxy roughness, deferred conventions, the 12 presets, LEAN).
//!
//! Cases: axis-aligned materials from `strategies::axis_aligned` (alpha log-uniform in
//! `[1e-4, 2]`, anisotropy up to `1e3`), half vectors from `strategies::upper_hemisphere(89)`
//! and footprints from `strategies::footprint`, as the CPU tests draw them.
//!
//! Tolerances. A filtered lobe is a roughness matrix `A'` evaluated in its eigenbasis: its
//! quadratic form is within `err_q = 10 + 16 sqrt(cond A')` ulp (`matrix.wgsl`'s
//! `8 + 8 sqrt(cond)` for the rotation and eigenvalues, plus `8 sqrt(cond)` for the rounding
//! of the kernel's entries, which tilts the computed eigenbasis by a few `EPS`, and 2 for
//! the determinant from non-negative terms); `cond A'` is taken from the `f64` reference.
//! `D` then follows the NDF rules of [`super::ndf`]: GGX `2 (err_q + 1) + 6 + err_det`,
//! Beckmann `(err_q + 3) x + 3 + 2x + 6 + err_det` with `err_det = 10` ulp for the
//! filtered `sqrt(det A')` (non-negative terms of 3-ulp inputs, a square root). The GGX proxy
//! has `alpha'` within 12 ulp per axis, which `D` carries four times into `q` (two axes,
//! squared) and twice into `sqrt(det)`. The deferred conventions are derived per case in
//! [`deferred_tol`].

use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, Beckmann, ClampRules, DVec2, DVec3, Footprint, Ggx, Ndf, RoughnessMatrix,
    SplitMix64, deferred, filter, presets, proxy, strategies, v2, v3,
};

/// One shading point of the trade table.
struct Point {
    alpha: [f32; 2],
    h: [f32; 3],
    dh_u: [f32; 2],
    dh_v: [f32; 2],
}

impl Point {
    fn input(&self) -> Vec<f32> {
        let mut v = self.alpha.to_vec();
        v.extend(self.h);
        v.extend(self.dh_u);
        v.extend(self.dh_v);
        v
    }
    fn alpha(&self) -> AxisAligned {
        AxisAligned::new(self.alpha[0].into(), self.alpha[1].into()).expect("in range")
    }
    fn fp(&self) -> Footprint {
        Footprint::from_slope_derivatives(v2(self.dh_u), v2(self.dh_v))
    }
    fn h(&self) -> DVec3 {
        v3(self.h)
    }
}

fn points(n: usize) -> Vec<Point> {
    let a = draw(strategies::axis_aligned(), n, "filters alpha");
    let h = draw(strategies::upper_hemisphere(89.0), n, "filters h");
    let f = draw(strategies::footprint(), n, "filters fp");
    (0..n)
        .map(|k| Point {
            alpha: [a[k].alpha().x as f32, a[k].alpha().y as f32],
            h: [h[k].x as f32, h[k].y as f32, h[k].z as f32],
            dh_u: [f[k].dh_u.x as f32, f[k].dh_u.y as f32],
            dh_v: [f[k].dh_v.x as f32, f[k].dh_v.y as f32],
        })
        .collect()
}

/// The snippet prologue: material `r`, roughness matrix `a`, half vector `h`, footprint `fp`.
const PROLOGUE: &str = "let r = axis_aligned::from_alpha(x2(0u));
let a = axis_aligned::to_matrix(r);
let h = x3(2u);
let fp = footprint::from_slope_derivatives(x2(5u), x2(7u));";

const IMPORTS: &str = "#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::footprint
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::proxy
#import filtered_ndf::filter::lean
#import filtered_ndf::filter::deferred
#import filtered_ndf::filter::presets";

/// The module docs' `D` tolerance (ulp) of a filtered matrix at `h`: `cond A'_c` of the matrix
/// the density evaluates (`A'` itself unless the determinant clamp is active, which adds
/// 5 ulp to the clamped eigenvalues, `matrix.wgsl`).
pub fn filtered_d_tol(m: &RoughnessMatrix, h: DVec3, ggx: bool) -> f64 {
    use crate::reference::Roughness;
    let (a, b, c) = m.entries();
    let active = m.clamped_det() > a * c - b * b;
    let err_q = 10.0 + 16.0 * super::ndf::clamped_cond(m).sqrt() + if active { 5.0 } else { 0.0 };
    if ggx {
        2.0 * (err_q + 1.0) + 6.0 + 10.0
    } else {
        let x = m.inv_quadratic(DVec2::new(h.x, h.y)) / (h.z * h.z);
        (err_q + 3.0) * x + 3.0 + 2.0 * x + 6.0 + 10.0
    }
}

/// A filtered-`D` check: `wgsl_matrix` builds `A'` from the prologue's names, `reference`
/// does the same in f64.
fn filtered_row(
    name: &str,
    wgsl_matrix: &str,
    ggx: bool,
    points: &[Point],
    reference: &dyn Fn(&Point) -> RoughnessMatrix,
) -> Check {
    let model = if ggx { "ggx" } else { "beckmann" };
    let body = format!("{PROLOGUE}\nlet af = {wgsl_matrix};\ny(0u, {model}::d_matrix(af, h));");
    let mut c = Check::new(name, IMPORTS, &body, 9, 1).tolerance(if ggx {
        "GGX D of A': 2 (err_q + 1) + 16 ulp, err_q = 10 + 16 sqrt(cond A')"
    } else {
        "Beckmann D of A': (err_q + 3) x + 2x + 19 ulp, err_q = 10 + 16 sqrt(cond A')"
    });
    for p in points {
        let m = reference(p);
        let d = if ggx {
            Ggx::new(m).d(p.h())
        } else {
            Beckmann::new(m).d(p.h())
        };
        c.case(
            p.input(),
            vec![d],
            vec![Tol::ulps(filtered_d_tol(&m, p.h(), ggx))],
        );
    }
    c
}

/// [`filtered_row`] with one more input per point, `tau` (slot 9): `wgsl_matrix` reads it as
/// `x(9u)`, `reference` gets it.
fn filtered_row_tau(
    name: &str,
    wgsl_matrix: &str,
    ggx: bool,
    points: &[Point],
    taus: &[f32],
    reference: &dyn Fn(&Point, f32) -> RoughnessMatrix,
) -> Check {
    let model = if ggx { "ggx" } else { "beckmann" };
    let body = format!("{PROLOGUE}\nlet af = {wgsl_matrix};\ny(0u, {model}::d_matrix(af, h));");
    let mut c = Check::new(name, IMPORTS, &body, 10, 1).tolerance(if ggx {
        "GGX D of A'_c: 2 (err_q + 1) + 16 ulp, err_q = 10 + 16 sqrt(cond A'_c) (+ 5 with the clamp active)"
    } else {
        "Beckmann D of A'_c: (err_q + 3) x + 2x + 19 ulp, err_q = 10 + 16 sqrt(cond A'_c) (+ 5 with the clamp active)"
    });
    for (p, &tau) in points.iter().zip(taus) {
        let m = reference(p, tau);
        let d = if ggx {
            Ggx::new(m).d(p.h())
        } else {
            Beckmann::new(m).d(p.h())
        };
        let mut input = p.input();
        input.push(tau);
        c.case(
            input,
            vec![d],
            vec![Tol::ulps(filtered_d_tol(&m, p.h(), ggx))],
        );
    }
    c
}

/// `tau` for each point: its determinant `det` (f64, of whatever the clamp is compared with)
/// times a ratio log-uniform in `[1 + 1e-6, 1e6]`, rounded to f32 (the clamp active, by a
/// hair to far beyond).
fn active_taus(points: &[Point], label: &str, det: &dyn Fn(&Point) -> f64) -> Vec<f32> {
    let e = draw(-6.0f64..6.0, points.len(), label);
    points
        .iter()
        .zip(e)
        .map(|(p, e)| {
            let ratio = if e < 0.0 {
                1.0 + 10f64.powf(e)
            } else {
                10f64.powf(e)
            };
            (det(p) * ratio) as f32
        })
        .collect()
}

/// The determinant-clamp rows: the filters with `tau` above the filtered determinant, and the
/// pipelines of a material whose own clamp is active (`A_c` filtered as `A + 2 Sigma` with its
/// own `tau = det A_c`, as in Rust).
fn clamp_rows(pts: &[Point], sigma: f64) -> Vec<Check> {
    let mut checks = Vec::new();
    let fdet = |m: RoughnessMatrix| {
        let (a, b, c) = m.entries();
        a * c - b * b
    };
    let taus = active_taus(pts, "gaussian tau", &|p| {
        fdet(filter::gaussian(p.alpha(), p.fp().covariance(sigma)))
    });
    for ggx in [true, false] {
        checks.push(filtered_row_tau(
            &format!(
                "gaussian::gaussian_with_det_clamp ({}, clamp active)",
                if ggx { "GGX" } else { "Beckmann" }
            ),
            "gaussian::gaussian_with_det_clamp(a, covariance::from_footprint(fp, 0.5), x(9u))",
            ggx,
            pts,
            &taus,
            &|p, tau| {
                filter::gaussian_with_det_clamp(p.alpha(), p.fp().covariance(sigma), tau.into())
            },
        ));
    }
    let taus = active_taus(pts, "projected tau", &|p| {
        fdet(filter::projected(p.alpha(), p.fp().covariance(sigma)))
    });
    checks.push(filtered_row_tau(
        "projected::projected_with_det_clamp (GGX, clamp active)",
        "projected::projected_with_det_clamp(a, covariance::from_footprint(fp, 0.5), x(9u))",
        true,
        pts,
        &taus,
        &|p, tau| filter::projected_with_det_clamp(p.alpha(), p.fp().covariance(sigma), tau.into()),
    ));
    // A clamped material: tau_m = det A times the ratio.
    let taus = active_taus(pts, "material tau", &|p| {
        let a = p.alpha().alpha();
        (a.x * a.y).powi(2)
    });
    let material = |p: &Point, tau: f32| {
        let a = p.alpha().alpha();
        RoughnessMatrix::new_with_det_clamp(a.x * a.x, 0.0, a.y * a.y, tau.into())
            .expect("in range")
    };
    for (ggx, module, f) in [
        (true, "gaussian", "filter_gaussian"),
        (false, "gaussian", "filter_gaussian"),
        (true, "projected", "filter_projected"),
    ] {
        checks.push(filtered_row_tau(
            &format!(
                "{module}::{f} ({}, default rules, clamped material)",
                if ggx { "GGX" } else { "Beckmann" }
            ),
            &format!(
                "{module}::{f}(clamp::DEFAULT_RULES, matrix::with_det_clamp(a, x(9u)), fp, 0.5)"
            ),
            ggx,
            pts,
            &taus,
            &|p, tau| {
                let rules = ClampRules::default();
                if f == "filter_gaussian" {
                    rules.filter_gaussian(material(p, tau), p.fp(), sigma)
                } else {
                    rules.filter_projected(material(p, tau), p.fp(), sigma)
                }
            },
        ));
    }
    checks
}

/// The entries of a filtered matrix as the oracle's GPU backend returns them
/// (`matrix::entries` of `gaussian::gaussian` and `projected::projected`): reconstructed from
/// the eigenbasis, `l1 c^2 + l2 s^2` etc., so within `32 EPS` of the largest entry: the
/// eigenvalue `l1` 5 ulp, the reconstruction 3 ulp of `l1`, the eigenvector's angle (from the
/// row without cancellation, 4 `EPS`) moving the entries by `2 (l1 - l2) 4 EPS`, i.e.
/// `16 EPS l1`, and `l1 <= 2 max |a_ij|`.
fn entries_rows(pts: &[Point], sigma: f64) -> Vec<Check> {
    let mut checks = Vec::new();
    for (name, call) in [
        (
            "matrix::entries(gaussian::gaussian)",
            "gaussian::gaussian(a, covariance::from_footprint(fp, 0.5))",
        ),
        (
            "matrix::entries(projected::projected)",
            "projected::projected(a, covariance::from_footprint(fp, 0.5))",
        ),
    ] {
        let body = format!("{PROLOGUE}\ny3(0u, matrix::entries({call}));");
        let mut c = Check::new(name, IMPORTS, &body, 9, 3)
            .tolerance("32 EPS of the largest entry (eigenvalue 5 ulp, reconstruction 3, eigenvector angle 4 EPS times 2 (l1 - l2); l1 <= 2 max |a_ij|)");
        for p in pts {
            let k = p.fp().covariance(sigma);
            let m = if name.contains("gaussian") {
                filter::gaussian(p.alpha(), k)
            } else {
                filter::projected(p.alpha(), k)
            };
            let (a11, a12, a22) = m.entries();
            let scale = a11.abs().max(a22.abs()).max(a12.abs());
            c.case(
                p.input(),
                vec![a11, a12, a22],
                vec![Tol::of_scale(32.0, scale); 3],
            );
        }
        checks.push(c);
    }
    checks
}

/// The per-case tolerance (ulp) of `KernelConvention::apply` (see [`all`]'s comment).
pub fn deferred_tol(
    conv: &deferred::KernelConvention,
    alpha: f64,
    dn_u: DVec3,
    dn_v: DVec3,
) -> f64 {
    use deferred::{Domain, Norm};
    let n = conv.norm.eval(dn_u, dn_v);
    // The kernel: the norm (sums of squares 2 ulp, the Gram eigenvalue 10), the scale and
    // bias (1), and for a non-unit exponent the driver's pow: exp2 (3 + 2 |e log2 n|) after
    // log2 (3 ulp of |log2 n|, times e), so (6 + 4 |e log2 n|) in all.
    let mut err_k = match conv.norm {
        Norm::MaxEigenvalue => 10.0,
        _ => 2.0,
    } + 1.0;
    if conv.exponent != 1.0 && n > 0.0 {
        err_k = err_k * conv.exponent + 6.0 + 4.0 * (conv.exponent * n.log2()).abs();
    }
    // The material's value in the domain: a square (0.5), a square root (4.5), or
    // a^2 / (1 - a^2), whose denominator cancels: 3 + a^2 / (1 - a^2).
    let a2 = alpha * alpha;
    let (err_v, back) = match conv.domain {
        Domain::Alpha2 => (0.5, 0.5),
        Domain::Alpha => (0.0, 1.0),
        Domain::Perceptual => (4.5, 2.0),
        Domain::ProjectedAlpha2 => (3.0 + a2 / (1.0 - a2).max(1e-30), 0.5),
    };
    // The sum (1 ulp), then back to alpha: half the error through a square root (plus its
    // 4.5 ulp), twice through a square, and for the projected domain sqrt(v / (1 + v)).
    back * (err_v.max(err_k) + 1.0) + 8.0
}

/// The checks of `shaders/filter/` (and the clamp pipeline).
pub fn all() -> Vec<Check> {
    let pts = points(2000);
    let mut checks = Vec::new();
    let sigma = 0.5;

    // The trade table's matrix rows.
    checks.push(filtered_row(
        "gaussian::filter_gaussian (GGX, TK19 A+2Sigma, default clamps)",
        "gaussian::filter_gaussian(clamp::DEFAULT_RULES, a, fp, 0.5)",
        true,
        &pts,
        &|p| ClampRules::default().filter_gaussian(p.alpha(), p.fp(), sigma),
    ));
    checks.push(filtered_row(
        "gaussian::gaussian (GGX, TK19 A+2Sigma, no clamps)",
        "gaussian::gaussian(a, covariance::from_footprint(fp, 0.5))",
        true,
        &pts,
        &|p| filter::gaussian(p.alpha(), p.fp().covariance(sigma)),
    ));
    checks.push(filtered_row(
        "projected::projected (GGX, TK21, default clamps)",
        "projected::projected(a, clamp::kernel(clamp::DEFAULT_RULES, covariance::from_footprint(clamp::footprint(clamp::DEFAULT_RULES, fp), 0.5)))",
        true,
        &pts,
        &|p| {
            let rules = ClampRules::default();
            let k = rules.kernel(rules.footprint(p.fp()).covariance(sigma));
            filter::projected(p.alpha(), k)
        },
    ));
    checks.push(filtered_row(
        "gaussian::gaussian (Beckmann, KHPL16 A+2Sigma exact)",
        "gaussian::gaussian(a, covariance::from_footprint(fp, 0.5))",
        false,
        &pts,
        &|p| filter::gaussian(p.alpha(), p.fp().covariance(sigma)),
    ));
    checks.push(filtered_row(
        "gaussian::filter_gaussian (Beckmann, default clamps)",
        "gaussian::filter_gaussian(clamp::DEFAULT_RULES, a, fp, 0.5)",
        false,
        &pts,
        &|p| ClampRules::default().filter_gaussian(p.alpha(), p.fp(), sigma),
    ));
    checks.push(filtered_row(
        "projected::filter_projected (GGX, TK21, default clamps)",
        "projected::filter_projected(clamp::DEFAULT_RULES, a, fp, 0.5)",
        true,
        &pts,
        &|p| ClampRules::default().filter_projected(p.alpha(), p.fp(), sigma),
    ));
    checks.extend(clamp_rows(&pts, sigma));
    checks.extend(entries_rows(&pts, sigma));
    checks.push(lean_row(&pts));

    // The GGX proxy rows: rectangle from the footprint under the default rules.
    for (simple, name) in [(false, "proxy::proxy"), (true, "proxy::proxy_simple")] {
        let f = if simple { "proxy_simple" } else { "proxy" };
        let body = format!(
            "{PROLOGUE}\nlet he = clamp::rect(clamp::DEFAULT_RULES, bounding::from_footprint(fp), r.alpha).half_extent;\ny(0u, ggx::d_axis_aligned(proxy::{f}(r, he), h));"
        );
        let ulps = if simple { 8.0 } else { 12.0 };
        let mut c = Check::new(&format!("{name} (GGX D of the proxy)"), IMPORTS, &body, 9, 1)
            .tolerance(&format!(
                "GGX D with alpha' within {ulps} ulp per axis: 2 (7 + 4 x {ulps} + 1) + 6 + 2 x {ulps} ulp"
            ));
        for p in &pts {
            let rules = ClampRules::default();
            let he = rules
                .rect(p.fp().bounding_rect(), p.alpha().alpha())
                .half_extent;
            let r = if simple {
                proxy::proxy_simple(p.alpha(), he)
            } else {
                proxy::proxy(p.alpha(), he)
            };
            let t = 2.0 * (7.0 + 4.0 * ulps + 1.0) + 6.0 + 2.0 * ulps;
            c.case(p.input(), vec![Ggx::new(r).d(p.h())], vec![Tol::ulps(t)]);
        }
        checks.push(c);
    }
    let mut rng = SplitMix64(0x7072_6f78);
    let mut ce = Check::new(
        "proxy::effective_alpha",
        IMPORTS,
        "y(0u, proxy::effective_alpha(x(0u), x(1u))); y(1u, proxy::effective_alpha_simple(x(0u), x(1u)));",
        2,
        2,
    )
    .tolerance("12 ulp (hypot 8 halved by nothing, t 2.5 + 8, math::atan 8, t/atan 2.5, sqrt 4.5, all halved under the square root where they enter it); simple: hypot's 8");
    for _ in 0..4000 {
        let a = rng.log_uniform(1e-4, 2.0) as f32;
        let he = if rng.uniform() < 0.1 {
            0.0
        } else {
            rng.log_uniform(1e-7, 1.0) as f32
        };
        ce.case(
            vec![a, he],
            vec![
                proxy::effective_alpha(a.into(), he.into()),
                proxy::effective_alpha_simple(a.into(), he.into()),
            ],
            vec![Tol::ulps(12.0), Tol::ulps(8.0)],
        );
    }
    checks.push(ce);

    // The 12 deferred presets, scalar alpha_bar, through `presets::preset(i)` (the named
    // constants) and `deferred::apply`.
    for (i, (name, conv)) in presets::ALL.iter().enumerate() {
        let body = format!("y(0u, deferred::apply(presets::preset({i}u), x(0u), x3(1u), x3(4u)));");
        let mut c = Check::new(
            &format!("deferred::apply (presets::preset({i}): {name})"),
            IMPORTS,
            &body,
            7,
            1,
        )
        .tolerance("per case: back (max(err_v, err_k) + 1) + 8 ulp (deferred_tol in gpu/src/checks/filters.rs)");
        for k in 0..1500 {
            let alpha = rng.log_uniform(1e-4, 2.0) as f32;
            let mut dn = || {
                let len = rng.log_uniform(1e-6, 1.0);
                let d = DVec3::new(rng.normal(), rng.normal(), rng.normal()).normalize() * len;
                [d.x as f32, d.y as f32, d.z as f32]
            };
            let (u, v) = if k % 10 == 0 {
                ([0.0; 3], [0.0; 3])
            } else {
                (dn(), dn())
            };
            let (ud, vd) = (v3(u), v3(v));
            let e = conv.apply(alpha.into(), ud, vd);
            let t = deferred_tol(conv, alpha.into(), ud, vd);
            let mut input = vec![alpha];
            input.extend(u);
            input.extend(v);
            c.case(input, vec![e], vec![Tol::ulps(t)]);
        }
        checks.push(c);
    }

    // TK19 eq. 1, 4, 5 from a covariance.
    let mut cf = Check::new(
        "deferred::filtered_alpha",
        IMPORTS,
        "let s = deferred::normal_difference_covariance(x3(1u), x3(4u), footprint::SIGMA_PIXEL);
y(0u, deferred::filtered_alpha(x(0u), s, deferred::BANDWIDTH_MAX, deferred::KAPPA));
y(1u, deferred::filtered_alpha(x(0u), s, deferred::BANDWIDTH_TRACE, deferred::KAPPA));
y(2u, deferred::filtered_alpha(x(0u), s, deferred::BANDWIDTH_AVERAGE, deferred::KAPPA));",
        7,
        3,
    )
    .tolerance("as the alpha^2 presets: 0.5 (max(0.5, err_k) + 1) + 8 ulp with err_k 11 (Gram eigenvalue) or 3");
    for _ in 0..2000 {
        let alpha = rng.log_uniform(1e-4, 2.0) as f32;
        let mut dn = || {
            let len = rng.log_uniform(1e-6, 1.0);
            let d = DVec3::new(rng.normal(), rng.normal(), rng.normal()).normalize() * len;
            [d.x as f32, d.y as f32, d.z as f32]
        };
        let (u, v) = (dn(), dn());
        let s = deferred::normal_difference_covariance(
            v3(u),
            v3(v),
            filtered_ndf::f64::kernel::SIGMA_PIXEL,
        );
        let mut input = vec![alpha];
        input.extend(u);
        input.extend(v);
        let out: Vec<f64> = [
            deferred::Bandwidth::Max,
            deferred::Bandwidth::Trace,
            deferred::Bandwidth::Average,
        ]
        .iter()
        .map(|b| deferred::filtered_alpha(alpha.into(), &s, *b, deferred::KAPPA))
        .collect();
        c_push(&mut cf, input, out);
    }
    checks.push(cf);
    let _ = EPS;
    checks
}

/// LEAN (KHPL16 eq. 21): the pixel kernel plus the covariance of normal-map moments, given
/// to the shader as f32 values (`mean = dh_u / 2`, `second` the Gram matrix of the
/// footprint vectors, so the moments' covariance is `0.75 dh_u dh_u^T + dh_v dh_v^T`).
/// The moments' covariance `second - mean mean^T` is formed from f32 entries, whose
/// rounding (2 `EPS` of `second` per entry, and 2 `EPS` of `c_xx c_yy + c_xy^2` in its
/// determinant) moves `det A'` by `4 delta`: the tolerance adds `2.5 * 4 delta / det A'` (the
/// minor eigenvalue and `sqrt(det)` carry it) to the filtered-`D` rule.
fn lean_row(points: &[Point]) -> Check {
    let body = format!(
        "{PROLOGUE}\nlet m = lean::LeanMoments(x2(9u), x3(11u));\nlet af = lean::lean(a, covariance::from_footprint(fp, 0.5), m);\ny(0u, ggx::d_matrix(af, h));"
    );
    let mut c = Check::new("lean::lean (GGX, pixel kernel + LEAN moments)", IMPORTS, &body, 14, 1)
        .tolerance("GGX D of A' (2 (err_q + 1) + 16 ulp) plus 10 delta / det A' for the f32 moments' covariance, delta = 4 EPS (sec_xx c_yy + sec_yy c_xx + 2 |sec_xy c_xy|) + 2 EPS (c_xx c_yy + c_xy^2)");
    for p in points {
        let (u, v) = (v2(p.dh_u), v2(p.dh_v));
        let mean = [(u.x * 0.5) as f32, (u.y * 0.5) as f32];
        let sec = [
            (u.x * u.x + v.x * v.x) as f32,
            (u.x * u.y + v.x * v.y) as f32,
            (u.y * u.y + v.y * v.y) as f32,
        ];
        let second = crate::reference::Covariance::new(sec[0].into(), sec[1].into(), sec[2].into());
        let moments = filter::LeanMoments::new(v2(mean), second);
        let m = filter::lean(p.alpha(), p.fp().covariance(0.5), &moments);
        let cl = moments.covariance();
        let delta = 4.0
            * EPS
            * (second.s11 * cl.s22 + second.s22 * cl.s11 + 2.0 * (second.s12 * cl.s12).abs())
            + 2.0 * EPS * (cl.s11 * cl.s22 + cl.s12 * cl.s12);
        let (b11, b12, b22) = m.entries();
        let det = b11 * b22 - b12 * b12;
        let t = filtered_d_tol(&m, p.h(), true) + 10.0 * delta / det / EPS;
        let mut input = p.input();
        input.extend(mean);
        input.extend(sec);
        c.case(input, vec![Ggx::new(m).d(p.h())], vec![Tol::ulps(t)]);
    }
    c
}

fn c_push(c: &mut Check, input: Vec<f32>, out: Vec<f64>) {
    let t = vec![
        Tol::ulps(0.5 * (11.0 + 1.0) + 8.0),
        Tol::ulps(0.5 * (3.0 + 1.0) + 8.0),
        Tol::ulps(0.5 * (3.0 + 1.0) + 8.0),
    ];
    c.case(input, out, t);
}
