#define_import_path filtered_ndf::filter::method

#import filtered_ndf::ndf
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::proxy as proxy_roughness
#import filtered_ndf::filter::rect
#import filtered_ndf::filter::rect::lambda as box_lambda

// The front door (`src/.../filter/method.rs`): one call from what a shader has (a material
// roughness and a pixel footprint) to a filtered lobe whose functions describe one
// distribution. WGSL has no traits, so each method is a small struct (its clamp rules and
// pixel filter width, with the Rust presets as constants) and a `*_lobe` function that returns
// the lobe, plus a `d_*` function that returns the filtered `D(m)` in one call:
//
// | method (Rust) | constants | lobe function | the lobe, evaluated with |
// |---|---|---|---|
// | `Gaussian` | `TK19_GAUSSIAN`, `KHPL16_GAUSSIAN` | `gaussian_lobe` | `matrix::RoughnessMatrix`: `ggx::*_matrix` (TK19's `A + 2 Sigma`), `beckmann::*_matrix` (exact) |
// | `ExactGaussian` | `KHPL16_EXACT_GAUSSIAN` | `exact_gaussian_lobe` | `gaussian_ggx::GaussianFilteredGgx`: `gaussian_ggx::{p22, d, lambda, g1, g2}`; for Beckmann the exact filter is `gaussian_lobe` with the same rules |
// | `Projected` | `TK21_PROJECTED` | `projected_lobe` | `matrix::RoughnessMatrix`: `ggx::*_matrix` |
// | `Rect` | `KHPL16_RECT`, `GDC2016_RECT` | `rect_lobe` | [`RectFilteredGgx`]: `p22_rect_filtered`, `d_rect_filtered`, `lambda_rect_filtered` (the box lobe's own), `g1_rect_filtered`, `g2_rect_filtered` |
// | `Proxy` | `KHPL16_PROXY` | `proxy_lobe` | `axis_aligned::AxisAligned`: `ggx::*_axis_aligned` |
//
// The materials: a roughness matrix for the Gaussian methods (an isotropic or axis-aligned
// material converts with its `to_matrix`), an axis-aligned roughness for the box methods (their
// rectangle is axis-aligned; an isotropic `alpha` is `axis_aligned::from_alpha(vec2(alpha))`,
// as the Rust `From<Isotropic>`). The footprint: `footprint::Footprint` from whichever
// derivatives the shader has (`footprint.wgsl`); `Projected` wants the projected-disk
// derivatives (TK19 section 3.2), a slope footprint is exact at `h = n`.
// (Names: WGSL identifiers may not end in a digit here, see shaders/README.md, so the Rust
// `Gaussian::TK19` is `TK19_GAUSSIAN`.)

/// `A' = A + 2 Sigma` with the clamped Gaussian pixel kernel (KHPL16 eq. 13-15; TK19 section
/// 2.2): exact for Beckmann, TK19's approximation for GGX.
struct Gaussian {
    /// The clamp rules applied to the footprint, the kernel and the filtered matrix.
    clamps: clamp::ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    sigma: f32,
}

/// TK19: the default rules (`lambda = 1`, `kappa = 0.18`, the determinant clamp), `sigma = 0.5`.
const TK19_GAUSSIAN: Gaussian = Gaussian(clamp::DEFAULT_RULES, pixel::SIGMA_PIXEL);
/// KHPL16's parallelogram kernel: `lambda = 1` and the determinant clamp, no `kappa`.
const KHPL16_GAUSSIAN: Gaussian = Gaussian(clamp::KHPL16_RULES, pixel::SIGMA_PIXEL);

/// The lobe of `material` filtered by `method` over `fp` (the Rust `Gaussian::lobe`): the
/// filtered roughness matrix, for `ggx::*_matrix` or `beckmann::*_matrix`.
fn gaussian_lobe(method: Gaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint) -> matrix::RoughnessMatrix {
    return gaussian::filter_gaussian(method.clamps, material, fp, method.sigma);
}

/// `D(m)` of the GGX lobe of [`gaussian_lobe`].
fn d_ggx_gaussian(method: Gaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return ggx::d_matrix(gaussian_lobe(method, material, fp), m);
}

