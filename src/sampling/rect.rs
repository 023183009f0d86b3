//! Exact importance sampling of the box-filtered GGX lobe ([`RectFilteredGgx`]; its density
//! [`d_rect`], its [`lambda_rect`]): the NDF `D(m) m_z` and the distribution of visible normals, with
//! their pdfs.
//!
//! # `D(m) m_z`
//! The lobe's slope is `s = g + delta` with `g` axis-aligned GGX and `delta` uniform on the box
//! `[-H_x, H_x] x [-H_y, H_y]`: its density is the box mean of `P22`, i.e. [`p22_rect`](super::super::filter::rect::p22_rect)
//! at `s`, and `D(m) m_z dm = P(s) ds`. So a GGX slope (the unit-roughness sample of
//! [`NdfSampling::sample_normal`] for `Ggx`, warped by `alpha`) plus a uniform offset is an
//! exact sample. **Four uniform numbers**: `u` for the GGX slope (as `NdfSampling`) and `u_box`
//! for the offset, each pair keeping its stratification. Two would need the inverse of the
//! lobe's conditional CDFs, which have no closed form (the `x`-marginal does, but the
//! conditional in `y` mixes GGX's `y | x` law over the box): a root find per dimension. So the
//! box lobe cannot implement [`NdfSampling`]'s two-number signature exactly without root
//! finding; these functions take the four numbers.
//!
//! # Visible normals
//! `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` (Heitz 2014 eq. 16) with `G1 = 1 / (1 + Lambda)`,
//! `Lambda` = [`lambda_rect`]. In slopes the visible density is proportional to
//! `(wo_z - wo_xy.s)^+ P(s) = E_delta[(wo'_z - wo_xy.g)^+ P_GGX(g)]` with
//! `wo'_z = wo_z - wo_xy.delta`: for a fixed offset, the visible slopes of GGX seen from the
//! sheared direction `wo' = (wo_xy, wo'_z)` (which may point below the horizon), whose total
//! weight is `|wo_xy| psi(u.delta - mu)` (the projected area `mu + E[(q - mu')^+]` of the
//! shifted GGX, `psi` of [`lambda_rect`]'s module docs, `u`, `mu` as there). So:
//! 1. draw the offset `delta` with density proportional to `psi(u.delta - mu)` on the box. In
//!    units of the projected roughness `a` the weight depends on `v = v_l + v_s`,
//!    `v_i = u_i delta_i / a` uniform on `[-k_i, k_i]`: `v_l` (the longer projected side) by
//!    inverting its marginal CDF, the mean over `v_s` of `Psi_1` differences (written without
//!    cancellation as in `lambda_rect`), then `v_s` given `v_l` by inverting
//!    `Psi_1(v_s + v_l - m) - Psi_1(-k_s + v_l - m)`; both by Newton steps kept in a bisection
//!    bracket, to `4e-16` of the larger of the sample and the interval (`u_box` gives the two
//!    numbers; an axis whose `u_i` is `0` has a uniform offset from its number);
//! 2. draw a visible normal of GGX seen from `wo'` by the spherical caps of Dupuy and Benyoub
//!    2023 (listing 3), which hold for a view below the horizon too (the cap `z >= -wi_z` is then
//!    the part above `|wi_z|`): `n = c + wi`, `c` uniform on the cap, in the unit-roughness
//!    space of the axis-aligned stretch (`u` gives the two numbers);
//! 3. the sample is the normal of the slope `g + delta`.
//!
//! This is exact up to the root finding (the marginal of step 1 is the one whose total is
//! `m (1 + Lambda)`, checked in the tests against `lambda_rect`) and costs two Newton solves
//! (each a few evaluations of `Psi_1` means), against none for plain GGX.
//!
//! # Out-of-domain input
//! As [`NdfSampling`]: `u` components clamped to `[0, 1 - eps/2]`, NaN to `0`; the visible
//! sampler returns `None` for `wo_z <= 0` or non-finite `wo`; half extents sanitised as in
//! [`p22_rect`](super::super::filter::rect::p22_rect) (magnitude, NaN as `0`, at most `1e60 alpha`). Zero half extents give
//! GGX's own samplers bit for bit. A sampled `m` is a finite unit vector with `m_z > 0` (in `f32`
//! a slope beyond `1e38` has its `m_z` rounded up to the smallest normal float), and the visible
//! sample has `wo.m > 0` (should rounding break it, the centre of the sheared GGX is used, as
//! the GGX sampler does).

