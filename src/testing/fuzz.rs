//! The byte decoder and the contract checks shared by the cargo-fuzz targets (`fuzz/`) and
//! their fixed-seed replay in CI (`tests/fuzz_replay.rs`), so that both check the same thing.
//!
//! [`Bytes`] turns arbitrary bytes into floats such that short byte patterns reach every
//! special value: NaN, `+-inf`, `0`, `-0`, `+-1e-30`, `+-1e30`, subnormals of both precisions,
//! the largest finite values, plus ordinary values on a linear and on a logarithmic scale.
//! [`check_ndf`] decodes an NDF case and its arguments and panics if the documented contract
//! is broken (see the function). One `check_*` function per further public evaluation family
//! lives in a submodule and is re-exported here: [`check_filter`], [`check_rect`],
//! [`check_isotropic`], [`check_jacobian`], [`check_sampling`], [`check_temporal`],
//! [`check_gaussian_ggx`], [`check_batch`].

use crate::RoughnessError;

mod batch;
mod dec;
mod filter;
mod gaussian_ggx;
mod isotropic;
mod jacobian;
mod rect;
mod sampling;
mod temporal;

pub use batch::check_batch;
pub use filter::check_filter;
pub use gaussian_ggx::check_gaussian_ggx;
pub use isotropic::check_isotropic;
pub use jacobian::check_jacobian;
pub use rect::check_rect;
pub use sampling::check_sampling;
pub use temporal::check_temporal;

/// A cursor over fuzzer bytes; reads past the end yield zeros, so every input decodes.
#[derive(Clone, Debug)]
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    /// A cursor at the start of `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Self { data, pos: 0 }
    }

    /// The next byte, or `0` past the end.
    pub fn byte(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }

    fn bytes<const N: usize>(&mut self) -> [u8; N] {
        core::array::from_fn(|_| self.byte())
    }

    /// The next float. A tag byte selects (tag mod 20): 0 NaN, 1 `+inf`, 2 `-inf`, 3 `0`,
    /// 4 `-0`, 5 `1e-30`, 6 `-1e-30`, 7 `1e30`, 8 `-1e30`, 9 `1e-40` (an `f32` subnormal),
    /// 10 `5e-324` (the smallest `f64` subnormal), 11 `f32::MAX`, 12 `f64::MAX`, 13 `1`, 14
    /// `-1`; 15..=17 an ordinary value in `[-2, 2]` from two more bytes; 18 a signed value
    /// `10^e` with `e` in `[-45, 45]` from two more bytes; 19 the raw bits of an `f64` from
    /// eight more bytes.
    pub fn float(&mut self) -> f64 {
        match self.byte() % 20 {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => f64::NEG_INFINITY,
            3 => 0.0,
            4 => -0.0,
            5 => 1e-30,
            6 => -1e-30,
            7 => 1e30,
            8 => -1e30,
            9 => 1e-40,
            10 => 5e-324,
            11 => f64::from(f32::MAX),
            12 => f64::MAX,
            13 => 1.0,
            14 => -1.0,
            15..=17 => f64::from(u16::from_le_bytes(self.bytes())) / 16383.75 - 2.0,
            18 => {
                let [a, b] = self.bytes();
                let e = f64::from(a) / 255.0 * 90.0 - 45.0;
                let v = libm::pow(10.0, e);
                if b & 1 == 1 { -v } else { v }
            }
            _ => f64::from_bits(u64::from_le_bytes(self.bytes())),
        }
    }

    /// The next float, rounded to `f32`.
    #[allow(clippy::cast_possible_truncation)]
    pub fn float32(&mut self) -> f32 {
        self.float() as f32
    }
}

/// One decoded NDF evaluation: model, roughness form and parameters, arguments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NdfInput {
    /// `0` GGX, `1` Beckmann.
    pub model: u8,
    /// `0` isotropic, `1` axis-aligned, `2` matrix, `3` matrix with a determinant clamp.
    pub form: u8,
    /// Roughness parameters: `alpha`, `(alpha_x, alpha_y)`, `(a11, a12, a22, tau)`.
    pub params: [f64; 4],
    /// Slope argument of `p22`.
    pub s: [f64; 2],
    /// Micronormal `m`, direction `w` (outgoing) and `i` (incoming).
    pub vecs: [[f64; 3]; 3],
    /// When set, the vectors are normalised (where finite and non-zero) before evaluation.
    pub normalize: bool,
}

