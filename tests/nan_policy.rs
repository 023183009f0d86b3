//! The NaN and infinity policy for footprints and normal differences (`filtered_ndf::contract`,
//! "Footprints and normal differences: one NaN policy"): a NaN entry carries no information
//! and counts as `0` (it widens nothing); a `+-inf` entry saturates to the widest kernel the
//! clamp rules allow. The forward route (footprints, every method of the front door) and the
//! deferred route (normal differences, every engine convention) follow it alike, in `f32`
//! and in `f64`.
//!
//! References: the same call with the NaN entries replaced by `0` by hand, compared bit for
//! bit (the policy is a substitution, so the results must be identical, not close); for
//! infinities, the call with the widest footprint or the clamp value written out. None of the
//! expected values comes from the code under test's handling of NaN or infinity.

macro_rules! nan_policy {
    ($m:ident, $p:ident) => {
        mod $m {
            use filtered_ndf::$p::filter::deferred::{Bandwidth, filtered_alpha};
            use filtered_ndf::$p::filter::presets;
            use filtered_ndf::$p::prelude::*;
            use filtered_ndf::$p::{Covariance, F, Vec2, Vec3};

            const NAN: F = F::NAN;
            const INF: F = F::INFINITY;

            /// Footprints with one NaN entry at each of the four positions, with the same
            /// footprint with that entry zeroed by hand.
            fn nan_footprints() -> Vec<(Footprint, Footprint)> {
                let (u, v) = (Vec2::new(0.03, -0.01), Vec2::new(0.005, 0.02));
                let mut out = Vec::new();
                for k in 0..4 {
                    let mut e = [u.x, u.y, v.x, v.y];
                    let mut z = e;
                    e[k] = NAN;
                    z[k] = 0.0;
                    let fp = |c: [F; 4]| {
                        Footprint::from_slope_derivatives(
                            Vec2::new(c[0], c[1]),
                            Vec2::new(c[2], c[3]),
                        )
                    };
                    out.push((fp(e), fp(z)));
                }
                out
            }

            fn h() -> Vec3 {
                Vec3::new(0.01, -0.005, 1.0).normalize()
            }

            /// `D(h)` of every method's lobe for a footprint.
            fn lobes(fp: Footprint) -> [F; 7] {
                let g = Ggx::axis_aligned(0.02, 0.03).unwrap();
                let gm = Ggx::isotropic(0.02).unwrap();
                let b = Beckmann::isotropic(0.02).unwrap();
                let h = h();
                [
                    gm.filtered(fp, Gaussian::TK19).d(h),
                    b.filtered(fp, Gaussian::KHPL16).d(h),
                    gm.filtered(fp, ExactGaussian::KHPL16).d(h),
                    gm.filtered(fp, Projected::TK21).d(h),
                    g.filtered(fp, Rect::KHPL16).d(h),
                    g.filtered(fp, Rect::GDC2016).d(h),
                    g.filtered(fp, Proxy::KHPL16).d(h),
                ]
            }

            /// Forward route: a NaN footprint entry filters as `0`, for every method (not "no
            /// filtering at all", not "the widest kernel").
            #[test]
            fn nan_footprint_entry_counts_as_zero() {
                for (nan, zeroed) in nan_footprints() {
                    let (got, want) = (lobes(nan), lobes(zeroed));
                    for (k, (g, w)) in got.iter().zip(want).enumerate() {
                        assert_eq!(g.to_bits(), w.to_bits(), "method {k}, {nan:?}: {g} vs {w}");
                    }
                    // And the zeroed footprint does filter (the test can tell the policies apart).
                    assert!(want[0] < Ggx::isotropic(0.02).unwrap().d(h()));
                }
            }

            /// Forward route: the kernel builders apply the same substitution.
            #[test]
            fn kernel_builders_count_nan_entries_as_zero() {
                for (nan, zeroed) in nan_footprints() {
                    assert_eq!(nan.covariance(0.5), zeroed.covariance(0.5));
                    assert_eq!(nan.bounding_rect(), zeroed.bounding_rect());
                    assert_eq!(
                        ClampRules::default().footprint(nan),
                        ClampRules::default().footprint(zeroed)
                    );
                }
                // A covariance's NaN entry counts as 0 too (then the nearest PSD matrix).
                assert_eq!(
                    Covariance::new(NAN, 0.0, 1e-3).sanitized(),
                    Covariance::new(0.0, 0.0, 1e-3)
                );
                // Beside an infinity, a NaN is what `inf * 0` gives: the widest kernel.
                let kmax = filtered_ndf::$p::kernel::KERNEL_MAX;
                assert_eq!(
                    Covariance::new(INF, NAN, 0.0).sanitized(),
                    Covariance::new(kmax, 0.0, kmax)
                );
            }

            /// Forward route: the footprint constructors drop NaN derivative entries before
            /// mapping them (the other entries still widen the kernel).
            #[test]
            fn footprint_constructors_count_nan_entries_as_zero() {
                let h = Vec3::new(0.2, -0.1, 1.0).normalize();
                let (du, dv) = (
                    Vec3::new(0.01, 0.02, -0.003),
                    Vec3::new(-0.02, 0.005, 0.001),
                );
                let nan_u = Vec3::new(du.x, NAN, du.z);
                let zero_u = Vec3::new(du.x, 0.0, du.z);
                assert_eq!(
                    Footprint::from_half_vector_derivatives(h, nan_u, dv),
                    Footprint::from_half_vector_derivatives(h, zero_u, dv)
                );
                let (pu, pv) = (Vec2::new(0.01, NAN), Vec2::new(NAN, 0.02));
                assert_eq!(
                    Footprint::from_projected_derivatives_in_slope(h, pu, pv),
                    Footprint::from_projected_derivatives_in_slope(
                        h,
                        Vec2::new(0.01, 0.0),
                        Vec2::new(0.0, 0.02)
                    )
                );
                assert_eq!(
                    Footprint::from_normal_differences(nan_u, dv),
                    Footprint::from_normal_differences(zero_u, dv)
                );
                assert_ne!(
                    Footprint::from_normal_differences(zero_u, dv),
                    Footprint::ZERO
                );
            }

            /// Forward route: an infinite derivative saturates: the constructors keep it
            /// infinite and the clamp rules make it the widest footprint they allow (extent
            /// `lambda` along the infinite entries), whatever the finite entries.
            #[test]
            fn infinite_footprint_saturates() {
                let rules = ClampRules::default();
                // Extent `lambda` (centre to vertex) along `+x`: `dh_u = (2 lambda, 0)`.
                let widest = Footprint::from_slope_derivatives(
                    Vec2::new(2.0 * rules.max_extent, 0.0),
                    Vec2::ZERO,
                );
                let fp =
                    Footprint::from_slope_derivatives(Vec2::new(INF, 0.3), Vec2::new(0.1, 0.0));
                assert_eq!(rules.footprint(fp), widest);
                let h = Vec3::new(0.0, 0.0, 1.0);
                let inf_fp = Footprint::from_half_vector_derivatives(
                    h,
                    Vec3::new(INF, 0.0, 0.0),
                    Vec3::ZERO,
                );
                assert!(inf_fp.dh_u.x.is_infinite(), "{inf_fp:?}");
                let gm = Ggx::isotropic(0.02).unwrap();
                let at = Vec3::new(0.3, 0.0, 1.0).normalize();
                assert_eq!(
                    gm.filtered(inf_fp, Gaussian::TK19).d(at).to_bits(),
                    gm.filtered(rules.footprint(inf_fp), Gaussian::TK19)
                        .d(at)
                        .to_bits()
                );
                // Saturated, not dropped: the lobe is wider than the unfiltered one.
                assert!(gm.filtered(inf_fp, Gaussian::TK19).d(Vec3::Z) < gm.d(Vec3::Z));
                let n = Footprint::from_normal_differences(Vec3::new(INF, 0.0, 0.0), Vec3::ZERO);
                assert!(n.dh_u.x.is_infinite() && n.dh_u.y == 0.0, "{n:?}");
            }

            /// Deferred route: a NaN entry of a normal difference counts as 0 for every
            /// engine convention, and an infinite one gives the clamp (the widest kernel).
            #[test]
            fn nan_normal_difference_entry_counts_as_zero() {
                let (du, dv) = (Vec3::new(0.02, -0.01, 0.003), Vec3::new(0.004, 0.015, 0.0));
                for (name, conv) in presets::ALL {
                    for alpha in [0.01, 0.2] {
                        for k in 0..6 {
                            let mut e = [du.x, du.y, du.z, dv.x, dv.y, dv.z];
                            let mut z = e;
                            e[k] = NAN;
                            z[k] = 0.0;
                            let v = |c: [F; 6]| {
                                (Vec3::new(c[0], c[1], c[2]), Vec3::new(c[3], c[4], c[5]))
                            };
                            let ((nu, nv), (zu, zv)) = (v(e), v(z));
                            let (got, want) =
                                (conv.apply(alpha, nu, nv), conv.apply(alpha, zu, zv));
                            assert_eq!(
                                got.to_bits(),
                                want.to_bits(),
                                "{name}, entry {k}: {got} vs {want}"
                            );
                        }
                        // Infinite: the clamp, i.e. the widest kernel the convention allows.
                        let inf = conv.apply(alpha, Vec3::new(INF, 0.0, 0.0), Vec3::ZERO);
                        assert_eq!(
                            inf.to_bits(),
                            conv.apply_widening(alpha, conv.clamp).to_bits(),
                            "{name}"
                        );
                    }
                }
            }

            /// Deferred route from a covariance (TK19 eq. 1, 4, 5): a NaN entry counts as 0.
            #[test]
            fn nan_kernel_entry_of_the_bandwidths_counts_as_zero() {
                for bw in [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average] {
                    let got = filtered_alpha(0.05, &Covariance::new(2e-3, NAN, 1e-3), bw, 0.18);
                    let want = filtered_alpha(0.05, &Covariance::new(2e-3, 0.0, 1e-3), bw, 0.18);
                    assert_eq!(got.to_bits(), want.to_bits(), "{bw:?}");
                    assert!(want > 0.05);
                }
            }
        }
    };
}

nan_policy!(nan_policy_f32, f32);
nan_policy!(nan_policy_f64, f64);
