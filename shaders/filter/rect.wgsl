#define_import_path filtered_ndf::filter::rect

#import filtered_ndf::math
#import filtered_ndf::ndf::ggx
#import filtered_ndf::ndf::roughness::axis_aligned

// The exact box filter of GGX (KHPL16 eq. 16 and Appendix A; GDC 2016 `GGXRectIntegral`),
// mirroring `src/.../filter/rect.rs`: the average of the axis-aligned GGX slope density over
// an axis-aligned slope-domain rectangle, and its solid-angle form.
//
// With `u = x / alpha_x`, `v = y / alpha_y` the density is `f(u, v) / (pi alpha_x alpha_y)`,
// `f = (1 + u^2 + v^2)^-2`, and the filter is the mean of `f` over
// `[u_c +- H_u] x [v_c +- H_v]`. The printed eight-term formula cancels catastrophically (in
// f32 already for moderate rectangles). The f32 algorithm here follows the Rust tiers, every
// path a sum of positive terms or a signed sum of four terms that do not cancel much:
// - each axis is carried as its normalised interval, the ends formed as `(c -+ |h|) / alpha`
//   before normalising ([`interval`]), so that a rectangle ending close to the peak keeps its
//   distance to the accuracy of its ends;
// - per axis, from its ratio `H / L` (`L^2 = 1 + (centre)^2 + (distance of the rectangle from
//   the peak along the other axis)^2`, the distance to the density's complex poles):
//   Gauss-Legendre with 2 nodes below `0.01`, 4 below `0.1`, 6 below `0.25` (error
//   `~(H / 2L)^(2n)`, below `1e-8` at each switch: invisible in f32), the closed form above;
// - both axes short: the tensor Gauss-Legendre rule;
// - one axis long: the rule in the short axis of the exact 1D mean in the long one
//   ([`mean_1d`], written without cancellation; its `atan` is `math::atan`);
// - both long, within `sqrt(FAR2) = 0.5` (normalised) of the peak: the four-edge closed form
//   ([`edges`]), whose four terms are angles of order one;
// - both long and farther: the polar form of the Rust `far_field` ([`far_field`]): the
//   integral is `-1/2` times the contour integral of `g d theta`, `g = 1 / (1 + r^2)`, one
//   positive integral per edge, each split where `|y| = |x|` and taken by the 8-point
//   Gauss-Legendre rule in `y / |x|` or `|x| / y` (rational in both: no `sin`/`cos`, whose
//   WGSL accuracy is absolute). The four-edge form there cancelled like `1e-6 D^2` in f32
//   (up to `0.25` relative far in the tail of sharp lobes); measured on lavapipe over
//   rectangles with both sides long at distances `D` from `1e-2` to `1e6` lobe widths: the
//   four-edge form within `4e-7` below `D = 0.3` and `3e-5` at `D ~ 3`, the polar form within
//   `5e-7` beyond `D = 0.5` (`2e-4` at `D = 0.1`, where its poles come close): the switch at
//   `0.5`.
// Bound: about 60 ulp for the Gauss-Legendre and 1D paths (the ends and half extents enter
// normalised, 5 ulp each, and `f` amplifies a relative change of `u` by at most 4; the nodes'
// `f` 9 ulp; `mean_1d` 20 ulp), and for the two four-term forms 60 ulp plus 16 ulp times
// their cancellation factor `sum |t_i| / |sum t_i|`, of order one (`gpu/src/checks/rect.rs`
// computes it per case; measured worst over its far-tail cases `4e-7`). [`d_rect`] forms the
// slope `-h_xy / h_z` in f32 (3 ulp), which a rectangle ending close to the peak amplifies
// by `|u_c| / gap`.

/// Normalised coordinates are clamped to this (`f` is below `1e-72` there, 0 in f32).
const BIG: f32 = 1e18;

/// Squared distance (normalised) of a rectangle with two long sides from the peak beyond
/// which [`far_field`] replaces the four-edge closed form [`edges`] (module docs).
const FAR2: f32 = 0.25;

