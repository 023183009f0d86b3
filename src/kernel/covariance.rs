//! The Gaussian kernel of a footprint: a slope-domain covariance `Sigma` (KHPL16 eq. 13-15,
//! TK19 section 2.2), with the eigenvalue clamp of TK19 eq. 1 and the sanitiser every filter
//! applies first.

use super::super::footprint::Footprint;
use super::super::ndf::roughness::ALPHA_MAX;
use super::F;
use crate::math::{self as m, Real};

/// A symmetric positive semi-definite 2x2 covariance `[[s11, s12], [s12, s22]]` in the slope
/// domain (units: slope^2). Covariances of independent kernels add (KHPL16 eq. 15, 21).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Covariance {
    /// Variance along the tangent `x` (slope^2).
    pub s11: F,
    /// Covariance of `x` and `y` (slope^2).
    pub s12: F,
    /// Variance along the bitangent `y` (slope^2).
    pub s22: F,
}

impl Covariance {
    /// The zero kernel (no filtering).
    pub const ZERO: Self = Self {
        s11: 0.0,
        s12: 0.0,
        s22: 0.0,
    };

    /// From the three distinct entries (not checked; see the filtering functions for what
    /// they do with an indefinite or non-finite covariance).
    #[inline]
    pub const fn new(s11: F, s12: F, s22: F) -> Self {
        Self { s11, s12, s22 }
    }

    /// The Gaussian pixel kernel of a footprint carried into the slope domain:
    /// `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)` (TK19 section 2.2; KHPL16 eq. 13 with
    /// `sigma` folded into the vectors), `sigma` the pixel filter's standard deviation in pixels
    /// (0.5 in both papers). Entries in slope^2. A NaN footprint entry counts as `0` (the NaN
    /// policy, [`Footprint::nan_to_zero`]); infinite ones give infinite entries, which
    /// [`Covariance::sanitized`] saturates.
    #[inline]
    pub fn from_footprint(fp: Footprint, sigma: F) -> Self {
        let fp = fp.nan_to_zero();
        let (u, v) = (fp.dh_u, fp.dh_v);
        Self::new(
            u.x * u.x + v.x * v.x,
            u.x * u.y + v.x * v.y,
            u.y * u.y + v.y * v.y,
        ) * (sigma * sigma)
    }

    /// `tr(Sigma) = lambda_min + lambda_max` (TK19 eq. 2).
    #[inline]
    pub fn trace(self) -> F {
        self.s11 + self.s22
    }

    /// `det(Sigma) = lambda_min lambda_max`.
    #[inline]
    pub fn det(self) -> F {
        self.s11 * self.s22 - self.s12 * self.s12
    }

    /// Eigenvalues `(lambda_min, lambda_max)`, both clamped to `>= 0`. The one of larger
    /// magnitude is `mean +/- hypot(half difference, s12)` with the sign of `mean` (no
    /// cancellation), the other `det` divided by it, so the small one keeps its relative
    /// accuracy for elongated kernels (and the positive one of an indefinite matrix for a
    /// dominant negative one). NaN entries give `(0, 0)`.
    #[inline]
    pub fn eigenvalues(self) -> (F, F) {
        let (mean, max_direct, direct) = self.mean_and_max_direct();
        // `mean + radius(d, b)`: `radius` is the direct root where `direct`.
        let max = if direct {
            max_direct
        } else {
            mean + m::hypot(0.5 * (self.s11 - self.s22), self.s12)
        };
        // `mean >= 0` (every PSD matrix) without overflow: `lambda_max = mean + rad` has no
        // cancellation. Otherwise (negative mean, overflow, NaN) the general case.
        if !(mean >= 0.0 && max <= F::MAX) {
            return self.eigenvalues_general();
        }
        let min = if max > 0.0 { self.det_over(max) } else { 0.0 };
        (min.max(0.0), max)
    }

