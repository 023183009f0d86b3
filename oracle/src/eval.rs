//! The oracle's evaluator: one JSON object in, one JSON object out, for the binary `oracle`,
//! its end-to-end test `tests/oracle.rs` and the GPU backend of `filtered-ndf-gpu`.
//!
//! Layout: [`OPS`] is the dispatcher and the documentation at once (every op is one entry with
//! its arguments, equation and handlers, so an op cannot exist without its `--list` text);
//! `args.rs` parses and checks arguments in `f64`; `typed.rs` and `ops_*.rs` evaluate them,
//! compiled once per precision into [`p32`] and [`p64`] as the library compiles its own
//! modules.

use crate::args::{self, Precision};
use serde_json::{Value, json};
use std::io::{BufRead, Write};

/// An op's evaluation in one precision.
pub type Handler = fn(&Value) -> Result<Value, String>;

/// One op of the evaluator: its name, arguments, the equation it implements and its
/// handlers.
pub struct OpInfo {
    /// The op name (`"op"` field).
    pub name: &'static str,
    /// Its arguments, `name: description`.
    pub args: &'static str,
    /// The equation it implements, with the paper equation it follows.
    pub equation: &'static str,
    /// What it returns (units, the values of the edge cases).
    pub returns: &'static str,
    /// The evaluation in `f32`.
    pub f32: Handler,
    /// The evaluation in `f64`.
    pub f64: Handler,
}

/// One [`OpInfo`] whose handlers are the function `$name` of [`p32`] and [`p64`].
macro_rules! op {
    ($name:ident, args: $a:expr, equation: $e:expr, returns: $r:expr $(,)?) => {
        OpInfo {
            name: stringify!($name),
            args: $a,
            equation: $e,
            returns: $r,
            f32: p32::$name,
            f64: p64::$name,
        }
    };
}