use super::super::filter::RectFilteredGgx;
use super::super::filter::rect::{
    BIG, Tier, d_rect, gl_of, lambda_rect, mean_psi, mean_psi1, psi, psi1_diff, scaled, tier,
};
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::AxisAligned;
use super::NdfSampling;
use super::{F, Vec2, Vec3};
use crate::math::{self as m, Real};

const PI64: f64 = core::f64::consts::PI;

/// Clamps a uniform number into `[0, 1 - eps/2]` of `F` (NaN to `0`), as `f64`.
#[inline]
fn uniform_f64(u: F) -> f64 {
    const ONE_MINUS_EPS: F = 1.0 - 0.5 * F::EPSILON;
    (if u >= 0.0 { u.min(ONE_MINUS_EPS) } else { 0.0 }).to_f64()
}

/// A half extent sanitised as [`p22_rect`](super::super::filter::rect::p22_rect) does, in slope units: `|h|`, NaN as `0`, at
/// most `1e60 alpha`.
#[inline]
fn sanitized_half_extent(h: F, alpha: f64) -> f64 {
    let v = h.to_f64().abs();
    if v.is_nan() { 0.0 } else { v.min(BIG * alpha) }
}

/// The unit normal of the slope `s = -m_xy / m_z`, scaled first so that no square overflows;
/// `m_z` is kept positive when it underflows in `F`.
#[inline]
fn normal_of_slope(sx: f64, sy: f64) -> Vec3 {
    let big = sx.abs().max(sy.abs()).max(1.0);
    let (x, y, z) = (-sx / big, -sy / big, 1.0 / big);
    let n = m::sqrt(x * x + y * y + z * z);
    let mz = F::from_f64(z / n);
    Vec3::new(
        F::from_f64(x / n),
        F::from_f64(y / n),
        if mz > 0.0 { mz } else { F::MIN_POSITIVE },
    )
}

/// Samples a unit micronormal `m` of the box-filtered GGX lobe with density `D(m) m_z` per
/// steradian, `D` = [`d_rect`] (module docs): the GGX slope of `u` (as
/// [`NdfSampling::sample_normal`]) plus the offset `(2 u_box - 1) H` uniform in the box. Exact;
/// four uniform numbers in `[0, 1)`. Zero half extents: GGX's sampler bit for bit.
#[inline]
pub fn sample_normal_rect(r: AxisAligned, half_extent: Vec2, u: Vec2, u_box: Vec2) -> Vec3 {
    let alpha = r.alpha();
    let (ax, ay) = (alpha.x.to_f64(), alpha.y.to_f64());
    let (hx, hy) = (
        sanitized_half_extent(half_extent.x, ax),
        sanitized_half_extent(half_extent.y, ay),
    );
    if hx == 0.0 && hy == 0.0 {
        return Ggx::new(r).sample_normal(u);
    }
    // Unit-roughness GGX: |t|^2 = u1 / (1 - u1), phi = 2 pi u2; slope -alpha t (the sign of
    // the GGX sampler's normal (sqrt(u1) cos phi, sqrt(u1) sin phi, sqrt(1 - u1))).
    let (u1, u2) = (uniform_f64(u.x), uniform_f64(u.y));
    let rad = m::sqrt(u1 / (1.0 - u1));
    let phi = 2.0 * PI64 * u2;
    let (gx, gy) = (-ax * rad * m::cos(phi), -ay * rad * m::sin(phi));
    let dx = (2.0 * uniform_f64(u_box.x) - 1.0) * hx;
    let dy = (2.0 * uniform_f64(u_box.y) - 1.0) * hy;
    normal_of_slope(gx + dx, gy + dy)
}

/// The density of [`sample_normal_rect`], `D(m) m_z` per steradian with `D` =
/// [`d_rect`], for a unit `m`; `0` for `m_z <= 0` and non-finite `m`.
#[inline]
pub fn normal_pdf_rect(r: AxisAligned, half_extent: Vec2, m: Vec3) -> F {
    if !m.is_finite() || m.z <= 0.0 {
        return 0.0;
    }
    d_rect(r, m, half_extent) * m.z
}

