//! `shaders/ndf/`: the roughness forms, GGX and Beckmann (`p22`, `d`, `lambda`, `g1`, `g2`)
//! in the three forms.
//!
//! Cases: roughness from the crate's strategies (`strategies::isotropic`, `axis_aligned`,
//! and the rotated matrices of `strategies::matrix`: alpha log-uniform in `[1e-4, 2]`,
//! anisotropy up to `1e3`) and the ends of the supported range (`1e-8`, `1e4`), directions
//! from `strategies::upper_hemisphere(89.9)` (pole and near-horizon weighted in), slopes those
//! of the micronormals. The matrix form is checked twice: as built (`from_eigen`) and with
//! the determinant clamp active (`with_det_clamp(tau)`, `tau` from `det A (1 + 1e-6)` to
//! `1e6 det A`), against `RoughnessMatrix::new_with_det_clamp`: the one clamped matrix
//! `A_c = A + t I` of both.
//!
//! Tolerances (ulp of f32; GGX's far tail beyond `1e-36` of the peak as in `ggx_tail`):
//! `err_q`, the error of the quadratic forms, is 6 (isotropic: a
//! dot product, `1 / alpha^2` with its division), 7 (axis-aligned) and
//! `8 + 8 sqrt(cond A)` for the matrix form (`matrix.wgsl`: the rotation error weighted by
//! `sqrt(cond)`), `13 + 8 sqrt(cond A_c)` with the clamp active (its eigenvalues 5 ulp more). GGX `P22`, `D`: `2 (err_q + 1) + 6` (the square of `1 + q`, five products
//! and a division). GGX `Lambda`: `1.5 err_q + 10` (a square root halves `err_q`, then a
//! division and three products). `G1 = 1 / (1 + Lambda)`: `err_Lambda + 3`; `G2`:
//! `err_Lambda + 4`. Beckmann `P22`, `D`: the exponent `x` carries `err_x = err_q + 3` ulp,
//! which `exp(-x)` multiplies by `x`, plus the driver's `exp` (`3 + 2x`), 6 for the
//! normalisation and, past the split at `x = 80`, `4 |ln k|` for the logarithm of the
//! normalisation. Beckmann `Lambda`: `a = |w_z| / sqrt(q)` carries
//! `err_a = err_q / 2 + 7`, amplified by `2 a^2 + 3`, plus `exp` (`3 + 2 a^2`) and 10 for the
//! fitted `K(a)` and the products (`beckmann.wgsl`).

use super::{Check, EPS, Tol, draw, r32};
use crate::reference::{
    AxisAligned, Beckmann, DVec2, DVec3, Ggx, Isotropic, Ndf, Roughness, RoughnessMatrix,
    matrix_from_eigen, strategies, v2, v3,
};

/// A roughness as the shader receives it and as the reference builds it.
#[derive(Clone, Copy, Debug)]
enum Form {
    Iso(f32),
    Aa([f32; 2]),
    /// `from_eigen(axis, alpha)`, then `with_det_clamp(tau)` for `tau > 0`.
    Mat([f32; 2], [f32; 2], f32),
}

/// The f64 roughness of a case.
#[derive(Clone, Copy, Debug)]
enum Rough {
    Iso(Isotropic),
    Aa(AxisAligned),
    Mat(RoughnessMatrix),
}

