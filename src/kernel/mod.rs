//! Kernels and clamps: the shapes a footprint takes in the slope domain ([`Covariance`], the
//! Gaussian; [`BoundingRect`], the conservative rectangle) and the clamping rules applied to
//! them before filtering ([`ClampRules`]).

use super::{F, Vec2};

mod clamp;
mod covariance;
mod rect;

pub use clamp::{ClampRules, ExtentFloor};
pub(crate) use clamp::{Narrow, RectBounds};
pub use covariance::{Covariance, KERNEL_MAX};
pub use rect::BoundingRect;

/// The standard deviation of the pixel filter used by KHPL16 and TK19, in pixels.
pub const SIGMA_PIXEL: F = 0.5;
