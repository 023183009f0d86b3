//! The Gaussian-filtered NDFs over slices (the front door's `Gaussian` method: KHPL16's exact
//! filtered Beckmann, TK19's `A + 2 Sigma` for GGX): each half vector with its own pixel
//! footprint through the clamp rules, one material for the whole batch.

use super::super::super::kernel::{ClampRules, Narrow};
use super::super::super::ndf::Ndf;
use super::super::super::ndf::beckmann::Beckmann;
use super::super::super::ndf::ggx::Ggx;
use super::super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::super::super::{F, PI, Vec2, Vec3};
use super::super::columns::{Footprints, footprint, footprint_columns};
use super::super::engine::lane_math::{K_MAX, WIDE, exp_neg_times};
use super::super::engine::{Kernel, Mid, run};
use super::ndf::LaneD;
use core::marker::PhantomData;

per_form! {
    /// Filtered Beckmann (exact Gaussian filtering, KHPL16 eq. 15) through the clamped pipeline
    /// for each half vector and footprint: `out[i] = Beckmann::new(rules.filter_gaussian(*r,
    /// fp_i, sigma)).d(h_i)` ([`ClampRules::filter_gaussian`]: footprint extent, kernel
    /// roughness `kappa`, determinant clamp; [`ClampRules::NONE`] for none), `sigma` the pixel
    /// filter's standard deviation in pixels (e.g. [`super::super::super::kernel::SIGMA_PIXEL`]).
    /// Returns the number of elements written. Allocates nothing.
    ///
    /// In `f32` the first lane builds `A'` in `f32` arithmetic (the `kappa` clamp by the
    /// footprint's own determinant and one division), within the module table's bound of the
    /// `f64` pipeline rather than bit for bit with the scalar route (one division and one
    /// square root fewer per element than the scalar route's matrix; module docs).
    #[allow(clippy::too_many_arguments)]
    pub fn beckmann_d_filtered(
        r: &R,
        rules: &ClampRules,
        sigma: F,
        hx: &[F],
        hy: &[F],
        hz: &[F],
        fp: Footprints<'_>,
        out: &mut [F],
    ) -> usize {
        d_filtered::<_, Beckmann<RoughnessMatrix>>(r, rules, sigma, [hx, hy, hz], fp, out)
    }
}

per_form! {
    /// Filtered GGX with the TK19 (section 2.2) matrix approximation `A' = A + 2 Sigma` through
    /// the clamped pipeline for each half vector and footprint: `out[i] =
    /// Ggx::new(rules.filter_gaussian(*r, fp_i, sigma)).d(h_i)` (see [`beckmann_d_filtered`]).
    /// Returns the number of elements written. Allocates nothing.
    ///
    /// In `f32` the first lane is Beckmann's narrow one (`A'`, `x` and `n` in `f32` arithmetic),
    /// then `D = n / (pi (1 + x)^2)`: within the module table's bound of the `f64` pipeline rather
    /// than bit for bit with the scalar route.
    #[allow(clippy::too_many_arguments)]
    pub fn ggx_d_filtered(
        r: &R,
        rules: &ClampRules,
        sigma: F,
        hx: &[F],
        hy: &[F],
        hz: &[F],
        fp: Footprints<'_>,
        out: &mut [F],
    ) -> usize {
        d_filtered::<_, Ggx<RoughnessMatrix>>(r, rules, sigma, [hx, hy, hz], fp, out)
    }
}

