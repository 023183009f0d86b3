//! The clamping rules of NDF filtering as one configurable set (KHPL16 section 5.2, the GDC
//! 2016 talk, TK19 eq. 1 and its supplement).
//!
//! Every rule trades aliasing (or a numerical failure) for bias. [`ClampRules::default`]
//! holds the papers' defaults; [`ClampRules::NONE`] disables all of them (the unbiased
//! filter, for references); [`ClampRules::GDC2016`] is the GDC listing's configuration.
//!
//! The rules are data: the filters apply them ([`ClampRules::filter_gaussian`] in
//! `filter::gaussian`, [`ClampRules::filter_projected`] in `filter::projected`, the methods of
//! `filter`).
//!
//! | rule | field | default | protects against | costs |
//! |---|---|---|---|---|
//! | maximum extent | `max_extent` | `lambda = 1` (KHPL16 5.2) | footprints that cover the slope plane (grazing views, silhouettes, quad extrapolation): false highlights and flattened lobes | footprints wider than `lambda` are under-filtered: aliasing is left where the footprint estimate exceeds `lambda` |
//! | rectangle floor | `floor` | `epsilon = 1e-3` (KHPL16 5.2) | the printed eight-term GGX rectangle formula dividing a cancelled difference by a tiny area | every rectangle is at least `2 epsilon` wide: the peak of a lobe with `alpha << epsilon` is capped near `1 / (4 epsilon_x epsilon_y)` (`2.5e5` for `1e-3`) instead of `1 / (pi alpha^2)` |
//! | GDC floor | `floor` | `min(alpha, 0.1)` ([`ClampRules::GDC2016`]) | the same, scaled to the lobe; flicker of sub-pixel footprints | always blurs, even at zero footprint: the peak of an isotropic lobe with `alpha <= 0.1` drops to the average over `[-alpha, alpha]^2` (measured in `tests/filter_clamp.rs`) |
//! | kernel roughness | `kappa` | `kappa = 0.18` (TK19 eq. 1) | derivative estimation errors at edges and grazing angles (TK19 3.1) that blow the kernel up | kernel roughness^2 is capped at `kappa` per eigen-direction: under-filtering (residual aliasing) where `2 lambda > kappa`, i.e. where the footprint is wider than `sqrt(0.18) = 0.42` in roughness units |
//! | determinant clamp | `det_clamp` | on, `tau = det(A)` (TK19 supplement) | an elongated filtered matrix whose determinant lost its digits when its entries were rounded (the inverse explodes) | none in exact arithmetic (`det(A + 2 Sigma) >= det(A)`); in floats, where it is active, it adds `t I` to the filtered matrix (`det = tau`, see `RoughnessMatrix`): the filtered peak never exceeds the unfiltered one |

use super::super::footprint::Footprint;
use super::super::ndf::roughness::Roughness;
use super::{BoundingRect, Covariance, KERNEL_MAX};
use super::{F, Vec2};
use crate::math::{self as m, Real};

/// The lower bound on a rectangle's half-extents (KHPL16 section 5.2; GDC 2016).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ExtentFloor {
    /// No floor: half-extents may be `0` (needs an exact rectangle integral).
    None,
    /// Half-extents `>= epsilon` on both axes (KHPL16 section 5.2: `epsilon = 1e-3`).
    Constant(F),
    /// Half-extents `>= min(alpha_axis, cap)` per axis (GDC 2016 listing:
    /// `fp_min = min(roughness, 0.1)`).
    AlphaCapped(F),
}

/// The clamping rules (see the module docs for what each protects against and costs).
///
/// A rule is off when its bound is `F::INFINITY` (`max_extent`, `kappa`),
/// [`ExtentFloor::None`] or `false` (`det_clamp`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClampRules {
    /// `lambda`: the largest centre-to-vertex extent of the parallelogram
    /// ([`Footprint::max_extent`]) and the largest half-extent of a rectangle (slope units).
    pub max_extent: F,
    /// The rectangle floor.
    pub floor: ExtentFloor,
    /// `kappa`: the largest kernel roughness^2 `2 lambda_i(Sigma)` per eigen-direction
    /// (TK19 eq. 1, `min(2 lambda, kappa)`).
    pub kappa: F,
    /// Evaluate filtered matrices with the determinant clamp `tau = det(A_unfiltered)`
    /// (TK19 supplement; [`ClampRules::det_clamp_for`]).
    pub det_clamp: bool,
}

