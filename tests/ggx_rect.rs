//! The exact GGX box filter (`ggx_rect`) against f64 adaptive quadrature of the GGX slope
//! density, in both precisions, plus the printed GDC formula as the baseline.

use filtered_ndf::testing::quadrature::{
    Estimate, Tolerance, integrate, integrate_2d, integrate_plane,
};
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use filtered_ndf::{f32 as s, f64 as d};
use proptest::prelude::*;
use std::f64::consts::PI;

/// The axis-aligned GGX slope density, written out here (not taken from the crate).
fn p22(a: f64, b: f64, x: f64, y: f64) -> f64 {
    let t = 1.0 + (x / a).powi(2) + (y / b).powi(2);
    1.0 / (PI * a * b * t * t)
}

/// The offsets `[-h, h]` from a centre `c`, split at the offset `-c` of the peak when the
/// interval contains it.
fn pieces(c: f64, h: f64) -> Vec<(f64, f64)> {
    if -h < -c && -c < h {
        vec![(-h, -c), (-c, h)]
    } else {
        vec![(-h, h)]
    }
}

/// Reference mean of `P22` over `center +/- half` by adaptive quadrature over the offsets from
/// the centre (1D when one half extent is zero, the density itself when both are). Over the
/// offsets, not over `[c - h, c + h]`: the rounded interval divided by the exact width `2 h` is
/// off by up to `1.1e-16 |c| / h` relative (issue 17; `tests/box_reference.rs`). Relative goal
/// 1e-14: the Gauss-Kronrod estimate over-estimates the true error of these smooth integrands
/// by orders of magnitude.
fn reference(a: f64, b: f64, cx: f64, cy: f64, hx: f64, hy: f64) -> f64 {
    let e = reference_estimate(a, b, cx, cy, hx, hy);
    // Every caller's tolerance is at least TOL64 = 1e-12: the estimate must be well below it.
    assert!(
        e.error <= 1e-13 * e.value.abs(),
        "reference not converged: {e:?} (a {a}, b {b}, c ({cx}, {cy}), h ({hx}, {hy}))"
    );
    e.value
}

/// [`reference`] with the quadrature's error estimate (summed over the pieces).
fn reference_estimate(a: f64, b: f64, cx: f64, cy: f64, hx: f64, hy: f64) -> Estimate {
    let tol = Tolerance::relative(1e-14);
    let sum = |es: Vec<Estimate>, w: f64| Estimate {
        value: es.iter().map(|e| e.value).sum::<f64>() / w,
        error: es.iter().map(|e| e.error).sum::<f64>() / w,
    };
    match (hx == 0.0, hy == 0.0) {
        (true, true) => Estimate {
            value: p22(a, b, cx, cy),
            error: 0.0,
        },
        (true, false) => sum(
            pieces(cy, hy)
                .iter()
                .map(|&(y0, y1)| integrate(|dy| p22(a, b, cx, cy + dy), y0, y1, tol))
                .collect(),
            2.0 * hy,
        ),
        (false, true) => sum(
            pieces(cx, hx)
                .iter()
                .map(|&(x0, x1)| integrate(|dx| p22(a, b, cx + dx, cy), x0, x1, tol))
                .collect(),
            2.0 * hx,
        ),
        (false, false) => {
            let mut es = Vec::new();
            for &xr in &pieces(cx, hx) {
                for &yr in &pieces(cy, hy) {
                    es.push(integrate_2d(
                        |dx, dy| p22(a, b, cx + dx, cy + dy),
                        xr,
                        yr,
                        tol,
                    ));
                }
            }
            sum(es, 4.0 * hx * hy)
        }
    }
}

/// Relative error of the f32 and f64 paths against the reference, for inputs given in f32
/// (so that the input rounding is not counted).
fn errors(a: f32, b: f32, c: (f32, f32), h: (f32, f32)) -> (f64, f64, f64) {
    let r = reference(
        a as f64, b as f64, c.0 as f64, c.1 as f64, h.0 as f64, h.1 as f64,
    );
    let r32 = s::AxisAligned::new(a, b).unwrap();
    let r64 = d::AxisAligned::new(a as f64, b as f64).unwrap();
    let v32 = s::filter::rect::p22_rect(r32, glam::Vec2::new(c.0, c.1), glam::Vec2::new(h.0, h.1));
    let v64 = d::filter::rect::p22_rect(
        r64,
        glam::DVec2::new(c.0 as f64, c.1 as f64),
        glam::DVec2::new(h.0 as f64, h.1 as f64),
    );
    ((v32 as f64 - r).abs() / r, (v64 - r).abs() / r, r)
}

