//! Double precision: the whole crate over `f64` and glam's `DVec2`, `DVec3`, `DMat2`.
//! References and offline renderers use this precision. Inside this module the glam types
//! are re-exported under the names `Vec2`, `Vec3`, `Mat2`; they are `DVec2`, `DVec3`, `DMat2`.

/// The scalar type of this precision.
pub type F = f64;
pub use glam::{DMat2 as Mat2, DVec2 as Vec2, DVec3 as Vec3};

precision_modules!();