impl Rough {
    fn inv_quadratic(&self, s: DVec2) -> f64 {
        match self {
            Rough::Iso(r) => r.inv_quadratic(s),
            Rough::Aa(r) => r.inv_quadratic(s),
            Rough::Mat(r) => r.inv_quadratic(s),
        }
    }
    fn quadratic(&self, w: DVec2) -> f64 {
        match self {
            Rough::Iso(r) => r.quadratic(w),
            Rough::Aa(r) => r.quadratic(w),
            Rough::Mat(r) => r.quadratic(w),
        }
    }
    fn sqrt_det(&self) -> f64 {
        match self {
            Rough::Iso(r) => r.sqrt_det(),
            Rough::Aa(r) => r.sqrt_det(),
            Rough::Mat(r) => r.sqrt_det(),
        }
    }
    fn ndf(&self, ggx: bool) -> Box<dyn Ndf> {
        match (self, ggx) {
            (Rough::Iso(r), true) => Box::new(Ggx::new(*r)),
            (Rough::Aa(r), true) => Box::new(Ggx::new(*r)),
            (Rough::Mat(r), true) => Box::new(Ggx::new(*r)),
            (Rough::Iso(r), false) => Box::new(Beckmann::new(*r)),
            (Rough::Aa(r), false) => Box::new(Beckmann::new(*r)),
            (Rough::Mat(r), false) => Box::new(Beckmann::new(*r)),
        }
    }
}

/// One NDF case: the roughness, a slope, and the directions `m`, `w` (= `i`), `o`.
struct NdfCase {
    form: Form,
    rough: Rough,
    /// `err_q` in ulp.
    err_q: f64,
    s: [f32; 2],
    m: [f32; 3],
    w: [f32; 3],
    o: [f32; 3],
}

impl NdfCase {
    /// The 16 input slots: roughness parameters (0..4), `s` (4..6), `m` (6..9), `w` (9..12),
    /// `o` (12..15), the determinant clamp `tau` (15).
    fn input(&self) -> Vec<f32> {
        let (mut v, tau) = match self.form {
            Form::Iso(a) => (vec![a, 0.0, 0.0, 0.0], 0.0),
            Form::Aa(a) => (vec![a[0], a[1], 0.0, 0.0], 0.0),
            Form::Mat(ax, a, tau) => (vec![ax[0], ax[1], a[0], a[1]], tau),
        };
        v.extend(self.s);
        v.extend(self.m);
        v.extend(self.w);
        v.extend(self.o);
        v.push(tau);
        v
    }
}

fn f32x3(d: DVec3) -> [f32; 3] {
    [d.x as f32, d.y as f32, d.z as f32]
}

