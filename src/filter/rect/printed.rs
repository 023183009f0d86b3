//! The printed GDC 2016 listing of the GGX box filter, kept as the baseline the benchmarks,
//! the trade table and the error comparisons measure [`super::d_rect`] against. Not for
//! shading: it cancels catastrophically for small footprints and far from the peak.

use super::super::super::ndf::roughness::AxisAligned;
use super::{F, Vec2, Vec3};
use crate::math as m;

/// The GDC 2016 listing `GGXRectIntegral` (Kaplanyan, "Stable specular highlights"), evaluated
/// as printed in precision `F`: the eight-term difference of KHPL16 Appendix A over
/// `[hpp - footprint, hpp + footprint]`, divided by `2 pi (x1 - x2)(y1 - y2)` (the listing's
/// undefined `f` taken as `1`, which is the correct normalisation of an average) and by the
/// Jacobian `max(1e-3, h_z^4)` exactly as printed.
///
/// The baseline of the benchmarks and error comparisons: it cancels catastrophically for small
/// footprints or far from the peak (use [`super::d_rect`]). `hpp` is the projected half vector
/// `h_xy / h_z` (slope up to sign; the density is even), `footprint` the half extents.
/// Differences from the listing: a non-finite result (e.g. `0 / 0` for a zero footprint) is
/// returned as `0`, so the crate's no-NaN contract holds.
#[inline]
pub fn d_rect_printed(r: AxisAligned, hpp: Vec2, h: Vec3, footprint: Vec2) -> F {
    use super::super::super::PI;
    let alpha = r.alpha();
    let (a, b) = (alpha.x, alpha.y);
    let (a_2, b_2) = (a * a, b * b);
    let (x1, x2) = (hpp.x - footprint.x, hpp.x + footprint.x);
    let (y1, y2) = (hpp.y - footprint.y, hpp.y + footprint.y);
    let (x1_2, x2_2) = (x1 * x1, x2 * x2);
    let (y1_2, y2_2) = (y1 * y1, y2 * y2);
    let val = ((x1
        * (m::atan((y1 * a) / (m::sqrt(x1_2 + a_2) * b))
            - m::atan((y2 * a) / (m::sqrt(x1_2 + a_2) * b))))
        / m::sqrt(x1_2 + a_2)
        + (x2
            * (-m::atan((y1 * a) / (m::sqrt(x2_2 + a_2) * b))
                + m::atan((y2 * a) / (m::sqrt(x2_2 + a_2) * b))))
            / m::sqrt(x2_2 + a_2)
        + (y1
            * m::sqrt(y2_2 + b_2)
            * (m::atan((x1 * b) / (a * m::sqrt(y1_2 + b_2)))
                - m::atan((x2 * b) / (a * m::sqrt(y1_2 + b_2))))
            + y2 * m::sqrt(y1_2 + b_2)
                * (-m::atan((x1 * b) / (a * m::sqrt(y2_2 + b_2)))
                    + m::atan((x2 * b) / (a * m::sqrt(y2_2 + b_2)))))
            / m::sqrt((y1_2 + b_2) * (y2_2 + b_2)))
        / ((2.0 * PI) * (x1 - x2) * (y1 - y2));
    let hz4 = h.z * h.z * h.z * h.z;
    let v = val / hz4.max(1e-3);
    if v.is_finite() { v } else { 0.0 }
}
