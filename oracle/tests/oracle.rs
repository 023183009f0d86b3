//! End-to-end test of the oracle's evaluator on a file of queries, bad lines
//! included, and value tests of every op. Expected values are closed forms written out here or
//! f64 quadrature (`filtered_ndf::testing::quadrature`), never the crate's own output; each
//! tolerance states why it is that size.

use filtered_ndf_oracle::eval;

use filtered_ndf::testing::quadrature::integrate_plane;
use filtered_ndf::testing::quadrature::{Tolerance, integrate, integrate_2d, integrate_line};
use serde_json::{Value, json};
use std::f64::consts::PI;

fn run_session() -> Vec<Value> {
    let input = include_str!("data/oracle_session.jsonl");
    input
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| serde_json::from_str(&eval::eval_line(l)).expect("every reply is JSON"))
        .collect()
}

fn ok(v: &Value) -> f64 {
    v.get("ok")
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("expected ok number, got {v}"))
}

fn err(v: &Value) -> &str {
    v.get("error")
        .and_then(Value::as_str)
        .unwrap_or_else(|| panic!("expected error, got {v}"))
}

#[test]
fn session_replies_line_by_line_with_closed_form_values() {
    let r = run_session();
    assert_eq!(r.len(), 63, "one reply per input line");
    // GGX peak 1 / (pi alpha^2); f64 to 1e-15 relative (a few roundings of 1.1e-16), f32 to
    // its three roundings (alpha^2, the product with pi, the reciprocal; 6e-8 each): 2e-7.
    let peak = 1.0 / (PI * 0.01);
    assert!((ok(&r[0]) - peak).abs() < 1e-15 * peak);
    assert!((ok(&r[1]) - peak).abs() < 2e-7 * peak);
    assert_ne!(ok(&r[0]), ok(&r[1]), "f32 evaluation is really done in f32");
    // Beckmann peak 1 / (pi ax ay).
    let b = 1.0 / (PI * 0.1 * 0.2);
    assert!((ok(&r[2]) - b).abs() < 1e-14 * b);
    // Matrix GGX slope density at 0: 1 / (pi sqrt(det A)).
    let s = 1.0 / (PI * (0.04f64 * 0.09 - 0.01 * 0.01).sqrt());
    assert!((ok(&r[3]) - s).abs() < 1e-14 * s);
    // GGX Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2 with tan = 0.75.
    let l = ((1.0f64 + 0.25 * 0.5625).sqrt() - 1.0) / 2.0;
    assert!((ok(&r[4]) - l).abs() < 1e-15);
    // Grazing direction: Lambda is infinite, written as the string "inf".
    assert_eq!(r[5]["ok"], "inf");
    assert!(err(&r[6]).contains("malformed"));
    assert!(err(&r[7]).contains("negative"));
    assert!(err(&r[8]).contains("missing argument `m`"));
    assert!(err(&r[9]).contains("dist"));
    assert!(err(&r[10]).contains("symmetric"));
    assert!(err(&r[11]).contains("positive definite"));
    assert!(err(&r[12]).contains("unknown op"));
    assert!(err(&r[13]).contains("precision"));
    assert!(err(&r[14]).contains("object"));
    assert!(err(&r[15]).contains("must be a number"));
    // TK19 supp. eq. 7 at h = (0.6, 0, 0.8): -1/(h_z^2 sqrt(1 - h_z^2)) [[h_x, -h_y h_z],
    // [h_y, h_x h_z]] = [[-1.5625, 0], [0, -1.25]].
    let j = &r[16]["ok"];
    let expect = [[-1.5625, 0.0], [0.0, -1.25]];
    for (i, row) in expect.iter().enumerate() {
        for (k, e) in row.iter().enumerate() {
            let got = j[i][k].as_f64().expect("number");
            assert!((got - e).abs() < 1e-14, "J[{i}][{k}] = {got}, expected {e}");
        }
    }
    assert!(err(&r[17]).contains("kind"));
    // TK19 eq. 4: alpha_bar^2 = alpha^2 + min(2 * 0.25 * (|dn_u|^2 + |dn_v|^2), 0.18)
    //           = 0.0016 + 0.5 * (0.05 + 0.0125).
    let a = (0.0016f64 + 0.5 * 0.0625).sqrt();
    assert!((ok(&r[18]) - a).abs() < 1e-15, "{}", r[18]);
    assert!(err(&r[19]).contains("variant"));
    assert!(err(&r[20]).contains("must be a number"));
    // KHPL16 eq. 13-15: A + 2 sigma^2 (du du^T + dv dv^T), sigma = 0.5, worked by hand:
    // diag(0.01, 0.04) + 0.5 [[4e-4, 2e-4], [2e-4, 1.7e-3]].
    let a = &r[21]["ok"];
    let expect = [[0.0102, 1e-4], [1e-4, 0.04085]];
    for (i, row) in expect.iter().enumerate() {
        for (k, e) in row.iter().enumerate() {
            let got = a[i][k].as_f64().expect("number");
            assert!(
                (got - e).abs() < 1e-15,
                "A'[{i}][{k}] = {got}, expected {e}"
            );
        }
    }
    assert!(err(&r[22]).contains("footprint"));
    // Zero footprint: the unfiltered GGX peak 1 / (pi ax ay).
    let peak = 1.0 / (PI * 0.1 * 0.2);
    assert!((ok(&r[23]) - peak).abs() < 1e-14 * peak);
    // An off-centre rectangle in f32 against f64 adaptive quadrature of the GGX density:
    // the crate's f32 bound is 1e-5 relative; quadrature is good to 1e-10.
    let p22 = |x: f64, y: f64| 1.0 / (PI * 0.01 * (1.0 + (x * x + y * y) / 0.01).powi(2));
    let q = integrate_2d(
        p22,
        (-0.05, 0.15),
        (-0.05, 0.01),
        Tolerance::relative(1e-11),
    );
    let mean = q.value / (0.2 * 0.06);
    assert!(
        (ok(&r[24]) - mean).abs() < 1e-5 * mean,
        "{} vs {mean}",
        r[24]
    );
    assert!(err(&r[25]).contains("axis-aligned"));
    // KHPL16 eq. 19 solved for the full side d = 2H:
    // alpha'^2 = d sqrt(4 alpha^2 + d^2) / (4 atan(d / sqrt(4 alpha^2 + d^2))).
    let (a, d) = (0.1f64, 0.2f64);
    let w = (4.0 * a * a + d * d).sqrt();
    let exact = (d * w / (4.0 * (d / w).atan())).sqrt();
    assert!((ok(&r[26]) - exact).abs() < 1e-14, "{} vs {exact}", r[26]);
    assert!((ok(&r[27]) - (0.02f64).sqrt()).abs() < 1e-15);
    assert!(err(&r[28]).contains("variant"));

    // Lines 29 on: every op has at least one answered and one refused line in the session
    // (the value tests of those ops are below).
    let lines: Vec<&str> = include_str!("data/oracle_session.jsonl")
        .lines()
        .filter(|l| !l.trim().is_empty())
        .collect();
    for op in eval::OPS {
        let tag = format!("\"op\":\"{}\"", op.name);
        let replies: Vec<&Value> = lines
            .iter()
            .zip(&r)
            .filter(|(l, _)| l.contains(&tag))
            .map(|(_, reply)| reply)
            .collect();
        assert!(
            replies.iter().any(|x| x.get("ok").is_some()),
            "no answered line for op {}",
            op.name
        );
        assert!(
            replies.iter().any(|x| x.get("error").is_some()),
            "no bad line for op {}",
            op.name
        );
    }
}

// ---------------------------------------------------------------------------------------
// Helpers: one query through the evaluator, and the closed forms the values are checked
// against. A roughness matrix is `[a11, a12, a22]`.

/// The reply to one query (a JSON object given as a `json!` value).
fn ask(q: Value) -> Value {
    serde_json::from_str(&eval::eval_line(&q.to_string())).expect("every reply is JSON")
}

