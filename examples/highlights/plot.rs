//! A minimal line plot (log-scale y) drawn into an RGB buffer.

use crate::image_out::Rgb8;

/// One polyline with its legend label and colour.
pub struct Series {
    pub label: String,
    pub color: [u8; 3],
    pub values: Vec<f32>,
}

/// Plots every series against its index, y on a log10 axis spanning all positive values.
pub fn line_plot(title: &str, series: &[Series], width: usize, height: usize) -> Rgb8 {
    let mut img = Rgb8::new(width, height, [250, 250, 250]);
    let (left, right, top, bottom) = (60i64, 200i64, 30i64, 30i64);
    let (pw, ph) = (width as i64 - left - right, height as i64 - top - bottom);
    let positive = series
        .iter()
        .flat_map(|s| s.values.iter().copied())
        .filter(|v| *v > 0.0);
    let (lo, hi) = positive.fold((f32::MAX, f32::MIN), |(a, b), v| (a.min(v), b.max(v)));
    let (lo, hi) = if lo > hi {
        (1.0, 10.0)
    } else {
        (
            lo.log10().floor(),
            hi.log10().ceil().max(lo.log10().floor() + 1.0),
        )
    };
    let n = series
        .iter()
        .map(|s| s.values.len())
        .max()
        .unwrap_or(1)
        .max(2);
    let to_px = |i: usize, v: f32| {
        let x = left + (i as i64 * pw) / (n as i64 - 1);
        let t = (v.max(1e-30).log10().clamp(lo, hi) - lo) / (hi - lo);
        (x, top + ph - (t * ph as f32).round() as i64)
    };
    // Axes, decade grid lines and labels.
    let grey = [200, 200, 200];
    for d in lo as i64..=hi as i64 {
        let (_, y) = to_px(0, 10f32.powi(d as i32));
        line(&mut img, (left, y), (left + pw, y), grey);
        img.text(
            &format!("1E{d}"),
            8,
            (y - 3).max(0) as usize,
            1,
            [60, 60, 60],
        );
    }
    line(&mut img, (left, top), (left, top + ph), [0, 0, 0]);
    line(&mut img, (left, top + ph), (left + pw, top + ph), [0, 0, 0]);
    img.text(&title.to_uppercase(), left as usize, 10, 1, [0, 0, 0]);
    img.text(
        "FRAME",
        (left + pw / 2) as usize,
        (top + ph + 12) as usize,
        1,
        [0, 0, 0],
    );
    for (k, s) in series.iter().enumerate() {
        for (i, w) in s.values.windows(2).enumerate() {
            let (a, b) = (to_px(i, w[0]), to_px(i + 1, w[1]));
            line(&mut img, a, b, s.color);
            line(&mut img, (a.0, a.1 + 1), (b.0, b.1 + 1), s.color);
        }
        let (lx, ly) = ((left + pw + 12) as usize, (top + 12 * k as i64) as usize);
        for dx in 0..10 {
            for dy in 2..5 {
                img.set((lx + dx) as i64, (ly + dy) as i64, s.color);
            }
        }
        img.text(&s.label.to_uppercase(), lx + 14, ly, 1, [0, 0, 0]);
    }
    img
}

/// Bresenham line.
fn line(img: &mut Rgb8, (mut x0, mut y0): (i64, i64), (x1, y1): (i64, i64), c: [u8; 3]) {
    let (dx, dy) = ((x1 - x0).abs(), -(y1 - y0).abs());
    let (sx, sy) = (if x0 < x1 { 1 } else { -1 }, if y0 < y1 { 1 } else { -1 });
    let mut err = dx + dy;
    loop {
        img.set(x0, y0, c);
        if x0 == x1 && y0 == y1 {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x0 += sx;
        }
        if e2 <= dx {
            err += dx;
            y0 += sy;
        }
    }
}
