//! Fuzz target over the exact GGX rectangle integral (`rect::p22_rect`, `d_rect`), the printed GDC
//! baseline (`d_rect_printed`) and the GGX proxy (`proxy::*`),
//! in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_rect` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_rect(data);
});
