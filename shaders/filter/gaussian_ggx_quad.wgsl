#define_import_path filtered_ndf::filter::gaussian_ggx_quad

#import filtered_ndf::math

// The quadrature rules of the exact Gaussian-filtered GGX (`gaussian_ggx.wgsl`), the f32
// rules of the Rust crate's `src/.../filter/gaussian_ggx_quad.rs` (derivations and bounds in
// the module docs of `gaussian_ggx.rs`, items cited as "item N"): the far-tail series, 8-node
// Gauss-Laguerre, the trapezoid rule in `ln w` with step 0.5 and the series-corrected lower
// end (4 terms); for `Lambda` 8-node Gauss-Hermite or the sinh-substituted trapezoid rule.
// Their own errors (proven or measured in Rust): `J` within `1.6e-6 + 2e-7` relative,
// `Lambda` within `3e-7`. Differences from the Rust f32 path, which sets each rule up in f64:
// everything here is f32, with `math::exp` (the Rust polynomial, 3 ulp) and `math::ln`; each
// node's exponent is still formed against the reference node (no `eps |E|` loss from the
// exponent's size), the nodes `w_k` from one `math::exp` per chunk of 8 (4 ulp); the series
// below the first node is scaled by powers of that node (every term bounded: no overflow);
// `1 / (p1 p2)` as two quotients (no overflow for kernels up to `KERNEL_MAX`). What remains of
// f32 is the rounding of the set-up (a few ulp of each `c_i^2`, `2 l_i`), which `J` amplifies by
// its condition numbers (`gaussian_ggx.wgsl`).

/// Far-tail switch: the series replaces the quadrature where `1 + q >= FAR 2 l1`.
const FAR: f32 = 3.2e5;
/// Trapezoid step in `t = ln w`.
const H: f32 = 0.5;
/// `e^H`.
const EXP_H: f32 = 1.6487212707001282;
/// Relative truncation tolerance at the top of the trapezoid rule.
const EPS_T: f32 = 1e-7;
/// The first node lies at or below `w = Y_LO / (1 + q + 2 l1)` (the series' bound).
const Y_LO: f32 = 0.054;
/// Chunks of 8 nodes at most (the Rust table has 176 nodes).
const CHUNKS: u32 = 22u;
/// Gauss-Laguerre applies where `2 l1 <= GL_RATIO (1 + q)` ...
const GL_RATIO: f32 = 0.0177;
/// ... and `2 l1 (GL_PLATEAU + 1.5 ln(1 + q)) <= 1 + q` (item 4) ...
const GL_PLATEAU: f32 = 20.0;
/// ... which the first implies below `1 + q = GL_WIDE`.
const GL_WIDE: f32 = 2.8e10;

/// The 8-node generalised Gauss-Laguerre rule for the weight `v e^-v`: node `k`.
fn laguerre_node(k: u32) -> f32 {
    switch k {
        case 0u: { return 0.40938357320318514; }
        case 1u: { return 1.3849631848031398; }
        case 2u: { return 2.956254556168862; }
        case 3u: { return 5.181943101040071; }
        case 4u: { return 8.161709688145818; }
        case 5u: { return 12.070055126837154; }
        case 6u: { return 17.24973552614899; }
        default: { return 24.585955243652784; }
    }
}

/// The 8-node Gauss-Laguerre rule: weight `k`.
fn laguerre_weight(k: u32) -> f32 {
    switch k {
        case 0u: { return 0.18763254140572366; }
        case 1u: { return 0.43898536073114236; }
        case 2u: { return 0.28999607078131334; }
        case 3u: { return 0.07514138461669734; }
        case 4u: { return 0.007932646648707345; }
        case 5u: { return 0.0003086421368133042; }
        case 6u: { return 3.348958209797096e-6; }
        default: { return 4.721392823193221e-9; }
    }
}

/// `J / z2^2` for `c_i^2 = v_i^2 / z2` from `(v1^2, v2^2)`, `z2 > 0` and `(2 l1, 2 l2)`,
/// `2 l1 >= 2 l2 >= 0` (the Rust `mixture_integral`): `J(c)` itself for `z2 = 1` (a slope), `J / m_z^4` for a
/// normal (`z2 = m_z^2`, `v = T m_xy`) without forming the slope. The rule by `q = |c|^2` and
/// the kernel ratio (module docs).
fn mixture_integral(v1s: f32, v2s: f32, z2: f32, tl1: f32, tl2: f32) -> f32 {
    let beta_m = z2 + v1s + v2s;
    if beta_m >= FAR * tl1 * z2 {
        return far_tail(beta_m, v1s, v2s, tl1, tl2, z2);
    }
    if tl1 * z2 <= GL_RATIO * beta_m
        && (beta_m <= GL_WIDE * z2 || tl1 * (GL_PLATEAU + 1.5 * math::ln(beta_m / z2)) * z2 <= beta_m) {
        return laguerre(beta_m, v1s, v2s, z2, tl1, tl2);
    }
    let iz2 = 1.0 / z2;
    return trapezoid_rule(v1s * iz2, v2s * iz2, tl1, tl2, FULL_RULE) * iz2 * iz2;
}

