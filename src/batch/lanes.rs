//! The chunk driver every batch kernel runs on: a [`Kernel`] gives the vector path of one
//! element (branch-free, so that the loop over elements vectorises) and the scalar path it
//! falls back to; [`run`] runs it over blocks of the columns, with the flagged elements (those
//! that left the lane's domain, see `lane_math`) recomputed by the scalar path, and for tiered
//! kernels a second lane over the elements the first leaves to it.

use super::super::filter::{STATE_F, TrapezoidState};
use super::F;

/// Elements per block: the vector pass and the fix-up scan of a block run while it is in L1.
pub(crate) const BLOCK: usize = 512;

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
    /// alone (measured: the box filter's lanes, with both branches of the clamps, and the
    /// `f64` filtered tiers, at or below the scalar loop's speed on SSE2).
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
    /// Gaussian filter's trapezoid rule): the driver then always starts from the first.
    const FULL_COVERS: bool = true;
    /// Whether [`Kernel::lane_full`] pays only with 256-bit vectors or wider: on the baseline
    /// the driver then leaves what [`Kernel::lane`] flags to [`Kernel::scalar`] (measured:
    /// the exact Gaussian filter's trapezoid lane, 0.96 and 0.88 times the scalar loop's
    /// speed on SSE2 in `f32` and `f64`).
    const FULL_WIDE_ONLY: bool = false;
    /// For a [`Kernel::TIERED`] kernel whose second lane does not cover the first
    /// (`!FULL_COVERS`): whether [`Kernel::lane`] leaves the element to
    /// [`Kernel::lane_full`], decided cheaply. Where the first lane flagged most of a block,
    /// the driver sorts the next blocks by it and runs each lane over its own elements only
    /// ([`Kernel::FULL_COVERS`]); a wrong answer costs speed only (the element is flagged by
    /// the lane it was sent to and ends on the scalar path).
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
    /// unfinished, gathered again, from the state it hands over. For a second lane whose
    /// work varies between elements (the exact Gaussian filter's trapezoid rule: 2 chunks of
    /// nodes for most elements, 3 for some); the straight-line lane would compute the
    /// longest for every element.
    const FULL_STAGED: bool = false;
    /// The first stage of a [`Kernel::FULL_STAGED`] second lane: `((outputs, slow), more,
    /// state)`, the outputs and flag of [`Kernel::lane_full`] where `more` is false.
    #[inline(always)]
    fn full_one(&self, x: [F; I]) -> (([F; O], bool), bool, TrapezoidState) {
        (self.lane_full(x), false, TrapezoidState::default())
    }
    /// The second stage of a [`Kernel::FULL_STAGED`] second lane, from the first's state (the
    /// contract of [`Kernel::lane_full`]).
    #[inline(always)]
    fn full_two(&self, x: [F; I], _state: TrapezoidState) -> ([F; O], bool) {
        self.lane_full(x)
    }
    /// Whether [`Kernel::lane`] is `stage_two(x, stage_one(x))` and the driver runs a whole
    /// block's first lane as two loops, [`Kernel::stage_one`] over the block into a [`Mid`]
    /// buffer, then [`Kernel::stage_two`]. For a lane whose dependency chain is long for its
    /// instruction count (a division and a square root in each half): the core's schedulers
    /// hold about one element group of such a lane, so its latency, not its arithmetic, set
    /// its speed; each loop of the split has half the chain. Measured (`f32`, AVX-512, the
    /// narrow filtered Beckmann lane, 6 rounds alternating): 4.68 to 4.83 against 6.12 to
    /// 6.21 us per 4096 elements.
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

/// Runs `k` over the elements of `ins` and writes its outputs to `outs`, for the common prefix
/// `n = min` of every slice length (returned). A flagged element is marked by a NaN in its
/// first output (no batch output is NaN otherwise) and recomputed by [`Kernel::scalar`] in a
/// scan of each block after its vector pass. Allocates nothing.
#[inline(always)]
pub(crate) fn run<K: Kernel<I, O>, const I: usize, const O: usize>(
    k: &K,
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
    super::simd::dispatch(Loop { k, ins, outs });
    n
}

