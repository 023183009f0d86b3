//! The box filter's Gauss-Legendre lanes in `f32` arithmetic: the `f32` build of
//! [`super::d_rect`] and [`super::d_rect_filtered`] (the `f64` build keeps `f64` lanes that
//! match the scalar path bit for bit).
//!
//! # What they compute
//! With `u_c = -h_x / (h_z a)`, `v_c = -h_y / (h_z b)`, `H_u = |s_x| / a`, `H_v = |s_y| / b`
//! (`a, b` the roughness, `s` the half extents), `D = mean(f) / (pi a b h_z^4)` over the
//! normalised rectangle, `f(u, v) = (1 + u^2 + v^2)^-2` (module docs of `filter::rect`), and
//! `mean(f)` by the tensor Gauss-Legendre rule whose tier per axis comes from `H / L`,
//! `L^2 = 1 + u_c^2 + d_v^2` (`d_v` the distance of the rectangle from `v = 0`; `v`
//! likewise) as in the scalar case analysis, with two more tiers than the scalar `f32` path:
//!
//! | rule | lane tier (`H / L` below) | worst truncation, measured |
//! |---|---|---|
//! | 2, 4, 6 points | `0.01`, `0.1`, `0.25` (the scalar `f32` tiers) | `3.1e-8`, `9.6e-9`, `1.1e-8` |
//! | 8 points | `0.4` | `1.5e-8` |
//! | 10 points | `0.5` | `6.5e-9` |
//! | the scalar path's closed forms | above | |
//!
//! The last column: the relative error of the rule for the mean of `(c^2 + x^2)^-2` over
//! `[x_c - H, x_c + H]`, worst over the centre, at the tier's upper ratio (against the
//! closed-form antiderivative in `f64`, centres from `0` to `100 c`: unit test
//! `tiers_truncation_within_the_table`; the first three are `filter::rect`'s measurements).
//! The scalar `f32` path takes its closed forms above `0.25` (four `atan2` in `f64`, about 40
//! cycles an element in the `f64` lane); with the 8- and 10-point tiers the closed forms'
//! share of the benchmark's realistic elements falls from 24 % to 11 %.
//!
//! # Scaling
//! Each node's `t = 1 + u^2 + v^2` is scaled by `sigma`, the power of two at or below
//! `1 / T`, `T = 1 + u_c^2 + v_c^2` (exact: from the exponent bits). The nodes of a
//! Gauss-Legendre tier lie within `H <= 0.5 L` of the centre on each axis, so `t / T` stays
//! in `[0.2, 2.4]` (unit test `nodes_within_the_scaling_range`) and `t sigma` in
//! `[0.1, 2.4]`; `mean(f) = sigma^2 mean((t sigma)^-2)` exactly. A row's mean is one division:
//! `sum w_k n_k / p_k` accumulated as `num / den` (`num <- num p + w n den`, `den <- den p`,
//! all terms positive), `n = s_0 + s_1`, `p = s_0 s_1` for the two nodes `s_i = (t_i sigma)^2`
//! of a symmetric pair; the two rows of a node pair of the outer axis share it while they
//! hold at most 8 pairs (`den` then within `[1e-4^8, 33^8]`, normal in `f32`). The outer axis
//! is the one with fewer nodes (the integrand is symmetric in `u` and `v`; the classification
//! swaps the axes).
//!
//! # Domain
//! The lane flags (for the scalar path) a zero footprint, `h_z < 1e-6`, `T >= 1e30`, a half
//! extent at or beyond `1e15` lobe widths, and a result outside `[1e-30, 1e37]` (so that every
//! product above is normal and nothing overflows); a non-finite `h` or `h_z <= 0` gives `0`
//! as the scalar path does.
//!
//! # Agreement (derived, first order)
//! Against the exact `D` of the same `f32` inputs, with `u = 2^-24` (half an `f32` ulp):
//! 1. **Inputs.** `u_c`, `v_c` carry at most `4 u` relative error (`1 / h_z`, the product,
//!    `1 / a` rounded, the product), `H_u`, `H_v` at most `2 u`: they move `D` by at most
//!    `sum_x |x dD/dx| e_x`, the conditioning of `D` itself (the test computes `dD/dx` per
//!    element by central differences of the `f64` scalar path).
//! 2. **Node coordinates.** A node `u_c -/+ H_u x_k` carries an absolute error of at most
//!    `2 u H_u + u |u|` (the node `x_k` rounded to `f32`, the product, the difference), which
//!    moves `u^2` by `4 u |u| H_u + 2 u u^2 <= (4.5 + 2) u t` (`|u| <= sqrt t`,
//!    `H_u <= 0.5 sqrt T <= 1.12 sqrt t`): `13 u` on `t` for both coordinates, `26 u` on `f`.
//! 3. **The rule's arithmetic.** `t` rounds three times (`3 u`), `s = t^2` then carries `7 u`,
//!    and `n / p = 1 / s_0 + 1 / s_1` with its own two roundings `9 u`. In the `num / den`
//!    recurrence over `m <= 8` pairs the longest path of a term is `2 m` roundings and `den`'s
//!    `m - 1`, with the division `3 m <= 24 u` (the `p_j` of the other pairs cancel exactly:
//!    the same rounded values divide both). The sum over at most 5 divisions `5 u`, the
//!    weights' products of two rounded weights `3 u`: `41 u`.
//! 4. **Forming `D`.** `D = ((mean k) g) g`, `g = sigma (1 / h_z)^2`: `1 / h_z` and its
//!    square `3 u`, twice through `g^2` `6 u`; `k = 1 / (pi a b)` rounded `1 u`; three
//!    products `3 u`: `10 u`.
//! 5. **Truncation.** The tiers' `3.1e-8` per axis, `6.2e-8 = 1.04 u` for both.
//!
//! In all, `|D_lane - D| <= 78 u |D|` (`4.6e-6` relative) plus the input term of 1; the
//! scalar `f32` path is within about one ulp of `D`. `tests/batch_bounds.rs`
//! (`d_rect_against_scalar_f64`) checks each element against the `f64` scalar path: worst
//! `0.12` of the bound, `11.4 u` relative. This is the price of the speed (the lanes run at
//! twice the `f64` lanes' width; figures in `docs/batch_measurements.md`).

