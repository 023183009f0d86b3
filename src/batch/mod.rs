//! Batch evaluation over slices (structure of arrays), for baking and offline use, at SIMD
//! speed on stable Rust.
//!
//! Each function evaluates one scalar function of the crate element by element and writes
//! `out[i]`. Inputs are separate slices per component (`mx`, `my`, `mz`, ...). The filtered
//! functions take the same [`ClampRules`](super::ClampRules) and pixel `sigma` as the scalar
//! route [`ClampRules::filter_gaussian`](super::ClampRules::filter_gaussian).
//!
//! **Lengths.** Every function processes the common prefix `n = min` of all slice lengths
//! (including `out`), leaves `out[n..]` untouched and returns `n`. It never panics.
//!
//! **Bad input.** As the scalar functions: NaN, infinite or back-facing (`m_z <= 0`)
//! elements give `0` for `D` (never NaN) and the scalar path's value for `Lambda` and `G2`,
//! without affecting the other elements.
//!
//! **Memory.** No batch function allocates (`tests/batch_alloc.rs` counts with a global
//! allocator, both precisions, the fallback path included) or touches memory beyond the
//! slices it is given.
//!
//! # How the loops vectorise
//!
//! Every function runs one chunk driver (`lanes.rs`): per block of 512 elements, a loop over a
//! branch-free *lane* form of the kernel, which LLVM vectorises (4 `f32` lanes with the
//! x86-64 baseline SSE2, 8 / 16 with AVX2 / AVX-512), then, only where some element was
//! flagged, a scan that evaluates the flagged elements by the scalar function itself. A lane
//! is the scalar function's own formula core with its checks turned into selects (the same
//! helpers, not a copy): the rare inputs whose scalar path branches elsewhere (a rescaled
//! direction, a grazing `w`, a kernel outside the eigenvalue clamp's common case, an active
//! determinant clamp, the box filter's far field) are flagged. The flags cost nothing where
//! nothing is flagged. Transcendental functions in lanes are polynomials (`exp`:
//! `filter::exp_poly`'s reduction; Beckmann's `Lambda`: the `erfc` fit shared with the exact
//! Gaussian filter's sampler; the box filter's `atan2`: Cephes' reduction and rational).
//! Where one kernel has several lane forms (the box filter's pairs of Gauss-Legendre rules
//! and its closed form), the elements are sorted by form first and each form runs its own
//! loop.
//!
//! With the optional `dispatch` feature (std, x86-64) the same loop is also compiled for
//! x86-64-v3 (AVX2, FMA) and x86-64-v4 (AVX-512) and the widest the CPU supports is chosen
//! at run time, through `pulp`'s safe target-feature contexts: the crate stays
//! `forbid(unsafe_code)`. [`simd_level`] names the instruction set in use. The lanes' results
//! do not depend on it (no fused multiply-add is formed: Rust does not contract `a * b + c`).
//! The filtered functions and the deferred presets vectorise profitably only with 256-bit
//! vectors or wider (the filters' lanes carry an `f64` matrix and both branches of the
//! clamps; on SSE2 they measured 0.7 times the scalar loop; the presets' lanes 0.4 to 1.5
//! times): on the SSE2 baseline they run the scalar path
//! (so [`beckmann_d_filtered`] there equals the scalar route bit for bit; with AVX2 or
//! AVX-512 it is within the bound below).
//!
//! # Agreement with the scalar path
//!
//! | function | against the scalar function of the same precision | why | tested in |
//! |---|---|---|---|
//! | [`ggx_d`], [`ggx_lambda`], [`ggx_g2`], [`ggx_d_filtered`] (every [`ClampRules`](super::ClampRules)) | bit for bit | the lane is the scalar formula; every branch it skips is flagged | `tests/batch.rs` (random and adversarial input, every rule set, footprints that trigger each clamp) |
//! | [`deferred_filter`] with `exponent = 1` (every preset but Unreal and Babylon.js) | bit for bit | the lane is the scalar steps with the domain and norm as constants (one loop per pair) and the branches as selects; the eigenvalue norm off its fast path is flagged | `tests/batch.rs` (every preset, every domain and norm, adversarial input) |
//! | [`deferred_filter`] with another exponent | relative `(2 d + 1) eps` in the perceptual domain (`d + 1` in the others), `d` the power's error in ulps: the lane power's (`f64` arithmetic: half an `f32` ulp plus `1e-13`; in `f64` `1.6e-14 + 3 eps abs(y)`, `y = exponent ln(norm)`) plus libm's `powf` (one ulp) | `norm^exponent` by `lanes.rs`' `pow_lane`; the perceptual domain squares `p` | `tests/batch.rs`, the `pow_lane` unit test |
//! | [`d_rect`], Gauss-Legendre elements (both sides short) and every element the lanes flag | bit for bit | the pairs of 2-, 4-, 6-point rules of the scalar case analysis in lanes (one loop per pair, the elements sorted by pair), every other case flagged | `tests/batch.rs` |
//! | [`d_rect`], four-edge closed-form elements (a long side) | before the rounding to `F`, `8 eps_64 M + 4 eps_64 abs(D)`, `M` the edge terms' magnitudes scaled as `D` (`M / D` the form's cancellation); in `f32` then the same value or one ulp apart (measured: the same) | the scalar formula (`edges_by`) with the four angles by `lanes.rs`' `atan2_upper_lane` (`3 eps_64`) in place of libm's (`2 eps_64`); the products and sums round apart (`3 eps_64 M`), the area, division, `k`, `1 / h_z^4` (`4 eps_64 abs(D)`) | `tests/batch_bounds.rs` (realistic and adversarial input), the `atan2_upper_lane` unit test |
//! | [`beckmann_d`], [`beckmann_d_filtered`] | relative `E + 2 eps`, plus `x eps` where the scalar path takes its far-tail branch (`x > -ln F::MIN_POSITIVE`); results below `F::MIN_POSITIVE` flushed to `0` (absolute error below `F::MIN_POSITIVE`) | the exponent `x` and factor `k = n / pi` are the scalar path's bit for bit; `exp(-x) k` is the polynomial exponential (relative `E = 2.5e-7` in `f32`, `1.5e-14` in `f64`) and one rounding, against libm's `exp` (one ulp) and the scalar product; the scalar far-tail branch rounds `x - ln k` (up to `x eps`) | `tests/batch.rs` |
//! | [`beckmann_lambda`] | absolute `L (1 + Lambda)`, `L = 2.1e-7` (`f32`), `1.9e-8` (`f64`), plus `(5 + 3 a^2) eps Lambda` | the `erfc` fit (Numerical Recipes `erfcc`) in place of libm's; `a = |w_z| / sqrt(q)` rounded twice in `F` (the scalar path forms it in `f64`), amplified by `2 a^2 + 3` | `tests/batch_bounds.rs` |
//! | [`beckmann_g2`] | relative `2 L + 3 eps` plus the `Lambda` terms over `1 + Lambda_i + Lambda_o` | `G2 = 1 / (1 + Lambda_i + Lambda_o)` | `tests/batch_bounds.rs` |
//! | [`ggx_sample_visible_normal`] | not bit for bit: the angle between the samples in the unit-roughness space within `B(E, S)` of `tests/batch_bounds.rs` (`~ (9 kappa + 1) E + (d_c + d_wi + E) / abs(n)`, `kappa` the warp's condition number, `d_c` growing as `1 / sin theta` of the cap point) | the scalar sampler's steps and shared cores; `(cos, sin)` of the azimuth by `lanes.rs`' `sincos_2pi` (absolute `2e-15` in `f64`) in place of libm's of the rounded `phi`, the cap height not fused | `tests/batch_bounds.rs` (against `f64`), the `sincos_2pi` unit test |
//!
//! The deferred presets in `f32` against the `f64` scalar path: the scalar `f32` path's
//! error, derived step by step in `tests/batch_bounds.rs` (at most `11 eps` for the presets,
//! `alpha <= 0.9` for the projected domain, whose `alpha^2 / (1 - alpha^2)` amplifies by
//! `1 / (1 - alpha^2)`).
//!
//! Against the `f64` scalar path on the same rounded inputs (`tests/batch_bounds.rs`), the
//! `f32` functions keep the scalar `f32` bounds of `tests/ndf_precision.rs` (GGX `D` and
//! `Lambda`: `8 eps`; `G2`: `12 eps`) or add the lane's terms to them (Beckmann `D`:
//! `(11 + 4 x) eps` for the scalar `(8 + 4 x) eps`; `Lambda`: `L (1 + Lambda) +
//! (13 + 7 a^2) eps Lambda`).
//!
//! The sampler's bound holds for the scalar `f32` sampler too (its own error has the same
//! form): both are within `B` of the `f64` sampler.
//!
//! Speed per core, scalar loop against batch, every kernel: the README's batch table
//! (`benches/batch.rs`, groups `batch_<kernel>/<precision>` with `scalar_loop` and `batch`).

