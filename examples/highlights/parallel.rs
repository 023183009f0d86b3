//! Row-parallel loops on `std::thread` and a progress bar on stderr.

use std::io::Write;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Runs `row(y)` for `y in 0..height` on `threads` threads (rows handed out dynamically) and
/// concatenates the rows in order. The result does not depend on the scheduling.
pub fn rows<T: Send>(
    height: usize,
    threads: usize,
    progress: Option<&str>,
    row: impl Fn(usize) -> Vec<T> + Sync,
) -> Vec<T> {
    let next = AtomicUsize::new(0);
    let bar = progress.map(|label| Progress::new(label, height));
    let out: Vec<Mutex<Vec<T>>> = (0..height).map(|_| Mutex::new(Vec::new())).collect();
    std::thread::scope(|s| {
        for _ in 0..threads.max(1) {
            s.spawn(|| {
                loop {
                    let y = next.fetch_add(1, Ordering::Relaxed);
                    if y >= height {
                        break;
                    }
                    *out[y].lock().unwrap() = row(y);
                    if let Some(b) = &bar {
                        b.tick();
                    }
                }
            });
        }
    });
    if let Some(b) = &bar {
        b.finish();
    }
    out.into_iter()
        .flat_map(|m| m.into_inner().unwrap())
        .collect()
}

/// A one-line progress bar: `label [#####.....] 50%`.
pub struct Progress {
    label: String,
    total: usize,
    done: AtomicUsize,
    shown: AtomicUsize,
}

impl Progress {
    pub fn new(label: &str, total: usize) -> Self {
        Self {
            label: label.to_string(),
            total: total.max(1),
            done: AtomicUsize::new(0),
            shown: AtomicUsize::new(usize::MAX),
        }
    }

    pub fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        let pct = done * 100 / self.total;
        if self.shown.swap(pct, Ordering::Relaxed) != pct {
            let filled = pct * 30 / 100;
            let mut err = std::io::stderr().lock();
            let _ = write!(
                err,
                "\r{:<28} [{}{}] {:3}%",
                self.label,
                "#".repeat(filled),
                ".".repeat(30 - filled),
                pct
            );
            let _ = err.flush();
        }
    }

    pub fn finish(&self) {
        eprintln!();
    }
}
