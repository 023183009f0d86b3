#define_import_path filtered_ndf::sampling::beckmann

#import filtered_ndf::math
#import filtered_ndf::ndf::beckmann as beckmann_ndf
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::sampling

// Importance sampling of Beckmann with a roughness matrix, and the pdfs, mirroring
// `src/.../sampling/beckmann.rs` (the inversion of the visible-slope CDF) and the Beckmann
// `NdfSampling` of `src/.../sampling/mod.rs`. Densities per steradian as for GGX
// (`sampling/mod.wgsl`): `D(m) m_z` (KHPL16 eq. 2) and the visible normals
// `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` (Heitz 2014 eq. 16). The same linear warp
// `A_c = L L^T` maps the unit-roughness samples to roughness `A` (`sampling::warp`).
//
// Visible normals (Heitz and d'Eon 2014 section 4; Jakob 2014): in the unit-roughness space
// with the view azimuth rotated to `x`, the view `(sin theta, 0, cos theta)` sees the slopes
// `(x, y)` with density `exp(-x^2 - y^2) (cos theta - x sin theta)+ / (pi cos theta (1 + Lambda))`:
// `y` is a Gaussian of variance `1/2` and `x` has the CDF `C(x) = K(x) / K(mu)`,
// `K(x) = cos theta erfc(-x) / 2 + sin theta exp(-x^2) / (2 sqrt(pi))`, `x <= mu = cot theta`,
// `K(mu) = cos theta (1 + Lambda(theta))` (Heitz 2014 eq. 80). Both quantiles are solved by
// the safeguarded Newton iteration of the Rust crate (Numerical Recipes' `rtsafe` rule) in
// f32, with `K` evaluated as a sum of terms of one sign (below).
//
// Out of domain: `wo_z <= 0` has no visible normal: the samplers return the zero vector (the
// Rust `None`) and the pdfs 0. `u` is clamped to `[0, 1 - 2^-24]`. The slope range is
// `[-X_MAX, min(mu, X_MAX)]` with `X_MAX = 9` (the Rust `f32` bound; the `f64` build's is 26):
// `u = 0` returns `-X_MAX` (the mass beyond, `< 1e-36`, is below the resolution of an f32
// `u`). `wo` need not be normalised; `m` must be a unit vector for the pdfs.

/// The bound of the slope range searched, in units of the unit roughness (the Rust `X_MAX`
/// for `f32`: `exp(-81) ~ 6e-36` stays a normal f32).
const X_MAX: f32 = 9.0;

/// The iteration cap of the solve (never binding: bisection alone shrinks the bracket of
/// width `< 2 X_MAX` to the f32 resolution in about 30 steps; Newton needs a few).
const MAX_ITERATIONS: u32 = 64u;

/// `1 / sqrt(pi)`.
const INV_SQRT_PI: f32 = 0.564189583547756;

/// f32 machine epsilon `2^-23`.
const EPS: f32 = 1.1920929e-7;

/// The scaled complementary error function `erfcx(z) = exp(z^2) erfc(z)` for `z >= 0`, as
/// `t exp(P(t))`, `t = 1 / (1 + z / 2)`, with the degree-9 polynomial `P` of Numerical
/// Recipes' `erfcc` (Press et al. 1992 section 6.2, after Chebyshev; fractional error below
/// `1.2e-7` for every `z >= 0`); `exp` is `math::exp` (3 ulp). Within about 11 ulp
/// relative. Not meant for `z < 0`.
fn erfcx(z: f32) -> f32 {
    let t = 1.0 / (1.0 + 0.5 * z);
    var p = 0.17087277;
    p = p * t - 0.82215223;
    p = p * t + 1.48851587;
    p = p * t - 1.13520398;
    p = p * t + 0.27886807;
    p = p * t - 0.18628806;
    p = p * t + 0.09678418;
    p = p * t + 0.37409196;
    p = p * t + 1.00002368;
    p = p * t - 1.26551223;
    return t * math::exp(p);
}