fn cases(kind: &str, n: usize) -> Vec<NdfCase> {
    let dirs = draw(
        strategies::upper_hemisphere(89.9),
        3 * n,
        &format!("{kind} dirs"),
    );
    let forms: Vec<Form> = match kind {
        "isotropic" => draw(strategies::isotropic(), n, kind)
            .into_iter()
            .map(|r| Form::Iso(r.alpha() as f32))
            .collect(),
        "axis_aligned" => draw(strategies::axis_aligned(), n, kind)
            .into_iter()
            .map(|r| Form::Aa([r.alpha().x as f32, r.alpha().y as f32]))
            .collect(),
        // The clamped matrices: tau = det A times a ratio log-uniform in [1 + 1e-6, 1e6]
        // (the clamp active by a hair up to far beyond the lobe's own determinant).
        "matrix_clamped" => draw(
            (
                strategies::axis_aligned(),
                0.0..core::f64::consts::PI,
                -6.0f64..6.0,
            ),
            n,
            kind,
        )
        .into_iter()
        .map(|(r, phi, e)| {
            let a = [r.alpha().x as f32, r.alpha().y as f32];
            let det = (f64::from(a[0]) * f64::from(a[1])).powi(2);
            let ratio = if e < 0.0 {
                1.0 + 10f64.powf(e)
            } else {
                10f64.powf(e)
            };
            Form::Mat(
                [phi.cos() as f32, phi.sin() as f32],
                a,
                (det * ratio) as f32,
            )
        })
        .collect(),
        _ => draw(
            (strategies::axis_aligned(), 0.0..core::f64::consts::PI),
            n,
            kind,
        )
        .into_iter()
        .map(|(r, phi)| {
            Form::Mat(
                [phi.cos() as f32, phi.sin() as f32],
                [r.alpha().x as f32, r.alpha().y as f32],
                0.0,
            )
        })
        .collect(),
    };
    // The ends of the supported range, [ALPHA_MIN, ALPHA_MAX] = [1e-8, 1e4], beside the
    // strategies' working range, 16 directions each.
    let ends: Vec<Form> = match kind {
        "isotropic" => vec![Form::Iso(1.0001e-8), Form::Iso(1e4)],
        "axis_aligned" => vec![
            Form::Aa([1.0001e-8, 1.0001e-8]),
            Form::Aa([1.0001e-8, 1e4]),
            Form::Aa([1e4, 1.0001e-8]),
        ],
        "matrix_clamped" => vec![
            Form::Mat([0.6, 0.8], [1.0001e-8, 1e-4], 1e-20),
            Form::Mat([0.6, 0.8], [1e-4, 1e-2], 1e-4),
        ],
        _ => vec![
            Form::Mat([0.6, 0.8], [1.0001e-8, 1.0001e-8], 0.0),
            Form::Mat([0.6, 0.8], [1.0001e-8, 1e-4], 0.0),
            Form::Mat([0.6, 0.8], [1e3, 1e4], 0.0),
        ],
    };
    let forms: Vec<Form> = forms
        .into_iter()
        .chain(ends.iter().flat_map(|f| std::iter::repeat_n(*f, 16)))
        .collect();
    let mut out = Vec::new();
    for (k, form) in forms.into_iter().enumerate() {
        let (rough, err_q) = match form {
            Form::Iso(a) => (Rough::Iso(Isotropic::new(a.into()).expect("in range")), 6.0),
            Form::Aa(a) => (
                Rough::Aa(AxisAligned::new(a[0].into(), a[1].into()).expect("in range")),
                7.0,
            ),
            Form::Mat(ax, a, tau) => {
                let Some(r) = matrix_from_eigen(ax, a) else {
                    continue;
                };
                if tau > 0.0 {
                    // A_c (`matrix.wgsl`): the clamp's eigenvalues add 5 ulp, and the
                    // rotation error is weighted by sqrt(cond A_c).
                    let (a11, a12, a22) = r.entries();
                    let Ok(rc) = RoughnessMatrix::new_with_det_clamp(a11, a12, a22, tau.into())
                    else {
                        continue;
                    };
                    (Rough::Mat(rc), 13.0 + 8.0 * clamped_cond(&rc).sqrt())
                } else {
                    let (l1, l2) = (f64::from(a[0]).powi(2), f64::from(a[1]).powi(2));
                    let cond = l1.max(l2) / l1.min(l2);
                    (Rough::Mat(r), 8.0 + 8.0 * cond.sqrt())
                }
            }
        };
        let j = k % n;
        let m = f32x3(dirs[3 * j]);
        let md = v3(m);
        let s = [(-md.x / md.z) as f32, (-md.y / md.z) as f32];
        out.push(NdfCase {
            form,
            rough,
            err_q,
            s,
            m,
            w: f32x3(dirs[3 * j + 1]),
            o: f32x3(dirs[3 * j + 2]),
        });
    }
    out
}

/// `cond A_c` of a (possibly clamped) reference matrix: the eigenvalues of the matrix its
/// functions evaluate, `lambda_max` from the clamped entries and `lambda_min = det A_c /
/// lambda_max`.
pub fn clamped_cond(m: &RoughnessMatrix) -> f64 {
    let (a, b, c) = m.clamped_entries();
    let l1 = 0.5 * (a + c) + (0.5 * (a - c)).hypot(b);
    let l2 = m.clamped_det() / l1;
    l1 / l2
}

/// GGX's far tail (`ggx.wgsl`): where `t = 1 + q` (or `q_xy + m_z^2`) exceeds `1e18` a
/// driver that reassociates the product may overflow `t^2` and return 0: the tolerance
/// there is the density at `t = 1e18`, `1e-36` of the peak `1 / (pi sqrt(det A))`.
fn ggx_tail(t: f64, sqrt_det: f64, ulps: f64) -> Tol {
    if t >= 1e18 {
        Tol::rel_abs(ulps * EPS, 1e-36 / (core::f64::consts::PI * sqrt_det))
    } else {
        Tol::ulps(ulps)
    }
}

