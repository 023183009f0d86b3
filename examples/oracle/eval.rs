//! The oracle's evaluator: one JSON object in, one JSON object out. Shared by
//! `examples/oracle/main.rs` and the end-to-end test `tests/oracle.rs` (one source).

use filtered_ndf::math::Real;
use serde_json::{Value, json};

/// One op of the evaluator: its name, arguments and the equation it implements.
pub struct OpInfo {
    /// The op name (`"op"` field).
    pub name: &'static str,
    /// Its arguments, `name: description`.
    pub args: &'static str,
    /// What it returns and the paper equation it implements.
    pub returns: &'static str,
}

/// Every op, for `--list`.
pub const OPS: &[OpInfo] = &[
    OpInfo {
        name: "ndf",
        args: "dist (\"ggx\"|\"beckmann\"), roughness, m (unit micronormal, tangent frame)",
        returns: "D(m) per steradian; GGX: TK19 supp. sec. 1, Beckmann: KHPL16 eq. 14 / Heitz 2014",
    },
    OpInfo {
        name: "slope_pdf",
        args: "dist, roughness, slope ([sx, sy], s = -m_xy/m_z)",
        returns: "P22(slope) per unit slope area (TK19 supp. sec. 1)",
    },
    OpInfo {
        name: "lambda",
        args: "dist, roughness, w (unit direction)",
        returns: "Smith Lambda(w) (TK19 supp. sec. 1; Heitz 2014 eq. 72, 80)",
    },
    OpInfo {
        name: "jacobian",
        args: "kind (\"sphere_to_slope\"|\"sphere_to_projected\"|\"projected_to_slope\"), h (unit half vector)",
        returns: "2x2 matrix [[j11, j12], [j21, j22]], j_ik = d out_i / d in_k; TK19 supp. eq. 7, 4, 6",
    },
    OpInfo {
        name: "isotropic_roughness",
        args: "alpha, dn_u, dn_v (world-space normal differences, [x, y, z]), variant (\"max\"|\"trace\"|\"average\"), optional kappa (default 0.18)",
        returns: "filtered alpha = sqrt(saturate(alpha^2 + min(kernel, kappa))); TK19 eq. 1, 4, 5 with eq. 3, sigma^2 = 0.25",
    },
    OpInfo {
        name: "filter_roughness",
        args: "roughness, footprint ([[dhu_x, dhu_y], [dhv_x, dhv_y]], slope change per pixel), optional sigma (pixels, default 0.5)",
        returns: "filtered roughness matrix [[a11, a12], [a12, a22]] = A + 2 Sigma, Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T); KHPL16 eq. 13-15, TK19 sec. 2.2 (exact for Beckmann)",
    },
    OpInfo {
        name: "ggx_rect",
        args: "roughness (number or [ax, ay]; axis-aligned), center ([sx, sy], slope), half_extent ([hx, hy], slope)",
        returns: "average of the GGX slope density over center +/- half_extent, per unit slope area; KHPL16 eq. 16 (Appendix A corrected), exact",
    },
    OpInfo {
        name: "ggx_proxy",
        args: "alpha, half_extent (slope, one axis), variant (\"exact\"|\"simple\")",
        returns: "effective GGX alpha whose peak 1/(pi alpha'^2) matches the rectangle-filtered peak (KHPL16 eq. 19-20, eq. 20 corrected: exact), or sqrt(alpha^2 + H^2) (simple)",
    },
];

/// `{"ok": ...}` or `{"error": ...}` for one input line. Never panics.
pub fn eval_line(line: &str) -> String {
    let out = match serde_json::from_str::<Value>(line) {
        Ok(v) => match eval(&v) {
            Ok(ok) => json!({ "ok": ok }),
            Err(e) => json!({ "error": e }),
        },
        Err(e) => json!({ "error": format!("malformed JSON: {e}") }),
    };
    out.to_string()
}

/// The precision an op evaluates in.
#[derive(Clone, Copy)]
enum Precision {
    F32,
    F64,
}

