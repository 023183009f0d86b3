//! `shaders/filter/lean_nested.wgsl`: LEAN moments nested into every method of the front door
//! (KHPL16 eq. 21), against the Rust `material.filtered(footprint, Lean::new(method,
//! moments))` in `f64` on the f32 values the shader reads, at the trade table's shading points
//! (as `checks/method.rs`) with texel moments: mean slopes uniform in `[-0.5, 0.5]^2`,
//! covariances `R diag(l1, l2) R^T` with `l_i` log-uniform in `[1e-5, 1e-1]`, second moments
//! `Sigma + E[s] E[s]^T` rounded to f32.
//!
//! Tolerances: each lobe is the method's lobe of a widened material, so each check carries the
//! bound of the method's own check (reused: `filters::filtered_d_tol`,
//! `gaussian_ggx::density_ulps`, `rect::d_rect_ulps`, the proxy's 128 ulp) plus the
//! conditioning of the f32 moments: the shader forms `Sigma_L = E[s s^T] - E[s] E[s]^T` from
//! f32 values, each entry within `delta_ij = EPS (|E[s_i] E[s_j]| + |Sigma_ij|)` (the product
//! and the difference each round once; `f32` moments whose covariance is far below their
//! squared mean keep only the digits above it, `src/bake/mod.rs`), and its determinant
//! within `2 EPS (Sigma_xx Sigma_yy + Sigma_xy^2)`. The first is measured on the `f64`
//! reference: the largest change of the output when each entry of `Sigma_L` moves by its
//! `delta` (six evaluations); the second adds `10 delta_det / det A'` (as `lean::lean`'s
//! check in `checks/filters.rs`) to the matrix methods.

use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, Beckmann, Covariance, DVec2, DVec3, ExactGaussian, Filterable, Footprint,
    Gaussian, Ggx, Lean, LeanMoments, Ndf, Projected, Proxy, Rect, Roughness, SplitMix64,
    strategies, v2, v3,
};

/// One shading point with the texel's moments.
struct Point {
    alpha: [f32; 2],
    du: [f32; 2],
    dv: [f32; 2],
    h: [f32; 3],
    w: [f32; 3],
    mean: [f32; 2],
    second: [f32; 3],
}

impl Point {
    fn input(&self) -> Vec<f32> {
        let mut v = self.alpha.to_vec();
        v.extend(self.du);
        v.extend(self.dv);
        v.extend(self.h);
        v.extend(self.w);
        v.extend(self.mean);
        v.extend(self.second);
        v
    }
    fn material(&self) -> AxisAligned {
        AxisAligned::new(self.alpha[0].into(), self.alpha[1].into()).expect("in range")
    }
    fn fp(&self) -> Footprint {
        Footprint::from_slope_derivatives(v2(self.du), v2(self.dv))
    }
    fn moments(&self) -> LeanMoments {
        let s = self.second.map(f64::from);
        LeanMoments::new(v2(self.mean), Covariance::new(s[0], s[1], s[2]))
    }
    /// The moments with `Sigma_L`'s entry `j` moved by `sign delta_j` (module docs).
    fn perturbed(&self, j: usize, sign: f64) -> LeanMoments {
        let m = self.moments();
        let c = m.covariance();
        let (mx, my) = (m.mean.x, m.mean.y);
        let d = [
            EPS * (mx * mx + c.s11.abs()),
            EPS * ((mx * my).abs() + c.s12.abs()),
            EPS * (my * my + c.s22.abs()),
        ];
        let mut s = m.second;
        match j {
            0 => s.s11 += sign * d[0],
            1 => s.s12 += sign * d[1],
            _ => s.s22 += sign * d[2],
        }
        LeanMoments::new(m.mean, s)
    }
    /// `10 delta_det / det A'` in ulp for the filtered matrix `(b11, b12, b22)`.
    fn det_ulps(&self, (b11, b12, b22): (f64, f64, f64)) -> f64 {
        let c = self.moments().covariance();
        let delta = 2.0 * EPS * (c.s11 * c.s22 + c.s12 * c.s12);
        10.0 * delta / (b11 * b22 - b12 * b12) / EPS
    }
}

/// The largest change of `f` over the six perturbed moments, in ulp of `f(moments)`.
fn moment_ulps(p: &Point, f: &dyn Fn(&LeanMoments) -> f64) -> f64 {
    let v = f(&p.moments());
    let mut worst: f64 = 0.0;
    for j in 0..3 {
        for sign in [-1.0, 1.0] {
            worst = worst.max((f(&p.perturbed(j, sign)) - v).abs());
        }
    }
    if v > 0.0 { worst / v / EPS } else { 0.0 }
}

