//! The rows of the trade table (`filtered-ndf-demo`'s `tradeoff`) as WGSL snippets over one input
//! layout, for the cost measurements (`--bin cost`): static SPIR-V instruction counts and
//! evaluations per second, both relative to unfiltered GGX. Their accuracy is checked
//! row by row in [`crate::checks::filters`] and [`crate::checks::rect`].
//!
//! Inputs per case (9 slots): `alpha` (2), the unit half vector `h` (3), the slope
//! footprint `dh_u`, `dh_v` (2 + 2). Output: the filtered `D(h)`.

/// Input slots per case.
pub const N_IN: usize = 9;

/// The imports every row needs.
pub const IMPORTS: &str = "#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::footprint
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::proxy
#import filtered_ndf::filter::rect
#import filtered_ndf::filter::deferred
#import filtered_ndf::filter::presets
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::rect::lambda as box_lambda";

/// The prologue every row starts with: material `r` (and as a matrix `a`), half vector `h`,
/// footprint `fp`.
pub const PROLOGUE: &str = "let r = axis_aligned::from_alpha(x2(0u));
let a = axis_aligned::to_matrix(r);
let h = x3(2u);
let fp = footprint::from_slope_derivatives(x2(5u), x2(7u));";

/// `(row name, expression of the filtered D)`, in the trade table's order.
pub fn rows() -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = [
        ("GGX unfiltered", "ggx::d_axis_aligned(r, h)"),
        (
            "GGX exact Gaussian (this crate)",
            "gaussian_ggx::d(gaussian_ggx::from_kernel(a, clamp::pixel_kernel(clamp::KHPL16_RULES, fp, 0.5)), h)",
        ),
        (
            "GGX exact Gaussian (this crate) Rel1e4",
            "gaussian_ggx::d(gaussian_ggx::with_tolerance(gaussian_ggx::from_kernel(a, clamp::pixel_kernel(clamp::KHPL16_RULES, fp, 0.5)), gaussian_ggx::TOL_1E4), h)",
        ),
        (
            "GGX exact Gaussian (this crate) Rel1e3",
            "gaussian_ggx::d(gaussian_ggx::with_tolerance(gaussian_ggx::from_kernel(a, clamp::pixel_kernel(clamp::KHPL16_RULES, fp, 0.5)), gaussian_ggx::TOL_1E3), h)",
        ),
        (
            "GGX exact Gaussian (this crate) Rel1e2",
            "gaussian_ggx::d(gaussian_ggx::with_tolerance(gaussian_ggx::from_kernel(a, clamp::pixel_kernel(clamp::KHPL16_RULES, fp, 0.5)), gaussian_ggx::TOL_1E2), h)",
        ),
        (
            "GGX TK19 A+2Sigma (matrix)",
            "ggx::d_matrix(gaussian::filter_gaussian(clamp::DEFAULT_RULES, a, fp, 0.5), h)",
        ),
        (
            "GGX TK19 A+2Sigma, no clamps",
            "ggx::d_matrix(gaussian::gaussian(a, covariance::from_footprint(fp, 0.5)), h)",
        ),
        (
            "GGX TK21 projected",
            "ggx::d_matrix(projected::projected(a, clamp::kernel(clamp::DEFAULT_RULES, covariance::from_footprint(clamp::footprint(clamp::DEFAULT_RULES, fp), 0.5))), h)",
        ),
        (
            "GGX exact rect (bounding box)",
            "rect::d_rect(r, h, clamp::rect(clamp::ClampRules(1.0, clamp::FLOOR_NONE, 0.0, 0.18, true), bounding::from_footprint(fp), r.alpha).half_extent)",
        ),
        (
            "GGX printed 8-term rect (GDC, eps floor)",
            "rect::d_rect_printed(r, h.xy / h.z, h, clamp::rect(clamp::DEFAULT_RULES, bounding::from_footprint(fp), r.alpha).half_extent)",
        ),
        (
            "GGX proxy exact (eq. 19)",
            "ggx::d_axis_aligned(proxy::proxy(r, clamp::rect(clamp::DEFAULT_RULES, bounding::from_footprint(fp), r.alpha).half_extent), h)",
        ),
        (
            "GGX proxy simple (eq. 20)",
            "ggx::d_axis_aligned(proxy::proxy_simple(r, clamp::rect(clamp::DEFAULT_RULES, bounding::from_footprint(fp), r.alpha).half_extent), h)",
        ),
        // Smith Lambda of the lobes whose Lambda is their own (not a trade-table column: the
        // cost of g1 / g2 beside D), `h` as the view.
        ("GGX unfiltered Lambda", "ggx::lambda_axis_aligned(r, h)"),
        (
            "GGX exact Gaussian Lambda",
            "gaussian_ggx::lambda(gaussian_ggx::from_kernel(a, clamp::pixel_kernel(clamp::KHPL16_RULES, fp, 0.5)), h)",
        ),
        (
            "GGX exact rect Lambda (box lobe)",
            "box_lambda::lambda_rect(r, clamp::rect(clamp::KHPL16_RULES, bounding::from_footprint(fp), r.alpha).half_extent, h)",
        ),
    ]
    .iter()
    .map(|(a, b)| (a.to_string(), b.to_string()))
    .collect();
    let names = [
        "TK19 max (eq. 1)",
        "TK19 trace (eq. 4)",
        "TK19 average (eq. 5)",
        "TK21 listing 5",
        "Filament",
        "Unity HDRP",
        "Unity HDRP projected",
        "Godot 4",
        "O3DE",
        "Unreal",
        "Babylon.js (Vlachos 2015)",
        "three.js",
    ];
    for (i, n) in names.iter().enumerate() {
        v.push((
            format!("GGX deferred: {n}"),
            format!(
                "ggx::d_axis_aligned(axis_aligned::from_alpha(vec2<f32>(deferred::apply(presets::preset({i}u), r.alpha.x, vec3<f32>(fp.dh_u, 0.0), vec3<f32>(fp.dh_v, 0.0)), deferred::apply(presets::preset({i}u), r.alpha.y, vec3<f32>(fp.dh_u, 0.0), vec3<f32>(fp.dh_v, 0.0)))), h)"
            ),
        ));
    }
    v.extend(
        [
            ("Beckmann unfiltered", "beckmann::d_axis_aligned(r, h)"),
            (
                "Beckmann KHPL16 A+2Sigma (exact)",
                "beckmann::d_matrix(gaussian::gaussian(a, covariance::from_footprint(fp, 0.5)), h)",
            ),
            (
                "Beckmann A+2Sigma, default clamps",
                "beckmann::d_matrix(gaussian::filter_gaussian(clamp::DEFAULT_RULES, a, fp, 0.5), h)",
            ),
        ]
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string())),
    );
    v
}

