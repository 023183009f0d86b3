//! `shaders/filter/method.wgsl`: the front door's method set as WGSL entry functions, against
//! the Rust front door `material.filtered(footprint, method)` in `f64`, at the trade table's
//! shading points (axis-aligned materials from `strategies::axis_aligned`, footprints from
//! `strategies::footprint`, half vectors from `upper_hemisphere(89)`, views from
//! `upper_hemisphere(89.9)`).
//!
//! Tolerances: each entry function is the composition of functions checked on their own, and
//! carries their stated bounds (reused from their checks): the filtered-matrix `D` rule of
//! [`super::filters`] (`Gaussian`, `Projected`), the exact Gaussian's condition-number rule of
//! [`super::gaussian_ggx`], `d_rect`'s and `lambda_rect`'s of [`super::rect`], the proxy's
//! `2 (7 + 4 x 12 + 1) + 6 + 2 x 12` ulp; `g1`, `g2` of the box lobe from its `Lambda`;
//! `p22_rect_filtered` from `p22_rect`'s and the box's f32 rounding.

use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, Beckmann, DVec2, DVec3, ExactGaussian, Filterable, Footprint, Gaussian, Ggx, Ndf,
    Projected, Proxy, Rect, RectFilteredGgx, Roughness, SplitMix64, strategies, v2, v3,
};

/// One shading point: material, footprint, half vector `h`, views `w`, `o`.
struct Point {
    alpha: [f32; 2],
    du: [f32; 2],
    dv: [f32; 2],
    h: [f32; 3],
    w: [f32; 3],
    o: [f32; 3],
}

impl Point {
    fn input(&self) -> Vec<f32> {
        let mut v = self.alpha.to_vec();
        v.extend(self.du);
        v.extend(self.dv);
        v.extend(self.h);
        v.extend(self.w);
        v.extend(self.o);
        v
    }
    fn material(&self) -> AxisAligned {
        AxisAligned::new(self.alpha[0].into(), self.alpha[1].into()).expect("in range")
    }
    fn fp(&self) -> Footprint {
        Footprint::from_slope_derivatives(v2(self.du), v2(self.dv))
    }
}

fn points(n: usize) -> Vec<Point> {
    let a = draw(strategies::axis_aligned(), n, "method alpha");
    let hs = draw(strategies::upper_hemisphere(89.0), n, "method h");
    let ws = draw(strategies::upper_hemisphere(89.9), 2 * n, "method w");
    let fps = draw(strategies::footprint(), n, "method fp");
    let f3 = |d: DVec3| [d.x as f32, d.y as f32, d.z as f32];
    (0..n)
        .map(|k| Point {
            alpha: [a[k].alpha().x as f32, a[k].alpha().y as f32],
            du: [fps[k].dh_u.x as f32, fps[k].dh_u.y as f32],
            dv: [fps[k].dh_v.x as f32, fps[k].dh_v.y as f32],
            h: f3(hs[k]),
            w: f3(ws[2 * k]),
            o: f3(ws[2 * k + 1]),
        })
        .collect()
}

const IMPORTS: &str = "#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::footprint
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::rect::lobe
#import filtered_ndf::filter::proxy";

const PROLOGUE: &str = "let r = axis_aligned::from_alpha(x2(0u));
let a = axis_aligned::to_matrix(r);
let fp = footprint::from_slope_derivatives(x2(2u), x2(4u));
let h = x3(6u);
let w = x3(9u);
let o = x3(12u);";

