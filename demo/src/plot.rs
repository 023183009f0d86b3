//! Line plots with plotters (bitmap backend, text in the embedded DejaVu Sans).

use crate::image_out::Rgb8;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// One distinct colour per method of `Method::ALL` (eleven).
pub const PALETTE: [[u8; 3]; 11] = [
    [220, 40, 40],
    [240, 140, 20],
    [30, 120, 220],
    [40, 170, 60],
    [150, 60, 200],
    [20, 170, 170],
    [200, 60, 140],
    [120, 120, 40],
    [90, 90, 90],
    [110, 70, 20],
    [0, 0, 160],
];

/// One polyline with its legend label, colour and dash (a dashed line for references).
pub struct Series {
    pub label: String,
    pub color: [u8; 3],
    pub values: Vec<f32>,
    pub dashed: bool,
}

/// Registers DejaVu Sans as plotters' `sans-serif` (its `ab_glyph` backend reads no system
/// font).
fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        if plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .is_err()
        {
            panic!("DejaVu Sans does not parse");
        }
    });
}

/// Plots every series against its index (frame), y on a log axis spanning all positive
/// values, with the legend to the right.
pub fn line_plot(title: &str, y_label: &str, series: &[Series], width: u32, height: u32) -> Rgb8 {
    register_font();
    let mut buf = vec![0u8; (width * height * 3) as usize];
    draw(&mut buf, title, y_label, series, width, height).expect("plotters draws into memory");
    Rgb8::from_raw(width, height, buf).expect("buffer of the plot's size")
}

fn draw(
    buf: &mut [u8],
    title: &str,
    y_label: &str,
    series: &[Series],
    width: u32,
    height: u32,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = BitMapBackend::with_buffer(buf, (width, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let legend_w = 230.min(width / 3);
    let (left, right) = root.split_horizontally(width - legend_w);
    let positive = series
        .iter()
        .flat_map(|s| s.values.iter().copied())
        .filter(|v| *v > 0.0);
    let (lo, hi) = positive.fold((f32::MAX, f32::MIN), |(a, b), v| (a.min(v), b.max(v)));
    let (lo, hi) = if lo > hi {
        (1.0, 10.0)
    } else {
        (lo * 0.8, hi * 1.25)
    };
    let n = series
        .iter()
        .map(|s| s.values.len())
        .max()
        .unwrap_or(1)
        .max(2);
    let mut chart = ChartBuilder::on(&left)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(32)
        .y_label_area_size(56)
        // The y axis is linear in log10(value), labelled with the values (two significant
        // digits at evenly spaced ratios: plotters' own log axis labels only whole decades).
        .build_cartesian_2d(0f32..(n - 1) as f32, lo.log10()..hi.log10())?;
    chart
        .configure_mesh()
        .x_labels(n.min(16))
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_labels(10)
        .y_label_formatter(&|y| {
            let v = 10f32.powf(*y);
            let digits = (1 - v.log10().floor() as i32).max(0) as usize;
            format!("{v:.digits$}")
        })
        .light_line_style(RGBColor(235, 235, 235))
        .x_desc("frame")
        .y_desc(y_label)
        .label_style(("sans-serif", 13))
        .draw()?;
    for s in series {
        let color = RGBColor(s.color[0], s.color[1], s.color[2]);
        let points = s
            .values
            .iter()
            .enumerate()
            .map(|(i, &v)| (i as f32, v.max(lo)));
        if s.dashed {
            chart.draw_series(DashedLineSeries::new(points, 6, 4, color.stroke_width(2)))?;
        } else {
            chart.draw_series(LineSeries::new(points, color.stroke_width(2)))?;
        }
    }
    // The legend: a swatch and the label per series.
    for (k, s) in series.iter().enumerate() {
        let y = 30 + 18 * k as i32;
        let color = RGBColor(s.color[0], s.color[1], s.color[2]);
        right.draw(&PathElement::new(
            vec![(4, y), (24, y)],
            color.stroke_width(3),
        ))?;
        right.draw(&Text::new(
            s.label.clone(),
            (30, y - 7),
            ("sans-serif", 13).into_font().color(&BLACK),
        ))?;
    }
    root.present()?;
    Ok(())
}