/// An NDF of a filtered matrix, as the Gaussian-filtered lanes evaluate it.
trait FilteredNdf: LaneD + Ndf + Sized {
    /// Whether the first tier in `f32` is the narrow lane (the filtered matrix in `f32`
    /// arithmetic, `Narrow::entries`, then the exponent and norm in `f32`,
    /// `RoughnessMatrix::exponent_and_norm_narrow`), within a stated error of the scalar
    /// route's instead of bit for bit, for an NDF whose [`FilteredNdf::d_narrow`] has the
    /// matching bound; else the scalar route's matrix.
    const NARROW: bool = false;
    /// The NDF of `A'` (`Ggx::new`, `Beckmann::new`).
    fn of(a: RoughnessMatrix) -> Self;
    /// The narrow lane's `D` from the exponent `x = m^T A^-1 m / m_z^2` (`x >= 0`, not NaN
    /// where the narrow flags hold) and the factor `k = 1 / (pi sqrt(det A) m_z^4)`: `(D, ok)`,
    /// `ok` where `D` is within its stated bound (module table). Used where
    /// [`FilteredNdf::NARROW`] only.
    fn d_narrow(x: F, k: F) -> (F, bool);
    /// `D(m)` of the matrix with entries `e` where the determinant clamp `tau` is inactive, in
    /// the first tier: `(D, flagged)`. In `f32` for a [`FilteredNdf::NARROW`] NDF the narrow
    /// exponent and norm (its flags: a correlation `rho^2 > 3/4`, a determinant near `tau`, a
    /// step near the range limits) and [`FilteredNdf::d_narrow`]: the whole lane at the full
    /// `f32` width. Otherwise the scalar path's matrix and the NDF's lane `D` (bit for bit where
    /// not flagged).
    #[inline(always)]
    fn d_entries_lane(e: (F, F, F), tau: f64, m: Vec3) -> (F, bool) {
        if WIDE || !Self::NARROW {
            return d_entries_exact::<Self>(e, tau, m);
        }
        let (x, n, matrix_ok, eval_ok) = RoughnessMatrix::exponent_and_norm_narrow(
            e.0,
            e.1,
            e.2,
            tau,
            Vec2::new(m.x, m.y),
            m.z * m.z,
        );
        let (v, ok) = Self::d_narrow(x, n * (1.0 / PI));
        let live = m.z > 0.0;
        (
            if live { v } else { 0.0 },
            !matrix_ok | (live & !(eval_ok & ok)),
        )
    }
}

/// [`FilteredNdf::d_entries_lane`]'s default: the scalar path's matrix
/// (`RoughnessMatrix::from_entries_unclamped`, flagged where its clamp would act) and the
/// NDF's lane `D`.
#[inline(always)]
fn d_entries_exact<N: FilteredNdf>((a11, a12, a22): (F, F, F), tau: f64, m: Vec3) -> (F, bool) {
    let (a, ok) = RoughnessMatrix::from_entries_unclamped(a11, a12, a22, tau);
    let (v, slow) = N::of(a).d_lane(m);
    (v, slow | !ok)
}

impl FilteredNdf for Ggx<RoughnessMatrix> {
    const NARROW: bool = true;
    #[inline(always)]
    fn of(a: RoughnessMatrix) -> Self {
        Ggx::new(a)
    }
    /// `D = k / (1 + x)^2`; a result off `[F::MIN_POSITIVE, F::MAX]` flagged.
    #[inline(always)]
    fn d_narrow(x: F, k: F) -> (F, bool) {
        let q = 1.0 + x;
        let v = k / (q * q);
        (v, (F::MIN_POSITIVE..=F::MAX).contains(&v))
    }
}

impl FilteredNdf for Beckmann<RoughnessMatrix> {
    const NARROW: bool = true;
    #[inline(always)]
    fn of(a: RoughnessMatrix) -> Self {
        Beckmann::new(a)
    }
    /// `D = k exp(-x)` by the `D` lane's exponential; where the narrow flags hold, `x >= 0` is
    /// not NaN (`num >= 0`, `0 < t <= 2^100`): only the factor's range is `exp_neg_times`' to
    /// check.
    #[inline(always)]
    fn d_narrow(x: F, k: F) -> (F, bool) {
        let (v, _) = exp_neg_times(x, k);
        (v, k <= K_MAX)
    }
}

/// The kernel shared by the Gaussian-filtered batch functions: the clamped pipeline
/// [`ClampRules::filter_gaussian`] evaluated by the NDF `N(A')` at `h_i`. In `f32` two lanes
/// (a [`Kernel::TIERED`] kernel), both with the rules' fast paths and the eigenvalue clamp's
/// common case ([`ClampRules::filter_gaussian_entries_lane`]): the first decides everything
/// in `f32` (the kernel's sanity by [`Covariance::is_sane_conservative`]) and evaluates `D` by
/// [`FilteredNdf::d_entries_lane`], so that it runs at the full `f32` vector width (for
/// Beckmann, [`FilteredNdf::NARROW`], the narrow lane instead:
/// `Narrow::entries`, in two loops, [`Kernel::STAGED`]); the
/// second, over what the first flags, decides and evaluates as the scalar path (`f64`
/// products, the scalar path's matrix, the NDF's lane `D`). What the second flags goes to the
/// scalar route. In `f64` the first lane alone (the two would be the same).
///
/// [`Covariance::is_sane_conservative`]: super::super::super::kernel::Covariance::is_sane_conservative
#[inline]
fn d_filtered<R: Roughness, N: FilteredNdf>(
    r: &R,
    rules: &ClampRules,
    sigma: F,
    [hx, hy, hz]: [&[F]; 3],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let kernel = Filtered::<R, N> {
        r: *r,
        rules: *rules,
        sigma,
        narrow: rules.narrow(*r, sigma),
        tau: rules.det_clamp_wide(*r),
        ndf: PhantomData,
    };
    run(&kernel, footprint_columns([hx, hy, hz], fp), [out])
}

