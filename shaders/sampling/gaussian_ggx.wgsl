#define_import_path filtered_ndf::sampling::gaussian_ggx

#import filtered_ndf::math
#import filtered_ndf::kernel::covariance
#import filtered_ndf::filter::gaussian_ggx as filtered
#import filtered_ndf::sampling

// Importance sampling of the exact Gaussian-filtered GGX lobe (`filter::gaussian_ggx`),
// mirroring `src/.../sampling/gaussian_ggx.rs`: normals with density `D(m) m_z`, exactly, as
// the sum of a GGX slope and an independent kernel slope.

/// Two uniform numbers from one (the Rust `split_bits` of the `f32` build): the high and the low
/// twelve bits of `u` in `[0, 1)`, `((floor(4096 u) + 1/2) / 4096, frac(4096 u))`, both
/// uniform on their grids and independent (every step exact in f32).
fn split_bits(u: f32) -> vec2<f32> {
    let x = u * 4096.0;
    let hi = floor(x);
    return vec2<f32>((hi + 0.5) / 4096.0, x - hi);
}

/// Samples a unit micronormal `m` of the filtered lobe with density `D(m) m_z` per steradian
/// (KHPL16 eq. 2; the Rust `NdfSampling::sample_normal`). Exact: the filtered slope is the sum
/// of two independent slopes (module docs: the convolution), a GGX slope of roughness `A_c`,
/// `B t` with `B` its Cholesky factor (`sampling::warp`) and `|t|^2 = u1 / (1 - u1)` (the
/// inverse radial CDF of unit-roughness GGX, Walter et al. 2007 eq. 35), and a kernel slope
/// `N(0, Sigma)` by Box-Muller along the kernel's principal axes (the eigenvector of the
/// larger eigenvalue from the row without cancellation, as Rust). The four uniform numbers are
/// the high and low halves of the bits of `u.x` (`u1`, `u3`) and `u.y` (`u2`, `u4`), 12 bits
/// each ([`split_bits`]). `u` is clamped to `[0, 1 - 2^-24]`. Always `m_z > 0` (kept at the
/// smallest normal f32 where the slope leaves the f32 range).
fn sample_normal(g: filtered::GaussianFilteredGgx, u: vec2<f32>) -> vec3<f32> {
    let a = split_bits(sampling::clamp_unit(u.x));
    let b = split_bits(sampling::clamp_unit(u.y));
    // The GGX slope B t.
    let t = sqrt(a.x / (1.0 - a.x)) * math::sincos_turns(b.x);
    let l = sampling::warp(g.a);
    let gs = vec2<f32>(l.l_xx * t.x, l.l_yx * t.x + l.l_yy * t.y);
    // The kernel slope: -2 ln(1 - u3) as ln_1p below 1/2 (no cancellation), exact above.
    let e = select(-math::ln(1.0 - a.y), math::ln_1p(a.y / (1.0 - a.y)), a.y < 0.5);
    let y = sqrt(2.0 * e) * math::sincos_turns(b.y);
    let k = g.k;
    let ev = covariance::eigenvalues(k);
    let khalf = 0.5 * (k.s_xx - k.s_yy);
    let krad = math::hypot(khalf, k.s_xy);
    var ax = vec2<f32>(1.0, 0.0);
    if krad > 0.0 {
        let w = select(vec2<f32>(k.s_xy, krad - khalf), vec2<f32>(krad + khalf, k.s_xy), khalf >= 0.0);
        ax = w / math::hypot(w.x, w.y);
    }
    let kk = vec2<f32>(sqrt(ev.y) * y.x, sqrt(ev.x) * y.y);
    let s = gs + vec2<f32>(ax.x * kk.x - ax.y * kk.y, ax.y * kk.x + ax.x * kk.y);
    let n = sampling::normalize_scaled(vec3<f32>(-s, 1.0));
    return vec3<f32>(n.xy, max(n.z, math::F32_MIN_POSITIVE));
}

/// The density of [`sample_normal`], `D(m) m_z` per steradian, for a unit `m`; 0 for
/// `m_z <= 0`.
fn normal_pdf(g: filtered::GaussianFilteredGgx, m: vec3<f32>) -> f32 {
    return select(0.0, filtered::d(g, m) * m.z, m.z > 0.0);
}
