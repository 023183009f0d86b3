//! Self-tests of the quadrature harness against closed-form integrals: the references of every
//! other test are only as good as this.

use filtered_ndf::testing::quadrature::{
    Tolerance, integrate, integrate_2d, integrate_line, integrate_plane,
};
use std::f64::consts::PI;

#[test]
fn one_panel_is_exact_for_degree_21_polynomials() {
    // K15 integrates polynomials up to degree 22 exactly; x^21 + x^20 on [0, 1] = 1/22 + 1/21.
    let tol = Tolerance {
        max_intervals: 1,
        ..Tolerance::default()
    };
    let e = integrate(|x| x.powi(21) + x.powi(20), 0.0, 1.0, tol);
    assert!((e.value - (1.0 / 22.0 + 1.0 / 21.0)).abs() < 1e-15, "{e:?}");
}

#[test]
fn gaussian_on_the_line_and_its_error_estimate_bounds_the_error() {
    for &(c, s) in &[(0.0, 1.0), (3.0, 1e-4), (-2.0, 50.0)] {
        let e = integrate_line(
            |x| (-((x - c) / s).powi(2)).exp(),
            c,
            s,
            Tolerance::relative(1e-12),
        );
        let exact = s * PI.sqrt();
        let err = (e.value - exact).abs();
        assert!(err <= 1e-11 * exact, "c={c} s={s}: {e:?} vs {exact}");
        assert!(
            err <= e.error.max(1e-15 * exact),
            "estimate {e:?} below true error {err}"
        );
    }
}

#[test]
fn heavy_tail_on_the_line() {
    // integral (1 + x^2)^-2 dx = pi / 2 (the GGX profile).
    let e = integrate_line(
        |x| (1.0 + x * x).powi(-2),
        0.0,
        1.0,
        Tolerance::relative(1e-12),
    );
    assert!((e.value - PI / 2.0).abs() < 1e-11, "{e:?}");
}

#[test]
fn nested_2d_on_a_rectangle() {
    // integral over [0,1]x[0,2] of x y^2 = 1/2 * 8/3.
    let e = integrate_2d(
        |x, y| x * y * y,
        (0.0, 1.0),
        (0.0, 2.0),
        Tolerance::default(),
    );
    assert!((e.value - 4.0 / 3.0).abs() < 1e-13, "{e:?}");
    // A narrow peak inside a square: (1 + (x^2 + y^2) / a^2)^-2 over [-L, L]^2 is
    // 4 a^2 F(L / a, L / a), F(U, V) = (U / sqrt(1 + U^2) atan(V / sqrt(1 + U^2))
    // + V / sqrt(1 + V^2) atan(U / sqrt(1 + V^2))) / 2 the integral over [0, U] x [0, V] of
    // (1 + u^2 + v^2)^-2 (checked against 30-digit nested quadrature, mpmath, at (3, 0.7)).
    let a: f64 = 1e-3;
    let l: f64 = 10.0;
    let e = integrate_2d(
        |x, y| (1.0 + (x * x + y * y) / (a * a)).powi(-2),
        (-l, l),
        (-l, l),
        Tolerance::relative(1e-9),
    );
    let u = l / a;
    let c = u / (1.0 + u * u).sqrt();
    let exact = 4.0 * a * a * c * (u / (1.0 + u * u).sqrt()).atan();
    let err = (e.value - exact).abs();
    assert!(err < 1e-9 * exact, "{e:?} vs {exact}");
    assert!(
        err <= e.error,
        "estimate {e:?} below the true error {err:e}"
    );
}

#[test]
fn plane_integral_of_a_correlated_gaussian() {
    // exp(-x^T S^-1 x / 2) integrates to 2 pi sqrt(det S).
    let (s11, s12, s22) = (2.0, 0.9, 0.5);
    let det: f64 = s11 * s22 - s12 * s12;
    let (i11, i12, i22) = (s22 / det, -s12 / det, s11 / det);
    let e = integrate_plane(
        |x, y| (-0.5 * (i11 * x * x + 2.0 * i12 * x * y + i22 * y * y)).exp(),
        (0.0, 0.0),
        (1.0, 1.0),
        Tolerance::relative(1e-10),
    );
    let exact = 2.0 * PI * det.sqrt();
    assert!((e.value - exact).abs() < 1e-9 * exact, "{e:?} vs {exact}");
}

#[test]
fn integrated_inner_errors_are_added_to_the_estimate() {
    // An integrand that carries its own error, (x^2, 1e-6 x): the value is 1/3, and the
    // estimate includes the inner errors integrated with the same weights, 1e-6 / 2 (one panel
    // integrates both exactly, so nothing else is added beyond rounding).
    use filtered_ndf::testing::quadrature::integrate_estimates;
    let e = integrate_estimates(|x| (x * x, 1e-6 * x), 0.0, 1.0, Tolerance::default());
    assert!((e.value - 1.0 / 3.0).abs() < 1e-15, "{e:?}");
    assert!((e.error - 0.5e-6).abs() < 1e-15, "{e:?}");
}
