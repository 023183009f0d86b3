//! What can be asserted about the error of the two matrix approximations of the
//! Gaussian-filtered GGX, against the exact Gaussian-filtered GGX (f64 quadrature,
//! `testing::gaussian_reference`): bounds and limits derived from the GGX density, not
//! figures measured from the code. The measured error distributions (median, p99, max over
//! realistic cases) are in the trade table (`cargo run --release -p filtered-ndf-demo --bin tradeoff`).
//!
//! Notation: `A` the lobe's roughness matrix, `Sigma` the kernel, `B = A^-1`, at a slope `s`:
//! `q = s^T B s`, `tau = tr(B Sigma)`, `u = s^T B Sigma B s`. TK19's approximation is the GGX
//! of `A + 2 Sigma`; TK21's the GGX of `A' = P' (I + P')^-1` with `P = A (I - A)^-1`,
//! `P' = P + 2 Sigma` (on the projected disk).
//!
//! **The GGX slope density is a Gaussian scale mixture.** `p22_A(s) = 1 / (pi sqrt(det A)
//! (1 + q)^2)` is the bivariate Student t with 2 degrees of freedom and scale `A / 2`:
//! `p22_A(s) = E_w[N(s; 0, A / (2 w))]` with `w ~ Exp(1)`. Convolved with `N(0, Sigma)`, the
//! exact filtered peak is `E_w[g(w)] / (2 pi)` with `g(w) = 1 / sqrt(det(A / (2 w) + Sigma))
//! = w / sqrt(d0 + d1 w + d2 w^2)` (`d0 = det(A / 2)`, `d1 = tr(adj(A / 2) Sigma)`,
//! `d2 = det Sigma`, all `>= 0`), and TK19's peak is `g(1) / (2 pi) = g(E[w]) / (2 pi)`.
//! `g'' = -(d1 d0 + d1^2 w / 4 + 3 d0 d2 w + d1 d2 w^2) / (d0 + d1 w + d2 w^2)^(5/2) <= 0`:
//! `g` is concave, so by Jensen **exact peak <= TK19 peak**. And `g(0) = 0` with `g`
//! concave and increasing gives `g(w) >= min(w, 1) g(1)`, so **exact peak >= (1 - 1/e) TK19
//! peak** (`E[min(w, 1)] = 1 - 1/e`): the TK19 peak overestimates the exact one by a factor
//! in `[1, e / (e - 1)] = [1, 1.582]` for every lobe and kernel.
//!
//! **Small kernels.** `exact(s) = p22 + Sigma : grad^2 p22 / 2 + O(Sigma^2)`, relative
//! `-2 tau / (1 + q) + 12 u / (1 + q)^2`; TK19's `d/dt p22_(A + 2 t Sigma)` at `t = 0`,
//! relative `-tau + 4 u / (1 + q)`. They differ: the approximation's relative error is
//! `t c(s) + O(t^2)` for the kernel `t Sigma`, with `c = (-tau + 4 u / (1 + q)) -
//! (-2 tau / (1 + q) + 12 u / (1 + q)^2)` (`c = tau` at the peak). The tests check this
//! limit and its first-order rate.

use filtered_ndf::f64 as d;
use filtered_ndf::f64::Ndf as _;
use filtered_ndf::testing::gaussian_reference as gref;
use filtered_ndf::testing::linalg::Sym2;
use filtered_ndf::testing::quadrature::{Estimate, Tolerance, integrate_plane};
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use glam::DVec2;
use std::f64::consts::{E, PI, TAU};

struct Case {
    a: d::RoughnessMatrix,
    k: d::Covariance,
    /// A unit direction in the slope plane.
    dir: DVec2,
}

/// alpha log-uniform in [1e-3, 0.3], anisotropy up to 10, random orientation; kernel
/// standard deviations log-uniform in [0.1, 10] alpha, random orientation.
fn sample(n: usize, seed: u64) -> Vec<Case> {
    let mut r = Rng(seed);
    (0..n)
        .map(|_| {
            let alpha = 10f64.powf(r.range(-3.0, -0.5));
            let aniso = 10f64.powf(r.range(0.0, 1.0));
            let phi = r.range(0.0, PI);
            let (a11, a12, a22) =
                Sym2::from_eigen(alpha * alpha, (alpha / aniso).powi(2), phi).entries();
            let a = d::RoughnessMatrix::new(a11, a12, a22).unwrap();
            let k1 = (alpha * 10f64.powf(r.range(-1.0, 1.0))).powi(2);
            let k2 = (alpha * 10f64.powf(r.range(-1.0, 1.0))).powi(2);
            let (s11, s12, s22) = Sym2::from_eigen(k1, k2, r.range(0.0, PI)).entries();
            let th = r.range(0.0, TAU);
            Case {
                a,
                k: d::Covariance::new(s11, s12, s22),
                dir: DVec2::new(th.cos(), th.sin()),
            }
        })
        .collect()
}

