//! `shaders/sampling/beckmann.wgsl`: Beckmann visible-normal and NDF sampling with a
//! roughness matrix, the pdfs, and the visible-slope quantile.
//!
//! Cases: those of [`super::sampling`] (rotated matrices, alpha log-uniform in `[1e-4, 2]`,
//! anisotropy up to `1e3`, views from `strategies::upper_hemisphere(89)`), with the corner
//! `u = 0` moved to `2^-24`: at `u = 0` both builds return their slope bound `-X_MAX`, 9 in
//! f32 (the shader, as the Rust `f32` build) and 26 in `f64`, a stated difference of the
//! bounds rather than an error. The quantile alone: view angles from 0 to 90 degrees (the
//! ends included), `u` uniform plus `2^-24`, `1e-30` and `1 - 2^-24`.
//!
//! Tolerances (absolute, derived per case from the `f64` reference):
//! - The quantile `x = C^-1(u)`: below `u = 1/2` the shader's solve returns the exact
//!   quantile of some `u'` with `|u' - u| <= delta u`, `delta = 2 err_K + 4 EPS`
//!   (`err_K = (x^2 + 36) EPS`, the relative error of `K` in `cdf_terms`, taken at `x` and at
//!   the bracket end `hi`); above, of some `u'` with `|(1 - u') - (1 - u)| <= delta (1 - u)`,
//!   `delta` the error of `K(hi) - K(x)` as the shader forms it (`(t^2 + 36)` ulp of each
//!   term's magnitude, over the difference, plus 4): the tolerance is the reference's own
//!   spread `max |C^-1(u') - x|` over those `u'`, plus the
//!   angle's error (`8 EPS` from the normalisation, times `|dx / dtheta|` by central
//!   differences of the reference), plus the stopping rule `4 EPS (1 + |x|)`.
//! - `sample_visible_normal`: the slopes `t = R(phi) (x, y)` carry the two quantiles'
//!   tolerances (the view angle's error is that of the stretched view `wi`,
//!   `8 EPS k_in + 2 EPS` per component as in [`super::sampling`]), plus `|t|` times the
//!   azimuth's error `min(2 delta_wi / sin theta, 2)` (the azimuth of a view near the pole
//!   is the map's own conditioning) and `4 EPS`; `n = (-t, 1)` is then warped as for GGX:
//!   `K delta_n + 8 EPS` per component, `K = |(I - m m^T) M| / |M n|`.
//! - `sample_normal`: `n = (r cos phi, r sin phi, 1)`, `r = sqrt(-ln(1 - u1))` within
//!   `6 EPS r` (`ln_1p` 6 ulp and the division, halved by the square root, plus the square
//!   root's own), `sincos_turns` 3 `EPS` and a product: `K 12 r EPS + 8 EPS`.
//! - The pdfs: Beckmann `D` and `Lambda` by the rules of [`super::ndf`] (`tol_density`,
//!   `tol_lambda`, with `err_q = 8 + 8 sqrt(cond A)`), plus `2 EPS / (wo.m)` for the dot
//!   product, 8 for the normalisation of `wo` and 4 for the products and the division.

use super::sampling::{Case, cases, err_q, warp_conditioning, warp_of};
use super::{Check, EPS, Tol, ndf};
use crate::reference::math::Real;
use crate::reference::{
    Beckmann, DVec3, NdfSampling, Roughness, RoughnessMatrix, SplitMix64, sampling, v2, v3,
};

/// The f64 quantile of the crate (`f64::sampling::beckmann::visible_slope_quantile`).
fn quantile(c: f64, s: f64, u: f64) -> f64 {
    sampling::beckmann::visible_slope_quantile(c, s, u)
}

/// `K(t)` of the visible-slope CDF (`beckmann.wgsl`) in f64, and the magnitude of the terms
/// the shader forms it from: for `t <= 0` `K` itself (two positive terms), above the upper
/// tail `phi(t) = c - K(t)` and its terms' magnitude `(c erfc(t) + s exp(-t^2) / sqrt(pi)) / 2`.
fn k_terms(t: f64, c: f64, s: f64) -> (f64, f64) {
    let g = s * (-t * t).exp() / core::f64::consts::PI.sqrt();
    if t <= 0.0 {
        let k = 0.5 * (c * Real::erfc(-t) + g);
        (k, k)
    } else {
        (0.5 * (c * Real::erfc(t) - g), 0.5 * (c * Real::erfc(t) + g))
    }
}

