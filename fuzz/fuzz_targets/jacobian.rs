//! Fuzz target over the half-vector Jacobians (`jacobian::*`), the slope maps and the geometric
//! footprints (`geometry::*`: half-vector Jacobian, footprint, projected footprint, ray
//! differentials),
//! in both precisions. The decoder and the contract live in
//! `filtered_ndf::testing::fuzz::check_jacobian` so that `tests/fuzz_replay.rs` checks the same
//! contract in CI.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    filtered_ndf::testing::fuzz::check_jacobian(data);
});