    /// `(mean, mean + sqrt(d^2 + b^2), direct)` with `d = (s11 - s22) / 2`, `b = s12`: the
    /// larger eigenvalue by [`radius_direct`], valid where `direct` (else
    /// [`Covariance::eigenvalues`] takes `hypot`).
    #[inline(always)]
    fn mean_and_max_direct(self) -> (F, F, bool) {
        let mean = 0.5 * (self.s11 + self.s22);
        let (r, direct) = radius_direct(0.5 * (self.s11 - self.s22), self.s12);
        (mean, mean + r, direct)
    }

    /// The larger eigenvalue in lane form (branch-free): `(lambda_max, ok)`, equal to
    /// `self.eigenvalues().1` bit for bit where `ok` (finite entries, the fast path of
    /// [`Covariance::eigenvalues`] with the direct radius).
    #[inline(always)]
    pub(crate) fn max_eigenvalue_lane(self) -> (F, bool) {
        let (mean, max, direct) = self.mean_and_max_direct();
        let finite = (self.s11.abs() < F::INFINITY)
            & (self.s12.abs() < F::INFINITY)
            & (self.s22.abs() < F::INFINITY);
        (max, finite & direct & (mean >= 0.0) & (max <= F::MAX))
    }

    /// `det / big` for `|big| >= ` every entry (an eigenvalue of the largest magnitude):
    /// `det` overflows (to inf, or inf - inf = NaN) for huge finite entries and loses its bits
    /// for tiny (subnormal) products; then the entries are divided first,
    /// `(s_hi / big) s_lo - (s12 / big) s12` with `s_hi` the larger diagonal entry (each
    /// quotient in `[-1, 1]`; the smaller entry's quotient could underflow).
    #[inline]
    fn det_over(self, big: F) -> F {
        let det = self.det();
        if det.is_finite() && det.abs() >= F::MIN_POSITIVE {
            det / big
        } else {
            let (lo, hi) = if self.s11.abs() <= self.s22.abs() {
                (self.s11, self.s22)
            } else {
                (self.s22, self.s11)
            };
            (hi / big) * lo - (self.s12 / big) * self.s12
        }
    }

    /// [`Covariance::eigenvalues`] of a matrix with a negative mean, of finite entries whose
    /// eigenvalue (or sum, or difference) overflows, or with NaN entries (`(0, 0)`).
    ///
    /// Out of line (for speed, not part of the formula): inlined, it changes how the isotropic
    /// conventions' `Norm` match compiles (it calls `eigenvalues` for `MaxEigenvalue`) and
    /// slows every convention (`benches/filtered.rs`, `isotropic/*`).
    #[cold]
    #[inline(never)]
    fn eigenvalues_general(self) -> (F, F) {
        let finite = self.s11.is_finite() && self.s12.is_finite() && self.s22.is_finite();
        let mean = 0.5 * (self.s11 + self.s22);
        let rad = radius(0.5 * (self.s11 - self.s22), self.s12);
        // The eigenvalue of larger magnitude: no cancellation.
        let up = mean >= 0.0;
        let big = if up { mean + rad } else { mean - rad };
        if finite && !big.is_finite() {
            // Beyond `F::MAX`: on `Sigma / scale` (largest entry 1), scaled back.
            let k = self.s11.abs().max(self.s22.abs()).max(self.s12.abs());
            let (min, max) = (self * (1.0 / k)).eigenvalues();
            return (min * k, max * k);
        }
        let other = if big != 0.0 && !big.is_nan() {
            self.det_over(big)
        } else {
            0.0
        };
        let (min, max) = if up { (other, big) } else { (big, other) };
        // NaN (from NaN entries) becomes 0.
        (min.max(0.0), max.max(0.0))
    }

