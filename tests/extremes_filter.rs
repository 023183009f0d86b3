//! The extremes sweep, part 2: the filtering kernels over the edges of their domains, in `f32`
//! and `f64`: `filter::gaussian` and `filter::projected` (evaluated through the densities they
//! feed), `rect::p22_rect` / `d_rect`, `ggx_proxy`, and the isotropic filters
//! (`deferred::filtered_alpha` and every preset).
//!
//! Grid: base roughness `alpha` in {1e-7, 1e-4, 1, 10} (isotropic, a matrix of condition
//! number `1e6`, and an exactly singular matrix with the TK19 clamp `tau` where the domain
//! admits it); footprints (kernel standard deviations, rectangle half extents, normal
//! differences) `0`, `1e-12`, `1e3`, isotropic and elongated `1000 : 1`; rectangle centres at
//! the pole, in the lobe, at 89.99 degrees, and half vectors exactly at 90 degrees.
//!
//! References: `filter::gaussian` is exact for Beckmann (KHPL16 eq. 15), so its reference is
//! the Beckmann density of `A + 2 Sigma` in double-double, spot-checked against the quadrature
//! convolution `testing::gaussian_reference::beckmann`; `filter::projected` against TK21's map
//! `P = A (I - A)^-1`, `A' = P' (I + P')^-1` in double-double (with the documented eigenvalue
//! clamp at 0.99); the rectangle integral against nested `f64` adaptive quadrature of the
//! density; the GGX proxy against the quadrature peak of the box-filtered lobe (KHPL16 eq.
//! 19); the isotropic filters against their closed forms (TK19 eq. 1, 4, 5, and each
//! preset's documented formula) in `f64`.
//!
//! Run with `--nocapture` to print the error map (the table published in `src/contract.rs`).

mod extremes_support;

use extremes_support::{
    ALPHAS, Dd, DdSym, ErrorMap, F32, F64, beckmann_p22_ref, ggx_p22_ref, integrate_feature,
    max_dd, min_positive, rel_err, unit_eps,
};
use filtered_ndf::math::Real;
use filtered_ndf::testing::linalg::Sym2;
use filtered_ndf::testing::quadrature::{Estimate, Tolerance};
use std::f64::consts::PI;
const FOOTPRINTS: [(f64, &str); 3] = [
    (0.0, "footprint 0"),
    (1e-12, "footprint 1e-12"),
    (1e3, "footprint 1e3"),
];
const GRAZE: f64 = 89.99 * PI / 180.0;

fn r32(x: f64) -> f64 {
    x as f32 as f64
}

/// The largest eigenvalue of a symmetric matrix (the test side's decomposition).
fn l_max(a11: f64, a12: f64, a22: f64) -> f64 {
    Sym2::new(a11, a12, a22).eigen().l1
}

/// Condition number of a symmetric positive semi-definite matrix (double-double entries).
fn cond(a: &DdSym, tau: f64) -> f64 {
    let l1 = l_max(a.a11.f(), a.a12.f(), a.a22.f());
    let det = max_dd(a.det(), tau).f();
    l1 * l1 / det
}

/// First-order sensitivity of a slope density of the matrix `a` (clamp `tau`) at `(x, y)` to
/// relative perturbations of the matrix's entries: `sum_i |d ln P22 / d a_i| |a_i|`, with
/// `ln P22 = -ln pi - ln(det) / 2 - g(q)`, `q = s^T A^-1 s`, `g = 2 ln(1 + q)` (GGX) or `q`
/// (Beckmann), and
/// `d ln det / d a = (a22, -2 a12, a11) / det`,
/// `d q / d a = (y^2 - q a22, -2 x y + 2 q a12, x^2 - q a11) / det`
/// (`a12` counted once as the off-diagonal entry). An entry of relative error `e` moves the
/// density by at most this times `e`, to first order. Where the clamp holds (`det A < tau`),
/// the determinant is `tau`'s and only the quadratic form depends on the entries.
fn p22_sensitivity(a: &DdSym, tau: f64, x: f64, y: f64, beckmann: bool) -> f64 {
    let (a11, a12, a22) = (a.a11.f(), a.a12.f(), a.a22.f());
    let det_a = a.det().f();
    let clamped = det_a < tau;
    let det = det_a.max(tau);
    let q = (a22 * x * x - 2.0 * a12 * x * y + a11 * y * y) / det;
    let dg = if beckmann { 1.0 } else { 2.0 / (1.0 + q) };
    let dlndet = if clamped {
        [0.0; 3]
    } else {
        [a22 / det, -2.0 * a12 / det, a11 / det]
    };
    let dq = [
        (y * y - q * a22) / det,
        (-2.0 * x * y + 2.0 * q * a12) / det,
        (x * x - q * a11) / det,
    ];
    [a11, a12, a22]
        .iter()
        .zip(dlndet.iter().zip(dq))
        .map(|(ai, (dl, dq))| ((-0.5 * dl - dg * dq) * ai).abs())
        .sum()
}

