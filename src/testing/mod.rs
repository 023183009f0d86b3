//! Test-harness exports (feature `testing`, std only): the f64 quadrature that every kernel of
//! the crate is tested against and proptest strategies for its inputs, so that a downstream
//! renderer can property-test its own port the same way.
//!
//! Enable it for tests only:
//!
//! ```toml
//! [dev-dependencies]
//! filtered-ndf = { version = "0.1", features = ["testing"] }
//! ```
//!
//! A downstream test of a hand-ported isotropic GGX (as a shader author would write it in
//! WGSL/HLSL, here in Rust f32) against the crate's f64 reference, over the crate's own input
//! distributions, and a check that the reference itself is normalised by quadrature:
//!
//! ```
//! use filtered_ndf::f64::{Ggx, Ndf};
//! use filtered_ndf::testing::{quadrature, strategies};
//! use proptest::prelude::*;
//!
//! /// The port under test: GGX D(m) as written in a shader.
//! fn my_shader_ggx(alpha: f32, n_dot_m: f32) -> f32 {
//!     let a2 = alpha * alpha;
//!     let d = n_dot_m * n_dot_m * (a2 - 1.0) + 1.0;
//!     a2 / (core::f32::consts::PI * d * d)
//! }
//!
//! proptest!(ProptestConfig::with_cases(200), |(
//!     alpha in strategies::alpha_in(0.02, 1.0),
//!     m in strategies::upper_hemisphere(80.0),
//! )| {
//!     let reference = Ggx::isotropic(alpha).unwrap().d(m);
//!     let port = my_shader_ggx(alpha as f32, m.z as f32) as f64;
//!     // The `a2 - 1` form cancels near the peak: about 1e-4 relative is what f32 gives here.
//!     prop_assert!((port - reference).abs() <= 1e-4 * reference + 1e-30);
//! });
//!
//! // The reference integrates to one over the slope plane (f64 adaptive quadrature).
//! let ggx = Ggx::isotropic(0.3).unwrap();
//! let total = quadrature::integrate_plane(
//!     |x, y| ggx.p22(glam::DVec2::new(x, y)),
//!     (0.0, 0.0),
//!     (0.3, 0.3),
//!     quadrature::Tolerance::relative(1e-9),
//! );
//! assert!((total.value - 1.0).abs() < 1e-7);
//! ```

pub mod cases;
pub mod fuzz;
pub mod gaussian_reference;
pub mod quadrature;
pub mod rng;
pub mod strategies;