/// `(q, tau, u)` of the module docs for the spread matrix `(m11, m12, m22)` (its inverse by
/// the adjugate, test side), the kernel and the point `s`.
fn invariants(m: (f64, f64, f64), k: d::Covariance, s: DVec2) -> (f64, f64, f64) {
    let det = m.0 * m.2 - m.1 * m.1;
    let b = Sym2::new(m.2 / det, -m.1 / det, m.0 / det);
    let ks = Sym2::new(k.s11, k.s12, k.s22);
    let bs = b.apply([s.x, s.y]);
    let q = s.x * bs[0] + s.y * bs[1];
    let bk = b.mul(&ks); // symmetric part; its trace is tr(B Sigma)
    let tau = bk.a11 + bk.a22;
    let kbs = ks.apply(bs);
    let u = bs[0] * kbs[0] + bs[1] * kbs[1];
    (q, tau, u)
}

/// The first-order relative error coefficient `c` of the module docs.
fn leading_coefficient(q: f64, tau: f64, u: f64) -> f64 {
    let approx = -tau + 4.0 * u / (1.0 + q);
    let exact = -2.0 * tau / (1.0 + q) + 12.0 * u / ((1.0 + q) * (1.0 + q));
    approx - exact
}

fn rel_err(e: &Estimate) -> f64 {
    e.error / e.value
}

const TOL: Tolerance = Tolerance {
    abs: 1e-300,
    rel: 1e-11,
    max_intervals: 4000,
};

#[test]
fn tk19_peak_overestimates_the_exact_peak_by_at_most_e_over_e_minus_1() {
    // Derived bracket (module docs): 1 <= TK19 peak / exact peak <= e / (e - 1), for any
    // lobe and kernel. Tolerance: the quadrature's estimated relative error (the reference
    // is converged to 1e-11; asserted below 1e-8).
    let upper = E / (E - 1.0);
    for c in &sample(96, 0x5EED_F117) {
        let approx = d::Ggx::new(d::filter::gaussian(c.a, c.k)).p22(DVec2::ZERO);
        let exact = gref::ggx(c.a, c.k, DVec2::ZERO, TOL);
        assert!(rel_err(&exact) <= 1e-8, "{exact:?}");
        let ratio = approx / exact.value;
        let q = rel_err(&exact);
        assert!(
            ratio >= 1.0 - q && ratio <= upper * (1.0 + q),
            "TK19 peak / exact = {ratio} outside [1, {upper}] ({:?}, {:?})",
            c.a,
            c.k
        );
    }
}

#[test]
fn tk19_error_vanishes_with_the_kernel_at_the_derived_first_order_rate() {
    // For the kernel t Sigma (Sigma normalised to tau = tr(A^-1 Sigma) = 1), the relative
    // error e(t) = approx / exact - 1 is t c(s) + O(t^2) with c of the module docs. With
    // g(t) = e(t) / t = c + C t + O(t^2): g(t/2) - c and g(t) - g(t/2) are both C t / 2 to
    // leading order, so |g(t/2) - c| <= 2 |g(t) - g(t/2)| (the factor 2 covers the O(t^2)
    // remainder), plus the quadrature's relative error over t/2. Points up to 2 lobe widths
    // from the peak (q <= 4), t = 1e-3 (kernel standard deviations ~3 % of the lobe's).
    let t = 1e-3;
    for (n, c) in sample(24, 0x0DE7_0001).iter().enumerate() {
        let (a11, a12, a22) = c.a.entries();
        let (_, tau, _) = invariants((a11, a12, a22), c.k, DVec2::ZERO);
        let k = c.k * (1.0 / tau);
        // Width of the lobe along `dir`: sqrt(dir^T A dir).
        let w = (c.dir.x * c.dir.x * a11 + 2.0 * c.dir.x * c.dir.y * a12 + c.dir.y * c.dir.y * a22)
            .sqrt();
        let s = c.dir * w * (2.0 * (n as f64) / 24.0);
        let (q, tau1, u) = invariants((a11, a12, a22), k, s);
        assert!((tau1 - 1.0).abs() < 1e-12);
        let coef = leading_coefficient(q, tau1, u);
        let e = |t: f64| {
            let kt = k * t;
            let approx = d::Ggx::new(d::filter::gaussian(c.a, kt)).p22(s);
            let exact = gref::ggx(c.a, kt, s, TOL);
            (approx / exact.value - 1.0, rel_err(&exact))
        };
        let ((e1, q1), (e2, q2)) = (e(t), e(t / 2.0));
        let (g1, g2) = (e1 / t, e2 / (t / 2.0));
        let bound = 2.0 * (g1 - g2).abs() + 2.0 * (q1 + q2) / (t / 2.0);
        assert!(
            (g2 - coef).abs() <= bound,
            "case {n}: e(t)/t = {g1}, e(t/2)/(t/2) = {g2}, derived limit {coef} (q = {q})"
        );
    }
}