/// Mean of the axis-aligned GGX slope density over `[cx +/- hx] x [cy +/- hy]`, by nested
/// adaptive quadrature with breakpoints around the peak (f64).
fn rect_mean_ref(a: f64, b: f64, cx: f64, cy: f64, hx: f64, hy: f64) -> Estimate {
    let p22 = |x: f64, y: f64| {
        let t = 1.0 + (x / a) * (x / a) + (y / b) * (y / b);
        1.0 / (PI * a * b * t * t)
    };
    // An axis whose half extent is below 1e-7 of the distance scale |c| + width is evaluated
    // at its centre: the mean then differs from the point value by a relative
    // ~ (h / (|c| + w))^2 <= 1e-14 (counted in the estimate), while a quadrature over an
    // interval of a few ulps of `c` (e.g. 1e-12 around 3400) would be dominated by the
    // rounding of its nodes.
    let small = |h: f64, c: f64, w: f64| h <= 1e-7 * (c.abs() + w);
    let (sx, sy) = (small(hx, cx, a), small(hy, cy, b));
    let point = |v: f64| Estimate {
        value: v,
        error: 1e-14 * v,
    };
    if sx && sy {
        return point(p22(cx, cy));
    }
    let tol = Tolerance::relative(1e-13);
    let inner = |y: f64| -> (f64, f64) {
        if sx {
            let v = p22(cx, y);
            (v, 1e-14 * v)
        } else {
            let e = integrate_feature(|x| (p22(x, y), 0.0), cx - hx, cx + hx, 0.0, a, tol);
            (e.value / (2.0 * hx), e.error / (2.0 * hx))
        }
    };
    if sy {
        let (v, e) = inner(cy);
        Estimate {
            value: v,
            error: e + 1e-14 * v,
        }
    } else {
        let e = integrate_feature(inner, cy - hy, cy + hy, 0.0, b, tol);
        Estimate {
            value: e.value / (2.0 * hy),
            error: e.error / (2.0 * hy),
        }
    }
}

