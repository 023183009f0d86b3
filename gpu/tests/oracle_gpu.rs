//! The oracle's GPU backend (`oracle_backend`, binary `oracle` of this crate) on the
//! session file of the oracle's test (`oracle/tests/data/oracle_session.jsonl`): every line it
//! answers with a number is within the conformance harness's tolerance of the function it
//! calls, relative to the CPU `f64` answer at the same f32 arguments (every number of the line
//! rounded to f32 before the `f64` evaluation: the references of `gpu/src/checks/` are taken
//! at exactly the values the shader reads); a line the CPU refuses, the GPU refuses too; ops
//! without a shader answer an error naming the op. The backend is chosen by
//! `FILTERED_NDF_GPU_BACKEND`; a missing adapter fails with a message naming the package.

use filtered_ndf_gpu::oracle_backend as gpu_backend;
use filtered_ndf_oracle::eval;

use filtered_ndf_gpu::checks::{self, Tol};
use filtered_ndf_gpu::reference::{
    self as r, AxisAligned, Covariance, DVec2, DVec3, Footprint, Roughness, RoughnessMatrix,
};
use serde_json::{Value, json};

/// The session, one entry per non-blank line.
fn session() -> Vec<&'static str> {
    include_str!("../../oracle/tests/data/oracle_session.jsonl")
        .lines()
        .filter(|l| !l.trim().is_empty())
        .collect()
}

/// Every number of a JSON value rounded to f32 (and widened back).
fn rounded(v: &Value) -> Value {
    match v {
        Value::Number(n) => n
            .as_f64()
            .map_or_else(|| v.clone(), |x| json!(f64::from(x as f32))),
        Value::Array(a) => Value::Array(a.iter().map(rounded).collect()),
        Value::Object(o) => Value::Object(o.iter().map(|(k, x)| (k.clone(), rounded(x))).collect()),
        _ => v.clone(),
    }
}

/// The CPU `f64` answer at the f32 arguments.
fn cpu_reference(line: &str) -> Value {
    let Ok(mut v) = serde_json::from_str::<Value>(line) else {
        return serde_json::from_str(&eval::eval_line(line)).expect("JSON");
    };
    if v.is_object() {
        v = rounded(&v);
        if v.get("precision").and_then(Value::as_str) == Some("f32") {
            v["precision"] = json!("f64");
        }
    }
    serde_json::from_str(&eval::eval_line(&v.to_string())).expect("JSON")
}

fn a3(v: &Value, k: &str) -> DVec3 {
    let a = v[k].as_array().expect("array");
    DVec3::new(
        a[0].as_f64().unwrap(),
        a[1].as_f64().unwrap(),
        a[2].as_f64().unwrap(),
    )
}

fn a2(v: &Value, k: &str) -> DVec2 {
    let a = v[k].as_array().expect("array");
    DVec2::new(a[0].as_f64().unwrap(), a[1].as_f64().unwrap())
}

/// The roughness of a line (rounded arguments) as the shader has it: its form's `err_q`
/// (`checks::ndf`: 6 isotropic, 7 axis-aligned; a matrix from its entries and `det`, the
/// filtered-matrix rule `10 + 16 sqrt(cond)` of `checks::filters`) and as a matrix.
fn roughness(v: &Value) -> (f64, RoughnessMatrix, Option<AxisAligned>) {
    let rv = &v["roughness"];
    if let Some(a) = rv.as_f64() {
        let r = AxisAligned::new(a, a).unwrap();
        return (6.0, r.to_matrix(), Some(r));
    }
    let arr = rv.as_array().unwrap();
    if let Some(ax) = arr[0].as_f64() {
        let r = AxisAligned::new(ax, arr[1].as_f64().unwrap()).unwrap();
        return (7.0, r.to_matrix(), Some(r));
    }
    let e = |i: usize, j: usize| arr[i].as_array().unwrap()[j].as_f64().unwrap();
    let m = RoughnessMatrix::new(e(0, 0), 0.5 * e(0, 1) + 0.5 * e(1, 0), e(1, 1)).unwrap();
    (10.0 + 16.0 * checks::ndf::clamped_cond(&m).sqrt(), m, None)
}

