//! The chunk driver every [`Kernel`] runs on: [`run`] cuts the columns into blocks of
//! [`BLOCK`] elements and runs each block's passes (`block.rs`, `gather.rs`), choosing per
//! block from what the last block flagged.

use super::super::super::F;
use super::block::{BLOCK, Block, Blocks, lane_pass, scalar_pass};
use super::dispatch::{SimdLoop, dispatch};
use super::gather::{Scratch, second_lane_pass, sorted_pass};
use super::kernel::Kernel;

/// Blocks run by the scalar path alone after a block whose vector pass flagged more than half
/// of its elements (then the vector pass probes again).
const SCALAR_RUN: usize = 7;

/// Runs `kernel` over the elements of `ins` and writes its outputs to `outs`, for the common
/// prefix `n = min` of every slice length (returned). A flagged element is marked by a NaN in
/// its first output (no batch output is NaN otherwise) and recomputed by [`Kernel::scalar`]
/// after its block's vector passes. Allocates nothing; its buffers (at most 48 KiB, in
/// `f64` for nine input columns) live on the stack of the loop compiled for the instruction
/// set in use.
///
/// Not inlined into the callers: each batch function then holds one driver frame, whichever
/// roughness forms and instruction sets it is compiled for (an unoptimised build keeps every
/// inlined copy's buffers in the caller's frame).
#[inline]
pub(crate) fn run<K: Kernel<I, O>, const I: usize, const O: usize>(
    kernel: &K,
    ins: [&[F]; I],
    outs: [&mut [F]; O],
) -> usize {
    let n = ins
        .iter()
        .map(|s| s.len())
        .chain(outs.iter().map(|s| s.len()))
        .min()
        .unwrap_or(0);
    // Re-sliced to `n`: the loops below then need no bounds checks and vectorise.
    let ins = ins.map(|s| &s[..n]);
    let outs = outs.map(|s| &mut s[..n]);
    dispatch(KernelLoop { kernel, ins, outs });
    n
}

/// The loop of [`run`] over equally long columns, as a value that the dispatcher compiles for
/// each instruction set.
struct KernelLoop<'a, K, const I: usize, const O: usize> {
    kernel: &'a K,
    ins: [&'a [F]; I],
    outs: [&'a mut [F]; O],
}

impl<K: Kernel<I, O>, const I: usize, const O: usize> SimdLoop for KernelLoop<'_, K, I, O> {
    const WIDE_ONLY: bool = K::WIDE_ONLY;

    #[inline(always)]
    fn run_lanes(self) {
        self.run_blocks(K::TIERED);
    }

    #[inline(always)]
    fn run_lanes_baseline(self) {
        self.run_blocks(K::TIERED && !K::FULL_WIDE_ONLY);
    }

    #[inline(always)]
    fn run_scalar(self) {
        let Self {
            kernel,
            ins,
            mut outs,
        } = self;
        let n = outs[0].len();
        scalar_pass(kernel, &ins, &mut outs, Block { start: 0, end: n }, false);
    }
}

/// How the driver runs one block, chosen from what the blocks before it flagged.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Plan {
    /// The kernel's one lane (a kernel of one tier, or the second lane not run here).
    OneLane,
    /// [`Kernel::lane`], then [`Kernel::lane_full`] over what it flags, gathered.
    FirstThenSecond,
    /// [`Kernel::lane_full`] over the whole block (the first lane flagged most of the last
    /// block, and the second covers its domain: [`Kernel::FULL_COVERS`]).
    SecondOnly,
    /// The block sorted by [`Kernel::second`], each lane over its own elements (the first lane
    /// flagged most of the last block, and the second does not cover its domain).
    Sorted,
    /// The scalar path alone (the last vector pass left more than half of its block to it).
    Scalar,
}

/// The driver's memory of the blocks before: where most of a block leaves a lane's domain,
/// the next blocks skip that lane, so that such input costs what the path it ends on costs.
struct Adaptive {
    /// Whether the kernel's second lane runs here (a [`Kernel::TIERED`] kernel, and on the
    /// baseline only where the second lane pays there).
    tiered: bool,
    /// Blocks still to run by the scalar path alone.
    scalar_blocks: usize,
    /// Blocks still to start from the second lane.
    second_blocks: usize,
    /// Whether the next block is sorted by [`Kernel::second`].
    sorted: bool,
}

