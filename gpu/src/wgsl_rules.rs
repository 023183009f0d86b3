//! The reduced accuracy settings' constants in `shaders/filter/gaussian_ggx_quad.wgsl`
//! (`reduced_far`, `reduced_rule`), written by `generate` between the lines [`BEGIN`] and
//! [`END`] from the rules the Rust crate evaluates
//! ([`filtered_ndf::testing::tolerance_rules`]), so that the WGSL cannot drift from them
//! (`generate -- --check` in CI).

use crate::modules::shaders_dir;
use filtered_ndf::testing::tolerance_rules::{ReducedRule, reduced_rules};

/// The file, relative to `shaders/`.
pub const FILE: &str = "filter/gaussian_ggx_quad.wgsl";
/// The line before the generated functions.
pub const BEGIN: &str = "// BEGIN reduced rules";
/// The line after them.
pub const END: &str = "// END reduced rules";

/// The file's path on disk.
pub fn path() -> std::path::PathBuf {
    shaders_dir().join(FILE)
}

/// The WGSL `TrapezoidRule` of `r`: its node count rounded down to the 8-node chunks of the
/// WGSL loop.
fn rule_literal(r: &ReducedRule) -> String {
    let g = r.geom;
    format!(
        "TrapezoidRule({:?}, {:?}, {:?}, {:?}, vec4<f32>({:?}, {:?}, {:?}, {:?}), {}u)",
        r.h,
        r.exp_h,
        r.eps_t,
        r.y_lo,
        g[0],
        g[1],
        g[2],
        g[3],
        r.nodes / 8 * 8
    )
}

/// The generated functions for `rules` (Rel1e4, Rel1e3, Rel1e2: `tol` 1, 2, 3), markers
/// included.
pub fn block(rules: &[ReducedRule; 3]) -> String {
    let mut far = String::new();
    let mut rule = String::new();
    for (i, r) in rules.iter().enumerate() {
        let case = if i == 2 {
            "default".to_string()
        } else {
            format!("case {}u", i + 1)
        };
        far.push_str(&format!("        {case}: {{ return {:?}; }}\n", r.far));
        rule.push_str(&format!(
            "        {case}: {{ return {}; }}\n",
            rule_literal(r)
        ));
    }
    format!(
        "{BEGIN}\n\
         // Written by `cargo run -p filtered-ndf-gpu --bin generate` from the Rust rules\n\
         // (`filtered_ndf::testing::tolerance_rules`); do not edit.\n\
         \n\
         /// The far-tail switch `K` of a reduced setting (`TOL_1E4`, `TOL_1E3`, else `TOL_1E2`).\n\
         fn reduced_far(tol: u32) -> f32 {{\n    switch tol {{\n{far}    }}\n}}\n\
         \n\
         /// The trapezoid rule of a reduced setting (`TOL_1E4`, `TOL_1E3`, else `TOL_1E2`): the\n\
         /// Rust rule's constants, its node count rounded down to the 8-node chunks of\n\
         /// [`trapezoid_rule`].\n\
         fn reduced_rule(tol: u32) -> TrapezoidRule {{\n    switch tol {{\n{rule}    }}\n}}\n\
         {END}\n"
    )
}

/// `source` with the lines from [`BEGIN`] to [`END`] replaced by [`block`] of the crate's
/// rules; an error if the markers are missing.
pub fn with_block(source: &str) -> Result<String, String> {
    let start = source
        .find(BEGIN)
        .ok_or_else(|| format!("shaders/{FILE}: no line `{BEGIN}`"))?;
    let end = source[start..]
        .find(END)
        .map(|e| start + e)
        .ok_or_else(|| format!("shaders/{FILE}: no line `{END}` after `{BEGIN}`"))?;
    let after = source[end..]
        .find('\n')
        .map_or(source.len(), |n| end + n + 1);
    Ok(format!(
        "{}{}{}",
        &source[..start],
        block(&reduced_rules()),
        &source[after..]
    ))
}
