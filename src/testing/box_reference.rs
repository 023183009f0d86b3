//! f64 quadrature reference of the box-filtered GGX (KHPL16 eq. 16): the average of the GGX
//! slope density over the rectangle `center +/- half_extent`, the quantity
//! [`crate::f64::filter::rect::p22_rect`] computes in closed form.
//!
//! The integration variable is the offset `delta` from the centre, over `[-H, H]` exactly,
//! with the density evaluated at `center + delta`. Integrating over `[c - H, c + H]` instead
//! would divide an integral over the *rounded* interval by the exact width `2 H`: for a
//! rectangle of half side `H` at distance `|c|` that is a relative error up to
//! `1.1e-16 |c| / H` (`6e-7` for a `1e-8` rectangle at slope 100), which would be read as an
//! error of the code under test. Rounding `c + delta` only moves a node by `1.1e-16 |c|`, a
//! relative change of the integrand of a few `1e-16`.

use super::quadrature::{Estimate, Tolerance, integrate, integrate_2d};
use crate::f64::{AxisAligned, Ggx, Ndf, Vec2};

/// `1 / (4 H_x H_y) integral over the rectangle of P22_GGX`, per unit slope area, by nested
/// adaptive Gauss-Kronrod over the offsets from the centre, with breakpoints at the lobe
/// centre when the rectangle straddles it. A zero half extent on one axis gives the 1D average
/// along the other; on both axes the density itself. Half extents are used by absolute value.
pub fn ggx_box(r: AxisAligned, center: Vec2, half_extent: Vec2, tol: Tolerance) -> Estimate {
    let ggx = Ggx::new(r);
    let h = half_extent.abs();
    // The offsets [-h, h], split at the offset -c of the peak when the interval contains it.
    let split = |c: f64, h: f64| -> Vec<(f64, f64)> {
        if -h < -c && -c < h {
            vec![(-h, -c), (-c, h)]
        } else {
            vec![(-h, h)]
        }
    };
    let p = |dx: f64, dy: f64| ggx.p22(Vec2::new(center.x + dx, center.y + dy));
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
            for (a, b) in split(center.x, h.x) {
                let e = integrate(|dx| p(dx, 0.0), a, b, tol);
                value += e.value;
                error += e.error;
            }
            return Estimate {
                value: value / (2.0 * h.x),
                error: error / (2.0 * h.x),
            };
        }
        (false, true) => {
            for (a, b) in split(center.y, h.y) {
                let e = integrate(|dy| p(0.0, dy), a, b, tol);
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
    for xs in split(center.x, h.x) {
        for ys in split(center.y, h.y) {
            let e = integrate_2d(p, xs, ys, tol);
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
