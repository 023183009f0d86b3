//! `shaders/sampling/`: GGX visible-normal sampling and the pdfs, roughness matrix.
//!
//! Cases: rotated matrices `from_eigen(axis, alpha)` drawn as `strategies::matrix` draws
//! them (alpha log-uniform in `[1e-4, 2]`, anisotropy up to `1e3`), views from
//! `strategies::upper_hemisphere(89)`, `u` uniform (SplitMix64), plus `u` at the corners.
//!
//! Tolerances. A sample is a unit vector compared componentwise with an absolute tolerance
//! `K delta_n + 8 EPS`: `delta_n` bounds the error of the unit-roughness sample
//! `n = c + wi` (the driver-independent `sincos_turns`, 3 `EPS`; `z` 6 `EPS`; the cap's
//! `sin theta = sqrt(1 - z^2)`, whose error `|z| delta_z / sin theta` is the map's own
//! conditioning near the cap's poles; the stretched view `wi`, 8 `EPS` times the stretch's
//! conditioning) and `K = |(I - m m^T) M| / |M n|` (Frobenius norm) is the conditioning of
//! the final warp `m = M n / |M n|`, both computed per case in f64 from the reference
//! matrix. The pdfs follow the NDF rules (`err_q = 8 + 8 sqrt(cond A)` for `D` and
//! `Lambda`, see `checks::ndf`) plus `2 EPS / (wo.m)` for the dot product `wo.m`, and for
//! `reflection_pdf` the half vector's recomputation: the largest relative change of the
//! reference `D` when its half vector moves by up to `4 EPS / (wo.h)` (a closed-form bound,
//! `d_spread`); where that half vector
//! is within its error of the horizon (`h_z <= 16 EPS / (wo.h)`, e.g. `wi` near `-wo`, or a
//! sample at the rim of the cap), the `chi+(h_z)` factor is decided by rounding and any
//! value in `[0, reference]` is accepted.

use super::{Check, EPS, Tol, draw};
use crate::reference::{
    DVec3, Ggx, NdfSampling, Roughness, RoughnessMatrix, SplitMix64, matrix_from_eigen, sampling,
    strategies, v2, v3,
};
use glam::DMat3;

pub(crate) struct Case {
    pub(crate) axis: [f32; 2],
    pub(crate) alpha: [f32; 2],
    pub(crate) m: RoughnessMatrix,
    pub(crate) wo: [f32; 3],
    pub(crate) u: [f32; 2],
}

impl Case {
    pub(crate) fn input(&self) -> Vec<f32> {
        let mut v = self.axis.to_vec();
        v.extend(self.alpha);
        v.extend(self.wo);
        v.extend(self.u);
        v
    }
}

pub(crate) fn cases(n: usize) -> Vec<Case> {
    let forms = draw(
        (strategies::axis_aligned(), 0.0..core::f64::consts::PI),
        n,
        "sampling forms",
    );
    let wos = draw(strategies::upper_hemisphere(89.0), n, "sampling wo");
    let mut rng = SplitMix64(0x7361_6d70);
    let mut out = Vec::new();
    for (k, ((r, phi), wo)) in forms.into_iter().zip(wos).enumerate() {
        let axis = [phi.cos() as f32, phi.sin() as f32];
        let alpha = [r.alpha().x as f32, r.alpha().y as f32];
        let Some(m) = matrix_from_eigen(axis, alpha) else {
            continue;
        };
        let u = match k % 50 {
            0 => [0.0, 0.0],
            1 => [0.99999994, 0.99999994],
            2 => [0.5, 0.99999994],
            _ => [rng.uniform() as f32, rng.uniform() as f32],
        };
        out.push(Case {
            axis,
            alpha,
            m,
            wo: [wo.x as f32, wo.y as f32, wo.z as f32],
            u,
        });
    }
    out
}

/// `|(I - m m^T) M| / |M n|` (Frobenius): how a change of `n` moves `m = M n / |M n|`.
pub(crate) fn warp_conditioning(mm: DMat3, n: DVec3) -> f64 {
    let v = mm * n;
    let m = v / v.length();
    let p = DMat3::IDENTITY - DMat3::from_cols(m * m.x, m * m.y, m * m.z);
    let k = p * mm;
    let f =
        (k.x_axis.length_squared() + k.y_axis.length_squared() + k.z_axis.length_squared()).sqrt();
    f / v.length()
}

/// The module docs' bound on the sampled `m` (absolute, per component).
fn sample_tol(c: &Case) -> f64 {
    sample_tol_of(&c.m, v3(c.wo), c.u)
}

