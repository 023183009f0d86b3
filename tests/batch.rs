//! The slice API (`batch`) against the scalar functions it vectorises, on seeded random and
//! adversarial inputs (NaN, infinities, zeros, huge and tiny values, back-facing directions):
//! the filtered functions against the scalar clamped route `ClampRules::filter_gaussian` under
//! several rule sets with footprints that trigger each clamp, the common-prefix rule for
//! mismatched lengths, and NaN-free output.
//!
//! - GGX (`D`, `Lambda`, `G2`; TK19 filtered `D` in `f64`) and the box filter's
//!   Gauss-Legendre elements in `f64`: **bit for bit** (`to_bits`). Their lanes evaluate the
//!   scalar path's own formula with its checks as selects; a difference (e.g. a
//!   reassociation) is a bug. The box filter's closed-form elements (a long side) differ by
//!   the polynomial `atan2`, and in `f32` its Gauss-Legendre elements run in `f32` lanes:
//!   both checked against their bounds in `tests/batch_bounds.rs`. TK19 filtered `D` in `f32`:
//!   bit for bit with the scalar route where its second lane takes the element, else within
//!   the narrow lane's bound of the `f64` pipeline (`filtered_ggx_close`).
//! - Beckmann `D` (unfiltered and filtered): the lane evaluates the scalar path's exponent
//!   `x` and factor `k = n / pi` bit for bit and replaces libm's `exp(-x) k` by the polynomial
//!   exponential `exp_neg_times` (relative `E = 2.5e-7` in `f32`, `1.5e-14` in `f64`, plus one
//!   rounding). Against the scalar path of the same precision: `E + 2 eps` relative (the
//!   lane's rounding of `p k`, libm's `exp` within one ulp and the scalar's product), plus
//!   `x eps` where the scalar path takes its far-tail branch (`x` past `-ln F::MIN_POSITIVE`:
//!   `exp(-(x - ln k))`, whose rounded argument costs up to `(x + |ln k|) eps / 2 <= x eps`);
//!   results below `F::MIN_POSITIVE` absolutely (the lane flushes them to `0`). In `f32`
//!   also against the `f64` scalar path on the same rounded inputs: `(11 + 4 x) eps`, the
//!   scalar `f32` bound of `tests/ndf_precision.rs` (`(8 + 4 x) eps`) plus the polynomial's
//!   `2.5e-7 <= 2.1 eps` and its rounding. The filtered `D` in `f32` evaluates `x` and the
//!   norm in `f32` (`RoughnessMatrix::exponent_and_norm_narrow`: within `30.7 u` and `16 u`
//!   of the exact forms of the same entries, against the scalar path's `x u` and `u`): `(16 x
//!   + 11) eps` more (`batch` module docs).
//! - The deferred presets (`deferred_filter`): bit for bit for `exponent = 1`; with a power,
//!   `(2 d + 1) eps` relative, `d` the lane power's error plus libm's (test docs).
//! - Beckmann `Lambda`: the shared `erfc` fit (`beckmann_lambda_fast`), absolute
//!   `L (1 + Lambda)`, `L = 2.1e-7` (`f32`) / `1.9e-8` (`f64`), plus the scalar path's own
//!   error against `f64` (`(8 + 4 a^2) eps Lambda`, `tests/ndf_precision.rs`) and one rounding
//!   of `a` amplified alike. `G2 = 1 / (1 + Lambda_i + Lambda_o)` then within
//!   `2 L + 3 eps` relative plus the same amplified terms over `1 + Lambda_i + Lambda_o`.

use filtered_ndf::f64 as d;
use filtered_ndf::testing::rng::SplitMix64 as Rng;

#[path = "common/rect_edges.rs"]
mod rect_edges;

/// Adversarial scalars mixed into every input column.
const SPECIAL: [f64; 12] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    1e30,
    -1e30,
    1e-30,
    -1e-30,
    1.0,
    -1.0,
    1e-3,
];

/// `n` values: mostly realistic (unit-ish directions, small slopes), one in five special.
fn column(n: usize, seed: u64, lo: f64, hi: f64) -> Vec<f64> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            if rng.uniform() < 0.2 {
                SPECIAL[(rng.uniform() * SPECIAL.len() as f64) as usize]
            } else {
                rng.range(lo, hi)
            }
        })
        .collect()
}

/// `n` footprint components over six decades, `+/-[1e-4, 10]` log-uniform (so that the
/// footprint extent clamp `lambda = 1` and the kernel clamp `kappa` both act on a good share
/// of the elements), one in five special.
fn wide_column(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            if rng.uniform() < 0.2 {
                SPECIAL[(rng.uniform() * SPECIAL.len() as f64) as usize]
            } else {
                let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
                sign * rng.log_uniform(1e-4, 10.0)
            }
        })
        .collect()
}

