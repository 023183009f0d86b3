#define_import_path filtered_ndf::filter::lean_nested

#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance as cov
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::lean
#import filtered_ndf::filter::projected
#import filtered_ndf::filter::proxy
#import filtered_ndf::filter::rect::lobe

// LEAN moments nested into every method of the front door (KHPL16 section 5.5, eq. 21),
// mirroring `src/.../filter/lean_nested.rs` (`Lean<M>`): the material is widened by the LEAN
// kernel, `A_L = A + 2 Sigma_L` (`lean_widened`), then each method filters the widened lobe
// over the pixel footprint as it filters a material. The clamp rules act on the pixel kernel
// only. `moments` come from the baked chain (`bake::moments::sample_grad`).
//
// | method | nested lobe function | evaluate with |
// |---|---|---|
// | `gaussian::Gaussian` | `gaussian_lobe` | `ggx::*_matrix`, `beckmann::*_matrix` |
// | `gaussian_ggx::ExactGaussian` | `exact_gaussian_lobe` (GGX: one kernel `Sigma_L + K_P`, exact); Beckmann: `gaussian_lobe` | `gaussian_ggx::*` |
// | `projected::Projected` | `projected_lobe` | `ggx::*_matrix` |
// | `lobe::Rect` (`filter::rect::lobe`) | `rect_lobe` (the widened diagonal, `lean_widened_axis_aligned`) | `lobe::*_rect_filtered` |
// | `proxy::Proxy` | `proxy_lobe` (likewise) | `ggx::*_axis_aligned` |

/// `A_L = A + 2 Sigma_L`, `Sigma_L = lean::covariance(moments)` (PSD-projected), with the
/// determinant clamp `tau = det A` (the Rust `lean_widened`; `gaussian::gaussian`).
fn lean_widened(a: matrix::RoughnessMatrix, moments: lean::LeanMoments) -> matrix::RoughnessMatrix {
    return gaussian::gaussian(a, lean::covariance(moments));
}

/// The box methods' lobe: `alpha_i' = sqrt(alpha_i^2 + 2 (Sigma_L)_ii)`, the diagonal of
/// `A_L` (the Rust `lean_widened_axis_aligned`), clamped as `axis_aligned::from_alpha`.
fn lean_widened_axis_aligned(r: axis_aligned::AxisAligned, moments: lean::LeanMoments) -> axis_aligned::AxisAligned {
    let c = lean::covariance(moments);
    let a = r.alpha;
    return axis_aligned::from_alpha(sqrt(a * a + 2.0 * vec2<f32>(c.s_xx, c.s_yy)));
}

/// The texel's shading normal, `normalize(-E[s_x], -E[s_y], 1)` (the Rust `lean_mean_normal`).
fn lean_mean_normal(moments: lean::LeanMoments) -> vec3<f32> {
    return normalize(vec3<f32>(-moments.mean, 1.0));
}

/// `Lean<Gaussian>::lobe`: `gaussian::gaussian_lobe` of the widened material.
fn gaussian_lobe(
    m: gaussian::Gaussian,
    material: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> matrix::RoughnessMatrix {
    return gaussian::gaussian_lobe(m, lean_widened(material, moments), fp);
}

/// `Lean<ExactGaussian>::lobe` for GGX: the exact Gaussian-filtered GGX of the material over
/// one kernel, the method's clamped pixel kernel plus `Sigma_L` (both Gaussians, so they add),
/// at the method's accuracy setting.
fn exact_gaussian_lobe(
    m: gaussian_ggx::ExactGaussian,
    material: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> gaussian_ggx::GaussianFilteredGgx {
    let k = cov::add(clamp::pixel_kernel(m.clamps, fp, m.sigma), lean::covariance(moments));
    return gaussian_ggx::with_tolerance(gaussian_ggx::from_kernel(material, k), m.tolerance);
}

/// `Lean<Projected>::lobe`: `projected::projected_lobe` of the widened material.
fn projected_lobe(
    m: projected::Projected,
    material: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> matrix::RoughnessMatrix {
    return projected::projected_lobe(m, lean_widened(material, moments), fp);
}

/// `Lean<Rect>::lobe`: `lobe::rect_lobe` of the widened axis-aligned lobe.
fn rect_lobe(
    m: lobe::Rect,
    material: axis_aligned::AxisAligned,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> lobe::RectFilteredGgx {
    return lobe::rect_lobe(m, lean_widened_axis_aligned(material, moments), fp);
}

/// `Lean<Proxy>::lobe`: `proxy::proxy_lobe` of the widened axis-aligned lobe.
fn proxy_lobe(
    m: proxy::Proxy,
    material: axis_aligned::AxisAligned,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> axis_aligned::AxisAligned {
    return proxy::proxy_lobe(m, lean_widened_axis_aligned(material, moments), fp);
}