/// `D`'s tolerance (ulp) of a lobe's matrix at `m` (`checks::ndf::tol_density`).
fn density_tol(ggx: bool, err_q: f64, a: &RoughnessMatrix, m: DVec3) -> f64 {
    let x = a.inv_quadratic(DVec2::new(m.x, m.y)) / (m.z * m.z);
    let ln_k = -((core::f64::consts::PI * a.sqrt_det()).ln() + 4.0 * m.z.ln());
    checks::ndf::tol_density(ggx, err_q, x, ln_k)
}

/// `Lambda`'s tolerance (ulp) of a lobe's matrix at `w`.
fn lambda_tol(ggx: bool, err_q: f64, a: &RoughnessMatrix, w: DVec3) -> f64 {
    let n = w.length();
    checks::ndf::tol_lambda(
        ggx,
        err_q,
        a.quadratic(DVec2::new(w.x, w.y) / n),
        (w.z / n).abs(),
    )
}

/// The unit normal of a slope.
fn normal_of(s: DVec2) -> DVec3 {
    DVec3::new(-s.x, -s.y, 1.0).normalize()
}

/// The footprint of a line (rounded), the CPU's constructors.
fn footprint(v: &Value) -> Footprint {
    let fp = &v["footprint"];
    let pair = |x: &Value| {
        let a = x.as_array().unwrap();
        (v2f(&a[0]), v2f(&a[1]))
    };
    if fp.is_array() {
        let (u, w) = pair(fp);
        return Footprint::from_slope_derivatives(u, w);
    }
    let (form, x) = fp.as_object().unwrap().iter().next().unwrap();
    match form.as_str() {
        "slope" => {
            let (u, w) = pair(x);
            Footprint::from_slope_derivatives(u, w)
        }
        "projected" => {
            let (u, w) = pair(x);
            Footprint::from_projected_derivatives(u, w)
        }
        "projected_in_slope" => {
            let (u, w) = pair(&x["dp"]);
            Footprint::from_projected_derivatives_in_slope(a3(x, "h"), u, w)
        }
        _ => {
            let a = x.as_array().unwrap();
            let t = |y: &Value| {
                let b = y.as_array().unwrap();
                DVec3::new(
                    b[0].as_f64().unwrap(),
                    b[1].as_f64().unwrap(),
                    b[2].as_f64().unwrap(),
                )
            };
            Footprint::from_normal_differences(t(&a[0]), t(&a[1]))
        }
    }
}

fn v2f(x: &Value) -> DVec2 {
    let a = x.as_array().unwrap();
    DVec2::new(a[0].as_f64().unwrap(), a[1].as_f64().unwrap())
}

/// The flat numbers of an answer (`"inf"` as infinity; `null` as nothing).
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Number(n) => vec![n.as_f64().unwrap()],
        Value::String(s) if s == "inf" => vec![f64::INFINITY],
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        Value::Object(o) => o.values().flat_map(numbers).collect(),
        _ => vec![],
    }
}

