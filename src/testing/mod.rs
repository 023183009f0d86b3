//! Test-harness exports (feature `testing`, std only): the f64 quadrature that every kernel of
//! the crate is tested against and proptest strategies for its inputs, so that a downstream
//! renderer can property-test its own port the same way.

pub mod quadrature;
pub mod strategies;
