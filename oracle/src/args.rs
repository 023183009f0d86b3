//! Argument parsing and output of the oracle, independent of the precision: every argument is
//! read as `f64` and checked here (finite, the right shape), and every error names the
//! argument. The ops convert to their precision afterwards (`eval::p32`, `eval::p64`).

use filtered_ndf::math::Real;
use serde_json::{Value, json};

/// The precision an op evaluates in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// `filtered_ndf::f32`.
    F32,
    /// `filtered_ndf::f64`.
    F64,
}

/// `"precision"`: `"f32"` or `"f64"` (default).
pub fn precision(v: &Value) -> Result<Precision, String> {
    match v.get("precision") {
        None => Ok(Precision::F64),
        Some(Value::String(s)) if s == "f64" => Ok(Precision::F64),
        Some(Value::String(s)) if s == "f32" => Ok(Precision::F32),
        Some(other) => Err(format!("precision must be \"f32\" or \"f64\", got {other}")),
    }
}

/// The argument `key`, which must be present.
pub fn get<'a>(v: &'a Value, key: &str) -> Result<&'a Value, String> {
    v.get(key)
        .ok_or_else(|| format!("missing argument `{key}`"))
}

/// A finite number.
pub fn finite(x: &Value, key: &str) -> Result<f64, String> {
    let f = x
        .as_f64()
        .ok_or_else(|| format!("argument `{key}` must be a number, got {x}"))?;
    if f.is_finite() {
        Ok(f)
    } else {
        Err(format!("argument `{key}` is not finite"))
    }
}

/// The finite number `key`.
pub fn number(v: &Value, key: &str) -> Result<f64, String> {
    finite(get(v, key)?, key)
}

/// The finite number `key` if present.
pub fn opt_number(v: &Value, key: &str) -> Result<Option<f64>, String> {
    v.get(key).map(|x| finite(x, key)).transpose()
}

/// The finite number `key >= 0` if present.
pub fn opt_non_negative(v: &Value, key: &str) -> Result<Option<f64>, String> {
    match opt_number(v, key)? {
        Some(x) if x < 0.0 => Err(format!("argument `{key}` must be >= 0, got {x}")),
        x => Ok(x),
    }
}

/// `N` finite numbers `[x1, ..., xN]`.
pub fn vector<const N: usize>(x: &Value, key: &str) -> Result<[f64; N], String> {
    let a = x
        .as_array()
        .ok_or_else(|| format!("argument `{key}` must be an array of {N} numbers, got {x}"))?;
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

/// The vector `key` of `N` finite numbers.
pub fn array<const N: usize>(v: &Value, key: &str) -> Result<[f64; N], String> {
    vector(get(v, key)?, key)
}

/// Two vectors of `N` numbers, `[[..], [..]]` (a pair of derivatives).
pub fn pair<const N: usize>(x: &Value, key: &str) -> Result<[[f64; N]; 2], String> {
    match x.as_array().map(Vec::as_slice) {
        Some([a, b]) => Ok([vector(a, key)?, vector(b, key)?]),
        _ => Err(format!(
            "argument `{key}` must be two arrays of {N} numbers [[..], [..]], got {x}"
        )),
    }
}

/// The string `key`.
pub fn string<'a>(v: &'a Value, key: &str) -> Result<&'a str, String> {
    let x = get(v, key)?;
    x.as_str()
        .ok_or_else(|| format!("argument `{key}` must be a string, got {x}"))
}

/// The boolean `key`, `default` if absent.
pub fn flag(v: &Value, key: &str, default: bool) -> Result<bool, String> {
    match v.get(key) {
        None => Ok(default),
        Some(Value::Bool(b)) => Ok(*b),
        Some(x) => Err(format!("argument `{key}` must be true or false, got {x}")),
    }
}

/// The NDF family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dist {
    /// GGX (Trowbridge-Reitz).
    Ggx,
    /// Beckmann.
    Beckmann,
}

/// `"dist"`: `"ggx"` or `"beckmann"`.
pub fn dist(v: &Value) -> Result<Dist, String> {
    match v.get("dist").and_then(Value::as_str) {
        Some("ggx") => Ok(Dist::Ggx),
        Some("beckmann") => Ok(Dist::Beckmann),
        Some(other) => Err(format!(
            "dist must be \"ggx\" or \"beckmann\", got \"{other}\""
        )),
        None => Err("missing argument `dist` (\"ggx\" or \"beckmann\")".into()),
    }
}