fn points(n: usize) -> Vec<Point> {
    let a = draw(strategies::axis_aligned(), n, "lean_nested alpha");
    let hs = draw(strategies::upper_hemisphere(89.0), n, "lean_nested h");
    let ws = draw(strategies::upper_hemisphere(89.9), n, "lean_nested w");
    let fps = draw(strategies::footprint(), n, "lean_nested fp");
    let mut rng = SplitMix64(0x1ea7_0050);
    let f3 = |d: DVec3| [d.x as f32, d.y as f32, d.z as f32];
    (0..n)
        .map(|k| {
            let mean = DVec2::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5));
            let (l1, l2) = (
                10f64.powf(rng.range(-5.0, -1.0)),
                10f64.powf(rng.range(-5.0, -1.0)),
            );
            let t = rng.range(0.0, std::f64::consts::PI);
            let (c, s) = (t.cos(), t.sin());
            let cov = (
                c * c * l1 + s * s * l2,
                c * s * (l1 - l2),
                s * s * l1 + c * c * l2,
            );
            Point {
                alpha: [a[k].alpha().x as f32, a[k].alpha().y as f32],
                du: [fps[k].dh_u.x as f32, fps[k].dh_u.y as f32],
                dv: [fps[k].dh_v.x as f32, fps[k].dh_v.y as f32],
                h: f3(hs[k]),
                w: f3(ws[k]),
                mean: [mean.x as f32, mean.y as f32],
                second: [
                    (cov.0 + mean.x * mean.x) as f32,
                    (cov.1 + mean.x * mean.y) as f32,
                    (cov.2 + mean.y * mean.y) as f32,
                ],
            }
        })
        .collect()
}

const IMPORTS: &str = "#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::footprint
#import filtered_ndf::filter::lean
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::rect::lobe
#import filtered_ndf::filter::proxy
#import filtered_ndf::filter::lean_nested";

const PROLOGUE: &str = "let r = axis_aligned::from_alpha(x2(0u));
let a = axis_aligned::to_matrix(r);
let fp = footprint::from_slope_derivatives(x2(2u), x2(4u));
let h = x3(6u);
let w = x3(9u);
let m = lean::LeanMoments(x2(12u), x3(14u));";

