//! Gaussian NDF filtering in roughness-matrix form: the Beckmann convolution (KHPL16 eq.
//! 13-15, TK19 section 2.2), the LEAN nested convolution (KHPL16 section 5.5, eq. 21), the
//! TK19 matrix approximation for GGX, and the projected-space filtering of Tokuyoshi and
//! Kaplanyan 2021 (JCGT 10(2)).
//!
//! Every function returns a [`RoughnessMatrix`](super::RoughnessMatrix), which [`super::Beckmann::new`] and
//! [`super::Ggx::new`] evaluate directly. Kernels are slope-domain covariances `Sigma`
//! (slope^2), e.g. [`super::Footprint::covariance`]; each function first applies
//! [`Covariance::sanitized`](super::Covariance::sanitized), so any kernel (NaN, infinite, indefinite) gives a finite,
//! positive-definite result. Clamps (extent, `kappa`) are applied by the caller or by
//! [`super::ClampRules::filter_gaussian`] / [`super::ClampRules::filter_projected`].
//!
//! ```
//! use filtered_ndf::f32::{filter, Beckmann, ClampRules, Footprint, Ggx, Isotropic, Ndf};
//! use glam::{Vec2, Vec3};
//!
//! let a = Isotropic::new(0.01).unwrap();
//! // ddx / ddy of the half vector's slope (KHPL16) or of h_xy on the disk (TK19).
//! let fp = Footprint::from_slope_derivatives(Vec2::new(0.02, 0.0), Vec2::new(0.0, 0.005));
//! let kernel = fp.covariance(0.5); // Sigma, from a pixel filter of sigma = 0.5 pixels
//! let beckmann = Beckmann::new(filter::gaussian(a, kernel)); // exact (KHPL16 eq. 15)
//! let ggx = Ggx::new(filter::projected(a, kernel)); // TK21 projected space
//! let clamped = ClampRules::default().filter_gaussian(a, fp, 0.5); // lambda, kappa, tau
//! let h = Vec3::new(0.005, 0.0, 1.0).normalize();
//! assert!(beckmann.d(h) < Beckmann::new(a).d(Vec3::Z));
//! assert!(ggx.d(h).is_finite() && Ggx::new(clamped).d(h).is_finite());
//! ```

use super::{F, Vec2, Vec3};

pub mod deferred;
mod exp_poly;
mod gaussian;
mod gaussian_ggx;
mod gaussian_ggx_quad;
pub(crate) mod gaussian_ggx_tol;
mod lean;
mod lean_nested;
pub mod method;
pub mod presets;
mod projected;
pub mod proxy;
pub mod rect;
mod tolerance;

pub(crate) use exp_poly::{
    LN2_HI_F32, LN2_LO_F32, MAGIC_F32, MAGIC_F64, exp_f32_poly, exp_f32_reduced, exp_f64,
    exp_f64_reduced,
};
pub use gaussian::{Gaussian, gaussian, gaussian_with_det_clamp};
pub use gaussian_ggx::{ExactGaussian, GaussianFilteredGgx};
pub(crate) use gaussian_ggx_quad::{
    SAMPLE_T0, TrapezoidState, beckmann_lambda_fast, sample_component,
};
pub use lean::{LeanMoments, lean};
pub use lean_nested::{Lean, lean_mean_normal, lean_widened, lean_widened_axis_aligned};
pub use method::{Filterable, Method};
pub(crate) use projected::ProjectedBase;
pub use projected::{PROJECTED_EIGEN_MAX, Projected, projected, projected_with_det_clamp};
pub use proxy::Proxy;
pub use rect::{Rect, RectFilteredGgx};
pub use tolerance::Tolerance;
