//! End-to-end test of the oracle example's evaluator on a file of queries, bad lines
//! included. Expected values are closed forms written out here, not the crate's output.

#[path = "../examples/oracle/eval.rs"]
#[allow(dead_code)]
mod eval;

use filtered_ndf::testing::quadrature::{Tolerance, integrate_2d};
use serde_json::Value;
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
    assert_eq!(r.len(), 29, "one reply per input line");
    // GGX peak 1 / (pi alpha^2); f64 to 1e-15 relative, f32 to one f32 rounding (6e-8).
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
}

#[test]
fn every_listed_op_is_dispatched() {
    for op in eval::OPS {
        let reply = eval::eval_line(&format!("{{\"op\":\"{}\"}}", op.name));
        assert!(
            !reply.contains("unknown op"),
            "op {} is listed but not evaluated: {reply}",
            op.name
        );
    }
}

#[test]
fn never_panics_on_mutated_queries() {
    // Every argument of every valid query in the session replaced by bad values, or removed:
    // the reply is always one JSON object with exactly one of `ok` / `error`, and an `ok`
    // number is never NaN (JSON cannot carry one anyway).
    let bad = [
        serde_json::json!(null),
        serde_json::json!("x"),
        serde_json::json!(1e308),
        serde_json::json!(-1e308),
        serde_json::json!(0.0),
        serde_json::json!(-0.0),
        serde_json::json!(1e-308),
        serde_json::json!([]),
        serde_json::json!([1e308, -1e308, 1e308]),
        serde_json::json!([[1e308, 0], [0, 1e308]]),
        serde_json::json!({}),
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
                count += 1;
            }
        }
    }
    assert!(count > 500, "mutated {count} queries");
}
