//! Projected-space filtering (Tokuyoshi and Kaplanyan 2021, JCGT 10(2)): the filter, its
//! pipeline through the clamp rules ([`ClampRules::filter_projected`]) and its method
//! ([`Projected`]).

use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, Covariance, SIGMA_PIXEL};
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::F;
use super::gaussian::{filter_tau, valid_clamp};
use super::method::Method;
use crate::math::Real;

/// The largest eigenvalue of `A` that [`projected`] maps to projected space: `0.99`
/// (`alpha <= 0.995`). The map `P = A (I - A)^-1` needs every eigenvalue of `A` below 1.
pub const PROJECTED_EIGEN_MAX: F = EIGEN_MAX as F;

/// [`PROJECTED_EIGEN_MAX`] in `f64`, the value both precisions compute with.
const EIGEN_MAX: f64 = 0.99;

/// Projected-space filtering (Tokuyoshi and Kaplanyan 2021, JCGT 10(2), Listing 1):
/// `P = A (I - A)^-1`, `P' = P + 2 Sigma`, `A' = P' (I + P')^-1`, evaluated with the
/// determinant clamp `tau = det(A)` (filtering only grows the determinant), as
/// [`super::gaussian`].
///
/// **Why.** On the projected disk `p = h_xy` the GGX density is itself a GGX-shaped slope
/// density: with `P^-1 = A^-1 - I`,
/// `D(h) = 1 / (pi sqrt(det A) (1 + p^T P^-1 p)^2) = P22_P(p) / sqrt(det(I - A))`
/// for `|p| < 1` (tested in `tests/filter_projected.rs`). The kernel of TK19 section 3.2 is
/// built from disk derivatives, so it lives in the same space as `P`, and it is added there.
/// **The factor 2** is the same as in the slope domain: the lobe is treated as a Gaussian
/// whose covariance is half its roughness matrix (KHPL16 eq. 14), so a kernel of covariance
/// `Sigma` adds `2 Sigma` to `P` (TK21 Listing 1: `kernelRoughnessMat = 2 SIGMA2 delta^T
/// delta`; TK21 uses `SIGMA2 = 1 / (2 pi)`, which is the caller's `sigma^2` here).
///
/// **Computation.** For 2x2 matrices, by Cayley-Hamilton,
/// `P = (A - det(A) I) / det(I - A)` with `a11 - det A = a11 (1 - a22) + a12^2` (a sum of
/// positive terms) and `A' = (P' + d I) / (1 + tr(P') + d)`, `d = max(det P', det P)` (TK21's
/// `detMin`), every term positive: `A'` is symmetric positive definite by construction. Both
/// precisions compute in `f64` from the entries and the sanitised kernel and round the
/// entries of `A'` once, so the `f32` result is the `f64` one correctly rounded (as
/// [`super::gaussian`]'s `a + 2 k` is): `(I - A)^-1` amplifies rounding by up to
/// `1 / (1 - lambda_max) = 100`, which `f32` arithmetic could not absorb.
///
/// **Roughness limit.** `I - A` is invertible with `P` positive definite iff both
/// eigenvalues of `A` are `< 1` (`alpha < 1`). Eigenvalues above [`PROJECTED_EIGEN_MAX`]
/// are clamped to it for the projected-space step and the excess is added back unfiltered:
/// `A' = proj(A_c) + (A - A_c)`. This is exact below the limit, continuous across it, and
/// never sharpens (`A' >= A`, as `P -> P (I + P)^-1` is operator monotone); lobes that rough
/// need no filtering (TK19 section 3.2).
#[inline]
pub fn projected<R: Roughness>(roughness: R, kernel: Covariance) -> RoughnessMatrix {
    projected_sanitized(roughness, kernel.sanitized(), roughness.lobe_det())
}

/// [`projected`] with an explicit determinant clamp `tau = det_clamp`, as
/// [`super::gaussian_with_det_clamp`] (`0`, NaN, infinite or negative: no clamp beyond what
/// keeps the result positive definite and a clamped matrix's own clamp).
#[inline]
pub fn projected_with_det_clamp<R: Roughness>(
    roughness: R,
    kernel: Covariance,
    det_clamp: F,
) -> RoughnessMatrix {
    projected_sanitized(
        roughness,
        kernel.sanitized(),
        filter_tau(roughness, det_clamp),
    )
}

