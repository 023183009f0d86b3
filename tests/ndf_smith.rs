//! Smith's `Lambda` against quadrature, and the ranges of `G1` and `G2`.
//!
//! The identity (Heitz 2014 eq. 25; TK19 supplement section 1) is
//! `(1 + Lambda(o)) cos(theta_o) = integral over the hemisphere of max(0, o.m) D(m) dm`.
//! With `dm = m_z^3 ds` and `D = P22 / m_z^4` the right side is the slope-plane integral
//! `integral of max(0, o_z - o_xy . s) P22(s) ds`. It is computed in the frame `(a, b)` with
//! `a` along `o_xy`, so that the kink `a = o_z / |o_xy|` is an end point of the outer range
//! (no kink inside a panel), and the inner integral over `b` is centred on the conditional
//! peak of the quadratic form, `b = -a (e_a^T A^-1 e_b) / (e_b^T A^-1 e_b)`. `A` comes from
//! the case's own `f64` description, not from the code under test.
//!
//! Tolerance: the quadrature is asked for `1e-11` relative (inner `1e-12`); the identity must
//! hold to `1e-8` relative, which leaves the estimate's factor-of-100 over-estimate room and
//! still catches any error in `Lambda`'s formula (a wrong projected roughness, a missing
//! factor 1/2, cancellation at grazing angles all exceed `1e-6`).

use filtered_ndf::testing::cases::{self, Form, Model, NdfCase};
use filtered_ndf::testing::quadrature::{Tolerance, integrate, integrate_line};
use glam::{DMat2, DVec2, DVec3};
use proptest::prelude::*;

const REL: f64 = 1e-8;

fn a_matrix(case: &NdfCase) -> DMat2 {
    let (a11, a12, a22) = case.form.entries();
    DMat2::from_cols(DVec2::new(a11, a12), DVec2::new(a12, a22))
}

/// `integral of max(0, o.m) D(m) dm` by quadrature in the slope plane.
fn projected_area(case: &NdfCase, o: DVec3) -> f64 {
    let ndf = case.build_f64().unwrap();
    let oxy = o.truncate();
    let r = oxy.length();
    let a = a_matrix(case);
    let inv = a.inverse();
    let ea = if r > 0.0 { oxy / r } else { DVec2::X };
    let eb = ea.perp();
    let (iab, ibb) = (ea.dot(inv * eb), eb.dot(inv * eb));
    let wb = 1.0 / ibb.sqrt();
    let wa = ea.dot(a * ea).sqrt();
    let inner_tol = Tolerance::relative(1e-12);
    let inner = |x: f64| {
        let c = -x * iab / ibb;
        integrate_line(|y| ndf.p22(ea * x + eb * y), c, wb, inner_tol).value
    };
    let tol = Tolerance::relative(1e-11);
    if r == 0.0 {
        // Normal incidence: max(0, o_z) = o_z everywhere; integrate over the whole line.
        return o.z * integrate_line(inner, 0.0, wa, tol).value;
    }
    let a0 = o.z / r;
    let weight = |x: f64| (o.z - r * x).max(0.0);
    // (-inf, 0]: x = -wa u / (1 - u).
    let left = integrate(
        |u| {
            let x = -wa * u / (1.0 - u);
            let v = weight(x) * inner(x) * wa / ((1.0 - u) * (1.0 - u));
            if v.is_finite() { v } else { 0.0 }
        },
        0.0,
        1.0,
        tol,
    );
    // [0, a0]: x = wa u / (1 - u), u in [0, a0 / (a0 + wa)].
    let u0 = a0 / (a0 + wa);
    let right = integrate(
        |u| {
            let x = wa * u / (1.0 - u);
            weight(x) * inner(x) * wa / ((1.0 - u) * (1.0 - u))
        },
        0.0,
        u0,
        tol,
    );
    left.value + right.value
}

