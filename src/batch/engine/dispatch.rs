//! The instruction set the batch kernels run at, and the dispatch of a loop to it.
//!
//! Without the `dispatch` feature (or off x86-64) every loop is compiled once, for the target
//! the crate is compiled for (x86-64's baseline is SSE2: 4 `f32` lanes). With it, [`dispatch`]
//! runs the same plain-Rust loop compiled also for x86-64-v3 (AVX2, 8 lanes) and x86-64-v4
//! (AVX-512, 16 lanes), inlined into `pulp`'s safe target-feature contexts (the crate stays
//! `forbid(unsafe_code)`), and picks the widest the CPU supports, or the level that
//! `FILTERED_NDF_SIMD` requests (read once per process):
//!
//! | `FILTERED_NDF_SIMD` | the kernels run |
//! |---|---|
//! | unset or empty | at the widest level available |
//! | `avx512`, `avx2`, `sse2` | at that level where it is available, else at the widest available (`simd_available` says which) |
//! | `sse2-lanes` | on SSE2 with every lane, also those that pay only with wider vectors (for tests: every lane runs on any x86-64 CPU) |
//! | `baseline` | off x86-64: the target's own build (the only level there) |
//! | anything else | at the widest level available, as unset; `simd_requested` returns the error |
//!
//! A level is *available* where this build can run it on this CPU: with `dispatch` on x86-64
//! `sse2` and `sse2-lanes` always, `avx2` and `avx512` where the CPU has them (`pulp`'s
//! run-time detection); without `dispatch` only the level the crate was compiled for.

use crate::error::UnknownSimdLevel;

/// A loop that [`dispatch`] compiles for each instruction set: the methods are inlined into
/// the target-feature context of each.
pub(crate) trait SimdLoop {
    /// Whether [`SimdLoop::run_lanes`] pays only with 256-bit vectors or wider: on the SSE2
    /// baseline the dispatcher then runs [`SimdLoop::run_scalar`].
    const WIDE_ONLY: bool;
    /// Runs the loop with every vector path.
    fn run_lanes(self);
    /// Runs the loop on the baseline instruction set: [`SimdLoop::run_lanes`] without what
    /// pays only with wider vectors.
    #[inline(always)]
    fn run_lanes_baseline(self)
    where
        Self: Sized,
    {
        self.run_lanes()
    }
    /// Runs the loop by the scalar path alone.
    fn run_scalar(self);
}

/// An instruction-set level of the batch kernels (the values of `FILTERED_NDF_SIMD`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Level {
    /// Off x86-64: the target's own build.
    Baseline,
    /// x86-64's baseline, SSE2: the lanes that pay at 128 bits, the scalar path for the others.
    Sse2,
    /// SSE2 with every lane (for tests).
    Sse2Lanes,
    /// x86-64-v3: AVX2 and FMA.
    Avx2,
    /// x86-64-v4: AVX-512.
    Avx512,
}

impl Level {
    /// Every level, narrowest first.
    pub(crate) const ALL: [Level; 5] = [
        Level::Baseline,
        Level::Sse2,
        Level::Sse2Lanes,
        Level::Avx2,
        Level::Avx512,
    ];

    /// The level's name (its value of `FILTERED_NDF_SIMD`).
    pub(crate) const fn name(self) -> &'static str {
        match self {
            Level::Baseline => "baseline",
            Level::Sse2 => "sse2",
            Level::Sse2Lanes => "sse2-lanes",
            Level::Avx2 => "avx2",
            Level::Avx512 => "avx512",
        }
    }

    /// The level named `name`, if any.
    pub(crate) fn from_name(name: &str) -> Result<Level, UnknownSimdLevel> {
        Level::ALL
            .into_iter()
            .find(|l| l.name() == name)
            .ok_or(UnknownSimdLevel)
    }
}

/// The level `FILTERED_NDF_SIMD` requests: `None` where it is unset or empty (or without `std`,
/// which has no environment), an error for a name that is no level.
pub(crate) fn requested() -> Result<Option<Level>, UnknownSimdLevel> {
    #[cfg(feature = "std")]
    {
        match std::env::var("FILTERED_NDF_SIMD") {
            Ok(name) if !name.is_empty() => Level::from_name(&name).map(Some),
            // Unset, or not Unicode (no level's name either).
            Ok(_) | Err(std::env::VarError::NotPresent) => Ok(None),
            Err(std::env::VarError::NotUnicode(_)) => Err(UnknownSimdLevel),
        }
    }
    #[cfg(not(feature = "std"))]
    {
        Ok(None)
    }
}

#[cfg(not(all(feature = "dispatch", target_arch = "x86_64")))]
pub(crate) use fixed::{available, dispatch, level};

#[cfg(all(feature = "dispatch", target_arch = "x86_64"))]
pub(crate) use runtime::{available, dispatch, level};

/// One build for one instruction set: the one the crate is compiled for.
#[cfg(not(all(feature = "dispatch", target_arch = "x86_64")))]
mod fixed {
    use super::{Level, SimdLoop};

