//! Fuzz target over footprint constructors and shapes, `Covariance` (eigenvalues, eigenvalue clamp,
//! sanitising), `ClampRules` and the Gaussian, projected and LEAN filters, with the filtered
//! matrices evaluated by GGX and Beckmann,
//! in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_filter` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_filter(data);
});