/// The loop of [`run`] over equally long columns, as a value that the dispatcher compiles
/// for each instruction set.
pub(crate) struct Loop<'a, K, const I: usize, const O: usize> {
    k: &'a K,
    ins: [&'a [F]; I],
    outs: [&'a mut [F]; O],
}

/// A loop that [`super::simd::dispatch`] compiles for each instruction set (inlined into
/// its target-feature context).
pub(crate) trait Body {
    /// Whether [`Body::go`] pays only with 256-bit vectors or wider ([`Kernel::WIDE_ONLY`]).
    const WIDE_ONLY: bool;
    /// Runs the loop.
    fn go(self);
    /// Runs the loop on the baseline instruction set (SSE2): [`Body::go`] without what pays
    /// only with wider vectors ([`Kernel::FULL_WIDE_ONLY`]).
    #[inline(always)]
    fn go_narrow(self)
    where
        Self: Sized,
    {
        self.go()
    }
    /// Runs the loop by the scalar path alone.
    fn go_scalar(self);
}

impl<K: Kernel<I, O>, const I: usize, const O: usize> Body for Loop<'_, K, I, O> {
    const WIDE_ONLY: bool = K::WIDE_ONLY;

    #[inline(always)]
    fn go_scalar(self) {
        let Self { k, ins, mut outs } = self;
        let n = outs[0].len();
        scalar_pass(k, &ins, &mut outs, 0, n, false);
    }

    /// The blocks: the vector pass, then (for a [`Kernel::TIERED`] kernel) the second vector
    /// pass over the flagged elements gathered densely, then the scalar path for the elements
    /// still flagged. Where the first lane of a tiered kernel flags more than half of a block,
    /// the next [`SKIP`] blocks start from [`Kernel::lane_full`]; where what is left to the
    /// scalar path is more than half of a block (inputs outside a kernel's lane domain, e.g.
    /// filter kernels outside the eigenvalue clamp's common case), the next [`SKIP`] blocks run the scalar path
    /// alone, so that such input costs what a scalar loop costs, not every pass.
    ///
    /// The loops index the columns by plain loops (`get`, `set`), not by `array::map` or
    /// iterator adapters: those are ordinary functions, which LLVM stopped inlining into this
    /// large function once it held two lanes, and then nothing vectorised (65 ns per element
    /// instead of 3).
    #[inline(always)]
    fn go(self) {
        self.blocks(K::TIERED);
    }

    #[inline(always)]
    fn go_narrow(self) {
        self.blocks(K::TIERED && !K::FULL_WIDE_ONLY);
    }
}

