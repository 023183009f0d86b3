//! `f32` against `f64` on identical inputs: every parameter and every vector is first rounded
//! to `f32`, then evaluated by both precisions, so the difference is the `f32` evaluation
//! error alone (not the input rounding, which the `f64` reference cannot see).
//!
//! Tolerances come from counting roundings (`eps = f32::EPSILON = 2^-23`, one rounding costs
//! at most `eps / 2` relative). The measured worst cases are printed as "worst / tolerance"
//! (`--nocapture`), to show how tight each bound is:
//! - GGX `p22`, `d`: about a dozen correctly rounded operations (quadratic form, square,
//!   product, reciprocal, the stored `1 / alpha^2`) and no cancellation: `8 eps`.
//! - GGX `lambda`: the same count through `q / (2 |w_z| (sqrt(w_z^2 + q) + |w_z|))`: `8 eps`.
//! - Beckmann `p22`, `d`: `exp(-x)` turns an absolute error of `x` into a relative error of
//!   the result; `x` carries about four roundings (`2 eps` relative), so `(8 + 4 x) eps`.
//! - Beckmann `lambda`: computed in `f64` from `q` and `|w_z|` rounded in `f32`; `Lambda`
//!   falls like `exp(-a^2)`, `a^2 = w_z^2 / q`, so the few-ulp error of `q` is amplified by
//!   `a^2`: `(8 + 4 a^2) eps`.
//! - Matrix form: the same tolerances as the other forms. Its quadratic forms are evaluated in
//!   `f64` from the `f32` entries, with exact products (`RoughnessMatrix` docs), and rounded
//!   to `f32` once: within `eps / 2 + 8 eps_f64` of the exact forms at any condition number,
//!   fewer roundings than the isotropic form's `|s|^2 / alpha^2`. The `f64` reference, from
//!   the same entries, carries `(sqrt(kappa) + 24) eps_f64` (`kappa = cond A <= 1e6` here):
//!   below `1e-5 eps`, added as `ref_err` times the same amplification (2 for GGX, the
//!   exponent for Beckmann). A representation that rounds in `f32` loses `sqrt(kappa) eps` or
//!   more (an `f32` eigenbasis rotation: up to `1e3 eps` at this sample's `kappa = 1e6`; the
//!   entrywise `A^-1`: `kappa eps`) and fails.
//!
//! Results whose `f64` value is below `f32::MIN_POSITIVE` (subnormal or zero in `f32`) are
//! compared absolutely: `|f32 - f64| <= f32::MIN_POSITIVE`. Run with `--nocapture` to see the
//! measured worst cases, printed as multiples of `eps`.

use filtered_ndf::f32 as s;
use filtered_ndf::f64 as d;
use filtered_ndf::testing::cases::{Form, Model, NdfCase};
use filtered_ndf::testing::rng::SplitMix64 as Rng;
use glam::{DVec2, DVec3, Vec2, Vec3};
use std::collections::BTreeMap;

const EPS: f64 = f32::EPSILON as f64;

fn random_case(rng: &mut Rng) -> NdfCase {
    let model = if rng.next_u64() & 1 == 0 {
        Model::Ggx
    } else {
        Model::Beckmann
    };
    let a = rng.log_uniform(1e-4, 2.0);
    let b = (a * rng.log_uniform(1e-3, 1e3)).clamp(1e-4, 2.0);
    let form = match rng.next_u64() % 3 {
        0 => Form::Isotropic(a),
        1 => Form::AxisAligned(a, b),
        _ => Form::Rotated {
            alpha_x: a,
            alpha_y: b,
            phi: std::f64::consts::PI * rng.uniform(),
        },
    };
    NdfCase { model, form }.rounded_to_f32()
}

fn r3(v: DVec3) -> (Vec3, DVec3) {
    let f = v.as_vec3();
    (f, f.as_dvec3())
}

/// A slope drawn around the lobe: Gaussian in the eigen frame times a scale from the peak
/// (`1e-3` widths) to the far tail (`1e3` widths).
fn lobe_slope(rng: &mut Rng, form: Form) -> DVec2 {
    let (ax, ay, phi) = form.axes();
    let k = rng.log_uniform(1e-3, 1e3);
    let u = DVec2::new(rng.normal() * ax, rng.normal() * ay) * k;
    DVec2::from_angle(phi).rotate(u)
}

#[derive(Default, Clone, Copy)]
struct Worst {
    ulps: f64,
    /// Largest error as a fraction of its tolerance (how tight the stated bound is).
    used: f64,
    n: usize,
}

type Key = (&'static str, &'static str, &'static str);

fn form_name(f: Form) -> &'static str {
    match f {
        Form::Isotropic(_) => "isotropic",
        Form::AxisAligned(..) => "axis-aligned",
        Form::Rotated { .. } => "matrix",
    }
}

