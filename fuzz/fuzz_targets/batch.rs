//! Fuzz target over the slice API (`batch`): the chunk driver and every lane family against
//! the scalar functions, in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_batch` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_batch(data);
});
