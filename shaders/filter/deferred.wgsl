#define_import_path filtered_ndf::filter::deferred

#import filtered_ndf::math
#import filtered_ndf::ndf::roughness
#import filtered_ndf::kernel::covariance

// Isotropic "deferred" roughness filtering: one scalar roughness widened by the spread of
// the shading normal across a pixel (TK19 section 4; KHPL16 section 5.4), mirroring
// `src/.../filter/deferred.rs`. The published engine conventions are values of
// [`KernelConvention`] in `filter::presets`.

/// TK19's clamp `kappa` on the kernel's squared roughness (TK19 eq. 1), slope^2.
const KAPPA: f32 = 0.18;

/// `v = alpha^2` (TK19, Filament, Unity HDRP, O3DE).
const DOMAIN_ALPHA_SQ: u32 = 0u;
/// `v = alpha` (Godot 4, whose "roughness squared" is `alpha`).
const DOMAIN_ALPHA: u32 = 1u;
/// `v = sqrt(alpha)`, the perceptual roughness (Unreal, three.js, Babylon.js).
const DOMAIN_PERCEPTUAL: u32 = 2u;
/// `v = alpha^2 / (1 - alpha^2)`, TK21's projected-space squared roughness (Unity HDRP
/// `ProjectedSpaceNormalFiltering`); `alpha >= 1` maps to `F32_MAX`.
const DOMAIN_PROJECTED_ALPHA_SQ: u32 = 3u;

/// `|dn_u|^2 + |dn_v|^2` (TK19 eq. 4).
const NORM_SUM_SQUARED: u32 = 0u;
/// `max(|dn_u|^2, |dn_v|^2)` (Vlachos 2015; Unreal, Babylon.js).
const NORM_MAX_SQUARED: u32 = 1u;
/// The largest eigenvalue of the Gram matrix of `dn_u, dn_v` (TK19 eq. 1, `sigma^2 = 1`).
const NORM_MAX_EIGENVALUE: u32 = 2u;
/// The largest absolute component of either difference, not squared (three.js).
const NORM_MAX_ABS_COMPONENT: u32 = 3u;

/// `v' = v + k` (variances add).
const COMBINE_ADD: u32 = 0u;
/// `v' = max(v, k)` (a roughness floor: Vlachos 2015, Unreal).
const COMBINE_MAX: u32 = 1u;

/// TK19 eq. 1: `2 lambda_max(Sigma)`.
const BANDWIDTH_MAX: u32 = 0u;
/// TK19 eq. 2, 4: `2 tr(Sigma)`.
const BANDWIDTH_TRACE: u32 = 1u;
/// TK19 eq. 5: `tr(Sigma)`.
const BANDWIDTH_AVERAGE: u32 = 2u;

/// How one engine turns normal differences into a widened roughness (the Rust
/// `KernelConvention`). [`apply`] computes: (1) `alpha = max(alpha, perceptual_floor^2)`,
/// `v = domain(alpha)`; (2) `k = min(max(scale norm^exponent + bias, 0), clamp)`;
/// (3) `v' = v + k` or `max(v, k)`, then `min(v', 1)` if `saturate`; (4) `alpha_bar` from
/// `v'`, clamped to `[0, ALPHA_MAX]`.
struct KernelConvention {
    /// `DOMAIN_*`.
    domain: u32,
    /// `NORM_*`.
    norm: u32,
    /// Factor on `norm^exponent` (TK19's `2 sigma^2` is 0.5).
    scale: f32,
    /// Exponent on the norm (1 for the variance forms, Unreal's 0.333).
    exponent: f32,
    /// Added after scaling.
    bias: f32,
    /// Upper bound of the kernel in domain units (`F32_MAX`: none).
    clamp: f32,
    /// `COMBINE_*`.
    combine: u32,
    /// Final `min(v', 1)` (HLSL `saturate`).
    saturate: bool,
    /// Minimum perceptual roughness `sqrt(alpha)` enforced first (0: none).
    perceptual_floor: f32,
}

/// `alpha -> v` in `domain` (`alpha >= 0`).
fn from_alpha(domain: u32, alpha: f32) -> f32 {
    if domain == DOMAIN_ALPHA {
        return alpha;
    }
    if domain == DOMAIN_PERCEPTUAL {
        return sqrt(alpha);
    }
    let a2 = alpha * alpha;
    if domain == DOMAIN_PROJECTED_ALPHA_SQ {
        return select(math::F32_MAX, a2 / (1.0 - a2), a2 < 1.0);
    }
    return a2;
}

/// `v -> alpha`, the inverse of [`from_alpha`] for `v >= 0`.
fn to_alpha(domain: u32, v: f32) -> f32 {
    if domain == DOMAIN_ALPHA {
        return v;
    }
    if domain == DOMAIN_PERCEPTUAL {
        return v * v;
    }
    if domain == DOMAIN_PROJECTED_ALPHA_SQ {
        return select(1.0, sqrt(v / (1.0 + v)), v < math::F32_MAX);
    }
    return sqrt(v);
}

/// The largest eigenvalue of `[[a, b], [b, c]]` (no cancellation: mean plus radius), `>= 0`.
fn max_eigenvalue(a: f32, b: f32, c: f32) -> f32 {
    return max(0.5 * (a + c) + math::hypot(0.5 * (a - c), b), 0.0);
}