use super::super::super::super::filter::rect::{
    GL2_X, GL4_W, GL4_X, GL6_W, GL6_X, GL8_W, GL8_X, GL10_W, GL10_X,
};
use super::super::super::super::ndf::roughness::AxisAligned;
use super::super::super::super::{F, Vec2, Vec3};
use crate::math::Real;

/// The lane tiers' upper ratios `H / L`, squared: 2, 4, 6, 8 and 10 points (module docs).
const TAU2: [f32; NT] = {
    let t = [0.01f32, 0.1, 0.25, 0.4, 0.5];
    let mut t2 = [0.0f32; NT];
    let mut k = 0;
    while k < NT {
        t2[k] = t[k] * t[k];
        k += 1;
    }
    t2
};
/// The number of lane tiers; a tier index `NT` is the scalar path's closed forms.
pub(crate) const NT: usize = 5;
/// The most symmetric node pairs of a lane rule (10 points).
const MAXP: usize = 5;
/// The most node pairs that share a division: their product `prod (t_0 t_1 sigma^2)^2` within
/// `[1e-4^8, 33^8]` (`t sigma` in `[0.1, 2.4]`), normal in `f32` (module docs, scaling).
const PER_DIVISION: usize = 8;

/// The rules by tier, `f64`: nodes (positive halves) and halved weights (unused entries `0`).
const RULES: [([f64; MAXP], [f64; MAXP]); NT] = {
    const fn pad<const N: usize>(a: [f64; N]) -> [f64; MAXP] {
        let mut t = [0.0; MAXP];
        let mut k = 0;
        while k < N {
            t[k] = a[k];
            k += 1;
        }
        t
    }
    [
        (pad([GL2_X]), pad([0.5])),
        (pad(GL4_X), pad(GL4_W)),
        (pad(GL6_X), pad(GL6_W)),
        (pad(GL8_X), pad(GL8_W)),
        (pad(GL10_X), pad(GL10_W)),
    ]
};
/// [`RULES`]' nodes in `f32`.
const XS: [[f32; MAXP]; NT] = rounded(0);
/// [`RULES`]' weights in `f32`.
const WS: [[f32; MAXP]; NT] = rounded(1);

/// [`RULES`]' nodes (`which = 0`) or weights (`1`) rounded to `f32`.
const fn rounded(which: usize) -> [[f32; MAXP]; NT] {
    let mut t = [[0.0f32; MAXP]; NT];
    let mut i = 0;
    while i < NT {
        let mut k = 0;
        while k < MAXP {
            t[i][k] = if which == 0 {
                RULES[i].0[k]
            } else {
                RULES[i].1[k]
            } as f32;
            k += 1;
        }
        i += 1;
    }
    t
}

