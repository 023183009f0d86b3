//! The exact box filter of GGX: the average of the axis-aligned GGX slope density over an
//! axis-aligned rectangle of the slope domain (KHPL16 eq. 16 and Appendix A; GDC 2016 listing
//! `GGXRectIntegral`), and its solid-angle form.
//!
//! # The integral
//! With `u = x / a`, `v = y / b` (`a = alpha_x`, `b = alpha_y`) the axis-aligned GGX slope
//! density is `P22(x, y) = f(u, v) / (pi a b)`, `f = (1 + u^2 + v^2)^-2`, so the average of
//! `P22` over `[x_c - H_x, x_c + H_x] x [y_c - H_y, y_c + H_y]` is
//! `mean(f) / (pi a b)` over the normalised rectangle `[u_c +/- H_u] x [v_c +/- H_v]`.
//! A double antiderivative of `f` is `F(u, v) = (phi(u, v) + phi(v, u)) / 2` with
//! `phi(u, v) = u / sqrt(1 + u^2) atan(v / sqrt(1 + u^2))` (KHPL16 Appendix A, whose
//! `varphi(x, y, gamma, delta)` is this `phi` in unnormalised coordinates), and the integral
//! over the rectangle is the four-corner difference of `F`: the printed eight-term formula.
//!
//! **Normalisation.** The integral of `P22` over the rectangle is
//! `(1 / (2 pi)) (eight-term sum)`, and the *average* divides it by the rectangle's area
//! `(2 H_x)(2 H_y)`. KHPL16 eq. 16 is right (bounds `h +/- Delta h / 2`, divided by
//! `|Delta h_s Delta h_t|`, the area); Appendix A is not: it writes the bounds as
//! `h +/- Delta h` but still divides by `|Delta h_s Delta h_t|`, a quarter of that area, so
//! read literally it returns **four times** the average. The GDC listing divides by
//! `2 pi f (x1 - x2)(y1 - y2)`, which is right with its undefined `f` set to `1` (checked
//! against quadrature in `tests/ggx_rect.rs`).
//!
//! # Why not the printed formula
//! The eight terms are `O(1)` angles while the average times the area can be as small as
//! `1e-24` (a `1e-7` footprint in the tail of an `alpha = 1e-4` lobe): the four-corner
//! difference cancels catastrophically, in `f32` already for moderate rectangles, and it is
//! `0 / 0` for a zero footprint. [`p22_rect`] instead (all internal arithmetic in `f64`, for
//! both precisions; rectangle normalised as above, `L_u^2 = 1 + u_c^2 + d_v^2`,
//! `L_v^2 = 1 + v_c^2 + d_u^2` with `d_u`, `d_v` the distances of the rectangle from the
//! peak along each axis, i.e. the distances to the density's complex poles).
//! Each axis gets a tier from its ratio `H / L`, with thresholds per precision (`TAU`):
//!
//! | rule | `f32` (target `1e-9`) | `f64` (target `1e-13`) |
//! |---|---|---|
//! | 2-point Gauss-Legendre | `H / L < 0.01` | `< 3e-4` |
//! | 4-point | `< 0.1` | `< 0.02` |
//! | 6-point | `< 0.25` | `< 0.08` |
//! | 8-point | - | `< 0.18` |
//! | 10-point | - | `< 0.25` |
//! | closed form | above | above |
//!
//! The rule's relative error for `(c^2 + x^2)^-2` over `[x_c - H, x_c + H]`, worst over the
//! centre, is `3.1 (H / L)^4` for 2 points and about `(H / 2L)^(2n)` beyond (measured in
//! 40-digit arithmetic: 2 points `3.1e-8` at `0.01` and `2.5e-14` at `3e-4`; 4 points
//! `9.6e-9` at `0.1`, `2.5e-14` at `0.02`; 6 points `1.1e-8` at `0.25`, `1.2e-14` at `0.08`;
//! 8 points `3e-14` at `0.18`; 10 points `2.9e-15` at `0.25`). The `f32` tiers stay below
//! `3.1e-8` (both sides of a switch agree to that, a quarter of an `f32` ulp at worst); the
//! `f64` ones below `5e-14` per axis: the `f64` build needs its own tiers, since the `f32`
//! ones truncate at `1e-9` far in the tail (`3e4` lobe widths with a 1000:1 box). Two other
//! losses of digits are avoided below: the series of `delta - sin delta` and, far out, the
//! polar form instead of the four edges.
//! 1. **Both axes short**: the tensor Gauss-Legendre rule of the two tiers (4 to 36 nodes in
//!    `f32`, one division per row of nodes; up to 100 in `f64`).
//! 2. **One long side** (say `u`): the closed form of case 3 while its cancellation allows
//!    (`(1 + u_c^2 + v_c^2)^(3/2) / H_v < 1e6` in `f32`, `< 1e3` in `f64`: error below `1e-10`,
//!    `1e-13`), else the Gauss-Legendre rule in `v` of the exact 1D average in `u`, written
//!    without cancellation (`mean_1d`): with
//!    `c^2 = 1 + v^2`, `delta = atan2(c Delta u, c^2 + u_0 u_1)` (the atan-difference
//!    identity) and `r_i^2 = c^2 + u_i^2`,
//!    `int f du = delta / (2 c^3) + Delta u (c^2 - u_0 u_1) / (2 c^2 r_0^2 r_1^2)` when the
//!    interval straddles `0`, and otherwise
//!    `(delta - sin delta) / (2 c^3) + Delta u / (2 r_0^2 r_1^2) [1 + (u_0^2 + u_1^2 + c^2) /
//!    (r_0 r_1 + u_0 u_1)]`, all terms positive (`delta - sin delta` by its Taylor series below
//!    1: through `delta^13 / 13!` in `f32`, `4.6e-12` relative at `delta = 1`; through
//!    `delta^19 / 19!` in `f64`, where the shorter series showed as `6.6e-13`).
//!    A zero half extent on one axis is the exact 1D average (both nodes coincide).
//! 3. **Both sides long**: the closed form as four edge terms (Lambert's contour form of the
//!    projected solid angle), each edge's two arctangents merged into one by
//!    `atan p - atan q = atan2(p - q, 1 + p q)` with the difference `p - q` taken from the side
//!    length directly: `2 I = sum over edges of +/- u_e / S_e atan2(Delta v S_e, S_e^2 + v_0 v_1)`,
//!    `S_e = sqrt(1 + u_e^2)`. Four `atan2` (each one `atan`) instead of eight `atan`. The edge
//!    terms are angles of order one while the integral of a rectangle at distance `D` from the
//!    peak is of order `1 / D^2`: the form cancels like `1e-15 D^2` (measured: `1.5e-8` at
//!    `D ~ 2e4`). Beyond `D = 316` (`f32`) or `D = 10` (`f64`) the polar
//!    form is used instead (`far_field`): with `g(r) = 1 / (1 + r^2)`, `f dA` is the exterior
//!    derivative of `-g / 2 d theta` (polar angle about the peak), so the integral is
//!    `-1/2` times the contour integral of `g d theta`, one positive integral per edge in the
//!    polar angle, by 10-point (`f64`) or 6-point (`f32`) Gauss-Legendre split at the foot of
//!    the edge's perpendicular. With every point at least `D` from the peak, the integrand's
//!    poles are at least `asinh(D)` away in the angle, and the rule converges far below the
//!    targets; the near and far sides of a rectangle with two long sides differ by a bounded
//!    factor, so the four terms do not cancel.
//!
//! Measured (`tests/ggx_rect.rs`, 2000 seeded samples over alpha `1e-4..1`, anisotropy up to
//! `100`, `|center|` components up to 4, half sides `1e-8..1`, against `f64` adaptive
//! quadrature over the offsets from the centre): `f32` relative error median `2.1e-8`, max
//! `6.4e-8` (about one ulp); `f64` median `2e-16`, max `4.2e-14`. A scan of 20000 cases per tier combination (slopes to `1e5` lobe widths, boxes to
//! 10000:1) against 80-digit arithmetic: `f64` at most `8e-14` in every case of the case
//! analysis. The printed formula in `f32` on the same sample: median `3.1e-3`, max `4e14`.
//! Far in the tail of a very sharp lobe (normalised distance `|center| / alpha ~ 1e8`, e.g.
//! `alpha = 1e-8` at slope 1) the result is still clamped to `>= 0` (the four-edge form had
//! cancelled below zero there before the polar form took over; found by fuzzing).
//!
//! # The box lobe
//! [`lambda_rect`] is the exact Smith `Lambda` of this distribution (module `lambda`), so
//! that `d_rect`, `G1 = 1 / (1 + lambda_rect)` and `G2` describe one lobe: [`RectFilteredGgx`]
//! (module `lobe`, with its method [`Rect`]). The sampling stage samples it exactly, with its
//! pdfs (`sampling::rect`).
//!
//! # Inputs outside the domain
//! Negative half extents are used by their absolute value (the rectangle is the same); NaN half
//! extents count as `0`; half extents and normalised centres are clamped to `1e60` (the density
//! there is below `1e-240` of its peak). A NaN centre gives `0`. Nothing here clamps the
//! footprint from below or above: the KHPL16 floor `epsilon = 1e-3`, the GDC floor
//! `min(alpha, 0.1)` and the upper bound `lambda = 1` are bias controls applied by the caller
//! (the footprint clamping rules); this integral is exact without them.

