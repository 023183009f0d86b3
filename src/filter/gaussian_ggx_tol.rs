//! The reduced-accuracy rules of the exact Gaussian-filtered GGX ([`super::Tolerance`]
//! settings other than `Full`): the far-tail series where its proven remainder allows, else
//! the trapezoid rule in `t = ln w` with a wider step, a looser truncation and a later first
//! node. The derivations and bounds are in the module docs of `gaussian_ggx.rs` ("Tolerance
//! settings"); the node loop and the far-tail series are those of `gaussian_ggx_quad.rs`.

use super::F;
use super::exp_poly::{exp_f64, exp_poly};

use super::gaussian_ggx_quad::{ceil_pos, far_tail, ln_upper, sum_tree};
use super::tolerance::Tolerance;
use crate::math::{self as m, Real};

/// Nodes per chunk of the trapezoid loop (one `f32` SIMD vector of the baseline `x86-64`: the
/// truncation test every 4 nodes, the rules stopping after 8 to 16 nodes).
const CH: usize = 4;
/// Length of the node tables (the longest, for the smallest step; a rule uses `len`).
const NR: usize = 144;

/// One reduced setting's constants (module docs of `gaussian_ggx.rs`, "Tolerance settings").
pub(super) struct Rule {
    /// Far-tail switch: the series where `2 l1 (far + 12 ln(1 + q)) <= 1 + q`.
    far: f64,
    /// Trapezoid step in `t = ln w`.
    h: f64,
    /// Relative truncation tolerance at the top.
    eps_t: f64,
    /// The first node lies at or below `w = y_lo / (1 + q + 2 l1)`.
    y_lo: f64,
    /// `1 / (e^((n + 2) h) - 1)`, `n < 4`: the series below the first node.
    geom: [f64; 4],
    /// Nodes used of the tables: `e^(k h)` stays finite in `f32` (`len h <= 88`), a multiple
    /// of [`CH`].
    len: usize,
    /// `e^(k h)` in `F`.
    ratio: [F; NR],
    /// `2 k h` in `F`.
    log2ratio: [F; NR],
    /// `e^(-k h)` in `f64`.
    inv_ratio: [f64; NR],
}

/// The rule of step `h` (`e^h` given to 17 digits: no `exp` in a const context).
const fn rule(h: f64, exp_h: f64, far: f64, eps_t: f64, y_lo: f64) -> Rule {
    let mut ratio = [0.0; NR];
    let mut log2ratio = [0.0; NR];
    let mut inv_ratio = [0.0; NR];
    let mut v = 1.0f64;
    let mut k = 0;
    while k < NR {
        ratio[k] = v as F;
        log2ratio[k] = (2.0 * h * k as f64) as F;
        inv_ratio[k] = exp_f64(-h * k as f64);
        v *= exp_h;
        k += 1;
    }
    let mut geom = [0.0; 4];
    let mut e = exp_h * exp_h;
    let mut n = 0;
    while n < 4 {
        geom[n] = 1.0 / (e - 1.0);
        e *= exp_h;
        n += 1;
    }
    let len = ((88.0 / h) as usize / CH) * CH;
    Rule {
        far,
        h,
        eps_t,
        y_lo,
        geom,
        len: if len < NR { len } else { NR },
        ratio,
        log2ratio,
        inv_ratio,
    }
}

/// The reduced settings' rules, indexed by [`index`]: [`Tolerance::Rel1e4`] (step `0.6`,
/// truncation `1e-5`, `Y = 0.12`, far tail `K = 1500`), [`Tolerance::Rel1e3`] (`0.75`, `1e-4`,
/// `0.2`, `500`), [`Tolerance::Rel1e2`] (`1`, `5e-4`, `0.35`, `160`). A `const`: each
/// setting's loop is compiled with its constants.
const RULES: [Rule; 3] = [
    rule(0.6, 1.822_118_800_390_508_9, 1500.0, 1e-5, 0.12),
    rule(0.75, 2.117_000_016_612_675, 500.0, 1e-4, 0.2),
    rule(1.0, core::f64::consts::E, 160.0, 5e-4, 0.35),
];