/// `sample_tol` for the (f64) roughness `m`, the view `wo` and the uniform numbers `u`
/// (as the shader reads them).
pub fn sample_tol_of(m: &RoughnessMatrix, wo: DVec3, u: [f32; 2]) -> f64 {
    let mm = warp_of(m);
    let wo = wo.normalize();
    let st = mm.transpose() * wo;
    let wi = st / st.length();
    // Conditioning of wi = normalize(M^T wo) in wo.
    let k_in = warp_conditioning(mm.transpose(), wo);
    let (u1, u2) = (f64::from(u[0]), f64::from(u[1]));
    let z = (1.0 - u2) * (1.0 + wi.z) - wi.z;
    let sin_t = (1.0 - z * z).max(0.0).sqrt();
    let dz = 6.0 * EPS + 8.0 * EPS * k_in;
    let d_sin =
        (z.abs() * dz / sin_t.max(1e-30) + 5.0 * EPS).min((2.0 * z.abs() * dz).sqrt() + 5.0 * EPS);
    let phi = 2.0 * core::f64::consts::PI * u1;
    let n = DVec3::new(sin_t * phi.cos(), sin_t * phi.sin(), z) + wi;
    let dn = 3.0 * EPS + d_sin + dz + 8.0 * EPS * k_in + 2.0 * EPS;
    warp_conditioning(mm, n) * dn + 8.0 * EPS
}

/// `M = [[l_xx, 0, 0], [l_yx, l_yy, 0], [0, 0, 1]]` of a reference matrix (f64), its `A_c`.
pub(crate) fn warp_of(m: &RoughnessMatrix) -> DMat3 {
    let (a11, a12, _) = m.clamped_entries();
    let l11 = a11.sqrt();
    DMat3::from_cols(
        DVec3::new(l11, a12 / l11, 0.0),
        DVec3::new(0.0, m.sqrt_det() / l11, 0.0),
        DVec3::Z,
    )
}

pub(crate) fn err_q(c: &Case) -> f64 {
    let (l1, l2) = (f64::from(c.alpha[0]).powi(2), f64::from(c.alpha[1]).powi(2));
    8.0 + 8.0 * (l1.max(l2) / l1.min(l2)).sqrt()
}

/// The checks of `shaders/sampling/`.
pub fn all() -> Vec<Check> {
    let cs = cases(2000);
    let imports = "#import filtered_ndf::ndf::roughness::matrix\n#import filtered_ndf::sampling";
    let pre = "let r = matrix::from_eigen(x2(0u), x2(2u));\nlet wo = x3(4u);\nlet u = x2(7u);\n";
    let mut checks = Vec::new();

    let mut sv = Check::new(
        "sampling::sample_visible_normal",
        imports,
        &format!("{pre}y3(0u, sampling::sample_visible_normal(r, wo, u));"),
        9,
        3,
    )
    .tolerance("K delta_n + 8 EPS absolute per component (module docs: the caps sampler's and the warps' conditioning, per case)");
    let mut sn = Check::new(
        "sampling::sample_normal",
        imports,
        &format!("{pre}y3(0u, sampling::sample_normal(r, u));"),
        9,
        3,
    )
    .tolerance("K 12 EPS + 8 EPS absolute per component (sincos 3, square roots 4.5, the warp's conditioning K)");
    let mut pv = Check::new(
        "sampling::visible_normal_pdf",
        imports,
        &format!(
            "{pre}let m = x3(9u);\ny(0u, sampling::visible_normal_pdf(r, wo, m));\ny(1u, sampling::normal_pdf(r, m));\ny(2u, sampling::reflection_pdf_from_normal(r, wo, m));"
        ),
        12,
        3,
    )
    .tolerance("D's 2 (err_q + 1) + 6 plus Lambda's 1.5 err_q + 10, 2 EPS / (wo.m), 8 for the normalisation of wo, 4 ulp");
    let mut pr = Check::new(
        "sampling::reflection_pdf",
        imports,
        &format!("{pre}let wi = x3(9u);\ny(0u, sampling::reflection_pdf(r, wo, wi));"),
        12,
        1,
    )
    .tolerance("reflection_pdf_from_normal's, plus the reference D's largest relative change under a move of the half vector by up to 4 EPS / (wo.h) (closed-form bound); [0, reference] where h_z <= 16 EPS / (wo.h) (chi+ decided by rounding)");

    // reflect(wo, m) = 2 (wo.m) m - wo of a view and the normal sampled for it: per
    // component the dot product (3 products and 2 sums of unit vectors, `1.5 EPS`) doubled and
    // scaled by `|m_i| <= 1` (3 EPS), the product (1 EPS) and the difference (1.5 EPS): within
    // `6 EPS` absolute of the unit length.
    let mut rf = Check::new(
        "sampling::reflect",
        imports,
        &format!("{pre}y3(0u, sampling::reflect(wo, x3(9u)));"),
        12,
        3,
    )
    .tolerance("6 EPS absolute per component (the dot product 1.5, doubled and scaled 3, product 1, difference 1.5)");
    for c in &cs {
        let ggx = Ggx::new(c.m);
        let wo = v3(c.wo);
        let s = ggx
            .sample_visible_normal(wo, v2(c.u))
            .unwrap_or(DVec3::ZERO);
        sv.case(
            c.input(),
            vec![s.x, s.y, s.z],
            vec![Tol::abs(sample_tol(c)); 3],
        );

        let n = ggx.sample_normal(v2(c.u));
        let (u1, _) = (f64::from(c.u[0]), 0.0);
        let phi = 2.0 * core::f64::consts::PI * f64::from(c.u[1]);
        let nstd = DVec3::new(
            u1.sqrt() * phi.cos(),
            u1.sqrt() * phi.sin(),
            (1.0 - u1).sqrt(),
        );
        let k = warp_conditioning(warp_of(&c.m), nstd);
        sn.case(
            c.input(),
            vec![n.x, n.y, n.z],
            vec![Tol::abs(k * 12.0 * EPS + 8.0 * EPS); 3],
        );

        if s == DVec3::ZERO {
            continue;
        }
        let m32 = [s.x as f32, s.y as f32, s.z as f32];
        let m = v3(m32);
        let eq = err_q(c);
        let wom = wo.normalize().dot(m);
        let base = 2.0 * (eq + 1.0) + 6.0 + 1.5 * eq + 10.0 + 2.0 / wom.max(1e-30) + 8.0 + 4.0;
        let mut input = c.input();
        input.extend(m32);
        pv.case(
            input,
            vec![
                ggx.visible_normal_pdf(wo, m),
                ggx.normal_pdf(m),
                ggx.reflection_pdf_from_normal(wo, m),
            ],
            vec![
                Tol::ulps(base),
                Tol::ulps(2.0 * (eq + 1.0) + 8.0),
                Tol::ulps(base),
            ],
        );
        let mut input = c.input();
        input.extend(m32);
        let r = sampling::reflect(wo, m);
        rf.case(input, vec![r.x, r.y, r.z], vec![Tol::of_scale(6.0, 1.0); 3]);
        let wi = sampling::reflect(wo.normalize(), m);
        let wi32 = [wi.x as f32, wi.y as f32, wi.z as f32];
        let wi = v3(wi32);
        let h = (wo.normalize() + wi.normalize()).normalize();
        // The reference's largest relative change when its half vector moves by up to the
        // recomputation error `delta = 4 EPS / (wo.h)` in any direction (`d_spread`).
        let woh = wo.normalize().dot(h);
        let delta = 4.0 * EPS / woh.max(1e-30);
        let spread = d_spread(&c.m, h, delta);
        let t = base + spread / EPS;
        // The recomputed half vector's components carry about 4 EPS / (wo.h): where its `h_z`
        // is within that of the horizon, rounding decides the `chi+(h_z)` factor, and 0 is
        // as right as the reference.
        let reference = ggx.reflection_pdf(wo, wi);
        let tol = if h.z <= 16.0 * EPS / woh.max(1e-30) {
            Tol {
                rel: 0.0,
                abs: reference + super::TINY,
                scale: reference.max(super::TINY),
            }
        } else {
            Tol::ulps(t)
        };
        let mut input = c.input();
        input.extend(wi32);
        pr.case(input, vec![reference], vec![tol]);
    }
    checks.extend([sv, sn, pv, pr, rf]);
    checks
}