/// `phi(x) = exp(-x^2) (c erfcx(x) - s / sqrt(pi)) / 2 = c - K(x)` for `x >= 0` (module
/// docs): the upper tail of the visible-slope CDF, `K(hi) - K(x) = phi(x) - phi(hi)` for
/// `0 <= x <= hi`, without the cancellation of `K(hi) - K(x)` in the far upper tail. Its
/// error is `(x^2 + 18)` ulp of the magnitude `exp(-x^2) (c erfcx(x) + s / sqrt(pi)) / 2`.
fn upper_tail(x: f32, c: f32, s: f32) -> f32 {
    return 0.5 * math::exp(-x * x) * (c * erfcx(x) - s * INV_SQRT_PI);
}

/// `(K(x), K'(x))` of the visible-slope CDF (module docs), `K'(x) = exp(-x^2) (c - s x) / sqrt(pi)`,
/// for `(c, s) = (cos theta, sin theta)`. With `erfc(-x) = exp(-x^2) erfcx(-x)` for `x <= 0`
/// and `2 - exp(-x^2) erfcx(x)` above: `K = exp(-x^2) (c erfcx(-x) + s / sqrt(pi)) / 2` (two
/// positive terms) for `x <= 0`, `K = c - upper_tail(x)` above (`K >= c / 2` there: the
/// difference loses at most a factor 2). Relative error within `(x^2 + 36)` ulp
/// (`exp(-x^2)` carries the rounding of `x^2`, `x^2 / 2` ulp; `erfcx` 11).
fn cdf_terms(x: f32, c: f32, s: f32) -> vec2<f32> {
    let e = math::exp(-x * x);
    var k: f32;
    if x <= 0.0 {
        k = 0.5 * e * (c * erfcx(-x) + s * INV_SQRT_PI);
    } else {
        k = c - upper_tail(x, c, s);
    }
    return vec2<f32>(k, INV_SQRT_PI * e * (c - s * x));
}

/// Starting point only: `erf^-1(x)` by Giles 2010 ("Approximating the erfinv function",
/// single-precision version). The solve owns the accuracy; `|x| >= 1` returns 0.
fn erfinv_guess(x: f32) -> f32 {
    let a = (1.0 - x) * (1.0 + x);
    if !(a > 0.0) {
        return 0.0;
    }
    var w = -math::ln(a);
    var p: f32;
    if w < 5.0 {
        w = w - 2.5;
        p = 2.81022636e-08;
        p = p * w + 3.43273939e-07;
        p = p * w - 3.5233877e-06;
        p = p * w - 4.39150654e-06;
        p = p * w + 0.00021858087;
        p = p * w - 0.00125372503;
        p = p * w - 0.00417768164;
        p = p * w + 0.246640727;
        p = p * w + 1.50140941;
    } else {
        w = sqrt(w) - 3.0;
        p = -0.000200214257;
        p = p * w + 0.000100950558;
        p = p * w + 0.00134934322;
        p = p * w - 0.00367342844;
        p = p * w + 0.00573950773;
        p = p * w - 0.0076224613;
        p = p * w + 0.00943887047;
        p = p * w + 1.00167406;
        p = p * w + 2.83297682;
    }
    return p * x;
}

