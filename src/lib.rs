//! # filtered-ndf
//!
//! Microfacet normal distribution functions (Beckmann and GGX in isotropic, axis-aligned and
//! full-matrix roughness) and the filtered-NDF kernels that stop glossy highlights from
//! sparkling and flickering: the pixel footprint is carried into the slope domain and the
//! NDF is filtered over it (Kaplanyan, Hill, Patney, Lefohn 2016, "KHPL16"; Tokuyoshi and
//! Kaplanyan 2019, "TK19"; Tessari et al. 2020 for motion blur).
//!
//! ## Layout
//! Every formula exists once and is compiled twice: [`f32`](mod@f32) (shading) and [`f64`](mod@f64) (reference
//! and offline) hold the same modules over glam's `Vec2/Vec3/Mat2` and `DVec2/DVec3/DMat2`.
//!
//! ```
//! use filtered_ndf::f32::{Ggx, Ndf};
//! use glam::{Vec2, Vec3};
//!
//! let ggx = Ggx::isotropic(0.1).unwrap();
//! let peak = ggx.d(Vec3::Z); // 1 / (pi alpha^2)
//! assert!((peak - 1.0 / (core::f32::consts::PI * 0.01)).abs() < 1e-3 * peak);
//! assert_eq!(ggx.p22(Vec2::ZERO), peak);
//! ```
//!
//! Filtering one shading point, three ways (TK19 matrix, KHPL16 exact box, deferred):
//!
//! ```
//! use filtered_ndf::f32::{ClampRules, Footprint, Ggx, Isotropic, Ndf, ggx_rect, presets};
//! use glam::{Vec2, Vec3};
//!
//! let alpha = Isotropic::new(0.01).unwrap();
//! let h = Vec3::new(0.001, 0.0, 1.0).normalize(); // near the peak of the lobe
//! // ddx/ddy of the half vector's slope (KHPL16 section 5.1).
//! let fp = Footprint::from_slope_derivatives(Vec2::new(0.03, 0.0), Vec2::new(0.0, 0.02));
//! let d_matrix = Ggx::new(ClampRules::default().filter_gaussian(alpha, fp, 0.5)).d(h);
//! let d_box = ggx_rect::d_rect(alpha.into(), h, fp.bounding_rect().half_extent);
//! // Deferred: one isotropic roughness from G-buffer normal differences (TK19 eq. 4).
//! let a = presets::TK19_TRACE.apply(0.01, Vec3::new(0.03, 0.0, 0.0), Vec3::new(0.0, 0.02, 0.0));
//! let d_iso = Ggx::isotropic(a).unwrap().d(h);
//! let unfiltered = Ggx::new(alpha).d(h);
//! for d in [d_matrix, d_box, d_iso] {
//!     assert!(d.is_finite() && d < unfiltered); // the sub-pixel peak is spread out
//! }
//! ```
//!
//! ## Conventions
//! Tangent frame with `z` along the shading normal; slope `s = -h_xy / h_z`; `p22` is a
//! density per unit slope area, `d` per steradian with `integral d(m) m_z dm = 1`.
//!
//! ## Features
//! - `std` (default): standard-library float intrinsics.
//! - `libm`: all float math through `libm` (required for `no_std`).
//! - `testing`: proptest strategies and f64 quadrature references for downstream tests.
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![allow(clippy::duplicate_mod)]

pub mod contract;
pub mod error;
pub mod math;
pub mod tables;

pub use error::RoughnessError;

/// Declares the precision-generic modules inside [`f32`] and [`f64`]. Each file is written
/// once against the aliases `F`, `Vec2`, `Vec3`, `Mat2` of its parent module.
macro_rules! precision_modules {
    () => {
        // Each file is deliberately loaded once per precision.
        #[path = "batch.rs"]
        pub mod batch;
        #[path = "beckmann.rs"]
        pub mod beckmann;
        #[path = "clamp.rs"]
        pub mod clamp;
        #[path = "filter.rs"]
        pub mod filter;
        #[path = "footprint.rs"]
        pub mod footprint;
        #[path = "gaussian_ggx.rs"]
        pub mod gaussian_ggx;
        #[path = "geometry.rs"]
        pub mod geometry;
        #[path = "ggx.rs"]
        pub mod ggx;
        #[path = "ggx_proxy.rs"]
        pub mod ggx_proxy;
        #[path = "ggx_rect.rs"]
        pub mod ggx_rect;
        #[path = "implicit.rs"]
        pub mod implicit;
        #[path = "isotropic.rs"]
        pub mod isotropic;
        #[path = "jacobian.rs"]
        pub mod jacobian;
        #[path = "ndf.rs"]
        pub mod ndf;
        #[path = "presets.rs"]
        pub mod presets;
        #[path = "quadric.rs"]
        pub mod quadric;
        #[path = "roughness.rs"]
        pub mod roughness;
        #[path = "sample_beckmann.rs"]
        pub mod sample_beckmann;
        #[path = "sampling.rs"]
        pub mod sampling;
        #[path = "slope.rs"]
        pub mod slope;
        #[path = "temporal.rs"]
        pub mod temporal;

        pub use beckmann::Beckmann;
        pub use clamp::{ClampRules, ExtentFloor};
        pub use filter::LeanMoments;
        pub use footprint::{BoundingRect, Covariance, Footprint};
        pub use gaussian_ggx::GaussianFilteredGgx;
        pub use geometry::{Endpoint, PinholeRay, ShadingFrame};
        pub use ggx::Ggx;
        pub use implicit::{HitRates, LevelSetSample, MovingRay, Sym3};
        pub use isotropic::{Bandwidth, KernelConvention};
        pub use ndf::Ndf;
        pub use quadric::{LocalQuadric, RigidMotion};
        pub use roughness::{
            ALPHA_MAX, ALPHA_MIN, AxisAligned, Isotropic, Roughness, RoughnessMatrix,
        };
        pub use sampling::NdfSampling;
        pub use temporal::{TemporalLobe, TemporalRoughness};
    };
}

pub mod f32;
pub mod f64;

#[cfg(feature = "testing")]
pub mod testing;
