//! Fuzz target over temporal roughness (`temporal::*`, `TemporalLobe`) and its inputs: moving
//! implicit surfaces (`implicit::*`) and local quadrics (`quadric::*`),
//! in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_temporal` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_temporal(data);
});