macro_rules! suite {
    ($modname:ident, $prec:ident, $t:ty) => {
        mod $modname {
            use super::*;
            use filtered_ndf::$prec::{
                AxisAligned, Beckmann, ClampRules, ExtentFloor, Footprint, GaussianFilteredGgx,
                Ggx, Isotropic, Ndf, Roughness, RoughnessMatrix, Vec2, Vec3, batch, filter::rect,
            };

            const N: usize = 2000;

            struct Cols {
                x: Vec<$t>,
                y: Vec<$t>,
                z: Vec<$t>,
                ux: Vec<$t>,
                uy: Vec<$t>,
                vx: Vec<$t>,
                vy: Vec<$t>,
                hx: Vec<$t>,
                hy: Vec<$t>,
            }

            fn cols(seed: u64) -> Cols {
                let c = |s: u64, lo: f64, hi: f64| -> Vec<$t> {
                    column(N, seed ^ s, lo, hi)
                        .into_iter()
                        .map(|v| v as $t)
                        .collect()
                };
                let w = |s: u64| -> Vec<$t> {
                    wide_column(N, seed ^ s)
                        .into_iter()
                        .map(|v| v as $t)
                        .collect()
                };
                Cols {
                    x: c(1, -0.7, 0.7),
                    y: c(2, -0.7, 0.7),
                    // Some back-facing z on purpose.
                    z: c(3, -0.2, 1.0),
                    ux: w(4),
                    uy: w(5),
                    vx: w(6),
                    vy: w(7),
                    hx: c(8, 0.0, 0.1),
                    hy: c(9, -0.1, 0.1),
                }
            }

            fn same(got: &[$t], want: impl Fn(usize) -> $t, what: &str) {
                for (i, g) in got.iter().enumerate() {
                    let w = want(i);
                    assert_eq!(
                        g.to_bits(),
                        w.to_bits(),
                        "{what} [{i}]: batch {g} vs scalar {w}"
                    );
                    assert!(!g.is_nan(), "{what} [{i}] is NaN");
                }
            }

            const EPS: f64 = <$t>::EPSILON as f64;
            const WIDE: bool = <$t>::MANTISSA_DIGITS > 24;
            /// The polynomial exponential's relative bound (`filter::exp_poly`).
            const EXP_POLY: f64 = if WIDE { 1.5e-14 } else { 2.5e-7 };
            /// Where the scalar Beckmann `D` takes its far-tail branch (`-ln F::MIN_POSITIVE`
            /// less one binade).
            const TAIL: f64 = -(<$t>::MIN_EXP as f64) * std::f64::consts::LN_2;

            /// `|batch - scalar|` of a Beckmann `D` as a share of its bound against the scalar
            /// path of the same precision (infinite beyond the flush): `x` is the exponent both
            /// evaluate (bound in the file docs); `filtered`: a lane whose exponent and norm
            /// are computed in `f32` in `f32` (the wider bound).
            fn scalar_share(g: f64, w: f64, x: f64, filtered: bool) -> f64 {
                let err = (g - w).abs();
                if w < <$t>::MIN_POSITIVE as f64 {
                    return if err <= <$t>::MIN_POSITIVE as f64 {
                        0.0
                    } else {
                        f64::INFINITY
                    };
                }
                let tail = if x >= TAIL { x } else { 0.0 };
                // The file docs' `(16 x + 11) eps` of the narrow exponent and norm.
                let narrow = if filtered && !WIDE {
                    16.0 * x + 11.0
                } else {
                    0.0
                };
                err / w / (EXP_POLY + (2.0 + narrow + tail) * EPS)
            }

            /// Batch Beckmann `D` against the scalar path of the same precision
            /// ([`scalar_share`], unfiltered).
            fn beckmann_close(got: &[$t], want: impl Fn(usize) -> ($t, f64), what: &str) {
                let mut worst = 0.0f64;
                for (i, &g) in got.iter().enumerate() {
                    let (w, x) = want(i);
                    assert!(!g.is_nan() && g >= 0.0, "{what} [{i}]: {g}");
                    let share = scalar_share(g as f64, w as f64, x, false);
                    worst = worst.max(share);
                    assert!(
                        share <= 1.0,
                        "{what} [{i}]: batch {g} vs scalar {w} (x {x})"
                    );
                }
                println!("{what}: worst {worst:.3} of the bound");
            }

            /// [`cols`] of three seeds end to end: `3 N` elements, about three units of the
            /// box filter's sort (2048 elements).
            fn cols3(seed: u64) -> Cols {
                let k = [seed, seed ^ 0x5EED_0001, seed ^ 0x5EED_0002].map(cols);
                let cat = |f: fn(&Cols) -> &Vec<$t>| -> Vec<$t> {
                    k.iter().flat_map(|c| f(c).iter().copied()).collect()
                };
                Cols {
                    x: cat(|c| &c.x),
                    y: cat(|c| &c.y),
                    z: cat(|c| &c.z),
                    ux: cat(|c| &c.ux),
                    uy: cat(|c| &c.uy),
                    vx: cat(|c| &c.vx),
                    vy: cat(|c| &c.vy),
                    hx: cat(|c| &c.hx),
                    hy: cat(|c| &c.hy),
                }
            }

            fn h(c: &Cols, i: usize) -> Vec3 {
                Vec3::new(c.x[i], c.y[i], c.z[i])
            }

            fn fp(c: &Cols, i: usize) -> Footprint {
                Footprint::from_slope_derivatives(
                    Vec2::new(c.ux[i], c.uy[i]),
                    Vec2::new(c.vx[i], c.vy[i]),
                )
            }

            fn soa(c: &Cols) -> batch::Footprints<'_> {
                batch::Footprints {
                    dh_u_x: &c.ux,
                    dh_u_y: &c.uy,
                    dh_v_x: &c.vx,
                    dh_v_y: &c.vy,
                }
            }

            /// The roughness forms every batch kernel is tested on, for one `alpha`: isotropic,
            /// axis-aligned (3.3:1), a rotated matrix (the LDL representation), an elongated
            /// one (cond 1e8: LDL in f32, the eigenbasis in f64) and the same with the
            /// determinant clamp active (LDL built out of line in f32).
            fn forms(
                alpha: $t,
            ) -> (
                Isotropic,
                AxisAligned,
                RoughnessMatrix,
                RoughnessMatrix,
                RoughnessMatrix,
            ) {
                let a2 = alpha * alpha;
                (
                    Isotropic::new(alpha).unwrap(),
                    AxisAligned::new(alpha, alpha * 0.3).unwrap(),
                    RoughnessMatrix::new(a2, 0.3 * a2, 0.5 * a2).unwrap(),
                    RoughnessMatrix::new(a2, 0.0, a2 * 1e-8).unwrap(),
                    RoughnessMatrix::new_with_det_clamp(a2, 0.0, a2 * 1e-8, 2e-8 * a2 * a2)
                        .unwrap(),
                )
            }

            #[test]
            fn ndf_d_bit_for_bit() {
                let c = cols(0xB47C);
                let mut out = vec![0.0 as $t; N];
                for alpha in [1e-4 as $t, 0.05, 0.5, 2.0] {
                    let (iso, aa, mat, long, clamped) = forms(alpha);
                    assert_eq!(batch::ggx_d(&iso, &c.x, &c.y, &c.z, &mut out), N);
                    same(&out, |i| Ggx::new(iso).d(h(&c, i)), "ggx iso");
                    batch::ggx_d(&aa, &c.x, &c.y, &c.z, &mut out);
                    same(&out, |i| Ggx::new(aa).d(h(&c, i)), "ggx aa");
                    batch::ggx_d(&mat, &c.x, &c.y, &c.z, &mut out);
                    same(&out, |i| Ggx::new(mat).d(h(&c, i)), "ggx matrix");
                    batch::ggx_d(&long, &c.x, &c.y, &c.z, &mut out);
                    same(&out, |i| Ggx::new(long).d(h(&c, i)), "ggx long matrix");
                    batch::ggx_d(&clamped, &c.x, &c.y, &c.z, &mut out);
                    same(
                        &out,
                        |i| Ggx::new(clamped).d(h(&c, i)),
                        "ggx clamped matrix",
                    );
                    let x = |r: &dyn Fn(Vec2) -> $t, i: usize| {
                        let z = c.z[i] as f64;
                        r(Vec2::new(c.x[i], c.y[i])) as f64 / (z * z)
                    };
                    assert_eq!(batch::beckmann_d(&iso, &c.x, &c.y, &c.z, &mut out), N);
                    beckmann_close(
                        &out,
                        |i| {
                            (
                                Beckmann::new(iso).d(h(&c, i)),
                                x(&|s| iso.inv_quadratic(s), i),
                            )
                        },
                        "beckmann iso",
                    );
                    assert_eq!(batch::beckmann_d(&aa, &c.x, &c.y, &c.z, &mut out), N);
                    beckmann_close(
                        &out,
                        |i| {
                            (
                                Beckmann::new(aa).d(h(&c, i)),
                                x(&|s| aa.inv_quadratic(s), i),
                            )
                        },
                        "beckmann aa",
                    );
                    for (name, m) in [("matrix", mat), ("long", long), ("clamped", clamped)] {
                        batch::beckmann_d(&m, &c.x, &c.y, &c.z, &mut out);
                        beckmann_close(
                            &out,
                            |i| (Beckmann::new(m).d(h(&c, i)), x(&|s| m.inv_quadratic(s), i)),
                            &format!("beckmann {name}"),
                        );
                    }
                }
            }

            /// Batch filtered Beckmann: each element is the `f32` first lane's (the narrow
            /// lane) or the scalar route's matrix (the second lane, the scalar route), so it
            /// must be as [`beckmann_close`] (`filtered`) to the scalar route's `D` or, in
            /// `f32`, within the narrow lane's bound of the `f64` pipeline (`tests/batch_bounds.rs`
            /// derives it: `E + (x (15.35 + 26 k) + 8.5 + 13 k) eps`, `k = 1 / (1 - |rho|)`).
            /// `want` gives the scalar route's `(D, x)`, `want_64` the `f64` pipeline's `(D, x,
            /// k)`.
            fn filtered_beckmann_close(
                got: &[$t],
                want: impl Fn(usize) -> ($t, f64),
                want_64: impl Fn(usize) -> (f64, f64, f64),
                what: &str,
            ) {
                let mut narrow = 0;
                for (i, &g) in got.iter().enumerate() {
                    let (w, x) = want(i);
                    assert!(!g.is_nan() && g >= 0.0, "{what} [{i}]: {g}");
                    let g = g as f64;
                    let scalar_ok = scalar_share(g, w as f64, x, true) <= 1.0;
                    if scalar_ok || WIDE {
                        assert!(scalar_ok, "{what} [{i}]: batch {g} vs scalar {w} (x {x})");
                        continue;
                    }
                    let (w64, x64, k) = want_64(i);
                    let tol = EXP_POLY + (x64 * (15.35 + 26.0 * k) + 8.5 + 13.0 * k) * EPS;
                    let ok = if w64 < <$t>::MIN_POSITIVE as f64 {
                        (g - w64).abs() <= <$t>::MIN_POSITIVE as f64
                    } else {
                        (g - w64).abs() <= tol * w64
                    };
                    assert!(
                        ok,
                        "{what} [{i}]: batch {g} vs scalar {w}, f64 {w64} (x {x64}, k {k})"
                    );
                    narrow += 1;
                }
                println!("{what}: {narrow} within the narrow lane's bound only");
            }

            /// The `f64` pipeline of [`ClampRules::filter_gaussian`] and Beckmann's `D` on the
            /// footprint `f` and half vector `h` (the lobe's entries as rounded to the batch
            /// precision): `(D, x, 1 / (1 - |rho|))` of the filtered matrix.
            fn pipeline_64(
                rules: &ClampRules,
                r: AxisAligned,
                sigma: $t,
                f: Footprint,
                h: Vec3,
            ) -> (f64, f64, f64) {
                pipeline_64_of(rules, r, sigma, f, h, false)
            }

            /// [`pipeline_64`] with GGX's `D` in place of Beckmann's where `ggx`.
            fn pipeline_64_of(
                rules: &ClampRules,
                r: AxisAligned,
                sigma: $t,
                f: Footprint,
                h: Vec3,
                ggx: bool,
            ) -> (f64, f64, f64) {
                let (r11, _, r22) = RoughnessMatrix::from(r).entries();
                let r64 = d::RoughnessMatrix::new(r11 as f64, 0.0, r22 as f64).unwrap();
                let rules64 = d::ClampRules {
                    max_extent: rules.max_extent as f64,
                    floor: d::ExtentFloor::None,
                    kappa: rules.kappa as f64,
                    det_clamp: rules.det_clamp,
                };
                let f64p = d::Footprint::from_slope_derivatives(
                    glam::DVec2::new(f.dh_u.x as f64, f.dh_u.y as f64),
                    glam::DVec2::new(f.dh_v.x as f64, f.dh_v.y as f64),
                );
                let a = rules64.filter_gaussian(r64, f64p, sigma as f64);
                let w = glam::DVec3::new(h.x as f64, h.y as f64, h.z as f64);
                let (b11, b12, b22) = a.clamped_entries();
                let k = 1.0 / (1.0 - b12.abs() / (b11 * b22).sqrt());
                let x = d::Roughness::inv_quadratic(&a, glam::DVec2::new(w.x, w.y)) / (w.z * w.z);
                let dw = if ggx {
                    d::Ndf::d(&d::Ggx::new(a), w)
                } else {
                    d::Ndf::d(&d::Beckmann::new(a), w)
                };
                (dw, x, k)
            }

            /// Batch TK19 GGX (`ggx_d_filtered`) against the scalar route: bit for bit, or in
            /// `f32` within the narrow lane's bound of the `f64` pipeline (`want_64`: `(D, x,
            /// k)`; `tests/batch_bounds.rs` derives it: `((2 x / (1 + x)) (15.35 + 26 k) + 11 +
            /// 13 k) eps`, `k = 1 / (1 - |rho|)`; below `F::MIN_POSITIVE` absolute).
            fn filtered_ggx_close(
                got: &[$t],
                want: impl Fn(usize) -> $t,
                want_64: impl Fn(usize) -> (f64, f64, f64),
                what: &str,
            ) {
                let mut narrow = 0;
                for (i, &g) in got.iter().enumerate() {
                    let w = want(i);
                    assert!(!g.is_nan() && g >= 0.0, "{what} [{i}]: {g}");
                    if g.to_bits() == w.to_bits() {
                        continue;
                    }
                    assert!(!WIDE, "{what} [{i}]: batch {g} vs scalar {w}");
                    let (w64, x, k) = want_64(i);
                    let g = g as f64;
                    let tol = (2.0 * x / (1.0 + x) * (15.35 + 26.0 * k) + 11.0 + 13.0 * k) * EPS;
                    let min = <$t>::MIN_POSITIVE as f64;
                    let ok = (g - w64).abs() <= tol * w64 || (w64 < min && (g - w64).abs() <= min);
                    assert!(
                        ok,
                        "{what} [{i}]: batch {g} vs scalar {w}, f64 {w64} (x {x}, k {k})"
                    );
                    narrow += 1;
                }
                println!("{what}: {narrow} within the narrow lane's bound only");
            }

            /// The clamp sets of the test: the papers' defaults, none, the GDC 2016 listing,
            /// and a custom set with a tight extent and `kappa` and no determinant clamp.
            fn rule_sets() -> [(&'static str, ClampRules); 4] {
                [
                    ("default", ClampRules::default()),
                    ("none", ClampRules::NONE),
                    ("gdc2016", ClampRules::GDC2016),
                    (
                        "custom",
                        ClampRules {
                            max_extent: 0.05,
                            floor: ExtentFloor::None,
                            kappa: 1e-4,
                            det_clamp: false,
                        },
                    ),
                ]
            }

            #[test]
            fn filtered_equal_the_scalar_clamped_route_bit_for_bit() {
                // The batch filtered functions answer what `ClampRules::filter_gaussian`
                // (`filter_projected` for the projected one, the exact Gaussian filter of the
                // rules' kernel for the exact one) answers, element by element, for every rule set and sigma, on footprints
                // that trigger each clamp (counted below, so the coverage cannot silently
                // vanish) and on adversarial values.
                let c = cols(0xF117);
                let mut out = vec![0.0 as $t; N];
                for (name, rules) in rule_sets() {
                    let (mut extent, mut kappa) = (0, 0);
                    for i in 0..N {
                        let f = fp(&c, i);
                        let clamped = rules.footprint(f);
                        extent += usize::from(clamped != f);
                        let k = clamped.covariance(0.5);
                        kappa += usize::from(rules.kernel(k) != k.sanitized());
                    }
                    if rules.max_extent.is_finite() {
                        assert!(extent > N / 10, "{name}: extent clamp on {extent} of {N}");
                    }
                    if rules.kappa.is_finite() {
                        assert!(kappa > N / 10, "{name}: kappa clamp on {kappa} of {N}");
                    }
                    for alpha in [1e-3 as $t, 0.1, 0.8] {
                        let aa = AxisAligned::new(alpha, alpha * 2.0).unwrap();
                        for sigma in [0.5 as $t, 0.0, 3.0, <$t>::NAN] {
                            let n = batch::beckmann_d_filtered(
                                &aa,
                                &rules,
                                sigma,
                                &c.x,
                                &c.y,
                                &c.z,
                                soa(&c),
                                &mut out,
                            );
                            assert_eq!(n, N);
                            filtered_beckmann_close(
                                &out,
                                |i| {
                                    let a = rules.filter_gaussian(aa, fp(&c, i), sigma);
                                    let z = c.z[i] as f64;
                                    let x =
                                        a.inv_quadratic(Vec2::new(c.x[i], c.y[i])) as f64 / (z * z);
                                    (Beckmann::new(a).d(h(&c, i)), x)
                                },
                                |i| pipeline_64(&rules, aa, sigma, fp(&c, i), h(&c, i)),
                                &format!("filtered beckmann, {name}"),
                            );
                            batch::ggx_d_filtered(
                                &aa,
                                &rules,
                                sigma,
                                &c.x,
                                &c.y,
                                &c.z,
                                soa(&c),
                                &mut out,
                            );
                            filtered_ggx_close(
                                &out,
                                |i| {
                                    Ggx::new(rules.filter_gaussian(aa, fp(&c, i), sigma))
                                        .d(h(&c, i))
                                },
                                |i| pipeline_64_of(&rules, aa, sigma, fp(&c, i), h(&c, i), true),
                                &format!("filtered ggx, {name}"),
                            );
                            batch::ggx_d_filtered_projected(
                                &aa,
                                &rules,
                                sigma,
                                &c.x,
                                &c.y,
                                &c.z,
                                soa(&c),
                                &mut out,
                            );
                            same(
                                &out,
                                |i| {
                                    Ggx::new(rules.filter_projected(aa, fp(&c, i), sigma))
                                        .d(h(&c, i))
                                },
                                &format!("filtered ggx projected, {name}"),
                            );
                            batch::ggx_d_filtered_exact(
                                &aa,
                                &rules,
                                sigma,
                                &c.x,
                                &c.y,
                                &c.z,
                                soa(&c),
                                &mut out,
                            );
                            same(
                                &out,
                                |i| {
                                    let k =
                                        rules.kernel(rules.footprint(fp(&c, i)).covariance(sigma));
                                    GaussianFilteredGgx::new(aa, k).d(h(&c, i))
                                },
                                &format!("filtered ggx exact, {name}"),
                            );
                        }
                    }
                }
            }

            /// The filtered kernels' driver through every state of its lanes (first lane,
            /// second lane, scalar path, and back), against the scalar route: GGX bit for bit,
            /// Beckmann within `beckmann_close`'s bound (details below).
            #[test]
            fn filtered_tiers_every_path() {
                // The `f32` filtered kernels run two lanes (`lanes.rs`, `Kernel::TIERED`): the
                // first decides the rules in `f32` alone and flags what it cannot decide (a
                // rank-one kernel, whose `s12^2` is within rounding of `s11 s22`), whose
                // flagged elements are gathered and run by the second lane, and what that
                // flags by the scalar path; a block whose first lane flags more than half of it
                // sends the next blocks to the second lane first, and one whose flags survive
                // on more than half of it the next ones to the scalar path. Blocks of 512 with a
                // chosen share of rank-one footprints (`dh_v = 0`: 15 %, 90 %, none) and of
                // NaN footprints (flagged by both lanes; 3 %, or every element), the others
                // with extents to 0.95 (the kappa clamp acts in the first lane on some), in an
                // order that takes the driver through each state and back, against the scalar
                // route: GGX bit for bit, Beckmann within the bound of `beckmann_close`. (`f64`
                // runs one lane: the same driver states with the scalar path.)
                const B: usize = 512;
                // (share rank-one, share NaN) per block.
                let plan: [(f64, f64); 24] = [
                    (0.15, 0.03),
                    (0.15, 0.0),
                    (0.9, 0.0),
                    (0.15, 0.03),
                    (0.0, 0.0),
                    (0.9, 0.03),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.0, 1.0),
                    (0.15, 0.03),
                    (0.9, 0.0),
                    (0.0, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                    (0.15, 0.0),
                ];
                let n = plan.len() * B;
                let mut rng = Rng(0x71E5);
                let mut cols: [Vec<$t>; 7] = Default::default();
                for &(rank_one, nan) in &plan {
                    for _ in 0..B {
                        let (p, q) = (rng.uniform(), rng.uniform());
                        // Extent below 1 (no extent clamp); beyond kappa / 2 = 0.09 where
                        // sigma^2 s^2 = s^2 / 4 > 0.09, i.e. s > 0.6.
                        let s = rng.log_uniform(1e-3, 0.95);
                        let shear = if p < rank_one {
                            0.0
                        } else {
                            rng.range(0.05, 0.4)
                        };
                        let phi = std::f64::consts::TAU * rng.uniform();
                        let (u, v) = (
                            [s * phi.cos(), s * phi.sin()],
                            [-shear * s * phi.sin(), shear * s * phi.cos()],
                        );
                        let u0 = if q < nan { f64::NAN } else { u[0] };
                        let slope = [rng.normal() * 0.3, rng.normal() * 0.3];
                        let l = (1.0 + slope[0] * slope[0] + slope[1] * slope[1]).sqrt();
                        let vals = [-slope[0] / l, -slope[1] / l, 1.0 / l, u0, u[1], v[0], v[1]];
                        for (c, x) in cols.iter_mut().zip(vals) {
                            c.push(x as $t);
                        }
                    }
                }
                let [x, y, z, ux, uy, vx, vy] = &cols;
                let fps = batch::Footprints {
                    dh_u_x: ux,
                    dh_u_y: uy,
                    dh_v_x: vx,
                    dh_v_y: vy,
                };
                let fp = |i: usize| {
                    Footprint::from_slope_derivatives(
                        Vec2::new(ux[i], uy[i]),
                        Vec2::new(vx[i], vy[i]),
                    )
                };
                let h = |i: usize| Vec3::new(x[i], y[i], z[i]);
                let mut out = vec![0.0 as $t; n];
                for (name, rules) in [
                    ("default", ClampRules::default()),
                    ("khpl16", ClampRules::KHPL16),
                ] {
                    // The input classes are there: per block, the share of rank-one kernels
                    // (`s12^2` within `2 eps` of `s11 s22`, as the first lane tests), and some
                    // that the kappa rule clamps.
                    let mut clamped = 0;
                    for (k, &(rank_one, nan)) in plan.iter().enumerate() {
                        let singular = (k * B..(k + 1) * B)
                            .filter(|&i| {
                                let c = rules.footprint(fp(i)).covariance(0.5);
                                clamped += usize::from(rules.kernel(c) != c.sanitized());
                                c.s12 * c.s12 > c.s11 * c.s22 * (1.0 - 2.0 * <$t>::EPSILON)
                            })
                            .count() as f64;
                        let want = rank_one * (1.0 - nan) * B as f64;
                        assert!(
                            (singular - want).abs() <= 0.1 * B as f64 + 1.0,
                            "block {k}: {singular}"
                        );
                    }
                    if rules.kappa.is_finite() {
                        assert!(clamped > n / 20, "{clamped} clamped");
                    }
                    for alpha in [0.005 as $t, 0.1, 0.5] {
                        let aa = AxisAligned::new(alpha, alpha * 1.5).unwrap();
                        assert_eq!(
                            batch::ggx_d_filtered(&aa, &rules, 0.5, x, y, z, fps, &mut out),
                            n
                        );
                        filtered_ggx_close(
                            &out,
                            |i| Ggx::new(rules.filter_gaussian(aa, fp(i), 0.5)).d(h(i)),
                            |i| pipeline_64_of(&rules, aa, 0.5, fp(i), h(i), true),
                            &format!("tiers ggx {name}"),
                        );
                        assert_eq!(
                            batch::ggx_d_filtered_projected(
                                &aa, &rules, 0.5, x, y, z, fps, &mut out
                            ),
                            n
                        );
                        same(
                            &out,
                            |i| Ggx::new(rules.filter_projected(aa, fp(i), 0.5)).d(h(i)),
                            &format!("tiers ggx projected {name}"),
                        );
                        assert_eq!(
                            batch::ggx_d_filtered_exact(&aa, &rules, 0.5, x, y, z, fps, &mut out),
                            n
                        );
                        same(
                            &out,
                            |i| {
                                let k = rules.kernel(rules.footprint(fp(i)).covariance(0.5));
                                GaussianFilteredGgx::new(aa, k).d(h(i))
                            },
                            &format!("tiers ggx exact {name}"),
                        );
                        assert_eq!(
                            batch::beckmann_d_filtered(&aa, &rules, 0.5, x, y, z, fps, &mut out),
                            n
                        );
                        filtered_beckmann_close(
                            &out,
                            |i| {
                                let a = rules.filter_gaussian(aa, fp(i), 0.5);
                                let zz = z[i] as f64;
                                let e = a.inv_quadratic(Vec2::new(x[i], y[i])) as f64 / (zz * zz);
                                (Beckmann::new(a).d(h(i)), e)
                            },
                            |i| pipeline_64(&rules, aa, 0.5, fp(i), h(i)),
                            &format!("tiers beckmann {name}"),
                        );
                    }
                }
            }

            /// The front door's `Rect` route over slices (`d_rect_filtered`) is `d_rect` on the
            /// rules' rectangles (`ClampRules::rect` of each footprint's bounding rectangle,
            /// computed here by the scalar functions), bit for bit, for every rule set (the
            /// floors of `GDC2016` included), on the columns three times over (6000 elements:
            /// about three units of the sort's 2048) with adversarial footprints among them.
            #[test]
            fn rect_filtered_is_d_rect_of_the_rules_rectangles() {
                let c = cols(0x2EC8);
                let rep =
                    |v: &Vec<$t>| -> Vec<$t> { v.iter().chain(v).chain(v).copied().collect() };
                let (x, y, z) = (rep(&c.x), rep(&c.y), rep(&c.z));
                let (ux, uy, vx, vy) = (rep(&c.ux), rep(&c.uy), rep(&c.vx), rep(&c.vy));
                let n = x.len();
                let fps = batch::Footprints {
                    dh_u_x: &ux,
                    dh_u_y: &uy,
                    dh_v_x: &vx,
                    dh_v_y: &vy,
                };
                let (mut got, mut want) = (vec![0.0 as $t; n], vec![0.0 as $t; n]);
                for (name, rules) in rule_sets() {
                    for alpha in [1e-3 as $t, 0.1, 0.8] {
                        let aa = AxisAligned::new(alpha, alpha * 2.0).unwrap();
                        let half: Vec<Vec2> = (0..n)
                            .map(|i| {
                                let f = Footprint::from_slope_derivatives(
                                    Vec2::new(ux[i], uy[i]),
                                    Vec2::new(vx[i], vy[i]),
                                );
                                rules.rect(f.bounding_rect(), aa.alpha()).half_extent
                            })
                            .collect();
                        let (ex, ey): (Vec<$t>, Vec<$t>) = half.iter().map(|h| (h.x, h.y)).unzip();
                        assert_eq!(
                            batch::d_rect_filtered(&aa, &rules, &x, &y, &z, fps, &mut got),
                            n
                        );
                        batch::d_rect(&aa, &x, &y, &z, &ex, &ey, &mut want);
                        same(&got, |i| want[i], &format!("rect filtered {name} {alpha}"));
                    }
                }
            }

            /// The front door's `Proxy` route over slices (`ggx_d_filtered_proxy`), for every
            /// rule set, three roughnesses and the adversarial columns. The half extents are
            /// the scalar route's bit for bit; the lane's `alpha'` per axis is within `10 u`
            /// (`u = 2^-53`) of the exact value, the `f64` reference
            /// (`filtered_ndf::f64::filter::proxy::effective_alpha`, libm) within `8.5 u`
            /// (`batch::ggx_d_filtered_proxy`'s docs). So in `f32` the lane's rounded `alpha'`
            /// is the reference's rounded value or a neighbour, and each element is the scalar
            /// `D` of one of those nine roughness pairs, bit for bit (or the scalar route's
            /// value, where the lane flags the element); in `f64` within `143 u` of the scalar
            /// route (the docs' derivation). The lane's share is counted, so that a lane that
            /// flags everything would not pass unnoticed.
            #[test]
            fn proxy_is_the_scalar_route_of_a_neighbouring_roughness() {
                use filtered_ndf::f64::filter::proxy::effective_alpha as alpha_64;
                use filtered_ndf::$prec::filter::proxy;
                let c = cols3(0x920C);
                let n = c.x.len();
                let mut got = vec![0.0 as $t; n];
                let u = f64::EPSILON / 2.0;
                let (mut lane, mut total, mut worst) = (0usize, 0usize, 0.0f64);
                for (name, rules) in rule_sets() {
                    for alpha in [1e-3 as $t, 0.1, 0.8] {
                        let aa = AxisAligned::new(alpha, alpha * 0.3).unwrap();
                        let n_done = batch::ggx_d_filtered_proxy(
                            &aa,
                            &rules,
                            &c.x,
                            &c.y,
                            &c.z,
                            soa(&c),
                            &mut got,
                        );
                        assert_eq!(n_done, n);
                        for i in 0..n {
                            let half = rules
                                .rect(fp(&c, i).bounding_rect(), aa.alpha())
                                .half_extent;
                            let scalar = Ggx::new(proxy::proxy(aa, half)).d(h(&c, i));
                            let g = got[i];
                            assert!(!g.is_nan(), "proxy {name} {alpha} [{i}] is NaN");
                            total += 1;
                            if WIDE {
                                let diff = (g as f64 - scalar as f64).abs();
                                let bound = 143.0 * u * (scalar as f64).abs();
                                assert!(
                                    diff <= bound,
                                    "proxy {name} {alpha} [{i}]: batch {g:e}, scalar {scalar:e}"
                                );
                                if diff > 0.0 {
                                    worst = worst.max(diff / bound);
                                }
                                continue;
                            }
                            // The reference's alpha' rounded to F, and its neighbours.
                            let near = |a: $t, hh: $t| -> [$t; 3] {
                                let r = alpha_64(a as f64, hh as f64) as $t;
                                [r.next_down(), r, r.next_up()]
                            };
                            let (nx, ny) = (near(aa.alpha().x, half.x), near(aa.alpha().y, half.y));
                            let candidate = nx.iter().any(|&ax| {
                                ny.iter().any(|&ay| {
                                    let lobe = Ggx::new(AxisAligned::new_clamped(ax, ay));
                                    lobe.d(h(&c, i)).to_bits() == g.to_bits()
                                })
                            });
                            lane += usize::from(candidate);
                            assert!(
                                candidate || g.to_bits() == scalar.to_bits(),
                                "proxy {name} {alpha} [{i}]: batch {g:e}, scalar {scalar:e}, \
                                 half {half:?}"
                            );
                        }
                    }
                }
                if WIDE {
                    println!("proxy: worst {worst:.3} of the bound over {total} elements");
                } else {
                    println!("proxy: {lane} of {total} elements from the lane's roughness");
                    assert!(lane * 10 >= total * 9, "{lane} of {total}");
                }
            }

            /// Rectangles far out on one axis (`|v_c|` from `4e12` to `1e15` roughness units)
            /// with sides short against that distance (`H / L` from `0.03` to `0.2`: the
            /// 4-, 6-, 8- and 10-point tiers), where a row's nodes lie beyond the shared
            /// division's range (`q + reach^2 >= 1e25`): the scalar path divides per pair
            /// there, the lanes flag them (in `f32` the `f32` lanes flag them too: `h_z` below
            /// `1e-6`, `1 + u_c^2 + v_c^2` at or beyond `1e30`). Bit for bit with the scalar
            /// `d_rect`.
            #[test]
            fn rect_far_rows_bit_for_bit() {
                let (mut x, mut y, mut z, mut hx, mut hy) =
                    (vec![], vec![], vec![], vec![], vec![]);
                for alpha in [0.01f64, 0.1, 0.5] {
                    for big in [4e12f64, 3e13, 1e15] {
                        for ratio in [0.03f64, 0.05, 0.09, 0.15, 0.2] {
                            for small in [0.5f64, 5e-3 * big, 0.05 * big] {
                                for swap in [false, true] {
                                    // Slope `big * alpha` on one axis: `h = (0, -1, 1 / s)`.
                                    let hz = 1.0 / (big * alpha);
                                    let (far, near) = (ratio * big * alpha, small * alpha);
                                    let (h, e) = if swap {
                                        ([-1.0, 0.0, hz], (far, near))
                                    } else {
                                        ([0.0, -1.0, hz], (near, far))
                                    };
                                    x.push(h[0] as $t);
                                    y.push(h[1] as $t);
                                    z.push(h[2] as $t);
                                    hx.push(e.0 as $t);
                                    hy.push(e.1 as $t);
                                }
                            }
                        }
                    }
                }
                let n = x.len();
                let mut out = vec![0.0 as $t; n];
                for alpha in [0.01 as $t, 0.1, 0.5] {
                    let aa = AxisAligned::new(alpha, alpha).unwrap();
                    assert_eq!(batch::d_rect(&aa, &x, &y, &z, &hx, &hy, &mut out), n);
                    let mut short = 0;
                    for i in 0..n {
                        let u = rect_edges::unit_rect(
                            (alpha as f64, alpha as f64),
                            [x[i] as f64, y[i] as f64, z[i] as f64],
                            (hx[i] as f64, hy[i] as f64),
                        );
                        if !u.is_some_and(|u| u.short()) {
                            continue;
                        }
                        short += 1;
                        let h = Vec3::new(x[i], y[i], z[i]);
                        let w = rect::d_rect(aa, h, Vec2::new(hx[i], hy[i]));
                        assert_eq!(out[i].to_bits(), w.to_bits(), "[{i}]: {} vs {w}", out[i]);
                    }
                    assert!(2 * short > n, "{short} of {n} in the Gauss-Legendre tiers");
                }
            }

            /// Over [`cols3`] (`3 N` elements, across the sort's units). `f64` only: in
            /// `f32` the Gauss-Legendre elements take the `f32` lanes (`batch::rect_lane`),
            /// checked against their bound in `tests/batch_bounds.rs`
            /// (`d_rect_against_scalar_f64`), and the elements they flag by
            /// `rect_far_rows_bit_for_bit` below.
            #[test]
            fn rect_bit_for_bit() {
                if !WIDE {
                    return;
                }
                let c = cols3(0x2EC7);
                let mut out = vec![0.0 as $t; 3 * N];
                let (mut short, mut long) = (0, 0);
                for alpha in [1e-3 as $t, 0.1, 0.8] {
                    let aa = AxisAligned::new(alpha, alpha * 2.0).unwrap();
                    let n = batch::d_rect(&aa, &c.x, &c.y, &c.z, &c.hx, &c.hy, &mut out);
                    assert_eq!(n, 3 * N);
                    let a = (alpha as f64, (alpha * 2.0) as f64);
                    for (i, &g) in out.iter().enumerate() {
                        let u = rect_edges::unit_rect(
                            a,
                            [c.x[i] as f64, c.y[i] as f64, c.z[i] as f64],
                            (c.hx[i] as f64, c.hy[i] as f64),
                        );
                        assert!(!g.is_nan(), "d_rect [{i}] is NaN");
                        if u.as_ref().is_some_and(|u| !u.short()) {
                            long += usize::from(u.is_some_and(|u| u.long()));
                            continue;
                        }
                        short += 1;
                        let w = rect::d_rect(aa, h(&c, i), Vec2::new(c.hx[i], c.hy[i]));
                        assert_eq!(
                            g.to_bits(),
                            w.to_bits(),
                            "d_rect [{i}]: batch {g} vs scalar {w}"
                        );
                    }
                }
                println!("d_rect: {short} elements bit for bit, {long} with a long side");
                assert!(
                    short > 3 * N && long > 3 * N / 10,
                    "{short} short, {long} long"
                );
            }

            /// An element's result does not depend on its place in the batch (an identity),
            /// where the driver keeps every block on the first lane (realistic inputs: half
            /// vectors within two lobe widths, footprints from a twentieth to eight lobe
            /// widths, few elements flagged; a block with most elements flagged switches the
            /// next blocks' path, by design): filtered Beckmann over the columns from offset
            /// 300 equals the whole batch's results there, bit for bit. The whole batch's last,
            /// partial block (the one-loop lane) falls in whole blocks of the shifted batch (in
            /// `f32` the two-loop lane, `Kernel::STAGED`), so the two forms must agree.
            #[test]
            fn filtered_results_do_not_depend_on_the_block() {
                let mut rng = Rng(0xB10C);
                let alpha = 0.1;
                let mut col = |f: &mut dyn FnMut(&mut Rng) -> f64| -> Vec<$t> {
                    (0..N).map(|_| f(&mut rng) as $t).collect()
                };
                let sx = col(&mut |r| 2.0 * alpha * (2.0 * r.uniform() - 1.0));
                let sy = col(&mut |r| 2.0 * alpha * (2.0 * r.uniform() - 1.0));
                let fp: Vec<Vec<$t>> = (0..4)
                    .map(|_| {
                        col(&mut |r| alpha * r.log_uniform(0.05, 8.0) * (2.0 * r.uniform() - 1.0))
                    })
                    .collect();
                let (mut x, mut y, mut z) = (vec![0.0 as $t; N], vec![0.0; N], vec![0.0; N]);
                for i in 0..N {
                    let m = Vec3::new(-sx[i], -sy[i], 1.0).normalize();
                    (x[i], y[i], z[i]) = (m.x, m.y, m.z);
                }
                let aa = AxisAligned::new(alpha as $t, (1.5 * alpha) as $t).unwrap();
                let k = 300;
                let cols = |b: usize| batch::Footprints {
                    dh_u_x: &fp[0][b..],
                    dh_u_y: &fp[1][b..],
                    dh_v_x: &fp[2][b..],
                    dh_v_y: &fp[3][b..],
                };
                for (name, rules) in [
                    ("default", ClampRules::default()),
                    ("none", ClampRules::NONE),
                ] {
                    let mut whole = vec![0.0 as $t; N];
                    batch::beckmann_d_filtered(&aa, &rules, 0.5, &x, &y, &z, cols(0), &mut whole);
                    let mut part = vec![0.0 as $t; N - k];
                    let n = batch::beckmann_d_filtered(
                        &aa,
                        &rules,
                        0.5,
                        &x[k..],
                        &y[k..],
                        &z[k..],
                        cols(k),
                        &mut part,
                    );
                    assert_eq!(n, N - k);
                    for i in 0..n {
                        assert_eq!(
                            part[i].to_bits(),
                            whole[k + i].to_bits(),
                            "{name} [{}]: {} vs {}",
                            k + i,
                            part[i],
                            whole[k + i]
                        );
                    }
                }
            }

            #[test]
            fn mismatched_lengths_process_the_common_prefix() {
                let c = cols(0x1E57);
                let aa = AxisAligned::new(0.2, 0.1).unwrap();
                let sentinel = 12345.0 as $t;
                // Each slice in turn is the short one (7 elements, the others 11).
                for short in 0..4 {
                    let len = |k: usize| if k == short { 7 } else { 11 };
                    let (x, y, z) = (&c.x[..len(0)], &c.y[..len(1)], &c.z[..len(2)]);
                    // `out` is the short one (7) or longer than every input (16).
                    let mut out = vec![sentinel; if short == 3 { 7 } else { 16 }];
                    let want_n = 7;
                    let n = batch::ggx_d(&aa, x, y, z, &mut out);
                    assert_eq!(n, want_n, "short input {short}");
                    same(&out[..n], |i| Ggx::new(aa).d(h(&c, i)), "prefix");
                    assert!(out[n..].iter().all(|&v| v == sentinel), "tail untouched");
                }
                // A short `out` bounds the work; empty slices do nothing.
                let mut out = vec![sentinel; 3];
                assert_eq!(batch::beckmann_d(&aa, &c.x, &c.y, &c.z, &mut out), 3);
                assert_eq!(batch::ggx_d(&aa, &[], &c.y, &c.z, &mut out), 0);
                let mut fps = soa(&c);
                fps.dh_v_y = &c.vy[..5];
                assert_eq!(fps.len(), 5);
                let mut out = vec![sentinel; N];
                let rules = ClampRules::default();
                assert_eq!(
                    batch::ggx_d_filtered(&aa, &rules, 0.5, &c.x, &c.y, &c.z, fps, &mut out),
                    5
                );
                assert!(out[5..].iter().all(|&v| v == sentinel));
                assert_eq!(
                    batch::d_rect(&aa, &c.x, &c.y, &c.z, &c.hx[..2], &c.hy, &mut out),
                    2
                );
                let mut out = vec![sentinel; N];
                assert_eq!(
                    batch::d_rect_filtered(&aa, &rules, &c.x, &c.y, &c.z, fps, &mut out),
                    5
                );
                assert!(out[5..].iter().all(|&v| v == sentinel));
                let full = soa(&c);
                assert_eq!(
                    batch::d_rect_filtered(&aa, &rules, &c.x, &c.y, &c.z[..3], full, &mut out),
                    3
                );
                let empty = batch::Footprints {
                    dh_u_x: &[],
                    dh_u_y: &[],
                    dh_v_x: &[],
                    dh_v_y: &[],
                };
                assert!(empty.is_empty());
            }

            /// The pdfs over the adversarial columns (views `(x, y, z)`, micronormals from a
            /// second draw, both with NaN, infinities, zeros, huge and tiny values and
            /// back-facing `z`), every roughness form and the clamped matrix: GGX's bit for
            /// bit (the lane is the scalar core on the bit-for-bit `D` and `Lambda` lanes);
            /// Beckmann's `0` wherever the scalar pdf is `0` (below the horizon, back-facing,
            /// non-finite: the same checks as selects), finite and non-negative everywhere
            /// (its value bounds: `tests/batch_bounds.rs`).
            #[test]
            fn pdfs_bit_for_bit_and_adversarial() {
                use filtered_ndf::$prec::NdfSampling as _;
                let c = cols(0x9DF);
                let c2 = cols(0x9E0);
                let wo = batch::Vec3s::new(&c.x, &c.y, &c.z);
                // Mostly front-facing micronormals near the normal (`hx`, `hy` small).
                let m = batch::Vec3s::new(&c2.hx, &c2.hy, &c2.z);
                let (w, mm) = (
                    |i: usize| h(&c, i),
                    |i: usize| Vec3::new(c2.hx[i], c2.hy[i], c2.z[i]),
                );
                let mut out = vec![0.0 as $t; N];
                let mut live = 0usize;
                for alpha in [1e-4 as $t, 0.05, 0.5, 2.0] {
                    let (iso, aa, mat, _, clamped) = forms(alpha);
                    macro_rules! each {
                        ($r:expr, $name:expr) => {{
                            let r = $r;
                            let (g, b) = (Ggx::new(r), Beckmann::new(r));
                            assert_eq!(
                                batch::ggx_normal_pdf(&r, &c2.hx, &c2.hy, &c2.z, &mut out),
                                N
                            );
                            same(
                                &out,
                                |i| g.normal_pdf(mm(i)),
                                &format!("ggx normal pdf {}", $name),
                            );
                            batch::beckmann_normal_pdf(&r, &c2.hx, &c2.hy, &c2.z, &mut out);
                            for i in 0..N {
                                let want = b.normal_pdf(mm(i));
                                assert!(
                                    out[i] >= 0.0 && out[i].is_finite(),
                                    "beckmann normal pdf [{i}]"
                                );
                                if want == 0.0 {
                                    assert_eq!(out[i], 0.0, "beckmann normal pdf {} [{i}]", $name);
                                }
                            }
                            assert_eq!(batch::ggx_visible_normal_pdf(&r, wo, m, &mut out), N);
                            same(
                                &out,
                                |i| g.visible_normal_pdf(w(i), mm(i)),
                                &format!("ggx visible {}", $name),
                            );
                            live += out.iter().filter(|&&v| v > 0.0).count();
                            batch::ggx_reflection_pdf_from_normal(&r, wo, m, &mut out);
                            same(
                                &out,
                                |i| g.reflection_pdf_from_normal(w(i), mm(i)),
                                &format!("ggx reflection {}", $name),
                            );
                            for reflection in [false, true] {
                                if reflection {
                                    batch::beckmann_reflection_pdf_from_normal(&r, wo, m, &mut out);
                                } else {
                                    batch::beckmann_visible_normal_pdf(&r, wo, m, &mut out);
                                }
                                for i in 0..N {
                                    let want = if reflection {
                                        b.reflection_pdf_from_normal(w(i), mm(i))
                                    } else {
                                        b.visible_normal_pdf(w(i), mm(i))
                                    };
                                    let got = out[i];
                                    assert!(
                                        got >= 0.0 && got.is_finite(),
                                        "beckmann {} [{i}]: {got}",
                                        $name
                                    );
                                    if want == 0.0 {
                                        assert_eq!(
                                            got, 0.0,
                                            "beckmann {} reflection {reflection} [{i}]",
                                            $name
                                        );
                                    }
                                }
                            }
                        }};
                    }
                    each!(iso, "iso");
                    each!(aa, "aa");
                    each!(mat, "matrix");
                    each!(clamped, "clamped");
                }
                // The columns reach the formula, not only the zero branches.
                assert!(live > N, "{live} live elements");
            }

            /// The exact Gaussian-filtered GGX over the adversarial micronormals (wide `(x, y,
            /// z)` and near-normal `(hx, hy, z)` columns: NaN, infinities, zeros, back-facing),
            /// bit for bit, for lobes whose elements take every rule of `J`: the zero kernel
            /// (far tail everywhere), kernels from `1e-4` to `10` lobe variances (Gauss-Laguerre
            /// near the peak of the light ones, the trapezoid rule, flagged, near the peak of
            /// the heavy ones, the far tail beyond), rank-one and rotated kernels on every
            /// roughness form, and NaN and infinite kernels (sanitised).
            #[test]
            fn gaussian_filtered_ggx_bit_for_bit() {
                use filtered_ndf::$prec::Covariance;
                let c = cols(0xE6A);
                let mut out = vec![0.0 as $t; N];
                let nan = <$t>::NAN;
                for alpha in [1e-3 as $t, 0.05, 0.5] {
                    let a2 = alpha * alpha;
                    let iso = Isotropic::new(alpha).unwrap();
                    let aa = AxisAligned::new(alpha, alpha * 0.3).unwrap();
                    let mat = RoughnessMatrix::new(a2, 0.3 * a2, 0.5 * a2).unwrap();
                    let kernels = [
                        Covariance::new(0.0, 0.0, 0.0),
                        Covariance::new(1e-4 * a2, 0.0, 1e-4 * a2),
                        Covariance::new(3e-3 * a2, 1e-3 * a2, 2e-3 * a2),
                        Covariance::new(0.3 * a2, 0.0, 0.0),
                        Covariance::new(2.0 * a2, -1.5 * a2, 2.0 * a2),
                        Covariance::new(10.0 * a2, 0.0, 10.0 * a2),
                        Covariance::new(nan, 0.0, nan),
                        Covariance::new(<$t>::INFINITY, 0.0, 1.0),
                    ];
                    for (j, k) in kernels.into_iter().enumerate() {
                        let lobes = [
                            ("iso", GaussianFilteredGgx::new(iso, k)),
                            ("aa", GaussianFilteredGgx::new(aa, k)),
                            ("matrix", GaussianFilteredGgx::new(mat, k)),
                        ];
                        for (name, lobe) in lobes {
                            assert_eq!(
                                batch::gaussian_filtered_ggx_d(&lobe, &c.x, &c.y, &c.z, &mut out),
                                N
                            );
                            same(
                                &out,
                                |i| lobe.d(h(&c, i)),
                                &format!("exact {name} {alpha} kernel {j} wide"),
                            );
                            batch::gaussian_filtered_ggx_d(&lobe, &c.hx, &c.hy, &c.z, &mut out);
                            same(
                                &out,
                                |i| lobe.d(Vec3::new(c.hx[i], c.hy[i], c.z[i])),
                                &format!("exact {name} {alpha} kernel {j} near"),
                            );
                        }
                    }
                }
            }

            /// The exact Gaussian filter's two lanes (`batch/exact.rs`): the far tail and
            /// Gauss-Laguerre, the trapezoid rule's lane for what the first flags, and where the
            /// first lane flagged most of a block, the next blocks sorted between the two
            /// (`lanes.rs`, `split_pass`) until one is mostly first-lane again. A lobe whose
            /// kernel is as wide as it (`2 l1 = 1`: the trapezoid rule where `1 + q < 56.5`),
            /// blocks of 512 with a chosen share of micronormals near the peak (slopes within
            /// 3 alpha, `q <= 9`: the trapezoid rule) against far ones (20 to 100 alpha:
            /// Gauss-Laguerre or the far tail), some NaN (flagged by every lane), in an order that
            /// takes the driver through each state and back; bit for bit against the scalar `D`,
            /// on every instruction set the tests run at (`.ci/run`).
            #[test]
            fn gaussian_filtered_ggx_tiers_every_path() {
                use filtered_ndf::$prec::Covariance;
                const B: usize = 512;
                // (share near the peak, share NaN) per block.
                let plan: [(f64, f64); 14] = [
                    (0.15, 0.0),
                    (0.9, 0.03),
                    (0.9, 0.0),
                    (1.0, 0.0),
                    (0.15, 0.03),
                    (0.15, 0.0),
                    (0.9, 0.0),
                    (0.0, 1.0),
                    (0.9, 0.0),
                    (0.0, 0.0),
                    (0.0, 0.0),
                    (0.9, 0.0),
                    (0.15, 0.0),
                    (0.5, 0.0),
                ];
                let alpha = 0.2;
                let iso = Isotropic::new(alpha as $t).unwrap();
                let k = (0.5 * alpha * alpha) as $t;
                let lobe = GaussianFilteredGgx::new(iso, Covariance::new(k, 0.0, k));
                let (l1, _) = lobe.kernel_ratio();
                assert!((2.0 * l1 as f64 - 1.0).abs() < 1e-6, "{l1}");
                let mut rng = Rng(0xE7AC);
                let (mut x, mut y, mut z) = (Vec::new(), Vec::new(), Vec::new());
                for &(near, nan) in &plan {
                    for _ in 0..B {
                        let (p, q) = (rng.uniform(), rng.uniform());
                        let r = alpha
                            * if p < near {
                                rng.range(0.0, 3.0)
                            } else {
                                rng.range(20.0, 100.0)
                            };
                        let phi = std::f64::consts::TAU * rng.uniform();
                        let (sx, sy) = (r * phi.cos(), r * phi.sin());
                        let l = (1.0 + sx * sx + sy * sy).sqrt();
                        let mx = if q < nan { f64::NAN } else { -sx / l };
                        x.push(mx as $t);
                        y.push((-sy / l) as $t);
                        z.push((1.0 / l) as $t);
                    }
                }
                let n = plan.len() * B;
                let mut out = vec![0.0 as $t; n];
                assert_eq!(
                    batch::gaussian_filtered_ggx_d(&lobe, &x, &y, &z, &mut out),
                    n
                );
                for (i, &g) in out.iter().enumerate() {
                    let w = lobe.d(Vec3::new(x[i], y[i], z[i]));
                    assert_eq!(g.to_bits(), w.to_bits(), "element {i}: {g:e} against {w:e}");
                }
            }

            /// Projected-space filtering (TK21) with a kernel per element, bit for bit against
            /// `Ggx::new(filter::projected(r, Sigma_i)).d(h_i)`: the footprints' covariances
            /// (`sigma = 0.5`; the wide columns give kernels from `1e-9` to `1e2`, and NaN and
            /// infinite ones from the special values) and the raw adversarial columns as
            /// entries (indefinite, negative, NaN, infinite: the sanitiser's general path),
            /// every roughness form, `alpha` up to `2` (the eigenvalue split of `A` above
            /// `PROJECTED_EIGEN_MAX`), and a matrix with an active determinant clamp.
            #[test]
            fn projected_bit_for_bit() {
                use filtered_ndf::$prec::{Covariance, filter::projected};
                let c = cols(0x7A21);
                let ks: Vec<Covariance> = (0..N).map(|i| fp(&c, i).covariance(0.5)).collect();
                let (k11, k12, k22): (Vec<$t>, Vec<$t>, Vec<$t>) = (
                    ks.iter().map(|k| k.s11).collect(),
                    ks.iter().map(|k| k.s12).collect(),
                    ks.iter().map(|k| k.s22).collect(),
                );
                let footprint_kernels = batch::Covariances {
                    s11: &k11,
                    s12: &k12,
                    s22: &k22,
                };
                let raw = batch::Covariances {
                    s11: &c.ux,
                    s12: &c.uy,
                    s22: &c.vx,
                };
                let mut out = vec![0.0 as $t; N];
                for alpha in [1e-4 as $t, 0.05, 0.5, 0.99, 2.0] {
                    let (iso, aa, mat, _, clamped) = forms(alpha);
                    macro_rules! each {
                        ($r:expr, $name:expr) => {{
                            let r = $r;
                            for (kname, kk) in [("footprint", footprint_kernels), ("raw", raw)] {
                                assert_eq!(
                                    batch::ggx_d_projected(&r, kk, &c.hx, &c.hy, &c.z, &mut out),
                                    N
                                );
                                same(
                                    &out,
                                    |i| {
                                        let k = Covariance::new(kk.s11[i], kk.s12[i], kk.s22[i]);
                                        Ggx::new(projected(r, k))
                                            .d(Vec3::new(c.hx[i], c.hy[i], c.z[i]))
                                    },
                                    &format!("projected {} {alpha} {kname}", $name),
                                );
                            }
                        }};
                    }
                    each!(iso, "iso");
                    each!(aa, "aa");
                    each!(mat, "matrix");
                    each!(clamped, "clamped");
                }
            }

            #[test]
            fn nan_and_back_facing_inputs_give_zero() {
                let aa = AxisAligned::new(0.2, 0.1).unwrap();
                let nan = <$t>::NAN;
                let x = [nan, 0.0, 0.0, 0.0, <$t>::INFINITY];
                let y = [0.0, nan, 0.0, 0.0, 0.0];
                let z = [1.0, 1.0, nan, -1.0, 1.0];
                let mut out = [1.0 as $t; 5];
                batch::ggx_d(&aa, &x, &y, &z, &mut out);
                assert_eq!(out, [0.0; 5], "ggx");
                let mut out = [1.0 as $t; 5];
                batch::beckmann_d(&aa, &x, &y, &z, &mut out);
                assert_eq!(out, [0.0; 5], "beckmann");
                // NaN footprints are sanitised to no filtering: the unfiltered value.
                let f = [nan; 5];
                let fps = batch::Footprints {
                    dh_u_x: &f,
                    dh_u_y: &f,
                    dh_v_x: &f,
                    dh_v_y: &f,
                };
                let (zx, zy, zz) = ([0.0 as $t; 5], [0.0 as $t; 5], [1.0 as $t; 5]);
                let mut out = [0.0 as $t; 5];
                let rules = ClampRules::default();
                batch::beckmann_d_filtered(&aa, &rules, 0.5, &zx, &zy, &zz, fps, &mut out);
                let peak = Beckmann::new(aa).d(Vec3::Z);
                // 4 ulps: the filtered matrix's sqrt(det) is computed from the entries, the
                // axis-aligned one as alpha_x alpha_y (a rounding or two apart).
                let tol = 4.0 * <$t>::EPSILON * peak;
                assert!(
                    out.iter().all(|&v| (v - peak).abs() <= tol),
                    "{out:?} vs {peak}"
                );
                let mut out = [1.0 as $t; 5];
                batch::d_rect(&aa, &x, &y, &z, &f, &f, &mut out);
                // NaN half extents count as 0; every element is NaN, below the horizon or
                // infinite: 0 each (documented), and written (`out` started at 1).
                assert_eq!(out, [0.0; 5], "d_rect");
            }

            /// Every deferred preset and a convention per remaining (domain, norm) pair over
            /// the adversarial columns (`ux..vy` as normal differences, `x` as alpha):
            /// bit for bit where `exponent = 1`; with a power (Unreal, Babylon.js: the
            /// perceptual domain, `alpha_bar = max(p, k)^2`) within `(2 d + 1) eps` relative,
            /// `d` the power's error in ulps against libm's (`pow_lane`: `(5 + 3 |e|) u` in
            /// `f32`, `u = eps / 2`, `1.6e-14 + 3 eps_64 |y| + eps_64` in `f64`; libm one ulp):
            /// the square doubles it and each side rounds it once.
            #[test]
            fn deferred_presets_bit_for_bit() {
                use filtered_ndf::$prec::filter::deferred::{
                    Combine, Domain, KernelConvention, Norm,
                };
                use filtered_ndf::$prec::filter::presets;
                let c = cols(0xDEF);
                let (u, v) = (
                    batch::Vec3s::new(&c.ux, &c.uy, &c.hy),
                    batch::Vec3s::new(&c.vx, &c.vy, &c.hx),
                );
                let mut convs: Vec<(String, KernelConvention)> = presets::ALL
                    .iter()
                    .map(|(n, k)| (n.to_string(), *k))
                    .collect();
                for domain in [
                    Domain::Alpha2,
                    Domain::Alpha,
                    Domain::Perceptual,
                    Domain::ProjectedAlpha2,
                ] {
                    for norm in [
                        Norm::SumSquared,
                        Norm::MaxSquared,
                        Norm::MaxEigenvalue,
                        Norm::MaxAbsComponent,
                    ] {
                        for (exponent, combine) in [(1.0, Combine::Max), (0.5, Combine::Add)] {
                            convs.push((
                                format!("{domain:?} {norm:?} ^{exponent}"),
                                KernelConvention {
                                    domain,
                                    norm,
                                    exponent,
                                    combine,
                                    bias: 0.01,
                                    ..presets::TK19_TRACE
                                },
                            ));
                        }
                    }
                }
                let mut out = vec![0.0 as $t; N];
                for (name, k) in &convs {
                    assert_eq!(batch::deferred_filter(k, &c.x, u, v, &mut out), N);
                    let want = |i: usize| {
                        k.filter(
                            c.x[i],
                            Vec3::new(c.ux[i], c.uy[i], c.hy[i]),
                            Vec3::new(c.vx[i], c.vy[i], c.hx[i]),
                        )
                        .alpha()
                    };
                    if k.exponent == 1.0 {
                        same(&out, want, name);
                        continue;
                    }
                    for (i, &g) in out.iter().enumerate() {
                        let w = want(i);
                        assert!(!g.is_nan() && g > 0.0, "{name} [{i}]: {g}");
                        if g == w {
                            continue; // also every flagged element (the scalar path)
                        }
                        let n = k.norm.eval(
                            Vec3::new(c.ux[i], c.uy[i], c.hy[i]),
                            Vec3::new(c.vx[i], c.vy[i], c.hx[i]),
                        ) as f64;
                        let y = (k.exponent as f64 * n.ln()).abs();
                        let d = if WIDE {
                            1.6e-14 / EPS + 3.0 * y + 1.0 + 1.0
                        } else {
                            // `(5 + 3 |e|) u`, `u = eps / 2`.
                            2.5 + 1.5 * (k.exponent as f64).abs() + 1.0
                        };
                        // The perceptual domain squares (2 d + 1); alpha^2 takes a root
                        // (d / 2 + 1), alpha and projected alpha^2 at most d + 1.
                        let tol = (2.0 * d + 1.0) * EPS * w as f64;
                        assert!(
                            ((g - w) as f64).abs() <= tol,
                            "{name} [{i}]: batch {g} vs scalar {w} (norm {n})"
                        );
                    }
                }
            }

            /// The kernels run at the level `FILTERED_NDF_SIMD` requests, and the test fails
            /// with the reason where they cannot: a name that is no level, a level this CPU
            /// (or this build) cannot run (`.ci/run` skips those, by the same detection:
            /// `examples/simd_levels.rs`), or an available level not used. Unset, the widest
            /// level available.
            #[test]
            fn simd_level_is_the_requested_one() {
                let level = batch::simd_level();
                assert_eq!(batch::simd_available(level), Ok(true), "{level}");
                let env = std::env::var("FILTERED_NDF_SIMD").unwrap_or_default();
                match batch::simd_requested() {
                    Err(e) => panic!("FILTERED_NDF_SIMD={env:?}: {e}"),
                    Ok(None) => {
                        assert!(env.is_empty(), "{env:?}");
                        // `sse2-lanes` is a test mode of SSE2, never chosen unrequested.
                        let widest = batch::SIMD_LEVELS
                            .into_iter()
                            .rev()
                            .find(|&l| l != "sse2-lanes" && batch::simd_available(l) == Ok(true));
                        assert_eq!(Some(level), widest, "unrequested: not the widest level");
                    }
                    Ok(Some(requested)) => {
                        assert_eq!(requested, env);
                        assert_eq!(
                            batch::simd_available(requested),
                            Ok(true),
                            "FILTERED_NDF_SIMD={requested}: this CPU or build cannot run it, \
                             so the batch kernels ran at {level} (the levels available here: \
                             `cargo run --features dispatch --example simd_levels`)"
                        );
                        assert_eq!(
                            level, requested,
                            "FILTERED_NDF_SIMD={requested} is available but not used"
                        );
                    }
                }
                println!("batch kernels on {level}");
            }

            /// Level names: each of `SIMD_LEVELS` is one, anything else (a near miss, a
            /// different case, the empty name) is not.
            #[test]
            fn simd_level_names() {
                for level in batch::SIMD_LEVELS {
                    assert!(batch::simd_available(level).is_ok(), "{level}");
                }
                for bad in ["", "avx-512", "AVX2", "sse", "sse2 ", "neon"] {
                    assert_eq!(
                        batch::simd_available(bad),
                        Err(filtered_ndf::error::UnknownSimdLevel),
                        "{bad:?}"
                    );
                }
            }

            #[test]
            fn ggx_peak_is_the_closed_form() {
                // Independent check of the vectorised loop's values: D(n) = 1 / (pi alpha^2).
                let alpha = 0.3 as $t;
                let iso = Isotropic::new(alpha).unwrap();
                let n = 37; // not a multiple of any vector width
                let (x, y, z) = (vec![0.0 as $t; n], vec![0.0 as $t; n], vec![1.0 as $t; n]);
                let mut out = vec![0.0 as $t; n];
                batch::ggx_d(&iso, &x, &y, &z, &mut out);
                let want = 1.0 / (std::f64::consts::PI * (alpha as f64).powi(2));
                // 4 ulps: one division, three products and the rounding of pi.
                for v in out {
                    assert!(
                        ((v as f64) - want).abs() <= 4.0 * (<$t>::EPSILON as f64) * want,
                        "{v} vs {want}"
                    );
                }
            }
        }
    };
}

