//! The NaN and infinity policy of footprints and normal differences (`filtered_ndf::contract`)
//! in the WGSL twins: a NaN entry counts as 0 (no widening from it), an infinite one saturates
//! to the widest kernel the clamp rules allow. The shaders decide NaN on its bits
//! (`math::is_nan`, integer arithmetic), so the policy holds whatever a driver assumes about
//! floats.
//!
//! Cases: inputs of the finite checks (`checks::footprint`, `checks::filters`) with NaN (or
//! `+-inf`) written into one entry in turn. The reference is the crate's `f64` function on the
//! same input, which applies the policy itself; the tolerance is that of the finite check of the
//! same function on the input with the NaN entries zeroed (the value the policy makes of it).

use super::filters::deferred_tol;
use super::{Check, EPS, Tol};
use crate::reference::{
    ClampRules, Covariance, DVec3, Footprint, SplitMix64, deferred, jacobian, presets, v2, v3,
};

const IMPORTS: &str = "#import filtered_ndf::math
#import filtered_ndf::footprint
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::rect
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::deferred
#import filtered_ndf::filter::presets";

/// `v` with entry `k` (of the concatenation) replaced by `x`.
fn with_entry<const N: usize>(mut v: [f32; N], k: usize, x: f32) -> [f32; N] {
    v[k] = x;
    v
}

/// `x` with NaN as 0, the policy the references apply.
fn zeroed(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x }
}

/// The checks of the policy.
pub fn all() -> Vec<Check> {
    let mut rng = SplitMix64(0x4e61_4e50_6f6c_6963);
    let mut checks = vec![bits(), vectors()];
    checks.extend(footprints(&mut rng));
    checks.extend(normal_differences(&mut rng));
    checks
}

/// `math::is_nan`, `math::nan_to_zero`: exact.
fn bits() -> Check {
    let mut c = Check::new(
        "math::{is_nan, nan_to_zero}",
        "#import filtered_ndf::math",
        "y(0u, select(0.0, 1.0, math::is_nan(x(0u)))); y(1u, math::nan_to_zero(x(0u)));",
        1,
        2,
    )
    .tolerance("exact (bit tests and a select)");
    let neg_nan = f32::from_bits(0xffc0_0001);
    for x in [
        f32::NAN,
        neg_nan,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        1.5,
        -2e30,
        f32::MAX,
    ] {
        let (n, z) = if x.is_nan() {
            (1.0, 0.0)
        } else {
            (0.0, f64::from(x))
        };
        c.case(vec![x], vec![n, z], vec![Tol::abs(0.0); 2]);
    }
    c
}

/// `math::{nan_to_zero2, nan_to_zero3}` and `footprint::nan_to_zero`: per component, exact.
fn vectors() -> Check {
    let mut c = Check::new(
        "math::{nan_to_zero2, nan_to_zero3}, footprint::nan_to_zero",
        IMPORTS,
        "y2(0u, math::nan_to_zero2(x2(0u)));
y3(2u, math::nan_to_zero3(x3(2u)));
let f = footprint::nan_to_zero(footprint::from_slope_derivatives(x2(5u), x2(7u)));
y2(5u, f.dh_u);
y2(7u, f.dh_v);",
        9,
        9,
    )
    .tolerance("exact (bit tests and selects)");
    let vals = [f32::NAN, f32::from_bits(0xffc0_0001), 0.25, -3.0, 0.0];
    for k in 0..9 {
        let input: Vec<f32> = (0..9).map(|i| vals[(i + k) % vals.len()]).collect();
        let want = input.iter().map(|&x| f64::from(zeroed(x))).collect();
        c.case(input, want, vec![Tol::abs(0.0); 9]);
    }
    c
}