/// The number the query answers.
fn num(q: Value) -> f64 {
    ok(&ask(q))
}

/// The array of numbers the query answers.
fn nums(q: Value) -> Vec<f64> {
    let r = ask(q);
    let a = r["ok"]
        .as_array()
        .unwrap_or_else(|| panic!("expected ok array, got {r}"));
    a.iter().map(|x| x.as_f64().expect("number")).collect()
}

/// The symmetric matrix `[[a11, a12], [a12, a22]]` the query answers, as `[a11, a12, a22]`.
fn mat(v: &Value) -> [f64; 3] {
    let g = |i: usize, k: usize| {
        v[i][k]
            .as_f64()
            .unwrap_or_else(|| panic!("matrix, got {v}"))
    };
    assert_eq!(g(0, 1), g(1, 0), "symmetric");
    [g(0, 0), g(0, 1), g(1, 1)]
}

/// The error message the query answers.
fn refused(q: Value) -> String {
    err(&ask(q)).to_string()
}

/// `|got - want| <= tol * |want|`.
fn rel(got: f64, want: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol * want.abs(),
        "{what}: {got} vs {want} (relative {:e}, allowed {tol:e})",
        ((got - want) / want).abs()
    );
}

/// Every entry within `tol` absolute.
fn close<const N: usize>(got: [f64; N], want: [f64; N], tol: f64, what: &str) {
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= tol, "{what}: {got:?} vs {want:?}");
    }
}

fn det(a: [f64; 3]) -> f64 {
    a[0] * a[2] - a[1] * a[1]
}

/// `s^T A^-1 s` by the adjugate.
fn inv_quad(a: [f64; 3], x: f64, y: f64) -> f64 {
    (a[2] * x * x - 2.0 * a[1] * x * y + a[0] * y * y) / det(a)
}

/// `w^T A w`.
fn quad(a: [f64; 3], x: f64, y: f64) -> f64 {
    a[0] * x * x + 2.0 * a[1] * x * y + a[2] * y * y
}

fn diag(ax: f64, ay: f64) -> [f64; 3] {
    [ax * ax, 0.0, ay * ay]
}

/// GGX slope density (TK19 supp. sec. 1).
fn ggx_p22(a: [f64; 3], x: f64, y: f64) -> f64 {
    1.0 / (PI * det(a).sqrt() * (1.0 + inv_quad(a, x, y)).powi(2))
}

/// GGX `D(m)`, homogeneous form.
fn ggx_d(a: [f64; 3], m: [f64; 3]) -> f64 {
    1.0 / (PI * det(a).sqrt() * (inv_quad(a, m[0], m[1]) + m[2] * m[2]).powi(2))
}

/// GGX Smith `Lambda(w) = (sqrt(1 + t) - 1) / 2`, `t = q / w_z^2`, written as
/// `t / (2 (sqrt(1 + t) + 1))` (no cancellation for small `t`).
fn ggx_lambda(a: [f64; 3], w: [f64; 3]) -> f64 {
    let t = quad(a, w[0], w[1]) / (w[2] * w[2]);
    t / (2.0 * ((1.0 + t).sqrt() + 1.0))
}

/// Beckmann slope density: a Gaussian of covariance `A / 2` (KHPL16 eq. 14).
fn beckmann_p22(a: [f64; 3], x: f64, y: f64) -> f64 {
    (-inv_quad(a, x, y)).exp() / (PI * det(a).sqrt())
}

