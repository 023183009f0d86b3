//! Fixed-seed replay of every fuzz target's contract (`fuzz/fuzz_targets/*.rs`) without a
//! fuzzer: the same decoders and checks (`filtered_ndf::testing::fuzz::check_*`) over seeded
//! random byte strings, every special value in every parameter slot (NDF family), and the
//! regression inputs of every crash the fuzzer found.

use filtered_ndf::testing::fuzz::{
    check_batch, check_filter, check_gaussian_ggx, check_isotropic, check_jacobian, check_ndf,
    check_rect, check_sampling, check_temporal,
};

use filtered_ndf::testing::rng::SplitMix64 as Rng;

/// `n` seeded random byte strings of length `0..max_len` through `check`.
fn replay(seed: u64, n: usize, max_len: u64, check: fn(&[u8])) {
    let mut rng = Rng(seed);
    for _ in 0..n {
        let len = (rng.next_u64() % max_len) as usize;
        let bytes: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        check(&bytes);
    }
}

#[test]
fn seeded_random_bytes() {
    replay(0xF022_0001, 4000, 96, check_ndf);
}

#[test]
fn seeded_random_bytes_filter() {
    replay(0xF022_0002, 3000, 256, check_filter);
}

#[test]
fn seeded_random_bytes_rect() {
    replay(0xF022_0003, 3000, 96, check_rect);
}

#[test]
fn seeded_random_bytes_isotropic() {
    replay(0xF022_0004, 3000, 128, check_isotropic);
}

#[test]
fn seeded_random_bytes_jacobian() {
    replay(0xF022_0005, 3000, 256, check_jacobian);
}

#[test]
fn seeded_random_bytes_sampling() {
    replay(0xF022_0006, 3000, 128, check_sampling);
}

#[test]
fn seeded_random_bytes_temporal() {
    replay(0xF022_0007, 3000, 256, check_temporal);
}

#[test]
fn seeded_random_bytes_gaussian_ggx() {
    replay(0xF022_0008, 2000, 128, check_gaussian_ggx);
}

#[test]
fn seeded_random_bytes_batch() {
    replay(0xF022_0009, 400, 2048, check_batch);
}

/// Every special-value tag (0..=14) in each of the first parameter and argument slots, for
/// every model/form/normalise header, with the other slots ordinary.
#[test]
fn every_special_value_in_every_slot() {
    // Tag 15 followed by two bytes is an ordinary value; 13 is 1.0.
    let ordinary = [15u8, 0x40, 0xa0];
    for head in 0u8..16 {
        for slot in 0..15 {
            for tag in 0u8..15 {
                let mut bytes = vec![head];
                for k in 0..15 {
                    if k == slot {
                        bytes.push(tag);
                    } else if k < 4 {
                        bytes.push(13); // roughness 1
                    } else {
                        bytes.extend_from_slice(&ordinary);
                    }
                }
                check_ndf(&bytes);
            }
        }
    }
}

/// Inputs that once broke the contract (found by the fuzzer or while writing the checks).
#[test]
fn regressions() {
    let cases: &[&[u8]] = &[
        // Empty input: everything decodes to NaN.
        &[],
        // Huge finite directions (f32::MAX components): Lambda once overflowed its quadratic
        // form; now rescaled.
        &[
            0, 13, 13, 13, 13, 13, 13, 11, 11, 11, 11, 11, 11, 11, 11, 11,
        ],
        &[1, 13, 13, 13, 13, 13, 13, 5, 5, 5, 5, 5, 5, 5, 5, 5],
    ];
    for c in cases {
        check_ndf(c);
    }
}

/// Every crash input the fuzzer found (`tests/data/fuzz_regressions/<target>/`, copied from
/// `fuzz/artifacts/<target>/`), replayed through its target's check.
#[test]
fn regression_corpus() {
    type Check = fn(&[u8]);
    let targets: [(&str, Check); 9] = [
        ("ndf", check_ndf),
        ("filter", check_filter),
        ("rect", check_rect),
        ("isotropic", check_isotropic),
        ("jacobian", check_jacobian),
        ("sampling", check_sampling),
        ("temporal", check_temporal),
        ("gaussian_ggx", check_gaussian_ggx),
        ("batch", check_batch),
    ];
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fuzz_regressions");
    // Every folder there is a target's (a crash input filed under a misspelt name would never
    // be replayed), and every file in it is replayed; a target without findings has no folder.
    let mut replayed = 0;
    for entry in std::fs::read_dir(&root).unwrap() {
        let folder = entry.unwrap().path();
        let name = folder.file_name().unwrap().to_str().unwrap().to_owned();
        let Some((_, check)) = targets.iter().find(|(t, _)| *t == name) else {
            panic!("{}: not a fuzz target's folder", folder.display());
        };
        for file in std::fs::read_dir(&folder).unwrap() {
            let path = file.unwrap().path();
            let bytes = std::fs::read(&path).unwrap();
            eprintln!("{}", path.display());
            check(&bytes);
            replayed += 1;
        }
    }
    // At least the 33 inputs filed when this check was written (findings are only added).
    assert!(replayed >= 33, "{replayed} regression inputs replayed");
}

