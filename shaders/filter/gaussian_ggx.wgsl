#define_import_path filtered_ndf::filter::gaussian_ggx

#import filtered_ndf::math
#import filtered_ndf::ndf
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::beckmann
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian_ggx_quad as quad

// The exact Gaussian-filtered GGX (`src/.../filter/gaussian_ggx.rs`, `GaussianFilteredGgx`):
// the convolution of a GGX slope density of roughness `A` with a Gaussian kernel
// `N(0, Sigma)`, with its own Smith `Lambda`, in f32. What TK19 section 2.2 and TK21
// approximate by a GGX of roughness `A + 2 Sigma`, and KHPL16 (section 5.2) replaces by a box.
//
// The mixture identity (Rust module docs): GGX is a scale mixture of Gaussians,
// `P22(s) = integral e^-w N(s; 0, A / (2w)) dw`, and convolving each component adds the
// kernel, so `P22_Sigma(s) = J / (pi sqrt(det A))` with
// `J = integral w e^-w exp(-E(w)) / sqrt(p1 p2) dw`, `p_i = 1 + 2 l_i w`,
// `E(w) = w (c1^2 / p1 + c2^2 / p2)`, where `(l1, l2)` are the eigenvalues of the kernel in
// units of the lobe, `B^-1 Sigma B^-T` (`A = B B^T`), and `c` the slope whitened by `B` and
// rotated into that eigenbasis. `J` by the rules of `gaussian_ggx_quad.wgsl`. `Lambda` is the
// filtered distribution's own: a Gaussian average of GGX's `Lambda` (Rust item 6).
//
// The build in f32 (the Rust crate builds in f64): in the eigenbasis of `A_c` (the matrix the
// material's density evaluates, `matrix.wgsl`), `B = R diag(sqrt l)`, so `B^-1 Sigma B^-T` has
// the entries `k_ij / sqrt(l_i l_j)` of the kernel rotated into that basis (`k_ij = e_i^T
// Sigma e_j`), its determinant is `det Sigma / det A_c` (the kernel's carried determinant: the
// minor eigenvalue `l2 = det / l1` keeps its relative accuracy), `l1` is a sum of non-negative
// terms, and its eigenvector comes from the row without cancellation. Whitening a slope is then
// `matrix::rotate`, a scaling, and one more rotation.
//
// Accuracy (stated bound; `gpu/src/checks/gaussian_ggx.rs` derives the per-case tolerance):
// the rules' own `1.8e-6` (`J`) and `3e-7` (`Lambda`), plus the f32 rounding of the set-up
// (a few ulp of each `c_i^2` and `2 l_i`, and of the kernel's eigenvector, an angle of a few
// ulp), which `P22_Sigma` amplifies by its condition numbers: `d ln J / d ln c_i^2 = -<E_i>`
// (the mean exponent over the integrand, `<= 2` for the unfiltered lobe, `~ln(2 l1)` where
// the kernel dominates), `|d ln J / d ln l_i| <= <E_i> + 1/2`, and the sensitivity to the
// kernel's orientation. NaN: not tested for (WGSL); `d` and `p22` return 0 where the density
// leaves the f32 range.

/// The exact Gaussian-filtered GGX lobe, built once per shading point by [`from_kernel`] (the Rust `new`; `new` is a reserved word in WGSL).
struct GaussianFilteredGgx {
    /// The material's roughness (its `A_c` is the lobe `A`): its eigenbasis whitens slopes.
    a: matrix::RoughnessMatrix,
    /// `1 / sqrt(l)` of `A_c`'s eigenvalues `l`.
    inv_sqrt_l: vec2<f32>,
    /// The unit eigenvector `v` of the kernel in units of the lobe (of `l1`), in `A_c`'s
    /// eigenbasis: `c = (v . u, v_perp . u)`, `u` the whitened slope.
    v: vec2<f32>,
    /// `(2 l1, 2 l2)`, `l1 >= l2 >= 0`.
    tl: vec2<f32>,
    /// `1 / (pi sqrt(det A_c))`.
    norm: f32,
    /// The sanitised kernel (for `Lambda`'s `o^T Sigma o`).
    k: covariance::Covariance,
    /// The accuracy setting of `p22` and `d` (the Rust `Tolerance`): one of the `TOL_*`
    /// constants.
    tol: u32,
}