use super::{F, PI, Vec2, Vec3};

mod deferred;
mod filtered;
mod lanes;
mod ndf;
mod rect;
mod sample;
mod simd;

pub use deferred::deferred_filter;
pub use filtered::{beckmann_d_filtered, ggx_d_filtered};
pub use ndf::{beckmann_d, beckmann_g2, beckmann_lambda, ggx_d, ggx_g2, ggx_lambda};
pub use rect::d_rect;
pub use sample::ggx_sample_visible_normal;

/// Multi-core batches (feature `rayon`, std only): calls `f(start, out_chunk)` for the
/// consecutive chunks of `out` of `chunk` elements (the last one shorter; `chunk = 0` counts as
/// `1`) on rayon's current thread pool, `start` being the chunk's offset in `out`, so that `f`
/// runs any batch function on the matching sub-slices of its inputs:
///
/// ```
/// # #[cfg(feature = "rayon")] {
/// use filtered_ndf::f32::{Isotropic, batch};
/// let (mx, my, mz) = (vec![0.1f32; 10_000], vec![0.0; 10_000], vec![0.99; 10_000]);
/// let mut out = vec![0.0; 10_000];
/// let r = Isotropic::new(0.2).unwrap();
/// batch::par_chunks(&mut out, 4096, |s, o| {
///     let e = s + o.len();
///     batch::ggx_d(&r, &mx[s..e], &my[s..e], &mz[s..e], o);
/// });
/// # }
/// ```
///
/// Each element gets what the sequential call gives it, bit for bit (no kernel depends on
/// its neighbours). Chunks of a few thousand elements amortise the scheduling. Allocates
/// nothing itself; rayon's pool allocates when it starts its threads.
#[cfg(feature = "rayon")]
pub fn par_chunks(out: &mut [F], chunk: usize, f: impl Fn(usize, &mut [F]) + Sync + Send) {
    use rayon::prelude::*;
    let chunk = chunk.max(1);
    out.par_chunks_mut(chunk)
        .enumerate()
        .for_each(|(k, o)| f(k * chunk, o));
}

