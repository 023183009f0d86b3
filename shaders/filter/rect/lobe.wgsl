#define_import_path filtered_ndf::filter::rect::lobe

#import filtered_ndf::ndf
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::rect as boxed
#import filtered_ndf::filter::rect::lambda as box_lambda

// The box-filter method and its lobe (`src/.../filter/rect/lobe.rs`): `Rect` (KHPL16 section
// 5.3, the footprint's bounding rectangle after the clamp rules) gives `RectFilteredGgx`, the
// axis-aligned GGX averaged over that rectangle (`boxed::p22_rect`, `boxed::d_rect`), with its
// own Smith `Lambda` (`box_lambda::lambda_rect`). Its sampler is `sampling::rect`.

/// The exact box filter of KHPL16 section 5.3 over the footprint's bounding rectangle, its half
/// extents clamped by the rules (`clamp::rect`).
struct Rect {
    /// The clamp rules applied to the rectangle's half extents.
    clamps: clamp::ClampRules,
}

/// KHPL16 with the exact integral: half extents clamped to `lambda = 1`, no floor.
const KHPL16_RECT: Rect = Rect(clamp::KHPL16_RULES);
/// The GDC 2016 listing's clamps: half extents in `[min(alpha, 0.1), 1]`.
const GDC2016_RECT: Rect = Rect(clamp::GDC2016_RULES);

/// The exactly box-filtered GGX lobe (the Rust `RectFilteredGgx`): the material's slope density
/// averaged over `[-half_extent, half_extent]` around each slope.
struct RectFilteredGgx {
    /// The material's roughness.
    roughness: axis_aligned::AxisAligned,
    /// The rectangle's half extents (slope units, `>= 0`).
    half_extent: vec2<f32>,
}

/// The box-filtered lobe of `material` over `fp` (the Rust `Rect::lobe`).
fn rect_lobe(method: Rect, material: axis_aligned::AxisAligned, fp: pixel::Footprint) -> RectFilteredGgx {
    let h = clamp::rect(method.clamps, bounding::from_footprint(fp), material.alpha).half_extent;
    return RectFilteredGgx(material, h);
}

/// `P22(s)` of the box lobe (`boxed::p22_rect`).
fn p22_rect_filtered(lobe: RectFilteredGgx, s: vec2<f32>) -> f32 {
    return boxed::p22_rect(lobe.roughness, s, lobe.half_extent);
}

/// `D(m)` of the box lobe (`boxed::d_rect`).
fn d_rect_filtered(lobe: RectFilteredGgx, m: vec3<f32>) -> f32 {
    return boxed::d_rect(lobe.roughness, m, lobe.half_extent);
}

/// Smith `Lambda(w)` of the box lobe: the box-filtered distribution's own
/// (`lambda::lambda_rect`), so that `g1`, `g2` and `d` describe one distribution.
fn lambda_rect_filtered(lobe: RectFilteredGgx, w: vec3<f32>) -> f32 {
    return box_lambda::lambda_rect(lobe.roughness, lobe.half_extent, w);
}

/// `G1(w, m)` of the box lobe.
fn g1_rect_filtered(lobe: RectFilteredGgx, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda_rect_filtered(lobe, w), dot(w, m));
}

/// `G2(i, o, m)` of the box lobe (height-correlated).
fn g2_rect_filtered(lobe: RectFilteredGgx, i: vec3<f32>, o: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g2_of(lambda_rect_filtered(lobe, i), lambda_rect_filtered(lobe, o), dot(i, m), dot(o, m));
}

/// `D(m)` of [`rect_lobe`].
fn d_ggx_rect(method: Rect, material: axis_aligned::AxisAligned, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return d_rect_filtered(rect_lobe(method, material, fp), m);
}
