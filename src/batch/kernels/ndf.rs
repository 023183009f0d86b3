//! The unfiltered NDF terms over slices: `D`, Smith `Lambda` and height-correlated `G2` of GGX
//! and Beckmann in every roughness form.
//!
//! Each lane evaluates the scalar path's own formula core (`Ggx::d_unchecked`,
//! `Roughness::inv_quadratic` / `quadratic` / `exponent_and_norm`, `ggx_lambda_core`); the
//! scalar function's checks become selects, and the rare inputs they send elsewhere
//! (a rescaled direction, a grazing `w`) are flagged and evaluated by the scalar function.
//! GGX's `D`, `Lambda` and `G2` are therefore the scalar values bit for bit; Beckmann's
//! replace libm's `exp` and `erfc` by the engine's lane math (bounds in the module docs of
//! `batch`).

use super::super::super::filter::beckmann_lambda_fast;
use super::super::super::ndf::beckmann::Beckmann;
use super::super::super::ndf::ggx::{Ggx, ggx_lambda_core};
use super::super::super::ndf::roughness::Roughness;
use super::super::super::ndf::{Ndf, needs_no_rescale};
use super::super::super::{F, PI, Vec2, Vec3};
use super::super::columns::Vec3s;
use super::super::engine::lane_math::exp_neg_times;
use super::super::engine::{CARRY, Carry, Kernel, run};

per_form! {
    /// [`Ndf::d`] of GGX for each micronormal `m_i = (mx[i], my[i], mz[i])`:
    /// `out[i] = Ggx::new(*r).d(m_i) = 1 / (pi sqrt(det A) m_z^4 (1 + m_xy^T A^-1 m_xy / m_z^2)^2)`
    /// per steradian (TK19 supplement sec. 1), **bit for bit**. Any `m` (unit or not); `0` for
    /// `m_z <= 0` and NaN input. Returns the number of elements written (the shortest slice
    /// length). Allocates nothing.
    pub fn ggx_d(r: &R, mx: &[F], my: &[F], mz: &[F], out: &mut [F]) -> usize {
        run(&D(Ggx::new(*r)), [mx, my, mz], [out])
    }
}

per_form! {
    /// [`Ndf::d`] of Beckmann for each micronormal:
    /// `out[i] = Beckmann::new(*r).d(m_i) = exp(-m_xy^T A^-1 m_xy / m_z^2) / (pi sqrt(det A)
    /// m_z^4)` per steradian (KHPL16 eq. 2), within the bound of the module docs of [`batch`](super::super)
    /// (relative `2.5e-7 + 2 eps` in `f32`: the exponential in lanes). `0` for `m_z <= 0`, NaN
    /// input and results below `F::MIN_POSITIVE`. Returns the number of elements written.
    /// Allocates nothing.
    pub fn beckmann_d(r: &R, mx: &[F], my: &[F], mz: &[F], out: &mut [F]) -> usize {
        run(&D(Beckmann::new(*r)), [mx, my, mz], [out])
    }
}

per_form! {
    /// Smith's [`Ndf::lambda`] of GGX for each direction `w_i = (wx[i], wy[i], wz[i])`:
    /// `out[i] = Ggx::new(*r).lambda(w_i) = (sqrt(1 + w_xy^T A w_xy / w_z^2) - 1) / 2`
    /// (dimensionless, Heitz 2014), **bit for bit**; out of domain as the scalar function (`+inf`
    /// for NaN or `w_z = 0` with `w_xy != 0`). Returns the number of elements written. Allocates
    /// nothing.
    pub fn ggx_lambda(r: &R, wx: &[F], wy: &[F], wz: &[F], out: &mut [F]) -> usize {
        run(&Lambda(Ggx::new(*r)), [wx, wy, wz], [out])
    }
}

per_form! {
    /// Smith's [`Ndf::lambda`] of Beckmann for each direction:
    /// `out[i] = Beckmann::new(*r).lambda(w_i) = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2`,
    /// `a = |w_z| / sqrt(w_xy^T A w_xy)` (dimensionless, Heitz 2014), within the bound of the
    /// module docs of [`batch`](super::super) (absolute `2.1e-7 (1 + Lambda)` in `f32`: the `erfc` fit shared
    /// with the exact Gaussian filter's sampler); out of domain as the scalar function. Returns
    /// the number of elements written. Allocates nothing.
    pub fn beckmann_lambda(r: &R, wx: &[F], wy: &[F], wz: &[F], out: &mut [F]) -> usize {
        run(&Lambda(Beckmann::new(*r)), [wx, wy, wz], [out])
    }
}

