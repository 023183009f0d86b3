//! The contract of the half-vector Jacobians, the slope maps and the geometric footprints.

use super::Bytes;
use super::dec::{d32, d64};

macro_rules! jacobian_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::footprint::geometry::{
            self, Endpoint, PinholeRay, ShadingFrame, footprint, footprint_projected, half_vector,
            half_vector_jacobian, half_vector_jacobian_deferred, half_vector_jacobian_far_field,
            tangent_plane_differentials,
        };
        use crate::$prec::footprint::jacobian::{self as jac, HZ_MIN};
        use crate::$prec::{F, Footprint, Mat2, footprint::slope};
        use $d::{TOL, m2, v2, v3};
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let h = $d::dir(b, head & 1 != 0);
        let eps = v2(b);
        let dh = v3(b);
        let s = v2(b);
        let x = v3(b);
        let (e0, e1) = (v3(b), v3(b));
        let eye = if head & 2 != 0 {
            Endpoint::Point(e0)
        } else {
            Endpoint::Direction(e0)
        };
        let light = if head & 4 != 0 {
            Endpoint::Point(e1)
        } else {
            Endpoint::Direction(e1)
        };
        let frame = if head & 8 != 0 {
            // An orthonormal frame from one direction (the documented input).
            let n = $d::unit(v3(b)).unwrap_or(crate::$prec::Vec3::Z);
            let (t, bt) = n.any_orthonormal_pair();
            ShadingFrame {
                s: t,
                t: bt,
                n,
                dn: m2(b),
                twist: v2(b),
            }
        } else {
            ShadingFrame::from_derivatives(v3(b), v3(b), v3(b), [v3(b), v3(b)], [v3(b), v3(b)])
        };
        let (dx_u, dx_v) = (v3(b), v3(b));
        let fp = Footprint::from_slope_derivatives(v2(b), v2(b));
        let ray = PinholeRay {
            origin: v3(b),
            dir: v3(b),
            ddir_du: v3(b),
            ddir_dv: v3(b),
        };
        let flat = ShadingFrame::flat(frame.s, frame.t, frame.n);
        let m_fin = |m: Mat2| m.is_finite();
        let fp_fin = |fp: &Footprint| fp.dh_u.is_finite() && fp.dh_v.is_finite();

        // Jacobians: finite for every input, the documented determinant ranges.
        let hs = jac::sanitize(h);
        assert!(
            $d::is_unit(hs) && hs.z >= HZ_MIN * (1.0 - TOL),
            "sanitize({h:?}) = {hs:?}"
        );
        let (ex, ey) = jac::spherical_basis(h);
        assert!(
            $d::is_unit(ex) && $d::is_unit(ey),
            "spherical_basis({h:?}) = {ex:?}, {ey:?}"
        );
        for (mm, what) in [
            (jac::sphere_to_projected(h), "sphere_to_projected"),
            (jac::projected_to_slope(h), "projected_to_slope"),
            (jac::slope_to_projected(h), "slope_to_projected"),
            (jac::sphere_to_slope(h), "sphere_to_slope"),
        ] {
            assert!(m_fin(mm), "{what}({h:?}) = {mm:?}");
        }
        let big = 1.0 + TOL;
        let d1 = jac::det_sphere_to_projected(h);
        assert!(
            d1 >= HZ_MIN * (1.0 - TOL) && d1 <= big,
            "det_sphere_to_projected {d1:?}"
        );
        let d2 = jac::det_projected_to_slope(h);
        assert!(
            d2 >= 1.0 - TOL && d2 <= 1e24 * big,
            "det_projected_to_slope {d2:?}"
        );
        let d3 = jac::det_sphere_to_slope(h);
        assert!(
            d3 >= 1.0 - TOL && d3 <= 1e18 * big,
            "det_sphere_to_slope {d3:?}"
        );
        // Vector products: NaN-free for finite vectors, finite where they cannot overflow.
        let sc = jac::spherical_components(h, dh);
        let ts = jac::spherical_to_slope(h, eps);
        let tp = jac::spherical_to_projected(h, eps);
        if dh.is_finite() {
            assert!(!sc.is_nan(), "spherical_components({h:?}, {dh:?}) = {sc:?}");
            if dh.abs().max_element() <= 1e30 {
                assert!(
                    sc.is_finite(),
                    "spherical_components({h:?}, {dh:?}) = {sc:?}"
                );
            }
        }
        if eps.is_finite() && eps.abs().max_element() <= 1e6 {
            assert!(
                ts.is_finite() && tp.is_finite(),
                "spherical_to_*({h:?}, {eps:?}) = {ts:?}, {tp:?}"
            );
        }

        // Slope maps: finite for finite input, unit directions.
        if h.is_finite() {
            assert!(
                slope::slope_from_sphere(h).is_finite(),
                "slope_from_sphere({h:?})"
            );
        }
        if s.is_finite() {
            let u = slope::sphere_from_slope(s);
            assert!(
                $d::is_unit(u) && u.z >= 0.0,
                "sphere_from_slope({s:?}) = {u:?}"
            );
            assert!(
                slope::projected_from_slope(s).is_finite(),
                "projected_from_slope({s:?})"
            );
            let u = slope::sphere_from_projected(s);
            assert!(
                $d::is_unit(u) && u.z >= 0.0,
                "sphere_from_projected({s:?}) = {u:?}"
            );
            assert!(
                slope::slope_from_projected(s).is_finite(),
                "slope_from_projected({s:?})"
            );
        }

        // Geometry: never NaN, degenerate input gives zero / +z.
        let hv = half_vector(x, eye, light, &frame);
        assert!(!hv.is_nan(), "half_vector = {hv:?} for {frame:?}");
        let _ = half_vector(x, eye, light, &flat);
        let mj = half_vector_jacobian(x, eye, light, &frame);
        assert!(m_fin(mj), "half_vector_jacobian = {mj:?}");
        let mf = half_vector_jacobian_far_field(e0, &frame);
        assert!(m_fin(mf), "half_vector_jacobian_far_field = {mf:?}");
        let md = half_vector_jacobian_deferred(&frame);
        assert!(m_fin(md), "half_vector_jacobian_deferred = {md:?}");
        let _ = frame.to_local(e1);
        for jm in [mj, mf, md, m2(b)] {
            // Never NaN; infinite entries only from infinite input or overflow (the NaN
            // policy saturates them).
            let f1 = footprint(jm, &frame, dx_u, dx_v);
            assert!(
                !(f1.dh_u.is_nan() || f1.dh_v.is_nan()),
                "footprint = {f1:?}"
            );
            // A bound on every product of the map and on the frame projections before it
            // (sums of three terms, then of two); NaN entries count as 0 (the policy).
            let amax = |xs: &[F]| {
                xs.iter()
                    .fold(0.0, |m: F, x| if x.abs() > m { x.abs() } else { m })
            };
            let big = 6.0
                * amax(&jm.to_cols_array()).max(1.0)
                * amax(&frame.s.to_array()).max(amax(&frame.t.to_array()))
                * amax(&dx_u.to_array()).max(amax(&dx_v.to_array()));
            if big <= 1e30 {
                assert!(
                    fp_fin(&f1),
                    "footprint = {f1:?} for {jm:?}, {frame:?}, {dx_u:?}, {dx_v:?}"
                );
            }
        }
        let fpp = footprint_projected(fp, h);
        assert!(
            !(fpp.dh_u.is_nan() || fpp.dh_v.is_nan()),
            "footprint_projected({fp:?}, {h:?}) = {fpp:?}"
        );
        if fp_fin(&fp) {
            let m = fp.dh_u.abs().max(fp.dh_v.abs()).max_element();
            if m <= 1e30 {
                assert!(fp_fin(&fpp), "footprint_projected({fp:?}, {h:?}) = {fpp:?}");
            }
        }
        if let Some((du, dv)) = tangent_plane_differentials(&ray, x, frame.n) {
            assert!(
                du.is_finite() && dv.is_finite(),
                "tangent_plane_differentials"
            );
        }
        let _: F = 0.0;
        let _ = geometry::half_vector;
    }};
}

/// The Jacobian, slope-map and geometric-footprint contract on fuzzer bytes, in both
/// precisions. Panics on a violation of: `jacobian::sanitize` unit with `h_z >= HZ_MIN`;
/// `spherical_basis` unit vectors; the four Jacobian matrices finite for any `h`; the
/// determinants in `[HZ_MIN, 1]`, `[1, 1e24]`, `[1, 1e18]`; `spherical_components`,
/// `spherical_to_slope`, `spherical_to_projected` NaN-free / finite for finite vectors that
/// cannot overflow; the slope maps finite (unit directions in the upper hemisphere) for finite
/// input; `geometry::half_vector` NaN-free, the three half-vector Jacobians finite for any
/// input, `footprint` NaN-free (finite where the frame projections and the products stay below `1e30`), `footprint_projected` NaN-free (finite for finite footprints), the
/// differentials of `tangent_plane_differentials` finite when returned.
pub fn check_jacobian(data: &[u8]) {
    jacobian_prec!(d64, f64, &mut Bytes::new(data));
    jacobian_prec!(d32, f32, &mut Bytes::new(data));
}