/// The tier of an axis: 2, 4 or 6 Gauss-Legendre nodes, or the closed form (`TIER_CLOSED`).
const TIER_CLOSED: u32 = 0u;

/// The tier of an axis from `H^2` and `L^2` (module docs): the number of nodes, or
/// `TIER_CLOSED`.
fn tier(h2: f32, l2: f32) -> u32 {
    if h2 < 1e-4 * l2 {
        return 2u;
    }
    if h2 < 1e-2 * l2 {
        return 4u;
    }
    if h2 < 0.0625 * l2 {
        return 6u;
    }
    return TIER_CLOSED;
}

/// The `k`-th positive Gauss-Legendre node on `[-1, 1]` of the `n`-node rule.
fn gl_node(n: u32, k: u32) -> f32 {
    if n == 2u {
        return 0.5773502691896258;
    }
    if n == 4u {
        return select(0.8611363115940526, 0.3399810435848563, k == 0u);
    }
    if k == 0u {
        return 0.2386191860831969;
    }
    return select(0.932469514203152, 0.6612093864662645, k == 1u);
}

/// The `k`-th weight of the `n`-node rule, halved (the rule then averages over `[-1, 1]`).
fn gl_weight(n: u32, k: u32) -> f32 {
    if n == 2u {
        return 0.5;
    }
    if n == 4u {
        return select(0.17392742256872693, 0.32607257743127307, k == 0u);
    }
    if k == 0u {
        return 0.2339569672863455;
    }
    return select(0.0856622461895852, 0.1803807865240693, k == 1u);
}

/// `f(u, v) = (1 + u^2 + v^2)^-2` (0 where the square overflows).
fn f(u: f32, v: f32) -> f32 {
    let t = 1.0 + u * u + v * v;
    return 1.0 / (t * t);
}

/// The mean of `f(u, .)` over `[c - h, c + h]` by the `n`-node rule (sum of positive terms).
fn gl_mean(n: u32, u: f32, c: f32, h: f32) -> f32 {
    var acc = 0.0;
    for (var k = 0u; k < n / 2u; k++) {
        let a = h * gl_node(n, k);
        acc += gl_weight(n, k) * (f(u, c - a) + f(u, c + a));
    }
    return acc;
}

/// `atan2(y, x)` for `y > 0`, in `(0, pi)`, with one `math::atan`.
fn atan2_upper(y: f32, x: f32) -> f32 {
    if x > 0.0 {
        return math::atan(y / x);
    }
    return math::HALF_PI + math::atan(-x / y);
}

/// `delta - sin(delta)` for `delta` in `[0, pi]` given `sin(delta)` (a series below 1, where
/// the difference cancels; its next term is below `1e-9` relative at 1).
fn delta_minus_sin(d: f32, sin_d: f32) -> f32 {
    if d < 1.0 {
        let d2 = d * d;
        var s = 1.0 - d2 * (1.0 / 72.0) * (1.0 - d2 * (1.0 / 110.0));
        s = 1.0 - d2 * (1.0 / 42.0) * s;
        s = 1.0 - d2 * (1.0 / 20.0) * s;
        return d * d2 * (1.0 / 6.0) * s;
    }
    return d - sin_d;
}