/// The integral over `[t0, t1]` (`w = t1 - t0 >= 0` given exactly) of the mean of `psi` over
/// `[y - k, y + k]`: the mean over `x` in `[-k, k]` of `Psi_1(t1 - x) - Psi_1(t0 - x)`, by
/// the Gauss-Legendre rule of the positive differences while `k` is short next to the branch
/// points (`L^2 = 1 + min(t0^2, t1^2)`), else the difference of the means of `Psi_1`.
#[inline]
fn mean_psi1_diff(t0: f64, t1: f64, w: f64, k: f64) -> f64 {
    if k == 0.0 {
        return psi1_diff(t0, t1, w);
    }
    let near = t0.abs().min(t1.abs());
    match tier(k * k, m::mul_add(near, near, 1.0)) {
        Tier::Closed => mean_psi1(t1, k) - mean_psi1(t0, k),
        t => gl_of(t, 0.0, k, |x| psi1_diff(t0 - x, t1 - x, w)),
    }
}

/// The `x` in `[lo, hi]` where the increasing `f` (returning value and derivative) reaches
/// `y`, `f(lo) <= y <= f(hi)`: Newton steps kept inside a bisection bracket, until a step or
/// the bracket is below `4e-16` of the larger of `|x|` and the initial bracket (at most 100
/// evaluations; bisection alone needs fewer than that to reach the tolerance).
fn invert_increasing(mut lo: f64, mut hi: f64, y: f64, f: impl Fn(f64) -> (f64, f64)) -> f64 {
    let width = hi - lo;
    let mut x = 0.5 * (lo + hi);
    for _ in 0..100 {
        let (fx, dfx) = f(x);
        let r = fx - y;
        if r == 0.0 {
            return x;
        }
        if r > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let tol = 4e-16 * x.abs().max(width);
        let mut nx = x - r / dfx;
        if !(nx > lo && nx < hi) {
            nx = 0.5 * (lo + hi);
        }
        if (nx - x).abs() <= tol || hi - lo <= tol {
            return nx;
        }
        x = nx;
    }
    x
}

/// The offsets `(v_l, v_s)` (module docs, step 1), `v_i` in `[-k_i, k_i]`, from two uniform
/// numbers; `k_l >= k_s >= 0`, `k_l > 0`.
fn sample_offsets(m: f64, kl: f64, ks: f64, ul: f64, us: f64) -> (f64, f64) {
    // v_l: the marginal CDF is cum(-k_l - m, v - m, k_s) / cum(-k_l - m, k_l - m, k_s), its
    // derivative the mean of psi over [v - m - k_s, v - m + k_s].
    let t0 = -kl - m;
    let total = mean_psi1_diff(t0, kl - m, 2.0 * kl, ks);
    let vl = invert_increasing(-kl, kl, ul * total, |v| {
        let c = mean_psi1_diff(t0, v - m, v + kl, ks);
        let d = if ks == 0.0 {
            psi(v - m)
        } else {
            mean_psi(v - m - ks, v - m + ks, 2.0 * ks)
        };
        (c, d)
    });
    if ks == 0.0 {
        return (vl, 0.0);
    }
    // v_s given v_l: density psi(v_s + v_l - m) on [-k_s, k_s].
    let c = vl - m;
    let total = psi1_diff(c - ks, c + ks, 2.0 * ks);
    let vs = invert_increasing(-ks, ks, us * total, |v| {
        (psi1_diff(c - ks, c + v, v + ks), psi(c + v))
    });
    (vl, vs)
}

