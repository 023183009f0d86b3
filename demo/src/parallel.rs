//! Row-parallel loops on rayon's thread pool, with indicatif progress bars on stderr (hidden
//! when stderr is not a terminal).

use indicatif::{ParallelProgressIterator, ProgressBar, ProgressStyle};
use rayon::prelude::*;

/// Runs `row(y)` for `y in 0..height` in parallel and concatenates the rows in order (the
/// result does not depend on the scheduling), with a progress bar labelled `progress`.
pub fn rows<T: Send>(
    height: usize,
    progress: Option<&str>,
    row: impl Fn(usize) -> Vec<T> + Sync + Send,
) -> Vec<T> {
    let rows: Vec<Vec<T>> = match progress {
        Some(label) => (0..height)
            .into_par_iter()
            .progress_with(bar(label, height))
            .map(row)
            .collect(),
        None => (0..height).into_par_iter().map(row).collect(),
    };
    rows.into_iter().flatten().collect()
}

/// A progress bar of `total` steps: `label [#####>....] 50% 3s`.
pub fn bar(label: &str, total: usize) -> ProgressBar {
    let style = ProgressStyle::with_template("{msg:28} [{bar:30}] {percent:>3}% {elapsed}")
        .expect("a valid template")
        .progress_chars("#>.");
    ProgressBar::new(total as u64)
        .with_style(style)
        .with_message(label.to_string())
}

/// Sizes rayon's global pool (once, before any parallel loop).
pub fn init_threads(threads: usize) {
    // A second call (or a pool already started) keeps the first size: nothing to do.
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build_global();
}