/// The exact mean of `(c2 + x^2)^-2` over the interval `i` of an axis (`hx > 0`, `c2 >= 1`)
/// without cancellation (the Rust `mean_1d`): reflected so that `x0 = |x_c| - hx`,
/// `x1 = |x_c| + hx` (the ends as given, not recomputed from the centre), with `c^2 = c2`,
/// `delta = atan(x1 / c) - atan(x0 / c) = atan2(c dx, c2 + x0 x1)` and `r_i^2 = c2 + x_i^2`,
/// `int = delta / (2 c^3) + dx (c2 - x0 x1) / (2 c2 r0^2 r1^2)` when the interval straddles
/// 0, else `(delta - sin delta) / (2 c^3) + dx / (2 r0^2 r1^2) [1 + (x0^2 + x1^2 + c2) /
/// (r0 r1 + x0 x1)]`, all terms positive.
fn mean_1d(i: vec4<f32>, c2: f32) -> f32 {
    let x0 = select(-i.y, i.x, i.z >= 0.0);
    let x1 = select(-i.x, i.y, i.z >= 0.0);
    let dx = 2.0 * i.w;
    let c = sqrt(c2);
    let r02 = c2 + x0 * x0;
    let r12 = c2 + x1 * x1;
    let x01 = x0 * x1;
    let d = atan2_upper(c * dx, c2 + x01);
    let inv = 1.0 / (2.0 * c * c2 * dx);
    if x0 <= 0.0 {
        // `(c2 - x0 x1) / (2 c2 r0^2 r1^2)` as the product of three factors in (0, 1]:
        // `q = (c2 - x0 x1) / (r0 r1)` (Cauchy-Schwarz, as `x0 <= 0 <= x1`), `s = 1 / (r0 r1)`
        // and `0.5 / c2`. However a compiler groups it, no partial product is below the term,
        // so none is subnormal unless the term is; `min` keeps `q` from being regrouped. As
        // `(c2 - x01) / p2 / c2` it lost the term on NVIDIA's Vulkan driver (H200, driver
        // 580): its compiler merges the two divisions into one by `c2 p2`, beyond `2^126`
        // for coordinates beyond about `1e6`, whose reciprocal flushes to 0 (`p22_rect` 15 %
        // low in the far tail; WGSL lets a driver flush subnormals).
        let s = inverseSqrt(r02) * inverseSqrt(r12);
        let q = min((c2 - x01) * s, 1.0);
        return d * inv + q * s * (0.5 / c2);
    }
    let rr = sqrt(r02) * sqrt(r12);
    let p2 = 2.0 * r02 * r12;
    return delta_minus_sin(d, c * dx / rr) * inv + (1.0 + (x0 * x0 + x1 * x1 + c2) / (rr + x01)) / p2;
}

/// The mean of `g(x) = mean_1d(other, 1 + x^2)` over `[c - h, c + h]` by the `n`-node rule.
fn gl_mean_1d(n: u32, c: f32, h: f32, other: vec4<f32>) -> f32 {
    var acc = 0.0;
    for (var k = 0u; k < n / 2u; k++) {
        let a = h * gl_node(n, k);
        let x0 = c - a;
        let x1 = c + a;
        acc += gl_weight(n, k) * (mean_1d(other, 1.0 + x0 * x0) + mean_1d(other, 1.0 + x1 * x1));
    }
    return acc;
}

/// One edge of the contour form: `u / S atan2(dv S, S^2 + v0 v1)`, `S = sqrt(1 + u^2)`.
fn edge(u: f32, dv: f32, v01: f32) -> f32 {
    let s2 = 1.0 + u * u;
    let s = sqrt(s2);
    return u / s * atan2_upper(dv * s, s2 + v01);
}

/// The four-edge closed form (Lambert's contour form; KHPL16 Appendix A with each edge's two
/// arctangents merged): the mean of `f` over the rectangle of the axis intervals `u`, `v`.
/// Cancels away from the peak (module docs): used within `sqrt(FAR2)` of it.
fn edges(u: vec4<f32>, v: vec4<f32>) -> f32 {
    let du = 2.0 * u.w;
    let dv = 2.0 * v.w;
    let v01 = v.x * v.y;
    let u01 = u.x * u.y;
    let i = 0.5 * ((edge(u.y, dv, v01) - edge(u.x, dv, v01)) + (edge(v.y, du, u01) - edge(v.x, du, u01)));
    return i / (du * dv);
}

