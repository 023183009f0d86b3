//! Fuzz target over the exact Gaussian-filtered GGX: any roughness form, any kernel (NaN,
//! infinite, indefinite, huge), slopes, normals, directions and uniform numbers, in both
//! precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_gaussian_ggx` so that `tests/fuzz_replay_gaussian_ggx.rs`
//! checks the same contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_gaussian_ggx(data);
});
