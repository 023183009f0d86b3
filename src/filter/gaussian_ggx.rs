//! The exact Gaussian-filtered GGX: the convolution of a GGX slope density (any roughness
//! form) with a Gaussian kernel `N(0, Sigma)` (any positive semi-definite `Sigma`), as slope
//! density, per steradian, with its own Smith `Lambda`, evaluated by a one-dimensional
//! quadrature with a proven error bound. KHPL16 (section 5.2) filters GGX over a bounding
//! rectangle because it "does not have an elegant closed-form convolution"; TK19 (section 2.2)
//! and TK21 approximate the Gaussian-filtered lobe by a GGX of roughness `A + 2 Sigma`. This
//! module computes the filter itself.
//!
//! # The mixture identity
//! GGX of roughness matrix `A` is a bivariate Student-t with two degrees of freedom, hence a
//! scale mixture of Gaussians with an exponential mixing density:
//!
//! `P22(s) = 1 / (pi sqrt(det A) (1 + s^T A^-1 s)^2) = integral_0^inf e^-w N(s; 0, A / (2w)) dw`
//!
//! (`N(s; 0, A/(2w)) = w exp(-w s^T A^-1 s) / (pi sqrt(det A))`, and
//! `integral w e^-(1+q) w dw = (1+q)^-2`). Each component is a Beckmann lobe of roughness
//! `A / w` (KHPL16 eq. 14: covariance `A / (2w)`); convolving it with `N(0, Sigma)` adds the
//! covariances (KHPL16 eq. 15), so
//!
//! `P22_Sigma(s) = integral_0^inf e^-w N(s; 0, (A + 2 w Sigma) / (2w)) dw`.
//!
//! With `A = B B^T` and the generalised eigen-decomposition `B^-1 Sigma B^-T = U diag(l1, l2) U^T`
//! (`l1 >= l2 >= 0`, the kernel in units of the lobe), `c = U^T B^-1 s` and `p_i = 1 + 2 l_i w`:
//! `det(A + 2 w Sigma) = det A p1 p2` and `w s^T (A + 2 w Sigma)^-1 s = E(w) = w (c1^2 / p1 + c2^2 / p2)`,
//! so
//!
//! `P22_Sigma(s) = J / (pi sqrt(det A))`, `J = integral_0^inf w e^-w exp(-E(w)) / sqrt(p1 p2) dw`,
//!
//! every term a sum of non-negative numbers (no cancellation at any anisotropy). The zero
//! kernel gives `J = (1 + |c|^2)^-2`, GGX itself.
//!
//! # Evaluating `J`
//! Three rules, chosen per evaluation from `q = |c|^2` and the kernel ratio `2 l1` (the code
//! is in `gaussian_ggx_quad.rs`):
//!
//! - **far tail** where `1 + q >= K 2 l1` (`K = 3.2e5` in `f32`, `3.2e7` in `f64`; always for
//!   the zero kernel): a two-term series (item 5), no exponential;
//! - **Gauss-Laguerre** where `2 l1 <= r_GL (1 + q)` (`r_GL = 0.0177` in `f32`, `0.01` in `f64`)
//!   and `2 l1 (A + 1.5 ln(1 + q)) <= 1 + q` (`A = 20`, resp. `31.5`): 8 (resp. 12) nodes
//!   (item 4);
//! - otherwise the **trapezoid rule in `t = ln w`** (items 1 to 3).
//!
//! The trapezoid rule: `J = integral g(t) dt`, `g = w^2 e^-w exp(-E) / sqrt(p1 p2)`, step `h`
//! (0.5 in `f32`, 0.3 in `f64`), nodes `w_k = w_r e^((k - k0) h)` from the first node at or below
//! `Y / (1 + q + 2 l1)` up to where item 3 stops the sum. Three errors, each bounded relative
//! to `J`:
//!
//! 1. **Discretisation** (the whole-line trapezoid sum minus the integral). `g` is analytic in
//!    the strip `|Im t| < pi/2` (`w = e^t` has `Re w > 0` there; the singularities of `p_i^-1/2`
//!    and `exp(-E)` sit at `w = -1/(2 l_i)`, `Im t = pi`). On the line `Im t = y`, with
//!    `rho = Re w = |w| cos y`: `|e^-w| = e^-rho`, `|p_i| >= 1 + 2 l_i rho` and
//!    `Re(w / p_i) >= rho / (1 + 2 l_i rho)` (the difference of the cross-multiplied sides is
//!    `2 l_i |w|^2 sin^2 y >= 0`), so `|g(t + iy)| <= g_real(t + ln cos y) / cos^2 y` and
//!    `integral |g(t + iy)| dt <= J / cos^2 y`. The trapezoid theorem for the real line
//!    (Trefethen and Weideman 2014, theorem 5.1: error `<= 2M / (e^(2 pi a / h) - 1)` for `g`
//!    analytic in `|Im t| < a` with `integral |g(t + iy)| dt <= M`) gives the relative bound
//!    `min over a in (0, pi/2) of 2 / (cos^2 a (e^(2 pi a / h) - 1))`: **`1.6e-6` for `h = 0.5`,
//!    `8.4e-12` for `h = 0.3`**. The bound is tight: the unfiltered lobe (`g = w^2 e^-(1+q) w`,
//!    whose transform is `Gamma(2 + i omega)`) has the actual error `6.0e-7`, resp. `2.5e-12`.
//!    The node offset is free (the bound holds for every offset): the grid is anchored at
//!    `w_r = 2 / (1 + q)`.
//! 2. **Lower end** (the nodes below the first, `w_f`). They are not dropped but summed in
//!    closed form: `phi(w) = g / w^2 = exp(-w - E(w)) / sqrt(p1 p2)` is analytic in
//!    `|w| < 1 / (2 l1)`, `phi = sum a_n w^n` with `ln phi = sum b_n w^n`,
//!    `b_n = -sum_i c_i^2 (-2 l_i)^(n-1) + sum_i (-2 l_i)^n / (2n)` (less 1 for `n = 1`) and
//!    `n a_n = sum_j j b_j a_(n-j)`, so the nodes `w_f e^(-kh)`, `k >= 1`, sum to
//!    `sum_n a_n w_f^(n+2) / (e^((n+2) h) - 1)`, kept for `n < N` (`N = 4` in `f32`, 8 in `f64`).
//!    The remainder: on the circle `|w| = r = 1 / (2 beta)`, `beta = 1 + q + 2 l1`, `|e^-w| <=
//!    e^(1/2)`, `|E| <= 2 q r < 1` and `|p_i|^-1/2 <= sqrt 2`, so `|phi| <= M = 2 e^(3/2)` and (Cauchy)
//!    `|phi - sum_(n<N) a_n w^n| <= M (|w| / r)^N / (1 - |w| / r)`; and `J >= 1 / beta^2 = 4 r^2`
//!    (`phi(w) >= e^(-beta w)` on `w >= 0`). With `x = w_f / r`, the neglected part is below
//!    `h M x^(N+2) / (4 (1 - x e^-h)(e^((N+2) h) - 1))` relative to `J`: `<= 1e-7` (resp.
//!    `1e-12`) for `w_f <= Y / beta`, **`Y = 0.054`** (resp. **`0.0437`**). This replaces the
//!    `w^2` tail that a truncation would need down to `w ~ 1e-4 / beta`: the rule starts 4 units
//!    of `t` higher (8, resp. 13, nodes fewer).
//! 3. **Upper truncation** (the nodes above the last). `h(w) = exp(-E) / sqrt(p1 p2)` is
//!    decreasing, so the nodes beyond `w_j` sum to at most `h(w_j) (1 + w_j) e^-w_j` for
//!    `w_j >= 2` (where `w^2 e^-w` decreases in `t`) and `1.01 h(w_j)` below; summing from the
//!    bottom in chunks of 8 (resp. 4) nodes, the rule stops once this is `<= eps_t` times the
//!    sum (`eps_t = 1e-7`, resp. `1e-12`).
//! 4. **Gauss-Laguerre** (the other rule). With `v = (1 + q) w`,
//!    `J = (1+q)^-2 integral v e^-v F(v / (1+q)) dv`, `F(w) = exp(sum_i c_i^2 2 l_i w^2 / p_i) /
//!    sqrt(p1 p2)`: the generalised Gauss-Laguerre rule (weight `v e^-v`, nodes and weights to 17
//!    digits from 60-digit Newton iterations) is exact for polynomial `F` and converges fast
//!    while `F`'s singularity at `v = -(1+q) / (2 l1)` is far, i.e. for small
//!    `rho = 2 l1 / (1 + q)`. Its error is measured, not proven: over `rho` in `[1e-5, 1e-1]` (32
//!    bins of `1/8` decade, 4 points each), `q` from `0` and `1e-4` to `1e8` (49 values),
//!    kernel anisotropy `l2 / l1` in `{0, 1e-3, 0.1, 0.5, 1}` and five splits of `q` between
//!    the axes (`1.96e5` cases against a trapezoid rule with `h = 0.1` over `w` from
//!    `1e-14 / (1 + q + 2 l1 + 2 l2)` to `90`, error `< 1e-15`), the worst relative error is
//!    `5e-8` (8 nodes) for `rho <= 10^-1.75` and `2e-13` (12 nodes) for `rho <= 10^-2`, rising
//!    smoothly with `rho` (`7e-7`, resp. `1e-11`, in the next bin): `r_GL` sits below both edges.
//!    The second condition excludes a plateau the rule cannot see: for `1 / (2 l1) << w << 1`
//!    the integrand is `e^(-Q) sqrt(w / (2 l1))` (rank-one kernel, `Q = c1^2 / (2 l1)`), whose
//!    mass relative to `(1+q)^-2` is `e^(-1/rho) (1+q)^1.5 / (1.5 sqrt(rho))`: `<= 1e-8` (resp.
//!    `1e-13`) under the condition (checked with an upper bound of `ln`, exact within
//!    `1 - ln 2`). Without it, the error reaches `1e-2` at `q = 2e7`, `rho = 0.03`.
//! 5. **Far tail.** The series `J = (1+q)^-2 (1 + 12 P / (1+q)^2 - 2 (l1 + l2) / (1+q))`,
//!    `P = l1 c1^2 + l2 c2^2` (the expansion of `ln(e^-w h(w))` to second order in `w` around the
//!    bump at `w ~ 1 / (1+q)`; its remainder is below `400 (l1 / (1+q))^2 <= 4e-9` resp.
//!    `4e-13`). [`Ndf::d`] evaluates every rule homogeneously in `m` (`c_i^2 = v_i^2 / m_z^2`,
//!    `J / m_z^4`), so the density stays finite and accurate up to the horizon.
//!
//! **Arithmetic.** The set-up of each rule (the whitening `c`, the reference exponent, the
//! series) is in `f64`; the node loops run in the lobe's precision, vectorised (`f32` lanes for
//! the `f32` lobe), with a polynomial `exp` (relative error `< 1.7e-7` in `f32`, `< 1.4e-14` in
//! `f64`; the terms are positive, so this is also its effect on `J`). A node's exponent is not
//! formed as `-w - E(w)`, whose rounding in `f32` would cost `eps |E|` (`E` reaches ~20 at the
//! dominant nodes of kernel-dominated lobes), but against the reference `w_r`:
//! `-w - E(w) = x_r - (w - w_r)(1 + sum_i c_i^2 / (p_i(w) p_i(w_r)))`, `x_r` in `f64`, and the
//! factor `w^2 / w_r^2 = e^(2 (k - k0) h)` folded into the exponent exactly; no cancellation, and
//! no overflow or underflow in `f32` at any scale.
//!
//! **Totals** (relative, against an independent trapezoid rule with `h = 0.1`, `6.8e4` cases:
//! the benches' distribution, the tests' domain and `l1` to `3e6`, `q` to `1e8` uniformly in
//! logarithm): worst **`1.4e-12` in `f64`** (bound `8.4e-12 + 2e-12` for the trapezoid rule;
//! the worst case sits at the Gauss-Laguerre edge) and **`1.6e-6` in `f32`** (bound
//! `1.6e-6 + 2e-7` plus the `f32` arithmetic). Nodes per evaluation on the benches' realistic
//! cases: 8 (`f32`) / 12 (`f64`) for the Gauss-Laguerre half, a median of 16 / 28 (90th
//! percentile 24 / 40) for the trapezoid half; up to 64 / 104 over the tested domain.
//!
//! # Tolerance settings
//! [`Tolerance`] chooses the rules of `J` (the density: `p22`, `d`; `Lambda` and the samplers
//! keep the rules above at every setting). [`Tolerance::Full`], the default, is the set above.
//! The reduced settings drop Gauss-Laguerre (whose bound is measured, item 4) and keep two
//! rules whose bounds are proven, with the constants of this table (`gaussian_ggx_tol.rs`):
//!
//! | setting | far tail `K` | step `h` | `Y` | `eps_t` | far-tail bound | trapezoid bound (disc. + lower end + top + `f32` exponent) |
//! |---|---:|---:|---:|---:|---:|---:|
//! | `Rel1e4` | 1500 | 0.6 | 0.12 | `1e-5` | `4.0e-5` | `2.94e-5 + 8.3e-6 + 1e-5 + 1.6e-5 = 6.4e-5` |
//! | `Rel1e3` | 500 | 0.75 | 0.2 | `1e-4` | `3.8e-4` | `5.09e-4 + 9.5e-5 + 1e-4 + 1.6e-5 = 7.2e-4` |
//! | `Rel1e2` | 160 | 1.0 | 0.35 | `5e-4` | `4.3e-3` | `7.80e-3 + 8.8e-4 + 5e-4 + 1.6e-5 = 9.2e-3` |
//!
//! - **T1. Where the rules switch.** The far-tail series where `2 l1 (K + 12 ln(1 + q)) <= 1 + q`
//!   (`ln` bounded above as in item 4, so the test errs toward the trapezoid rule), the
//!   trapezoid rule everywhere else. Nothing else switches: the trapezoid rule's node count
//!   follows from its first node and its truncation test.
//! - **T2. The far tail's remainder, proven.** With `u = (1 + q) w`, `rho_i = 2 l_i / (1 + q)`,
//!   `rho = rho_1`, `gamma_i = c_i^2 / (1 + q)` (`sum gamma_i < 1`): `J (1 + q)^2 =
//!   integral u e^-u e^psi du`, `psi = sum gamma_i rho_i u^2 / (1 + rho_i u) - sum ln(1 + rho_i
//!   u) / 2`, and the series of item 5 is `integral u e^-u (1 + psi_1) du`, `psi_1 = sum gamma_i
//!   rho_i u^2 - sum rho_i u / 2`. For `u <= 1 / (2 rho)`: `|psi - psi_1| <= rho^2 (u^3 +
//!   u^2 / 2)` (from `1 - 1 / (1 + x) <= x` and `x - x^2 / 2 <= ln(1 + x) <= x`), `|psi| <= rho
//!   max(u^2, u)` and `psi <= rho u^2 <= u / 2`, so by Taylor's remainder `|e^psi - 1 - psi_1| <=
//!   rho^2 (u^3 + u^2 / 2 + max(u^4, u^2) e^min(rho u^2, u / 2) / 2)`, whose integral against
//!   `u e^-u` is `C rho^2` with `C = 88.7, 92.5, 107.4` at `rho = 1 / K` (numerical integration
//!   of this explicit bound). Beyond `u = 1 / (2 rho)` the integrand is at most `u exp(-u / (1 +
//!   q) - q / (6 l1))` (there `u / (1 + rho u) >= 1 / (3 rho)`), which integrates to at most
//!   `(1 + q)^2 (1 + 1 / (2 rho)) e^(-1 / (3 rho))`: the kernel's own Gaussian tail, which the
//!   series does not hold and which the `12 ln(1 + q)` term of the switch keeps below
//!   `exp(-(K / 6 - ln(1 + K / 2)))` (`<= 2.2e-10`). Relative to `J (1 + q)^2 >= 1 - 2 rho -
//!   C rho^2`: the table's far-tail bounds.
//! - **T3. The trapezoid rule's error, proven.** Items 1 to 3 hold for any step: the discretisation
//!   bound `min_a 2 / (cos^2 a (e^(2 pi a / h) - 1))` at the setting's `h`, the lower end's
//!   bound of item 2 with four terms (`N = 4`) and the first node at or below `Y / (1 + q +
//!   2 l1)`, and the truncation `eps_t` (its `b = 7.47` below `w = 2` needs the whole-line sum
//!   of `w e^-w` within 1 % of its integral: the discretisation bound is `<= 7.8e-3`). The
//!   nodes' exponent is formed in the lobe's precision with the reference exponent folded in
//!   (`|x_r| <= 4`), so in `f32` it carries at most the rounding of two terms below `180`:
//!   `1.6e-5` (at the largest first-node offsets; `< 2e-6` for kernels below `1e6` lobe
//!   variances), and the polynomial `exp` its `2.5e-7`. The node tables cover the first node's
//!   offset up to `e^88` (kernels to about `1e37` lobe variances), as the full rule's.
//!
//! Measured against the `Full` rule in `f64` (2e5 seeded cases over `alpha` `1e-4..1`, kernels
//! `1e-3..1e3` lobe widths, slopes `1e-3..1e3` filtered widths): worst `1.2e-5`, `2.1e-4`,
//! `4.1e-3` for `Rel1e4`, `Rel1e3`, `Rel1e2` (the discretisation bound is about three times
//! the actual error, item 1); `tests/gaussian_ggx_tolerance.rs` tests each setting against
//! the 2-D quadrature of the convolution, on both sides of its switch.
//!
//! # Smith `Lambda`: the filtered distribution's own
//! `Lambda` is a linear functional of the slope density (Heitz 2014 eq. 72), so the filtered
//! lobe's `Lambda` is the same mixture of the Beckmann `Lambda`s of its components, roughness
//! `A / w + 2 Sigma`: `Lambda(o) = integral_0^inf e^-w Lambda_B(o; A / w + 2 Sigma) dw`. This
//! is the choice of Tessari et al. 2020 section 3.1 for *spatial* filtering (pixel footprint,
//! curvature): "we alter both the normal distribution and the masking term according to the new
//! covariance matrix", the new microsurface passing the weak white furnace test; their base
//! roughness `G` (section 3.2) is for *temporal* filtering, where microfacets at different
//! times do not shadow each other. A pixel footprint is spatial; and only the filtered `Lambda`
//! normalises the distribution of visible normals (`integral D_o(m) dm = 1`), which the
//! visible-normal sampler and its pdf need.
//!
//! 6. **Evaluation.** Along the view's azimuth `e`, the filtered slope is a GGX slope plus an
//!    independent Gaussian one, so with `Lambda = E[(X - mu)+] / mu` (Heitz 2014 eq. 72),
//!    `mu = cot theta`, and GGX's closed form `E[(Y - m)+] = (sqrt(alpha_e^2 + m^2) - m) / 2`,
//!    scaled by `|o_xy|`:
//!    `Lambda(o) = E[h(o_z - Z)] / (2 o_z)`, `Z ~ N(0, qs)`, `h(y) = sqrt(qa + y^2) - y`,
//!    `qa = o^T A o`, `qs = o^T Sigma o` (`qs = 0`: GGX's `Lambda`). `h` is analytic but for
//!    branch points at `y = +-i sqrt(qa)`, and `delta_s = sqrt(qs / (qa + o_z^2))` (the
//!    Gaussian's width against their distance from its centre) picks the rule:
//!    - `delta_s <= 0.1`: **Gauss-Hermite**, 8 nodes (`f32`) / 10 (`f64`), `h(y)` evaluated as
//!      `qa / (sqrt(qa + y^2) + y)` for `y >= 0`. Measured over 3065 points of the grid
//!      `sqrt(qa / qs)` in `[1e-4, 1e3]` (steps of `0.1` decade) by `o_z / sqrt(qa)` in
//!      `[1e-3, 1e8]` (steps of `1/6` decade) with `delta_s <= 0.1`, against the mixture
//!      itself (adaptive quadrature of `integral e^-w Lambda_B dw` with libm's `erfc`): worst
//!      `8.3e-12` (8 nodes) / `1.2e-13` (10 nodes); the error grows to `1e-5` for `delta_s` in
//!      `[0.1, 0.18]` whatever the node count (the branch points enter the Gaussian's bulk).
//!    - otherwise the **trapezoid rule in `s`**, `y = sqrt(qa) sinh s`:
//!      `Lambda = qa / (4 o_z) integral phi_sigma(o_z - sqrt(qa) sinh s) (1 + e^-2s) ds`, an
//!      entire integrand decaying double-exponentially at both ends, nodes `s0 + k h` with
//!      `sinh s0 = o_z / sqrt(qa)` and `o_z - sqrt(qa) sinh(s0 + d) = -2 sqrt(qa) cosh(s0 + d/2)
//!      sinh(d/2)` (no cancellation). The step is measured: the largest `h` meeting `1e-7`
//!      (resp. `2e-12`) at every point of the grid, per `1/8` decade of `delta_s`, is `0.095`
//!      at `delta_s = 0.1`, `0.19` at `0.32`, `0.26` beyond `0.75` (resp. `0.065`, `0.13`,
//!      `0.16`); the rule takes `min(0.25, 0.25 sqrt(delta_s))` (resp.
//!      `min(0.16, 0.17 sqrt(delta_s))`), below all of them. Each end stops (every 8 nodes)
//!      when the last term `f_k` is `<= eps` times the sum (`1e-8`, resp. `1e-13`) and the
//!      terms beyond fall by half per node: going up, `|x(s)| >= |x_k| + sqrt(qa) (s - s_k)`
//!      (`sinh' >= 1`) and `1 + e^-2s` decreases, so the ratio is `<= 1/2` once
//!      `|x_k| sqrt(qa) h / qs >= ln 2`; going down `1 + e^-2s` grows by at most `e^2h` per
//!      node, so `>= 2h + ln 2`; the neglected terms then sum to at most `f_k`. The grid and the
//!      Gaussian's argument are in `f64` (the grid ratio `e^(h/2)` from the library `exp`: its
//!      error compounds over the nodes), the exponential in the lobe's lanes. Over the 1692 grid
//!      points with `delta_s > 0.1`: worst `2.9e-7` (`f32` rule), `9.0e-13` (`f64` rule); 20 to
//!      60 nodes on the benches' grazing views, up to 240 / 410 for kernels `1e4` lobe widths.
//!
//!    Measured through [`Ndf::lambda`] against the mixture (`tests/gaussian_ggx.rs`, 480
//!    seeded views of the tests' lobes): worst `8.8e-13` (`f64`), `1.8e-7` (`f32`).
//!
//! # Bad input
//! The kernel is [`Covariance::sanitized`] (a NaN entry counts as `0`; infinite: the widest kernel;
//! indefinite: the nearest PSD matrix with the same diagonal; eigenvalues capped at
//! `KERNEL_MAX`), so every finite or non-finite input gives a finite lobe. `p22`, `d`,
//! `lambda` never return NaN: non-finite arguments give `0` (`p22`, `d`) and `lambda` follows
//! [`Ndf::lambda`] (`+inf` at grazing, `0` at normal incidence).