/// The positive nodes of the 8-point Gauss-Legendre rule on `[-1, 1]`.
fn gl8_node(k: u32) -> f32 {
    if k == 0u {
        return 0.1834346424956498;
    }
    if k == 1u {
        return 0.525532409916329;
    }
    return select(0.9602898564975363, 0.7966664774136267, k == 2u);
}

/// The weights of the 8-point rule, halved (the rule then averages over `[-1, 1]`).
fn gl8_weight(k: u32) -> f32 {
    if k == 0u {
        return 0.181341891689181;
    }
    if k == 1u {
        return 0.15685332293894364;
    }
    return select(0.05061426814518813, 0.11119051722668724, k == 2u);
}

/// `integral over tau in [lo, hi] of 1 / ((1 + tau^2)(1 + x2 (1 + tau^2)))` (`[lo, hi]` in
/// `[0, 1]`), by the 8-point rule: the part `|y| <= |x|` of an edge of [`far_field`], in
/// `tau = y / |x|`. Poles at `tau = +-i` and `+-i sqrt(1 + 1 / x2)`: at least `1` from the
/// segment, whose length is at most 1 (error below `2.4e-11` relative, from the Bernstein
/// ellipse through `i` of `[0, 1]`, `rho = 4.6`).
fn polar_near(x2: f32, lo: f32, hi: f32) -> f32 {
    let c = 0.5 * (lo + hi);
    let h = 0.5 * (hi - lo);
    var acc = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let d = h * gl8_node(k);
        let q0 = 1.0 + (c - d) * (c - d);
        let q1 = 1.0 + (c + d) * (c + d);
        acc += gl8_weight(k) * (1.0 / (q0 * (1.0 + x2 * q0)) + 1.0 / (q1 * (1.0 + x2 * q1)));
    }
    return acc * (hi - lo);
}

/// `integral over t in [lo, hi] of t^2 / ((1 + t^2)(t^2 + x2 (1 + t^2)))` (`[lo, hi]` in
/// `[0, 1]`), by the 8-point rule: the part `|y| >= |x|` of an edge of [`far_field`], in
/// `t = |x| / |y|`. Poles at `t = +-i` and `+-i |x| / sqrt(1 + x2)`; with every point of the
/// rectangle at least `sqrt(FAR2)` from the peak the segment ends at `|x| / |y| <= |x| /
/// sqrt(FAR2 - x2)` (module docs), at least `2.4` half-lengths from the nearer pole
/// (`rho >= 4.6`: error below `2.4e-11` relative).
fn polar_far(x2: f32, lo: f32, hi: f32) -> f32 {
    let c = 0.5 * (lo + hi);
    let h = 0.5 * (hi - lo);
    var acc = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let d = h * gl8_node(k);
        let t0 = (c - d) * (c - d);
        let t1 = (c + d) * (c + d);
        acc += gl8_weight(k) * (t0 / ((1.0 + t0) * (t0 + x2 * (1.0 + t0))) + t1 / ((1.0 + t1) * (t1 + x2 * (1.0 + t1))));
    }
    return acc * (hi - lo);
}

/// `integral over y in [a, b] of |x| / ((x^2 + y^2)(1 + x^2 + y^2))` for `0 <= a <= b` and
/// `ax = |x| > 0`: the integral of `g d theta` along the edge `{x} x [a, b]` (`g = 1 / (1 + r^2)`,
/// `theta` the polar angle about the peak), split at `y = |x|` into [`polar_near`] and
/// [`polar_far`], both sums of positive terms.
fn edge_range(ax: f32, a: f32, b: f32) -> f32 {
    let x2 = ax * ax;
    var v = 0.0;
    if a < ax {
        v += polar_near(x2, a / ax, min(b, ax) / ax);
    }
    if b > ax {
        v += polar_far(x2, ax / b, ax / max(a, ax));
    }
    return v;
}

