//! The structure-of-arrays inputs of the batch functions: footprints, pixel kernels and
//! vectors as one slice per component.

use super::super::{F, Vec2, Vec3};

/// Footprints in structure-of-arrays form: element `i` is the
/// [`Footprint`](super::super::Footprint) with `dh_u = (dh_u_x[i], dh_u_y[i])`,
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
    pub fn at(&self, i: usize) -> super::super::Footprint {
        footprint(
            self.dh_u_x[i],
            self.dh_u_y[i],
            self.dh_v_x[i],
            self.dh_v_y[i],
        )
    }
}

/// The footprint of one element from its four derivatives (the footprint kernels' lanes).
#[inline(always)]
pub(super) fn footprint(ux: F, uy: F, vx: F, vy: F) -> super::super::Footprint {
    super::super::Footprint::from_slope_derivatives(Vec2::new(ux, uy), Vec2::new(vx, vy))
}

/// The input columns of the footprint kernels: the half vector's three, then the four
/// derivatives.
#[inline]
pub(super) fn footprint_columns<'a>(
    [hx, hy, hz]: [&'a [F]; 3],
    fp: Footprints<'a>,
) -> [&'a [F]; 7] {
    [hx, hy, hz, fp.dh_u_x, fp.dh_u_y, fp.dh_v_x, fp.dh_v_y]
}

/// Pixel kernels (slope covariances, [`Covariance`](super::super::Covariance)) in
/// structure-of-arrays form: element `i` is `Covariance::new(s11[i], s12[i], s22[i])`.
#[derive(Clone, Copy, Debug)]
pub struct Covariances<'a> {
    /// `Sigma_11` per element.
    pub s11: &'a [F],
    /// `Sigma_12` per element.
    pub s12: &'a [F],
    /// `Sigma_22` per element.
    pub s22: &'a [F],
}

impl Covariances<'_> {
    /// The shortest of the three slices.
    #[inline]
    pub fn len(&self) -> usize {
        self.s11.len().min(self.s12.len()).min(self.s22.len())
    }

    /// Whether [`Covariances::len`] is `0`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
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
