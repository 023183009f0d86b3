//! The passes over one block of the driver: the kernel's lane over every element (vectorised),
//! and the scalar path over the elements the lanes flagged.

use super::super::super::F;
use super::kernel::{Kernel, MAX_OUTPUTS, MID};

/// Elements per block: the vector pass and the fix-up scan of a block run while it is in L1.
pub(crate) const BLOCK: usize = 512;

/// The elements `start..end` of the columns.
#[derive(Clone, Copy)]
pub(crate) struct Block {
    pub(crate) start: usize,
    pub(crate) end: usize,
}

impl Block {
    /// The number of elements.
    #[inline(always)]
    pub(crate) fn len(self) -> usize {
        self.end - self.start
    }
}

/// The blocks of `size` elements that cover `0..n` (the last one shorter).
pub(crate) struct Blocks {
    start: usize,
    n: usize,
    size: usize,
}

impl Blocks {
    #[inline(always)]
    pub(crate) fn new(n: usize, size: usize) -> Self {
        Self { start: 0, n, size }
    }
}

impl Iterator for Blocks {
    type Item = Block;
    #[inline(always)]
    fn next(&mut self) -> Option<Block> {
        if self.start >= self.n {
            return None;
        }
        let block = Block {
            start: self.start,
            end: self.n.min(self.start + self.size),
        };
        self.start = block.end;
        Some(block)
    }
}

/// A block's results, written there by the lane and copied out after it (columns of
/// [`BLOCK`] elements; a [`Kernel::STAGED`] lane's first half too): stored through the output
/// slices, LLVM guarded the lane's loop with run-time alias checks against the inputs and
/// ran several kernels at half the vector width.
pub(crate) type BlockBuffer = [[F; BLOCK]; MAX_OUTPUTS];

/// Element `i` of every column.
#[inline(always)]
pub(crate) fn element<const I: usize>(cols: &[&[F]; I], i: usize) -> [F; I] {
    let mut x = [0.0 as F; I];
    for c in 0..I {
        x[c] = cols[c][i];
    }
    x
}

/// Writes element `i` of every column.
#[inline(always)]
pub(crate) fn set_element<const O: usize>(cols: &mut [&mut [F]; O], i: usize, v: [F; O]) {
    for c in 0..O {
        cols[c][i] = v[c];
    }
}

/// Whether every column holds at least `end` elements (always, for the driver's columns; the
/// test lets LLVM drop the bounds checks of the loops that follow it).
// Index loops on purpose: iterators are functions that LLVM may leave out of line.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
pub(crate) fn long_enough<const I: usize, const O: usize>(
    ins: &[&[F]; I],
    outs: &[&mut [F]; O],
    end: usize,
) -> bool {
    let mut ok = true;
    for c in 0..I {
        ok &= ins[c].len() >= end;
    }
    for c in 0..O {
        ok &= outs[c].len() >= end;
    }
    ok
}

/// [`Kernel::scalar`] over the block (with `only_flagged`, only where the first output is the
/// NaN mark of a flagged element).
#[inline(always)]
pub(crate) fn scalar_pass<K: Kernel<I, O>, const I: usize, const O: usize>(
    kernel: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    block: Block,
    only_flagged: bool,
) {
    if !long_enough(ins, outs, block.end) {
        return;
    }
    for i in block.start..block.end {
        if !only_flagged || outs[0][i].is_nan() {
            set_element(outs, i, kernel.scalar(element(ins, i)));
        }
    }
}

/// [`Kernel::lane`] (with `FULL` [`Kernel::lane_full`]) of one element, its first output
/// replaced by the NaN mark where it is flagged: `(outputs, flagged)`.
#[inline(always)]
pub(crate) fn marked_lane<K: Kernel<I, O>, const I: usize, const O: usize, const FULL: bool>(
    kernel: &K,
    x: [F; I],
) -> ([F; O], bool) {
    mark(if FULL {
        kernel.lane_full(x)
    } else {
        kernel.lane(x)
    })
}

/// A lane's `(outputs, slow)` with the first output replaced by the NaN mark where `slow`.
#[inline(always)]
pub(crate) fn mark<const O: usize>((mut v, slow): ([F; O], bool)) -> ([F; O], bool) {
    if slow {
        v[0] = F::NAN;
    }
    (v, slow)
}