fn model_name(m: Model) -> &'static str {
    match m {
        Model::Ggx => "GGX",
        Model::Beckmann => "Beckmann",
    }
}

/// Checks one pair and records it; `tol_eps` is the tolerance in units of `eps`.
fn check(
    table: &mut BTreeMap<Key, Worst>,
    key: Key,
    got: f32,
    want: f64,
    tol_eps: f64,
    what: &dyn Fn() -> String,
) {
    assert!(got.is_finite() && got >= 0.0, "{}: f32 gave {got}", what());
    assert!(
        want.is_finite() && want >= 0.0,
        "{}: f64 gave {want}",
        what()
    );
    let w = table.entry(key).or_default();
    w.n += 1;
    if want < f64::from(f32::MIN_POSITIVE) {
        assert!(
            (f64::from(got) - want).abs() <= f64::from(f32::MIN_POSITIVE),
            "{}: f32 {got} vs f64 {want} (below the f32 normal range)",
            what()
        );
        return;
    }
    let ulps = ((f64::from(got) - want) / want).abs() / EPS;
    w.ulps = w.ulps.max(ulps);
    w.used = w.used.max(ulps / tol_eps);
    assert!(
        ulps <= tol_eps,
        "{}: f32 {got} vs f64 {want}: {ulps:.1} eps > {tol_eps:.1} eps",
        what()
    );
}

fn exponent_of(case: &NdfCase, p22_64: f64) -> f64 {
    let (ax, ay, _) = case.form.axes();
    (-(p22_64 * std::f64::consts::PI * ax * ay).ln()).max(0.0)
}

/// The `f64` reference's relative error in its quadratic forms, in units of `eps` (`f32`):
/// `(sqrt(kappa) + 24) eps_f64` for the matrix form (`RoughnessMatrix` docs), a few `eps_f64`
/// for the others (counted as the same; both far below one `eps`).
fn ref_err(case: &NdfCase) -> f64 {
    let (ax, ay, _) = case.form.axes();
    let kappa = (ax / ay).max(ay / ax).powi(2);
    (kappa.sqrt() + 24.0) * f64::EPSILON / EPS
}

/// The `lambda` tolerance in `eps`: `q = w^T A w` carries a few roundings (one for the matrix
/// form); GGX passes the relative error of `q` through about unchanged, Beckmann amplifies it
/// by `a^2 = w_z^2 / q`.
fn lambda_tol(case: &NdfCase, w: DVec3) -> f64 {
    let (ax, ay, phi) = case.form.axes();
    let u = DVec2::from_angle(-phi).rotate(w.truncate());
    let q = u.x * u.x * ax * ax + u.y * u.y * ay * ay;
    let r = ref_err(case);
    match case.model {
        Model::Ggx => 8.0 + r,
        Model::Beckmann => 8.0 + (4.0 + r) * (w.z * w.z / q).max(1.0),
    }
}

/// The `p22` / `d` tolerance in `eps` for a density of exponent `x` (Beckmann; `None` for
/// GGX): `8 eps` for GGX and `(8 + 4 x) eps` for Beckmann (module docs), plus the reference's
/// error amplified alike.
fn density_tol(case: &NdfCase, x: Option<f64>) -> f64 {
    let r = ref_err(case);
    match x {
        None => 8.0 + 2.0 * r,
        Some(x) => 8.0 + (4.0 + r) * x,
    }
}

fn run_case(table: &mut BTreeMap<Key, Worst>, rng: &mut Rng, case: NdfCase, inputs: usize) {
    let f = case.build_f32().expect("f32 build");
    let g = case.build_f64().expect("f64 build");
    let (mn, fname) = (model_name(case.model), form_name(case.form));
    let beck = case.model == Model::Beckmann;
    for i in 0..inputs {
        // Slope domain.
        let sl = lobe_slope(rng, case.form);
        let sf = sl.as_vec2();
        let s64 = sf.as_dvec2();
        let want = g.p22(s64);
        let tol = density_tol(&case, beck.then(|| exponent_of(&case, want)));
        check(table, (mn, "p22", fname), f.p22(sf), want, tol, &|| {
            format!("{case:?} p22({sf:?})")
        });
        // Micronormal: the same slope on the sphere, or every fourth one grazing.
        let mv = if i % 4 == 3 {
            let t = (89.0 + 0.999 * rng.uniform()).to_radians();
            let p = std::f64::consts::TAU * rng.uniform();
            DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
        } else {
            DVec3::new(-sl.x, -sl.y, 1.0).normalize()
        };
        let (mf, m64) = r3(mv);
        let want = g.d(m64);
        let tol = density_tol(
            &case,
            beck.then(|| exponent_of(&case, want * m64.z.powi(4))),
        );
        check(table, (mn, "d", fname), f.d(mf), want, tol, &|| {
            format!("{case:?} d({mf:?})")
        });
        // Lambda: directions up to 89.9 degrees, half of them within 60 degrees.
        let tmax: f64 = if i % 2 == 0 { 60.0 } else { 89.9 };
        let t = (tmax * rng.uniform()).to_radians();
        let p = std::f64::consts::TAU * rng.uniform();
        let (wf, w64) = r3(DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()));
        let want = g.lambda(w64);
        let tol = lambda_tol(&case, w64);
        check(
            table,
            (mn, "lambda", fname),
            f.lambda(wf),
            want,
            tol,
            &|| format!("{case:?} lambda({wf:?})"),
        );
    }
}

