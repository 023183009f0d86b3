//! `shaders/math.wgsl`: the driver-independent elementary functions.

use super::{Check, EPS, Tol, r32};
use crate::reference::{SplitMix64, math};

/// The checks of `math.wgsl`.
pub fn all() -> Vec<Check> {
    let mut rng = SplitMix64(0x6d61_7468);
    let imports = "#import filtered_ndf::math";

    // atan: stated bound 8 ulp relative (math.wgsl); reference `filtered_ndf::math::atan`.
    let mut atan = Check::new("math::atan", imports, "y(0u, math::atan(x(0u)));", 1, 1)
        .tolerance("8 ulp relative: reduction 4 ulp mapped to 2, polynomial 3e-9, Horner and final additions 3 ulp (math.wgsl)");
    let mut xs: Vec<f64> = vec![
        0.0, 1.0, -1.0, 0.41421356, 0.4142136, 2.414, 1e-30, 1e30, 3e38,
    ];
    for _ in 0..4000 {
        let x = rng.log_uniform(1e-6, 1e6);
        xs.push(if rng.uniform() < 0.5 { -x } else { x });
    }
    for _ in 0..1000 {
        xs.push(rng.range(-2.5, 2.5));
    }
    for x in xs {
        let x = r32(x);
        atan.case(vec![x as f32], vec![math::atan(x)], vec![Tol::ulps(8.0)]);
    }

    // sincos_turns: stated bound 3 ulp of 1 absolute (math.wgsl); reference f64 sin/cos.
    let mut sc = Check::new(
        "math::sincos_turns",
        imports,
        "y2(0u, math::sincos_turns(x(0u)));",
        1,
        2,
    )
    .tolerance("3 ulp of 1 absolute: exact quarter-turn reduction, polynomials 4e-8, Horner 2 ulp (math.wgsl)");
    let mut us: Vec<f64> = vec![0.0, 0.125, 0.25, 0.375, 0.5, 0.75, 1.0 - 1e-7, -0.3];
    for _ in 0..4000 {
        us.push(rng.uniform());
    }
    for u in us {
        let u = r32(u);
        let a = 2.0 * core::f64::consts::PI * u;
        sc.case(
            vec![u as f32],
            vec![math::cos(a), math::sin(a)],
            vec![Tol::abs(3.0 * EPS); 2],
        );
    }

    // hypot: 8 ulp (two divisions 5, sqrt 4.5 halved, products and sum 2).
    let mut hy = Check::new(
        "math::hypot",
        imports,
        "y(0u, math::hypot(x(0u), x(1u)));",
        2,
        1,
    )
    .tolerance("8 ulp relative: two quotients 2.5 ulp each (halved by the square root), sqrt 4.5, products 1");
    for _ in 0..2000 {
        let a = r32(rng.log_uniform(1e-30, 1e30) * if rng.uniform() < 0.5 { -1.0 } else { 1.0 });
        let b = r32(rng.log_uniform(1e-30, 1e30));
        hy.case(
            vec![a as f32, b as f32],
            vec![math::hypot(a, b)],
            vec![Tol::ulps(8.0)],
        );
    }
    // exp, ln, ln_1p against f64.
    let mut ex = Check::new("math::exp", imports, "y(0u, math::exp(x(0u)));", 1, 1).tolerance(
        "3 ulp relative: polynomial 1.9e-9, reduction exact but for its last rounding (|r| <= 0.35: 0.5 ulp), Estrin 1.5 ulp, the product with 2^n 0.5",
    );
    let mut xs: Vec<f64> = vec![0.0, -0.0, 1.0, -1.0, 88.0, -86.99, 1e-30, -1e-30, 0.3465736];
    for _ in 0..6000 {
        xs.push(rng.range(-87.0, 88.0));
    }
    for _ in 0..2000 {
        xs.push(rng.range(-1.0, 1.0) * rng.log_uniform(1e-8, 1.0));
    }
    for x in xs {
        let x = r32(x);
        ex.case(vec![x as f32], vec![x.exp()], vec![Tol::ulps(3.0)]);
    }
    let mut ln = Check::new(
        "math::ln, math::ln_1p",
        imports,
        "y(0u, math::ln(x(0u))); y(1u, math::ln_1p(x(1u)));",
        2,
        2,
    )
    .tolerance("ln 4 ulp relative (z 3 ulp, series and Horner 1, e ln 2 split exact, the sums 1; near 1 relative through z); ln_1p 6 ulp (ln's 4, the quotient 2)");
    for k in 0..8000 {
        let x = r32(match k % 4 {
            0 => rng.log_uniform(1.2e-38, 3e38),
            1 => 1.0 + rng.range(-0.3, 0.5),
            2 => 1.0 + rng.range(-1.0, 1.0) * rng.log_uniform(1e-7, 1e-2),
            _ => rng.log_uniform(0.5, 2.0),
        });
        let y = r32(rng.log_uniform(1e-12, 1e12));
        // ln at exactly 1 is 0: relative tolerance 0 with the flush floor.
        ln.case(
            vec![x as f32, y as f32],
            vec![x.ln(), y.ln_1p()],
            vec![Tol::ulps(4.0), Tol::ulps(6.0)],
        );
    }
    vec![atan, sc, hy, ex, ln]
}