/// Roughness as given: a number, `[ax, ay]`, or `[[a11, a12], [a21, a22]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RoughnessArg {
    /// `alpha`.
    Iso(f64),
    /// `[alpha_x, alpha_y]`.
    Aniso(f64, f64),
    /// `[[a11, a12], [a21, a22]]` (checked for symmetry by the library).
    Matrix([[f64; 2]; 2]),
}

impl RoughnessArg {
    /// `(alpha_x, alpha_y)` of an isotropic or axis-aligned roughness; an error naming `what`
    /// for a matrix.
    pub fn axis_aligned(self, what: &str) -> Result<(f64, f64), String> {
        match self {
            Self::Iso(a) => Ok((a, a)),
            Self::Aniso(ax, ay) => Ok((ax, ay)),
            Self::Matrix(_) => Err(format!(
                "{what} needs an axis-aligned roughness (number or [ax, ay]): its rectangle is \
                 axis-aligned"
            )),
        }
    }
}

const ROUGHNESS_FORMS: &str = "a number, [ax, ay] or [[a11, a12], [a12, a22]]";

/// `"roughness"` in one of its three forms.
pub fn roughness_arg(v: &Value) -> Result<RoughnessArg, String> {
    let r = get(v, "roughness")?;
    if r.is_number() {
        return Ok(RoughnessArg::Iso(finite(r, "roughness")?));
    }
    let err = || format!("roughness must be {ROUGHNESS_FORMS}, got {r}");
    match r.as_array().ok_or_else(err)?.as_slice() {
        [x, y] if x.is_number() && y.is_number() => Ok(RoughnessArg::Aniso(
            finite(x, "roughness")?,
            finite(y, "roughness")?,
        )),
        [r1, r2] if r1.is_array() && r2.is_array() => Ok(RoughnessArg::Matrix([
            vector(r1, "roughness")?,
            vector(r2, "roughness")?,
        ])),
        _ => Err(err()),
    }
}

/// What to evaluate on a lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Point {
    /// `"m"`: `D(m)` per steradian.
    D([f64; 3]),
    /// `"slope"`: `P22(slope)` per unit slope area.
    P22([f64; 2]),
    /// `"w"`: Smith `Lambda(w)`.
    Lambda([f64; 3]),
    /// None of them: the lobe itself (its roughness).
    Lobe,
}

/// At most one of `"m"`, `"slope"`, `"w"`.
pub fn point(v: &Value) -> Result<Point, String> {
    let given: Vec<&str> = ["m", "slope", "w"]
        .into_iter()
        .filter(|k| v.get(*k).is_some())
        .collect();
    match given.as_slice() {
        [] => Ok(Point::Lobe),
        ["m"] => Ok(Point::D(array(v, "m")?)),
        ["slope"] => Ok(Point::P22(array(v, "slope")?)),
        ["w"] => Ok(Point::Lambda(array(v, "w")?)),
        _ => Err(format!(
            "give at most one of `m`, `slope`, `w` (got {})",
            given.join(", ")
        )),
    }
}

/// A pixel footprint as the renderer has it (the constructors of `Footprint`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FootprintArg {
    /// `{"slope": [dh_u, dh_v]}` (or the bare pair): `from_slope_derivatives`.
    Slope([[f64; 2]; 2]),
    /// `{"projected": [dp_u, dp_v]}`: `from_projected_derivatives` (TK19 sec. 3.2, used as
    /// slope changes).
    Projected([[f64; 2]; 2]),
    /// `{"projected_in_slope": {"h", "dp"}}`: `from_projected_derivatives_in_slope`.
    ProjectedInSlope {
        /// The half vector.
        h: [f64; 3],
        /// `[dp_u, dp_v]`.
        dp: [[f64; 2]; 2],
    },
    /// `{"normal_differences": [dn_u, dn_v]}`: `from_normal_differences` (tangent frame).
    NormalDifferences([[f64; 3]; 2]),
    /// `{"half_vector": {"h", "dh_dx", "dh_dy"}}`: `from_half_vector_derivatives` (not in
    /// the library yet).
    HalfVector {
        /// The half vector.
        h: [f64; 3],
        /// `ddx` of the tangent-space half vector.
        dh_dx: [f64; 3],
        /// `ddy` of the tangent-space half vector.
        dh_dy: [f64; 3],
    },
}

