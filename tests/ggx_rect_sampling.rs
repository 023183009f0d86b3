//! Sampling of the box-filtered GGX lobe (`sampling::rect::sample_normal_rect`,
//! `sampling::rect::sample_visible_normal_rect`) against its own pdfs (`normal_pdf_rect` = `d_rect m_z`,
//! `visible_normal_pdf_rect` = `G1 max(0, wo.m) d_rect / wo_z` with `G1 = 1 / (1 + lambda_rect)`)
//! by the crate's chi-square harness (`tests/common/chi2.rs`, from `tests/sampling_chi2.rs`):
//! 40 000 samples, 40 x 40 cells of the whitened `(cos theta, phi)` grid, pooled below 5
//! expected, Sidak-corrected for the 29 tests of this file at a suite false-alarm rate of 1%.
//! The grid is whitened with the lobe's width per axis, `sqrt(alpha_i^2 + H_i^2)` (any fixed
//! partition is a valid test; this one scales with the lobe).
//!
//! Each test also checks that the cell integrals of the pdf add up to 1 within 1e-5: for the
//! visible pdf that is the Smith normalisation of `d_rect` with `lambda_rect`,
//! `integral G1(wo, m) max(0, wo.m) D(m) dm = wo_z`.

#[path = "common/chi2.rs"]
mod chi2;
mod common;

use chi2::{ALPHA_SUITE, Radial, chi2_test};
use filtered_ndf::f64::{AxisAligned, NdfSampling as _, filter::rect, sampling};
use filtered_ndf::{f32 as s, f64 as d};
use glam::{DVec2, DVec3, Vec2, Vec3};

const N_TESTS: usize = 29;

/// `(alpha_x, alpha_y, H_x, H_y)`: a box about the lobe's size, a 300:1 box, a box a hundred
/// lobe widths wide, one zero half extent, a rough lobe.
const LOBES: [(f64, f64, f64, f64); 5] = [
    (0.1, 0.05, 0.05, 0.02),
    (0.1, 0.1, 0.3, 0.001),
    (1e-3, 1e-3, 0.01, 0.003),
    (0.3, 0.15, 0.0, 0.2),
    (0.8, 0.8, 0.2, 0.4),
];
const VIEW_DEG: [f64; 4] = [0.0, 30.0, 80.0, 89.9];