/// Solves `C(x) = u` for `x` in `[-X_MAX, min(mu, X_MAX)]` (the Rust
/// `invert_visible_slope_cdf`), `(c, s) = (cos, sin)` of the unit-roughness view angle
/// (`c, s >= 0`, not both zero), `u` in `[0, 1)`. Newton steps where they stay in the bracket
/// and shrink the residual faster than bisection, bisection otherwise. Below `u = 1/2` the
/// equation is `K(x) = u K(hi)`; above, `K(hi) - K(x) = (1 - u) K(hi)` (`1 - u` exact), with
/// `K(hi) - K(x) = upper_tail(x) - upper_tail(hi)` for `x > 0`, so that the upper tail keeps
/// its relative accuracy in `1 - u` as the lower one does in `u` (as f32 `K` it would carry
/// `eps / (1 - u)`). Returns when the residual is within `4 eps` of the goal, a Newton step
/// is below `2 eps (1 + |x|)`, or the bracket is narrower than `4 eps (1 + |x|)`: the result
/// is the exact quantile of some `u'` with `|u' - u| <= u (2 err_K + 4 eps)` (`err_K` the
/// relative error of `K`, `cdf_terms`) below `1/2`, `|(1 - u') - (1 - u)| <= (1 - u) err_R`
/// above (`err_R` the error of the difference relative to it: the terms' magnitudes over
/// their difference), to within `4 eps (1 + |x|)`.
fn invert_visible_slope_cdf(c: f32, s: f32, u: f32) -> f32 {
    let hi0 = select(X_MAX, min(c / s, X_MAX), s > 0.0);
    var lo = -X_MAX;
    var hi = hi0;
    // The normaliser `K(mu)` by the same formula as `K(x)`: `C(hi) = 1` exactly.
    let norm = cdf_terms(hi0, c, s).x;
    let upper = u > 0.5;
    let goal = select(u, 1.0 - u, upper) * norm;
    if !(goal > 0.0) {
        return lo;
    }
    let tail_hi = upper_tail(max(hi0, 0.0), c, s);
    let tol = 4.0 * EPS * goal;
    let guess = erfinv_guess(2.0 * u - 1.0);
    var x = select(min(0.0, 0.5 * hi), guess, guess > lo && guess < hi);
    var dx_old = hi - lo;
    for (var i = 0u; i < MAX_ITERATIONS; i = i + 1u) {
        let kd = cdf_terms(x, c, s);
        // The residual, increasing in `x`: `K(x) - u K(hi)`, or `(1 - u) K(hi) - (K(hi) - K(x))`.
        var g = kd.x - goal;
        if upper {
            g = goal - select(norm - kd.x, upper_tail(x, c, s) - tail_hi, x > 0.0);
        }
        if abs(g) <= tol {
            return x;
        }
        if g < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        if hi - lo <= 4.0 * EPS * (1.0 + abs(x)) {
            return 0.5 * (lo + hi);
        }
        let step = g / kd.y;
        let xn = x - step;
        if xn > lo && xn < hi && abs(2.0 * g) <= abs(dx_old * kd.y) {
            dx_old = abs(step);
            x = xn;
            if abs(step) <= 2.0 * EPS * (1.0 + abs(x)) {
                return x;
            }
        } else {
            dx_old = 0.5 * (hi - lo);
            x = 0.5 * (lo + hi);
        }
    }
    return x;
}

/// The `x` component of a Beckmann visible slope in the standard configuration (the Rust
/// `visible_slope_quantile`): the quantile `C^-1(u)` of the visible-slope CDF (module docs,
/// Heitz 2014 eq. 80) for a view with `(cos theta, sin theta) = (cos_theta, sin_theta)` in
/// the unit-roughness space (any non-negative pair, normalised here; `(1, 0)` gives the
/// Gaussian of variance `1/2`, `erf^-1(2u - 1)`). `u` is clamped to `[0, 1 - 2^-24]`; the
/// result lies in `[-9, min(cot theta, 9)]` (`u = 0` gives `-9`). Negative or NaN angles are
/// treated as normal incidence. Accuracy: see `invert_visible_slope_cdf`.
fn visible_slope_quantile(cos_theta: f32, sin_theta: f32, u: f32) -> f32 {
    var c = 1.0;
    var s = 0.0;
    if cos_theta >= 0.0 && sin_theta >= 0.0 && cos_theta + sin_theta > 0.0 {
        let r = math::hypot(cos_theta, sin_theta);
        c = cos_theta / r;
        s = sin_theta / r;
    }
    return invert_visible_slope_cdf(c, s, sampling::clamp_unit(u));
}

