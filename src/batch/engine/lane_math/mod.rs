//! Lane math: transcendental functions in a form LLVM vectorises (plain arithmetic, bit
//! casts and selects; no calls, no branches), each with its stated and tested bound.
//!
//! | function | replaces | bound (relative) | where tested |
//! |---|---|---|---|
//! | [`exp_neg_times`] `e^-x k` | `Beckmann`'s `exp_neg_times` (libm `exp`, `ln`) | `exp_poly`'s (`2.5e-7` in `f32`, `1.5e-14` in `f64`) plus one rounding, for normal results | `exp.rs` |
//! | `filter::exp_poly` (shared with the exact Gaussian filter) | libm `exp` | `2.5e-7` / `1.5e-14`; its `f32` polynomial alone `3.5 u` | `filter/exp_poly.rs` |
//! | [`pow_lane`] `x^e` | libm `powf` (the deferred presets' norm exponent) | in `f64` `1.6e-14 + 3 eps_64 abs(y)` + `eps_64`, `y = e ln x`; in `f32`, computed in `f32` with `e ln 2` split, `(5 + 3 abs(e)) u` (`u = 2^-24`) | `pow.rs` |
//! | [`ln_lane`] `ln x` | libm `ln` (the Beckmann `D(m) m_z` sampler's `ln(1 - u1)`) | `4 eps_64` in `f64`, `3 eps_32` in `f32` (each computed in its precision) | `log.rs` |
//! | [`sincos_2pi`] `(sin 2 pi u, cos 2 pi u)` | libm `sin`, `cos` of `phi = 2 pi u` (the samplers' azimuth) | absolute `2e-15` computed in `f64` (in `f32`: `2 eps_32`) | `trig.rs` |
//! | [`atan2_upper_lane`] `atan2(y, x)`, `y > 0` | the box filter's `atan2_upper` (libm `atan`; the closed form's edge angles) | `3 eps_64` (derived `2.1`), in `f64` for both precisions | `trig.rs` |
//! | `filter::beckmann_lambda_fast` (shared with its sampler) | Beckmann `Lambda` in `f64` (libm `erfc`) | `2.1e-7 (1 + Lambda)` / `1.9e-8 (1 + Lambda)` absolute | `gaussian_ggx_quad` |
//!
//! A lane whose input leaves the range these functions cover (a subnormal result, a
//! non-finite factor) is flagged, and the driver evaluates that element by the scalar
//! function instead: the flags cost nothing where nothing is flagged.

use super::super::super::F;

mod exp;
mod log;
mod pow;
mod trig;

pub(crate) use exp::{K_MAX, exp_neg_times};
pub(crate) use log::{LN2_HI, LN2_LO, ln_lane, ln_parts_f64};
pub(crate) use pow::{Power, pow_lane};
pub(crate) use trig::{atan2_upper_lane, sincos_2pi};

/// Whether `F` is `f64`.
pub(crate) const WIDE: bool = F::MANTISSA_DIGITS > 24;