/// The far-tail series of `J` (item 5), homogeneous as [`mixture_integral`]:
/// `J = beta^-2 (1 + 12 P z2 / beta^2 - 2 (l1 + l2) z2 / beta)`, `P = l1 c1^2 + l2 c2^2`
/// (`P / beta` formed first: no overflow).
fn far_tail(beta: f32, c1s: f32, c2s: f32, tl1: f32, tl2: f32, z2: f32) -> f32 {
    let ib = 1.0 / beta;
    let p_ib = 0.5 * (tl1 * (c1s * ib) + tl2 * (c2s * ib));
    let ls = 0.5 * (tl1 + tl2);
    return ib * ib * (1.0 + z2 * ib * (12.0 * p_ib - 2.0 * ls));
}

/// Gauss-Laguerre in `v = (1 + q) w` (item 4): `J = beta^-2 sum W_k F(v_k / beta)`,
/// `F(w) = exp(sum c_i^2 2 l_i w^2 / p_i) / sqrt(p1 p2)`; homogeneous as [`mixture_integral`].
fn laguerre(beta_m: f32, v1s: f32, v2s: f32, z2: f32, tl1: f32, tl2: f32) -> f32 {
    let ib = 1.0 / beta_m;
    let t1 = tl1 * z2 * ib;
    let t2 = tl2 * z2 * ib;
    let g1 = (v1s * ib) * t1;
    let g2 = (v2s * ib) * t2;
    var acc = 0.0;
    for (var k = 0u; k < 8u; k++) {
        let v = laguerre_node(k);
        let p1 = 1.0 + t1 * v;
        let p2 = 1.0 + t2 * v;
        let ip1 = 1.0 / p1;
        let ip2 = 1.0 / p2;
        let e = v * v * (g1 * ip1 + g2 * ip2);
        acc += laguerre_weight(k) * math::exp(e) * sqrt(ip1) * sqrt(ip2);
    }
    return acc * ib * ib;
}

/// The constants of a trapezoid rule in `ln w` (items 2 and 3, and the Rust `Tolerance`
/// settings): step `h`, `e^h`, the truncation tolerance, the first node's bound `Y`, the
/// geometric sums `1 / (e^((n + 2) h) - 1)`, `n < 4`, of the series below the first node, and
/// the most nodes (a multiple of 8, `nodes h <= 88`: every `e^(k h)` finite in f32).
struct TrapezoidRule {
    h: f32,
    exp_h: f32,
    eps_t: f32,
    y_lo: f32,
    geom: vec4<f32>,
    nodes: u32,
}

/// The full rule (step 0.5).
const FULL_RULE: TrapezoidRule = TrapezoidRule(H, EXP_H, EPS_T, Y_LO, vec4<f32>(0.5819767068693265, 0.2872169167888683, 0.15651764274966565, 0.08942548983385201), CHUNKS * 8u);

/// The accuracy settings (the Rust `Tolerance`): `TOL_FULL` the rules above; the others the
/// far-tail series where `2 l1 (K + 12 ln(1 + q)) <= 1 + q`, else the trapezoid rule of
/// [`reduced_rule`], with the relative bounds `1e-4`, `1e-3`, `1e-2` (Rust module docs,
/// "Tolerance settings"); their constants are the Rust rules' (written by `generate`). `ln` is
/// `math::ln` here, not the Rust upper bound, so the switch can sit a few ulp of `1 + q` away
/// from the Rust one: both rules hold their bounds on both sides. The truncation test runs
/// every 8 nodes (Rust: 4), so the WGSL never stops earlier than the Rust rule.
const TOL_FULL: u32 = 0u;
const TOL_1E4: u32 = 1u;
const TOL_1E3: u32 = 2u;
const TOL_1E2: u32 = 3u;

// BEGIN reduced rules
// Written by `cargo run -p filtered-ndf-gpu --bin generate` from the Rust rules
// (`filtered_ndf::testing::tolerance_rules`); do not edit.