/// The constants of the reduced setting `RULES[s]` as the rule holds them: the far-tail
/// switch `K`, the step `h`, `e^h`, the truncation tolerance, `Y`, the geometric sums and the
/// node count. The one source of the WGSL mirror's constants
/// ([`crate::testing::tolerance_rules`]).
#[cfg(feature = "testing")]
#[allow(dead_code, reason = "read from the f64 instance only")]
pub(crate) fn constants(s: usize) -> (f64, f64, f64, f64, f64, [f64; 4], usize) {
    let r = &RULES[s];
    (
        r.far,
        r.h,
        r.ratio[1].to_f64(),
        r.eps_t,
        r.y_lo,
        r.geom,
        r.len,
    )
}

/// The index of a reduced setting in [`RULES`] (`None` for [`Tolerance::Full`]).
#[inline(always)]
pub(super) const fn index(t: Tolerance) -> Option<usize> {
    match t {
        Tolerance::Full => None,
        Tolerance::Rel1e4 => Some(0),
        Tolerance::Rel1e3 => Some(1),
        Tolerance::Rel1e2 => Some(2),
    }
}

/// Whether the rule takes the far-tail series at `beta = beta_m / z2 = 1 + q`:
/// `2 l1 (far + 12 ln beta) <= beta` (`ln` bounded above, so the test errs toward the
/// trapezoid rule).
#[inline(always)]
pub(super) fn takes_far(rule: &Rule, beta_m: f64, z2: f64, tl1: f64) -> bool {
    tl1 * z2 * (rule.far + 12.0 * ln_upper(beta_m / z2)) <= beta_m
}

/// `J / z2^2` by the rule `RULES[S]` (the reduced counterpart of `gaussian_ggx_quad::mixture_integral`, same
/// arguments).
#[inline]
pub(super) fn mixture_integral<const S: usize>(
    v1s: f64,
    v2s: f64,
    z2: f64,
    tl1: f64,
    tl2: f64,
) -> f64 {
    let rule = const { &RULES[S] };
    let beta_m = z2 + v1s + v2s;
    if takes_far(rule, beta_m, z2, tl1) {
        return far_tail(beta_m, v1s, v2s, tl1, tl2, z2);
    }
    let iz2 = 1.0 / z2;
    trapezoid(rule, v1s * iz2, v2s * iz2, tl1, tl2) * iz2 * iz2
}

