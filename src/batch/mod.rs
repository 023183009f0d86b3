//! Batch evaluation over slices (structure of arrays), for baking and offline use.
//!
//! (Module docs being rewritten for issue 20.)

use super::{F, PI, Vec2, Vec3};

mod filtered;
pub mod lanes;
mod simd;
mod ndf;
mod rect;

pub use filtered::{beckmann_d_filtered, ggx_d_filtered};
pub use ndf::{beckmann_d, beckmann_g2, beckmann_lambda, ggx_d, ggx_g2, ggx_lambda};
pub use rect::d_rect;

/// The vector instruction set the batch kernels run on in this process: `"avx512"`,
/// `"avx2"` or `"sse2"` (x86-64; `"baseline"` elsewhere). With the `dispatch` feature on
/// x86-64, the widest the CPU supports (detected once, capped by the environment variable
/// `FILTERED_NDF_SIMD=sse2|avx2|avx512`); without it, the target features the crate was
/// compiled for (`-C target-cpu`). For reports and benchmarks; it changes no result
/// (every lane computes the same operations at any width).
pub fn simd_level() -> &'static str {
    simd::level_name()
}

/// Footprints in structure-of-arrays form: element `i` is the
/// [`Footprint`](super::Footprint) with `dh_u = (dh_u_x[i], dh_u_y[i])`,
/// `dh_v = (dh_v_x[i], dh_v_y[i])` (slope change per pixel).
#[derive(Clone, Copy, Debug)]
pub struct Footprints<'a> {
    /// `dh_u.x` per element.
    pub dh_u_x: &'a [F],
    /// `dh_u.y` per element.
    pub dh_u_y: &'a [F],
    /// `dh_v.x` per element.
    pub dh_v_x: &'a [F],
    /// `dh_v.y` per element.
    pub dh_v_y: &'a [F],
}

impl Footprints<'_> {
    /// The shortest of the four slices.
    #[inline]
    pub fn len(&self) -> usize {
        self.dh_u_x
            .len()
            .min(self.dh_u_y.len())
            .min(self.dh_v_x.len())
            .min(self.dh_v_y.len())
    }

    /// Whether [`Footprints::len`] is `0`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element `i` (which must be below every slice length).
    #[inline]
    pub fn at(&self, i: usize) -> super::Footprint {
        super::Footprint::from_slope_derivatives(
            Vec2::new(self.dh_u_x[i], self.dh_u_y[i]),
            Vec2::new(self.dh_v_x[i], self.dh_v_y[i]),
        )
    }
}

/// Vectors in structure-of-arrays form: element `i` is `(x[i], y[i], z[i])` (directions,
/// micronormals, normal differences).
#[derive(Clone, Copy, Debug)]
pub struct Vec3s<'a> {
    /// `x` per element.
    pub x: &'a [F],
    /// `y` per element.
    pub y: &'a [F],
    /// `z` per element.
    pub z: &'a [F],
}

impl<'a> Vec3s<'a> {
    /// The three slices as one value.
    #[inline]
    pub const fn new(x: &'a [F], y: &'a [F], z: &'a [F]) -> Self {
        Self { x, y, z }
    }

    /// The shortest of the three slices.
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len().min(self.y.len()).min(self.z.len())
    }

    /// Whether [`Vec3s::len`] is `0`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element `i` (which must be below every slice length).
    #[inline]
    pub fn at(&self, i: usize) -> Vec3 {
        Vec3::new(self.x[i], self.y[i], self.z[i])
    }
}
