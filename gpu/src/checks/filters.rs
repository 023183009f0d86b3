//! `shaders/footprint/` and `shaders/kernel/`.
use super::Check;
/// The checks.
pub fn all() -> Vec<Check> {
    Vec::new()
}