#[test]
fn tk19_tail_overestimate_is_the_derived_limit_ratio() {
    // Far from the peak the kernel is narrow against the lobe's local scale: exact(s) =
    // p22_A(s) (1 + delta) with the first-order delta = -2 tau / (1 + q) + 12 u / (1 + q)^2,
    // |delta| <= 14 tau / (1 + q) (u <= tau q). TK19 is p22_(A + 2 Sigma)(s) exactly, so
    // TK19 / exact -> R(s) = p22_(A + 2 Sigma)(s) / p22_A(s) (closed form, test side): the
    // large relative errors of the approximation in the tails (R grows like
    // det(A + 2 Sigma)^(1/2) det(A)^(-1/2) (q_A / q_(A + 2 Sigma))^2, 1 + 2 sigma^2 / alpha^2
    // for isotropic A and Sigma). At tau / (1 + q) = 1e-4 the assertion allows twice the
    // first-order bound (higher orders are O((tau / q)^2) ~ 1e-8) plus the quadrature error.
    let mut largest: f64 = 0.0;
    for c in sample(16, 0x7A11_0001) {
        let (a11, a12, a22) = c.a.entries();
        let (_, tau, _) = invariants((a11, a12, a22), c.k, DVec2::ZERO);
        // q = s^T A^-1 s = 1e4 tau along `dir` (plus 1).
        let (q_dir, _, _) = invariants((a11, a12, a22), c.k, c.dir);
        let s = c.dir * ((1e4 * tau + 1.0) / q_dir).sqrt();
        let (q, tau, _) = invariants((a11, a12, a22), c.k, s);
        let p22 = |m: (f64, f64, f64)| {
            let (qm, _, _) = invariants(m, c.k, s);
            1.0 / (PI * (m.0 * m.2 - m.1 * m.1).sqrt() * (1.0 + qm) * (1.0 + qm))
        };
        let filtered = (
            a11 + 2.0 * c.k.s11,
            a12 + 2.0 * c.k.s12,
            a22 + 2.0 * c.k.s22,
        );
        let r = p22(filtered) / p22((a11, a12, a22));
        let approx = d::Ggx::new(d::filter::gaussian(c.a, c.k)).p22(s);
        let exact = gref::ggx(c.a, c.k, s, Tolerance::relative(1e-10));
        let b = 2.0 * 14.0 * tau / (1.0 + q) + rel_err(&exact);
        let measured = approx / exact.value;
        assert!(
            (measured / r - 1.0).abs() <= b,
            "TK19 / exact = {measured}, derived limit {r} (q = {q}, tau = {tau})"
        );
        largest = largest.max(r);
    }
    // Coverage, not a claim: the sample's kernels reach 10 alpha, where the limit ratio is in
    // the hundreds (the trade table's largest relative errors).
    assert!(largest > 100.0, "{largest}");
}

#[test]
fn tk19_equals_the_lobe_at_zero_kernel_and_stays_normalised() {
    for c in sample(8, 0x2E40_0001) {
        // Zero kernel: A + 2 * 0 = A, the unfiltered density (closed form, test side), which
        // is also the exact filtered density (the reference returns it with zero error).
        let (a11, a12, a22) = c.a.entries();
        let det = a11 * a22 - a12 * a12;
        let g0 = d::Ggx::new(d::filter::gaussian(c.a, d::Covariance::ZERO));
        for r in [0.0, 0.5, 3.0] {
            let s = c.dir * r * a11.sqrt();
            let (q, _, _) = invariants((a11, a12, a22), d::Covariance::ZERO, s);
            let closed = 1.0 / (PI * det.sqrt() * (1.0 + q) * (1.0 + q));
            // 16 ulps: a handful of roundings in either form.
            assert!((g0.p22(s) - closed).abs() <= 16.0 * f64::EPSILON * closed);
            let exact = gref::ggx(c.a, d::Covariance::ZERO, s, TOL);
            assert_eq!(exact.value, d::Ggx::new(c.a).p22(s));
        }
        // The filtered lobe integrates to one over the slope plane, like the exact filtered
        // density (a convolution of two unit masses). Tolerance: ten times the quadrature goal.
        let g = d::Ggx::new(d::filter::gaussian(c.a, c.k));
        let (b11, _, b22) = d::filter::gaussian(c.a, c.k).entries();
        let total = integrate_plane(
            |x, y| g.p22(DVec2::new(x, y)),
            (0.0, 0.0),
            (b11.sqrt(), b22.sqrt()),
            Tolerance::relative(1e-10),
        );
        assert!((total.value - 1.0).abs() <= 1e-9, "{total:?}");
    }
}