/// The number of symmetric node pairs of tier `t` (`1` to `5`).
const fn pairs(t: usize) -> usize {
    t + 1
}

/// `$body` for `$k` from `0` to `$n - 1`, `$n <= 5` a constant, written out (the lanes' loops
/// must be straight-line code for the element loop to vectorise; LLVM does not unroll the
/// nested loops of the larger tiers).
macro_rules! unroll5 {
    ($n:expr, |$k:ident| $body:block) => {{
        let n: usize = $n;
        debug_assert!(n <= MAXP);
        unroll5!(@ n, $k, $body, 0 1 2 3 4);
    }};
    (@ $n:ident, $k:ident, $body:block, $($i:literal)*) => {$(
        if $i < $n {
            let $k: usize = $i;
            $body
        }
    )*};
}

/// One row of the tensor rule: the row at `u` of tier `J` along `v` (centre `vc`, half side
/// `hv`), its pairs weighted by `w` times their own weights, accumulated into
/// `(num, den)` (module docs: `num <- num p + w n den`, `den <- den p`).
#[inline(always)]
fn row<const J: usize>(
    u: f32,
    vc: f32,
    hv: f32,
    sigma: f32,
    w: f32,
    acc: (f32, f32),
) -> (f32, f32) {
    let (mut num, mut den) = acc;
    // Scaled by the power of two `sigma` before the sum (exact): `t sigma = q sigma +
    // v^2 sigma`, the second term shared by every row.
    let q = (1.0 + u * u) * sigma;
    unroll5!(pairs(J), |j| {
        let b = hv * XS[J][j];
        let (v0, v1) = (vc - b, vc + b);
        let t0 = q + (v0 * v0) * sigma;
        let t1 = q + (v1 * v1) * sigma;
        let (s0, s1) = (t0 * t0, t1 * t1);
        let (n, p) = (s0 + s1, s0 * s1);
        num = num * p + (w * WS[J][j]) * n * den;
        den *= p;
    });
    (num, den)
}

/// The roughness' constants, once per call: `1 / a`, `1 / b`, `1 / (pi a b)` rounded to `f32`.
#[derive(Clone, Copy)]
pub(crate) struct Consts {
    ia: f32,
    ib: f32,
    k: f32,
}

impl Consts {
    /// The constants of `r` (computed in `f64`, rounded once).
    #[inline(always)]
    pub(crate) fn new(r: &AxisAligned) -> Self {
        let alpha = r.alpha();
        let (a, b) = (alpha.x.to_f64(), alpha.y.to_f64());
        Self {
            ia: (1.0 / a) as f32,
            ib: (1.0 / b) as f32,
            k: (1.0 / (core::f64::consts::PI * a * b)) as f32,
        }
    }
}

/// An element's normalised rectangle and tiers in `f32` (module docs), branch-free: what the
/// classification stores ([`Setup::cols`]) and the lanes read.
#[derive(Clone, Copy)]
pub(crate) struct Setup {
    /// `(u_c, H_u, v_c, H_v)`, the axes swapped where the first has the larger tier (the
    /// lanes' outer axis is the one with fewer nodes; `f` is symmetric).
    rect: [f32; 4],
    /// `(1 / h_z)^2`; `0` for a non-finite or sub-horizon `h` (the result `0`), `-1` outside
    /// the lanes' domain (module docs: flagged).
    g: f32,
    /// The tier indices `(min, max)` of the two axes (`NT` for the closed forms).
    pub(crate) tiers: (u8, u8),
}

/// The tier index of an axis: the number of [`TAU2`] thresholds `H^2` does not stay below
/// (`NT` for the closed forms; a NaN counts as beyond every threshold).
#[inline(always)]
fn tier_index(h2: f32, l2: f32) -> u8 {
    let mut k = 0u8;
    for t in TAU2 {
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        let beyond = !(h2 < t * l2);
        k += u8::from(beyond);
    }
    k
}

