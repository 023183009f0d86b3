//! The deferred presets over slices: one [`KernelConvention`] (a preset of
//! [`presets`](super::super::super::filter::presets) or any other) applied to arrays of material
//! roughness and world-space normal differences.

use super::super::super::filter::deferred::{Domain, KernelConvention, Norm};
use super::super::super::ndf::roughness::Isotropic;
use super::super::super::{F, Vec3};
use super::super::columns::Vec3s;
use super::super::engine::lane_math::{Power, pow_lane};
use super::super::engine::{Kernel, run};

/// [`KernelConvention::filter`] for each material roughness `alpha[i]` and pair of
/// world-space normal differences `dn_u_i = (dn_u.x[i], ...)`, `dn_v_i` (G-buffer
/// `ddx(normal)`, `ddy(normal)`): `out[i] = conv.filter(alpha[i], dn_u_i, dn_v_i).alpha()`,
/// the filtered roughness `alpha_bar = domain.to_alpha(saturate(combine(domain.from_alpha(
/// max(alpha, floor^2)), min(max(scale norm^exponent + bias, 0), clamp))))` clamped into
/// `[ALPHA_MIN, ALPHA_MAX]` (the steps of [`KernelConvention`]; dimensionless). Any input:
/// NaN or negative `alpha` counts as `0`, NaN or infinite differences give the clamped maximal
/// kernel, as the scalar function; never NaN.
///
/// **Bit for bit** with the scalar function for conventions with `exponent = 1` (every preset
/// but [`UNREAL`](super::super::super::filter::presets::UNREAL) and
/// [`BABYLON`](super::super::super::filter::presets::BABYLON)): the lane is the scalar formula, its
/// branches as selects. With another exponent, `norm^exponent` is the engine's lane power
/// `pow_lane` in place of libm's `powf` (relative, in `f64` `1.6e-14 + 3 eps_64 |y|`, `y =
/// exponent ln(norm)`; in `f32`, computed in `f32` arithmetic, `(5 + 3 |exponent|) u`, `u =
/// 2^-24`, for any norm: `6 u` for Unreal's `0.333`; in `f32` arithmetic so that no `f64`
/// value holds the loop to half the vector width), so the widening `k = scale
/// norm^exponent + bias` differs from the scalar one by that plus libm's ulp, and
/// `alpha_bar` by what the domain's `to_alpha` makes of it (the perceptual domain:
/// `alpha = p^2`, twice the relative error of `p`); see the module docs of `batch`.
/// Elements whose norm leaves the lanes' domain (non-finite or overflowing Gram matrix for
/// the eigenvalue norm, a NaN, infinite or subnormal norm before a power) are evaluated by
/// the scalar function. On the SSE2 baseline (no `dispatch`, or a CPU without AVX2) every
/// element runs the scalar function (the lanes do not pay there; see the module docs of
/// `batch`), so the results there equal it bit for bit for every exponent. Returns the
/// number of elements written. Allocates nothing.
pub fn deferred_filter(
    conv: &KernelConvention,
    alpha: &[F],
    dn_u: Vec3s<'_>,
    dn_v: Vec3s<'_>,
    out: &mut [F],
) -> usize {
    let ins = [alpha, dn_u.x, dn_u.y, dn_u.z, dn_v.x, dn_v.y, dn_v.z];
    let c = *conv;
    let pow = Power::new(c.exponent);
    // One loop per (domain, norm, power) with those constants: a `match` in the lane on a
    // loop-invariant enum would stop the vectoriser.
    macro_rules! go {
        ($d:literal, $n:literal) => {
            if c.exponent == 1.0 {
                run(&Deferred::<$d, $n, false> { c, pow }, ins, [out])
            } else {
                run(&Deferred::<$d, $n, true> { c, pow }, ins, [out])
            }
        };
    }
    macro_rules! norms {
        ($d:literal) => {
            match c.norm {
                Norm::SumSquared => go!($d, 0),
                Norm::MaxSquared => go!($d, 1),
                Norm::MaxEigenvalue => go!($d, 2),
                Norm::MaxAbsComponent => go!($d, 3),
            }
        };
    }
    match c.domain {
        Domain::Alpha2 => norms!(0),
        Domain::Alpha => norms!(1),
        Domain::Perceptual => norms!(2),
        Domain::ProjectedAlpha2 => norms!(3),
    }
}

/// The domains and norms by the index of [`Deferred`]'s parameters.
const DOMAINS: [Domain; 4] = [
    Domain::Alpha2,
    Domain::Alpha,
    Domain::Perceptual,
    Domain::ProjectedAlpha2,
];
const NORMS: [Norm; 4] = [
    Norm::SumSquared,
    Norm::MaxSquared,
    Norm::MaxEigenvalue,
    Norm::MaxAbsComponent,
];

/// [`KernelConvention::filter`] with the domain `DOMAINS[D]` and norm `NORMS[N]` constants
/// (the convention's own, set by [`deferred_filter`]), and `POW` whether `exponent != 1`.
struct Deferred<const D: usize, const N: usize, const POW: bool> {
    c: KernelConvention,
    /// `c.exponent` split for [`pow_lane`].
    pow: Power,
}

impl<const D: usize, const N: usize, const POW: bool> Kernel<7, 1> for Deferred<D, N, POW> {
    // The lanes pay only with 256-bit vectors or wider: on SSE2 they run at or below the
    // scalar loop's speed (`docs/batch_measurements.md`).
    const WIDE_ONLY: bool = true;

    /// The scalar steps ([`Norm::eval_lane`], [`KernelConvention::widening_of`],
    /// [`KernelConvention::apply_widening`], [`Isotropic::new_clamped`]) with the power of
    /// [`pow_lane`]; flagged where the norm or the power leaves its fast path.
    #[inline(always)]
    fn lane(&self, [a, ux, uy, uz, vx, vy, vz]: [F; 7]) -> ([F; 1], bool) {
        let c = KernelConvention {
            domain: DOMAINS[D],
            norm: NORMS[N],
            ..self.c
        };
        let (n, n_ok) = c
            .norm
            .eval_lane(Vec3::new(ux, uy, uz), Vec3::new(vx, vy, vz));
        let (raw, p_ok) = if POW {
            pow_lane(n, &self.pow)
        } else {
            (n, true)
        };
        let k = c.widening_of(raw);
        let v = Isotropic::new_clamped(c.apply_widening(a, k)).alpha();
        ([v], !(n_ok & p_ok))
    }

    #[inline(always)]
    fn scalar(&self, [a, ux, uy, uz, vx, vy, vz]: [F; 7]) -> [F; 1] {
        [self
            .c
            .filter(a, Vec3::new(ux, uy, uz), Vec3::new(vx, vy, vz))
            .alpha()]
    }
}
