//! Test-harness exports (feature `testing`, std only): the f64 quadrature that every kernel of
//! the crate is tested against, so that a downstream renderer can test its own port the same
//! way.

pub mod cases;
pub mod fuzz;
pub mod quadrature;
