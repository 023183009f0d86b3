//! Single precision: the whole crate over `f32` and glam's `Vec2`, `Vec3`, `Mat2`.
//! Renderers shade in this precision.

/// The scalar type of this precision.
pub type F = f32;
pub use glam::{Mat2, Vec2, Vec3};

precision_modules!();
