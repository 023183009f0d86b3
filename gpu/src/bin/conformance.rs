//! Runs every conformance check on the adapter `FILTERED_NDF_GPU_BACKEND` selects and
//! prints one markdown table: each WGSL function, its cases, the worst measured error
//! (relative, or absolute where the tolerance is absolute) and the worst error as a
//! fraction of its stated tolerance. The tests (`gpu/tests/conformance.rs`) assert the same
//! checks; this prints them all, for reports.
//!
//! ```text
//! FILTERED_NDF_GPU_BACKEND=gl cargo run --release -p filtered-ndf-gpu --bin conformance
//! ```

use filtered_ndf_gpu::checks::{self, run_group};
use filtered_ndf_gpu::harness;

fn main() {
    let gpu = harness::gpu().unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    println!("Conformance on {}\n", gpu.label());
    println!("| group | WGSL function | cases | worst error | of tolerance | tolerance |");
    println!("|---|---|---:|---|---:|---|");
    let mut failed = 0;
    for (group, all) in checks::GROUPS {
        let (outcomes, _) = run_group(group, &all()).unwrap_or_else(|e| panic!("{e}"));
        for o in outcomes {
            failed += usize::from(o.n_failed > 0);
            println!(
                "| {group} | `{}` | {} | {} | {:.3}{} | {} |",
                o.name,
                o.cases,
                o.worst(),
                o.worst_of_tol,
                if o.n_failed > 0 { " FAILED" } else { "" },
                o.tolerance
            );
        }
    }
    if failed > 0 {
        eprintln!("{failed} functions out of tolerance");
        std::process::exit(1);
    }
}