impl Adaptive {
    /// The plan of the next block.
    #[inline(always)]
    fn next<K: Kernel<I, O>, const I: usize, const O: usize>(&mut self) -> Plan {
        if self.scalar_blocks > 0 {
            self.scalar_blocks -= 1;
            return Plan::Scalar;
        }
        if !K::FULL_COVERS && self.tiered && self.sorted {
            return Plan::Sorted;
        }
        if !self.tiered {
            return Plan::OneLane;
        }
        if self.second_blocks > 0 {
            self.second_blocks -= 1;
            return Plan::SecondOnly;
        }
        Plan::FirstThenSecond
    }

    /// Records that the first lane flagged most of a block: the next blocks start from the
    /// second lane, or are sorted where it does not cover the first one's domain.
    #[inline(always)]
    fn first_lane_missed<K: Kernel<I, O>, const I: usize, const O: usize>(&mut self) {
        if K::FULL_COVERS {
            self.second_blocks = SCALAR_RUN;
        } else {
            self.sorted = true;
        }
    }

    /// Records how many of a block's `len` elements the lanes left to the scalar path.
    #[inline(always)]
    fn left_to_scalar(&mut self, flagged: usize, len: usize) {
        if 2 * flagged > len {
            self.scalar_blocks = SCALAR_RUN;
        }
    }
}

impl<K: Kernel<I, O>, const I: usize, const O: usize> KernelLoop<'_, K, I, O> {
    /// The blocks, each by its [`Plan`]: the vector pass, then (for a [`Kernel::TIERED`]
    /// kernel where `tiered`) the second vector pass over the flagged elements gathered
    /// densely, then the scalar path for the elements still flagged.
    ///
    /// The passes index the columns by plain loops, not by `array::map` or iterator adapters:
    /// those are ordinary functions, which LLVM may leave out of line once this function holds
    /// two lanes, and then nothing vectorises.
    #[inline(always)]
    fn run_blocks(self, tiered: bool) {
        let Self {
            kernel,
            ins,
            mut outs,
        } = self;
        let n = outs[0].len();
        let mut scratch = Scratch::<I, O>::new(K::FULL_STAGED);
        let mut adaptive = Adaptive {
            tiered,
            scalar_blocks: 0,
            second_blocks: 0,
            sorted: false,
        };
        for block in Blocks::new(n, BLOCK) {
            let len = block.len();
            // Each pass has one call site: an unoptimised build keeps the buffers and locals
            // of every inlined call in this frame.
            let plan = adaptive.next::<K, I, O>();
            let flagged = match plan {
                Plan::Scalar => len,
                Plan::Sorted => {
                    let (flagged, seconds) =
                        sorted_pass(kernel, &ins, &mut outs, block, &mut scratch);
                    adaptive.sorted = 2 * seconds > len;
                    flagged
                }
                // A const parameter, not a closure: a closure is a function of its own, which
                // the dispatcher's target-feature context does not reach.
                Plan::SecondOnly if K::FULL_COVERS => {
                    lane_pass::<K, I, O, true>(kernel, &ins, &mut outs, block, &mut scratch.block)
                }
                plan => {
                    let first = lane_pass::<K, I, O, false>(
                        kernel,
                        &ins,
                        &mut outs,
                        block,
                        &mut scratch.block,
                    );
                    if plan != Plan::FirstThenSecond || first == 0 {
                        first
                    } else {
                        if 2 * first > len {
                            adaptive.first_lane_missed::<K, I, O>();
                        }
                        second_lane_pass(kernel, &ins, &mut outs, block, &mut scratch)
                    }
                }
            };
            // The scalar path over the marked elements, or over every element where all are
            // (or the plan was the scalar path, which marks none).
            if flagged > 0 {
                scalar_pass(kernel, &ins, &mut outs, block, flagged < len);
            }
            if plan != Plan::Scalar {
                adaptive.left_to_scalar(flagged, len);
            }
        }
    }
}