/// Samples a visible micronormal of the box-filtered GGX lobe seen from `wo`, with density
/// `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo_z` per steradian, `D` = [`d_rect`],
/// `G1 = 1 / (1 + Lambda)`, `Lambda` = [`lambda_rect`] (module docs: the offset by its
/// projected-area weight, then GGX's visible normals seen from the sheared direction). Four
/// uniform numbers: `u_box` for the offset, `u` for the GGX visible normal. `None` if
/// `wo_z <= 0` or `wo` is not finite. Zero half extents: GGX's sampler bit for bit (which
/// also returns `None` for a view within the float range of grazing, module `sampling`).
/// Should rounding put both the sample and its fallback, the sheared cap's pole, on or behind
/// `wo`'s horizon, the geometric normal `(0, 0, 1)` is returned (a rounding corner: a box of
/// huge extent beside a view near grazing).
pub fn sample_visible_normal_rect(
    r: AxisAligned,
    half_extent: Vec2,
    wo: Vec3,
    u: Vec2,
    u_box: Vec2,
) -> Option<Vec3> {
    if !(wo.is_finite() && wo.z > 0.0) {
        return None;
    }
    let alpha = r.alpha();
    let (ax, ay) = (alpha.x.to_f64(), alpha.y.to_f64());
    let (hx, hy) = (
        sanitized_half_extent(half_extent.x, ax),
        sanitized_half_extent(half_extent.y, ay),
    );
    if hx == 0.0 && hy == 0.0 {
        return Ggx::new(r).sample_visible_normal(wo, u);
    }
    // wo scaled by a power of two into [2^-400, 2^400] (homogeneous; no overflow below).
    let (wx, wy, wz) = scaled(wo);
    let l = m::hypot(wx, wy);
    let (bx, by) = (uniform_f64(u_box.x), uniform_f64(u_box.y));
    let uniform = ((2.0 * bx - 1.0) * hx, (2.0 * by - 1.0) * hy);
    let (dx, dy) = if l == 0.0 {
        // Normal incidence: every offset sees the same projected area.
        uniform
    } else {
        let (ux, uy) = (wx / l, wy / l);
        let a = m::hypot(ux * ax, uy * ay);
        let mu = wz / l / a;
        let (kx, ky) = ((ux * hx).abs() / a, (uy * hy).abs() / a);
        if (kx == 0.0 && ky == 0.0) || mu > 1e100 {
            // The box projects to a point on u: the weight is constant. Or the view is so
            // close to the normal that the weight m - v + psi(m - v) varies by less than
            // k / m <= 1e-40 over the box (k <= 1e60): uniform (and no square of m overflows).
            return visible_with_offset((wx, wy, wz), (ax, ay), uniform, u);
        }
        // An axis with u_i = 0 (or H_i = 0) does not enter the weight: uniform offset.
        let free = |k: f64, ui: f64, h: f64, b: f64, v: f64| {
            if k == 0.0 {
                (2.0 * b - 1.0) * h
            } else {
                a * v / ui
            }
        };
        if kx >= ky {
            let (vx, vy) = sample_offsets(mu, kx, ky, bx, by);
            (free(kx, ux, hx, bx, vx), free(ky, uy, hy, by, vy))
        } else {
            let (vy, vx) = sample_offsets(mu, ky, kx, by, bx);
            (free(kx, ux, hx, bx, vx), free(ky, uy, hy, by, vy))
        }
    };
    visible_with_offset((wx, wy, wz), (ax, ay), (dx, dy), u)
}

