//! Importance sampling of the exact Gaussian-filtered GGX lobe
//! ([`GaussianFilteredGgx`](super::super::filter::GaussianFilteredGgx), the mixture identity of
//! `filter::gaussian_ggx`): normals `D(m) m_z` exactly (a GGX slope plus an independent kernel
//! slope), visible normals through the mixture's Beckmann components.

use super::super::filter::{GaussianFilteredGgx, SAMPLE_T0, sample_component};
use super::super::kernel::Covariance;
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::NdfSampling;
use super::{F, Vec2, Vec3};
use crate::math::{self as m, Real};

/// A uniform number from `[0, 1)` (NaN and out-of-range values clamped, as the other samplers).
#[inline]
fn uniform_f64(u: F) -> f64 {
    let u = u.to_f64();
    if u >= 0.0 {
        u.min(1.0 - 0.5 * f64::EPSILON)
    } else {
        0.0
    }
}

/// Two uniform numbers from one: the high and the low half of its bits (`2^12` levels each
/// from an `f32`, `2^26` from an `f64`). Both uniform on their grids, independent.
#[inline]
fn split_bits(u: f64) -> (f64, f64) {
    let k = if F::MANTISSA_DIGITS > 24 {
        67_108_864.0
    } else {
        4096.0
    };
    let x = u * k;
    // Truncation by conversion (`x` in `[0, k)`; no `floor` in `core`).
    let hi = (x as u64) as f64;
    ((hi + 0.5) / k, x - hi)
}

/// The kernel's principal standard deviations and the unit axis of the first:
/// `(sd1, sd2, cos, sin)`.
fn kernel_axes(lobe: &GaussianFilteredGgx) -> [f64; 4] {
    let [s11, s12, s22] = lobe.k;
    let k = Covariance::new(F::from_f64(s11), F::from_f64(s12), F::from_f64(s22));
    let (ksd2, ksd1) = k.eigenvalues();
    let khalf = 0.5 * (s11 - s22);
    let krad = m::hypot(khalf, s12);
    let (kx, ky) = if krad > 0.0 {
        let (vx, vy) = if khalf >= 0.0 {
            (krad + khalf, s12)
        } else {
            (s12, krad - khalf)
        };
        let n = m::hypot(vx, vy);
        (vx / n, vy / n)
    } else {
        (1.0, 0.0)
    };
    [m::sqrt(ksd1.to_f64()), m::sqrt(ksd2.to_f64()), kx, ky]
}

impl NdfSampling for GaussianFilteredGgx {
    /// Exact: the filtered slope is the sum of two independent slopes, a GGX slope of
    /// roughness `A` (`B t`, `|t|^2 = u / (1 - u)`, the inverse radial CDF of unit-roughness
    /// GGX) and a kernel slope `N(0, Sigma)` (Box-Muller along the kernel's principal axes).
    /// The four uniform numbers are the high and low halves of the bits of `u.x` and `u.y`
    /// (12 bits each from an `f32`, 26 from an `f64`).
    #[inline]
    fn sample_normal(&self, u: Vec2) -> Vec3 {
        let (u1, u3) = split_bits(uniform_f64(u.x));
        let (u2, u4) = split_bits(uniform_f64(u.y));
        let tau = core::f64::consts::TAU;
        let r = m::sqrt(u1 / (1.0 - u1));
        let (tx, ty) = (r * m::cos(tau * u2), r * m::sin(tau * u2));
        let [b11, b21, b22] = self.b;
        let g = (b11 * tx, b21 * tx + b22 * ty);
        let rk = m::sqrt(-2.0 * m::ln(1.0 - u3));
        let (y1, y2) = (rk * m::cos(tau * u4), rk * m::sin(tau * u4));
        let [sd1, sd2, kx, ky] = kernel_axes(self);
        let (k1, k2) = (sd1 * y1, sd2 * y2);
        let s = (g.0 + kx * k1 - ky * k2, g.1 + ky * k1 + kx * k2);
        let mm = crate::f64::footprint::slope::sphere_from_slope(glam::DVec2::new(s.0, s.1));
        Vec3::new(
            F::from_f64(mm.x),
            F::from_f64(mm.y),
            F::from_f64(mm.z).max(F::MIN_POSITIVE),
        )
        .normalize()
    }

    /// Visible normals of the mixture (module docs): with the sampler's fixed grid `w_k`
    /// (step `0.5` in `ln w` from `w = 8.3e-7` to `39`) and weights `W_k = 0.5 w_k e^-w_k`
    /// (the trapezoid rule in `ln w` of `e^-w dw`), the filtered lobe is approximated by the
    /// discrete mixture `sum W_k D_k` of the Beckmann lobes `D_k` of roughness
    /// `A / w_k + 2 Sigma`. The visible normals of a mixture are the mixture of its components'
    /// visible normals with weights `W_k (1 + Lambda_k(wo))` (`D_wo = (wo.m)+ D / (wo_z (1 +
    /// Lambda))` and `Lambda = sum W_k Lambda_k`): a component is drawn by inverting the
    /// cumulative weights with `u.x` (the remainder, rescaled to `[0, 1)`, is reused), then its
    /// visible normal exactly ([`Beckmann`]'s sampler, any matrix form). The drawn density equals
    /// the quadrature of `D_wo` on this grid: its relative error is the rule's discretisation
    /// error (`<= 1.6e-6`, module docs) for normals whose slope has `|c|^2 < ~1e5`, and the
    /// mixture mass below the grid (`~8e-7`) is missing from the far tail. The weights use a
    /// fast Beckmann `Lambda` (Numerical Recipes' Chebyshev fit of `erfc`, relative error
    /// `< 1.2e-7`), computed for the 36 components at once in SIMD lanes: the weights, hence
    /// the choice of the component, are within `2.1e-7` (`f32`) / `1.9e-8` (`f64`) relative
    /// of the exact mixture's.
    fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        if !(wo.is_finite() && wo.z > 0.0) {
            return None;
        }
        let big = wo.abs().max_element().to_f64();
        let (ox, oy, oz) = (
            wo.x.to_f64() / big,
            wo.y.to_f64() / big,
            wo.z.to_f64() / big,
        );
        let n = m::sqrt(ox * ox + oy * oy + oz * oz);
        let (ox, oy, oz) = (ox / n, oy / n, oz / n);
        let (qa, qs) = self.projected(ox, oy);
        let (k, ux) = sample_component(qa, qs, oz, uniform_f64(u.x));
        let (a11, a12, a22) = self.a.clamped_entries();
        let [s11, s12, s22] = self.k;
        let iw = m::exp(-SAMPLE_T0 - 0.5 * k as f64);
        let sd = self.a.sqrt_det().to_f64() * iw;
        let comp = RoughnessMatrix::from_entries(
            F::from_f64(a11.to_f64() * iw + 2.0 * s11),
            F::from_f64(a12.to_f64() * iw + 2.0 * s12),
            F::from_f64(a22.to_f64() * iw + 2.0 * s22),
            sd * sd,
        );
        Beckmann::new(comp).sample_visible_normal(wo, Vec2::new(F::from_f64(ux), u.y))
    }
}