/// The findings of the replay and the fuzzers, one direct call each (the minimal input the
/// decoder produced), so that each fix is pinned independently of the decoders' byte layout.
mod findings {
    use filtered_ndf::{f32, f64};
    use glam::{DVec2, DVec3, Vec2, Vec3};

    #[test]
    fn lambda_rect_of_a_direction_near_overflow() {
        // The rescaling of a direction whose largest component has binary exponent 1023
        // multiplied by 0 (2^-1023 has no exponent field) and answered the zero vector's 0:
        // found by the box lobe's contract check. GGX's own Lambda here is 9.9e307; the box only
        // adds masking, so the box lobe's Lambda is at least that (Jensen), +inf once the box is
        // wide.
        let r = f64::AxisAligned::new(1.0, 1.0).unwrap();
        let w = DVec3::new(-1.0, f64::MAX, 0.9066);
        use f64::Ndf;
        let lg = f64::Ggx::new(r).lambda(w);
        assert!(lg > 9.9e307, "{lg:e}");
        // GGX's Lambda at a grazing direction whose |w_z| is near 1e-308 after rescaling:
        // Lambda = q / (2 |w_z| (r + |w_z|)) -> sqrt(q) / (2 |w_z|) = (alpha_y w_y / w_z) / 2
        // exactly here; the subnormal product kept 8 digits (6e-9 off), now 1e-15.
        let ra = f64::AxisAligned::new(1e4, 1e-8).unwrap();
        let wa = DVec3::new(-9.95e-307, f64::MAX, 1.0);
        let expect = f64::MAX * 1e-8 / 2.0;
        let la = f64::Ggx::new(ra).lambda(wa);
        assert!((la / expect - 1.0).abs() < 1e-14, "{la:e} vs {expect:e}");
        // A subnormal |w_z| beside a unit w_xy (no rescaling): Lambda = sqrt(q) / (2 |w_z|)
        // = 1e-4 / 2e-310 = 5e305 to 1e-9 (w_z = 1e-310 carries 44 bits); 1 / (2 |w_z|)
        // alone would overflow (the reason the formula divides twice).
        let ri = f64::Isotropic::new(1e-4).unwrap();
        let ls = f64::Ggx::new(ri).lambda(DVec3::new(1.0, 0.0, 1e-310));
        assert!((ls / 5e305 - 1.0).abs() < 1e-9, "{ls:e}");
        for hy in [1.0, 1e10, f64::INFINITY] {
            let l = f64::filter::rect::lambda_rect(r, DVec2::new(1.57, hy), w);
            assert!(l >= lg, "half_y {hy:e}: {l:e} < {lg:e}");
        }
        let m = f64::sampling::rect::sample_visible_normal_rect(
            r,
            DVec2::new(1.57, 1.0),
            w,
            DVec2::new(0.3, 0.7),
            DVec2::new(0.2, 0.9),
        );
        assert!(m.is_some_and(|m| m.is_finite() && m.z > 0.0), "{m:?}");
    }

    #[test]
    fn clamp_eigenvalues_nan_entry_is_zero() {
        // The fast path passed a NaN off-diagonal through.
        let c = f64::Covariance::new(0.1, f64::NAN, 0.1).clamp_eigenvalues(1.0);
        assert_eq!(c, f64::Covariance::ZERO);
        let c = f64::Covariance::new(f64::INFINITY, 0.0, 0.0).clamp_eigenvalues(f64::INFINITY);
        assert_eq!(c, f64::Covariance::ZERO);
    }

    #[test]
    fn clamp_eigenvalues_subnormal_and_small_bounds() {
        // f32: 1 / (2 r) overflowed for subnormal entries (NaN out).
        let c = f32::Covariance::new(1e-40, 0.0, 0.0).clamp_eigenvalues(5e-41);
        assert!(c.s11.is_finite() && c.s11 <= 5e-41 && c.s12 == 0.0, "{c:?}");
        // f32: `max / scale` was subnormal and rebuilt the bound 40 % too large.
        let c = f32::Covariance::new(1.0, 0.0, 1.0).clamp_eigenvalues(1e-30);
        assert!(c.eigenvalues().1 <= 1e-30 * (1.0 + 1e-6), "{c:?}");
        let c = f32::Covariance::new(1.0, 0.3, 0.5).clamp_eigenvalues(1e-30);
        assert!(c.eigenvalues().1 <= 1e-30 * (1.0 + 1e-5), "{c:?}");
    }

