//! Isotropic "deferred" roughness filtering: one scalar roughness widened by the spread of the
//! shading normal across a pixel (TK19 section 4; KHPL16 section 5.4).
//!
//! The exact filtered NDF needs the anisotropic slope-domain covariance `Sigma` of the pixel
//! footprint (see [`footprint`](super::super::footprint)). A G-buffer with one roughness channel can
//! only hold an isotropic kernel, so TK19 replaces `Sigma` by a multiple of the identity whose
//! variance bounds (or averages) its eigenvalues, and adds it to the squared roughness:
//!
//! - eq. 1, [`Bandwidth::Max`]: `alpha_bar^2 = alpha^2 + min(2 lambda_max, kappa)` (the
//!   tightest conservative isotropic kernel);
//! - eq. 2 and 4, [`Bandwidth::Trace`]: `2 tr(Sigma) = 2 sigma^2 (|dn_u|^2 + |dn_v|^2)`
//!   (conservative, since `lambda_max <= tr(Sigma)`);
//! - eq. 5, [`Bandwidth::Average`]: `2 (lambda_min + lambda_max) / 2 = tr(Sigma)` (less
//!   conservative: balances over- and under-filtering).
//!
//! Listing 2 of TK19 finishes with `saturate`, so `alpha_bar^2 <= 1`. Defaults: `sigma^2 =
//! 0.25` (`SIGMA_PIXEL^2`, a Gaussian pixel filter of standard deviation half a pixel) and `kappa =
//! 0.18` ([`KAPPA`]).
//!
//! Shipping engines write the same shortcut with other constants and in other roughness
//! domains; [`KernelConvention`] describes all of them with one plain value, and
//! [`presets`](super::presets) holds one documented value per published convention. The three
//! TK19 variants are themselves such values ([`Bandwidth::convention`]), so the formula exists
//! once.
//!
//! ```
//! use filtered_ndf::f32::filter::deferred::{Bandwidth, KAPPA, filtered_alpha, normal_difference_covariance};
//! use filtered_ndf::f32::filter::presets;
//! use glam::Vec3;
//!
//! // ddx(normal), ddy(normal) of the G-buffer normal, and the material roughness.
//! let (dn_u, dn_v) = (Vec3::new(0.1, 0.2, 0.0), Vec3::new(0.0, 0.05, -0.1));
//! let alpha = 0.04;
//! // TK19 eq. 4 (Listing 2): alpha_bar^2 = saturate(alpha^2 + min(0.5 (0.05 + 0.0125), 0.18)).
//! let a = presets::TK19_TRACE.apply(alpha, dn_u, dn_v);
//! assert!((a * a - (0.0016 + 0.03125)).abs() < 1e-6);
//! // The same through the covariance form (TK19 eq. 2 with eq. 3).
//! let kernel = normal_difference_covariance(dn_u, dn_v, 0.5); // sigma = 0.5 pixels
//! assert!((filtered_alpha(alpha, &kernel, Bandwidth::Trace, KAPPA) - a).abs() < 1e-6);
//! ```
//!
//! ## Normal differences
//! `dn_u`, `dn_v` are the differences of the unit world-space shading normal between
//! neighbouring pixels (`ddx(normal)`, `ddy(normal)`; TK19 Listing 2). TK19 section 4.4 shows
//! that the derivative of the two-pixel average normal on the projected unit disk has the
//! length `|n - n_u|` (eq. 3), so `tr(Sigma) = sigma^2 (|dn_u|^2 + |dn_v|^2)` needs no
//! tangent frame. The eigenvalues need the angle between the two derivatives as well; this
//! module takes it from the world-space vectors: the Gram matrix
//! `sigma^2 [[dn_u.dn_u, dn_u.dn_v], [dn_u.dn_v, dn_v.dn_v]]` ([`normal_difference_covariance`])
//! has the same trace as `Sigma` exactly and the same eigenvalues to first order in `|dn|`
//! (exactly when both average normals share one tangent frame).

use super::super::kernel::{Covariance, SIGMA_PIXEL};
use super::super::ndf::roughness::{ALPHA_MAX, Isotropic};
use super::super::vector;
use super::{F, Vec3};
use crate::math as m;