#[test]
fn f32_matches_f64_on_a_seeded_sample_and_reports_the_worst_case() {
    let mut rng = Rng(0x5EED_F00D);
    let mut table = BTreeMap::new();
    for _ in 0..3000 {
        let case = random_case(&mut rng);
        run_case(&mut table, &mut rng, case, 16);
    }
    println!("worst f32 relative error vs f64 on identical inputs, in eps = 2^-23:");
    println!(
        "| NDF | function | form | worst (eps) | worst (relative) | worst / tolerance | samples |"
    );
    println!("|---|---|---|---|---|---|---|");
    for ((m, func, form), w) in &table {
        println!(
            "| {m} | {func} | {form} | {:.2} | {:.2e} | {:.3} | {} |",
            w.ulps,
            w.ulps * EPS,
            w.used,
            w.n
        );
    }
}

#[test]
fn extremes_alpha_1e4_peak_tail_and_grazing() {
    let mut table = BTreeMap::new();
    let mut rng = Rng(7);
    for model in [Model::Ggx, Model::Beckmann] {
        for form in [
            Form::Isotropic(1e-4),
            Form::AxisAligned(1e-4, 1e-1),
            Form::Rotated {
                alpha_x: 1e-4,
                alpha_y: 1e-1,
                phi: 0.3,
            },
            Form::Isotropic(2.0),
        ] {
            let case = NdfCase { model, form }.rounded_to_f32();
            let f = case.build_f32().unwrap();
            let g = case.build_f64().unwrap();
            // The peak: exactly 1 / (pi sqrt(det A)) in both precisions' rounding.
            let want = g.d(DVec3::Z);
            check(
                &mut table,
                ("", "d", "peak"),
                f.d(Vec3::Z),
                want,
                8.0,
                &|| format!("{case:?} peak"),
            );
            // Far in the tail and grazing: slopes 1e-6 .. 1e6 along several azimuths and
            // polar angles up to 89.999 degrees.
            for k in -6..=6 {
                for az in 0..8 {
                    let sl = DVec2::from_angle(f64::from(az) * 0.7) * 10f64.powi(k);
                    let (mf, m64) = r3(DVec3::new(-sl.x, -sl.y, 1.0).normalize());
                    let want = g.d(m64);
                    let beck = model == Model::Beckmann;
                    let tol = density_tol(
                        &case,
                        beck.then(|| exponent_of(&case, want * m64.z.powi(4))),
                    );
                    check(&mut table, ("", "d", "tail"), f.d(mf), want, tol, &|| {
                        format!("{case:?} d({mf:?})")
                    });
                    let sf = sl.as_vec2();
                    let want = g.p22(sf.as_dvec2());
                    let tol = density_tol(&case, beck.then(|| exponent_of(&case, want)));
                    check(
                        &mut table,
                        ("", "p22", "tail"),
                        f.p22(sf),
                        want,
                        tol,
                        &|| format!("{case:?} p22({sf:?})"),
                    );
                }
            }
            for deg in [89.9, 89.99, 89.999] {
                let t = f64::to_radians(deg);
                let p = std::f64::consts::TAU * rng.uniform();
                let (wf, w64) = r3(DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()));
                let want = g.lambda(w64);
                // Grazing: GGX Lambda ~ sqrt(q) / (2 w_z), a few roundings; Beckmann as in
                // the sample test, `(32 + 8 a^2) eps` (its value may underflow f32 when
                // `a = w_z / sqrt(q)` is large: then the absolute check applies).
                let tol = lambda_tol(&case, w64);
                check(
                    &mut table,
                    ("", "lambda", "grazing"),
                    f.lambda(wf),
                    want,
                    tol,
                    &|| format!("{case:?} lambda at {deg} deg"),
                );
            }
        }
    }
    println!("extremes (alpha = 1e-4 .. 2, slopes 1e-6 .. 1e6, 89.9 .. 89.999 degrees):");
    for ((_, func, region), w) in &table {
        println!(
            "  {func} {region}: worst {:.2} eps ({:.2e}), {:.3} of tolerance, {} samples",
            w.ulps,
            w.ulps * EPS,
            w.used,
            w.n
        );
    }
    let _ = (s::ALPHA_MIN, d::ALPHA_MIN, Vec2::ZERO);
}