/// Each engine preset's published formula (the sources quoted in `filter::presets`), written
/// out per preset in `f64`, independently of `KernelConvention::apply`: `a` the material's
/// GGX `alpha`, `du`, `dv` the world-space normal differences. The crate's input and output
/// contract is applied around it (`alpha` taken in `[0, ALPHA_MAX]`, the result clamped to
/// `[0, ALPHA_MAX]`). A preset without a formula here fails the test.
fn preset_reference(name: &str, a: f64, du: [f64; 3], dv: [f64; 3], alpha_max: f64) -> f64 {
    let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let (uu, uv, vv) = (dot(du, du), dot(du, dv), dot(dv, dv));
    let sum = uu + vv;
    let a = a.clamp(0.0, alpha_max);
    let a2 = a * a;
    // TK19 Listing 2 and its variants: alpha_bar^2 = saturate(alpha^2 + min(k, clamp)).
    let tk = |k: f64, clamp: f64| (a2 + k.min(clamp)).min(1.0).sqrt();
    let out = match name {
        // eq. 4 (Listing 2; O3DE's SpecularAA.azsli verbatim): 2 sigma^2 (|dn_u|^2 + |dn_v|^2),
        // sigma^2 = 0.25, kappa = 0.18.
        "TK19 trace (eq. 4)" | "O3DE" => tk(0.5 * sum, 0.18),
        // eq. 5: sigma^2 (|dn_u|^2 + |dn_v|^2).
        "TK19 average (eq. 5)" => tk(0.25 * sum, 0.18),
        // eq. 1: 2 sigma^2 lambda_max of the Gram matrix of dn_u, dn_v.
        "TK19 max (eq. 1)" => tk(0.5 * l_max(uu, uv, vv), 0.18),
        // TK21 Listing 5: (|dn_u|^2 + |dn_v|^2) / (2 pi).
        "TK21 listing 5" => tk(sum / (2.0 * PI), 0.18),
        // Filament: perceptual roughness floored at 0.045, then 2 * 0.15 * sum clamped at
        // 0.2^2.
        "Filament" => {
            let p = a.sqrt().max(0.045);
            (p.powi(4) + (0.3 * sum).min(0.04)).min(1.0).sqrt()
        }
        // Unity HDRP NormalFiltering: 2 * 0.1 * sum clamped at 0.2^2.
        "Unity HDRP" => tk(0.2 * sum, 0.04),
        // Unity HDRP ProjectedSpaceNormalFiltering: the same kernel added to
        // P = alpha^2 / (1 - alpha^2), saturated there, alpha_bar^2 = P' / (1 + P').
        "Unity HDRP projected" => {
            let p = if a2 < 1.0 {
                a2 / (1.0 - a2)
            } else {
                f64::INFINITY
            };
            let p = (p + (0.2 * sum).min(0.04)).min(1.0);
            (p / (1.0 + p)).sqrt()
        }
        // Godot 4: r^2 = alpha; r'^2 = min(1, r^2 + min(2 * 0.25 * sum, 0.18)); alpha = r'^2.
        "Godot 4" => (a + (0.5 * sum).min(0.18)).min(1.0),
        // Unreal / Babylon (Vlachos 2015): r' = max(r, saturate(max(|dn_u|^2, |dn_v|^2))^0.333)
        // on the perceptual roughness r = sqrt(alpha).
        "Unreal" | "Babylon.js (Vlachos 2015)" => {
            let k = uu.max(vv).min(1.0).powf(0.333);
            a.sqrt().max(k).powi(2)
        }
        // three.js: r' = min(max(r, 0.0525) + max abs component of dn_u, dn_v, 1).
        "three.js" => {
            let g = du
                .iter()
                .chain(dv.iter())
                .fold(0.0_f64, |m, x| m.max(x.abs()));
            (a.sqrt().max(0.0525) + g).min(1.0).powi(2)
        }
        _ => panic!("no reference formula for preset {name}"),
    };
    out.clamp(0.0, alpha_max)
}

/// A base roughness of the filter sweep (entries rounded to the precision).
struct Base {
    alpha: &'static str,
    form: &'static str,
    a: DdSym,
    tau: f64,
    entries: (f64, f64, f64),
}

/// A kernel covariance (entries rounded to the precision).
struct Kernel {
    label: &'static str,
    shape: &'static str,
    s: (f64, f64, f64),
}