impl<K: Kernel<I, O>, const I: usize, const O: usize> Loop<'_, K, I, O> {
    /// [`Body::go`], with the second vector pass where `tiered`.
    #[inline(always)]
    fn blocks(self, tiered: bool) {
        let Self { k, ins, mut outs } = self;
        let n = outs[0].len();
        let mut b = 0;
        let mut skip = 0usize;
        let mut full_only = 0usize;
        // A kernel whose second lane does not cover the first, after a block whose first lane
        // flagged most of it: each block sorted by `Kernel::second` (see `split_pass`).
        let mut split = false;
        let mut buf = Dense {
            xs: [[0.0; DENSE]; I],
            ys: [[0.0; DENSE]; O],
            at: [0; DENSE],
            marks: [false; BLOCK],
            staged: if K::FULL_STAGED {
                Some(Staged {
                    sf: [[0.0; DENSE]; STATE_F],
                    sf2: [[0.0; DENSE]; STATE_F],
                    xs2: [[0.0; DENSE]; I],
                    more: [false; DENSE],
                    at2: [0; DENSE],
                    ys2: [[0.0; DENSE]; O],
                })
            } else {
                None
            },
        };
        while b < n {
            let e = n.min(b + BLOCK);
            if skip > 0 {
                skip -= 1;
                scalar_pass(k, &ins, &mut outs, b, e, false);
                b = e;
                continue;
            }
            if !K::FULL_COVERS && tiered && split {
                let (flagged, seconds) = split_pass(k, &ins, &mut outs, b, e, &mut buf);
                split = 2 * seconds > e - b;
                if flagged > 0 {
                    scalar_pass(k, &ins, &mut outs, b, e, true);
                }
                if 2 * flagged > e - b {
                    skip = SKIP;
                }
                b = e;
                continue;
            }
            // `lane` (`first`), or where the last block flagged most of its elements and
            // `lane_full` covers `lane`'s domain, `lane_full` (also `lane` for a kernel of one
            // tier).
            let first = tiered && full_only == 0;
            full_only = full_only.saturating_sub(1);
            // A const parameter, not a closure: a closure is a function of its own, which the
            // dispatcher's target-feature context does not reach.
            let mut flagged = if first || !K::TIERED || !tiered {
                vector_pass::<K, I, O, false>(k, &ins, &mut outs, b, e)
            } else {
                vector_pass::<K, I, O, true>(k, &ins, &mut outs, b, e)
            };
            if first && flagged > 0 {
                if 2 * flagged > e - b {
                    if K::FULL_COVERS {
                        full_only = SKIP;
                    } else {
                        split = true;
                    }
                }
                flagged =
                    dense_pass::<K, I, O, true, false>(k, &ins, &mut outs, b, e, &mut buf, true);
            }
            if flagged > 0 {
                scalar_pass(k, &ins, &mut outs, b, e, true);
            }
            if 2 * flagged > e - b {
                skip = SKIP;
            }
            b = e;
        }
    }
}

/// Element `i` of every column.
#[inline(always)]
fn get<const I: usize>(cols: &[&[F]; I], i: usize) -> [F; I] {
    let mut x = [0.0 as F; I];
    for c in 0..I {
        x[c] = cols[c][i];
    }
    x
}

/// Writes element `i` of every column.
#[inline(always)]
fn set<const O: usize>(cols: &mut [&mut [F]; O], i: usize, v: [F; O]) {
    for c in 0..O {
        cols[c][i] = v[c];
    }
}

/// Whether every column holds at least `e` elements (always, for the driver's columns; the
/// test lets LLVM drop the bounds checks of the loops that follow it).
// Index loops on purpose: iterators are functions that LLVM may leave out of line (see `go`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn long_enough<const I: usize, const O: usize>(
    ins: &[&[F]; I],
    outs: &[&mut [F]; O],
    e: usize,
) -> bool {
    let mut ok = true;
    for c in 0..I {
        ok &= ins[c].len() >= e;
    }
    for c in 0..O {
        ok &= outs[c].len() >= e;
    }
    ok
}

/// [`Kernel::scalar`] over `b..e` (with `only_flagged`, only where the first output is the
/// NaN mark of a flagged element).
#[inline(always)]
fn scalar_pass<K: Kernel<I, O>, const I: usize, const O: usize>(
    k: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    b: usize,
    e: usize,
    only_flagged: bool,
) {
    if !long_enough(ins, outs, e) {
        return;
    }
    for i in b..e {
        if !only_flagged || outs[0][i].is_nan() {
            set(outs, i, k.scalar(get(ins, i)));
        }
    }
}

