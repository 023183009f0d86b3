//! The GGX proxy of KHPL16 section 5.4 (eq. 18-20): an effective roughness `alpha'` whose
//! unfiltered GGX has the same peak as the box-filtered GGX, so that a G-buffer can store the
//! filtered lobe as a plain (axis-aligned) roughness.
//!
//! # Eq. 19 solved, and eq. 20 corrected
//! The box-filtered density at the peak (eq. 18) over the square `[-H, H]^2` of an isotropic
//! lobe is, from the four-edge closed form of [`super::rect`] with `U = H / alpha`,
//! `C = atan(U / sqrt(1 + U^2)) / (pi alpha^2 U sqrt(1 + U^2))`. Equating it with the peak
//! `1 / (pi alpha'^2)` of a GGX of roughness `alpha'` (eq. 19) gives
//!
//! `alpha'^2 = H sqrt(alpha^2 + H^2) / atan(H / sqrt(alpha^2 + H^2))
//!           = (alpha^2 + H^2) t / atan(t)`, `t = H / sqrt(alpha^2 + H^2)` in `[0, 1)`.
//!
//! In KHPL16's variable `Delta h = 2 H` (the full side, as in eq. 16) this is
//! `alpha' = sqrt(Delta h) (4 alpha^2 + Delta h^2)^(1/4) / (2 sqrt(atan(Delta h /
//! sqrt(4 alpha^2 + Delta h^2))))`. **Eq. 20 as printed is not consistent with eq. 19**: it has
//! `sqrt(4 alpha^2 + Delta h^2)` where the fourth root belongs, which makes it dimensionally a
//! `slope^(3/2)` and sends it to `sqrt(2) alpha^(3/2)`, not `alpha`, as `Delta h -> 0`. The form
//! above is the one that satisfies eq. 19 (tested against the rectangle integral and against
//! quadrature in `tests/ggx_proxy.rs`).
//!
//! # The simple form
//! Since `t / atan(t)` lies in `[1, 4 / pi)`, the exact value is
//! `alpha' = sqrt(alpha^2 + H^2) sqrt(t / atan t)`: the simple form
//! `sqrt(alpha^2 + Delta h^2)` of eq. 20, read with `Delta h = H` the **half** extent,
//! underestimates it by a factor in `(sqrt(pi) / 2, 1]`, i.e. by at most 11.4 % (`alpha'_simple /
//! alpha'_exact >= 0.886`), approached when the footprint dominates the roughness. Read with the
//! full side `Delta h = 2H` it would overestimate by up to a factor `sqrt(pi) = 1.77`.
//!
//! # Per axis
//! Both forms are applied per axis (`alpha_x` with `H_x`, `alpha_y` with `H_y`), as KHPL16 does
//! for its anisotropic G-buffer roughness. Eq. 19 then holds exactly for isotropic lobes and
//! square footprints (the case the paper solves); otherwise it is the paper's approximation.

use super::super::footprint::Footprint;
use super::super::kernel::ClampRules;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{AxisAligned, Isotropic};
use super::method::Method;
use super::rect::Rect;
use super::{F, Vec2};
use crate::math as m;

/// Sanitised half extent: `|h|`, NaN as `0`, `+inf` as `F::MAX`.
#[inline(always)]
fn sanitized_half_extent(h: F) -> F {
    if h.is_nan() { 0.0 } else { h.abs().min(F::MAX) }
}

/// The exact effective roughness of one axis (KHPL16 eq. 19 solved, module docs):
/// `alpha' = sqrt(alpha^2 + H^2) sqrt(t / atan t)`, `t = H / sqrt(alpha^2 + H^2)`, for a lobe of
/// roughness `alpha` box-filtered over the half extent `H` (slope domain).
///
/// Dimensionless (a slope). `alpha' = alpha` at `H = 0`, `alpha' ~ 2 H / sqrt(pi)` for
/// `H >> alpha`. Domain: `alpha > 0` finite; `H` any value, used as `|H|`, NaN as `0`. Outside
/// that, the result is whatever [`AxisAligned::new_clamped`] makes of it (it may be `inf` or
/// NaN for a non-positive or non-finite `alpha`).
#[inline]
pub fn effective_alpha(alpha: F, half_extent: F) -> F {
    let h = sanitized_half_extent(half_extent);
    let s = m::hypot(alpha, h);
    let t = if s > 0.0 { h / s } else { 0.0 };
    let ratio = if t > 0.0 { t / m::atan(t) } else { 1.0 };
    s * m::sqrt(ratio)
}

