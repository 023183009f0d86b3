//! Runtime dispatch to the widest vector instruction set of the CPU (feature `dispatch`).
//!
//! Without the feature every kernel is compiled once, for the target's baseline (SSE2 on
//! x86-64: 4 `f32` lanes). With it, [`dispatch`] runs the same plain-Rust loop compiled also for
//! x86-64-v3 (AVX2, 8 lanes) and x86-64-v4 (AVX-512, 16 lanes) and picks the widest the CPU
//! supports, through `pulp`'s safe target-feature contexts: the crate stays
//! `forbid(unsafe_code)`. `FILTERED_NDF_SIMD=sse2|avx2|avx512` caps the choice (read once; for
//! measurements); `sse2-lanes` runs every kernel's lanes on the baseline, also those that pay
//! only with wider vectors (for tests: every lane runs on any x86-64 CPU).

use super::lanes::Body;

#[cfg(not(all(feature = "dispatch", target_arch = "x86_64")))]
pub(crate) fn level_name() -> &'static str {
    if cfg!(target_feature = "avx512f") {
        "avx512"
    } else if cfg!(target_feature = "avx2") {
        "avx2"
    } else if cfg!(target_feature = "sse2") {
        "sse2"
    } else {
        "baseline"
    }
}

#[cfg(not(all(feature = "dispatch", target_arch = "x86_64")))]
#[inline(always)]
pub(crate) fn dispatch<B: Body>(l: B) {
    if WIDE_BUILD {
        l.go()
    } else if B::WIDE_ONLY {
        l.go_scalar()
    } else {
        l.go_narrow()
    }
}

/// Whether the crate is compiled for 256-bit vectors or wider (`-C target-cpu` with AVX2).
#[cfg(not(all(feature = "dispatch", target_arch = "x86_64")))]
const WIDE_BUILD: bool = cfg!(target_feature = "avx2");

#[cfg(all(feature = "dispatch", target_arch = "x86_64"))]
pub(crate) use wide::{dispatch, level_name};

#[cfg(all(feature = "dispatch", target_arch = "x86_64"))]
mod wide {
    use super::Body;
    use std::sync::OnceLock;

    /// A loop body as `pulp`'s unit of work.
    struct Go<B>(B);

    impl<B: Body> pulp::WithSimd for Go<B> {
        type Output = ();
        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, _: S) {
            self.0.go()
        }
    }

    /// The instruction set this process uses, with its token.
    #[derive(Clone, Copy)]
    enum Level {
        Base,
        /// The baseline with every kernel's lanes, also those that pay only with wider vectors
        /// (`FILTERED_NDF_SIMD=sse2-lanes`: for tests, so that every lane runs on any CPU).
        BaseLanes,
        V3(pulp::x86::V3),
        V4(pulp::x86::V4),
    }

    /// The CPU's widest instruction set, capped by `FILTERED_NDF_SIMD` (detected once).
    fn level() -> Level {
        static LEVEL: OnceLock<Level> = OnceLock::new();
        *LEVEL.get_or_init(|| {
            let cap = std::env::var("FILTERED_NDF_SIMD").unwrap_or_default();
            if cap == "sse2-lanes" {
                return Level::BaseLanes;
            }
            let (v3, v4) = match cap.as_str() {
                "sse2" => (false, false),
                "avx2" => (true, false),
                _ => (true, true),
            };
            if let Some(s) = pulp::x86::V4::try_new().filter(|_| v4) {
                Level::V4(s)
            } else if let Some(s) = pulp::x86::V3::try_new().filter(|_| v3) {
                Level::V3(s)
            } else {
                Level::Base
            }
        })
    }

    /// The instruction set [`dispatch`] uses: `"avx512"`, `"avx2"` or `"sse2"`.
    pub(crate) fn level_name() -> &'static str {
        match level() {
            Level::V4(_) => "avx512",
            Level::V3(_) => "avx2",
            Level::Base | Level::BaseLanes => "sse2",
        }
    }

    #[inline(always)]
    pub(crate) fn dispatch<B: Body>(l: B) {
        use pulp::Simd;
        match level() {
            Level::V4(s) => Simd::vectorize(s, Go(l)),
            Level::V3(s) => Simd::vectorize(s, Go(l)),
            Level::Base if B::WIDE_ONLY => l.go_scalar(),
            Level::Base => l.go_narrow(),
            Level::BaseLanes => l.go(),
        }
    }
}
