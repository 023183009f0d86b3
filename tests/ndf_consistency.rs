//! The three roughness forms agree where they describe the same lobe, rotating `A` rotates
//! the lobe, and the TK19 determinant clamp does what its documentation says (one matrix
//! `A_c = A + t I` of determinant `max(det A, tau)` for the density and `Lambda`).
//!
//! Tolerances (in units of the precision's `eps`):
//! - Same lobe, different form: the forms compute `sqrt(det A)` and the quadratic forms with
//!   different but equally short operation sequences (`alpha_x alpha_y` versus
//!   `sqrt(alpha_x^2 alpha_y^2)`, a stored `1 / alpha^2` versus an eigenvalue quotient), a
//!   handful of roundings each, amplified by the exponent `x` for Beckmann: `(16 + 4 x) eps`.
//!   Beckmann `Lambda ~ exp(-a^2)`, `x = -ln Lambda >= a^2`: `a` carries 1.5 eps (3 a^2 eps
//!   in `exp(-a^2)`), the cancellation of its two terms another `2 a^2 eps`: `(16 + 8 x) eps`.
//! - Rotation: `A = R diag(l1, l2) R^T` is formed in `f64` and rounded, which moves the small
//!   eigenvalue by `eps l1`, a relative `eps l1 / l2 = eps cond(A)`; `D` follows with the
//!   factor `(2 + x)` (GGX `2 q / (1 + q) <= 2`, Beckmann `x`; Beckmann `Lambda` `4 x` as
//!   above): `64 cond(A) (2 + x) eps`.

use filtered_ndf::f32::{self as s, Ndf as _};
use filtered_ndf::f64::{AxisAligned, Beckmann, Ggx, Isotropic, Ndf, Roughness, RoughnessMatrix};
use filtered_ndf::testing::cases;
use glam::{DMat2, DVec2, DVec3, Vec3};
use proptest::prelude::*;

const EPS: f64 = f64::EPSILON;

fn close(a: f64, b: f64, tol_eps: f64) -> bool {
    a == b || (a - b).abs() <= tol_eps * EPS * a.abs().max(b.abs())
}

/// Exponent `x` of a Beckmann evaluation (for the tolerance), from the density's peak.
fn x_of(v: f64, peak: f64) -> f64 {
    if v > 0.0 {
        (peak / v).ln().max(0.0)
    } else {
        0.0
    }
}

fn micronormal(d: [f64; 3]) -> DVec3 {
    DVec3::from_array(d)
}

/// Evaluates `p22(s)`, `d(m)`, `lambda(w)` of both models for a roughness form.
fn evals<R: Roughness>(r: R, s: DVec2, m: DVec3, w: DVec3) -> [f64; 6] {
    let (g, b) = (Ggx::new(r), Beckmann::new(r));
    [g.p22(s), g.d(m), g.lambda(w), b.p22(s), b.d(m), b.lambda(w)]
}

