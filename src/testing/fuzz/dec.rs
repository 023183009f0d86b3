//! Per-precision decoders shared by the family checks: scalars, vectors, valid roughness in
//! every form, and the NDF evaluation contract of `check_ndf` for any `&dyn Ndf`.
//!
//! Every check decodes the same bytes once per precision (`d64` then `d32`), so both
//! precisions see the same values (the `f32` ones rounded from the `f64` ones).

macro_rules! decoders {
    ($d:ident, $prec:ident) => {
        pub(crate) mod $d {
            use super::super::Bytes;
            use crate::math::Real;
            #[allow(unused_imports)]
            use crate::$prec::{
                AxisAligned, F, Isotropic, Mat2, Ndf, Roughness, RoughnessMatrix, Vec2, Vec3,
            };

            /// Relative tolerance for "a few ulps" (rounding of a handful of operations).
            pub(crate) const TOL: F = 64.0 * F::EPSILON;

            pub(crate) fn f(b: &mut Bytes<'_>) -> F {
                F::from_f64(b.float())
            }

            pub(crate) fn v2(b: &mut Bytes<'_>) -> Vec2 {
                let x = f(b);
                Vec2::new(x, f(b))
            }

            pub(crate) fn v3(b: &mut Bytes<'_>) -> Vec3 {
                let x = f(b);
                let y = f(b);
                Vec3::new(x, y, f(b))
            }

            pub(crate) fn m2(b: &mut Bytes<'_>) -> Mat2 {
                let x = v2(b);
                Mat2::from_cols(x, v2(b))
            }

            /// `v` normalised without overflow or underflow, when finite and non-zero
            /// (the crate's one helper, `vector::unit`).
            pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
                crate::$prec::vector::unit(v)
            }

            /// A vector decoded raw, normalised when the header bit says so (and possible).
            pub(crate) fn dir(b: &mut Bytes<'_>, normalize: bool) -> Vec3 {
                let v = v3(b);
                if normalize { unit(v).unwrap_or(v) } else { v }
            }

            fn m_sqrt(x: F) -> F {
                crate::math::sqrt(x)
            }

            /// `|len(v) - 1| <= tol`.
            pub(crate) fn is_unit(v: Vec3) -> bool {
                v.is_finite() && (m_sqrt(v.length_squared()) - 1.0).abs() <= TOL
            }

            /// A valid roughness in one of the three forms.
            #[derive(Clone, Copy, Debug)]
            pub(crate) enum Rough {
                Iso(Isotropic),
                Axis(AxisAligned),
                Mat(RoughnessMatrix),
            }

            /// Decodes a valid roughness: clamped isotropic / axis-aligned, or a matrix either
            /// from raw entries (when the checked constructor accepts them) or rotated from
            /// two clamped alphas, with a determinant clamp `tau` of `0`, `det A` or raw.
            pub(crate) fn rough(b: &mut Bytes<'_>) -> Rough {
                let head = b.byte();
                let (p0, p1, p2, p3) = (f(b), f(b), f(b), f(b));
                match head % 4 {
                    0 => Rough::Iso(Isotropic::new_clamped(p0)),
                    1 => Rough::Axis(AxisAligned::new_clamped(p0, p1)),
                    2 => {
                        let tau = if head & 4 != 0 { p3 } else { 0.0 };
                        match RoughnessMatrix::new_with_det_clamp(p0, p1, p2, tau) {
                            Ok(r) => Rough::Mat(r),
                            Err(_) => Rough::Mat(AxisAligned::new_clamped(p0, p2).to_matrix()),
                        }
                    }
                    _ => {
                        let a = AxisAligned::new_clamped(p0, p1).alpha();
                        let th = if p2.is_finite() { p2 } else { 0.0 };
                        let (c, s) = (crate::math::cos(th), crate::math::sin(th));
                        let (l1, l2) = (a.x * a.x, a.y * a.y);
                        let a11 = c * c * l1 + s * s * l2;
                        let a12 = c * s * (l1 - l2);
                        let a22 = s * s * l1 + c * c * l2;
                        let tau = match (head >> 2) % 3 {
                            0 => 0.0,
                            1 => l1 * l2,
                            _ => p3,
                        };
                        match RoughnessMatrix::new_with_det_clamp(a11, a12, a22, tau) {
                            Ok(r) => Rough::Mat(r),
                            Err(_) => Rough::Mat(AxisAligned::new(a.x, a.y).unwrap().to_matrix()),
                        }
                    }
                }
            }

            /// The NDF contract of `check_ndf` for one evaluation (arguments finite, as the
            /// caller guarantees by construction or checks here): `p22`, `d` finite and
            /// `>= 0` (`d = 0` below the horizon), `lambda >= 0`, `g1`, `g2` in `[0, 1]`,
            /// `g1 = 0` for `w.m <= 0`, `g2 <= g1`.
            pub(crate) fn ndf_contract(
                ndf: &dyn Ndf,
                s: Vec2,
                mm: Vec3,
                w: Vec3,
                i: Vec3,
                what: &str,
            ) {
                if s.is_finite() {
                    let p = ndf.p22(s);
                    assert!(p.is_finite() && p >= 0.0, "{what}: p22({s}) = {p}");
                }
                if mm.is_finite() {
                    let d = ndf.d(mm);
                    assert!(d.is_finite() && d >= 0.0, "{what}: d({mm}) = {d}");
                    if mm.z <= 0.0 {
                        assert_eq!(d, 0.0, "{what}: d below the horizon");
                    }
                }
                if w.is_finite() {
                    let l = ndf.lambda(w);
                    assert!(l >= 0.0, "{what}: lambda({w}) = {l}");
                    if mm.is_finite() {
                        let g1 = ndf.g1(w, mm);
                        assert!((0.0..=1.0).contains(&g1), "{what}: g1 = {g1}");
                        if w.dot(mm) <= 0.0 {
                            assert_eq!(g1, 0.0, "{what}: chi+ of g1");
                        }
                        if i.is_finite() {
                            let g2 = ndf.g2(i, w, mm);
                            assert!((0.0..=1.0).contains(&g2), "{what}: g2 = {g2}");
                            assert!(g2 <= g1, "{what}: g2 {g2} > g1 {g1}");
                        }
                    }
                }
            }

            /// A filtered (or otherwise derived) roughness matrix is usable: finite entries,
            /// positive diagonal, `sqrt_det` finite and `> 0`.
            pub(crate) fn valid_matrix(r: &RoughnessMatrix, what: &str) {
                let (a11, a12, a22) = r.entries();
                let sd = r.sqrt_det();
                assert!(
                    a11.is_finite() && a12.is_finite() && a22.is_finite() && a11 > 0.0 && a22 > 0.0,
                    "{what}: entries {:?}",
                    r.entries()
                );
                assert!(
                    sd.is_finite() && sd > 0.0,
                    "{what}: sqrt_det {sd} of {:?}",
                    r.entries()
                );
            }
        }
    };
}

decoders!(d64, f64);
decoders!(d32, f32);

/// `with_rough!(d64, rough, r => expr)`: evaluates `expr` with `r` bound to the concrete
/// roughness inside a decoded `Rough` (the expression is instantiated once per form).
macro_rules! with_rough {
    ($d:ident, $rough:expr, $r:ident => $body:expr) => {
        match $rough {
            $crate::testing::fuzz::dec::$d::Rough::Iso($r) => $body,
            $crate::testing::fuzz::dec::$d::Rough::Axis($r) => $body,
            $crate::testing::fuzz::dec::$d::Rough::Mat($r) => $body,
        }
    };
}
pub(crate) use with_rough;