use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, Covariance, SIGMA_PIXEL};
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::{Ggx, ggx_lambda};
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::super::ndf::{Ndf, rescale_direction};
use super::gaussian::Gaussian;
use super::gaussian_ggx_quad as quad;
use super::gaussian_ggx_tol as tol;
use super::method::Method;
use super::tolerance::Tolerance;
use super::{F, Vec2, Vec3};
use crate::math::{self as m, Real};

const INV_PI: f64 = core::f64::consts::FRAC_1_PI;

/// The exact Gaussian-filtered GGX lobe (module docs): GGX of roughness `A` convolved in the
/// slope domain with the Gaussian kernel `N(0, Sigma)`.
///
/// Built once per shading point ([`GaussianFilteredGgx::new`], a few dozen flops, two
/// divisions and two square roots in `f64`), then evaluated through [`Ndf`] and
/// [`NdfSampling`](super::super::sampling::NdfSampling).
///
/// ```
/// use filtered_ndf::f32::{Covariance, GaussianFilteredGgx, Ggx, Isotropic, Ndf};
/// use glam::{Vec2, Vec3};
///
/// let a = Isotropic::new(0.05).unwrap();
/// let lobe = GaussianFilteredGgx::new(a, Covariance::new(4e-3, 1e-3, 1e-3));
/// let h = Vec3::new(0.02, 0.01, 1.0).normalize();
/// assert!(lobe.d(h) > 0.0 && lobe.d(h) < Ggx::new(a).d(Vec3::Z));
/// // The zero kernel is GGX itself.
/// let unfiltered = GaussianFilteredGgx::new(a, Covariance::ZERO);
/// let ggx = Ggx::new(a);
/// assert!((unfiltered.p22(Vec2::new(0.03, 0.0)) - ggx.p22(Vec2::new(0.03, 0.0))).abs() < 1e-6 * ggx.p22(Vec2::ZERO));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussianFilteredGgx {
    /// `T = V^T B^-1` by rows, `V` the eigenvectors of `B^-1 Sigma B^-T` with the common
    /// squared length `1 / n2`: `c_i^2 = (T s)_i^2 n2`.
    t: [f64; 4],
    /// See `t`.
    n2: f64,
    /// `(2 l1, 2 l2)`, `l1 >= l2 >= 0`.
    tl: [f64; 2],
    /// `1 / (pi sqrt(det A))`.
    norm: f64,
    /// The lower Cholesky factor `B = [[b11, 0], [b21, b22]]` of `A` (`b22 = sqrt(det A) / b11`).
    pub(crate) b: [f64; 3],
    /// The sanitised kernel `(s11, s12, s22)`.
    pub(crate) k: [f64; 3],
    /// The unfiltered roughness as a matrix (the `Beckmann` components of the sampler).
    pub(crate) a: RoughnessMatrix,
    /// The accuracy setting of `p22` and `d`.
    tol: Tolerance,
}