/// The trapezoid rule in `t = ln w` of `rule`: the full rule's nodes, reference exponent and
/// truncation test (`gaussian_ggx_quad`, items 1 to 3 of the module docs) with the rule's
/// step, first node and tolerance, and a four-term series below the first node.
#[inline(always)]
fn trapezoid(rule: &'static Rule, c1s: f64, c2s: f64, tl1: f64, tl2: f64) -> f64 {
    let h = rule.h;
    let beta = 1.0 + c1s + c2s;
    let w_r = 2.0 / beta;
    // k0 h >= ln(w_r / w_lo), w_lo = y_lo / (beta + 2 l1).
    let k0 = ceil_pos(ln_upper(2.0 / rule.y_lo * (beta + tl1) / beta) * (1.0 / h));
    let k0 = k0.min((rule.len - 1) as f64);
    let w_first = w_r * rule.inv_ratio[k0 as usize];
    // The reference exponent x_r = -w_r - E(w_r) in f64 (no eps |E| loss in the nodes).
    let (pr1, pr2) = (1.0 + tl1 * w_r, 1.0 + tl2 * w_r);
    let ipr = w_r / (pr1 * pr2);
    let (k1, k2) = (c1s * pr2 * ipr, c2s * pr1 * ipr);
    // x_r in each node's exponent (`F`): `|x_r| <= w_r + k1 + k2 <= 4`, so its rounding costs
    // at most `4 eps_F` relative.
    let x_r = -w_r - k1 - k2;
    let scale = w_r * w_r;
    let c = [
        F::from_f64(rule.inv_ratio[k0 as usize]),
        F::from_f64(tl1 * w_r),
        F::from_f64(tl2 * w_r),
        F::from_f64(w_r),
        F::from_f64(k1),
        F::from_f64(k2),
        F::from_f64(x_r - 2.0 * h * k0),
    ];
    let stop = rule.eps_t * h * w_r * w_r;
    let mut tot = [0.0; CH];
    let mut k = 0;
    while k < rule.len {
        let (rk, lk) = (
            rule.ratio[k..].first_chunk::<CH>(),
            rule.log2ratio[k..].first_chunk::<CH>(),
        );
        let (Some(rk), Some(lk)) = (rk, lk) else {
            break;
        };
        let mut acc = [0.0; CH];
        for j in 0..CH {
            acc[j] = node(c, rk[j], lk[j]);
        }
        for (t, a) in tot.iter_mut().zip(acc.iter()) {
            *t += *a;
        }
        let last = acc[CH - 1];
        k += CH;
        // Item 3: the nodes above the last sum to at most g_last b / w_last^2.
        let s = sum_tree(tot).to_f64();
        let vl = (c[0] * rk[CH - 1]).to_f64();
        let wl = vl * w_r;
        let b = if wl >= 2.0 { 1.0 + wl } else { 7.47 };
        if last.to_f64() * b <= stop * s * vl * vl || s.is_nan() {
            break;
        }
    }
    let sum = sum_tree(tot).to_f64();
    h * (sum * scale + series_below(rule, c1s, c2s, tl1, tl2, w_first))
}

/// One node: `g(t) / scale` at `v = v0 r_k` (`gaussian_ggx_quad::trapezoid_node`).
#[inline(always)]
fn node(c: [F; 7], rk: F, lk: F) -> F {
    let [v0, t1, t2, fw, fk1, fk2, l0] = c;
    let v = v0 * rk;
    let p1 = 1.0 + t1 * v;
    let p2 = 1.0 + t2 * v;
    let inv = 1.0 / (p1 * p2);
    let a = fw + (fk1 * p2 + fk2 * p1) * inv;
    let x = (l0 + lk) - (v - 1.0) * a;
    exp_poly(x) * m::sqrt(inv)
}

/// The nodes below `w_first` (item 2) with four terms of `phi = sum a_n w^n`:
/// `sum_(n<4) a_n w_first^(n+2) / (e^((n+2) h) - 1)`, scaled by `y = w_first` (`b~_n = b_n
/// y^n`, `a~_n = a_n y^n`, all bounded).
#[inline(always)]
fn series_below(rule: &Rule, c1s: f64, c2s: f64, tl1: f64, tl2: f64, y: f64) -> f64 {
    let (x1, x2) = (tl1 * y, tl2 * y);
    let (d1, d2) = (c1s * y, c2s * y);
    // b~_n: -(d1 (-x1)^(n-1) + d2 (-x2)^(n-1)) from -E, ((-x1)^n + (-x2)^n) / (2n) from
    // -ln(p1 p2) / 2, and -y for n = 1.
    let b1 = -(d1 + d2) - 0.5 * (x1 + x2) - y;
    let b2 = (d1 * x1 + d2 * x2) + 0.25 * (x1 * x1 + x2 * x2);
    let b3 = -(d1 * x1 * x1 + d2 * x2 * x2) - (x1 * x1 * x1 + x2 * x2 * x2) / 6.0;
    // n a_n = sum_j j b_j a_(n-j).
    let a1 = b1;
    let a2 = 0.5 * (b1 * a1 + 2.0 * b2);
    let a3 = (b1 * a2 + 2.0 * b2 * a1 + 3.0 * b3) / 3.0;
    let g = &rule.geom;
    (g[0] + a1 * g[1] + a2 * g[2] + a3 * g[3]) * y * y
}