    #[test]
    fn clamp_eigenvalues_of_indefinite_inputs() {
        // Found while making the clamp total over indefinite input (issue 16, item 2).
        // A negative diagonal entry that underflows to -0 when scaled: still dropped.
        let c = f32::Covariance::new(f32::MAX, 1.98, -1e-30).clamp_eigenvalues(f32::MAX);
        assert!(c.s11 > 0.0 && c.s22 >= 0.0, "{c:?}");
        // A dominant negative eigenvalue: lambda_max = det / lambda_min = 1.364 (no
        // cancellation in mean + rad), kept along x.
        let c = f64::Covariance::new(1.364, -1e-30, -1.145e16).clamp_eigenvalues(10.0);
        assert!((c.s11 - 1.364).abs() <= 1e-15 && c.s12.abs() <= 1e-45 && c.s22 >= 0.0);
        // lambda_max = det / lambda_min = (1e30 * 1e-30 + 0.9966^2) / 1e30 = 1.993e-30 where
        // the unit-size matrix underflows (f32): along y.
        let c = f32::Covariance::new(-1e30, -0.9966, 1e-30).clamp_eigenvalues(1.0);
        let want = (1.0 + 0.9966f64 * 0.9966) / 1e30;
        assert!(
            ((c.s22 as f64) - want).abs() <= 1e-6 * want && c.s11 == 0.0,
            "{c:?}"
        );
        // Negative definite (det = 1 - 0.749^2 > 0, trace < 0): nothing left.
        let c = f32::Covariance::new(-1e-30, -0.749, -1e30).clamp_eigenvalues(f32::INFINITY);
        assert_eq!(c, f32::Covariance::ZERO);
        // lambda_max = 1.618 f32::MAX is not representable: clamped to F::MAX, finite.
        let c = f32::Covariance::new(f32::MAX, f32::MAX, 1.0).clamp_eigenvalues(f32::INFINITY);
        assert!(
            c.s11.is_finite() && c.s12.is_finite() && c.s22.is_finite(),
            "{c:?}"
        );
        // mean - rad overflows although lambda_max = 3.4028e38 is finite: computed scaled.
        let (lo, hi) = f32::Covariance::new(-2.2539338e33, f32::MAX, -1.0).eigenvalues();
        assert!(
            lo == 0.0 && (hi as f64 - 3.4028122e38).abs() <= 1e-6 * 3.4e38,
            "{hi}"
        );
    }

    #[test]
    fn eigenvalues_of_huge_and_tiny_entries() {
        // f32: det overflowed to inf and lambda_min came out as inf (> lambda_max).
        let (lo, hi) = f32::Covariance::new(1e30, 0.0, 1e30).eigenvalues();
        assert!(
            (lo - 1e30).abs() <= 1e24 && (hi - 1e30).abs() <= 1e24,
            "{lo} {hi}"
        );
        let (lo, hi) = f32::Covariance::new(1e30, 0.0, 1e25).eigenvalues();
        assert!((lo - 1e25).abs() <= 1e19 && hi == 1e30, "{lo} {hi}");
        // f32: a subnormal det lost its bits (lambda_min > lambda_max).
        let (lo, hi) = f32::Covariance::new(2e-22, 0.0, 2e-22).eigenvalues();
        assert!(lo <= hi && (lo - 2e-22).abs() <= 1e-27, "{lo} {hi}");
    }

    #[test]
    fn sanitized_underflowing_off_diagonal() {
        // f32: b * b <= a * c held by underflow for an indefinite [[0, 1e-30], [1e-30, 0]].
        let c = f32::Covariance::new(-0.0, 1e-30, 0.0).sanitized();
        assert_eq!(c.s12, 0.0, "{c:?}");
    }

    #[test]
    fn in_slope_footprint_of_a_huge_h() {
        // f32: 1 - h_y^2 overflowed to -inf, times 0 = NaN.
        let h = Vec3::new(1e30, 1e30, 1e30);
        let f =
            f32::Footprint::from_projected_derivatives_in_slope(h, Vec2::new(-1.0, 0.0), Vec2::Y);
        assert!(f.dh_u.is_finite() && f.dh_v.is_finite(), "{f:?}");
        // Only the direction counts: the same as (1, 1, 1), bit for bit (both normalise to
        // (1, 1, 1) / sqrt(3) in `vector::unit`).
        let unit = f32::Footprint::from_projected_derivatives_in_slope(
            Vec3::ONE,
            Vec2::new(-1.0, 0.0),
            Vec2::Y,
        );
        assert_eq!(f, unit);
    }