/// The far-tail switch `K` of a reduced setting (`TOL_1E4`, `TOL_1E3`, else `TOL_1E2`).
fn reduced_far(tol: u32) -> f32 {
    switch tol {
        case 1u: { return 1500.0; }
        case 2u: { return 500.0; }
        default: { return 160.0; }
    }
}

/// The trapezoid rule of a reduced setting (`TOL_1E4`, `TOL_1E3`, else `TOL_1E2`): the
/// Rust rule's constants, its node count rounded down to the 8-node chunks of
/// [`trapezoid_rule`].
fn reduced_rule(tol: u32) -> TrapezoidRule {
    switch tol {
        case 1u: { return TrapezoidRule(0.6, 1.8221188003905089, 1e-5, 0.12, vec4<f32>(0.43101276069333316, 0.19803362651500594, 0.09976877209617539, 0.05239569649125596), 144u); }
        case 2u: { return TrapezoidRule(0.75, 2.117000016612675, 0.0001, 0.2, vec4<f32>(0.2872169167888682, 0.11781705030408056, 0.05239569649125593, 0.02408415079352912), 112u); }
        default: { return TrapezoidRule(1.0, 2.718281828459045, 0.0005, 0.35, vec4<f32>(0.15651764274966568, 0.05239569649125596, 0.01865736036377405, 0.006783654906304232), 88u); }
    }
}
// END reduced rules

/// `J / z2^2` (as [`mixture_integral`]) at the accuracy setting `tol` (`TOL_FULL` to `TOL_1E2`).
fn j_tol(v1s: f32, v2s: f32, z2: f32, tl1: f32, tl2: f32, tol: u32) -> f32 {
    if tol == TOL_FULL {
        return mixture_integral(v1s, v2s, z2, tl1, tl2);
    }
    let beta_m = z2 + v1s + v2s;
    if tl1 * z2 * (reduced_far(tol) + 12.0 * math::ln(beta_m / z2)) <= beta_m {
        return far_tail(beta_m, v1s, v2s, tl1, tl2, z2);
    }
    let iz2 = 1.0 / z2;
    return trapezoid_rule(v1s * iz2, v2s * iz2, tl1, tl2, reduced_rule(tol)) * iz2 * iz2;
}

/// The nodes below `w_first` (item 2): `sum_k w_k^2 phi(w_k)` over `w_k = w_first e^(-k H)`,
/// `k >= 1`, with `phi = exp(-w - E(w)) / sqrt(p1 p2) = sum a_n w^n` truncated after 4 terms.
/// Scaled by `y = w_first`: with `x_i = 2 l_i y`, `d_i = c_i^2 y` (both `<= Y_LO`), the
/// coefficients `b~_n = b_n y^n` of `ln phi` and `a~_n = a_n y^n` are bounded, and the sum is
/// `y^2 sum_n a~_n / (e^((n + 2) H) - 1)`.
fn series_below(c1s: f32, c2s: f32, tl1: f32, tl2: f32, y: f32, geom: vec4<f32>) -> f32 {
    let x1 = tl1 * y;
    let x2 = tl2 * y;
    let d1 = c1s * y;
    let d2 = c2s * y;
    // b~_n for n = 1..3 (coefficient of w^n times y^n): -(d1 (-x1)^(n-1) + d2 (-x2)^(n-1))
    // from -E, + ((-x1)^n + (-x2)^n) / (2 n) from -ln(p1 p2) / 2, and -y for n = 1.
    let b1 = -(d1 + d2) - 0.5 * (x1 + x2) - y;
    let b2 = (d1 * x1 + d2 * x2) + 0.25 * (x1 * x1 + x2 * x2);
    let b3 = -(d1 * x1 * x1 + d2 * x2 * x2) - (1.0 / 6.0) * (x1 * x1 * x1 + x2 * x2 * x2);
    // n a_n = sum_j j b_j a_(n-j).
    let a1 = b1;
    let a2 = 0.5 * (b1 * a1 + 2.0 * b2);
    let a3 = (1.0 / 3.0) * (b1 * a2 + 2.0 * b2 * a1 + 3.0 * b3);
    let tail = geom.x + a1 * geom.y + a2 * geom.z + a3 * geom.w;
    return tail * y * y;
}

