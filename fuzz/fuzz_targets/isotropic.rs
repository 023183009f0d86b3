//! Fuzz target over isotropic filtering (`deferred::*`: bandwidths, domains, norms,
//! `KernelConvention` with arbitrary fields) and every preset in `presets::ALL`,
//! in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_isotropic` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_isotropic(data);
});
