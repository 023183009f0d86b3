//! The bad-input contract of `src/contract.rs`: one test per statement group, each run in
//! `f32` and in `f64` (`contract_f32::<name>`, `contract_f64::<name>`). The module docs of
//! `filtered_ndf::contract` name these tests.

macro_rules! contract {
    ($m:ident, $p:ident) => {
        mod $m {
            use filtered_ndf::RoughnessError as E;
            use filtered_ndf::math::Real as _;
            use filtered_ndf::$p::filter::{presets, proxy, rect};
            use filtered_ndf::$p::footprint::{jacobian, slope};
            use filtered_ndf::$p::ndf::roughness;
            use filtered_ndf::$p::*;

            const NAN: F = F::NAN;
            const INF: F = F::INFINITY;
            /// A few roundings of the precision under test (a handful of operations, each
            /// half an ulp, with sensitivities of order 1): 64 eps of `F`.
            const TOL: F = 64.0 * F::EPSILON;

            fn iso() -> Isotropic {
                Isotropic::new(0.3).unwrap()
            }
            fn mat() -> RoughnessMatrix {
                RoughnessMatrix::new(0.09, 0.02, 0.04).unwrap()
            }
            fn singular() -> RoughnessMatrix {
                RoughnessMatrix::new_with_det_clamp(0.25, 0.5, 1.0, 1e-4).unwrap()
            }

            #[test]
            fn roughness_constructors() {
                for bad in [NAN, INF, -INF] {
                    assert_eq!(Isotropic::new(bad), Err(E::NotFinite));
                    assert_eq!(AxisAligned::new(0.1, bad), Err(E::NotFinite));
                    assert_eq!(RoughnessMatrix::new(0.1, bad, 0.1), Err(E::NotFinite));
                    assert_eq!(Ggx::isotropic(bad).err(), Some(E::NotFinite));
                    assert_eq!(Beckmann::matrix(bad, 0.0, 0.1).err(), Some(E::NotFinite));
                }
                for bad in [0.0, -0.0, -0.1] {
                    assert_eq!(Isotropic::new(bad), Err(E::NotPositive));
                    assert_eq!(AxisAligned::new(bad, 0.1), Err(E::NotPositive));
                    assert_eq!(RoughnessMatrix::new(bad, 0.0, 0.1), Err(E::NotPositive));
                }
                assert_eq!(Isotropic::new(1e-9), Err(E::OutOfRange));
                assert_eq!(Isotropic::new(1e5), Err(E::OutOfRange));
                assert_eq!(RoughnessMatrix::new(1e9, 0.0, 1.0), Err(E::OutOfRange));
                // Indefinite and singular matrices.
                assert_eq!(
                    RoughnessMatrix::new(0.1, 0.2, 0.1),
                    Err(E::NotPositiveDefinite)
                );
                assert_eq!(
                    RoughnessMatrix::new(0.25, 0.5, 1.0),
                    Err(E::NotPositiveDefinite)
                );
                assert!(RoughnessMatrix::new_with_det_clamp(0.25, 0.5, 1.0, 1e-4).is_ok());
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(0.1, 0.2, 0.1, 1e-6),
                    Err(E::NotPositiveDefinite)
                );
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(0.1, 0.0, 0.1, -1.0),
                    Err(E::NotPositive)
                );
                assert_eq!(
                    RoughnessMatrix::new_with_det_clamp(0.1, 0.0, 0.1, NAN),
                    Err(E::NotFinite)
                );
                // Non-symmetric Mat2.
                let ns = Mat2::from_cols(Vec2::new(0.1, 0.01), Vec2::new(0.02, 0.1));
                assert_eq!(RoughnessMatrix::from_mat2(ns), Err(E::NotSymmetric));
                let nanm = Mat2::from_cols(Vec2::new(0.1, NAN), Vec2::new(0.0, 0.1));
                assert_eq!(RoughnessMatrix::from_mat2(nanm), Err(E::NotFinite));
                let ok = Mat2::from_cols(Vec2::new(0.1, 0.01), Vec2::new(0.01, 0.1));
                assert!(RoughnessMatrix::from_mat2(ok).is_ok());
                // Clamped constructors never fail.
                assert_eq!(Isotropic::new_clamped(NAN).alpha(), ALPHA_MIN);
                assert_eq!(Isotropic::new_clamped(-1.0).alpha(), ALPHA_MIN);
                assert_eq!(Isotropic::new_clamped(INF).alpha(), ALPHA_MAX);
                assert_eq!(
                    AxisAligned::new_clamped(NAN, INF).alpha(),
                    Vec2::new(ALPHA_MIN, ALPHA_MAX)
                );
                assert_eq!(roughness::clamp_alpha(-INF), ALPHA_MIN);
                // with_det_clamp: a bad tau means no clamp.
                for t in [NAN, -1.0, INF] {
                    assert_eq!(mat().with_det_clamp(t), mat().with_det_clamp(0.0));
                }
            }

            #[test]
            fn roughness_forms() {
                let big = Vec2::new(F::MAX, F::MAX);
                let forms: [&dyn Fn(Vec2) -> (F, F); 4] = [
                    &|v| (iso().inv_quadratic(v), iso().quadratic(v)),
                    &|v| {
                        let r = AxisAligned::new(0.1, 0.4).unwrap();
                        (r.inv_quadratic(v), r.quadratic(v))
                    },
                    &|v| (mat().inv_quadratic(v), mat().quadratic(v)),
                    &|v| (singular().inv_quadratic(v), singular().quadratic(v)),
                ];
                for f in forms {
                    let (a, b) = f(Vec2::new(0.3, -0.2));
                    assert!(a.is_finite() && a > 0.0 && b.is_finite() && b > 0.0);
                    assert_eq!(f(Vec2::ZERO), (0.0, 0.0));
                    // Overflow gives +inf (also against the null direction of a clamped
                    // singular matrix), never NaN.
                    let (a, b) = f(big);
                    assert!(a == INF && b == INF, "{a} {b}");
                    let (a, b) = f(Vec2::new(INF, -INF));
                    assert!(a == INF && b == INF);
                    let (a, b) = f(Vec2::new(NAN, 0.0));
                    assert!(a.is_nan() && b.is_nan());
                }
                for r in [mat().sqrt_det(), singular().sqrt_det(), iso().sqrt_det()] {
                    assert!(r.is_finite() && r > 0.0);
                }
            }

            fn ndfs() -> Vec<(bool, Box<dyn NdfSampling>)> {
                vec![
                    (true, Box::new(Ggx::new(iso()))),
                    (
                        true,
                        Box::new(Ggx::new(AxisAligned::new(0.1, 0.4).unwrap())),
                    ),
                    (true, Box::new(Ggx::new(mat()))),
                    (true, Box::new(Ggx::new(singular()))),
                    (false, Box::new(Beckmann::new(iso()))),
                    (
                        false,
                        Box::new(Beckmann::new(AxisAligned::new(0.1, 0.4).unwrap())),
                    ),
                    (false, Box::new(Beckmann::new(mat()))),
                    (false, Box::new(Beckmann::new(singular()))),
                ]
            }

            /// `sqrt(det A)` of `ndfs()`'s roughness `k` (in order: isotropic 0.3, axis-aligned
            /// (0.1, 0.4), `mat()`, `singular()`, for GGX then Beckmann), in `f64`.
            fn peak_sqrt_det(k: usize) -> f64 {
                match k % 4 {
                    0 => 0.09,
                    1 => 0.04,
                    2 => (0.09f64 * 0.04 - 0.02 * 0.02).sqrt(),
                    _ => 1e-4f64.sqrt(), // the clamp tau = 1e-4 (det A = 0)
                }
            }

            #[test]
            fn ndf_p22() {
                for (k, (_, n)) in ndfs().into_iter().enumerate() {
                    for s in [
                        Vec2::ZERO,
                        Vec2::new(0.1, -3.0),
                        Vec2::new(1e30, 1e30),
                        Vec2::splat(F::MAX),
                    ] {
                        let v = n.p22(s);
                        assert!(v.is_finite() && v >= 0.0, "{s:?}: {v}");
                    }
                    assert_eq!(n.p22(Vec2::new(INF, 0.0)), 0.0);
                    assert_eq!(n.p22(Vec2::new(-INF, INF)), 0.0);
                    // Both densities peak at 1 / (pi sqrt(det A)) (det of the clamped matrix).
                    let peak = 1.0 / (core::f64::consts::PI * peak_sqrt_det(k));
                    let p0 = n.p22(Vec2::ZERO).to_f64();
                    assert!(
                        (p0 / peak - 1.0).abs() <= TOL.to_f64(),
                        "{k}: {p0} vs {peak}"
                    );
                    // NaN policy (src/ndf/mod.rs): a NaN argument contributes nothing.
                    for s in [
                        Vec2::new(NAN, 0.0),
                        Vec2::new(0.0, NAN),
                        Vec2::new(NAN, INF),
                    ] {
                        assert_eq!(n.p22(s), 0.0, "{s:?}");
                    }
                }
            }

            #[test]
            fn ndf_d() {
                for (_, n) in ndfs() {
                    let m = Vec3::new(0.1, 0.05, 1.0).normalize();
                    // Back-facing, horizon, zero, NaN, infinite: 0.
                    for bad in [
                        Vec3::new(0.1, 0.05, -1.0),
                        -Vec3::Z,
                        Vec3::X,
                        Vec3::ZERO,
                        Vec3::new(NAN, 0.0, 1.0),
                        Vec3::new(0.0, 0.0, NAN),
                        Vec3::new(INF, 0.0, 1.0),
                        Vec3::new(0.0, 0.0, INF),
                    ] {
                        assert_eq!(n.d(bad), 0.0, "{bad:?}");
                    }
                    // Non-unit m: the homogeneous form, D(k m) = D(m) / k^4.
                    let (a, b) = (n.d(m), n.d(m * 2.0));
                    assert!((b * 16.0 - a).abs() <= TOL * a, "{a} {b}");
                    for tiny in [1e-30, 1e-6] {
                        let v = n.d(Vec3::new(0.5, 0.5, tiny).normalize());
                        assert!(v.is_finite() && v >= 0.0);
                    }
                }
            }

            #[test]
            fn ndf_lambda_g() {
                for (_, n) in ndfs() {
                    let w = Vec3::new(0.6, 0.4, 0.3);
                    let l = n.lambda(w);
                    assert!(l.is_finite() && l >= 0.0);
                    // Non-unit: homogeneous of degree 0, also for huge and tiny finite vectors.
                    for k in [1e-30, 1e-3, 7.0, 1e30] {
                        let lk = n.lambda(w * k);
                        assert!((lk - l).abs() <= TOL * l, "{k}: {lk} vs {l}");
                    }
                    // Back-facing: |w_z|.
                    assert_eq!(n.lambda(Vec3::new(0.6, 0.4, -0.3)), l);
                    assert_eq!(n.lambda(Vec3::new(0.3, 0.2, 0.0)), INF);
                    assert_eq!(n.lambda(Vec3::ZERO), 0.0);
                    assert_eq!(n.lambda(Vec3::Z), 0.0);
                    // Infinite components: the limit direction.
                    assert_eq!(n.lambda(Vec3::new(0.1, 0.0, INF)), 0.0);
                    assert_eq!(n.lambda(Vec3::new(INF, 0.0, 1.0)), INF);
                    // NaN policy: fully masked, in every component (w_z alone too).
                    for bad in [
                        Vec3::new(NAN, 0.0, 1.0),
                        Vec3::new(0.0, NAN, 1.0),
                        Vec3::new(0.0, 0.0, NAN),
                        Vec3::new(NAN, INF, 1.0),
                    ] {
                        assert_eq!(n.lambda(bad), INF, "{bad:?}");
                    }
                    // G1, G2 in [0, 1]; 0 for w.m <= 0 and grazing w.
                    let m = Vec3::Z;
                    let g = n.g1(w, m);
                    assert!(g > 0.0 && g <= 1.0);
                    assert_eq!(n.g1(-w, m), 0.0);
                    assert_eq!(n.g1(Vec3::X, m), 0.0);
                    assert_eq!(n.g2(w, -w, m), 0.0);
                    let g2 = n.g2(w, Vec3::new(-0.2, 0.1, 0.9), m);
                    assert!(g2 > 0.0 && g2 <= 1.0);
                    let nan = Vec3::new(NAN, 0.0, 1.0);
                    assert_eq!(n.g1(nan, m), 0.0);
                    assert_eq!(n.g1(w, Vec3::new(0.0, 0.0, NAN)), 0.0);
                    assert_eq!(n.g2(nan, w, m), 0.0);
                    assert_eq!(n.g2(w, nan, m), 0.0);
                    assert_eq!(n.g2(w, w, Vec3::new(NAN, 0.0, 1.0)), 0.0);
                }
            }

            #[test]
            fn sampling() {
                use filtered_ndf::$p::sampling::reflect;
                for (_, n) in ndfs() {
                    for u in [
                        Vec2::new(NAN, 0.5),
                        Vec2::new(-1.0, 2.0),
                        Vec2::new(INF, -INF),
                        Vec2::ONE,
                    ] {
                        let m = n.sample_normal(u);
                        assert!(m.is_finite() && m.z > 0.0 && (m.length() - 1.0).abs() < TOL);
                        let wo = Vec3::new(0.5, 0.1, 0.2) * 30.0; // non-unit
                        let m = n.sample_visible_normal(wo, u).unwrap();
                        assert!(m.is_finite() && m.z > 0.0 && wo.dot(m) > 0.0);
                    }
                    // u outside [0, 1): clamped to [0, 1 - eps/2] per component, NaN to 0.
                    let top = 1.0 - F::EPSILON / 2.0;
                    let wo = Vec3::new(0.5, 0.1, 0.2);
                    for (u, clamped) in [
                        (Vec2::new(NAN, 0.5), Vec2::new(0.0, 0.5)),
                        (Vec2::new(-1.0, 2.0), Vec2::new(0.0, top)),
                        (Vec2::new(INF, -INF), Vec2::new(top, 0.0)),
                    ] {
                        assert_eq!(n.sample_normal(u), n.sample_normal(clamped), "{u:?}");
                        assert_eq!(
                            n.sample_visible_normal(wo, u),
                            n.sample_visible_normal(wo, clamped),
                            "{u:?}"
                        );
                    }
                    let u = Vec2::splat(0.3);
                    for bad in [
                        Vec3::new(0.5, 0.0, -0.5),
                        Vec3::X,
                        Vec3::ZERO,
                        Vec3::new(NAN, 0.0, 1.0),
                        Vec3::new(0.0, 0.0, INF),
                    ] {
                        assert_eq!(n.sample_visible_normal(bad, u), None, "{bad:?}");
                        assert_eq!(n.visible_normal_pdf(bad, Vec3::Z), 0.0);
                        assert_eq!(n.reflection_pdf(bad, Vec3::Z), 0.0);
                        assert_eq!(n.reflection_pdf_from_normal(bad, Vec3::Z), 0.0);
                    }
                    let wo = Vec3::new(0.3, 0.0, 0.9);
                    assert_eq!(n.normal_pdf(-Vec3::Z), 0.0);
                    assert_eq!(n.normal_pdf(Vec3::new(NAN, 0.0, 1.0)), 0.0);
                    assert_eq!(n.visible_normal_pdf(wo, -Vec3::Z), 0.0);
                    assert_eq!(
                        n.visible_normal_pdf(wo, Vec3::new(-1.0, 0.0, 0.1).normalize()),
                        0.0
                    );
                    assert_eq!(n.reflection_pdf(wo, -wo), 0.0);
                    assert_eq!(n.reflection_pdf(wo, Vec3::ZERO), 0.0);
                    // Non-unit wo and wi: scale invariant.
                    let wi = Vec3::new(-0.2, 0.1, 0.9);
                    let (a, b) = (
                        n.reflection_pdf(wo, wi),
                        n.reflection_pdf(wo * 1e3, wi * 1e-3),
                    );
                    // The rescaled half vector rounds differently (a few eps), and D amplifies
                    // a slope error by its log-derivative 4 |s| / (alpha^2 (1 + q)), at most 16
                    // here (alpha 0.1, slope 0.05): 16 TOL.
                    assert!(
                        a > 0.0 && (a - b).abs() <= 16.0 * TOL * a,
                        "{} eps",
                        (a - b).abs() / a / F::EPSILON
                    );
                    assert_eq!(reflect(wo, Vec3::Z).length(), wo.length());
                }
                use filtered_ndf::$p::sampling::beckmann::visible_slope_quantile;
                for (c, s, u) in [
                    (NAN, 0.0, 0.5),
                    (-1.0, 0.5, 0.5),
                    (1.0, 0.0, NAN),
                    (0.5, 0.5, 2.0),
                    (0.5, 0.5, -1.0),
                ] {
                    assert!(visible_slope_quantile(c, s, u).is_finite());
                }
                assert_eq!(
                    visible_slope_quantile(NAN, 0.0, 0.3),
                    visible_slope_quantile(1.0, 0.0, 0.3)
                );
            }

            #[test]
            fn footprints_and_covariances() {
                let fp = Footprint::from_projected_derivatives_in_slope(
                    Vec3::new(NAN, 0.0, 1.0),
                    Vec2::X,
                    Vec2::Y,
                );
                assert_eq!(fp, Footprint::ZERO);
                // Back-facing / horizon h: h_z clamped to 1e-6, a huge finite footprint.
                let fp = Footprint::from_projected_derivatives_in_slope(
                    Vec3::new(0.6, 0.0, -0.8),
                    Vec2::X,
                    Vec2::Y,
                );
                assert!(fp.dh_u.is_finite() && fp.dh_u.length() > 1e10);
                // An infinite difference saturates (an infinite entry, for the clamp rules).
                let inf = Footprint::from_normal_differences(Vec3::new(INF, 0.0, 0.0), Vec3::ZERO);
                assert!(inf.dh_u.x == INF && inf.dh_u.y == 0.0 && inf.dh_v == Vec2::ZERO);
                let fp = Footprint::from_normal_differences(Vec3::new(1e-7, 0.0, -2.0), Vec3::ZERO);
                assert!(fp.dh_u.is_finite());
                // The kernel builders count a NaN entry as 0; max_extent is plain arithmetic.
                let nanfp = Footprint::from_slope_derivatives(Vec2::new(NAN, 0.0), Vec2::ZERO);
                assert_eq!(nanfp.covariance(0.5), Covariance::ZERO);
                assert_eq!(nanfp.bounding_rect(), BoundingRect::new(Vec2::ZERO));
                assert!(nanfp.max_extent().is_nan());
                // sanitized: a NaN entry -> 0, inf -> KERNEL_MAX I, indefinite -> PSD.
                let kmax = kernel::KERNEL_MAX;
                assert_eq!(
                    Covariance::new(NAN, 0.0, 1.0).sanitized(),
                    Covariance::new(0.0, 0.0, 1.0)
                );
                assert_eq!(
                    Covariance::new(INF, 0.0, 1.0).sanitized(),
                    Covariance::new(kmax, 0.0, kmax)
                );
                let s = Covariance::new(-1.0, 5.0, 2.0).sanitized();
                assert!(s.s11 >= 0.0 && s.s22 >= 0.0 && s.det() >= -TOL * (s.s11 + s.s22).powi(2));
                let (lo, hi) = Covariance::new(1.0, 3.0, 1.0).eigenvalues();
                assert!(lo == 0.0 && hi > 0.0);
                assert_eq!(
                    Covariance::new(1.0, 0.0, 1.0).clamp_eigenvalues(NAN),
                    Covariance::ZERO
                );
                assert_eq!(
                    Covariance::new(1.0, 0.0, 1.0).clamp_eigenvalues(-1.0),
                    Covariance::ZERO
                );
                assert_eq!(
                    Covariance::new(INF, 0.0, 1.0).clamp_eigenvalues(1.0),
                    Covariance::ZERO
                );
                let lean = LeanMoments::new(Vec2::new(1.0, 0.0), Covariance::new(0.5, 0.0, 0.1));
                let c = lean.covariance();
                assert!(c.s11 >= 0.0 && c.det() >= 0.0);
            }

            fn valid(m: RoughnessMatrix) -> bool {
                let g = Ggx::new(m);
                let b = Beckmann::new(m);
                let s = Vec2::new(0.01, -0.02);
                let (x, y) = (g.p22(s), b.p22(s));
                m.sqrt_det() > 0.0
                    && m.sqrt_det().is_finite()
                    && x.is_finite()
                    && x > 0.0
                    && y.is_finite()
                    && y >= 0.0
            }

            #[test]
            fn filters() {
                let kernels = [
                    Covariance::new(NAN, 0.0, 1.0),
                    Covariance::new(INF, -INF, INF),
                    Covariance::new(-1.0, 3.0, 0.5),
                    Covariance::new(1e30, 0.0, 1e-30),
                    Covariance::ZERO,
                ];
                for k in kernels {
                    for r in [
                        mat(),
                        singular(),
                        iso().to_matrix(),
                        Isotropic::new(10.0).unwrap().to_matrix(),
                    ] {
                        assert!(valid(filter::gaussian(r, k)), "{k:?}");
                        for tau in [NAN, -1.0, INF, 0.0] {
                            assert!(valid(filter::gaussian_with_det_clamp(r, k, tau)));
                        }
                        assert!(valid(filter::projected(r, k)), "{k:?}");
                        assert!(valid(filter::lean(
                            r,
                            k,
                            &LeanMoments::new(Vec2::new(NAN, 1.0), k)
                        )));
                        assert!(valid(temporal::widen(r, k)));
                        let rules = [ClampRules::default(), ClampRules::NONE, ClampRules::GDC2016];
                        for rule in rules {
                            let fp = Footprint::from_slope_derivatives(
                                Vec2::new(k.s11, k.s12),
                                Vec2::new(k.s22, 0.0),
                            );
                            assert!(valid(rule.filter_gaussian(r, fp, 0.5)));
                        }
                    }
                }
                // A zero kernel leaves the lobe unchanged (to rounding).
                let a = filter::gaussian(mat(), Covariance::ZERO);
                assert_eq!(a.entries(), mat().entries());
            }

            #[test]
            fn clamp_rules() {
                let r = ClampRules::default();
                let nanfp = Footprint::from_slope_derivatives(Vec2::new(NAN, 0.0), Vec2::ZERO);
                assert_eq!(r.footprint(nanfp), Footprint::ZERO);
                let inffp = Footprint::from_slope_derivatives(Vec2::new(INF, 0.0), Vec2::ZERO);
                assert!((r.footprint(inffp).max_extent() - 1.0).abs() < TOL);
                assert_eq!(ClampRules::NONE.footprint(inffp), inffp);
                // A NaN or negative lambda counts as 0; so does a NaN or negative kappa.
                for bad in [NAN, -1.0] {
                    let neg = ClampRules {
                        max_extent: bad,
                        ..r
                    };
                    assert_eq!(
                        neg.footprint(Footprint::from_slope_derivatives(Vec2::X, Vec2::Y))
                            .max_extent(),
                        0.0
                    );
                    let neg = ClampRules { kappa: bad, ..r };
                    assert_eq!(neg.kernel(Covariance::new(1.0, 0.2, 0.5)), Covariance::ZERO);
                }
                let h = r.rect(BoundingRect::new(Vec2::new(NAN, -0.5)), Vec2::splat(0.1));
                assert_eq!(h.half_extent, Vec2::new(1e-3, 0.5));
                let h = r.rect(BoundingRect::new(Vec2::new(INF, 0.1)), Vec2::splat(0.1));
                assert_eq!(h.half_extent.x, 1.0);
                let bad_kappa = ClampRules { kappa: NAN, ..r };
                assert_eq!(
                    bad_kappa.kernel(Covariance::new(1.0, 0.0, 1.0)),
                    Covariance::ZERO
                );
                assert_eq!(r.det_clamp_for(iso()), 0.3 * 0.3 * (0.3 * 0.3));
            }

            #[test]
            fn rect_and_proxy() {
                let r = AxisAligned::new(0.1, 0.2).unwrap();
                let c = Vec2::new(0.05, -0.1);
                assert_eq!(
                    rect::p22_rect(r, Vec2::new(NAN, 0.0), Vec2::splat(0.1)),
                    0.0
                );
                // NaN half extents count as 0: both NaN (or one NaN, one 0) is the unfiltered
                // lobe bit for bit, as a zero footprint is; in the batch too (its lanes hand
                // these elements to the scalar path).
                let hv = Vec3::new(-0.1, 0.05, 0.99).normalize();
                for half in [
                    Vec2::new(NAN, NAN),
                    Vec2::new(NAN, 0.0),
                    Vec2::new(-0.0, NAN),
                ] {
                    assert_eq!(
                        rect::p22_rect(r, c, half).to_bits(),
                        Ggx::new(r).p22(c).to_bits()
                    );
                    assert_eq!(
                        rect::d_rect(r, hv, half).to_bits(),
                        Ggx::new(r).d(hv).to_bits()
                    );
                    let mut out = [1.0; 40];
                    let (x, y, z) = ([hv.x; 40], [hv.y; 40], [hv.z; 40]);
                    batch::d_rect(&r, &x, &y, &z, &[half.x; 40], &[half.y; 40], &mut out);
                    assert!(
                        out.iter()
                            .all(|v| v.to_bits() == Ggx::new(r).d(hv).to_bits())
                    );
                }
                assert_eq!(
                    rect::p22_rect(r, c, Vec2::new(-0.1, 0.2)),
                    rect::p22_rect(r, c, Vec2::new(0.1, 0.2))
                );
                for h in [
                    Vec2::splat(INF),
                    Vec2::splat(F::MAX),
                    Vec2::new(1e-30, 1e30),
                ] {
                    let v = rect::p22_rect(r, c, h);
                    assert!(v.is_finite() && v >= 0.0);
                }
                let v = rect::p22_rect(r, Vec2::splat(F::MAX), Vec2::splat(1.0));
                assert!(v.is_finite() && v >= 0.0);
                for h in [
                    Vec3::new(0.1, 0.0, -1.0),
                    Vec3::X,
                    Vec3::ZERO,
                    Vec3::new(NAN, 0.0, 1.0),
                    Vec3::new(0.0, 0.0, INF),
                ] {
                    assert_eq!(rect::d_rect(r, h, Vec2::splat(0.1)), 0.0, "{h:?}");
                }
                let h = Vec3::new(0.1, 0.2, 1.0).normalize();
                assert_eq!(rect::d_rect(r, h, Vec2::ZERO), Ggx::new(r).d(h));
                let v = rect::d_rect(r, Vec3::new(1.0, 0.0, 1e-30), Vec2::splat(0.1));
                assert!(v.is_finite() && v >= 0.0);
                assert_eq!(
                    rect::d_rect_printed(r, Vec2::ZERO, Vec3::Z, Vec2::ZERO),
                    0.0
                );
                assert_eq!(
                    rect::d_rect_printed(r, Vec2::new(NAN, 0.0), Vec3::Z, Vec2::splat(0.1)),
                    0.0
                );
                // Proxy: NaN half extent as 0, negative by magnitude; proxy() is always valid.
                assert_eq!(proxy::effective_alpha(0.1, NAN), 0.1);
                assert_eq!(
                    proxy::effective_alpha(0.1, -0.2),
                    proxy::effective_alpha(0.1, 0.2)
                );
                assert_eq!(proxy::effective_alpha_simple(0.1, NAN), 0.1);
                assert_eq!(proxy::effective_alpha(0.1, INF), INF);
                assert_eq!(
                    proxy::proxy(r, Vec2::splat(INF)).alpha(),
                    Vec2::splat(ALPHA_MAX)
                );
                for h in [Vec2::splat(NAN), Vec2::splat(INF), Vec2::splat(-1.0)] {
                    let p = proxy::proxy(r, h);
                    assert!(p.alpha().x >= ALPHA_MIN && p.alpha().y <= ALPHA_MAX);
                    let p = proxy::proxy_simple(r, h);
                    assert!(p.alpha().x >= ALPHA_MIN && p.alpha().y <= ALPHA_MAX);
                }
            }

            #[test]
            fn isotropic_filters() {
                use filtered_ndf::$p::filter::deferred::{
                    Domain, KAPPA, filtered_alpha, normal_difference_covariance,
                };
                let sig = Covariance::new(0.01, 0.0, 0.02);
                for a in [NAN, -1.0, -INF] {
                    assert_eq!(
                        filtered_alpha(a, &Covariance::ZERO, Bandwidth::Max, KAPPA),
                        0.0
                    );
                }
                assert_eq!(filtered_alpha(INF, &sig, Bandwidth::Trace, KAPPA), 1.0);
                for bw in [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average] {
                    let nan = Covariance::new(NAN, 0.0, 0.0);
                    assert_eq!(bw.alpha2(&nan), 0.0);
                    // A NaN kernel entry counts as 0: no widening from it.
                    let a = filtered_alpha(0.1, &nan, bw, KAPPA);
                    assert!((a * a - 0.01).abs() < TOL);
                    // An infinite one counts as kappa (the maximal clamped kernel).
                    let a = filtered_alpha(0.1, &Covariance::new(INF, 0.0, 0.0), bw, KAPPA);
                    assert!((a * a - (0.01 + KAPPA)).abs() < TOL);
                    // Indefinite: negative eigenvalues count as 0.
                    let v = filtered_alpha(0.1, &Covariance::new(-1.0, 0.0, -1.0), bw, KAPPA);
                    assert!(v.is_finite() && v >= 0.0);
                }
                for (_, conv) in presets::ALL {
                    for (u, v) in [
                        (Vec3::new(NAN, 0.0, 0.0), Vec3::ZERO),
                        (Vec3::splat(INF), Vec3::ZERO),
                        (Vec3::ZERO, Vec3::ZERO),
                        (Vec3::splat(1e30), Vec3::splat(-1e30)),
                    ] {
                        for a in [NAN, -1.0, 0.0, 0.5, 1e30, INF] {
                            let x = conv.apply(a, u, v);
                            assert!(
                                x.is_finite() && (0.0..=ALPHA_MAX).contains(&x),
                                "{a} {u:?}: {x}"
                            );
                        }
                    }
                }
                assert!(
                    normal_difference_covariance(Vec3::new(NAN, 0.0, 0.0), Vec3::ZERO, 0.5)
                        .s11
                        .is_nan()
                );
                assert_eq!(Domain::ProjectedAlpha2.from_alpha(1.0), INF);
                assert_eq!(Domain::ProjectedAlpha2.to_alpha(INF), 1.0);
            }

            #[test]
            fn jacobians_and_slope_maps() {
                for h in [Vec3::ZERO, Vec3::new(NAN, 0.0, 1.0), Vec3::splat(INF)] {
                    assert_eq!(jacobian::sanitize(h), Vec3::Z);
                    assert_eq!(jacobian::sphere_to_projected(h), Mat2::IDENTITY);
                }
                for h in [
                    Vec3::new(0.6, 0.8, -0.3),
                    -Vec3::Z,
                    Vec3::X,
                    Vec3::new(3.0, 4.0, 0.0) * 1e20,
                ] {
                    let s = jacobian::sanitize(h);
                    assert!(
                        (s.z - jacobian::HZ_MIN).abs() <= TOL * jacobian::HZ_MIN,
                        "{h:?} -> {s:?}"
                    );
                    for m in [
                        jacobian::sphere_to_projected(h),
                        jacobian::projected_to_slope(h),
                        jacobian::slope_to_projected(h),
                        jacobian::sphere_to_slope(h),
                    ] {
                        assert!(m.is_finite());
                    }
                    assert!(jacobian::det_projected_to_slope(h).is_finite());
                }
                // Non-unit h is normalised.
                let h = Vec3::new(0.3, 0.1, 0.8);
                assert!((jacobian::sanitize(h * 1e3) - jacobian::sanitize(h)).length() < TOL);
                // Slope maps: finite at and beyond the horizon.
                assert!(slope::slope_from_sphere(Vec3::X).is_finite());
                assert!(slope::slope_from_sphere(Vec3::new(0.6, 0.0, -0.8)).is_finite());
                assert_eq!(
                    slope::sphere_from_slope(Vec2::new(INF, 0.0)),
                    Vec3::new(-1.0, 0.0, 0.0)
                );
                assert_eq!(slope::sphere_from_projected(Vec2::new(3.0, 4.0)).z, 0.0);
                assert!(slope::slope_from_projected(Vec2::new(2.0, 0.0)).is_finite());
                assert_eq!(
                    slope::slope_from_sphere(Vec3::new(NAN, 0.0, 1.0)).x,
                    -F::MAX
                );
                assert!(slope::slope_from_sphere(Vec3::new(0.5, 0.0, NAN)).is_finite());
                assert!(slope::sphere_from_slope(Vec2::new(NAN, 0.0)).x.is_nan());
                assert_eq!(slope::sphere_from_projected(Vec2::ZERO), Vec3::Z);
            }

            #[test]
            fn geometry() {
                use filtered_ndf::$p::footprint::geometry::{
                    self as g, Endpoint, PinholeRay, ShadingFrame,
                };
                let frame = ShadingFrame::flat(Vec3::X, Vec3::Y, Vec3::Z);
                let x = Vec3::ZERO;
                // Eye on the shading point, opposite directions, NaN: degenerate -> zero / +z.
                for (e, l) in [
                    (Endpoint::Point(x), Endpoint::Direction(Vec3::Z)),
                    (Endpoint::Direction(Vec3::X), Endpoint::Direction(-Vec3::X)),
                    (
                        Endpoint::Direction(Vec3::new(NAN, 0.0, 1.0)),
                        Endpoint::Direction(Vec3::Z),
                    ),
                    (
                        Endpoint::Direction(Vec3::ZERO),
                        Endpoint::Direction(Vec3::Z),
                    ),
                ] {
                    assert_eq!(g::half_vector(x, e, l, &frame), Vec3::Z);
                    assert_eq!(g::half_vector_jacobian(x, e, l, &frame), Mat2::ZERO);
                }
                // Below the horizon: clamped, finite.
                let m = g::half_vector_jacobian(
                    x,
                    Endpoint::Point(Vec3::new(1.0, 0.0, -1.0)),
                    Endpoint::Direction(Vec3::new(1.0, 0.0, -0.1)),
                    &frame,
                );
                assert!(m.is_finite());
                assert_eq!(
                    g::half_vector_jacobian_far_field(Vec3::ZERO, &frame),
                    Mat2::ZERO
                );
                assert_eq!(
                    g::half_vector_jacobian_far_field(Vec3::new(NAN, 0.0, 1.0), &frame),
                    Mat2::ZERO
                );
                // An infinite Jacobian entry saturates (infinite entries, never NaN); a NaN one
                // counts as 0.
                let f = g::footprint(
                    Mat2::from_cols(Vec2::splat(INF), Vec2::ZERO),
                    &frame,
                    Vec3::X,
                    Vec3::Y,
                );
                let e = [f.dh_u.x, f.dh_u.y, f.dh_v.x, f.dh_v.y];
                assert!(e.iter().all(|x| !x.is_nan()) && e.iter().any(|x| x.is_infinite()));
                assert_eq!(
                    g::footprint(
                        Mat2::from_cols(Vec2::splat(NAN), Vec2::ZERO),
                        &frame,
                        Vec3::X,
                        Vec3::Y
                    ),
                    Footprint::ZERO
                );
                let ray = PinholeRay {
                    origin: Vec3::Z,
                    dir: Vec3::X,
                    ddir_du: Vec3::Y,
                    ddir_dv: Vec3::Z,
                };
                assert_eq!(g::tangent_plane_differentials(&ray, x, Vec3::Z), None);
                let fp = g::footprint_projected(
                    Footprint::from_slope_derivatives(Vec2::X, Vec2::Y),
                    Vec3::new(NAN, 0.0, 0.0),
                );
                assert!(fp.dh_u.is_finite());
            }

            #[test]
            fn implicit_quadric_temporal() {
                use filtered_ndf::$p::temporal::implicit::{self, d_normalized, project};
                let zero = LevelSetSample::default();
                let ray = MovingRay::fixed(Vec3::ZERO, Vec3::Z);
                assert_eq!(implicit::hit_rates(&zero, &ray, 1.0), HitRates::ZERO);
                let tangent = LevelSetSample {
                    grad: Vec3::X,
                    dphi_dt: 1.0,
                    ..zero
                };
                assert_eq!(implicit::hit_rates(&tangent, &ray, 1.0), HitRates::ZERO);
                let nan = LevelSetSample {
                    grad: Vec3::Z,
                    dphi_dt: NAN,
                    ..zero
                };
                assert_eq!(implicit::hit_rates(&nan, &ray, 1.0), HitRates::ZERO);
                assert_eq!(
                    implicit::hit_distance_rate(
                        &LevelSetSample {
                            grad: Vec3::Z,
                            ..zero
                        },
                        &ray,
                        INF
                    ),
                    0.0
                );
                assert_eq!(zero.normal(), Vec3::ZERO);
                assert_eq!(zero.shape_operator(), Sym3::ZERO);
                assert_eq!(project(Vec3::ZERO, Vec3::X), Vec3::X);
                assert_eq!(project(Vec3::Z, Vec3::new(NAN, 0.0, 0.0)), Vec3::ZERO);
                assert_eq!(d_normalized(Vec3::ZERO, Vec3::X), Vec3::ZERO);
                assert!(LocalQuadric::new(Vec3::ZERO, Vec3::ZERO, Vec3::X, 1.0, 1.0).is_none());
                assert!(LocalQuadric::new(Vec3::ZERO, Vec3::Z, Vec3::Z, 1.0, 1.0).is_none());
                assert!(LocalQuadric::new(Vec3::ZERO, Vec3::Z, Vec3::X, NAN, 1.0).is_none());
                for (rate, dt) in [
                    (Vec2::new(NAN, 0.0), 1.0),
                    (Vec2::ZERO, 1.0),
                    (Vec2::X, -1.0),
                    (Vec2::X, NAN),
                    (Vec2::X, 0.0),
                ] {
                    assert_eq!(
                        TemporalRoughness::from_normal_rate(rate, dt),
                        TemporalRoughness::ZERO
                    );
                }
                assert_eq!(
                    TemporalRoughness::from_normal_rate(Vec2::splat(F::MAX), F::MAX).alpha(),
                    ALPHA_MAX
                );
                let t = TemporalRoughness::from_normal_rate(Vec2::X, 0.1);
                assert_eq!(t.cosine_weighted(NAN), TemporalRoughness::ZERO);
                assert_eq!(t.share(NAN), TemporalRoughness::ZERO);
                assert_eq!(t.share(5.0), t);
                assert_eq!(temporal::box_shutter_dt(NAN), 0.0);
                assert_eq!(temporal::box_shutter_dt(-1.0), 0.0);
                assert!(valid(TemporalRoughness::ZERO.roughness_matrix(NAN)));
                let lobe = TemporalLobe::ggx(iso(), t.covariance());
                assert_eq!(
                    lobe.lambda(Vec3::new(0.3, 0.2, 0.7)),
                    Ggx::new(iso()).lambda(Vec3::new(0.3, 0.2, 0.7))
                );
                assert_eq!(lobe.d(-Vec3::Z), 0.0);
            }
        }
    };
}

contract!(contract_f32, f32);
contract!(contract_f64, f64);
