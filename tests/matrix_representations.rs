//! The one representation of `RoughnessMatrix` against double-double references
//! (`tests/extremes_support`, which never calls the code under test): the `L D L^T` form of
//! the evaluated matrix `A_c`, its pivot `p` and determinant `c = max(det A, tau)`.
//!
//! Cases: rotated matrices of nominal condition number 1 to `1e12`, entries rounded to the
//! precision (their true condition number is computed from the rounded entries), each without
//! and with the determinant clamp (`tau = 1.5 det A`, and at the rounding level for a matrix
//! whose rounded determinant is `<= 0`). For each case, three claims of the type docs:
//!
//! 1. `c = max(det A, tau)`: exactly `tau` when the clamp is active; otherwise `det A` of the
//!    entries as stored, within `eps_f64 / 2` (`f32`: exact products, one rounding) or
//!    `16 eps` (`f64`, `det_wide`'s bound).
//! 2. The pivot: `a11` exactly without the clamp; else `a11 + t`, `t` the root of
//!    `det(A + t I) = tau` (here in double-double), within its rounding to the precision
//!    (`eps / 2` relative) plus `48 eps_f64` (the `f64` evaluation of `t`: `tau - det A` carries
//!    up to `32 eps_f64` from `det A`, the root a few more).
//! 3. The evaluation of that matrix: `s^T A_c^-1 s`, `w^T A_c w`, `sqrt(c)`, Beckmann's and
//!    GGX's `D`, against the same forms of `[[p, a12], [a12, (a12^2 + c) / p]]` in
//!    double-double. Tolerances (relative):
//!    - `f32`: the forms are evaluated in `f64` with exact products; about ten `f64` roundings
//!      precede the one rounding to `f32`: `eps_f32 / 2 + 8 eps_f64`, at every condition
//!      number (a representation that rounds a product or the determinant in `f32`, or
//!      rotates `s` into an eigenbasis in `f32`, fails by orders of magnitude beyond
//!      condition `1e3`).
//!    - `f64`: `u = p s_y - a12 s_x` cancels; its rounding error is at most
//!      `eps |s| sqrt(lambda_max p) / 2` and `|u| <= sqrt(p c q)`, so its share of the form is
//!      at most `sqrt(kappa) eps`; plus `c`'s `16 eps` and a handful of roundings:
//!      `(sqrt(kappa) + 24) eps`. `w^T A_c w` the same with `u = p w_x + a12 w_y`.
//!    - `sqrt(c)`: half of `c`'s error plus one rounding. Densities: GGX `2 tol_q + 16 eps`
//!      (the square of `1 + q`, then the normalisation's roundings), Beckmann
//!      `(tol_q + eps / 2) (1 + x) + 16 eps` (`x = q / m_z^2` with `m_z^2` rounded in the
//!      precision; `exp` turns a relative error `e` of `x` into `x e`), and
//!      past the normal range of `exp(-x)`, where `exp(-(x - ln k))` is evaluated, another
//!      `eps / 2 (|ln k| + |ln D|)` for the roundings of `ln k` and of the difference.
//!
//! Slopes are drawn half in a box of a few lobe widths, half in the lobe's whitened frame
//! (`s = R diag(sqrt(l1), sqrt(l2)) g`), where both eigen-components weigh alike: the worst
//! case of the cancellation in `f64`. Also Beckmann's far tail, where `D` leaves the normal
//! range and the evaluation switches to `exp(-(x - ln k))` and, beyond the subnormals, to an
//! exact 0.

mod extremes_support;

use extremes_support::{Dd, DdSym};
use filtered_ndf::math::Real;
use filtered_ndf::testing::rng::SplitMix64;

/// One test matrix: entries rounded to the precision under test.
struct Case {
    entries: (f64, f64, f64),
    tau: f64,
    /// Nominal eigen-frame of the rotation (for the whitened slopes).
    rot: (f64, f64),
    l: (f64, f64),
}

