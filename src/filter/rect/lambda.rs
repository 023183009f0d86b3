//! Smith `Lambda` of the box-filtered GGX: the masking function of the slope distribution
//! that [`super::p22_rect`] and [`super::d_rect`] describe, so that `g1`, `g2` and `d` of the
//! box lobe are one distribution.
//!
//! # Derivation
//! Smith's `Lambda` is a linear functional of the slope distribution (Heitz 2014 eq. 72-73):
//! with `u` the unit azimuth of `w_xy` and `mu = |w_z| / |w_xy|`,
//! `Lambda(w) = (1 / mu) E[(q - mu)^+]`, `q = s.u` the slope along `u` (the distribution is
//! even, so the orientation of `u` does not matter). The box lobe's slope is `s = g + delta`,
//! `g` axis-aligned GGX and `delta` uniform on `[-H_x, H_x] x [-H_y, H_y]` (its density is the
//! box mean of `P22`, [`super::p22_rect`]), so `q = g.u + delta.u` with:
//! - `g.u` the 1D GGX marginal of scale `a = sqrt(u^T A u)`, density
//!   `(1 / 2a) (1 + x^2 / a^2)^(-3/2)`, for which `psi(t) = E[(X - t)^+] = (sqrt(a^2 + t^2) - t) / 2`
//!   (GGX's own `Lambda` is `psi(mu) / mu`);
//! - `delta.u = V_1 + V_2`, independent uniforms on `[-c_i, c_i]`, `c_1 = |u_x| H_x`,
//!   `c_2 = |u_y| H_y` (a trapezoid).
//!
//! So `Lambda = (1 / mu) E[psi(mu - V_1 - V_2)]`. Everything is computed in units of `a`
//! (`m = mu / a`, `k_i = c_i / a`, `psi(t) = (sqrt(1 + t^2) - t) / 2`), in `f64` for both
//! precisions. With `t = sinh(theta)`, `psi = e^-theta / 2` and its antiderivatives are
//! `Psi_1 = (theta - e^(-2 theta) / 2) / 4`,
//! `Psi_2 = (t theta - cosh(theta) + e^-theta / 4 + e^(-3 theta) / 12) / 4`, so that
//! `E = [Psi_2(m + k_1 + k_2) - Psi_2(m + k_1 - k_2) - Psi_2(m - k_1 + k_2) + Psi_2(m - k_1 - k_2)] / (4 k_1 k_2)`
//! in closed form. That second difference cancels when a side is short next to the distance of
//! `psi`'s branch points `+/- i` (in units of `a`), so the evaluation is tiered as
//! [`super::p22_rect`] is (the same Gauss-Legendre tiers and thresholds; `psi` is smoother than
//! the density, so they hold with room). Sides sorted `k_s <= k_l`:
//! 1. **Both short** (`k_l < 0.25 L_l`, `L_l^2 = 1 + max(m - k_s, 0)^2`, the distance of the
//!    branch points from the arguments): the tensor Gauss-Legendre rule of `psi`.
//! 2. **Long side, short side short next to the long side's ends** (`k_s` in a Gauss-Legendre
//!    tier of `L^2 = 1 + (m - k_l)^2`, or `k_s = 0`): the rule in the short side of the exact
//!    mean of `psi` over the long side, written without cancellation: with
//!    `E_i = e^(-theta_i) = sqrt(1 + t_i^2) - t_i` (as `1 / (sqrt(1 + t^2) + t)` for `t > 0`) and
//!    `d = (t_1 - t_0)(E_0 + E_1) / (rho_0 + rho_1) = E_0 - E_1`,
//!    `Psi_1(t_1) - Psi_1(t_0) = (ln(1 + d / E_1) + d (E_0 + E_1) / 2) / 4`, all terms positive,
//!    with `t_1 - t_0 = 2 k_l` exactly and `m - k_l` formed first.
//! 3. **Otherwise** (the short side long next to the distance of `m - k_l` from the branch
//!    points): `E = (A(m + k_l) - A(m - k_l)) / (2 k_l)` with `A(t)` the mean of `Psi_1` over
//!    `[t - k_s, t + k_s]`, by Gauss-Legendre when `k_s` is short next to `sqrt(1 + t^2)` and
//!    else the closed difference of `Psi_2`. The outer difference loses at most about
//!    `ln(2 m) / (2 * 0.25)` (the long side's ratio is at least 0.25), the inner closed
//!    difference a factor below 4.
//!
//! **Conditioning.** `Lambda` is sensitive to where the box's far edge lies relative to `mu`:
//! at `|m - k_l| ~ 1` its relative derivative in `m - k_l` is about `m / 5` (`2e3` at
//! `alpha = 1e-4`, `H = 1`), so forming `m - k_l` from a rounded `m` and `k_l` would cost up
//! to `1e-12`. It is formed instead as `(|w_z| - |w_l| H_l) / (|w_xy| a)` with the difference
//! rounded once (a fused multiply-add), and the other arguments (`m + k_l`, the nodes) carry no
//! such amplification.
//!
//! Accuracy (prototype against 110-digit arithmetic over `m` in `1e-12..1e8`, `k` up to `1e6`,
//! ratios to `1e8`; `tests/ggx_rect_lambda.rs` against independent quadrature): `f64` below
//! `1e-13` relative (2000 seeded cases over the domain: median `1.4e-16`, max `2.2e-15`; a grid
//! where the box's edge meets `mu` at `alpha = 1e-4`: `2.2e-14`); `f32` is the `f64` value
//! rounded once (max `5.9e-8`, half an ulp).
//!
//! # Special inputs
//! Zero half extents (after the sanitising of [`super::p22_rect`]: magnitude, NaN as `0`,
//! clamped to `1e60` normalised), or a box that projects to a point on `u`: GGX's own
//! [`Ndf::lambda`] bit for bit. A NaN component of `w`: `+inf` (a NaN direction is masked);
//! `w_z = 0` (grazing) or an infinite `w_xy`: `+inf`; `w_xy = 0` (normal incidence, also the
//! zero vector) or an infinite `w_z` with finite `w_xy`: `0`. Homogeneous of degree 0 in `w`
//! (`hypot` and ratios; no squares of `w`). For `m > 1e100` the box's correction
//! (`(k / m)^2 <= 1e-80`) is below rounding and `Lambda = 1 / (4 m^2)`.

