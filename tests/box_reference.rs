//! The exported box-filter reference (`testing::box_reference`) against closed forms, and the
//! crate's exact rectangle integral against it.

use approx::assert_relative_eq;
use filtered_ndf::f64::{AxisAligned, Ggx, Ndf, filter::rect};
use filtered_ndf::testing::box_reference::ggx_box;
use filtered_ndf::testing::quadrature::Tolerance;
use glam::DVec2;
use std::f64::consts::PI;

#[test]
fn one_dimensional_average_matches_its_antiderivative() {
    // integral_{-H}^{H} P22(x, 0) dx = (k / (1 + k^2) + atan k) / (pi alpha), k = H / alpha.
    for &(alpha, h) in &[(0.1, 0.05), (1e-3, 0.5), (0.5, 2.0)] {
        let r = AxisAligned::new(alpha, alpha).unwrap();
        let e = ggx_box(
            r,
            DVec2::ZERO,
            DVec2::new(h, 0.0),
            Tolerance::relative(1e-12),
        );
        let k: f64 = h / alpha;
        let exact = (k / (1.0 + k * k) + k.atan()) / (PI * alpha) / (2.0 * h);
        // Quadrature to 1e-12 relative; the closed form is exact to rounding.
        assert!(
            (e.value - exact).abs() < 1e-10 * exact,
            "{alpha} {h}: {e:?} vs {exact}"
        );
    }
}

#[test]
fn zero_extent_is_the_density_and_rect_integral_agrees() {
    let r = AxisAligned::new(0.05, 0.2).unwrap();
    let c = DVec2::new(0.1, -0.3);
    let e = ggx_box(r, c, DVec2::ZERO, Tolerance::default());
    assert_eq!(e.value, Ggx::new(r).p22(c));
    // The closed form of the crate against the reference on a rectangle straddling the peak
    // (both f64; the closed form is good to ~1e-12 there, the reference to 1e-11).
    let h = DVec2::new(0.07, 0.4);
    let e = ggx_box(r, DVec2::new(0.02, 0.1), h, Tolerance::relative(1e-11));
    let v = rect::p22_rect(r, DVec2::new(0.02, 0.1), h);
    assert_relative_eq!(v, e.value, max_relative = 1e-9);
}