/// The trapezoid rule in `t = ln w` (items 1 to 3): nodes `w_k = w_r e^((k - k0) H)` from the
/// first node at or below `Y_LO / (1 + q + 2 l1)`, the nodes below it summed by
/// [`series_below`], each exponent against the reference `w_r = 2 / (1 + q)`, the top truncated
/// by the monotone bound, in chunks of 8 nodes; the constants of `rule` (the first node's
/// offset `k0 h` at most 87, so that `e^(-k0 h)` is a normal f32).
fn trapezoid_rule(c1s: f32, c2s: f32, tl1: f32, tl2: f32, rule: TrapezoidRule) -> f32 {
    let hs = rule.h;
    let beta = 1.0 + c1s + c2s;
    let ib = 1.0 / beta;
    let w_r = 2.0 * ib;
    // k0 h >= ln(w_r / w_lo), w_lo = Y / (beta + 2 l1).
    let k0 = min(ceil(math::ln(2.0 / rule.y_lo * (beta + tl1) * ib) / hs), min(f32(rule.nodes - 1u), floor(87.0 / hs)));
    let w_first = w_r * math::exp(-k0 * hs);
    // The reference exponent x_r = -w_r - E(w_r); E(w) - E(w_r) = sum c_i^2 (w - w_r) /
    // (p_i(w) p_i(w_r)) without cancellation.
    let pr1 = 1.0 + tl1 * w_r;
    let pr2 = 1.0 + tl2 * w_r;
    let k1 = c1s * (w_r / pr1);
    let k2 = c2s * (w_r / pr2);
    let x_r = -w_r - k1 - k2;
    let scale = w_r * w_r * math::exp(x_r);
    // Per node, v = w / w_r = e^((k - k0) hs), p_i = 1 + (2 l_i w_r) v:
    // g / scale = exp(2 ln v - (v - 1)(w_r + k1 / p1 + k2 / p2)) / sqrt(p1 p2).
    let t1 = tl1 * w_r;
    let t2 = tl2 * w_r;
    let stop = rule.eps_t * hs * w_r * w_r;
    var sum = 0.0;
    for (var ch = 0u; ch < rule.nodes / 8u; ch++) {
        let kb = f32(ch * 8u) - k0;
        var v = math::exp(kb * hs);
        var part = 0.0;
        var last = 0.0;
        var vl = v;
        for (var jj = 0u; jj < 8u; jj++) {
            let ip1 = 1.0 / (1.0 + t1 * v);
            let ip2 = 1.0 / (1.0 + t2 * v);
            let a = w_r + k1 * ip1 + k2 * ip2;
            let x = 2.0 * hs * (kb + f32(jj)) - (v - 1.0) * a;
            last = math::exp(x) * sqrt(ip1) * sqrt(ip2);
            part += last;
            vl = v;
            v = v * rule.exp_h;
        }
        sum += part;
        // Item 3: the nodes above the last sum to at most g_last b / w_last^2.
        let wl = vl * w_r;
        let b = select(7.47, 1.0 + wl, wl >= 2.0);
        if last * b <= stop * sum * vl * vl {
            break;
        }
    }
    return hs * (sum * scale + series_below(c1s, c2s, tl1, tl2, w_first, rule.geom));
}

/// The 8-node Gauss-Hermite rule for the standard normal density: positive node `k`
/// (the rule is symmetric).
fn hermite_node(k: u32) -> f32 {
    switch k {
        case 0u: { return 0.5390798113513751; }
        case 1u: { return 1.636519042435108; }
        case 2u: { return 2.8024858612875416; }
        default: { return 4.1445471861258945; }
    }
}

/// The 8-node Gauss-Hermite rule: weight of node `k` (and of its mirror).
fn hermite_weight(k: u32) -> f32 {
    switch k {
        case 0u: { return 0.37301225767907736; }
        case 1u: { return 0.11723990766175901; }
        case 2u: { return 0.009635220120788266; }
        default: { return 0.00011261453837536777; }
    }
}

/// `h(y) = sqrt(1 + y^2) - y` without cancellation or overflow: `1 / (sqrt(1 + y^2) + y)` for
/// `y >= 0`.
fn h_of(y: f32) -> f32 {
    let a = abs(y);
    var r: f32;
    if a > 1.0 {
        let i = 1.0 / a;
        r = a * sqrt(1.0 + i * i);
    } else {
        r = sqrt(1.0 + y * y);
    }
    return select(r - y, 1.0 / (r + y), y >= 0.0);
}

