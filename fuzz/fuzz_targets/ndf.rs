//! Fuzz target over the NDF family (GGX, Beckmann; isotropic, axis-aligned, matrix and
//! clamped-matrix roughness; `p22`, `d`, `lambda`, `g1`, `g2`; the slope maps) in both
//! precisions. The decoder and the contract live in `filtered_ndf::testing::fuzz` so that
//! `tests/fuzz_replay.rs` checks the same contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_ndf(data);
});
