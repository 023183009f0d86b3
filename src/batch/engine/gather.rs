//! The passes of a [`Kernel::TIERED`] kernel's second lane: the elements a block's first lane
//! flagged, gathered into dense columns so that the loop over them vectorises, and the block
//! sorted by [`Kernel::second`] where most of it belongs to the second lane.

use super::super::super::F;
use super::block::{BLOCK, Block, BlockBuffer, element, long_enough, mark, marked_lane};
use super::kernel::{CARRY, Carry, Kernel, MAX_OUTPUTS};

/// Elements per gather (the gathered columns: `(I + O) GATHER` floats).
const GATHER: usize = 128;

/// Flags per word of [`flag_bits`].
const FLAG_WORD: usize = 32;

/// The most flags in a word that [`gather_indices`] visits by their bits (more: one
/// branch-free step per element of the word).
const SPARSE: u32 = 8;

/// The multiple of elements the gathered lanes run over (the widest vector, 16 `f32`): the
/// vectorised loop then has no remainder, which LLVM runs as a scalar loop of the lane
/// (slower than the scalar path).
const PAD: usize = 16;

/// The driver's buffers, made once per call (zeroed per block, they would cost the second
/// lane's pass a measurable share): a block's results ([`BlockBuffer`]), and for the second lane the
/// gathered columns. In all at most `(3 BLOCK + (I + 3) GATHER) size_of::<F>()` bytes and
/// `GATHER` indices and `BLOCK` marks, with the [`Staged`] buffers of a
/// [`Kernel::FULL_STAGED`] kernel: 48 KiB in `f64` for nine input columns.
pub(crate) struct Scratch<const I: usize, const O: usize> {
    pub(crate) block: BlockBuffer,
    gather: Gather<I, O>,
}

/// The buffers of [`second_lane_pass`].
struct Gather<const I: usize, const O: usize> {
    /// The gathered elements' inputs, by columns.
    xs: [[F; GATHER]; I],
    /// Their outputs.
    ys: [[F; GATHER]; O],
    /// Their indices in the columns.
    at: [usize; GATHER],
    /// [`sorted_pass`]'s sort of a block: [`Kernel::second`] per element.
    second: [bool; BLOCK],
    /// The buffers of a [`Kernel::FULL_STAGED`] lane (`None` for the other kernels, which
    /// then neither fill nor zero them).
    staged: Option<Staged<I, O>>,
}

/// The buffers of [`staged_second_lane`]: the first stage's carries, by columns, the
/// unfinished elements' indices, inputs and carries gathered, and their results.
struct Staged<const I: usize, const O: usize> {
    carry: [[F; GATHER]; CARRY],
    carry_gathered: [[F; GATHER]; CARRY],
    xs: [[F; GATHER]; I],
    more: [bool; GATHER],
    at: [usize; GATHER],
    ys: [[F; GATHER]; O],
}

impl<const I: usize, const O: usize> Scratch<I, O> {
    /// The buffers, with those of a staged second lane where `staged`.
    #[inline(always)]
    pub(crate) fn new(staged: bool) -> Self {
        Self {
            block: [[0.0; BLOCK]; MAX_OUTPUTS],
            gather: Gather {
                xs: [[0.0; GATHER]; I],
                ys: [[0.0; GATHER]; O],
                at: [0; GATHER],
                second: [false; BLOCK],
                staged: if staged {
                    Some(Staged {
                        carry: [[0.0; GATHER]; CARRY],
                        carry_gathered: [[0.0; GATHER]; CARRY],
                        xs: [[0.0; GATHER]; I],
                        more: [false; GATHER],
                        at: [0; GATHER],
                        ys: [[0.0; GATHER]; O],
                    })
                } else {
                    None
                },
            },
        }
    }
}

/// [`Kernel::lane_full`] over the elements of the block that its first lane flagged (a NaN in
/// the first output), gathered [`GATHER`] at a time into dense columns, the results scattered
/// back. Returns how many the second lane flagged in turn (their first output NaN, for the
/// scalar path).
#[inline(always)]
pub(crate) fn second_lane_pass<K: Kernel<I, O>, const I: usize, const O: usize>(
    kernel: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    block: Block,
    scratch: &mut Scratch<I, O>,
) -> usize {
    gathered_pass::<K, I, O, true, false>(kernel, ins, outs, block, &mut scratch.gather, true)
}