impl Default for ClampRules {
    /// [`ClampRules::DEFAULT`].
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl ClampRules {
    /// The papers' defaults: `lambda = 1`, `epsilon = 1e-3`, `kappa = 0.18`, `tau = det A`.
    pub const DEFAULT: Self = Self {
        max_extent: 1.0,
        floor: ExtentFloor::Constant(1e-3),
        kappa: 0.18,
        det_clamp: true,
    };

    /// KHPL16's rules for its exact kernels: the maximum extent `lambda = 1` (section 5.2) and
    /// the determinant clamp; no rectangle floor (the crate's rectangle integral is exact
    /// without one) and no `kappa` (a TK19 addition).
    pub const KHPL16: Self = Self {
        max_extent: 1.0,
        floor: ExtentFloor::None,
        kappa: F::INFINITY,
        det_clamp: true,
    };

    /// No clamping at all (unbiased; for references and for an exact rectangle integral).
    pub const NONE: Self = Self {
        max_extent: F::INFINITY,
        floor: ExtentFloor::None,
        kappa: F::INFINITY,
        det_clamp: false,
    };

    /// The GDC 2016 listing: `fp = clamp(fp, min(roughness, 0.1), fp_max = 1)`, no `kappa`,
    /// with the determinant clamp.
    pub const GDC2016: Self = Self {
        max_extent: 1.0,
        floor: ExtentFloor::AlphaCapped(0.1),
        kappa: F::INFINITY,
        det_clamp: true,
    };

    /// The maximum-extent rule on a parallelogram (KHPL16 section 5.2, "rescaling the
    /// parallelogram"): both vectors are scaled by `min(1, lambda / max_extent)`, keeping the
    /// shape. Non-finite input (the NaN policy, [`crate::contract`]): a NaN component counts
    /// as `0` ([`Footprint::nan_to_zero`]); infinite components keep their sign (finite ones
    /// become `0`) and the result is rescaled to extent `lambda`, the widest footprint the rule
    /// allows (with an infinite `lambda` they are returned unchanged, and the filters'
    /// [`Covariance::sanitized`] turns them into the widest kernel). A NaN or negative
    /// `lambda` is treated as `0`.
    #[inline]
    pub fn footprint(&self, fp: Footprint) -> Footprint {
        // Fast path (every finite footprint of a real pixel): the squared extent against
        // lambda^2 (no square root, no division). A NaN component makes `e2` NaN and an
        // infinite or overflowing one `+inf`: both take the general path (`l * l` overflows
        // too for a huge lambda: fuzzing).
        if self.footprint_within(fp) {
            return fp;
        }
        let [ux, uy, vx, vy] = [fp.dh_u.x, fp.dh_u.y, fp.dh_v.x, fp.dh_v.y];
        Self::footprint_general(self.max_extent, ux, uy, vx, vy)
    }

    /// Whether [`ClampRules::footprint`] returns `fp` by its fast path (finite, extent at most
    /// `max_extent`); shared with `batch`'s lanes.
    #[inline(always)]
    fn footprint_within(&self, fp: Footprint) -> bool {
        extent_within(self.max_extent, fp)
    }

    /// [`ClampRules::footprint`] beyond its fast path, for `max_extent = l`. Out of line and
    /// taking the components by value, for speed: passed by reference, a footprint assembled
    /// from four scalars in the caller (as in the batch loops) is stored as four floats and
    /// read back as vectors, a store-forwarding stall that costs the batch loops their
    /// vector speed (`benches/batch.rs`, `ggx_d_filtered`).
    #[cold]
    #[inline(never)]
    fn footprint_general(l: F, ux: F, uy: F, vx: F, vy: F) -> Footprint {
        let fp =
            Footprint::from_slope_derivatives(Vec2::new(ux, uy), Vec2::new(vx, vy)).nan_to_zero();
        // With its NaN entries zeroed, a footprint within the extent is returned as the fast
        // path returns it (the same test, so that `fp` and `fp.nan_to_zero()` agree bit for
        // bit even where the squared extent underflows).
        if extent_within(l, fp) {
            return fp;
        }
        let c = [fp.dh_u.x, fp.dh_u.y, fp.dh_v.x, fp.dh_v.y];
        let lambda = if l >= 0.0 { l } else { 0.0 };
        if c.iter().any(|x| x.is_infinite()) {
            if !lambda.is_finite() {
                return fp;
            }
            let dir = |v: F| {
                if v.is_infinite() { v.signum() } else { 0.0 }
            };
            return scaled_to(
                Footprint::from_slope_derivatives(
                    Vec2::new(dir(fp.dh_u.x), dir(fp.dh_u.y)),
                    Vec2::new(dir(fp.dh_v.x), dir(fp.dh_v.y)),
                ),
                lambda,
            );
        }
        let scale = fp.dh_u.abs().max(fp.dh_v.abs()).max_element();
        if scale == 0.0 {
            return fp;
        }
        // Extent of fp / scale (no overflow), compared with lambda / scale.
        let unit = Footprint::from_slope_derivatives(fp.dh_u / scale, fp.dh_v / scale);
        let e = unit.max_extent();
        if e * scale <= lambda {
            fp
        } else {
            scaled_to(unit, lambda)
        }
    }

    /// The rectangle rules: half-extents clamped to `[floor, lambda]` per axis (KHPL16
    /// section 5.2 "clamping h_s and h_t"; GDC 2016 `clamp(fp, fp_min, fp_max)`), `alpha` the
    /// lobe's per-axis roughness for [`ExtentFloor::AlphaCapped`]. If the floor exceeds
    /// `lambda` the floor wins (as GLSL `clamp` with `min > max` is undefined, we pick the
    /// conservative side). NaN half-extents become `0` before the floor; `+inf` becomes
    /// `lambda`, the widest rectangle the rule allows (and stays infinite under
    /// [`ClampRules::NONE`]); negative values are taken by magnitude.
    #[inline]
    pub fn rect(&self, r: BoundingRect, alpha: Vec2) -> BoundingRect {
        self.rect_bounds(alpha).apply(r)
    }

    /// The per-axis bounds of [`ClampRules::rect`] for the lobe's `alpha`: computed once per
    /// lobe by `batch`'s box filter, then applied per element.
    #[inline]
    pub(crate) fn rect_bounds(&self, alpha: Vec2) -> RectBounds {
        let floor = match self.floor {
            ExtentFloor::None => Vec2::ZERO,
            ExtentFloor::Constant(e) => Vec2::splat(e),
            ExtentFloor::AlphaCapped(cap) => alpha.abs().min(Vec2::splat(cap)),
        };
        let floor_fix = |v: F| if v >= 0.0 && v.is_finite() { v } else { 0.0 };
        let lambda = if self.max_extent >= 0.0 {
            self.max_extent
        } else {
            0.0
        };
        RectBounds {
            floor: Vec2::new(floor_fix(floor.x), floor_fix(floor.y)),
            lambda,
        }
    }

    /// The kernel-roughness rule of TK19 eq. 1 in matrix form: `2 Sigma'` has the
    /// eigenvalues `min(2 lambda_i, kappa)` and `Sigma`'s eigenvectors
    /// ([`Covariance::clamp_eigenvalues`] with `kappa / 2`), after
    /// [`Covariance::sanitized`]. For an isotropic kernel this is exactly eq. 1. A NaN or
    /// negative `kappa` is treated as `0` (no filtering).
    #[inline]
    pub fn kernel(&self, k: Covariance) -> Covariance {
        let k = k.sanitized();
        if self.kappa_off() {
            return k;
        }
        k.clamp_eigenvalues_sanitized(self.half_kappa())
    }

    /// Whether the `kappa` rule is off (`+inf`).
    #[inline(always)]
    fn kappa_off(&self) -> bool {
        self.kappa.is_infinite() && self.kappa > 0.0
    }

    /// The eigenvalue bound of the `kappa` rule, `kappa / 2` (`0` for a NaN or negative
    /// `kappa`).
    #[inline(always)]
    fn half_kappa(&self) -> F {
        0.5 * if self.kappa >= 0.0 { self.kappa } else { 0.0 }
    }

    /// The determinant clamp `tau` for filtering `roughness`: `det(A)` of the unfiltered
    /// lobe (`alpha_x^2 alpha_y^2` for an axis-aligned one, TK19 supplement; for a clamped
    /// [`RoughnessMatrix`](super::super::ndf::roughness::RoughnessMatrix) its `det A_c`) if `det_clamp`, else `0` (but a clamped
    /// `RoughnessMatrix` keeps its own clamp, `det A_c`, either way). The determinant is the one
    /// every filter clamps with (computed in `f64` from the entries by
    /// `det_wide`), rounded to `F`.
    #[inline]
    pub fn det_clamp_for<R: Roughness>(&self, roughness: R) -> F {
        F::from_f64(self.det_clamp_wide(roughness))
    }

    /// [`ClampRules::det_clamp_for`] in `f64`, as the filters use it.
    #[inline(always)]
    pub(crate) fn det_clamp_wide<R: Roughness>(&self, roughness: R) -> f64 {
        if self.det_clamp {
            roughness.lobe_det()
        } else {
            roughness.own_det_clamp()
        }
    }

    /// `kernel(footprint(fp).covariance(sigma))` of the filters' lanes: `(kernel, ok)`, the
    /// scalar rules' kernel bit for bit where `ok` (the footprint within `max_extent`; the
    /// kernel sane, decided exactly with `EXACT`, else by [`Covariance::is_sane_conservative`]; then
    /// within `kappa / 2` or clamped by the eigenvalue clamp's common case).
    #[inline(always)]
    pub(crate) fn kernel_lane<const EXACT: bool>(
        &self,
        fp: Footprint,
        sigma: F,
    ) -> (Covariance, bool) {
        // `kernel`: the sanitiser's fast path, then the eigenvalue clamp of the kappa rule.
        let k = fp.covariance(sigma);
        let sane = if EXACT {
            k.is_sane()
        } else {
            k.is_sane_conservative()
        };
        let (clamped, clamp_ok) = k.clamp_eigenvalues_lane(self.half_kappa());
        let off = self.kappa_off();
        let k = if off { k } else { clamped };
        (k, self.footprint_within(fp) & sane & (off | clamp_ok))
    }

    /// The per-batch constants of [`Narrow::entries`] for `roughness` and `sigma`, computed
    /// once per call of a batch function: inside the lane loop, the conditional division of
    /// `mu` and the conditional load of `kappa` keep LLVM from vectorising the AVX2 loop of
    /// `batch::beckmann_d_filtered`.
    #[inline(always)]
    pub(crate) fn narrow<R: Roughness>(&self, roughness: R, sigma: F) -> Narrow {
        // The kernel in units of sigma^2, Sigma = sigma^2 Sigma_0.
        let s2 = sigma * sigma;
        let mu = if s2 > 0.0 {
            self.half_kappa() / s2
        } else {
            F::INFINITY
        };
        let l = self.max_extent;
        let l4 = if l >= 0.0 { 4.0 * (l * l) } else { -1.0 };
        let cap = (l4 * (1.0 - 16.0 * F::EPSILON))
            .min(32.0 * mu)
            .min(KERNEL_MAX / s2 * (1.0 - 16.0 * F::EPSILON));
        let scale = 2.0 * s2;
        Narrow {
            mu,
            cap,
            scale,
            s_ok: scale <= F::MAX,
            a: roughness.entries_f(),
        }
    }
}

/// The narrow filtered-Beckmann lane's per-batch constants ([`ClampRules::narrow`]): the
/// lobe's entries, the `kappa` bound `mu`, the extent cap and the scale `2 sigma^2`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Narrow {
    mu: F,
    cap: F,
    scale: F,
    s_ok: bool,
    a: (F, F, F),
}