    /// Clamps both eigenvalues to `[0, max]` without rotating the eigenvectors:
    /// `Sigma' = V clamp(Lambda, 0, max) V^T`, the nearest (Frobenius) matrix with eigenvalues
    /// in `[0, max]`. For a positive semi-definite input this is the matrix form of TK19 eq. 1's
    /// `min(2 lambda, kappa)` (see [`super::clamp::ClampRules::kernel`]); an indefinite input
    /// loses its negative part as well (e.g. `[[0, 1], [1, 0]]` with `max = 0.5` gives
    /// `0.5 P_max = [[0.25, 0.25], [0.25, 0.25]]`), a negative semi-definite one gives
    /// [`Covariance::ZERO`]. The result is always finite and positive semi-definite with
    /// `lambda_max <= max` (to rounding; a `max` above `F::MAX (1 - 16 eps)`, infinite
    /// included, acts as that).
    ///
    /// Computed as `c_max P_max + c_min P_min` with the clamped eigenvalues `c` and the spectral
    /// projectors `P_max = (Sigma - lambda_min I) / (lambda_max - lambda_min)`,
    /// `P_min = I - P_max` (no eigenvector is formed, every term is non-negative), and
    /// `c I` when both eigenvalues clamp to the same `c`. The matrix is first scaled to unit
    /// size (largest entry 1) so nothing overflows or underflows. A negative or NaN `max`
    /// yields [`Covariance::ZERO`], a non-finite input [`Covariance::ZERO`] (use
    /// [`Covariance::sanitized`] for the full contract).
    #[inline]
    pub fn clamp_eigenvalues(self, max: F) -> Self {
        let (a, b, c) = (self.s11, self.s12, self.s22);
        // PSD with a bounded trace (so that `a c` in `psd` cannot overflow) and the largest
        // eigenvalue within the bound: unchanged.
        if psd(a, b, c) && a + c <= FAST_EIGEN_MAX && self.psd_within(max) {
            return self;
        }
        Self::clamp_eigenvalues_general(a, b, c, max).fresh_values()
    }

    /// [`Covariance::clamp_eigenvalues`] of a kernel that [`Covariance::sanitized`] returned
    /// (finite and positive semi-definite, so the fast path needs no test of definiteness).
    #[inline]
    pub(crate) fn clamp_eigenvalues_sanitized(self, max: F) -> Self {
        if self.psd_within(max) {
            return self;
        }
        Self::clamp_eigenvalues_general(self.s11, self.s12, self.s22, max).fresh_values()
    }

    /// Whether the largest eigenvalue of a finite PSD matrix is at most `max` (NaN: false),
    /// decided without a square root where cheap; `false` leaves it to the general path.
    /// First the trace (`lambda_min + lambda_max`; `max` is then not NaN and `>= 0`); then
    /// `mean + sqrt(d^2 + b^2) <= max` as `d^2 + b^2 <= (max - mean)^2`. The bounds on
    /// `h = max - mean` keep `h^2` finite and normal (a square that underflows beside it is
    /// negligible; fuzzing found `h = 0` against underflowing squares).
    ///
    /// Branch-free (`|`, `&` of the comparisons, the same truth value as the short-circuit
    /// form): `batch`'s first filtered lane is this test without the clamp, and with a branch
    /// its loop did not vectorise.
    #[inline(always)]
    #[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
    pub(crate) fn psd_within(self, max: F) -> bool {
        let (a, b, c) = (self.s11, self.s12, self.s22);
        let tr = a + c;
        let (mean, d) = (0.5 * tr, 0.5 * (a - c));
        let h = max - mean;
        (tr <= max)
            | ((h >= 1.0 / FAST_EIGEN_MAX) & (h <= FAST_EIGEN_MAX) & (d * d + b * b <= h * h))
    }