/// TK19's clamp `kappa` on the kernel's squared roughness (TK19 eq. 1, after KHPL16's
/// axis-aligned filtering): it bounds the extra `alpha^2` a footprint can add, protecting
/// against the huge derivatives of silhouettes and grazing angles at the cost of
/// under-filtering strongly curved regions (units: slope^2).
pub const KAPPA: F = 0.18;

/// Which isotropic bandwidth replaces the anisotropic covariance `Sigma` (TK19 sections
/// 4.2-4.6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bandwidth {
    /// `2 lambda_max(Sigma)`, TK19 eq. 1: the tightest conservative isotropic kernel.
    Max,
    /// `2 tr(Sigma) = 2 (lambda_min + lambda_max)`, TK19 eq. 2 and 4: conservative and cheap.
    Trace,
    /// `tr(Sigma) = 2 (lambda_min + lambda_max) / 2`, TK19 eq. 5: less conservative.
    Average,
}

impl Bandwidth {
    /// The kernel's squared roughness before the clamp, from a slope-domain covariance
    /// (slope^2): `2 lambda_max`, `2 tr(Sigma)` or `tr(Sigma)`. A NaN entry counts as `0` (the
    /// crate's NaN policy, [`crate::contract`]). For `Max` a covariance with an infinite entry
    /// gives NaN (no eigenvalue) and a negative eigenvalue is clamped to 0; `Trace` and
    /// `Average` read only the diagonal (`+inf` for an infinite variance, negative for
    /// negative variances). [`filtered_alpha`] treats NaN and `+inf` as the maximal, clamped
    /// kernel and a negative kernel as 0.
    #[inline]
    pub fn alpha2(self, kernel: &Covariance) -> F {
        let zero_nan = |x: F| if x.is_nan() { 0.0 } else { x };
        let kernel = &Covariance::new(
            zero_nan(kernel.s11),
            zero_nan(kernel.s12),
            zero_nan(kernel.s22),
        );
        match self {
            Self::Max => 2.0 * lambda_max(kernel),
            Self::Trace => 2.0 * kernel.trace(),
            Self::Average => kernel.trace(),
        }
    }

    /// The same variant as a [`KernelConvention`] on world-space normal differences, with
    /// TK19's defaults (Listing 2: `sigma^2 = 0.25`, `kappa = 0.18` on `alpha^2`, final
    /// saturate): the kernel `2 sigma^2 lambda_max(Gram)` ([`Norm::MaxEigenvalue`]),
    /// `2 sigma^2 (|dn_u|^2 + |dn_v|^2)` or `sigma^2 (|dn_u|^2 + |dn_v|^2)`
    /// ([`Norm::SumSquared`]). The presets `TK19_MAX`, `TK19_TRACE` and `TK19_AVERAGE` are
    /// these values.
    #[inline]
    pub const fn convention(self) -> KernelConvention {
        let s2 = SIGMA_PIXEL * SIGMA_PIXEL;
        let (norm, scale) = match self {
            Self::Max => (Norm::MaxEigenvalue, 2.0 * s2),
            Self::Trace => (Norm::SumSquared, 2.0 * s2),
            Self::Average => (Norm::SumSquared, s2),
        };
        KernelConvention {
            domain: Domain::Alpha2,
            norm,
            scale,
            exponent: 1.0,
            bias: 0.0,
            clamp: KAPPA,
            combine: Combine::Add,
            saturate: true,
            perceptual_floor: 0.0,
        }
    }
}

/// `lambda_max(Sigma)` (clamped to `>= 0`), or NaN if an entry is not finite (the
/// eigenvalue routine would otherwise turn NaN into 0, an under-filtering kernel).
#[inline]
fn lambda_max(kernel: &Covariance) -> F {
    if kernel.s11.is_finite() && kernel.s12.is_finite() && kernel.s22.is_finite() {
        kernel.eigenvalues().1
    } else {
        F::NAN
    }
}

