#define_import_path filtered_ndf::filter::rect::lambda

#import filtered_ndf::math
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::filter::rect as boxed

// Smith `Lambda` of the box-filtered GGX (`src/.../filter/rect/lambda.rs`): the masking
// function of the slope distribution that `rect::p22_rect` and `rect::d_rect` describe, so
// that `d`, `g1 = 1 / (1 + Lambda)` and `g2` of the box lobe are one distribution.
//
// With `u` the unit azimuth of `w_xy`, `mu = |w_z| / |w_xy|` and everything in units of the
// projected roughness `a = sqrt(u^T A u)`: `Lambda = E[psi(m - V_1 - V_2)] / m`, `m = mu / a`,
// `V_i` uniform on `[-k_i, k_i]` (`k_i = |u_i| H_i / a`, the box projected on `u`), and
// `psi(t) = (sqrt(1 + t^2) - t) / 2` (GGX's 1D marginal: `E[(X - t)+]`). The expectation is
// taken by the Rust tiers (the Gauss-Legendre tiers of `rect`, with `psi`'s branch points at
// `+-i`): both sides short, the tensor rule of `psi`; a long side, the rule in the short side
// of the exact mean of `psi` over the long one (`Psi_1` differences without cancellation,
// [`psi1_diff`]); otherwise differences of the antiderivatives `Psi_1`, `Psi_2`, which lose
// at most about `ln(2 m) / 0.5` (the outer difference) times 4 (the inner one), i.e. up to
// `~80` ulp at `m = 1e4`.
//
// f32 form: `sqrt(1 + t^2)` scaled for `|t| > 1` (no overflow), `asinh` by the
// driver-independent `math::ln` / `math::ln_1p`, normalised half extents clamped to `1e12`
// (the Rust crate clamps at `1e60`; `Psi_2`'s cube stays finite below `4e12`: only boxes
// wider than `1e12` lobe widths, beyond every clamp rule, differ), and `m > 1e18` answers the
// box-free `1 / (4 m^2)` (the box's correction `(k / m)^2 <= 1e-12`).
//
// Conditioning (as in Rust): where the box's far edge meets `mu` (`|m - k_l| ~ 1`), `Lambda`'s
// relative sensitivity to `m - k_l` is about `m / 5`. The Rust crate forms `m - k_l` with a
// fused multiply-add; WGSL's `fma` may be evaluated unfused, so here `|w_z| - |w_l| H_l` is
// formed in f32 (its product rounded once): the result carries `Lambda`'s condition number
// with respect to its inputs times a few ulp (`gpu/src/checks/rect.rs` computes it per case).

/// Normalised half extents are clamped to this (module docs).
const BIG_K: f32 = 1e12;

/// `sqrt(1 + t^2)` without overflow.
fn rho(t: f32) -> f32 {
    let a = abs(t);
    if a > 1.0 {
        let i = 1.0 / a;
        return a * sqrt(1.0 + i * i);
    }
    return sqrt(1.0 + t * t);
}

/// `e^(-asinh t) = sqrt(1 + t^2) - t` without cancellation, given `r = sqrt(1 + t^2)`.
fn e_neg(t: f32, r: f32) -> f32 {
    return select(r - t, 1.0 / (r + t), t >= 0.0);
}

/// `asinh(t)` given `r = sqrt(1 + t^2)`: `ln(|t| + r)` above 1, `ln_1p(|t| + t^2 / (1 + r))`
/// below (no cancellation), odd.
fn asinh_of(t: f32, r: f32) -> f32 {
    let a = abs(t);
    var v: f32;
    if a > 1.0 {
        v = math::ln(a + r);
    } else {
        v = math::ln_1p(a + a * a / (1.0 + r));
    }
    return select(v, -v, t < 0.0);
}

/// `psi(t) = (sqrt(1 + t^2) - t) / 2`.
fn psi(t: f32) -> f32 {
    return 0.5 * e_neg(t, rho(t));
}