impl GaussianFilteredGgx {
    /// The lobe of GGX roughness `roughness` filtered by the kernel `kernel` (slope^2, e.g.
    /// [`Footprint::covariance`](super::super::Footprint::covariance)), which is
    /// [`Covariance::sanitized`] first. `A` is the matrix GGX evaluates: for a matrix with an
    /// active determinant clamp the clamped `A_c` ([`RoughnessMatrix::clamped_entries`]), with
    /// `det A = sqrt_det()^2`.
    #[inline(always)]
    pub fn new<R: Roughness>(roughness: R, kernel: Covariance) -> Self {
        Self::of_sanitized(roughness, kernel.sanitized())
    }

    /// [`GaussianFilteredGgx::new`] for a kernel `k` already sanitised
    /// ([`Covariance::sanitized`] returns it unchanged), branch-free (its cases as selects):
    /// `batch`'s lanes build a lobe per element with it.
    #[inline(always)]
    pub(crate) fn of_sanitized<R: Roughness>(roughness: R, k: Covariance) -> Self {
        let a = roughness.to_matrix();
        let (a11, a12, _) = a.clamped_entries();
        let (a11, a12) = (a11.to_f64(), a12.to_f64());
        let sd = roughness.sqrt_det().to_f64();
        let (s11, s12, s22) = (k.s11.to_f64(), k.s12.to_f64(), k.s22.to_f64());
        // C = B^-1 Sigma B^-T for the Cholesky factor B of A (b22 from sqrt(det A): exact for
        // the isotropic and axis-aligned forms, accurate at any condition for the matrix
        // form), written without B: c11 = s11 / a11, c12 = (a11 s12 - a12 s11) / (a11 sd),
        // c22 = u^T Sigma u / (a11 sd^2), u = (-a12, a11). The build is latency-bound: its
        // critical path is one division, one square root and one division.
        let r = 1.0 / (a11 * sd);
        let c11 = s11 * sd * r;
        let c12 = (a11 * s12 - a12 * s11) * r;
        let c22 =
            ((a12 * a12 * s11 - 2.0 * a12 * a11 * s12 + a11 * a11 * s22) * r * (a11 * r)).max(0.0);
        // B^-1 = [[i11, 0], [i21, i22]] (off the critical path).
        let b11 = m::sqrt(a11);
        let (i11, i21, i22) = (b11 * sd * r, -a12 * b11 * r, b11 * a11 * r);
        let half = 0.5 * (c11 - c22);
        // |half|, |c12| < 1e50 (kernel <= KERNEL_MAX, lobe >= ALPHA_MIN): no overflow.
        let rad = m::sqrt(half * half + c12 * c12);
        let l1 = 0.5 * (c11 + c22) + rad;
        // l2 = det C / l1 without cancellation: det C = det Sigma / det A.
        let det_s = (s11 * s22 - s12 * s12).max(0.0);
        // The eigenvector v of l1 from the row without cancellation, unnormalised:
        // |v|^2 = 2 rad (rad + |half|); `T` holds its rows for v and v_perp, and `n2` is
        // 1 / |v|^2 (c_i^2 = (T s)_i^2 n2). One division for 1 / |v|^2 and 1 / l1.
        // (Computed for every C and selected: an isotropic C, `rad = 0`, has `v = (1, 0)`,
        // `n2 = 1` and `l2 = l1`, or `0` for `l1 = 0`.)
        let aniso = rad > 0.0;
        let (ux, uy) = if half >= 0.0 {
            (rad + half, c12)
        } else {
            (c12, rad - half)
        };
        let nv2 = 2.0 * rad * (rad + half.abs());
        let r2 = 1.0 / (nv2 * l1);
        let (vx, vy) = if aniso { (ux, uy) } else { (1.0, 0.0) };
        let n2 = if aniso { l1 * r2 } else { 1.0 };
        let l2 = if aniso {
            (det_s * (a11 * r) * (a11 * r) * (nv2 * r2)).min(l1)
        } else if l1 > 0.0 {
            l1
        } else {
            0.0
        };
        let t = [
            vx * i11 + vy * i21,
            vy * i22,
            -vy * i11 + vx * i21,
            vx * i22,
        ];
        Self {
            t,
            n2,
            tl: [2.0 * l1, 2.0 * l2],
            norm: INV_PI * a11 * r,
            b: [b11, a12 * b11 * sd * r, sd * b11 * sd * r],
            k: [s11, s12, s22],
            a,
            tol: Tolerance::Full,
        }
    }