impl NdfInput {
    /// Decodes an input from bytes (never fails).
    pub fn decode(b: &mut Bytes<'_>) -> Self {
        let head = b.byte();
        let params = [b.float(), b.float(), b.float(), b.float()];
        let s = [b.float(), b.float()];
        let mut vecs = [[0.0; 3]; 3];
        for v in &mut vecs {
            *v = [b.float(), b.float(), b.float()];
        }
        Self {
            model: head & 1,
            form: (head >> 1) & 3,
            params,
            s,
            vecs,
            normalize: head & 8 != 0,
        }
    }
}

macro_rules! check_precision {
    ($prec:ident, $t:ty, $inp:expr) => {{
        use crate::$prec::{
            AxisAligned, Beckmann, Ggx, Isotropic, Ndf, Roughness, RoughnessMatrix, Vec2, Vec3,
            footprint::slope,
        };
        let inp: &NdfInput = $inp;
        #[allow(clippy::cast_possible_truncation)]
        let c = |x: f64| x as $t;
        let p = inp.params.map(c);
        let fin = |x: &[$t]| x.iter().all(|v| v.is_finite());

        fn eval<R: Roughness>(r: R, model: u8, inp: &NdfInput) {
            #[allow(clippy::cast_possible_truncation)]
            let c = |x: f64| x as $t;
            let s = Vec2::new(c(inp.s[0]), c(inp.s[1]));
            let mut v = inp.vecs.map(|v| Vec3::new(c(v[0]), c(v[1]), c(v[2])));
            if inp.normalize {
                for x in &mut v {
                    *x = x.try_normalize().unwrap_or(*x);
                }
            }
            let [mm, w, i] = v;
            let ndf: &dyn Ndf = match model {
                0 => &Ggx::new(r),
                _ => &Beckmann::new(r),
            };
            let p22 = ndf.p22(s);
            let d = ndf.d(mm);
            let l = ndf.lambda(w);
            let g1 = ndf.g1(w, mm);
            let g2 = ndf.g2(i, w, mm);
            if s.is_finite() {
                assert!(
                    p22.is_finite() && p22 >= 0.0,
                    "p22({s}) = {p22} for {inp:?}"
                );
            }
            if mm.is_finite() {
                assert!(d.is_finite() && d >= 0.0, "d({mm}) = {d} for {inp:?}");
                if mm.z <= 0.0 {
                    assert_eq!(d, 0.0, "d below the horizon for {inp:?}");
                }
            }
            if w.is_finite() {
                // Lambda may overflow to +inf (w_z = 0, or w_z tiny against w_xy), never NaN.
                assert!(l >= 0.0, "lambda({w}) = {l} for {inp:?}");
                if mm.is_finite() {
                    assert!((0.0..=1.0).contains(&g1), "g1 = {g1} for {inp:?}");
                    if w.dot(mm) <= 0.0 {
                        assert_eq!(g1, 0.0, "chi+ of g1 for {inp:?}");
                    }
                    if i.is_finite() {
                        assert!((0.0..=1.0).contains(&g2), "g2 = {g2} for {inp:?}");
                        assert!(g2 <= g1, "g2 {g2} > g1 {g1} for {inp:?}");
                    }
                }
            }
        }

        let fam = inp.model;
        let range = (
            f64::from(crate::$prec::ALPHA_MIN),
            f64::from(crate::$prec::ALPHA_MAX),
        );
        match inp.form {
            0 => {
                let r = Isotropic::new(p[0]);
                expect_alpha_error(&[p[0].into()], range, r.map(|_| ()));
                if let Ok(r) = r {
                    eval(r, fam, inp);
                }
                eval(Isotropic::new_clamped(p[0]), fam, inp);
            }
            1 => {
                let r = AxisAligned::new(p[0], p[1]);
                expect_alpha_error(&[p[0].into(), p[1].into()], range, r.map(|_| ()));
                if let Ok(r) = r {
                    eval(r, fam, inp);
                    eval(r.to_matrix(), fam, inp);
                }
                eval(AxisAligned::new_clamped(p[0], p[1]), fam, inp);
            }
            f => {
                let tau = if f == 3 { p[3] } else { 0.0 };
                let r = RoughnessMatrix::new_with_det_clamp(p[0], p[1], p[2], tau);
                match r {
                    Ok(r) => {
                        assert!(fin(&[p[0], p[1], p[2], tau]) && p[0] > 0.0 && p[2] > 0.0);
                        assert!(r.sqrt_det() > 0.0 && r.sqrt_det().is_finite());
                        eval(r, fam, inp);
                        eval(r.with_det_clamp(p[3]), fam, inp);
                    }
                    Err(e) => {
                        if !fin(&[p[0], p[1], p[2], tau]) {
                            assert_eq!(e, RoughnessError::NotFinite, "{inp:?}");
                        } else if p[0] <= 0.0 || p[2] <= 0.0 || tau < 0.0 {
                            assert_eq!(e, RoughnessError::NotPositive, "{inp:?}");
                        }
                    }
                }
                let m2 =
                    crate::$prec::Mat2::from_cols(Vec2::new(p[0], p[1]), Vec2::new(p[3], p[2]));
                if let Ok(r) = RoughnessMatrix::from_mat2(m2) {
                    eval(r, fam, inp);
                }
            }
        }

        // The slope maps: finite in, finite out.
        let h = Vec3::new(c(inp.vecs[0][0]), c(inp.vecs[0][1]), c(inp.vecs[0][2]));
        let sl = Vec2::new(c(inp.s[0]), c(inp.s[1]));
        if h.is_finite() {
            assert!(
                slope::slope_from_sphere(h).is_finite(),
                "slope_from_sphere({h})"
            );
            let p = slope::projected_from_sphere(h).truncate_or_self();
            assert!(
                slope::sphere_from_projected(p).is_finite(),
                "sphere_from_projected({p})"
            );
            assert!(
                slope::slope_from_projected(p).is_finite(),
                "slope_from_projected({p})"
            );
        }
        if sl.is_finite() {
            assert!(
                slope::sphere_from_slope(sl).is_finite(),
                "sphere_from_slope({sl})"
            );
            assert!(
                slope::projected_from_slope(sl).is_finite(),
                "projected_from_slope({sl})"
            );
        }
    }};
}

