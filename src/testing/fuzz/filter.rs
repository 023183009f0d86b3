//! The contract of the footprint / covariance / clamp / Gaussian-filter family.

use super::Bytes;
use super::dec::{d32, d64, with_rough};

macro_rules! filter_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::kernel::KERNEL_MAX;
        use crate::$prec::{
            Beckmann, BoundingRect, ClampRules, Covariance, ExtentFloor, F, Footprint, Ggx,
            LeanMoments, Roughness, Vec2, Vec3, filter,
        };
        use $d::{TOL, f, v2, v3};
        use crate::math::Real;
        use crate::testing::linalg::Sym2;
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let rough = $d::rough(b);
        let (du, dv) = (v2(b), v2(b));
        let cov = Covariance::new(f(b), f(b), f(b));
        let maxv = f(b);
        let sigma = f(b);
        let h = v3(b);
        let (n_u, n_v) = (v3(b), v3(b));
        let rules = match head % 4 {
            0 => ClampRules::default(),
            1 => ClampRules::NONE,
            2 => ClampRules::GDC2016,
            _ => {
                let max_extent = f(b);
                let floor = match b.byte() % 3 {
                    0 => ExtentFloor::None,
                    1 => ExtentFloor::Constant(f(b)),
                    _ => ExtentFloor::AlphaCapped(f(b)),
                };
                ClampRules {
                    max_extent,
                    floor,
                    kappa: f(b),
                    det_clamp: head & 4 != 0,
                }
            }
        };
        let alpha2 = v2(b);
        let moments = LeanMoments::new(v2(b), Covariance::new(f(b), f(b), f(b)));
        let tau = f(b);
        let (t, bt, n) = (v3(b), v3(b), v3(b));
        let normalize = head & 8 != 0;
        let s = v2(b);
        let mm = $d::dir(b, normalize);
        let w = $d::dir(b, normalize);
        let wi = $d::dir(b, normalize);

        let fin2 = |v: Vec2| v.is_finite();
        let fp_fin = |fp: &Footprint| fp.dh_u.is_finite() && fp.dh_v.is_finite();
        let fp_nan = |fp: &Footprint| fp.dh_u.is_nan() || fp.dh_v.is_nan();
        let cov_fin = |c: &Covariance| c.s11.is_finite() && c.s12.is_finite() && c.s22.is_finite();
        // Positive semi-definite up to rounding: `lambda_min >= -TOL lambda_max`, i.e.
        // `-det <= TOL tr^2` (and underflow of the products).
        let psd = |c: &Covariance| {
            let tr = c.s11 + c.s22;
            c.s11 >= 0.0
                && c.s22 >= 0.0
                && c.s12 * c.s12 <= c.s11 * c.s22 + TOL * tr * tr + F::MIN_POSITIVE
        };
        // The kernel contract of `sanitized` and everything built on it, with eigenvalue bound.
        let kernel_ok = |c: &Covariance, bound: F, what: &str| {
            assert!(cov_fin(c) && psd(c), "{what}: {c:?} not finite PSD");
            let (lo, hi) = c.eigenvalues();
            assert!(
                hi <= bound * (1.0 + TOL) + 4.0 * F::MIN_POSITIVE,
                "{what}: lambda_max {hi:?} > {bound:?} ({c:?})"
            );
            assert!(lo >= 0.0 && lo <= hi * (1.0 + TOL) + F::MIN_POSITIVE, "{what}: {lo:?} {hi:?}");
        };

        // --- Footprint constructors and shapes.
        let fp = Footprint::from_slope_derivatives(du, dv);
        let _ = Footprint::from_projected_derivatives(du, dv);
        let fs = Footprint::from_projected_derivatives_in_slope(h, du, dv);
        if !h.is_finite() {
            assert_eq!(fs, Footprint::ZERO, "in_slope: non-finite h {h:?}");
        } else if fin2(du) && fin2(dv) {
            assert!(!fp_nan(&fs), "in_slope({h:?}, {du:?}, {dv:?}) = {fs:?}");
            // In the domain (unit h, disk derivatives |dp| <= 2): finite.
            if let Some(hu) = $d::unit(h) {
                if du.abs().max_element() <= 2.0 && dv.abs().max_element() <= 2.0 {
                    let fu = Footprint::from_projected_derivatives_in_slope(hu, du, dv);
                    assert!(fp_fin(&fu), "in_slope({hu:?}, {du:?}, {dv:?}) = {fu:?}");
                }
            }
        }
        // Never NaN (the NaN policy: a NaN entry counts as 0, an infinite one saturates to an
        // infinite entry); `ZERO` for a non-finite `h`; the same as with NaN entries zeroed.
        let zero_nan = |v: Vec3| Vec3::select(v.is_nan_mask(), Vec3::ZERO, v);
        let fh = Footprint::from_half_vector_derivatives(h, n_u, n_v);
        assert!(!fp_nan(&fh), "half_vector_derivatives({h:?}, {n_u:?}, {n_v:?}) = {fh:?}");
        if !h.is_finite() {
            assert_eq!(fh, Footprint::ZERO, "half_vector_derivatives: non-finite h");
        }
        assert_eq!(
            fh,
            Footprint::from_half_vector_derivatives(h, zero_nan(n_u), zero_nan(n_v)),
            "half_vector_derivatives: NaN entries count as 0"
        );
        let fnd = Footprint::from_normal_differences(n_u, n_v);
        assert!(!fp_nan(&fnd), "from_normal_differences({n_u:?}, {n_v:?}) = {fnd:?}");
        assert_eq!(
            fnd,
            Footprint::from_normal_differences(zero_nan(n_u), zero_nan(n_v)),
            "normal differences: NaN entries count as 0"
        );
        if n_u.is_finite() && n_v.is_finite() {
            assert!(fp_fin(&fnd), "from_normal_differences({n_u:?}, {n_v:?}) = {fnd:?}");
        }
        let fw = Footprint::from_world_normal_differences(t, bt, n, n_u, n_v);
        assert!(!fp_nan(&fw), "from_world_normal_differences = {fw:?}");

        if fp_fin(&fp) {
            let r = fp.bounding_rect();
            let e = fp.max_extent();
            assert!(r.half_extent.x >= 0.0 && r.half_extent.y >= 0.0, "bounding_rect {r:?}");
            assert!(e >= 0.0, "max_extent {e:?} of {fp:?}");
            // The lengths in `max_extent` underflow below `sqrt(MIN_POSITIVE)` (documented).
            if r.half_extent.is_finite() && e.is_finite() && r.half_extent.max_element() > 1e-18 {
                assert!(
                    r.half_extent.max_element() <= e * (1.0 + TOL) + F::MIN_POSITIVE,
                    "max_extent {e:?} below half extent {r:?}"
                );
            }
            if sigma.is_finite() {
                let c = fp.covariance(sigma);
                if cov_fin(&c) {
                    assert!(psd(&c), "covariance({sigma:?}) = {c:?} of {fp:?}");
                }
            }
        }
        let _ = BoundingRect::new(du).covariance(sigma);

        // --- Covariance.
        let _ = (cov.trace(), cov.det());
        // The test side's own f64 decomposition of the input, and the rounding a small
        // eigenvalue inherits from `det` when computed as `det / lambda_big`:
        // `eps (|s11 s22| + s12^2) / |lambda_big|` (its conditioning; `|lambda_big|` bounds
        // every entry, so the quotients are at most 1).
        let (ra, rb, rc) = (cov.s11.to_f64(), cov.s12.to_f64(), cov.s22.to_f64());
        let e = Sym2::new(ra, rb, rc).eigen();
        let big = e.l1.abs().max(e.l2.abs());
        let det_err =
            if big > 0.0 { ra.abs() * (rc.abs() / big) + rb.abs() * (rb.abs() / big) } else { 0.0 };
        let (lo, hi) = cov.eigenvalues();
        assert!(lo >= 0.0 && hi >= 0.0, "eigenvalues {lo:?} {hi:?} of {cov:?}");
        if cov_fin(&cov) && hi.is_finite() {
            assert!(lo <= hi * (1.0 + TOL) + F::MIN_POSITIVE, "eigenvalues {lo:?} > {hi:?}");
        }
        if cov_fin(&cov) && e.l1 <= F::MAX.to_f64() {
            // Both clamped to >= 0, each within a few ulps of the larger plus the small
            // eigenvalue's conditioning.
            let tol = TOL.to_f64() * (e.l1.max(0.0) + det_err) + 4.0 * F::MIN_POSITIVE.to_f64();
            for (got, want) in [(lo, e.l2.max(0.0)), (hi, e.l1.max(0.0))] {
                assert!(
                    (got.to_f64() - want).abs() <= tol,
                    "eigenvalues of {cov:?} = {lo:?} {hi:?}, reference {e:?}"
                );
            }
        }
        let ce = cov.clamp_eigenvalues(maxv);
        if maxv.is_nan() || maxv < 0.0 || !cov_fin(&cov) {
            assert_eq!(ce, Covariance::ZERO, "clamp_eigenvalues({maxv:?}) of {cov:?}");
        } else {
            // Every finite input, definite or not: PSD with eigenvalues <= max, and equal to
            // `V clamp(Lambda, 0, min(max, F::MAX)) V^T` of the reference decomposition
            // (documented: the bound is at most `F::MAX`). Tolerance: the result is
            // `c_min I + (c_max - c_min) P_max` with `c_max - c_min` at most the eigenvalue
            // gap, so the projector's rounding (relative to the gap) costs a few ulps of
            // `c_max`; the clamp does not enlarge the small eigenvalue's conditioning. Hence
            // `TOL (c_max + det_err)`, plus 4 `MIN_POSITIVE` for subnormal entries.
            assert!(cov_fin(&ce), "clamp_eigenvalues({maxv:?}) of {cov:?} = {ce:?}");
            kernel_ok(&ce, maxv, "clamp_eigenvalues");
            let mv = maxv.min(F::MAX).to_f64();
            let want = e.map(|l| l.clamp(0.0, mv));
            let tol = TOL.to_f64() * (e.l1.clamp(0.0, mv) + det_err)
                + 4.0 * F::MIN_POSITIVE.to_f64();
            for (got, want) in [(ce.s11, want.a11), (ce.s12, want.a12), (ce.s22, want.a22)] {
                assert!(
                    (got.to_f64() - want).abs() <= tol,
                    "clamp_eigenvalues({maxv:?}) of {cov:?} = {ce:?}, reference {want:?}"
                );
            }
        }
        let sa = cov.sanitized();
        let entries = [cov.s11, cov.s12, cov.s22];
        if entries.iter().any(|x| x.is_infinite()) {
            assert_eq!(sa, Covariance::new(KERNEL_MAX, 0.0, KERNEL_MAX), "sanitized inf");
        } else if entries.iter().any(|x| x.is_nan()) {
            let z = |x: F| if x.is_nan() { 0.0 } else { x };
            let zeroed = Covariance::new(z(cov.s11), z(cov.s12), z(cov.s22)).sanitized();
            assert_eq!(sa, zeroed, "sanitized: a NaN entry counts as 0");
        }
        kernel_ok(&sa, KERNEL_MAX, "sanitized");

        // --- Clamp rules.
        let lambda = if rules.max_extent >= 0.0 { rules.max_extent } else { 0.0 };
        let cf = rules.footprint(fp);
        assert_eq!(cf, rules.footprint(fp.nan_to_zero()), "rules.footprint: NaN entries as 0");
        assert!(!fp_nan(&cf), "rules.footprint({fp:?}) = {cf:?} with {rules:?}");
        // Above `F::MAX / 2` the rescaled vectors (length up to `2 lambda`) may overflow.
        if lambda <= 1e30 {
            assert!(fp_fin(&cf), "rules.footprint({fp:?}) = {cf:?} with {rules:?}");
            // `max_extent` squares the vectors: compare where that cannot overflow or
            // underflow into subnormals (f32).
            if (1e-15..=1e15).contains(&lambda) {
                let e = cf.max_extent();
                assert!(
                    e <= lambda * (1.0 + TOL) + 4.0 * F::MIN_POSITIVE,
                    "rules.footprint extent {e:?} > {lambda:?}: {fp:?} -> {cf:?}"
                );
            }
        }
        let rr = rules.rect(BoundingRect::new(du), alpha2);
        let he = rr.half_extent;
        assert!(!he.is_nan() && he.x >= 0.0 && he.y >= 0.0, "rules.rect {rr:?}");
        if lambda.is_finite() {
            assert!(he.is_finite(), "rules.rect({du:?}) = {rr:?} with {rules:?}");
        }
        match rules.floor {
            ExtentFloor::None => assert!(he.max_element() <= lambda, "rules.rect above lambda"),
            ExtentFloor::Constant(e) if e >= 0.0 && e.is_finite() => {
                assert!(he.min_element() >= e, "rules.rect below the floor {e:?}: {rr:?}")
            }
            _ => {}
        }
        let kk = rules.kernel(cov);
        let kb = if rules.kappa >= 0.0 && rules.kappa.is_finite() {
            (0.5 * rules.kappa).min(KERNEL_MAX)
        } else if rules.kappa > 0.0 {
            KERNEL_MAX
        } else {
            0.0
        };
        kernel_ok(&kk, kb, &format!("rules.kernel({cov:?}) with {rules:?}"));

        // --- Filters, evaluated.
        let eval = |a: &crate::$prec::RoughnessMatrix, what: &str| {
            $d::valid_matrix(a, what);
            $d::ndf_contract(&Ggx::new(*a), s, mm, w, wi, what);
            $d::ndf_contract(&Beckmann::new(*a), s, mm, w, wi, what);
        };
        let lean_cov = moments.covariance();
        kernel_ok(&lean_cov, KERNEL_MAX, "LeanMoments::covariance");
        with_rough!($d, rough, r => {
            let sd = r.sqrt_det();
            let tr = rules.det_clamp_for(r);
            assert!(tr.is_finite() && tr >= 0.0, "rules.det_clamp_for {tr:?}");
            let g = rules.filter_gaussian(r, fp, sigma);
            eval(&g, "rules.filter_gaussian");
            if rules.det_clamp {
                assert!(g.sqrt_det() >= sd * (1.0 - TOL), "filter_gaussian sharpened");
            }
            let g = filter::gaussian(r, cov);
            eval(&g, "filter::gaussian");
            assert!(g.sqrt_det() >= sd * (1.0 - TOL), "gaussian sharpened: {g:?} < {r:?}");
            let gc = filter::gaussian_with_det_clamp(r, cov, tau);
            eval(&gc, &format!("filter::gaussian_with_det_clamp({r:?}, {cov:?}, {tau:?}) = {gc:?}"));
            let pr = rules.filter_projected(r, fp, sigma);
            eval(&pr, "rules.filter_projected");
            if rules.det_clamp {
                assert!(pr.sqrt_det() >= sd * (1.0 - TOL), "filter_projected sharpened");
            }
            let p = filter::projected(r, cov);
            eval(&p, &format!("filter::projected of {:?} by {cov:?}", r.to_matrix().entries()));
            assert!(p.sqrt_det() >= sd * (1.0 - TOL), "projected sharpened: {p:?} < {r:?}");
            let (a11, _, a22) = r.to_matrix().entries();
            let (p11, _, p22) = p.entries();
            let tol = 1e3 * F::EPSILON;
            assert!(
                p11 >= a11 * (1.0 - tol) && p22 >= a22 * (1.0 - tol),
                "projected sharpened: {:?} -> {:?} (kernel {cov:?})",
                r.to_matrix().entries(),
                p.entries()
            );
            let l = filter::lean(r, cov, &moments);
            eval(&l, "filter::lean");
            assert!(l.sqrt_det() >= sd * (1.0 - TOL), "lean sharpened");
        });
    }};
}