    /// The general case of [`Covariance::clamp_eigenvalues`] (out of line, with
    /// [`Covariance::fresh_values`] at its call sites).
    #[cold]
    #[inline(never)]
    fn clamp_eigenvalues_general(s11: F, s12: F, s22: F, max: F) -> Self {
        // Non-finite entries are caught here: `F::max` below would pass a NaN through.
        let finite = s11.is_finite() && s12.is_finite() && s22.is_finite();
        if max.is_nan() || max < 0.0 || !finite {
            return Self::ZERO;
        }
        // An eigenvalue beyond `F::MAX` (entries near `F::MAX`) is not representable: the
        // bound is at most `F::MAX (1 - 16 eps)`, so the result stays finite (the rebuilt
        // entries are `c_max` times projector entries within a few roundings of `[0, 1]`:
        // with the bound `F::MAX` itself, `[[-1.4e305, 1e30], [1e30, F::MAX]]` rebuilt to an
        // infinite `s22`; found by fuzzing).
        let max = max.min(F::MAX * (1.0 - 16.0 * F::EPSILON));
        let this = Self::new(s11, s12, s22);
        let scale = s11.abs().max(s22.abs()).max(s12.abs());
        if scale <= 0.0 {
            return Self::ZERO;
        }
        // Unless every square below is a finite normal number (the entries within the fast
        // range and `r^2 = d^2 + s12^2` well above the subnormals: fuzzing found `s12^2`
        // underflowing beside normal diagonal entries), work on Sigma / scale (largest entry
        // 1). Tiny (subnormal) entries are scaled up too: `1 / (2 r)` below would overflow to
        // inf (0 * inf = NaN); dividing (not multiplying by `1 / k`, which overflows for a
        // subnormal `k`).
        let d0 = 0.5 * (s11 - s22);
        let r2 = d0 * d0 + s12 * s12;
        let unscaled = (1.0 / FAST_EIGEN_MAX..=FAST_EIGEN_MAX).contains(&scale)
            && r2 >= F::MIN_POSITIVE / F::EPSILON;
        let (k, s) = if unscaled {
            (1.0, this)
        } else {
            (scale, Self::new(s11 / scale, s12 / scale, s22 / scale))
        };
        // The eigenvalues in the caller's units: the one of larger magnitude, `mean +/- r` with
        // the sign of `mean` (no cancellation), from the unit-size matrix; the other as
        // `det / big` with the caller's entries divided first (`(s22 / big) s11 - (s12 / big)
        // s12`), which keeps it where the scaled entries underflow (fuzzing: `[[-1e30, -1],
        // [-1, 1e-30]]` has `lambda_max = 2e-30`). Negative eigenvalues contribute nothing:
        // they are clamped to 0, and an input with one (indefinite, or a negative diagonal
        // entry) is rebuilt even when its largest eigenvalue is within the bound.
        let r = radius(0.5 * (s.s11 - s.s22), s.s12);
        let (lmin, lmax) = Self::eigen_pair(this, k, s, r);
        let indefinite = s11 < 0.0 || s22 < 0.0 || lmin < 0.0;
        // Compared and rebuilt in the caller's units (`lambda` against `max`): `max / k` is
        // subnormal when `max << scale` and carries only a few bits (fuzzing found 40 %
        // overshoots in f32).
        if !indefinite && lmax <= max {
            return this;
        }
        let (c_max, c_min) = (lmax.clamp(0.0, max), lmin.clamp(0.0, max));
        if c_max <= 0.0 {
            return Self::ZERO;
        }
        if c_min >= c_max {
            return Self::new(c_max, 0.0, c_max);
        }
        let (v, finite) = s.rebuild(r, c_max, c_min);
        if !finite {
            // lambda_max - lambda_min = 2 r below the normal range: isotropic to rounding.
            return Self::new(c_max, 0.0, c_max);
        }
        v
    }