    #[test]
    fn clamp_rules_footprint_with_huge_lambda() {
        // f64: e / cur overflowed to inf and 0 * inf gave NaN.
        let rules = f64::ClampRules {
            max_extent: f64::MAX,
            ..f64::ClampRules::NONE
        };
        let fp = f64::Footprint::from_slope_derivatives(
            DVec2::new(f64::INFINITY, f64::INFINITY),
            DVec2::new(-6.7e41, -2.6e34),
        );
        let f = rules.footprint(fp);
        assert!(!f.dh_u.is_nan() && !f.dh_v.is_nan(), "{f:?}");
    }

    #[test]
    fn projected_filter_with_a_huge_rank_one_kernel() {
        // f32: det(P + 2K) cancelled and the minor axis came out 60x sharper than alpha.
        let a = f32::Isotropic::new(1e-8).unwrap();
        let k = f32::Covariance::new(1e30, -1e30, 1.5013107e12);
        let (a11, _, a22) = f32::filter::projected(a, k).entries();
        assert!(a11 >= 1e-16 && a22 >= 1e-16 * (1.0 - 1e-4), "{a11} {a22}");
    }

    #[test]
    fn projected_filter_keeps_a_tiny_diagonal_positive() {
        // f64: a subnormal a11 (accepted with a large tau) became 0 or -5e-324.
        use f64::Roughness;
        let r = f64::RoughnessMatrix::new_with_det_clamp(5e-324, 5e-324, 0.776, 0.1).unwrap();
        let p = f64::filter::projected(r, f64::Covariance::ZERO);
        let (a11, _, a22) = p.entries();
        assert!(
            a11 > 0.0 && a22 > 0.0 && p.sqrt_det() > 0.0,
            "{:?}",
            p.entries()
        );
    }

    #[test]
    fn gaussian_with_det_clamp_zero_and_an_underflowing_det() {
        // f32: the filtered det underflowed to 0 without tau: sqrt_det 0, inverse inf.
        use f32::Roughness;
        let r = f32::RoughnessMatrix::new_with_det_clamp(2.2525264e-23, 0.0, 2.2525264e-23, 1e-16)
            .unwrap();
        let k = f32::Covariance::new(1.1262632e-23, 1.1262632e-23, 0.0);
        let g = f32::filter::gaussian_with_det_clamp(r, k, 0.0);
        assert!(
            g.sqrt_det() > 0.0 && g.sqrt_det().is_finite(),
            "{:?}",
            g.entries()
        );
    }

    #[test]
    fn filters_keep_a_clamped_matrix_clamp() {
        // f32: entries 1e-40 (singular) clamped to det A_c = 1 evaluate as about the identity;
        // filtered without a clamp, A + 2 Sigma had det 2e-80 and D(0) = 1 / (pi sqrt(det))
        // overflowed to inf. A kernel of 1e-40 next to A_c ~ I changes nothing measurable, so
        // each filter must return a lobe with D(0) = 1 / pi (the identity's peak, GGX and
        // Beckmann alike) to a few f32 ulps (tolerance 1e-6 relative: the clamp shift's
        // rounding and 1 / pi's).
        use f32::{Ndf, Roughness};
        let r = f32::RoughnessMatrix::new_with_det_clamp(1e-40, 1e-40, 1e-40, 1.0).unwrap();
        let k = f32::Covariance::new(1e-40, 0.0, 0.0);
        let peak = 1.0 / core::f64::consts::PI;
        let rules = f32::ClampRules {
            det_clamp: false,
            ..f32::ClampRules::DEFAULT
        };
        assert_eq!(rules.det_clamp_for(r), 1.0);
        let fp = f32::Footprint::from_slope_derivatives(Vec2::new(1e-20, 0.0), Vec2::ZERO);
        for (g, what) in [
            (
                f32::filter::gaussian_with_det_clamp(r, k, 0.0),
                "gaussian_with_det_clamp",
            ),
            (
                f32::filter::projected_with_det_clamp(r, k, 0.0),
                "projected_with_det_clamp",
            ),
            (
                rules.filter_gaussian(r, fp, 1.0),
                "filter_gaussian without det_clamp",
            ),
            (
                rules.filter_projected(r, fp, 1.0),
                "filter_projected without det_clamp",
            ),
        ] {
            for d in [
                f32::Ggx::new(g).d(Vec3::Z),
                f32::Beckmann::new(g).d(Vec3::Z),
            ] {
                assert!(
                    (f64::from(d) / peak - 1.0).abs() < 1e-6,
                    "{what}: D(0) = {d} for {:?}, sqrt_det {}",
                    g.entries(),
                    g.sqrt_det()
                );
            }
        }
    }

