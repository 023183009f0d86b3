//! TK19 isotropic deferred roughness (eq. 1-5): bandwidth ordering, each variant against its
//! paper equation written out independently here, the normal-difference identity of section
//! 4.4 (eq. 3) checked geometrically, and bad input.

use filtered_ndf::f32 as p32;
use filtered_ndf::f64::filter::deferred::{
    Bandwidth, Combine, Domain, KAPPA, KernelConvention, Norm, filtered_alpha,
    normal_difference_covariance,
};
use filtered_ndf::f64::kernel::SIGMA_PIXEL;
use filtered_ndf::f64::{Covariance, Footprint};
use glam::{DVec2, DVec3, Vec3};
use proptest::prelude::*;

fn cov_strategy() -> impl Strategy<Value = Covariance> {
    (
        -1.0..1.0f64,
        -1.0..1.0f64,
        -1.0..1.0f64,
        -1.0..1.0f64,
        -4.0..0.0f64,
    )
        .prop_map(|(a, b, c, d, e)| {
            let s = 10f64.powf(e);
            Footprint::from_slope_derivatives(DVec2::new(a, b) * s, DVec2::new(c, d) * s)
                .covariance(0.5)
        })
}

/// lambda_max of [[a, b], [b, c]] by the textbook quadratic formula (independent of
/// `Covariance::eigenvalues`).
fn lambda_max(s: &Covariance) -> f64 {
    let (a, b, c) = (s.s11, s.s12, s.s22);
    0.5 * (a + c) + (0.25 * (a - c) * (a - c) + b * b).sqrt()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn max_eigenvalue_is_at_most_the_trace(s in cov_strategy()) {
        // TK19 eq. 2: lambda_max <= lambda_min + lambda_max = tr; exact up to rounding of the
        // hypot-based eigenvalue (a few ulps of the trace).
        let (lo, hi) = s.eigenvalues();
        prop_assert!(hi <= s.trace() * (1.0 + 1e-14), "{hi} > {}", s.trace());
        prop_assert!(lo <= hi);
        prop_assert!(Bandwidth::Max.alpha2(&s) <= Bandwidth::Trace.alpha2(&s) * (1.0 + 1e-14));
        // The average lies between half the max and the max bandwidth.
        prop_assert!(Bandwidth::Average.alpha2(&s) <= Bandwidth::Max.alpha2(&s) * (1.0 + 1e-14));
        prop_assert!(Bandwidth::Average.alpha2(&s) >= 0.5 * Bandwidth::Max.alpha2(&s) * (1.0 - 1e-14));
    }

    #[test]
    fn each_variant_matches_its_paper_equation(s in cov_strategy(), alpha in 0.0..1.2f64) {
        // Closed forms written from the paper: eq. 1 (2 lambda_max), eq. 2/4 (2 tr), eq. 5 (tr),
        // each clamped by kappa = 0.18 and saturated (Listing 2).
        let tr = s.s11 + s.s22;
        let cases = [
            (Bandwidth::Max, 2.0 * lambda_max(&s)),
            (Bandwidth::Trace, 2.0 * tr),
            (Bandwidth::Average, tr),
        ];
        for (b, k) in cases {
            let expect = (alpha * alpha + k.min(0.18)).min(1.0).sqrt();
            let got = filtered_alpha(alpha, &s, b, KAPPA);
            // Two roundings of values <= 1 plus the eigenvalue's: 1e-14 relative.
            prop_assert!((got - expect).abs() <= 1e-14 * expect.max(1e-300), "{b:?}: {got} vs {expect}");
        }
    }

    #[test]
    fn normal_difference_form_equals_trace_and_average(
        ux in -0.3..0.3f64, uy in -0.3..0.3f64, uz in -0.3..0.3f64,
        vx in -0.3..0.3f64, vy in -0.3..0.3f64, vz in -0.3..0.3f64,
        alpha in 0.0..1.0f64,
    ) {
        // TK19 eq. 4 and 5 on world-space differences against the same equation written out.
        let (u, v) = (DVec3::new(ux, uy, uz), DVec3::new(vx, vy, vz));
        let s2 = u.length_squared() + v.length_squared();
        for (b, k) in [(Bandwidth::Trace, 2.0 * 0.25 * s2), (Bandwidth::Average, 0.25 * s2)] {
            let expect = (alpha * alpha + k.min(0.18)).min(1.0).sqrt();
            let got = b.convention().apply(alpha, u, v);
            prop_assert!((got - expect).abs() <= 1e-14 * expect.max(1e-300));
            // And through the covariance form with the Gram covariance (same trace).
            let c = normal_difference_covariance(u, v, SIGMA_PIXEL);
            let via = filtered_alpha(alpha, &c, b, KAPPA);
            prop_assert!((via - got).abs() <= 1e-14 * got.max(1e-300));
        }
        // Max: the normal-difference preset and the covariance form agree (same Gram matrix).
        let c = normal_difference_covariance(u, v, SIGMA_PIXEL);
        let got = Bandwidth::Max.convention().apply(alpha, u, v);
        let via = filtered_alpha(alpha, &c, Bandwidth::Max, KAPPA);
        prop_assert!((via - got).abs() <= 1e-13 * got.max(1e-300));
    }
}

