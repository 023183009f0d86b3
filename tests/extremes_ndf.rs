//! The extremes sweep, part 1: the NDFs (GGX, Beckmann; `p22`, `d`, `Lambda`; isotropic,
//! axis-aligned and matrix roughness), the sampling pdfs and the Jacobians, over the edges of
//! their domains, in `f32` and `f64`.
//!
//! Grid: roughness `alpha` in {1e-7, 1e-4, 1, 10}; roughness forms isotropic, axis-aligned
//! (`alpha`, `3 alpha`), a rotated matrix (eigenvalues `alpha^2`, `4 alpha^2`), a matrix of
//! condition number `1e6` (eigenvalues `alpha^2`, `1e6 alpha^2`, capped at `0.99 ALPHA_MAX^2`)
//! and two near-singular matrices (`a12 = (1 - eps_F) sqrt(a11 a22)`, determinant `~2 eps_F
//! a11 a22`, i.e. at the rounding level; and `a12 = sqrt(a11 a22)` exactly, determinant `0`,
//! accepted only with the TK19 clamp `tau`); half vectors at the pole, in the lobe (slopes
//! `0.5, 1, 4` lobe widths), at 89.99 degrees and exactly at 90 degrees.
//!
//! References: closed forms evaluated in double-double (`tests/extremes_support`), so that the
//! determinant and the quadratic form of a near-singular matrix are exact; the sampling
//! normalisation and the Smith identity `int max(0, w.m) D(m) dm = w_z (1 + Lambda(w))` by
//! `f64` adaptive quadrature (`filtered_ndf::testing::quadrature`). Every input is first
//! rounded to the precision under test and the reference is evaluated at the rounded input,
//! so the errors are the kernels' own.
//!
//! Run with `--nocapture` to print the error map (the table published in `src/contract.rs`).

mod extremes_support;

use extremes_support::{
    ALPHAS, Dd, DdSym, ErrorMap, F32, F64, beckmann_lambda_ref, beckmann_p22_ref, ggx_lambda_ref,
    ggx_p22_ref, min_positive, rel_err, unit_eps,
};
use filtered_ndf::math::Real;
use filtered_ndf::testing::quadrature::{Estimate, Tolerance, integrate_estimates, integrate_line};

/// `int f(s) ds` over the half plane `{s : wo.m(s) > 0}` = `{u < u0}` with `u = s . d`,
/// `d = -wo_xy / |wo_xy|` (the clamp of the visible-normal pdf is a boundary, not a kink):
/// outer integral over `u` split at the lobe (width `w`, features at `0`) plus a mapped tail,
/// inner integral over the perpendicular coordinate by `integrate_line` (width `w_min`; the
/// lobe must be centred on each inner line, i.e. `wo_xy` along an axis of the lobe).
fn visible_integral(
    f: impl Fn(f64, f64) -> f64,
    wo: [f64; 3],
    w: f64,
    w_min: f64,
    tol: Tolerance,
) -> Estimate {
    let rxy = wo[0].hypot(wo[1]);
    let (dx, dy) = if rxy > 0.0 {
        (-wo[0] / rxy, -wo[1] / rxy)
    } else {
        (1.0, 0.0)
    };
    // m = (-s, 1) / n, so wo.m > 0 <=> wo_z - s . wo_xy > 0 <=> u = s . d > -wo_z / rxy.
    let u0 = if rxy > 0.0 {
        -wo[2] / rxy
    } else {
        f64::NEG_INFINITY
    };
    // The inner integrals' estimates ride along with their values (integrated by the outer
    // rule's weights, `integrate_estimates`).
    let inner = |u: f64| {
        let e = integrate_line(|v| f(u * dx - v * dy, u * dy + v * dx), 0.0, w_min, tol);
        (e.value, e.error)
    };
    if u0 == f64::NEG_INFINITY {
        // Normal incidence: the outer line through the same substitution as `integrate_line`,
        // x = L t / (1 - t^2).
        return integrate_estimates(
            |t| {
                let d = 1.0 - t * t;
                let j = w * (1.0 + t * t) / (d * d);
                let (v, e) = inner(w * t / d);
                let (v, e) = (v * j, e * j);
                if v.is_finite() && e.is_finite() {
                    (v, e)
                } else {
                    (0.0, 0.0)
                }
            },
            -1.0,
            1.0,
            tol,
        );
    }
    // u in (u0, u0 + R] piecewise, then the tail beyond, mapped.
    let big = 1e4 * w + u0.abs();
    let body = extremes_support::integrate_feature(&inner, u0, u0 + big, 0.0, w, tol);
    let tail = integrate_estimates(
        |t| {
            let d = 1.0 - t;
            let j = big / (d * d);
            let (v, e) = inner(u0 + big + big * t / d);
            let (v, e) = (v * j, e * j);
            if v.is_finite() && e.is_finite() {
                (v, e)
            } else {
                (0.0, 0.0)
            }
        },
        0.0,
        1.0,
        tol,
    );
    Estimate {
        value: body.value + tail.value,
        error: body.error + tail.error,
    }
}