/// The f32 path for a zero footprint: GGX's own `p22` in f32, bit for bit. Its roundings: the
/// quadratic form (three operations, relative `3u`, `u = 2^-24`), `1 + q` and its square
/// (amplifying the form's error by `2 q / (1 + q) <= 2`), the product with `pi sqrt(det)` and
/// the reciprocal: about `12 u`; bound `16 eps = 32 u`. (The spec bound for the whole
/// domain was 1e-5.)
const TOL32: f64 = 16.0 * f32::EPSILON as f64;
/// f64 path: every tier aims at 1e-13 (rect.rs module docs: Gauss-Legendre truncation below
/// 5e-14 per axis, the four-edge form used while its cancellation stays below 1e-13, the polar
/// far-field form beyond), measured 8e-14 at worst over 20000 seeded cases; 1e-12 covers that,
/// the reference's 1e-14 and the rounding of the normalised inputs (a few ulps, amplified at
/// most fourfold by P22 ~ |s|^-4). The issue-17 target.
const TOL64: f64 = 1e-12;
/// The f32 path to about one ulp for a non-zero footprint: the f64 result (1e-12) rounded once
/// to f32 is within half an ulp, at most `2^-24` relative; the bound `2^-23` leaves room for
/// the f32 tiers' truncation (below 3e-8, rect.rs module docs). A zero footprint returns the
/// f32 GGX `p22` bit for bit (a few ulps; bound `TOL32`).
const ULP32: f64 = 1.0 / (1u32 << 23) as f64;

fn alpha_pair() -> impl Strategy<Value = (f32, f32)> {
    (-4.0f64..0.0, 0.0f64..2.0, any::<bool>()).prop_map(|(la, lk, up)| {
        let a = 10f64.powf(la);
        let k = 10f64.powf(lk);
        let b = if up { a * k } else { a / k }.clamp(1e-4, 1.0);
        (a as f32, b as f32)
    })
}

fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        6 => (-6.0f64..0.6, any::<bool>())
            .prop_map(|(l, neg)| (if neg { -1.0 } else { 1.0 } * 10f64.powf(l)).clamp(-4.0, 4.0) as f32),
    ]
}

fn half() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        6 => (-8.0f64..0.0).prop_map(|l| 10f64.powf(l) as f32),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn rect_mean_matches_quadrature((a, b) in alpha_pair(), cx in coord(), cy in coord(),
                                    hx in half(), hy in half()) {
        let (e32, e64, r) = errors(a, b, (cx, cy), (hx, hy));
        // A zero footprint is the f32 GGX `p22` itself (bit for bit), a few ulps: the spec bound.
        let tol32 = if hx == 0.0 && hy == 0.0 { TOL32 } else { ULP32 };
        prop_assert!(e32 <= tol32, "f32 rel err {e32:e} (ref {r:e})");
        prop_assert!(e64 <= TOL64, "f64 rel err {e64:e} (ref {r:e})");
        // Box filtering never raises the density above its peak 1 / (pi a b).
        let r32 = s::AxisAligned::new(a, b).unwrap();
        let v = s::filter::rect::p22_rect(r32, glam::Vec2::new(cx, cy), glam::Vec2::new(hx, hy));
        prop_assert!(v <= 1.0 / (core::f32::consts::PI * a * b) * (1.0 + 1e-6));
    }
}

/// `(alpha_x, alpha_y, center, half extent)`.
type Case = (f32, f32, (f32, f32), (f32, f32));