/// The checks of `shaders/filter/method.wgsl`.
pub fn all() -> Vec<Check> {
    let pts = points(1500);
    let mut checks = Vec::new();
    let mut one = |name: &str, expr: &str, f: &dyn Fn(&Point) -> (f64, f64)| {
        let body = format!("{PROLOGUE}\ny(0u, {expr});");
        let mut c = Check::new(name, IMPORTS, &body, 15, 1)
            .tolerance("the stated bound of the functions it composes (checks/method.rs)");
        for p in &pts {
            let (e, t) = f(p);
            c.case(p.input(), vec![e], vec![Tol::ulps(t)]);
        }
        checks.push(c);
    };
    for (name, tk19) in [("TK19_GAUSSIAN", true), ("KHPL16_GAUSSIAN", false)] {
        let m = if tk19 {
            Gaussian::TK19
        } else {
            Gaussian::KHPL16
        };
        one(
            &format!("gaussian::d_ggx_gaussian (gaussian::{name})"),
            &format!("gaussian::d_ggx_gaussian(gaussian::{name}, a, fp, h)"),
            &move |p| {
                let lobe = Ggx::new(p.material()).filtered(p.fp(), m);
                let h = v3(p.h);
                (
                    lobe.d(h),
                    super::filters::filtered_d_tol(&lobe.roughness, h, true),
                )
            },
        );
        one(
            &format!("gaussian::d_beckmann_gaussian (gaussian::{name})"),
            &format!("gaussian::d_beckmann_gaussian(gaussian::{name}, a, fp, h)"),
            &move |p| {
                let lobe = Beckmann::new(p.material()).filtered(p.fp(), m);
                let h = v3(p.h);
                (
                    lobe.d(h),
                    super::filters::filtered_d_tol(&lobe.roughness, h, false),
                )
            },
        );
    }
    one(
        "projected::d_ggx_projected (projected::TK21_PROJECTED)",
        "projected::d_ggx_projected(projected::TK21_PROJECTED, a, fp, h)",
        &|p| {
            let lobe = Ggx::new(p.material()).filtered(p.fp(), Projected::TK21);
            let h = v3(p.h);
            (
                lobe.d(h),
                super::filters::filtered_d_tol(&lobe.roughness, h, true),
            )
        },
    );
    let exact_kernel = |p: &Point| {
        let r = ExactGaussian::KHPL16.clamps;
        r.kernel(r.footprint(p.fp()).covariance(0.5))
    };
    one(
        "gaussian_ggx::d_ggx_exact_gaussian (gaussian_ggx::KHPL16_EXACT_GAUSSIAN)",
        "gaussian_ggx::d_ggx_exact_gaussian(gaussian_ggx::KHPL16_EXACT_GAUSSIAN, a, fp, h)",
        &|p| {
            let lobe = Ggx::new(p.material()).filtered(p.fp(), ExactGaussian::KHPL16);
            let h = v3(p.h);
            let s = DVec2::new(-h.x / h.z, -h.y / h.z);
            let t =
                super::gaussian_ggx::density_ulps(&p.material().to_matrix(), &exact_kernel(p), s);
            (lobe.d(h), t)
        },
    );
    one(
        "gaussian_ggx::lambda(gaussian_ggx::exact_gaussian_lobe) (gaussian_ggx::KHPL16_EXACT_GAUSSIAN)",
        "gaussian_ggx::lambda(gaussian_ggx::exact_gaussian_lobe(gaussian_ggx::KHPL16_EXACT_GAUSSIAN, a, fp), w)",
        &|p| {
            let lobe = Ggx::new(p.material()).filtered(p.fp(), ExactGaussian::KHPL16);
            let w = v3(p.w);
            let t =
                super::gaussian_ggx::lambda_ulps(&p.material().to_matrix(), &exact_kernel(p), w);
            (lobe.lambda(w), t)
        },
    );
    for (name, gdc) in [("KHPL16_RECT", false), ("GDC2016_RECT", true)] {
        let m = if gdc { Rect::GDC2016 } else { Rect::KHPL16 };
        one(
            &format!("lobe::d_ggx_rect (lobe::{name})"),
            &format!("lobe::d_ggx_rect(lobe::{name}, r, fp, h)"),
            &move |p| {
                let lobe = Ggx::new(p.material()).filtered(p.fp(), m);
                let h = v3(p.h);
                let c = DVec2::new(-h.x / h.z, -h.y / h.z);
                let t = super::rect::d_rect_ulps(lobe.roughness, c, lobe.half_extent);
                (lobe.d(h), t)
            },
        );
        one(
            &format!("lobe::lambda_rect_filtered (lobe::{name})"),
            &format!("lobe::lambda_rect_filtered(lobe::rect_lobe(lobe::{name}, r, fp), w)"),
            &move |p| {
                let lobe = Ggx::new(p.material()).filtered(p.fp(), m);
                let w = v3(p.w);
                let t = super::rect::lambda_rect_ulps(lobe.roughness, lobe.half_extent, w);
                (lobe.lambda(w), t)
            },
        );
        one(
            &format!("lobe::g2_rect_filtered (lobe::{name})"),
            &format!("lobe::g2_rect_filtered(lobe::rect_lobe(lobe::{name}, r, fp), w, o, h)"),
            &move |p| {
                let lobe = Ggx::new(p.material()).filtered(p.fp(), m);
                let (w, o, h) = (v3(p.w), v3(p.o), v3(p.h));
                let lt = super::rect::lambda_rect_ulps(lobe.roughness, lobe.half_extent, w).max(
                    super::rect::lambda_rect_ulps(lobe.roughness, lobe.half_extent, o),
                );
                let l = lobe.lambda(w) + lobe.lambda(o);
                let f = if l.is_finite() { l / (1.0 + l) } else { 1.0 };
                (lobe.g2(w, o, h), lt * f + 4.0)
            },
        );
    }
    one(
        "proxy::d_ggx_proxy (proxy::KHPL16_PROXY)",
        "proxy::d_ggx_proxy(proxy::KHPL16_PROXY, r, fp, h)",
        &|p| {
            let lobe = Ggx::new(p.material()).filtered(p.fp(), Proxy::KHPL16);
            (
                lobe.d(v3(p.h)),
                2.0 * (7.0 + 4.0 * 12.0 + 1.0) + 6.0 + 2.0 * 12.0,
            )
        },
    );
    for (name, m) in [
        ("KHPL16_RECT", Rect::KHPL16),
        ("GDC2016_RECT", Rect::GDC2016),
    ] {
        checks.push(p22_rect_filtered(&pts, name, m));
        checks.push(g1_rect_filtered(&pts, name, m));
    }
    checks
}

