#define_import_path filtered_ndf::bake::moments

#import filtered_ndf::filter::lean

// The baked LEAN moment chain (`src/bake`, `filtered_ndf::bake::bake_rows`) as two textures
// with all their mips, sampled by the hardware's trilinear or anisotropic filtering. Every
// moment is linear in the texel weights, so a filtered fetch is the moments of the filter's
// footprint on the base level (to the chain's storage rounding): the covariance is formed
// after filtering, never filtered itself.
//
// | texture | format | channels |
// |---|---|---|
// | `moments` | `rgba16float` (filterable everywhere) or `rgba32float` (`float32-filterable`) | `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])` |
// | `moments_xy` | `r16float` or `r32float` | `E[s_x s_y]` |
//
// (the layout the command-line baker writes, `moments.ktx2` and `moments_xy.ktx2`: RGBA + R
// because no filterable three-channel float format exists in WebGPU). Slopes are the bake's:
// `s = -n_xy / n_z` in its OpenGL tangent frame (`x` along `+u`, `y` up the image, i.e. along
// `-v` in WebGPU's texture coordinates when the image's first row is its top).

/// The moments of one filtered fetch of each texture: `rgba = (E[s_x], E[s_y], E[s_x^2],
/// E[s_y^2])`, `xy = E[s_x s_y]` (the Rust `bake::lean_moments` of the texel
/// `[rgba.x, rgba.y, rgba.z, xy, rgba.w]`).
fn from_texels(rgba: vec4<f32>, xy: f32) -> lean::LeanMoments {
    return lean::LeanMoments(rgba.xy, vec3<f32>(rgba.z, xy, rgba.w));
}

/// The moments over a pixel footprint: both textures sampled with explicit derivatives of
/// `uv` (`textureSampleGrad`: trilinear or anisotropic, as `s` is set up; any shader stage,
/// uniform control flow not required). In a fragment shader pass `dpdx(uv)`, `dpdy(uv)`.
fn sample_grad(
    moments: texture_2d<f32>,
    moments_xy: texture_2d<f32>,
    s: sampler,
    uv: vec2<f32>,
    ddx_uv: vec2<f32>,
    ddy_uv: vec2<f32>,
) -> lean::LeanMoments {
    let rgba = textureSampleGrad(moments, s, uv, ddx_uv, ddy_uv);
    let xy = textureSampleGrad(moments_xy, s, uv, ddx_uv, ddy_uv).x;
    return from_texels(rgba, xy);
}

/// The moments at an explicit level of detail (`textureSampleLevel`: bilinear within a
/// level, linear between levels with a linear mipmap filter): for ray tracing, compute
/// shaders, or a level chosen from the footprint by the caller.
fn sample_level(
    moments: texture_2d<f32>,
    moments_xy: texture_2d<f32>,
    s: sampler,
    uv: vec2<f32>,
    level: f32,
) -> lean::LeanMoments {
    let rgba = textureSampleLevel(moments, s, uv, level);
    let xy = textureSampleLevel(moments_xy, s, uv, level).x;
    return from_texels(rgba, xy);
}