/// The checks of `shaders/filter/lean_nested.wgsl`.
pub fn all() -> Vec<Check> {
    let pts = points(1200);
    let mut checks = Vec::new();
    let mut one = |name: &str, expr: &str, f: &dyn Fn(&Point) -> (f64, f64)| {
        let body = format!("{PROLOGUE}\ny(0u, {expr});");
        let mut c = Check::new(name, IMPORTS, &body, 17, 1).tolerance(
            "the method's own bound plus the f32 moments' conditioning (checks/lean_nested.rs)",
        );
        for p in &pts {
            let (e, t) = f(p);
            c.case(p.input(), vec![e], vec![Tol::ulps(t)]);
        }
        checks.push(c);
    };
    for (name, m) in [
        ("TK19_GAUSSIAN", Gaussian::TK19),
        ("KHPL16_GAUSSIAN", Gaussian::KHPL16),
    ] {
        one(
            &format!("lean_nested::gaussian_lobe (GGX, gaussian::{name})"),
            &format!("ggx::d_matrix(lean_nested::gaussian_lobe(gaussian::{name}, a, fp, m), h)"),
            &move |p| {
                let h = v3(p.h);
                let d =
                    |mo: &LeanMoments| Ggx::new(p.material()).filtered(p.fp(), Lean::new(m, *mo));
                let lobe = d(&p.moments());
                let t = super::filters::filtered_d_tol(&lobe.roughness, h, true)
                    + p.det_ulps(lobe.roughness.entries())
                    + moment_ulps(p, &|mo| d(mo).d(h));
                (lobe.d(h), t)
            },
        );
        one(
            &format!("lean_nested::gaussian_lobe (Beckmann, gaussian::{name})"),
            &format!(
                "beckmann::d_matrix(lean_nested::gaussian_lobe(gaussian::{name}, a, fp, m), h)"
            ),
            &move |p| {
                let h = v3(p.h);
                let d = |mo: &LeanMoments| {
                    Beckmann::new(p.material()).filtered(p.fp(), Lean::new(m, *mo))
                };
                let lobe = d(&p.moments());
                let t = super::filters::filtered_d_tol(&lobe.roughness, h, false)
                    + p.det_ulps(lobe.roughness.entries())
                    + moment_ulps(p, &|mo| d(mo).d(h));
                (lobe.d(h), t)
            },
        );
    }
    one(
        "lean_nested::projected_lobe (projected::TK21_PROJECTED)",
        "ggx::d_matrix(lean_nested::projected_lobe(projected::TK21_PROJECTED, a, fp, m), h)",
        &|p| {
            let h = v3(p.h);
            let d = |mo: &LeanMoments| {
                Ggx::new(p.material()).filtered(p.fp(), Lean::new(Projected::TK21, *mo))
            };
            let lobe = d(&p.moments());
            let t = super::filters::filtered_d_tol(&lobe.roughness, h, true)
                + p.det_ulps(lobe.roughness.entries())
                + moment_ulps(p, &|mo| d(mo).d(h));
            (lobe.d(h), t)
        },
    );
    one(
        "lean_nested::exact_gaussian_lobe (gaussian_ggx::KHPL16_EXACT_GAUSSIAN)",
        "gaussian_ggx::d(lean_nested::exact_gaussian_lobe(gaussian_ggx::KHPL16_EXACT_GAUSSIAN, a, fp, m), h)",
        &|p| {
            let h = v3(p.h);
            let e = ExactGaussian::KHPL16;
            let d = |mo: &LeanMoments| Ggx::new(p.material()).filtered(p.fp(), Lean::new(e, *mo));
            let r = e.clamps;
            let k = r.kernel(r.footprint(p.fp()).covariance(0.5)) + p.moments().covariance();
            let s = DVec2::new(-h.x / h.z, -h.y / h.z);
            let t = super::gaussian_ggx::density_ulps(&p.material().to_matrix(), &k, s)
                + moment_ulps(p, &|mo| d(mo).d(h));
            (d(&p.moments()).d(h), t)
        },
    );
    for (name, m) in [
        ("KHPL16_RECT", Rect::KHPL16),
        ("GDC2016_RECT", Rect::GDC2016),
    ] {
        one(
            &format!("lean_nested::rect_lobe (lobe::{name})"),
            &format!("lobe::d_rect_filtered(lean_nested::rect_lobe(lobe::{name}, r, fp, m), h)"),
            &move |p| {
                let h = v3(p.h);
                let d =
                    |mo: &LeanMoments| Ggx::new(p.material()).filtered(p.fp(), Lean::new(m, *mo));
                let lobe = d(&p.moments());
                let c = DVec2::new(-h.x / h.z, -h.y / h.z);
                // Plus the widened alphas' own rounding (sqrt of a rounded sum: 2 ulp each)
                // times D's log-sensitivity to each.
                let a = lobe.roughness.alpha();
                let dr = |x: f64, y: f64| {
                    crate::reference::RectFilteredGgx::new(
                        AxisAligned::new(x, y).expect("in range"),
                        lobe.half_extent,
                    )
                    .d(h)
                };
                let ka = super::rect::log_sensitivity(a.x, |x| dr(x, a.y)).abs()
                    + super::rect::log_sensitivity(a.y, |y| dr(a.x, y)).abs();
                let t = super::rect::d_rect_ulps(lobe.roughness, c, lobe.half_extent)
                    + 2.0 * ka
                    + moment_ulps(p, &|mo| d(mo).d(h));
                (lobe.d(h), t)
            },
        );
    }
    one(
        "lean_nested::proxy_lobe (proxy::KHPL16_PROXY)",
        "ggx::d_axis_aligned(lean_nested::proxy_lobe(proxy::KHPL16_PROXY, r, fp, m), h)",
        &|p| {
            let h = v3(p.h);
            let d = |mo: &LeanMoments| {
                Ggx::new(p.material()).filtered(p.fp(), Lean::new(Proxy::KHPL16, *mo))
            };
            // The proxy's bound (checks/method.rs) with the widened alphas' rounding added to
            // its inputs (2 ulp, entering `D` with weight up to 4).
            let t = 2.0 * (7.0 + 4.0 * 12.0 + 1.0)
                + 6.0
                + 2.0 * 12.0
                + 8.0
                + moment_ulps(p, &|mo| d(mo).d(h));
            (d(&p.moments()).d(h), t)
        },
    );
    one(
        "lean_nested::lean_mean_normal",
        "dot(lean_nested::lean_mean_normal(m), w)",
        &|p| {
            // normalize of (-mean, 1): 3 ulp for the length and the quotient, 3 for the dot
            // (|w| = 1), relative to 1.
            let n = filtered_ndf::f64::filter::lean_mean_normal(&p.moments());
            (n.dot(v3(p.w)), 0.0)
        },
    );
    // lean_mean_normal's dot may be near zero: an absolute tolerance.
    if let Some(c) = checks.last_mut() {
        for case in &mut c.cases {
            case.tol = vec![Tol::abs(8.0 * EPS)];
        }
        c.tolerance =
            "8 EPS absolute (normalize: 3 ulp; dot with a unit vector: 3 ulp of 1)".into();
    }
    checks
}
