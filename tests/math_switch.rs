//! The one math switch (`filtered_ndf::math`): with the `libm` feature every float function
//! is libm's, bit for bit, also where `std` is on (`cargo test --features libm`: for
//! reproducibility across platforms); without it (and with `std`) the standard library's.
//! Checked function by function over arguments spread across each one's domain. The two
//! backends round differently in some last bits (except `sqrt`, which both round correctly),
//! so a switch that picked the other backend fails here wherever they differ: the count of
//! such arguments is printed per function (none where the platform's libm is the one the
//! `libm` crate ports, as on musl; there the backends are the same functions).

use filtered_ndf::math::Real;

/// Arguments of `f64`: log-spaced magnitudes of both signs, and values near the reduction
/// boundaries of the trigonometric and exponential functions.
fn args() -> Vec<f64> {
    let mut v = Vec::new();
    for i in 0..4000 {
        let m = 10f64.powf(-6.0 + 12.0 * (i as f64 / 4000.0));
        v.extend([m, -m, m * 1.000_000_3]);
    }
    for k in -40..40 {
        let x = k as f64 * std::f64::consts::FRAC_PI_4;
        v.extend([x, x + 1e-9, x - 1e-9, k as f64 * std::f64::consts::LN_2]);
    }
    v
}

/// Asserts `got` is the selected backend's value bit for bit, and returns whether the two
/// backends differ at this argument.
fn check(name: &str, x: f64, got: f64, libm: f64, std: f64) -> bool {
    let want = if cfg!(feature = "libm") { libm } else { std };
    assert!(
        got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
        "{name}({x:e}): {got:e}, want {want:e} (libm {libm:e}, std {std:e})"
    );
    libm.to_bits() != std.to_bits() && !(libm.is_nan() && std.is_nan())
}

macro_rules! unary {
    ($($name:ident: $libm:path, $std:path;)*) => {$({
        let differ = args()
            .into_iter()
            .filter(|&x| check(stringify!($name), x, Real::$name(x), $libm(x), $std(x)))
            .count();
        println!("{}: libm and std differ at {differ} arguments", stringify!($name));
    })*};
}

/// Each unary function of the switch in `f64`.
#[test]
fn unary_functions_come_from_the_selected_backend() {
    unary! {
        sqrt: libm::sqrt, f64::sqrt;
        exp: libm::exp, f64::exp;
        ln: libm::log, f64::ln;
        atan: libm::atan, f64::atan;
        sin: libm::sin, f64::sin;
        cos: libm::cos, f64::cos;
    }
}

/// The binary functions in `f64`, and the `f32` forms of a few.
#[test]
fn binary_and_f32_functions_come_from_the_selected_backend() {
    let xs = args();
    let mut differ = [0usize; 4];
    for (&x, &y) in xs.iter().zip(xs.iter().rev()) {
        differ[0] += usize::from(check(
            "atan2",
            x,
            Real::atan2(x, y),
            libm::atan2(x, y),
            x.atan2(y),
        ));
        let b = x.abs();
        let p = y.clamp(-30.0, 30.0);
        differ[1] += usize::from(check(
            "powf",
            b,
            Real::powf(b, p),
            libm::pow(b, p),
            b.powf(p),
        ));
        differ[2] += usize::from(check(
            "hypot",
            x,
            Real::hypot(x, y),
            libm::hypot(x, y),
            x.hypot(y),
        ));
        let xf = x as f32;
        let e = Real::exp(xf) as f64;
        differ[3] += usize::from(check("expf", x, e, libm::expf(xf) as f64, xf.exp() as f64));
    }
    println!("atan2, powf, hypot, expf: libm and std differ at {differ:?} arguments");
}