per_form! {
    /// Height-correlated Smith `G2(i, o, m) = chi+(i.m) chi+(o.m) / (1 + Lambda(i) + Lambda(o))`
    /// of GGX ([`Ndf::g2`], Heitz 2014, height-correlated form) for each triple of directions:
    /// `out[k] = Ggx::new(*r).g2(i_k, o_k, m_k)`, **bit for bit**; in `[0, 1]`, `0` for NaN.
    /// Returns the number of elements written (the shortest of the ten slices). Allocates
    /// nothing.
    pub fn ggx_g2(
        r: &R,
        i: Vec3s<'_>,
        o: Vec3s<'_>,
        m: Vec3s<'_>,
        out: &mut [F],
    ) -> usize {
        run(&G2(Ggx::new(*r)), nine([i, o, m]), [out])
    }
}

per_form! {
    /// Height-correlated Smith `G2(i, o, m)` of Beckmann (as [`ggx_g2`]) for each triple of
    /// directions: `out[k] = Beckmann::new(*r).g2(i_k, o_k, m_k)` within the bound of the module
    /// docs of [`batch`](super::super) (relative `4.2e-7 + 3 eps` in `f32`, plus the amplified rounding of
    /// `a`). Returns the number of elements written. Allocates nothing.
    pub fn beckmann_g2(
        r: &R,
        i: Vec3s<'_>,
        o: Vec3s<'_>,
        m: Vec3s<'_>,
        out: &mut [F],
    ) -> usize {
        run(&G2(Beckmann::new(*r)), nine([i, o, m]), [out])
    }
}

/// The nine columns of three vectors.
#[inline(always)]
fn nine<'a>([i, o, m]: [Vec3s<'a>; 3]) -> [&'a [F]; 9] {
    [i.x, i.y, i.z, o.x, o.y, o.z, m.x, m.y, m.z]
}

/// The lane form of an NDF's `D` (`(value, slow)`, see [`Kernel::lane`]): GGX, Beckmann and
/// the exact Gaussian-filtered GGX.
pub(crate) trait LaneD: Ndf {
    /// `D(m)`.
    fn d_lane(&self, m: Vec3) -> (F, bool);
    /// Whether `D` has a second, costlier lane for what [`LaneD::d_lane`] flags
    /// ([`Kernel::TIERED`]).
    const TIERED: bool = false;
    /// [`Kernel::FULL_COVERS`].
    const FULL_COVERS: bool = true;
    /// [`Kernel::FULL_WIDE_ONLY`].
    const FULL_WIDE_ONLY: bool = false;
    /// [`Kernel::second`].
    #[inline(always)]
    fn d_second(&self, _m: Vec3) -> bool {
        false
    }
    /// The second lane of a [`LaneD::TIERED`] `D`.
    #[inline(always)]
    fn d_lane_full(&self, m: Vec3) -> (F, bool) {
        self.d_lane(m)
    }
    /// [`Kernel::FULL_STAGED`].
    const FULL_STAGED: bool = false;
    /// [`Kernel::full_one`].
    #[inline(always)]
    fn d_full_one(&self, m: Vec3) -> ((F, bool), bool, Carry) {
        (self.d_lane_full(m), false, [0.0; CARRY])
    }
    /// [`Kernel::full_two`].
    #[inline(always)]
    fn d_full_two(&self, m: Vec3, _carry: Carry) -> (F, bool) {
        self.d_lane_full(m)
    }
}

/// The lane form of an NDF's `Lambda` too (GGX, Beckmann).
pub(crate) trait LaneNdf: LaneD {
    /// `Lambda(w)`.
    fn lambda_lane(&self, w: Vec3) -> (F, bool);
}

impl<R: Roughness> LaneD for Ggx<R> {
    /// [`Ndf::d`]'s checks as one select (`&`, and `abs() < inf` rather than `is_finite`, which
    /// compiles to integer bit tests): the same value, bit for bit, without a branch.
    #[inline(always)]
    fn d_lane(&self, m: Vec3) -> (F, bool) {
        let v = self.d_unchecked(m);
        let keep = (m.z > 0.0) & (v.abs() < F::INFINITY);
        (if keep { v } else { 0.0 }, false)
    }
}

impl<R: Roughness> LaneNdf for Ggx<R> {
    /// `ggx_lambda_core` where the scalar path takes it (no rescaling, `q >= 0`, `|w_z| > 0`,
    /// `w_z^2 + q` finite, a normal denominator), flagged elsewhere.
    #[inline(always)]
    fn lambda_lane(&self, w: Vec3) -> (F, bool) {
        let q = self.roughness.quadratic(Vec2::new(w.x, w.y));
        let az = w.z.abs();
        let fast = needs_no_rescale(w) & (q >= 0.0) & (az > 0.0) & (az * az + q < F::INFINITY);
        let (lambda, normal) = ggx_lambda_core(q, az);
        (lambda, !(fast & normal))
    }
}