    /// The eigenvalues `(lambda_min, lambda_max)` of `this` in the caller's units from the
    /// unit-size matrix `s = this / k` and its radius `r` (see
    /// [`Covariance::clamp_eigenvalues_general`]): [`Covariance::eigen_pair_recip`] where
    /// its flag holds, otherwise the smaller one from quotients (`|big|` finite and nonzero)
    /// or from `det / big`, the cases being rare.
    #[inline(always)]
    fn eigen_pair(this: Self, k: F, s: Self, r: F) -> (F, F) {
        let (lmin, lmax, recip) = Self::eigen_pair_recip(this, k, s, r);
        if recip {
            return (lmin, lmax);
        }
        let (up, big_s, big) = Self::larger_magnitude_eigenvalue(k, s, r);
        let (s11, s12, s22) = (this.s11, this.s12, this.s22);
        let other = if big.is_finite() && big != 0.0 {
            let (lo, hi) = Self::lo_hi(s11, s22);
            (hi / big) * lo - (s12 / big) * s12
        } else if big_s != 0.0 {
            s.det() / big_s * k
        } else {
            0.0
        };
        if up { (other, big) } else { (big, other) }
    }

    /// The eigenvalue of larger magnitude of the unit-size matrix `s` of radius `r`, `mean
    /// +/- r` with the sign of `mean` (no cancellation): `(mean >= 0, big_s, big_s k)`.
    #[inline(always)]
    fn larger_magnitude_eigenvalue(k: F, s: Self, r: F) -> (bool, F, F) {
        let mean = 0.5 * (s.s11 + s.s22);
        let up = mean >= 0.0;
        let big_s = if up { mean + r } else { mean - r };
        (up, big_s, big_s * k)
    }

    /// The diagonal entries of smaller and larger magnitude.
    #[inline(always)]
    fn lo_hi(s11: F, s22: F) -> (F, F) {
        if s11.abs() <= s22.abs() {
            (s11, s22)
        } else {
            (s22, s11)
        }
    }

    /// [`Covariance::eigen_pair`]'s common case, `batch`'s lane form: the eigenvalue of
    /// larger magnitude `big = mean +/- r` (the sign of `mean`, no cancellation) and the
    /// other as `(hi / big) lo - (s12 / big) s12` (`hi`, `lo` the diagonal entries of larger
    /// and smaller magnitude: `|big| >= |s11|, |s22|, |s12|`, so each quotient is in
    /// `[-1, 1]`; dividing the larger one, whose quotient cannot underflow) with one
    /// division: the quotients as products with `1 / big`, one more rounding each (1.5 ulp
    /// instead of 0.5). The flag says whether `1 / big` is a finite normal number (`|big|`
    /// nonzero and at most `1 / F::MIN_POSITIVE`); without it the smaller eigenvalue is
    /// meaningless.
    #[inline(always)]
    #[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
    fn eigen_pair_recip(this: Self, k: F, s: Self, r: F) -> (F, F, bool) {
        let (s11, s12, s22) = (this.s11, this.s12, this.s22);
        let (up, _, big) = Self::larger_magnitude_eigenvalue(k, s, r);
        let ib = 1.0 / big;
        let recip = (ib.abs() >= F::MIN_POSITIVE) & (ib.abs() < F::INFINITY);
        let (lo, hi) = Self::lo_hi(s11, s22);
        let other = (hi * ib) * lo - (s12 * ib) * s12;
        let (lmin, lmax) = if up { (other, big) } else { (big, other) };
        (lmin, lmax, recip)
    }