use super::super::super::ndf::Ndf;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::ndf::roughness::AxisAligned;
use super::{BIG, F, Tier, Vec2, Vec3, gl_of, half64, tier};
use crate::math::{self as m, Real};

/// `w` in `f64`, scaled by a power of two (exactly) when its largest component is outside
/// `[2^-400, 2^400]`, into `[1, 2)`, so that `|w_i| H_i` (`H_i <= 1e60 alpha_i`) neither
/// overflows nor underflows, nor do the visible sampler's squares of `w_i delta_i`; `Lambda`
/// is homogeneous of degree 0. Unit vectors pass unchanged; a non-finite `w` too.
#[inline]
pub(crate) fn scaled(w: Vec3) -> (f64, f64, f64) {
    scaled_to(w, 0)
}

/// [`scaled`] with a largest component above `2^400` scaled into `[2^top, 2^(top + 1))`
/// instead (`0 <= top <= 399`); below `2^-400`, into `[1, 2)` as there.
#[inline]
fn scaled_to(w: Vec3, top: i64) -> (f64, f64, f64) {
    let (x, y, z) = (w.x.to_f64(), w.y.to_f64(), w.z.to_f64());
    let mx = x.abs().max(y.abs()).max(z.abs());
    const HI: f64 = 2.58e120; // 2^400
    const LO: f64 = 3.87e-121; // 2^-400
    if (LO..=HI).contains(&mx) || !mx.is_finite() || mx == 0.0 {
        return (x, y, z);
    }
    // 2^-e for the binary exponent e of mx (subnormal mx: e = -1023, 2^1023), or 2^-1022
    // for e = 1023, whose 2^-1023 is subnormal and has no exponent field (the field 0 would
    // read as 0 and scale every vector to the zero vector): mx then lands in [2, 4).
    let e = ((mx.to_bits() >> 52) & 0x7ff) as i64 - 1023;
    let e = if mx > HI { e - top } else { e };
    let s = f64::from_bits(((1023 - e).max(1) as u64) << 52);
    (x * s, y * s, z * s)
}

/// `ln(1 + x)` for `x >= 0` to a few ulps (Kahan's trick: the rounding of `1 + x` is undone by
/// the same rounding in the denominator).
#[inline]
fn ln_1p(x: f64) -> f64 {
    let u = 1.0 + x;
    if u == 1.0 {
        x
    } else {
        m::ln(u) * x / (u - 1.0)
    }
}

/// `sqrt(1 + t^2)`.
#[inline(always)]
fn rho(t: f64) -> f64 {
    m::sqrt(m::mul_add(t, t, 1.0))
}