/// GGX / Beckmann tolerances of the module docs, in ulp.
pub fn tol_density(ggx: bool, err_q: f64, x: f64, ln_k: f64) -> f64 {
    if ggx {
        2.0 * (err_q + 1.0) + 6.0
    } else {
        let log_part = if x > 80.0 { 4.0 * ln_k.abs() } else { 0.0 };
        (err_q + 3.0) * x + 3.0 + 2.0 * x + 6.0 + log_part
    }
}

/// The `Lambda` tolerance of the module docs, in ulp, from `q = w_xy^T A w_xy` and `|w_z|`.
pub fn tol_lambda(ggx: bool, err_q: f64, q: f64, abs_wz: f64) -> f64 {
    if ggx {
        1.5 * err_q + 10.0
    } else {
        let a2 = if q > 0.0 { abs_wz * abs_wz / q } else { 0.0 };
        (2.0 * a2 + 3.0) * (0.5 * err_q + 7.0) + 3.0 + 2.0 * a2 + 10.0
    }
}

fn form_checks(kind: &str, n: usize) -> Vec<Check> {
    let cases = cases(kind, n);
    let (ctor, module) = match kind {
        "isotropic" => ("isotropic::from_alpha(x(0u))", "isotropic"),
        "axis_aligned" => ("axis_aligned::from_alpha(x2(0u))", "axis_aligned"),
        "matrix_clamped" => (
            "matrix::with_det_clamp(matrix::from_eigen(x2(0u), x2(2u)), x(15u))",
            "matrix",
        ),
        _ => ("matrix::from_eigen(x2(0u), x2(2u))", "matrix"),
    };
    let fname = if kind == "matrix_clamped" {
        "matrix"
    } else {
        kind
    };
    let suffix = if kind == "matrix_clamped" {
        " (determinant clamp active)"
    } else {
        ""
    };
    let imports = format!(
        "#import filtered_ndf::ndf::roughness::{module}\n#import filtered_ndf::ndf::ggx\n#import filtered_ndf::ndf::beckmann"
    );
    let pre = format!("let r = {ctor};");
    let mut checks = Vec::new();
    let mut add = |name: String, call: &str, f: &dyn Fn(&NdfCase) -> (f64, Tol)| {
        let body = format!("{pre}\ny(0u, {call});");
        let mut c = Check::new(&format!("{name}{suffix}"), &imports, &body, 16, 1);
        for k in &cases {
            let (e, t) = f(k);
            c.case(k.input(), vec![e], vec![t]);
        }
        checks.push(c);
    };
    add(
        format!("{module}::inv_quadratic"),
        &format!("{module}::inv_quadratic(r, x2(4u))"),
        &|k| (k.rough.inv_quadratic(v2(k.s)), Tol::ulps(k.err_q)),
    );
    add(
        format!("{module}::quadratic"),
        &format!("{module}::quadratic(r, x3(9u).xy)"),
        &|k| {
            let w = v3(k.w);
            (k.rough.quadratic(DVec2::new(w.x, w.y)), Tol::ulps(k.err_q))
        },
    );
    add(
        format!("{module}::sqrt_det"),
        &format!("{module}::sqrt_det(r)"),
        &|k| (k.rough.sqrt_det(), Tol::ulps(2.0)),
    );
    for ggx in [true, false] {
        let model = if ggx { "ggx" } else { "beckmann" };
        add(
            format!("{model}::p22_{fname}"),
            &format!("{model}::p22_{fname}(r, x2(4u))"),
            &|k| {
                let q = k.rough.inv_quadratic(v2(k.s));
                let ln_k = -(core::f64::consts::PI * k.rough.sqrt_det()).ln();
                let t = tol_density(ggx, k.err_q, q, ln_k);
                let tol = if ggx {
                    ggx_tail(1.0 + q, k.rough.sqrt_det(), t)
                } else {
                    Tol::ulps(t)
                };
                (k.rough.ndf(ggx).p22(v2(k.s)), tol)
            },
        );
        add(
            format!("{model}::d_{fname}"),
            &format!("{model}::d_{fname}(r, x3(6u))"),
            &|k| {
                let m = v3(k.m);
                let x = k.rough.inv_quadratic(DVec2::new(m.x, m.y)) / (m.z * m.z);
                let ln_k = -((core::f64::consts::PI * k.rough.sqrt_det()).ln() + 4.0 * m.z.ln());
                let t = tol_density(ggx, k.err_q, x, ln_k);
                let tol = if ggx {
                    let tt = k.rough.inv_quadratic(DVec2::new(m.x, m.y)) + m.z * m.z;
                    ggx_tail(tt, k.rough.sqrt_det(), t)
                } else {
                    Tol::ulps(t)
                };
                (k.rough.ndf(ggx).d(m), tol)
            },
        );
        let lambda_tol = |k: &NdfCase, w: DVec3| {
            tol_lambda(
                ggx,
                k.err_q,
                k.rough.quadratic(DVec2::new(w.x, w.y)),
                w.z.abs(),
            )
        };
        add(
            format!("{model}::lambda_{fname}"),
            &format!("{model}::lambda_{fname}(r, x3(9u))"),
            &|k| {
                let w = v3(k.w);
                (k.rough.ndf(ggx).lambda(w), Tol::ulps(lambda_tol(k, w)))
            },
        );
        add(
            format!("{model}::g1_{fname}"),
            &format!("{model}::g1_{fname}(r, x3(9u), x3(6u))"),
            &|k| {
                let w = v3(k.w);
                let t = lambda_tol(k, w) + 3.0;
                (k.rough.ndf(ggx).g1(w, v3(k.m)), Tol::ulps(t))
            },
        );
        add(
            format!("{model}::g2_{fname}"),
            &format!("{model}::g2_{fname}(r, x3(9u), x3(12u), x3(6u))"),
            &|k| {
                let (i, o) = (v3(k.w), v3(k.o));
                let t = lambda_tol(k, i).max(lambda_tol(k, o)) + 4.0;
                (k.rough.ndf(ggx).g2(i, o, v3(k.m)), Tol::ulps(t))
            },
        );
    }
    checks
}