impl<R: Roughness> LaneD for Beckmann<R> {
    /// The formula of Beckmann's `d` (`exponent_and_norm`, then `e^-x n / pi`) with the
    /// exponential of [`exp_neg_times`]. `0` below the horizon and for a NaN exponent, as the
    /// scalar path.
    #[inline(always)]
    fn d_lane(&self, m: Vec3) -> (F, bool) {
        let (x, n) = self
            .roughness
            .exponent_and_norm(Vec2::new(m.x, m.y), m.z * m.z);
        let (v, ok) = exp_neg_times(x, n * (1.0 / PI));
        let live = (m.z > 0.0) & !x.is_nan();
        (if live { v } else { 0.0 }, live & !ok)
    }
}

impl<R: Roughness> LaneNdf for Beckmann<R> {
    /// `Lambda(a)`, `a = |w_z| / sqrt(w_xy^T A w_xy)`, by `beckmann_lambda_fast` (`0` at
    /// normal incidence, `q = 0`), flagged where the scalar path rescales `w`, at grazing `w`
    /// and for `a < 1e-20` (where `Lambda` leaves the range of `F`).
    #[inline(always)]
    #[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
    fn lambda_lane(&self, w: Vec3) -> (F, bool) {
        let q = self.roughness.quadratic(Vec2::new(w.x, w.y));
        let a = w.z.abs() / crate::math::sqrt(q);
        let v = beckmann_lambda_fast(a);
        let fast = needs_no_rescale(w) & (q >= 0.0) & (q < F::INFINITY) & (a >= 1e-20);
        (if q > 0.0 { v } else { 0.0 }, !fast)
    }
}

/// `D` of an NDF.
pub(super) struct D<N>(pub(super) N);

impl<N: LaneD> Kernel<3, 1> for D<N> {
    const TIERED: bool = N::TIERED;
    const FULL_COVERS: bool = N::FULL_COVERS;
    const FULL_WIDE_ONLY: bool = N::FULL_WIDE_ONLY;
    #[inline(always)]
    fn lane(&self, [x, y, z]: [F; 3]) -> ([F; 1], bool) {
        let (v, slow) = self.0.d_lane(Vec3::new(x, y, z));
        ([v], slow)
    }
    #[inline(always)]
    fn lane_full(&self, [x, y, z]: [F; 3]) -> ([F; 1], bool) {
        let (v, slow) = self.0.d_lane_full(Vec3::new(x, y, z));
        ([v], slow)
    }
    #[inline(always)]
    fn second(&self, [x, y, z]: [F; 3]) -> bool {
        self.0.d_second(Vec3::new(x, y, z))
    }
    const FULL_STAGED: bool = N::FULL_STAGED;
    #[inline(always)]
    fn full_one(&self, [x, y, z]: [F; 3]) -> (([F; 1], bool), bool, Carry) {
        let ((v, slow), more, carry) = self.0.d_full_one(Vec3::new(x, y, z));
        (([v], slow), more, carry)
    }
    #[inline(always)]
    fn full_two(&self, [x, y, z]: [F; 3], carry: Carry) -> ([F; 1], bool) {
        let (v, slow) = self.0.d_full_two(Vec3::new(x, y, z), carry);
        ([v], slow)
    }
    #[inline]
    fn scalar(&self, [x, y, z]: [F; 3]) -> [F; 1] {
        [self.0.d(Vec3::new(x, y, z))]
    }
}

/// `Lambda` of an NDF.
struct Lambda<N>(N);

impl<N: LaneNdf> Kernel<3, 1> for Lambda<N> {
    #[inline(always)]
    fn lane(&self, [x, y, z]: [F; 3]) -> ([F; 1], bool) {
        let (v, slow) = self.0.lambda_lane(Vec3::new(x, y, z));
        ([v], slow)
    }
    #[inline]
    fn scalar(&self, [x, y, z]: [F; 3]) -> [F; 1] {
        [self.0.lambda(Vec3::new(x, y, z))]
    }
}

/// `G2` of an NDF: [`Ndf::g2`]'s formula, `chi+(i.m) chi+(o.m) / (1 + Lambda(i) +
/// Lambda(o))`, its check as a select.
struct G2<N>(N);

impl<N: LaneNdf> Kernel<9, 1> for G2<N> {
    #[inline(always)]
    fn lane(&self, [ix, iy, iz, ox, oy, oz, mx, my, mz]: [F; 9]) -> ([F; 1], bool) {
        let (wi, wo, m) = (
            Vec3::new(ix, iy, iz),
            Vec3::new(ox, oy, oz),
            Vec3::new(mx, my, mz),
        );
        let ((li, si), (lo, so)) = (self.0.lambda_lane(wi), self.0.lambda_lane(wo));
        let front = (wi.dot(m) > 0.0) & (wo.dot(m) > 0.0);
        let v = 1.0 / (1.0 + li + lo);
        ([if front { v } else { 0.0 }], front & (si | so))
    }
    #[inline]
    fn scalar(&self, [ix, iy, iz, ox, oy, oz, mx, my, mz]: [F; 9]) -> [F; 1] {
        [self.0.g2(
            Vec3::new(ix, iy, iz),
            Vec3::new(ox, oy, oz),
            Vec3::new(mx, my, mz),
        )]
    }
}