/// `Psi_1(t) = (asinh t - E^2 / 2) / 4`, an antiderivative of `psi` (`E = e^(-asinh t)`).
fn psi1(t: f32) -> f32 {
    let r = rho(t);
    let e = e_neg(t, r);
    return 0.25 * (asinh_of(t, r) - 0.5 * e * e);
}

/// `Psi_2(t) = (t asinh t - rho + E / 4 + E^3 / 12) / 4`, an antiderivative of `Psi_1`.
fn psi2(t: f32) -> f32 {
    let r = rho(t);
    let e = e_neg(t, r);
    return 0.25 * (t * asinh_of(t, r) - r + 0.25 * e + e * e * e * (1.0 / 12.0));
}

/// `Psi_1(t1) - Psi_1(t0)` for `w = t1 - t0 >= 0` given exactly:
/// `(ln_1p(d / E_1) + d (E_0 + E_1) / 2) / 4`, `d = E_0 - E_1 = w (E_0 + E_1) / (rho_0 + rho_1)`;
/// all terms `>= 0`.
fn psi1_diff(t0: f32, t1: f32, w: f32) -> f32 {
    let r0 = rho(t0);
    let r1 = rho(t1);
    let e0 = e_neg(t0, r0);
    let e1 = e_neg(t1, r1);
    let s = e0 + e1;
    let d = w * s / (r0 + r1);
    return 0.25 * (math::ln_1p(d / e1) + 0.5 * d * s);
}

/// The mean of `psi` over `[t0, t1]`, `w = t1 - t0 > 0` given exactly.
fn mean_psi(t0: f32, t1: f32, w: f32) -> f32 {
    return psi1_diff(t0, t1, w) / w;
}

/// The Gauss-Legendre rule of a tier (`rect`'s `tier`; the closed tier takes the 6-point
/// rule, as the Rust `rule`).
fn rule(t: u32) -> u32 {
    return select(t, 6u, t == boxed::TIER_CLOSED);
}

/// `A(t)`: the mean of `Psi_1` over `[t - k, t + k]`, by Gauss-Legendre while `k` is short
/// next to `sqrt(1 + t^2)`, else the closed difference of `Psi_2`.
fn mean_psi1(t: f32, k: f32) -> f32 {
    if k == 0.0 {
        return psi1(t);
    }
    let tt = boxed::tier(k * k, 1.0 + t * t);
    if tt == boxed::TIER_CLOSED {
        return (psi2(t + k) - psi2(t - k)) / (2.0 * k);
    }
    var acc = 0.0;
    for (var j = 0u; j < tt / 2u; j++) {
        let a = k * boxed::gl_node(tt, j);
        acc += boxed::gl_weight(tt, j) * (psi1(t - a) + psi1(t + a));
    }
    return acc;
}

/// The mean of `psi` over `[c - h, c + h]` by the rule of tier `t`.
fn gl_psi(t: u32, c: f32, h: f32) -> f32 {
    let n = rule(t);
    var acc = 0.0;
    for (var j = 0u; j < n / 2u; j++) {
        let a = h * boxed::gl_node(n, j);
        acc += boxed::gl_weight(n, j) * (psi(c - a) + psi(c + a));
    }
    return acc;
}