    /// `c_max P_max + c_min P_min` for the unit-size matrix `self` of radius `r`, with
    /// `c_min < c_max` (so `lambda_max - lambda_min = 2 r > 0`); the flag is `false` where
    /// `2 r p` (`p = r + |d| >= r`) is not a finite normal number, i.e. `r` below about
    /// `sqrt(F::MIN_POSITIVE / 4)` (the caller then answers the isotropic `c_max I`, whose
    /// error, at most `2 r` relative to the unit-size matrix, is far below `F::EPSILON`).
    #[inline(always)]
    #[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
    fn rebuild(self, r: F, c_max: F, c_min: F) -> (Self, bool) {
        let d = 0.5 * (self.s11 - self.s22);
        let p = r + d.abs();
        // One division for `1 / 2r` and `q = s12^2 / p` (`batch`'s lane computes this for
        // every element that needs the clamp): `w = 1 / (2 r p)`, `1 / 2r = p w`,
        // `q / 2r = s12^2 w` (two more roundings than the quotients).
        let rp = (2.0 * r) * p;
        let w = 1.0 / rp;
        let inv = p * w;
        let (pp, pq) = (p * inv, (self.s12 * self.s12) * w);
        let (p11, p22) = if d >= 0.0 { (pp, pq) } else { (pq, pp) };
        // Sigma' = c_max P_max + c_min P_min with the (scale-free) spectral projectors
        // P_max = [[e11, s12], [s12, e22]] / 2r and P_min = [[e22, -s12], [-s12, e11]] / 2r
        // (`e` the larger of `p`, `q = s12^2 / p` on the larger diagonal entry's side): sums
        // of non-negative terms, no cancellation.
        let p12 = self.s12 * inv;
        (
            Self::new(
                c_max * p11 + c_min * p22,
                (c_max - c_min) * p12,
                c_max * p22 + c_min * p11,
            ),
            (rp >= F::MIN_POSITIVE) & (rp < F::INFINITY),
        )
    }

    /// [`Covariance::clamp_eigenvalues_sanitized`] for a kernel that
    /// [`Covariance::is_sane`] accepts, in `batch`'s lane form (branch-free): `(result, ok)`,
    /// equal to it bit for bit where `ok`. `ok` holds on its fast path and on the general
    /// path's common case (entries in the fast range, the radius a normal square root, the
    /// direct eigenvalue quotient, `2 r p` a finite normal number); the same helpers as the general path.
    #[inline(always)]
    #[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
    pub(crate) fn clamp_eigenvalues_lane(self, max: F) -> (Self, bool) {
        let (s11, s12, s22) = (self.s11, self.s12, self.s22);
        let scale = s11.abs().max(s22.abs()).max(s12.abs());
        let d0 = 0.5 * (s11 - s22);
        let (r, r_direct) = radius_direct(d0, s12);
        let unscaled = (scale >= 1.0 / FAST_EIGEN_MAX)
            & (scale <= FAST_EIGEN_MAX)
            & (d0 * d0 + s12 * s12 >= F::MIN_POSITIVE / F::EPSILON);
        let (lmin, lmax, direct) = Self::eigen_pair_recip(self, 1.0, self, r);
        let max_c = max.min(F::MAX);
        let keep = !((s11 < 0.0) | (s22 < 0.0) | (lmin < 0.0)) & (lmax <= max_c);
        // `F::clamp` without its assertion (a panic path stops the vectoriser); `max_c >= 0`
        // wherever `ok`.
        let clamp = |x: F| {
            let x = if x < 0.0 { 0.0 } else { x };
            if x > max_c { max_c } else { x }
        };
        let (c_max, c_min) = (clamp(lmax), clamp(lmin));
        let iso = c_min >= c_max;
        let (v, finite) = self.rebuild(r, c_max, c_min);
        let general = if keep {
            self
        } else if iso {
            Self::new(c_max, 0.0, c_max)
        } else {
            v
        }
        .fresh_values();
        let fast = self.psd_within(max);
        let ok = fast
            | ((max >= 0.0)
                & (scale > 0.0)
                & unscaled
                & r_direct
                & direct
                & (keep | (c_max > 0.0))
                & (keep | iso | finite));
        (if fast { self } else { general }, ok)
    }