/// One vector pass of [`Kernel::lane`] (or with `FULL` [`Kernel::lane_full`]) over the
/// elements `b..e`: writes the outputs, a NaN in the first output of each flagged element,
/// and returns how many were flagged.
#[inline(always)]
fn vector_pass<K: Kernel<I, O>, const I: usize, const O: usize, const FULL: bool>(
    k: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    b: usize,
    e: usize,
) -> usize {
    if !long_enough(ins, outs, e) {
        return 0;
    }
    // A whole block as arrays of `BLOCK` elements: the loop then has no bounds checks to
    // prove. Indexed by `b..e` on the slices, it kept them (`long_enough` notwithstanding),
    // and the vectoriser then left a last vector's worth of every block (16 or 32 of 512
    // elements) to a scalar epilogue, measured at 45 % of the time of GGX's `Lambda`.
    if e - b == BLOCK {
        let mut xs: [&[F; BLOCK]; I] = [&[0.0; BLOCK]; I];
        for c in 0..I {
            if let Ok(x) = <&[F; BLOCK]>::try_from(&ins[c][b..e]) {
                xs[c] = x;
            }
        }
        // Never fails: every column holds `e` elements (`long_enough`), and `e - b = BLOCK`.
        let ys = outs
            .each_mut()
            .map(|o| <&mut [F; BLOCK]>::try_from(&mut o[b..e]).expect("a whole block"));
        return lane_loop::<K, I, O, FULL, BLOCK>(k, xs, ys);
    }
    let mut flagged = 0usize;
    for i in b..e {
        let x = get(ins, i);
        let (v, slow) = marked::<K, I, O, FULL>(k, x);
        set(outs, i, v);
        flagged += usize::from(slow);
    }
    flagged
}

/// [`Kernel::lane`] (or with `FULL` [`Kernel::lane_full`]) of one element, its first output
/// replaced by the NaN mark where it is flagged: `(outputs, flagged)`.
#[inline(always)]
fn marked<K: Kernel<I, O>, const I: usize, const O: usize, const FULL: bool>(
    k: &K,
    x: [F; I],
) -> ([F; O], bool) {
    mark(if FULL { k.lane_full(x) } else { k.lane(x) })
}

/// A lane's `(outputs, slow)` with the first output replaced by the NaN mark where `slow`.
#[inline(always)]
fn mark<const O: usize>((mut v, slow): ([F; O], bool)) -> ([F; O], bool) {
    if slow {
        v[0] = F::NAN;
    }
    (v, slow)
}

/// The loop of [`vector_pass`] over one whole block (columns of `L` elements).
#[inline(always)]
fn lane_loop<K: Kernel<I, O>, const I: usize, const O: usize, const FULL: bool, const L: usize>(
    k: &K,
    xs: [&[F; L]; I],
    ys: [&mut [F; L]; O],
) -> usize {
    // A 32-bit count: a 64-bit one is the loop's widest type and held `f32` lanes to half
    // the vector width (8 with AVX-512).
    let mut flagged = 0u32;
    if K::STAGED && !FULL {
        // The first half of every element, then the second (`Kernel::STAGED`). The buffer:
        // `MID L` floats (6 KiB in `f32`). The second loop writes its results over the first
        // `O` columns of the buffer (element `i`'s after reading them), copied out after the
        // loop: stored through the output slices, LLVM guarded the loop with run-time alias
        // checks against the inputs and ran it at half the vector width (`f32`: 4 lanes on
        // AVX2, 8 on AVX-512; filtered Beckmann 4.7 ns per element instead of 3.3 on AVX2).
        const { assert!(O <= MID, "a staged kernel's outputs fit its buffer") };
        let mut mid = [[0.0 as F; L]; MID];
        for i in 0..L {
            let mut x = [0.0 as F; I];
            for c in 0..I {
                x[c] = xs[c][i];
            }
            let m = k.stage_one(x);
            for c in 0..MID {
                mid[c][i] = m[c];
            }
        }
        for i in 0..L {
            let mut x = [0.0 as F; I];
            for c in 0..I {
                x[c] = xs[c][i];
            }
            let mut m = [0.0 as F; MID];
            for c in 0..MID {
                m[c] = mid[c][i];
            }
            let (v, slow) = mark(k.stage_two(x, m));
            for c in 0..O {
                mid[c][i] = v[c];
            }
            flagged += u32::from(slow);
        }
        for c in 0..O {
            ys[c].copy_from_slice(&mid[c]);
        }
        return flagged as usize;
    }
    // The results to a buffer of the block's own, copied out after the loop: stored through
    // the output slices, LLVM guarded the loop with run-time alias checks against the inputs
    // and ran several kernels at half the vector width (measured on AVX2, `f32`: GGX `D`
    // in the matrix form 1.32 -> 0.89 ns per element, the GGX normal pdf 2.08 -> 1.21, the
    // Beckmann normal pdf 5.26 -> 2.65). `O L` floats (at most 12 KiB, in `f64`).
    let mut res = [[0.0 as F; L]; O];
    for i in 0..L {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs[c][i];
        }
        let (v, slow) = marked::<K, I, O, FULL>(k, x);
        for c in 0..O {
            res[c][i] = v[c];
        }
        flagged += u32::from(slow);
    }
    for c in 0..O {
        ys[c].copy_from_slice(&res[c]);
    }
    flagged as usize
}