/// Orthonormal tangent frame (t, b) of the plane orthogonal to unit `n`.
fn frame(n: DVec3) -> (DVec3, DVec3) {
    let a = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let t = (a - n * a.dot(n)).normalize();
    (t, n.cross(t))
}

/// Orthographic projection of unit `m` onto the tangent plane of `n` (TK19 sect. 3.2: the
/// projected unit disk), in the frame (t, b).
fn disk(m: DVec3, n: DVec3) -> DVec2 {
    let (t, b) = frame(n);
    DVec2::new(m.dot(t), m.dot(b))
}

/// Smooth unit normal field of a sphere of radius `r` seen through a pixel grid: pixel
/// (x, y) maps to the surface point whose normal is normalize(x h, y h, r).
fn normal_at(x: f64, y: f64, h: f64) -> DVec3 {
    DVec3::new(x * h, y * h, 1.0).normalize()
}

#[test]
fn eq3_projected_derivative_of_average_normal_has_length_of_world_difference() {
    // TK19 sect. 4.4 / Fig. 5: with n_bar_u = normalize(n + n_u), the difference of the
    // projections of n and n_u on the disk of n_bar_u has length 2 sin(theta_u) = |n - n_u|.
    // Checked on a finite-difference normal field (neighbouring pixels of a sphere) at several
    // curvatures, up to large angles.
    let mut worst: f64 = 0.0;
    for &h in &[1e-4, 1e-2, 0.1, 0.5, 2.0] {
        for &(x, y) in &[(0.0, 0.0), (3.0, -1.0), (-7.0, 4.0), (0.3, 0.9)] {
            let n = normal_at(x, y, h);
            for nn in [normal_at(x + 1.0, y, h), normal_at(x, y + 1.0, h)] {
                let nbar = (n + nn).normalize();
                let d = disk(nn, nbar) - disk(n, nbar);
                let rel = (d.length() - (n - nn).length()).abs() / (n - nn).length();
                worst = worst.max(rel);
            }
        }
    }
    // An identity: only rounding remains (the smallest difference is ~1e-4, its length is
    // computed to ~1e-12 relative).
    assert!(worst < 1e-10, "worst relative mismatch {worst}");
}

#[test]
fn eq4_normal_difference_trace_equals_footprint_covariance_trace() {
    // Build the footprint as TK19 sect. 4.4 does (per-axis average normals, projected-disk
    // differences) and compare tr(Sigma) (eq. 2) with sigma^2 (|dn_u|^2 + |dn_v|^2) (eq. 4),
    // and lambda_max of the footprint (in the common frame of the centre normal) with the
    // Gram eigenvalue, which agree to first order: the relative gap must shrink with h.
    let mut prev_gap = f64::INFINITY;
    for &h in &[0.1, 0.01, 0.001] {
        let (x, y) = (2.0, -1.5);
        let n = normal_at(x, y, h);
        let (nu, nv) = (normal_at(x + 1.0, y, h), normal_at(x, y + 1.0, h));
        let (bu, bv) = ((n + nu).normalize(), (n + nv).normalize());
        let fp = Footprint::from_slope_derivatives(
            disk(nu, bu) - disk(n, bu),
            disk(nv, bv) - disk(n, bv),
        );
        let kernel = fp.covariance(0.5);
        let eq4 = 0.25 * ((n - nu).length_squared() + (n - nv).length_squared());
        assert!(
            (kernel.trace() - eq4).abs() <= 1e-12 * eq4,
            "h={h}: {} vs {eq4}",
            kernel.trace()
        );

        // Common frame at the centre normal (first-order footprint).
        let fc =
            Footprint::from_slope_derivatives(disk(nu, n) - disk(n, n), disk(nv, n) - disk(n, n));
        let gram = normal_difference_covariance(n - nu, n - nv, 0.5);
        let gap = (fc.covariance(0.5).eigenvalues().1 - gram.eigenvalues().1).abs()
            / gram.eigenvalues().1;
        assert!(
            gap < prev_gap,
            "h={h}: gap {gap} did not shrink from {prev_gap}"
        );
        prev_gap = gap;
    }
    // At h = 1e-3 the normals differ by ~1e-3 rad: second-order gap ~1e-6.
    assert!(prev_gap < 1e-5, "gap {prev_gap}");
}