impl Narrow {
    /// The entries of `A' = A + 2 Sigma'` of [`ClampRules::filter_gaussian`] in `f32`
    /// arithmetic throughout, for `batch`'s narrow filtered-Beckmann lane (branch-free), for the footprint `[u_x, u_y, v_x, v_y]`:
    /// `(entries, ok)`, **not** the scalar route's entries bit for bit but within a scaled
    /// error of them (below) where `ok`.
    ///
    /// The kernel in units of `sigma^2`: `Sigma_0 = u u^T + v v^T = [[a, b], [b, c]]` of the
    /// footprint `(u, v)` ([`Footprint::covariance`], TK19 section 2.2), its eigenvalues
    /// `lambda_+- = (T +- R) / 2` (`T = a + c`, `R = sqrt((a - c)^2 + 4 b^2)`), its determinant
    /// from the footprint, `(u_x v_y - u_y v_x)^2` (no cancelled `a c - b^2`), the `kappa`
    /// rule's bound `mu = kappa / (2 sigma^2)` (TK19 eq. 1): `Sigma_0` itself where `lambda_+
    /// <= mu`, `mu I` where `lambda_- >= mu` (decided as `det >= mu lambda_+`, no division),
    /// else `Sigma_0' = lambda_- I + h (Sigma_0 - lambda_- I)` with `h = (mu - lambda_-) / R`
    /// and `lambda_- = det / lambda_+` (one division for both): the larger eigenvalue clamped
    /// to `mu`, the smaller kept, each entry a sum of non-negative terms. Then `A' = A + 2
    /// sigma^2 Sigma_0'` (KHPL16 eq. 15).
    ///
    /// `ok` holds where the footprint is within `max_extent` (decided by `2 lambda_+`, that is
    /// `T + R`, at least `T + 2 |b|`, four times the squared extent, with a margin of `16
    /// eps`: an element nearer the bound is decided by the scalar route), the kernel within
    /// [`KERNEL_MAX`] (the sanitiser's fast path), the clamp at most 16-fold (`lambda_+ <= 16
    /// mu`: the bound below) and `2 sigma^2` finite; everything else is the scalar route's
    /// (the caller flags it).
    ///
    /// Error where `ok` (against the exact pipeline on the same inputs): each entry of `A'`
    /// within `24 u sqrt(A'_ii A'_jj)` (`u = eps / 2`), the sum of: the kernel's entries
    /// (`2 u`, the off-diagonal one by Cauchy-Schwarz, `|u_x u_y| + |v_x v_y| <= sqrt(a c)`);
    /// the determinant (`3 u` relative, and where the footprint is nearly degenerate its
    /// absolute `2 u sqrt(lambda_- lambda_+)`, at most `8 u` of `sqrt(A'_11 A'_22)` once the
    /// clamp is at most 16-fold); the clamp's arithmetic (`8 u`, the longest chain of
    /// roundings, each relative to a non-negative term or, for `h`, cancelling only where its
    /// product with `Sigma_0 - lambda_- I` is small); the scale and the sum with `A` (`3 u`),
    /// and `2 u` for a `keep` or `iso` decided by rounding at its boundary (where the
    /// branches meet). Tested against the `f64` pipeline below.
    #[inline(always)]
    pub(crate) fn entries(&self, [ux, uy, vx, vy]: [F; 4]) -> ((F, F, F), bool) {
        let Self {
            mu,
            cap,
            scale,
            s_ok,
            a: (a11, a12, a22),
        } = *self;
        let (a0, b0, c0) = (ux * ux + vx * vx, ux * uy + vx * vy, uy * uy + vy * vy);
        let dd = ux * vy - uy * vx;
        let det2 = dd * (dd + dd);
        let t0 = a0 + c0;
        let d0 = a0 - c0;
        let b2 = b0 + b0;
        let r0 = m::sqrt(d0 * d0 + b2 * b2);
        let l0 = t0 + r0;
        let keep = l0 <= mu + mu;
        let hn = mu * l0 - det2;
        let iso = hn <= 0.0;
        let w = 1.0 / (r0 * l0);
        let h = hn * w;
        let lmin = det2 * (r0 * w);
        let (x11, x12, x22) = if keep {
            (a0, b0, c0)
        } else if iso {
            (mu, 0.0, mu)
        } else {
            (lmin + h * (a0 - lmin), h * b0, lmin + h * (c0 - lmin))
        };
        let ok = s_ok & (l0 <= cap) & (keep | iso | (w <= F::MAX));
        (
            (a11 + scale * x11, a12 + scale * x12, a22 + scale * x22),
            ok,
        )
    }
}