fn check_identity(case: &NdfCase, o: DVec3) -> Result<(), TestCaseError> {
    let ndf = case.build_f64().unwrap();
    let lhs = (1.0 + ndf.lambda(o)) * o.z;
    let rhs = projected_area(case, o);
    prop_assert!(
        (lhs - rhs).abs() <= REL * rhs,
        "{case:?} o = {o:?}: (1 + Lambda) cos = {lhs}, quadrature {rhs}, rel {:.2e}",
        (lhs - rhs).abs() / rhs
    );
    Ok(())
}

fn dir(d: [f64; 3]) -> DVec3 {
    DVec3::from_array(d)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn smith_identity_holds(case in cases::case(), o in cases::direction(89.9)) {
        check_identity(&case, dir(o))?;
    }

    #[test]
    fn g1_and_g2_are_in_the_unit_interval_and_respect_chi_plus(
        case in cases::case(),
        i in cases::direction(89.9),
        o in cases::direction(89.9),
        m in cases::direction(89.9),
    ) {
        let ndf = case.build_f64().unwrap();
        let (i, o, m) = (dir(i), dir(o), dir(m));
        let g1 = ndf.g1(o, m);
        let g2 = ndf.g2(i, o, m);
        prop_assert!((0.0..=1.0).contains(&g1) && (0.0..=1.0).contains(&g2));
        // chi+: a back-facing micronormal masks completely.
        prop_assert_eq!(ndf.g1(o, -o), 0.0);
        prop_assert_eq!(ndf.g2(i, o, -o), 0.0);
        prop_assert_eq!(ndf.g2(-m, o, m), 0.0);
        // Front-facing: exactly the Smith forms 1 / (1 + Lambda).
        if o.dot(m) > 0.0 {
            prop_assert_eq!(g1, 1.0 / (1.0 + ndf.lambda(o)));
        }
        if i.dot(m) > 0.0 && o.dot(m) > 0.0 {
            prop_assert_eq!(g2, 1.0 / (1.0 + ndf.lambda(i) + ndf.lambda(o)));
            // Height correlation: G2 <= min(G1(i), G1(o)) and >= G1(i) G1(o).
            let (gi, go) = (ndf.g1(i, m), ndf.g1(o, m));
            prop_assert!(g2 <= gi.min(go) * (1.0 + 1e-15));
            prop_assert!(g2 >= gi * go * (1.0 - 1e-15));
        }
        // Lambda is even in w (it uses |w_z| and a quadratic form).
        prop_assert_eq!(ndf.lambda(o), ndf.lambda(-o));
    }
}

/// The corners: smallest and largest roughness, the largest anisotropy, directions at the
/// normal, 60 degrees and 89.9 degrees, along and across the lobe's axes.
#[test]
fn smith_identity_at_the_corners() {
    for model in [Model::Ggx, Model::Beckmann] {
        for form in [
            Form::Isotropic(1e-4),
            Form::Isotropic(2.0),
            Form::AxisAligned(1e-4, 1e-1),
            Form::Rotated {
                alpha_x: 2.0,
                alpha_y: 2e-3,
                phi: 0.4,
            },
        ] {
            let case = NdfCase { model, form };
            for deg in [0.0f64, 30.0, 60.0, 85.0, 89.9] {
                for az in [0.0f64, 0.4, std::f64::consts::FRAC_PI_2, 2.0] {
                    let t = deg.to_radians();
                    let o = DVec3::new(t.sin() * az.cos(), t.sin() * az.sin(), t.cos());
                    check_identity(&case, o).unwrap();
                }
            }
        }
    }
}

#[test]
fn lambda_limits() {
    for model in [Model::Ggx, Model::Beckmann] {
        let case = NdfCase {
            model,
            form: Form::Isotropic(0.3),
        };
        let ndf = case.build_f64().unwrap();
        // Normal incidence: no masking. Horizon: infinite Lambda, G1 = 0.
        assert_eq!(ndf.lambda(DVec3::Z), 0.0);
        assert_eq!(ndf.lambda(DVec3::X), f64::INFINITY);
        assert_eq!(ndf.g1(DVec3::X, DVec3::new(0.6, 0.0, 0.8)), 0.0);
        assert_eq!(ndf.g1(DVec3::Z, DVec3::Z), 1.0);
    }
}