use super::super::ndf::Ndf;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::AxisAligned;
use super::{F, Vec2, Vec3};
use crate::math::{self as m, Real};

mod gauss;
mod lambda;
mod lobe;
mod printed;
pub(crate) use gauss::{
    CLOSED_INDEX, GL2_X, GL4_W, GL4_X, GL6_W, GL6_X, GL8_W, GL8_X, GL10_W, GL10_X, Tier, WIDE,
    gl_of, rule, tier,
};
use gauss::{tier_index, tier_of_index};
pub use lambda::lambda_rect;
pub(crate) use lambda::{mean_psi, mean_psi1, psi, psi1_diff, scaled};
pub use lobe::{Rect, RectFilteredGgx};
pub use printed::d_rect_printed;

const PI64: f64 = core::f64::consts::PI;

/// Largest normalised half extent or centre coordinate used (see the module docs).
pub(crate) const BIG: f64 = 1e60;

/// The four-edge closed form is used while its relative error, about
/// `1e-16 (1 + u_c^2 + v_c^2)^(3/2) / H_short`, stays below `1e-16 EDGES_GAIN`: `1e-10` in
/// `f32`, `1e-13` in `f64` (see [`edges_ok`]).
const EDGES_GAIN: f64 = if WIDE { 1e3 } else { 1e6 };
/// Squared distance `D^2` (normalised) of a rectangle from the peak beyond which two long
/// sides use the polar form [`far_field`] instead of the four-edge form, whose cancellation
/// grows like `1e-15 D^2` (measured; module docs): `D > 10` in `f64`, `D > 316` in `f32`.
const FAR2: f64 = if WIDE { 1e2 } else { 1e5 };