const PI: f64 = std::f64::consts::PI;
const GRAZE: f64 = 89.99 * PI / 180.0;

/// A roughness case, described in `f64` from inputs already rounded to the precision.
#[derive(Clone, Copy)]
enum Form {
    Iso(f64),
    Axis(f64, f64),
    /// Entries and clamp `tau`.
    Mat(f64, f64, f64, f64),
}

struct Case {
    alpha: &'static str,
    form: &'static str,
    spec: Form,
    /// The roughness matrix (double-double, from the rounded inputs) and `tau`.
    a: DdSym,
    tau: f64,
    /// Lobe widths along two directions, for the lobe sample points.
    widths: (f64, f64),
}

/// A direction (unit, `f64`) with its region label.
fn directions(widths: (f64, f64)) -> Vec<(&'static str, [f64; 3])> {
    let mut v = vec![("pole", [0.0, 0.0, 1.0])];
    for &k in &[0.5, 1.0, 4.0] {
        for (phi, w) in [(0.3_f64, widths.0), (2.0_f64, widths.1)] {
            let t = k * w;
            let n = (1.0 + t * t).sqrt();
            v.push(("lobe", [t * phi.cos() / n, t * phi.sin() / n, 1.0 / n]));
        }
    }
    for phi in [0.0_f64, 0.7, PI / 2.0] {
        v.push((
            "89.99 deg",
            [
                GRAZE.sin() * phi.cos(),
                GRAZE.sin() * phi.sin(),
                GRAZE.cos(),
            ],
        ));
    }
    for phi in [0.0_f64, 0.7] {
        v.push(("90 deg", [phi.cos(), phi.sin(), 0.0]));
    }
    v
}

