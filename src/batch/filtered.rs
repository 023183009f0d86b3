//! The front door's methods over slices: each half vector with its own pixel footprint, one
//! material and one method for the whole batch.

use super::super::footprint::Footprint;
use super::super::kernel::ClampRules;
use super::super::ndf::Ndf;
use super::super::ndf::beckmann::Beckmann;
use super::super::ndf::ggx::Ggx;
use super::super::ndf::roughness::{Roughness, RoughnessMatrix};
use super::{F, Footprints, Vec2, Vec3};

/// Filtered Beckmann (exact Gaussian filtering, KHPL16 eq. 15) through the clamped pipeline
/// for each half vector and footprint: `out[i] = Beckmann::new(rules.filter_gaussian(*r,
/// fp_i, sigma)).d(h_i)` ([`ClampRules::filter_gaussian`]: footprint extent, kernel
/// roughness `kappa`, determinant clamp; [`ClampRules::NONE`] for none), `sigma` the pixel
/// filter's standard deviation in pixels (e.g. [`super::super::kernel::SIGMA_PIXEL`]).
/// Returns the number of elements written. Allocates nothing.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn beckmann_d_filtered<R: Roughness>(
    r: &R,
    rules: &ClampRules,
    sigma: F,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    d_filtered(Beckmann::new, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// Filtered GGX with the TK19 (section 2.2) matrix approximation `A' = A + 2 Sigma` through
/// the clamped pipeline for each half vector and footprint: `out[i] =
/// Ggx::new(rules.filter_gaussian(*r, fp_i, sigma)).d(h_i)` (see [`beckmann_d_filtered`]).
/// Returns the number of elements written. Allocates nothing.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn ggx_d_filtered<R: Roughness>(
    r: &R,
    rules: &ClampRules,
    sigma: F,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    d_filtered(Ggx::new, r, rules, sigma, [hx, hy, hz], fp, out)
}

/// The loop shared by the Gaussian-filtered batch functions: the clamped pipeline
/// [`ClampRules::filter_gaussian`] (the one scalar route, inlined) evaluated by the NDF
/// `ndf(A')` at `h_i`.
#[inline]
fn d_filtered<R: Roughness, N: Ndf>(
    ndf: impl Fn(RoughnessMatrix) -> N,
    r: &R,
    rules: &ClampRules,
    sigma: F,
    [hx, hy, hz]: [&[F]; 3],
    fp: Footprints<'_>,
    out: &mut [F],
) -> usize {
    let n = out
        .len()
        .min(hx.len())
        .min(hy.len())
        .min(hz.len())
        .min(fp.len());
    let (hx, hy, hz, out) = (&hx[..n], &hy[..n], &hz[..n], &mut out[..n]);
    let (ux, uy, vx, vy) = (
        &fp.dh_u_x[..n],
        &fp.dh_u_y[..n],
        &fp.dh_v_x[..n],
        &fp.dh_v_y[..n],
    );
    for i in 0..n {
        let f = Footprint::from_slope_derivatives(Vec2::new(ux[i], uy[i]), Vec2::new(vx[i], vy[i]));
        let a = rules.filter_gaussian(*r, f, sigma);
        out[i] = ndf(a).d(Vec3::new(hx[i], hy[i], hz[i]));
    }
    n
}
