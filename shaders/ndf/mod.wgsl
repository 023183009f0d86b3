#define_import_path filtered_ndf::ndf

// What every NDF shares (`src/.../ndf/mod.rs`, the `Ndf` trait): the Smith terms derived
// from `Lambda` once. Conventions (all NDFs, all roughness forms): tangent frame with `z` the
// shading normal; slope of a micronormal `s = -m_xy / m_z` (TK19 supplement eq. 5);
// `p22(s)` per unit slope area, integrating to 1 over the plane; `d(m) = p22(s(m)) / m_z^4`
// per steradian with `integral d(m) m_z dm = 1` (KHPL16 eq. 2).
//
// WGSL has no generics: the NDF modules (`ggx`, `beckmann`) take the numbers a roughness
// form reduces to (`inv_quadratic`, `quadratic`, `sqrt_det` of the `roughness` modules) and
// add one entry point per form (`d_isotropic`, `d_axis_aligned`, `d_matrix`, ...). The
// form-independent cores carry the suffix `_of` (`p22_of`, `d_of`, `lambda_of`, `g1_of`,
// `g2_of`): naga renames any identifier that ends in a digit when it writes a module back
// out, which naga_oil refuses for composable modules, so `p22`, `g1`, `g2` cannot be names
// of their own.
//
// NaN policy. The Rust crate decides it once (`src/.../ndf/mod.rs`): a NaN argument
// contributes nothing, `p22 = d = 0` and `lambda = +inf` (so `g1 = g2 = 0`), both families,
// every form. WGSL lets a driver assume that no NaN occurs at run time, so the shaders do not
// test for one and promise nothing where a driver takes that licence. Where it costs nothing
// (the comparisons every function makes anyway), they are written so that a NaN fails them
// and the result is the Rust one: `d_of` and `p22_of` return 0 (`select` on `m_z > 0`,
// `q >= 0`), `lambda_of` returns `F32_MAX` (the shaders' `+inf`), `g1_of` and `g2_of` return 0
// (`w.m > 0`). Mesa's lavapipe and llvmpipe keep these comparisons.

/// Smith masking `G1(w, m) = chi+(w.m) / (1 + Lambda(w))` from `Lambda(w)` and `w.m` (TK19
/// supplement section 1). In `[0, 1]`; `0` for `w.m <= 0`. (A grazing `w` has
/// `Lambda = F32_MAX` in the shaders, so `G1` is `0` up to rounding.)
fn g1_of(lambda_w: f32, w_dot_m: f32) -> f32 {
    return select(0.0, 1.0 / (1.0 + lambda_w), w_dot_m > 0.0);
}

/// Height-correlated masking-shadowing
/// `G2(i, o, m) = chi+(i.m) chi+(o.m) / (1 + Lambda(i) + Lambda(o))` (TK19 supplement
/// section 1; Heitz 2014 eq. 99) from both `Lambda`s and both dot products. In `[0, 1]`.
fn g2_of(lambda_i: f32, lambda_o: f32, i_dot_m: f32, o_dot_m: f32) -> f32 {
    return select(0.0, 1.0 / (1.0 + lambda_i + lambda_o), i_dot_m > 0.0 && o_dot_m > 0.0);
}