impl Setup {
    /// The setup of the unit half vector `h` and the half extents `s` (in `F`, rounded to
    /// `f32` where `F` is `f64`: the lanes run in the `f32` build only).
    #[inline(always)]
    pub(crate) fn new(c: Consts, h: Vec3, s: Vec2) -> Self {
        let f = |x: F| x.to_f64() as f32;
        let (hx, hy, hz, sx, sy) = (f(h.x), f(h.y), f(h.z), f(s.x), f(s.y));
        let live = (hx.abs() < f32::INFINITY)
            & (hy.abs() < f32::INFINITY)
            & (hz < f32::INFINITY)
            & (hz > 0.0);
        let iz = 1.0 / hz;
        let uc = -(hx * iz) * c.ia;
        let vc = -(hy * iz) * c.ib;
        // NaN half extents count as `0` (as the scalar path).
        let hu = (sx.abs() * c.ia).max(0.0);
        let hv = (sy.abs() * c.ib).max(0.0);
        let t0 = 1.0 + uc * uc + vc * vc;
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        // Both half extents zero or NaN: the scalar path's unfiltered `D`, bit for bit.
        let special = (!(sx.abs() > 0.0) & !(sy.abs() > 0.0))
            | !(hz >= 1e-6)
            | !(t0 < 1e30)
            | !(hu < 1e15)
            | !(hv < 1e15);
        let du = (uc.abs() - hu).max(0.0);
        let dv = (vc.abs() - hv).max(0.0);
        let lu2 = 1.0 + uc * uc + dv * dv;
        let lv2 = 1.0 + vc * vc + du * du;
        let (iu, iv) = (tier_index(hu * hu, lu2), tier_index(hv * hv, lv2));
        let g = if !live {
            0.0
        } else if special {
            -1.0
        } else {
            iz * iz
        };
        Self {
            rect: if iu <= iv {
                [uc, hu, vc, hv]
            } else {
                [vc, hv, uc, hu]
            },
            g,
            tiers: (iu.min(iv), iu.max(iv)),
        }
    }

    /// What the lanes read: `(u_c, H_u, v_c, H_v, g)` (the fields).
    #[inline(always)]
    pub(crate) fn cols(self) -> [f32; 5] {
        let [a, b, c, d] = self.rect;
        [a, b, c, d, self.g]
    }
}

