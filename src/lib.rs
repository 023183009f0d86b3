//! # filtered-ndf
//!
//! Microfacet normal distribution functions (Beckmann and GGX in isotropic, axis-aligned and
//! full-matrix roughness) and the filtered-NDF kernels that stop glossy highlights from
//! sparkling and flickering: the pixel footprint is carried into the slope domain and the
//! NDF is filtered over it (Kaplanyan, Hill, Patney, Lefohn 2016, "KHPL16"; Tokuyoshi and
//! Kaplanyan 2019, "TK19"; Tessari et al. 2020 for motion blur).
//!
//! ## The front door: a filtered lobe in three lines
//!
//! ```
//! use filtered_ndf::f32::prelude::*;
//! use glam::{Vec2, Vec3};
//! # let (ddx_slope, ddy_slope) = (Vec2::new(0.03, 0.0), Vec2::new(0.0, 0.02));
//! # let h = Vec3::new(0.001, 0.0, 1.0).normalize();
//!
//! let material = Ggx::isotropic(0.01).unwrap();             // any NDF, any roughness form
//! let footprint = Footprint::from_slope_derivatives(ddx_slope, ddy_slope); // what you have
//! let lobe = material.filtered(footprint, Gaussian::TK19);   // TK19: Ggx<RoughnessMatrix>
//! # assert!(lobe.d(h) < material.d(h));
//! ```
//!
//! `lobe` is an ordinary NDF: `d`, `p22`, `lambda`, `g1`, `g2`, and (for this method)
//! `sample_visible_normal` and the pdfs, all of one distribution. The method is a value whose
//! type says what it returns ([`f32::filter::Method`]): [`Gaussian`](f32::filter::Gaussian)
//! (`A + 2 Sigma`: exact for Beckmann, TK19's approximation for GGX),
//! [`Projected`](f32::filter::Projected) (TK21), [`Rect`](f32::filter::Rect) (the exact box
//! filter of KHPL16) and [`Proxy`](f32::filter::Proxy) (KHPL16's GGX proxy). Footprints come
//! from whatever derivatives the renderer has ([`f32::Footprint`]'s constructors).
//!
//! Deferred shading, from G-buffer normal differences and an engine's convention, in one line:
//!
//! ```
//! use filtered_ndf::f32::prelude::*;
//! use glam::Vec3;
//! # let (alpha, ddx_normal, ddy_normal) = (0.01, Vec3::new(0.03, 0.0, 0.0), Vec3::ZERO);
//!
//! let lobe = Ggx::new(presets::TK19_TRACE.filter(alpha, ddx_normal, ddy_normal));
//! # assert!(lobe.d(Vec3::Z).is_finite());
//! ```
//!
//! ## Which kernel for which scene
//!
//! Cost: CPU `f32` time per evaluation relative to unfiltered GGX; error: median relative error
//! of `D` against the exact Gaussian-filtered NDF; both written by the trade table's run (the
//! demonstration crate's `tradeoff`). Each row runs as
//! `cargo run --release --example which_kernel -- ROW`.
//!
#![doc = include_str!("doc/which_kernel.md")]
//!
//! ## Layout
//! Every formula exists once and is compiled twice: [`f32`](mod@f32) (shading) and
//! [`f64`](mod@f64) (reference and offline) hold the same modules over glam's
//! `Vec2/Vec3/Mat2` and `DVec2/DVec3/DMat2`. The modules follow the pipeline: `ndf`
//! (roughness forms, GGX, Beckmann) -> `footprint` (slope maps, Jacobians, footprints) ->
//! `kernel` (covariance, rectangle, clamp rules) -> `filter` (the methods, the front door,
//! deferred presets) -> `sampling` -> `bsdf` (microfacet reflection with Fresnel, for path
//! tracers), with `temporal` (Tessari et al.) and `batch` beside.
//!
//! ## Conventions
//! Tangent frame with `z` along the shading normal; slope `s = -h_xy / h_z`; `p22` is a
//! density per unit slope area, `d` per steradian with `integral d(m) m_z dm = 1`.
//!
//! ## Features
//! - `std` (default): standard-library float intrinsics.
//! - `libm`: all float math through `libm` (required for `no_std`).
//! - `testing`: proptest strategies, f64 quadrature references and seeded shading cases for
//!   downstream tests.
//! - `dispatch`: runtime AVX2 / AVX-512 dispatch of the [`f32::batch`] kernels.
//! - `rayon`: batch kernels over chunks on rayon's thread pool.
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![allow(clippy::duplicate_mod)]

pub mod bake;
pub mod contract;
pub mod error;
pub mod math;

pub use error::{FresnelError, RoughnessError};

/// Declares the precision-generic modules inside [`f32`] and [`f64`]. Each file is written
/// once against the aliases `F`, `Vec2`, `Vec3`, `Mat2` of its parent module.
macro_rules! precision_modules {
    () => {
        // Each stage is deliberately loaded once per precision. The folders read as the
        // pipeline: roughness and NDFs -> footprints and Jacobians -> kernels and clamps ->
        // filters -> sampling -> bsdf, with the temporal extension and batch evaluation
        // beside.
        #[path = "batch/mod.rs"]
        pub mod batch;
        #[path = "bsdf/mod.rs"]
        pub mod bsdf;
        #[path = "filter/mod.rs"]
        pub mod filter;
        #[path = "footprint/mod.rs"]
        pub mod footprint;
        #[path = "kernel/mod.rs"]
        pub mod kernel;
        #[path = "ndf/mod.rs"]
        pub mod ndf;
        #[path = "prelude.rs"]
        pub mod prelude;
        #[path = "sampling/mod.rs"]
        pub mod sampling;
        #[path = "temporal/mod.rs"]
        pub mod temporal;
        #[path = "vector.rs"]
        pub mod vector;

        /// `pi` in this precision (`core::f64::consts::PI` rounded to `F`): the one copy every
        /// formula uses.
        pub const PI: F = core::f64::consts::PI as F;

        pub use filter::deferred::{Bandwidth, KernelConvention};
        pub use filter::{GaussianFilteredGgx, LeanMoments};
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