    /// This lobe with the density (`p22`, `d`) evaluated at the accuracy setting `tolerance`
    /// (module docs, "Tolerance settings"); [`GaussianFilteredGgx::new`] gives
    /// [`Tolerance::Full`]. `Lambda` and the samplers are unchanged.
    #[inline]
    #[must_use]
    pub const fn with_tolerance(self, tolerance: Tolerance) -> Self {
        Self {
            tol: tolerance,
            ..self
        }
    }

    /// The accuracy setting of the density.
    #[inline]
    pub const fn tolerance(&self) -> Tolerance {
        self.tol
    }

    /// The unfiltered GGX lobe (its roughness as a matrix).
    #[inline]
    pub fn unfiltered(&self) -> Ggx<RoughnessMatrix> {
        Ggx::new(self.a)
    }

    /// The kernel in units of the lobe: the eigenvalues `(l1, l2)` of `B^-1 Sigma B^-T`
    /// (`A = B B^T`), `l1 >= l2 >= 0`. `2 l1` is the ratio of the filtered to the unfiltered
    /// variance along the kernel's widest direction, less one.
    #[inline]
    pub fn kernel_ratio(&self) -> (F, F) {
        (F::from_f64(0.5 * self.tl[0]), F::from_f64(0.5 * self.tl[1]))
    }

