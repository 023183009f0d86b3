//! `shaders/filter/rect.wgsl`: the exact GGX box filter in f32, and the printed GDC listing.
//!
//! Cases: the trade table's shading points (materials from `strategies::axis_aligned`, half
//! vectors from `strategies::upper_hemisphere(89)`, footprints from `strategies::footprint`,
//! rectangle = the footprint's bounding rectangle under the default rules without the
//! floor, as the trade table's exact-rect row), and rectangles drawn as
//! `tests/ggx_rect.rs` draws them (alpha log-uniform in `[1e-4, 1]`, anisotropy up to 100,
//! centre components up to 4, half sides log-uniform in `[1e-8, 1]`).
//!
//! And rectangles far into the tail (`far_tail_cases`): centres up to `1e6` lobe widths from
//! the peak, half sides from `1e-7` to ten times that distance, where the four-edge closed
//! form cancelled (up to `0.25` relative before the polar form).
//!
//! Tolerances (per case, from the normalised rectangle in f64, [`rect_ulps`]): 60 ulp, plus
//! `16 sum |t_i| / |sum t_i|` ulp where both axes take a closed form (the four edge terms
//! `t_i` of the four-edge form near the peak or of the polar form beyond, and their
//! cancellation factor computed here in f64). The printed listing: `16 EPS` times the sum of
//! the magnitudes of its eight terms, divided as the result is, plus 8 ulp.

use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, ClampRules, DVec2, DVec3, ExtentFloor, SplitMix64, rect, strategies, v2, v3,
};

/// The 8-point Gauss-Legendre rule (positive nodes, halved weights), as `rect.wgsl`.
const GL8: [(f64, f64); 4] = [
    (0.183_434_642_495_649_8, 0.181_341_891_689_181),
    (0.525_532_409_916_329, 0.156_853_322_938_943_64),
    (0.796_666_477_413_626_7, 0.111_190_517_226_687_24),
    (0.960_289_856_497_536_2, 0.050_614_268_145_188_13),
];

/// `integral over [lo, hi] of g` by the 8-point rule, in f64.
fn gl8(lo: f64, hi: f64, g: impl Fn(f64) -> f64) -> f64 {
    let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    GL8.iter()
        .map(|&(x, w)| w * (g(c - h * x) + g(c + h * x)))
        .sum::<f64>()
        * (hi - lo)
}

/// The polar edge term of `rect.wgsl`'s `far_field`, `sign(x) integral over y in [a, b] of
/// |x| / ((x^2 + y^2)(1 + x^2 + y^2))`, in f64 (for the cancellation factor of the
/// tolerance only).
fn edge_polar(x: f64, a: f64, b: f64) -> f64 {
    let ax = x.abs();
    if ax < 1e-12 {
        return 0.0;
    }
    let x2 = ax * ax;
    let range = |a: f64, b: f64| {
        let mut v = 0.0;
        if a < ax {
            v += gl8(a / ax, b.min(ax) / ax, |t| {
                let q = 1.0 + t * t;
                1.0 / (q * (1.0 + x2 * q))
            });
        }
        if b > ax {
            v += gl8(ax / b, ax / a.max(ax), |t| {
                let t2 = t * t;
                t2 / ((1.0 + t2) * (t2 + x2 * (1.0 + t2)))
            });
        }
        v
    };
    let v = if a >= 0.0 {
        range(a, b)
    } else if b <= 0.0 {
        range(-b, -a)
    } else {
        range(0.0, -a) + range(0.0, b)
    };
    v.copysign(x)
}

/// The four-edge closed form's edge term `u / S atan2(dv S, S^2 + v0 v1)`, in f64.
fn edge(u: f64, dv: f64, v01: f64) -> f64 {
    let s2 = 1.0 + u * u;
    let s = s2.sqrt();
    u / s * (dv * s).atan2(s2 + v01)
}

/// `sum |t_i| / |sum t_i|` of four signed terms: the amplification of their rounding.
fn cancellation(t: [f64; 4]) -> f64 {
    let sum = t[0] + t[1] + t[2] + t[3];
    t.iter().map(|x| x.abs()).sum::<f64>() / sum.abs()
}