/// The footprint, covariance, clamp and Gaussian-filter contract on fuzzer bytes, in both
/// precisions. Panics on a violation of:
///
/// - `Footprint` constructors: `from_projected_derivatives_in_slope` is [`ZERO`] for a
///   non-finite `h`, NaN-free for finite input and finite for a unit `h` and disk
///   derivatives `|dp| <= 2`; `from_half_vector_derivatives` is never NaN, [`ZERO`] for a
///   non-finite `h`; it and `from_normal_differences` equal their value with the NaN entries
///   of the derivatives zeroed (the NaN policy), `from_normal_differences` finite for finite
///   input, `from_world_normal_differences` never NaN; `bounding_rect` and `max_extent` are
///   `>= 0` and `max_extent` bounds both half-extents; `covariance` is PSD when finite.
/// - `Covariance`: `eigenvalues` `>= 0`, `min <= max`, and for finite input within
///   `TOL (lambda_max + det_err)` of the reference's (clamped to `>= 0`; `det_err` the
///   conditioning of the small eigenvalue, see the code); `clamp_eigenvalues(max)` is
///   [`Covariance::ZERO`](crate::f64::Covariance::ZERO) for a NaN / negative `max` or a
///   non-finite input, else finite, PSD with eigenvalues `<= max` for every input (also
///   indefinite), and within `TOL c_max` of `V clamp(Lambda, 0, max) V^T` computed by
///   [`crate::testing::linalg`];
///   `sanitized` is finite, PSD, eigenvalues `<= KERNEL_MAX`, `KERNEL_MAX I` for infinite
///   entries, else its value with the NaN entries zeroed.
/// - `ClampRules` (default, `NONE`, `GDC2016` and arbitrary fields): `footprint` equals its
///   value with the NaN entries zeroed, NaN-free, finite with extent `<= lambda` for a finite `lambda`; `rect`
///   is NaN-free, `>= 0`, finite for finite `lambda`, `<= lambda` without floor, `>= epsilon`
///   with a constant floor; `kernel` is finite PSD with eigenvalues `<= kappa / 2`;
///   `det_clamp_for` finite `>= 0`.
/// - `filter::{gaussian, gaussian_with_det_clamp, projected, lean}`,
///   `ClampRules::{filter_gaussian, filter_projected}`,
///   `LeanMoments::covariance` for any kernel: a valid matrix (finite entries, positive
///   diagonal, finite positive `sqrt_det`) that never sharpens the lobe where `tau = det A`,
///   and whose GGX and Beckmann evaluations satisfy the NDF contract of [`super::check_ndf`].
///
/// [`ZERO`]: crate::f64::Footprint::ZERO
pub fn check_filter(data: &[u8]) {
    filter_prec!(d64, f64, &mut Bytes::new(data));
    filter_prec!(d32, f32, &mut Bytes::new(data));
}