#[test]
fn hand_picked_extremes() {
    let cases: &[Case] = &[
        // alpha = 1e-4 with a 1e-7 footprint: at the peak, near it, in the far tail.
        (1e-4, 1e-4, (0.0, 0.0), (1e-7, 1e-7)),
        (1e-4, 1e-4, (1e-4, -2e-4), (1e-7, 1e-7)),
        (1e-4, 1e-4, (4.0, 4.0), (1e-7, 1e-7)),
        (1e-4, 1e-4, (-4.0, 0.0), (1e-7, 0.0)),
        // far in the tail with large rectangles (the closed-form branch at its worst)
        (1e-4, 1e-4, (3.0, -2.5), (0.4, 1.0)),
        (1e-4, 1e-2, (4.0, 4.0), (1.0, 1e-7)),
        (1e-4, 1e-2, (4.0, 0.01), (1.0, 1.0)),
        (1.0, 1e-2, (4.0, 4.0), (1.0, 1.0)),
        // rectangles straddling the peak
        (0.01, 0.01, (0.3, -0.2), (0.5, 0.5)),
        (1e-4, 1e-4, (0.0, 0.0), (1.0, 1.0)),
        (1e-4, 1e-2, (1e-5, -3e-3), (1.0, 1e-6)),
        (0.5, 0.005, (-0.1, 0.001), (0.3, 0.0)),
        // rectangles about the size of their distance to the peak
        (0.01, 0.01, (0.1, 0.1), (0.01, 0.01)),
        (0.01, 0.01, (0.1, 0.1), (0.1, 0.1)),
        (0.3, 0.3, (1.0, 0.0), (0.1, 0.03)),
        // outside the domain, |s| / alpha = 1e13: the per-pair divisions of the far field
        (2e-8, 2e-8, (2e5, 0.0), (2e3, 1e4)),
        (2e-8, 2e-8, (2e5, 2e5), (4e4, 2e4)),
    ];
    for &(a, b, c, h) in cases {
        let (e32, e64, r) = errors(a, b, c, h);
        println!("a={a} b={b} c={c:?} h={h:?}: ref {r:e}, f32 {e32:.2e}, f64 {e64:.2e}");
        assert!(e32 <= TOL32.min(ULP32), "f32 {e32:e}");
        assert!(e64 <= TOL64, "f64 {e64:e}");
    }
}

#[test]
fn zero_footprint_is_the_unfiltered_density_exactly() {
    use filtered_ndf::f32::Ndf;
    for &(a, b, cx, cy) in &[
        (0.1f32, 0.3f32, 0.2f32, -0.7f32),
        (1e-4, 1e-2, 4.0, 4.0),
        (1.0, 1.0, 0.0, 0.0),
    ] {
        let r = s::AxisAligned::new(a, b).unwrap();
        let c = glam::Vec2::new(cx, cy);
        let ggx = s::Ggx::new(r);
        assert_eq!(
            s::filter::rect::p22_rect(r, c, glam::Vec2::ZERO),
            ggx.p22(c)
        );
        let h = s::footprint::slope::sphere_from_slope(c);
        assert_eq!(s::filter::rect::d_rect(r, h, glam::Vec2::ZERO), ggx.d(h));
        // And continuously so: a 1e-30 footprint goes through the quadrature branch.
        let tiny = s::filter::rect::p22_rect(r, c, glam::Vec2::splat(1e-30));
        let exact = p22(a as f64, b as f64, cx as f64, cy as f64);
        assert!(
            (tiny as f64 - exact).abs() <= 1e-6 * exact,
            "{tiny} vs {exact}"
        );
    }
}

#[test]
fn solid_angle_form_divides_by_cos4() {
    // D = mean P22 at s(h) / h_z^4, against quadrature.
    let (a, b) = (0.05f64, 0.2f64);
    let r = d::AxisAligned::new(a, b).unwrap();
    for &(hx, hy) in &[(0.3, -0.1), (-0.8, 0.5), (0.0, 0.0), (0.05, 0.9)] {
        let h = glam::DVec3::new(hx, hy, (1.0f64 - hx * hx - hy * hy).sqrt());
        let c = (-h.x / h.z, -h.y / h.z);
        let half = glam::DVec2::new(0.02, 0.07);
        let want = reference(a, b, c.0, c.1, half.x, half.y) / h.z.powi(4);
        let got = d::filter::rect::d_rect(r, h, half);
        // f64 path: TOL64, plus the division by h_z^4 (a few ulps).
        assert!((got - want).abs() <= TOL64 * want, "{got} vs {want}");
    }
}

