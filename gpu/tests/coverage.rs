//! Every exported WGSL function of `shaders/` has a conformance check: some check's snippet
//! calls it, or it is listed with a checked caller that reaches it in
//! `gpu/src/checks/through_callers.txt` (see `gpu/src/coverage.rs` for how a check declares
//! what it covers). No GPU needed: the checks are built (cases and `f64` references) but not
//! run.

use filtered_ndf_gpu::checks::GROUPS;
use filtered_ndf_gpu::coverage::{REGISTRY, coverage, parse_registry};
use filtered_ndf_gpu::modules::load_all;

#[test]
fn every_exported_wgsl_function_has_a_conformance_check() {
    let modules = load_all().expect("modules load");
    let checks: Vec<_> = GROUPS.iter().flat_map(|(_, all)| all()).collect();
    let registry = parse_registry(REGISTRY).unwrap_or_else(|e| panic!("{e}"));
    let c = coverage(&modules, &checks, &registry).unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "{} exported functions: {} called by a check, {} through their callers, {} uncovered",
        c.exported,
        c.called.len(),
        registry.len(),
        c.uncovered.len()
    );
    assert!(
        c.is_complete(),
        "exported WGSL functions without a conformance check (add a check in gpu/src/checks/ \
         whose snippet calls each, or list it with a checked caller that reaches it in \
         gpu/src/checks/through_callers.txt):\n  {}\nbad entries of through_callers.txt:\n  {}",
        c.uncovered.join("\n  "),
        c.bad_entries.join("\n  ")
    );
}