    #[test]
    fn gaussian_filtered_ggx_far_tail_of_a_sharp_lobe() {
        // The far-tail series formed P = l1 c1^2 + l2 c2^2 before dividing by beta: at a
        // slope of 1e137 (1e145 lobe widths, the widest kernel) P overflowed while beta^-2
        // underflowed, 0 inf = NaN. There the density is below every f64 (GGX's tail
        // alpha^2 / (pi |s|^4) = 1e-565), so 0; at 1e60 it is representable, and a kernel of
        // 1e8 slope^2 beside |s|^2 = 1e120 changes GGX's tail by a relative 1e-112: the
        // filtered lobe equals GGX's closed form there to rounding (1e-12 relative: the
        // series' and GGX's few roundings).
        use f64::Ndf;
        let r = f64::Isotropic::new(1e-8).unwrap();
        let lobe =
            f64::GaussianFilteredGgx::new(r, f64::Covariance::new(-0.0, 1e30, f64::INFINITY));
        for s in [
            DVec2::new(8.783404179181653e137, -1e-30),
            DVec2::new(0.0, 1e137),
        ] {
            assert_eq!(lobe.p22(s), 0.0, "{s:?}");
        }
        let s = DVec2::new(1e60, 0.0);
        let (p, g) = (lobe.p22(s), f64::Ggx::new(r).p22(s));
        assert!(g > 0.0 && (p / g - 1.0).abs() < 1e-12, "{p:e} vs GGX {g:e}");
    }

    #[test]
    fn clamp_eigenvalues_at_the_top_of_the_range() {
        // The bound F::MAX itself let the rebuilt s22 round past it: (0, 1e30, inf). The
        // eigenvalues of [[-1.39e305, 1e30], [1e30, F::MAX]] are F::MAX (to 1e-29 relative,
        // s12^2 / F::MAX^2 beside 1) and -1.39e305 (negative: clamped to 0), so the result is
        // F::MAX times the projector on e_y (its off-diagonal s12 / (lambda_max - lambda_min)
        // of it, 1e30 to 1e-3): finite, s22 within 16 eps of F::MAX.
        let c = f64::Covariance::new(-1.3931855364567272e305, 1e30, f64::MAX);
        for max in [f64::MAX, f64::INFINITY] {
            let e = c.clamp_eigenvalues(max);
            assert!(
                e.s11.is_finite() && e.s12.is_finite() && e.s22.is_finite(),
                "{e:?}"
            );
            assert!(e.s11 >= 0.0 && (e.s12 / 1e30 - 1.0).abs() < 1e-3, "{e:?}");
            assert!(
                e.s22 <= f64::MAX && e.s22 >= f64::MAX * (1.0 - 16.0 * f64::EPSILON),
                "{e:?}"
            );
        }
    }

    #[test]
    fn ggx_lambda_of_a_view_within_the_subnormals_of_grazing() {
        // f32: w / max|w| made w_z = 3.4e-45 subnormal (two significant bits) and GGX's
        // Lambda 20 % high. Lambda = (sqrt(1 + alpha^2 |w_xy|^2 / w_z^2) - 1) / 2 is
        // alpha |w_xy| / (2 |w_z|) - 1/2 + O(w_z / |w_xy|) here (a ratio of 3e44): the closed
        // form in f64, to 1e-6 relative (a few f32 roundings). The box lobe's Lambda is at
        // least GGX's (Jensen), equal for a vanishing box.
        use f32::Ndf;
        let r = f32::AxisAligned::new(1e-8, 1e-8).unwrap();
        let w = Vec3::new(1.1450476e34, 3.8746752e-11, 3.8746752e-11);
        let (x, y, z) = (f64::from(w.x), f64::from(w.y), f64::from(w.z));
        let want = 1e-8 * (x * x + y * y).sqrt() / (2.0 * z) - 0.5;
        for l in [
            f32::Ggx::new(r).lambda(w),
            f32::filter::rect::lambda_rect(r, Vec2::new(0.0, 1e-30), w),
        ] {
            assert!(
                (f64::from(l) / want - 1.0).abs() < 1e-6,
                "{l:e} vs {want:e}"
            );
        }
    }