/// `D` of `N(rules.filter_gaussian(r, fp, sigma))`.
struct Filtered<R, N> {
    r: R,
    rules: ClampRules,
    sigma: F,
    /// The narrow lane's per-batch constants (once per call: computed in the lane loop, their
    /// branches kept LLVM from vectorising it for AVX2).
    narrow: Narrow,
    /// The determinant clamp (`ClampRules::det_clamp_wide`), once per call.
    tau: f64,
    ndf: PhantomData<N>,
}

impl<R: Roughness, N: FilteredNdf> Filtered<R, N> {
    /// The lane of [`ClampRules::filter_gaussian_entries_lane`], then `D`: the first tier's
    /// (`FULL = false`: decided in `F`, [`FilteredNdf::d_entries_lane`]) or the second's
    /// (`FULL`: decided as the scalar path, `d_entries_exact`).
    #[inline(always)]
    fn lane_with<const FULL: bool>(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> ([F; 1], bool) {
        let fp = footprint(ux, uy, vx, vy);
        let (e, tau, ok) = self
            .rules
            .filter_gaussian_entries_lane::<R, FULL>(self.r, fp, self.sigma);
        let m = Vec3::new(hx, hy, hz);
        let (v, slow) = if FULL {
            d_entries_exact::<N>(e, tau, m)
        } else {
            N::d_entries_lane(e, tau, m)
        };
        ([v], slow | !ok)
    }
}

impl<R: Roughness, N: FilteredNdf> Kernel<7, 1> for Filtered<R, N> {
    // In `f32` the tiered lanes pay on SSE2 too; in `f64` (two lanes per 128-bit vector) they
    // do not, so there the baseline runs the scalar path (`docs/batch_measurements.md`).
    const WIDE_ONLY: bool = WIDE;
    // The second lane takes what the first cannot decide or evaluate in `f32` alone (a
    // correlated filtered matrix, `rho^2 > 3/4`; a nearly singular kernel): rare for
    // realistic footprints, more frequent for smooth lobes. In `f64` the two lanes would be
    // the same.
    const TIERED: bool = !WIDE;

    // The narrow lanes in two loops (`Kernel::STAGED`): the filtered matrix, then `D`. Each
    // half has a division and a square root in its dependency chain; split, the core overlaps
    // twice the elements.
    const STAGED: bool = !WIDE && N::NARROW;

    /// The narrow lane's first half: the entries of `A'`
    /// (`Narrow::entries`), a NaN first entry where its domain
    /// ends (the second half's correlation test then flags the element).
    #[inline(always)]
    fn stage_one(&self, [_, _, _, ux, uy, vx, vy]: [F; 7]) -> Mid {
        let ((a11, a12, a22), ok) = self.narrow.entries([ux, uy, vx, vy]);
        [if ok { a11 } else { F::NAN }, a12, a22]
    }

    /// The narrow lane's second half: `D` of the entries ([`FilteredNdf::d_entries_lane`]).
    #[inline(always)]
    fn stage_two(&self, [hx, hy, hz, ..]: [F; 7], [a11, a12, a22]: Mid) -> ([F; 1], bool) {
        let (v, slow) = N::d_entries_lane((a11, a12, a22), self.tau, Vec3::new(hx, hy, hz));
        ([v], slow)
    }

    #[inline(always)]
    fn lane(&self, x: [F; 7]) -> ([F; 1], bool) {
        if Self::STAGED {
            return self.stage_two(x, self.stage_one(x));
        }
        self.lane_with::<false>(x)
    }
    #[inline(always)]
    fn lane_full(&self, x: [F; 7]) -> ([F; 1], bool) {
        self.lane_with::<true>(x)
    }
    // Always inlined: out of line, the footprint travels through memory and is read back
    // with wider loads than it was stored with (a store-forwarding stall, see
    // `ClampRules::filter_gaussian`).
    #[inline(always)]
    fn scalar(&self, [hx, hy, hz, ux, uy, vx, vy]: [F; 7]) -> [F; 1] {
        let fp = footprint(ux, uy, vx, vy);
        let a = self.rules.filter_gaussian(self.r, fp, self.sigma);
        [N::of(a).d(Vec3::new(hx, hy, hz))]
    }
}
