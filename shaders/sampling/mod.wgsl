#define_import_path filtered_ndf::sampling

#import filtered_ndf::math
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::roughness::matrix

// Importance sampling of GGX with a roughness matrix, and the pdfs for multiple importance
// sampling, mirroring `src/.../sampling/mod.rs` (GGX, `NdfSampling`). Densities per
// steradian: `D(m) m_z` (KHPL16 eq. 2) and the visible normals
// `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` (Heitz 2014 eq. 16); the reflected direction
// `wi = reflect(wo, m)` has `D_wo(m) / (4 wo.m)` (Walter et al. 2007 eq. 14).
//
// One linear warp for every roughness: with `A = L L^T` (lower Cholesky factor), slopes
// `s = L t` map the unit-roughness NDF of `t` to the NDF of `A`; the visible normals of `A`
// seen from `wo` are the image of the unit-roughness visible normals seen from
// `normalize(L^T wo_xy, wo_z)` (Heitz and d'Eon 2014 section 4; the same algebra for any
// `L`). The unit-roughness GGX sampler is the spherical caps of Dupuy and Benyoub 2023
// (listing 3). The angle `2 pi u` goes through `math::sincos_turns` (WGSL allows the driver
// `sin`/`cos` an absolute `2^-11`).
//
// Out of domain: `wo_z <= 0` has no visible normal: the samplers return the zero vector
// (the Rust `None`) and the pdfs 0. `u` is clamped to `[0, 1 - 2^-24]`. `wo` need not be
// normalised; `m` must be a unit vector for the pdfs.

/// The largest f32 below 1: the upper clamp of the uniform numbers.
const ONE_MINUS_EPS: f32 = 0.99999994;

/// The lower Cholesky factor `L = [[l_xx, 0], [l_yx, l_yy]]` of a roughness, `A = L L^T`.
struct Warp {
    /// `sqrt(a11)`.
    l_xx: f32,
    /// `a12 / sqrt(a11)`.
    l_yx: f32,
    /// `sqrt(det A) / sqrt(a11)`.
    l_yy: f32,
}

/// The warp of a roughness matrix: the Cholesky factor of the clamped matrix `A_c` that the
/// density evaluates (`matrix.wgsl`; entries from its eigenbasis, `sqrt(det A_c)` as stored),
/// so that the sampled lobe is the one `D` describes.
fn warp(r: matrix::RoughnessMatrix) -> Warp {
    let e = matrix::clamped_entries(r);
    let l_xx = sqrt(e.x);
    return Warp(l_xx, e.y / l_xx, r.sqrt_det / l_xx);
}

/// `v / |v|` after scaling by the largest component (no overflow or underflow of the
/// squares). `v` non-zero.
fn normalize_scaled(v: vec3<f32>) -> vec3<f32> {
    let w = v / max(max(abs(v.x), abs(v.y)), abs(v.z));
    return w / length(w);
}

/// `(L^T w_xy, w_z)`: a view direction into the unit-roughness space (unnormalised).
fn stretch(l: Warp, w: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(l.l_xx * w.x + l.l_yx * w.y, l.l_yy * w.y, w.z);
}

/// `normalize(L n_xy, n_z)`: a unit-roughness normal back to roughness `A`.
fn unstretch(l: Warp, n: vec3<f32>) -> vec3<f32> {
    return normalize_scaled(vec3<f32>(l.l_xx * n.x, l.l_yx * n.x + l.l_yy * n.y, n.z));
}

/// A uniform number clamped into `[0, 1 - 2^-24]` (negative values to 0).
fn clamp_unit(u: f32) -> f32 {
    return select(0.0, min(u, ONE_MINUS_EPS), u >= 0.0);
}

/// Mirror reflection of `wo` about the unit normal `m`: `2 (wo.m) m - wo` (Walter et al.
/// 2007 eq. 13).
fn reflect(wo: vec3<f32>, m: vec3<f32>) -> vec3<f32> {
    return 2.0 * dot(wo, m) * m - wo;
}

/// Unit-roughness GGX visible normal by spherical caps (Dupuy and Benyoub 2023): a uniform
/// point `c` on the cap `z >= -wi_z` of the unit sphere, returned as `c + wi` (unnormalised).
fn ggx_standard_visible(wi: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    let cs = math::sincos_turns(u.x);
    let z = (1.0 - u.y) * (1.0 + wi.z) - wi.z;
    let sin_theta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    return vec3<f32>(sin_theta * cs, z) + wi;
}

