//! Charts of the collision cases (plotters, SVG, the shared DejaVu Sans
//! font of `crate::pictures::font`), written into `reports/` by release runs
//! of the harness only: a debug build (the tests) draws nothing, so running
//! the tests never rewrites the committed report.

use crate::pictures::font::{FAMILY, ensure_fonts};
use anyhow::{Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::PathBuf;

/// Width and height of a chart (px).
const SIZE: (u32, u32) = (1100, 460);

/// One curve: a name and its points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend.
    pub name: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A named series.
    pub fn new(name: &str, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
        }
    }
}

/// Colours of the closed form, the engine and rapier2d.
const COLOURS: [RGBColor; 3] = [
    RGBColor(90, 90, 90),
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
];

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// `reports/` at the workspace root.
fn reports_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("reports")
}

/// Draws a chart into `reports/<file>` and returns `file` (the path
/// relative to the report's README).
pub fn write_chart(file: &str, draw: impl FnOnce(&Area<'_>) -> Result<()>) -> Result<String> {
    ensure_fonts();
    let dir = reports_dir();
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let path = dir.join(file);
    {
        let area = SVGBackend::new(&path, SIZE).into_drawing_area();
        area.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e}"))?;
        draw(&area)?;
        area.present().map_err(|e| anyhow::anyhow!("{e}"))?;
    }
    Ok(file.to_string())
}

fn panel(
    area: &Area<'_>,
    title: &str,
    y_label: &str,
    series: &[Series],
    log_y: bool,
) -> Result<()> {
    let xs = series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let x_max = xs.fold(1.0f64, f64::max);
    let ys: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|y| y.is_finite() && (!log_y || *y > 0.0))
        .collect();
    let (mut lo, mut hi) = ys
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
            (a.min(y), b.max(y))
        });
    let err = |e: String| anyhow::anyhow!(e);
    if log_y {
        lo /= 1.5;
        hi *= 1.5;
        let mut chart = ChartBuilder::on(area)
            .caption(title, (FAMILY, 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..x_max + 1.0, (lo..hi).log_scale())
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("bounce n")
            .y_desc(y_label)
            .label_style((FAMILY, 13))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        for (s, c) in series.iter().zip(COLOURS) {
            let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(|p| p.1 > 0.0).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                .map_err(|e| err(e.to_string()))?
                .label(s.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
                .map_err(|e| err(e.to_string()))?;
        }
        chart
            .configure_series_labels()
            .label_font((FAMILY, 13))
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(e.to_string()))?;
    } else {
        let pad = ((hi - lo) * 0.1).max(1e-6);
        lo -= pad;
        hi += pad;
        let mut chart = ChartBuilder::on(area)
            .caption(title, (FAMILY, 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..x_max + 1.0, lo..hi)
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("bounce n")
            .y_desc(y_label)
            .label_style((FAMILY, 13))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        for (s, c) in series.iter().zip(COLOURS) {
            chart
                .draw_series(LineSeries::new(s.points.clone(), c.stroke_width(2)))
                .map_err(|e| err(e.to_string()))?
                .label(s.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .label_font((FAMILY, 13))
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(e.to_string()))?;
    }
    Ok(())
}

/// Apex per bounce: e = 1 (apex / h0, linear) beside e = 0.8 (apex in m,
/// log scale), each with the closed form, the engine and rapier2d.
pub fn apex_chart(area: &Area<'_>, elastic: &[Series; 3], damped: &[Series; 3]) -> Result<()> {
    let (left, right) = area.split_horizontally(SIZE.0 / 2);
    panel(
        &left,
        "e = 1: apex / h0 per bounce",
        "apex / h0",
        elastic,
        false,
    )?;
    panel(&right, "e = 0.8: apex per bounce", "apex (m)", damped, true)?;
    Ok(())
}

/// A time series chart: one panel, x = time (s).
pub fn time_chart(area: &Area<'_>, title: &str, y_label: &str, series: &[Series]) -> Result<()> {
    let err = |e: String| anyhow::anyhow!(e);
    let x_max = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .fold(0.0f64, f64::max);
    let ys = series.iter().flat_map(|s| s.points.iter().map(|p| p.1));
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
        (a.min(y), b.max(y))
    });
    let pad = ((hi - lo) * 0.1).max(1e-9);
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FAMILY, 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..x_max, (lo - pad)..(hi + pad))
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(y_label)
        .label_style((FAMILY, 13))
        .draw()
        .map_err(|e| err(e.to_string()))?;
    for (s, c) in series.iter().zip(COLOURS) {
        chart
            .draw_series(LineSeries::new(s.points.clone(), c.stroke_width(2)))
            .map_err(|e| err(e.to_string()))?
            .label(s.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font((FAMILY, 13))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(e.to_string()))?;
    Ok(())
}
