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
//! use filtered_ndf::f32::{ClampRules, Footprint, Ggx, Isotropic, Ndf, filter::rect, filter::presets};
//! use glam::{Vec2, Vec3};
//!
//! let alpha = Isotropic::new(0.01).unwrap();
//! let h = Vec3::new(0.001, 0.0, 1.0).normalize(); // near the peak of the lobe
//! // ddx/ddy of the half vector's slope (KHPL16 section 5.1).
//! let fp = Footprint::from_slope_derivatives(Vec2::new(0.03, 0.0), Vec2::new(0.0, 0.02));
//! let d_matrix = Ggx::new(ClampRules::default().filter_gaussian(alpha, fp, 0.5)).d(h);
//! let d_box = rect::d_rect(alpha.into(), h, fp.bounding_rect().half_extent);
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
        // Each stage is deliberately loaded once per precision. The folders read as the
        // pipeline: roughness and NDFs -> footprints and Jacobians -> kernels and clamps ->
        // filters -> sampling, with the temporal extension and batch evaluation beside.
        #[path = "batch.rs"]
        pub mod batch;
        #[path = "filter/mod.rs"]
        pub mod filter;
        #[path = "footprint/mod.rs"]
        pub mod footprint;
        #[path = "kernel/mod.rs"]
        pub mod kernel;
        #[path = "ndf/mod.rs"]
        pub mod ndf;
        #[path = "sampling/mod.rs"]
        pub mod sampling;
        #[path = "temporal/mod.rs"]
        pub mod temporal;
        #[path = "vector.rs"]
        pub mod vector;

        /// `pi` in this precision (`core::f64::consts::PI` rounded to `F`): the one copy every
        /// formula uses.
        pub const PI: F = core::f64::consts::PI as F;

        pub use filter::LeanMoments;
        pub use filter::deferred::{Bandwidth, KernelConvention};
        pub use footprint::Footprint;
        pub use footprint::geometry::{Endpoint, PinholeRay, ShadingFrame};
        pub use kernel::{BoundingRect, ClampRules, Covariance, ExtentFloor};
        pub use ndf::Ndf;
        pub use ndf::beckmann::Beckmann;
        pub use ndf::ggx::Ggx;
        pub use ndf::roughness::{
            ALPHA_MAX, ALPHA_MIN, AxisAligned, Isotropic, Roughness, RoughnessMatrix,
        };
        pub use sampling::NdfSampling;
        pub use temporal::implicit::{HitRates, LevelSetSample, MovingRay, Sym3};
        pub use temporal::quadric::{LocalQuadric, RigidMotion};
        pub use temporal::{TemporalLobe, TemporalRoughness};
    };
}

pub mod f32;
pub mod f64;

#[cfg(feature = "testing")]
pub mod testing;