/// `e^(-asinh t) = sqrt(1 + t^2) - t`, without cancellation, and `sqrt(1 + t^2)`.
#[inline(always)]
fn exp_neg_asinh(t: f64) -> (f64, f64) {
    let r = rho(t);
    (if t >= 0.0 { 1.0 / (r + t) } else { r - t }, r)
}

/// `asinh(t)` from `t` and `sqrt(1 + t^2)`, to a few ulps.
#[inline(always)]
fn asinh(t: f64, r: f64) -> f64 {
    let a = t.abs();
    let v = ln_1p(a + a * a / (1.0 + r));
    if t < 0.0 { -v } else { v }
}

/// `psi(t) = E[(X - t)^+]` of the unit GGX marginal, `(sqrt(1 + t^2) - t) / 2`.
#[inline(always)]
pub(crate) fn psi(t: f64) -> f64 {
    0.5 * exp_neg_asinh(t).0
}

/// `Psi_1`, an antiderivative of `psi`: `(asinh t - E^2 / 2) / 4`.
#[inline]
fn psi1(t: f64) -> f64 {
    let (e, r) = exp_neg_asinh(t);
    0.25 * (asinh(t, r) - 0.5 * e * e)
}

/// `Psi_2`, an antiderivative of `Psi_1`: `(t asinh t - rho + E / 4 + E^3 / 12) / 4`.
#[inline]
fn psi2(t: f64) -> f64 {
    let (e, r) = exp_neg_asinh(t);
    0.25 * (t * asinh(t, r) - r + 0.25 * e + e * e * e * (1.0 / 12.0))
}

/// `Psi_1(t1) - Psi_1(t0)`, the integral of `psi` over `[t0, t1]`, `w = t1 - t0 >= 0` given
/// exactly (module docs, case 2): `(ln(1 + d / E_1) + d (E_0 + E_1) / 2) / 4`,
/// `d = E_0 - E_1 = w (E_0 + E_1) / (rho_0 + rho_1)`; all terms `>= 0`.
#[inline]
pub(crate) fn psi1_diff(t0: f64, t1: f64, w: f64) -> f64 {
    let (e0, r0) = exp_neg_asinh(t0);
    let (e1, r1) = exp_neg_asinh(t1);
    let s = e0 + e1;
    let d = w * s / (r0 + r1);
    0.25 * (ln_1p(d / e1) + 0.5 * d * s)
}

/// The mean of `psi` over `[t0, t1]`, `w = t1 - t0 > 0` given exactly.
#[inline]
pub(crate) fn mean_psi(t0: f64, t1: f64, w: f64) -> f64 {
    psi1_diff(t0, t1, w) / w
}

/// `A(t)`: the mean of `Psi_1` over `[t - k, t + k]` (module docs, case 3).
#[inline]
pub(crate) fn mean_psi1(t: f64, k: f64) -> f64 {
    if k == 0.0 {
        return psi1(t);
    }
    match tier(k * k, m::mul_add(t, t, 1.0)) {
        Tier::Closed => (psi2(t + k) - psi2(t - k)) / (2.0 * k),
        tt => gl_of(tt, t, k, psi1),
    }
}

/// `E[psi(m - V_1 - V_2)]` for `m >= 0`, `V_i` uniform on `[-k_i, k_i]`, `k_i >= 0` finite
/// and not both zero (module docs, the three cases). `lo` is `m - max(k_1, k_2)`, formed by the
/// caller without cancellation (the edge of the box that meets `mu` drives the conditioning).
fn expected_psi(m: f64, k1: f64, k2: f64, lo: f64) -> f64 {
    let (ks, kl) = if k1 <= k2 { (k1, k2) } else { (k2, k1) };
    let near_l = (m - ks).max(0.0);
    let tl = tier(kl * kl, m::mul_add(near_l, near_l, 1.0));
    if tl != Tier::Closed {
        // Case 1. The short side is in a tier too (`k_s / L_s < k_l / L_l` for `k_s <= k_l`
        // at these ratios); a `Closed` there would take the largest rule.
        let near_s = (m - kl).max(0.0);
        let ts = tier(ks * ks, m::mul_add(near_s, near_s, 1.0));
        return gl_of(tl, m, kl, |t| gl_of(ts, t, ks, psi));
    }
    let (hi, w) = (m + kl, 2.0 * kl);
    if ks == 0.0 {
        return mean_psi(lo, hi, w);
    }
    match tier(ks * ks, m::mul_add(lo, lo, 1.0)) {
        // Case 2.
        Tier::Closed => {}
        ts => return gl_of(ts, 0.0, ks, |x| mean_psi(lo - x, hi - x, w)),
    }
    // Case 3.
    (mean_psi1(hi, ks) - mean_psi1(lo, ks)) / w
}