/// A block sorted by [`Kernel::second`]: [`Kernel::lane`] over the elements it sends to the
/// first lane and [`Kernel::lane_full`] over the others, each gathered densely, so that
/// neither lane runs over the other's elements. Returns how many the lanes flagged (a NaN in
/// the first output) and how many were sent to the second lane.
#[inline(always)]
pub(crate) fn sorted_pass<K: Kernel<I, O>, const I: usize, const O: usize>(
    kernel: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    block: Block,
    scratch: &mut Scratch<I, O>,
) -> (usize, usize) {
    let gather = &mut scratch.gather;
    if !long_enough(ins, outs, block.end) || block.len() > BLOCK {
        return (0, 0);
    }
    let mut seconds = 0usize;
    for i in block.start..block.end {
        let second = kernel.second(element(ins, i));
        gather.second[i - block.start] = second;
        seconds += usize::from(second);
    }
    let flagged = gathered_pass::<K, I, O, false, true>(kernel, ins, outs, block, gather, false)
        + gathered_pass::<K, I, O, true, true>(kernel, ins, outs, block, gather, true);
    (flagged, seconds)
}

/// [`Kernel::lane_full`] (`FULL`, else [`Kernel::lane`]) over the elements of the block that
/// the first pass flagged (a NaN in the first output; with `SORTED` instead those whose
/// `second` mark is `want`), gathered [`GATHER`] at a time into dense columns so that the loop
/// over them vectorises, the results scattered back. Returns how many the lane flagged in
/// turn (their first output NaN, for the scalar path).
// Index loops on purpose: iterators are functions that LLVM may leave out of line.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn gathered_pass<
    K: Kernel<I, O>,
    const I: usize,
    const O: usize,
    const FULL: bool,
    const SORTED: bool,
>(
    kernel: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    block: Block,
    gather: &mut Gather<I, O>,
    want: bool,
) -> usize {
    if !long_enough(ins, outs, block.end) || block.len() > BLOCK {
        return 0;
    }
    let mut still_flagged = 0usize;
    let mut next = block.start;
    while next < block.end {
        let count = gather_indices::<SORTED>(
            &mut gather.at,
            &gather.second,
            outs[0],
            block,
            &mut next,
            want,
        );
        for j in 0..count.min(GATHER) {
            for c in 0..I {
                gather.xs[c][j] = ins[c][gather.at[j]];
            }
        }
        // The lane runs over `count` rounded up to a multiple of `PAD` (the padding repeats
        // the last element, its results unused).
        let padded = count.next_multiple_of(PAD).min(GATHER);
        for j in count..padded {
            for c in 0..I {
                gather.xs[c][j] = gather.xs[c][count - 1];
            }
        }
        match (FULL, gather.staged.as_mut()) {
            (true, Some(staged)) => {
                staged_second_lane(kernel, &gather.xs, &mut gather.ys, count, padded, staged)
            }
            _ => {
                for j in 0..padded {
                    let mut x = [0.0 as F; I];
                    for c in 0..I {
                        x[c] = gather.xs[c][j];
                    }
                    let (v, _) = marked_lane::<K, I, O, FULL>(kernel, x);
                    for c in 0..O {
                        gather.ys[c][j] = v[c];
                    }
                }
            }
        }
        for j in 0..count.min(GATHER) {
            let i = gather.at[j];
            for c in 0..O {
                outs[c][i] = gather.ys[c][j];
            }
            still_flagged += usize::from(gather.ys[0][j].is_nan());
        }
    }
    still_flagged
}

/// The indices of the next picked elements from `*next` on, into `at` (at most [`GATHER`]):
/// where the first output is the NaN mark of a flagged element, or with `SORTED` where the
/// `second` mark (from the block's start) is `want`. Advances `*next` past the elements
/// looked at; returns how many were picked.
#[inline(always)]
fn gather_indices<const SORTED: bool>(
    at: &mut [usize; GATHER],
    second: &[bool; BLOCK],
    out0: &[F],
    block: Block,
    next: &mut usize,
    want: bool,
) -> usize {
    let mut count = 0;
    let mut i = *next;
    // The NaN marks by words of `FLAG_WORD`: their bits first (a vector compare), then one
    // step per flagged element (one scan step per element would cost more than a 16-wide
    // lane of filtered Beckmann). The sorted blocks' marks (about half
    // picked) by the loop below: a word scan of them changed LLVM's vector width for the
    // exact Gaussian filter's trapezoid lane.
    while !SORTED && i + FLAG_WORD <= block.end && count + FLAG_WORD <= GATHER {
        let mut word = flag_bits(out0, i);
        if word.count_ones() <= SPARSE {
            while word != 0 {
                at[count] = i + word.trailing_zeros() as usize;
                count += 1;
                word &= word - 1;
            }
        } else {
            // Many flagged (an unpredictable loop count): one branch-free step per element.
            for j in 0..FLAG_WORD {
                at[count] = i + j;
                count += ((word >> j) & 1) as usize;
            }
        }
        i += FLAG_WORD;
    }
    // Branch-free (every index is written at `count`, which advances past the picked
    // elements only: a branch on the mark mispredicted about as often as elements are
    // picked).
    while i < block.end && count < GATHER {
        at[count] = i;
        count += usize::from(is_picked::<SORTED>(second, out0, block.start, i, want));
        i += 1;
    }
    *next = i;
    count
}

