//! Measured tables, included verbatim from `docs/` so that the crate docs and the README
//! carry the same figures. Regenerate them whenever a kernel changes:
//! `cargo run --release --example tradeoff -- --out docs` (the trade table and
//! `docs/tradeoff.svg`) and `cargo run --release --example highlights` (copy
//! `target/highlights/results.md` to `docs/highlights.md`).
//!
//! # Trade table: error and cost of every kernel
//!
//! Error: relative to the f64 quadrature of the exact Gaussian-filtered NDF
//! (`testing::gaussian_reference`) at the same half vector and footprint; "max err / filtered
//! peak" is the worst absolute error over the exact filtered peak, i.e. how visible an error
//! is. Supersampling rows average the unfiltered GGX over N jittered points of the same
//! Gaussian footprint (what a renderer does without this crate).
//!
#![doc = include_str!("../docs/tradeoff.md")]
//!
//! # Demonstration: what a viewer sees (FLIP, flicker, specular error, false glints) and the RMSE, on the water and on a normal-mapped floor
//!
#![doc = include_str!("../docs/highlights.md")]