/// The bounds of [`ClampRules::rect`] for one lobe: half extents clamped to `[floor,
/// lambda]` per axis (the floor winning).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RectBounds {
    floor: Vec2,
    lambda: F,
}

impl RectBounds {
    /// The clamped rectangle (branch-free: selects, `min`, `max`).
    #[inline(always)]
    pub(crate) fn apply(self, r: BoundingRect) -> BoundingRect {
        let fix = |v: F| if v.is_nan() { 0.0 } else { v.abs() };
        let h = Vec2::new(fix(r.half_extent.x), fix(r.half_extent.y)).min(Vec2::splat(self.lambda));
        BoundingRect::new(h.max(self.floor))
    }
}

/// Scales a footprint with nonzero, finite extent to extent `e` (else zero).
fn scaled_to(fp: Footprint, e: F) -> Footprint {
    let cur = fp.max_extent();
    if !(cur > 0.0 && cur.is_finite()) {
        return Footprint::ZERO;
    }
    // Divide first: `e / cur` alone overflows for `e` near `F::MAX`, and `0 * inf` is NaN.
    Footprint::from_slope_derivatives(fp.dh_u / cur * e, fp.dh_v / cur * e)
}

/// Whether `fp` is finite with extent at most `l` (and `l >= 0`), by its squared extent
/// against `l^2` (no square root, no division): the fast path of [`ClampRules::footprint`].
#[inline(always)]
fn extent_within(l: F, fp: Footprint) -> bool {
    let (p, q) = (fp.dh_u + fp.dh_v, fp.dh_u - fp.dh_v);
    let e2 = 0.25 * p.length_squared().max(q.length_squared());
    (l >= 0.0) & (e2 <= l * l) & (e2 <= F::MAX)
}