    /// `(c1^2, c2^2)` of `c = U^T B^-1 s` (module docs) in `f64`.
    #[inline(always)]
    fn whiten(&self, x: f64, y: f64) -> (f64, f64) {
        let t = &self.t;
        let (u, v) = (t[0] * x + t[1] * y, t[2] * x + t[3] * y);
        (u * u * self.n2, v * v * self.n2)
    }

    /// `P22_Sigma` at a slope given in `f64`.
    #[inline]
    fn p22_f64(&self, x: f64, y: f64) -> f64 {
        let (c1s, c2s) = self.whiten(x, y);
        if !(c1s + c2s).is_finite() {
            // |s| beyond ~1e150: the density is below every representable positive value.
            return 0.0;
        }
        self.norm * self.mixture_integral(c1s, c2s, 1.0)
    }

    /// `J / z2^2` (`quad::mixture_integral`) by the rules of the lobe's setting.
    #[inline(always)]
    fn mixture_integral(&self, v1s: f64, v2s: f64, z2: f64) -> f64 {
        let [tl1, tl2] = self.tl;
        match tol::index(self.tol) {
            None => quad::mixture_integral(v1s, v2s, z2, tl1, tl2),
            Some(0) => tol::mixture_integral::<0>(v1s, v2s, z2, tl1, tl2),
            Some(1) => tol::mixture_integral::<1>(v1s, v2s, z2, tl1, tl2),
            Some(_) => tol::mixture_integral::<2>(v1s, v2s, z2, tl1, tl2),
        }
    }