/// The stack buffers of [`dense_pass`], made once per call of the driver (zeroing them per
/// block cost a tenth of the dense pass).
struct Dense<const I: usize, const O: usize> {
    xs: [[F; DENSE]; I],
    ys: [[F; DENSE]; O],
    at: [usize; DENSE],
    /// [`split_pass`]'s sort of a block: `Kernel::second` per element.
    marks: [bool; BLOCK],
    /// The buffers of a [`Kernel::FULL_STAGED`] lane (`None` for the other kernels, which
    /// then neither fill nor zero them).
    staged: Option<Staged<I, O>>,
}

/// The buffers of [`staged_full`]: the first stage's states, by columns, the unfinished
/// elements' indices, inputs and states gathered, and their results (`(2 STATE_F + I + O)
/// DENSE` floats and `DENSE` indices and marks: 11 KiB in `f32`, 13 KiB in `f64`, for `D`'s
/// three inputs).
struct Staged<const I: usize, const O: usize> {
    sf: [[F; DENSE]; STATE_F],
    sf2: [[F; DENSE]; STATE_F],
    xs2: [[F; DENSE]; I],
    more: [bool; DENSE],
    at2: [usize; DENSE],
    ys2: [[F; DENSE]; O],
}

/// Elements per gather of [`dense_pass`] (its buffers live on the stack: `(I + O) DENSE`
/// floats).
const DENSE: usize = 128;

/// Marks per word of [`dense_pass`]'s scan.
const SCAN: usize = 32;

/// The most picked marks in a word that [`dense_pass`] visits by their bits (more: one step
/// per mark).
const SPARSE: u32 = 8;

/// The multiple of elements [`dense_pass`] runs its lane on (the widest vector, 16 `f32`).
const PAD: usize = 16;

/// [`Kernel::lane_full`] (`FULL`, else [`Kernel::lane`]) over the elements of `b..e` that
/// the first pass flagged (a NaN in the first output; with `MARKED` instead those whose
/// mark in `buf.marks` is `want`), gathered [`DENSE`] at a time into dense columns so that
/// the loop over them vectorises, the results scattered back. Returns how many the lane
/// flagged in turn (their first output NaN, for the scalar path).
// Index loops on purpose: iterators are functions that LLVM may leave out of line (see `go`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn dense_pass<
    K: Kernel<I, O>,
    const I: usize,
    const O: usize,
    const FULL: bool,
    const MARKED: bool,
