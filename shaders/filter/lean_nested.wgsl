#define_import_path filtered_ndf::filter::lean_nested

#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance as cov
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::filter::lean
#import filtered_ndf::filter::method

// LEAN moments nested into every method of the front door (KHPL16 section 5.5, eq. 21),
// mirroring `src/.../filter/lean_nested.rs` (`Lean<M>`): the material is widened by the LEAN
// kernel, `A_L = A + 2 Sigma_L` (`lean_widened`), then each method filters the widened lobe
// over the pixel footprint as it filters a material. The clamp rules act on the pixel kernel
// only. `moments` come from the baked chain (`bake::moments::sample_grad`).
//
// | method (`filter::method`) | nested lobe function | evaluate with |
// |---|---|---|
// | `Gaussian` | `gaussian_lobe` | `ggx::*_matrix`, `beckmann::*_matrix` |
// | `ExactGaussian` | `exact_gaussian_lobe` (GGX: one kernel `Sigma_L + K_P`, exact); Beckmann: `gaussian_lobe` | `gaussian_ggx::*` |
// | `Projected` | `projected_lobe` | `ggx::*_matrix` |
// | `Rect` | `rect_lobe` (the widened diagonal, `lean_widened_axis_aligned`) | `method::*_rect_filtered` |
// | `Proxy` | `proxy_lobe` (likewise) | `ggx::*_axis_aligned` |

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

/// `Lean<Gaussian>::lobe`: `method::gaussian_lobe` of the widened material.
fn gaussian_lobe(
    m: method::Gaussian,
    material: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> matrix::RoughnessMatrix {
    return method::gaussian_lobe(m, lean_widened(material, moments), fp);
}

/// `Lean<ExactGaussian>::lobe` for GGX: the exact Gaussian-filtered GGX of the material over
/// one kernel, the method's clamped pixel kernel plus `Sigma_L` (both Gaussians, so they add).
fn exact_gaussian_lobe(
    m: method::ExactGaussian,
    material: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> gaussian_ggx::GaussianFilteredGgx {
    let k = cov::add(clamp::pixel_kernel(m.clamps, fp, m.sigma), lean::covariance(moments));
    return gaussian_ggx::from_kernel(material, k);
}

/// `Lean<Projected>::lobe`: `method::projected_lobe` of the widened material.
fn projected_lobe(
    m: method::Projected,
    material: matrix::RoughnessMatrix,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> matrix::RoughnessMatrix {
    return method::projected_lobe(m, lean_widened(material, moments), fp);
}

/// `Lean<Rect>::lobe`: `method::rect_lobe` of the widened axis-aligned lobe.
fn rect_lobe(
    m: method::Rect,
    material: axis_aligned::AxisAligned,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> method::RectFilteredGgx {
    return method::rect_lobe(m, lean_widened_axis_aligned(material, moments), fp);
}

/// `Lean<Proxy>::lobe`: `method::proxy_lobe` of the widened axis-aligned lobe.
fn proxy_lobe(
    m: method::Proxy,
    material: axis_aligned::AxisAligned,
    fp: pixel::Footprint,
    moments: lean::LeanMoments,
) -> axis_aligned::AxisAligned {
    return method::proxy_lobe(m, lean_widened_axis_aligned(material, moments), fp);
}
