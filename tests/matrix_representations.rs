//! The two representations of `RoughnessMatrix` against double-double references
//! (`tests/extremes_support`, which never calls the code under test): the LDL form (f32:
//! whenever the determinant is positive; f64: below `cond 16`) and the eigenbasis otherwise.
//! Condition numbers from 1 to 400 straddle the f64 threshold densely, and f32 goes on to
//! `1e6`, where its LDL form must stay exact to a few ulps; every case is checked with and
//! without the determinant clamp, in both precisions. Also Beckmann's far tail, where `D` leaves
//! the normal range and the evaluation switches to `exp(-(x - ln k))` and, beyond the
//! subnormals, to an exact 0.

mod extremes_support;

use extremes_support::{Dd, DdSym, max_dd};
use filtered_ndf::math::Real;
use filtered_ndf::testing::rng::SplitMix64;

/// One test matrix: entries rounded to the precision under test, kept in double-double.
struct Case {
    a: DdSym,
    tau: f64,
    cond: f64,
    entries: (f64, f64, f64),
}

/// Rotated matrices with eigenvalues `l, l / cond`, `l` log-uniform in `[1e-8, 1]`, over a
/// condition grid that is dense around 16 (the f64 switch) and reaches `max_cond`, rounded
/// through `round`; `tau` is 0 or 1.5 det (clamp active).
fn cases(round: impl Fn(f64) -> f64, max_cond: f64) -> Vec<Case> {
    let mut rng = SplitMix64(0x1d1);
    let mut conds: Vec<f64> = (0..=40).map(|i| 400f64.powf(i as f64 / 40.0)).collect();
    conds.extend([15.0, 15.8, 15.9, 15.94, 15.95, 16.0, 16.1, 17.0]);
    conds.extend((1..=8).map(|i| 400.0 * (max_cond / 400.0).powf(i as f64 / 8.0)));
    conds.retain(|&c| c <= max_cond);
    let mut out = Vec::new();
    for &cond in &conds {
        for k in 0..24 {
            let l = rng.log_uniform(1e-8, 1.0);
            let t = std::f64::consts::PI * rng.uniform();
            let (c, s) = (t.cos(), t.sin());
            let (l1, l2) = (l, l / cond);
            let (a11, a12, a22) = (
                round(c * c * l1 + s * s * l2),
                round(c * s * (l1 - l2)),
                round(s * s * l1 + c * c * l2),
            );
            let a = DdSym::new(a11, a12, a22);
            let tau = if k % 2 == 0 {
                0.0
            } else {
                round(1.5 * a.det().f())
            };
            out.push(Case {
                a,
                tau,
                cond,
                entries: (a11, a12, a22),
            });
        }
    }
    out
}

macro_rules! representations {
    ($name:ident, $prec:ident, $t:ty, $max_cond:expr) => {
        #[test]
        fn $name() {
            use filtered_ndf::$prec::{Beckmann, Ggx, Ndf, Roughness, RoughnessMatrix, Vec2, Vec3};
            let eps = <$t>::EPSILON as f64;
            let f = |x: f64| <$t as Real>::from_f64(x);
            let mut worst: f64 = 0.0;
            let mut rng = SplitMix64(0x5eed);
            let wide = std::mem::size_of::<$t>() == 4;
            for c in cases(|x| f(x).to_f64(), $max_cond) {
                let (a11, a12, a22) = c.entries;
                let m =
                    RoughnessMatrix::new_with_det_clamp(f(a11), f(a12), f(a22), f(c.tau)).unwrap();
                let det = max_dd(c.a.det(), c.tau);
                // Tolerances, in units of the precision's eps. The LDL form's one cancelling
                // term `a11 s_y - a12 s_x` costs about 2 sqrt(cond) eps and its determinant 10
                // eps (f64 at cond < 16); the eigenbasis rotation costs as much; plus a few
                // roundings: (2 sqrt(cond) + 32) eps. In f32 (the LDL form at any condition)
                // that term is exact in f64 (products of f32 numbers), the determinant too: the
                // f64 evaluation is within a few eps_f64 and the result within its rounding to
                // f32, half an ulp; 2 eps is asserted at every condition number.
                let tol_q = if wide {
                    2.0 * eps
                } else {
                    (2.0 * c.cond.sqrt() + 32.0) * eps
                };
                // Relative error, measured against the smallest normal number below it (a
                // subnormal result carries fewer bits: its error counts absolutely).
                let floor = <$t>::MIN_POSITIVE as f64;
                let mut check = |got: f64, want: f64, tol: f64, what: &str| {
                    let err = (got - want).abs() / want.abs().max(floor);
                    assert!(
                        err <= tol,
                        "{what}: cond {} entries {:?} tau {}: got {got:e}, want {want:e} \
                         (error {err:.2e}, tolerance {tol:.2e})",
                        c.cond,
                        c.entries,
                        c.tau
                    );
                    worst = worst.max(err / tol);
                };
                check(m.sqrt_det().to_f64(), det.sqrt().f(), 8.0 * eps, "sqrt_det");
                for _ in 0..6 {
                    // A slope within a few lobe widths and a unit micronormal over it.
                    let w = (c.a.a11.f() + c.a.a22.f()).sqrt();
                    let s = Vec2::new(
                        f(w * 3.0 * (rng.uniform() - 0.5)),
                        f(w * 3.0 * (rng.uniform() - 0.5)),
                    );
                    let (x, y) = (s.x.to_f64(), s.y.to_f64());
                    let q = c.a.adj_quadratic(x, y).div(det);
                    check(m.inv_quadratic(s).to_f64(), q.f(), tol_q, "inv_quadratic");
                    let fq = c.a.quadratic(x, y);
                    check(m.quadratic(s).to_f64(), fq.f(), tol_q, "quadratic");
                    // Densities at the micronormal of slope s: D = P22 / m_z^4, exactly.
                    let h = Vec3::new(-s.x, -s.y, 1.0).normalize();
                    let (hx, hy, hz) = (h.x.to_f64(), h.y.to_f64(), h.z.to_f64());
                    let z2 = Dd::prod(hz, hz);
                    let xq = c.a.adj_quadratic(hx, hy).div(det).div(z2).f();
                    let norm = std::f64::consts::PI * det.sqrt().f() * z2.f() * z2.f();
                    // In log space: exp(-x) alone may leave the normal range.
                    let beckmann = (-xq - norm.ln()).exp();
                    // exp turns a relative error e of its argument into x e.
                    let tol_d = tol_q * (1.0 + xq) + 16.0 * eps;
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
            println!("{}: worst error / tolerance {worst:.3}", stringify!($prec));
        }
    };
}

representations!(f32_matrices_match_double_double, f32, f32, 1e6);
representations!(f64_matrices_match_double_double, f64, f64, 400.0);

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