/// The accuracy settings of the density (the Rust `Tolerance`; bounds in its module docs,
/// "Tolerance settings"): the full rules (relative error `1.8e-6`, the default), then `1e-4`,
/// `1e-3` and `1e-2`. Out-of-range values act as `TOL_1E2`.
const TOL_FULL: u32 = quad::TOL_FULL;
const TOL_1E4: u32 = quad::TOL_1E4;
const TOL_1E3: u32 = quad::TOL_1E3;
const TOL_1E2: u32 = quad::TOL_1E2;

/// The lobe `g` with its density at the accuracy setting `tol` (the Rust
/// `GaussianFilteredGgx::with_tolerance`); `Lambda` and the samplers are unchanged.
fn with_tolerance(g: GaussianFilteredGgx, tol: u32) -> GaussianFilteredGgx {
    var out = g;
    out.tol = tol;
    return out;
}

/// The lobe of GGX roughness `a` (evaluated as its `A_c`) filtered by the kernel `kernel`
/// (slope^2; `covariance::sanitized` first), the Rust `GaussianFilteredGgx::new`.
fn from_kernel(a: matrix::RoughnessMatrix, kernel: covariance::Covariance) -> GaussianFilteredGgx {
    let k = covariance::sanitized(kernel);
    let c = a.axis.x;
    let s = a.axis.y;
    // The kernel in A_c's eigenbasis.
    let k11 = max(c * c * k.s_xx + 2.0 * c * s * k.s_xy + s * s * k.s_yy, 0.0);
    let k22 = max(s * s * k.s_xx - 2.0 * c * s * k.s_xy + c * c * k.s_yy, 0.0);
    let k12 = (c * c - s * s) * k.s_xy + c * s * (k.s_yy - k.s_xx);
    let l = a.eig_c;
    let isl = 1.0 / sqrt(l);
    // C = diag(l)^-1/2 K diag(l)^-1/2, det C = det Sigma / det A_c.
    let c11 = k11 * isl.x * isl.x;
    let c22 = k22 * isl.y * isl.y;
    let c12 = k12 * isl.x * isl.y;
    let det_c = max(k.det, 0.0) / (l.x * l.y);
    let half = 0.5 * (c11 - c22);
    let rad = math::hypot(half, c12);
    let l1 = 0.5 * (c11 + c22) + rad;
    var l2 = 0.0;
    var v = vec2<f32>(1.0, 0.0);
    if rad > 0.0 {
        let big = rad + abs(half);
        let w = select(vec2<f32>(c12, big), vec2<f32>(big, c12), half >= 0.0);
        v = w / length(w);
        l2 = min(det_c / l1, l1);
    } else if l1 > 0.0 {
        l2 = l1;
    }
    return GaussianFilteredGgx(a, isl, v, vec2<f32>(2.0 * l1, 2.0 * l2), math::INV_PI / matrix::sqrt_det(a), k, TOL_FULL);
}

/// `(c1^2, c2^2)` of a tangent-plane vector `s` (a slope, or `m_xy` of a normal).
fn whiten(g: GaussianFilteredGgx, s: vec2<f32>) -> vec2<f32> {
    let u = matrix::rotate(g.a, s) * g.inv_sqrt_l;
    let c = vec2<f32>(g.v.x * u.x + g.v.y * u.y, g.v.x * u.y - g.v.y * u.x);
    return c * c;
}

/// `P22_Sigma(s) = J / (pi sqrt(det A))` per unit slope area (the Rust `p22`); 0 where it
/// underflows.
fn p22(g: GaussianFilteredGgx, s: vec2<f32>) -> f32 {
    let c = whiten(g, s);
    return g.norm * quad::j_tol(c.x, c.y, 1.0, g.tl.x, g.tl.y, g.tol);
}