/// The mean over `v` in `[c - h, c + h]` of `f(u, v) = (1 + u^2 + v^2)^-2` by the
/// Gauss-Legendre rule of tier `t`. A symmetric pair of nodes is
/// `f(u, c - a) + f(u, c + a) = (s_1 + s_2) / (s_1 s_2)`, `s_i = t_i^2`, and while every
/// `t_i < 1e25` (so that a product of six `s_i` stays below `1e300`) all pairs share one
/// division: `sum_k w_k n_k / p_k = (sum_k w_k n_k prod_{j != k} p_j) / prod_k p_k`, all terms
/// positive. Beyond that, one division per pair; with the inputs clamped to `BIG`,
/// `s_i <= 1e243`, and a product that overflows gives `finite / inf = 0`, the (underflowing)
/// right value.
///
/// Returns the mean and whether the pairs share one division (always for `Gl2`, `Gl8`,
/// `Gl10`). With `SHARED_ONLY` (`batch`'s lanes, which compute both sides of a select) the
/// shared division's value alone, the scalar path's where the flag holds: a `Gl4` lane then
/// takes one division instead of three, a `Gl6` lane one instead of four.
#[inline(always)]
fn gl_f_by<const SHARED_ONLY: bool>(t: Tier, u: f64, c: f64, h: f64) -> (f64, bool) {
    let q = 1.0 + u * u;
    let pair = |a: f64| {
        let (v0, v1) = (c - a, c + a);
        let (t0, t1) = (q + v0 * v0, q + v1 * v1);
        let (s0, s1) = (t0 * t0, t1 * t1);
        (s0 + s1, s0 * s1)
    };
    let reach = c.abs() + h;
    let shared = q + reach * reach < 1e25;
    let v = match t {
        Tier::Gl2 => {
            let (n, p) = pair(h * GL2_X);
            return (0.5 * n / p, true);
        }
        Tier::Gl4 => {
            let (n0, p0) = pair(h * GL4_X[0]);
            let (n1, p1) = pair(h * GL4_X[1]);
            if SHARED_ONLY || shared {
                (GL4_W[0] * n0 * p1 + GL4_W[1] * n1 * p0) / (p0 * p1)
            } else {
                GL4_W[0] * n0 / p0 + GL4_W[1] * n1 / p1
            }
        }
        Tier::Gl8 | Tier::Gl10 if WIDE => {
            // `f64` only (the guard removes the arm from the `f32` build): one division per
            // pair.
            let (xs, ws) = rule(t);
            let mut acc = 0.0;
            for (&x, &w) in xs.iter().zip(ws) {
                let (n, p) = pair(h * x);
                acc += w * n / p;
            }
            return (acc, true);
        }
        _ => {
            let (n0, p0) = pair(h * GL6_X[0]);
            let (n1, p1) = pair(h * GL6_X[1]);
            let (n2, p2) = pair(h * GL6_X[2]);
            if SHARED_ONLY || shared {
                (GL6_W[0] * n0 * (p1 * p2) + (GL6_W[1] * n1 * p2 + GL6_W[2] * n2 * p1) * p0)
                    / (p0 * p1 * p2)
            } else {
                GL6_W[0] * n0 / p0 + GL6_W[1] * n1 / p1 + GL6_W[2] * n2 / p2
            }
        }
    };
    (v, shared)
}