macro_rules! sweep {
    ($name:ident, $p:ident, $prec:expr) => {
        mod $name {
            use super::*;
            use filtered_ndf::$p::{
                AxisAligned, Beckmann, F, Ggx, Isotropic, NdfSampling, RoughnessMatrix, Vec2, Vec3,
                footprint::jacobian,
            };

            const PREC: usize = $prec;

            fn r(x: f64) -> f64 {
                F::from_f64(x).to_f64()
            }

            /// Whether the checked constructor accepts the matrix (near-singular matrices exist
            /// in the domain only where `eps lambda_max >= ALPHA_MIN^2`).
            fn valid(a11: f64, a12: f64, a22: f64, tau: f64) -> bool {
                let f = F::from_f64;
                RoughnessMatrix::new_with_det_clamp(f(a11), f(a12), f(a22), f(tau)).is_ok()
            }

            pub fn cases() -> Vec<Case> {
                let eps = unit_eps(PREC);
                let mut out = Vec::new();
                for &(alpha, label) in &ALPHAS {
                    let a = r(alpha);
                    out.push(Case {
                        alpha: label,
                        form: "isotropic",
                        spec: Form::Iso(a),
                        a: DdSym {
                            a11: Dd::prod(a, a),
                            a12: Dd::from(0.0),
                            a22: Dd::prod(a, a),
                        },
                        tau: 0.0,
                        widths: (a, a),
                    });
                    let b = r(3.0 * alpha);
                    out.push(Case {
                        alpha: label,
                        form: "axis-aligned",
                        spec: Form::Axis(a, b),
                        a: DdSym {
                            a11: Dd::prod(a, a),
                            a12: Dd::from(0.0),
                            a22: Dd::prod(b, b),
                        },
                        tau: 0.0,
                        widths: (a, b),
                    });
                    // Rotated matrices R diag(l1, l2) R^T, entries rounded to F.
                    let rot = |l1: f64, l2: f64, th: f64| {
                        let (c, s) = (th.cos(), th.sin());
                        (
                            r(l1 * c * c + l2 * s * s),
                            r((l1 - l2) * c * s),
                            r(l1 * s * s + l2 * c * c),
                        )
                    };
                    let (m11, m12, m22) = rot(4.0 * alpha * alpha, alpha * alpha, 0.5);
                    out.push(Case {
                        alpha: label,
                        form: "matrix",
                        spec: Form::Mat(m11, m12, m22, 0.0),
                        a: DdSym::new(m11, m12, m22),
                        tau: 0.0,
                        widths: (alpha, 2.0 * alpha),
                    });
                    let l1 = (1e6 * alpha * alpha).min(0.99e8);
                    let (c11, c12, c22) = rot(l1, alpha * alpha, 0.3);
                    out.push(Case {
                        alpha: label,
                        form: "cond 1e6",
                        spec: Form::Mat(c11, c12, c22, 0.0),
                        a: DdSym::new(c11, c12, c22),
                        tau: 0.0,
                        widths: (alpha, l1.sqrt()),
                    });
                    // Near-singular: a11 = alpha^2, a22 = 4 alpha^2, a12 = (1 - eps) 2 alpha^2
                    // (determinant ~ 8 eps alpha^4, at the rounding level of the entries).
                    let (n11, n22) = (r(alpha * alpha), r(4.0 * alpha * alpha));
                    let n12 = r((1.0 - eps) * (n11 * n22).sqrt());
                    let nd = DdSym::new(n11, n12, n22);
                    if nd.det().f() > 0.0 && valid(n11, n12, n22, 0.0) {
                        out.push(Case {
                            alpha: label,
                            form: "near-singular",
                            spec: Form::Mat(n11, n12, n22, 0.0),
                            a: nd,
                            tau: 0.0,
                            widths: (alpha, 2.0 * alpha),
                        });
                    }
                    // Exactly singular, with the TK19 clamp tau = (alpha^2 / 10)^2.
                    let s12 = r(2.0 * alpha * alpha);
                    let tau = r((0.1 * alpha * alpha).powi(2));
                    if valid(n11, s12, n22, tau) {
                        // The clamp evaluates A_c = A + t I (det tau) with its pivot rounded to
                        // F (RoughnessMatrix docs; the pivot is checked against A + t I in
                        // tests/matrix_representations.rs): the reference is that matrix.
                        let f = F::from_f64;
                        let p = RoughnessMatrix::new_with_det_clamp(f(n11), f(s12), f(n22), f(tau))
                            .unwrap()
                            .clamped_entries()
                            .0
                            .to_f64();
                        out.push(Case {
                            alpha: label,
                            form: "singular + tau",
                            spec: Form::Mat(n11, s12, n22, tau),
                            a: DdSym::ldl(p, s12, tau),
                            tau,
                            widths: (alpha, 2.0 * alpha),
                        });
                    }
                }
                out
            }

            /// GGX and Beckmann of a case, boxed (object-safe traits).
            fn build(spec: Form) -> Vec<(&'static str, Box<dyn NdfSampling>)> {
                let f = F::from_f64;
                match spec {
                    Form::Iso(a) => {
                        let r = Isotropic::new(f(a)).unwrap();
                        vec![
                            ("GGX", Box::new(Ggx::new(r)) as Box<dyn NdfSampling>),
                            ("Beckmann", Box::new(Beckmann::new(r))),
                        ]
                    }
                    Form::Axis(a, b) => {
                        let r = AxisAligned::new(f(a), f(b)).unwrap();
                        vec![
                            ("GGX", Box::new(Ggx::new(r)) as Box<dyn NdfSampling>),
                            ("Beckmann", Box::new(Beckmann::new(r))),
                        ]
                    }
                    Form::Mat(a11, a12, a22, tau) => {
                        let r = RoughnessMatrix::new_with_det_clamp(f(a11), f(a12), f(a22), f(tau))
                            .unwrap_or_else(|e| {
                                panic!("matrix ({a11:e}, {a12:e}, {a22:e}, tau {tau:e}): {e:?}")
                            });
                        vec![
                            ("GGX", Box::new(Ggx::new(r)) as Box<dyn NdfSampling>),
                            ("Beckmann", Box::new(Beckmann::new(r))),
                        ]
                    }
                }
            }

            fn v3(d: [f64; 3]) -> Vec3 {
                Vec3::new(F::from_f64(d[0]), F::from_f64(d[1]), F::from_f64(d[2]))
            }

            fn back(v: Vec3) -> [f64; 3] {
                [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
            }

            /// Reference `D(m)` (homogeneous form, TK19 supplement; Beckmann's
            /// `exp(-q / m_z^2) / (pi sqrt(det) m_z^4)`) at the rounded `m`.
            fn d_ref(model: &str, c: &Case, m: [f64; 3]) -> f64 {
                if m[2] <= 0.0 {
                    return 0.0;
                }
                let det = extremes_support::max_dd(c.a.det(), c.tau);
                let q = c.a.adj_quadratic(m[0], m[1]).div(det);
                if model == "GGX" {
                    let t = q.add(Dd::prod(m[2], m[2])).f();
                    1.0 / (PI * det.sqrt().f() * t * t)
                } else {
                    let x = q.div(Dd::prod(m[2], m[2])).f();
                    (-x - (PI * det.sqrt().f()).ln() - 4.0 * m[2].ln()).exp()
                }
            }

            /// The exponent `m_xy^T A^-1 m_xy / m_z^2` of Beckmann `D` (0 for GGX and at or
            /// below the horizon): it scales the Beckmann tolerances.
            fn d_exponent(model: &str, c: &Case, m: [f64; 3]) -> f64 {
                if model == "GGX" || m[2] <= 0.0 {
                    return 0.0;
                }
                let det = extremes_support::max_dd(c.a.det(), c.tau);
                c.a.adj_quadratic(m[0], m[1])
                    .div(det)
                    .div(Dd::prod(m[2], m[2]))
                    .f()
            }

            fn lambda_ref(model: &str, c: &Case, w: [f64; 3]) -> f64 {
                let q = c.a.quadratic(w[0], w[1]);
                if model == "GGX" {
                    ggx_lambda_ref(q, w[2])
                } else {
                    beckmann_lambda_ref(q, w[2])
                }
            }

            pub fn ndfs(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                let floor = min_positive(PREC);
                for c in cases() {
                    for (model, ndf) in build(c.spec) {
                        let kp = &format!("{model} p22");
                        let kd = &format!("{model} D");
                        let kl = &format!("{model} 1+Lambda");
                        for (dir, m) in directions(c.widths) {
                            let regions = [c.alpha, c.form, dir];
                            // p22 at the slope of m (a huge slope 1e30 for 90 degrees).
                            let s = if m[2] > 0.0 {
                                [-m[0] / m[2], -m[1] / m[2]]
                            } else {
                                [-m[0] * 1e30, -m[1] * 1e30]
                            };
                            let sv = Vec2::new(F::from_f64(s[0]), F::from_f64(s[1]));
                            let (sx, sy) = (sv.x.to_f64(), sv.y.to_f64());
                            let got = ndf.p22(sv).to_f64();
                            let (reference, q) = if model == "GGX" {
                                (ggx_p22_ref(&c.a, c.tau, sx, sy), 0.0)
                            } else {
                                let det = extremes_support::max_dd(c.a.det(), c.tau);
                                let q = c.a.adj_quadratic(sx, sy).div(det).f();
                                (beckmann_p22_ref(&c.a, c.tau, sx, sy), q)
                            };
                            // Tolerance: GGX p22 = 1 / (pi sqrt(det) (1 + q)^2) is twice as
                            // sensitive to q as q is to its inputs, and q costs a few ulps in
                            // any form (the matrix form works in the eigenbasis): 32 eps. For
                            // Beckmann, exp(-q) turns a relative error e of q into q e: the
                            // tolerance grows like (32 + 8 q) eps (the conditioning of exp).
                            let tol = (32.0 + 8.0 * q) * eps;
                            map.record_density(
                                kp,
                                &regions,
                                PREC,
                                (got, reference, floor),
                                tol,
                                || {
                                    format!(
                                        "{} {} s = {s:?}: got {got:e}, ref {reference:e}",
                                        c.alpha, c.form
                                    )
                                },
                            );

                            // D(m).
                            let mv = v3(m);
                            let mr = back(mv);
                            let got = ndf.d(mv).to_f64();
                            let reference = d_ref(model, &c, mr);
                            let x = d_exponent(model, &c, mr);
                            // Tolerance: as p22 (32 eps; Beckmann (32 + 8 x) eps with x the
                            // exponent), and 0 exactly at and below the horizon.
                            let tol = (32.0 + 8.0 * x) * eps;
                            map.record_density(
                                kd,
                                &regions,
                                PREC,
                                (got, reference, floor),
                                tol,
                                || {
                                    format!(
                                        "{} {} m = {mr:?}: got {got:e}, ref {reference:e}",
                                        c.alpha, c.form
                                    )
                                },
                            );

                            // Lambda, measured as 1 + Lambda (what G1 = 1 / (1 + Lambda) uses; a
                            // tiny Lambda near the pole is irrelevant next to 1).
                            let got = ndf.lambda(mv).to_f64();
                            let reference = lambda_ref(model, &c, mr);
                            if reference.is_infinite() {
                                map.require(got == f64::INFINITY, || {
                                    format!("{kl}: expected +inf at the horizon {mr:?}, got {got}")
                                });
                                map.record(kl, &regions, PREC, 0.0, 0.0, String::new);
                            } else {
                                map.require(got.is_finite() && got >= 0.0, || {
                                    format!("{kl} not finite/non-negative at {mr:?}: {got}")
                                });
                                // Tolerance: 1 + Lambda to 32 eps (q and w_z to a few ulps,
                                // a square root; Beckmann's cancellation is done in f64).
                                map.record(
                                    kl,
                                    &regions,
                                    PREC,
                                    rel_err(1.0 + got, 1.0 + reference, 1.0),
                                    32.0 * eps,
                                    || {
                                        format!(
                                            "{} {} w = {mr:?}: got {got:e}, ref {reference:e}",
                                            c.alpha, c.form
                                        )
                                    },
                                );
                            }
                        }
                    }
                }
            }

            pub fn pdfs(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                let floor = min_positive(PREC);
                for c in cases() {
                    for (model, ndf) in build(c.spec) {
                        let kn = &format!("{model} normal pdf");
                        let kv = &format!("{model} visible pdf");
                        let kr = &format!("{model} reflection pdf");
                        let dirs = directions(c.widths);
                        for (wlabel, wo) in [
                            ("wo pole", [0.0, 0.0, 1.0]),
                            (
                                "wo 89.99 deg",
                                [GRAZE.sin() * 0.6, GRAZE.sin() * 0.8, GRAZE.cos()],
                            ),
                            ("wo 90 deg", [0.6, 0.8, 0.0]),
                        ] {
                            let wov = v3(wo);
                            let wr = back(wov);
                            for (dir, m) in &dirs {
                                let regions = [c.alpha, c.form, dir, wlabel];
                                let mv = v3(*m);
                                let mr = back(mv);
                                let d = d_ref(model, &c, mr);
                                let x = d_exponent(model, &c, mr);
                                // Tolerance: that of D ((32 + 8 x) eps), plus 32 eps for the
                                // products, 1 + Lambda and the normalisation of wo.
                                let tol = (64.0 + 8.0 * x) * eps;
                                let got = ndf.normal_pdf(mv).to_f64();
                                let reference = if mr[2] > 0.0 { d * mr[2] } else { 0.0 };
                                map.record_density(
                                    kn,
                                    &regions[..3],
                                    PREC,
                                    (got, reference, floor),
                                    tol,
                                    || {
                                        format!(
                                            "{} {} m {mr:?}: {got:e} vs {reference:e}",
                                            c.alpha, c.form
                                        )
                                    },
                                );

                                let lam = lambda_ref(model, &c, wr);
                                let wom = wr[0] * mr[0] + wr[1] * mr[1] + wr[2] * mr[2];
                                let got = ndf.visible_normal_pdf(wov, mv).to_f64();
                                let reference = if wr[2] > 0.0 && wom > 0.0 && mr[2] > 0.0 {
                                    wom * d / (wr[2] * (1.0 + lam))
                                } else {
                                    0.0
                                };
                                // wo.m cancels for m near the horizon of wo: its error is
                                // eps |wo| |m| / (wo.m), added to the tolerance.
                                let cancel = if wom > 0.0 { 4.0 * eps / wom } else { 0.0 };
                                map.record_density(
                                    kv,
                                    &regions,
                                    PREC,
                                    (got, reference, floor),
                                    tol + cancel,
                                    || {
                                        format!(
                                            "{} {} wo {wr:?} m {mr:?}: {got:e} vs {reference:e}",
                                            c.alpha, c.form
                                        )
                                    },
                                );

                                let got = ndf.reflection_pdf_from_normal(wov, mv).to_f64();
                                let n = (wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2]).sqrt();
                                let reference = if wr[2] > 0.0 && wom > 0.0 && mr[2] > 0.0 {
                                    d / (4.0 * wr[2] / n * (1.0 + lam))
                                } else {
                                    0.0
                                };
                                map.record_density(
                                    kr,
                                    &regions,
                                    PREC,
                                    (got, reference, floor),
                                    tol,
                                    || {
                                        format!(
                                            "{} {} wo {wr:?} m {mr:?}: {got:e} vs {reference:e}",
                                            c.alpha, c.form
                                        )
                                    },
                                );
                            }
                        }
                    }
                }
            }

            /// The visible-normal pdf integrates to one over the hemisphere (Heitz 2014 eq. 16,
            /// i.e. the Smith identity), by quadrature over the slope plane with
            /// `dm = m_z^3 ds`.
            #[allow(dead_code)] // f64 only (see the goal below)
            pub fn normalisation(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                // The goal 1e-10 (f64 only: in f32 the integrand carries rounding noise that
                // an adaptive rule cannot converge through; the f32 pdfs are checked pointwise
                // against the closed form above).
                let goal = Tolerance {
                    abs: 1e-300,
                    rel: 1e-10,
                    max_intervals: 400,
                };
                for &(alpha, label) in &ALPHAS {
                    let a = r(alpha);
                    for (form, spec, scale) in [
                        ("isotropic", Form::Iso(a), (a, a)),
                        (
                            "cond 1e6",
                            Form::Axis(a, r(1e3 * alpha).min(0.99e4)),
                            (a, (1e3 * alpha).min(0.99e4)),
                        ),
                    ] {
                        for (model, ndf) in build(spec) {
                            let k = &format!("{model} visible pdf");
                            // Azimuths along the lobe's axes, so that the inner lines of the
                            // quadrature run along one axis (width known exactly).
                            for (wlabel, theta, along_y) in [
                                ("wo pole", 0.0_f64, false),
                                ("wo 89.99 deg", GRAZE, false),
                                ("wo 89.99 deg", GRAZE, true),
                            ] {
                                let (cx, cy) = if along_y { (0.0, 1.0) } else { (1.0, 0.0) };
                                let wo = v3([theta.sin() * cx, theta.sin() * cy, theta.cos()]);
                                let (w_outer, w_inner) = if along_y {
                                    (scale.1, scale.0)
                                } else {
                                    (scale.0, scale.1)
                                };
                                let wr = back(wo);
                                let total = visible_integral(
                                    |x, y| {
                                        let n = (1.0 + x * x + y * y).sqrt();
                                        let m = v3([-x / n, -y / n, 1.0 / n]);
                                        let mz = 1.0 / n;
                                        ndf.visible_normal_pdf(wo, m).to_f64() * mz * mz * mz
                                    },
                                    wr,
                                    w_outer,
                                    w_inner,
                                    goal,
                                );
                                // Tolerance: four times the quadrature's own estimate (the
                                // clamp along wo.m = 0 is a boundary of the integration
                                // domain, not a kink inside it), required within ten times its
                                // goal, plus 64 eps of rounding per sample.
                                map.require(total.error <= 10.0 * goal.rel, || {
                                    format!("{label} {form} {wlabel}: quadrature {total:?}")
                                });
                                let tol = 4.0 * total.error.max(1e-16) + 64.0 * eps;
                                map.record(
                                    k,
                                    &[label, form, wlabel, "normalisation (quadrature)"],
                                    PREC,
                                    (total.value - 1.0).abs(),
                                    tol,
                                    || format!("{label} {form} {wlabel}: integral {}", total.value),
                                );
                            }
                        }
                    }
                }
            }

            pub fn jacobians(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                let hz_min = jacobian::HZ_MIN.to_f64();
                let mut hs: Vec<(&str, [f64; 3])> = vec![("pole", [0.0, 0.0, 1.0])];
                for th in [0.3_f64, 1.2] {
                    hs.push(("lobe", [th.sin() * 0.6, th.sin() * 0.8, th.cos()]));
                }
                for phi in [0.0_f64, 0.7, PI / 2.0] {
                    hs.push((
                        "89.99 deg",
                        [
                            GRAZE.sin() * phi.cos(),
                            GRAZE.sin() * phi.sin(),
                            GRAZE.cos(),
                        ],
                    ));
                    hs.push(("90 deg", [phi.cos(), phi.sin(), 0.0]));
                }
                // Non-unit input (Jacobians normalise h).
                hs.push(("lobe", [3.0, 4.0, 12.0]));
                for (label, h) in hs {
                    let hv = v3(h);
                    let hr = back(hv);
                    let n = (hr[0] * hr[0] + hr[1] * hr[1] + hr[2] * hr[2]).sqrt();
                    let mut u = [hr[0] / n, hr[1] / n, hr[2] / n];
                    let rxy = u[0].hypot(u[1]);
                    let (cp, sp) = if rxy > 0.0 {
                        (u[0] / rxy, u[1] / rxy)
                    } else {
                        (1.0, 0.0)
                    };
                    if u[2] < hz_min {
                        let st = (1.0 - hz_min * hz_min).sqrt();
                        u = [st * cp, st * sp, hz_min];
                    }
                    let hz = u[2];
                    let regions = [label];
                    // Determinants against the closed forms (TK19 section 3.1, 3.2): h_z,
                    // 1 / h_z^4, 1 / h_z^3. Tolerance 16 eps: a normalisation and a power.
                    for (k, got, reference) in [
                        (
                            "det J(o->perp)",
                            jacobian::det_sphere_to_projected(hv).to_f64(),
                            hz,
                        ),
                        (
                            "det J(perp->par)",
                            jacobian::det_projected_to_slope(hv).to_f64(),
                            1.0 / hz.powi(4),
                        ),
                        (
                            "det J(o->par)",
                            jacobian::det_sphere_to_slope(hv).to_f64(),
                            1.0 / hz.powi(3),
                        ),
                    ] {
                        map.require(got.is_finite() && got > 0.0, || {
                            format!("{k} at {hr:?}: {got}")
                        });
                        map.record(
                            k,
                            &regions,
                            PREC,
                            rel_err(got, reference, 0.0),
                            16.0 * eps,
                            || format!("h {hr:?}: {got:e} vs {reference:e}"),
                        );
                    }
                    // Matrices against the paper's closed forms (TK19 supplement eq. 4, 6, 7),
                    // evaluated here in double-double from the reference unit h, error relative
                    // to the largest entry. Tolerance 64 eps: entries carry the rounding of h's
                    // normalisation amplified by at most 1 / h_z^3 / (1 / h_z^3).
                    let (hx, hy) = (u[0], u[1]);
                    let one_minus = |a: f64| Dd::from(1.0).sub(Dd::prod(a, a)).f();
                    let k6 = -1.0 / (hz * hz * hz);
                    let refs: [(&str, [f64; 4], Mat); 4] = [
                        (
                            "J(o->perp)",
                            [hz * cp, hz * sp, -sp, cp],
                            jacobian::sphere_to_projected(hv),
                        ),
                        (
                            "J(perp->par)",
                            [
                                k6 * one_minus(hy),
                                k6 * hx * hy,
                                k6 * hx * hy,
                                k6 * one_minus(hx),
                            ],
                            jacobian::projected_to_slope(hv),
                        ),
                        (
                            "J(par->perp)",
                            [
                                -hz * one_minus(hx),
                                hz * hx * hy,
                                hz * hx * hy,
                                -hz * one_minus(hy),
                            ],
                            jacobian::slope_to_projected(hv),
                        ),
                        (
                            "J(o->par)",
                            [-cp / (hz * hz), -sp / (hz * hz), sp / hz, -cp / hz],
                            jacobian::sphere_to_slope(hv),
                        ),
                    ];
                    for (k, reference, got) in refs {
                        let g = got.to_cols_array();
                        let big = reference.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
                        let err = g
                            .iter()
                            .zip(reference.iter())
                            .map(|(a, b)| (a.to_f64() - b).abs())
                            .fold(0.0, f64::max)
                            / big;
                        map.require(g.iter().all(|x| x.is_finite()), || {
                            format!("{k} at {hr:?} not finite")
                        });
                        map.record(k, &regions, PREC, err, 64.0 * eps, || {
                            format!("h {hr:?}: {g:?} vs {reference:?}")
                        });
                    }
                }
            }

            type Mat = filtered_ndf::$p::Mat2;
        }
    };
}

sweep!(p32, f32, F32);
sweep!(p64, f64, F64);

#[test]
fn extremes_ndf_error_map() {
    let t0 = std::time::Instant::now();
    let mut map = ErrorMap::new("NDFs: worst relative error, f32 / f64");
    p32::ndfs(&mut map);
    p64::ndfs(&mut map);
    println!("ndfs: {:?}", t0.elapsed());
    let mut pdf = ErrorMap::new("Sampling pdfs: worst relative error, f32 / f64");
    p32::pdfs(&mut pdf);
    p64::pdfs(&mut pdf);
    println!("pdfs: {:?}", t0.elapsed());
    p64::normalisation(&mut pdf);
    println!("normalisation: {:?}", t0.elapsed());
    let mut jac = ErrorMap::new("Jacobians: worst relative error, f32 / f64");
    p32::jacobians(&mut jac);
    p64::jacobians(&mut jac);
    let mut failed = Vec::new();
    for m in [&map, &pdf, &jac] {
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| m.finish())).is_err() {
            failed.push(());
        }
    }
    assert!(failed.is_empty(), "see the FAIL lines above");
}
