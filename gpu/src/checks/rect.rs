//! `shaders/filter/rect.wgsl`: the exact GGX box filter in f32, and the printed GDC listing.
//!
//! Cases: the trade table's shading points (materials from `strategies::axis_aligned`, half
//! vectors from `strategies::upper_hemisphere(89)`, footprints from `strategies::footprint`,
//! rectangle = the footprint's bounding rectangle under the default rules without the
//! floor, as the trade table's exact-rect row), and rectangles drawn as
//! `tests/ggx_rect.rs` draws them (alpha log-uniform in `[1e-4, 1]`, anisotropy up to 100,
//! centre components up to 4, half sides log-uniform in `[1e-8, 1]`).
//!
//! Tolerances (per case, from the normalised rectangle in f64, `filter/rect.wgsl`'s bound):
//! 60 ulp, plus `8 (1 + u_c^2 + v_c^2)^(3/2) / min(H_u, H_v)` ulp where both axes take the
//! four-edge closed form. The printed listing: `16 EPS` times the sum of the magnitudes of
//! its eight terms, divided as the result is, plus 8 ulp.

use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, ClampRules, DVec2, ExtentFloor, SplitMix64, rect, strategies, v2, v3,
};

/// The stated bound (ulp) for the normalised rectangle.
fn rect_ulps(r: AxisAligned, center: DVec2, he: DVec2) -> f64 {
    let a = r.alpha();
    let (uc, vc) = (center.x / a.x, center.y / a.y);
    let (hu, hv) = (he.x.abs() / a.x, he.y.abs() / a.y);
    let du = (uc.abs() - hu).max(0.0);
    let dv = (vc.abs() - hv).max(0.0);
    let closed = |h: f64, l2: f64| h * h >= 0.0625 * l2;
    let both = closed(hu, 1.0 + uc * uc + dv * dv) && closed(hv, 1.0 + vc * vc + du * du);
    let mut t = 60.0;
    if both {
        t += 8.0 * (1.0 + uc * uc + vc * vc).powf(1.5) / hu.min(hv);
    }
    t
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
    .tolerance("60 ulp; plus 8 (1 + u_c^2 + v_c^2)^1.5 / min(H_u, H_v) ulp where both axes take the closed form (filter/rect.wgsl)");
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
            vec![Tol::ulps(rect_ulps(r, center, he))],
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
    .tolerance("60 ulp; plus 8 (1 + u_c^2 + v_c^2)^1.5 / min(H_u, H_v) ulp where both axes take the closed form");
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
    vec![d, pr, p]
}