/// Samples `m` with density `D(m) m_z` per steradian (the NDF itself, KHPL16 eq. 2) of
/// Beckmann with roughness `r`: in the unit-roughness space `|t|^2 = -ln(1 - u1)` (a Gaussian
/// of slopes with covariance `I / 2`), `phi = 2 pi u2`, `n = (-t, 1)` up to the sign of `t`,
/// then warped by `L` (slope covariance `A / 2`, KHPL16 eq. 14). `-ln(1 - u1)` as
/// `ln_1p(u1 / (1 - u1))` below `u1 = 1/2` (no cancellation), `-ln(1 - u1)` (exact
/// argument) above. Always `m_z > 0`.
fn sample_normal(r: matrix::RoughnessMatrix, u: vec2<f32>) -> vec3<f32> {
    let u1 = sampling::clamp_unit(u.x);
    let cs = math::sincos_turns(sampling::clamp_unit(u.y));
    let e = select(-math::ln(1.0 - u1), math::ln_1p(u1 / (1.0 - u1)), u1 < 0.5);
    let n = vec3<f32>(sqrt(e) * cs, 1.0);
    return sampling::unstretch(sampling::warp(r), n);
}

/// Samples a visible micronormal `m` of Beckmann with roughness `r` from `u` in `[0, 1)^2`,
/// with density `D_wo(m)` per steradian (Heitz 2014 eq. 16; Heitz and d'Eon 2014 section 4):
/// the view stretched into the unit-roughness space, its azimuth rotated to `x`, the slope
/// `x` the quantile of the visible-slope CDF of `u1` and `y` the Gaussian quantile of `u2`
/// (`invert_visible_slope_cdf`), rotated back and warped by `L`. The zero vector if
/// `wo_z <= 0` (or the view is grazing to within the f32 range); otherwise a unit `m` with
/// `m_z > 0` and `wo.m > 0` (should rounding break either, the lobe centre
/// `unstretch(wi)` is returned, as in Rust).
fn sample_visible_normal(r: matrix::RoughnessMatrix, wo: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    if !(wo.z > 0.0) {
        return vec3<f32>(0.0);
    }
    let l = sampling::warp(r);
    let wi = sampling::normalize_scaled(sampling::stretch(l, sampling::normalize_scaled(wo)));
    if !(wi.z > 0.0) {
        return vec3<f32>(0.0);
    }
    let s = math::hypot(wi.x, wi.y);
    let phi = select(vec2<f32>(1.0, 0.0), wi.xy / s, s > 0.0);
    let x = invert_visible_slope_cdf(wi.z, s, sampling::clamp_unit(u.x));
    let y = invert_visible_slope_cdf(1.0, 0.0, sampling::clamp_unit(u.y));
    let t = vec2<f32>(phi.x * x - phi.y * y, phi.y * x + phi.x * y);
    let m = sampling::unstretch(l, vec3<f32>(-t, 1.0));
    if m.z > 0.0 && dot(wo, m) > 0.0 {
        return m;
    }
    let c = sampling::unstretch(l, wi);
    return select(vec3<f32>(0.0), c, c.z > 0.0);
}

/// The density of [`sample_normal`], `D(m) m_z` per steradian, for a unit `m`; 0 for
/// `m_z <= 0`.
fn normal_pdf(r: matrix::RoughnessMatrix, m: vec3<f32>) -> f32 {
    return select(0.0, beckmann_ndf::d_matrix(r, m) * m.z, m.z > 0.0);
}

/// The visible-normal density `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` per steradian
/// (Heitz 2014 eq. 16) of Beckmann for a unit `m`; 0 for `wo_z <= 0`, `wo.m <= 0`,
/// `m_z <= 0`.
fn visible_normal_pdf(r: matrix::RoughnessMatrix, wo: vec3<f32>, m: vec3<f32>) -> f32 {
    let d = beckmann_ndf::d_matrix(r, m);
    return sampling::visible_normal_pdf_of(wo, m, d, beckmann_ndf::lambda_matrix(r, wo));
}

/// The density per steradian of `wi = reflect(wo, m)` for the unit half vector `m` itself:
/// `G1(wo) D(m) / (4 wo_z)` (Walter et al. 2007 eq. 14, `wo` normalised here); 0 for
/// `wo_z <= 0`, `wo.m <= 0`, `m_z <= 0`.
fn reflection_pdf_from_normal(r: matrix::RoughnessMatrix, wo: vec3<f32>, m: vec3<f32>) -> f32 {
    let o = sampling::normalize_scaled(wo);
    let d = beckmann_ndf::d_matrix(r, m);
    return sampling::reflection_pdf_of(o, m, d, beckmann_ndf::lambda_matrix(r, o));
}