#[test]
fn tk21_projected_peak_never_underestimates_and_its_error_vanishes_at_the_derived_rate() {
    // TK21 on the projected disk. The GGX density at the disk point p = h_xy is
    // D(h(p)) = t2(p; P) sqrt(det(I + P)) (a Student t in p, as p22 in s, with
    // P = A (I - A)^-1), zero outside the disk; TK21's lobe is t2(p; P') sqrt(det(I + P')),
    // P' = P + 2 Sigma. At the peak: the exact convolution of the disk-truncated density is at
    // most that of its untruncated extension, E_w[N(0; P / (2w) + Sigma)] sqrt(det(I + P)),
    // at most (Jensen, as for TK19) t2(0; P') sqrt(det(I + P)), at most TK21's peak
    // (det(I + P') >= det(I + P)). Hence TK21 peak >= exact peak, one-sided.
    let density = |a: d::RoughnessMatrix| {
        let g = d::Ggx::new(a);
        move |p: DVec2| {
            if p.length_squared() < 1.0 {
                g.d(d::footprint::slope::sphere_from_projected(p))
            } else {
                0.0
            }
        }
    };
    // Quadrature goal 1e-8 (the disk rim is a discontinuity the adaptive rule has to
    // resolve); its estimated error enters the comparison.
    for c in &sample(32, 0xD15C_0001) {
        let exact = gref::gaussian_convolution(
            density(c.a),
            DVec2::ZERO,
            c.a,
            c.k,
            DVec2::ZERO,
            Tolerance::relative(1e-8),
        );
        assert!(rel_err(&exact) <= 1e-6, "{exact:?}");
        let approx = d::Ggx::new(d::filter::projected(c.a, c.k)).d(glam::DVec3::Z);
        assert!(
            approx >= exact.value * (1.0 - rel_err(&exact)),
            "TK21 peak {approx} below the exact {:?} ({:?}, {:?})",
            exact,
            c.a,
            c.k
        );
    }
    // Small kernels: the relative error is t c_P(p) + O(t^2) with the TK19 coefficient in
    // disk terms (q, tau, u of P at p) plus tr((I + P)^-1 Sigma) from sqrt(det(I + P')); the
    // disk edge is ~30 kernel widths away and contributes nothing. Same rate check as TK19.
    let t = 1e-3;
    for (n, c) in sample(16, 0xD15C_0002).iter().enumerate() {
        let (a11, a12, a22) = c.a.entries();
        let det_ima = (1.0 - a11) * (1.0 - a22) - a12 * a12;
        // P = A (I - A)^-1 = (A - det(A) I) / det(I - A) for 2x2 matrices.
        let det_a = a11 * a22 - a12 * a12;
        let p_m = (
            (a11 - det_a) / det_ima,
            a12 / det_ima,
            (a22 - det_a) / det_ima,
        );
        let (_, tau, _) = invariants(p_m, c.k, DVec2::ZERO);
        let k = c.k * (1.0 / tau);
        let w = (c.dir.x * c.dir.x * p_m.0
            + 2.0 * c.dir.x * c.dir.y * p_m.1
            + c.dir.y * c.dir.y * p_m.2)
            .sqrt();
        let p = c.dir * w * (2.0 * (n as f64) / 16.0);
        let (q, tau1, u) = invariants(p_m, k, p);
        let ipp = Sym2::new(1.0 + p_m.0, p_m.1, 1.0 + p_m.2);
        let d_ipp = ipp.det();
        let tr_ipp_k =
            ((1.0 + p_m.2) * k.s11 - 2.0 * p_m.1 * k.s12 + (1.0 + p_m.0) * k.s22) / d_ipp;
        let coef = leading_coefficient(q, tau1, u) + tr_ipp_k;
        let h = d::footprint::slope::sphere_from_projected(p);
        let e = |t: f64| {
            let kt = k * t;
            let approx = d::Ggx::new(d::filter::projected(c.a, kt)).d(h);
            let exact = gref::gaussian_convolution(density(c.a), DVec2::ZERO, c.a, kt, p, TOL);
            (approx / exact.value - 1.0, rel_err(&exact))
        };
        let ((e1, q1), (e2, q2)) = (e(t), e(t / 2.0));
        let (g1, g2) = (e1 / t, e2 / (t / 2.0));
        let bound = 2.0 * (g1 - g2).abs() + 2.0 * (q1 + q2) / (t / 2.0);
        assert!(
            (g2 - coef).abs() <= bound,
            "case {n}: e(t)/t = {g1}, e(t/2)/(t/2) = {g2}, derived limit {coef} (q = {q})"
        );
    }
}
