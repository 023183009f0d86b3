//! The temporal test's statistics of a peak-luminance series `P(t)` (KHPL16 Fig. 12), shared
//! by the CPU and GPU demonstrations.

/// The mean of the series.
pub fn mean(p: &[f32]) -> f64 {
    p.iter().map(|&v| v as f64).sum::<f64>() / p.len().max(1) as f64
}

/// Mean `|P(t) - P(t-1)|` relative to the mean peak (the flicker).
pub fn variation(p: &[f32]) -> f64 {
    let steps: Vec<f32> = p.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    mean(&steps) / mean(p).max(1e-30)
}

/// Mean `|P(t) - R(t)|` relative to the mean reference peak `R`.
pub fn distance(p: &[f32], r: &[f32]) -> f64 {
    let d: Vec<f32> = p.iter().zip(r).map(|(a, b)| (a - b).abs()).collect();
    mean(&d) / mean(r).max(1e-30)
}