    /// `(o^T A o, o^T Sigma o)` for a tangent-plane vector `o`, in `f64`.
    #[inline]
    pub(crate) fn projected(&self, ox: f64, oy: f64) -> (f64, f64) {
        let [b11, b21, b22] = self.b;
        // o^T B B^T o = (B^T o)^2.
        let u = b11 * ox + b21 * oy;
        let v = b22 * oy;
        let [s11, s12, s22] = self.k;
        let qs = (s11 * ox * ox + 2.0 * s12 * ox * oy + s22 * oy * oy).max(0.0);
        (u * u + v * v, qs)
    }
}

impl GaussianFilteredGgx {
    /// [`Ndf::d`] in lanes (`batch::gaussian_filtered_ggx_d`): the same checks as selects,
    /// the same whitening and `J` by `quad::mixture_integral_lane` (without `TRAPEZOID` the far tail or
    /// Gauss-Laguerre, with it the trapezoid rule's first chunks), so the value of [`Ndf::d`]
    /// bit for bit where not flagged; flagged (`slow`) where `d` takes a rule the lane does
    /// not hold. `(value, slow)`.
    #[inline(always)]
    pub(crate) fn d_lane<const TRAPEZOID: bool>(&self, mn: Vec3) -> (F, bool) {
        let live = live_lane(mn);
        let z = mn.z.to_f64();
        let z2 = z * z;
        let (v1s, v2s) = self.whiten(mn.x.to_f64(), mn.y.to_f64());
        let [tl1, tl2] = self.tl;
        let (v, ok) = quad::mixture_integral_lane::<TRAPEZOID>(v1s, v2s, z2, tl1, tl2);
        finish_lane(self.norm, v, live, ok & self.full())
    }