    /// A finite, symmetric positive semi-definite covariance whose eigenvalues are at most
    /// [`KERNEL_MAX`] (`ALPHA_MAX^2`, a kernel already wider than the widest supported lobe):
    ///
    /// - any infinite entry: `KERNEL_MAX * I` (the widest kernel, direction unknown; a NaN
    ///   beside it is what `inf * 0` gives);
    /// - otherwise a NaN entry counts as `0` (no information, no widening from it: the crate's
    ///   NaN policy, [`crate::contract`]);
    /// - negative variances are raised to `0` and `|s12|` lowered to `sqrt(s11 s22)` (the
    ///   nearest PSD matrix with the same diagonal; only rounding produces these from
    ///   [`Footprint::covariance`](super::super::Footprint::covariance));
    /// - then [`Covariance::clamp_eigenvalues`] with `KERNEL_MAX`.
    ///
    /// Every filtering function applies this first, so their results are NaN-free for any
    /// input.
    #[inline]
    pub fn sanitized(self) -> Self {
        let (a, b, c) = (self.s11, self.s12, self.s22);
        // Fast path (every footprint covariance): finite, positive semi-definite and with
        // trace <= KERNEL_MAX, which bounds both eigenvalues (and excludes infinities).
        if self.is_sane() {
            return self;
        }
        Self::sanitized_general(a, b, c).fresh_values()
    }

    /// Whether [`Covariance::sanitized`] returns `self` by its fast path: finite, positive
    /// semi-definite, trace at most `KERNEL_MAX` (shared with `batch`'s lanes).
    #[inline(always)]
    pub(crate) fn is_sane(self) -> bool {
        let (a, b, c) = (self.s11, self.s12, self.s22);
        psd(a, b, c) & (a + c <= KERNEL_MAX)
    }

    /// [`Covariance::is_sane`] decided in `F` alone, `true` only where it is (`false` where
    /// the rounded products cannot decide: `b^2` within `2 eps` of `a c`): for `batch`'s
    /// `f32` lanes, which an `f64` product would hold to half their width. `f64`: `is_sane`.
    #[inline(always)]
    pub(crate) fn is_sane_conservative(self) -> bool {
        let (a, b, c) = (self.s11, self.s12, self.s22);
        psd_conservative(a, b, c) & (a + c <= KERNEL_MAX)
    }

    /// The general case of [`Covariance::sanitized`] (out of line, with
    /// [`Covariance::fresh_values`] at its call site).
    #[cold]
    #[inline(never)]
    fn sanitized_general(a: F, b: F, c: F) -> Self {
        if [a, b, c].iter().any(|x| x.is_infinite()) {
            return Self::new(KERNEL_MAX, 0.0, KERNEL_MAX);
        }
        let zero_nan = |x: F| if x.is_nan() { 0.0 } else { x };
        let (a, b, c) = (zero_nan(a), zero_nan(b), zero_nan(c));
        let s11 = a.max(0.0);
        let s22 = c.max(0.0);
        let bound = m::sqrt(s11) * m::sqrt(s22);
        let s12 = b.clamp(-bound, bound);
        Self::new(s11, s12, s22).clamp_eigenvalues(KERNEL_MAX)
    }
}

impl Covariance {
    /// The result of an out-of-line general path as fresh values (`x + 0`, which only turns
    /// `-0` into `+0`). Not part of any formula: an aggregate comes back from an out-of-line
    /// call through memory, and returned as is the compiler also writes the inlined fast
    /// path's value into that memory and reads it back with loads straddling the stores (a
    /// store-forwarding stall); the additions keep the values in registers
    /// (`benches/filtered.rs`, `ggx_matrix/*/tk21_projected`, shows the difference).
    #[inline(always)]
    fn fresh_values(self) -> Self {
        Self::new(self.s11 + 0.0, self.s12 + 0.0, self.s22 + 0.0)
    }
}

/// Bounds `[1 / FAST_EIGEN_MAX, FAST_EIGEN_MAX]` on `max - mean` in
/// [`Covariance::clamp_eigenvalues`]'s second fast path: its square is a finite normal number
/// (`sqrt(F::MAX) / 2`, rounded down to a power of ten; its reciprocal is above
/// `sqrt(F::MIN_POSITIVE)`). Also the bound on the trace below which `psd` cannot overflow.
const FAST_EIGEN_MAX: F = (if core::mem::size_of::<F>() == 4 {
    1e18
} else {
    1e153
}) as F;