macro_rules! sweep {
    ($name:ident, $p:ident, $prec:expr) => {
        mod $name {
            use super::*;
            use filtered_ndf::$p::filter::deferred::{self, Bandwidth};
            use filtered_ndf::$p::{
                ALPHA_MAX, AxisAligned, Beckmann, Covariance, F, Ggx, Ndf, RoughnessMatrix, Vec2,
                Vec3, filter, filter::proxy, filter::rect, filter::presets,
            };

            const PREC: usize = $prec;

            fn r(x: f64) -> f64 {
                F::from_f64(x).to_f64()
            }
            fn f(x: f64) -> F {
                F::from_f64(x)
            }

            fn bases() -> Vec<Base> {
                let mut out = Vec::new();
                for &(alpha, label) in &ALPHAS {
                    let a2 = r(alpha * alpha);
                    out.push(Base {
                        alpha: label,
                        form: "isotropic",
                        a: DdSym::new(a2, 0.0, a2),
                        tau: 0.0,
                        entries: (a2, 0.0, a2),
                    });
                    let l1 = (1e6 * alpha * alpha).min(0.99e8);
                    let (c, s) = (0.3_f64.cos(), 0.3_f64.sin());
                    let l2 = alpha * alpha;
                    let e = (
                        r(l1 * c * c + l2 * s * s),
                        r((l1 - l2) * c * s),
                        r(l1 * s * s + l2 * c * c),
                    );
                    out.push(Base {
                        alpha: label,
                        form: "cond 1e6",
                        a: DdSym::new(e.0, e.1, e.2),
                        tau: 0.0,
                        entries: e,
                    });
                    let (n11, n12, n22) = (a2, r(2.0 * alpha * alpha), r(4.0 * alpha * alpha));
                    let tau = r((0.1 * alpha * alpha).powi(2));
                    if RoughnessMatrix::new_with_det_clamp(f(n11), f(n12), f(n22), f(tau)).is_ok() {
                        out.push(Base {
                            alpha: label,
                            form: "singular + tau",
                            a: DdSym::new(n11, n12, n22),
                            tau,
                            entries: (n11, n12, n22),
                        });
                    }
                }
                out
            }

            fn kernels() -> Vec<Kernel> {
                let mut out = Vec::new();
                for &(fp, label) in &FOOTPRINTS {
                    // Sigma = sigma^2 (u u^T + v v^T), sigma = 1/2 (KHPL16, TK19).
                    let v = 0.25 * fp * fp;
                    out.push(Kernel {
                        label,
                        shape: "kernel isotropic",
                        s: (r(v), 0.0, r(v)),
                    });
                    let (c, s) = (0.4_f64.cos(), 0.4_f64.sin());
                    let (u, w) = ([fp * c, fp * s], [-1e-3 * fp * s, 1e-3 * fp * c]);
                    out.push(Kernel {
                        label,
                        shape: "kernel 1000:1",
                        s: (
                            r(0.25 * (u[0] * u[0] + w[0] * w[0])),
                            r(0.25 * (u[0] * u[1] + w[0] * w[1])),
                            r(0.25 * (u[1] * u[1] + w[1] * w[1])),
                        ),
                    });
                }
                out
            }

            /// The reference lobe of a filtered matrix `m` under the clamp `tau`: `a` itself
            /// where its determinant reaches `tau`, else the clamped matrix `A_c` of
            /// determinant `tau` with the result's pivot (`RoughnessMatrix` docs: `A + t I`
            /// with the pivot rounded to F, checked in `tests/matrix_representations.rs`).
            fn clamp_ref(a: DdSym, tau: f64, m: &RoughnessMatrix) -> DdSym {
                if a.det().f() >= tau {
                    a
                } else {
                    DdSym::ldl(m.clamped_entries().0.to_f64(), a.a12.f(), tau)
                }
            }

            fn matrix(b: &Base) -> RoughnessMatrix {
                let (a11, a12, a22) = b.entries;
                RoughnessMatrix::new_with_det_clamp(f(a11), f(a12), f(a22), f(b.tau)).unwrap()
            }

            /// Evaluates the filtered matrix `m` against the reference matrix `aref` (with clamp
            /// `tau`) through the GGX and Beckmann densities at the peak and one lobe width
            /// along each axis.
            #[allow(clippy::too_many_arguments)]
            fn compare(
                map: &mut ErrorMap,
                kernel: &str,
                beckmann_too: bool,
                regions: &[&str],
                m: RoughnessMatrix,
                aref: &DdSym,
                tau: f64,
                tol_of: &dyn Fn(f64) -> f64,
            ) {
                let floor = min_positive(PREC);
                let (w1, w2) = (aref.a11.f().sqrt(), aref.a22.f().sqrt());
                for (x, y) in [(0.0, 0.0), (w1, 0.0), (0.0, w2)] {
                    let s = Vec2::new(f(x), f(y));
                    let (sx, sy) = (s.x.to_f64(), s.y.to_f64());
                    let g = Ggx::new(m).p22(s).to_f64();
                    let gr = ggx_p22_ref(aref, tau, sx, sy);
                    map.require(g.is_finite() && g >= 0.0, || format!("{kernel}: GGX p22 {g}"));
                    let tol = tol_of(p22_sensitivity(aref, tau, sx, sy, false));
                    map.record(kernel, regions, PREC, rel_err(g, gr, floor), tol, || {
                        format!("GGX at ({sx:e}, {sy:e}): {g:e} vs {gr:e}")
                    });
                    if beckmann_too {
                        let bk = Beckmann::new(m).p22(s).to_f64();
                        let br = beckmann_p22_ref(aref, tau, sx, sy);
                        map.require(bk.is_finite() && bk >= 0.0, || format!("{kernel}: Beckmann p22 {bk}"));
                        let tol = tol_of(p22_sensitivity(aref, tau, sx, sy, true));
                        map.record(kernel, regions, PREC, rel_err(bk, br, floor), tol, || {
                            format!("Beckmann at ({sx:e}, {sy:e}): {bk:e} vs {br:e}")
                        });
                    }
                }
            }

            pub fn gaussian(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                for b in bases() {
                    for k in kernels() {
                        let sig = DdSym::new(k.s.0, k.s.1, k.s.2);
                        let aref = b.a.add(&sig.scale(2.0));
                        let tau = max_dd(b.a.det(), b.tau).f();
                        let m = filter::gaussian(matrix(&b), Covariance::new(f(k.s.0), f(k.s.1), f(k.s.2)));
                        let aref = clamp_ref(aref, tau, &m);
                        // Tolerance: each filtered entry carries a relative error of at most
                        // eps (A + 2 Sigma rounded once, u = eps / 2; the matrix's determinant
                        // and inverse formed from the entries, another u in first order), which
                        // the density amplifies by its sensitivity S to the entries
                        // (`p22_sensitivity`: about kappa / 2 at the peak, where an ill-
                        // conditioned determinant cancels), plus 16 eps for the density's own
                        // operations; doubled for the second order: (2 S + 32) eps.
                        let tol_of = |sens: f64| (2.0 * sens + 32.0) * eps;
                        compare(map, "gaussian", true, &[b.alpha, b.form, k.label, k.shape], m, &aref, tau, &tol_of);
                    }
                }
            }

            /// TK21's projected-space filter in double-double, with the eigenvalue clamp at
            /// 0.99 of `filter::projected` when both eigenvalues exceed it (the mixed case has
            /// no exact reference here and is checked for monotonicity only).
            fn projected_ref(b: &Base, sig: &DdSym) -> Option<(DdSym, f64)> {
                let l1 = l_max(b.a.a11.f(), b.a.a12.f(), b.a.a22.f());
                let l2 = max_dd(b.a.det(), 0.0).f() / l1;
                let cap = filter::PROJECTED_EIGEN_MAX.to_f64();
                let (ac, e) = if l1 < cap {
                    (b.a, DdSym::new(0.0, 0.0, 0.0))
                } else if l2 >= cap {
                    (DdSym::new(cap, 0.0, cap), b.a.add(&DdSym::new(-cap, 0.0, -cap)))
                } else {
                    return None;
                };
                let ima = ac.identity_minus();
                let p = ac.mul_sym(&ima.adj()).div(ima.det());
                let q = p.add(&sig.scale(2.0));
                let ipq = q.identity_plus();
                let bm = q.mul_sym(&ipq.adj()).div(ipq.det());
                Some((bm.add(&e), cond(&q, 0.0)))
            }

            pub fn projected(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                for b in bases() {
                    for k in kernels() {
                        let sig = DdSym::new(k.s.0, k.s.1, k.s.2);
                        let m = filter::projected(matrix(&b), Covariance::new(f(k.s.0), f(k.s.1), f(k.s.2)));
                        let regions = [b.alpha, b.form, k.label, k.shape];
                        let tau = max_dd(b.a.det(), b.tau).f();
                        match projected_ref(&b, &sig) {
                            Some((aref, cond_q)) => {
                                let aref = clamp_ref(aref, tau, &m);
                                // Tolerance: as gaussian (entries rounded to F, 64 (1 + kappa)
                                // eps), times 1 / (1 - lambda_max) for the map P = A (I - A)^-1,
                                // whose condition grows towards the clamp at 0.99, plus the
                                // condition of the projected-space sum P' = P + 2 Sigma: it is
                                // formed in F and its determinant enters A' (an elongated 1e3
                                // kernel makes it ~1e6, the f32 result then carries ~1e-3).
                                let l1 = l_max(b.a.a11.f(), b.a.a12.f(), b.a.a22.f());
                                let amp = 1.0 / (1.0 - l1.min(0.99));
                                let tol = 64.0 * (1.0 + cond(&aref, tau) + cond_q) * amp * eps;
                                compare(map, "projected", false, &regions, m, &aref, tau, &|_| tol);
                            }
                            None => {
                                // Mixed eigenvalues around the clamp: A' >= A (filtering never
                                // sharpens), so the peak may not rise above the unfiltered one.
                                let peak = Ggx::new(m).p22(Vec2::ZERO).to_f64();
                                let base = Ggx::new(matrix(&b)).p22(Vec2::ZERO).to_f64();
                                map.require(peak.is_finite() && peak <= base * (1.0 + 64.0 * eps), || {
                                    format!("projected {} {}: peak {peak:e} > unfiltered {base:e}", b.alpha, b.form)
                                });
                            }
                        }
                    }
                }
            }

            /// Spot checks of `filter::gaussian` + Beckmann against the quadrature convolution
            /// (no closed form used): isotropic alpha 1e-4 and 1, footprints 1e-12 and 1e3, at
            /// the peak.
            pub fn gaussian_quadrature(map: &mut ErrorMap) {
                use filtered_ndf::f64 as d;
                let eps = unit_eps(PREC);
                for &(alpha, label) in &ALPHAS[1..3] {
                    let a = r32(alpha);
                    for &(fp, flabel) in &FOOTPRINTS[1..] {
                        let v = r32(0.25 * fp * fp);
                        let reference = filtered_ndf::testing::gaussian_reference::beckmann(
                            d::Isotropic::new(a).unwrap(),
                            d::Covariance::new(v, 0.0, v),
                            d::Vec2::ZERO,
                            Tolerance::relative(1e-11),
                        );
                        let m = filter::gaussian(
                            filtered_ndf::$p::Isotropic::new(f(a)).unwrap(),
                            Covariance::new(f(v), 0.0, f(v)),
                        );
                        let got = Beckmann::new(m).p22(Vec2::ZERO).to_f64();
                        // Tolerance: the quadrature's own error estimate (required to meet its
                        // goal of 1e-11 relative), four times over for an estimate's
                        // unreliability, plus 64 eps for the kernel and the density.
                        let qerr = reference.error / reference.value.abs();
                        map.require(qerr <= 1e-11, || {
                            format!("{label} {flabel}: quadrature estimate {qerr:e} above its goal")
                        });
                        let tol = 4.0 * qerr.max(1e-16) + 64.0 * eps;
                        map.record(
                            "gaussian",
                            &[label, flabel, "kernel isotropic", "quadrature (gaussian_reference)"],
                            PREC,
                            rel_err(got, reference.value, 0.0),
                            tol,
                            || format!("{label} {flabel}: {got:e} vs quadrature {:e} +/- {:e}", reference.value, reference.error),
                        );
                    }
                }
            }

            pub fn rect(map: &mut ErrorMap, refs: &mut Vec<Estimate>, use_refs: bool) {
                let eps = unit_eps(PREC);
                let floor = min_positive(PREC);
                let mut idx = 0;
                for &(alpha, label) in &ALPHAS {
                    for (form, ax, ay) in [("isotropic", alpha, alpha), ("axis 1:3", alpha, 3.0 * alpha)] {
                        let (ax, ay) = (r32(ax), r32(ay));
                        let rough = AxisAligned::new(f(ax), f(ay)).unwrap();
                        for &(fp, flabel) in &FOOTPRINTS {
                            for (shape, hx, hy) in [("square", fp, fp), ("1000:1", fp, 1e-3 * fp)] {
                                let (hx, hy) = (r32(hx), r32(hy));
                                let half = Vec2::new(f(hx), f(hy));
                                let hs: [(&str, [f64; 3]); 4] = [
                                    ("pole", [0.0, 0.0, 1.0]),
                                    ("lobe", [0.7 * ax, -1.3 * ay, 1.0]),
                                    ("89.99 deg", [GRAZE.sin() * 0.6, GRAZE.sin() * 0.8, GRAZE.cos()]),
                                    ("90 deg", [0.6, 0.8, 0.0]),
                                ];
                                for (dir, h) in hs {
                                    let hn = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
                                    let h = [r32(h[0] / hn), r32(h[1] / hn), r32(h[2] / hn)];
                                    let hv = Vec3::new(f(h[0]), f(h[1]), f(h[2]));
                                    let regions = [label, form, flabel, shape, dir];
                                    let got = rect::d_rect(rough, hv, half).to_f64();
                                    map.require(got.is_finite() && got >= 0.0, || {
                                        format!("d_rect {label} {form} {flabel} {dir}: {got}")
                                    });
                                    if h[2] <= 0.0 {
                                        map.require(got == 0.0, || format!("d_rect at 90 deg: {got}"));
                                        map.record("d_rect", &regions, PREC, 0.0, 0.0, String::new);
                                        continue;
                                    }
                                    let (cx, cy) = (-h[0] / h[2], -h[1] / h[2]);
                                    let mean = if use_refs {
                                        refs[idx]
                                    } else {
                                        let v = rect_mean_ref(ax, ay, cx, cy, hx, hy);
                                        refs.push(v);
                                        v
                                    };
                                    idx += 1;
                                    let reference = mean.value / (h[2] * h[2] * h[2] * h[2]);
                                    // Tolerance: the module documents the f64 value rounded
                                    // once in f32 (16 eps also covers GGX's own D, a few ulps,
                                    // for a zero box) and at most 8e-14 in f64 (a scan against
                                    // 80-digit arithmetic): 1e-13; plus four times the
                                    // reference's own estimate (its goal 1e-13), both required.
                                    let qerr = |e: &Estimate| e.error / e.value.abs().max(floor);
                                    map.require(qerr(&mean) <= 1e-12, || format!("rect reference {mean:?}"));
                                    let doc = if PREC == F64 { 1e-13 } else { 16.0 * eps };
                                    let tol = doc + 4.0 * qerr(&mean);
                                    map.record("d_rect", &regions, PREC, rel_err(got, reference, floor), tol, || {
                                        format!("{label} {form} {flabel} {shape} {dir}: {got:e} vs {reference:e}")
                                    });
                                    // p22_rect at the centre rounded to f32 (its own reference).
                                    let (px, py) = (r32(cx), r32(cy));
                                    let pmean = if use_refs {
                                        refs[idx]
                                    } else {
                                        let v = rect_mean_ref(ax, ay, px, py, hx, hy);
                                        refs.push(v);
                                        v
                                    };
                                    idx += 1;
                                    let got = rect::p22_rect(rough, Vec2::new(f(px), f(py)), half).to_f64();
                                    map.require(qerr(&pmean) <= 1e-12, || format!("rect reference {pmean:?}"));
                                    let tol = doc + 4.0 * qerr(&pmean);
                                    let pmean = pmean.value;
                                    map.record_density("p22_rect", &regions, PREC, (got, pmean, floor), tol, || {
                                        format!("{label} {form} {flabel} {shape} {dir}: {got:e} vs {pmean:e}")
                                    });
                                }
                            }
                        }
                    }
                }
            }

            pub fn proxy(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                for &(alpha, label) in &ALPHAS {
                    let a = r32(alpha);
                    for &(fp, flabel) in &FOOTPRINTS {
                        let h = r32(fp);
                        // KHPL16 eq. 19: the GGX of roughness alpha' has the peak of the lobe
                        // box-filtered over [-H, H]^2: 1 / (pi alpha'^2) = mean (quadrature).
                        let mean = rect_mean_ref(a, a, 0.0, 0.0, h, h).value;
                        let reference = 1.0 / (PI * mean).sqrt();
                        let got = proxy::effective_alpha(f(a), f(h)).to_f64();
                        // Tolerance: a hypot, an atan, a square root: 16 eps; plus the
                        // reference's quadrature (goal 1e-13 relative on the mean, halved by the
                        // square root) with a factor 20 for its estimate being an estimate:
                        // 1e-12 (f64 measures 2.6e-16 worst).
                        map.record("effective_alpha", &[label, flabel], PREC, rel_err(got, reference, 0.0), 16.0 * eps + 1e-12, || {
                            format!("{label} H {h:e}: {got:e} vs {reference:e}")
                        });
                        let px = proxy::proxy(AxisAligned::new(f(a), f(a)).unwrap(), Vec2::new(f(h), f(h)));
                        let got = px.alpha().x.to_f64();
                        map.record("proxy", &[label, flabel], PREC, rel_err(got, reference, 0.0), 16.0 * eps + 1e-12, || {
                            format!("proxy {label} H {h:e}: {got:e} vs {reference:e}")
                        });
                        let got = proxy::effective_alpha_simple(f(a), f(h)).to_f64();
                        let reference = Dd::prod(a, a).add(Dd::prod(h, h)).sqrt().f();
                        map.record("effective_alpha_simple", &[label, flabel], PREC, rel_err(got, reference, 0.0), 4.0 * eps, || {
                            format!("simple {label} H {h:e}: {got:e} vs {reference:e}")
                        });
                    }
                }
            }

            pub fn isotropic(map: &mut ErrorMap) {
                let eps = unit_eps(PREC);
                let kappa = deferred::KAPPA.to_f64();
                for &(alpha, label) in &ALPHAS {
                    let a = r(alpha);
                    for &(fp, flabel) in &FOOTPRINTS {
                        for (shape, s11, s22) in [("kernel isotropic", fp * fp, fp * fp), ("kernel 1000:1", fp * fp, 1e-6 * fp * fp)] {
                            let (s11, s22) = (r(0.25 * s11), r(0.25 * s22));
                            let sigma = Covariance::new(f(s11), 0.0, f(s22));
                            for (bw, kernel) in [
                                (Bandwidth::Max, 2.0 * s11.max(s22)),
                                (Bandwidth::Trace, 2.0 * (s11 + s22)),
                                (Bandwidth::Average, s11 + s22),
                            ] {
                                let got = deferred::filtered_alpha(f(a), &sigma, bw, deferred::KAPPA).to_f64();
                                let reference = (a * a + kernel.min(kappa)).min(1.0).sqrt();
                                // Tolerance: a sum, a min and a square root: 8 eps.
                                map.record("filtered_alpha", &[label, flabel, shape], PREC, rel_err(got, reference, 0.0), 8.0 * eps, || {
                                    format!("{bw:?} {label} {flabel} {shape}: {got:e} vs {reference:e}")
                                });
                            }
                        }
                    }
                }
                // Every preset on world-space normal differences of size fp, against its
                // published formula written out per preset (`preset_reference`), not through
                // `KernelConvention`'s generic steps.
                let alpha_max = ALPHA_MAX.to_f64();
                for (name, conv) in presets::ALL {
                    for &(alpha, label) in &ALPHAS {
                        let a = r(alpha);
                        for &(fp, flabel) in &FOOTPRINTS {
                            let du = [r(0.6 * fp), r(0.8 * fp), 0.0];
                            let dv = [0.0, r(0.6e-3 * fp), r(-0.8e-3 * fp)];
                            let got = conv
                                .apply(f(a), Vec3::new(f(du[0]), f(du[1]), f(du[2])), Vec3::new(f(dv[0]), f(dv[1]), f(dv[2])))
                                .to_f64();
                            let reference = preset_reference(name, a, du, dv, alpha_max);
                            // Tolerance: each formula is a handful of operations; the
                            // exponent 0.333 of Unreal/Babylon adds the conditioning of
                            // powf, |0.333 ln n| eps (n = 1e-24: 18 eps), and the presets'
                            // constants rounded to F (half an ulp each). 64 eps.
                            map.record("presets", &[label, flabel, name], PREC, rel_err(got, reference, 0.0), 64.0 * eps, || {
                                format!("{name} {label} {flabel}: {got:e} vs {reference:e}")
                            });
                        }
                    }
                }
            }
        }
    };
}

sweep!(p32, f32, F32);
sweep!(p64, f64, F64);

#[test]
fn extremes_filter_error_map() {
    let mut g = ErrorMap::new(
        "filter::gaussian and filter::projected (through p22): worst relative error, f32 / f64",
    );
    p32::gaussian(&mut g);
    p64::gaussian(&mut g);
    p32::gaussian_quadrature(&mut g);
    p64::gaussian_quadrature(&mut g);
    p32::projected(&mut g);
    p64::projected(&mut g);
    let mut rect = ErrorMap::new("ggx_rect: worst relative error, f32 / f64");
    let mut refs = Vec::new();
    p32::rect(&mut rect, &mut refs, false);
    p64::rect(&mut rect, &mut refs, true);
    let mut iso = ErrorMap::new("ggx_proxy and isotropic filters: worst relative error, f32 / f64");
    p32::proxy(&mut iso);
    p64::proxy(&mut iso);
    p32::isotropic(&mut iso);
    p64::isotropic(&mut iso);
    let mut failed = 0;
    for m in [&g, &rect, &iso] {
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| m.finish())).is_err() {
            failed += 1;
        }
    }
    assert_eq!(failed, 0, "see the FAIL lines above");
}
