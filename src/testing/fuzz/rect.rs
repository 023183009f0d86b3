//! The contract of the GGX rectangle integral and the GGX proxy.

use super::Bytes;
use super::dec::{d32, d64};

macro_rules! rect_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::{AxisAligned, F, Ggx, Ndf, filter::proxy, filter::rect, sampling};
        use $d::{TOL, f, v2, v3};
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let (ax, ay) = (f(b), f(b));
        let center = v2(b);
        let half = v2(b);
        let h = $d::dir(b, head & 1 != 0);
        let hpp = v2(b);
        let (alpha, he) = (f(b), f(b));
        let r = AxisAligned::new_clamped(ax, ay);
        let ggx = Ggx::new(r);
        let peak = ggx.p22(crate::$prec::Vec2::ZERO);

        // p22_rect: never NaN, never negative, at most the peak (an average of P22).
        let p = rect::p22_rect(r, center, half);
        assert!(
            p.is_finite() && p >= 0.0,
            "p22_rect({r:?}, {center:?}, {half:?}) = {p:?}"
        );
        assert!(
            p <= peak * (1.0 + TOL),
            "p22_rect {p:?} above the peak {peak:?}"
        );
        if center.is_nan() {
            assert_eq!(p, 0.0, "p22_rect: NaN centre");
        }
        // d_rect: 0 below the horizon or for non-finite h; else finite (saturating), >= 0.
        let d = rect::d_rect(r, h, half);
        assert!(
            d.is_finite() && d >= 0.0,
            "d_rect({r:?}, {h:?}, {half:?}) = {d:?}"
        );
        if !h.is_finite() || h.z <= 0.0 {
            assert_eq!(d, 0.0, "d_rect below the horizon / non-finite: {h:?}");
        }
        // The printed baseline: never NaN or infinite (a non-finite value is returned as 0).
        let dp = rect::d_rect_printed(r, hpp, h, half);
        assert!(
            dp.is_finite(),
            "d_rect_printed({r:?}, {hpp:?}, {h:?}, {half:?}) = {dp:?}"
        );

        // Proxy: alpha' >= alpha for an in-domain alpha, NaN-free, finite unless |H| overflows.
        for (e, what) in [
            (proxy::effective_alpha(alpha, he), "effective_alpha"),
            (
                proxy::effective_alpha_simple(alpha, he),
                "effective_alpha_simple",
            ),
        ] {
            if alpha.is_finite() && alpha > 0.0 {
                assert!(
                    !e.is_nan() && e >= alpha * (1.0 - TOL),
                    "{what}({alpha:?}, {he:?}) = {e:?}"
                );
                if (he.is_nan() || he.abs() <= F::MAX / 4.0) && alpha <= F::MAX / 4.0 {
                    assert!(e.is_finite(), "{what}({alpha:?}, {he:?}) = {e:?}");
                }
            }
        }
        let a = r.alpha();
        for (pr, what) in [
            (proxy::proxy(r, half), "proxy"),
            (proxy::proxy_simple(r, half), "proxy_simple"),
        ] {
            let q = pr.alpha();
            assert!(
                AxisAligned::new(q.x, q.y).is_ok(),
                "{what}({r:?}, {half:?}) = {pr:?} out of range"
            );
            assert!(
                q.x >= a.x * (1.0 - TOL) && q.y >= a.y * (1.0 - TOL),
                "{what}({r:?}, {half:?}) = {pr:?} sharpened"
            );
            if h.is_finite() {
                let v = Ggx::new(pr).d(h);
                assert!(v.is_finite() && v >= 0.0, "{what}: d({h:?}) = {v:?}");
            }
        }
        // lambda_rect: never NaN, >= 0 (+inf at grazing); for a NaN direction +inf; at least
        // GGX's own Lambda (box filtering only adds masking, Jensen) to rounding.
        let w = v3(b);
        let l = rect::lambda_rect(r, half, w);
        assert!(
            !l.is_nan() && l >= 0.0,
            "lambda_rect({r:?}, {half:?}, {w:?}) = {l:?}"
        );
        if w.is_nan() {
            assert_eq!(l, F::INFINITY, "lambda_rect: NaN direction");
        }
        let lg = ggx.lambda(w);
        if lg.is_finite() && l.is_finite() {
            assert!(
                l >= lg * (1.0 - 64.0 * TOL) - F::MIN_POSITIVE,
                "lambda_rect({r:?}, {half:?}, {w:?}) = {l:?} below GGX's {lg:?}"
            );
        }
        // The box lobe's samplers: unit micronormals above the horizon; None only for a view
        // at or below the horizon, or non-finite.
        let (u, ub) = (v2(b), v2(b));
        let m = sampling::rect::sample_normal_rect(r, half, u, ub);
        assert!(
            m.is_finite() && m.z > 0.0 && (m.length() - 1.0).abs() < 1e-3,
            "sample_normal_rect({r:?}, {half:?}, {u:?}, {ub:?}) = {m:?}"
        );
        let pdf = sampling::rect::normal_pdf_rect(r, half, m);
        assert!(pdf.is_finite() && pdf >= 0.0, "normal_pdf_rect = {pdf:?}");
        let wo = $d::dir(b, head & 2 != 0);
        match sampling::rect::sample_visible_normal_rect(r, half, wo, u, ub) {
            Some(mv) => {
                assert!(
                    mv.is_finite() && mv.z > 0.0 && (mv.length() - 1.0).abs() < 1e-3,
                    "sample_visible_normal_rect({r:?}, {half:?}, {wo:?}) = {mv:?}"
                );
                let vp = sampling::rect::visible_normal_pdf_rect(r, half, wo, mv);
                assert!(
                    vp.is_finite() && vp >= 0.0,
                    "visible_normal_pdf_rect = {vp:?}"
                );
            }
            // `None` is documented for a view at or below the horizon, and with zero half
            // extents for views within the float range of grazing (GGX's sampler, module
            // `sampling`): relative to `wo`'s scale, not absolute (a view `(1e30, 0, 1e-30)`
            // is `1e-60` from grazing; found by fuzzing).
            None => assert!(
                !(wo.is_finite() && wo.z > 0.0)
                    || (!(half.x.abs() > 0.0 || half.y.abs() > 0.0) // zero or NaN: GGX's
                        && wo.z / wo.abs().max_element() <= 1e-30),
                "sample_visible_normal_rect({r:?}, {half:?}, {wo:?}, {u:?}, {ub:?}) refused a view \
                 above the horizon"
            ),
        }
    }};
}

/// The rectangle-integral and proxy contract on fuzzer bytes, in both precisions (roughness
/// from `AxisAligned::new_clamped`, all other arguments arbitrary). Panics on a violation of:
/// `rect::p22_rect` finite, `>= 0`, at most the unfiltered peak `1 / (pi a b)`, `0` for a
/// NaN centre; `rect::d_rect` finite, `>= 0`, `0` for non-finite `h` or `h_z <= 0`;
/// `rect::d_rect_printed` finite (no panic; its sign is not checked: it cancels);
/// `proxy::effective_alpha{,_simple}(alpha, H)` NaN-free and `>= alpha` for finite
/// `alpha > 0`, finite unless `|H|` is near overflow; `proxy::proxy{,_simple}` in the
/// checked roughness range, never below the input roughness, and evaluable; `lambda_rect`
/// NaN-free, `>= 0`, `+inf` for a NaN direction and never below GGX's own `Lambda`; the box
/// lobe's samplers return unit micronormals above the horizon with finite, non-negative pdfs.
pub fn check_rect(data: &[u8]) {
    rect_prec!(d64, f64, &mut Bytes::new(data));
    rect_prec!(d32, f32, &mut Bytes::new(data));
}
