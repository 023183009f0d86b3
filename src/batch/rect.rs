//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::ndf::roughness::AxisAligned;
use super::lanes::{Kernel, run};
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
    run(&Rect(*r), [hx, hy, hz, half_x, half_y], [out])
}

/// [`rect::d_rect`] of one roughness.
struct Rect(AxisAligned);

impl Kernel<5, 1> for Rect {
    #[inline(always)]
    fn lane(&self, [hx, hy, hz, sx, sy]: [F; 5]) -> ([F; 1], bool) {
        let (v, slow) = rect::d_rect_lane(self.0, Vec3::new(hx, hy, hz), Vec2::new(sx, sy));
        ([v], slow)
    }
    #[inline]
    fn scalar(&self, [hx, hy, hz, sx, sy]: [F; 5]) -> [F; 1] {
        [rect::d_rect(self.0, Vec3::new(hx, hy, hz), Vec2::new(sx, sy))]
    }
}