/// Samples a visible micronormal `m` of GGX with roughness `r` from `u` in `[0, 1)^2`, with
/// density `D_wo(m)` per steradian (Heitz 2014 eq. 16). The zero vector if `wo_z <= 0` (or
/// the view is grazing to within the f32 range); otherwise a unit `m` with `m_z > 0` and
/// `wo.m > 0` (should rounding break either, the lobe centre `unstretch(wi)` is returned,
/// as in Rust).
fn sample_visible_normal(r: matrix::RoughnessMatrix, wo: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    if !(wo.z > 0.0) {
        return vec3<f32>(0.0);
    }
    let l = warp(r);
    let wi = normalize_scaled(stretch(l, normalize_scaled(wo)));
    if !(wi.z > 0.0) {
        return vec3<f32>(0.0);
    }
    let n = ggx_standard_visible(wi, vec2<f32>(clamp_unit(u.x), clamp_unit(u.y)));
    let m = unstretch(l, n);
    if m.z > 0.0 && dot(wo, m) > 0.0 {
        return m;
    }
    let c = unstretch(l, wi);
    return select(vec3<f32>(0.0), c, c.z > 0.0);
}

/// Samples `m` with density `D(m) m_z` per steradian (the NDF itself): in the unit-roughness
/// space `|t|^2 = u1 / (1 - u1)`, `n = (sqrt(u1) cos phi, sqrt(u1) sin phi, sqrt(1 - u1))`,
/// `phi = 2 pi u2`, then warped by `L`. Always `m_z > 0`.
fn sample_normal(r: matrix::RoughnessMatrix, u: vec2<f32>) -> vec3<f32> {
    let u1 = clamp_unit(u.x);
    let cs = math::sincos_turns(clamp_unit(u.y));
    let n = vec3<f32>(sqrt(u1) * cs, sqrt(1.0 - u1));
    return unstretch(warp(r), n);
}

/// The density of [`sample_normal`], `D(m) m_z` per steradian, for a unit `m`; 0 for
/// `m_z <= 0`.
fn normal_pdf(r: matrix::RoughnessMatrix, m: vec3<f32>) -> f32 {
    return select(0.0, ggx::d_matrix(r, m) * m.z, m.z > 0.0);
}

/// The visible-normal density `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` per steradian
/// (Heitz 2014 eq. 16) for a unit `m`; 0 for `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0`.
fn visible_normal_pdf(r: matrix::RoughnessMatrix, wo: vec3<f32>, m: vec3<f32>) -> f32 {
    return visible_normal_pdf_of(wo, m, ggx::d_matrix(r, m), ggx::lambda_matrix(r, wo));
}

/// [`visible_normal_pdf`] from `D(m)` and `Lambda(wo)` of any NDF (GGX here, Beckmann in
/// `sampling::beckmann`): `(wo.m) D / (wo_z (1 + Lambda))`; 0 for `wo_z <= 0`, `wo.m <= 0`
/// and where the quotient is not finite.
fn visible_normal_pdf_of(wo: vec3<f32>, m: vec3<f32>, d: f32, lambda: f32) -> f32 {
    let wom = dot(wo, m);
    let v = wom * d / (wo.z * (1.0 + lambda));
    return select(0.0, v, wo.z > 0.0 && wom > 0.0 && v <= math::F32_MAX);
}

/// The density per steradian of `wi = reflect(wo, m)` for the unit half vector `m` itself:
/// `G1(wo) D(m) / (4 wo_z)` (Walter et al. 2007 eq. 14, `wo` normalised here); 0 for
/// `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0`.
fn reflection_pdf_from_normal(r: matrix::RoughnessMatrix, wo: vec3<f32>, m: vec3<f32>) -> f32 {
    let o = normalize_scaled(wo);
    return reflection_pdf_of(o, m, ggx::d_matrix(r, m), ggx::lambda_matrix(r, o));
}

/// [`reflection_pdf_from_normal`] from the normalised `o = normalize_scaled(wo)`, `D(m)` and
/// `Lambda(o)` of any NDF: `D / (4 o_z (1 + Lambda))`; 0 for `o_z <= 0` (`wo_z <= 0`, or a
/// `wo_z` that vanishes against `wo_xy`), `o.m <= 0` and where the quotient is not finite.
fn reflection_pdf_of(o: vec3<f32>, m: vec3<f32>, d: f32, lambda: f32) -> f32 {
    let v = d / (4.0 * o.z * (1.0 + lambda));
    return select(0.0, v, o.z > 0.0 && dot(o, m) > 0.0 && v <= math::F32_MAX);
}

/// The density per steradian of `wi` when `m` is drawn by [`sample_visible_normal`] and
/// `wi = reflect(wo, m)`: [`reflection_pdf_from_normal`] with `m = normalize(wo + wi)`
/// (both normalised first). 0 for `wo_z <= 0` and for `wi = -wo`. The recomputed half vector
/// carries a direction error of about `eps / (2 wo.m)`: for a sampled direction prefer
/// [`reflection_pdf_from_normal`] with the sampled `m`.
fn reflection_pdf(r: matrix::RoughnessMatrix, wo: vec3<f32>, wi: vec3<f32>) -> f32 {
    if !(wo.z > 0.0) {
        return 0.0;
    }
    let h = normalize_scaled(wo) + normalize_scaled(wi);
    let len = length(h);
    if !(len > 0.0) {
        return 0.0;
    }
    return reflection_pdf_from_normal(r, wo, h / len);
}
