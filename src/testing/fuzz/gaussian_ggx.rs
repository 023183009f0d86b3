//! The contract of the exact Gaussian-filtered GGX (`gaussian_ggx`).

use super::Bytes;
use super::dec::{d32, d64, with_rough};

macro_rules! gaussian_ggx_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::{Covariance, GaussianFilteredGgx, Ndf, NdfSampling, Vec3};
        use $d::{f, v2};
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let rough = $d::rough(b);
        let kernel = Covariance::new(f(b), f(b), f(b));
        let s = v2(b);
        let u = v2(b);
        let mm = $d::dir(b, head & 1 != 0);
        let wo = $d::dir(b, head & 2 != 0);
        with_rough!($d, rough, r => {
            let lobe = GaussianFilteredGgx::new(r, kernel);
            let what = format!("{r:?} {kernel:?}");
            let p = lobe.p22(s);
            assert!(p.is_finite() && p >= 0.0, "{what}: p22({s:?}) = {p:?}");
            if !s.is_finite() {
                assert_eq!(p, 0.0, "{what}: p22({s:?})");
            }
            let dv = lobe.d(mm);
            assert!(dv.is_finite() && dv >= 0.0, "{what}: d({mm:?}) = {dv:?}");
            if !(mm.is_finite() && mm.z > 0.0) {
                assert_eq!(dv, 0.0, "{what}: d({mm:?})");
            }
            if wo.is_finite() {
                let l = lobe.lambda(wo);
                assert!(l >= 0.0, "{what}: lambda({wo:?}) = {l:?}");
            }
            let n = lobe.sample_normal(u);
            assert!($d::is_unit(n) && n.z > 0.0, "{what}: sample_normal({u:?}) = {n:?}");
            let v = lobe.sample_visible_normal(wo, u);
            if !(wo.is_finite() && wo.z > 0.0) {
                assert!(v.is_none(), "{what}: sample_visible_normal({wo:?}) = {v:?}");
            }
            if let Some(m) = v {
                assert!($d::is_unit(m) && m.z > 0.0, "{what}: visible {wo:?} {u:?} = {m:?}");
                let p = lobe.visible_normal_pdf(wo, m);
                assert!(p.is_finite() && p >= 0.0, "{what}: visible_normal_pdf = {p:?}");
            }
            let p = lobe.visible_normal_pdf(wo, mm);
            assert!(p.is_finite() && p >= 0.0, "{what}: visible_normal_pdf({wo:?}, {mm:?})");
            let _ = Vec3::ZERO;
        });
    }};
}

/// The contract of [`GaussianFilteredGgx`](crate::f64::GaussianFilteredGgx) on fuzzer bytes,
/// in both precisions, for every roughness form and any kernel (NaN, infinite, indefinite,
/// huge): `p22` finite and `>= 0` (`0` for a
/// non-finite slope); `d` finite and `>= 0` (`0` below the horizon or for non-finite `m`);
/// `lambda >= 0` (never NaN) for a finite direction; `sample_normal` a unit vector with
/// `m_z > 0`; `sample_visible_normal` `None` for `wo_z <= 0` or non-finite `wo`, every `Some(m)`
/// a unit vector with `m_z > 0` and a finite, non-negative pdf; `visible_normal_pdf` finite and
/// `>= 0` for any input. Panics on a violation.
pub fn check_gaussian_ggx(data: &[u8]) {
    gaussian_ggx_prec!(d64, f64, &mut Bytes::new(data));
    gaussian_ggx_prec!(d32, f32, &mut Bytes::new(data));
}