/// `delta - sin(delta)` for `delta` in `[0, pi]`, given `sin(delta)` (series below 1, where
/// the difference cancels).
#[inline(always)]
fn delta_minus_sin(d: f64, sin_d: f64) -> f64 {
    if d < 1.0 {
        let d2 = d * d;
        // d^3/6 (1 - d^2/20 (1 - d^2/42 (1 - d^2/72 (1 - d^2/110 (1 - d^2/156 ...))))), the
        // Taylor series through d^13 / 13!: the first term left out, d^15 / 15!, is 4.6e-12
        // relative at d = 1, far below f32 rounding; in f64 three more factors (through
        // d^19 / 19!) leave 1.2e-19 (the shorter series would show as 6.6e-13 in `mean_1d`).
        let s = if WIDE {
            1.0 - d2
                * (1.0 / 156.0)
                * (1.0
                    - d2 * (1.0 / 210.0) * (1.0 - d2 * (1.0 / 272.0) * (1.0 - d2 * (1.0 / 342.0))))
        } else {
            1.0 - d2 * (1.0 / 156.0)
        };
        let s = 1.0 - d2 * (1.0 / 110.0) * s;
        let s = 1.0 - d2 * (1.0 / 72.0) * s;
        let s = 1.0 - d2 * (1.0 / 42.0) * s;
        let s = 1.0 - d2 * (1.0 / 20.0) * s;
        d * d2 * (1.0 / 6.0) * s
    } else {
        d - sin_d
    }
}

/// Mean of `(c2 + x^2)^-2` over `[xc - hx, xc + hx]`, `hx > 0`, `c2 >= 1`, without
/// cancellation (module docs, case 2).
#[inline]
fn mean_1d(xc: f64, hx: f64, c2: f64) -> f64 {
    let x0 = xc.abs() - hx;
    let x1 = xc.abs() + hx;
    let dx = 2.0 * hx;
    let c = m::sqrt(c2);
    let r02 = c2 + x0 * x0;
    let r12 = c2 + x1 * x1;
    let x01 = x0 * x1;
    // atan(x1 / c) - atan(x0 / c), exactly, in (0, pi).
    let d = atan2_upper(c * dx, c2 + x01);
    // The divisions below do not depend on `d`: they overlap with the `atan`.
    let inv = 1.0 / (2.0 * c * c2 * dx);
    let p2 = 2.0 * r02 * r12;
    if x0 <= 0.0 {
        d * inv + (c2 - x01) / (c2 * p2)
    } else {
        let rr = m::sqrt(r02 * r12);
        delta_minus_sin(d, c * dx / rr) * inv + (1.0 + (x0 * x0 + x1 * x1 + c2) / (rr + x01)) / p2
    }
}

/// `atan2(y, x)` for `y > 0`, in `(0, pi)`, with one `atan` and one division (cheaper than a
/// general `atan2`; relative error that of `atan`, since `atan(z) / z` is well conditioned):
/// libm's `atan` plus the division's and the sum's roundings, at most `2 eps_64` relative.
/// The scalar path's angle of [`edges_by`]; `batch` passes its polynomial lane form instead.
#[inline(always)]
fn atan2_upper(y: f64, x: f64) -> f64 {
    if x > 0.0 {
        m::atan(y / x)
    } else {
        0.5 * PI64 + m::atan(-x / y)
    }
}

/// One edge of the contour form: `u / S atan2(dv S, S^2 + v0 v1)`, `S = sqrt(1 + u^2)`, with
/// the angle `atan2(y, x)` (`y > 0`) by `at2`.
#[inline(always)]
fn edge_by(at2: impl Fn(f64, f64) -> f64, u: f64, dv: f64, v01: f64) -> f64 {
    let s2 = 1.0 + u * u;
    let s = m::sqrt(s2);
    u / s * at2(dv * s, s2 + v01)
}

/// Mean of `f` over the normalised rectangle `[uc +/- hu] x [vc +/- hv]` (`hu, hv >= 0`,
/// finite), by the case analysis of the module docs.
fn mean_f(uc: f64, vc: f64, hu: f64, hv: f64) -> f64 {
    let (tu, tv, du, dv) = tiers(uc, vc, hu, hv);
    if edges_route(tu, tv, (du, dv), uc, vc, hu, hv) {
        return edges(uc, vc, hu, hv);
    }
    match (tu, tv) {
        (Tier::Closed, Tier::Closed) => far_field(uc, vc, hu, hv),
        (Tier::Closed, t) => gl_of(t, vc, hv, |y| mean_1d(uc, hu, 1.0 + y * y)),
        (t, Tier::Closed) => gl_of(t, uc, hu, |x| mean_1d(vc, hv, 1.0 + x * x)),
        (Tier::Gl2, Tier::Gl2) => gl2x2(uc, vc, hu, hv),
        (t, t2) => tensor(t, t2, uc, vc, hu, hv),
    }
}

/// The tensor Gauss-Legendre rule of tiers `(t, t2)` (neither `Closed`): rows along `u` by
/// `t`, each row's mean along `v` by [`gl_f_by`] of tier `t2`. Written out rather than through
/// `gl_of`'s closure: with two call sites the closure is not inlined, a call per row.
#[inline(always)]
fn tensor(t: Tier, t2: Tier, uc: f64, vc: f64, hu: f64, hv: f64) -> f64 {
    tensor_by::<false>(t, t2, uc, vc, hu, hv).0
}

