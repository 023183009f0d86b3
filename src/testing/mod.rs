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
//! /// The port under test: GGX D(m) as a shader would write it, in the form without
//! /// cancellation near the peak: `(m_x^2 + m_y^2) + m_z^2 alpha^2` rather than
//! /// `1 + m_z^2 (alpha^2 - 1)`, which loses `alpha^2` to rounding for small alpha.
//! fn my_shader_ggx(alpha: f32, m: [f32; 3]) -> f32 {
//!     let a2 = alpha * alpha;
//!     let d = (m[0] * m[0] + m[1] * m[1]) + m[2] * m[2] * a2;
//!     a2 / (core::f32::consts::PI * d * d)
//! }
//!
//! proptest!(ProptestConfig::with_cases(200), |(
//!     alpha in strategies::alpha_in(1e-3, 1.0),
//!     m in strategies::upper_hemisphere(80.0),
//! )| {
//!     let reference = Ggx::isotropic(alpha).unwrap().d(m);
//!     let port = my_shader_ggx(alpha as f32, [m.x as f32, m.y as f32, m.z as f32]) as f64;
//!     // About ten f32 roundings (1.2e-7 each) plus the rounding of the inputs, which D
//!     // amplifies at most fourfold: 2e-6 relative bounds it with room.
//!     prop_assert!((port - reference).abs() <= 2e-6 * reference);
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

pub mod box_reference;
pub mod cases;
pub mod fuzz;
pub mod gaussian_reference;
pub mod linalg;
pub mod quadrature;
pub mod rng;
pub mod shading;
pub mod strategies;
pub mod tolerance_rules;