/// `D(m)` of the Beckmann lobe of [`gaussian_lobe`] (the exact Gaussian filter of Beckmann).
fn d_beckmann_gaussian(method: Gaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return beckmann::d_matrix(gaussian_lobe(method, material, fp), m);
}

/// The exact Gaussian filter: the material's slope density convolved with the clamped pixel
/// kernel (GGX: `GaussianFilteredGgx`; Beckmann: `A + 2 Sigma`, [`gaussian_lobe`] with the
/// same rules).
struct ExactGaussian {
    /// The clamp rules applied to the footprint and the kernel.
    clamps: clamp::ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    sigma: f32,
}

/// The unbiased filter of the footprint: `lambda = 1` (KHPL16 section 5.2), no `kappa`,
/// `sigma = 0.5`.
const KHPL16_EXACT_GAUSSIAN: ExactGaussian = ExactGaussian(clamp::KHPL16_RULES, pixel::SIGMA_PIXEL);

/// The GGX lobe of the exact Gaussian filter (the Rust `ExactGaussian::lobe` for GGX).
fn exact_gaussian_lobe(method: ExactGaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint) -> gaussian_ggx::GaussianFilteredGgx {
    return gaussian_ggx::from_kernel(material, clamp::pixel_kernel(method.clamps, fp, method.sigma));
}

/// `D(m)` of [`exact_gaussian_lobe`].
fn d_ggx_exact_gaussian(method: ExactGaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return gaussian_ggx::d(exact_gaussian_lobe(method, material, fp), m);
}

/// Projected-space filtering of GGX (Tokuyoshi and Kaplanyan 2021), the kernel of the
/// footprint after the clamp rules.
struct Projected {
    /// The clamp rules applied to the footprint, the kernel and the filtered matrix.
    clamps: clamp::ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    sigma: f32,
}

/// TK21: the default rules, `sigma = 0.5`.
const TK21_PROJECTED: Projected = Projected(clamp::DEFAULT_RULES, pixel::SIGMA_PIXEL);

/// The GGX lobe of projected-space filtering (the Rust `Projected::lobe`), for `ggx::*_matrix`.
fn projected_lobe(method: Projected, material: matrix::RoughnessMatrix, fp: pixel::Footprint) -> matrix::RoughnessMatrix {
    return projected::filter_projected(method.clamps, material, fp, method.sigma);
}

/// `D(m)` of [`projected_lobe`].
fn d_ggx_projected(method: Projected, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return ggx::d_matrix(projected_lobe(method, material, fp), m);
}

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

/// `P22(s)` of the box lobe (`rect::p22_rect`).
fn p22_rect_filtered(lobe: RectFilteredGgx, s: vec2<f32>) -> f32 {
    return rect::p22_rect(lobe.roughness, s, lobe.half_extent);
}

/// `D(m)` of the box lobe (`rect::d_rect`).
fn d_rect_filtered(lobe: RectFilteredGgx, m: vec3<f32>) -> f32 {
    return rect::d_rect(lobe.roughness, m, lobe.half_extent);
}

/// Smith `Lambda(w)` of the box lobe: the box-filtered distribution's own
/// (`rect::lambda::lambda_rect`), so that `g1`, `g2` and `d` describe one distribution.
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

/// The GGX proxy of KHPL16 section 5.4 (eq. 18-19, solved exactly): the axis-aligned GGX whose
/// peak is the box-filtered peak over the clamped bounding rectangle, per axis.
struct Proxy {
    /// The clamp rules applied to the rectangle's half extents.
    clamps: clamp::ClampRules,
}

/// KHPL16: half extents clamped to `lambda = 1`, no floor.
const KHPL16_PROXY: Proxy = Proxy(clamp::KHPL16_RULES);

/// The proxy roughness (the Rust `Proxy::lobe`), for `ggx::*_axis_aligned`.
fn proxy_lobe(method: Proxy, material: axis_aligned::AxisAligned, fp: pixel::Footprint) -> axis_aligned::AxisAligned {
    let h = clamp::rect(method.clamps, bounding::from_footprint(fp), material.alpha).half_extent;
    return proxy_roughness::proxy(material, h);
}

/// `D(m)` of [`proxy_lobe`].
fn d_ggx_proxy(method: Proxy, material: axis_aligned::AxisAligned, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return ggx::d_axis_aligned(proxy_lobe(method, material, fp), m);
}