const FOOTPRINT_FORMS: &str = "`footprint` must be [[dhu_x, dhu_y], [dhv_x, dhv_y]] or an \
    object with one key: \"slope\", \"projected\", \"projected_in_slope\", \
    \"normal_differences\" or \"half_vector\"";

/// `"footprint"`: the bare pair of slope derivatives or an object naming its form.
pub fn footprint_arg(v: &Value) -> Result<FootprintArg, String> {
    let fp = get(v, "footprint")?;
    if fp.is_array() {
        return Ok(FootprintArg::Slope(pair(fp, "footprint")?));
    }
    let obj = fp.as_object().ok_or(FOOTPRINT_FORMS)?;
    let mut it = obj.iter();
    let (Some((form, x)), None) = (it.next(), it.next()) else {
        return Err(FOOTPRINT_FORMS.into());
    };
    match form.as_str() {
        "slope" => Ok(FootprintArg::Slope(pair(x, "footprint.slope")?)),
        "projected" => Ok(FootprintArg::Projected(pair(x, "footprint.projected")?)),
        "projected_in_slope" => Ok(FootprintArg::ProjectedInSlope {
            h: array(x, "h").map_err(|e| format!("footprint.projected_in_slope: {e}"))?,
            dp: pair(get(x, "dp")?, "footprint.projected_in_slope.dp")?,
        }),
        "normal_differences" => Ok(FootprintArg::NormalDifferences(pair(
            x,
            "footprint.normal_differences",
        )?)),
        "half_vector" => {
            let ctx = |e: String| format!("footprint.half_vector: {e}");
            Ok(FootprintArg::HalfVector {
                h: array(x, "h").map_err(ctx)?,
                dh_dx: array(x, "dh_dx").map_err(ctx)?,
                dh_dy: array(x, "dh_dy").map_err(ctx)?,
            })
        }
        other => Err(format!(
            "unknown footprint form \"{other}\"; {FOOTPRINT_FORMS}"
        )),
    }
}

/// A named set of clamp rules (`ClampRules::DEFAULT`, `NONE`, `GDC2016`, `KHPL16`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClampPreset {
    /// `ClampRules::DEFAULT`.
    Default,
    /// `ClampRules::NONE`.
    None,
    /// `ClampRules::GDC2016`.
    Gdc2016,
    /// `ClampRules::KHPL16`.
    Khpl16,
}

/// The rectangle floor (`ExtentFloor`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FloorArg {
    /// `ExtentFloor::None`.
    None,
    /// `ExtentFloor::Constant(e)`.
    Constant(f64),
    /// `ExtentFloor::AlphaCapped(cap)`.
    AlphaCapped(f64),
}

/// Clamp rules as given: a base set (the method's own if `None`) and field overrides.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClampArg {
    /// The base set.
    pub preset: Option<ClampPreset>,
    /// `max_extent` (`inf` allowed).
    pub max_extent: Option<f64>,
    /// `floor`.
    pub floor: Option<FloorArg>,
    /// `kappa` (`inf` allowed).
    pub kappa: Option<f64>,
    /// `det_clamp`.
    pub det_clamp: Option<bool>,
}

fn clamp_preset(s: &str) -> Result<ClampPreset, String> {
    match s {
        "default" => Ok(ClampPreset::Default),
        "none" => Ok(ClampPreset::None),
        "gdc2016" => Ok(ClampPreset::Gdc2016),
        "khpl16" => Ok(ClampPreset::Khpl16),
        _ => Err(format!(
            "clamps must be \"default\", \"none\", \"gdc2016\", \"khpl16\" or an object, got \
             \"{s}\""
        )),
    }
}

/// A bound `>= 0`: a number or `"inf"` (JSON has no infinity).
fn bound(x: &Value, key: &str) -> Result<f64, String> {
    if x.as_str() == Some("inf") {
        return Ok(f64::INFINITY);
    }
    let b = finite(x, key).map_err(|_| format!("`{key}` must be a number >= 0 or \"inf\""))?;
    if b < 0.0 {
        return Err(format!("`{key}` must be >= 0, got {b}"));
    }
    Ok(b)
}