/// [`tensor`] and whether every row's pairs share one division (with `SHARED_ONLY` the shared
/// values alone: [`gl_f_by`]).
#[inline(always)]
fn tensor_by<const SHARED_ONLY: bool>(
    t: Tier,
    t2: Tier,
    uc: f64,
    vc: f64,
    hu: f64,
    hv: f64,
) -> (f64, bool) {
    let (xs, ws) = rule(t);
    let (mut acc, mut shared) = (0.0, true);
    for (&x, &w) in xs.iter().zip(ws) {
        let a = hu * x;
        let (f0, s0) = gl_f_by::<SHARED_ONLY>(t2, uc - a, vc, hv);
        let (f1, s1) = gl_f_by::<SHARED_ONLY>(t2, uc + a, vc, hv);
        acc += w * (f0 + f1);
        shared &= s0 & s1;
    }
    (acc, shared)
}

/// The tiers of the two axes (module docs) and the distances `(du, dv)` of the centre from
/// the rectangle along each axis (`0` inside).
#[inline(always)]
fn tiers(uc: f64, vc: f64, hu: f64, hv: f64) -> (Tier, Tier, f64, f64) {
    let (iu, iv, du, dv) = tier_indices(uc, vc, hu, hv);
    (tier_of_index(iu), tier_of_index(iv), du, dv)
}

/// [`tiers`] as [`tier_index`]es (branch-free).
#[inline(always)]
fn tier_indices(uc: f64, vc: f64, hu: f64, hv: f64) -> (u8, u8, f64, f64) {
    let du = (uc.abs() - hu).max(0.0);
    let dv = (vc.abs() - hv).max(0.0);
    let lu2 = 1.0 + uc * uc + dv * dv;
    let lv2 = 1.0 + vc * vc + du * du;
    let (hu2, hv2) = (hu * hu, hv * hv);
    (tier_index(hu2, lu2), tier_index(hv2, lv2), du, dv)
}

/// The 2 x 2-point tensor Gauss-Legendre rule (both axes in tier `Gl2`, the most common case
/// for pixel footprints): the mean of `f` at the four nodes, `(n0 / p0 + n1 / p1) / 4` per
/// row pair as in [`gl_f_by`], with one division for both rows while `p0 p1` stays below
/// `1e300` (a few `f64` ulps from two divisions; all terms positive).
#[inline(always)]
fn gl2x2(uc: f64, vc: f64, hu: f64, hv: f64) -> f64 {
    let (n0, p0, n1, p1) = gl2x2_rows(uc, vc, hu, hv);
    let pp = p0 * p1;
    if pp < 1e300 {
        0.25 * (n0 * p1 + n1 * p0) / pp
    } else {
        0.25 * (n0 / p0 + n1 / p1)
    }
}

/// [`gl2x2`]'s two row pairs `(n0, p0, n1, p1)`.
#[inline(always)]
fn gl2x2_rows(uc: f64, vc: f64, hu: f64, hv: f64) -> (f64, f64, f64, f64) {
    let (a, b) = (hu * GL2_X, hv * GL2_X);
    let (v0, v1) = (vc - b, vc + b);
    let (w0, w1) = (v0 * v0, v1 * v1);
    let row = |u: f64| {
        let q = 1.0 + u * u;
        let (t0, t1) = (q + w0, q + w1);
        let (s0, s1) = (t0 * t0, t1 * t1);
        (s0 + s1, s0 * s1)
    };
    let (n0, p0) = row(uc - a);
    let (n1, p1) = row(uc + a);
    (n0, p0, n1, p1)
}

/// The four-edge closed form (module docs, case 3): the mean of `f` over the rectangle, with
/// libm's `atan` ([`edges_by`] with [`atan2_upper`]).
#[inline]
fn edges(uc: f64, vc: f64, hu: f64, hv: f64) -> f64 {
    edges_by(atan2_upper, uc, vc, hu, hv)
}

/// The four-edge closed form with the edges' angles `atan2(y, x)` (`y > 0`) by `at2`: the one
/// formula of the scalar path ([`edges`]) and of `batch`'s lane ([`RectSetup::closed_lane`]).
///
/// Computed as `0.5 ((e(u1) - e(u0)) + (e(v1) - e(v0))) / (4 H_u H_v)` with the edge terms
/// `e = (u / S) A`, `A` the angle. An angle with relative error `d` moves the result by at
/// most `d` times `M = 0.5 sum |e| / (4 H_u H_v)`; the other roundings (the product by the
/// angle, the three sums, the area, the division) by at most `3 eps_64 M + 2 eps_64 |mean|`.
/// `M / |mean|` is the form's cancellation gain, which [`edges_route`] keeps below about
/// `EDGES_GAIN` (module docs).
#[inline(always)]
fn edges_by(at2: impl Fn(f64, f64) -> f64 + Copy, uc: f64, vc: f64, hu: f64, hv: f64) -> f64 {
    let (u0, u1, v0, v1) = (uc - hu, uc + hu, vc - hv, vc + hv);
    let (du, dv) = (2.0 * hu, 2.0 * hv);
    let (u01, v01) = (u0 * u1, v0 * v1);
    let e = |u: f64, d: f64, w01: f64| edge_by(at2, u, d, w01);
    let i = 0.5 * ((e(u1, dv, v01) - e(u0, dv, v01)) + (e(v1, du, u01) - e(v0, du, u01)));
    i / (du * dv)
}