/// Rotated matrices with eigenvalues `l, l / cond` (`l` log-uniform, `l / cond >= 4e-16`) on a
/// log grid of conditions up to `1e12`, rounded through `round`; each case once with
/// `tau = 0` (skipped if the rounded determinant is `<= 0`) and once with the clamp active.
fn cases(round: impl Fn(f64) -> f64, eps: f64) -> Vec<Case> {
    let mut rng = SplitMix64(0x1d1);
    let conds: Vec<f64> = (0..=48).map(|i| 10f64.powf(i as f64 / 4.0)).collect();
    let mut out = Vec::new();
    for &cond in &conds {
        for _ in 0..12 {
            let l = rng.log_uniform((4e-16 * cond).max(1e-8), 1.0);
            let t = std::f64::consts::PI * rng.uniform();
            let (c, s) = (t.cos(), t.sin());
            let (l1, l2) = (l, l / cond);
            let (a11, a12, a22) = (
                round(c * c * l1 + s * s * l2),
                round(c * s * (l1 - l2)),
                round(s * s * l1 + c * c * l2),
            );
            let det = DdSym::new(a11, a12, a22).det().f();
            let case = |tau| Case {
                entries: (a11, a12, a22),
                tau,
                rot: (c, s),
                l: (l1, l2),
            };
            if det > 0.0 {
                out.push(case(0.0));
                out.push(case(round(1.5 * det)));
            } else {
                // Singular by rounding: only with a clamp at the rounding level.
                out.push(case(round(4.0 * eps * a11 * a22)));
            }
        }
    }
    out
}

/// `t > 0` with `det(A + t I) = tau`, in double-double.
fn shift(a: &DdSym, tau: f64) -> Dd {
    let gap = Dd::from(tau).sub(a.det());
    let h = a.a11.add(a.a22).mul(Dd::from(0.5));
    gap.div(h.add(h.mul(h).add(gap).sqrt()))
}

