//! The concatenated file evaluates exactly as the composed modules: the same snippets,
//! run once through naga_oil's composition and once through
//! `shaders/generated/filtered_ndf.wgsl`, give bit-identical results on the GPU.

use filtered_ndf_gpu::checks;
use filtered_ndf_gpu::harness::{Kernel, run, run_concatenated};

#[test]
fn concatenated_file_matches_composition() {
    let mut all = checks::math::all();
    all.extend(checks::ndf::all());
    all.extend(checks::footprint::all());
    all.extend(checks::filters::all());
    all.extend(checks::sampling::all());
    all.extend(checks::sampling_beckmann::all());
    all.extend(checks::rect::all());
    all.extend(checks::rect_sample::all());
    all.extend(checks::nan_policy::all());
    for c in &all {
        let k = Kernel {
            imports: &c.imports,
            body: &c.body,
            n_in: c.n_in,
            n_out: c.n_out,
        };
        let input: Vec<f32> = c
            .cases
            .iter()
            .take(256)
            .flat_map(|c| c.input.clone())
            .collect();
        let a = run(&k, &input).unwrap_or_else(|e| panic!("{e}"));
        let b = run_concatenated(&k, &input).unwrap_or_else(|e| panic!("{}: {e}", c.name));
        let same = a
            .iter()
            .zip(&b)
            .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()));
        assert!(
            same,
            "{}: concatenated file differs from composition",
            c.name
        );
    }
}