/// Whether [`mean_f`] takes the four-edge closed form for tiers `(tu, tv)` and distances
/// `(du, dv)` from [`tiers`]: both sides long and the rectangle within `sqrt(FAR2)` of the
/// peak, or one side long and [`edges_ok`] for the other. Branch-free (`&`, `|` of compares),
/// for the lane.
#[inline(always)]
fn edges_route(tu: Tier, tv: Tier, d: (f64, f64), uc: f64, vc: f64, hu: f64, hv: f64) -> bool {
    let (cu, cv) = (tu == Tier::Closed, tv == Tier::Closed);
    (cu & cv & (d.0 * d.0 + d.1 * d.1 <= FAR2))
        | (cu & !cv & edges_ok(uc, vc, hv))
        | (!cu & cv & edges_ok(uc, vc, hu))
}

/// The mean of `f` over a rectangle far from the peak (`D^2 > FAR2`, both sides long), by the
/// polar form of the module docs: with `g(r) = 1 / (1 + r^2)`, Green's theorem on
/// `f dA = d(-g / 2) ^ d theta` gives `I = -1/2` times the contour integral of `g d theta`, one
/// positive integral per edge ([`edge_polar`]); the edges' cancellation is that of the near and
/// far sides seen from the peak, bounded for long sides.
#[inline(never)]
fn far_field(uc: f64, vc: f64, hu: f64, hv: f64) -> f64 {
    let (u0, u1, v0, v1) = (uc - hu, uc + hu, vc - hv, vc + hv);
    let i = -0.5
        * ((edge_polar(u1, v0, v1) - edge_polar(u0, v0, v1))
            + (edge_polar(v1, u0, u1) - edge_polar(v0, u0, u1)));
    i / (4.0 * hu * hv)
}

/// `sign(x)` times the integral of `g(|x| / cos phi) = c^2 / (c^2 + x^2)`, `c = cos phi`, over
/// `phi` from `atan(a / |x|)` to `atan(b / |x|)`: the integral of `g d theta` along the edge
/// `{x} x [a, b]` of the rectangle (either orientation of the axes; the sign of `x` orients it).
/// Every point of the edge is at least `sqrt(FAR2)` from the peak, so the integrand's poles
/// (`cos phi = +/- i x`, at `phi = +/- pi/2 +/- i asinh|x|`) are at least `0.19` half-lengths
/// away once the range is split at `phi = 0` (module docs): 10-point Gauss-Legendre in `f64`,
/// 6-point in `f32`, both far below their targets.
#[inline]
fn edge_polar(x: f64, a: f64, b: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let ax = x.abs();
    let x2 = ax * ax;
    let (p0, p1) = (m::atan(a / ax), m::atan(b / ax));
    let piece = |lo: f64, hi: f64| {
        let g = |phi: f64| {
            let c = m::cos(phi);
            let c2 = c * c;
            c2 / (c2 + x2)
        };
        gl_of(
            if WIDE { Tier::Gl10 } else { Tier::Gl6 },
            0.5 * (lo + hi),
            0.5 * (hi - lo),
            g,
        ) * (hi - lo)
    };
    let v = if p0 < 0.0 && p1 > 0.0 {
        piece(p0, 0.0) + piece(0.0, p1)
    } else {
        piece(p0, p1)
    };
    if x > 0.0 { v } else { -v }
}

/// Whether the four-edge form is accurate for a rectangle whose short half side is `h_short`:
/// its relative error is about `1e-16 (1 + u_c^2 + v_c^2)^(3/2) / h_short` (measured), so it is
/// used while that stays below `1e-16 EDGES_GAIN` (and is cheaper than the 1D closed form at 2
/// to 6 nodes).
#[inline(always)]
fn edges_ok(uc: f64, vc: f64, h_short: f64) -> bool {
    let l2 = 1.0 + uc * uc + vc * vc;
    l2 * l2 * l2 < EDGES_GAIN * EDGES_GAIN * h_short * h_short
}

/// Both half extents `0` or NaN (NaN counts as `0`): the unfiltered lobe, bit for bit.
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub(crate) fn zero_footprint(half_extent: Vec2) -> bool {
    !(half_extent.x.abs() > 0.0) & !(half_extent.y.abs() > 0.0)
}

/// Sanitised `f64` half extent: `|h|`, NaN as `0`, at most `BIG`.
#[inline(always)]
pub(crate) fn half64(h: F, inv_alpha: f64) -> f64 {
    let v = (h.to_f64() * inv_alpha).abs();
    if v.is_nan() { 0.0 } else { v.min(BIG) }
}