/// Step 2 and 3 of the visible sampler (module docs) for the offset `(dx, dy)`: a GGX visible
/// normal seen from the sheared view, shifted by the offset. `(wx, wy, wz)` is `wo` scaled by
/// a power of two.
fn visible_with_offset(
    (wx, wy, wz): (f64, f64, f64),
    (ax, ay): (f64, f64),
    (dx, dy): (f64, f64),
    u: Vec2,
) -> Option<Vec3> {
    // GGX visible normal seen from wo' = (wo_xy, wo_z - wo_xy.delta) in the unit-roughness
    // space of the stretch diag(alpha): wi = normalize(alpha_x wo_x, alpha_y wo_y, wo'_z).
    let wz_shear = wz - (wx * dx + wy * dy);
    let (sx, sy) = (ax * wx, ay * wy);
    let norm = m::sqrt(sx * sx + sy * sy + wz_shear * wz_shear);
    let wi = (sx / norm, sy / norm, wz_shear / norm);
    // Spherical cap (Dupuy and Benyoub 2023, listing 3): c uniform on z >= -wi_z, n = c + wi,
    // written so that neither n_z = (1 - u_y)(1 + wi_z) nor 1 - c_z = u_y (1 + wi_z) cancels.
    let (u1, u2) = (uniform_f64(u.x), uniform_f64(u.y));
    let one_plus = if wi.2 < -0.5 {
        (wi.0 * wi.0 + wi.1 * wi.1) / (1.0 - wi.2)
    } else {
        1.0 + wi.2
    };
    let nz = (1.0 - u2) * one_plus;
    let cz = nz - wi.2;
    let sin_theta = m::sqrt((u2 * one_plus * (1.0 + cz)).max(0.0));
    let phi = 2.0 * PI64 * u1;
    let (nx, ny) = (
        sin_theta * m::cos(phi) + wi.0,
        sin_theta * m::sin(phi) + wi.1,
    );
    // Back to roughness alpha: the GGX slope -(alpha_x n_x, alpha_y n_y) / n_z, then + delta.
    let sample =
        |nx: f64, ny: f64, nz: f64| normal_of_slope(-ax * nx / nz + dx, -ay * ny / nz + dy);
    // wo.m > 0, in f64 with the scaled wo: the product with a huge or tiny wo must not
    // underflow (as GGX's sampler checks with a normalised wo).
    let visible = |m: Vec3| {
        m.is_finite()
            && m.z > 0.0
            && wx * m.x.to_f64() + wy * m.y.to_f64() + wz * m.z.to_f64() > 0.0
    };
    let mm = sample(nx, ny, nz);
    if visible(mm) {
        return Some(mm);
    }
    // Rounding broke wo.m > 0 (u on the rim of the cap): the cap's pole c = (0, 0, 1), which
    // is on every cap, gives n = (wi_x, wi_y, 1 + wi_z) with n_z > 0 and wi.n = 1 + wi_z > 0.
    let c = sample(wi.0, wi.1, one_plus);
    if visible(c) {
        return Some(c);
    }
    // Rounding broke that too (a box of huge extent beside a view near grazing, in `f32`:
    // the pole's slope is `delta` itself, whose normal rounds onto wo's horizon; found by
    // fuzzing): the geometric normal, visible for every `wo_z > 0` and of positive density.
    let n = Vec3::new(0.0, 0.0, 1.0);
    visible(n).then_some(n)
}

/// The density of [`sample_visible_normal_rect`],
/// `D_wo(m) = max(0, wo.m) D(m) / (wo_z (1 + Lambda(wo)))` per steradian for a unit `m`, with
/// `D` = [`d_rect`] and `Lambda` = [`lambda_rect`]. `0` for `wo_z <= 0`,
/// `wo.m <= 0`, `m_z <= 0` or non-finite input.
#[inline]
pub fn visible_normal_pdf_rect(r: AxisAligned, half_extent: Vec2, wo: Vec3, m: Vec3) -> F {
    if !(wo.is_finite() && m.is_finite() && wo.z > 0.0 && m.z > 0.0) {
        return 0.0;
    }
    let wom = wo.dot(m);
    if wom.is_nan() || wom <= 0.0 {
        return 0.0;
    }
    let v = wom * d_rect(r, m, half_extent) / (wo.z * (1.0 + lambda_rect(r, half_extent, wo)));
    if v.is_finite() { v } else { 0.0 }
}

/// The box lobe's exact samplers (four uniform numbers, see the module docs) and their pdfs.
impl RectFilteredGgx {
    /// A micronormal with density `D(m) m_z` ([`sample_normal_rect`]: the GGX slope of
    /// `u` plus the offset of `u_box` in the box). Exact.
    #[inline]
    pub fn sample_normal(&self, u: Vec2, u_box: Vec2) -> Vec3 {
        sample_normal_rect(self.roughness, self.half_extent, u, u_box)
    }

    /// The density `D(m) m_z` of [`RectFilteredGgx::sample_normal`] per steradian.
    #[inline]
    pub fn normal_pdf(&self, m: Vec3) -> F {
        normal_pdf_rect(self.roughness, self.half_extent, m)
    }

    /// A visible micronormal seen from `wo`, density `G1(wo) max(0, wo.m) D(m) / wo_z`
    /// ([`sample_visible_normal_rect`]). Exact; `None` for `wo_z <= 0` or non-finite
    /// `wo`.
    #[inline]
    pub fn sample_visible_normal(&self, wo: Vec3, u: Vec2, u_box: Vec2) -> Option<Vec3> {
        sample_visible_normal_rect(self.roughness, self.half_extent, wo, u, u_box)
    }

    /// The density of [`RectFilteredGgx::sample_visible_normal`] per steradian.
    #[inline]
    pub fn visible_normal_pdf(&self, wo: Vec3, m: Vec3) -> F {
        visible_normal_pdf_rect(self.roughness, self.half_extent, wo, m)
    }
}