/// Whether `[[a, b], [b, c]]` is positive semi-definite, `a, c >= 0` and `b^2 <= a c`
/// (false for NaN), for a caller that bounds the trace (below [`FAST_EIGEN_MAX`]: `a c`
/// cannot overflow). In `f32` the products are formed in `f64`, where they are exact:
/// decided exactly. In `f64` decided on the rounded products where `a c` is a normal number
/// (or `b = 0`), else `false` (the callers' general paths decide then): `a c` may underflow to
/// `0` or a subnormal, where `b^2 <= a c` says nothing (fuzzing found
/// `a = -1e-231, c = 2e-197, b = 0` passing otherwise). The signs are tested explicitly:
/// `a c >= 0` for two negative variances.
#[inline(always)]
fn psd(a: F, b: F, c: F) -> bool {
    let products = if core::mem::size_of::<F>() == 4 {
        let (a, b, c) = (a.to_f64(), b.to_f64(), c.to_f64());
        b * b <= a * c
    } else {
        let (bb, ac) = (b * b, a * c);
        bb <= ac && (ac >= F::MIN_POSITIVE || b == 0.0)
    };
    products && a >= 0.0 && c >= 0.0
}

/// [`psd`] in `F` alone (for `f64`, `psd` itself), `true` only where `psd` is: in `f32`,
/// `fl(b^2) <= fl(fl(a c) (1 - 2 eps))` with `fl(a c)` normal (or `b = 0`) implies
/// `b^2 <= a c (1 - 2 u) / (1 - u) < a c` exactly (`u = eps / 2`; a subnormal `fl(b^2)` is
/// off by at most `2^-150 < 2 u a c`).
#[inline(always)]
fn psd_conservative(a: F, b: F, c: F) -> bool {
    if core::mem::size_of::<F>() == 8 {
        return psd(a, b, c);
    }
    let (bb, ac) = (b * b, a * c);
    (bb <= ac * (1.0 - 2.0 * F::EPSILON))
        & ((ac >= F::MIN_POSITIVE) | (b == 0.0))
        & (a >= 0.0)
        & (c >= 0.0)
}

/// `hypot(d, b)`: a plain square root where `d^2 + b^2` is a normal number at least
/// `1 / eps` times the smallest (an underflowed square then weighs below `eps^2`), the
/// library's `hypot` (a call) otherwise.
#[inline]
fn radius(d: F, b: F) -> F {
    let (r, direct) = radius_direct(d, b);
    if direct { r } else { m::hypot(d, b) }
}

/// [`radius`]'s square root branch: `(sqrt(d^2 + b^2), taken)`.
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of compares: no branch in the lane.
fn radius_direct(d: F, b: F) -> (F, bool) {
    let r2 = d * d + b * b;
    (
        m::sqrt(r2),
        (r2 >= F::MIN_POSITIVE / F::EPSILON) & (r2 <= F::MAX),
    )
}

/// The largest kernel eigenvalue kept by [`Covariance::sanitized`] (slope^2): `ALPHA_MAX^2`.
pub const KERNEL_MAX: F = ALPHA_MAX * ALPHA_MAX;

impl Footprint {
    /// `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)` (TK19 section 2.2), `sigma` in pixels:
    /// [`Covariance::from_footprint`].
    #[inline]
    pub fn covariance(self, sigma: F) -> Covariance {
        Covariance::from_footprint(self, sigma)
    }
}

impl core::ops::Add for Covariance {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.s11 + o.s11, self.s12 + o.s12, self.s22 + o.s22)
    }
}

impl core::ops::Mul<F> for Covariance {
    type Output = Self;
    #[inline]
    fn mul(self, k: F) -> Self {
        Self::new(self.s11 * k, self.s12 * k, self.s22 * k)
    }
}