/// Exact Smith `Lambda` of the box-filtered GGX (module docs): the masking function of the
/// slope distribution whose density is [`super::p22_rect`] (`Lambda(w) = (1 / mu) E[(q - mu)^+]`
/// over `s = g + delta`, `g` GGX of roughness `r`, `delta` uniform on
/// `[-half_extent, half_extent]`), so that `G1 = 1 / (1 + Lambda)` and [`super::d_rect`] satisfy
/// the Smith normalisation `integral of G1(w, m) max(0, w.m) D(m) dm = w_z`.
///
/// Uses `|w_z|`; homogeneous of degree 0 in `w`. Zero half extents (after the sanitising of
/// [`super::p22_rect`]): GGX's [`Ndf::lambda`] bit for bit. `+inf` for a grazing `w`
/// (`w_z = 0` or infinite `w_xy`) and for NaN input; `0` at normal incidence and for the zero
/// vector. Never NaN. Accuracy: about one ulp in `f32`, `1e-12` relative in `f64` (module
/// docs).
#[inline]
pub fn lambda_rect(r: AxisAligned, half_extent: Vec2, w: Vec3) -> F {
    if w.is_nan() {
        return F::INFINITY;
    }
    let alpha = r.alpha();
    let (ax, ay) = (alpha.x.to_f64(), alpha.y.to_f64());
    // Normalised half extents, sanitised as p22_rect does (NaN as 0, magnitude, <= 1e60).
    let (hu, hv) = (
        half64(half_extent.x, 1.0 / ax),
        half64(half_extent.y, 1.0 / ay),
    );
    // A huge `w` is scaled down only to `[2^399, 2^400)`: into `[1, 2)` a small `w_z` beside
    // it could turn subnormal and lose digits (`w = (1, -8e298, -3.9e-17)` went to `9e-316`:
    // 9e-10 relative, found by fuzzing); here it does so only where `|w_xy| / |w_z|` exceeds
    // `2^1421`, where `Lambda` is `+inf` for every roughness in range.
    let (wx, wy, wz) = scaled_to(w, 399);
    let l = m::hypot(wx, wy);
    let mu = wz.abs() / l;
    if mu.is_nan() {
        // 0 / 0 (the zero vector: 0) or inf / inf (an infinite direction: grazing or not,
        // undetermined; masked like NaN).
        return if l == 0.0 { 0.0 } else { F::INFINITY };
    }
    if mu == 0.0 {
        return F::INFINITY;
    }
    if !mu.is_finite() {
        return 0.0;
    }
    let (ux, uy) = ((wx / l).abs(), (wy / l).abs());
    // Projected roughness a = sqrt(u^T A u) and the box's projected half extents in units of
    // a: k_i = |u_i| alpha_i H_i / (alpha_i a) <= H_i / alpha_i.
    let (px, py) = (ux * ax, uy * ay);
    let a = m::hypot(px, py);
    let (k1, k2) = (px / a * hu, py / a * hv);
    if k1 == 0.0 && k2 == 0.0 {
        return Ggx::new(r).lambda(w);
    }
    // `mu` subnormal (a subnormal `w_z` beside a unit `w_xy`): divided once by `l a`, so the
    // quotient keeps its digits (`mu / a` had lost them in `mu`: 1.4e-12 in `f64`, found by
    // fuzzing). Otherwise as before, bit for bit.
    let sub = mu < f64::MIN_POSITIVE;
    let mm = if sub { wz.abs() / (l * a) } else { mu / a };
    if mm > 1e100 {
        return F::from_f64(0.25 / mm / mm);
    }
    // m - k_l = (|w_z| - |w_i| H_i) / (|w_xy| a) for the long axis i, the difference rounded
    // once (a fused multiply-add) instead of after m and k_l: where the box's far edge meets
    // mu, Lambda's sensitivity to that difference reaches m / 5 (module docs).
    // The half extent in slope units as given (exact), clamped as `half64` clamps it.
    let (wi, h, ai) = if k1 >= k2 {
        (wx, half_extent.x, ax)
    } else {
        (wy, half_extent.y, ay)
    };
    let h = h.to_f64().abs().min(BIG * ai);
    let num = m::mul_add(-wi.abs(), h, wz.abs());
    let lo = if sub { num / (l * a) } else { num / l / a };
    let lambda = expected_psi(mm, k1, k2, lo) / mm;
    F::from_f64(lambda)
}
