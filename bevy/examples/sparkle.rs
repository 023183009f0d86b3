//! The sparkle scene (placeholder while the build runs).
fn main() {}