fn precision(v: &Value) -> Result<Precision, String> {
    match v.get("precision") {
        None => Ok(Precision::F64),
        Some(Value::String(s)) if s == "f64" => Ok(Precision::F64),
        Some(Value::String(s)) if s == "f32" => Ok(Precision::F32),
        Some(other) => Err(format!("precision must be \"f32\" or \"f64\", got {other}")),
    }
}

fn number(v: &Value, key: &str) -> Result<f64, String> {
    let x = v
        .get(key)
        .ok_or_else(|| format!("missing argument `{key}`"))?;
    finite(x, key)
}

fn finite(x: &Value, key: &str) -> Result<f64, String> {
    let f = x
        .as_f64()
        .ok_or_else(|| format!("argument `{key}` must be a number, got {x}"))?;
    if f.is_finite() {
        Ok(f)
    } else {
        Err(format!("argument `{key}` is not finite"))
    }
}

fn array<const N: usize>(v: &Value, key: &str) -> Result<[f64; N], String> {
    let a = v
        .get(key)
        .ok_or_else(|| format!("missing argument `{key}`"))?
        .as_array()
        .ok_or_else(|| format!("argument `{key}` must be an array of {N} numbers"))?;
    if a.len() != N {
        return Err(format!(
            "argument `{key}` must have {N} elements, has {}",
            a.len()
        ));
    }
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(a) {
        *o = finite(x, key)?;
    }
    Ok(out)
}

/// Roughness as given: a number, `[ax, ay]`, or `[[a11, a12], [a21, a22]]`.
enum RoughnessArg {
    Iso(f64),
    Aniso(f64, f64),
    Matrix([[f64; 2]; 2]),
}

fn roughness_arg(v: &Value) -> Result<RoughnessArg, String> {
    let r = v.get("roughness").ok_or("missing argument `roughness`")?;
    if r.is_number() {
        return Ok(RoughnessArg::Iso(finite(r, "roughness")?));
    }
    let a = r
        .as_array()
        .ok_or("roughness must be a number, [ax, ay] or [[a11, a12], [a12, a22]]")?;
    match a.as_slice() {
        [x, y] if x.is_number() && y.is_number() => Ok(RoughnessArg::Aniso(
            finite(x, "roughness")?,
            finite(y, "roughness")?,
        )),
        [r1, r2] if r1.is_array() && r2.is_array() => {
            let row = |r: &Value| -> Result<[f64; 2], String> {
                match r.as_array().map(|a| a.as_slice()) {
                    Some([a, b]) => Ok([finite(a, "roughness")?, finite(b, "roughness")?]),
                    _ => Err("roughness matrix rows must have 2 numbers".into()),
                }
            };
            Ok(RoughnessArg::Matrix([row(r1)?, row(r2)?]))
        }
        _ => Err("roughness must be a number, [ax, ay] or [[a11, a12], [a12, a22]]".into()),
    }
}

fn dist(v: &Value) -> Result<&str, String> {
    match v.get("dist").and_then(Value::as_str) {
        Some(d @ ("ggx" | "beckmann")) => Ok(d),
        Some(other) => Err(format!(
            "dist must be \"ggx\" or \"beckmann\", got \"{other}\""
        )),
        None => Err("missing argument `dist` (\"ggx\" or \"beckmann\")".into()),
    }
}

/// Widens a result to f64 and refuses NaN (a NaN here is a crate bug, reported as such).
fn out<T: Real>(x: T) -> Result<Value, String> {
    let x = x.to_f64();
    if x.is_nan() {
        return Err("internal error: NaN result".into());
    }
    // JSON has no infinity: report it as the string "inf" (documented in --list).
    Ok(if x.is_infinite() {
        json!(if x > 0.0 { "inf" } else { "-inf" })
    } else {
        json!(x)
    })
}

/// Runs `$body` with `$p` bound to the precision module (`filtered_ndf::f32` or `f64`).
macro_rules! in_precision {
    ($prec:expr, $p:ident, $body:block) => {
        match $prec {
            Precision::F32 => {
                use filtered_ndf::f32 as $p;
                $body
            }
            Precision::F64 => {
                use filtered_ndf::f64 as $p;
                $body
            }
        }
    };
}