#[cfg(test)]
mod tests {
    use super::super::super::ndf::roughness::AxisAligned;
    use super::*;

    /// Which of `Narrow::entries`' cases the reference took.
    #[derive(PartialEq)]
    enum Split {
        Kept,
        Clamped,
        Isotropic,
    }

    /// The entries of `A' = A + 2 Sigma'` in `f64`, computed independently of
    /// `Narrow::entries`: the kernel `Sigma = sigma^2 (u u^T + v v^T)` of the footprint
    /// `[u_x, u_y, v_x, v_y]`, its eigenvalues from `hypot` and the footprint's determinant, its
    /// eigenvectors from `atan2`, both eigenvalues clamped to `kappa / 2` and the kernel rebuilt
    /// from them; `A = diag(alpha^2, (1.5 alpha)^2)` rounded to `F` as the lobe stores it.
    fn reference_entries(fp: [f64; 4], sigma: F, kappa: F, alpha: f64) -> ([f64; 3], Split) {
        let [ux, uy, vx, vy] = fp;
        let s2 = sigma.to_f64() * sigma.to_f64();
        let (a, b, cc) = (
            s2 * (ux * ux + vx * vx),
            s2 * (ux * uy + vx * vy),
            s2 * (uy * uy + vy * vy),
        );
        let det = s2 * s2 * (ux * vy - uy * vx).powi(2);
        let lmax = 0.5 * (a + cc) + (0.5 * (a - cc)).hypot(b);
        let lmin = if lmax > 0.0 { det / lmax } else { 0.0 };
        let m = 0.5 * kappa.to_f64();
        // The larger eigenvalue's direction.
        let phi = 0.5 * b.atan2(0.5 * (a - cc));
        let (ec, es) = (phi.cos(), phi.sin());
        let (p, q) = (lmax.min(m), lmin.min(m));
        let split = if lmin >= m {
            Split::Isotropic
        } else if lmax > m {
            Split::Clamped
        } else {
            Split::Kept
        };
        let (ax, ay) = (alpha * alpha, (1.5 * alpha) * (1.5 * alpha));
        let (ax, ay) = (F::from_f64(ax).to_f64(), F::from_f64(ay).to_f64());
        let want = [
            ax + 2.0 * (p * ec * ec + q * es * es),
            2.0 * (p - q) * ec * es,
            ay + 2.0 * (p * es * es + q * ec * ec),
        ];
        (want, split)
    }