/// The conformance tolerance of each number of a line's answer (rounded arguments `v`,
/// the CPU reference answer `reference`).
fn tolerances(v: &Value, reference: &[f64]) -> Vec<Tol> {
    let op = v["op"].as_str().unwrap();
    let ggx = v.get("dist").and_then(Value::as_str) != Some("beckmann");
    let n = reference.len();
    let scale = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let all = |t: Tol| vec![t; n];
    match op {
        "ndf" | "slope_pdf" | "lambda" | "g1" | "g2" => {
            let (eq, a, _) = roughness(v);
            let t = match op {
                "ndf" => density_tol(ggx, eq, &a, a3(v, "m")),
                "slope_pdf" => density_tol(ggx, eq, &a, normal_of(a2(v, "slope"))),
                "lambda" => lambda_tol(ggx, eq, &a, a3(v, "w")),
                "g1" => lambda_tol(ggx, eq, &a, a3(v, "w")) + 3.0,
                _ => {
                    lambda_tol(ggx, eq, &a, a3(v, "i")).max(lambda_tol(ggx, eq, &a, a3(v, "o")))
                        + 4.0
                }
            };
            all(Tol::ulps(t))
        }
        "pdf" => {
            // checks::sampling: D's and Lambda's rules, 2 EPS / (wo.m), 8 and 4 ulp.
            let (eq, a, _) = roughness(v);
            let (o, m) = (a3(v, "o"), a3(v, "m"));
            let om = o.normalize().dot(m);
            let t = density_tol(ggx, eq, &a, m) + lambda_tol(ggx, eq, &a, o) + 2.0 / om + 12.0;
            all(Tol::ulps(t))
        }
        "sample" => {
            let (_, a, _) = roughness(v);
            let u = a2(v, "u");
            let u = [u.x as f32, u.y as f32];
            all(Tol::abs(if ggx {
                checks::sampling::sample_tol_of(&a, a3(v, "o"), u)
            } else {
                checks::sampling_beckmann::sample_tol_of(&a, a3(v, "o"), u)
            }))
        }
        // checks::footprint: 8, 20, 16 EPS of the largest entry.
        "jacobian" => {
            let k = match v["kind"].as_str().unwrap() {
                "sphere_to_projected" => 8.0,
                "projected_to_slope" => 20.0,
                _ => 16.0,
            };
            all(Tol::of_scale(k, scale))
        }
        // checks::filters (c_push): the alpha^2 presets' rule, err_k 11 (max) or 3.
        "isotropic_roughness" => {
            let k = if v["variant"] == "max" { 11.0 } else { 3.0 };
            all(Tol::ulps(0.5 * (k + 1.0) + 8.0))
        }
        "preset" => {
            let name = v["name"].as_str().unwrap();
            let conv = &r::presets::ALL.iter().find(|(x, _)| *x == name).unwrap().1;
            let alpha = v["alpha"].as_f64().unwrap();
            all(Tol::ulps(checks::filters::deferred_tol(
                conv,
                alpha,
                a3(v, "dn_u"),
                a3(v, "dn_v"),
            )))
        }
        // checks::filters::entries_rows.
        "filter_roughness" | "projected_roughness" => all(Tol::of_scale(32.0, scale)),
        "ggx_rect" => {
            let (_, _, aa) = roughness(v);
            all(Tol::ulps(checks::rect::rect_ulps(
                aa.unwrap(),
                a2(v, "center"),
                a2(v, "half_extent"),
            )))
        }
        "ggx_proxy" => {
            let t = if v["variant"] == "simple" { 8.0 } else { 12.0 };
            all(Tol::ulps(t))
        }
        "ggx_rect_footprint" => {
            let (_, _, aa) = roughness(v);
            let rect = r::RectFilteredGgx::new(aa.unwrap(), DVec2::ZERO);
            rect_tol(v, rect.roughness, reference, n)
        }
        "filtered" => filtered_tol(v, ggx, reference, n, scale),
        "gaussian_filtered" => {
            let (_, a, _) = roughness(v);
            let k = v["kernel"].as_array().unwrap();
            let e = |i: usize, j: usize| k[i].as_array().unwrap()[j].as_f64().unwrap();
            let kernel = Covariance::new(e(0, 0), e(0, 1), e(1, 1));
            let s = a2(v, "slope");
            let t = if ggx {
                checks::gaussian_ggx::density_ulps(&a, &kernel, s)
            } else {
                checks::filters::filtered_d_tol(
                    &r::filter::gaussian(a, kernel),
                    normal_of(s),
                    false,
                )
            };
            all(Tol::ulps(t))
        }
        other => panic!("no tolerance for op {other}"),
    }
}