/// The stated bound (ulp) for the normalised rectangle (`filter/rect.wgsl`'s): 60 ulp for the
/// Gauss-Legendre tiers and the 1D closed form; where both axes take the closed form the
/// result is a signed sum of four edge terms (the four-edge form within `sqrt(FAR2) = 0.5` of
/// the peak, the polar form beyond), each within 16 ulp of its magnitude (the edges: `math::atan`
/// 8, its argument 5, the factor 3; the polar pieces: 8 nodes of a few ulp each and their
/// end points), so 60 plus `16 sum |t_i| / |sum t_i|` ulp, that factor computed here in f64.
pub fn rect_ulps(r: AxisAligned, center: DVec2, he: DVec2) -> f64 {
    let a = r.alpha();
    let (uc, vc) = (center.x / a.x, center.y / a.y);
    let (hu, hv) = (he.x.abs() / a.x, he.y.abs() / a.y);
    let du = (uc.abs() - hu).max(0.0);
    let dv = (vc.abs() - hv).max(0.0);
    let closed = |h: f64, l2: f64| h * h >= 0.0625 * l2;
    let both = closed(hu, 1.0 + uc * uc + dv * dv) && closed(hv, 1.0 + vc * vc + du * du);
    if !both {
        return 60.0;
    }
    let (u0, u1, v0, v1) = (uc - hu, uc + hu, vc - hv, vc + hv);
    let terms = if du * du + dv * dv > 0.25 {
        [
            edge_polar(u1, v0, v1),
            -edge_polar(u0, v0, v1),
            edge_polar(v1, u0, u1),
            -edge_polar(v0, u0, u1),
        ]
    } else {
        let (u01, v01) = (u0 * u1, v0 * v1);
        [
            edge(u1, 2.0 * hv, v01),
            -edge(u0, 2.0 * hv, v01),
            edge(v1, 2.0 * hu, u01),
            -edge(v0, 2.0 * hu, u01),
        ]
    };
    let c = cancellation(terms);
    60.0 + 16.0 * if c.is_finite() { c } else { 1e30 }
}

/// [`rect_ulps`] for `d_rect`, whose centre, the slope `-h_xy / h_z`, is formed in f32: its
/// 3 ulp of `|s|` move the rectangle's ends by `3 eps |u_c|` (normalised), which changes the
/// mean by at most 4 times that over the distance of the ends from the peak (at least 1 in
/// normalised units, the width of `f`): `12 (|u_c| / max(gap_u, 1) + |v_c| / max(gap_v, 1))`
/// ulp more.
pub fn d_rect_ulps(r: AxisAligned, center: DVec2, he: DVec2) -> f64 {
    let a = r.alpha();
    let (uc, vc) = (center.x / a.x, center.y / a.y);
    let (hu, hv) = (he.x.abs() / a.x, he.y.abs() / a.y);
    let gu = (uc.abs() - hu).max(1.0);
    let gv = (vc.abs() - hv).max(1.0);
    rect_ulps(r, center, he) + 12.0 * (uc.abs() / gu + vc.abs() / gv)
}

/// The sum of the magnitudes of the printed formula's eight terms over `|den|`, `/ max(hz^4, 1e-3)`.
fn printed_scale(r: AxisAligned, hpp: DVec2, hz: f64, fp: DVec2) -> f64 {
    let al = r.alpha();
    let (a, b) = (al.x, al.y);
    let (x1, x2, y1, y2) = (hpp.x - fp.x, hpp.x + fp.x, hpp.y - fp.y, hpp.y + fp.y);
    let (sx1, sx2) = ((x1 * x1 + a * a).sqrt(), (x2 * x2 + a * a).sqrt());
    let (sy1, sy2) = ((y1 * y1 + b * b).sqrt(), (y2 * y2 + b * b).sqrt());
    let t = [
        x1 / sx1 * (y1 * a / (sx1 * b)).atan(),
        x1 / sx1 * (y2 * a / (sx1 * b)).atan(),
        x2 / sx2 * (y1 * a / (sx2 * b)).atan(),
        x2 / sx2 * (y2 * a / (sx2 * b)).atan(),
        y1 / sy1 * (x1 * b / (a * sy1)).atan(),
        y1 / sy1 * (x2 * b / (a * sy1)).atan(),
        y2 / sy2 * (x1 * b / (a * sy2)).atan(),
        y2 / sy2 * (x2 * b / (a * sy2)).atan(),
    ];
    let sum: f64 = t.iter().map(|x| x.abs()).sum();
    let den = (2.0 * core::f64::consts::PI * (x1 - x2) * (y1 - y2)).abs();
    sum / den / (hz.powi(4)).max(1e-3)
}

