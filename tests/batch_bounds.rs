//! The vectorised batch kernels against the `f64` scalar path, on identical inputs (every
//! parameter and vector rounded to the batch precision first, as `tests/ndf_precision.rs`),
//! within each kernel's stated bound (`batch` module docs):
//!
//! - GGX `D`, `Lambda`, `G2`: bit for bit with the scalar path of the batch precision
//!   (`tests/batch.rs`); against `f64`: the scalar `f32` bound, `8 eps` (`D`, `Lambda`) and
//!   `12 eps` for `G2` (two `Lambda`s, two sums and a reciprocal).
//! - Beckmann `D`: `(11 + 4 x) eps` relative (`x` the exponent): the scalar `f32` bound
//!   `(8 + 4 x) eps` plus the polynomial exponential's `2.5e-7 <= 2.1 eps` and the rounding of
//!   `p k`. In `f64` (against itself): `1.5e-14 + (2 + x) eps` (file docs of
//!   `tests/batch.rs`). Below `F::MIN_POSITIVE`: absolute `F::MIN_POSITIVE`.
//! - Beckmann `Lambda`: absolute `L (1 + Lambda)` of the shared `erfc` fit (`L = 2.1e-7` in
//!   `f32`, `1.9e-8` in `f64`), plus `(13 + 7 a^2) eps Lambda`: the scalar `f32` path's
//!   `(8 + 4 a^2) eps` and the lane's `a = |w_z| / sqrt(q)` rounded twice in `F`, which
//!   `Lambda ~ exp(-a^2) / a^3` amplifies by `2 a^2 + 3`.
//! - Beckmann `G2 = 1 / (1 + Lambda_i + Lambda_o)`: relative `2 L + 3 eps` plus the amplified
//!   terms of each `Lambda` over `1 + Lambda_i + Lambda_o`.
//! - The box filter `d_rect`: against the scalar path of the batch precision (whose integral
//!   is computed in `f64` in both builds: the `f64` scalar path of the same case analysis),
//!   `|batch - scalar| <= (A + 2 + 3) eps_64 M + 4 eps_64 |D|` plus, in `f32`, one `f32` ulp
//!   (the two `f64` values round apart at most once), `A = 3` the polynomial `atan2`'s bound
//!   (`lanes.rs`), `2` libm's `atan` with its division and sum, `M` the four-edge terms'
//!   magnitude scaled as their sum (`common/rect_edges.rs`; `filter::rect::edges_by`'s docs
//!   derive the other roundings); so bit for bit off the closed form, except in `f32` on the
//!   elements of the `f32` lanes (`batch::rect_lane`: both sides within half their distance
//!   from the poles), which are checked against the `f64` scalar path within their derived
//!   bound instead ([`lane_bound`]).
//! - The deferred presets (`deferred_filter`): bit for bit with the scalar path of the batch
//!   precision for `exponent = 1` (`tests/batch.rs`), so against `f64` the scalar `f32`
//!   path's error, derived step by step (in `eps` of the batch precision, relative): the
//!   norm `R_n` (`|dn_u|^2 + |dn_v|^2`: six products and five sums of non-negative terms,
//!   `3`; the larger of two dot products `1.5`; the Gram matrix's larger eigenvalue: entry
//!   errors of `3 u tr`, a 1-Lipschitz eigenvalue with `tr <= 2 lambda_max`, and its own
//!   mean, root and sum, `6`; the largest component `0`); the kernel `R_k = exponent R_n + 2`
//!   (the scale constant rounded to `F` and the product) plus the power's (`2.5 + 1.5
//!   |exponent|` in `f32`: the lane power's `(5 + 3 |e|) u`, `u = eps / 2`, computed in
//!   `f32`; `1.6e-14 / eps + 3 |y| + 1` in `f64`); the
//!   material's value `R_v` (`alpha^2`, `sqrt(alpha)`: `1`; `alpha`: `0`; `alpha^2 / (1 -
//!   alpha^2)`: `1 + 1 / (1 - alpha^2)`, the subtraction's conditioning, so `alpha <= 0.9`
//!   here); the sum or max and the clamps and saturate (1-Lipschitz) `R = max(R_v, R_k) + 1`;
//!   `to_alpha`: `R / 2 + 1` (`sqrt`), `R` (identity), `2 R + 1` (square), `R / 2 + 2`
//!   (`sqrt(v / (1 + v))`); plus `1` for the rounded `ALPHA_MIN` floor.

use filtered_ndf::f64 as d;
use filtered_ndf::testing::rng::SplitMix64 as Rng;

#[path = "common/rect_edges.rs"]
mod rect_edges;

/// Unit directions over the hemisphere and a little below, a share near grazing.
fn directions(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let t = if rng.uniform() < 0.2 {
                90.0 - rng.log_uniform(1e-4, 1.0)
            } else {
                95.0 * rng.uniform()
            };
            let t = t.to_radians();
            let p = std::f64::consts::TAU * rng.uniform();
            [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
        })
        .collect()
}

/// Micronormals around a lobe of width `alpha`: slopes from `1e-3` to `30` widths.
fn micronormals(n: usize, seed: u64, alpha: f64) -> Vec<[f64; 3]> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let k = rng.log_uniform(1e-3, 30.0) * alpha;
            let (sx, sy) = (rng.normal() * k, rng.normal() * k);
            let l = (1.0 + sx * sx + sy * sy).sqrt();
            [-sx / l, -sy / l, 1.0 / l]
        })
        .collect()
}

/// Half an `f32` ulp, `2^-24`.
const U: f64 = 1.0 / 16_777_216.0;

/// The `f32` box-filter lanes' bound (`batch::rect_lane`'s module docs) for the element
/// `(alpha, h, s)` where the lanes may take it (both sides of the normalised rectangle within
/// half their distance from the integrand's poles, with a margin of `1e-3` for the `f32`
/// classification): `(D, bound)`, `D` the `f64` scalar path's value and the bound
/// `78 u |D|` (derived there: node coordinates `26 u`, the rule's arithmetic `41 u`, forming
/// `D` `10 u`, truncation `1.04 u`) plus the inputs' term `sum_x |x dD/dx| e_x` over
/// `x = h_x, h_y` (`e = 4 u`: `u_c`, `v_c` in `f32`) and the half extents (`e = 2 u`), the
/// derivatives by central differences of the `f64` path (relative step `1e-5`: their error,
/// about `1e-13 / 1e-5` of `D`, is far below the term). `None` elsewhere.
fn lane_bound(alpha: (f64, f64), h: [f64; 3], s: (f64, f64)) -> Option<(f64, f64)> {
    let aa = d::AxisAligned::new(alpha.0, alpha.1).unwrap();
    let dr = |h: [f64; 3], s: (f64, f64)| {
        d::filter::rect::d_rect(aa, d::Vec3::from_array(h), d::Vec2::new(s.0, s.1))
    };
    if h[2] <= 0.0 || h.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let (uc, vc) = (-h[0] / h[2] / alpha.0, -h[1] / h[2] / alpha.1);
    let clean = |x: f64| if x.is_nan() { 0.0 } else { x.abs() };
    let (hu, hv) = (clean(s.0) / alpha.0, clean(s.1) / alpha.1);
    let du = (uc.abs() - hu).max(0.0);
    let dv = (vc.abs() - hv).max(0.0);
    let (lu2, lv2) = (1.0 + uc * uc + dv * dv, 1.0 + vc * vc + du * du);
    let lim = 0.5 * (1.0 + 1e-3);
    if hu * hu >= lim * lim * lu2 || hv * hv >= lim * lim * lv2 {
        return None;
    }
    let d0 = dr(h, s);
    let step = 1e-5;
    let fd = |f: &dyn Fn(f64) -> f64| ((f(1.0 + step) - f(1.0 - step)) / (2.0 * step)).abs();
    let input = 4.0 * U * fd(&|k| dr([h[0] * k, h[1], h[2]], s))
        + 4.0 * U * fd(&|k| dr([h[0], h[1] * k, h[2]], s))
        + 2.0 * U * fd(&|k| dr(h, (s.0 * k, s.1)))
        + 2.0 * U * fd(&|k| dr(h, (s.0, s.1 * k)));
    Some((d0, 78.0 * U * d0 + input))
}