#[test]
fn filtered_density_stays_normalised() {
    // Box filtering preserves mass: the mean over the rectangle, integrated over all centres,
    // is 1. The quadrature's goal is 1e-9 relative and the f64 kernel is accurate to 1e-13
    // (TOL64's derivation): the error within four times the quadrature's estimate, which
    // must meet ten times its goal.
    for &(a, b, hx, hy) in &[(0.3, 0.1, 0.2, 0.05), (0.05, 0.05, 0.5, 0.0)] {
        let r = d::AxisAligned::new(a, b).unwrap();
        let half = glam::DVec2::new(hx, hy);
        let e = integrate_plane(
            |x, y| d::filter::rect::p22_rect(r, glam::DVec2::new(x, y), half),
            (0.0, 0.0),
            (a + hx, b + hy),
            Tolerance::relative(1e-9),
        );
        assert!(e.error <= 1e-8, "{e:?}");
        assert!((e.value - 1.0).abs() <= 4.0 * e.error + 1e-12, "{e:?}");
    }
}

/// KHPL16 Appendix A written out: bounds `h +/- Delta h`, divided by `|Delta h_s Delta h_t|`.
fn appendix_a(a: f64, b: f64, hs: f64, ht: f64, ds: f64, dt: f64) -> f64 {
    let phi = |x: f64, y: f64, g: f64, dd: f64| {
        let r = (x * x + g * g).sqrt();
        x * (g * y / (r * dd)).atan() / r
    };
    let (s0, s1, t0, t1) = (hs - ds, hs + ds, ht - dt, ht + dt);
    (phi(s0, t0, a, b) - phi(s0, t1, a, b) + phi(s1, t1, a, b) - phi(s1, t0, a, b)
        + phi(t0, s0, b, a)
        - phi(t0, s1, b, a)
        + phi(t1, s1, b, a)
        - phi(t1, s0, b, a))
        / (2.0 * PI * (ds * dt).abs())
}

#[test]
fn appendix_a_as_printed_is_four_times_the_average() {
    // Moderate inputs, where the eight terms do not cancel: 1e-9 relative.
    for &(a, b, hs, ht, ds, dt) in &[
        (0.2, 0.3, 0.1, -0.2, 0.05, 0.1),
        (0.5, 0.1, 0.0, 0.3, 0.4, 0.2),
    ] {
        let avg = reference(a, b, hs, ht, ds, dt);
        let printed = appendix_a(a, b, hs, ht, ds, dt);
        assert!((printed / avg - 4.0).abs() < 1e-9, "{printed} vs 4 x {avg}");
        // The GDC listing (with f = 1) is the average itself, as is eq. 16.
        let r = d::AxisAligned::new(a, b).unwrap();
        let gdc = d::filter::rect::d_rect_printed(
            r,
            glam::DVec2::new(hs, ht),
            glam::DVec3::Z,
            glam::DVec2::new(ds, dt),
        );
        assert!((gdc / avg - 1.0).abs() < 1e-9, "{gdc} vs {avg}");
    }
}

fn stats(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = v.len();
    (v[n / 2], v[(n * 99) / 100], v[n - 1])
}

#[test]
fn exact_vs_printed_on_a_seeded_sample() {
    // The closing figure: f32 relative error of the exact integral and of the printed
    // eight-term formula (evaluated in f32, h_z = 1 so its Jacobian clamp is inert) against the
    // same f64 quadrature reference, over the whole domain, 600 seeded samples.
    let mut rng = Rng(0x5eed);
    let (mut ex, mut pr, mut e6) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..2000 {
        let a = rng.log_uniform(1e-4, 1.0);
        let k = rng.log_uniform(1.0, 100.0);
        let b = if rng.uniform() < 0.5 { a * k } else { a / k }.clamp(1e-4, 1.0);
        let mut c = || {
            let v = rng.log_uniform(1e-6, 4.0);
            if rng.uniform() < 0.5 { -v } else { v }
        };
        let (cx, cy) = (c(), c());
        // The printed formula is 0/0 at a zero footprint: nonzero half sides here.
        let (hx, hy) = (rng.log_uniform(1e-8, 1.0), rng.log_uniform(1e-8, 1.0));
        let (a, b, cx, cy, hx, hy) = (
            a as f32, b as f32, cx as f32, cy as f32, hx as f32, hy as f32,
        );
        let (e32, e64, r) = errors(a, b, (cx, cy), (hx, hy));
        e6.push(e64);
        let p = s::filter::rect::d_rect_printed(
            s::AxisAligned::new(a, b).unwrap(),
            glam::Vec2::new(cx, cy),
            glam::Vec3::Z,
            glam::Vec2::new(hx, hy),
        );
        ex.push(e32);
        pr.push((p as f64 - r).abs() / r);
    }
    let (em, e99, emax) = stats(ex);
    let (pm, p99, pmax) = stats(pr);
    println!("exact   f32: median {em:.2e}  p99 {e99:.2e}  max {emax:.2e}");
    println!("printed f32: median {pm:.2e}  p99 {p99:.2e}  max {pmax:.2e}");
    let (dm, d99, dmax) = stats(e6);
    println!("exact   f64: median {dm:.2e}  p99 {d99:.2e}  max {dmax:.2e}");
    assert!(dmax <= TOL64);
    assert!(emax <= TOL32.min(ULP32));
    // The printed formula is worse than the exact one by orders of magnitude at the median.
    assert!(pm > 100.0 * em, "printed median {pm:e} vs exact {em:e}");
}