/// The largest relative change of the GGX `D` of roughness matrix `A` when the unit half
/// vector `h` moves by up to `delta` in any direction, bounded in closed form. With
/// `s = -h_xy / h_z`, `h_z^4 (1 + s^T A^-1 s)^2 = (1 + Q)^2`, `Q = h_xy^T B h_xy`,
/// `B = A^-1 - I`, so `D` is proportional to `(1 + Q)^-2`. A move by `delta` in the tangent
/// plane, renormalised, moves `h_xy` by `e`, `|e| <= delta' = delta + delta^2 / 2`, and `Q` by
/// `2 e^T B h_xy + e^T B e`, at most `2 delta' |B h_xy| + delta'^2 |B|` in magnitude (`|B|`
/// the spectral norm); `1 + Q >= h_z^2` bounds it below as well. The direction towards the lobe's peak counts: sampling a few
/// directions missed it (a `D` 2.7 times the reference's, within this bound, on an NVIDIA
/// H200, at roughness `1e-4` and `2e-6`).
fn d_spread(m: &RoughnessMatrix, h: DVec3, delta: f64) -> f64 {
    let b = m.inverse() - glam::DMat2::IDENTITY;
    let hxy = glam::DVec2::new(h.x, h.y);
    let q = hxy.dot(b * hxy);
    let (b11, b12, b22) = (b.x_axis.x, b.x_axis.y, b.y_axis.y);
    let norm = 0.5 * (b11 + b22).abs() + (0.25 * (b11 - b22).powi(2) + b12 * b12).sqrt();
    let dp = delta + 0.5 * delta * delta;
    let dq = 2.0 * dp * (b * hxy).length() + dp * dp * norm;
    // `1 + Q = h_z^2 + h_xy^T A^-1 h_xy >= h_z^2` after the move too.
    let floor = (h.z - dp).max(0.0).powi(2);
    let (lo, hi) = ((1.0 + q - dq).max(floor).max(1e-300), 1.0 + q + dq);
    let ratio = |x: f64| ((1.0 + q) / x).powi(2);
    (ratio(lo) - 1.0).max(1.0 - ratio(hi))
}