/// Footprints with a NaN entry: the footprint constructors and the kernel builders.
fn footprints(rng: &mut SplitMix64) -> Vec<Check> {
    let mut cn = Check::new(
        "footprint::from_normal_differences (a NaN entry)",
        IMPORTS,
        "let f = footprint::from_normal_differences(x3(0u), x3(3u)); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        6,
        4,
    )
    .tolerance("as the finite check: 8 EPS |dn| absolute per component");
    let mut cp = Check::new(
        "footprint::from_projected_derivatives_in_slope (a NaN entry)",
        IMPORTS,
        "let f = footprint::from_projected_derivatives_in_slope(x3(0u), x2(3u), x2(5u)); y2(0u, f.dh_u); y2(2u, f.dh_v);",
        7,
        4,
    )
    .tolerance("as the finite check: 20 EPS |J|max |dp| absolute");
    let mut cc = Check::new(
        "covariance::from_footprint, rect::from_footprint, clamp::footprint (a NaN entry)",
        IMPORTS,
        "let f = footprint::from_slope_derivatives(x2(0u), x2(2u));
let c = covariance::from_footprint(f, 0.5);
y4(0u, vec4<f32>(c.s_xx, c.s_xy, c.s_yy, c.det));
y2(4u, rect::from_footprint(f).half_extent);
let g = clamp::footprint(clamp::DEFAULT_RULES, f);
y2(6u, g.dh_u);
y2(8u, g.dh_v);",
        4,
        10,
    )
    .tolerance("as the finite checks: entries 4 EPS of the largest (sums of two products), det 12 EPS of s_xx s_yy; the rectangle 1 ulp; the extent rule exact within lambda");
    for k in 0..300 {
        let d = |rng: &mut SplitMix64| {
            let len = rng.log_uniform(1e-4, 0.5);
            let v = DVec3::new(rng.normal(), rng.normal(), rng.normal()).normalize() * len;
            [v.x as f32, v.y as f32, v.z as f32]
        };
        let (a, b) = (d(rng), d(rng));
        // Normal differences, NaN at entry k % 6.
        let mut input: [f32; 6] = [a[0], a[1], a[2], b[0], b[1], b[2]];
        input = with_entry(input, k % 6, f32::NAN);
        let f = Footprint::from_normal_differences(
            v3([input[0], input[1], input[2]]),
            v3([input[3], input[4], input[5]]),
        );
        let z = input.map(zeroed);
        let m = v3([z[0], z[1], z[2]])
            .length()
            .max(v3([z[3], z[4], z[5]]).length());
        cn.case(
            input.to_vec(),
            vec![f.dh_u.x, f.dh_u.y, f.dh_v.x, f.dh_v.y],
            vec![Tol::of_scale(8.0, m); 4],
        );
        // Disk derivatives at a half vector within 60 degrees of the normal (|J| <= 4).
        let h = DVec3::new(0.5 * rng.normal(), 0.5 * rng.normal(), 1.0).normalize();
        let h = if h.z < 0.5 { DVec3::Z } else { h };
        let hf = [h.x as f32, h.y as f32, h.z as f32];
        let dp: [f32; 4] = [a[0], a[1], b[0], b[1]];
        let dp = with_entry(dp, k % 4, f32::NAN);
        let f = Footprint::from_projected_derivatives_in_slope(
            v3(hf),
            v2([dp[0], dp[1]]),
            v2([dp[2], dp[3]]),
        );
        let dz = dp.map(zeroed);
        let mag = v2([dz[0], dz[1]]).length().max(v2([dz[2], dz[3]]).length());
        let jm = jacobian::projected_to_slope(v3(hf));
        let j = jm
            .x_axis
            .abs()
            .max_element()
            .max(jm.y_axis.abs().max_element());
        let mut input = hf.to_vec();
        input.extend(dp);
        cp.case(
            input,
            vec![f.dh_u.x, f.dh_u.y, f.dh_v.x, f.dh_v.y],
            vec![Tol::of_scale(20.0, j * mag); 4],
        );
        // Slope footprint: the kernel builders.
        let fp = Footprint::from_slope_derivatives(v2([dp[0], dp[1]]), v2([dp[2], dp[3]]));
        let c = fp.covariance(0.5);
        let r = fp.bounding_rect();
        let g = ClampRules::default().footprint(fp);
        let big = c.s11.abs().max(c.s22.abs()).max(c.s12.abs());
        let mut tol = vec![Tol::of_scale(4.0, big); 3];
        tol.push(Tol::of_scale(12.0, c.s11 * c.s22));
        tol.extend([Tol::ulps(1.0); 2]);
        tol.extend([Tol::abs(12.0 * EPS); 4]);
        cc.case(
            dp.to_vec(),
            vec![
                c.s11,
                c.s12,
                c.s22,
                Covariance::det(c),
                r.half_extent.x,
                r.half_extent.y,
                g.dh_u.x,
                g.dh_u.y,
                g.dh_v.x,
                g.dh_v.y,
            ],
            tol,
        );
    }
    vec![cn, cp, cc]
}

/// Normal differences with a NaN or an infinite entry: every preset through `deferred::apply`.
fn normal_differences(rng: &mut SplitMix64) -> Vec<Check> {
    let mut checks = Vec::new();
    for (i, (name, conv)) in presets::ALL.iter().enumerate() {
        let body = format!("y(0u, deferred::apply(presets::preset({i}u), x(0u), x3(1u), x3(4u)));");
        let mut c = Check::new(
            &format!("deferred::apply (presets::preset({i}): {name}; NaN and inf entries)"),
            IMPORTS,
            &body,
            7,
            1,
        )
        .tolerance("as the finite check on the zeroed input (deferred_tol); an infinite entry: the clamp, 8 ulp");
        for k in 0..120 {
            let alpha = rng.log_uniform(1e-3, 1.0) as f32;
            let len = rng.log_uniform(1e-4, 0.3);
            let mut e = [0f32; 6];
            for x in e.iter_mut() {
                *x = (rng.normal() * len) as f32;
            }
            let bad = if k % 4 == 3 {
                if k % 8 == 3 {
                    f32::INFINITY
                } else {
                    f32::NEG_INFINITY
                }
            } else {
                f32::NAN
            };
            let e = with_entry(e, k % 6, bad);
            let (u, v) = (v3([e[0], e[1], e[2]]), v3([e[3], e[4], e[5]]));
            let want = conv.apply(alpha.into(), u, v);
            let t = if bad.is_nan() {
                let z = e.map(zeroed);
                deferred_tol(
                    conv,
                    alpha.into(),
                    v3([z[0], z[1], z[2]]),
                    v3([z[3], z[4], z[5]]),
                )
            } else {
                8.0
            };
            let mut input = vec![alpha];
            input.extend(e);
            c.case(input, vec![want], vec![Tol::ulps(t)]);
        }
        // The saturated value is the clamp's: checked against `apply_widening` directly.
        let a = 0.1f32;
        let clamp: &deferred::KernelConvention = conv;
        let want = clamp.apply_widening(a.into(), clamp.clamp);
        let mut input = vec![a];
        input.extend([f32::INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0]);
        c.case(input, vec![want], vec![Tol::ulps(8.0)]);
        checks.push(c);
    }
    checks
}
