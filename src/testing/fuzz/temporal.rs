//! The contract of temporal roughness, moving implicit surfaces and local quadrics.

use super::Bytes;
use super::dec::{d32, d64, with_rough};

macro_rules! temporal_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::temporal::implicit::{self, HitRates, LevelSetSample, MovingRay, Sym3};
        use crate::$prec::temporal::quadric::{LocalQuadric, RigidMotion};
        use crate::$prec::temporal::{self, TemporalLobe, TemporalRoughness};
        use crate::$prec::{ALPHA_MAX, Covariance, F, Vec3};
        use $d::{TOL, f, v2, v3};
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let rough = $d::rough(b);
        let rate = v2(b);
        let (dt, c, frac, amin) = (f(b), f(b), f(b), f(b));
        let nsplit = u32::from(b.byte());
        let p = Covariance::new(f(b), f(b), f(b));
        let (dn_w, tg, bt) = (v3(b), v3(b), v3(b));
        let hess = Sym3::new(f(b), f(b), f(b), f(b), f(b), f(b));
        let sample = LevelSetSample { grad: v3(b), hess, dphi_dt: f(b), dgrad_dt: v3(b) };
        let ray = MovingRay { origin: v3(b), dir: v3(b), d_origin: v3(b), d_dir: v3(b) };
        let sd = f(b);
        let (qp, qn, qe, k1, k2) = (v3(b), v3(b), v3(b), f(b), f(b));
        let motion = RigidMotion { center: v3(b), velocity: v3(b), angular_velocity: v3(b) };
        let (x, w) = (v3(b), v3(b));
        let normalize = head & 1 != 0;
        let s = v2(b);
        let mm = $d::dir(b, normalize);
        let wv = $d::dir(b, normalize);
        let wi = $d::dir(b, normalize);

        let v_fin = |v: Vec3| v.is_finite();
        let rates_ok = |r: &HitRates, what: &str| {
            assert!(
                r.ds_dt.is_finite() && v_fin(r.dn_dt) && v_fin(r.dx_dt),
                "{what}: {r:?}"
            );
        };
        let tr_ok = |t: &TemporalRoughness, what: &str| {
            let a = t.alpha();
            assert!((0.0..=ALPHA_MAX).contains(&a), "{what}: alpha {a:?}");
            assert!($d::is_unit(t.axis().extend(0.0)), "{what}: axis {}", t.axis());
            let cv = t.covariance();
            assert!(
                cv.s11.is_finite() && cv.s12.is_finite() && cv.s22.is_finite(),
                "{what}: covariance {cv:?}"
            );
            assert!(cv.s11 >= 0.0 && cv.s22 >= 0.0, "{what}: covariance {cv:?}");
            let m = t.roughness_matrix(amin);
            $d::valid_matrix(&m, what);
            $d::ndf_contract(&crate::$prec::Ggx::new(m), s, mm, wv, wi, what);
        };

        // Shutter and temporal roughness.
        let sdt = temporal::box_shutter_dt(dt);
        assert!(sdt.is_finite() && sdt >= 0.0, "box_shutter_dt({dt:?}) = {sdt:?}");
        if !(dt.is_finite() && dt > 0.0) {
            assert_eq!(sdt, 0.0, "box_shutter_dt({dt:?})");
        }
        let t = TemporalRoughness::from_normal_rate(rate, dt);
        if !(rate.is_finite() && dt.is_finite() && dt > 0.0) || rate == crate::$prec::Vec2::ZERO {
            assert_eq!(t, TemporalRoughness::ZERO, "from_normal_rate({rate:?}, {dt:?})");
        }
        tr_ok(&t, "from_normal_rate");
        let tw = TemporalRoughness::from_world_rate(dn_w, tg, bt, dt);
        tr_ok(&tw, "from_world_rate");
        let tc = t.cosine_weighted(c);
        tr_ok(&tc, "cosine_weighted");
        assert!(tc.alpha() <= t.alpha(), "cosine_weighted grew alpha");
        let ts = t.share(frac);
        tr_ok(&ts, "share");
        assert!(ts.alpha() <= t.alpha(), "share grew alpha");
        tr_ok(&t.split_even(nsplit), "split_even");

        // Widening and the lobe: valid, never sharper, NDF contract (G from the base).
        with_rough!($d, rough, r => {
            use crate::$prec::{Ndf, Roughness};
            let wd = temporal::widen(r, p);
            $d::valid_matrix(&wd, "widen");
            assert!(wd.sqrt_det() >= r.sqrt_det() * (1.0 - TOL), "widen sharpened");
            for cv in [p, t.covariance()] {
                let lb = TemporalLobe::beckmann(r, cv);
                $d::ndf_contract(&lb, s, mm, wv, wi, "TemporalLobe::beckmann");
                let lg = TemporalLobe::ggx(r, cv);
                $d::ndf_contract(&lg, s, mm, wv, wi, "TemporalLobe::ggx");
                if wv.is_finite() && mm.is_finite() {
                    assert_eq!(lg.g1(wv, mm), lg.base.g1(wv, mm), "G of the lobe is the base G");
                }
            }
        });

        // Implicit surfaces: finite everywhere, zero for degenerate input.
        for (v, what) in [
            (implicit::project(dn_w, tg), "project"),
            (implicit::d_normalized(dn_w, tg), "d_normalized"),
            (sample.normal(), "normal"),
            (sample.normal_partial_t(), "normal_partial_t"),
            (sample.normal_gradient_apply(w), "normal_gradient_apply"),
        ] {
            assert!(v_fin(v), "{what} = {v:?}");
        }
        let nrm = sample.normal();
        assert!(nrm == Vec3::ZERO || $d::is_unit(nrm), "normal = {nrm:?}");
        assert!(sample.shape_operator().is_finite(), "shape_operator");
        let hr = implicit::hit_rates(&sample, &ray, sd);
        rates_ok(&hr, "hit_rates");
        assert!(implicit::hit_distance_rate(&sample, &ray, sd).is_finite(), "hit_distance_rate");
        assert!(v_fin(implicit::hit_normal_rate(&sample, &ray, sd)), "hit_normal_rate");
        let fixed = MovingRay::fixed(ray.origin, ray.dir);
        rates_ok(&implicit::hit_rates(&sample, &fixed, sd), "hit_rates (fixed ray)");
        let _ = (ray.at(sd), Sym3::outer(w).bilinear(w, x), Sym3::from_diagonal(w) + Sym3::IDENTITY);

        // Quadrics and rigid motions.
        let q = LocalQuadric::new(qp, qn, qe, k1, k2);
        let fin_in = qp.is_finite() && qn.is_finite() && qe.is_finite() && k1.is_finite() && k2.is_finite();
        if !fin_in {
            assert!(q.is_none(), "LocalQuadric::new accepted non-finite input");
        }
        let _ = motion.point_velocity(x);
        let ls = motion.level_set_sample(x, w, hess);
        rates_ok(&implicit::hit_rates(&ls, &ray, sd), "hit_rates (rigid motion)");
        if let Some(q) = q {
            let (_, n, e1, e2) = q.frame();
            assert!(
                $d::is_unit(n) && $d::is_unit(e1) && $d::is_unit(e2),
                "quadric frame {:?} of {qn:?}, {qe:?}",
                q.frame()
            );
            assert!(
                n.dot(e1).abs() <= TOL && n.dot(e2).abs() <= TOL,
                "quadric frame {:?} of {qn:?}, {qe:?}",
                q.frame()
            );
            assert_eq!(q.curvatures(), (k1, k2));
            let ls = q.level_set_sample(x, &motion);
            let hr = implicit::hit_rates(&ls, &ray, sd);
            rates_ok(&hr, "hit_rates (quadric)");
            // Moderate input: the quadric's own values are finite.
            let small = |v: Vec3| v.is_finite() && v.abs().max_element() <= 1e6;
            if small(x) && small(qp) && k1.abs() <= 1e6 && k2.abs() <= 1e6 {
                assert!(q.value(x).is_finite() && v_fin(q.gradient(x)), "quadric at {x:?}");
                assert!(q.hessian().is_finite(), "quadric hessian");
                let (u1, u2) = (x.x, x.y);
                assert!(v_fin(q.point(u1, u2)), "quadric point");
            }
        }
        let _: F = 0.0;
    }};
}

/// The temporal-roughness, implicit-surface and quadric contract on fuzzer bytes, in both
/// precisions. Panics on a violation of: `temporal::box_shutter_dt` finite `>= 0` (`0` for a
/// non-finite or non-positive shutter); `TemporalRoughness` from every constructor and
/// modifier with `alpha` in `[0, ALPHA_MAX]`, a unit axis, a finite PSD-diagonal covariance and
/// a valid `roughness_matrix` (`ZERO` for a non-finite or zero rate or a bad `dt`;
/// `cosine_weighted` and `share` never grow `alpha`); `temporal::widen` valid and never sharper;
/// `TemporalLobe::{beckmann, ggx}` satisfy the NDF contract of [`super::check_ndf`] with the
/// base lobe's `G`; `implicit::{project, d_normalized}`, the `LevelSetSample` derivatives,
/// `shape_operator` and `hit_rates` (and its two projections) finite for any input;
/// `LocalQuadric::new` `None` for non-finite input, else an orthonormal frame, finite values
/// for moderate input, and finite `hit_rates` through `RigidMotion`.
pub fn check_temporal(data: &[u8]) {
    temporal_prec!(d64, f64, &mut Bytes::new(data));
    temporal_prec!(d32, f32, &mut Bytes::new(data));
}