/// What every op shares, printed before the ops by `--list`.
pub const CONVENTIONS: &str = "\
Input: one JSON object per line, {\"op\": NAME, ...}; output: one line per input line, in order,
{\"ok\": VALUE} or {\"error\": MESSAGE}. A bad line answers an error and the stream goes on.
Every op takes \"precision\": \"f32\" | \"f64\" (default f64): the arguments are rounded to it
and the library's code for that precision runs. Arguments must be finite JSON numbers.
Infinite results are written as the strings \"inf\" / \"-inf\" (JSON has no infinity).
Tangent frame with z the shading normal; slope s = -m_xy / m_z.
roughness:  alpha | [ax, ay] | [[a11, a12], [a12, a22]] (A = alpha^2 I, diag(ax^2, ay^2), A).
footprint:  [[dhu_x, dhu_y], [dhv_x, dhv_y]] (slope change per pixel in x and y), or an object
            with one key naming the constructor of Footprint:
              {\"slope\": [dh_u, dh_v]}                        from_slope_derivatives
              {\"projected\": [dp_u, dp_v]}                    from_projected_derivatives (TK19 3.2)
              {\"projected_in_slope\": {\"h\": [x,y,z], \"dp\": [dp_u, dp_v]}}
                                                          from_projected_derivatives_in_slope
              {\"normal_differences\": [dn_u, dn_v]}  (3-vectors, tangent frame; TK19 eq. 3)
              {\"half_vector\": {\"h\", \"dh_dx\", \"dh_dy\"}}     (3-vectors; not in the library yet)
            Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T), sigma in pixels (TK19 sec. 2.2).
clamps:     \"default\" | \"none\" | \"gdc2016\" | \"khpl16\" (ClampRules::DEFAULT, ...), or an object
            {\"preset\"?, \"max_extent\"?, \"floor\"?, \"kappa\"?, \"det_clamp\"?} overriding the
            op's own rules; max_extent, kappa: number >= 0 or \"inf\"; floor: \"none\" |
            {\"constant\": e} | {\"alpha_capped\": cap}; det_clamp: bool. The rules (KHPL16 5.2,
            TK19 eq. 1): footprint scaled to max_extent lambda = max(|dh_u + dh_v|,
            |dh_u - dh_v|) / 2 <= max_extent; kernel eigenvalues min(2 lambda_i, kappa);
            rectangle half extents in [floor, max_extent]; tau = det(A) for the filtered matrix.
point:      at most one of \"m\" (unit micronormal: D), \"slope\" (P22), \"w\" (direction: Lambda);
            without one the ops that build a lobe return the lobe (its roughness).
backends:   --backend cpu (the default) evaluates with the library; --backend gpu answers every
            op that has a shader through the WGSL modules of shaders/ in f32, batched, after
            the end of input (ops without one answer an error naming the op):
            cargo run --release -p filtered-ndf-gpu --bin oracle-gpu -- --backend gpu";

/// Every op: the dispatcher and `--list` (see [`list`]).
pub const OPS: &[OpInfo] = &[
    op!(ndf,
        args: "dist (\"ggx\"|\"beckmann\"), roughness, m (unit micronormal)",
        equation: "GGX D(m) = 1 / (pi sqrt(det A) (m_xy^T A^-1 m_xy + m_z^2)^2); Beckmann \
                   D(m) = exp(-s^T A^-1 s) / (pi sqrt(det A) m_z^4); 0 for m_z <= 0 (TK19 supp. \
                   sec. 1; KHPL16 eq. 2, 14; Heitz 2014)",
        returns: "D(m) per steradian, integral D(m) m_z dm = 1",
    ),
    op!(slope_pdf,
        args: "dist, roughness, slope ([sx, sy])",
        equation: "GGX P22(s) = 1 / (pi sqrt(det A) (1 + s^T A^-1 s)^2); Beckmann P22(s) = \
                   exp(-s^T A^-1 s) / (pi sqrt(det A)) (TK19 supp. sec. 1)",
        returns: "P22(slope) per unit slope area",
    ),
    op!(lambda,
        args: "dist, roughness, w (direction; need not be unit)",
        equation: "q = w_xy^T A w_xy, a = |w_z| / sqrt(q); GGX Lambda = (sqrt(1 + q / w_z^2) - 1) \
                   / 2; Beckmann Lambda = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)) (TK19 \
                   supp. sec. 1; Heitz 2014 eq. 72, 80)",
        returns: "Smith Lambda(w); \"inf\" at w_z = 0, 0 for w = 0",
    ),
    op!(g1,
        args: "dist, roughness, w (direction), m (unit micronormal)",
        equation: "G1(w, m) = chi+(w.m) / (1 + Lambda(w)) (TK19 supp. sec. 1; Heitz 2014 sec. 5)",
        returns: "Smith masking in [0, 1]; 0 for w.m <= 0 and for grazing w",
    ),
    op!(g2,
        args: "dist, roughness, i, o (directions), m (unit micronormal)",
        equation: "G2(i, o, m) = chi+(i.m) chi+(o.m) / (1 + Lambda(i) + Lambda(o)) (height-\
                   correlated; Heitz 2014 eq. 99)",
        returns: "masking-shadowing in [0, 1]",
    ),
    op!(pdf,
        args: "dist, roughness, o (view direction), m (unit micronormal)",
        equation: "D_o(m) = G1(o) max(0, o.m) D(m) / o_z, G1(o) = 1 / (1 + Lambda(o)) (the \
                   distribution of visible normals: Heitz 2014 eq. 16; Heitz and d'Eon 2014 eq. 2)",
        returns: "the visible-normal density of m per steradian (integrates to 1 over m for \
                  every o above the surface); 0 for o_z <= 0, o.m <= 0, m_z <= 0",
    ),
    op!(sample,
        args: "dist, roughness, o (view direction), u ([u1, u2], each clamped into [0, 1), \
               NaN as 0)",
        equation: "m(u) = the visible micronormal NdfSampling::sample_visible_normal returns: \
                   with A = L L^T, o' = normalize(L^T o_xy, o_z) and n sampled for unit roughness, \
                   m = normalize(L n_xy, n_z); GGX: n = c + o', c on the spherical cap phi = 2 pi \
                   u1, c_z = (1 - u2)(1 + o'_z) - o'_z (Dupuy and Benyoub 2023, listing 3); \
                   Beckmann: slope of n by inverting the visible-slope CDF at u1 along o' and the \
                   Gaussian quantile at u2 across it (Heitz and d'Eon 2014 sec. 4). At o = z: GGX \
                   n = (sin t cos phi, sin t sin phi, cos t), tan^2 t = u2 / (1 - u2), phi = 2 pi \
                   u1; Beckmann n has the slopes -n_xy / n_z = (Phi^-1(u1), Phi^-1(u2)) / sqrt 2",
        returns: "[mx, my, mz], a unit vector with m_z > 0 and o.m > 0, distributed with the \
                  density of the op pdf; null where the sampler returns None (o_z <= 0)",
    ),
    op!(jacobian,
        args: "kind (\"sphere_to_slope\"|\"sphere_to_projected\"|\"projected_to_slope\"), h \
               (unit half vector)",
        equation: "J_ik = d out_i / d in_k of the maps between the sphere, the projected disk \
                   p = h_xy and the slope plane s = -h_xy / h_z (TK19 supp. eq. 7, 4, 6)",
        returns: "2x2 matrix [[j11, j12], [j21, j22]]",
    ),
    op!(isotropic_roughness,
        args: "alpha (>= 0), dn_u, dn_v (world-space normal differences [x, y, z]), variant \
               (\"max\"|\"trace\"|\"average\"), optional kappa (default 0.18)",
        equation: "alpha' = sqrt(saturate(alpha^2 + min(k, kappa))), k = 2 lambda_max(Sigma) \
                   (max), 2 tr(Sigma) (trace), tr(Sigma) (average), Sigma = 0.25 Gram(dn_u, dn_v) \
                   (TK19 eq. 1, 4, 5 with eq. 3)",
        returns: "the filtered isotropic alpha",
    ),
    op!(preset,
        args: "name (a name of filter::presets::ALL: \"TK19 max (eq. 1)\", \"TK19 trace (eq. \
               4)\", \"TK19 average (eq. 5)\", \"TK21 listing 5\", \"Filament\", \"Unity HDRP\", \
               \"Unity HDRP projected\", \"Godot 4\", \"O3DE\", \"Unreal\", \"Babylon.js \
               (Vlachos 2015)\", \"three.js\"), alpha (GGX roughness; <= 0 counts as 0), dn_u, \
               dn_v (world-space normal differences), optional raw (bool, default false)",
        equation: "the engine's KernelConvention: v = domain(max(alpha, floor^2)), \
                   k = min(max(scale norm(dn_u, dn_v)^exponent + bias, 0), clamp), v' = v + k (or \
                   max(v, k)), \
                   saturate: min(v', 1), alpha' = domain^-1(v'); domain alpha^2, alpha^2 / (1 - \
                   alpha^2), alpha or sqrt(alpha) (constants per preset: src/filter/presets.rs)",
        returns: "alpha' clamped into [1e-8, 1e4] (KernelConvention::filter, always a valid \
                  roughness); with raw: true the engine formula's own value \
                  (KernelConvention::apply, may be 0)",
    ),
    op!(filter_roughness,
        args: "roughness, footprint, optional sigma (pixels, default 0.5)",
        equation: "A' = A + 2 Sigma, no clamps (KHPL16 eq. 13-15; TK19 sec. 2.2: exact for \
                   Beckmann, the TK19 approximation for GGX), evaluated with tau = det A",
        returns: "the filtered roughness matrix [[a11, a12], [a12, a22]]",
    ),
    op!(projected_roughness,
        args: "roughness, footprint (TK21 means projected-disk derivatives), optional sigma \
               (pixels, default 0.5)",
        equation: "P = A (I - A)^-1, P' = P + 2 Sigma, A' = P' (I + P')^-1, no clamps (TK21 \
                   listing 1; eigenvalues of A above 0.99 pass unfiltered), tau = det A",
        returns: "the filtered GGX roughness matrix [[a11, a12], [a12, a22]]",
    ),
    op!(ggx_rect,
        args: "roughness (number or [ax, ay]), center ([sx, sy], slope), half_extent ([hx, hy])",
        equation: "mean of the GGX P22 over center +/- half_extent = (1 / (4 H_x H_y)) integral \
                   P22 (KHPL16 eq. 16; App. A divides by a quarter of the area), exact",
        returns: "per unit slope area",
    ),
    op!(ggx_rect_footprint,
        args: "roughness (number or [ax, ay]), footprint, optional clamps (default \"default\": \
               lambda = 1, floor 1e-3), optional point",
        equation: "H = clamp((|dh_u| + |dh_v|) / 2, floor, max_extent) per axis (the bounding \
                   rectangle of the one-pixel parallelogram, KHPL16 sec. 5.2-5.3); P22'(s) = mean \
                   of P22 over s +/- H (eq. 16); D'(m) = P22'(s(m)) / m_z^4; Lambda' = Smith \
                   Lambda of P22'",
        returns: "D', P22' or Lambda' at the point (Lambda': rect::lambda_rect, the box-filtered \
                  distribution's own); without one the clamped half extents [Hx, Hy]",
    ),
    op!(ggx_proxy,
        args: "alpha, half_extent (slope, one axis), variant (\"exact\"|\"simple\")",
        equation: "exact: alpha'^2 = (alpha^2 + H^2) t / atan(t), t = H / sqrt(alpha^2 + H^2) \
                   (KHPL16 eq. 19 solved; eq. 20 as printed is inconsistent with it); simple: \
                   alpha' = sqrt(alpha^2 + H^2)",
        returns: "the effective GGX alpha whose peak 1 / (pi alpha'^2) is the box-filtered peak",
    ),
    op!(filtered,
        args: "dist, roughness, footprint, method (\"gaussian_tk19\" | \"gaussian_khpl16\" | \
               \"gaussian_exact\" | \
               \"projected_tk21\" | \"rect_khpl16\" | \"rect_gdc2016\" | \"proxy_khpl16\"), \
               optional clamps (overrides the method's), optional sigma (pixels; gaussian and \
               projected only), optional point",
        equation: "the front door material.filtered(footprint, method). gaussian: A' = A + 2 \
                   Sigma_c, Sigma_c the clamped kernel (KHPL16 eq. 13-15, TK19 sec. 2.2; exact \
                   for Beckmann); gaussian_exact: the exact Gaussian filter with Sigma_c \
                   (gaussian_filtered; clamps \"khpl16\"); projected: TK21 as projected_roughness with Sigma_c; rect: the \
                   exact box filter over the clamped bounding rectangle (ggx_rect_footprint); \
                   proxy: per axis the exact ggx_proxy of the clamped half extent. Defaults: \
                   gaussian_tk19 and projected_tk21 clamps \"default\" (lambda 1, kappa 0.18, tau), \
                   sigma 0.5; gaussian_khpl16 \"khpl16\" (lambda 1, tau), sigma 0.5; rect_khpl16 \
                   and proxy_khpl16 \"khpl16\" (lambda 1, no floor); rect_gdc2016 \"gdc2016\" \
                   (floor min(alpha, 0.1))",
        returns: "D, P22 or Lambda of the filtered lobe at the point; without one the lobe: \
                  gaussian and projected [[a11, a12], [a12, a22]] (evaluated with tau = det A of \
                  the material), proxy [ax, ay], rect {\"roughness\": [ax, ay], \"half_extent\": \
                  [Hx, Hy]}. Beckmann with projected, rect or proxy, and rect or proxy with a \
                  matrix roughness, answer an error. Lambda of a rect lobe is the box-filtered \
                  distribution's own (rect::lambda_rect)",
    ),
    op!(gaussian_filtered,
        args: "dist, roughness, kernel ([[s11, s12], [s12, s22]], slope-domain covariance, \
               slope^2; finite, symmetric, positive semi-definite), slope ([sx, sy])",
        equation: "(P22 * N(0, kernel))(slope): GGX by the mixture identity P22_Sigma(s) = \
                   integral e^-w N(s; 0, (A + 2 w Sigma) / (2w)) dw (GaussianFilteredGgx, a \
                   trapezoid in ln w with a proven bound: 1.8e-6 relative in f32, 1.1e-11 in \
                   f64); Beckmann by A + 2 Sigma (KHPL16 eq. 15), exact",
        returns: "the filtered slope density per unit slope area; a negative diagonal, an \
                  indefinite, an asymmetric or a non-finite kernel answers an error",
    ),
    op!(temporal,
        args: "dist, roughness (base), dn_dt ([x, y]: the normal's rate in the tangent frame, \
               1/T), dt (T) or shutter (a box shutter's length T: dt = T / sqrt 6), optional \
               cos_theta, optional fraction (path share), optional point",
        equation: "alpha_t = min(|dt dn_dt| |cos_theta| sqrt(fraction), 1e4), a = dn_dt / \
                   |dn_dt|; D and P22 from A_conv = A + alpha_t^2 a a^T (Tessari et al. 2020 \
                   eq. 16 with A = 2 Sigma, tau = det A), Lambda from A (eq. 17: G_conv = G_mu); \
                   cos_theta and fraction clamped into [0, 1]",
        returns: "D, P22 or Lambda at the point; without one {\"alpha_t\", \"axis\": [ax, ay], \
                  \"roughness\": A_conv}",
    ),
];

/// The `--list` text: [`CONVENTIONS`], then every op with its arguments, equation and result
/// (wrapped at 100 columns).
pub fn list() -> String {
    let mut s = format!("{CONVENTIONS}\n\n");
    for op in OPS {
        s += op.name;
        s += "\n";
        for (label, text) in [
            ("args:", op.args),
            ("equation:", op.equation),
            ("returns:", op.returns),
        ] {
            s += &wrap(&format!("  {label:<10}"), text, 100);
        }
        s += "\n";
    }
    s
}

/// `text` after `head`, word-wrapped at `width` columns, continuation lines indented like
/// the first.
fn wrap(head: &str, text: &str, width: usize) -> String {
    let indent = " ".repeat(head.len());
    let mut out = String::new();
    let mut line = head.to_string();
    for word in text.split_whitespace() {
        if line.len() > indent.len() && line.len() + 1 + word.len() > width {
            out += line.trim_end();
            out += "\n";
            line.clone_from(&indent);
        } else if line.len() > indent.len() {
            line.push(' ');
        }
        line += word;
    }
    out += &line;
    out += "\n";
    out
}

/// `{"ok": ...}` or `{"error": ...}` for one input line. Never panics: a panic inside the
/// library (a bug) answers `{"error": "internal error: panic ..."}`.
pub fn eval_line(line: &str) -> String {
    let out = match serde_json::from_str::<Value>(line) {
        Ok(v) => match std::panic::catch_unwind(|| eval(&v)) {
            Ok(Ok(ok)) => json!({ "ok": ok }),
            Ok(Err(e)) => json!({ "error": e }),
            Err(_) => json!({ "error": "internal error: panic (a bug; please report the line)" }),
        },
        Err(e) => json!({ "error": format!("malformed JSON: {e}") }),
    };
    out.to_string()
}

/// Answers every non-blank line of `input` on `output`, flushing after each reply (so that a
/// client may wait for each answer). A line that is not UTF-8 answers an error; only I/O
/// errors stop it.
pub fn serve<R: BufRead, W: Write>(mut input: R, mut output: W) -> std::io::Result<()> {
    let mut buf = Vec::new();
    loop {
        buf.clear();
        if input.read_until(b'\n', &mut buf)? == 0 {
            return Ok(());
        }
        let reply = match std::str::from_utf8(&buf) {
            Ok(l) if l.trim().is_empty() => continue,
            Ok(l) => eval_line(l),
            Err(e) => json!({ "error": format!("line is not UTF-8: {e}") }).to_string(),
        };
        writeln!(output, "{reply}")?;
        output.flush()?;
    }
}

fn eval(v: &Value) -> Result<Value, String> {
    if !v.is_object() {
        return Err("each line must be a JSON object with an `op` field".into());
    }
    let name = v
        .get("op")
        .and_then(Value::as_str)
        .ok_or("missing `op` (string); run with --list for the ops")?;
    let op = OPS
        .iter()
        .find(|op| op.name == name)
        .ok_or_else(|| format!("unknown op \"{name}\"; run with --list for the ops"))?;
    match args::precision(v)? {
        Precision::F32 => (op.f32)(v),
        Precision::F64 => (op.f64)(v),
    }
}

/// The ops evaluated in one precision: `$module` with `p = filtered_ndf::$precision`.
macro_rules! typed_ops {
    ($module:ident, $precision:ident) => {
        #[doc = concat!("The ops evaluated in `filtered_ndf::", stringify!($precision), "`.")]
        pub mod $module {
            use crate::args::*;
            use filtered_ndf::$precision as p;
            include!("typed.rs");
            include!("ops_ndf.rs");
            include!("ops_filter.rs");
            include!("ops_temporal.rs");
        }
    };
}

typed_ops!(p32, f32);
typed_ops!(p64, f64);