/// The tolerance of the module docs on the quantile `x` at `(c, s)` (unit) and `u`, with the
/// angle known to within `dtheta`.
fn quantile_tol(c: f64, s: f64, u: f64, dtheta: f64) -> f64 {
    let x = quantile(c, s, u);
    let hi = if s > 0.0 { (c / s).min(9.0) } else { 9.0 };
    let ulps = |v: f64| v * v + 36.0;
    let q = |u: f64| quantile(c, s, u.min(1.0 - f64::EPSILON / 2.0));
    let spread = if u <= 0.5 {
        // K(x) = u K(hi): relative errors err_K at x and at hi.
        let delta = (2.0 * ulps(x).max(ulps(hi)) + 4.0) * EPS;
        (q(u * (1.0 + delta)) - x)
            .abs()
            .max((q(u * (1.0 - delta)) - x).abs())
    } else {
        // K(hi) - K(x) = (1 - u) K(hi): the difference's error is its terms' magnitudes
        // (times their ulp) over the difference itself.
        let (kx, mx) = k_terms(x, c, s);
        let (kh, mh) = k_terms(hi, c, s);
        let (r, mags) = if x > 0.0 {
            (kx - kh, ulps(x) * mx + ulps(hi) * mh)
        } else {
            // K(hi): c - phi(hi) above 0 (c and phi's terms), K itself at hi = 0.
            let k_hi = if hi > 0.0 { c - kh } else { kh };
            (k_hi - kx, ulps(x) * mx + 2.0 * ulps(hi) * (c + mh))
        };
        let v = 1.0 - u;
        let delta = if r > 0.0 { (mags / r + 4.0) * EPS } else { 1.0 };
        (q(1.0 - v * (1.0 + delta)) - x)
            .abs()
            .max((q(1.0 - v * (1.0 - delta)) - x).abs())
    };
    let th = s.atan2(c);
    let h = 1e-6;
    let (a, b) = (
        (th - h).max(0.0),
        (th + h).min(core::f64::consts::FRAC_PI_2),
    );
    let dxdt = if b > a {
        (quantile(b.cos(), b.sin(), u) - quantile(a.cos(), a.sin(), u)) / (b - a)
    } else {
        0.0
    };
    spread + dxdt.abs() * dtheta + 4.0 * EPS * (1.0 + x.abs())
}

/// The sampling cases with `u = 0` moved to `2^-24` (module docs).
fn beckmann_cases(n: usize) -> Vec<Case> {
    let mut cs = cases(n);
    for c in &mut cs {
        for u in &mut c.u {
            if *u == 0.0 {
                *u = 2f32.powi(-24);
            }
        }
    }
    cs
}

/// The bound on the sampled visible normal (module docs), per component.
fn visible_tol(c: &Case) -> f64 {
    sample_tol_of(&c.m, v3(c.wo), c.u)
}

/// `visible_tol` for the (f64) roughness `m`, the view `wo` and the uniform numbers `u` (as
/// the shader reads them; the oracle's GPU backend uses it too).
pub fn sample_tol_of(m: &RoughnessMatrix, wo: DVec3, u: [f32; 2]) -> f64 {
    let mm = warp_of(m);
    let wo = wo.normalize();
    let st = mm.transpose() * wo;
    let wi = st / st.length();
    let k_in = warp_conditioning(mm.transpose(), wo);
    let d_wi = 8.0 * EPS * k_in + 2.0 * EPS;
    let s = wi.x.hypot(wi.y);
    let (cphi, sphi) = if s > 0.0 {
        (wi.x / s, wi.y / s)
    } else {
        (1.0, 0.0)
    };
    let (u1, u2) = (f64::from(u[0]), f64::from(u[1]));
    let x = quantile(wi.z, s, u1);
    let y = quantile(1.0, 0.0, u2);
    let dx = quantile_tol(wi.z, s, u1, 2.0 * d_wi);
    let dy = quantile_tol(1.0, 0.0, u2, 0.0);
    let t = (cphi * x - sphi * y, sphi * x + cphi * y);
    let tl = t.0.hypot(t.1);
    let dphi = if s > 0.0 {
        (2.0 * d_wi / s).min(2.0)
    } else {
        0.0
    };
    let dt = dx + dy + tl * (dphi + 4.0 * EPS);
    let n = DVec3::new(-t.0, -t.1, 1.0);
    warp_conditioning(mm, n) * dt + 8.0 * EPS
}

/// `x = s^T A_c^-1 s` at the slope of the unit `m` and `ln k`, `k = 1 / (pi sqrt(det) m_z^4)`:
/// the exponent and the normalisation of the Beckmann density.
fn density_terms(c: &Case, m: DVec3) -> (f64, f64) {
    let (a11, a12, a22) = c.m.clamped_entries();
    let det = a11 * a22 - a12 * a12;
    let (sx, sy) = (-m.x / m.z, -m.y / m.z);
    let x = (a22 * sx * sx - 2.0 * a12 * sx * sy + a11 * sy * sy) / det;
    let ln_k = -((core::f64::consts::PI * c.m.sqrt_det()).ln() + 4.0 * m.z.ln());
    (x, ln_k)
}

