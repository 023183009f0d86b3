//! Pixel footprints in the slope domain and their Gaussian covariance (KHPL16 sections 4.2
//! and 4.3, TK19 section 2.2).
//!
//! A footprint is the pair of slope-domain vectors `(dh_u, dh_v)`: the change of the half
//! vector's slope across one pixel step in `x` and in `y`. A Gaussian pixel filter of standard
//! deviation `sigma` pixels (0.5 in both papers) carried into the slope domain has covariance
//! `Sigma = sigma^2 U^T U` with `U` the matrix whose rows are `dh_u` and `dh_v` (TK19
//! section 2.2; KHPL16 eq. 13 with `sigma` folded into the vectors).

use super::{F, Vec2};
use crate::math as m;

/// The standard deviation of the pixel filter used by KHPL16 and TK19, in pixels.
pub const SIGMA_PIXEL: F = 0.5;

/// A symmetric positive semi-definite 2x2 covariance `[[s11, s12], [s12, s22]]` in the slope
/// domain (units: slope^2). Covariances of independent kernels add (KHPL16 eq. 15, 21).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Covariance {
    /// Variance along the tangent `x` (slope^2).
    pub s11: F,
    /// Covariance of `x` and `y` (slope^2).
    pub s12: F,
    /// Variance along the bitangent `y` (slope^2).
    pub s22: F,
}

impl Covariance {
    /// The zero kernel (no filtering).
    pub const ZERO: Self = Self {
        s11: 0.0,
        s12: 0.0,
        s22: 0.0,
    };

    /// From the three distinct entries (not checked; see the filtering functions for what
    /// they do with an indefinite or non-finite covariance).
    #[inline]
    pub const fn new(s11: F, s12: F, s22: F) -> Self {
        Self { s11, s12, s22 }
    }

    /// `tr(Sigma) = lambda_min + lambda_max` (TK19 eq. 2).
    #[inline]
    pub fn trace(&self) -> F {
        self.s11 + self.s22
    }

    /// `det(Sigma) = lambda_min lambda_max`.
    #[inline]
    pub fn det(&self) -> F {
        self.s11 * self.s22 - self.s12 * self.s12
    }

    /// Eigenvalues `(lambda_min, lambda_max)`, computed as `mean +/- hypot(half difference,
    /// s12)` for `lambda_max` and `det / lambda_max` for `lambda_min`, so the small one keeps
    /// its relative accuracy for elongated kernels. Both are clamped to `>= 0`.
    #[inline]
    pub fn eigenvalues(&self) -> (F, F) {
        let mean = 0.5 * (self.s11 + self.s22);
        let rad = m::hypot(0.5 * (self.s11 - self.s22), self.s12);
        let max = (mean + rad).max(0.0);
        let min = if max > 0.0 {
            (self.det() / max).max(0.0)
        } else {
            0.0
        };
        (min, max)
    }
}

impl core::ops::Add for Covariance {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.s11 + o.s11, self.s12 + o.s12, self.s22 + o.s22)
    }
}

impl core::ops::Mul<F> for Covariance {
    type Output = Self;
    #[inline]
    fn mul(self, k: F) -> Self {
        Self::new(self.s11 * k, self.s12 * k, self.s22 * k)
    }
}

/// A slope-domain pixel footprint: the slope change per pixel step in `x` (`dh_u`) and in `y`
/// (`dh_v`) (KHPL16 section 4.2, `Delta h_u = Delta x_u M`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// Slope change per pixel step along the image `x` axis.
    pub dh_u: Vec2,
    /// Slope change per pixel step along the image `y` axis.
    pub dh_v: Vec2,
}

impl Footprint {
    /// A zero footprint (the filtered NDF equals the unfiltered one).
    pub const ZERO: Self = Self {
        dh_u: Vec2::ZERO,
        dh_v: Vec2::ZERO,
    };

    /// From slope-domain derivatives, e.g. `ddx`/`ddy` of the slope of `h` (KHPL16 section
    /// 5.1) or `dx_u M`, `dx_v M` from ray differentials (KHPL16 section 4.2).
    #[inline]
    pub const fn from_slope_derivatives(dh_u: Vec2, dh_v: Vec2) -> Self {
        Self { dh_u, dh_v }
    }

    /// `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)` (TK19 section 2.2), `sigma` in pixels.
    #[inline]
    pub fn covariance(&self, sigma: F) -> Covariance {
        let (u, v) = (self.dh_u, self.dh_v);
        Covariance::new(
            u.x * u.x + v.x * v.x,
            u.x * u.y + v.x * v.y,
            u.y * u.y + v.y * v.y,
        ) * (sigma * sigma)
    }
}