/// The checks of `shaders/ndf/`.
pub fn all() -> Vec<Check> {
    let _ = EPS;
    let mut v = Vec::new();
    for kind in ["isotropic", "axis_aligned", "matrix", "matrix_clamped"] {
        v.extend(form_checks(kind, 2000));
    }
    v.extend(matrix_constructors(2000));
    v
}

/// `isotropic::to_matrix` and `matrix::from_entries`, read back through `matrix::entries`,
/// `matrix::sqrt_det` and `matrix::determinant`.
///
/// `isotropic::to_matrix` (isotropic roughness from `strategies::isotropic` and the range's
/// ends `1e-8`, `1e4`): `alpha^2 I` through `from_eigen((1, 0), (alpha, alpha))`, so the
/// diagonal and `sqrt det` are `alpha alpha` rounded once (1 ulp), the off-diagonal entry
/// `(l - l) c s` exactly 0, the determinant `l l` rounded twice (2 ulp).
///
/// `matrix::from_entries` (the f32 entries of `strategies::matrix`: `alpha_x` log-uniform in
/// `[1e-4, 2]`, anisotropy `1e-3` to `1e3`, rotated): `det = a11 a22 - a12^2` formed in f32,
/// within `u (a11 a22 + a12^2) + u |det|` (`u = EPS / 2`: the two products and the
/// difference, each rounded once; fewer with a fused multiply-add), the documented
/// `cond(A) eps` for elongated matrices. `sqrt det`: half that relative error plus 3 ulp for
/// `sqrt`, so `c / 4 + 4` ulp with `c = (a11 a22 + a12^2) / |det|`. The entries,
/// reconstructed from the eigenbasis: `32 EPS` of the largest entry as for the filtered
/// matrices ([`super::filters`]: `l1` 5 ulp, the reconstruction 3, the eigenvector's angle
/// 4 `EPS` times `2 (l1 - l2)`), plus the determinant's error carried into `l2 = det / l1`.
fn matrix_constructors(n: usize) -> Vec<Check> {
    let read =
        "y3(0u, matrix::entries(a));\ny(3u, matrix::sqrt_det(a));\ny(4u, matrix::determinant(a));";
    let mut iso = Check::new(
        "isotropic::to_matrix",
        "#import filtered_ndf::ndf::roughness::isotropic\n#import filtered_ndf::ndf::roughness::matrix",
        &format!("let a = isotropic::to_matrix(isotropic::from_alpha(x(0u)));\n{read}"),
        1,
        5,
    )
    .tolerance("diagonal and sqrt det 1 ulp (alpha alpha), off-diagonal exactly 0, det 2 ulp");
    let alphas = draw(strategies::isotropic(), n, "to_matrix alpha")
        .into_iter()
        .map(|r| r.alpha() as f32)
        .chain([1.0001e-8, 1e4]);
    for a in alphas {
        let m = Isotropic::new(a.into()).expect("in range").to_matrix();
        let (a11, a12, a22) = m.entries();
        let l = f64::from(a).powi(2);
        iso.case(
            vec![a],
            vec![a11, a12, a22, m.sqrt_det(), l * l],
            vec![
                Tol::ulps(1.0),
                Tol::abs(0.0),
                Tol::ulps(1.0),
                Tol::ulps(1.0),
                Tol::ulps(2.0),
            ],
        );
    }
    let mut ent = Check::new(
        "matrix::from_entries",
        "#import filtered_ndf::ndf::roughness::matrix",
        &format!("let a = matrix::from_entries(x(0u), x(1u), x(2u));\n{read}"),
        3,
        5,
    )
    .tolerance("det u (a11 a22 + a12^2) + u |det| (f32 products and difference); sqrt det c / 4 + 4 ulp; entries 32 EPS of the largest plus det's error / l1");
    let u = 0.5 * EPS;
    for m in draw(strategies::matrix(), n, "from_entries matrix") {
        let (b11, b12, b22) = m.entries();
        let e = [b11 as f32, b12 as f32, b22 as f32];
        let (a11, a12, a22) = (f64::from(e[0]), f64::from(e[1]), f64::from(e[2]));
        // The f32 entries as a matrix (products of f32 values are exact in f64).
        let det = a11 * a22 - a12 * a12;
        let Ok(r) = RoughnessMatrix::new(a11, a12, a22) else {
            continue;
        };
        let terms = a11 * a22 + a12 * a12;
        let det_err = u * terms + u * det.abs();
        let l1 = 0.5 * (a11 + a22) + (0.5 * (a11 - a22)).hypot(a12);
        let largest = a11.abs().max(a22.abs()).max(a12.abs());
        let entry = Tol::of_scale(32.0 + det_err / l1 / (EPS * largest), largest);
        ent.case(
            e.to_vec(),
            vec![a11, a12, a22, r.sqrt_det(), det],
            vec![
                entry,
                entry,
                entry,
                Tol::ulps(0.25 * terms / det + 4.0),
                // Reported relative to `det`.
                Tol {
                    rel: 0.0,
                    abs: det_err + super::TINY,
                    scale: det.abs(),
                },
            ],
        );
    }
    vec![iso, ent]
}

/// `r32` re-exported for sibling modules' use in doc examples.
pub fn round(x: f64) -> f64 {
    r32(x)
}
