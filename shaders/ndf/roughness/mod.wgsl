#define_import_path filtered_ndf::ndf::roughness

// The roughness forms (`src/.../roughness/`): a roughness is the matrix `A` of TK19
// supplement section 1 (Heitz 2014 section 5.4). Both NDFs depend on a slope `s` only through
// `s^T A^-1 s` and `sqrt(det A)`, and Smith's `Lambda(w)` only through `w_xy^T A w_xy`: each
// form (`isotropic`, `axis_aligned`, `matrix`) provides those three numbers as
// `inv_quadratic`, `quadratic` and `sqrt_det`, and the NDF modules take them as arguments.
// This module holds what the three share.

/// Smallest supported roughness `alpha` (`A`'s smallest eigenvalue is `ALPHA_MIN^2`).
const ALPHA_MIN: f32 = 1e-8;
/// Largest supported roughness `alpha` (`A`'s largest eigenvalue is `ALPHA_MAX^2`).
const ALPHA_MAX: f32 = 1e4;

/// `alpha` clamped into `[ALPHA_MIN, ALPHA_MAX]` (the Rust `clamp_alpha`; a NaN that the
/// driver preserves maps to `ALPHA_MIN`).
fn clamp_alpha(alpha: f32) -> f32 {
    return select(ALPHA_MIN, min(alpha, ALPHA_MAX), alpha >= ALPHA_MIN);
}
