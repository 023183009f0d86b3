//! The contract of the slice API (`batch`): the chunk driver and every lane family on columns
//! of fuzzer values, against the scalar functions they vectorise.

use super::Bytes;
use super::dec::{d32, d64, with_rough};

/// The most elements decoded (then repeated, see [`check_batch`]).
const MAX_DECODED: u8 = 40;
/// The most repetitions of the decoded elements: up to `40 x 16 = 640` elements, past the
/// driver's block of 512.
const MAX_REPEAT: u8 = 16;
/// A value no batch function writes for these inputs: the columns' tail in `out` must keep it.
const SENTINEL: f64 = -12_345.0;

macro_rules! batch_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::{
            AxisAligned, Beckmann, ClampRules, Covariance, ExtentFloor, F, Footprint,
            GaussianFilteredGgx, Ggx, Ndf, NdfSampling, Vec2, Vec3, batch,
            filter::{presets, projected, proxy, rect},
        };
        use $d::f;
        use crate::math::Real;
        let b: &mut Bytes<'_> = $b;
        let rough = $d::rough(b);
        let aa = AxisAligned::new_clamped(f(b), f(b));
        let rules = match b.byte() % 4 {
            0 => ClampRules::default(),
            1 => ClampRules::NONE,
            2 => ClampRules::GDC2016,
            _ => ClampRules {
                max_extent: f(b),
                floor: ExtentFloor::Constant(f(b)),
                kappa: f(b),
                det_clamp: true,
            },
        };
        let sigma = f(b);
        let kernel = Covariance::new(f(b), f(b), f(b));
        let n0 = usize::from(b.byte() % (MAX_DECODED + 1));
        let rep = usize::from(1 + b.byte() % MAX_REPEAT);
        // Seven columns, element by element: the half vector, then the footprint's slope
        // derivatives (also read as half extents and as kernel entries below).
        let mut one: [Vec<F>; 7] = Default::default();
        for _ in 0..n0 {
            for c in &mut one {
                c.push(f(b));
            }
        }
        let cols: [Vec<F>; 7] = one.map(|c| c.repeat(rep));
        let n = n0 * rep;
        let [hx, hy, hz, ux, uy, vx, vy] = &cols;
        let fp = batch::Footprints {
            dh_u_x: ux,
            dh_u_y: uy,
            dh_v_x: vx,
            dh_v_y: vy,
        };
        let h = |i: usize| Vec3::new(hx[i], hy[i], hz[i]);
        let foot = |i: usize| {
            let (du, dv) = (Vec2::new(ux[i], uy[i]), Vec2::new(vx[i], vy[i]));
            Footprint::from_slope_derivatives(du, dv)
        };
        let sentinel = F::from_f64(SENTINEL);
        let mut out = vec![sentinel; n + 3];
        // Runs one batch function, then checks the length rule and each element against the
        // scalar function: bit for bit where `zero` is `None`; else NaN-free where the scalar
        // value is, and within `zero` of `0` where the scalar value is `0` (the documented
        // zeros of the densities, below the horizon and for NaN input: `0`; Beckmann's
        // `Lambda`, within its absolute bound `L (1 + Lambda)` of it: `L`).
        let mut check = |what: &str,
                         zero: Option<f64>,
                         run: &mut dyn FnMut(&mut [F]) -> usize,
                         scalar: &dyn Fn(usize) -> F| {
            out.fill(sentinel);
            let written = run(&mut out);
            assert_eq!(written, n, "{what}: wrote {written} of {n}");
            assert!(
                out[n..].iter().all(|&v| v.to_bits() == sentinel.to_bits()),
                "{what}: wrote past the columns"
            );
            for (i, &g) in out[..n].iter().enumerate() {
                let s = scalar(i);
                if let Some(z) = zero {
                    assert!(!g.is_nan() || s.is_nan(), "{what} [{i}]: batch NaN, scalar {s:e}");
                    if s == 0.0 {
                        assert!(
                            g.to_f64().abs() <= z,
                            "{what} [{i}]: batch {g:e} where the scalar is 0"
                        );
                    }
                } else {
                    assert!(
                        g.to_bits() == s.to_bits(),
                        "{what} [{i}]: batch {g:e}, scalar {s:e}"
                    );
                }
            }
        };
        const WIDE: bool = F::MANTISSA_DIGITS > 24;
        with_rough!($d, rough, r => {
            check("ggx_d", None, &mut |o| batch::ggx_d(&r, hx, hy, hz, o), &|i| {
                Ggx::new(r).d(h(i))
            });
            check("ggx_lambda", None, &mut |o| batch::ggx_lambda(&r, hx, hy, hz, o), &|i| {
                Ggx::new(r).lambda(h(i))
            });
            check("beckmann_d", Some(0.0), &mut |o| batch::beckmann_d(&r, hx, hy, hz, o), &|i| {
                Beckmann::new(r).d(h(i))
            });
            check(
                "ggx_d_filtered",
                if WIDE { None } else { Some(0.0) },
                &mut |o| batch::ggx_d_filtered(&r, &rules, sigma, hx, hy, hz, fp, o),
                &|i| Ggx::new(rules.filter_gaussian(r, foot(i), sigma)).d(h(i)),
            );
            check(
                "beckmann_d_filtered",
                Some(0.0),
                &mut |o| batch::beckmann_d_filtered(&r, &rules, sigma, hx, hy, hz, fp, o),
                &|i| Beckmann::new(rules.filter_gaussian(r, foot(i), sigma)).d(h(i)),
            );
            check(
                "ggx_d_filtered_projected",
                None,
                &mut |o| batch::ggx_d_filtered_projected(&r, &rules, sigma, hx, hy, hz, fp, o),
                &|i| Ggx::new(rules.filter_projected(r, foot(i), sigma)).d(h(i)),
            );
            check(
                "ggx_d_filtered_exact",
                None,
                &mut |o| batch::ggx_d_filtered_exact(&r, &rules, sigma, hx, hy, hz, fp, o),
                &|i| {
                    let k = rules.kernel(rules.footprint(foot(i)).covariance(sigma));
                    GaussianFilteredGgx::new(r, k).d(h(i))
                },
            );
            let kernels = batch::Covariances {
                s11: ux,
                s12: uy,
                s22: vx,
            };
            check(
                "ggx_d_projected",
                None,
                &mut |o| batch::ggx_d_projected(&r, kernels, hx, hy, hz, o),
                &|i| Ggx::new(projected(r, Covariance::new(ux[i], uy[i], vx[i]))).d(h(i)),
            );
            // The pdfs: `m` the half-vector columns, `wo` three of the footprint's.
            let (m, wo) = (
                batch::Vec3s { x: hx, y: hy, z: hz },
                batch::Vec3s { x: ux, y: uy, z: vx },
            );
            let w = |i: usize| Vec3::new(ux[i], uy[i], vx[i]);
            let (ggx, beckmann) = (Ggx::new(r), Beckmann::new(r));
            check("ggx_normal_pdf", None, &mut |o| batch::ggx_normal_pdf(&r, hx, hy, hz, o), &|i| {
                ggx.normal_pdf(h(i))
            });
            check(
                "ggx_visible_normal_pdf",
                None,
                &mut |o| batch::ggx_visible_normal_pdf(&r, wo, m, o),
                &|i| ggx.visible_normal_pdf(w(i), h(i)),
            );
            check(
                "ggx_reflection_pdf_from_normal",
                None,
                &mut |o| batch::ggx_reflection_pdf_from_normal(&r, wo, m, o),
                &|i| ggx.reflection_pdf_from_normal(w(i), h(i)),
            );
            check(
                "beckmann_normal_pdf",
                Some(0.0),
                &mut |o| batch::beckmann_normal_pdf(&r, hx, hy, hz, o),
                &|i| beckmann.normal_pdf(h(i)),
            );
            check(
                "beckmann_visible_normal_pdf",
                Some(0.0),
                &mut |o| batch::beckmann_visible_normal_pdf(&r, wo, m, o),
                &|i| beckmann.visible_normal_pdf(w(i), h(i)),
            );
            check(
                "beckmann_reflection_pdf_from_normal",
                Some(0.0),
                &mut |o| batch::beckmann_reflection_pdf_from_normal(&r, wo, m, o),
                &|i| beckmann.reflection_pdf_from_normal(w(i), h(i)),
            );
            check(
                "beckmann_lambda",
                Some(if WIDE { 1.9e-8 } else { 2.1e-7 }),
                &mut |o| batch::beckmann_lambda(&r, hx, hy, hz, o),
                &|i| beckmann.lambda(h(i)),
            );
            // G2 with the footprint's columns as the second direction and the half vector as
            // the micronormal too.
            let wi = batch::Vec3s { x: vy, y: ux, z: uy };
            let v = |i: usize| Vec3::new(vy[i], ux[i], uy[i]);
            check("ggx_g2", None, &mut |o| batch::ggx_g2(&r, wi, wo, m, o), &|i| {
                ggx.g2(v(i), w(i), h(i))
            });
            check(
                "beckmann_g2",
                Some(0.0),
                &mut |o| batch::beckmann_g2(&r, wi, wo, m, o),
                &|i| beckmann.g2(v(i), w(i), h(i)),
            );
            let lobe = GaussianFilteredGgx::new(r, kernel);
            check(
                "gaussian_filtered_ggx_d",
                None,
                &mut |o| batch::gaussian_filtered_ggx_d(&lobe, hx, hy, hz, o),
                &|i| lobe.d(h(i)),
            );
        });
        // The deferred presets: roughness from the half vector's `x`, the differences from
        // the other six columns.
        let (du, dv) = (
            batch::Vec3s { x: hy, y: hz, z: ux },
            batch::Vec3s { x: uy, y: vx, z: vy },
        );
        for (name, conv) in presets::ALL {
            let exact = conv.exponent == 1.0;
            check(
                name,
                if exact { None } else { Some(0.0) },
                &mut |o| batch::deferred_filter(&conv, hx, du, dv, o),
                &|i| {
                    let (a, b) = (Vec3::new(hy[i], hz[i], ux[i]), Vec3::new(uy[i], vx[i], vy[i]));
                    conv.filter(hx[i], a, b).alpha()
                },
            );
        }
        check(
            "d_rect",
            Some(0.0),
            &mut |o| batch::d_rect(&aa, hx, hy, hz, ux, vy, o),
            &|i| rect::d_rect(aa, h(i), Vec2::new(ux[i], vy[i])),
        );
        // The rules' clamped rectangle of element `i` (the box filter's and the proxy's).
        let half = |i: usize| rules.rect(foot(i).bounding_rect(), aa.alpha()).half_extent;
        check(
            "d_rect_filtered",
            Some(0.0),
            &mut |o| batch::d_rect_filtered(&aa, &rules, hx, hy, hz, fp, o),
            &|i| rect::d_rect(aa, h(i), half(i)),
        );
        check(
            "ggx_d_filtered_proxy",
            Some(0.0),
            &mut |o| batch::ggx_d_filtered_proxy(&aa, &rules, hx, hy, hz, fp, o),
            &|i| Ggx::new(proxy::proxy(aa, half(i))).d(h(i)),
        );
    }};
}

/// The contract of the slice API (`batch`) on fuzzer bytes, in both precisions: a roughness
/// in every form, an axis-aligned one, clamp rules (the presets, or raw extent, floor and
/// `kappa`), a pixel `sigma`, a kernel, and up to 40 elements of seven columns (half vector,
/// footprint), repeated up to 16 times so that the driver's blocks and its sorted second
/// lanes see runs longer than a block. For `D`, `Lambda` and `G2`, the pdfs, the deferred
/// presets, the filtered routes, the projected and exact Gaussian filters, the box filter and
/// the proxy: every function writes exactly the common length and nothing past it; the
/// functions documented bit for bit equal the scalar function element by element (GGX `D`,
/// `Lambda`, `G2` and pdfs, the presets of exponent 1, the projected routes, the exact
/// Gaussian filter, TK19 GGX in `f64`); the others are NaN-free where the scalar function is
/// and `0` where it is `0`. Panics on a violation.
pub fn check_batch(data: &[u8]) {
    batch_prec!(d64, f64, &mut Bytes::new(data));
    batch_prec!(d32, f32, &mut Bytes::new(data));
}
