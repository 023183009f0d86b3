//! The batch engine: the chunk driver that runs a kernel's lanes over slices, the dispatch to
//! the CPU's vector instruction set, and the lane math the kernels' lanes call. It knows
//! nothing of any kernel: the kernels (`super::kernels`) implement [`Kernel`] (or, for a
//! driver of their own, [`SimdLoop`]) and call [`run`] (or [`dispatch`]).
//!
//! # How the loops vectorise
//!
//! [`run`] cuts the columns into blocks of 512 elements; per block it runs a loop over the
//! kernel's branch-free *lane* ([`Kernel::lane`]), which LLVM vectorises (4 `f32` lanes with
//! the x86-64 baseline SSE2, 8 / 16 with AVX2 / AVX-512), then, only where some element was
//! flagged, a scan that evaluates the flagged elements by the kernel's scalar path
//! ([`Kernel::scalar`]). A kernel may have a second lane ([`Kernel::TIERED`]): the elements
//! the first flags are gathered into a dense buffer (their indices from the flags' bits, a
//! word at a time) and the second lane runs over them, still vectorised; only what that
//! flags goes to the scalar path. A lane whose dependency chain is long for its instruction
//! count can run as two loops over a block ([`Kernel::STAGED`]), and a second lane whose work
//! varies between elements in two stages ([`Kernel::FULL_STAGED`]). The flags cost nothing
//! where nothing is flagged; where most of a block leaves a lane's domain, the next blocks
//! skip that lane (`driver.rs`), so that such input costs what the path it ends on costs.
//!
//! # Memory
//!
//! Nothing allocates. The driver's buffers live on the stack of the loop compiled for the
//! instruction set in use, made once per call ([`run`]: at most 48 KiB); [`run`] is not
//! inlined into the batch functions, so that an unoptimised build, which keeps the buffers
//! of every inlined copy in the caller's frame, still needs a few hundred KiB of stack at
//! most (the test `tests/batch_stack.rs` runs every batch function on a 2 MiB thread).

mod block;
mod dispatch;
mod driver;
mod gather;
mod kernel;
pub(crate) mod lane_math;

pub(crate) use dispatch::{Level, SimdLoop, available, dispatch, level, requested};
pub(crate) use driver::run;
pub(crate) use kernel::{CARRY, Carry, Kernel, Mid};
