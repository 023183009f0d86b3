//! Fuzz target over `NdfSampling` (normal and visible-normal sampling and their pdfs) for GGX and
//! Beckmann in every roughness form, and the Beckmann visible-slope quantile,
//! in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_sampling` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_sampling(data);
});