    /// [`Self::d_lane`]`::<true>` in two stages (`batch`'s staged trapezoid lane), its first:
    /// `(value, slow, more, state)`, where `more` is false [`Self::d_lane`]`::<true>`'s
    /// `(value, slow)` bit for bit, else the state that [`Self::d_trapezoid_rest`] finishes
    /// (the trapezoid rule's element, not stopped after the first chunks).
    #[inline(always)]
    pub(crate) fn d_trapezoid_first(&self, mn: Vec3) -> (F, bool, bool, quad::TrapezoidState) {
        let live = live_lane(mn);
        let z = mn.z.to_f64();
        let z2 = z * z;
        let (v1s, v2s) = self.whiten(mn.x.to_f64(), mn.y.to_f64());
        let [tl1, tl2] = self.tl;
        let (v, ok, more, st) = quad::mixture_integral_trapezoid_first(v1s, v2s, z2, tl1, tl2);
        let full = self.full();
        let (d, slow) = finish_lane(self.norm, v, live, ok & full);
        (d, slow, live & more & full, st)
    }

    /// The second stage of [`Self::d_trapezoid_first`] at the same `mn`, from its state:
    /// `(value, slow)` of [`Self::d_lane`]`::<true>`, bit for bit.
    #[inline(always)]
    pub(crate) fn d_trapezoid_rest(&self, mn: Vec3, st: &quad::TrapezoidState) -> (F, bool) {
        let z = mn.z.to_f64();
        let z2 = z * z;
        let (v1s, v2s) = self.whiten(mn.x.to_f64(), mn.y.to_f64());
        let [tl1, tl2] = self.tl;
        let (v, ok) = quad::mixture_integral_trapezoid_rest(v1s, v2s, z2, tl1, tl2, st);
        finish_lane(self.norm, v, live_lane(mn), ok & self.full())
    }
}

/// The end of [`GaussianFilteredGgx::d_lane`]: `D = norm J / m_z^4` from `v = J / m_z^4`, `0`
/// where not `live` or not finite; `(value, slow)`, `slow` where live and not `ok`.
#[inline(always)]
fn finish_lane(norm: f64, v: f64, live: bool, ok: bool) -> (F, bool) {
    let d = F::from_f64(norm * v);
    let keep = live & (d.abs() < F::INFINITY);
    (if keep { d } else { 0.0 }, live & !ok)
}

impl GaussianFilteredGgx {
    /// Whether [`Ndf::d`] takes the trapezoid rule at `mn` (a live micronormal outside the
    /// far tail and Gauss-Laguerre, `quad::rule`): the batch driver's sort of elements
    /// between its two lanes.
    #[inline(always)]
    pub(crate) fn takes_trapezoid(&self, mn: Vec3) -> bool {
        let z = mn.z.to_f64();
        let (v1s, v2s) = self.whiten(mn.x.to_f64(), mn.y.to_f64());
        live_lane(mn) & quad::takes_trapezoid(v1s, v2s, z * z, self.tl[0]) & self.full()
    }

    /// Whether the lobe's setting is [`Tolerance::Full`], the rules the batch lanes hold: the
    /// lanes flag every element of a lobe at another setting (the scalar `d` evaluates it).
    #[inline(always)]
    fn full(&self) -> bool {
        matches!(self.tol, Tolerance::Full)
    }
}

/// Whether `D` evaluates at `mn` (finite, `m_z > 0`; else `0`): [`Ndf::d`]'s checks as one
/// branch-free expression (`abs() < inf` rather than `is_finite`, which compiles to integer
/// bit tests).
#[inline(always)]
fn live_lane(mn: Vec3) -> bool {
    (mn.z > 0.0) & (mn.x.abs() < F::INFINITY) & (mn.y.abs() < F::INFINITY) & (mn.z < F::INFINITY)
}

impl Ndf for GaussianFilteredGgx {
    /// `P22_Sigma(s) = J / (pi sqrt(det A))` (module docs); `0` for a non-finite `s`.
    #[inline]
    fn p22(&self, s: Vec2) -> F {
        if !s.is_finite() {
            return 0.0;
        }
        F::from_f64(self.p22_f64(s.x.to_f64(), s.y.to_f64()))
    }

    /// `D(m) = P22_Sigma(s(m)) / m_z^4`; `0` for `m_z <= 0` and non-finite `m`. The far tail
    /// is evaluated in homogeneous form (finite up to the horizon).
    #[inline]
    fn d(&self, mn: Vec3) -> F {
        if mn.z.is_nan() || mn.z <= 0.0 || !mn.is_finite() {
            return 0.0;
        }
        let z = mn.z.to_f64();
        let z2 = z * z;
        let (v1s, v2s) = self.whiten(mn.x.to_f64(), mn.y.to_f64());
        let v = self.mixture_integral(v1s, v2s, z2);
        let d = F::from_f64(self.norm * v);
        if d.is_finite() { d } else { 0.0 }
    }

