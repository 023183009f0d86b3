//! f64 quadrature reference of the box-filtered GGX (KHPL16 eq. 16): the average of the GGX
//! slope density over the rectangle `center +/- half_extent`, the quantity
//! [`crate::f64::filter::rect::p22_rect`] computes in closed form.

use super::quadrature::{Estimate, Tolerance, integrate, integrate_2d};
use crate::f64::{AxisAligned, Ggx, Ndf, Vec2};

/// `1 / (4 H_x H_y) integral over the rectangle of P22_GGX`, per unit slope area, by nested
/// adaptive Gauss-Kronrod with breakpoints at the lobe centre when the rectangle straddles it.
/// A zero half extent on one axis gives the 1D average along the other; on both axes the
/// density itself. Half extents are used by absolute value.
pub fn ggx_box(r: AxisAligned, center: Vec2, half_extent: Vec2, tol: Tolerance) -> Estimate {
    let ggx = Ggx::new(r);
    let h = half_extent.abs();
    let (x0, x1) = (center.x - h.x, center.x + h.x);
    let (y0, y1) = (center.y - h.y, center.y + h.y);
    // Split each axis at 0 (the peak) when the interval contains it.
    let split = |a: f64, b: f64| -> Vec<(f64, f64)> {
        if a < 0.0 && b > 0.0 {
            vec![(a, 0.0), (0.0, b)]
        } else {
            vec![(a, b)]
        }
    };
    let mut value = 0.0;
    let mut error = 0.0;
    match (h.x > 0.0, h.y > 0.0) {
        (false, false) => {
            return Estimate {
                value: ggx.p22(center),
                error: 0.0,
            };
        }
        (true, false) => {
            for (a, b) in split(x0, x1) {
                let e = integrate(|x| ggx.p22(Vec2::new(x, center.y)), a, b, tol);
                value += e.value;
                error += e.error;
            }
            return Estimate {
                value: value / (2.0 * h.x),
                error: error / (2.0 * h.x),
            };
        }
        (false, true) => {
            for (a, b) in split(y0, y1) {
                let e = integrate(|y| ggx.p22(Vec2::new(center.x, y)), a, b, tol);
                value += e.value;
                error += e.error;
            }
            return Estimate {
                value: value / (2.0 * h.y),
                error: error / (2.0 * h.y),
            };
        }
        (true, true) => {}
    }
    for xs in split(x0, x1) {
        for ys in split(y0, y1) {
            let e = integrate_2d(|x, y| ggx.p22(Vec2::new(x, y)), xs, ys, tol);
            value += e.value;
            error += e.error;
        }
    }
    let area = 4.0 * h.x * h.y;
    Estimate {
        value: value / area,
        error: error / area,
    }
}