/// The vector instruction set the batch kernels run on in this process: `"avx512"`,
/// `"avx2"` or `"sse2"` (x86-64; `"baseline"` elsewhere). With the `dispatch` feature on
/// x86-64, the widest the CPU supports (detected once, capped by the environment variable
/// `FILTERED_NDF_SIMD=sse2|avx2|avx512`, or `sse2-lanes`: the baseline with every lane, for
/// tests); without it, the target features the crate was compiled for (`-C target-cpu`). For
/// reports and benchmarks. A lane computes the same operations at any width; what the level
/// changes is only whether the filtered functions and the deferred presets run their lanes
/// (AVX2, AVX-512) or their scalar path (baseline), see the module docs.
pub fn simd_level() -> &'static str {
    simd::level_name()
}

/// Footprints in structure-of-arrays form: element `i` is the
/// [`Footprint`](super::Footprint) with `dh_u = (dh_u_x[i], dh_u_y[i])`,
/// `dh_v = (dh_v_x[i], dh_v_y[i])` (slope change per pixel).
#[derive(Clone, Copy, Debug)]
pub struct Footprints<'a> {
    /// `dh_u.x` per element.
    pub dh_u_x: &'a [F],
    /// `dh_u.y` per element.
    pub dh_u_y: &'a [F],
    /// `dh_v.x` per element.
    pub dh_v_x: &'a [F],
    /// `dh_v.y` per element.
    pub dh_v_y: &'a [F],
}

impl Footprints<'_> {
    /// The shortest of the four slices.
    #[inline]
    pub fn len(&self) -> usize {
        self.dh_u_x
            .len()
            .min(self.dh_u_y.len())
            .min(self.dh_v_x.len())
            .min(self.dh_v_y.len())
    }

    /// Whether [`Footprints::len`] is `0`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element `i` (which must be below every slice length).
    #[inline]
    pub fn at(&self, i: usize) -> super::Footprint {
        super::Footprint::from_slope_derivatives(
            Vec2::new(self.dh_u_x[i], self.dh_u_y[i]),
            Vec2::new(self.dh_v_x[i], self.dh_v_y[i]),
        )
    }
}

/// Vectors in structure-of-arrays form: element `i` is `(x[i], y[i], z[i])` (directions,
/// micronormals, normal differences).
#[derive(Clone, Copy, Debug)]
pub struct Vec3s<'a> {
    /// `x` per element.
    pub x: &'a [F],
    /// `y` per element.
    pub y: &'a [F],
    /// `z` per element.
    pub z: &'a [F],
}

impl<'a> Vec3s<'a> {
    /// The three slices as one value.
    #[inline]
    pub const fn new(x: &'a [F], y: &'a [F], z: &'a [F]) -> Self {
        Self { x, y, z }
    }

    /// The shortest of the three slices.
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len().min(self.y.len()).min(self.z.len())
    }

    /// Whether [`Vec3s::len`] is `0`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element `i` (which must be below every slice length).
    #[inline]
    pub fn at(&self, i: usize) -> Vec3 {
        Vec3::new(self.x[i], self.y[i], self.z[i])
    }
}