/// The Gram covariance `sigma^2 [[dn_u.dn_u, dn_u.dn_v], [dn_u.dn_v, dn_v.dn_v]]` of two
/// world-space normal differences (slope^2 near the normal). Its trace is exactly TK19's
/// `sigma^2 (|dn_u|^2 + |dn_v|^2)` (eq. 2 with eq. 3) and its eigenvalues are those of the
/// footprint covariance when both average normals share a tangent frame (see the module
/// docs). The entries are not in the tangent frame: use only its invariants (trace,
/// eigenvalues, determinant). Non-finite input gives non-finite entries.
#[inline]
pub fn normal_difference_covariance(dn_u: Vec3, dn_v: Vec3, sigma: F) -> Covariance {
    Covariance::new(dn_u.dot(dn_u), dn_u.dot(dn_v), dn_v.dot(dn_v)) * (sigma * sigma)
}

/// TK19 eq. 1, 4 or 5 from a slope-domain covariance: `alpha_bar = sqrt(saturate(alpha^2 +
/// min(kernel, kappa)))` with `kernel = bandwidth.alpha2(kernel)`, `kappa` = [`KAPPA`] by
/// default. Bad input: see [`KernelConvention::apply_widening`] (negative or NaN `alpha` counts
/// as 0); a NaN kernel entry counts as `0`, an infinite one gives `kappa`.
#[inline]
pub fn filtered_alpha(alpha: F, kernel: &Covariance, bandwidth: Bandwidth, kappa: F) -> F {
    KernelConvention {
        clamp: kappa,
        ..bandwidth.convention()
    }
    .apply_widening(alpha, bandwidth.alpha2(kernel))
}

/// The roughness domain a kernel is added (or max-combined) in, and clamped and saturated in.
/// `alpha` is the GGX/Beckmann roughness (`D(0) = 1 / (pi alpha^2)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Domain {
    /// `v = alpha^2` (TK19, Filament, Unity HDRP, O3DE).
    Alpha2,
    /// `v = alpha` (Godot 4: its "roughness squared" is `alpha`).
    Alpha,
    /// `v = sqrt(alpha)`, the artist-facing "perceptual" roughness (Unreal, three.js,
    /// Babylon.js).
    Perceptual,
    /// `v = alpha^2 / (1 - alpha^2)`, the projected-space squared roughness of Tokuyoshi and
    /// Kaplanyan 2021 (Unity HDRP's `ProjectedSpaceNormalFiltering`); `alpha >= 1` maps to
    /// `+inf`.
    ProjectedAlpha2,
}

impl Domain {
    /// `alpha -> v` (see the variants). `alpha >= 0` expected.
    #[inline(always)]
    pub fn from_alpha(self, alpha: F) -> F {
        match self {
            Self::Alpha2 => alpha * alpha,
            Self::Alpha => alpha,
            Self::Perceptual => m::sqrt(alpha),
            Self::ProjectedAlpha2 => {
                let a2 = alpha * alpha;
                if a2 < 1.0 {
                    a2 / (1.0 - a2)
                } else {
                    F::INFINITY
                }
            }
        }
    }

    /// `v -> alpha`, the inverse of [`Domain::from_alpha`] for `v >= 0`; `+inf` maps to
    /// `+inf` (1 for [`Domain::ProjectedAlpha2`]).
    #[inline(always)]
    pub fn to_alpha(self, v: F) -> F {
        match self {
            Self::Alpha2 => m::sqrt(v),
            Self::Alpha => v,
            Self::Perceptual => v * v,
            Self::ProjectedAlpha2 => {
                if v.is_finite() {
                    m::sqrt(v / (1.0 + v))
                } else {
                    1.0
                }
            }
        }
    }
}

/// The scalar measure of the normal differences a kernel is built from (units: the normal
/// differences are dimensionless, per pixel step).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Norm {
    /// `|dn_u|^2 + |dn_v|^2` (TK19 eq. 4; Filament, HDRP, Godot, O3DE).
    SumSquared,
    /// `max(|dn_u|^2, |dn_v|^2)` (Vlachos 2015; Unreal, Babylon.js).
    MaxSquared,
    /// The largest eigenvalue of the Gram matrix of `dn_u, dn_v` (TK19 eq. 1 with
    /// `sigma = 1`; see [`normal_difference_covariance`]).
    MaxEigenvalue,
    /// `max_i max(|dn_u,i|, |dn_v,i|)`: the largest absolute component of either difference,
    /// not squared (three.js `geometryRoughness`). Frame-dependent.
    MaxAbsComponent,
}