    /// Whether the crate is compiled for 256-bit vectors or wider (`-C target-cpu` with AVX2).
    const WIDE_BUILD: bool = cfg!(target_feature = "avx2");

    /// The level the crate is compiled for.
    pub(crate) fn level() -> Level {
        if cfg!(target_feature = "avx512f") {
            Level::Avx512
        } else if WIDE_BUILD {
            Level::Avx2
        } else if cfg!(target_arch = "x86_64") {
            Level::Sse2
        } else {
            Level::Baseline
        }
    }

    /// Whether this build runs at `l`: only at the level it is compiled for.
    pub(crate) fn available(l: Level) -> bool {
        l == level()
    }

    /// Runs `work` as the build's level runs it.
    #[inline(always)]
    pub(crate) fn dispatch<L: SimdLoop>(work: L) {
        if WIDE_BUILD {
            work.run_lanes()
        } else if L::WIDE_ONLY {
            work.run_scalar()
        } else {
            work.run_lanes_baseline()
        }
    }
}

/// Run-time dispatch through `pulp` (x86-64 with the `dispatch` feature).
#[cfg(all(feature = "dispatch", target_arch = "x86_64"))]
mod runtime {
    use super::{Level, SimdLoop, requested};
    use std::sync::OnceLock;

    /// A loop as `pulp`'s unit of work.
    struct Vectorized<L>(L);

    impl<L: SimdLoop> pulp::WithSimd for Vectorized<L> {
        type Output = ();
        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, _: S) {
            self.0.run_lanes()
        }
    }

    /// The level chosen for this process, with its `pulp` token.
    #[derive(Clone, Copy)]
    enum Chosen {
        Sse2,
        Sse2Lanes,
        Avx2(pulp::x86::V3),
        Avx512(pulp::x86::V4),
    }

    /// The widest level the CPU supports at or below `cap` (`pulp`'s detection).
    fn widest_up_to(cap: Level) -> Chosen {
        let v4 = pulp::x86::V4::try_new().filter(|_| cap == Level::Avx512);
        let v3 = pulp::x86::V3::try_new().filter(|_| matches!(cap, Level::Avx2 | Level::Avx512));
        match (v4, v3) {
            (Some(s), _) => Chosen::Avx512(s),
            (None, Some(s)) => Chosen::Avx2(s),
            (None, None) => Chosen::Sse2,
        }
    }

    /// The level of this process: the requested one where available, else the widest
    /// available (module docs). Detected once.
    fn chosen() -> Chosen {
        static CHOSEN: OnceLock<Chosen> = OnceLock::new();
        *CHOSEN.get_or_init(|| match requested() {
            Ok(Some(Level::Sse2Lanes)) => Chosen::Sse2Lanes,
            Ok(Some(Level::Sse2)) => Chosen::Sse2,
            Ok(Some(Level::Avx2)) => widest_up_to(Level::Avx2),
            // Unset, `avx512`, `baseline` (no x86-64 level) and unknown names.
            _ => widest_up_to(Level::Avx512),
        })
    }

    /// The level this process runs the kernels at.
    pub(crate) fn level() -> Level {
        match chosen() {
            Chosen::Sse2 => Level::Sse2,
            Chosen::Sse2Lanes => Level::Sse2Lanes,
            Chosen::Avx2(_) => Level::Avx2,
            Chosen::Avx512(_) => Level::Avx512,
        }
    }

    /// Whether this process can run the kernels at `l` (`pulp`'s detection, as [`level`]).
    pub(crate) fn available(l: Level) -> bool {
        match l {
            Level::Baseline => false,
            Level::Sse2 | Level::Sse2Lanes => true,
            Level::Avx2 => pulp::x86::V3::try_new().is_some(),
            Level::Avx512 => pulp::x86::V4::try_new().is_some(),
        }
    }

    /// Runs `work` at the process's level: compiled for AVX-512 or AVX2 inside `pulp`'s
    /// target-feature context, or on the baseline. Each level's loop is a function of its
    /// own (the baseline's too): an unoptimised build, which does not reuse
    /// stack slots, then holds one level's buffers at a time.
    #[inline(always)]
    pub(crate) fn dispatch<L: SimdLoop>(work: L) {
        use pulp::Simd;
        match chosen() {
            Chosen::Avx512(s) => Simd::vectorize(s, Vectorized(work)),
            Chosen::Avx2(s) => Simd::vectorize(s, Vectorized(work)),
            Chosen::Sse2 => baseline(work),
            Chosen::Sse2Lanes => every_lane(work),
        }
    }

    /// `work` on the baseline with the lanes that pay there.
    #[inline]
    fn baseline<L: SimdLoop>(work: L) {
        if L::WIDE_ONLY {
            work.run_scalar()
        } else {
            work.run_lanes_baseline()
        }
    }

    /// `work` on the baseline with every lane.
    #[inline]
    fn every_lane<L: SimdLoop>(work: L) {
        work.run_lanes()
    }
}
