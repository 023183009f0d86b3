//! Normalisation of every NDF in every roughness form against `f64` adaptive quadrature:
//! `integral of P22(s) ds = 1` over the slope plane, and `integral of D(m) cos(theta_m) dm = 1`
//! over the hemisphere (KHPL16 eq. 2; TK19 supplement section 1).
//!
//! Tolerance: the quadrature is asked for a relative error of `1e-10` (inner `1e-11`) and its
//! QUADPACK estimate is asserted below `1e-8`; the integral must equal 1 within `2e-8`, which
//! is that bound plus the `f64` rounding of a few thousand summed panels (`~1e-12`). A wrong
//! normalisation constant (a missing `pi`, `alpha` instead of `alpha^2`, `sqrt det` of the
//! wrong matrix) is off by a factor, a wrong slope/solid-angle Jacobian by far more than that.

#[path = "common/ndf_integrals.rs"]
mod ndf_integrals;

use filtered_ndf::testing::cases::{self, NdfCase};
use proptest::prelude::*;

const TOL: f64 = 2e-8;

/// The slope-plane and hemisphere integrals of the case's lobe (`tests/common/ndf_integrals.rs`,
/// in the case's own frame), as `(value, error estimate)`.
fn slope_plane_integral(case: &NdfCase) -> (f64, f64) {
    let (ax, ay, phi) = case.form.axes();
    let e = ndf_integrals::slope_plane_integral(case.build_f64().unwrap().as_ref(), ax, ay, phi);
    (e.value, e.error)
}

fn hemisphere_integral(case: &NdfCase) -> (f64, f64) {
    let (ax, ay, phi) = case.form.axes();
    let e = ndf_integrals::hemisphere_integral(case.build_f64().unwrap().as_ref(), ax, ay, phi);
    (e.value, e.error)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn p22_integrates_to_one_over_the_slope_plane(case in cases::case()) {
        let (v, err) = slope_plane_integral(&case);
        prop_assert!(err < 1e-8, "{case:?}: quadrature did not converge: {v} +- {err}");
        prop_assert!((v - 1.0).abs() < TOL, "{case:?}: integral {v} +- {err}");
    }

    #[test]
    fn d_cos_integrates_to_one_over_the_hemisphere(case in cases::case()) {
        let (v, err) = hemisphere_integral(&case);
        prop_assert!(err < 1e-8, "{case:?}: quadrature did not converge: {v} +- {err}");
        prop_assert!((v - 1.0).abs() < TOL, "{case:?}: integral {v} +- {err}");
    }
}

/// The corners of the domain, deterministic: the smallest and largest tested roughness and
/// the largest anisotropy, in every form and both models.
#[test]
fn normalisation_at_the_corners() {
    use filtered_ndf::testing::cases::{Form, Model};
    for model in [Model::Ggx, Model::Beckmann] {
        for form in [
            Form::Isotropic(1e-4),
            Form::Isotropic(2.0),
            Form::AxisAligned(1e-4, 1e-1),
            Form::AxisAligned(2.0, 2e-3),
            Form::Rotated {
                alpha_x: 1e-4,
                alpha_y: 0.1,
                phi: 0.7,
            },
            Form::Rotated {
                alpha_x: 2.0,
                alpha_y: 2e-3,
                phi: 2.0,
            },
        ] {
            let case = NdfCase { model, form };
            for (name, (v, err)) in [
                ("plane", slope_plane_integral(&case)),
                ("hemisphere", hemisphere_integral(&case)),
            ] {
                assert!(
                    err < 1e-8 && (v - 1.0).abs() < TOL,
                    "{case:?} {name}: {v} +- {err}"
                );
            }
        }
    }
}