/// Gauss-Hermite `Lambda` (item 6) in units of `sqrt(qa)`: `sum W_k h(z0 - sigma x_k) / (2 z0)`,
/// `z0 = oz / sqrt(qa)`, `sigma = sqrt(qs / qa)`.
fn lambda_hermite(qa: f32, qs: f32, oz: f32) -> f32 {
    let iq = 1.0 / qa;
    let z0 = oz * sqrt(iq);
    let fs = sqrt(qs * iq);
    var acc = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let x = fs * hermite_node(k);
        acc += hermite_weight(k) * (h_of(z0 - x) + h_of(z0 + x));
    }
    return acc / (2.0 * z0);
}

/// Gauss-Hermite applies where `delta_s^2 = qs / (qa + oz^2) <= GH_MAX` (item 6).
const GH_MAX: f32 = 0.01;
/// The sinh rule's step `min(S_MAX, S_COEF sqrt(delta_s))`, truncation `S_EPS`, and its
/// safety net on the nodes per direction (never reached).
const S_MAX: f32 = 0.25;
const S_COEF: f32 = 0.25;
const S_EPS: f32 = 1e-8;
const S_MAX_CHUNKS: u32 = 512u;

/// One direction of the sinh rule (see [`lambda_sinh`]): nodes `T = e^(d/2)`, `d = +-k h`
/// (`k >= 0` up, `k >= 1` down), each `T` by one `math::exp`; stops (every 8 nodes) once the
/// terms fall by half per node and the last is `<= S_EPS` of the running total.
fn sinh_run(up: bool, h: f32, rq: f32, e0: f32, ie0: f32, i2s2: f32, e2: f32, c_stop: f32, total_in: f32) -> f32 {
    var total = total_in;
    let sgn = select(-1.0, 1.0, up);
    let first = select(1u, 0u, up);
    for (var ch = 0u; ch < S_MAX_CHUNKS; ch++) {
        var fl = 0.0;
        var xl = 0.0;
        var part = 0.0;
        for (var jj = 0u; jj < 8u; jj++) {
            let k = f32(first + ch * 8u + jj);
            let t = math::exp(sgn * 0.5 * h * k);
            let it = 1.0 / t;
            // oz - sqrt(qa) sinh(s0 + d) = -sqrt(qa) 2 cosh(s0 + d/2) sinh(d/2).
            let x = -0.5 * rq * (e0 * t + ie0 * it) * (t - it);
            let arg = -x * x * i2s2;
            let it2 = it * it;
            fl = select(0.0, math::exp(arg) * (1.0 + e2 * it2 * it2), arg > -87.0);
            xl = x;
            part += fl;
        }
        total += part;
        let done = select(xl >= c_stop, -xl >= c_stop, up);
        if done && fl <= S_EPS * total {
            break;
        }
    }
    return total;
}

/// The trapezoid rule in `s`, `y = sqrt(qa) sinh s` (item 6):
/// `Lambda = qa / (4 oz) integral phi_sigma(oz - sqrt(qa) sinh s) (1 + e^-2s) ds`, nodes
/// `s0 + k h` with `sinh s0 = oz / sqrt(qa)`, outward from `s0` in both directions.
fn lambda_sinh(qa: f32, qs: f32, oz: f32, ds2: f32) -> f32 {
    let rq = sqrt(qa);
    let root = oz + sqrt(qa + oz * oz);
    let e0 = root / rq;
    let ie0 = rq / root;
    let h = min(S_MAX, S_COEF * sqrt(sqrt(ds2)));
    let i2s2 = 0.5 / qs;
    // |x| sqrt(qa) h / qs beyond which the terms fall by half per node (Rust module docs).
    let c_up = math::LN_2 * qs / (rq * h);
    let c_down = (2.0 * h + math::LN_2) * qs / (rq * h);
    let e2 = ie0 * ie0;
    let up = sinh_run(true, h, rq, e0, ie0, i2s2, e2, c_up, 0.0);
    let all = sinh_run(false, h, rq, e0, ie0, i2s2, e2, c_down, up);
    return all * (h * qa / (4.0 * oz * sqrt(qs) * math::SQRT_TAU));
}

/// Smith `Lambda` of the filtered lobe (item 6) for `qa = o^T A o > 0`, `qs = o^T Sigma o > 0`
/// and `oz = |o_z| > 0` (unit `o`): `Lambda = E[h(oz - Z)] / (2 oz)`, `Z ~ N(0, qs)`.
fn lambda(qa: f32, qs: f32, oz: f32) -> f32 {
    let ds2 = qs / (qa + oz * oz);
    if ds2 <= GH_MAX {
        return lambda_hermite(qa, qs, oz);
    }
    return lambda_sinh(qa, qs, oz, ds2);
}
