//! The crate's `f64` functions that the shader functions are compared with, in one place.
//!
//! Every reference is evaluated by the library's `f64` build on exactly the f32 values the
//! shader reads (widened without rounding). This file is the only one that names the
//! library's module paths (below the root re-exports), so a restructuring of `src/` touches
//! it alone.

/// `f64::filter::method`: the front door's methods.
pub use filtered_ndf::f64::filter::{
    ExactGaussian, Filterable, Gaussian, Lean, LeanMoments, Projected, Proxy, Rect, RectFilteredGgx,
};
pub use filtered_ndf::f64::{
    AxisAligned, Beckmann, ClampRules, Covariance, Footprint, GaussianFilteredGgx, Ggx, Isotropic,
    Ndf, NdfSampling, Roughness, RoughnessMatrix,
};
pub use filtered_ndf::testing::{rng::SplitMix64, strategies};
pub use glam::{DVec2, DVec3};

/// `f64::footprint::BoundingRect`.
pub use filtered_ndf::f64::BoundingRect;
/// `f64::ExtentFloor`.
pub use filtered_ndf::f64::ExtentFloor;
/// `f64::filter`: Gaussian, LEAN and projected (TK21) filtering.
pub use filtered_ndf::f64::filter;
/// `f64::isotropic`: `KernelConvention` and its parts.
pub use filtered_ndf::f64::filter::deferred;
/// `f64::presets`: the 12 deferred conventions.
pub use filtered_ndf::f64::filter::presets;
/// `f64::ggx_proxy`: the GGX proxy roughness (KHPL16 eq. 19, 20).
pub use filtered_ndf::f64::filter::proxy;
/// `f64::ggx_rect`: the exact GGX box filter.
pub use filtered_ndf::f64::filter::rect;
/// `f64::jacobian`: their Jacobians.
pub use filtered_ndf::f64::footprint::jacobian;
/// `f64::slope`: the maps between the half-vector domains.
pub use filtered_ndf::f64::footprint::slope;
/// `f64::sampling::reflect`.
pub use filtered_ndf::f64::sampling;
/// `filtered_ndf::math`: the float backend switch (atan, ...).
pub use filtered_ndf::math;

/// A vector of f32 values widened to f64.
pub fn v2(v: [f32; 2]) -> DVec2 {
    DVec2::new(v[0].into(), v[1].into())
}

/// A vector of f32 values widened to f64.
pub fn v3(v: [f32; 3]) -> DVec3 {
    DVec3::new(v[0].into(), v[1].into(), v[2].into())
}

/// The f64 roughness matrix `R diag(alpha^2) R^T` of the shader's `matrix::from_eigen(axis,
/// alpha)` with the f32 `axis` (normalised in f64) and `alpha`: entries formed in f64.
/// `None` where rounding puts an eigenvalue outside the supported range.
pub fn matrix_from_eigen(axis: [f32; 2], alpha: [f32; 2]) -> Option<RoughnessMatrix> {
    let a = v2(axis).normalize();
    let (l1, l2) = (f64::from(alpha[0]).powi(2), f64::from(alpha[1]).powi(2));
    let (c, s) = (a.x, a.y);
    RoughnessMatrix::new(
        l1 * c * c + l2 * s * s,
        (l1 - l2) * c * s,
        l1 * s * s + l2 * c * c,
    )
    .ok()
}