macro_rules! suite {
    ($modname:ident, $prec:ident, $t:ty) => {
        mod $modname {
            use super::*;
            use filtered_ndf::$prec::{AxisAligned, Isotropic, RoughnessMatrix, batch};
            use filtered_ndf::f64::{Ndf as _, Roughness as _};

            const N: usize = 3000;
            const EPS: f64 = <$t>::EPSILON as f64;
            const WIDE: bool = <$t>::MANTISSA_DIGITS > 24;
            const MIN: f64 = <$t>::MIN_POSITIVE as f64;
            const L: f64 = if WIDE { 1.9e-8 } else { 2.1e-7 };

            struct Cols {
                x: Vec<$t>,
                y: Vec<$t>,
                z: Vec<$t>,
            }

            impl Cols {
                fn new(v: &[[f64; 3]]) -> Self {
                    Self {
                        x: v.iter().map(|v| v[0] as $t).collect(),
                        y: v.iter().map(|v| v[1] as $t).collect(),
                        z: v.iter().map(|v| v[2] as $t).collect(),
                    }
                }
                fn at(&self, i: usize) -> glam::DVec3 {
                    glam::DVec3::new(self.x[i] as f64, self.y[i] as f64, self.z[i] as f64)
                }
                fn soa(&self) -> batch::Vec3s<'_> {
                    batch::Vec3s::new(&self.x, &self.y, &self.z)
                }
            }

            /// The three forms in the batch precision, with their `f64` twins from the same
            /// rounded parameters.
            fn forms(alpha: f64) -> Vec<(&'static str, Forms)> {
                let a = alpha as $t;
                let b = (alpha * 0.3) as $t;
                let (a2, b2) = (a * a, b * b);
                let m12 = 0.4 * a * b;
                vec![
                    (
                        "isotropic",
                        Forms::Iso(
                            Isotropic::new(a).unwrap(),
                            d::Isotropic::new(a as f64).unwrap(),
                        ),
                    ),
                    (
                        "axis-aligned",
                        Forms::Aa(
                            AxisAligned::new(a, b).unwrap(),
                            d::AxisAligned::new(a as f64, b as f64).unwrap(),
                        ),
                    ),
                    (
                        "matrix",
                        Forms::Mat(
                            RoughnessMatrix::new(a2, m12, b2).unwrap(),
                            d::RoughnessMatrix::new(a2 as f64, m12 as f64, b2 as f64).unwrap(),
                        ),
                    ),
                ]
            }

            enum Forms {
                Iso(Isotropic, d::Isotropic),
                Aa(AxisAligned, d::AxisAligned),
                Mat(RoughnessMatrix, d::RoughnessMatrix),
            }

            /// Runs `f` with the form pair of `forms` as generic roughness values.
            macro_rules! with_form {
                ($f:expr, |$r:ident, $r64:ident| $body:expr) => {
                    match $f {
                        Forms::Iso($r, $r64) => $body,
                        Forms::Aa($r, $r64) => $body,
                        Forms::Mat($r, $r64) => $body,
                    }
                };
            }

            /// The `f64` Cholesky factor `(l11, l21, l22)` of the form `name` of `forms(alpha)`
            /// (no determinant clamp at these determinants), and the condition number `kappa`
            /// of the warp `diag(L, 1)`.
            fn warp_of(alpha: f64, name: &str) -> ((f64, f64, f64), f64) {
                let (a, b) = ((alpha as $t) as f64, ((alpha * 0.3) as $t) as f64);
                let (l11, l21, l22) = match name {
                    "isotropic" => (a, 0.0, a),
                    "axis-aligned" => (a, 0.0, b),
                    _ => {
                        let (a, b) = (alpha as $t, (alpha * 0.3) as $t);
                        let (a2, m12, b2) = ((a * a) as f64, (0.4 * a * b) as f64, (b * b) as f64);
                        let l11 = a2.sqrt();
                        let l21 = m12 / l11;
                        (l11, l21, (b2 - l21 * l21).sqrt())
                    }
                };
                // Singular values of [[l11, 0], [l21, l22]].
                let (t, det) = (l11 * l11 + l21 * l21 + l22 * l22, (l11 * l22).abs());
                let d = (t * t - 4.0 * det * det).max(0.0).sqrt();
                let (s_max, s_min) = (((t + d) / 2.0).sqrt(), (2.0 * det * det / (t + d)).sqrt());
                ((l11, l21, l22), s_max.max(1.0) / s_min.min(1.0))
            }

            /// `normalize(L^-1 m_xy, m_z)`: a micronormal pulled back to the unit-roughness
            /// space by the exact inverse of the `f64` factor.
            fn pull_back((l11, l21, l22): (f64, f64, f64), m: glam::DVec3) -> glam::DVec3 {
                let y = (m.y - l21 / l11 * m.x) / l22;
                glam::DVec3::new(m.x / l11, y, m.z).normalize()
            }

            /// Uniform pairs with the unit square's edges and out-of-range values mixed in.
            fn uniforms(seed: u64) -> (Vec<$t>, Vec<$t>) {
                let mut rng = Rng(seed);
                let mut u: Vec<$t> = (0..2 * N).map(|_| rng.uniform() as $t).collect();
                for (k, v) in [0.0, 1.0, -0.5, 2.0, <$t>::NAN, 1e-30, 0.25, 0.5, 0.75, 1e-7, 1.0 - <$t>::EPSILON]
                    .into_iter()
                    .enumerate()
                {
                    u[7 * k] = v;
                    u[N + 11 * k + 3] = v;
                    u[13 * k + 5] = v;
                    u[N + 13 * k + 5] = 1.0 - v;
                }
                let u2 = u.split_off(N);
                (u, u2)
            }

            /// The `D(m) m_z` samplers against the `f64` scalar samplers on the same inputs,
            /// compared in the unit-roughness space (angle between the pulled-back samples;
            /// angles of unit vectors = absolute errors), the bound derived step by step in
            /// units `E` of a precision, for the batch and, with `E = eps_64`, for the `f64`
            /// reference itself (the tolerance is the sum: both against the exact sample):
            ///
            /// - the azimuth's `(cos, sin)`: `S E` (`S = 8` in `f32`, `9` in `f64`, as for the
            ///   visible-normal sampler above: `sincos_2pi`'s `2 E` or `2e-15`, or
            ///   libm's of the rounded `phi = 2 pi u2`), times `r` in the standard normal's
            ///   `xy`, plus the products' rounding `E r`;
            /// - GGX: `r = sqrt(u1)` (`E`), `n_z = sqrt(1 - u1)` (`1 - u1` rounds by `E / 2`
            ///   relative only for `u1 < 1/2`, the root halves it and rounds: `E`): `|n| = 1`,
            ///   so the angle of `n` is within `(S + 3) E`;
            /// - Beckmann: `l = ln(1 - u1)`: `1 - u1` rounded in `F` (`E / 2` relative, so
            ///   `E / 2` absolute in `l`) and the logarithm (lane: `3 E` in `f32`, `4 E` in
            ///   `f64`; libm: an ulp): `dl = E / 2 + c E |l|`, `c = 3`, `4`, `1`; `r = sqrt(-l)`: `|sqrt(p) -
            ///   sqrt(q)| <= |p - q| / sqrt(q)` and `<= sqrt(|p - q|)`, so `dr = min(dl / r,
            ///   sqrt(dl)) + E r / 2` (the root's rounding); `n = (r cos, r sin, 1)` turns by
            ///   `dr / (1 + r^2)` and by `(S + 1) E r / sqrt(1 + r^2)`;
            /// - `m = normalize(L n)` pulled back by the exact `L^-1`: `9 kappa E + E` (as for
            ///   the visible-normal sampler above).
            #[test]
            fn sample_normal_against_f64() {
                use filtered_ndf::f64::NdfSampling as _;
                let (u1, u2) = uniforms(0x5C);
                let (mut ox, mut oy, mut oz) = (vec![0.0 as $t; N], vec![0.0 as $t; N], vec![0.0 as $t; N]);
                let s_batch = if WIDE { 9.0 } else { 8.0 };
                // The lane logarithm's bound in units of `E` (`log.rs`).
                let c_ln = if WIDE { 4.0 } else { 3.0 };
                let mut worst = [0.0f64; 2];
                for alpha in [0.01f64, 0.2, 1.0, 2.0] {
                    for (name, f) in forms(alpha) {
                        let (l, kappa) = warp_of(alpha, name);
                        let cu = |x: f64| if x >= 0.0 { x.min(1.0 - EPS / 2.0) } else { 0.0 };
                        let warp = |e: f64| 9.0 * kappa * e + e;
                        for beckmann in [false, true] {
                            with_form!(f, |r, r64| {
                                let n = if beckmann {
                                    batch::beckmann_sample_normal(&r, &u1, &u2, &mut ox, &mut oy, &mut oz)
                                } else {
                                    batch::ggx_sample_normal(&r, &u1, &u2, &mut ox, &mut oy, &mut oz)
                                };
                                assert_eq!(n, N);
                                for i in 0..N {
                                    // The batch precision's clamp (`u = 1` clamps to `1 - E / 2`, not to
                                    // the `f64` sampler's `1 - eps_64 / 2`), which the `f64` sampler's
                                    // own clamp then leaves as it is: the same sampled point.
                                    let uu = glam::DVec2::new(cu(u1[i] as f64), cu(u2[i] as f64));
                                    let got = glam::DVec3::new(ox[i] as f64, oy[i] as f64, oz[i] as f64);
                                    assert!(got.z > 0.0 && (got.length() - 1.0).abs() <= 4.0 * EPS, "[{i}] {got}");
                                    let c1 = uu.x;
                                    let (want, bound): (glam::DVec3, &dyn Fn(f64, f64, f64) -> f64) = if beckmann {
                                        // (Not `.max(0.0)`: `-0.0` may survive it, and `rr = -0` made the bound `-inf`.)
                                        let lq = -(1.0 - c1).ln();
                                        let lq = if lq > 0.0 { lq } else { 0.0 };
                                        let rr = lq.sqrt();
                                        (
                                            d::Beckmann::new(r64).sample_normal(uu),
                                            &move |e: f64, s: f64, c: f64| {
                                                let dl = e / 2.0 + c * e * lq;
                                                let dr = (dl / rr).min(dl.sqrt()) + e * rr / 2.0;
                                                dr / (1.0 + lq) + (s + 1.0) * e * rr / (1.0 + lq).sqrt() + warp(e)
                                            },
                                        )
                                    } else {
                                        (
                                            d::Ggx::new(r64).sample_normal(uu),
                                            &move |e: f64, s: f64, _: f64| (s + 3.0) * e + warp(e),
                                        )
                                    };
                                    let tol = bound(EPS, s_batch, c_ln) + bound(f64::EPSILON, 8.0, 1.0);
                                    let angle = (pull_back(l, got) - pull_back(l, want)).length();
                                    worst[beckmann as usize] = worst[beckmann as usize].max(angle / tol);
                                    assert!(
                                        angle <= tol,
                                        "{name} {alpha} beckmann {beckmann} [{i}] u {uu}: {got} vs {want} ({angle:e} > {tol:e})"
                                    );
                                }
                            });
                        }
                    }
                }
                println!("sample_normal: worst GGX {:.3}, Beckmann {:.3} of the bound", worst[0], worst[1]);
            }

            /// The pdfs against the `f64` scalar pdfs on the same rounded inputs (relative, in
            /// `eps` of the batch precision; GGX's batch pdfs are the scalar ones bit for bit,
            /// `tests/batch.rs`, so the scalar path's error), derived step by step (first
            /// order `t`, the products of `1 + e_i` within `t + t^2`):
            ///
            /// - `D(m)`: GGX `8`; Beckmann `11 + 4 x` (`f32`) or `1.5e-14 / eps + 2 + x`
            ///   (`f64`), `x` the exponent (the `D` bounds above);
            /// - `1 + Lambda(wo)`: `Lambda`'s absolute error over `1 + Lambda`, GGX
            ///   `8 Lambda / (1 + Lambda)`, Beckmann `L + (13 + 7 a^2) Lambda / (1 + Lambda)`
            ///   (the `Lambda` bounds above), plus the sum's rounding `1`;
            /// - the visible pdf `(wo.m) D / (wo_z (1 + Lambda))`: `wo.m` in `F` (three
            ///   products, two sums: `3 sum|wo_k m_k| / |wo.m|`) and three roundings;
            /// - the reflection pdf `D / (4 o_z (1 + Lambda(o)))`, `o = wo / |wo|`: `o_z`
            ///   within `3` (the squared length `1.5`, its root `0.5 + 0.75`, the quotient
            ///   `0.5`, rounded up), the direction of `o` (each component's quotient rounds
            ///   alone: `1`) moves `a = |o_z| / sqrt(q)` of Beckmann by `2` relative, which
            ///   `Lambda` amplifies by `2 a^2 + 3` (`(4 a^2 + 6) Lambda / (1 + Lambda)`), and
            ///   GGX's `1 + Lambda` by at most `2` (`t = q / o_z^2` moves by `4`, `1 + Lambda =
            ///   (1 + sqrt(1 + t)) / 2` halves it at most); two roundings (`4 o_z` is exact).
            ///
            /// - the `D(m) m_z` pdf: `D`'s bound plus the product's rounding `1`.
            ///
            /// Where Beckmann's `D` is flushed below `F::MIN_POSITIVE`, the pdf's absolute
            /// error adds `F::MIN_POSITIVE` times its factor `wo.m / (wo_z (1 + Lambda))`
            /// (`m_z` for the `D(m) m_z` pdf).
            /// Where the `f64` pdf is `0` (below the horizon, back-facing) the batch gives `0`.
            #[test]
            fn pdfs_against_f64() {
                use filtered_ndf::f64::NdfSampling as _;
                let wo = Cols::new(&directions(N, 0x9D));
                let mut worst = [0.0f64; 4];
                for (k, alpha) in [1e-3, 0.05, 0.4, 1.5].into_iter().enumerate() {
                    let m = Cols::new(&micronormals(N, 0x9E + k as u64, alpha));
                    let mut out = vec![0.0 as $t; N];
                    for (name, f) in forms(alpha) {
                        with_form!(f, |r, r64| {
                            for (j, what) in ["ggx visible", "beckmann visible", "ggx reflection", "beckmann reflection"].into_iter().enumerate() {
                                let (beckmann, reflection) = (j % 2 == 1, j >= 2);
                                let n = match j {
                                    0 => batch::ggx_visible_normal_pdf(&r, wo.soa(), m.soa(), &mut out),
                                    1 => batch::beckmann_visible_normal_pdf(&r, wo.soa(), m.soa(), &mut out),
                                    2 => batch::ggx_reflection_pdf_from_normal(&r, wo.soa(), m.soa(), &mut out),
                                    _ => batch::beckmann_reflection_pdf_from_normal(&r, wo.soa(), m.soa(), &mut out),
                                };
                                assert_eq!(n, N);
                                for i in 0..N {
                                    let (w, mm) = (wo.at(i), m.at(i));
                                    let o = w.normalize();
                                    let (want, lam, dtol, lam_tol) = if beckmann {
                                        let b = d::Beckmann::new(r64);
                                        let want = if reflection { b.reflection_pdf_from_normal(w, mm) } else { b.visible_normal_pdf(w, mm) };
                                        let x = r64.inv_quadratic(glam::DVec2::new(mm.x, mm.y)) / (mm.z * mm.z);
                                        let dtol = if WIDE { 1.5e-14 / EPS + 2.0 + x } else { 11.0 + 4.0 * x };
                                        let a = a_of(&r64, o);
                                        let lam = b.lambda(o);
                                        let amp = 13.0 + 7.0 * a * a + if reflection { 4.0 * a * a + 6.0 } else { 0.0 };
                                        (want, lam, dtol, L / EPS + amp * lam / (1.0 + lam))
                                    } else {
                                        let g = d::Ggx::new(r64);
                                        let want = if reflection { g.reflection_pdf_from_normal(w, mm) } else { g.visible_normal_pdf(w, mm) };
                                        let lam = g.lambda(o);
                                        (want, lam, 8.0, 8.0 * lam / (1.0 + lam) + if reflection { 2.0 } else { 0.0 })
                                    };
                                    let got = out[i] as f64;
                                    assert!(got >= 0.0 && got.is_finite(), "{what} {name} [{i}]: {got}");
                                    if want == 0.0 {
                                        assert_eq!(got, 0.0, "{what} {name} {alpha} [{i}]");
                                        continue;
                                    }
                                    let rest = if reflection {
                                        3.0 + 2.0
                                    } else {
                                        let s = (w.x * mm.x).abs() + (w.y * mm.y).abs() + (w.z * mm.z).abs();
                                        3.0 * s / w.dot(mm).abs() + 3.0
                                    };
                                    let t = (dtol + lam_tol + 1.0 + rest) * EPS;
                                    let factor = if reflection { 0.25 / o.z } else { w.dot(mm) / w.z } / (1.0 + lam);
                                    let flush = if beckmann { MIN * factor } else { 0.0 };
                                    let tol = (t + t * t) * want + flush;
                                    let err = (got - want).abs();
                                    if got != 0.0 {
                                        // The relative part (a flushed element is within `flush`).
                                        worst[j] = worst[j].max(err / (tol - flush));
                                    }
                                    assert!(
                                        err <= tol,
                                        "{what} {name} {alpha} [{i}] wo {w} m {mm}: {got} vs {want} ({:.2} eps)",
                                        err / want / EPS
                                    );
                                }
                            }
                        })
                    }
                }
                // The `D(m) m_z` pdfs: `D`'s bound plus the product's rounding (`m_z` is an
                // input, exact), relative; Beckmann's flush: absolute `F::MIN_POSITIVE m_z`.
                for (k, alpha) in [1e-3, 0.05, 0.4, 1.5].into_iter().enumerate() {
                    let m = Cols::new(&micronormals(N, 0xA0 + k as u64, alpha));
                    let mut out = vec![0.0 as $t; N];
                    for (name, f) in forms(alpha) {
                        with_form!(f, |r, r64| {
                            for beckmann in [false, true] {
                                if beckmann {
                                    batch::beckmann_normal_pdf(&r, &m.x, &m.y, &m.z, &mut out);
                                } else {
                                    batch::ggx_normal_pdf(&r, &m.x, &m.y, &m.z, &mut out);
                                }
                                for i in 0..N {
                                    let mm = m.at(i);
                                    let (want, dtol) = if beckmann {
                                        let x = r64.inv_quadratic(glam::DVec2::new(mm.x, mm.y)) / (mm.z * mm.z);
                                        let dtol = if WIDE { 1.5e-14 / EPS + 2.0 + x } else { 11.0 + 4.0 * x };
                                        (d::Beckmann::new(r64).normal_pdf(mm), dtol)
                                    } else {
                                        (d::Ggx::new(r64).normal_pdf(mm), 8.0)
                                    };
                                    let got = out[i] as f64;
                                    let t = (dtol + 1.0) * EPS;
                                    let flush = if beckmann { MIN * mm.z } else { 0.0 };
                                    let err = (got - want).abs();
                                    assert!(
                                        err <= (t + t * t) * want + flush,
                                        "normal pdf beckmann {beckmann} {name} {alpha} [{i}]: {got} vs {want}"
                                    );
                                }
                            }
                        })
                    }
                }
                println!(
                    "pdfs, worst of the relative bound (unflushed): GGX visible {:.3}, Beckmann visible {:.3}, GGX reflection {:.3}, Beckmann reflection {:.3}",
                    worst[0], worst[1], worst[2], worst[3]
                );
            }

            /// `batch::d_rect` against `filter::rect::d_rect` of the same precision (the
            /// integral in `f64` in both builds) within the bound of the file docs, derived:
            /// the closed-form lane and the scalar path share every operation but the four
            /// angles (`edges_by`); an angle with relative error `d` moves its edge term `e` by
            /// `d |e|`, so the two angles' errors (`3` and `2 eps_64`) give
            /// `5 eps_64 sum |e|`; the products by the angles and the three sums of each path
            /// `1.5 eps_64 sum |e|` each (`3` in all); the area, the division, `k` and
            /// `1 / h_z^4` round each path's result four times (`2 eps_64 |D|` each); `M` is
            /// `sum |e|` scaled as `D` (`common/rect_edges.rs`, by libm: its own rounding is a
            /// few `eps_64` of `M`, covered by the factor `1 + 1e-12`). In `f32` the two `f64`
            /// values then round to `f32` at most one ulp apart. Inputs: realistic (half
            /// vectors near the lobe, footprints from `1e-3` to `1e3` lobe widths, so a good
            /// share with long sides: the four-edge form, the 1D closed form and the far field)
            /// and adversarial (grazing and back-facing `h`, lobes to `1e-4`, half extents
            /// `0`, negative, `1e-30`, `1e30`, NaN, infinite). Never NaN.
            #[test]
            fn d_rect_against_scalar_f64() {
                use filtered_ndf::$prec::{Vec2, Vec3, filter::rect};
                const SPECIAL: [f64; 9] =
                    [0.0, -0.0, -0.3, 1e-30, 1e30, f64::NAN, f64::INFINITY, -1e-3, 5.0];
                let mut rng = Rng(0x2EC7_B0D5);
                let (mut differ, mut long, mut worst) = (0usize, 0usize, 0.0f64);
                let (mut gain, mut worst_rel) = (0.0f64, 0.0f64);
                let (mut lane_only, mut worst_lane, mut worst_lane_u) = (0usize, 0.0f64, 0.0f64);
                for (ax, ay) in [(1e-4, 3e-4), (0.01, 0.01), (0.2, 0.05), (0.7, 1.0)] {
                    let (ax, ay) = (ax as $t as f64, ay as $t as f64);
                    let aa = AxisAligned::new(ax as $t, ay as $t).unwrap();
                    let mut dirs = micronormals(N, rng.next_u64(), ax.max(ay));
                    dirs.extend(directions(N / 2, rng.next_u64()));
                    let n = dirs.len();
                    let c = Cols::new(&dirs);
                    let mut half = |a: f64| -> Vec<$t> {
                        (0..n)
                            .map(|_| {
                                if rng.uniform() < 0.1 {
                                    SPECIAL[(rng.uniform() * SPECIAL.len() as f64) as usize] as $t
                                } else {
                                    (a * rng.log_uniform(1e-3, 1e3)) as $t
                                }
                            })
                            .collect()
                    };
                    let (hx, hy) = (half(ax), half(ay));
                    let mut out = vec![0.0 as $t; n];
                    assert_eq!(batch::d_rect(&aa, &c.x, &c.y, &c.z, &hx, &hy, &mut out), n);
                    for i in 0..n {
                        let (g, hv) = (out[i], Vec3::new(c.x[i], c.y[i], c.z[i]));
                        let w = rect::d_rect(aa, hv, Vec2::new(hx[i], hy[i]));
                        assert!(!g.is_nan(), "[{i}] NaN");
                        let u = rect_edges::unit_rect(
                            (ax, ay),
                            c.at(i).to_array(),
                            (hx[i] as f64, hy[i] as f64),
                        );
                        let m = u.as_ref().map_or(0.0, |u| u.edge_magnitude());
                        long += usize::from(u.is_some_and(|u| u.long()));
                        let (g64, w64) = (g as f64, w as f64);
                        let e64 = f64::EPSILON;
                        let mut bound = ((3.0 + 2.0 + 3.0) * e64 * m + 4.0 * e64 * w64.abs())
                            * (1.0 + 1e-12);
                        if !WIDE {
                            bound += EPS * g64.abs().max(w64.abs());
                        }
                        let err = (g64 - w64).abs();
                        // In `f32` an element the `f32` lanes took (both sides within half
                        // their distance from the poles) is within their bound of the `f64`
                        // scalar path instead (`lane_bound`).
                        let lane = if WIDE {
                            None
                        } else {
                            let (ex, ey) = (hx[i] as f64, hy[i] as f64);
                            lane_bound((ax, ay), c.at(i).to_array(), (ex, ey))
                        };
                        let by_lane = lane.is_some_and(|(d64, b)| (g64 - d64).abs() <= b);
                        if let Some((d64, b)) = lane.filter(|_| by_lane) {
                            if g.to_bits() != w.to_bits() {
                                lane_only += 1;
                                worst_lane = worst_lane.max((g64 - d64).abs() / b);
                                worst_lane_u = worst_lane_u.max((g64 - d64).abs() / d64 / U);
                            }
                        // A non-finite magnitude (a rectangle beyond the range of f64 terms)
                        // bounds nothing: those elements must agree bit for bit.
                        } else if m.is_finite() {
                            assert!(err <= bound, "[{i}] h {hv:?} half ({}, {}): batch {g:e} vs scalar {w:e}, bound {bound:e}, lane {lane:?}", hx[i], hy[i]);
                        } else {
                            assert_eq!(g.to_bits(), w.to_bits(), "[{i}]");
                        }
                        if g.to_bits() != w.to_bits() && !by_lane {
                            differ += 1;
                            worst = worst.max(err / bound);
                            worst_rel = worst_rel.max(err / w64.abs());
                            gain = gain.max(m / w64.abs());
                        }
                    }
                }
                println!(
                    "d_rect: {long} elements with a long side, {differ} differ from the \
                     scalar path (largest M / D {gain:.3e}), worst {worst:.3} of the bound, \
                     {worst_rel:.3e} relative"
                );
                assert!(long > N, "{long} long");
                if !WIDE {
                    println!(
                        "d_rect, f32 lanes: {lane_only} elements off the scalar path, \
                         worst {worst_lane:.3} of it ({worst_lane_u:.2} u relative)"
                    );
                    assert!(lane_only > N / 4, "{lane_only} elements took the f32 lanes");
                }
            }

            /// GGX visible-normal sampling against the `f64` scalar sampler, on the same rounded
            /// inputs. The sample is compared in the unit-roughness space (the angle between
            /// `normalize(L^-1 m_xy, m_z)` of both, `L` the `f64` Cholesky factor): the
            /// position of the sample within the lobe. The bound, in units `E` of the batch
            /// precision, `kappa` the condition number of `diag(L, 1)`, derived step by step
            /// (angles of unit vectors = absolute errors):
            ///
            /// - `L`'s entries: relative `3 E` (square roots, a division and a difference
            ///   with cancellation below `1 / (1 - 0.4^2)` for these forms); a map by `L` or
            ///   `L^T` with those entries and its rounded sums (`1.5 E` per component) moves a
            ///   direction by at most `kappa (3 + 1.5) sqrt(3) E < 8 kappa E`;
            /// - the view `wi = normalize(L^T normalize(wo))`: `d_wi = (8.5 kappa + 1) E`;
            /// - the cap height `z = (1 - u2)(1 + wi_z) - wi_z`: `d_z = 2 d_wi + 3 E`;
            /// - the cap point `(sin t cos phi, sin t sin phi, z)`: `sin t = sqrt(1 - z^2)`
            ///   errs by `(d_z + E) / sin t + E`; the azimuth's `(cos, sin)` by `S`:
            ///   `sincos_2pi`'s (lane: `2 E` in `f32`, `2e-15` in `f64`), or libm's of `phi =
            ///   2 pi u1` rounded in the batch precision (`2 pi E`) plus its ulp (flagged
            ///   elements): `S = 8 E` in `f32`, `9 E` (`2e-15 / eps_64`) in `f64`;
            ///   `d_c = (d_z + E) / sin t + d_z + S + E`;
            /// - `n = c + wi` (length `|n|` in `(0, 2]`, small where the cap point nears
            ///   `-wi`): angle `(d_c + d_wi + E) / |n|`;
            /// - `m = normalize(L n)`, pulled back by the exact `L^-1`: `9 kappa E`.
            ///
            /// So `B(E, S) = (d_c + d_wi + E) / |n| + 9 kappa E + E`, for the batch and,
            /// with `E = eps_64`, `S = 8 E`, for the `f64` reference itself; the test takes
            /// `sin t` and `|n|` from the `f64` steps. Elements where the `f64` sampler
            /// returns `None` must give `(0, 0, 0)`.
            #[test]
            fn ggx_sample_visible_normal_against_f64() {
                use filtered_ndf::f64::NdfSampling as _;
                let dirs = directions(N, 0x5A);
                let wo = Cols::new(&dirs);
                let mut rng = Rng(0x5B);
                let mut u: Vec<$t> = (0..2 * N).map(|_| rng.uniform() as $t).collect();
                // Adversarial uniforms: the unit square's edges and out of range.
                for (k, v) in [0.0, 1.0, -0.5, 2.0, <$t>::NAN, 1e-30, 0.25, 0.5, 0.75]
                    .into_iter()
                    .enumerate()
                {
                    u[7 * k] = v;
                    u[N + 11 * k + 3] = v;
                }
                let (u1, u2) = u.split_at(N);
                let (mut ox, mut oy, mut oz) = (vec![0.0 as $t; N], vec![0.0 as $t; N], vec![0.0 as $t; N]);
                let s_batch = if WIDE { 9.0 } else { 8.0 };
                let mut worst = 0.0f64;
                for alpha in [0.01f64, 0.2, 1.0, 2.0] {
                    for (name, f) in forms(alpha) {
                        let ((l11, l21, l22), kappa) = warp_of(alpha, name);
                        with_form!(f, |r, r64| {
                            let n = batch::ggx_sample_visible_normal(
                                &r, wo.soa(), u1, u2, &mut ox, &mut oy, &mut oz,
                            );
                            assert_eq!(n, N);
                            let ggx = d::Ggx::new(r64);
                            for i in 0..N {
                                let w = wo.at(i);
                                let uu = glam::DVec2::new(u1[i] as f64, u2[i] as f64);
                                let got = glam::DVec3::new(ox[i] as f64, oy[i] as f64, oz[i] as f64);
                                let Some(want) = ggx.sample_visible_normal(w, uu) else {
                                    assert_eq!(got, glam::DVec3::ZERO, "{name} {alpha} [{i}]");
                                    continue;
                                };
                                assert!(got.z > 0.0 && w.dot(got) > 0.0, "{name} {alpha} [{i}]: {got}");
                                // The f64 steps' conditioning: sin t and |n|.
                                let o = w.normalize();
                                let wi = glam::DVec3::new(l11 * o.x + l21 * o.y, l22 * o.y, o.z).normalize();
                                let cu = |x: f64| if x >= 0.0 { x.min(1.0 - EPS / 2.0) } else { 0.0 };
                                let (c1, c2) = (cu(uu.x), cu(uu.y));
                                let z = (1.0 - c2) * (1.0 + wi.z) - wi.z;
                                let sin_t = (1.0 - z * z).max(0.0).sqrt();
                                let phi = std::f64::consts::TAU * c1;
                                let nn = glam::DVec3::new(sin_t * phi.cos(), sin_t * phi.sin(), z) + wi;
                                let bound = |e: f64, s: f64| {
                                    let d_wi = (8.5 * kappa + 1.0) * e;
                                    let d_z = 2.0 * d_wi + 3.0 * e;
                                    let d_c = (d_z + e) / sin_t + d_z + s * e + e;
                                    (d_c + d_wi + e) / nn.length() + 9.0 * kappa * e + e
                                };
                                let tol = bound(EPS, s_batch) + bound(f64::EPSILON, 8.0);
                                let (gb, wb) = (pull_back((l11, l21, l22), got), pull_back((l11, l21, l22), want));
                                let angle = (gb - wb).length();
                                worst = worst.max(angle / tol);
                                assert!(
                                    angle <= tol,
                                    "{name} {alpha} [{i}] wo {w} u {uu}: {got} vs {want} ({angle:e} > {tol:e})"
                                );
                            }
                        });
                    }
                }
                println!("ggx_sample_visible_normal: worst {worst:.3} of the bound");
            }

            /// Beckmann's visible-slope CDF in `f64` with libm (the scalar sampler's `K`,
            /// Heitz 2014 eq. 80): `C(x) = K(x) / K(hi)`, `hi = min(cot theta, x_max)`, and
            /// the density `p(x) = K'(x) / K(hi)`, for the view `(c, s)`.
            fn visible_cdf(x: f64, c: f64, s: f64, x_max: f64) -> (f64, f64) {
                const INV_SQRT_PI: f64 = 0.564_189_583_547_756_3;
                let k = |x: f64| {
                    let e = (-x * x).exp();
                    (0.5 * c * libm::erfc(-x) + 0.5 * s * INV_SQRT_PI * e, INV_SQRT_PI * e * (c - s * x))
                };
                let hi = if s > 0.0 { (c / s).min(x_max) } else { x_max };
                let norm = k(hi).0;
                let (kx, dk) = k(x.min(hi));
                (kx / norm, dk.max(0.0) / norm)
            }

            /// The largest visible-slope density over `[a, b]`: at the ends or at the mode
            /// `(c - sqrt(c^2 + 2 s^2)) / (2 s)` of `(c - s x) exp(-x^2)`.
            fn density_max(a: f64, b: f64, c: f64, s: f64, x_max: f64) -> f64 {
                let mode = if s > 0.0 { (c - (c * c + 2.0 * s * s).sqrt()) / (2.0 * s) } else { 0.0 };
                let mut p = visible_cdf(a, c, s, x_max).1.max(visible_cdf(b, c, s, x_max).1);
                if mode > a && mode < b {
                    p = p.max(visible_cdf(mode, c, s, x_max).1);
                }
                p
            }

            /// The Beckmann visible-normal sampler against the `f64` scalar sampler's
            /// visible-slope CDF, in `u`: each sample is pulled back to the unit-roughness
            /// space by the exact `f64` warp, its slope turned into the `f64` view's frame,
            /// `(x, y)`, and `C_theta(x)`, `C_0(y)` (libm) must be within `tol` of the clamped
            /// `u1`, `u2`, where (`E` the batch precision's epsilon)
            ///
            /// - the quantile: the exact one of a `u'` within `A u` of `u`, `A = 8.5 eps_64 +
            ///   d(x) + d(hi)`, `d(x) = 1.5e-14 + (x^2 / 2 + 66) eps_64` (`batch::quantile`),
            ///   plus the reference `C`'s own error `(x^2 / 2 + 4) eps_64` at `x` and `hi`,
            ///   plus the mass beyond the batch precision's bracket `C(-X_MAX)` (`X_MAX = 9`
            ///   in `f32`);
            /// - the view `wi` in `F`: within `d_wi = (8.5 kappa + 1) E` of the `f64` view (as
            ///   for GGX above), so `theta` within `d_wi` (the test evaluates `C` at `theta
            ///   +/- d_wi` and takes the largest change), and the azimuth within `d_wi / s`
            ///   (`+ 2 eps_64`: the lane's `sqrt(wx^2 + wy^2)` for `hypot`), which turns the
            ///   slope `t` by up to `|t| d_wi / s` (at most `2 |t|`);
            /// - after the quantiles: `(-t_x, -t_y)` rounded to `F` (`E |t|`), the warp and
            ///   normalisation in `F` and the exact pull-back (`9 kappa E + E` in angle, as
            ///   above), which moves the slope of a unit vector by up to `(1 + |t|^2)` times
            ///   the angle;
            ///
            /// so the slope moves by `dt` and the `u` of each component by the largest density
            /// over `[x - dt, x + dt]` times `dt`. The same check with `E = eps_64` on the
            /// `f64` scalar sampler's own samples (its quantile's `A = 8 eps_64` plus libm's
            /// errors) validates the check. Elements where the `f64` sampler returns `None`
            /// must give `(0, 0, 0)`.
            #[test]
            fn beckmann_sample_visible_normal_against_f64() {
                use filtered_ndf::f64::NdfSampling as _;
                let x_max_batch = if WIDE { 26.0 } else { 9.0 };
                let dirs = directions(N, 0x5D);
                let wo = Cols::new(&dirs);
                let (u1, u2) = uniforms(0x5E);
                let (mut ox, mut oy, mut oz) = (vec![0.0 as $t; N], vec![0.0 as $t; N], vec![0.0 as $t; N]);
                let cu = |x: f64| if x >= 0.0 { x.min(1.0 - EPS / 2.0) } else { 0.0 };
                let mut worst = [0.0f64; 2];
                for alpha in [0.01f64, 0.2, 1.0, 2.0] {
                    for (name, f) in forms(alpha) {
                        let (l, kappa) = warp_of(alpha, name);
                        let (l11, l21, l22) = l;
                        with_form!(f, |r, r64| {
                            let n = batch::beckmann_sample_visible_normal(
                                &r, wo.soa(), &u1, &u2, &mut ox, &mut oy, &mut oz,
                            );
                            assert_eq!(n, N);
                            let beckmann = d::Beckmann::new(r64);
                            for i in 0..N {
                                let w = wo.at(i);
                                let (c1, c2) = (cu(u1[i] as f64), cu(u2[i] as f64));
                                let got = glam::DVec3::new(ox[i] as f64, oy[i] as f64, oz[i] as f64);
                                let Some(want) = beckmann.sample_visible_normal(w, glam::DVec2::new(c1, c2)) else {
                                    assert_eq!(got, glam::DVec3::ZERO, "{name} {alpha} [{i}]");
                                    continue;
                                };
                                assert!(
                                    got.z > 0.0 && w.dot(got) > 0.0 && (got.length() - 1.0).abs() <= 4.0 * EPS,
                                    "{name} {alpha} [{i}]: {got}"
                                );
                                // The f64 view and its frame.
                                let o = w.normalize();
                                let wi = glam::DVec3::new(l11 * o.x + l21 * o.y, l22 * o.y, o.z).normalize();
                                let (c, s) = (wi.z, wi.x.hypot(wi.y));
                                let (cp, sp) = if s > 0.0 { (wi.x / s, wi.y / s) } else { (1.0, 0.0) };
                                for (k, m, e, x_max, a_quant) in [
                                    (0usize, got, EPS, x_max_batch, None),
                                    (1, want, f64::EPSILON, 26.0, Some(8.0 * f64::EPSILON)),
                                ] {
                                    let nb = pull_back(l, m);
                                    let (tx, ty) = (-nb.x / nb.z, -nb.y / nb.z);
                                    let t = tx.hypot(ty);
                                    let (x, y) = (cp * tx + sp * ty, -sp * tx + cp * ty);
                                    let d_wi = (8.5 * kappa + 1.0) * e;
                                    let turn = if s > 0.0 { (d_wi / s + 2.0 * f64::EPSILON).min(2.0) } else { 2.0 };
                                    let dt = t * turn + e * t + (9.0 * kappa * e + e) * (1.0 + t * t);
                                    let lane_err = |x: f64| 1.5e-14 + (0.5 * x * x + 66.0) * f64::EPSILON;
                                    let ref_err = |x: f64| (0.5 * x * x + 4.0) * f64::EPSILON;
                                    let (tail, tail_y) = (visible_cdf(-x_max, c, s, 26.0).0, visible_cdf(-x_max, 1.0, 0.0, 26.0).0);
                                    // x: the view angle moves by d_wi.
                                    let theta = s.atan2(c);
                                    let (cx, _) = visible_cdf(x, c, s, 26.0);
                                    // `u = 0`: the bracket's bottom, `C(-X_MAX)` (the tail terms below).
                                    let mut dc_theta = 0.0f64;
                                    for tt in [theta - d_wi, theta + d_wi] {
                                        let tt = tt.clamp(0.0, std::f64::consts::FRAC_PI_2);
                                        dc_theta = dc_theta.max((visible_cdf(x, tt.cos(), tt.sin(), 26.0).0 - cx).abs());
                                    }
                                    let hi = if s > 0.0 { (c / s).min(x_max) } else { x_max };
                                    let ax = a_quant.unwrap_or(8.5 * f64::EPSILON + lane_err(x) + lane_err(hi));
                                    let tol_x = (ax + ref_err(x) + ref_err(hi)) * c1
                                        + dc_theta
                                        + density_max(x - dt, x + dt, c, s, 26.0) * dt
                                        + if c1 == 0.0 { tail } else { 0.0 }
                                        + 4.0 * f64::MIN_POSITIVE;
                                    let ay = a_quant.unwrap_or(8.5 * f64::EPSILON + lane_err(y) + lane_err(x_max));
                                    let (cy, _) = visible_cdf(y, 1.0, 0.0, 26.0);
                                    let tol_y = (ay + ref_err(y) + ref_err(26.0)) * c2
                                        + density_max(y - dt, y + dt, 1.0, 0.0, 26.0) * dt
                                        + if c2 == 0.0 { tail_y } else { 0.0 }
                                        + 4.0 * f64::MIN_POSITIVE;
                                    // The scalar solve's other stop (also the batch's, for the
                                    // elements its lane flags): a bracket of width `1e-13 (1 + |x|)`.
                                    let wx = 1e-13 * (1.0 + x.abs());
                                    let wy = 1e-13 * (1.0 + y.abs());
                                    let tol_x = tol_x + density_max(x - wx - dt, x + wx + dt, c, s, 26.0) * wx;
                                    let tol_y = tol_y + density_max(y - wy - dt, y + wy + dt, 1.0, 0.0, 26.0) * wy;
                                    let (ex, ey) = ((cx - c1).abs(), (cy - c2).abs());
                                    // (`u = 0` sits at its tail term.)
                                    if c1 > 0.0 && c2 > 0.0 {
                                        worst[k] = worst[k].max(ex / tol_x).max(ey / tol_y);
                                    }
                                    assert!(
                                        ex <= tol_x && ey <= tol_y,
                                        "{name} {alpha} [{i}] {} wo {w} u ({c1:e}, {c2:e}): m {m} (x, y) = ({x}, {y}): \
                                         C(x) {cx:e} ({ex:e} vs {tol_x:e}), C(y) {cy:e} ({ey:e} vs {tol_y:e})",
                                        ["batch", "f64"][k]
                                    );
                                }
                            }
                        });
                    }
                }
                println!(
                    "beckmann_sample_visible_normal: worst {:.3} of the bound (the f64 sampler: {:.3})",
                    worst[0], worst[1]
                );
            }

            /// `a = |w_z| / sqrt(q)` of Beckmann's `Lambda` (in `f64`).
            /// A batch Beckmann `D` (`got`) against the `f64` `D` of `r64` at `w`: below
            /// `F::MIN_POSITIVE` absolutely, else relative within `tol(x)` in `f32` (`x` the
            /// exponent) and `1.5e-14 + (2 + x) eps` in `f64`. Returns the error's share of
            /// the bound.
            fn beckmann_against_f64<R: d::Roughness>(
                r64: R,
                w: glam::DVec3,
                got: f64,
                tol: impl Fn(f64) -> f64,
                what: &str,
            ) -> f64 {
                let want = d::Beckmann::new(r64).d(w);
                let x = r64.inv_quadratic(glam::DVec2::new(w.x, w.y)) / (w.z * w.z);
                assert!(got >= 0.0 && !got.is_nan(), "{what}: {got}");
                if want < MIN {
                    assert!((got - want).abs() <= MIN, "{what}: {got} vs {want}");
                    return 0.0;
                }
                let tol = if WIDE { 1.5e-14 + (2.0 + x) * EPS } else { tol(x) };
                let e = (got - want).abs() / want;
                assert!(e <= tol, "{what}: {got} vs {want} (x {x})");
                e / tol
            }

            fn a_of<R: d::Roughness>(r: &R, w: glam::DVec3) -> f64 {
                w.z.abs() / r.quadratic(glam::DVec2::new(w.x, w.y)).sqrt()
            }

            #[test]
            fn d_against_f64() {
                let mut worst = [0.0f64; 2];
                for (k, alpha) in [1e-3, 0.05, 0.4, 1.5].into_iter().enumerate() {
                    let m = Cols::new(&micronormals(N, 0xD0 + k as u64, alpha));
                    let mut out = vec![0.0 as $t; N];
                    for (name, f) in forms(alpha) {
                        with_form!(f, |r, r64| {
                            batch::ggx_d(&r, &m.x, &m.y, &m.z, &mut out);
                            for i in 0..N {
                                let want = d::Ggx::new(r64).d(m.at(i));
                                let got = out[i] as f64;
                                if want < MIN {
                                    assert!((got - want).abs() <= MIN);
                                    continue;
                                }
                                let e = (got - want).abs() / want / EPS;
                                worst[0] = worst[0].max(e / 8.0);
                                assert!(e <= 8.0, "ggx {name} {alpha} [{i}]: {got} vs {want}");
                            }
                            batch::beckmann_d(&r, &m.x, &m.y, &m.z, &mut out);
                            for i in 0..N {
                                let share = beckmann_against_f64(
                                    r64,
                                    m.at(i),
                                    out[i] as f64,
                                    |x| (11.0 + 4.0 * x) * EPS,
                                    &format!("beckmann {name} {alpha} [{i}]"),
                                );
                                worst[1] = worst[1].max(share);
                            }
                        })
                    }
                }
                println!("D: worst GGX {:.3}, Beckmann {:.3} of the bound", worst[0], worst[1]);
            }

            /// Filtered Beckmann (`batch::beckmann_d_filtered`) and TK19 GGX
            /// (`batch::ggx_d_filtered`, the same first lane's matrix, `x` and `n`; its bound
            /// in the loop) against `f64`, on footprints
            /// from a twentieth of the lobe to twenty lobe widths, smooth lobes included
            /// (`alpha = 0.01`: elongated filtered lobes whose correlation leaves the `f32`
            /// lane's domain, `rho^2 > 3/4`, for the second, counted). Each element is the
            /// first lane's or the second's (or the scalar route's), so it must meet one of
            /// their bounds:
            ///
            /// - the first lane (`f32`: the narrow lane, `A'` in `f32` arithmetic) against the
            ///   `f64` pipeline (`ClampRules::filter_gaussian` of the `f64` build on the same
            ///   inputs): its entries within `delta = 26 u sqrt(A'_ii A'_jj)`
            ///   (`Narrow::entries`), which moves `x` by at most
            ///   `2 delta x / (1 - |rho|)` and `ln n` by `delta / (1 - |rho|)` (first order;
            ///   `rho` the correlation of `A'`), plus the narrow `x` (`30.7 u`) and `n`
            ///   (`16 u`), the exponential `E` and the result's rounding: `E + (x (15.35 + 26 /
            ///   (1 - |rho|)) + 8.5 + 13 / (1 - |rho|)) eps`;
            /// - the second lane (the scalar route's matrix, bit for bit) against the `f64` `D`
            ///   of that matrix: `E + (16 x + 10) eps` as before (in `f64`, where the first lane
            ///   is the scalar route's matrix too: `1.5e-14 + (2 + x) eps`).
            ///
            /// Most elements must meet the first (the first lane's share of the bench's inputs).
            #[test]
            fn d_filtered_against_f64() {
                use filtered_ndf::$prec::{ClampRules, Footprint, Vec2};
                let mut rng = Rng(0xF1D);
                let (mut worst, mut correlated, mut total, mut first) =
                    (0.0f64, 0usize, 0usize, 0usize);
                let (mut worst_ggx, mut first_ggx) = (0.0f64, 0usize);
                for (k, alpha) in [0.01, 0.05, 0.3].into_iter().enumerate() {
                    let m = Cols::new(&micronormals(N, 0xF0 + k as u64, 3.0 * alpha));
                    let mut fp = [vec![0.0 as $t; N], vec![0.0; N], vec![0.0; N], vec![0.0; N]];
                    for i in 0..N {
                        let ext = (alpha * rng.log_uniform(0.05, 20.0)).min(1.0);
                        let e2 = ext * rng.log_uniform(0.1, 1.0);
                        let (p1, p2) = (
                            std::f64::consts::TAU * rng.uniform(),
                            std::f64::consts::TAU * rng.uniform(),
                        );
                        fp[0][i] = (ext * p1.cos()) as $t;
                        fp[1][i] = (ext * p1.sin()) as $t;
                        fp[2][i] = (e2 * p2.cos()) as $t;
                        fp[3][i] = (e2 * p2.sin()) as $t;
                    }
                    let soa = batch::Footprints {
                        dh_u_x: &fp[0],
                        dh_u_y: &fp[1],
                        dh_v_x: &fp[2],
                        dh_v_y: &fp[3],
                    };
                    let r = AxisAligned::new(alpha as $t, (1.5 * alpha) as $t).unwrap();
                    // The `f64` pipeline's lobe: the same (rounded) entries.
                    let (r11, _, r22) = RoughnessMatrix::from(r).entries();
                    let r64 = d::RoughnessMatrix::new(r11 as f64, 0.0, r22 as f64).unwrap();
                    for (rules, rules64) in [
                        (ClampRules::default(), d::ClampRules::default()),
                        (ClampRules::NONE, d::ClampRules::NONE),
                    ] {
                        let mut out = vec![0.0 as $t; N];
                        batch::beckmann_d_filtered(&r, &rules, 0.5, &m.x, &m.y, &m.z, soa, &mut out);
                        let mut out_ggx = vec![0.0 as $t; N];
                        batch::ggx_d_filtered(&r, &rules, 0.5, &m.x, &m.y, &m.z, soa, &mut out_ggx);
                        for i in 0..N {
                            let f = Footprint::from_slope_derivatives(
                                Vec2::new(fp[0][i], fp[1][i]),
                                Vec2::new(fp[2][i], fp[3][i]),
                            );
                            let a = rules.filter_gaussian(r, f, 0.5);
                            if a.clamped_entries() != a.entries() {
                                continue; // the determinant clamp: not on the lanes' path
                            }
                            let (a11, a12, a22) = a.entries();
                            let (a11, a12, a22) = (a11 as f64, a12 as f64, a22 as f64);
                            total += 1;
                            correlated += usize::from(4.0 * a12 * a12 > 3.0 * a11 * a22);
                            let got = out[i] as f64;
                            let w = m.at(i);
                            // The first lane's bound, against the `f64` pipeline.
                            let f64p = d::Footprint::from_slope_derivatives(
                                glam::DVec2::new(fp[0][i] as f64, fp[1][i] as f64),
                                glam::DVec2::new(fp[2][i] as f64, fp[3][i] as f64),
                            );
                            let a64 = rules64.filter_gaussian(r64, f64p, 0.5);
                            let want = d::Beckmann::new(a64).d(w);
                            let (b11, b12, b22) = a64.entries();
                            let k = 1.0 / (1.0 - b12.abs() / (b11 * b22).sqrt());
                            let x = a64.inv_quadratic(glam::DVec2::new(w.x, w.y)) / (w.z * w.z);
                            let tol = if WIDE {
                                1.5e-14 + (2.0 + x) * EPS
                            } else {
                                2.5e-7
                                    + (x * (15.35 + 26.0 * k) + 8.5 + 13.0 * k) * EPS
                            };
                            // TK19 GGX: its first lane in `f32` the same narrow matrix and
                            // narrow `x`, `n`, then `D = n / (pi (1 + x)^2)`: `x`'s relative
                            // error enters `D` times `2 x / (1 + x)` (instead of Beckmann's
                            // `x`), `n`'s once, the sum, square, `1 / pi` (rounded), product and
                            // division `6 u = 3 eps`: `(2 x / (1 + x)) (15.35 + 26 k) + 11 +
                            // 13 k` eps. Else the second lane's (the scalar route's matrix,
                            // bit for bit): the scalar `f32` GGX `D`'s `8 eps` against the `f64`
                            // `D` of that matrix.
                            let got_ggx = out_ggx[i] as f64;
                            let want_ggx = d::Ggx::new(a64).d(w);
                            let tol_ggx = if WIDE {
                                8.0 * EPS
                            } else {
                                (2.0 * x / (1.0 + x) * (15.35 + 26.0 * k) + 11.0 + 13.0 * k) * EPS
                            };
                            let err_ggx = (got_ggx - want_ggx).abs();
                            assert!(got_ggx >= 0.0, "ggx [{i}]: {got_ggx}");
                            if want_ggx < MIN && err_ggx <= MIN {
                                first_ggx += 1;
                            } else if err_ggx <= tol_ggx * want_ggx {
                                first_ggx += 1;
                                worst_ggx = worst_ggx.max(err_ggx / want_ggx / tol_ggx);
                            } else {
                                let m64 = d::RoughnessMatrix::new(a11, a12, a22).unwrap();
                                let w64 = d::Ggx::new(m64).d(w);
                                assert!(
                                    (got_ggx - w64).abs() <= 8.0 * EPS * w64
                                        || (w64 < MIN && (got_ggx - w64).abs() <= MIN),
                                    "filtered ggx, alpha {alpha} [{i}]: {got_ggx} vs f64 \
                                     {want_ggx} (x {x}, k {k}), scalar route's f64 {w64}"
                                );
                            }
                            let lane_ok = if want < MIN {
                                (got - want).abs() <= MIN
                            } else {
                                (got - want).abs() <= tol * want
                            };
                            if lane_ok {
                                first += 1;
                                if want >= MIN {
                                    worst = worst.max((got - want).abs() / want / tol);
                                }
                                continue;
                            }
                            // Else the second lane's (or the scalar route's).
                            beckmann_against_f64(
                                d::RoughnessMatrix::new(a11, a12, a22).unwrap(),
                                w,
                                got,
                                |x| 2.5e-7 + (16.0 * x + 10.0) * EPS,
                                &format!("filtered, alpha {alpha} [{i}]"),
                            );
                        }
                    }
                }
                assert!(total > 4 * N, "{total}");
                assert!(correlated > total / 100, "{correlated} of {total} correlated");
                assert!(first > total * 9 / 10, "{first} of {total} within the first bound");
                assert!(
                    first_ggx > total * 9 / 10,
                    "{first_ggx} of {total} GGX within the first bound"
                );
                println!(
                    "filtered D: {first} of {total} within the first lane's bound, worst \
                     {worst:.3} of it; {correlated} correlated; GGX {first_ggx}, worst \
                     {worst_ggx:.3}"
                );
            }

            #[test]
            fn lambda_and_g2_against_f64() {
                let (o, i) = (
                    Cols::new(&directions(N, 0x1A)),
                    Cols::new(&directions(N, 0x1B)),
                );
                let mut worst = [0.0f64; 4];
                for (k, alpha) in [1e-3, 0.05, 0.4, 1.5].into_iter().enumerate() {
                    let m = Cols::new(&micronormals(N, 0x3C + k as u64, alpha));
                    let mut out = vec![0.0 as $t; N];
                    for (name, f) in forms(alpha) {
                        with_form!(f, |r, r64| {
                            batch::ggx_lambda(&r, &o.x, &o.y, &o.z, &mut out);
                            for j in 0..N {
                                let want = d::Ggx::new(r64).lambda(o.at(j));
                                let got = out[j] as f64;
                                let ok = if want.is_infinite() {
                                    got == want
                                } else {
                                    let e = (got - want).abs() / want.max(MIN) / EPS;
                                    worst[0] = worst[0].max(e / 8.0);
                                    e <= 8.0
                                };
                                assert!(ok, "ggx lambda {name} {alpha} [{j}]: {got} vs {want}");
                            }
                            batch::ggx_g2(&r, i.soa(), o.soa(), m.soa(), &mut out);
                            for j in 0..N {
                                let want = d::Ggx::new(r64).g2(i.at(j), o.at(j), m.at(j));
                                let got = out[j] as f64;
                                let e = (got - want).abs() / want.max(MIN) / EPS;
                                worst[1] = worst[1].max(e / 12.0);
                                assert!(e <= 12.0, "ggx g2 {name} [{j}]: {got} vs {want}");
                            }
                            let lam = |w: glam::DVec3| {
                                let l = d::Beckmann::new(r64).lambda(w);
                                let a = a_of(&r64, w);
                                (l, (13.0 + 7.0 * a * a) * EPS * l)
                            };
                            batch::beckmann_lambda(&r, &o.x, &o.y, &o.z, &mut out);
                            for j in 0..N {
                                let (want, amp) = lam(o.at(j));
                                let got = out[j] as f64;
                                let ok = if want.is_infinite() {
                                    got == want
                                } else {
                                    let tol = L * (1.0 + want) + amp;
                                    worst[2] = worst[2].max((got - want).abs() / tol);
                                    (got - want).abs() <= tol
                                };
                                assert!(ok, "beckmann lambda {name} {alpha} [{j}]: {got} vs {want}");
                            }
                            batch::beckmann_g2(&r, i.soa(), o.soa(), m.soa(), &mut out);
                            for j in 0..N {
                                let want = d::Beckmann::new(r64).g2(i.at(j), o.at(j), m.at(j));
                                let got = out[j] as f64;
                                let ((li, ai), (lo, ao)) = (lam(i.at(j)), lam(o.at(j)));
                                let s = 1.0 + li + lo;
                                let tol = if s.is_finite() {
                                    (2.0 * L + 3.0 * EPS + (ai + ao) / s) * want
                                } else {
                                    0.0
                                };
                                if tol > 0.0 {
                                    worst[3] = worst[3].max((got - want).abs() / tol);
                                }
                                assert!(
                                    (got - want).abs() <= tol,
                                    "beckmann g2 {name} {alpha} [{j}]: {got} vs {want}"
                                );
                            }
                        })
                    }
                }
                println!(
                    "worst of the bound: GGX Lambda {:.3}, G2 {:.3}; Beckmann Lambda {:.3}, G2 {:.3}",
                    worst[0], worst[1], worst[2], worst[3]
                );
            }

            /// The deferred presets against the `f64` scalar path (bound in the file docs).
            #[test]
            fn deferred_presets_against_f64() {
                use filtered_ndf::f64::filter::deferred::{Domain, Norm};
                let mut rng = Rng(0xDEF0);
                let mut col = |f: &mut dyn FnMut(&mut Rng) -> f64| -> Vec<$t> {
                    (0..N).map(|_| f(&mut rng) as $t).collect()
                };
                let alpha = col(&mut |r| if r.uniform() < 0.05 { 0.0 } else { r.log_uniform(1e-3, 0.9) });
                // Normal differences from 1e-4 to 1 per pixel: unclamped to clamped kernels.
                let mut dn = || col(&mut |r| r.normal() * r.log_uniform(1e-4, 1.0));
                let (ux, uy, uz, vx, vy, vz) = (dn(), dn(), dn(), dn(), dn(), dn());
                let (u, v) = (batch::Vec3s::new(&ux, &uy, &uz), batch::Vec3s::new(&vx, &vy, &vz));
                let mut out = vec![0.0 as $t; N];
                for (j, (name, k)) in filtered_ndf::$prec::filter::presets::ALL.iter().enumerate() {
                    let k64 = filtered_ndf::f64::filter::presets::ALL[j].1;
                    batch::deferred_filter(k, &alpha, u, v, &mut out);
                    let mut worst = 0.0f64;
                    for i in 0..N {
                        let (a, du, dv) = (
                            alpha[i] as f64,
                            glam::DVec3::new(ux[i] as f64, uy[i] as f64, uz[i] as f64),
                            glam::DVec3::new(vx[i] as f64, vy[i] as f64, vz[i] as f64),
                        );
                        let want = k64.filter(a, du, dv).alpha();
                        let e = k64.exponent;
                        let r_n = match k64.norm {
                            Norm::SumSquared => 3.0,
                            Norm::MaxSquared => 1.5,
                            Norm::MaxEigenvalue => 6.0,
                            Norm::MaxAbsComponent => 0.0,
                        };
                        let pow = if e == 1.0 {
                            0.0
                        } else if WIDE {
                            let y = (e * k64.norm.eval(du, dv).ln()).abs();
                            1.6e-14 / EPS + 3.0 * y + 1.0
                        } else {
                            // `pow_lane`'s `(5 + 3 |e|) u`, `u = eps / 2`.
                            2.5 + 1.5 * e.abs()
                        };
                        let r_k = e * r_n + 2.0 + pow;
                        let r_v = match k64.domain {
                            Domain::Alpha => 0.0,
                            Domain::Alpha2 | Domain::Perceptual => 1.0,
                            Domain::ProjectedAlpha2 => 1.0 + 1.0 / (1.0 - a * a),
                        };
                        let r_out = r_v.max(r_k) + 1.0;
                        let tol = 1.0 + match k64.domain {
                            Domain::Alpha2 => r_out / 2.0 + 1.0,
                            Domain::Alpha => r_out,
                            Domain::Perceptual => 2.0 * r_out + 1.0,
                            Domain::ProjectedAlpha2 => r_out / 2.0 + 2.0,
                        };
                        let err = (out[i] as f64 - want).abs() / want / EPS;
                        worst = worst.max(err / tol);
                        assert!(err <= tol, "{name} [{i}]: {} vs {want} ({err:.2} eps > {tol:.2})", out[i]);
                    }
                    println!("{name}: worst {worst:.3} of the bound");
                }
            }
        }
    };
}

suite!(single, f32, f32);
suite!(double, f64, f64);
