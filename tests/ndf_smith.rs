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

#[path = "common/ndf_integrals.rs"]
mod ndf_integrals;

use filtered_ndf::testing::cases::{self, Form, Model, NdfCase};
use glam::{DMat2, DVec2, DVec3};
use proptest::prelude::*;

const REL: f64 = 1e-8;

fn a_matrix(case: &NdfCase) -> DMat2 {
    let (a11, a12, a22) = case.form.entries();
    DMat2::from_cols(DVec2::new(a11, a12), DVec2::new(a12, a22))
}

/// `integral of max(0, o.m) D(m) dm` by quadrature in the slope plane
/// (`tests/common/ndf_integrals.rs`), `A` from the case's own description.
fn projected_area(case: &NdfCase, o: DVec3) -> f64 {
    ndf_integrals::projected_area(case.build_f64().unwrap().as_ref(), a_matrix(case), o)
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