macro_rules! representation {
    ($name:ident, $prec:ident, $t:ty) => {
        #[test]
        fn $name() {
            use filtered_ndf::$prec::{Beckmann, Ggx, Ndf, Roughness, RoughnessMatrix, Vec2, Vec3};
            let eps = <$t>::EPSILON as f64;
            let eps64 = f64::EPSILON;
            let f = |x: f64| <$t as Real>::from_f64(x);
            let wide = std::mem::size_of::<$t>() == 4;
            let (mut worst_cond, mut n_clamped) = (0.0f64, 0);
            let mut worst = std::collections::BTreeMap::<&str, f64>::new();
            let mut rng = SplitMix64(0x5eed);
            // Relative error, measured against the smallest normal number below it (a
            // subnormal result carries fewer bits: its error counts absolutely).
            let floor = <$t>::MIN_POSITIVE as f64;
            for c in cases(|x| f(x).to_f64(), eps) {
                let (a11, a12, a22) = c.entries;
                let a = DdSym::new(a11, a12, a22);
                let m = RoughnessMatrix::new_with_det_clamp(f(a11), f(a12), f(a22), f(c.tau))
                    .unwrap_or_else(|e| panic!("{:?} tau {}: {e:?}", c.entries, c.tau));
                let det = a.det();
                let clamped = det.f() < c.tau;
                n_clamped += usize::from(clamped);
                let mut check = |got: f64, want: f64, tol: f64, what: &'static str| {
                    let err = (got - want).abs() / want.abs().max(floor);
                    assert!(
                        err <= tol,
                        "{what}: entries {:?} tau {:e} (clamped {clamped}): got {got:e}, \
                         want {want:e} (error {err:.2e}, tolerance {tol:.2e})",
                        c.entries,
                        c.tau,
                    );
                    let w = worst.entry(what).or_default();
                    *w = w.max(err / tol);
                };
                // 1. c = max(det A, tau).
                let cc = if clamped { Dd::from(c.tau) } else { det };
                let tol_c = if wide { 0.5 * eps64 } else { 16.0 * eps };
                if clamped {
                    assert_eq!(m.clamped_det(), c.tau, "{:?}", c.entries);
                } else {
                    check(m.clamped_det(), det.f(), tol_c, "c = det A");
                }
                // 2. The pivot.
                let p = m.clamped_entries().0.to_f64();
                if clamped {
                    let want = a.a11.add(shift(&a, c.tau)).f();
                    check(p, want, 0.5 * eps + 48.0 * eps64, "pivot a11 + t");
                } else {
                    assert_eq!(p, a11, "{:?}", c.entries);
                }
                // 3. The evaluation of [[p, a12], [a12, (a12^2 + c) / p]].
                let ac = DdSym::ldl(p, a12, cc.f());
                let (q11, q22) = (ac.a11.f(), ac.a22.f());
                let l1 = 0.5 * (q11 + q22) + (0.5 * (q11 - q22)).hypot(a12);
                let kappa = l1 * l1 / cc.f();
                worst_cond = worst_cond.max(kappa);
                let tol_q = if wide {
                    0.5 * eps + 8.0 * eps64
                } else {
                    (kappa.sqrt() + 24.0) * eps
                };
                let sqrt_c = cc.sqrt().f();
                check(
                    m.sqrt_det().to_f64(),
                    sqrt_c,
                    0.5 * tol_c + 0.5 * eps + 2.0 * eps64,
                    "sqrt_det",
                );
                for k in 0..8 {
                    let (x, y) = if k % 2 == 0 {
                        // A box of a few lobe widths.
                        let w = (a11 + a22).sqrt();
                        (
                            w * 3.0 * (rng.uniform() - 0.5),
                            w * 3.0 * (rng.uniform() - 0.5),
                        )
                    } else {
                        // The whitened frame: both eigen-components weigh alike.
                        let (g1, g2) = (3.0 * rng.normal(), 3.0 * rng.normal());
                        let (u1, u2) = (g1 * c.l.0.sqrt(), g2 * c.l.1.sqrt());
                        let (cs, sn) = c.rot;
                        (cs * u1 - sn * u2, sn * u1 + cs * u2)
                    };
                    let s = Vec2::new(f(x), f(y));
                    let (x, y) = (s.x.to_f64(), s.y.to_f64());
                    let q = ac.adj_quadratic(x, y).div(cc);
                    check(m.inv_quadratic(s).to_f64(), q.f(), tol_q, "inv_quadratic");
                    check(
                        m.quadratic(s).to_f64(),
                        ac.quadratic(x, y).f(),
                        tol_q,
                        "quadratic",
                    );
                    // Densities at the micronormal of slope s: D = P22 / m_z^4, exactly.
                    let h = Vec3::new(-s.x, -s.y, 1.0).normalize();
                    let (hx, hy, hz) = (h.x.to_f64(), h.y.to_f64(), h.z.to_f64());
                    let z2 = Dd::prod(hz, hz);
                    let xq = ac.adj_quadratic(hx, hy).div(cc).div(z2).f();
                    let norm = std::f64::consts::PI * sqrt_c * z2.f() * z2.f();
                    // In log space: exp(-x) alone may leave the normal range.
                    let beckmann = (-xq - norm.ln()).exp();
                    // The exponent `x = q / m_z^2` carries the form's error and the rounding of
                    // `m_z^2` in the precision (eps / 2); exp turns its absolute error
                    // `x (tol_q + eps / 2)` into a relative one.
                    // Past the normal range of exp(-x) (`x >= -MIN_EXP ln 2`) the code
                    // evaluates exp(-(x - ln k)), `k = 1 / norm`: the roundings of `ln k` and
                    // of the difference add `eps / 2` of `|ln k|` and of `|ln D|`.
                    let far = xq >= 0.99 * -(<$t>::MIN_EXP as f64) * std::f64::consts::LN_2;
                    let far_tol = if far {
                        0.5 * eps * (norm.ln().abs() + (xq + norm.ln()).abs())
                    } else {
                        0.0
                    };
                    let tol_d = (tol_q + 0.5 * eps) * (1.0 + xq) + far_tol + 16.0 * eps;
                    check(
                        Beckmann::new(m).d(h).to_f64(),
                        beckmann,
                        tol_d,
                        "Beckmann D",
                    );
                    let ggx = 1.0 / (norm * (1.0 + xq) * (1.0 + xq));
                    check(
                        Ggx::new(m).d(h).to_f64(),
                        ggx,
                        2.0 * tol_q + 16.0 * eps,
                        "GGX D",
                    );
                }
            }
            assert!(
                n_clamped > 100 && worst_cond > 1e10,
                "{n_clamped} {worst_cond:e}"
            );
            println!(
                "{}: worst error / tolerance {worst:.3?} (conditions up to {worst_cond:.1e}, \
                 {n_clamped} clamped)",
                stringify!($prec)
            );
        }
    };
}