/// `lobe::g1_rect_filtered(lobe, w, h)` of the box lobe at the trade table's shading points
/// (views `w` from `upper_hemisphere(89.9)`, micronormals `h` from `upper_hemisphere(89)`).
///
/// Tolerance: `G1 = chi+(w.m) / (1 + Lambda(w))` carries the bound of its `Lambda`
/// ([`super::rect::lambda_rect_ulps`]) times `|d ln G1 / d ln Lambda| = Lambda / (1 + Lambda)`,
/// plus 4 ulp for `1 + Lambda` and the quotient (as `g2_rect_filtered`'s). Where `|w.m| <= 4
/// EPS` the f32 dot product of the unit vectors (within 3 EPS) may take either sign, so the
/// shader may answer 0 or the value: the tolerance there is the value (absolute).
fn g1_rect_filtered(pts: &[Point], name: &str, m: Rect) -> Check {
    let body = format!(
        "{PROLOGUE}\ny(0u, lobe::g1_rect_filtered(lobe::rect_lobe(lobe::{name}, r, fp), w, h));"
    );
    let mut c = Check::new(
        &format!("lobe::g1_rect_filtered (lobe::{name})"),
        IMPORTS,
        &body,
        15,
        1,
    )
    .tolerance("lambda_rect_ulps times Lambda / (1 + Lambda), plus 4 ulp; the value itself where |w.m| <= 4 EPS (the sign of the f32 dot)");
    for p in pts {
        let lobe = Ggx::new(p.material()).filtered(p.fp(), m);
        let (w, h) = (v3(p.w), v3(p.h));
        let l = lobe.lambda(w);
        let tol = if w.dot(h).abs() <= 4.0 * EPS {
            Tol::abs(1.0 / (1.0 + l) + super::TINY)
        } else {
            let f = if l.is_finite() { l / (1.0 + l) } else { 1.0 };
            let lt = super::rect::lambda_rect_ulps(lobe.roughness, lobe.half_extent, w);
            Tol::ulps(lt * f + 4.0)
        };
        c.case(p.input(), vec![lobe.g1(w, h)], vec![tol]);
    }
    c
}

/// `lobe::p22_rect_filtered` of the box lobe `lobe::rect_lobe(method, r, fp)` at the
/// trade table's shading points, at two slopes each: the half vector's `-h_xy / h_z` (rounded
/// to f32, as the shader reads it), and a slope drawn uniformly in the box widened by half
/// (`s_i = t_i H_i`, `t_i` in `[-1.5, 1.5]`), where the filtered lobe is flat-topped and its
/// edges cut through it.
///
/// Tolerance: the bound of `rect::p22_rect` at that centre and box ([`super::rect::rect_ulps`]),
/// plus the rounding of the box: the shader forms the half extents `(|dh_u| + |dh_v|) / 2`
/// in f32 (one rounding, half an ulp; the clamps' `min` and `max` are exact), which moves
/// `P22` by its log-sensitivity to each half extent (central differences of the `f64`
/// reference, [`super::rect::log_sensitivity`]) times one ulp.
fn p22_rect_filtered(pts: &[Point], name: &str, m: Rect) -> Check {
    let body = format!(
        "{PROLOGUE}\ny(0u, lobe::p22_rect_filtered(lobe::rect_lobe(lobe::{name}, r, fp), x2(15u)));"
    );
    let mut c = Check::new(
        &format!("lobe::p22_rect_filtered (lobe::{name})"),
        IMPORTS,
        &body,
        17,
        1,
    )
    .tolerance("rect_ulps at the slope and box, plus 1 ulp times P22's log-sensitivity to each half extent (the box's f32 rounding)");
    let mut rng = SplitMix64(0x7032_3272);
    for p in pts {
        let lobe = Ggx::new(p.material()).filtered(p.fp(), m);
        let he = lobe.half_extent;
        let h = v3(p.h);
        let inside = [
            (rng.range(-1.5, 1.5) * he.x) as f32,
            (rng.range(-1.5, 1.5) * he.y) as f32,
        ];
        for s in [[(-h.x / h.z) as f32, (-h.y / h.z) as f32], inside] {
            let sd = v2(s);
            let p22 = |he: DVec2| RectFilteredGgx::new(lobe.roughness, he).p22(sd);
            let kx = super::rect::log_sensitivity(he.x, |x| p22(DVec2::new(x, he.y)));
            let ky = super::rect::log_sensitivity(he.y, |y| p22(DVec2::new(he.x, y)));
            let t = super::rect::rect_ulps(lobe.roughness, sd, he) + kx + ky;
            let mut input = p.input();
            input.extend(s);
            c.case(input, vec![lobe.p22(sd)], vec![Tol::ulps(t)]);
        }
    }
    c
}
