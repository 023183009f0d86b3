// Helpers of the typed ops, included (with `ops_*.rs`) into `eval::p32` and `eval::p64`,
// where `p` is `filtered_ndf::f32` or `filtered_ndf::f64` and `F` its float. Every argument
// arrives checked in `f64` (see `args.rs`) and is rounded to `F` here, once.

use filtered_ndf::math::Real;
use p::filter::Filterable as _;
use p::{Ndf as _, NdfSampling as _};
use serde_json::{Value, json};

/// `x` rounded to the precision of the op.
fn f(x: f64) -> p::F {
    <p::F as Real>::from_f64(x)
}

fn v2(a: [f64; 2]) -> p::Vec2 {
    p::Vec2::new(f(a[0]), f(a[1]))
}

fn v3(a: [f64; 3]) -> p::Vec3 {
    p::Vec3::new(f(a[0]), f(a[1]), f(a[2]))
}

/// Runs `$body` with `$r` bound to the checked roughness (one of the three forms) of `$arg`;
/// an invalid roughness answers the library's `RoughnessError`.
macro_rules! with_roughness {
    ($arg:expr, $r:ident => $body:expr) => {
        match $arg {
            RoughnessArg::Iso(a) => {
                let $r = p::Isotropic::new(f(a)).map_err(|e| e.to_string())?;
                $body
            }
            RoughnessArg::Aniso(ax, ay) => {
                let $r = p::AxisAligned::new(f(ax), f(ay)).map_err(|e| e.to_string())?;
                $body
            }
            RoughnessArg::Matrix(m) => {
                let $r = p::RoughnessMatrix::from_mat2(p::Mat2::from_cols(
                    p::Vec2::new(f(m[0][0]), f(m[1][0])),
                    p::Vec2::new(f(m[0][1]), f(m[1][1])),
                ))
                .map_err(|e| e.to_string())?;
                $body
            }
        }
    };
}

/// Runs `$body` with `$ndf` bound to the material NDF `$dist` of roughness `$arg` (two
/// families times three roughness forms).
macro_rules! with_ndf {
    ($dist:expr, $arg:expr, $ndf:ident => $body:expr) => {
        with_roughness!($arg, r => match $dist {
            Dist::Ggx => {
                let $ndf = p::Ggx::new(r);
                $body
            }
            Dist::Beckmann => {
                let $ndf = p::Beckmann::new(r);
                $body
            }
        })
    };
}

/// `D`, `P22` or `Lambda` of `lobe` at the point; without one, `describe(lobe)`.
fn lobe_out<L: p::Ndf>(
    lobe: &L,
    point: Point,
    describe: impl FnOnce(&L) -> Result<Value, String>,
) -> Result<Value, String> {
    match point {
        Point::D(m) => out(lobe.d(v3(m))),
        Point::P22(s) => out(lobe.p22(v2(s))),
        Point::Lambda(w) => out(lobe.lambda(v3(w))),
        Point::Lobe => describe(lobe),
    }
}

/// `[[a11, a12], [a12, a22]]` of a roughness matrix.
fn matrix_of(r: &p::RoughnessMatrix) -> Result<Value, String> {
    let (a11, a12, a22) = r.entries();
    matrix_out(a11, a12, a22)
}

/// The footprint of the form given (the constructors of `Footprint`).
fn footprint(arg: FootprintArg) -> Result<p::Footprint, String> {
    Ok(match arg {
        FootprintArg::Slope([u, v]) => p::Footprint::from_slope_derivatives(v2(u), v2(v)),
        FootprintArg::Projected([u, v]) => p::Footprint::from_projected_derivatives(v2(u), v2(v)),
        FootprintArg::ProjectedInSlope { h, dp: [u, v] } => {
            p::Footprint::from_projected_derivatives_in_slope(v3(h), v2(u), v2(v))
        }
        FootprintArg::NormalDifferences([u, v]) => {
            p::Footprint::from_normal_differences(v3(u), v3(v))
        }
        FootprintArg::HalfVector { h, dh_dx, dh_dy } => {
            // PLACEHOLDER(from_half_vector_derivatives): `Footprint::from_half_vector_derivatives(
            // h, dh_dx, dh_dy)` is being added to the library; when it lands, replace this
            // error by
            //     p::Footprint::from_half_vector_derivatives(v3(h), v3(dh_dx), v3(dh_dy))
            // and move the op's test line in tests/data/oracle_session.jsonl to a value test.
            let _ = (h, dh_dx, dh_dy);
            return Err(
                "footprint form \"half_vector\" is not available yet: the library has \
                        no Footprint::from_half_vector_derivatives"
                    .into(),
            );
        }
    })
}

/// `base` (the method's own rules) with the preset and field overrides of `arg`.
fn clamp_rules(base: p::ClampRules, arg: Option<ClampArg>) -> p::ClampRules {
    let Some(arg) = arg else {
        return base;
    };
    let mut rules = match arg.preset {
        None => base,
        Some(ClampPreset::Default) => p::ClampRules::DEFAULT,
        Some(ClampPreset::None) => p::ClampRules::NONE,
        Some(ClampPreset::Gdc2016) => p::ClampRules::GDC2016,
        Some(ClampPreset::Khpl16) => p::ClampRules::KHPL16,
    };
    if let Some(l) = arg.max_extent {
        rules.max_extent = f(l);
    }
    if let Some(k) = arg.kappa {
        rules.kappa = f(k);
    }
    if let Some(d) = arg.det_clamp {
        rules.det_clamp = d;
    }
    if let Some(floor) = arg.floor {
        rules.floor = match floor {
            FloorArg::None => p::ExtentFloor::None,
            FloorArg::Constant(e) => p::ExtentFloor::Constant(f(e)),
            FloorArg::AlphaCapped(c) => p::ExtentFloor::AlphaCapped(f(c)),
        };
    }
    rules
}
