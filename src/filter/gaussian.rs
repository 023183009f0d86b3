//! `A' = A + 2 Sigma`: the Beckmann convolution (KHPL16 eq. 13-15) and the TK19 (section 2.2)
//! matrix approximation for GGX; its pipeline through the clamp rules
//! ([`ClampRules::filter_gaussian`]) and its method ([`Gaussian`]).

use super::super::footprint::Footprint;
use super::super::kernel::{ClampRules, Covariance, SIGMA_PIXEL};
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix, det_clamp_tau, det_wide};
use super::F;
use super::method::Method;

/// `A' = A + 2 Sigma`, evaluated with the determinant clamp `tau = det(A)` (TK19 supplement).
///
/// - **Beckmann: exact.** A Beckmann lobe is a Gaussian of slopes with covariance
///   `B = A / 2` (KHPL16 eq. 14); convolving with the kernel `N(0, Sigma)` adds covariances
///   (eq. 15, `B' = B + Sigma`), and the filtered lobe is Beckmann with `A' = 2 B'`.
/// - **GGX: the TK19 (section 2.2) / KHPL16 approximation.** The GGX lobe is treated as if it
///   were Gaussian. Against the exact Gaussian-filtered GGX ([`super::GaussianFilteredGgx`])
///   its peak is bounded by `1 <= peak / exact peak <= e / (e - 1)` (Jensen on the mixture
///   identity; `tests/filter_ggx_error.rs`); its errors are measured in the trade table.
///
/// `tau = det(A)` has no bias in exact arithmetic since `det(A + 2 Sigma) >= det(A)` for
/// `Sigma >= 0`; it is the determinant of the entries as stored, in `f64`
/// (`roughness::det_wide`). A clamped [`RoughnessMatrix`] is filtered as `A + 2 Sigma` (its
/// entries as given) with its own `tau = det A_c`: a zero kernel returns the lobe unchanged,
/// and the filtered lobe is never sharper than the clamped one. Units: `A` dimensionless
/// (slope^2), `Sigma` slope^2.
#[inline(always)]
pub fn gaussian<R: Roughness>(roughness: R, kernel: Covariance) -> RoughnessMatrix {
    gaussian_sanitized(roughness, kernel.sanitized(), roughness.lobe_det())
}

/// [`gaussian`] with an explicit determinant clamp `tau = det_clamp` (`0` disables it;
/// NaN, infinite or negative is treated as `0`). The kernel is [`Covariance::sanitized`]
/// first. Without a clamp, a filtered determinant that rounds to `<= 0` (an extremely
/// elongated kernel, or underflow) is clamped with `det(A)`, its exact lower bound, so the
/// result is always valid. A clamped [`RoughnessMatrix`] keeps its own clamp: `tau` is at
/// least its `det A_c` (its entries may be far sharper than `A_c`, even singular).
#[inline]
pub fn gaussian_with_det_clamp<R: Roughness>(
    roughness: R,
    kernel: Covariance,
    det_clamp: F,
) -> RoughnessMatrix {
    gaussian_sanitized(
        roughness,
        kernel.sanitized(),
        filter_tau(roughness, det_clamp),
    )
}

/// The clamp of the filters' `*_with_det_clamp`: `det_clamp` as read by `det_clamp_tau`, at
/// least the lobe's own clamp ([`Sealed::own_det_clamp`](super::super::ndf::roughness::sealed::Sealed::own_det_clamp):
/// filtering never drops a clamped matrix's clamp).
#[inline(always)]
pub(crate) fn filter_tau<R: Roughness>(roughness: R, det_clamp: F) -> f64 {
    det_clamp_tau(det_clamp).max(roughness.own_det_clamp())
}

/// `A + 2 K` with the clamp `tau` (`<= 0`: none) for a kernel that [`Covariance::sanitized`]
/// (or a clamp applied after it) has already made finite, positive semi-definite and bounded.
#[inline(always)]
pub(crate) fn gaussian_sanitized<R: Roughness>(
    roughness: R,
    k: Covariance,
    tau: f64,
) -> RoughnessMatrix {
    let (b11, b12, b22) = gaussian_entries(roughness, k);
    RoughnessMatrix::from_entries(b11, b12, b22, valid_clamp(roughness, (b11, b12, b22), tau))
}

/// The entries of `A + 2 K` (KHPL16 eq. 15, TK19 sec. 2.2), rounded to `F`: the one formula of
/// [`gaussian_sanitized`] and `batch`'s lanes.
#[inline(always)]
pub(crate) fn gaussian_entries<R: Roughness>(roughness: R, k: Covariance) -> (F, F, F) {
    let (a11, a12, a22) = roughness.entries_f();
    (a11 + 2.0 * k.s11, a12 + 2.0 * k.s12, a22 + 2.0 * k.s22)
}

/// `tau`, or where `tau <= 0` (no clamp) and the result's determinant rounded to `<= 0`,
/// `det(A)` of the unfiltered lobe: the exact lower bound of a filtered determinant, which
/// keeps the result positive definite. Shared by every filter that adds a kernel.
#[inline(always)]
pub(crate) fn valid_clamp<R: Roughness>(roughness: R, (b11, b12, b22): (F, F, F), tau: f64) -> f64 {
    if tau > 0.0 || det_wide(b11, b12, b22) > 0.0 {
        tau
    } else {
        roughness.lobe_det()
    }
}