/// Beckmann Smith `Lambda(w)` from its definition, by quadrature:
/// `Lambda = (1 / mu) integral_mu^inf (q - mu) P2(q) dq`, `mu = cot theta`, with `P2` the
/// slope marginal along the azimuth of `w`, a Gaussian of variance `e^T A e / 2`.
fn beckmann_lambda(a: [f64; 3], w: [f64; 3]) -> f64 {
    let r = w[0].hypot(w[1]);
    let (mu, a2) = (w[2] / r, quad(a, w[0] / r, w[1] / r));
    let p2 = |q: f64| (-q * q / a2).exp() / (a2 * PI).sqrt();
    let width = a2.sqrt();
    integrate(
        |q| (q - mu) * p2(q),
        mu,
        mu + 40.0 * width,
        Tolerance::relative(1e-14),
    )
    .value
        / mu
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `sigma^2 (u u^T + v v^T)`.
fn kernel(u: [f64; 2], v: [f64; 2], sigma: f64) -> [f64; 3] {
    let k = sigma * sigma;
    [
        k * (u[0] * u[0] + v[0] * v[0]),
        k * (u[0] * u[1] + v[0] * v[1]),
        k * (u[1] * u[1] + v[1] * v[1]),
    ]
}

/// `A + 2 K`.
fn plus_2k(a: [f64; 3], k: [f64; 3]) -> [f64; 3] {
    [a[0] + 2.0 * k[0], a[1] + 2.0 * k[1], a[2] + 2.0 * k[2]]
}

// 2x2 matrices as [[m11, m12], [m21, m22]], for the TK21 closed form.
type M2 = [[f64; 2]; 2];

fn m2(a: [f64; 3]) -> M2 {
    [[a[0], a[1]], [a[1], a[2]]]
}

fn mul(a: M2, b: M2) -> M2 {
    [
        [
            a[0][0] * b[0][0] + a[0][1] * b[1][0],
            a[0][0] * b[0][1] + a[0][1] * b[1][1],
        ],
        [
            a[1][0] * b[0][0] + a[1][1] * b[1][0],
            a[1][0] * b[0][1] + a[1][1] * b[1][1],
        ],
    ]
}

fn inv(a: M2) -> M2 {
    let d = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [[a[1][1] / d, -a[0][1] / d], [-a[1][0] / d, a[0][0] / d]]
}

fn add(a: M2, b: M2, sb: f64) -> M2 {
    [
        [a[0][0] + sb * b[0][0], a[0][1] + sb * b[0][1]],
        [a[1][0] + sb * b[1][0], a[1][1] + sb * b[1][1]],
    ]
}

const I2: M2 = [[1.0, 0.0], [0.0, 1.0]];

/// TK21 listing 1 with explicit inverses: `P = A (I - A)^-1`, `P' = P + 2 K`,
/// `A' = P' (I + P')^-1`.
fn tk21(a: [f64; 3], k: [f64; 3]) -> [f64; 3] {
    let p = mul(m2(a), inv(add(I2, m2(a), -1.0)));
    let q = add(p, m2(k), 2.0);
    let r = mul(q, inv(add(I2, q, 1.0)));
    [r[0][0], 0.5 * (r[0][1] + r[1][0]), r[1][1]]
}

/// The mean of the GGX slope density over `[cx +/- hx] x [cy +/- hy]`, by quadrature
/// (relative 1e-12 requested).
fn box_mean(a: [f64; 3], c: [f64; 2], h: [f64; 2]) -> f64 {
    let q = integrate_2d(
        |x, y| ggx_p22(a, x, y),
        (c[0] - h[0], c[0] + h[0]),
        (c[1] - h[1], c[1] + h[1]),
        Tolerance::relative(1e-12),
    );
    q.value / (4.0 * h[0] * h[1])
}

// ---------------------------------------------------------------------------------------

/// `s` with every run of whitespace made one space.
fn words(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[test]
fn list_documents_every_op_with_its_equation() {
    let text = eval::list();
    let mut names: Vec<&str> = eval::OPS.iter().map(|op| op.name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), eval::OPS.len(), "op names are unique");
    for op in eval::OPS {
        // OPS is the dispatcher: every op evaluates through its entry, so an op cannot exist
        // without its listing. Each entry states its arguments and an equation.
        assert!(
            op.equation.contains('=') && !op.args.is_empty() && !op.returns.is_empty(),
            "{}",
            op.name
        );
        for part in [op.name, op.args, op.equation, op.returns] {
            // Compared word by word: --list wraps the lines.
            assert!(words(&text).contains(&words(part)), "--list lacks {part}");
        }
        let reply = eval::eval_line(&format!("{{\"op\":\"{}\"}}", op.name));
        assert!(
            reply.contains("missing argument") && !reply.contains("unknown op"),
            "op {} without arguments: {reply}",
            op.name
        );
    }
}

#[test]
fn the_stream_goes_on_after_bad_lines() {
    // Through `serve`, as main runs it: a blank line is skipped, a line that is not UTF-8 and
    // a bad line of every kind answer an error, and the good line after them is answered.
    let mut input = Vec::new();
    input.extend_from_slice(b"{\"op\":\"ndf\",\"dist\":\"ggx\",\"roughness\":0.1,\"m\":[0,0,1]}\n");
    input.extend_from_slice(b"\n   \n");
    input.extend_from_slice(b"{\"op\":\"ndf\",\"dist\":\"ggx\xff\"}\n");
    input.extend_from_slice(b"{\"op\":\"lambda\",\"w\":[1e400,0,1]}\n");
    input.extend_from_slice(b"{\"op\":\"lambda\",\"w\":[NaN,0,1]}\n");
    for op in eval::OPS {
        input.extend_from_slice(format!("{{\"op\":\"{}\",\"dist\":7}}\n", op.name).as_bytes());
    }
    input.extend_from_slice(b"{\"op\":\"ndf\",\"dist\":\"ggx\",\"roughness\":0.1,\"m\":[0,0,1]}");
    let mut output = Vec::new();
    eval::serve(&input[..], &mut output).expect("in-memory I/O");
    let replies: Vec<Value> = std::str::from_utf8(&output)
        .expect("UTF-8 output")
        .lines()
        .map(|l| serde_json::from_str(l).expect("every reply is JSON"))
        .collect();
    assert_eq!(replies.len(), 5 + eval::OPS.len());
    let peak = 1.0 / (PI * 0.01);
    assert!((ok(&replies[0]) - peak).abs() < 1e-15 * peak);
    assert!(err(&replies[1]).contains("UTF-8"));
    for r in &replies[1..replies.len() - 1] {
        assert!(r.get("error").is_some(), "{r}");
    }
    assert!((ok(replies.last().unwrap()) - peak).abs() < 1e-15 * peak);
}

#[test]
fn g1_and_g2_are_the_smith_terms_of_the_closed_forms() {
    // GGX axis-aligned: G1 = 1 / (1 + Lambda), Lambda = (sqrt(1 + q / w_z^2) - 1) / 2. A few
    // f64 roundings in a sqrt and a division: 1e-15 relative.
    let a = diag(0.3, 0.1);
    let w = unit([0.6, 0.3, 0.5]);
    let m = unit([0.1, -0.05, 1.0]);
    let g1 = num(json!({"op": "g1", "dist": "ggx", "roughness": [0.3, 0.1], "w": w, "m": m}));
    rel(g1, 1.0 / (1.0 + ggx_lambda(a, w)), 1e-15, "GGX G1");
    // chi+(w.m): a micronormal facing away from w masks fully, exactly.
    let back = unit([-1.0, 0.0, 0.2]);
    assert!(dot(w, back) < 0.0);
    let q = json!({"op": "g1", "dist": "ggx", "roughness": [0.3, 0.1], "w": w, "m": back});
    assert_eq!(num(q), 0.0);
    // f32: one rounding of the inputs and a few of the evaluation (6e-8 each): 1e-6.
    let q = json!({"op": "g1", "dist": "ggx", "roughness": [0.3, 0.1], "w": w, "m": m,
                   "precision": "f32"});
    rel(num(q), 1.0 / (1.0 + ggx_lambda(a, w)), 1e-6, "GGX G1 f32");

    // Beckmann, full matrix, height-correlated G2 = 1 / (1 + Lambda(i) + Lambda(o)) with
    // Lambda from the slope marginal by quadrature (relative 1e-14 requested; the crate's
    // erfc is good to a few ulps): 1e-12.
    let a = [0.25, 0.05, 0.16];
    let (i, o) = (unit([0.95, 0.0, 0.2]), unit([0.0, -0.9, 0.3]));
    let m = unit([0.1, -0.1, 1.0]);
    let want = 1.0 / (1.0 + beckmann_lambda(a, i) + beckmann_lambda(a, o));
    assert!(want < 0.9, "both Lambdas matter: {want}");
    let r = [[0.25, 0.05], [0.05, 0.16]];
    let g2 = num(json!({"op": "g2", "dist": "beckmann", "roughness": r, "i": i, "o": o, "m": m}));
    rel(g2, want, 1e-12, "Beckmann G2");
    // The same Lambda through the op lambda (its closed form in erf) and g1.
    let l = num(json!({"op": "lambda", "dist": "beckmann", "roughness": r, "w": i}));
    rel(l, beckmann_lambda(a, i), 1e-12, "Beckmann Lambda");
    let g1 = num(json!({"op": "g1", "dist": "beckmann", "roughness": r, "w": i, "m": m}));
    rel(
        g1,
        1.0 / (1.0 + beckmann_lambda(a, i)),
        1e-12,
        "Beckmann G1",
    );
    // o below m's horizon: 0.
    let q =
        json!({"op": "g2", "dist": "beckmann", "roughness": r, "i": i, "o": [0, 0, -1], "m": m});
    assert_eq!(num(q), 0.0);
}

#[test]
fn pdf_is_the_visible_normal_density_per_steradian() {
    // D_o(m) = (o.m) D(m) / (o_z (1 + Lambda(o))) with the GGX closed forms: 1e-14 relative
    // (the matrix D in f64 to a few ulps, squared).
    let a = [0.09, 0.02, 0.04];
    let r = [[0.09, 0.02], [0.02, 0.04]];
    let o = unit([0.5, 0.3, 0.7]);
    for m in [
        [0.0, 0.0, 1.0],
        unit([0.2, 0.1, 1.0]),
        unit([-0.1, 0.25, 0.9]),
    ] {
        let want = dot(o, m) * ggx_d(a, m) / (o[2] * (1.0 + ggx_lambda(a, o)));
        let got = num(json!({"op": "pdf", "dist": "ggx", "roughness": r, "o": o, "m": m}));
        rel(got, want, 1e-14, "GGX visible-normal pdf");
    }
    // A back-facing micronormal and a view below the surface: 0.
    let m = unit([-1.0, -0.6, 0.1]);
    assert!(dot(o, m) < 0.0);
    assert_eq!(
        num(json!({"op": "pdf", "dist": "ggx", "roughness": r, "o": o, "m": m})),
        0.0
    );
    let q =
        json!({"op": "pdf", "dist": "ggx", "roughness": r, "o": [0.5, 0, -0.5], "m": [0, 0, 1]});
    assert_eq!(num(q), 0.0);

    // Per steradian: Beckmann's density integrates to 1 over the hemisphere of m, for an
    // oblique view (f64 quadrature in (theta, phi) with the solid-angle element sin theta;
    // relative 1e-8 requested, the integrand has a kink at o.m = 0): within four times the
    // quadrature's own estimate, which must meet ten times its goal, plus 1e-12 for the
    // oracle's printed digits and the pdf's rounding.
    let o = unit([0.5, 0.3, 0.6]);
    let total = integrate_2d(
        |theta: f64, phi: f64| {
            let m = [
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ];
            let q =
                json!({"op": "pdf", "dist": "beckmann", "roughness": [0.4, 0.2], "o": o, "m": m});
            num(q) * theta.sin()
        },
        (0.0, PI / 2.0),
        (0.0, 2.0 * PI),
        Tolerance::relative(1e-8),
    );
    assert!(total.error <= 1e-7, "{total:?}");
    rel(
        total.value,
        1.0,
        4.0 * total.error + 1e-12,
        "integral of the Beckmann pdf",
    );
}

/// The sampled micronormal as `[x, y, z]`.
fn sampled(dist: &str, r: Value, o: [f64; 3], u: [f64; 2]) -> [f64; 3] {
    let q = serde_json::json!({"op": "sample", "dist": dist, "roughness": r, "o": o, "u": u});
    let m = nums(q);
    [m[0], m[1], m[2]]
}

#[test]
fn sample_returns_the_micronormal_of_the_closed_form_inverse() {
    // GGX at normal incidence: the visible-normal density is D(m) m_z, whose CDF in
    // t = tan^2 of the unit-roughness normal is t / (1 + t); the spherical cap gives
    // tan^2 theta_n = u2 / (1 - u2), phi = 2 pi u1, stretched to m ~ (ax n_x, ay n_y, n_z).
    // The f64 sampler's trigonometry: 1e-14 absolute.
    for u in [[0.125, 0.36], [0.8, 0.05], [0.4, 0.93f64]] {
        let t = (u[1] / (1.0 - u[1])).sqrt();
        let phi = 2.0 * PI * u[0];
        let want = unit([0.5 * t * phi.cos(), 0.2 * t * phi.sin(), 1.0]);
        let got = sampled("ggx", json!([0.5, 0.2]), [0.0, 0.0, 1.0], u);
        close(got, want, 1e-14, "GGX sample at normal incidence");
    }
    // Beckmann at normal incidence: the slopes of the unit-roughness normal are the quantiles
    // of a Gaussian of variance 1/2, (Phi^-1(u1), Phi^-1(u2)) / sqrt 2, and m ~ (-ax x,
    // -ay y, 1) (slope s = -m_xy / m_z). Phi(1) and Phi(-0.5) to 16 digits; the sampler's
    // Newton solve is good to 8 ulps of u: 1e-12.
    let (phi_1, phi_m05) = (0.841_344_746_068_542_9, 0.308_537_538_725_986_9);
    let (x, y) = (1.0 / 2f64.sqrt(), -0.5 / 2f64.sqrt());
    let want = unit([-0.5 * x, -0.2 * y, 1.0]);
    let got = sampled(
        "beckmann",
        json!([0.5, 0.2]),
        [0.0, 0.0, 1.0],
        [phi_1, phi_m05],
    );
    close(got, want, 1e-12, "Beckmann sample at normal incidence");
    // No visible normal below the horizon: null.
    let q = json!({"op": "sample", "dist": "ggx", "roughness": 0.3, "o": [0.3, 0, -0.1], "u": [0.5, 0.5]});
    assert!(ask(q)["ok"].is_null());
    // f32 samples the same micronormal to f32 rounding (a few 6e-8 steps): 1e-6.
    let q = json!({"op": "sample", "dist": "ggx", "roughness": [0.5, 0.2], "o": [0, 0, 1],
                   "u": [0.125, 0.36], "precision": "f32"});
    let t = (0.36f64 / 0.64).sqrt();
    let want = unit([0.5 * t * (PI / 4.0).cos(), 0.2 * t * (PI / 4.0).sin(), 1.0]);
    let got = nums(q);
    close([got[0], got[1], got[2]], want, 1e-6, "GGX sample f32");
}

#[test]
fn sample_pushes_the_unit_square_to_pdf() {
    // For oblique views: the sampler maps u to m with pdf(m) |dm/du1 x dm/du2| = 1 (the
    // solid angle a unit of u-area covers is 1 / density). The derivatives by central
    // differences of the oracle's own samples, step h = 1e-5: truncation h^2 / 6 |m''' / m'|,
    // 2e-11 times the ratio of derivatives (which grows towards u = 1: 1.7e-9 measured at
    // u_2 = 0.9), rounding ~1e-16 / h = 1e-11, the Beckmann quantile's 8-ulp solve ~1e-10:
    // 1e-8.
    let cases = [
        (
            "ggx",
            json!([[0.09, 0.02], [0.02, 0.04]]),
            unit([0.5, 0.3, 0.7]),
        ),
        ("ggx", json!(0.6), unit([-0.8, 0.1, 0.3])),
        ("beckmann", json!([0.4, 0.2]), unit([0.5, 0.3, 0.6])),
        (
            "beckmann",
            json!([[0.09, -0.02], [-0.02, 0.25]]),
            unit([0.1, -0.7, 0.4]),
        ),
    ];
    let h = 1e-5;
    for (dist, r, o) in cases {
        for u in [[0.3, 0.6], [0.7, 0.2], [0.55, 0.9]] {
            let m = sampled(dist, r.clone(), o, u);
            let d = |k: usize| {
                let (mut lo, mut hi) = (u, u);
                lo[k] -= h;
                hi[k] += h;
                let (a, b) = (
                    sampled(dist, r.clone(), o, lo),
                    sampled(dist, r.clone(), o, hi),
                );
                [
                    (b[0] - a[0]) / (2.0 * h),
                    (b[1] - a[1]) / (2.0 * h),
                    (b[2] - a[2]) / (2.0 * h),
                ]
            };
            let (d1, d2) = (d(0), d(1));
            let cross = [
                d1[1] * d2[2] - d1[2] * d2[1],
                d1[2] * d2[0] - d1[0] * d2[2],
                d1[0] * d2[1] - d1[1] * d2[0],
            ];
            let area = dot(cross, cross).sqrt();
            let pdf = num(json!({"op": "pdf", "dist": dist, "roughness": r, "o": o, "m": m}));
            rel(
                pdf * area,
                1.0,
                1e-8,
                &format!("{dist} {r} o = {o:?} u = {u:?}"),
            );
        }
    }
}

#[test]
fn filtered_gaussian_is_a_plus_2_sigma_with_the_clamps() {
    // Clamps inactive (extent 0.02 < 1, 2 lambda_max ~ 5e-4 < kappa): A' = A + 2 Sigma,
    // Sigma = 0.25 (u u^T + v v^T), to a few f64 roundings of entries ~0.1: 1e-16 absolute.
    let a = [0.04, 0.01, 0.09];
    let r = [[0.04, 0.01], [0.01, 0.09]];
    let (u, v) = ([0.03, 0.01], [-0.01, 0.02]);
    let want = plus_2k(a, kernel(u, v, 0.5));
    let base = json!({"op": "filtered", "dist": "ggx", "roughness": r,
                      "footprint": {"slope": [u, v]}, "method": "gaussian_tk19"});
    let with = |k: &str, x: Value| {
        let mut q = base.clone();
        q[k] = x;
        q
    };
    close(mat(&ask(base.clone())["ok"]), want, 1e-16, "TK19 lobe");
    // D and Lambda of the lobe: the GGX closed forms of A' (1e-14 relative: D squares a
    // quadratic form of a few ulps).
    let m = unit([0.1, -0.05, 1.0]);
    rel(
        num(with("m", json!(m))),
        ggx_d(want, m),
        1e-14,
        "D of the TK19 lobe",
    );
    let w = unit([0.6, 0.3, 0.75]);
    rel(
        num(with("w", json!(w))),
        ggx_lambda(want, w),
        1e-14,
        "Lambda of the TK19 lobe",
    );
    let s = [0.05, -0.02];
    rel(
        num(with("slope", json!(s))),
        ggx_p22(want, s[0], s[1]),
        1e-14,
        "P22 of the TK19 lobe",
    );
    // f32 front door: inputs and A' rounded to f32, D amplifies relative errors about
    // fourfold: 2e-6.
    let mut q = with("m", json!(m));
    q["precision"] = json!("f32");
    rel(num(q), ggx_d(want, m), 2e-6, "D of the TK19 lobe, f32");

    // kappa active: an isotropic kernel 2 Sigma = 0.32 I is clamped to 0.18 I (TK19 eq. 1);
    // gaussian_tk19 with clamps "none" keeps it; kappa overridden to 0.1 clamps to 0.1.
    let big = json!({"op": "filtered", "dist": "ggx", "roughness": 0.1,
                     "footprint": [[0.8, 0], [0, 0.8]], "method": "gaussian_tk19"});
    let mut q = big.clone();
    close(
        mat(&ask(q.clone())["ok"]),
        [0.19, 0.0, 0.19],
        1e-15,
        "kappa clamp",
    );
    q["clamps"] = json!("none");
    close(
        mat(&ask(q.clone())["ok"]),
        [0.33, 0.0, 0.33],
        1e-15,
        "no clamps",
    );
    q["clamps"] = json!({"kappa": 0.1});
    close(mat(&ask(q)["ok"]), [0.11, 0.0, 0.11], 1e-15, "kappa 0.1");
    // sigma overrides the pixel filter: sigma = 0.25 gives 2 Sigma = 0.08 I, under kappa.
    let mut q = big;
    q["sigma"] = json!(0.25);
    close(mat(&ask(q)["ok"]), [0.09, 0.0, 0.09], 1e-15, "sigma 0.25");

    // Maximum extent (KHPL16 5.2): dh_u = (3, 0) has extent 1.5 and is rescaled to extent 1,
    // i.e. dh_u = (2, 0), Sigma_xx = 0.25 * 4; without the rule 0.25 * 9.
    let q = json!({"op": "filtered", "dist": "beckmann", "roughness": 0.1,
                   "footprint": [[3, 0], [0, 0]], "method": "gaussian_khpl16"});
    close(
        mat(&ask(q.clone())["ok"]),
        [2.01, 0.0, 0.01],
        1e-14,
        "max extent",
    );
    let mut q = q;
    q["clamps"] = json!({"max_extent": "inf"});
    close(
        mat(&ask(q)["ok"]),
        [4.51, 0.0, 0.01],
        1e-14,
        "max extent off",
    );
}

#[test]
fn filtered_gaussian_beckmann_is_the_convolution_with_the_pixel_kernel() {
    // Beckmann filtered by gaussian_khpl16 from normal differences is the exact convolution
    // of the lobe with the kernel N(0, Sigma) (KHPL16 eq. 15). Footprint from TK19 eq. 3,
    // written out: dh = 2 dn_xy / |2 e_z + dn| for the differences of unit normals.
    let n_u = unit([0.06, 0.01, 1.0]);
    let n_v = unit([-0.02, 0.05, 1.0]);
    let (dn_u, dn_v) = (
        [n_u[0], n_u[1], n_u[2] - 1.0],
        [n_v[0], n_v[1], n_v[2] - 1.0],
    );
    let half = |d: [f64; 3]| {
        let l = (d[0] * d[0] + d[1] * d[1] + (2.0 + d[2]).powi(2)).sqrt();
        [2.0 * d[0] / l, 2.0 * d[1] / l]
    };
    let k = kernel(half(dn_u), half(dn_v), 0.5);
    let a = [0.002, 0.0005, 0.003];
    let r = [[0.002, 0.0005], [0.0005, 0.003]];
    let gauss = |x: f64, y: f64| {
        let dk = det(k);
        (-(k[2] * x * x - 2.0 * k[1] * x * y + k[0] * y * y) / (2.0 * dk)).exp()
            / (2.0 * PI * dk.sqrt())
    };
    for s in [[0.0, 0.0], [0.02, -0.01], [-0.03, 0.04]] {
        let conv = integrate_plane(
            |x, y| beckmann_p22(a, s[0] - x, s[1] - y) * gauss(x, y),
            (0.5 * s[0], 0.5 * s[1]),
            (0.02, 0.02),
            Tolerance::relative(1e-11),
        );
        let q = json!({"op": "filtered", "dist": "beckmann", "roughness": r,
                       "footprint": {"normal_differences": [dn_u, dn_v]},
                       "method": "gaussian_khpl16", "slope": s});
        // The quadrature's estimate plus 1e-12 relative for the closed form's exponent.
        let got = num(q);
        assert!(
            (got - conv.value).abs() <= conv.error + 1e-12 * conv.value,
            "s = {s:?}: {got} vs {} +- {}",
            conv.value,
            conv.error
        );
    }
}

#[test]
fn filtered_projected_is_tk21_in_projected_space() {
    // TK21 with explicit inverses; kernel clamps inactive (extent 0.03, 2 lambda ~ 1e-3).
    // The library's Cayley-Hamilton form rounds differently: 1e-15 absolute on entries < 1.
    let a = [0.09, 0.02, 0.16];
    let r = [[0.09, 0.02], [0.02, 0.16]];
    let (u, v) = ([0.04, 0.01], [0.0, 0.03]);
    let want = tk21(a, kernel(u, v, 0.5));
    let q = json!({"op": "filtered", "dist": "ggx", "roughness": r,
                   "footprint": {"projected": [u, v]}, "method": "projected_tk21"});
    close(mat(&ask(q)["ok"]), want, 1e-15, "TK21 lobe");
    let q =
        json!({"op": "projected_roughness", "roughness": r, "footprint": {"projected": [u, v]}});
    close(mat(&ask(q)["ok"]), want, 1e-15, "projected_roughness");
    let m = unit([0.2, 0.1, 1.0]);
    let q = json!({"op": "filtered", "dist": "ggx", "roughness": r, "m": m,
                   "footprint": {"projected": [u, v]}, "method": "projected_tk21"});
    rel(num(q), ggx_d(want, m), 1e-13, "D of the TK21 lobe");
    // Isotropic, diagonal kernel: per axis a' = p' / (1 + p'), p' = a / (1 - a) + 2 k.
    let q = json!({"op": "projected_roughness", "roughness": 0.3, "sigma": 1.0,
                   "footprint": [[0.1, 0], [0, 0.05]]});
    let p = 0.09 / 0.91;
    let (px, py) = (p + 2.0 * 0.01, p + 2.0 * 0.0025);
    // The library's (P' + det P' I) / (1 + tr P' + det P') rounds differently: 1e-15.
    close(
        mat(&ask(q)["ok"]),
        [px / (1.0 + px), 0.0, py / (1.0 + py)],
        1e-15,
        "TK21 isotropic",
    );
    // alpha = 1.2: the eigenvalue 1.44 is above 0.99; 0.99 is filtered and 0.45 added back.
    let q = json!({"op": "projected_roughness", "roughness": 1.2, "footprint": [[0.2, 0], [0, 0]]});
    let p = 0.99 / 0.01 + 2.0 * 0.01;
    let want = p / (1.0 + p) + 0.45;
    // P = 99 amplifies the rounding of 1 - 0.99 (1e-16 / 1e-2): 1e-13.
    close(
        mat(&ask(q)["ok"]),
        [want, 0.0, 1.44],
        1e-13,
        "TK21 above the limit",
    );
    // The footprint from projected derivatives at h mapped to slope space (TK19 supp. eq. 6),
    // through gaussian_khpl16 (no kappa): dh = -1/h_z^3 [[1 - h_y^2, h_x h_y], [h_x h_y,
    // 1 - h_x^2]] dp.
    let h = unit([0.3, -0.2, 0.9]);
    let j = |d: [f64; 2]| {
        let c = -1.0 / h[2].powi(3);
        [
            c * ((1.0 - h[1] * h[1]) * d[0] + h[0] * h[1] * d[1]),
            c * (h[0] * h[1] * d[0] + (1.0 - h[0] * h[0]) * d[1]),
        ]
    };
    let (dp_u, dp_v) = ([0.05, 0.0], [0.01, 0.04]);
    let want = plus_2k(diag(0.2, 0.2), kernel(j(dp_u), j(dp_v), 0.5));
    let q = json!({"op": "filtered", "dist": "ggx", "roughness": 0.2, "method": "gaussian_khpl16",
                   "footprint": {"projected_in_slope": {"h": h, "dp": [dp_u, dp_v]}}});
    close(
        mat(&ask(q)["ok"]),
        want,
        1e-16,
        "projected_in_slope footprint",
    );
}

#[test]
fn filtered_rect_and_proxy_are_the_box_filter_and_its_peak() {
    // rect_khpl16: the average of the GGX density over the footprint's bounding rectangle,
    // half extents (|dh_u| + |dh_v|) / 2 = (0.03, 0.02) (inside lambda = 1), against
    // quadrature (relative 1e-12 requested; the crate's integral is good to 1e-10 near the
    // peak): 1e-9.
    let a = diag(0.05, 0.1);
    let (u, v) = ([0.04, 0.01], [-0.02, 0.03]);
    let base = json!({"op": "filtered", "dist": "ggx", "roughness": [0.05, 0.1],
                      "footprint": {"slope": [u, v]}, "method": "rect_khpl16"});
    let lobe = ask(base.clone());
    close(
        [
            lobe["ok"]["half_extent"][0].as_f64().unwrap(),
            lobe["ok"]["half_extent"][1].as_f64().unwrap(),
        ],
        [0.03, 0.02],
        1e-17,
        "rect half extents",
    );
    let s = [0.02, -0.01];
    let mut q = base.clone();
    q["slope"] = json!(s);
    let mean = box_mean(a, s, [0.03, 0.02]);
    rel(num(q), mean, 1e-9, "rect P22");
    // D = P22(s(m)) / m_z^4 at the micronormal of that slope.
    let m = unit([-s[0], -s[1], 1.0]);
    let mut q = base;
    q["m"] = json!(m);
    rel(num(q), mean / m[2].powi(4), 1e-9, "rect D");

    // rect_gdc2016: a zero footprint still blurs over the floor min(alpha, 0.1) = 0.05.
    let q = json!({"op": "filtered", "dist": "ggx", "roughness": 0.05,
                   "footprint": [[0, 0], [0, 0]], "method": "rect_gdc2016", "slope": [0, 0]});
    rel(
        num(q),
        box_mean(diag(0.05, 0.05), [0.0, 0.0], [0.05, 0.05]),
        1e-9,
        "GDC floor",
    );
    // ggx_rect_footprint: the same pipeline piece by piece, with ClampRules::DEFAULT (floor
    // 1e-3): a 1e-4 footprint is widened to half extents 1e-3.
    let q = json!({"op": "ggx_rect_footprint", "roughness": [0.01, 0.02],
                   "footprint": [[1e-4, 0], [0, 0]]});
    assert_eq!(nums(q), vec![1e-3, 1e-3]);
    let q = json!({"op": "ggx_rect_footprint", "roughness": [0.01, 0.02],
                   "footprint": [[1e-4, 0], [0, 0]], "slope": [0.005, 0]});
    rel(
        num(q),
        box_mean(diag(0.01, 0.02), [0.005, 0.0], [1e-3, 1e-3]),
        1e-9,
        "floor 1e-3",
    );
    let q = json!({"op": "ggx_rect_footprint", "roughness": 0.1, "footprint": [[3, 0], [0, 1]]});
    assert_eq!(
        nums(q.clone()),
        vec![1.0, 0.5],
        "lambda = 1 caps the half extents"
    );
    let mut q = q;
    q["clamps"] = json!("none");
    assert_eq!(nums(q), vec![1.5, 0.5], "no clamps");

    // proxy_khpl16: per axis alpha'^2 = (alpha^2 + H^2) t / atan t, t = H / sqrt(alpha^2 +
    // H^2) (KHPL16 eq. 19 solved), H = (0.1, 0.05); the library takes hypot and sqrt(t /
    // atan t) separately: a few ulps each side, 2e-15 (the peak squares them: 4e-15).
    let proxy = |a: f64, h: f64| {
        let s2 = a * a + h * h;
        let t = h / s2.sqrt();
        (s2 * t / t.atan()).sqrt()
    };
    let q = json!({"op": "filtered", "dist": "ggx", "roughness": [0.05, 0.1],
                   "footprint": [[0.2, 0], [0, 0.1]], "method": "proxy_khpl16"});
    let got = nums(q.clone());
    let want = [proxy(0.05, 0.1), proxy(0.1, 0.05)];
    rel(got[0], want[0], 2e-15, "proxy x");
    rel(got[1], want[1], 2e-15, "proxy y");
    let mut peak = q.clone();
    peak["m"] = json!([0, 0, 1]);
    rel(
        num(peak),
        1.0 / (PI * want[0] * want[1]),
        4e-15,
        "proxy peak",
    );
    // The GDC floor as an override: H = max(H, min(alpha, 0.1)) = (0.1, 0.1).
    let mut q = q;
    q["clamps"] = json!({"floor": {"alpha_capped": 0.1}});
    let got = nums(q);
    rel(got[1], proxy(0.1, 0.1), 2e-15, "proxy with the GDC floor");
}

#[test]
fn filtered_rect_lambda_is_the_smith_lambda_of_the_box_filtered_density() {
    // Smith: Lambda = (1 / mu) integral_mu^inf (q - mu) P2(q) dq with P2 the slope marginal
    // along w's azimuth (x here). The box-filtered marginal is the mean of the GGX marginal
    // over q +/- H_x: (C(q + H) - C(q - H)) / (2 H), C(t) = 1/2 + t / (2 sqrt(alpha^2 + t^2)).
    let (ax, hx) = (0.05f64, 0.03f64);
    let cdf = |t: f64| 0.5 + t / (2.0 * (ax * ax + t * t).sqrt());
    // For q > H the CDF difference cancels (both near 1; garbage beyond q ~ 1e3, where the
    // tail still holds 1e-3 of the integral): there it is written without cancellation,
    // C(t1) - C(t2) = a^2 (t1 - t2)(t1 + t2) / (2 s1 s2 (t1 s2 + t2 s1)), s_i = sqrt(a^2 + t_i^2).
    let p2 = |q: f64| {
        if q > hx {
            let (t1, t2) = (q + hx, q - hx);
            let (s1, s2) = ((ax * ax + t1 * t1).sqrt(), (ax * ax + t2 * t2).sqrt());
            ax * ax * q / (s1 * s2 * (t1 * s2 + t2 * s1))
        } else {
            (cdf(q + hx) - cdf(q - hx)) / (2.0 * hx)
        }
    };
    let w = unit([0.9, 0.0, 0.2]);
    let mu = w[2] / w[0];
    // q = mu + L x / (1 - x), x in [0, 1).
    let l = 0.1;
    let lambda = integrate(
        |x| {
            let q = mu + l * x / (1.0 - x);
            (q - mu) * p2(q) * l / ((1.0 - x) * (1.0 - x))
        },
        0.0,
        1.0,
        Tolerance::relative(1e-12),
    )
    .value
        / mu;
    let q = json!({"op": "filtered", "dist": "ggx", "roughness": [0.05, 0.1],
                   "footprint": [[0.06, 0], [0, 0.04]], "method": "rect_khpl16", "w": w});
    rel(num(q), lambda, 1e-9, "Lambda of the box-filtered lobe");
}

#[test]
fn filtered_refuses_what_the_method_does_not_define() {
    let q = |dist: &str, r: Value, method: &str| {
        json!({"op": "filtered", "dist": dist, "roughness": r, "method": method,
               "footprint": [[0.01, 0], [0, 0.01]]})
    };
    for method in [
        "projected_tk21",
        "rect_khpl16",
        "rect_gdc2016",
        "proxy_khpl16",
    ] {
        let e = refused(q("beckmann", json!(0.1), method));
        assert!(e.contains("not defined for Beckmann"), "{e}");
    }
    for method in ["rect_khpl16", "rect_gdc2016", "proxy_khpl16"] {
        let e = refused(q("ggx", json!([[0.01, 0.0], [0.0, 0.02]]), method));
        assert!(e.contains("axis-aligned"), "{e}");
        let mut s = q("ggx", json!(0.1), method);
        s["sigma"] = json!(0.5);
        assert!(refused(s).contains("takes no `sigma`"));
    }
    assert!(refused(q("ggx", json!(0.1), "box")).contains("unknown method"));
    let mut hv = q("ggx", json!(0.1), "gaussian_tk19");
    hv["footprint"] =
        json!({"half_vector": {"h": [0, 0, 1], "dh_dx": [0.01, 0, 0], "dh_dy": [0, 0.01, 0]}});
    assert!(refused(hv.clone()).contains("not available yet"));
    hv["footprint"] = json!({"slope": [[0.01, 0], [0, 0.01]], "projected": [[0.01, 0], [0, 0.01]]});
    assert!(refused(hv.clone()).contains("one key"));
    hv["footprint"] = json!({"screen": [[0.01, 0], [0, 0.01]]});
    assert!(refused(hv).contains("unknown footprint form"));
    let mut two = q("ggx", json!(0.1), "gaussian_tk19");
    two["m"] = json!([0, 0, 1]);
    two["slope"] = json!([0, 0]);
    assert!(refused(two).contains("at most one"));
    let mut c = q("ggx", json!(0.1), "gaussian_tk19");
    c["clamps"] = json!({"kappa": -1});
    assert!(refused(c.clone()).contains(">= 0"));
    c["clamps"] = json!({"lambda": 1});
    assert!(refused(c).contains("unknown clamp rule"));
}

#[test]
fn presets_by_name_follow_their_published_formulas() {
    let (du, dv) = ([0.1, 0.2, 0.0], [0.0, 0.05, -0.1]);
    let (su, sv) = (0.05f64, 0.0125f64); // |dn_u|^2, |dn_v|^2
    let preset = |name: &str, alpha: f64| {
        num(json!({"op": "preset", "name": name, "alpha": alpha, "dn_u": du, "dn_v": dv}))
    };
    // Each a few f64 roundings (and one powf for Unreal): 1e-14 relative.
    // TK19 eq. 4 / Listing 2: alpha'^2 = alpha^2 + min(0.5 (|dn_u|^2 + |dn_v|^2), 0.18).
    rel(
        preset("TK19 trace (eq. 4)", 0.04),
        (0.0016 + 0.5 * (su + sv)).sqrt(),
        1e-14,
        "TK19",
    );
    rel(
        preset("O3DE", 0.04),
        (0.0016 + 0.5 * (su + sv)).sqrt(),
        1e-14,
        "O3DE",
    );
    // TK21 listing 5: kernel (|dn_u|^2 + |dn_v|^2) / (2 pi).
    rel(
        preset("TK21 listing 5", 0.04),
        (0.0016 + (su + sv) / (2.0 * PI)).sqrt(),
        1e-14,
        "TK21",
    );
    // Godot: added to alpha itself: min(1, alpha + min(0.5 (...), 0.18)).
    rel(
        preset("Godot 4", 0.04),
        0.04 + 0.5 * (su + sv),
        1e-14,
        "Godot",
    );
    // Unity HDRP projected: P = alpha^2 / (1 - alpha^2) + min(0.2 (...), 0.04),
    // alpha'^2 = P / (1 + P).
    let p = 0.0016 / 0.9984 + 0.2 * (su + sv);
    rel(
        preset("Unity HDRP projected", 0.04),
        (p / (1.0 + p)).sqrt(),
        1e-14,
        "HDRP projected",
    );
    // Unreal: perceptual roughness max(sqrt(alpha), max(|dn_u|^2, |dn_v|^2)^0.333), squared.
    let pr = 0.2f64.max(su.max(sv).powf(0.333));
    rel(preset("Unreal", 0.04), pr * pr, 1e-14, "Unreal");
    // three.js: perceptual max(sqrt(alpha), 0.0525) + the largest |component| (0.2).
    rel(preset("three.js", 0.04), 0.4 * 0.4, 1e-14, "three.js");
    // Filament's perceptual floor 0.045: alpha >= 0.045^2 before filtering.
    let q = json!({"op": "preset", "name": "Filament", "alpha": 0.001, "dn_u": [0, 0, 0], "dn_v": [0, 0, 0]});
    rel(num(q), 0.045 * 0.045, 1e-14, "Filament floor");
    // raw: the engine's own value (0 for a zero roughness on a flat G-buffer); filter: a
    // valid roughness, ALPHA_MIN = 1e-8.
    let flat = json!({"op": "preset", "name": "TK19 trace (eq. 4)", "alpha": 0.0,
                      "dn_u": [0, 0, 0], "dn_v": [0, 0, 0]});
    assert_eq!(num(flat.clone()), 1e-8);
    let mut raw = flat;
    raw["raw"] = json!(true);
    assert_eq!(num(raw), 0.0);
    // Every name of presets::ALL answers, in both precisions, and --list names it.
    let args = eval::OPS
        .iter()
        .find(|op| op.name == "preset")
        .unwrap()
        .args;
    for (name, _) in filtered_ndf::f64::filter::presets::ALL {
        assert!(
            args.contains(&format!("\"{name}\"")),
            "--list lacks preset {name}"
        );
        for prec in ["f32", "f64"] {
            let q = json!({"op": "preset", "name": name, "alpha": 0.3, "dn_u": du, "dn_v": dv,
                           "precision": prec});
            assert!(num(q) > 0.0, "{name}");
        }
    }
    // f32: 1e-6 relative.
    let q = json!({"op": "preset", "name": "TK19 trace (eq. 4)", "alpha": 0.04, "dn_u": du,
                   "dn_v": dv, "precision": "f32"});
    rel(num(q), (0.0016 + 0.5 * (su + sv)).sqrt(), 1e-6, "TK19 f32");
}

#[test]
fn temporal_lobe_widens_d_along_the_motion_and_keeps_the_base_masking() {
    // alpha_t = |dt dN/dt| = 0.5 along a = (0.6, 0.8): A_conv = A + alpha_t^2 a a^T
    // (Tessari et al. 2020 eq. 16 with A = 2 Sigma).
    let base = json!({"op": "temporal", "dist": "beckmann", "roughness": 0.1,
                      "dn_dt": [3, 4], "dt": 0.1});
    let lobe = ask(base.clone());
    rel(
        lobe["ok"]["alpha_t"].as_f64().unwrap(),
        0.5,
        1e-15,
        "alpha_t",
    );
    close(
        [
            lobe["ok"]["axis"][0].as_f64().unwrap(),
            lobe["ok"]["axis"][1].as_f64().unwrap(),
        ],
        [0.6, 0.8],
        1e-16,
        "axis",
    );
    let want = [0.01 + 0.25 * 0.36, 0.25 * 0.48, 0.01 + 0.25 * 0.64];
    close(mat(&lobe["ok"]["roughness"]), want, 1e-16, "A_conv");
    // P22 is the convolution of the base Beckmann with the 1-D Gaussian of variance
    // alpha_t^2 / 2 along a (f64 quadrature, relative 1e-12 requested): 1e-10.
    for s in [[0.0, 0.0], [0.1, -0.05], [0.3, 0.35]] {
        let var = 0.25 / 2.0;
        let conv = integrate_line(
            |t| {
                let g = (-t * t / (2.0 * var)).exp() / (2.0 * PI * var).sqrt();
                beckmann_p22(diag(0.1, 0.1), s[0] - 0.6 * t, s[1] - 0.8 * t) * g
            },
            0.6 * s[0] + 0.8 * s[1],
            0.1,
            Tolerance::relative(1e-12),
        );
        let mut q = base.clone();
        q["slope"] = json!(s);
        rel(num(q), conv.value, 1e-10, "temporal P22");
    }
    // GGX, shutter T: dt = T / sqrt 6, cos_theta and the path share scale alpha_t;
    // D from A_conv, Lambda from the base (eq. 17).
    let base = json!({"op": "temporal", "dist": "ggx", "roughness": [0.1, 0.2], "dn_dt": [1, -2],
                      "shutter": 0.25, "cos_theta": 0.5, "fraction": 0.5});
    let at = 0.25 / 6f64.sqrt() * 5f64.sqrt() * 0.5 * 0.5f64.sqrt();
    let lobe = ask(base.clone());
    rel(
        lobe["ok"]["alpha_t"].as_f64().unwrap(),
        at,
        1e-15,
        "alpha_t with shutter",
    );
    let (ex, ey) = (1.0 / 5f64.sqrt(), -2.0 / 5f64.sqrt());
    let a = [
        0.01 + at * at * ex * ex,
        at * at * ex * ey,
        0.04 + at * at * ey * ey,
    ];
    close(mat(&lobe["ok"]["roughness"]), a, 1e-16, "A_conv GGX");
    let m = unit([0.1, 0.05, 1.0]);
    let mut q = base.clone();
    q["m"] = json!(m);
    rel(num(q), ggx_d(a, m), 1e-14, "temporal D");
    let w = unit([0.3, -0.6, 0.5]); // along the motion
    let mut q = base;
    q["w"] = json!(w);
    let l = num(q);
    rel(
        l,
        ggx_lambda(diag(0.1, 0.2), w),
        1e-15,
        "temporal Lambda is the base's",
    );
    assert!(
        (l - ggx_lambda(a, w)).abs() > 1e-3 * l,
        "and not the widened lobe's"
    );
}

#[test]
fn never_panics_on_mutated_queries() {
    // Every argument of every valid query in the session replaced by bad values, or removed:
    // the reply is always one JSON object with exactly one of `ok` / `error`, an `ok` number
    // is never NaN (JSON cannot carry one anyway), and nothing panics (which would answer
    // "internal error").
    let bad = [
        serde_json::json!(null),
        serde_json::json!("x"),
        serde_json::json!("inf"),
        serde_json::json!(1e308),
        serde_json::json!(-1e308),
        serde_json::json!(0.0),
        serde_json::json!(-0.0),
        serde_json::json!(1e-308),
        serde_json::json!(-1),
        serde_json::json!(true),
        serde_json::json!([]),
        serde_json::json!([1e308, -1e308]),
        serde_json::json!([1e308, -1e308, 1e308]),
        serde_json::json!([[1e308, 0], [0, 1e308]]),
        serde_json::json!([[1e-308, -1e308, 0], [0, 1e308, 1e-308]]),
        serde_json::json!({}),
        serde_json::json!({"slope": [[1e308, 0], [0, -1e308]]}),
        serde_json::json!({"normal_differences": [[1e308, 0, -2], [0, 0, -2]]}),
        serde_json::json!({"projected_in_slope": {"h": [0, 0, 0], "dp": [[1e308, 0], [0, 1]]}}),
        serde_json::json!({"max_extent": 0, "kappa": 0, "floor": {"constant": 1e308}}),
    ];
    let mut count = 0;
    for line in include_str!("data/oracle_session.jsonl").lines() {
        let Ok(Value::Object(q)) = serde_json::from_str::<Value>(line) else {
            continue;
        };
        for key in q.keys().filter(|k| *k != "op") {
            let mut variants: Vec<Value> = bad
                .iter()
                .map(|b| {
                    let mut m = q.clone();
                    m.insert(key.clone(), b.clone());
                    Value::Object(m)
                })
                .collect();
            let mut removed = q.clone();
            removed.remove(key);
            variants.push(Value::Object(removed));
            for v in variants {
                let reply: Value =
                    serde_json::from_str(&eval::eval_line(&v.to_string())).expect("reply is JSON");
                let obj = reply.as_object().expect("reply is an object");
                assert_eq!(obj.len(), 1, "{v} -> {reply}");
                assert!(
                    obj.contains_key("ok") || obj.contains_key("error"),
                    "{reply}"
                );
                if let Some(e) = obj.get("error") {
                    assert!(!e.as_str().unwrap().contains("internal"), "{v} -> {reply}");
                }
                count += 1;
            }
        }
    }
    assert!(count > 3000, "mutated {count} queries");
}

#[test]
fn gaussian_filtered_is_the_convolution_with_the_kernel() {
    // GGX written out (not the library's) convolved with N(0, K) by 2-D quadrature around the
    // kernel's centre; the op evaluates the mixture identity (issue 17), bounded at 1.1e-11
    // relative in f64 and 1.8e-6 in f32 (module docs of gaussian_ggx).
    let a = [0.01, 0.002, 0.004];
    let r = [[0.01, 0.002], [0.002, 0.004]];
    let k = [0.004, 0.001, 0.002];
    let gauss = |x: f64, y: f64| {
        let dk = det(k);
        (-(k[2] * x * x - 2.0 * k[1] * x * y + k[0] * y * y) / (2.0 * dk)).exp()
            / (2.0 * PI * dk.sqrt())
    };
    for s in [[0.0, 0.0], [0.05, -0.02], [-0.2, 0.3]] {
        let conv = integrate_plane(
            |x, y| ggx_p22(a, s[0] - x, s[1] - y) * gauss(x, y),
            (0.5 * s[0], 0.5 * s[1]),
            (0.06, 0.06),
            Tolerance::relative(1e-12),
        );
        for (precision, rel) in [("f64", 2e-11), ("f32", 2e-6 + 4.0 * f32::EPSILON as f64)] {
            let q = json!({"op": "gaussian_filtered", "dist": "ggx", "roughness": r,
                           "kernel": [[k[0], k[1]], [k[1], k[2]]], "slope": s,
                           "precision": precision});
            let got = num(q);
            // The rule's bound (f32: plus the rounding of the inputs and the result), plus the
            // quadrature's own estimate.
            assert!(
                (got - conv.value).abs() <= conv.error + rel * conv.value,
                "{precision} s = {s:?}: {got} vs {} +- {}",
                conv.value,
                conv.error
            );
        }
    }
    // Beckmann through the same op: its closed form with A + 2 K (KHPL16 eq. 15), written out.
    let b = [a[0] + 2.0 * k[0], a[1] + 2.0 * k[1], a[2] + 2.0 * k[2]];
    let q = json!({"op": "gaussian_filtered", "dist": "beckmann", "roughness": r,
                   "kernel": [[k[0], k[1]], [k[1], k[2]]], "slope": [0.1, 0.05]});
    let want = beckmann_p22(b, 0.1, 0.05);
    assert!((num(q) - want).abs() <= 1e-14 * want);
    // The front door's exact method with an unclamped footprint gives the same density.
    let (u, v) = ([0.1, 0.02], [-0.03, 0.08]);
    let kk = kernel(u, v, 0.5);
    let q = json!({"op": "gaussian_filtered", "dist": "ggx", "roughness": r,
                   "kernel": [[kk[0], kk[1]], [kk[1], kk[2]]], "slope": [0.05, 0.0]});
    let p = json!({"op": "filtered", "dist": "ggx", "roughness": r, "footprint": [u, v],
                   "method": "gaussian_exact", "slope": [0.05, 0.0]});
    // The same kernel up to the rounding of its entries (an ulp each, which moves the density
    // by a few ulps): 1e-13 relative.
    let (x, y) = (num(q), num(p));
    assert!((x - y).abs() <= 1e-13 * x, "{x} vs {y}");
    // Kernels that are not covariances answer errors.
    for bad in [
        json!([[-1e-3, 0.0], [0.0, 1e-3]]),
        json!([[1e-3, 2e-3], [2e-3, 1e-3]]),
        json!([[1e-3, 1e-4], [2e-4, 1e-3]]),
        json!([[1e-3, 0.0], [0.0, "inf"]]),
    ] {
        let q = json!({"op": "gaussian_filtered", "dist": "ggx", "roughness": 0.1,
                       "kernel": bad, "slope": [0.0, 0.0]});
        let reply: Value = serde_json::from_str(&eval::eval_line(&q.to_string())).unwrap();
        assert!(reply.get("error").is_some(), "{q} -> {reply}");
    }
}
