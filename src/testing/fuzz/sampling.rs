//! The contract of NDF importance sampling and its pdfs.

use super::Bytes;
use super::dec::{d32, d64, with_rough};

macro_rules! sampling_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::sampling::beckmann::visible_slope_quantile;
        use crate::$prec::sampling::reflect;
        use crate::$prec::{Beckmann, F, Ggx, NdfSampling, Vec3};
        use $d::{TOL, f, v2};
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let rough = $d::rough(b);
        let u = v2(b);
        let wo = $d::dir(b, head & 1 != 0);
        let mm = $d::dir(b, head & 2 != 0);
        let wi = $d::dir(b, head & 4 != 0);
        let (qc, qs, qu) = (f(b), f(b), f(b));

        fn check<N: NdfSampling>(
            ndf: &N,
            u: crate::$prec::Vec2,
            wo: Vec3,
            mm: Vec3,
            wi: Vec3,
            consistent: bool,
            what: &str,
        ) {
            let n = ndf.sample_normal(u);
            assert!($d::is_unit(n) && n.z > 0.0, "{what}: sample_normal({u:?}) = {n:?}");
            let p = ndf.normal_pdf(n);
            assert!(p.is_finite() && p >= 0.0, "{what}: normal_pdf({n:?}) = {p:?}");
            let p = ndf.normal_pdf(mm);
            assert!(p >= 0.0, "{what}: normal_pdf({mm:?}) = {p:?}");
            if $d::is_unit(mm) {
                assert!(p.is_finite(), "{what}: normal_pdf({mm:?}) = {p:?}");
            }
            if !mm.is_finite() || mm.z <= 0.0 {
                assert_eq!(p, 0.0, "{what}: normal_pdf({mm:?})");
            }
            let v = ndf.sample_visible_normal(wo, u);
            if !(wo.is_finite() && wo.z > 0.0) {
                assert!(v.is_none(), "{what}: sample_visible_normal({wo:?}) = {v:?}");
            } else if v.is_some() || (wo.z / wo.abs().max_element() > 1e-30 && consistent) {
                // (`None` is documented where every candidate's `m_z` underflows: views within
                // about 1e-37 of grazing, or a `tau` far above `a11 a22`.)
                let m = v.unwrap_or_else(|| panic!("{what}: no visible normal for {wo:?}"));
                // `wo.m > 0` as documented, or for the direction of `wo` (its scale is free: a
                // tiny `wo` underflows the product, a huge one its normalised `z`).
                let o = $d::unit(wo).unwrap();
                assert!(
                    $d::is_unit(m) && m.z > 0.0 && (wo.dot(m) > 0.0 || o.dot(m) > 0.0),
                    "{what}: sample_visible_normal({wo:?}, {u:?}) = {m:?}: |m| = {}, o.m = {}",
                    m.length(),
                    o.dot(m)
                );
                let p = ndf.visible_normal_pdf(wo, m);
                assert!(p.is_finite() && p >= 0.0, "{what}: visible_normal_pdf = {p:?}");
                let r = ndf.reflection_pdf_from_normal(wo, m);
                assert!(r.is_finite() && r >= 0.0, "{what}: reflection_pdf_from_normal = {r:?}");
                let r = ndf.reflection_pdf(wo, reflect(o, m));
                assert!(r.is_finite() && r >= 0.0, "{what}: reflection_pdf = {r:?}");
            }
            let bad = !(wo.is_finite() && wo.z > 0.0);
            for (p, pdf) in [
                (ndf.visible_normal_pdf(wo, mm), "visible_normal_pdf"),
                (ndf.reflection_pdf(wo, wi), "reflection_pdf"),
                (ndf.reflection_pdf_from_normal(wo, mm), "reflection_pdf_from_normal"),
            ] {
                assert!(p.is_finite() && p >= 0.0, "{what}: {pdf}({wo:?}, {mm:?}, {wi:?}) = {p:?}");
                if bad {
                    assert_eq!(p, 0.0, "{what}: {pdf} for wo = {wo:?}");
                }
            }
            if wo.is_finite() && mm.is_finite() && wo.dot(mm) <= 0.0 {
                assert_eq!(ndf.visible_normal_pdf(wo, mm), 0.0, "{what}: wo.m <= 0");
            }
        }
        with_rough!($d, rough, r => {
            use crate::$prec::Roughness;
            let what = format!("{:?} tau-clamped sqrt_det {:?}", r.to_matrix().entries(), r.sqrt_det());
            // A determinant clamp far above `a11 a22` describes no matrix (module docs).
            let (a11, _, a22) = r.to_matrix().entries();
            let consistent = r.sqrt_det() * r.sqrt_det() <= 2.0 * a11 * a22;
            check(&Ggx::new(r), u, wo, mm, wi, consistent, &format!("ggx {what}"));
            check(&Beckmann::new(r), u, wo, mm, wi, consistent, &format!("beckmann {what}"));
        });

        // The Beckmann visible-slope quantile: finite, in [-X, X] (X = 9 / 26).
        let x_max: F = if F::MANTISSA_DIGITS > 24 { 26.0 } else { 9.0 };
        let q = visible_slope_quantile(qc, qs, qu);
        assert!(
            q.is_finite() && q.abs() <= x_max * (1.0 + TOL),
            "visible_slope_quantile({qc:?}, {qs:?}, {qu:?}) = {q:?}"
        );
    }};
}

/// The sampling contract on fuzzer bytes, in both precisions, for GGX and Beckmann in every
/// roughness form (valid roughness from clamped or checked constructors, arbitrary `u`, `wo`,
/// `m`, `wi`). Panics on a violation of: `sample_normal` a unit vector with `m_z > 0` and a
/// finite `normal_pdf`; `normal_pdf` `>= 0` (finite for unit `m`, `0` below the horizon or
/// for non-finite `m`); `sample_visible_normal` `None` for `wo_z <= 0` or non-finite `wo`,
/// `Some` for other views unless documented (`wo_z / |wo| < 1e-30`, or a determinant clamp
/// `tau > 2 a11 a22`), and every `Some(m)` a unit `m` with `m_z > 0` and `wo.m > 0` (for `wo`
/// or its direction) whose pdfs
/// are finite and `>= 0`; `visible_normal_pdf`, `reflection_pdf`,
/// `reflection_pdf_from_normal` finite and `>= 0` for any input, `0` for a `wo` at or below the
/// horizon or non-finite, and `visible_normal_pdf = 0` for `wo.m <= 0`;
/// `sample_beckmann::visible_slope_quantile` finite and within `[-X, X]`.
pub fn check_sampling(data: &[u8]) {
    sampling_prec!(d64, f64, &mut Bytes::new(data));
    sampling_prec!(d32, f32, &mut Bytes::new(data));
}