#[test]
fn zero_differences_leave_alpha_unchanged() {
    for b in [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average] {
        for &a in &[0.0, 1e-6, 0.01, 0.5, 1.0] {
            let got = b.convention().apply(a, DVec3::ZERO, DVec3::ZERO);
            assert!((got - a).abs() <= 1e-15 * a.max(1e-300), "{b:?} {a}: {got}");
        }
    }
}

#[test]
fn kappa_bounds_the_kernel_and_saturate_bounds_the_result() {
    let big = DVec3::new(10.0, 0.0, 0.0);
    for b in [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average] {
        // kernel clamped to 0.18: alpha = 0.1 -> sqrt(0.01 + 0.18).
        let got = b.convention().apply(0.1, big, big);
        assert!((got - 0.19f64.sqrt()).abs() < 1e-15, "{b:?}: {got}");
        // saturate: alpha = 0.95 -> min(0.9025 + 0.18, 1) = 1.
        assert_eq!(b.convention().apply(0.95, big, big), 1.0);
    }
}

#[test]
fn bad_input_is_documented_behaviour() {
    let t = Bandwidth::Trace.convention();
    let d = DVec3::new(0.01, 0.02, 0.0);
    // Negative and NaN alpha count as 0.
    let zero = t.apply(0.0, d, d);
    assert_eq!(t.apply(-0.3, d, d), zero);
    assert_eq!(t.apply(f64::NAN, d, d), zero);
    // +inf alpha is ALPHA_MAX, then saturated to 1.
    assert_eq!(t.apply(f64::INFINITY, d, d), 1.0);
    // An infinite normal difference gives the maximal (clamped) kernel; a NaN entry counts as
    // 0 (the NaN policy).
    let kmax = (0.01f64 + 0.18).sqrt();
    for b in [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average] {
        let got = b
            .convention()
            .apply(0.1, DVec3::new(f64::INFINITY, 0.0, 0.0), d);
        assert!((got - kmax).abs() < 1e-15, "{b:?}: {got}");
        for (bad, zeroed) in [
            (DVec3::NAN, DVec3::ZERO),
            (DVec3::new(0.0, f64::NAN, 1.0), DVec3::new(0.0, 0.0, 1.0)),
        ] {
            let c = b.convention();
            assert_eq!(
                c.apply(0.1, bad, d),
                c.apply(0.1, zeroed, d),
                "{b:?} {bad:?}"
            );
        }
    }
    // Indefinite or NaN covariance in the covariance form: never NaN, within [alpha, 1].
    for s in [
        Covariance::new(-1.0, 0.0, -1.0),
        Covariance::new(f64::NAN, 0.0, 0.0),
        Covariance::new(f64::INFINITY, 0.0, 1.0),
    ] {
        for b in [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average] {
            let got = filtered_alpha(0.1, &s, b, KAPPA);
            assert!((0.1..=1.0).contains(&got), "{b:?} {s:?}: {got}");
        }
    }
    // f32: huge differences and alpha never overflow to NaN.
    let c32 = p32::filter::deferred::Bandwidth::Max.convention();
    let h = Vec3::splat(f32::MAX);
    let got = c32.apply(f32::MAX, h, h);
    assert!(got.is_finite() && got <= 1.0, "{got}");
    let got = c32.apply(0.2, Vec3::splat(1e30), Vec3::splat(-1e30));
    assert!((got - (0.04f32 + 0.18).sqrt()).abs() < 1e-6, "{got}");
}

#[test]
fn generic_configuration_never_returns_nan() {
    // A configuration without clamp or saturate, in every domain and both combines: the
    // result stays finite and within [0, ALPHA_MAX] for any input.
    let inputs = [
        0.0,
        -1.0,
        f64::NAN,
        f64::INFINITY,
        1e-30,
        0.5,
        1.0,
        3.0,
        1e300,
    ];
    let diffs = [
        DVec3::ZERO,
        DVec3::NAN,
        DVec3::splat(f64::INFINITY),
        DVec3::splat(1e200),
    ];
    for domain in [
        Domain::Alpha2,
        Domain::Alpha,
        Domain::Perceptual,
        Domain::ProjectedAlpha2,
    ] {
        for norm in [
            Norm::SumSquared,
            Norm::MaxSquared,
            Norm::MaxEigenvalue,
            Norm::MaxAbsComponent,
        ] {
            for combine in [Combine::Add, Combine::Max] {
                let c = KernelConvention {
                    domain,
                    norm,
                    scale: 1.0,
                    exponent: 0.5,
                    bias: -0.1,
                    clamp: f64::INFINITY,
                    combine,
                    saturate: false,
                    perceptual_floor: 0.0,
                };
                for &a in &inputs {
                    for &u in &diffs {
                        let got = c.apply(a, u, DVec3::ZERO);
                        assert!(
                            (0.0..=1e4).contains(&got),
                            "{domain:?} {norm:?} {combine:?} a={a} u={u:?}: {got}"
                        );
                    }
                }
            }
        }
    }
}