/// The box filter's tolerances (`checks::rect`): `D`, `P22`, `Lambda`, or the half extents
/// (`footprint::bounding_rect`'s 1 ulp; the clamps are exact).
fn rect_tol(v: &Value, r: AxisAligned, reference: &[f64], n: usize) -> Vec<Tol> {
    // The half extents, as the CPU computes them (the lobe answer without a point).
    let mut lobe = v.clone();
    for k in ["m", "slope", "w"] {
        if let Some(o) = lobe.as_object_mut() {
            o.remove(k);
        }
    }
    let he = numbers(&cpu_reference(&lobe.to_string())["ok"]);
    let he = DVec2::new(he[he.len() - 2], he[he.len() - 1]);
    let t = if v.get("m").is_some() {
        let h = a3(v, "m");
        checks::rect::d_rect_ulps(r, DVec2::new(-h.x / h.z, -h.y / h.z), he)
    } else if v.get("slope").is_some() {
        checks::rect::rect_ulps(r, a2(v, "slope"), he)
    } else if v.get("w").is_some() {
        checks::rect::lambda_rect_ulps(r, he, a3(v, "w"))
    } else {
        return reference.iter().map(|_| Tol::ulps(1.0)).collect();
    };
    vec![Tol::ulps(t); n]
}

/// The front door's tolerances (`checks::method`).
fn filtered_tol(v: &Value, ggx: bool, reference: &[f64], n: usize, scale: f64) -> Vec<Tol> {
    let method = v["method"].as_str().unwrap();
    let (eq, a, aa) = roughness(v);
    let lobe_only = v.get("m").is_none() && v.get("slope").is_none() && v.get("w").is_none();
    let mut lobe_line = v.clone();
    for k in ["m", "slope", "w"] {
        if let Some(o) = lobe_line.as_object_mut() {
            o.remove(k);
        }
    }
    match method {
        "rect_khpl16" | "rect_gdc2016" => {
            if lobe_only {
                return reference.iter().map(|_| Tol::ulps(1.0)).collect();
            }
            let lobe = numbers(&cpu_reference(&lobe_line.to_string())["ok"]);
            let he = DVec2::new(lobe[0], lobe[1]);
            let r = aa.unwrap();
            let t = if v.get("m").is_some() {
                let h = a3(v, "m");
                checks::rect::d_rect_ulps(r, DVec2::new(-h.x / h.z, -h.y / h.z), he)
            } else if v.get("slope").is_some() {
                checks::rect::rect_ulps(r, a2(v, "slope"), he)
            } else {
                checks::rect::lambda_rect_ulps(r, he, a3(v, "w"))
            };
            vec![Tol::ulps(t); n]
        }
        "proxy_khpl16" => {
            // alpha' within 12 ulp per axis (checks::filters); D, P22: 2 (7 + 4 x 12 + 1) +
            // 6 + 2 x 12; Lambda: the matrix rule with err_q 8 + 8 sqrt(cond) + 24.
            if lobe_only {
                return vec![Tol::ulps(12.0); n];
            }
            let t = if v.get("w").is_some() {
                let lobe = numbers(&cpu_reference(&lobe_line.to_string())["ok"]);
                let p = AxisAligned::new(lobe[0], lobe[1]).unwrap().to_matrix();
                let e = 8.0 + 8.0 * checks::ndf::clamped_cond(&p).sqrt() + 24.0;
                lambda_tol(true, e, &p, a3(v, "w"))
            } else {
                2.0 * (7.0 + 4.0 * 12.0 + 1.0) + 6.0 + 2.0 * 12.0
            };
            vec![Tol::ulps(t); n]
        }
        "gaussian_exact" if ggx => {
            let fp = footprint(v);
            let rules = r::ClampRules::KHPL16;
            let sigma = v.get("sigma").and_then(Value::as_f64).unwrap_or(0.5);
            let kernel = rules.kernel(rules.footprint(fp).covariance(sigma));
            let t = if v.get("w").is_some() {
                checks::gaussian_ggx::lambda_ulps(&a, &kernel, a3(v, "w"))
            } else {
                let s = if v.get("m").is_some() {
                    let h = a3(v, "m");
                    DVec2::new(-h.x / h.z, -h.y / h.z)
                } else {
                    a2(v, "slope")
                };
                checks::gaussian_ggx::density_ulps(&a, &kernel, s)
            };
            vec![Tol::ulps(t); n]
        }
        _ => {
            // Gaussian (and exact Beckmann) and projected: the filtered matrix of the CPU's lobe.
            if lobe_only {
                return vec![Tol::of_scale(32.0, scale); n];
            }
            let e = numbers(&cpu_reference(&lobe_line.to_string())["ok"]);
            let m = RoughnessMatrix::new(e[0], e[1], e[3]).unwrap();
            let _ = eq;
            let t = if v.get("w").is_some() {
                let e = 10.0 + 16.0 * checks::ndf::clamped_cond(&m).sqrt();
                lambda_tol(ggx, e, &m, a3(v, "w"))
            } else {
                let h = if v.get("m").is_some() {
                    a3(v, "m")
                } else {
                    normal_of(a2(v, "slope"))
                };
                checks::filters::filtered_d_tol(&m, h, ggx)
            };
            vec![Tol::ulps(t); n]
        }
    }
}

