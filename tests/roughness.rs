//! The checked constructors' errors, the clamping constructors, the one-way conversions
//! `Isotropic -> AxisAligned -> RoughnessMatrix`, and the bad-input contract of
//! `p22`, `d`, `lambda`, `g1`, `g2` (no NaN and no panic for any finite input: zero, tiny,
//! subnormal, huge, back-facing, horizon, non-unit vectors), in both precisions.

use filtered_ndf::RoughnessError::{self, *};

macro_rules! per_precision {
    ($name:ident, $prec:ident, $t:ty) => {
        mod $name {
            use super::*;
            use filtered_ndf::$prec::{
                ALPHA_MAX, ALPHA_MIN, AxisAligned, Beckmann, Ggx, Isotropic, Mat2, Ndf, Roughness,
                RoughnessMatrix, Vec2, Vec3,
            };
            type F = $t;
            const EPS: F = F::EPSILON;

            fn iso_err(a: F) -> Option<RoughnessError> {
                Isotropic::new(a).err()
            }

            #[test]
            fn isotropic_errors() {
                for bad in [F::NAN, F::INFINITY, F::NEG_INFINITY] {
                    assert_eq!(iso_err(bad), Some(NotFinite), "{bad}");
                    assert_eq!(Ggx::isotropic(bad).err(), Some(NotFinite));
                    assert_eq!(Beckmann::isotropic(bad).err(), Some(NotFinite));
                }
                for bad in [0.0, -0.0, -1.0, -F::MIN_POSITIVE, -F::MAX] {
                    assert_eq!(iso_err(bad), Some(NotPositive), "{bad}");
                }
                for bad in [
                    ALPHA_MIN * 0.5,
                    1e-30,
                    F::MIN_POSITIVE,
                    ALPHA_MAX * 2.0,
                    F::MAX,
                ] {
                    assert_eq!(iso_err(bad), Some(OutOfRange), "{bad}");
                }
                for ok in [ALPHA_MIN, 1e-4, 1.0, ALPHA_MAX] {
                    assert_eq!(Isotropic::new(ok).unwrap().alpha(), ok);
                }
            }

            #[test]
            fn axis_aligned_errors_and_precedence() {
                assert_eq!(AxisAligned::new(F::NAN, 1.0).err(), Some(NotFinite));
                assert_eq!(AxisAligned::new(1.0, F::INFINITY).err(), Some(NotFinite));
                assert_eq!(AxisAligned::new(1.0, 0.0).err(), Some(NotPositive));
                assert_eq!(AxisAligned::new(-1.0, 1.0).err(), Some(NotPositive));
                assert_eq!(AxisAligned::new(1.0, 1e5).err(), Some(OutOfRange));
                // Both invalid: alpha_x decides (documented).
                assert_eq!(AxisAligned::new(1e-30, -1.0).err(), Some(OutOfRange));
                assert_eq!(AxisAligned::new(-1.0, F::NAN).err(), Some(NotPositive));
                assert_eq!(Ggx::axis_aligned(0.1, F::NAN).err(), Some(NotFinite));
                assert_eq!(Beckmann::axis_aligned(0.0, 0.1).err(), Some(NotPositive));
                let r = AxisAligned::new(0.1, 0.2).unwrap();
                assert_eq!(r.alpha(), Vec2::new(0.1, 0.2));
            }

            #[test]
            fn matrix_errors() {
                assert_eq!(
                    RoughnessMatrix::new(F::NAN, 0.0, 1.0).err(),
                    Some(NotFinite)
                );
                assert_eq!(
                    RoughnessMatrix::new(1.0, F::INFINITY, 1.0).err(),
                    Some(NotFinite)
                );
                assert_eq!(RoughnessMatrix::new(0.0, 0.0, 1.0).err(), Some(NotPositive));
                assert_eq!(
                    RoughnessMatrix::new(1.0, 0.0, -1.0).err(),
                    Some(NotPositive)
                );
                // Indefinite, and exactly singular, without a clamp.
                assert_eq!(
                    RoughnessMatrix::new(1.0, 2.0, 1.0).err(),
                    Some(NotPositiveDefinite)
                );
                assert_eq!(
                    RoughnessMatrix::new(1.0, 1.0, 1.0).err(),
                    Some(NotPositiveDefinite)
                );
                assert_eq!(
                    RoughnessMatrix::new(1.0, -1.0, 1.0).err(),
                    Some(NotPositiveDefinite)
                );
                // Eigenvalues out of [ALPHA_MIN^2, ALPHA_MAX^2].
                let hi = ALPHA_MAX * ALPHA_MAX;
                let lo = ALPHA_MIN * ALPHA_MIN;
                assert_eq!(
                    RoughnessMatrix::new(hi * 4.0, 0.0, 1.0).err(),
                    Some(OutOfRange)
                );
                assert_eq!(
                    RoughnessMatrix::new(1.0, 0.0, lo * 0.25).err(),
                    Some(OutOfRange)
                );
                assert_eq!(
                    RoughnessMatrix::new(F::MAX, 0.0, F::MAX).err(),
                    Some(OutOfRange)
                );
                assert!(RoughnessMatrix::new(hi, 0.0, lo).is_ok());
                // Near-singular: det = 1 - (1 - d)^2 ~ 2 d, fine without clamp while positive.
                let d: F = 1e3 * EPS;
                let r = RoughnessMatrix::new(1.0, 1.0 - d, 1.0).unwrap();
                let det = r.sqrt_det() * r.sqrt_det();
                assert!((det - (2.0 * d - d * d)).abs() <= 4.0 * EPS * det, "{det}");
                // Tau: singular-by-rounding accepted with a clamp, clearly indefinite refused.
                let r = RoughnessMatrix::new_with_det_clamp(1.0, 1.0, 1.0, 1e-6).unwrap();
                assert_eq!(r.sqrt_det(), (1e-6 as F).sqrt());
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(1.0, 1.5, 1.0, 1e-6).err(),
                    Some(NotPositiveDefinite)
                );
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(1.0, 0.0, 1.0, F::NAN).err(),
                    Some(NotFinite)
                );
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(1.0, 0.0, 1.0, -1.0).err(),
                    Some(NotPositive)
                );
                assert_eq!(Ggx::matrix(1.0, 2.0, 1.0).err(), Some(NotPositiveDefinite));
                assert_eq!(Beckmann::matrix(F::NAN, 0.0, 1.0).err(), Some(NotFinite));
            }

            #[test]
            fn matrix_equality_is_by_value() {
                // From<AxisAligned> / From<Isotropic> equal the checked constructor with the
                // squares rounded to F, over the whole range (in f32 they once differed by the
                // representation of the determinant).
                for i in 0..=24 {
                    let ax = ALPHA_MIN * (ALPHA_MAX / ALPHA_MIN).powf(i as F / 24.0);
                    for j in 0..=24 {
                        let ay = ALPHA_MIN * (ALPHA_MAX / ALPHA_MIN).powf(j as F / 24.0);
                        let (Ok(aa), Ok(m)) = (
                            AxisAligned::new(ax, ay),
                            RoughnessMatrix::new(ax * ax, 0.0, ay * ay),
                        ) else {
                            continue;
                        };
                        assert_eq!(RoughnessMatrix::from(aa), m, "{ax} {ay}");
                        assert_eq!(aa.to_matrix(), m);
                    }
                    let iso = Isotropic::new(ax).unwrap();
                    let m = RoughnessMatrix::new(ax * ax, 0.0, ax * ax).unwrap();
                    assert_eq!(RoughnessMatrix::from(iso), m, "{ax}");
                }
                // The value, not the construction: a clamp at or below det A is no clamp,
                // -0 = +0, and removing a clamp gives the matrix back.
                let m = RoughnessMatrix::new(0.5, 0.2, 0.3).unwrap();
                let det = 0.5 * 0.3 - 0.2 * 0.2;
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(0.5, 0.2, 0.3, 0.5 * det).unwrap(),
                    m
                );
                assert_eq!(m.with_det_clamp(0.0), m);
                let c = m.with_det_clamp(10.0 * det);
                assert_ne!(c, m);
                assert_eq!(c.entries(), m.entries());
                assert_eq!(c.with_det_clamp(0.0), m);
                assert_eq!(
                    RoughnessMatrix::new(0.5, -0.0, 0.3).unwrap(),
                    RoughnessMatrix::new(0.5, 0.0, 0.3).unwrap()
                );
            }

            #[test]
            fn from_mat2_symmetry() {
                let m = |a11: F, a21: F, a12: F, a22: F| {
                    Mat2::from_cols(Vec2::new(a11, a21), Vec2::new(a12, a22))
                };
                assert_eq!(
                    RoughnessMatrix::from_mat2(m(1.0, 0.1, 0.2, 1.0)).err(),
                    Some(NotSymmetric)
                );
                assert_eq!(
                    RoughnessMatrix::from_mat2(m(1.0, F::NAN, 0.1, 1.0)).err(),
                    Some(NotFinite)
                );
                assert_eq!(
                    RoughnessMatrix::from_mat2(m(1.0, 2.0, 2.0, 1.0)).err(),
                    Some(NotPositiveDefinite)
                );
                // Asymmetric by a couple of ulps: accepted and symmetrised.
                let r =
                    RoughnessMatrix::from_mat2(m(1.0, 0.25, 0.25 + 2.0 * EPS * 0.25, 1.0)).unwrap();
                let (_, a12, _) = r.entries();
                assert!((a12 - 0.25).abs() <= 2.0 * EPS);
                assert_eq!(r.to_mat2().x_axis.y, r.to_mat2().y_axis.x);
            }

            #[test]
            fn clamped_constructors() {
                let c = |a: F| Isotropic::new_clamped(a).alpha();
                assert_eq!(c(F::NAN), ALPHA_MIN);
                assert_eq!(c(-1.0), ALPHA_MIN);
                assert_eq!(c(0.0), ALPHA_MIN);
                assert_eq!(c(F::NEG_INFINITY), ALPHA_MIN);
                assert_eq!(c(F::INFINITY), ALPHA_MAX);
                assert_eq!(c(1e30), ALPHA_MAX);
                assert_eq!(c(0.5), 0.5);
                let a = AxisAligned::new_clamped(F::NAN, 1e30).alpha();
                assert_eq!(a, Vec2::new(ALPHA_MIN, ALPHA_MAX));
            }

            #[test]
            fn conversions_iso_aniso_matrix() {
                let iso = Isotropic::new(0.3).unwrap();
                let aa = AxisAligned::from(iso);
                assert_eq!(aa.alpha(), Vec2::splat(0.3));
                let m = RoughnessMatrix::from(iso);
                assert_eq!(m.entries(), (0.3 * 0.3, 0.0, 0.3 * 0.3));
                assert_eq!(m, iso.to_matrix());
                let aa = AxisAligned::new(0.1, 0.7).unwrap();
                let m = RoughnessMatrix::from(aa);
                assert_eq!(m.entries(), (0.1 * 0.1, 0.0, 0.7 * 0.7));
                // Equal by value to the checked constructor with the squares rounded to F.
                assert_eq!(m, RoughnessMatrix::new(0.1 * 0.1, 0.0, 0.7 * 0.7).unwrap());
                // sqrt_det: the axis-aligned form rounds alpha_x alpha_y once (eps / 2); the
                // matrix rounds each square (eps / 2, halved by the root) and the root
                // (eps / 2), its f64 product exact: within 1.5 eps of each other, 2 eps asserted.
                let (u, v) = (m.sqrt_det(), aa.sqrt_det());
                assert!((u - v).abs() <= 2.0 * EPS * v, "{u} vs {v}");
                let inv = m.inverse();
                assert!((inv.x_axis.x * 0.01 - 1.0).abs() <= 4.0 * EPS);
                assert!((inv.y_axis.y * 0.49 - 1.0).abs() <= 4.0 * EPS);
                assert_eq!(inv.x_axis.y, 0.0);
                // A A^-1 = I for a rotated, anisotropic matrix (cond = 100: 100 eps each).
                let r = RoughnessMatrix::new(0.5, 0.3, 0.2 + 1e-2).unwrap();
                let p = r.to_mat2() * r.inverse();
                let e = (p - Mat2::IDENTITY).to_cols_array();
                assert!(e.iter().all(|x| x.abs() <= 400.0 * EPS), "{p}");
                // quadratic / inv_quadratic are the two forms of the same A.
                let w = Vec2::new(0.3, -0.7);
                let q = r.quadratic(w);
                let aw = r.to_mat2() * w;
                assert!((q - w.dot(aw)).abs() <= 16.0 * EPS * q);
                assert!((r.inv_quadratic(aw) - q).abs() <= 400.0 * EPS * q);
            }

            /// Finite vectors of every awkward kind.
            fn vectors() -> Vec<Vec3> {
                let mut v = vec![
                    Vec3::ZERO,
                    Vec3::Z,
                    -Vec3::Z,
                    Vec3::X,
                    Vec3::new(0.6, 0.0, 0.8),
                    Vec3::new(0.6, 0.0, -0.8),
                    Vec3::new(1.0, 1.0, F::MIN_POSITIVE),
                    Vec3::new(1.0, 0.0, F::from_bits(1)),
                    Vec3::new(0.0, 0.0, F::from_bits(1)),
                    Vec3::splat(F::MAX),
                    Vec3::new(F::MAX, -F::MAX, F::MAX),
                    Vec3::new(1e-30, 0.0, 1e-30),
                    Vec3::new(-3.0, 4.0, 12.0),
                    Vec3::new(1.0, 0.0, 1e-30),
                    Vec3::new(F::MAX, 0.0, 1.0),
                ];
                v.extend(v.clone().into_iter().map(|x| -x));
                v
            }

            fn check<N: Ndf + core::fmt::Debug>(n: &N) {
                let vs = vectors();
                for &m in &vs {
                    let s = Vec2::new(m.x, m.y);
                    let p = n.p22(s);
                    assert!(p.is_finite() && p >= 0.0, "{n:?} p22({s}) = {p}");
                    let d = n.d(m);
                    assert!(d.is_finite() && d >= 0.0, "{n:?} d({m}) = {d}");
                    if m.z <= 0.0 {
                        assert_eq!(d, 0.0, "{n:?} d({m}) below the horizon");
                    }
                    let l = n.lambda(m);
                    assert!(l >= 0.0, "{n:?} lambda({m}) = {l}");
                    for (j, &w) in vs.iter().enumerate() {
                        let g1 = n.g1(w, m);
                        assert!((0.0..=1.0).contains(&g1), "{n:?} g1({w}, {m}) = {g1}");
                        if w.dot(m) <= 0.0 {
                            assert_eq!(g1, 0.0);
                        }
                        // G2 against each other vector as the incoming direction (i = -w
                        // would always give 0: one of i.m, w.m is <= 0): in [0, 1], at most
                        // either G1, 0 where either direction is behind m.
                        for &i in vs.iter().skip(j % 3).step_by(3) {
                            let g2 = n.g2(i, w, m);
                            let gi = n.g1(i, m);
                            assert!(
                                (0.0..=1.0).contains(&g2) && g2 <= g1 && g2 <= gi,
                                "{n:?} g2({i}, {w}, {m}) = {g2}, g1 {g1} {gi}"
                            );
                            if i.dot(m) <= 0.0 || w.dot(m) <= 0.0 {
                                assert_eq!(g2, 0.0, "{n:?} g2({i}, {w}, {m})");
                            }
                        }
                    }
                }
                // Lambda is scale invariant: tiny and huge copies of a direction agree. Scaling
                // by a non-power of two rounds `w` (an eps per component), which Beckmann's
                // `exp(-a^2)` amplifies by `2 a^2 <= 2 (-ln Lambda)`: 8 (1 + 2 max(0, -ln L)) eps.
                let w = Vec3::new(0.48, 0.36, 0.8);
                let l = n.lambda(w);
                let amp = 1.0 + 2.0 * (-l.ln()).max(0.0);
                for k in [1e-30 as F, 1e-20, 1e20, 1e30] {
                    let lk = n.lambda(w * k);
                    assert!(
                        lk == l || (lk - l).abs() <= 8.0 * amp * EPS * l,
                        "{n:?} lambda({k} w) = {lk} vs {l}"
                    );
                }
            }

            #[test]
            fn evaluations_never_nan_for_finite_input() {
                for a in [ALPHA_MIN, 1e-4, 0.5, 1.0, ALPHA_MAX] {
                    let iso = Isotropic::new(a).unwrap();
                    check(&Ggx::new(iso));
                    check(&Beckmann::new(iso));
                    let aa = AxisAligned::new(a, (a * 1e3).min(ALPHA_MAX)).unwrap();
                    check(&Ggx::new(aa));
                    check(&Beckmann::new(aa));
                    let m = aa.to_matrix();
                    check(&Ggx::new(m));
                    check(&Beckmann::new(m));
                }
                let r = RoughnessMatrix::new(0.5, 0.3, 0.2 + 1e-3).unwrap();
                check(&Ggx::new(r));
                check(&Beckmann::new(r));
                let r = RoughnessMatrix::new_with_det_clamp(1.0, 1.0, 1.0, 1e-6).unwrap();
                check(&Ggx::new(r));
                check(&Beckmann::new(r));
            }
        }
    };
}

per_precision!(f32, f32, f32);
per_precision!(f64, f64, f64);