/// The checks of `shaders/filter/rect.wgsl`.
pub fn all() -> Vec<Check> {
    let imports =
        "#import filtered_ndf::ndf::roughness::axis_aligned\n#import filtered_ndf::filter::rect";
    let mut d = Check::new(
        "rect::d_rect (trade table: bounding box, no floor)",
        imports,
        "y(0u, rect::d_rect(axis_aligned::from_alpha(x2(0u)), x3(2u), x2(5u)));",
        7,
        1,
    )
    .tolerance("rect_ulps plus 12 (|u_c| / max(gap_u, 1) + |v_c| / max(gap_v, 1)) ulp for the slope's rounding (d_rect_ulps)");
    let mut pr = Check::new(
        "rect::d_rect_printed (GDC 2016 listing, epsilon floor)",
        imports,
        "let h = x3(2u);\ny(0u, rect::d_rect_printed(axis_aligned::from_alpha(x2(0u)), h.xy / h.z, h, x2(5u)));",
        7,
        1,
    )
    .tolerance("16 EPS sum |terms| / |2 pi dx dy| / max(h_z^4, 1e-3) absolute, plus 8 ulp");
    let n = 2000;
    let a = draw(strategies::axis_aligned(), n, "rect alpha");
    let hs = draw(strategies::upper_hemisphere(89.0), n, "rect h");
    let fps = draw(strategies::footprint(), n, "rect fp");
    let no_floor = ClampRules {
        floor: ExtentFloor::None,
        ..ClampRules::default()
    };
    for k in 0..n {
        let alpha = [a[k].alpha().x as f32, a[k].alpha().y as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        let h = [hs[k].x as f32, hs[k].y as f32, hs[k].z as f32];
        let hd = v3(h);
        let fp = crate::reference::Footprint::from_slope_derivatives(
            v2([fps[k].dh_u.x as f32, fps[k].dh_u.y as f32]),
            v2([fps[k].dh_v.x as f32, fps[k].dh_v.y as f32]),
        );
        let he = no_floor.rect(fp.bounding_rect(), r.alpha()).half_extent;
        let he32 = [he.x as f32, he.y as f32];
        let he = v2(he32);
        let mut input = alpha.to_vec();
        input.extend(h);
        input.extend(he32);
        let center = DVec2::new(-hd.x / hd.z, -hd.y / hd.z);
        d.case(
            input.clone(),
            vec![rect::d_rect(r, hd, he)],
            vec![Tol::ulps(d_rect_ulps(r, center, he))],
        );
        // The printed listing with the default epsilon floor (the trade table's row).
        let he_p = ClampRules::default()
            .rect(fp.bounding_rect(), r.alpha())
            .half_extent;
        let hp32 = [he_p.x as f32, he_p.y as f32];
        let he_p = v2(hp32);
        let hpp = DVec2::new(
            f64::from((hd.x / hd.z) as f32),
            f64::from((hd.y / hd.z) as f32),
        );
        let mut input = alpha.to_vec();
        input.extend(h);
        input.extend(hp32);
        let reference = rect::d_rect_printed(r, hpp, hd, he_p);
        pr.case(
            input,
            vec![reference],
            vec![Tol::rel_abs(
                8.0 * EPS,
                16.0 * EPS * printed_scale(r, hpp, hd.z, he_p) + super::TINY,
            )],
        );
    }

    // Rectangles as tests/ggx_rect.rs draws them, through p22_rect.
    let mut p = Check::new(
        "rect::p22_rect",
        imports,
        "y(0u, rect::p22_rect(axis_aligned::from_alpha(x2(0u)), x2(2u), x2(4u)));",
        6,
        1,
    )
    .tolerance("60 ulp; plus 16 sum |t_i| / |sum t_i| ulp where both axes take a closed form (four edge or polar terms t_i; rect_ulps)");
    let mut rng = SplitMix64(0x7265_6374);
    for _ in 0..3000 {
        let ax = rng.log_uniform(1e-4, 1.0);
        let ay = (ax * rng.log_uniform(0.01, 100.0)).clamp(1e-4, 1.0);
        let alpha = [ax as f32, ay as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        let c = [
            (rng.range(-4.0, 4.0) * ax) as f32,
            (rng.range(-4.0, 4.0) * ay) as f32,
        ];
        let he = [
            rng.log_uniform(1e-8, 1.0) as f32,
            rng.log_uniform(1e-8, 1.0) as f32,
        ];
        let mut input = alpha.to_vec();
        input.extend(c);
        input.extend(he);
        p.case(
            input,
            vec![rect::p22_rect(r, v2(c), v2(he))],
            vec![Tol::ulps(rect_ulps(r, v2(c), v2(he)))],
        );
    }
    let mut far = Check::new(
        "rect::p22_rect (far tail: centres to 1e6 lobe widths)",
        imports,
        "y(0u, rect::p22_rect(axis_aligned::from_alpha(x2(0u)), x2(2u), x2(4u)));",
        6,
        1,
    )
    .tolerance("60 ulp; plus 16 sum |t_i| / |sum t_i| ulp where both axes take a closed form (four edge or polar terms t_i; rect_ulps)");
    let mut rng = SplitMix64(0x6661_7274);
    for _ in 0..6000 {
        let ax = rng.log_uniform(1e-4, 1.0);
        let ay = (ax * rng.log_uniform(0.01, 100.0)).clamp(1e-4, 1.0);
        let alpha = [ax as f32, ay as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        // Normalised centre at distance `dist` in a random direction, half sides from 1e-7
        // to 10 times (1 + dist), in lobe widths.
        let dist = rng.log_uniform(1e-2, 1e6);
        let th = rng.range(0.0, core::f64::consts::TAU);
        let c = [(dist * th.cos() * ax) as f32, (dist * th.sin() * ay) as f32];
        let he = [
            (rng.log_uniform(1e-7, 10.0) * (1.0 + dist) * ax) as f32,
            (rng.log_uniform(1e-7, 10.0) * (1.0 + dist) * ay) as f32,
        ];
        let reference = rect::p22_rect(r, v2(c), v2(he));
        let mut input = alpha.to_vec();
        input.extend(c);
        input.extend(he);
        far.case(
            input,
            vec![reference],
            vec![Tol::ulps(rect_ulps(r, v2(c), v2(he)))],
        );
    }
    let mut v = vec![d, pr, p, far];
    v.extend(lambda_checks());
    v
}

/// `|d ln F / d ln x|` of a positive function at `x` by central differences with the relative
/// step `1e-5` (the f64 references are accurate to `~1e-13`, so the quotient is good to
/// `1e-8` absolute: ample for a condition factor). `0` where `F` is 0 or not finite.
pub fn log_sensitivity(x: f64, f: impl Fn(f64) -> f64) -> f64 {
    let h = 1e-5;
    let (a, b) = (f(x * (1.0 + h)), f(x * (1.0 - h)));
    let s = (a.ln() - b.ln()) / (2.0 * h);
    if s.is_finite() { s.abs() } else { 0.0 }
}

/// The f32 Gauss-Legendre tier of `rect.wgsl` (`true`: the closed form).
fn closed_tier(h2: f64, l2: f64) -> bool {
    h2 >= 0.0625 * l2
}

/// The stated bound (ulp) of `lambda::lambda_rect` (`rect/lambda.wgsl`): the expectation's
/// own error, 30 ulp on the Gauss-Legendre and `Psi_1`-difference paths, and where both
/// closed differences are taken (case 3) `30 + 64 ln(2 + 2m)` (the outer difference loses
/// `2 ln(2m)`, the inner closed difference a factor 4, of `Psi_2` values within 8 ulp); plus
/// the input conditioning: the shader forms `m`, `k_1`, `k_2` and `m - k_l` with up to 16 ulp
/// (hypot, quotients, the product `|w_l| H_l` rounded before the difference), which `Lambda`
/// amplifies by its condition numbers with respect to `w_z` (moves `m` and `m - k_l`), `H_x`
/// and `H_y` (move `k_1`, `k_2`), computed here from the f64 reference.
pub fn lambda_rect_ulps(r: AxisAligned, he: DVec2, w: DVec3) -> f64 {
    let al = r.alpha();
    let l = w.x.hypot(w.y);
    let (ux, uy) = (w.x.abs() / l, w.y.abs() / l);
    let a = (ux * al.x).hypot(uy * al.y);
    let m = w.z.abs() / l / a;
    let k1 = ux * he.x.abs() / a;
    let k2 = uy * he.y.abs() / a;
    let (ks, kl) = (k1.min(k2), k1.max(k2));
    let near_l = (m - ks).max(0.0);
    let lo = m - kl;
    let case3 = closed_tier(kl * kl, 1.0 + near_l * near_l)
        && ks > 0.0
        && closed_tier(ks * ks, 1.0 + lo * lo);
    let base = if case3 {
        30.0 + 64.0 * (2.0 + 2.0 * m).ln()
    } else {
        30.0
    };
    let lam = |w: DVec3, he: DVec2| rect::lambda_rect(r, he, w);
    let kz = log_sensitivity(w.z, |z| lam(DVec3::new(w.x, w.y, z), he));
    let kx = log_sensitivity(he.x, |h| lam(w, DVec2::new(h, he.y)));
    let ky = log_sensitivity(he.y, |h| lam(w, DVec2::new(he.x, h)));
    base + 16.0 * (kz + kx + ky)
}

/// The checks of `rect/lambda.wgsl`: the box lobe's `Lambda` at the trade table's shading
/// points (rectangle: the footprint's bounding box under KHPL16's rules, `lambda = 1`, no
/// floor) seen from `strategies::upper_hemisphere(89.9)` directions, and over boxes as
/// `tests/ggx_rect_lambda.rs` draws them (alpha `1e-4..1`, anisotropy to 100, half sides
/// `1e-6..1`).
pub fn lambda_checks() -> Vec<Check> {
    let imports = "#import filtered_ndf::ndf::roughness::axis_aligned\n#import filtered_ndf::filter::rect::lambda";
    let body = "y(0u, lambda::lambda_rect(axis_aligned::from_alpha(x2(0u)), x2(2u), x3(4u)));";
    let tol = "base 30 ulp (case 3: 30 + 64 ln(2 + 2m)) plus 16 ulp times Lambda's condition numbers in w_z, H_x, H_y (lambda_rect_ulps)";
    let mut c = Check::new("lambda::lambda_rect (trade table)", imports, body, 7, 1).tolerance(tol);
    let n = 2000;
    let a = draw(strategies::axis_aligned(), n, "lambda alpha");
    let ws = draw(strategies::upper_hemisphere(89.9), n, "lambda w");
    let fps = draw(strategies::footprint(), n, "lambda fp");
    for k in 0..n {
        let alpha = [a[k].alpha().x as f32, a[k].alpha().y as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        let fp = crate::reference::Footprint::from_slope_derivatives(
            v2([fps[k].dh_u.x as f32, fps[k].dh_u.y as f32]),
            v2([fps[k].dh_v.x as f32, fps[k].dh_v.y as f32]),
        );
        let he = ClampRules::KHPL16
            .rect(fp.bounding_rect(), r.alpha())
            .half_extent;
        let he32 = [he.x as f32, he.y as f32];
        let w = [ws[k].x as f32, ws[k].y as f32, ws[k].z as f32];
        let (hd, wd) = (v2(he32), v3(w));
        let mut input = alpha.to_vec();
        input.extend(he32);
        input.extend(w);
        c.case(
            input,
            vec![rect::lambda_rect(r, hd, wd)],
            vec![Tol::ulps(lambda_rect_ulps(r, hd, wd))],
        );
    }
    let mut b = Check::new(
        "lambda::lambda_rect (boxes of tests/ggx_rect_lambda.rs)",
        imports,
        body,
        7,
        1,
    )
    .tolerance(tol);
    let mut rng = SplitMix64(0x6c61_6d62);
    for _ in 0..3000 {
        let ax = rng.log_uniform(1e-4, 1.0);
        let ay = (ax * rng.log_uniform(0.01, 100.0)).clamp(1e-4, 1.0);
        let alpha = [ax as f32, ay as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        let he32 = [
            rng.log_uniform(1e-6, 1.0) as f32,
            rng.log_uniform(1e-6, 1.0) as f32,
        ];
        let th = rng.range(0.0, 0.9999 * core::f64::consts::FRAC_PI_2);
        let phi = rng.range(0.0, core::f64::consts::TAU);
        let w = [
            (th.sin() * phi.cos()) as f32,
            (th.sin() * phi.sin()) as f32,
            th.cos() as f32,
        ];
        let (hd, wd) = (v2(he32), v3(w));
        let mut input = alpha.to_vec();
        input.extend(he32);
        input.extend(w);
        b.case(
            input,
            vec![rect::lambda_rect(r, hd, wd)],
            vec![Tol::ulps(lambda_rect_ulps(r, hd, wd))],
        );
    }
    vec![c, b]
}