    /// The filtered lobe's own Smith `Lambda` (module docs): the mixture of the Beckmann
    /// `Lambda` of roughness `A / w + 2 Sigma` over `e^-w dw`; GGX's closed form for the zero
    /// kernel.
    #[inline]
    fn lambda(&self, w: Vec3) -> F {
        let w = rescale_direction(w);
        // A NaN direction contributes nothing (the crate's NaN policy, `Ndf`).
        if w.is_nan() {
            return F::INFINITY;
        }
        let (ox, oy, oz) = (w.x.to_f64(), w.y.to_f64(), w.z.to_f64().abs());
        // Lambda is homogeneous of degree 0: normalise first (`w` is finite and rescaled).
        let n = m::sqrt(ox * ox + oy * oy + oz * oz);
        if n.is_nan() || n <= 0.0 || n.is_infinite() {
            return 0.0;
        }
        let (ox, oy, oz) = (ox / n, oy / n, oz / n);
        let (qa, qs) = self.projected(ox, oy);
        if qs <= 0.0 {
            // This direction does not see the kernel: every component has the projected
            // roughness of A / w, and their mixture is GGX's Lambda.
            return ggx_lambda(F::from_f64(qa), F::from_f64(oz));
        }
        if oz <= 0.0 {
            return F::INFINITY;
        }
        if qa <= 0.0 {
            // `o^T A o` underflowed beside `o^T Sigma o` (a nearly normal view of a lobe far
            // narrower than the kernel): the limit, Beckmann of `2 Sigma`.
            return F::from_f64(crate::f64::ndf::beckmann::beckmann_lambda(2.0 * qs, oz));
        }
        let v = quad::lambda(qa, qs, oz);
        // Only overflow (a view within ~1e-290 of grazing) makes the sum NaN: its limit is +inf.
        if v.is_nan() {
            F::INFINITY
        } else {
            F::from_f64(v)
        }
    }
}

/// The exact Gaussian filter: the material's slope density convolved with the pixel kernel
/// `N(0, Sigma)`, `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)` after the clamp rules
/// ([`ClampRules::footprint`], [`ClampRules::kernel`]). For GGX the lobe is
/// [`GaussianFilteredGgx`] (what [`Gaussian`] approximates by `A + 2 Sigma`); for Beckmann the
/// exact filter is `A + 2 Sigma` itself, so this gives the same lobe as [`Gaussian`] with the
/// same rules: a renderer switches NDF without switching method.
///
/// `tolerance` sets the accuracy of the GGX lobe's density ([`Tolerance`]: the proven relative
/// bound of each setting and its rules in the module docs of [`GaussianFilteredGgx`]); the
/// Beckmann lobe is exact at every setting.
///
/// ```
/// use filtered_ndf::f32::prelude::*;
/// use glam::{Vec2, Vec3};
///
/// let material = Ggx::isotropic(0.05).unwrap();
/// let footprint = Footprint::from_slope_derivatives(Vec2::new(0.04, 0.0), Vec2::new(0.0, 0.03));
/// let fast = material.filtered(footprint, ExactGaussian::KHPL16.with_tolerance(Tolerance::Rel1e3));
/// let full = material.filtered(footprint, ExactGaussian::KHPL16);
/// let h = Vec3::new(0.03, 0.01, 1.0).normalize();
/// assert!((fast.d(h) - full.d(h)).abs() <= 1e-3 * full.d(h));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactGaussian {
    /// The clamp rules applied to the footprint and the kernel (for Beckmann also the
    /// determinant clamp of the filtered matrix).
    pub clamps: ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    pub sigma: F,
    /// The accuracy setting of the GGX lobe's density ([`Tolerance::Full`] unless asked).
    pub tolerance: Tolerance,
}

impl ExactGaussian {
    /// The unbiased filter of the footprint: the maximum extent `lambda = 1` of KHPL16
    /// section 5.2 (a first-order footprint wider than that is not trustworthy), no `kappa`;
    /// `sigma = 0.5` pixels.
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
        sigma: SIGMA_PIXEL,
        tolerance: Tolerance::Full,
    };

    /// This method with the GGX lobe's density at the accuracy setting `tolerance`
    /// ([`Tolerance`]; e.g. `ExactGaussian::KHPL16.with_tolerance(Tolerance::Rel1e3)`).
    #[inline]
    #[must_use]
    pub const fn with_tolerance(self, tolerance: Tolerance) -> Self {
        Self { tolerance, ..self }
    }

    /// The clamped pixel kernel of `footprint`.
    #[inline]
    fn kernel(&self, footprint: Footprint) -> Covariance {
        let rules = self.clamps;
        rules.kernel(rules.footprint(footprint).covariance(self.sigma))
    }
}

impl Default for ExactGaussian {
    /// [`ExactGaussian::KHPL16`].
    fn default() -> Self {
        Self::KHPL16
    }
}

impl<R: Roughness> Method<Ggx<R>> for ExactGaussian {
    type Lobe = GaussianFilteredGgx;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        GaussianFilteredGgx::new(material.roughness, self.kernel(footprint))
            .with_tolerance(self.tolerance)
    }
}

impl<R: Roughness> Method<Beckmann<R>> for ExactGaussian {
    type Lobe = Beckmann<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Beckmann<R>, footprint: Footprint) -> Self::Lobe {
        Gaussian {
            clamps: self.clamps,
            sigma: self.sigma,
        }
        .lobe(material, footprint)
    }
}