/// Runs `$body` with `$r` bound to the checked roughness (one of three forms) of `$arg`.
macro_rules! with_roughness {
    ($p:ident, $arg:expr, $r:ident, $body:expr) => {{
        let c = |x: f64| <$p::F as Real>::from_f64(x);
        match $arg {
            RoughnessArg::Iso(a) => {
                let $r = $p::Isotropic::new(c(a)).map_err(|e| e.to_string())?;
                $body
            }
            RoughnessArg::Aniso(ax, ay) => {
                let $r = $p::AxisAligned::new(c(ax), c(ay)).map_err(|e| e.to_string())?;
                $body
            }
            RoughnessArg::Matrix(m) => {
                let $r = $p::RoughnessMatrix::from_mat2($p::Mat2::from_cols(
                    $p::Vec2::new(c(m[0][0]), c(m[1][0])),
                    $p::Vec2::new(c(m[0][1]), c(m[1][1])),
                ))
                .map_err(|e| e.to_string())?;
                $body
            }
        }
    }};
}

/// Runs `$body` with `$ndf` bound to the NDF `$dist` of roughness `$arg` (three forms).
macro_rules! with_ndf {
    ($p:ident, $dist:expr, $arg:expr, $ndf:ident, $body:expr) => {
        with_roughness!($p, $arg, r, {
            if $dist == "ggx" {
                let $ndf = $p::Ggx::new(r);
                $body
            } else {
                let $ndf = $p::Beckmann::new(r);
                $body
            }
        })
    };
}

fn matrix_json<T: Real>(a11: T, a12: T, a22: T) -> Result<Value, String> {
    Ok(json!([[out(a11)?, out(a12)?], [out(a12)?, out(a22)?]]))
}