/// `sign(x)` times the integral of `g d theta` along the edge `{x} x [a, b]`, `a < b` (either
/// orientation of the axes). An edge within `1e-12` of the axis through the peak contributes at
/// most `1e-12` of the rectangle's integral (its angle integral is below `|x| (1/a - 1/b)`): 0.
fn edge_polar(x: f32, a: f32, b: f32) -> f32 {
    let ax = abs(x);
    if ax < 1e-12 {
        return 0.0;
    }
    var v: f32;
    if a >= 0.0 {
        v = edge_range(ax, a, b);
    } else if b <= 0.0 {
        v = edge_range(ax, -b, -a);
    } else {
        v = edge_range(ax, 0.0, -a) + edge_range(ax, 0.0, b);
    }
    return select(-v, v, x > 0.0);
}

/// The mean of `f` over a rectangle whose every point is at least `sqrt(FAR2)` from the peak
/// (both sides long), by the polar form of the Rust `far_field` (module docs): with
/// `g(r) = 1 / (1 + r^2)`, `f dA` is the exterior derivative of `-g / 2 d theta`, so the
/// integral is `-1/2` times the contour integral of `g d theta`, one positive integral per
/// edge ([`edge_polar`]); the four terms are those of the near and far sides seen from the
/// peak and do not cancel like the four-edge closed form's angles.
fn far_field(u: vec4<f32>, v: vec4<f32>) -> f32 {
    let i = -0.5 * ((edge_polar(u.y, v.x, v.y) - edge_polar(u.x, v.x, v.y)) + (edge_polar(v.y, u.x, u.y) - edge_polar(v.x, u.x, u.y)));
    return i / (4.0 * u.w * v.w);
}

/// The distance of an axis interval from 0 (0 if it contains 0), from its ends.
fn gap(i: vec4<f32>) -> f32 {
    return max(max(i.x, -i.y), 0.0);
}

/// The mean of `f` over the rectangle of the axis intervals `u`, `v` by the tiers of the
/// module docs. An interval is `(lo, hi, centre, half)` in normalised coordinates, its ends
/// formed from the slope-domain centre and half extent before normalising
/// ([`interval`]): where a rectangle ends close to the peak, its distance is then as accurate
/// as the ends (recomputing it as `centre - half` after normalising would cancel).
fn mean_f(u: vec4<f32>, v: vec4<f32>) -> f32 {
    let du = gap(u);
    let dv = gap(v);
    let tu = tier(u.w * u.w, 1.0 + u.z * u.z + dv * dv);
    let tv = tier(v.w * v.w, 1.0 + v.z * v.z + du * du);
    if tu == TIER_CLOSED && tv == TIER_CLOSED {
        if du * du + dv * dv > FAR2 {
            return far_field(u, v);
        }
        return edges(u, v);
    }
    if tu == TIER_CLOSED {
        return gl_mean_1d(tv, v.z, v.w, u);
    }
    if tv == TIER_CLOSED {
        return gl_mean_1d(tu, u.z, u.w, v);
    }
    var acc = 0.0;
    for (var k = 0u; k < tu / 2u; k++) {
        let a = u.w * gl_node(tu, k);
        acc += gl_weight(tu, k) * (gl_mean(tv, u.z - a, v.z, v.w) + gl_mean(tv, u.z + a, v.z, v.w));
    }
    return acc;
}

/// The normalised interval `(lo, hi, centre, half)` of one axis of the rectangle
/// `c +- h` for roughness `a` (`h` by magnitude), each clamped to `+-BIG`: the ends as
/// `(c -+ |h|) / a`, one rounding before the division.
fn interval(c: f32, h: f32, a: f32) -> vec4<f32> {
    let ah = abs(h);
    let lo = clamp((c - ah) / a, -BIG, BIG);
    let hi = clamp((c + ah) / a, -BIG, BIG);
    return vec4<f32>(lo, hi, clamp(c / a, -BIG, BIG), min(ah / a, BIG));
}