fn floor_arg(x: &Value) -> Result<FloorArg, String> {
    const FORMS: &str =
        "clamps.floor must be \"none\", {\"constant\": e} or {\"alpha_capped\": cap}";
    if x.as_str() == Some("none") {
        return Ok(FloorArg::None);
    }
    let obj = x.as_object().ok_or(FORMS)?;
    match (obj.len(), obj.get("constant"), obj.get("alpha_capped")) {
        (1, Some(e), None) => Ok(FloorArg::Constant(bound(e, "clamps.floor.constant")?)),
        (1, None, Some(c)) => Ok(FloorArg::AlphaCapped(bound(
            c,
            "clamps.floor.alpha_capped",
        )?)),
        _ => Err(FORMS.into()),
    }
}

/// `"clamps"` if present: a preset name, or an object with an optional `"preset"` and any of
/// `max_extent`, `floor`, `kappa`, `det_clamp`.
pub fn clamps_arg(v: &Value) -> Result<Option<ClampArg>, String> {
    let Some(c) = v.get("clamps") else {
        return Ok(None);
    };
    if let Some(s) = c.as_str() {
        return Ok(Some(ClampArg {
            preset: Some(clamp_preset(s)?),
            ..ClampArg::default()
        }));
    }
    let obj = c
        .as_object()
        .ok_or("clamps must be a preset name or an object")?;
    let mut arg = ClampArg::default();
    for (k, x) in obj {
        match k.as_str() {
            "preset" => {
                let s = x.as_str().ok_or("clamps.preset must be a string")?;
                arg.preset = Some(clamp_preset(s)?);
            }
            "max_extent" => arg.max_extent = Some(bound(x, "clamps.max_extent")?),
            "kappa" => arg.kappa = Some(bound(x, "clamps.kappa")?),
            "floor" => arg.floor = Some(floor_arg(x)?),
            "det_clamp" => {
                arg.det_clamp = Some(x.as_bool().ok_or("clamps.det_clamp must be a boolean")?)
            }
            other => {
                return Err(format!(
                    "unknown clamp rule \"{other}\" (preset, max_extent, floor, kappa, \
                     det_clamp)"
                ));
            }
        }
    }
    Ok(Some(arg))
}

/// A result widened to `f64`; NaN is refused (a NaN here is a crate bug, reported as such)
/// and infinities are written as the strings `"inf"` / `"-inf"` (JSON has none).
pub fn out<T: Real>(x: T) -> Result<Value, String> {
    let x = x.to_f64();
    if x.is_nan() {
        return Err("internal error: NaN result".into());
    }
    Ok(if x.is_infinite() {
        json!(if x > 0.0 { "inf" } else { "-inf" })
    } else {
        json!(x)
    })
}

/// `[x1, ..., xN]` through [`out`].
pub fn vec_out<T: Real>(xs: &[T]) -> Result<Value, String> {
    xs.iter()
        .map(|&x| out(x))
        .collect::<Result<Vec<_>, _>>()
        .map(Value::Array)
}

/// The symmetric matrix `[[a11, a12], [a12, a22]]` through [`out`].
pub fn matrix_out<T: Real>(a11: T, a12: T, a22: T) -> Result<Value, String> {
    Ok(json!([[out(a11)?, out(a12)?], [out(a12)?, out(a22)?]]))
}

/// `"kernel"`: a slope-domain covariance `[[s11, s12], [s12, s22]]` (slope^2), checked to be
/// finite, symmetric (to 8 ulps of its largest entry) and positive semi-definite; returns
/// `[s11, s12, s22]`.
pub fn kernel_arg(v: &Value) -> Result<[f64; 3], String> {
    let k = pair::<2>(get(v, "kernel")?, "kernel")?;
    let (s11, s12, s21, s22) = (k[0][0], k[0][1], k[1][0], k[1][1]);
    let scale = s11.abs().max(s22.abs()).max(s12.abs());
    if (s12 - s21).abs() > 8.0 * f64::EPSILON * scale {
        return Err("kernel is not symmetric".into());
    }
    if s11 < 0.0 || s22 < 0.0 {
        return Err("kernel has a negative variance (diagonal entry)".into());
    }
    if s12 * s12 > s11 * s22 {
        return Err("kernel is indefinite (s12^2 > s11 s22)".into());
    }
    Ok([s11, s12, s22])
}
