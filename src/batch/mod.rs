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
//! slices it is given. Their working buffers are on the stack, made once per call: at most
//! 48 KiB for the kernels of the chunk driver (`f64`, nine input columns), 60 KiB (`f32`) and
//! 108 KiB (`f64`) for the box filter's sort ([`d_rect`], [`d_rect_filtered`]). Unoptimised
//! builds included, every function runs on a thread of 2 MiB of stack, the default of a
//! spawned thread and of a test (`tests/batch_stack.rs`).
//!
//! **Compilation.** Every function's loops are compiled in this crate, once per roughness form
//! (the generic functions match on the form and call a non-generic function per kernel), not
//! in the crates that call them.
//!
//! # Layout
//!
//! `engine/` is the machinery every kernel runs on and knows no kernel: the chunk driver
//! (blocks, the kernels' lanes, the gathered second lanes, the scalar fallback), the dispatch
//! to the CPU's vector instruction set ([`simd_level`]) and the lane math (branch-free
//! `exp`, `ln`, `pow`, `sin`/`cos`, `atan2` with stated bounds). `kernels/` holds one file
//! per family (the NDF terms, the Gaussian filters, the projected filter, the exact Gaussian
//! filter, the proxy, the box filter, the deferred presets, the pdfs, the samplers), each the
//! lane form of the scalar function and the public functions that run it.
//!
//! # How the loops vectorise
//!
//! Every function but the box filter runs the engine's chunk driver: per block of 512
//! elements, a loop over a branch-free *lane* form of the kernel, which LLVM vectorises (4
//! `f32` lanes with the x86-64 baseline SSE2, 8 / 16 with AVX2 / AVX-512), then, only where
//! some element was flagged, a scan that evaluates the flagged elements by the scalar function
//! itself. A lane is the scalar function's own formula core with its checks turned into
//! selects (the same helpers, not a copy): the rare inputs whose scalar path branches
//! elsewhere (a rescaled direction, a grazing `w`, a kernel outside the eigenvalue clamp's
//! common case, an active determinant clamp, the box filter's far field) are flagged. The
//! `f32` filtered functions run two lanes (*tiers*): the first decides the rules and
//! evaluates the filtered lobe in `f32` alone, so that it runs at the full vector width, and
//! flags what it cannot decide or evaluate to that precision (a nearly singular kernel, a
//! filtered matrix with correlation `rho^2 > 3/4`); the driver gathers those into a dense
//! buffer and runs the second lane over them, still vectorised, which decides and evaluates
//! as the scalar path; only what that flags goes to the scalar path. Filtered Beckmann's and
//! TK19's first lane builds the filtered matrix in `f32` arithmetic too (within a stated bound
//! of the scalar route's, not bit for bit; the table below) and runs as two loops over each
//! block, the matrix then `D`, through a block buffer: its dependency chain (two divisions and
//! two square roots) is long for its instruction count, and the split lets the core overlap
//! twice the elements. Transcendental functions in lanes are polynomials (`exp`:
//! `filter::exp_poly`'s reduction; Beckmann's `Lambda`: the `erfc` fit shared with the exact
//! Gaussian filter's sampler; Beckmann's visible-slope quantile: Cephes' `erfc` rationals;
//! `ln`, `pow`, `sin`/`cos` of the azimuth and the box filter's `atan2`: the engine's lane
//! math). The box filter sorts its elements by the form its case analysis takes (its pairs of
//! Gauss-Legendre rules and its closed form) and runs one loop per form.
//!
//! With the optional `dispatch` feature (std, x86-64) the same loop is also compiled for
//! x86-64-v3 (AVX2, FMA) and x86-64-v4 (AVX-512) and the widest the CPU supports is chosen
//! at run time, through `pulp`'s safe target-feature contexts: the crate stays
//! `forbid(unsafe_code)`. [`simd_level`] names the instruction set in use;
//! `FILTERED_NDF_SIMD` requests one ([`simd_requested`], [`simd_available`]). The lanes'
//! results do not depend on it (no fused multiply-add is formed: Rust does not contract
//! `a * b + c`). [`ggx_d_projected`], [`ggx_d_filtered_projected`], the deferred presets and
//! the `f64` Gaussian-filtered functions vectorise profitably only with 256-bit vectors or
//! wider (the projected filter's lanes carry both branches of the clamps; the presets' and
//! the `f64` tiers' lanes measured at or below the scalar loop's speed on SSE2): on the SSE2
//! baseline they run the scalar path (so `f64` [`beckmann_d_filtered`] there equals the scalar
//! route bit for bit; with AVX2 or AVX-512 it is within the bound below). The `f32`
//! Gaussian-filtered tiers and the box filter's lanes pay on SSE2 too and run there.
//!
//! # Agreement with the scalar path
//!
//! | function | against the scalar function of the same precision | why | tested in |
//! |---|---|---|---|
//! | [`ggx_d`], [`ggx_lambda`], [`ggx_g2`], [`ggx_d_filtered`] in `f64` (every [`ClampRules`](super::ClampRules)) | bit for bit | the lane is the scalar formula; every branch it skips is flagged | `tests/batch.rs` (random and adversarial input, every rule set, footprints that trigger each clamp, both tiers of the filtered lanes) |
//! | [`deferred_filter`] with `exponent = 1` (every preset but Unreal and Babylon.js) | bit for bit | the lane is the scalar steps with the domain and norm as constants (one loop per pair) and the branches as selects; the eigenvalue norm off its fast path is flagged | `tests/batch.rs` (every preset, every domain and norm, adversarial input) |
//! | [`deferred_filter`] with another exponent | relative `(2 d + 1) eps` in the perceptual domain (`d + 1` in the others), `d` the power's error in ulps: the lane power's (in `f32` computed in `f32`, `(5 + 3 abs(e)) u`, `u = 2^-24`, `e` the exponent, whatever the norm; in `f64` `1.6e-14 + 3 eps abs(y)`, `y = exponent ln(norm)`) plus libm's `powf` (one ulp) | `norm^exponent` by `pow_lane` (`engine/lane_math`); the perceptual domain squares `p` | `tests/batch.rs`, the `pow_lane` unit test |
//! | [`d_rect`] in `f64`, Gauss-Legendre elements (both sides short), and in both precisions every element the lanes flag | bit for bit | the pairs of 2- to 10-point rules of the scalar case analysis in lanes (one loop per pair, the elements sorted by pair), every other case flagged | `tests/batch.rs` |
//! | [`d_rect`] in `f32`, Gauss-Legendre elements (both sides within `0.5` of their distance from the poles) | against the exact `D` of the same inputs: `78 u abs(D)` (`u = 2^-24`: `4.6e-6` relative) plus the inputs' rounding (`u_c`, `v_c` `4 u`, half extents `2 u`) times `D`'s sensitivity to them; the scalar `f32` path is within about `2 u` | `kernels/rect/lanes32.rs`: the rectangle and the tensor rules (2 to 10 points, two tiers more than the scalar `f32` path) in `f32` arithmetic, scaled by a power of two, one division per row pair (the scalar path: `f64`); node coordinates `26 u`, the rule's arithmetic `41 u`, forming `D` `10 u`, truncation `1.04 u`, derived in its module docs | `tests/batch_bounds.rs` (against `f64`, the input term by central differences; worst `0.12` of the bound), the unit tests of `lanes32` (the rules, their truncation, the scaling's range) |
//! | [`d_rect`], four-edge closed-form elements (a long side) | before the rounding to `F`, `8 eps_64 M + 4 eps_64 abs(D)`, `M` the edge terms' magnitudes scaled as `D` (`M / D` the form's cancellation); in `f32` then the same value or one ulp apart (measured: the same) | the scalar formula (`edges_by`) with the four angles by `atan2_upper_lane` (`engine/lane_math`) (`3 eps_64`) in place of libm's (`2 eps_64`); the products and sums round apart (`3 eps_64 M`), the area, division, `k`, `1 / h_z^4` (`4 eps_64 abs(D)`) | `tests/batch_bounds.rs` (realistic and adversarial input), the `atan2_upper_lane` unit test |
//! | [`beckmann_d`], [`beckmann_d_filtered`] in `f64` | relative `E + 2 eps`, plus `x eps` where the scalar path takes its far-tail branch (`x > -ln F::MIN_POSITIVE`); results below `F::MIN_POSITIVE` flushed to `0` (absolute error below `F::MIN_POSITIVE`) | the exponent `x` and factor `k = n / pi` are the scalar path's bit for bit; `exp(-x) k` is the polynomial exponential (relative `E = 2.5e-7` in `f32`, `1.5e-14` in `f64`) and one rounding, against libm's `exp` (one ulp) and the scalar product; the scalar far-tail branch rounds `x - ln k` (up to `x eps`) | `tests/batch.rs` |
//! | [`beckmann_d_filtered`] in `f32` | against the `f64` pipeline (`ClampRules::filter_gaussian` and `D` in `f64` on the same inputs) relative `E + (x (15.35 + 26 k) + 8.5 + 13 k) eps`, `k = 1 / (1 - abs(rho))` of the filtered matrix (`<= 7.5`), flushed as [`beckmann_d`]; the second lane's elements against the `f64` `D` of the scalar route's matrix `E + (16 x + 10) eps` | the first (narrow) lane builds the filtered matrix in `f32` arithmetic (`Narrow::entries`: its entries within `26 u sqrt(A'_ii A'_jj)` of the exact ones, `u = eps / 2`; not the scalar route's matrix bit for bit: one division and one square root fewer per element), which moves `x` by at most `2 x 26 u k` and `ln n` by `26 u k` (first order), then forms `x` and `n` in `f32` (`RoughnessMatrix::exponent_and_norm_narrow`, where `rho^2 <= 3/4`: `x` within `30.7 u`, `n` within `16 u`); the second lane and the scalar path use the scalar route's matrix, `x` and `n` in `f64`; the condition number of `exp(-x)` makes the relative errors grow with `x` | `tests/batch.rs` (each element within the scalar route's bound or the first lane's), `tests/batch_bounds.rs` (against `f64`), the unit tests of `Narrow::entries` and `exponent_and_norm_narrow` |
//! | [`ggx_d_filtered`] in `f32` | against the `f64` pipeline relative `((2 x / (1 + x)) (15.35 + 26 k) + 11 + 13 k) eps`, `k = 1 / (1 - abs(rho))` of the filtered matrix; the second lane's elements bit for bit with the scalar route | the first lane is [`beckmann_d_filtered`]'s narrow one (`Narrow::entries`, then `x` and `n` by `exponent_and_norm_narrow`: the same derivation), then `D = n / (pi (1 + x)^2)`: `x`'s relative error enters times `2 x / (1 + x)` (Beckmann's `exp(-x)`: times `x`), `n`'s once, and five roundings and `1 / pi` rounded `3 eps`; a result below `F::MIN_POSITIVE` flagged | `tests/batch_bounds.rs` (against `f64`, realistic footprints, smooth lobes: worst `0.18` of the bound), `tests/batch.rs` (every rule set, adversarial input: bit for bit or within the bound) |
//! | [`beckmann_lambda`] | absolute `L (1 + Lambda)`, `L = 2.1e-7` (`f32`), `1.9e-8` (`f64`), plus `(5 + 3 a^2) eps Lambda` | the `erfc` fit (Numerical Recipes `erfcc`) in place of libm's; `a = |w_z| / sqrt(q)` rounded twice in `F` (the scalar path forms it in `f64`), amplified by `2 a^2 + 3` | `tests/batch_bounds.rs` |
//! | [`beckmann_g2`] | relative `2 L + 3 eps` plus the `Lambda` terms over `1 + Lambda_i + Lambda_o` | `G2 = 1 / (1 + Lambda_i + Lambda_o)` | `tests/batch_bounds.rs` |
//! | [`ggx_sample_visible_normal`] | not bit for bit: the angle between the samples in the unit-roughness space within `B(E, S)` of `tests/batch_bounds.rs` (`~ (9 kappa + 1) E + (d_c + d_wi + E) / abs(n)`, `kappa` the warp's condition number, `d_c` growing as `1 / sin theta` of the cap point) | the scalar sampler's steps and shared cores; `(cos, sin)` of the azimuth by `sincos_2pi` (`engine/lane_math`) (absolute `2 eps_32` computed in `f32`, `2e-15` in `f64`) in place of libm's of the rounded `phi`, the cap height not fused | `tests/batch_bounds.rs` (against `f64`), the `sincos_2pi` unit test |
//! | [`ggx_normal_pdf`], [`ggx_visible_normal_pdf`], [`ggx_reflection_pdf_from_normal`] (every roughness form) | bit for bit | the scalar pdf's core (`sampling`'s `normal_pdf_core`, `visible_normal_pdf_core`, `reflection_pdf_core`) on GGX's bit-for-bit `D` and `Lambda` lanes, its checks as selects; a view to rescale or a grazing `Lambda` flagged | `tests/batch.rs` (adversarial input, every form, the clamped matrix); against `f64`: `tests/batch_bounds.rs` |
//! | [`beckmann_visible_normal_pdf`], [`beckmann_reflection_pdf_from_normal`] | relative `E + L + 10 eps + (5 + 3 a^2) eps Lambda / (1 + Lambda)` to first order (plus `x eps` where the scalar `D` takes its far-tail branch); where the lane `D` flushes below `F::MIN_POSITIVE`, absolute `F::MIN_POSITIVE` times the factor `wo.m / (wo_z (1 + Lambda))` (visible) or `1 / (4 o_z (1 + Lambda))` (reflection); `0` exactly where the scalar pdf is `0` | the same core on Beckmann's `D` lane (`E + 2 eps`) and `Lambda` lane (absolute `L (1 + Lambda) + (5 + 3 a^2) eps Lambda` over `1 + Lambda`), the sum and three operations rounding in each path | `tests/batch_bounds.rs` (against `f64`: `(15 + 4 x) eps + L + (13 + 7 a^2) eps Lambda / (1 + Lambda) + 3 eps sum|wo_k m_k| / wo.m` in `f32`, derived there), `tests/batch.rs` (the zeros, adversarial input) |
//! | [`beckmann_normal_pdf`] | relative `E + 4 eps` (plus `x eps` in the scalar far tail); flushed below `F::MIN_POSITIVE` as [`beckmann_d`] (absolute `F::MIN_POSITIVE m_z`) | `D(m) m_z` on the `D` lane, the product rounding in each path | `tests/batch_bounds.rs` (against `f64`: `(12 + 4 x) eps`), `tests/batch.rs` (the zeros) |
//! | [`beckmann_sample_visible_normal`] | not bit for bit: each slope the exact quantile of a `u'` within `(8.5 eps_64 + d(x) + d(hi)) u` of `u`, `d(x) = 1.5e-14 + (x^2 / 2 + 66) eps_64` (the scalar path: `8 eps_64` plus libm's `(x^2 / 2 + 4) eps_64`, or a bracket of width `1e-13 (1 + abs(x))`) | the scalar sampler's view, rotation and warp; each quantile from Jakob's fitted guess by a fixed number of Halley steps on `erfc` by Cephes' rationals (`kernels/sample/quantile.rs`) in place of the scalar safeguarded Newton solve on libm's `erfc`, the residual tested against the scalar solve's goal and every miss flagged (in the far tails of `u`) | `tests/batch_bounds.rs` (against the `f64` sampler's visible-slope CDF, the view's and the rounding's share derived there), the unit tests of `quantile` |
//! | [`ggx_sample_normal`], [`beckmann_sample_normal`] (`D(m) m_z`) | not bit for bit: the pulled-back angle within `(S + 3) E + 9 kappa E + E` (GGX) and `dr / (1 + r^2) + (S + 1) E r / sqrt(1 + r^2) + 9 kappa E + E` (Beckmann, `r^2 = -ln(1 - u1)`, `dr` the error of `r` from the logarithm's, `tests/batch_bounds.rs`) against `f64`, as the scalar sampler | the scalar sampler's steps and shared cores (`ggx_standard_normal`, `beckmann_standard_normal`, `Warp::unstretch_raw`); the azimuth by `sincos_2pi` and `ln(1 - u1)` by `ln_lane` (`engine/lane_math`) (relative `3 eps_32` computed in `f32`, `4 eps_64` in `f64`) in place of libm's | `tests/batch_bounds.rs`, the `ln_lane` unit test |
//! | [`gaussian_filtered_ggx_d`] (one lobe) | bit for bit | the scalar `D`'s steps with the rule choice of `J` shared (`gaussian_ggx_quad::rule`): the far-tail series and Gauss-Laguerre in the first lane, the trapezoid rule's first chunks in the second (its truncation test as a select, `e^(-k0 H)` by the polynomial that fills the scalar path's table; in two stages, the elements not stopped after the first chunks gathered for the last), a longer trapezoid rule flagged | `tests/batch.rs` (kernels from `0` to `10` lobe variances, rank one, rotated, NaN, infinite; every form; both lanes, both stages and the driver's sorted blocks; a mutation of the second stage caught), the trapezoid lane's unit tests in `gaussian_ggx_quad.rs` |
//! | [`ggx_d_filtered_projected`] (a footprint per element through the clamp rules) | bit for bit | the rules' lane (`ClampRules::filter_projected_entries_lane`: the kernel of the Gaussian lanes, decided exactly) and the projected filter's kernel part as [`ggx_d_projected`]; what leaves the rules' fast paths or the eigenvalue clamp's common case, and an active determinant clamp, flagged | `tests/batch.rs` (every rule set, footprints that trigger each clamp, adversarial input, the driver's states) |
//! | [`ggx_d_filtered_exact`] (a footprint per element through the clamp rules) | bit for bit | the rules' kernel as for [`ggx_d_filtered_projected`], the lobe built in the lane by [`GaussianFilteredGgx::new`](super::GaussianFilteredGgx::new)'s steps (its cases as selects), then the lanes of [`gaussian_filtered_ggx_d`]; a kernel the lobe's sanitiser would change flagged | `tests/batch.rs` (every rule set, adversarial input, rank-one footprints, the driver's states; mutations of both lanes caught) |
//! | [`ggx_d_filtered_proxy`] (a footprint per element through the clamp rules) | not bit for bit: each axis's effective roughness `alpha'` within `10 u` (`u = 2^-53`) of the exact value, so in `f32` the correctly rounded value or a neighbour and `D` the scalar `D` of that roughness bit for bit; in `f64` within `143 u` of the scalar route | the rules' clamped rectangle as [`d_rect_filtered`] (bit for bit), `alpha' = s sqrt(t / atan2(H, s))` in `f64` with `atan2` by `atan2_upper_lane` (`engine/lane_math`) in place of libm's `hypot` and `atan`, then GGX's lane `D`; a direction to rescale, and in `f64` a half extent beyond `1e150`, flagged | `tests/batch.rs` (every rule set, adversarial footprints and half vectors: in `f32` each element the scalar `D` of one of the nine neighbouring roughness pairs; in `f64` worst `0.11` of the bound; perturbations of `alpha'` by `1e-12` (`f64`) and `2e-7` (`f32`) caught) |
//! | [`ggx_d_projected`] (a kernel per element) | bit for bit | the scalar projected filter split into its lobe part (once per batch) and kernel part (`filter::ProjectedBase`); a kernel off the sanitiser's fast path and an active determinant clamp flagged | `tests/batch.rs` (footprint kernels and raw adversarial entries, `alpha` to `2`, the clamped matrix) |
//!
//! The deferred presets in `f32` against the `f64` scalar path: the scalar `f32` path's
//! error, and for a power the lane power's in place of libm's, derived step by step in
//! `tests/batch_bounds.rs` (at most `11 eps` for the presets without a power, `15 eps` for
//! Unreal's and Babylon.js's `^0.333`; `alpha <= 0.9` for the projected domain, whose
//! `alpha^2 / (1 - alpha^2)` amplifies by `1 / (1 - alpha^2)`).
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
//! Speed per core, scalar loop against batch, every kernel: `docs/batch_measurements.md`
//! (`benches/batch.rs`, groups `batch_<kernel>/<precision>` with `scalar_loop` and `batch`).