>(
    k: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    b: usize,
    e: usize,
    buf: &mut Dense<I, O>,
    want: bool,
) -> usize {
    if !long_enough(ins, outs, e) || e - b > BLOCK {
        return 0;
    }
    let Dense {
        xs,
        ys,
        at,
        marks,
        staged,
    } = buf;
    let mut still = 0usize;
    let mut i = b;
    while i < e {
        let mut m = 0;
        // The indices first, then the columns of those. The NaN marks by words of `SCAN`:
        // their bits first (a vector compare), then one step per flagged element (one scan
        // step per element cost a third of filtered Beckmann's time once its lane ran 16
        // wide). The sorted blocks' marks (`MARKED`, about half picked) by the loop below: a
        // word scan of them changed LLVM's vector width for the exact Gaussian filter's
        // trapezoid lane (16 to 8) and cost its heavy kernel 60 %.
        while !MARKED && i + SCAN <= e && m + SCAN <= DENSE {
            let mut word = nan_word(outs[0], i);
            if word.count_ones() <= SPARSE {
                while word != 0 {
                    at[m] = i + word.trailing_zeros() as usize;
                    m += 1;
                    word &= word - 1;
                }
            } else {
                // Many flagged (an unpredictable loop count): one branch-free step per mark.
                for j in 0..SCAN {
                    at[m] = i + j;
                    m += ((word >> j) & 1) as usize;
                }
            }
            i += SCAN;
        }
        // Branch-free (every index is written at `m`, which advances past the picked
        // elements only: a branch on the mark mispredicted about as often as elements are
        // picked).
        while i < e && m < DENSE {
            at[m] = i;
            m += usize::from(picked::<MARKED>(marks, outs[0], b, i, want));
            i += 1;
        }
        for j in 0..m.min(DENSE) {
            for c in 0..I {
                xs[c][j] = ins[c][at[j]];
            }
        }
        // The lane runs over `m` rounded up to a multiple of `PAD` (the padding repeats the
        // last element, its results unused): the vectorised loop then has no remainder,
        // which LLVM runs as a scalar loop of the lane (slower than the scalar path).
        let padded = m.next_multiple_of(PAD).min(DENSE);
        for j in m..padded {
            for c in 0..I {
                xs[c][j] = xs[c][m - 1];
            }
        }
        if let (true, Some(st)) = (FULL, staged.as_mut()) {
            staged_full(k, xs, ys, m, padded, st);
        } else {
            for j in 0..padded {
                let mut x = [0.0 as F; I];
                for c in 0..I {
                    x[c] = xs[c][j];
                }
                let (v, _) = marked::<K, I, O, FULL>(k, x);
                for c in 0..O {
                    ys[c][j] = v[c];
                }
            }
        }
        for j in 0..m.min(DENSE) {
            let i = at[j];
            for c in 0..O {
                outs[c][i] = ys[c][j];
            }
            still += usize::from(ys[0][j].is_nan());
        }
    }
    still
}

