//! The constants of the exact Gaussian-filtered GGX's reduced accuracy settings
//! ([`Tolerance`](crate::f64::filter::Tolerance) other than `Full`; derivations in the module
//! docs of `GaussianFilteredGgx`, "Tolerance settings"), read from the rules the crate
//! evaluates: the one source of a port's constants. The `filtered-ndf-gpu` crate's `generate`
//! writes them into the WGSL (`shaders/filter/gaussian_ggx_quad.wgsl`), and its `--check`
//! fails when the two differ.
//!
//! ```
//! use filtered_ndf::f64::filter::Tolerance;
//! use filtered_ndf::testing::tolerance_rules::reduced_rules;
//!
//! let r = reduced_rules()[1];
//! assert_eq!(r.tolerance, Tolerance::Rel1e3);
//! assert_eq!((r.far, r.h, r.y_lo), (500.0, 0.75, 0.2));
//! assert!((r.exp_h - 0.75f64.exp()).abs() <= 1e-15 * r.exp_h);
//! ```

use crate::f64::filter::Tolerance;

/// One reduced setting's rules: the far-tail series where `2 l1 (far + 12 ln(1 + q)) <= 1 + q`,
/// else the trapezoid rule in `t = ln w` of step `h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReducedRule {
    /// The setting.
    pub tolerance: Tolerance,
    /// The far-tail switch `K`.
    pub far: f64,
    /// The trapezoid step `h` in `t = ln w`.
    pub h: f64,
    /// `e^h`.
    pub exp_h: f64,
    /// The relative truncation tolerance at the top of the trapezoid rule.
    pub eps_t: f64,
    /// The first node lies at or below `w = y_lo / (1 + q + 2 l1)`.
    pub y_lo: f64,
    /// `1 / (e^((n + 2) h) - 1)`, `n < 4`: the series below the first node.
    pub geom: [f64; 4],
    /// The most nodes the rule takes (`e^(k h)` finite in `f32`: `nodes h <= 88`).
    pub nodes: usize,
}

/// The rules of [`Tolerance::Rel1e4`], [`Tolerance::Rel1e3`] and [`Tolerance::Rel1e2`], in that
/// order.
pub fn reduced_rules() -> [ReducedRule; 3] {
    let tolerance = [Tolerance::Rel1e4, Tolerance::Rel1e3, Tolerance::Rel1e2];
    core::array::from_fn(|s| {
        let (far, h, exp_h, eps_t, y_lo, geom, nodes) =
            crate::f64::filter::gaussian_ggx_tol::constants(s);
        ReducedRule {
            tolerance: tolerance[s],
            far,
            h,
            exp_h,
            eps_t,
            y_lo,
            geom,
            nodes,
        }
    })
}