/// The mean of `P22` over the rectangle, in `f64`; `None` for a NaN centre.
#[inline]
fn p22_rect64(r: AxisAligned, center: (f64, f64), half_extent: Vec2) -> Option<f64> {
    let (uc, vc, hu, hv, k) = unit_coords(r, center, half_extent);
    if uc.is_nan() || vc.is_nan() {
        return None;
    }
    let (uc, vc) = (uc.clamp(-BIG, BIG), vc.clamp(-BIG, BIG));
    // Clamped: far in the tail (`|center| / alpha ~ 1e8`, both sides long) the closed form
    // cancels to a tiny negative value (found by fuzzing; module docs, accuracy).
    Some((mean_f(uc, vc, hu, hv) * k).max(0.0))
}

/// The rectangle in units of the roughness: `(u_c, v_c, H_u, H_v, 1 / (pi a b))`, the centre
/// not yet clamped to `BIG` (NaN stays NaN).
#[inline(always)]
fn unit_coords(r: AxisAligned, center: (f64, f64), half_extent: Vec2) -> (f64, f64, f64, f64, f64) {
    let alpha = r.alpha();
    let (a, b) = (alpha.x.to_f64(), alpha.y.to_f64());
    let (ia, ib) = (1.0 / a, 1.0 / b);
    let hu = half64(half_extent.x, ia);
    let hv = half64(half_extent.y, ib);
    (center.0 * ia, center.1 * ib, hu, hv, ia * ib * (1.0 / PI64))
}

/// Exact box-filtered GGX slope density: the average of the axis-aligned GGX `P22` over the
/// slope-domain rectangle `center +/- half_extent` (KHPL16 eq. 16, with the normalisation of
/// eq. 16, not of Appendix A: see the module docs).
///
/// `mean P22 = 1 / (4 H_x H_y) int int P22(x, y) dx dy` per unit slope area, with
/// `P22(s) = 1 / (pi a b (1 + s_x^2 / a^2 + s_y^2 / b^2)^2)`. Exact to within a few ulps of `F`
/// over the whole domain (module docs), including a zero half extent on one axis (the 1D
/// average) or both (returns [`Ndf::p22`] of the unfiltered GGX, bit for bit).
///
/// Domain: any finite `center` and `half_extent`; negative half extents count by their
/// absolute value, NaN half extents as `0` (both NaN or zero: bit for bit the unfiltered
/// `p22`), a NaN centre returns `0`. Never NaN, never
/// negative; `0` only where the average underflows.
#[inline]
pub fn p22_rect(r: AxisAligned, center: Vec2, half_extent: Vec2) -> F {
    if zero_footprint(half_extent) {
        // A NaN centre returns 0 here too (the unfiltered `p22` would give NaN).
        let p = Ggx::new(r).p22(center);
        return if p.is_nan() { 0.0 } else { p };
    }
    match p22_rect64(r, (center.x.to_f64(), center.y.to_f64()), half_extent) {
        Some(v) => F::from_f64(v),
        None => 0.0,
    }
}

/// Exact box-filtered GGX in solid-angle measure: [`p22_rect`] at the slope `s(h) = -h_xy / h_z`
/// of the unit half vector `h`, divided by `h_z^4` (the Jacobian from slopes to solid angle,
/// TK19 supplement; GDC listing `GGXRectIntegral`, without its `max(1e-3, h_z^4)` clamp).
///
/// `half_extent` is the slope-domain half extent of the filtering rectangle (half the sides
/// `Delta h_s`, `Delta h_t` of KHPL16 eq. 16). Per steradian; with a zero footprint it returns
/// [`Ndf::d`] of the unfiltered GGX bit for bit.
///
/// Outside the domain: `0` for `h_z <= 0` (below the horizon) and for non-finite `h`; for
/// `0 < h_z < 1e-70` (reachable in `f64` only) the unfiltered `D(h)`, which is the limit there
/// for finite half extents. Half extents as in [`p22_rect`]. Never NaN; a value beyond the
/// range of `F` (only for a non-unit `h` with a tiny `h_z`) saturates at `F::MAX`.
#[inline]
pub fn d_rect(r: AxisAligned, h: Vec3, half_extent: Vec2) -> F {
    if !h.is_finite() || h.z <= 0.0 {
        return 0.0;
    }
    if zero_footprint(half_extent) || h.z.to_f64() < 1e-70 {
        return Ggx::new(r).d(h);
    }
    let (center, ihz4) = slope_of(h);
    match p22_rect64(r, center, half_extent) {
        Some(v) => to_solid_angle(v, ihz4),
        None => 0.0,
    }
}

/// The slope `-h_xy / h_z` of a half vector and `1 / h_z^4`, in `f64`.
#[inline(always)]
fn slope_of(h: Vec3) -> ((f64, f64), f64) {
    let ihz = 1.0 / h.z.to_f64();
    let ihz2 = ihz * ihz;
    ((-h.x.to_f64() * ihz, -h.y.to_f64() * ihz), ihz2 * ihz2)
}

/// `P22 / h_z^4` rounded to `F`, saturated at `F::MAX`.
#[inline(always)]
fn to_solid_angle(p22: f64, ihz4: f64) -> F {
    let d = F::from_f64(p22 * ihz4);
    if d.is_finite() { d } else { F::MAX }
}