/// Exact box-filtered GGX slope density: the average of the axis-aligned GGX `P22` over the
/// slope-domain rectangle `center +- half_extent` (KHPL16 eq. 16, normalised by the area as
/// eq. 16 does; Appendix A's normalisation is four times too large). Half extents count by
/// magnitude; both zero gives the unfiltered `P22`. Accuracy in the module docs. Never
/// negative.
fn p22_rect(r: axis_aligned::AxisAligned, center: vec2<f32>, half_extent: vec2<f32>) -> f32 {
    if half_extent.x == 0.0 && half_extent.y == 0.0 {
        return ggx::p22_axis_aligned(r, center);
    }
    let a = r.alpha;
    let u = interval(center.x, half_extent.x, a.x);
    let v = interval(center.y, half_extent.y, a.y);
    return max(mean_f(u, v) * (math::INV_PI / (a.x * a.y)), 0.0);
}

/// Exact box-filtered GGX per steradian: [`p22_rect`] at the slope `-h_xy / h_z` of the unit
/// half vector, divided by `h_z^4` (TK19 supplement; the GDC listing without its
/// `max(1e-3, h_z^4)` clamp). `0` for `h_z <= 0`; a zero footprint gives the unfiltered `D`;
/// a value beyond the f32 range saturates at `F32_MAX`.
fn d_rect(r: axis_aligned::AxisAligned, h: vec3<f32>, half_extent: vec2<f32>) -> f32 {
    if !(h.z > 0.0) {
        return 0.0;
    }
    if half_extent.x == 0.0 && half_extent.y == 0.0 {
        return ggx::d_axis_aligned(r, h);
    }
    let p = p22_rect(r, -h.xy / h.z, half_extent);
    let z2 = h.z * h.z;
    return min(p / (z2 * z2), math::F32_MAX);
}

/// The GDC 2016 listing `GGXRectIntegral` as printed (the eight-term difference of KHPL16
/// Appendix A over `[hpp - footprint, hpp + footprint]`, divided by `2 pi (x1 - x2)(y1 - y2)`
/// and by `max(1e-3, h_z^4)`), with `math::atan`: the baseline engines ship. It cancels
/// catastrophically for small footprints and far from the peak (use [`d_rect`]): its error
/// is about `16 eps` times the sum of the magnitudes of its eight terms, over the result. A
/// zero footprint gives 0 (the listing's `0 / 0`).
fn d_rect_printed(r: axis_aligned::AxisAligned, hpp: vec2<f32>, h: vec3<f32>, footprint: vec2<f32>) -> f32 {
    let a = r.alpha.x;
    let b = r.alpha.y;
    let a_2 = a * a;
    let b_2 = b * b;
    let x1 = hpp.x - footprint.x;
    let x2 = hpp.x + footprint.x;
    let y1 = hpp.y - footprint.y;
    let y2 = hpp.y + footprint.y;
    let sx1 = sqrt(x1 * x1 + a_2);
    let sx2 = sqrt(x2 * x2 + a_2);
    let sy1 = sqrt(y1 * y1 + b_2);
    let sy2 = sqrt(y2 * y2 + b_2);
    let val = (x1 * (math::atan((y1 * a) / (sx1 * b)) - math::atan((y2 * a) / (sx1 * b)))) / sx1
        + (x2 * (-math::atan((y1 * a) / (sx2 * b)) + math::atan((y2 * a) / (sx2 * b)))) / sx2
        + (y1 * sy2 * (math::atan((x1 * b) / (a * sy1)) - math::atan((x2 * b) / (a * sy1)))
            + y2 * sy1 * (-math::atan((x1 * b) / (a * sy2)) + math::atan((x2 * b) / (a * sy2))))
            / (sy1 * sy2);
    let den = (2.0 * math::PI) * (x1 - x2) * (y1 - y2);
    let hz4 = h.z * h.z * h.z * h.z;
    let v = val / den / max(hz4, 1e-3);
    return select(0.0, v, abs(v) <= math::F32_MAX && den != 0.0);
}