impl Norm {
    /// The measure of `(dn_u, dn_v)` (`>= 0`). A NaN entry of a difference counts as `0` (the
    /// crate's NaN policy: it carries no information, [`crate::contract`]); an infinite entry
    /// gives `+inf`, or for [`Norm::MaxEigenvalue`] NaN (as does a Gram matrix that
    /// overflows), which the widening saturates to its clamp.
    #[inline]
    pub fn eval(self, dn_u: Vec3, dn_v: Vec3) -> F {
        let (v, ok) = self.eval_lane(dn_u, dn_v);
        if ok {
            v
        } else {
            let (dn_u, dn_v) = (vector::nan_to_zero(dn_u), vector::nan_to_zero(dn_v));
            lambda_max(&normal_difference_covariance(dn_u, dn_v, 1.0))
        }
    }

    /// [`Norm::eval`] without branches (the batch lane, and the scalar path's core):
    /// `(measure, ok)`, the measure equal to [`Norm::eval`]'s where `ok`. Only
    /// [`Norm::MaxEigenvalue`] can fail (not `ok` off the eigenvalue routine's fast path:
    /// non-finite or overflowing Gram entries), then `eval` takes the full routine.
    /// The single place the deferred route applies the NaN policy to its input: each NaN entry
    /// of the differences is replaced by `0` first, so no measure below sees a NaN (an
    /// infinite entry gives `+inf`, or NaN through `inf * 0` in the Gram matrix).
    #[inline(always)]
    pub(crate) fn eval_lane(self, dn_u: Vec3, dn_v: Vec3) -> (F, bool) {
        let (dn_u, dn_v) = (vector::nan_to_zero(dn_u), vector::nan_to_zero(dn_v));
        match self {
            Self::SumSquared => (dn_u.dot(dn_u) + dn_v.dot(dn_v), true),
            Self::MaxSquared => (dn_u.dot(dn_u).max(dn_v.dot(dn_v)), true),
            Self::MaxEigenvalue => {
                normal_difference_covariance(dn_u, dn_v, 1.0).max_eigenvalue_lane()
            }
            Self::MaxAbsComponent => (dn_u.abs().max(dn_v.abs()).max_element(), true),
        }
    }
}

/// How the kernel combines with the material's roughness value in [`Domain`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Combine {
    /// `v' = v + k` (convolution: variances add).
    Add,
    /// `v' = max(v, k)` (a roughness floor: Vlachos 2015, Unreal).
    Max,
}

/// An isotropic kernel convention: a plain value that says how one engine turns normal
/// differences into a widened roughness.
///
/// [`apply`](Self::apply) computes, in order:
/// 1. `p = max(sqrt(alpha), perceptual_floor)` and `v = domain.from_alpha(p^2)` (the floor is
///    the engine's minimum perceptual roughness, applied before filtering; 0 = none);
/// 2. `k = scale * norm(dn_u, dn_v)^exponent + bias`, then `k = min(max(k, 0), clamp)` (the
///    clamp is in `domain` units): a NaN entry of a difference counts as `0`, an infinite one
///    gives `clamp`, the maximal kernel (the crate's NaN policy, [`crate::contract`]);
/// 3. `v' = v + k` or `max(v, k)` ([`Combine`]), then `min(v', 1)` if `saturate`;
/// 4. `alpha_bar = domain.to_alpha(v')`, clamped to `[0, ALPHA_MAX]`.
///
/// `scale` includes every constant factor: TK19's `2 sigma^2` is `scale = 0.5`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KernelConvention {
    /// Domain in which the kernel is combined, clamped and saturated.
    pub domain: Domain,
    /// Measure of the normal differences.
    pub norm: Norm,
    /// Factor `c` on `norm^exponent`.
    pub scale: F,
    /// Exponent on the norm (1 for the variance forms; Unreal's default 0.333).
    pub exponent: F,
    /// Added after scaling (Unreal's bias; 0 elsewhere).
    pub bias: F,
    /// Upper bound of the kernel in `domain` units (`F::INFINITY` = none).
    pub clamp: F,
    /// Add or max-combine.
    pub combine: Combine,
    /// Final `min(v', 1)` in `domain` units (HLSL `saturate`).
    pub saturate: bool,
    /// Minimum perceptual roughness `sqrt(alpha)` enforced before filtering (0 = none).
    pub perceptual_floor: F,
}