/// The Gaussian pipeline on the clamp rules: the rules (`kernel::clamp`) are data, the filter
/// applies them.
impl ClampRules {
    /// The whole Gaussian pipeline: [`ClampRules::footprint`] -> [`Footprint::covariance`]
    /// (`sigma` pixels) -> [`ClampRules::kernel`] -> `A' = A + 2 Sigma` ([`gaussian`]), with
    /// the determinant clamp `tau = det(A)` if `det_clamp` (else as
    /// [`gaussian_with_det_clamp`] with `0`). The kernel is sanitised once (by
    /// [`ClampRules::kernel`]). Exact for Beckmann, the TK19 approximation for GGX.
    ///
    /// Always inlined: called out of line, the footprint argument travels through memory, and
    /// a footprint assembled from four scalars just before the call (the batch loops; a
    /// shader's `ddx`/`ddy`) is read back with wider loads than it was stored with, a
    /// store-forwarding stall.
    #[inline(always)]
    pub fn filter_gaussian<R: Roughness>(
        &self,
        roughness: R,
        fp: Footprint,
        sigma: F,
    ) -> RoughnessMatrix {
        let k = self.kernel(self.footprint(fp).covariance(sigma));
        gaussian_sanitized(roughness, k, self.det_clamp_wide(roughness))
    }

    /// [`ClampRules::filter_gaussian`] in `batch`'s lane form (branch-free) up to the entries
    /// of `A' = A + 2 Sigma`: `((a11, a12, a22), tau, ok)`, the entries `filter_gaussian`'s
    /// (before its determinant clamp) bit for bit where `ok`, i.e. where the footprint and
    /// kernel rules take their fast path or common case (the footprint within `max_extent`;
    /// the kernel sane, then within `kappa / 2` or clamped by the eigenvalue clamp's common
    /// case); `tau` the determinant clamp it applies (`f64`; `0` without `det_clamp`). Where
    /// `det A' >= tau` (the caller's test), `filter_gaussian` returns the matrix of these
    /// entries unclamped. The composition of the same pieces, not a second formula. With
    /// `EXACT` the kernel's sanity is decided exactly (with `f64` products in `f32`), else in
    /// `F` alone (a nearly singular kernel is flagged), which keeps an `f32` lane at the full
    /// vector width.
    #[inline(always)]
    pub(crate) fn filter_gaussian_entries_lane<R: Roughness, const EXACT: bool>(
        &self,
        roughness: R,
        fp: Footprint,
        sigma: F,
    ) -> ((F, F, F), f64, bool) {
        let (k, ok) = self.kernel_lane::<EXACT>(fp, sigma);
        (
            gaussian_entries(roughness, k),
            self.det_clamp_wide(roughness),
            ok,
        )
    }
}

/// `A' = A + 2 Sigma` with the Gaussian pixel kernel `Sigma = sigma^2 (dh_u dh_u^T + dh_v
/// dh_v^T)` (KHPL16 eq. 13-15; TK19 section 2.2), after the clamp rules
/// ([`ClampRules::filter_gaussian`]: maximum extent, `kappa`, determinant clamp).
///
/// For Beckmann this is the exact convolution of the lobe with the kernel (a Beckmann lobe is
/// a Gaussian of slopes with covariance `A / 2`). For GGX it is TK19's approximation: the GGX
/// of roughness `A + 2 Sigma` (its error against the exact Gaussian-filtered GGX is in the
/// trade table, `docs/tradeoff.md` in the repository). Where it is wrong (measured on a grid,
/// "Where each approximation is wrong" in the same table): for GGX, `D` errs by more than 10 % once
/// the footprint (the slope change per pixel) is wider than about 0.3 lobe widths, except
/// within one lobe width of the peak, where the approximation crosses the exact lobe (there
/// from 0.7 to 2 lobe widths of footprint); a footprint as wide as the lobe gives 21 % at the
/// peak and 29 % two lobe widths out, and 1 to 2 lobe widths of footprint give 58 % to 325 %
/// five to ten lobe widths out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gaussian {
    /// The clamp rules applied to the footprint, the kernel and the filtered matrix.
    pub clamps: ClampRules,
    /// The standard deviation of the Gaussian pixel filter, in pixels.
    pub sigma: F,
}

impl Gaussian {
    /// TK19's configuration: [`ClampRules::default`] (`lambda = 1`, `kappa = 0.18`, the
    /// determinant clamp) and `sigma = 0.5` pixels.
    pub const TK19: Self = Self {
        clamps: ClampRules::DEFAULT,
        sigma: SIGMA_PIXEL,
    };

    /// KHPL16's configuration for the parallelogram kernel: the maximum extent `lambda = 1`
    /// (section 5.2) and the determinant clamp, no `kappa`; `sigma = 0.5` pixels.
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
        sigma: SIGMA_PIXEL,
    };
}

impl Default for Gaussian {
    /// [`Gaussian::TK19`].
    fn default() -> Self {
        Self::TK19
    }
}

impl<R: Roughness> Method<Ggx<R>> for Gaussian {
    type Lobe = Ggx<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Ggx<R>, footprint: Footprint) -> Self::Lobe {
        Ggx::new(
            self.clamps
                .filter_gaussian(material.roughness, footprint, self.sigma),
        )
    }
}

impl<R: Roughness> Method<Beckmann<R>> for Gaussian {
    type Lobe = Beckmann<RoughnessMatrix>;
    #[inline]
    fn lobe(&self, material: &Beckmann<R>, footprint: Footprint) -> Self::Lobe {
        Beckmann::new(
            self.clamps
                .filter_gaussian(material.roughness, footprint, self.sigma),
        )
    }
}