    #[test]
    fn ggx_lambda_of_a_subnormal_w_z() {
        // f64: w_z = 5e-324 (one bit) on input; w / max|w| rounded it to a multiple of the
        // smallest subnormal (w_z / max|w| = 1.3e-313, 2e-11 apart) and GGX's Lambda came out
        // 7e-12 off, below the box lobe's (found by the rect target). Here Lambda =
        // alpha |w_xy| / (2 |w_z|) - 1/2 + O(|w_z| / |w_xy|) with alpha |w_xy| / (2 |w_z|) =
        // 3.9e304: the 1/2 is 1e-305 of it, so the leading term in f64 (four roundings of a
        // few 1e-16) is the reference, to 1e-14 relative. The box lobe's Lambda (a box of
        // 1e-32 lobe widths along w_xy adds (k / m)^2 ~ 1e-65) is the same to 1e-14.
        use f64::Ndf;
        let r = f64::AxisAligned::new(1e-8, 1e-8).unwrap();
        let w = DVec3::new(1e-40, 3.874675120456176e-11, 5e-324);
        let want = 1e-8 * w.x.hypot(w.y) / (2.0 * w.z);
        for l in [
            f64::Ggx::new(r).lambda(w),
            f64::filter::rect::lambda_rect(r, DVec2::new(3.874675120456176e-11, f64::NAN), w),
        ] {
            assert!((l / want - 1.0).abs() < 1e-14, "{l:e} vs {want:e}");
        }
        // No f32 twin: the rescaling only runs for |w| >= 2^20, so a subnormal w_z makes
        // |w_xy| / |w_z| >= 2^20 / 1.4e-45 = 7e50 and Lambda >= 1e-8 of that, beyond f32::MAX.
    }

    #[test]
    fn box_lambda_of_a_huge_direction_with_a_small_w_z() {
        // f64: w = (1, -8.3e298, -3.9e-17) was scaled by 2^-992 into [1, 2), which made w_z
        // subnormal (9e-316, 27 bits): the box lobe's Lambda 9e-10 below GGX's. Lambda =
        // alpha_y |w_y| / (2 |w_z|) - 1/2 + O(|w_z| / |w_xy|) (alpha_x |w_x| adds 1e-582 to
        // q): 1.07e307, the 1/2 far below rounding, so the leading term in f64 (three
        // roundings) is the reference to 1e-14. The box (1e-30 along y, 1e-22 lobe widths;
        // infinite along x, where w_x / |w_xy| = 1e-299) changes the expectation of psi by
        // about 1e-22 relative.
        use f64::Ndf;
        let r = f64::AxisAligned::new(1e4, 1e-8).unwrap();
        let w = DVec3::new(1.0, -8.266521481192677e298, -3.8746751204561125e-17);
        let want = 1e-8 * w.y.abs() / (2.0 * w.z.abs());
        for l in [
            f64::Ggx::new(r).lambda(w),
            f64::filter::rect::lambda_rect(r, DVec2::new(f64::NEG_INFINITY, -1e-30), w),
        ] {
            assert!((l / want - 1.0).abs() < 1e-14, "{l:e} vs {want:e}");
        }
    }

    #[test]
    fn ggx_lambda_of_a_tiny_w_xy_beside_a_large_alpha() {
        // f32: after the rescaling w = (2e-22, 0, -1), and w_x^2 = 3.9e-44 was subnormal (five
        // bits) before its product with alpha^2 = 1e8: GGX's Lambda 1.3 % high, above the box
        // lobe's (found by the rect target). Lambda = (sqrt(1 + x^2) - 1) / 2 with
        // x = alpha |w_xy| / |w_z| = 2e-18 is x^2 / 4 to 1e-36 relative: that in f64 is the
        // reference, to 1e-6 (a few f32 roundings: the rescaling, the product, the square, the
        // quotient). The same in f64 at w_x = 1e-156 (a subnormal square there, 1e-312: 2.5e-12
        // before), to 1e-14.
        use f32::Ndf as _;
        let w = Vec3::new(1e-30, 0.0, -5.080218e-9);
        let x = 1e4 * f64::from(w.x) / f64::from(w.z).abs();
        let want = x * x / 4.0;
        for l in [
            f32::Ggx::new(f32::AxisAligned::new(1e4, 1e4).unwrap()).lambda(w),
            f32::Ggx::new(f32::Isotropic::new(1e4).unwrap()).lambda(w),
            f32::filter::rect::lambda_rect(f32::AxisAligned::new(1e4, 1e4).unwrap(), Vec2::ONE, w),
        ] {
            assert!(
                (f64::from(l) / want - 1.0).abs() < 1e-6,
                "{l:e} vs {want:e}"
            );
        }
        use f64::Ndf as _;
        let w = DVec3::new(1e-156, 0.0, 1.0);
        let want = (1e4 * 1e-156) * (1e4 * 1e-156) / 4.0;
        for l in [
            f64::Ggx::new(f64::AxisAligned::new(1e4, 1e4).unwrap()).lambda(w),
            f64::Ggx::new(f64::Isotropic::new(1e4).unwrap()).lambda(w),
        ] {
            assert!((l / want - 1.0).abs() < 1e-14, "{l:e} vs {want:e}");
        }
    }