#[test]
fn bad_input_never_nan() {
    let r = s::AxisAligned::new(0.1, 0.2).unwrap();
    let v2 = glam::Vec2::new;
    let nan = f32::NAN;
    let inf = f32::INFINITY;
    let c = v2(0.1, -0.2);
    // Negative half extents are their absolute value.
    assert_eq!(
        s::filter::rect::p22_rect(r, c, v2(-0.05, 0.3)),
        s::filter::rect::p22_rect(r, c, v2(0.05, -0.3))
    );
    assert_eq!(
        s::filter::rect::p22_rect(r, c, v2(-0.05, 0.3)),
        s::filter::rect::p22_rect(r, c, v2(0.05, 0.3))
    );
    // NaN half extent counts as zero (here: the 1D average over the other axis).
    assert_eq!(
        s::filter::rect::p22_rect(r, c, v2(nan, 0.3)),
        s::filter::rect::p22_rect(r, c, v2(0.0, 0.3))
    );
    for (cc, hh) in [
        (v2(nan, 0.0), v2(0.1, 0.1)),
        (v2(inf, -inf), v2(0.1, 0.1)),
        (v2(0.0, 0.0), v2(inf, inf)),
        (v2(3e38, -3e38), v2(3e38, 0.0)),
        (v2(0.0, 0.0), v2(1e-45, 1e-45)),
        (v2(1e-45, 0.0), v2(0.0, 1e-45)),
    ] {
        let v = s::filter::rect::p22_rect(r, cc, hh);
        assert!(v.is_finite() && v >= 0.0, "{cc:?} {hh:?}: {v}");
    }
    let v3 = glam::Vec3::new;
    for (h, hh) in [
        (v3(0.0, 0.0, -1.0), v2(0.1, 0.1)),
        (v3(1.0, 0.0, 0.0), v2(0.1, 0.1)),
        (v3(nan, 0.0, 1.0), v2(0.1, 0.1)),
        (v3(0.0, inf, 1.0), v2(0.1, 0.1)),
        (v3(0.999_999, 0.0, 1e-30), v2(0.1, 0.1)),
        (v3(0.0, 0.0, 1.0), v2(inf, nan)),
        (v3(0.6, 0.0, 0.8), v2(-1e30, 1e30)),
    ] {
        let v = s::filter::rect::d_rect(r, h, hh);
        assert!(v.is_finite() && v >= 0.0, "{h:?} {hh:?}: {v}");
        let p = s::filter::rect::d_rect_printed(r, v2(h.x, h.y), h, hh);
        assert!(!p.is_nan(), "printed {h:?} {hh:?}: {p}");
    }
    assert_eq!(
        s::filter::rect::d_rect(r, v3(0.0, 0.0, -1.0), v2(0.1, 0.1)),
        0.0
    );
    assert_eq!(
        s::filter::rect::d_rect_printed(r, v2(0.0, 0.0), glam::Vec3::Z, v2(0.0, 0.0)),
        0.0
    );
    // f64: a half vector grazing the horizon stays finite (unfiltered limit).
    let r64 = d::AxisAligned::new(0.1, 0.2).unwrap();
    let h = glam::DVec3::new(1.0, 0.0, 1e-200);
    let v = d::filter::rect::d_rect(r64, h, glam::DVec2::splat(0.1));
    assert!(v.is_finite() && v > 0.0, "{v}");
}
