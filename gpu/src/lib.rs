//! Development tooling for the WGSL modules of `filtered-ndf` (the `shaders/` tree).
//!
//! - [`modules`]: the shader modules as the `filtered-ndf-wgsl` crate ships them (and as the
//!   files on disk, which `generate` writes its table from), their `#define_import_path`s and
//!   imports, and their composition with naga_oil (as Bevy composes its shaders).
//! - [`syntax`]: a lexical scan of WGSL (top-level items, qualified names, calls).
//! - [`concat`](mod@concat): the single concatenated WGSL file for those who paste.
//! - [`generate`]: the naga translations under `shaders/generated/` (GLSL 330, GLSL ES 310,
//!   HLSL SM 5.1, MSL) and the check that the checked-in copies are up to date.
//! - [`wgsl_crate`]: the `filtered-ndf-wgsl` crate's table of modules (`shaders/src/`).
//! - [`wgsl_rules`]: the WGSL constants of the exact Gaussian filter's accuracy settings, from
//!   the Rust rules.
//! - [`harness`]: a wgpu compute harness that evaluates a WGSL function over many cases in one
//!   dispatch, on the backend chosen by `FILTERED_NDF_GPU_BACKEND`.
//! - [`reference`](mod@reference): the crate's `f64` functions the shader functions are compared with.
//! - [`checks`]: the conformance checks (cases, WGSL call, reference, tolerance).
//! - [`coverage`]: which exported WGSL functions the checks call.
//! - [`oracle_backend`]: the reference oracle's `--backend gpu` (binary `oracle`).
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod checks;
pub mod concat;
pub mod coverage;
pub mod generate;
pub mod harness;
pub mod kernels;
pub mod modules;
pub mod oracle_backend;
pub mod reference;
pub mod syntax;
pub mod wgsl_crate;
pub mod wgsl_rules;