/// A [`Kernel::FULL_STAGED`] second lane over the gathered columns `xs` (`m` elements,
/// `padded` with the padding): [`Kernel::full_one`] over all, its states to `st`; then the
/// unfinished ones gathered (padded to a multiple of [`PAD`]) and [`Kernel::full_two`] over
/// them; every result to `ys` (the NaN mark where flagged).
// Index loops on purpose: iterators are functions that LLVM may leave out of line (see `go`).
// The rows read and written here as `#[inline(always)]` helper functions measured 32 -> 54 ns
// per element on the heavy exact Gaussian filter (the lane lost its vector width).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn staged_full<K: Kernel<I, O>, const I: usize, const O: usize>(
    k: &K,
    xs: &[[F; DENSE]; I],
    ys: &mut [[F; DENSE]; O],
    m: usize,
    padded: usize,
    st: &mut Staged<I, O>,
) {
    let Staged {
        sf,
        sf2,
        xs2,
        more,
        at2,
        ys2,
    } = st;
    for j in 0..padded.min(DENSE) {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs[c][j];
        }
        let (r, mo, st) = k.full_one(x);
        let (v, _) = mark(r);
        for c in 0..O {
            ys[c][j] = v[c];
        }
        for c in 0..STATE_F {
            sf[c][j] = st.f[c];
        }
        more[j] = mo;
    }
    // Branch-free compaction (as `dense_pass`'s gather).
    let mut n = 0;
    for j in 0..m.min(DENSE) {
        at2[n] = j;
        n += usize::from(more[j]);
    }
    if n == 0 {
        return;
    }
    let padded2 = n.next_multiple_of(PAD).min(DENSE);
    for t in n..padded2 {
        at2[t] = at2[n - 1];
    }
    // The unfinished elements' inputs and states gathered first, then the lane over dense
    // columns: gathering in the lane's loop (64-bit indices) held it to 8 `f32` lanes on
    // AVX-512.
    for t in 0..padded2 {
        // Masked to the buffer's size (`DENSE` is a power of two): no bounds checks.
        let j = at2[t] & (DENSE - 1);
        for c in 0..I {
            xs2[c][t] = xs[c][j];
        }
        for c in 0..STATE_F {
            sf2[c][t] = sf[c][j];
        }
    }
    for t in 0..padded2 {
        let mut x = [0.0 as F; I];
        for c in 0..I {
            x[c] = xs2[c][t];
        }
        let mut st = TrapezoidState::default();
        for c in 0..STATE_F {
            st.f[c] = sf2[c][t];
        }
        let (v, _) = mark(k.full_two(x, st));
        for c in 0..O {
            ys2[c][t] = v[c];
        }
    }
    for t in 0..n {
        let j = at2[t] & (DENSE - 1);
        for c in 0..O {
            ys[c][j] = ys2[c][t];
        }
    }
}

/// Whether [`dense_pass`] picks element `i`: with `MARKED` its mark in `marks` (from `b`) is
/// `want`, else its first output is the NaN mark of a flagged element. (A function, not a
/// closure in `dense_pass`: see [`Body::go`].)
#[inline(always)]
fn picked<const MARKED: bool>(
    marks: &[bool; BLOCK],
    out0: &[F],
    b: usize,
    i: usize,
    want: bool,
) -> bool {
    if MARKED {
        marks[i - b] == want
    } else {
        out0[i].is_nan()
    }
}

/// The NaN marks of the elements `i..i + SCAN` as the bits of a word (from a
/// fixed-size array: one vector compare, no bounds checks).
// Index loop on purpose: iterators are functions that LLVM may leave out of line (see `go`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn nan_word(out0: &[F], i: usize) -> u32 {
    let mut word = 0u32;
    if let Some(Ok(w)) = out0.get(i..i + SCAN).map(<&[F; SCAN]>::try_from) {
        for j in 0..SCAN {
            word |= u32::from(w[j].is_nan()) << j;
        }
    }
    word
}

/// A block sorted by [`Kernel::second`]: [`Kernel::lane`] over the elements it sends to the
/// first lane and [`Kernel::lane_full`] over the others, each gathered densely
/// ([`dense_pass`]), so that neither lane runs over the other's elements. Returns how many
/// the lanes flagged (a NaN in the first output) and how many were sent to the second lane.
// Index loops on purpose: iterators are functions that LLVM may leave out of line (see `go`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn split_pass<K: Kernel<I, O>, const I: usize, const O: usize>(
    k: &K,
    ins: &[&[F]; I],
    outs: &mut [&mut [F]; O],
    b: usize,
    e: usize,
    buf: &mut Dense<I, O>,
) -> (usize, usize) {
    if !long_enough(ins, outs, e) || e - b > BLOCK {
        return (0, 0);
    }
    let mut seconds = 0usize;
    for i in b..e {
        let s = k.second(get(ins, i));
        buf.marks[i - b] = s;
        seconds += usize::from(s);
    }
    let flagged = dense_pass::<K, I, O, false, true>(k, ins, outs, b, e, buf, false)
        + dense_pass::<K, I, O, true, true>(k, ins, outs, b, e, buf, true);
    (flagged, seconds)
}

/// Blocks run by the scalar path alone after a block whose vector pass flagged more than half
/// of its elements (then the vector pass probes again).
const SKIP: usize = 7;