    #[test]
    fn box_visible_normal_of_an_infinite_box_near_grazing() {
        // f32: a view 1.2e-30 from grazing beside a box infinite along y; the sample and the
        // sheared cap's pole both rounded onto wo's horizon and the sampler refused. It now
        // returns a unit normal above both horizons (wo.m > 0, checked in f64).
        let r = f32::AxisAligned::new(1e-8, 1e-8).unwrap();
        let wo = Vec3::new(1e30, 1e-30, 1.2156863);
        let half = Vec2::new(1e-30, f32::INFINITY);
        let u = Vec2::splat(1e30);
        let m = f32::sampling::rect::sample_visible_normal_rect(r, half, wo, u, u).unwrap();
        let wom = wo.as_dvec3().dot(m.as_dvec3());
        assert!(
            m.z > 0.0 && (m.length() - 1.0).abs() < 1e-6 && wom > 0.0,
            "{m:?}"
        );
    }

    #[test]
    fn box_lambda_of_a_subnormal_w_z() {
        // f64: mu = |w_z| / |w_xy| was subnormal and lost digits before dividing by a: the box
        // lobe's Lambda 1.4e-12 below GGX's. With a box of 5e-324 (5e-316 lobe widths) the
        // box lobe's Lambda is GGX's, q / (2 w_z (sqrt(w_z^2 + q) + w_z)), here
        // 1.5985629990652341e306 (50-digit decimal arithmetic on the same inputs; the
        // nearest f64); asserted to 1e-14 relative (a few roundings).
        let r = f64::AxisAligned::new(1e-8, 1e-8).unwrap();
        let w = DVec3::new(-1.4844281681544214, 2.0, 7.790396926e-315);
        let want = 1.598562999065234e306;
        let l = f64::filter::rect::lambda_rect(r, DVec2::new(5e-324, f64::NAN), w);
        assert!((l / want - 1.0).abs() < 1e-14, "{l:e}");
    }

    #[test]
    fn footprint_projected_of_a_nan_footprint() {
        let fp = f64::Footprint::from_slope_derivatives(DVec2::NAN, DVec2::NAN);
        let h = DVec3::new(-0.0, 0.0, -1e-30);
        assert_eq!(
            f64::footprint::geometry::footprint_projected(fp, h),
            f64::Footprint::ZERO
        );
    }

    #[test]
    fn half_vector_with_a_non_finite_frame() {
        let frame = f64::ShadingFrame {
            s: DVec3::new(-1e30, 0.0, 0.0),
            t: DVec3::new(f64::INFINITY, 1.0, 0.0),
            n: DVec3::new(1.7, 1.0, f64::NAN),
            dn: glam::DMat2::ZERO,
            twist: DVec2::ZERO,
        };
        let eye = f64::Endpoint::Direction(DVec3::Z);
        let light = f64::Endpoint::Direction(DVec3::new(0.3, 0.0, 1.0));
        assert_eq!(
            f64::footprint::geometry::half_vector(DVec3::ZERO, eye, light, &frame),
            DVec3::Z
        );
    }

    #[test]
    fn jacobian_azimuth_of_subnormal_components() {
        // f64: h_x / hypot(h_x, h_y) was not a unit pair for subnormal components.
        let h = f64::footprint::jacobian::sanitize(DVec3::new(5e-324, 5e-324, -1.1367));
        assert!((h.length() - 1.0).abs() < 1e-15, "{h}");
    }

    #[test]
    fn p22_rect_nan_centre_and_far_tail() {
        let r = f32::AxisAligned::new(1.0, 1e-8).unwrap();
        let p = f32::filter::rect::p22_rect(r, Vec2::new(f32::NAN, f32::MAX), Vec2::ZERO);
        assert_eq!(p, 0.0);
        // f32, alpha = 1e-8, |center| / alpha ~ 1.7e8: the closed form cancelled below zero.
        let r = f32::AxisAligned::new(1e-8, 1e-8).unwrap();
        let p =
            f32::filter::rect::p22_rect(r, Vec2::new(-1.7321126, -0.0), Vec2::new(0.97044325, 1.0));
        assert!(p >= 0.0, "{p}");
    }

    #[test]
    fn visible_normals_for_extreme_views() {
        use f64::NdfSampling;
        // f64: stretching a huge wo overflowed (NaN sample).
        let ggx = f64::Ggx::new(f64::Isotropic::new(2.0).unwrap());
        let wo = DVec3::new(f64::MAX, f64::MAX, 1e300);
        let m = ggx
            .sample_visible_normal(wo, DVec2::new(-1e30, 1.0))
            .unwrap();
        assert!((m.length() - 1.0).abs() < 1e-12 && m.z > 0.0, "{m}");
        // f64: wo_z / |wo| underflows (1e-40 / 1.8e308): a certified m with m_z > 0 does not
        // exist, and the sampler documents None for a view grazing to within the float range.
        let beckmann = f64::Beckmann::new(f64::Isotropic::new(1.0).unwrap());
        let wo = DVec3::new(f64::MAX, -1.0, 1e-40);
        let u = DVec2::new(f64::MAX, f64::NEG_INFINITY);
        assert_eq!(beckmann.sample_visible_normal(wo, u), None);
    }

