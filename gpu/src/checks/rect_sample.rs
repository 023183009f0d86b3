//! `shaders/sampling/rect.wgsl`: the box lobe's `D(m) m_z` sampler and its pdfs.
//!
//! Cases: alpha from `strategies::axis_aligned()`, the half extents of the trade table (the
//! bounding box of `strategies::footprint()` under KHPL16's rules, as `checks::rect` draws
//! them; one case in eight with a zero box), views from `strategies::upper_hemisphere(89)`,
//! four uniform numbers (SplitMix64) with the corners `0` and `1 - 2^-24` mixed in.
//!
//! Tolerances (derived per case from the `f64` reference):
//! - `sample_normal_rect`: the slope `s = g + delta` carries `10 EPS rad (alpha_x + alpha_y)`
//!   from the GGX slope (`rad = sqrt(u1 / (1 - u1))`: the division 3 ulp, the square root
//!   halving it plus its own; `sincos_turns` 3 `EPS`; the products), `3 EPS |delta|` from the
//!   offset (`2 u - 1` and the product) and `EPS |s|` from the sum; the unit normal
//!   `(-s, 1) / sqrt(1 + |s|^2)` moves by at most `|ds| / sqrt(1 + |s|^2)`, and its
//!   normalisation adds `8 EPS`. Absolute, per component.
//! - `normal_pdf_rect`: `d_rect`'s bound (`checks::rect::d_rect_ulps` at the slope of `m`)
//!   plus 2 ulp for the product. `visible_normal_pdf_rect`: that, plus `lambda_rect`'s bound
//!   (`checks::rect::lambda_rect_ulps`, with its condition numbers), `2 EPS / (wo.m)` for the
//!   dot product and 4 ulp for the products and the division.

use super::rect::{d_rect_ulps, lambda_rect_ulps};
use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, ClampRules, DVec2, Footprint, SplitMix64, sampling, strategies, v2, v3,
};

/// The checks of `sampling/rect.wgsl`.
pub fn all() -> Vec<Check> {
    let imports =
        "#import filtered_ndf::ndf::roughness::axis_aligned\n#import filtered_ndf::sampling::rect";
    let pre = "let r = axis_aligned::from_alpha(x2(0u));\nlet he = x2(2u);\nlet wo = x3(4u);\nlet u = x2(7u);\nlet ub = x2(9u);\n";
    let mut sn = Check::new(
        "sampling::rect::sample_normal_rect",
        imports,
        &format!("{pre}y3(0u, rect::sample_normal_rect(r, he, u, ub));"),
        11,
        3,
    )
    .tolerance("|ds| / sqrt(1 + |s|^2) + 8 EPS absolute per component, |ds| = 10 EPS rad (alpha_x + alpha_y) + 3 EPS |delta| + EPS |s| (module docs)");
    let mut pd = Check::new(
        "sampling::rect::{normal_pdf_rect, visible_normal_pdf_rect}",
        imports,
        &format!(
            "{pre}let m = x3(11u);\ny(0u, rect::normal_pdf_rect(r, he, m));\ny(1u, rect::visible_normal_pdf_rect(r, he, wo, m));"
        ),
        14,
        2,
    )
    .tolerance("d_rect_ulps + 2 ulp; plus lambda_rect_ulps, 2 EPS / (wo.m) and 4 ulp for the visible density");

    let n = 2000;
    let a = draw(strategies::axis_aligned(), n, "rect sample alpha");
    let ws = draw(strategies::upper_hemisphere(89.0), n, "rect sample wo");
    let fps = draw(strategies::footprint(), n, "rect sample fp");
    let mut rng = SplitMix64(0x7265_6374);
    for k in 0..n {
        let alpha = [a[k].alpha().x as f32, a[k].alpha().y as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        let fp = Footprint::from_slope_derivatives(
            v2([fps[k].dh_u.x as f32, fps[k].dh_u.y as f32]),
            v2([fps[k].dh_v.x as f32, fps[k].dh_v.y as f32]),
        );
        let he = ClampRules::KHPL16
            .rect(fp.bounding_rect(), r.alpha())
            .half_extent;
        let he32 = if k % 8 == 0 {
            [0.0, 0.0]
        } else {
            [he.x as f32, he.y as f32]
        };
        let wo = [ws[k].x as f32, ws[k].y as f32, ws[k].z as f32];
        let mut us = [0f32; 4];
        for (j, u) in us.iter_mut().enumerate() {
            *u = match (k + j) % 40 {
                0 => 0.0,
                1 => 0.99999994,
                _ => rng.uniform() as f32,
            };
        }
        let mut input = alpha.to_vec();
        input.extend(he32);
        input.extend(wo);
        input.extend(us);
        let (hd, wd) = (v2(he32), v3(wo));
        let (u, ub) = (
            DVec2::new(us[0].into(), us[1].into()),
            DVec2::new(us[2].into(), us[3].into()),
        );

        let m = sampling::rect::sample_normal_rect(r, hd, u, ub);
        // The tolerance's terms, from the reference's own slope.
        let (u1, ax, ay) = (u.x, r.alpha().x, r.alpha().y);
        let rad = (u1 / (1.0 - u1)).sqrt();
        let delta = DVec2::new((2.0 * ub.x - 1.0) * hd.x, (2.0 * ub.y - 1.0) * hd.y);
        let s = DVec2::new(-m.x / m.z, -m.y / m.z);
        let ds = 10.0 * EPS * rad * (ax + ay)
            + 3.0 * EPS * (delta.x.abs() + delta.y.abs())
            + EPS * s.length();
        let t = ds / (1.0 + s.length_squared()).sqrt() + 8.0 * EPS;
        sn.case(input.clone(), vec![m.x, m.y, m.z], vec![Tol::abs(t); 3]);

        // The pdfs at the reference's visible sample (the normals a renderer evaluates).
        let Some(mv) = sampling::rect::sample_visible_normal_rect(r, hd, wd, u, ub) else {
            continue;
        };
        let m32 = [mv.x as f32, mv.y as f32, mv.z as f32];
        let md = v3(m32);
        let wom = wd.normalize().dot(md);
        if !(wom > 0.0 && md.z > 0.0) {
            continue;
        }
        let center = DVec2::new(-md.x / md.z, -md.y / md.z);
        let t_d = d_rect_ulps(r, center, hd);
        let t_l = lambda_rect_ulps(r, hd, wd);
        input.extend(m32);
        pd.case(
            input,
            vec![
                sampling::rect::normal_pdf_rect(r, hd, md),
                sampling::rect::visible_normal_pdf_rect(r, hd, wd, md),
            ],
            vec![Tol::ulps(t_d + 2.0), Tol::ulps(t_d + t_l + 2.0 / wom + 4.0)],
        );
    }
    vec![sn, pd]
}