/// The quantile check: cases `(c, s, u)` with their tolerances.
fn quantile_check() -> Check {
    let mut q = Check::new(
        "sampling::beckmann::visible_slope_quantile",
        "#import filtered_ndf::sampling::beckmann",
        "y(0u, beckmann::visible_slope_quantile(x(0u), x(1u), x(2u)));",
        3,
        1,
    )
    .tolerance("the reference's spread over u (1 +- (2 err_K + 4 EPS)), err_K = (x^2 + 36) EPS; |dx/dtheta| 8 EPS; 4 EPS (1 + |x|) for the stopping rule (absolute)");
    let mut rng = SplitMix64(0x6265_636b);
    let angles: Vec<f64> = (0..=30).map(|k| f64::from(k) * 3.0).collect();
    for deg in angles {
        let th = deg.to_radians();
        let (c32, s32) = if deg >= 90.0 {
            (0.0f32, 1.0f32)
        } else {
            (th.cos() as f32, th.sin() as f32)
        };
        let (c, s) = (f64::from(c32), f64::from(s32));
        let r = c.hypot(s);
        let (cn, sn) = (c / r, s / r);
        let mut us: Vec<f32> = vec![2f32.powi(-24), 1e-30, 0.99999994, 0.5];
        us.extend((0..60).map(|_| rng.uniform() as f32));
        for u in us {
            let uf = f64::from(u);
            let x = quantile(c, s, uf);
            q.case(
                vec![c32, s32, u],
                vec![x],
                vec![Tol::abs(quantile_tol(cn, sn, uf, 8.0 * EPS))],
            );
        }
    }
    q
}

/// The checks of `shaders/sampling/beckmann.wgsl`.
pub fn all() -> Vec<Check> {
    let cs = beckmann_cases(2000);
    let imports =
        "#import filtered_ndf::ndf::roughness::matrix\n#import filtered_ndf::sampling::beckmann";
    let pre = "let r = matrix::from_eigen(x2(0u), x2(2u));\nlet wo = x3(4u);\nlet u = x2(7u);\n";
    let mut sv = Check::new(
        "sampling::beckmann::sample_visible_normal",
        imports,
        &format!("{pre}y3(0u, beckmann::sample_visible_normal(r, wo, u));"),
        9,
        3,
    )
    .tolerance("K delta_t + 8 EPS absolute per component: the quantiles' tolerances at the stretched view, |t| times the azimuth's error, the warp's conditioning K (module docs, per case)");
    let mut sn = Check::new(
        "sampling::beckmann::sample_normal",
        imports,
        &format!("{pre}y3(0u, beckmann::sample_normal(r, u));"),
        9,
        3,
    )
    .tolerance("K 12 r EPS + 8 EPS absolute per component (r = sqrt(-ln(1 - u1)) 6 r EPS, sincos 3, the warp's conditioning K)");
    let mut pv = Check::new(
        "sampling::beckmann::visible_normal_pdf",
        imports,
        &format!(
            "{pre}let m = x3(9u);\ny(0u, beckmann::visible_normal_pdf(r, wo, m));\ny(1u, beckmann::normal_pdf(r, m));\ny(2u, beckmann::reflection_pdf_from_normal(r, wo, m));"
        ),
        12,
        3,
    )
    .tolerance("Beckmann D's (err_q + 3) x + 2x + 9 (+ 4 |ln k| past x = 80) plus Lambda's rule (checks::ndf), 2 EPS / (wo.m), 8 for the normalisation of wo, 4 ulp");

    for c in &cs {
        let bk = Beckmann::new(c.m);
        let wo = v3(c.wo);
        let s = bk.sample_visible_normal(wo, v2(c.u)).unwrap_or(DVec3::ZERO);
        sv.case(
            c.input(),
            vec![s.x, s.y, s.z],
            vec![Tol::abs(visible_tol(c)); 3],
        );

        let n = bk.sample_normal(v2(c.u));
        let u1 = f64::from(c.u[0]);
        let r = (-(1.0 - u1).ln()).sqrt();
        let phi = 2.0 * core::f64::consts::PI * f64::from(c.u[1]);
        let nstd = DVec3::new(r * phi.cos(), r * phi.sin(), 1.0);
        let k = warp_conditioning(warp_of(&c.m), nstd);
        sn.case(
            c.input(),
            vec![n.x, n.y, n.z],
            vec![Tol::abs(k * 12.0 * r * EPS + 8.0 * EPS); 3],
        );

        if s == DVec3::ZERO {
            continue;
        }
        let m32 = [s.x as f32, s.y as f32, s.z as f32];
        let m = v3(m32);
        let eq = err_q(c);
        let (x, ln_k) = density_terms(c, m);
        let t_d = ndf::tol_density(false, eq, x, ln_k);
        let q_w = c.m.quadratic(wo.truncate());
        let t_l = ndf::tol_lambda(false, eq, q_w, wo.z.abs());
        let wom = wo.normalize().dot(m);
        let base = t_d + t_l + 2.0 / wom.max(1e-30) + 8.0 + 4.0;
        let mut input = c.input();
        input.extend(m32);
        pv.case(
            input,
            vec![
                bk.visible_normal_pdf(wo, m),
                bk.normal_pdf(m),
                bk.reflection_pdf_from_normal(wo, m),
            ],
            vec![Tol::ulps(base), Tol::ulps(t_d + 2.0), Tol::ulps(base)],
        );
    }
    vec![quantile_check(), sv, sn, pv]
}
