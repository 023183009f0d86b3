//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::ndf::roughness::AxisAligned;
use super::{F, Vec2, Vec3};

/// The exact box-filtered GGX [`rect::d_rect`] (KHPL16 eq. 16) for each half vector
/// `h_i` and slope-domain half extent `(half_x[i], half_y[i])`:
/// `out[i] = d_rect(*r, h_i, (half_x[i], half_y[i]))`. The half extents are the kernel as
/// given (no clamps: pass rectangles already through `ClampRules::rect` for the clamped
/// route). Returns the number of elements written. Allocates nothing.
#[inline]
pub fn d_rect(
    r: &AxisAligned,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    half_x: &[F],
    half_y: &[F],
    out: &mut [F],
) -> usize {
    let n = out
        .len()
        .min(hx.len())
        .min(hy.len())
        .min(hz.len())
        .min(half_x.len())
        .min(half_y.len());
    let (hx, hy, hz) = (&hx[..n], &hy[..n], &hz[..n]);
    let (half_x, half_y, out) = (&half_x[..n], &half_y[..n], &mut out[..n]);
    for i in 0..n {
        out[i] = rect::d_rect(
            *r,
            Vec3::new(hx[i], hy[i], hz[i]),
            Vec2::new(half_x[i], half_y[i]),
        );
    }
    n
}