fn eval(v: &Value) -> Result<Value, String> {
    if !v.is_object() {
        return Err("each line must be a JSON object with an `op` field".into());
    }
    let op = v
        .get("op")
        .and_then(Value::as_str)
        .ok_or("missing `op` (string); run with --list for the ops")?;
    let prec = precision(v)?;
    match op {
        "ndf" => {
            let (d, r, mv) = (dist(v)?, roughness_arg(v)?, array::<3>(v, "m")?);
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let m = p::Vec3::new(c(mv[0]), c(mv[1]), c(mv[2]));
                with_ndf!(p, d, r, ndf, out(p::Ndf::d(&ndf, m)))
            })
        }
        "slope_pdf" => {
            let (d, r, sv) = (dist(v)?, roughness_arg(v)?, array::<2>(v, "slope")?);
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let s = p::Vec2::new(c(sv[0]), c(sv[1]));
                with_ndf!(p, d, r, ndf, out(p::Ndf::p22(&ndf, s)))
            })
        }
        "lambda" => {
            let (d, r, wv) = (dist(v)?, roughness_arg(v)?, array::<3>(v, "w")?);
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let w = p::Vec3::new(c(wv[0]), c(wv[1]), c(wv[2]));
                with_ndf!(p, d, r, ndf, out(p::Ndf::lambda(&ndf, w)))
            })
        }
        "jacobian" => {
            let hv = array::<3>(v, "h")?;
            let kind = v.get("kind").and_then(Value::as_str).unwrap_or("");
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let h = p::Vec3::new(c(hv[0]), c(hv[1]), c(hv[2]));
                let j = match kind {
                    "sphere_to_slope" => p::footprint::jacobian::sphere_to_slope(h),
                    "sphere_to_projected" => p::footprint::jacobian::sphere_to_projected(h),
                    "projected_to_slope" => p::footprint::jacobian::projected_to_slope(h),
                    _ => return Err(format!("unknown jacobian kind \"{kind}\"; see --list")),
                };
                // glam is column-major: x_axis holds d out / d in_1.
                Ok(json!([
                    [out(j.x_axis.x)?, out(j.y_axis.x)?],
                    [out(j.x_axis.y)?, out(j.y_axis.y)?]
                ]))
            })
        }
        "isotropic_roughness" => {
            let alpha = number(v, "alpha")?;
            let (du, dv) = (array::<3>(v, "dn_u")?, array::<3>(v, "dn_v")?);
            let kappa = match v.get("kappa") {
                None => 0.18,
                Some(k) => finite(k, "kappa")?,
            };
            let variant = v.get("variant").and_then(Value::as_str).unwrap_or("");
            if alpha < 0.0 {
                return Err("alpha must be >= 0".into());
            }
            in_precision!(prec, p, {
                use p::filter::deferred::{
                    Bandwidth, SIGMA2, filtered_alpha, normal_difference_covariance,
                };
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let bw = match variant {
                    "max" => Bandwidth::Max,
                    "trace" => Bandwidth::Trace,
                    "average" => Bandwidth::Average,
                    _ => {
                        return Err(format!(
                            "variant must be \"max\", \"trace\" or \"average\", got \"{variant}\""
                        ));
                    }
                };
                let dn_u = p::Vec3::new(c(du[0]), c(du[1]), c(du[2]));
                let dn_v = p::Vec3::new(c(dv[0]), c(dv[1]), c(dv[2]));
                let sigma = normal_difference_covariance(dn_u, dn_v, SIGMA2);
                out(filtered_alpha(c(alpha), &sigma, bw, c(kappa)))
            })
        }
        "filter_roughness" => {
            let r = roughness_arg(v)?;
            let fp = v.get("footprint").ok_or("missing argument `footprint`")?;
            let rows = fp
                .as_array()
                .filter(|a| a.len() == 2)
                .ok_or("footprint must be [[dhu_x, dhu_y], [dhv_x, dhv_y]]")?;
            let wrap = |x: &Value| json!({ "footprint": x });
            let du = array::<2>(&wrap(&rows[0]), "footprint")?;
            let dv = array::<2>(&wrap(&rows[1]), "footprint")?;
            let sigma = match v.get("sigma") {
                None => 0.5,
                Some(x) => finite(x, "sigma")?,
            };
            if sigma < 0.0 {
                return Err("sigma must be >= 0".into());
            }
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let fp = p::Footprint::from_slope_derivatives(
                    p::Vec2::new(c(du[0]), c(du[1])),
                    p::Vec2::new(c(dv[0]), c(dv[1])),
                );
                with_roughness!(p, r, rr, {
                    let (a11, a12, a22) =
                        p::filter::gaussian(rr, fp.covariance(c(sigma))).entries();
                    matrix_json(a11, a12, a22)
                })
            })
        }
        "ggx_rect" => {
            let r = roughness_arg(v)?;
            let (cv, hv) = (array::<2>(v, "center")?, array::<2>(v, "half_extent")?);
            let (ax, ay) = match r {
                RoughnessArg::Iso(a) => (a, a),
                RoughnessArg::Aniso(ax, ay) => (ax, ay),
                RoughnessArg::Matrix(_) => {
                    return Err(
                        "ggx_rect needs an axis-aligned roughness (number or [ax, ay])".into(),
                    );
                }
            };
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let r = p::AxisAligned::new(c(ax), c(ay)).map_err(|e| e.to_string())?;
                out(p::filter::rect::p22_rect(
                    r,
                    p::Vec2::new(c(cv[0]), c(cv[1])),
                    p::Vec2::new(c(hv[0]), c(hv[1])),
                ))
            })
        }
        "ggx_proxy" => {
            let (alpha, h) = (number(v, "alpha")?, number(v, "half_extent")?);
            let variant = v.get("variant").and_then(Value::as_str).unwrap_or("");
            in_precision!(prec, p, {
                let c = |x: f64| <p::F as Real>::from_f64(x);
                let a = p::Isotropic::new(c(alpha))
                    .map_err(|e| e.to_string())?
                    .alpha();
                match variant {
                    "exact" => out(p::filter::proxy::effective_alpha(a, c(h))),
                    "simple" => out(p::filter::proxy::effective_alpha_simple(a, c(h))),
                    _ => Err(format!(
                        "variant must be \"exact\" or \"simple\", got \"{variant}\""
                    )),
                }
            })
        }
        other => Err(format!(
            "unknown op \"{other}\"; run with --list for the ops"
        )),
    }
}