/// The lane of the tier pair `(I, J)`, `I <= J < NT`, on [`Setup::cols`] of an element whose
/// tiers are `(I, J)` (the caller's classification): `D` by the tensor rule of the module
/// docs, `(value, slow)`: `slow` for the elements outside the domain (module docs), `0`
/// without `slow` for a non-finite or sub-horizon `h`.
#[inline(always)]
pub(crate) fn lane<const I: usize, const J: usize>(c: Consts, cols: [f32; 5]) -> (F, bool) {
    let [uc, hu, vc, hv, iz2] = cols;
    // sigma: the power of two at or below 1 / t0 (t0 >= 1, below 1e30 where not flagged:
    // exponent bits in [127, 226], so 254 - e is a normal exponent).
    let t0 = 1.0 + uc * uc + vc * vc;
    let e = (t0.to_bits() >> 23) & 0xff;
    let sigma = f32::from_bits((254u32.wrapping_sub(e) & 0xff) << 23);
    let mut acc = 0.0f32;
    unroll5!(pairs(I), |k| {
        let a = hu * XS[I][k];
        let w = WS[I][k];
        if 2 * pairs(J) <= PER_DIVISION {
            // Both rows of the node pair share a division.
            let (num, den) = row::<J>(uc - a, vc, hv, sigma, w, (0.0, 1.0));
            let (num, den) = row::<J>(uc + a, vc, hv, sigma, w, (num, den));
            acc += num / den;
        } else {
            let (num, den) = row::<J>(uc - a, vc, hv, sigma, w, (0.0, 1.0));
            acc += num / den;
            let (num, den) = row::<J>(uc + a, vc, hv, sigma, w, (0.0, 1.0));
            acc += num / den;
        }
    });
    let g = sigma * iz2;
    let d = ((acc * c.k) * g) * g;
    let fast = (iz2 > 0.0) & (1e-30..1e37).contains(&d);
    let live = iz2 != 0.0;
    let v = if live { F::from_f64(d as f64) } else { 0.0 };
    (v, live & !fast)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule integrates the monomials it should exactly: the mean of `x^(2m)` over
    /// `[-1, 1]` is `1 / (2m + 1)` for `2m <= 2n - 1` (`n` points), in `f64` (the rules'
    /// `f64` constants; their `f32` roundings are part of the lanes' stated bound).
    #[test]
    fn rules_integrate_polynomials() {
        for (t, (xs, ws)) in RULES.iter().enumerate() {
            let n = 2 * pairs(t);
            for m in 0..n {
                let mean: f64 = (0..pairs(t))
                    .map(|k| 2.0 * ws[k] * xs[k].powi(2 * m as i32))
                    .sum();
                let want = 1.0 / (2 * m + 1) as f64;
                assert!(
                    (mean - want).abs() <= 1e-15,
                    "{n} points, x^{}: {mean} vs {want}",
                    2 * m
                );
            }
        }
    }

    /// The truncation error of each rule at its tier's upper ratio stays within the module
    /// docs' table (`3.1e-8`, the scalar `f32` tiers' worst): the relative error of the mean
    /// of `(1 + x^2)^-2` over `[x_c - H, x_c + H]`, `H = tau L`, `L = sqrt(1 + x_c^2)` the
    /// distance to the poles, over centres from `0` to `100`, against the antiderivative
    /// `x / (2 (1 + x^2)) + atan(x) / 2` in `f64` (its cancellation, below `1e-12` relative
    /// for these wide intervals, far below the tolerance).
    #[test]
    fn tiers_truncation_within_the_table() {
        let prim = |x: f64| x / (2.0 * (1.0 + x * x)) + 0.5 * x.atan();
        let taus = [0.01f64, 0.1, 0.25, 0.4, 0.5];
        for (t, &tau) in taus.iter().enumerate() {
            let (xs, ws) = RULES[t];
            let mut worst = 0.0f64;
            for k in 0..=4000 {
                let xc = 100.0 * (k as f64 / 4000.0).powi(3);
                let h = tau * (1.0 + xc * xc).sqrt();
                let exact = (prim(xc + h) - prim(xc - h)) / (2.0 * h);
                let f = |x: f64| 1.0 / ((1.0 + x * x) * (1.0 + x * x));
                let q: f64 = (0..pairs(t))
                    .map(|j| ws[j] * (f(xc - h * xs[j]) + f(xc + h * xs[j])))
                    .sum();
                worst = worst.max((q - exact).abs() / exact);
            }
            // The 2-point tier's worst is its measured `3.1e-8` (module docs of
            // `filter::rect`); the tolerance adds the reference's cancellation at `0.01`.
            let tol = if t == 0 { 4e-8 } else { 3.1e-8 };
            assert!(worst <= tol, "tier {t}: {worst:e}");
        }
    }

    /// The scaling's premise (module docs): at every node of a Gauss-Legendre tier,
    /// `t = 1 + u^2 + v^2` is within `[0.2, 2.4] T`, `T = 1 + u_c^2 + v_c^2`, so that
    /// `t sigma` lies in `[0.1, 2.4]`. Rectangles at the largest tier's limit (`H = 0.5 L`
    /// on both axes, solved for self-consistently since `L` depends on the other side) and
    /// inside it, centres from `0` to `1e6` on each axis.
    #[test]
    fn nodes_within_the_scaling_range() {
        let mut rng = crate::testing::rng::SplitMix64(0x5CA1E);
        let (mut lo, mut hi) = (f64::MAX, 0.0f64);
        for _ in 0..200_000 {
            let s = 10f64.powf(rng.uniform() * 9.0 - 3.0);
            let pick = |r: &mut crate::testing::rng::SplitMix64| {
                let z = [0.0, 1.0, 1.0, 0.01][(r.uniform() * 4.0) as usize];
                (2.0 * r.uniform() - 1.0) * s * z
            };
            let (uc, vc) = (pick(&mut rng), pick(&mut rng));
            let (fu, fv) = (rng.uniform(), rng.uniform());
            let (mut hu, mut hv) = (0.0f64, 0.0f64);
            for _ in 0..60 {
                let du = (uc.abs() - hu).max(0.0);
                let dv = (vc.abs() - hv).max(0.0);
                hu = 0.5 * fu * (1.0 + uc * uc + dv * dv).sqrt();
                hv = 0.5 * fv * (1.0 + vc * vc + du * du).sqrt();
            }
            let t0 = 1.0 + uc * uc + vc * vc;
            for a in [-hu, hu] {
                for b in [-hv, hv] {
                    let r = (1.0 + (uc + a).powi(2) + (vc + b).powi(2)) / t0;
                    lo = lo.min(r);
                    hi = hi.max(r);
                }
            }
        }
        assert!(lo >= 0.2 && hi <= 2.4, "t / T in [{lo}, {hi}]");
    }
}