/// `D(m) = P22_Sigma(s(m)) / m_z^4` per steradian for a unit micronormal (the Rust `d`): `0`
/// for `m_z <= 0` and where the density leaves the f32 range; every rule homogeneous in `m`
/// (finite up to the horizon).
fn d(g: GaussianFilteredGgx, m: vec3<f32>) -> f32 {
    if !(m.z > 0.0) {
        return 0.0;
    }
    let c = whiten(g, m.xy);
    let v = g.norm * quad::j_tol(c.x, c.y, m.z * m.z, g.tl.x, g.tl.y, g.tol);
    return select(0.0, v, v <= math::F32_MAX);
}

/// The filtered lobe's own Smith `Lambda(w)` (the Rust `lambda`): the mixture of the Beckmann
/// `Lambda`s of roughness `A / w + 2 Sigma` over `e^-w dw`, as `E[h(o_z - Z)] / (2 o_z)`,
/// `Z ~ N(0, o^T Sigma o)`, `h(y) = sqrt(o^T A o + y^2) - y` (`quad::lambda`); GGX's own where
/// the view does not see the kernel. Uses `|w_z|`, homogeneous in `w` (normalised here after
/// scaling by the largest component). `F32_MAX` at grazing, `0` at normal incidence.
fn lambda(g: GaussianFilteredGgx, w: vec3<f32>) -> f32 {
    let big = max(max(abs(w.x), abs(w.y)), abs(w.z));
    if !(big > 0.0) {
        return select(math::F32_MAX, 0.0, big == 0.0);
    }
    let ws = w / big;
    let o = ws / length(ws);
    let oz = abs(o.z);
    let qa = matrix::quadratic(g.a, o.xy);
    let kk = g.k;
    let qs = max(kk.s_xx * o.x * o.x + 2.0 * kk.s_xy * o.x * o.y + kk.s_yy * o.y * o.y, 0.0);
    if qs <= 0.0 {
        return ggx::lambda_of(qa, oz);
    }
    if oz <= 0.0 {
        return math::F32_MAX;
    }
    if qa <= 0.0 {
        return beckmann::lambda_of(2.0 * qs, oz);
    }
    return quad::lambda(qa, qs, oz);
}

/// Smith masking `G1(w, m) = chi+(w.m) / (1 + Lambda(w))` of the filtered lobe.
fn g1(g: GaussianFilteredGgx, w: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g1_of(lambda(g, w), dot(w, m));
}

/// Height-correlated `G2(i, o, m) = chi+(i.m) chi+(o.m) / (1 + Lambda(i) + Lambda(o))` of the
/// filtered lobe.
fn g2(g: GaussianFilteredGgx, i: vec3<f32>, o: vec3<f32>, m: vec3<f32>) -> f32 {
    return ndf::g2_of(lambda(g, i), lambda(g, o), dot(i, m), dot(o, m));
}

/// The exact Gaussian filter: the material's slope density convolved with the clamped pixel
/// kernel (GGX: `GaussianFilteredGgx`; Beckmann: `A + 2 Sigma`, `gaussian::gaussian_lobe` with the
/// same rules).
struct ExactGaussian {
    /// The clamp rules applied to the footprint and the kernel.
    clamps: clamp::ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    sigma: f32,
    /// The accuracy setting of the GGX lobe's density (`TOL_*`, the Rust `Tolerance`).
    tolerance: u32,
}

/// The unbiased filter of the footprint: `lambda = 1` (KHPL16 section 5.2), no `kappa`,
/// `sigma = 0.5`, the full accuracy.
const KHPL16_EXACT_GAUSSIAN: ExactGaussian = ExactGaussian(clamp::KHPL16_RULES, pixel::SIGMA_PIXEL, TOL_FULL);

/// The GGX lobe of the exact Gaussian filter (the Rust `ExactGaussian::lobe` for GGX).
fn exact_gaussian_lobe(method: ExactGaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint) -> GaussianFilteredGgx {
    return with_tolerance(from_kernel(material, clamp::pixel_kernel(method.clamps, fp, method.sigma)), method.tolerance);
}

/// `D(m)` of [`exact_gaussian_lobe`].
fn d_ggx_exact_gaussian(method: ExactGaussian, material: matrix::RoughnessMatrix, fp: pixel::Footprint, m: vec3<f32>) -> f32 {
    return d(exact_gaussian_lobe(method, material, fp), m);
}