/// The measure `norm` of `(dn_u, dn_v)`, `>= 0`. The NaN policy (as the Rust `Norm::eval`):
/// a NaN entry of a difference counts as 0 (`math::nan_to_zero3`, decided on the bits).
fn norm_eval(norm: u32, dn_u_in: vec3<f32>, dn_v_in: vec3<f32>) -> f32 {
    let dn_u = math::nan_to_zero3(dn_u_in);
    let dn_v = math::nan_to_zero3(dn_v_in);
    let a = dot(dn_u, dn_u);
    let c = dot(dn_v, dn_v);
    if norm == NORM_MAX_SQUARED {
        return max(a, c);
    }
    if norm == NORM_MAX_EIGENVALUE {
        return max_eigenvalue(a, dot(dn_u, dn_v), c);
    }
    if norm == NORM_MAX_ABS_COMPONENT {
        let m = max(abs(dn_u), abs(dn_v));
        return max(max(m.x, m.y), m.z);
    }
    return a + c;
}

/// `min(max(k, 0), clamp)`; a NaN `k` (which only an infinite difference gives, `inf * 0`,
/// once NaN entries count as 0) is the clamp: an infinite difference saturates.
fn clamp_widening(conv: KernelConvention, k: f32) -> f32 {
    return select(min(max(k, 0.0), conv.clamp), conv.clamp, math::is_nan(k));
}

/// The widening `min(max(scale norm^exponent + bias, 0), clamp)` in domain units (the kernel's
/// contribution to the roughness value). `pow` is the
/// driver's (`exp2(e log2 n)`: within `3 + 2 |e log2 n|` ulp plus `log2`'s error); a zero
/// norm gives `max(bias, 0)`.
fn widening(conv: KernelConvention, dn_u: vec3<f32>, dn_v: vec3<f32>) -> f32 {
    // An infinite entry (where the driver keeps infinities) saturates: the clamp, as the Rust
    // widening of an infinite norm (decided here, before `inf * 0` can meet a `max`).
    let lim = vec3<f32>(math::F32_MAX);
    if any(abs(dn_u) > lim) || any(abs(dn_v) > lim) {
        return conv.clamp;
    }
    let n = norm_eval(conv.norm, dn_u, dn_v);
    var raw = n;
    if conv.exponent != 1.0 {
        raw = select(0.0, pow(n, conv.exponent), n > 0.0);
    }
    return clamp_widening(conv, conv.scale * raw + conv.bias);
}

/// Steps 1, 3, 4 of [`apply`] for a widening `k` already in domain units (clamped here).
/// A negative `alpha` counts as 0; the result is in `[0, ALPHA_MAX]`.
fn apply_widening(conv: KernelConvention, alpha_in: f32, k: f32) -> f32 {
    var alpha = clamp(alpha_in, 0.0, roughness::ALPHA_MAX);
    alpha = max(alpha, conv.perceptual_floor * conv.perceptual_floor);
    let v = from_alpha(conv.domain, alpha);
    let kc = clamp_widening(conv, k);
    var out = select(v + kc, max(v, kc), conv.combine == COMBINE_MAX);
    if conv.saturate {
        out = min(out, 1.0);
    }
    return clamp(to_alpha(conv.domain, out), 0.0, roughness::ALPHA_MAX);
}

/// The filtered roughness `alpha_bar` for material roughness `alpha` and world-space normal
/// differences `dn_u`, `dn_v` (`ddx(normal)`, `ddy(normal)`; TK19 Listing 2).
fn apply(conv: KernelConvention, alpha: f32, dn_u: vec3<f32>, dn_v: vec3<f32>) -> f32 {
    return apply_widening(conv, alpha, widening(conv, dn_u, dn_v));
}

/// The Gram covariance `sigma^2 [[dn_u.dn_u, dn_u.dn_v], [dn_u.dn_v, dn_v.dn_v]]` of two
/// normal differences, `sigma` the pixel filter's standard deviation in pixels (its trace is
/// TK19's `sigma^2 (|dn_u|^2 + |dn_v|^2)`; use only its invariants). Determinant
/// `sigma^4 |dn_u x dn_v|^2` (Lagrange's identity, no cancellation).
fn normal_difference_covariance(dn_u: vec3<f32>, dn_v: vec3<f32>, sigma: f32) -> covariance::Covariance {
    let sigma_sq = sigma * sigma;
    let x = cross(dn_u, dn_v) * sigma_sq;
    return covariance::Covariance(
        dot(dn_u, dn_u) * sigma_sq,
        dot(dn_u, dn_v) * sigma_sq,
        dot(dn_v, dn_v) * sigma_sq,
        dot(x, x),
    );
}

/// The kernel's squared roughness of a bandwidth (`BANDWIDTH_*`) before the clamp:
/// `2 lambda_max`, `2 tr(Sigma)` or `tr(Sigma)`.
fn bandwidth_alpha2(bandwidth: u32, kernel: covariance::Covariance) -> f32 {
    // A NaN entry counts as 0 (the NaN policy, as the Rust `Bandwidth::alpha2`).
    let s_xx = math::nan_to_zero(kernel.s_xx);
    let s_xy = math::nan_to_zero(kernel.s_xy);
    let s_yy = math::nan_to_zero(kernel.s_yy);
    if bandwidth == BANDWIDTH_MAX {
        return 2.0 * max_eigenvalue(s_xx, s_xy, s_yy);
    }
    let t = s_xx + s_yy;
    return select(t, 2.0 * t, bandwidth == BANDWIDTH_TRACE);
}

/// TK19 eq. 1, 4 or 5 from a slope-domain covariance:
/// `alpha_bar = sqrt(saturate(alpha^2 + min(kernel, kappa)))`.
fn filtered_alpha(alpha: f32, kernel: covariance::Covariance, bandwidth: u32, kappa: f32) -> f32 {
    let conv = KernelConvention(
        DOMAIN_ALPHA_SQ,
        NORM_SUM_SQUARED,
        0.5,
        1.0,
        0.0,
        kappa,
        COMBINE_ADD,
        true,
        0.0,
    );
    return apply_widening(conv, alpha, bandwidth_alpha2(bandwidth, kernel));
}