impl KernelConvention {
    /// The widening `min(max(scale * norm^exponent + bias, 0), clamp)` in `domain` units (the
    /// kernel's contribution to the roughness value). A NaN entry of a difference counts as `0`
    /// ([`Norm::eval`]); an infinite one saturates to `clamp` (the widest kernel of the
    /// convention). Zero differences give `max(bias, 0)` for `exponent > 0`.
    #[inline]
    pub fn widening(&self, dn_u: Vec3, dn_v: Vec3) -> F {
        let n = self.norm.eval(dn_u, dn_v);
        let raw = if self.exponent == 1.0 {
            n
        } else {
            m::powf(n, self.exponent)
        };
        self.widening_of(raw)
    }

    /// The widening from `raw = norm^exponent`: `min(max(scale * raw + bias, 0), clamp)`,
    /// NaN -> `clamp` (shared by [`KernelConvention::widening`] and the batch lane; a NaN here
    /// comes from an infinite difference, the norm having dropped NaN entries).
    #[inline(always)]
    pub(crate) fn widening_of(&self, raw: F) -> F {
        self.clamp_widening(self.scale * raw + self.bias)
    }

    /// `min(max(k, 0), clamp)`, NaN -> `clamp` (the saturated kernel: see
    /// [`KernelConvention::widening_of`]).
    #[inline(always)]
    fn clamp_widening(&self, k: F) -> F {
        if k.is_nan() {
            self.clamp
        } else {
            k.max(0.0).min(self.clamp)
        }
    }

    /// Steps 1, 3 and 4 of [`apply`](Self::apply) for a kernel `k` already in `domain` units
    /// (clamped here like step 2). `alpha` NaN or negative counts as 0, `+inf` as
    /// [`ALPHA_MAX`]; the result is in `[0, ALPHA_MAX]` and never NaN.
    #[inline(always)]
    pub fn apply_widening(&self, alpha: F, k: F) -> F {
        let alpha = if alpha > 0.0 {
            alpha.min(ALPHA_MAX)
        } else {
            0.0
        };
        // sqrt(alpha) >= floor  <=>  alpha >= floor^2 (no sqrt round trip).
        let alpha = alpha.max(self.perceptual_floor * self.perceptual_floor);
        let v = self.domain.from_alpha(alpha);
        let k = self.clamp_widening(k);
        let mut out = match self.combine {
            Combine::Add => v + k,
            Combine::Max => v.max(k),
        };
        if self.saturate {
            out = out.min(1.0);
        }
        let a = self.domain.to_alpha(out);
        if a > 0.0 { a.min(ALPHA_MAX) } else { 0.0 }
    }

    /// The filtered roughness `alpha_bar` for material roughness `alpha` and world-space
    /// normal differences `dn_u`, `dn_v` (see the type docs for the steps and
    /// [`apply_widening`](Self::apply_widening) for bad input; a NaN entry of a difference
    /// counts as `0`, an infinite one gives the clamped maximal kernel).
    #[inline]
    pub fn apply(&self, alpha: F, dn_u: Vec3, dn_v: Vec3) -> F {
        self.apply_widening(alpha, self.widening(dn_u, dn_v))
    }

    /// The deferred front door: the filtered roughness of [`apply`](Self::apply) as an
    /// [`Isotropic`] that every NDF constructor accepts, for any input. `apply` reproduces the
    /// engine's formula and may return `0` (a zero material roughness with zero normal
    /// differences), which is outside the NDFs' domain; here the result is clamped into
    /// `[ALPHA_MIN, ALPHA_MAX]` ([`Isotropic::new_clamped`]).
    ///
    /// ```
    /// use filtered_ndf::f32::{Ggx, Ndf, filter::presets};
    /// use glam::Vec3;
    ///
    /// // alpha 0 and a flat G-buffer: a valid (ALPHA_MIN) roughness, not a panic.
    /// let alpha = presets::TK19_TRACE.filter(0.0, Vec3::ZERO, Vec3::ZERO);
    /// assert!(Ggx::new(alpha).d(Vec3::Z).is_finite());
    /// ```
    #[inline]
    pub fn filter(&self, alpha: F, dn_u: Vec3, dn_v: Vec3) -> Isotropic {
        Isotropic::new_clamped(self.apply(alpha, dn_u, dn_v))
    }
}