fn view(theta_deg: f64, phi: f64) -> DVec3 {
    let t = theta_deg.to_radians();
    DVec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// The grid's roughness: the lobe's width per axis.
fn grid(l: (f64, f64, f64, f64)) -> AxisAligned {
    AxisAligned::new(l.0.hypot(l.2), l.1.hypot(l.3)).unwrap()
}

fn alpha_test() -> f64 {
    1.0 - (1.0 - ALPHA_SUITE).powf(1.0 / N_TESTS as f64)
}

/// Runs one test and records a failure (p-value or mass).
fn check(label: String, out: chi2::Outcome, failures: &mut Vec<String>) {
    println!(
        "| {label} | {:>8.1} | {:>4} | {:>8.4} | mass - 1 {:.1e} |",
        out.chi2,
        out.dof,
        out.p,
        out.expected_total - 1.0
    );
    if (out.expected_total - 1.0).abs() > 1e-5 {
        failures.push(format!("{label}: mass {}", out.expected_total));
    }
    if out.p.is_nan() || out.p <= alpha_test() {
        failures.push(format!("{label}: p = {}", out.p));
    }
}

/// Four uniform numbers from the harness's two: the harness draws `u` per sample; the box
/// offset takes a second, independent pair from a stream of its own.
struct Box2(std::cell::RefCell<filtered_ndf::testing::rng::SplitMix64>);

impl Box2 {
    fn new(seed: u64) -> Self {
        Self(std::cell::RefCell::new(
            filtered_ndf::testing::rng::SplitMix64(seed ^ 0xb0c5),
        ))
    }
    fn next(&self) -> DVec2 {
        let mut r = self.0.borrow_mut();
        DVec2::new(r.uniform(), r.uniform())
    }
}

#[test]
fn chi2_d_cos_and_visible_normals() {
    let mut failures = Vec::new();
    let mut seed = 7000u64;
    for l in LOBES {
        let r = AxisAligned::new(l.0, l.1).unwrap();
        let h = DVec2::new(l.2, l.3);
        let g = grid(l);
        seed += 1;
        let b = Box2::new(seed);
        let out = chi2_test(
            &g,
            Radial::Ggx,
            seed,
            |u| sampling::rect::sample_normal_rect(r, h, u, b.next()),
            |m| sampling::rect::normal_pdf_rect(r, h, m),
        );
        check(
            format!("alpha ({}, {}) H ({}, {}) D cos", l.0, l.1, l.2, l.3),
            out,
            &mut failures,
        );
        for deg in VIEW_DEG {
            seed += 1;
            let b = Box2::new(seed);
            let wo = view(deg, 1.0);
            let out = chi2_test(
                &g,
                Radial::Ggx,
                seed,
                |u| {
                    let m =
                        sampling::rect::sample_visible_normal_rect(r, h, wo, u, b.next()).unwrap();
                    assert!(wo.dot(m) > 0.0, "{m} faces away from {wo}");
                    m
                },
                |m| sampling::rect::visible_normal_pdf_rect(r, h, wo, m),
            );
            check(
                format!("alpha ({}, {}) H ({}, {}) vis {deg:>4}", l.0, l.1, l.2, l.3),
                out,
                &mut failures,
            );
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn chi2_view_along_an_axis() {
    // u_y = 0: the y offset does not enter the weight and is drawn uniformly.
    let mut failures = Vec::new();
    for (k, l) in [LOBES[0], LOBES[2]].into_iter().enumerate() {
        let r = AxisAligned::new(l.0, l.1).unwrap();
        let h = DVec2::new(l.2, l.3);
        let seed = 8000 + k as u64;
        let b = Box2::new(seed);
        let wo = view(60.0, 0.0);
        let out = chi2_test(
            &grid(l),
            Radial::Ggx,
            seed,
            |u| sampling::rect::sample_visible_normal_rect(r, h, wo, u, b.next()).unwrap(),
            |m| sampling::rect::visible_normal_pdf_rect(r, h, wo, m),
        );
        check(
            format!(
                "alpha ({}, {}) H ({}, {}) vis 60 along x",
                l.0, l.1, l.2, l.3
            ),
            out,
            &mut failures,
        );
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn chi2_f32_samplers_against_the_f64_pdf() {
    // The f32 samplers (computing in f64 internally, rounding the normal) with f32-rounded
    // uniform numbers, against the f64 pdf of the same (f32-representable) lobe.
    let mut failures = Vec::new();
    let l = LOBES[0];
    let (a, bb, hx, hy) = (l.0 as f32, l.1 as f32, l.2 as f32, l.3 as f32);
    let r32 = s::AxisAligned::new(a, bb).unwrap();
    let r64 = d::AxisAligned::new(a as f64, bb as f64).unwrap();
    let (h32, h64) = (Vec2::new(hx, hy), DVec2::new(hx as f64, hy as f64));
    let f = |u: DVec2| u.as_vec2();
    let grid = grid((a as f64, bb as f64, hx as f64, hy as f64));
    let b = Box2::new(9000);
    let out = chi2_test(
        &grid,
        Radial::Ggx,
        9000,
        |u| s::sampling::rect::sample_normal_rect(r32, h32, f(u), f(b.next())).as_dvec3(),
        |m| sampling::rect::normal_pdf_rect(r64, h64, m),
    );
    check("f32 D cos".into(), out, &mut failures);
    let wo = view(80.0, 1.0);
    let wo32 = wo.as_vec3();
    let wo64 = wo32.as_dvec3();
    let b = Box2::new(9001);
    let out = chi2_test(
        &grid,
        Radial::Ggx,
        9001,
        |u| {
            s::sampling::rect::sample_visible_normal_rect(r32, h32, wo32, f(u), f(b.next()))
                .unwrap()
                .as_dvec3()
        },
        |m| sampling::rect::visible_normal_pdf_rect(r64, h64, wo64, m),
    );
    check("f32 vis 80".into(), out, &mut failures);
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn zero_extent_is_ggx_bit_for_bit() {
    use filtered_ndf::f32::NdfSampling as _;
    let r = s::AxisAligned::new(0.2, 0.07).unwrap();
    let ggx = s::Ggx::new(r);
    let wo = Vec3::new(0.3, -0.5, 0.6);
    for (ux, uy) in [(0.1f32, 0.9f32), (0.5, 0.5), (0.999, 0.01)] {
        let u = Vec2::new(ux, uy);
        for h in [Vec2::ZERO, Vec2::new(f32::NAN, -0.0)] {
            assert_eq!(
                s::sampling::rect::sample_normal_rect(r, h, u, Vec2::new(0.3, 0.8)),
                ggx.sample_normal(u)
            );
            assert_eq!(
                s::sampling::rect::sample_visible_normal_rect(r, h, wo, u, Vec2::new(0.3, 0.8)),
                ggx.sample_visible_normal(wo, u)
            );
        }
    }
}

#[test]
fn pdfs_are_the_lobe() {
    // normal_pdf_rect = d_rect m_z and visible_normal_pdf_rect = G1 max(0, wo.m) d_rect / wo_z
    // with G1 = 1 / (1 + lambda_rect): the same numbers (a few ulps of the division order).
    let r = d::AxisAligned::new(0.1, 0.05).unwrap();
    let h = DVec2::new(0.05, 0.02);
    let wo = view(50.0, 2.0);
    let lam = rect::lambda_rect(r, h, wo);
    for m in [
        DVec3::new(0.1, -0.2, 1.0),
        DVec3::new(-0.5, 0.1, 0.7),
        DVec3::Z,
    ] {
        let m = m.normalize();
        let dd = rect::d_rect(r, m, h);
        assert_eq!(sampling::rect::normal_pdf_rect(r, h, m), dd * m.z);
        let want = wo.dot(m).max(0.0) * dd / (wo.z * (1.0 + lam));
        let got = sampling::rect::visible_normal_pdf_rect(r, h, wo, m);
        assert!(
            (got - want).abs() <= 4.0 * f64::EPSILON * want,
            "{got} vs {want}"
        );
    }
    // Below the horizon / facing away / non-finite: 0.
    assert_eq!(sampling::rect::normal_pdf_rect(r, h, -DVec3::Z), 0.0);
    assert_eq!(
        sampling::rect::visible_normal_pdf_rect(r, h, -DVec3::Z, DVec3::Z),
        0.0
    );
    assert_eq!(
        sampling::rect::visible_normal_pdf_rect(
            r,
            h,
            DVec3::new(1.0, 0.0, 0.01),
            DVec3::new(-0.9, 0.0, 0.1).normalize()
        ),
        0.0
    );
    assert_eq!(
        sampling::rect::visible_normal_pdf_rect(r, h, DVec3::NAN, DVec3::Z),
        0.0
    );
    assert!(
        sampling::rect::sample_visible_normal_rect(
            r,
            h,
            DVec3::new(0.3, 0.0, 0.0),
            DVec2::ZERO,
            DVec2::ZERO
        )
        .is_none()
    );
    assert!(
        sampling::rect::sample_visible_normal_rect(r, h, DVec3::NAN, DVec2::ZERO, DVec2::ZERO)
            .is_none()
    );
    // A view within 1e-300 of the normal (f64): a sample, no overflow.
    for wo in [
        DVec3::new(1e-300, 0.0, 1.0),
        DVec3::new(1e-300, -1e-300, 1e-10),
    ] {
        let m = sampling::rect::sample_visible_normal_rect(
            r,
            h,
            wo,
            DVec2::splat(0.3),
            DVec2::splat(0.7),
        );
        let m = m.expect("a sample");
        assert!(m.is_finite() && m.z > 0.0 && wo.dot(m) > 0.0, "{m}");
    }
    // The GGX of zero extent: the same pdfs as GGX's.
    let ggx = d::Ggx::new(r);
    let m = DVec3::new(0.1, 0.2, 1.0).normalize();
    assert_eq!(
        sampling::rect::normal_pdf_rect(r, DVec2::ZERO, m),
        ggx.normal_pdf(m)
    );
}

mod contract {
    use super::*;
    use proptest::prelude::*;

    fn any_f32() -> impl Strategy<Value = f32> {
        prop_oneof![
            4 => -2.0f32..2.0,
            1 => any::<f32>().prop_filter("finite", |x| x.is_finite()),
            1 => Just(0.0f32),
        ]
    }

    fn unit() -> impl Strategy<Value = f32> {
        prop_oneof![6 => 0.0f32..1.0, 1 => Just(0.0f32), 1 => Just(1.0f32), 1 => any::<f32>()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn samples_are_unit_upper_and_visible(
            ax in 1e-4f32..1.0, ay in 1e-4f32..1.0, hx in any_f32(), hy in any_f32(),
            wx in any_f32(), wy in any_f32(), wz in 1e-30f32..2.0,
            u0 in unit(), u1 in unit(), u2 in unit(), u3 in unit(),
        ) {
            let r = s::AxisAligned::new(ax, ay).unwrap();
            let h = Vec2::new(hx, hy);
            let (u, ub) = (Vec2::new(u0, u1), Vec2::new(u2, u3));
            let m = s::sampling::rect::sample_normal_rect(r, h, u, ub);
            prop_assert!(m.is_finite() && m.z > 0.0 && (m.length() - 1.0).abs() < 1e-5, "{m}");
            let wo = Vec3::new(wx, wy, wz);
            if let Some(m) = s::sampling::rect::sample_visible_normal_rect(r, h, wo, u, ub) {
                prop_assert!(m.is_finite() && m.z > 0.0 && (m.length() - 1.0).abs() < 1e-5, "{m}");
                prop_assert!(wo.dot(m) > 0.0 || wo.normalize().dot(m) > 0.0, "{wo} {m}");
            }
            let r64 = d::AxisAligned::new(ax as f64, ay as f64).unwrap();
            let wo64 = wo.as_dvec3();
            let m = sampling::rect::sample_visible_normal_rect(r64, h.as_dvec2(), wo64, u.as_dvec2(), ub.as_dvec2());
            prop_assert!(m.is_some(), "no f64 sample for {wo64}");
            let m = m.unwrap();
            prop_assert!(m.is_finite() && m.z > 0.0 && wo64.dot(m) > 0.0, "{m}");
        }

        #[test]
        fn f64_extremes(
            hx in any_f64(), hy in any_f64(), wx in any_f64(), wy in any_f64(),
            wz in (-300.0f64..300.0).prop_map(|e| 10f64.powf(e)),
            u0 in 0.0f64..1.0, u1 in 0.0f64..1.0, u2 in 0.0f64..1.0, u3 in 0.0f64..1.0,
        ) {
            let r = d::AxisAligned::new(0.05, 2e-3).unwrap();
            let (h, wo) = (DVec2::new(hx, hy), DVec3::new(wx, wy, wz));
            let (u, ub) = (DVec2::new(u0, u1), DVec2::new(u2, u3));
            let m = sampling::rect::sample_normal_rect(r, h, u, ub);
            prop_assert!(m.is_finite() && m.z > 0.0 && (m.length() - 1.0).abs() < 1e-12, "{m}");
            // As GGX's sampler (`NdfSampling`'s contract): `None` only where the view is within
            // the float range of the horizon, `wo_z / |wo|` below about 1e-300.
            let wn = wo / wo.abs().max_element();
            match sampling::rect::sample_visible_normal_rect(r, h, wo, u, ub) {
                Some(m) => prop_assert!(m.is_finite() && m.z > 0.0 && wn.dot(m) > 0.0, "{wo} {m}"),
                None => prop_assert!(wn.z < 1e-290, "no sample for {wo}"),
            }
            let l = rect::lambda_rect(r, h, wo);
            prop_assert!(!l.is_nan() && l >= 0.0, "{l}");
        }
    }

    fn any_f64() -> impl Strategy<Value = f64> {
        prop_oneof![
            3 => -2.0f64..2.0,
            2 => (-300.0f64..300.0, any::<bool>())
                .prop_map(|(e, neg)| if neg { -10f64.powf(e) } else { 10f64.powf(e) }),
            1 => Just(0.0f64),
        ]
    }
}