representation!(f32_matrices_match_double_double, f32, f32);
representation!(f64_matrices_match_double_double, f64, f64);

macro_rules! far_tail {
    ($name:ident, $prec:ident, $t:ty) => {
        /// Beckmann's D from the peak to beyond the subnormals, against
        /// `exp(-x - ln(pi alpha^2 m_z^4))` in f64 (the micronormal rounded to the precision
        /// first). Where the reference is normal: relative error within `(16 + 4 x) eps`
        /// (the exponent's own rounding, amplified by `exp`); in the subnormal range, that plus
        /// one subnormal step; below half the smallest subnormal: exactly 0.
        #[test]
        fn $name() {
            use filtered_ndf::$prec::{Beckmann, Ndf, Vec3};
            let eps = <$t>::EPSILON as f64;
            // The smallest normal and subnormal numbers of the precision, and ln(min_sub / 2)
            // computed as a sum (min_sub / 2 itself is 0 in f64).
            let (min_normal, min_sub) = (<$t>::MIN_POSITIVE as f64, {
                let m = <$t>::MIN_POSITIVE as f64;
                m * eps
            });
            let half_sub_ln = min_sub.ln() - std::f64::consts::LN_2;
            let mut counts = [0usize; 3];
            for alpha in [1e-4, 1e-2, 0.3, 2.0] {
                let b = Beckmann::isotropic(alpha as $t).unwrap();
                let a2 = (alpha as $t as f64).powi(2);
                for i in 0..4000 {
                    // Polar angles up to 89.99 degrees, dense in the exponent.
                    let t = (89.99f64 * (i as f64 / 4000.0).sqrt()).to_radians();
                    let h = Vec3::new(t.sin() as $t, 0.0, t.cos() as $t);
                    let (hx, hz) = (h.x as f64, h.z as f64);
                    let x = (hx * hx) / (a2 * hz * hz);
                    let ln_k = (std::f64::consts::PI * a2).ln() + 4.0 * hz.ln();
                    let le = -x - ln_k;
                    let want = le.exp();
                    let got = b.d(h) as f64;
                    let tol = (16.0 + 4.0 * x) * eps;
                    if want >= min_normal {
                        counts[0] += 1;
                        assert!(
                            (got - want).abs() <= tol * want,
                            "alpha {alpha} theta {t}: {got:e} vs {want:e}"
                        );
                    } else if le > half_sub_ln + 1e-9 {
                        counts[1] += 1;
                        assert!(
                            (got - want).abs() <= tol * want + min_sub,
                            "alpha {alpha} theta {t}: subnormal {got:e} vs {want:e}"
                        );
                    } else if le < half_sub_ln - 1e-9 {
                        counts[2] += 1;
                        assert_eq!(got, 0.0, "alpha {alpha} theta {t}: {got:e} vs {want:e}");
                    }
                }
            }
            // Every regime was reached.
            assert!(counts.iter().all(|&n| n > 0), "{counts:?}");
        }
    };
}

far_tail!(f32_beckmann_far_tail, f32, f32);
far_tail!(f64_beckmann_far_tail, f64, f64);