/// [`Kernel::lane`] (with `FULL` [`Kernel::lane_full`]) over the block: writes the outputs, a
/// NaN in the first output of each flagged element, and returns how many were flagged.
#[inline(always)]
pub(crate) fn lane_pass<K: Kernel<I, O>, const I: usize, const O: usize, const FULL: bool>(
    kernel: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    block: Block,
    buffer: &mut BlockBuffer,
) -> usize {
    if !long_enough(ins, outs, block.end) {
        return 0;
    }
    let Block { start, end } = block;
    // A whole block as arrays of `BLOCK` elements: the loop then has no bounds checks to
    // prove. Indexed by `start..end` on the slices, it kept them (`long_enough`
    // notwithstanding), and the vectoriser then left a last vector's worth of every block to
    // a scalar epilogue.
    if block.len() == BLOCK {
        let mut xs: [&[F; BLOCK]; I] = [&[0.0; BLOCK]; I];
        for c in 0..I {
            if let Ok(x) = <&[F; BLOCK]>::try_from(&ins[c][start..end]) {
                xs[c] = x;
            }
        }
        // Never fails: every column holds `end` elements (`long_enough`), and the block is
        // whole.
        let ys = outs
            .each_mut()
            .map(|o| <&mut [F; BLOCK]>::try_from(&mut o[start..end]).expect("a whole block"));
        return if K::STAGED && !FULL {
            staged_lane_over_block(kernel, xs, ys, buffer)
        } else {
            lane_over_block::<K, I, O, FULL>(kernel, xs, ys, buffer)
        };
    }
    let mut flagged = 0usize;
    for i in start..end {
        let (v, slow) = marked_lane::<K, I, O, FULL>(kernel, element(ins, i));
        set_element(outs, i, v);
        flagged += usize::from(slow);
    }
    flagged
}

/// The loop of [`lane_pass`] over one whole block: the results to `buffer`, then copied out.
/// Returns how many elements were flagged.
#[inline(always)]
fn lane_over_block<K: Kernel<I, O>, const I: usize, const O: usize, const FULL: bool>(
    kernel: &K,
    xs: [&[F; BLOCK]; I],
    ys: [&mut [F; BLOCK]; O],
    buffer: &mut BlockBuffer,
) -> usize {
    const { assert!(O <= MAX_OUTPUTS, "a kernel's outputs fit the block buffer") };
    // A 32-bit count: a 64-bit one is the loop's widest type and held `f32` lanes to half
    // the vector width.
    let mut flagged = 0u32;
    for i in 0..BLOCK {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs[c][i];
        }
        let (v, slow) = marked_lane::<K, I, O, FULL>(kernel, x);
        for c in 0..O {
            buffer[c][i] = v[c];
        }
        flagged += u32::from(slow);
    }
    for c in 0..O {
        ys[c].copy_from_slice(&buffer[c]);
    }
    flagged as usize
}

/// A [`Kernel::STAGED`] lane over one whole block: the first half of every element into
/// `buffer`, then the second half, which writes its results over the first `O` columns of
/// `buffer` (element `i`'s after reading them), copied out after the loop. Returns how many
/// elements were flagged.
#[inline(always)]
fn staged_lane_over_block<K: Kernel<I, O>, const I: usize, const O: usize>(
    kernel: &K,
    xs: [&[F; BLOCK]; I],
    ys: [&mut [F; BLOCK]; O],
    buffer: &mut BlockBuffer,
) -> usize {
    const {
        assert!(
            O <= MID && MID <= MAX_OUTPUTS,
            "a staged lane fits the block buffer"
        )
    };
    let mut flagged = 0u32;
    for i in 0..BLOCK {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs[c][i];
        }
        let m = kernel.stage_one(x);
        for c in 0..MID {
            buffer[c][i] = m[c];
        }
    }
    for i in 0..BLOCK {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs[c][i];
        }
        let mut m = [0.0 as F; MID];
        for c in 0..MID {
            m[c] = buffer[c][i];
        }
        let (v, slow) = mark(kernel.stage_two(x, m));
        for c in 0..O {
            buffer[c][i] = v[c];
        }
        flagged += u32::from(slow);
    }
    for c in 0..O {
        ys[c].copy_from_slice(&buffer[c]);
    }
    flagged as usize
}
