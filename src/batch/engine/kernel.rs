//! What a batch kernel gives the driver: the vector path of one element and the scalar path it
//! falls back to, with the optional second lane and staging the driver knows how to run.

use super::super::super::F;

/// A batch kernel of `I` input and `O` output columns: the vector path of one element and the
/// scalar path it falls back to. `lane` must be branch-free (selects, no calls) so that the
/// loop over elements vectorises; it returns its outputs and whether the element left the
/// vector path's domain, in which case the element is recomputed by `scalar` (the crate's
/// scalar function, the reference the lane is tested against).
pub(crate) trait Kernel<const I: usize, const O: usize> {
    /// The vector path of one element: `(outputs, slow)`.
    fn lane(&self, x: [F; I]) -> ([F; O], bool);
    /// The scalar path of one element.
    fn scalar(&self, x: [F; I]) -> [F; O];
    /// Whether the lane pays only with 256-bit vectors or wider (AVX2, AVX-512): on the
    /// baseline (SSE2: 4 `f32` and 2 `f64` lanes) the driver then runs [`Kernel::scalar`]
    /// alone (the kernels that set it measured at or below their scalar loop's speed there).
    const WIDE_ONLY: bool = false;
    /// Whether the kernel has a second vector path, [`Kernel::lane_full`], for the elements
    /// that [`Kernel::lane`] flags: `lane` is then a cheaper lane covering the common case
    /// only, and the driver gathers the elements it flags into a dense buffer, runs
    /// `lane_full` over them (vectorised too) and leaves only what `lane_full` flags to
    /// [`Kernel::scalar`].
    const TIERED: bool = false;
    /// Whether [`Kernel::lane_full`] covers what [`Kernel::lane`] covers too, so that the
    /// driver may start a block from it (where the first lane flagged most of the last
    /// block). `false` for a second lane that holds only what the first one flags (the exact
    /// Gaussian filter's trapezoid rule): the driver then sorts such blocks by
    /// [`Kernel::second`] instead.
    const FULL_COVERS: bool = true;
    /// Whether [`Kernel::lane_full`] pays only with 256-bit vectors or wider: on the baseline
    /// the driver then leaves what [`Kernel::lane`] flags to [`Kernel::scalar`].
    const FULL_WIDE_ONLY: bool = false;
    /// For a [`Kernel::TIERED`] kernel whose second lane does not cover the first
    /// (`!FULL_COVERS`): whether [`Kernel::lane`] leaves the element to
    /// [`Kernel::lane_full`], decided cheaply. Where the first lane flagged most of a block,
    /// the driver sorts the next blocks by it and runs each lane over its own elements only;
    /// a wrong answer costs speed only (the element is flagged by the lane it was sent to and
    /// ends on the scalar path).
    #[inline(always)]
    fn second(&self, _x: [F; I]) -> bool {
        false
    }
    /// The second vector path of a [`Kernel::TIERED`] kernel (same contract as
    /// [`Kernel::lane`]: where it does not flag, the value the kernel documents).
    #[inline(always)]
    fn lane_full(&self, x: [F; I]) -> ([F; O], bool) {
        self.lane(x)
    }
    /// Whether [`Kernel::lane_full`] runs in two stages over the gathered elements:
    /// [`Kernel::full_one`] over all of them, then [`Kernel::full_two`] over those it leaves
    /// unfinished, gathered again, from the [`Carry`] it hands over. For a second lane whose
    /// work varies between elements (the exact Gaussian filter's trapezoid rule: 2 chunks of
    /// nodes for most elements, 3 for some): the straight-line lane would compute the
    /// longest for every element.
    const FULL_STAGED: bool = false;
    /// The first stage of a [`Kernel::FULL_STAGED`] second lane: `((outputs, slow), more,
    /// carry)`, the outputs and flag of [`Kernel::lane_full`] where `more` is false.
    #[inline(always)]
    fn full_one(&self, x: [F; I]) -> (([F; O], bool), bool, Carry) {
        (self.lane_full(x), false, [0.0; CARRY])
    }
    /// The second stage of a [`Kernel::FULL_STAGED`] second lane, from the first's carry (the
    /// contract of [`Kernel::lane_full`]).
    #[inline(always)]
    fn full_two(&self, x: [F; I], _carry: Carry) -> ([F; O], bool) {
        self.lane_full(x)
    }
    /// Whether [`Kernel::lane`] is `stage_two(x, stage_one(x))` and the driver runs a whole
    /// block's first lane as two loops, [`Kernel::stage_one`] over the block into a [`Mid`]
    /// buffer, then [`Kernel::stage_two`]. For a lane whose dependency chain is long for its
    /// instruction count (a division and a square root in each half): the core's schedulers
    /// hold about one element group of such a lane, so its latency, not its arithmetic, sets
    /// its speed; each loop of the split has half the chain.
    const STAGED: bool = false;
    /// The first half of a [`Kernel::STAGED`] lane: the values it hands to the second.
    #[inline(always)]
    fn stage_one(&self, _x: [F; I]) -> Mid {
        [0.0; MID]
    }
    /// The second half of a [`Kernel::STAGED`] lane (the contract of [`Kernel::lane`]).
    #[inline(always)]
    fn stage_two(&self, x: [F; I], _mid: Mid) -> ([F; O], bool) {
        self.lane(x)
    }
}

/// Values per element that a [`Kernel::STAGED`] lane hands from its first loop to its second.
pub(crate) const MID: usize = 3;

/// What a [`Kernel::STAGED`] lane hands from [`Kernel::stage_one`] to [`Kernel::stage_two`].
pub(crate) type Mid = [F; MID];

/// Values per element that a [`Kernel::FULL_STAGED`] second lane hands from its first stage to
/// its second: one 256-bit vector's worth (8 `f32`, 4 `f64`).
pub(crate) const CARRY: usize = 32 / core::mem::size_of::<F>();

/// What a [`Kernel::FULL_STAGED`] second lane hands from [`Kernel::full_one`] to
/// [`Kernel::full_two`].
pub(crate) type Carry = [F; CARRY];

/// The most outputs a kernel has: the driver's block buffer holds this many columns (the
/// samplers' three coordinates).
pub(crate) const MAX_OUTPUTS: usize = 3;