/// `E[psi(m - V_1 - V_2)]` for `m >= 0`, `V_i` uniform on `[-k_i, k_i]`, `k_i >= 0` finite and
/// not both zero (the Rust `expected_psi`, its three cases). `lo` is `m - max(k_1, k_2)`, formed
/// by the caller from the inputs (module docs, conditioning).
fn expected_psi(m: f32, k1: f32, k2: f32, lo: f32) -> f32 {
    let ks = min(k1, k2);
    let kl = max(k1, k2);
    let near_l = max(m - ks, 0.0);
    let tl = boxed::tier(kl * kl, 1.0 + near_l * near_l);
    if tl != boxed::TIER_CLOSED {
        // Case 1: both short, the tensor rule.
        let near_s = max(m - kl, 0.0);
        let ts = boxed::tier(ks * ks, 1.0 + near_s * near_s);
        var acc = 0.0;
        for (var j = 0u; j < tl / 2u; j++) {
            let a = kl * boxed::gl_node(tl, j);
            acc += boxed::gl_weight(tl, j) * (gl_psi(ts, m - a, ks) + gl_psi(ts, m + a, ks));
        }
        return acc;
    }
    let hi = m + kl;
    let w = 2.0 * kl;
    if ks == 0.0 {
        return mean_psi(lo, hi, w);
    }
    let ts = boxed::tier(ks * ks, 1.0 + lo * lo);
    if ts != boxed::TIER_CLOSED {
        // Case 2: the rule in the short side of the exact mean over the long one.
        var acc = 0.0;
        for (var j = 0u; j < ts / 2u; j++) {
            let x = ks * boxed::gl_node(ts, j);
            acc += boxed::gl_weight(ts, j) * (mean_psi(lo + x, hi + x, w) + mean_psi(lo - x, hi - x, w));
        }
        return acc;
    }
    // Case 3.
    return (mean_psi1(hi, ks) - mean_psi1(lo, ks)) / w;
}

/// Exact Smith `Lambda` of the box-filtered GGX (the Rust `lambda_rect`): the masking function
/// of the slope distribution `rect::p22_rect` averages (`Lambda(w) = (1 / mu) E[(q - mu)+]`
/// over `s = g + delta`, `g` GGX of roughness `r`, `delta` uniform on
/// `[-half_extent, half_extent]`), so that `g1 = 1 / (1 + Lambda)` and `rect::d_rect` satisfy
/// the Smith normalisation `integral of G1(w, m) max(0, w.m) D(m) dm = w_z`.
///
/// Uses `|w_z|`; homogeneous of degree 0 in `w` (scaled by a power of two when its largest
/// component leaves `[2^-60, 2^60]`). Half extents by magnitude; zero half extents (or a box
/// that projects to a point on `u`): GGX's `lambda_axis_aligned`. `F32_MAX` (the Rust `+inf`)
/// for a grazing `w` (`w_z = 0`) and, where the driver keeps NaN, for NaN input; `0` at normal
/// incidence and for the zero vector.
fn lambda_rect(r: axis_aligned::AxisAligned, half_extent: vec2<f32>, w_in: vec3<f32>) -> f32 {
    // Exact power-of-two scaling: |w_i| H_i neither overflows nor underflows.
    let big = max(max(abs(w_in.x), abs(w_in.y)), abs(w_in.z));
    var w = w_in;
    if big > 1.152921504606847e18 || (big < 8.673617379884035e-19 && big > 0.0) {
        let e = i32((bitcast<u32>(big) >> 23u) & 0xffu) - 127;
        w = w_in * bitcast<f32>(u32(127 - e) << 23u);
    }
    let l = math::hypot(w.x, w.y);
    if l <= 0.0 {
        // Normal incidence or the zero vector (NaN fails and goes on).
        return 0.0;
    }
    let wz = abs(w.z);
    if !(wz > 0.0) {
        // Grazing, or NaN.
        return math::F32_MAX;
    }
    let alpha = r.alpha;
    let ha = min(abs(half_extent), alpha * BIG_K);
    let ux = abs(w.x) / l;
    let uy = abs(w.y) / l;
    let px = ux * alpha.x;
    let py = uy * alpha.y;
    let a = math::hypot(px, py);
    let k1 = px / a * (ha.x / alpha.x);
    let k2 = py / a * (ha.y / alpha.y);
    if k1 == 0.0 && k2 == 0.0 {
        return ggx::lambda_axis_aligned(r, w);
    }
    let mm = wz / l / a;
    if mm > 1e18 {
        return 0.25 / mm / mm;
    }
    // m - k_l = (|w_z| - |w_l| H_l) / (|w_xy| a) for the long axis l (module docs).
    let long_x = k1 >= k2;
    let wl = select(abs(w.y), abs(w.x), long_x);
    let hl = select(ha.y, ha.x, long_x);
    let lo = (wz - wl * hl) / l / a;
    return expected_psi(mm, k1, k2, lo) / mm;
}