/// Whether [`gather_indices`] picks element `i`: with `SORTED` its `second` mark (from
/// `start`) is `want`, else its first output is the NaN mark of a flagged element.
#[inline(always)]
fn is_picked<const SORTED: bool>(
    second: &[bool; BLOCK],
    out0: &[F],
    start: usize,
    i: usize,
    want: bool,
) -> bool {
    if SORTED {
        second[i - start] == want
    } else {
        out0[i].is_nan()
    }
}

/// A [`Kernel::FULL_STAGED`] second lane over the gathered columns `xs` (`count` elements,
/// `padded` with the padding): [`Kernel::full_one`] over all, its carries to `staged`; then
/// the unfinished ones gathered (padded to a multiple of [`PAD`]) and [`Kernel::full_two`]
/// over them; every result to `ys` (the NaN mark where flagged).
// Index loops on purpose: iterators are functions that LLVM may leave out of line. The rows
// read and written here as helper functions, even always inlined, held the exact Gaussian
// filter's trapezoid lane to a narrower vector width.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn staged_second_lane<K: Kernel<I, O>, const I: usize, const O: usize>(
    kernel: &K,
    xs: &[[F; GATHER]; I],
    ys: &mut [[F; GATHER]; O],
    count: usize,
    padded: usize,
    staged: &mut Staged<I, O>,
) {
    for j in 0..padded.min(GATHER) {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs[c][j];
        }
        let (result, more, carry) = kernel.full_one(x);
        let (v, _) = mark(result);
        for c in 0..O {
            ys[c][j] = v[c];
        }
        for c in 0..CARRY {
            staged.carry[c][j] = carry[c];
        }
        staged.more[j] = more;
    }
    // Branch-free compaction (as the gather's indices).
    let mut unfinished = 0;
    for j in 0..count.min(GATHER) {
        staged.at[unfinished] = j;
        unfinished += usize::from(staged.more[j]);
    }
    if unfinished == 0 {
        return;
    }
    let padded = unfinished.next_multiple_of(PAD).min(GATHER);
    for t in unfinished..padded {
        staged.at[t] = staged.at[unfinished - 1];
    }
    // The unfinished elements' inputs and carries gathered first, then the lane over dense
    // columns: gathering in the lane's loop (64-bit indices) held it to 8 `f32` lanes on
    // AVX-512.
    for t in 0..padded {
        // Masked to the buffer's size (`GATHER` is a power of two): no bounds checks.
        let j = staged.at[t] & (GATHER - 1);
        for c in 0..I {
            staged.xs[c][t] = xs[c][j];
        }
        for c in 0..CARRY {
            staged.carry_gathered[c][t] = staged.carry[c][j];
        }
    }
    for t in 0..padded {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = staged.xs[c][t];
        }
        let mut carry: Carry = [0.0; CARRY];
        for c in 0..CARRY {
            carry[c] = staged.carry_gathered[c][t];
        }
        let (v, _) = mark(kernel.full_two(x, carry));
        for c in 0..O {
            staged.ys[c][t] = v[c];
        }
    }
    for t in 0..unfinished {
        let j = staged.at[t] & (GATHER - 1);
        for c in 0..O {
            ys[c][j] = staged.ys[c][t];
        }
    }
}

/// The NaN marks of the elements `i..i + FLAG_WORD` as the bits of a word (from a fixed-size
/// array: one vector compare, no bounds checks).
// Index loop on purpose: iterators are functions that LLVM may leave out of line.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn flag_bits(out0: &[F], i: usize) -> u32 {
    let mut word = 0u32;
    if let Some(Ok(w)) = out0.get(i..i + FLAG_WORD).map(<&[F; FLAG_WORD]>::try_from) {
        for j in 0..FLAG_WORD {
            word |= u32::from(w[j].is_nan()) << j;
        }
    }
    word
}