/// Identity for a `Vec2` (lets the slope check above read uniformly).
trait TruncateOrSelf {
    fn truncate_or_self(self) -> Self;
}
impl TruncateOrSelf for glam::Vec2 {
    fn truncate_or_self(self) -> Self {
        self
    }
}
impl TruncateOrSelf for glam::DVec2 {
    fn truncate_or_self(self) -> Self {
        self
    }
}

/// Checks the error of a checked scalar-roughness constructor against its documented rule:
/// the first failing `alpha` decides, NaN / inf before non-positive before out of
/// `[lo, hi]`.
fn expect_alpha_error(alphas: &[f64], (lo, hi): (f64, f64), got: Result<(), RoughnessError>) {
    let want = alphas.iter().find_map(|&a| {
        if !a.is_finite() {
            Some(RoughnessError::NotFinite)
        } else if a <= 0.0 {
            Some(RoughnessError::NotPositive)
        } else if !(lo..=hi).contains(&a) {
            Some(RoughnessError::OutOfRange)
        } else {
            None
        }
    });
    match (want, got) {
        (Some(w), Err(e)) => assert_eq!(w, e, "alphas {alphas:?}"),
        (Some(w), Ok(())) => panic!("alphas {alphas:?} accepted, want {w:?}"),
        (None, Err(e)) => panic!("alphas {alphas:?} refused with {e:?}"),
        (None, Ok(())) => {}
    }
}

/// The contract of the NDF family on fuzzer bytes, in both precisions: no panic; a checked
/// constructor returns the documented error for NaN / infinite (`NotFinite`), zero or
/// negative (`NotPositive`) and out-of-range (`OutOfRange`) roughness; for finite arguments
/// `p22` and `d` are finite and `>= 0` (`d = 0` below the horizon), `lambda >= 0` (not NaN; `+inf` where it
/// overflows), `g1` and `g2` in `[0, 1]` with `g1 = 0` when `w.m <= 0` and `g2 <= g1`;
/// the slope maps return finite vectors for finite input. Panics on a violation.
pub fn check_ndf(data: &[u8]) {
    let mut b = Bytes::new(data);
    let inp = NdfInput::decode(&mut b);
    check_precision!(f64, f64, &inp);
    check_precision!(f32, f32, &inp);
}