    /// `Narrow::entries` (`f32`) against the pipeline in `f64` on the same
    /// inputs, computed independently (the kernel's eigenvalues from `hypot` and the
    /// footprint's determinant, its eigenvectors from `atan2`, both eigenvalues clamped and
    /// the kernel rebuilt from them): where `ok`, every entry of `A'` within the documented
    /// `24 u sqrt(A'_ii A'_jj)` plus `2 u` at the branches' boundaries (tested at `26 u`). On
    /// footprints from `1e-4` to the extent bound, anisotropies to `1e4` (nearly degenerate
    /// ones among them), exactly isotropic and degenerate ones, and clamps from none to
    /// sixteen-fold; the shares of clamped and `mu I` results are counted so that neither
    /// branch can go untested.
    #[test]
    fn narrow_entries_within_their_bound() {
        if F::MANTISSA_DIGITS > 24 {
            return; // `f32` only: `batch` uses it in `f32`.
        }
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || crate::math::test_uniform(&mut state);
        let u = F::EPSILON.to_f64() / 2.0;
        let (mut worst, mut ok_n, mut clamped, mut iso, mut total) = (0.0f64, 0, 0, 0, 0);
        for kappa in [0.18, 1e-3, F::INFINITY] {
            let rules = ClampRules {
                kappa,
                ..ClampRules::DEFAULT
            };
            for sigma in [0.5 as F, 2.0] {
                for alpha in [1e-3, 0.01, 0.1, 0.5] {
                    let r = AxisAligned::new(F::from_f64(alpha), F::from_f64(1.5 * alpha)).unwrap();
                    for k in 0..20_000 {
                        let ext = 10f64.powf(-3.0 + 3.0 * next()) / sigma.to_f64();
                        let aniso = match k % 8 {
                            0 => 1.0, // an isotropic kernel (`R = 0`)
                            1 => 0.0, // a degenerate one (`det = 0`)
                            _ => 10f64.powf(-4.0 * next()),
                        };
                        let th = core::f64::consts::TAU * next();
                        let (c, s) = (th.cos(), th.sin());
                        let (ux, uy, vx, vy) = (
                            F::from_f64(ext * c),
                            F::from_f64(ext * s),
                            F::from_f64(-ext * aniso * s),
                            F::from_f64(ext * aniso * c),
                        );
                        let ((b11, b12, b22), ok) =
                            rules.narrow(r, sigma).entries([ux, uy, vx, vy]);
                        total += 1;
                        if !ok {
                            continue;
                        }
                        ok_n += 1;
                        let fp = [ux, uy, vx, vy].map(|x| x.to_f64());
                        let (want, split) = reference_entries(fp, sigma, kappa, alpha);
                        clamped += usize::from(split == Split::Clamped);
                        iso += usize::from(split == Split::Isotropic);
                        let got = [b11.to_f64(), b12.to_f64(), b22.to_f64()];
                        let scale = [want[0], (want[0] * want[2]).sqrt(), want[2]];
                        for j in 0..3 {
                            let e = (got[j] - want[j]).abs() / scale[j] / u;
                            worst = worst.max(e);
                            assert!(
                                e <= 26.0,
                                "entry {j}: {} vs {} ({e} u; kappa {kappa}, sigma {sigma}, \
                                 alpha {alpha}, footprint {:?})",
                                got[j],
                                want[j],
                                fp
                            );
                        }
                    }
                }
            }
        }
        assert!(ok_n > total / 3, "{ok_n} of {total} on the narrow path");
        assert!(clamped > ok_n / 10, "{clamped} of {ok_n} clamped");
        assert!(iso > ok_n / 50, "{iso} of {ok_n} isotropic");
        std::println!(
            "narrow entries: {ok_n} of {total} ok ({clamped} clamped, {iso} mu I); worst {worst:.2} u"
        );
    }
}