/// The body of `eval()` for a row: the prologue, then `reps` evaluations with the half
/// vector nudged each time (so that a loop cannot be folded), summed into output 0.
pub fn body(expr: &str, reps: u32) -> String {
    if reps <= 1 {
        return format!("{PROLOGUE}\ny(0u, {expr});");
    }
    format!(
        "{PROLOGUE}\nvar acc = 0.0;\nvar hh = h;\nfor (var k = 0u; k < {reps}u; k++) {{\n    let h = hh;\n    acc += {expr};\n    hh = normalize(hh + vec3<f32>(1e-4, 0.0, 0.0));\n}}\ny(0u, acc);"
    )
}

/// Static SPIR-V instruction count of a composed module: the instructions inside function
/// bodies (everything between `OpFunction` and `OpFunctionEnd`, less labels, parameters and
/// variables), i.e. the code size of the row, calls not inlined, loops counted once.
pub fn spirv_instructions(words: &[u32]) -> usize {
    const OP_FUNCTION: u32 = 54;
    const OP_FUNCTION_PARAMETER: u32 = 55;
    const OP_FUNCTION_END: u32 = 56;
    const OP_VARIABLE: u32 = 59;
    const OP_LABEL: u32 = 248;
    const OP_LINE: u32 = 8;
    const OP_NO_LINE: u32 = 317;
    let mut i = 5; // header
    let mut inside = false;
    let mut n = 0;
    while i < words.len() {
        let w = words[i];
        let (len, op) = ((w >> 16) as usize, w & 0xffff);
        match op {
            OP_FUNCTION => inside = true,
            OP_FUNCTION_END => inside = false,
            OP_FUNCTION_PARAMETER | OP_VARIABLE | OP_LABEL | OP_LINE | OP_NO_LINE => {}
            _ if inside => n += 1,
            _ => {}
        }
        i += len.max(1);
    }
    n
}