/// What [`d_rect`] computes before its case analysis, branch-free (for `batch`'s lanes).
#[derive(Clone, Copy)]
pub(crate) struct RectSetup {
    /// `h` finite and above the horizon (else `d_rect` is `0`).
    live: bool,
    /// A case `d_rect` answers before the integral (zero footprint, `h_z < 1e-70`) or a NaN
    /// centre.
    special: bool,
    ihz4: f64,
    uc: f64,
    vc: f64,
    hu: f64,
    hv: f64,
    k: f64,
    /// The tiers of the two axes.
    pub(crate) tiers: (Tier, Tier),
    /// The same as [`tier_index`]es (for `batch`'s branch-free classification).
    pub(crate) tier_indices: (u8, u8),
    /// The distances of the centre from the rectangle along each axis ([`tiers`]).
    d: (f64, f64),
}

impl RectSetup {
    /// The unit-roughness rectangle of `h` and `half_extent` and its tiers.
    #[inline(always)]
    pub(crate) fn new(r: AxisAligned, h: Vec3, half_extent: Vec2) -> Self {
        let live = (h.x.abs() < F::INFINITY)
            & (h.y.abs() < F::INFINITY)
            & (h.z < F::INFINITY)
            & (h.z > 0.0);
        let special = zero_footprint(half_extent) | (h.z.to_f64() < 1e-70);
        let (center, ihz4) = slope_of(h);
        let (uc, vc, hu, hv, k) = unit_coords(r, center, half_extent);
        let nan = uc.is_nan() | vc.is_nan();
        let (uc, vc) = (uc.clamp(-BIG, BIG), vc.clamp(-BIG, BIG));
        let (iu, iv, du, dv) = tier_indices(uc, vc, hu, hv);
        Self {
            live,
            special: special | nan,
            ihz4,
            uc,
            vc,
            hu,
            hv,
            k,
            tiers: (tier_of_index(iu), tier_of_index(iv)),
            tier_indices: (iu, iv),
            d: (du, dv),
        }
    }

    /// [`d_rect`] in lane form for an element that [`mean_f`] takes through the four-edge
    /// closed form ([`edges_route`]: a long side, near enough to the peak), the edges' angles
    /// by `at2` (`batch`'s polynomial `atan2` for `y > 0`) instead of libm's: `(value, slow)`,
    /// `slow` for every element that `d_rect` takes elsewhere (the far field, the 1D closed
    /// form, the Gauss-Legendre tiers, the special cases). The value is `d_rect`'s up to the
    /// angles' error propagated through [`edges_by`] (its docs; `batch::d_rect` states the
    /// bound).
    #[inline(always)]
    pub(crate) fn closed_lane(self, at2: impl Fn(f64, f64) -> f64 + Copy) -> (F, bool) {
        let Self { uc, vc, hu, hv, .. } = self;
        let (tu, tv) = self.tiers;
        let route = edges_route(tu, tv, self.d, uc, vc, hu, hv);
        let mean = edges_by(at2, uc, vc, hu, hv);
        let v = to_solid_angle((mean * self.k).max(0.0), self.ihz4);
        let fast = route & !self.special;
        (if self.live { v } else { 0.0 }, self.live & !fast)
    }

    /// [`d_rect`] in lane form for an element whose tiers are `(tu, tv)`, both Gauss-Legendre
    /// tiers (constants at the call site: one vector loop per pair): `(value, slow)`,
    /// the value `d_rect`'s bit for bit unless `slow`. `slow` flags every element that
    /// `d_rect` does not take through that pair's Gauss-Legendre rule with its rows' shared
    /// division (the special cases, the 2 x 2 rule's overflow branch, a row's pairs beyond the
    /// shared division's range: [`gl_f_by`]) or its early zero. The same pieces as `d_rect`,
    /// composed without branches.
    ///
    /// Precondition: `self.tiers == (tu, tv)`, which the caller has established by
    /// classifying the element with this same setup's [`RectSetup::tier_indices`] (`batch`'s
    /// class of each element; debug builds assert it there). The lane does not test it again:
    /// a second evaluation of the same comparisons would cost the lane time for nothing (with
    /// the precondition the tiers are dead code in the lane). An element of another pair (`batch`'s
    /// padding of a pass, whose results it discards) gives a value of no meaning, without a
    /// panic.
    #[inline(always)]
    pub(crate) fn lane(self, tu: Tier, tv: Tier) -> (F, bool) {
        let Self { uc, vc, hu, hv, .. } = self;
        let (mean, ok) = if tu == Tier::Gl2 && tv == Tier::Gl2 {
            let (n0, p0, n1, p1) = gl2x2_rows(uc, vc, hu, hv);
            let pp = p0 * p1;
            (0.25 * (n0 * p1 + n1 * p0) / pp, pp < 1e300)
        } else {
            tensor_by::<true>(tu, tv, uc, vc, hu, hv)
        };
        let fast = ok & !self.special;
        let v = to_solid_angle((mean * self.k).max(0.0), self.ihz4);
        (if self.live { v } else { 0.0 }, self.live & !fast)
    }
}