suite!(single, f32, f32);
suite!(double, f64, f64);

/// `batch::par_chunks` on 1 and 2 threads gives each element what the sequential call gives
/// it, bit for bit, for chunk sizes that do and do not divide the length.
#[cfg(feature = "rayon")]
#[test]
fn par_chunks_equal_the_sequential_call() {
    use filtered_ndf::f32::{AxisAligned, ClampRules, batch};
    const N: usize = 10_007;
    let c = |s: u64, lo: f64, hi: f64| -> Vec<f32> {
        column(N, s, lo, hi).into_iter().map(|v| v as f32).collect()
    };
    let (x, y, z) = (c(1, -0.7, 0.7), c(2, -0.7, 0.7), c(3, -0.2, 1.0));
    let (ux, uy, vx, vy) = (
        c(4, -0.1, 0.1),
        c(5, -0.1, 0.1),
        c(6, -0.1, 0.1),
        c(7, -0.1, 0.1),
    );
    let fp = batch::Footprints {
        dh_u_x: &ux,
        dh_u_y: &uy,
        dh_v_x: &vx,
        dh_v_y: &vy,
    };
    let r = AxisAligned::new(0.1, 0.3).unwrap();
    let rules = ClampRules::default();
    let mut want = vec![0.0f32; N];
    batch::beckmann_d_filtered(&r, &rules, 0.5, &x, &y, &z, fp, &mut want);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        for chunk in [0, 1000, 4096, N] {
            let mut got = vec![1.0f32; N];
            pool.install(|| {
                batch::par_chunks(&mut got, chunk, |s, o| {
                    let e = s + o.len();
                    let f = batch::Footprints {
                        dh_u_x: &ux[s..e],
                        dh_u_y: &uy[s..e],
                        dh_v_x: &vx[s..e],
                        dh_v_y: &vy[s..e],
                    };
                    batch::beckmann_d_filtered(&r, &rules, 0.5, &x[s..e], &y[s..e], &z[s..e], f, o);
                })
            });
            let same = got
                .iter()
                .zip(&want)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{threads} threads, chunk {chunk}");
        }
    }
}