/// [`projected`] for a sanitised kernel, with the clamp `tau` (`<= 0`: none).
#[inline]
pub(crate) fn projected_sanitized<R: Roughness>(
    roughness: R,
    k: Covariance,
    tau: f64,
) -> RoughnessMatrix {
    let base = ProjectedBase::new(roughness);
    let b = base.entries(k);
    RoughnessMatrix::from_entries(b.0, b.1, b.2, valid_clamp(roughness, b, tau))
}

/// The projected-space pipeline on the clamp rules (the rules are data, the filter applies
/// them).
impl ClampRules {
    /// The projected-space pipeline (TK21), the rules as in [`ClampRules::filter_gaussian`]:
    /// [`ClampRules::footprint`] -> [`Footprint::covariance`] (`sigma` pixels; the footprint
    /// of the half vector's projected-disk derivatives, TK19 section 3.2) ->
    /// [`ClampRules::kernel`] -> [`projected`], with the determinant clamp `tau = det(A)` if
    /// `det_clamp` (else as [`projected_with_det_clamp`] with `0`).
    ///
    /// Always inlined, as [`ClampRules::filter_gaussian`] (a footprint passed through memory
    /// stalls on store forwarding).
    #[inline(always)]
    pub fn filter_projected<R: Roughness>(
        &self,
        roughness: R,
        fp: Footprint,
        sigma: F,
    ) -> RoughnessMatrix {
        let k = self.kernel(self.footprint(fp).covariance(sigma));
        projected_sanitized(roughness, k, self.det_clamp_wide(roughness))
    }

    /// [`ClampRules::filter_projected`] in `batch`'s lane form up to the entries of `A'`, as
    /// [`ClampRules::filter_gaussian_entries_lane`] (with the kernel's sanity decided exactly):
    /// the same kernel, then the projected filter's kernel part on the lobe's part `base`
    /// (`ProjectedBase::new(roughness)`, once per batch).
    #[inline(always)]
    pub(crate) fn filter_projected_entries_lane<R: Roughness>(
        &self,
        roughness: R,
        base: &ProjectedBase,
        fp: Footprint,
        sigma: F,
    ) -> ((F, F, F), f64, bool) {
        let (k, ok) = self.kernel_lane::<true>(fp, sigma);
        (base.entries(k), self.det_clamp_wide(roughness), ok)
    }
}

/// The lobe's part of [`projected`] (its eigenvalue split `A = A_c + excess`, `P = A_c (I -
/// A_c)^-1`, `det P`), computed once; [`ProjectedBase::entries`] then adds a kernel. Shared
/// by the scalar path and `batch::ggx_d_projected`'s lanes (one lobe, a kernel per element).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ProjectedBase {
    /// `A`'s entries in `F` (the floor of the result's diagonal).
    a: (F, F, F),
    /// `P`'s entries in `f64`.
    p: (f64, f64, f64),
    /// `det P`, `>= 0`.
    det_p: f64,
    /// `A - A_c`.
    excess: (f64, f64, f64),
}

impl ProjectedBase {
    /// The lobe's part, from its entries (in `f64`, see [`projected`]).
    #[inline]
    pub(crate) fn new<R: Roughness>(roughness: R) -> Self {
        use crate::f64::kernel::Covariance as Wide;
        let (a11, a12, a22) = roughness.entries_f();
        let (w11, w12, w22) = (a11.to_f64(), a12.to_f64(), a22.to_f64());
        let ac = Wide::new(w11, w12, w22).clamp_eigenvalues(EIGEN_MAX);
        let excess = (w11 - ac.s11, w12 - ac.s12, w22 - ac.s22);
        let (c11, c12, c22) = (ac.s11, ac.s12, ac.s22);
        // P = (A - det(A) I) / det(I - A).
        let det_ima = ((1.0 - c11) * (1.0 - c22) - c12 * c12).max(f64::MIN_POSITIVE);
        let p = (
            (c11 * (1.0 - c22) + c12 * c12) / det_ima,
            c12 / det_ima,
            (c22 * (1.0 - c11) + c12 * c12) / det_ima,
        );
        let det_p = (p.0 * p.2 - p.1 * p.1).max(0.0);
        Self {
            a: (a11, a12, a22),
            p,
            det_p,
            excess,
        }
    }