    #[test]
    fn det_clamp_above_the_range_is_refused() {
        // tau = F::MAX was accepted: sqrt_det 1.3e154 against entries 1e-16, and the samplers
        // of that lobe returned NaN (GGX sample_normal) or normals on the horizon. The clamped
        // matrix A_c = A + t I (det tau) must have its eigenvalues in range: tau = 1e17 gives
        // t ~ 3e8 > ALPHA_MAX^2 (tau = 1e9 is A_c ~ 3e4 I, a valid lobe since the clamp became
        // one matrix).
        let r = f64::RoughnessMatrix::new_with_det_clamp(1e-16, 0.0, 1.0, f64::MAX);
        assert_eq!(r.err(), Some(filtered_ndf::RoughnessError::OutOfRange));
        let r = f32::RoughnessMatrix::new_with_det_clamp(1e-8, 0.0, 1e-8, 1e17);
        assert_eq!(r.err(), Some(filtered_ndf::RoughnessError::OutOfRange));
    }

    #[test]
    fn beckmann_visible_normal_of_a_subnormal_grazing_view() {
        // f64: wo_z = 5e-324: the sample and the fallback lobe centre had m_z = 0.
        use f64::NdfSampling;
        let r = f64::RoughnessMatrix::new_with_det_clamp(1e-16, 0.0, 4.0, 4e-16).unwrap();
        let b = f64::Beckmann::new(r);
        for wo in [
            DVec3::new(0.5836255802574746, 0.8120228950399897, 5e-324),
            DVec3::new(-1.9929449743934577e-5, -0.9999999998014086, 5e-324),
        ] {
            // wo_z / |wo| = 5e-324 is within the documented None range (below 1e-300), so
            // None is allowed; a sample must keep the guarantees (unit, m_z > 0, wo.m > 0 as
            // computed).
            if let Some(m) = b.sample_visible_normal(wo, DVec2::new(2.0, 5e-324)) {
                assert!(
                    m.z > 0.0 && wo.dot(m) > 0.0 && (m.length() - 1.0).abs() < 1e-15,
                    "{m}"
                );
            }
        }
    }

    #[test]
    fn implicit_normal_of_a_subnormal_gradient() {
        let s = f64::LevelSetSample {
            grad: DVec3::splat(5e-324),
            ..Default::default()
        };
        assert!((s.normal().length() - 1.0).abs() < 1e-15, "{}", s.normal());
    }

    #[test]
    fn quadric_frame_near_the_parallel_limit() {
        // f32: one Gram-Schmidt pass left N . e1 ~ 1e-5.
        let q = f32::LocalQuadric::new(
            Vec3::ZERO,
            Vec3::new(-1.0, 0.008880751, 1e-30),
            Vec3::new(-1.8416724, -0.0, 2.5808616e-32),
            1.0,
            1.0,
        )
        .unwrap();
        let (_, n, e1, e2) = q.frame();
        assert!(
            n.dot(e1).abs() < 1e-6 && n.dot(e2).abs() < 1e-6,
            "{:?}",
            q.frame()
        );
    }

    #[test]
    fn quadric_frame_of_tiny_directions() {
        // f32: |N|^2 of N = (-8.7e-23, 0, 0) is subnormal and glam's normalisation returned
        // a vector of length 1.04.
        let q = f32::LocalQuadric::new(
            Vec3::ZERO,
            Vec3::new(-8.7332614e-23, 0.0, 0.0),
            Vec3::new(1e-30, -8.7332614e-23, 0.0),
            1.0,
            1.0,
        )
        .unwrap();
        let (_, n, e1, e2) = q.frame();
        for v in [n, e1, e2] {
            assert!((v.length() - 1.0).abs() < 1e-6, "{:?}", q.frame());
        }
    }

    #[test]
    fn temporal_roughness_matrix_with_a_wide_minor_axis() {
        // s2 + (b2 - s2) a_x^2 lost b2 entirely: a zero diagonal entry.
        let t = f64::TemporalRoughness::from_normal_rate(DVec2::X, 1e-8);
        let (a11, _, a22) = t.roughness_matrix(1e4).entries();
        assert!(a11 > 0.0 && a22 > 0.0, "{a11} {a22}");
    }
}