/// The simple form of KHPL16 eq. 20 for one axis, `sqrt(alpha^2 + H^2)`, with `H` the half
/// extent (module docs: within 11.4 % below [`effective_alpha`]). Half extent as in
/// [`effective_alpha`].
#[inline]
pub fn effective_alpha_simple(alpha: F, half_extent: F) -> F {
    m::hypot(alpha, sanitized_half_extent(half_extent))
}

/// The exact GGX proxy roughness per axis ([`effective_alpha`] on each axis), clamped into the
/// supported range by [`AxisAligned::new_clamped`]. `half_extent` is the slope-domain half
/// extent of the filtering rectangle (the footprint of [`super::rect::d_rect`]).
#[inline]
pub fn proxy(r: AxisAligned, half_extent: Vec2) -> AxisAligned {
    let a = r.alpha();
    AxisAligned::new_clamped(
        effective_alpha(a.x, half_extent.x),
        effective_alpha(a.y, half_extent.y),
    )
}

/// The simple GGX proxy roughness per axis, `sqrt(alpha^2 + H^2)` ([`effective_alpha_simple`]),
/// clamped by [`AxisAligned::new_clamped`].
#[inline]
pub fn proxy_simple(r: AxisAligned, half_extent: Vec2) -> AxisAligned {
    let a = r.alpha();
    AxisAligned::new_clamped(
        effective_alpha_simple(a.x, half_extent.x),
        effective_alpha_simple(a.y, half_extent.y),
    )
}

/// The GGX proxy of KHPL16 section 5.4 (eq. 18-19, solved exactly: [`proxy`]): the
/// axis-aligned GGX whose peak equals the peak of the box-filtered GGX over the clamped
/// bounding rectangle ([`Rect`]), per axis. Axis-aligned materials only. Where it is wrong
/// against the exact Gaussian filter (`docs/tradeoff.md`, "Where each approximation is
/// wrong"): `D` errs by more than 10 % once the footprint is wider than about 0.2 lobe widths
/// at the peak and 0.3 to 0.5 lobe widths two or more lobe widths out; between one half and
/// one lobe width from the peak only from 0.3 to 5 lobe widths of footprint; up to 420 %.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Proxy {
    /// The clamp rules applied to the rectangle's half extents.
    pub clamps: ClampRules,
}

impl Proxy {
    /// KHPL16: half extents clamped to `lambda = 1`, no floor.
    pub const KHPL16: Self = Self {
        clamps: ClampRules::KHPL16,
    };
}

impl Default for Proxy {
    /// [`Proxy::KHPL16`].
    fn default() -> Self {
        Self::KHPL16
    }
}

impl Method<Ggx<AxisAligned>> for Proxy {
    type Lobe = Ggx<AxisAligned>;
    #[inline]
    fn lobe(&self, material: &Ggx<AxisAligned>, footprint: Footprint) -> Self::Lobe {
        let r = material.roughness;
        let half = Rect {
            clamps: self.clamps,
        }
        .half_extent(r, footprint);
        Ggx::new(proxy(r, half))
    }
}

impl Method<Ggx<Isotropic>> for Proxy {
    type Lobe = Ggx<AxisAligned>;
    #[inline]
    fn lobe(&self, material: &Ggx<Isotropic>, footprint: Footprint) -> Self::Lobe {
        self.lobe(&Ggx::new(AxisAligned::from(material.roughness)), footprint)
    }
}