    /// The entries of `A'` for the sanitised kernel `k`, rounded to `F` once (never below
    /// `A` on the diagonal). Branch-free (`max` of values only).
    #[inline(always)]
    pub(crate) fn entries(&self, k: Covariance) -> (F, F, F) {
        let w = |x: F| x.to_f64();
        let (r11, r12, r22) = self.wide((w(k.s11), w(k.s12), w(k.s22)));
        // Never below A on the diagonal (exact, by monotonicity): rounding in the excess split
        // otherwise takes a tiny (e.g. subnormal, accepted with a large `tau`) `a11` to `<= 0`.
        (
            F::from_f64(r11).max(self.a.0),
            F::from_f64(r12),
            F::from_f64(r22).max(self.a.2),
        )
    }

    /// The entries of `A'` in `f64` (see [`projected`]).
    #[inline(always)]
    fn wide(&self, k: (f64, f64, f64)) -> (f64, f64, f64) {
        let p = self.p;
        let det_p = self.det_p;
        let q = (p.0 + 2.0 * k.0, p.1 + 2.0 * k.1, p.2 + 2.0 * k.2);
        // det(P + 2K) = det P + 2 tr(adj(P) K) + 4 det K, every term >= 0 for P, K PSD: unlike
        // q11 q22 - q12^2 it does not cancel when a huge, nearly rank-one K meets a tiny P (which
        // sharpened the minor axis by 60x in f32 for alpha = 1e-8, found by fuzzing).
        let det_k = (k.0 * k.2 - k.1 * k.1).max(0.0);
        let cross = (p.0 * k.2 + p.2 * k.0 - 2.0 * p.1 * k.1).max(0.0);
        let d = (det_p + 2.0 * cross + 4.0 * det_k).max(det_p);
        let den = 1.0 + q.0 + q.2 + d;
        // Each part is finite: q's entries are bounded by P (<= 1 / (1 - 0.99)^2 scale) plus the
        // sanitized kernel (<= ALPHA_MAX^2).
        let e = self.excess;
        (
            (q.0 + d) / den + e.0,
            q.1 / den + e.1,
            (q.2 + d) / den + e.2,
        )
    }
}

/// Projected-space filtering of GGX (Tokuyoshi and Kaplanyan 2021, JCGT 10(2)): `P = A (I -
/// A)^-1`, `P' = P + 2 Sigma`, `A' = P' (I + P')^-1` ([`projected`]), with the kernel
/// `Sigma` of the footprint after the clamp rules ([`ClampRules::filter_projected`]: maximum
/// extent, `kappa`, determinant clamp). The footprint should hold projected-disk derivatives (see the
/// [front door](super::method)). Where it is wrong (`docs/tradeoff.md`, "Where each approximation is
/// wrong"; a slope footprint, exact at `h = n`): as TK19, `D` errs by more than 10 % once the
/// footprint is wider than about 0.3 lobe widths, except within one lobe width of the peak
/// (there from 0.7 to 2 lobe widths of footprint); up to 600 % far in the tails.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    /// The clamp rules applied to the footprint and the kernel.
    pub clamps: ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    pub sigma: F,
}

impl Projected {
    /// TK21's configuration: [`ClampRules::default`] and `sigma = 0.5` pixels (TK21's
    /// `SIGMA2 = 1 / (2 pi)` is a variance of its own pixel filter; set `sigma` to
    /// `sqrt(1 / (2 pi))` to reproduce it).
    pub const TK21: Self = Self {
        clamps: ClampRules::DEFAULT,
        sigma: SIGMA_PIXEL,
    };
}

impl Default for Projected {
    /// [`Projected::TK21`].
    fn default() -> Self {
        Self::TK21
    }
}

impl<R: Roughness> Method<Ggx<R>> for Projected {
    type Lobe = Ggx<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        Ggx::new(
            self.clamps
                .filter_projected(material.roughness, footprint, self.sigma),
        )
    }
}