#[test]
fn session_through_the_shaders() {
    if let Err(e) = filtered_ndf_gpu::harness::gpu() {
        panic!("{e}");
    }
    let lines = session();
    let gpu = gpu_backend::answer_session(&lines, &eval::eval_line);
    assert_eq!(gpu.len(), lines.len(), "one answer per line");
    let mut compared = 0;
    let mut report = String::new();
    let mut failures = Vec::new();
    for (line, g) in lines.iter().zip(&gpu) {
        let g: Value = serde_json::from_str(g).expect("JSON");
        let c = cpu_reference(line);
        let v: Value = serde_json::from_str(line)
            .map(|x| rounded(&x))
            .unwrap_or(Value::Null);
        let op = v.get("op").and_then(Value::as_str).unwrap_or("");
        match (c.get("ok"), g.get("ok")) {
            (Some(cv), Some(gv)) => {
                let (cn, gn) = (numbers(cv), numbers(gv));
                assert_eq!(cn.len(), gn.len(), "{line}: {c} vs {g}");
                let tols = tolerances(&v, &cn);
                for ((x, y), t) in cn.iter().zip(&gn).zip(&tols) {
                    let err = (x - y).abs();
                    let ok = (x == y) || err <= t.rel * x.abs() + t.abs;
                    let rel = if *x != 0.0 { err / x.abs() } else { err };
                    report += &format!(
                        "  {op:<20} {rel:9.2e} of {:9.2e}\n",
                        t.rel + t.abs / x.abs().max(1e-300)
                    );
                    if !ok {
                        failures.push(format!("{line}\n    cpu {x:e} gpu {y:e} tol {t:?}"));
                    }
                    compared += 1;
                }
            }
            (Some(_), None) => {
                // Only an op (or an NDF family's sampler) without a shader may refuse.
                let e = g["error"].as_str().unwrap_or("");
                assert!(
                    e.contains(&format!("op \"{op}\" has no shader")),
                    "{line}: the CPU answers {c}, the GPU {g}"
                );
            }
            (None, Some(_)) => panic!("{line}: the CPU refuses ({c}) but the GPU answers {g}"),
            (None, None) => {}
        }
    }
    eprintln!("{compared} numbers compared\n{report}");
    assert!(compared > 40, "the session's numbers are compared");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn ops_without_a_shader_answer_an_error_naming_the_op() {
    let lines = [
        r#"{"op":"temporal","dist":"ggx","roughness":0.1,"dn_dt":[1,2],"dt":0.1,"m":[0,0,1]}"#,
        r#"{"op":"ndf","dist":"ggx","roughness":0.1,"m":[0,0,1],"precision":"f64"}"#,
        r#"{"op":"sample","dist":"beckmann","roughness":0.5,"o":[0,0,1],"u":[0.25,0.5]}"#,
    ];
    let a = gpu_backend::answer_session(&lines, &eval::eval_line);
    let e = |i: usize| {
        let v: Value = serde_json::from_str(&a[i]).unwrap();
        v["error"].as_str().unwrap_or_default().to_string()
    };
    assert!(
        e(0).contains("\"temporal\"") && e(0).contains("no shader"),
        "{}",
        a[0]
    );
    assert!(e(1).contains("f32"), "{}", a[1]);
    // Beckmann sampling has its shader (`sampling::beckmann`): an answer, not an error.
    assert!(e(2).is_empty(), "{}", a[2]);
}