fn assert_same(
    x: [f64; 6],
    y: [f64; 6],
    peak: f64,
    m: DVec3,
    what: &str,
) -> Result<(), TestCaseError> {
    for (k, (a, b)) in x.iter().zip(y.iter()).enumerate() {
        // Beckmann densities (indices 3, 4) get the exponent amplification; Beckmann Lambda
        // (5) falls like exp(-a^2), so a relative error d of `a` becomes 2 a^2 d = 2 ln(1/L) d
        // in L. `a = |w_z| / sqrt(w^T A w)` takes up to 3 roundings per side (quadratic form,
        // sqrt, division) and the two sides round independently: 2 * 2 * 3 = 12 ln(1/L) eps,
        // i.e. xx = 3 ln(1/L) in the 16 + 4 xx below (a seed at L = 2.8e-184 measured
        // 8.3 ln(1/L) eps, above the earlier 8 ln(1/L) that counted one side only).
        let xx = match k {
            3 => x_of(*a, peak),
            4 => x_of(*a * m.z.powi(4), peak),
            5 => 3.0 * (-a.max(1e-300).ln()).max(0.0),
            _ => 0.0,
        };
        prop_assert!(close(*a, *b, 16.0 + 4.0 * xx), "{what} [{k}]: {a} vs {b}");
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn diagonal_matrix_equals_axis_aligned_equals_isotropic(
        ax in cases::alpha(1e-4, 2.0),
        ay in cases::alpha(1e-4, 2.0),
        sl in (-1e3f64..1e3, -1e3f64..1e3),
        m in cases::direction(89.9),
        w in cases::direction(89.9),
    ) {
        let (m, w) = (micronormal(m), micronormal(w));
        let s = DVec2::new(sl.0 * ax, sl.1 * ay) * 1e-2;
        let aa = AxisAligned::new(ax, ay).unwrap();
        let mx = RoughnessMatrix::new(ax * ax, 0.0, ay * ay).unwrap();
        let peak = 1.0 / (std::f64::consts::PI * ax * ay);
        assert_same(evals(aa, s, m, w), evals(mx, s, m, w), peak, m, "aligned vs matrix")?;
        assert_same(evals(aa, s, m, w), evals(aa.to_matrix(), s, m, w), peak, m, "to_matrix")?;
        let iso = Isotropic::new(ax).unwrap();
        let aa2 = AxisAligned::new(ax, ax).unwrap();
        let peak = 1.0 / (std::f64::consts::PI * ax * ax);
        assert_same(evals(iso, s, m, w), evals(aa2, s, m, w), peak, m, "iso vs aligned")?;
        assert_same(evals(iso, s, m, w), evals(AxisAligned::from(iso), s, m, w), peak, m, "From")?;
        assert_same(evals(iso, s, m, w), evals(RoughnessMatrix::from(iso), s, m, w), peak, m, "iso matrix")?;
        // The same in f32 (inputs rounded first; the tolerance scales with f32's eps).
        let (axf, ayf) = (ax as f32, ay as f32);
        let a32 = s::Ggx::new(s::AxisAligned::new(axf, ayf).unwrap());
        let m32 = s::Ggx::new(s::RoughnessMatrix::new(axf * axf, 0.0, ayf * ayf).unwrap());
        let mf = m.as_vec3();
        let (u, v) = (a32.d(mf), m32.d(mf));
        prop_assert!((u - v).abs() <= 16.0 * f32::EPSILON * u.max(v), "f32 aligned vs matrix {u} {v}");
        let i32_ = s::Ggx::new(s::Isotropic::new(axf).unwrap());
        let (u, v) = (i32_.d(mf), s::Ggx::new(s::AxisAligned::new(axf, axf).unwrap()).d(mf));
        prop_assert!((u - v).abs() <= 16.0 * f32::EPSILON * u.max(v), "f32 iso vs aligned {u} {v}");
    }

    #[test]
    fn rotating_a_rotates_the_lobe(
        ax in cases::alpha(1e-4, 2.0),
        ratio in cases::alpha(1e-3, 1e3),
        phi in 0.0..std::f64::consts::TAU,
        m in cases::direction(89.9),
        w in cases::direction(89.9),
    ) {
        let ay = (ax * ratio).clamp(1e-4, 2.0);
        let (m, w) = (micronormal(m), micronormal(w));
        let rot = DMat2::from_angle(phi);
        let a = rot * DMat2::from_diagonal(DVec2::new(ax * ax, ay * ay)) * rot.transpose();
        let mx = RoughnessMatrix::new(a.x_axis.x, 0.5 * (a.x_axis.y + a.y_axis.x), a.y_axis.y)
            .unwrap();
        let aa = AxisAligned::new(ax, ay).unwrap();
        let rz = |v: DVec3| (rot * v.truncate()).extend(v.z);
        let cond = (ax / ay).max(ay / ax).powi(2);
        let s = DVec2::new(-m.x / m.z, -m.y / m.z);
        let peak = 1.0 / (std::f64::consts::PI * ax * ay);
        let want = evals(aa, s, m, w);
        let got = evals(mx, rot * s, rz(m), rz(w));
        for (k, (x, y)) in want.iter().zip(got.iter()).enumerate() {
            let xx = match k {
                3 => x_of(*x, peak),
                4 => x_of(*x * m.z.powi(4), peak),
                5 => 4.0 * (-x.max(1e-300).ln()).max(0.0),
                _ => 0.0,
            };
            let tol = 64.0 * cond * (2.0 + xx) + 16.0;
            prop_assert!(close(*x, *y, tol), "[{k}] D_A(m) {x} vs D_RAR^T(Rm) {y} (tol {tol} eps)");
        }
    }

    #[test]
    fn det_clamp_evaluates_a_plus_t_identity(
        ax in cases::alpha(1e-3, 1.0),
        ay in cases::alpha(1e-3, 1.0),
        phi in 0.0..std::f64::consts::PI,
        tau_scale in cases::alpha(1e-3, 1e3),
        sl in (-3.0f64..3.0, -3.0f64..3.0),
    ) {
        let rot = DMat2::from_angle(phi);
        let a = rot * DMat2::from_diagonal(DVec2::new(ax * ax, ay * ay)) * rot.transpose();
        let (a11, a12, a22) = (a.x_axis.x, a.x_axis.y, a.y_axis.y);
        let det = a11 * a22 - a12 * a12;
        let tau = det * tau_scale;
        let mx = RoughnessMatrix::new_with_det_clamp(a11, a12, a22, tau).unwrap();
        // The documented rule, written out: A_c = A + t I with det(A_c) = max(det, tau),
        // t the positive root of t^2 + tr(A) t + det - tau = 0 (0 for tau <= det).
        let dd = det.max(tau);
        let h = 0.5 * (a11 + a22);
        let t = if tau > det { (tau - det) / (h + (h * h + tau - det).sqrt()) } else { 0.0 };
        let ac = DMat2::from_cols(DVec2::new(a11 + t, a12), DVec2::new(a12, a22 + t));
        let inv = mx.inverse();
        // The reference's own det(A) cancels to a relative cond(A) eps, which moves t, the
        // entries of A_c and those of its inverse by cond(A) eps relative to the largest
        // entry (cond(A_c) <= cond(A)); so does the pivot's rounding in the code:
        // 64 cond(A) eps of the largest entry of A_c^-1, about lambda_max / c.
        let cond = (ax / ay).max(ay / ax).powi(2);
        let big = ax.max(ay).powi(2) / dd;
        for (x, y) in inv.to_cols_array().iter().zip(ac.inverse().to_cols_array()) {
            prop_assert!((x - y).abs() <= 64.0 * cond * EPS * big, "inverse {inv} vs {ac}^-1");
        }
        prop_assert!(close(mx.sqrt_det(), dd.sqrt(), 64.0 * cond));
        prop_assert!(close(mx.clamped_det(), dd, 64.0 * cond));
        // GGX's density and Lambda of A_c, written out: the one clamped matrix everywhere.
        let s = DVec2::new(sl.0 * ax, sl.1 * ay);
        let q = s.dot(ac.inverse() * s);
        let want = 1.0 / (std::f64::consts::PI * dd.sqrt() * (1.0 + q) * (1.0 + q));
        let got = Ggx::new(mx).p22(s);
        prop_assert!(close(got, want, 64.0 * cond), "{got} vs {want}");
        let w = DVec3::new(0.3, -0.5, 0.5).normalize();
        let qw = w.truncate().dot(ac * w.truncate());
        let want = qw / (2.0 * w.z * ((w.z * w.z + qw).sqrt() + w.z));
        let got = Ggx::new(mx).lambda(w);
        prop_assert!(close(got, want, 64.0 * cond), "Lambda {got} vs {want}");
        // tau <= det: identical to the unclamped matrix, and equal by value.
        let plain = RoughnessMatrix::new(a11, a12, a22).unwrap();
        if tau <= det {
            prop_assert_eq!(Ggx::new(mx).p22(s), Ggx::new(plain).p22(s));
            prop_assert_eq!(mx, plain);
        }
        prop_assert_eq!(plain.with_det_clamp(tau), mx);
        prop_assert_eq!(mx.with_det_clamp(0.0), plain);
    }
}

#[test]
fn det_clamp_rescues_a_matrix_singular_by_rounding() {
    // A rank-one matrix plus a rounding-level residue: det is ~0 or negative by rounding.
    let v = DVec2::new(0.6, 0.8);
    let (a11, a12, a22) = (v.x * v.x, v.x * v.y, v.y * v.y);
    assert!(RoughnessMatrix::new(a11, a12, a22).is_err());
    let tau = 1e-8;
    let mx = RoughnessMatrix::new_with_det_clamp(a11, a12, a22, tau).unwrap();
    assert_eq!(mx.sqrt_det(), tau.sqrt());
    let g = Ggx::new(mx);
    for k in 0..50 {
        let t = f64::from(k) * 0.1;
        let m = DVec3::new(t.sin(), 0.3 * t.cos(), 1.0).normalize();
        let d = g.d(m);
        assert!(d.is_finite() && d >= 0.0);
        let l = g.lambda(m);
        assert!(l.is_finite() && l >= 0.0);
    }
    // A clearly indefinite matrix is refused even with a clamp.
    assert!(RoughnessMatrix::new_with_det_clamp(1.0, 2.0, 1.0, tau).is_err());
    // with_det_clamp: NaN, negative and infinite tau mean no clamp.
    let plain = RoughnessMatrix::new(1.0, 0.5, 1.0).unwrap();
    for bad in [f64::NAN, -1.0, f64::INFINITY] {
        assert_eq!(plain.with_det_clamp(bad), plain);
    }
    let _ = Vec3::ZERO;
}
