//! The SIMD levels the batch kernels can run at in this build on this CPU, one name per line
//! (`batch::simd_available`, the detection the kernels' own choice uses): the values of
//! `FILTERED_NDF_SIMD` that `.ci/run` tests. With `--all`, every level and whether it is
//! available, and the level this process runs at.
//!
//! `cargo run --release --features dispatch --example simd_levels [-- --all]`

use filtered_ndf::f32::batch;

fn main() {
    let all = std::env::args().any(|a| a == "--all");
    for level in batch::SIMD_LEVELS {
        // Every name of `SIMD_LEVELS` is a level: `simd_available` cannot refuse it.
        let available = batch::simd_available(level).unwrap_or(false);
        if all {
            let word = if available {
                "available"
            } else {
                "not available"
            };
            println!("{level}: {word}");
        } else if available {
            println!("{level}");
        }
    }
    if all {
        println!("this process runs at {}", batch::simd_level());
    }
}