/// Defines a public batch function over any roughness form `R` whose loops are compiled in
/// this crate, once per form, rather than in every crate that calls it: the generic function
/// only turns `r` into its [`Form`](super::ndf::roughness::sealed::Form) and calls a
/// non-generic function that matches on it, each arm the body with `r` bound to a reference
/// to that concrete form. The names `Roughness`, `Form` and `Sealed` resolve in the parent of
/// the module that expands it (`kernels`).
macro_rules! per_form {
    (
        $(#[$attr:meta])*
        pub fn $name:ident($r:ident: &R $(, $p:ident: $t:ty)* $(,)?) -> usize $body:block
    ) => {
        $(#[$attr])*
        #[inline]
        pub fn $name<R: super::Roughness>($r: &R $(, $p: $t)*) -> usize {
            #[allow(clippy::too_many_arguments)]
            fn each(form: &super::Form $(, $p: $t)*) -> usize {
                match form {
                    super::Form::Isotropic($r) => $body,
                    super::Form::AxisAligned($r) => $body,
                    super::Form::Matrix($r) => $body,
                }
            }
            each(&super::Sealed::form($r) $(, $p)*)
        }
    };
}

mod columns;
mod engine;
mod kernels;

pub use crate::error::UnknownSimdLevel;
pub use columns::{Covariances, Footprints, Vec3s};
pub use kernels::*;

#[cfg(feature = "rayon")]
use super::F;

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
/// `"avx2"`, `"sse2"` or `"sse2-lanes"` (x86-64; `"baseline"` elsewhere). With the `dispatch`
/// feature on x86-64, the one `FILTERED_NDF_SIMD` requests where it is available, else the
/// widest the CPU supports (detected once; [`simd_requested`] for the table of values);
/// without it, the one the crate was compiled for (`-C target-cpu`). `"sse2-lanes"` is the
/// baseline with every lane, also those that pay only with wider vectors (for tests). A lane
/// computes the same operations at any width; what the level changes is only whether the
/// deferred presets, [`ggx_d_projected`] and the `f64` Gaussian-filtered functions run their
/// lanes (AVX2, AVX-512, `sse2-lanes`) or their scalar path (`sse2`), see the module docs.
pub fn simd_level() -> &'static str {
    engine::level().name()
}

/// The names of the SIMD levels (the values `FILTERED_NDF_SIMD` takes), narrowest first:
/// `"baseline"` (off x86-64), `"sse2"`, `"sse2-lanes"`, `"avx2"`, `"avx512"`.
pub const SIMD_LEVELS: [&str; 5] = {
    let mut names = [""; 5];
    let mut i = 0;
    while i < names.len() {
        names[i] = engine::Level::ALL[i].name();
        i += 1;
    }
    names
};

/// Whether this process can run the batch kernels at the level named `level` (a value of
/// `FILTERED_NDF_SIMD`: `"sse2"`, `"sse2-lanes"`, `"avx2"`, `"avx512"` or `"baseline"`): with
/// `dispatch` on x86-64, `sse2` and `sse2-lanes` always, `avx2` and `avx512` where the CPU has
/// them (the detection [`simd_level`]'s choice uses); without it, only the level the crate
/// was compiled for; off x86-64, `baseline`. An error for a name that is no level.
pub fn simd_available(level: &str) -> Result<bool, UnknownSimdLevel> {
    engine::Level::from_name(level).map(engine::available)
}

/// The level the environment variable `FILTERED_NDF_SIMD` requests, checked: `Ok(None)` where
/// it is unset or empty (and without `std`, which has no environment), `Ok(Some(name))` for
/// a level's name, [`UnknownSimdLevel`] for anything else. At run time (with `dispatch` on
/// x86-64) the kernels use
///
/// | `FILTERED_NDF_SIMD` | the kernels run at |
/// |---|---|
/// | unset or empty | the widest level the CPU supports |
/// | `avx512`, `avx2` | that level where the CPU has it ([`simd_available`]), else the widest below it |
/// | `sse2`, `sse2-lanes` | that level |
/// | `baseline`, or a name that is no level | the widest level the CPU supports, as unset |
///
/// so [`simd_level`] differs from the request exactly where the request is not available or
/// not a level. Without `dispatch` the level is fixed when the crate is compiled and the
/// variable changes nothing (a request other than that level is not available).
pub fn simd_requested() -> Result<Option<&'static str>, UnknownSimdLevel> {
    engine::requested().map(|level| level.map(engine::Level::name))
}
