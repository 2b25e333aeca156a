//! Charts of `reports/`, drawn with plotters into SVG: work-precision
//! diagrams, convergence, stability failures, energy, trajectories.
//!
//! One small chart model ([`Chart`], [`Series`]) serves them all. Log axes
//! are drawn as linear axes over log10 of the data, labelled `1e<k>`, which
//! keeps every chart one type.

pub mod bench;
pub mod convergence;
pub mod energy;
pub mod failures;
pub mod trajectories;
pub mod work_precision;

use crate::pictures::font::{FAMILY, ensure_fonts};
use anyhow::{Context, Result, anyhow};
use plotters::prelude::*;
use std::path::Path;

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points in data units (non-finite points are skipped; on a log axis,
    /// non-positive ones too).
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// Dashed line (references, rapier2d, guides).
    pub dashed: bool,
    /// Draw markers at the points.
    pub markers: bool,
}

impl Series {
    /// A solid line with markers.
    pub fn new(label: impl Into<String>, color: RGBColor, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            color,
            dashed: false,
            markers: true,
        }
    }

    /// The same, dashed.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }

    /// Without markers.
    pub fn plain(mut self) -> Self {
        self.markers = false;
        self
    }
}

/// One chart panel.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Caption.
    pub title: String,
    /// x axis label (with unit).
    pub x_label: String,
    /// y axis label (with unit).
    pub y_label: String,
    /// log10 x axis.
    pub log_x: bool,
    /// log10 y axis.
    pub log_y: bool,
    /// Curves.
    pub series: Vec<Series>,
    /// Fixed y range in data units (clips what lies outside).
    pub y_range: Option<(f64, f64)>,
}

/// A fixed colour per method id (tab10), so every chart agrees.
pub fn method_color(method: &str) -> RGBColor {
    const TAB10: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    let index = match method {
        "explicit_euler" => 0,
        "semi_implicit_euler" => 1,
        "rk2_midpoint" => 2,
        "rk4" => 3,
        "velocity_verlet" => 4,
        "implicit_euler" => 5,
        "dormand_prince" => 6,
        "reference" | "exact" => 7,
        m if m.starts_with("rapier2d_1") && !m.starts_with("rapier2d_16") => 8,
        m if m.starts_with("rapier2d") => 9,
        _ => 7,
    };
    TAB10[index]
}

fn transform(v: f64, log: bool) -> Option<f64> {
    if !v.is_finite() {
        return None;
    }
    if log {
        (v > 0.0).then(|| v.log10())
    } else {
        Some(v)
    }
}

fn bounds(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !lo.is_finite() {
        return None;
    }
    let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.5 };
    Some((lo - pad, hi + pad))
}

fn label(v: f64, log: bool) -> String {
    if log {
        if (v - v.round()).abs() < 1e-9 {
            format!("1e{}", v.round() as i64)
        } else {
            format!("{:.1e}", 10f64.powf(v))
        }
    } else {
        let a = v.abs();
        if a != 0.0 && !(1e-3..1e5).contains(&a) {
            format!("{v:.1e}")
        } else {
            format!("{v:.3}")
                .trim_end_matches('0')
                .trim_end_matches('.')
                .to_string()
        }
    }
}

/// Draws `chart` into `area`.
pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    chart: &Chart,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let points: Vec<Vec<(f64, f64)>> = chart
        .series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .filter_map(|&(x, y)| {
                    Some((transform(x, chart.log_x)?, transform(y, chart.log_y)?))
                })
                .collect()
        })
        .collect();
    let x = bounds(points.iter().flatten().map(|p| p.0)).unwrap_or((0.0, 1.0));
    let y = match chart.y_range {
        Some((lo, hi)) => (
            transform(lo, chart.log_y).unwrap_or(lo),
            transform(hi, chart.log_y).unwrap_or(hi),
        ),
        None => bounds(points.iter().flatten().map(|p| p.1)).unwrap_or((0.0, 1.0)),
    };
    let mut ctx = ChartBuilder::on(area)
        .caption(&chart.title, (FAMILY, 18))
        .margin(12)
        .x_label_area_size(42)
        .y_label_area_size(70)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(|e| anyhow!("chart '{}': {e}", chart.title))?;
    let (log_x, log_y) = (chart.log_x, chart.log_y);
    ctx.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .x_label_formatter(&|v| label(*v, log_x))
        .y_label_formatter(&|v| label(*v, log_y))
        .label_style((FAMILY, 12))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| anyhow!("chart '{}': {e}", chart.title))?;
    for (series, pts) in chart.series.iter().zip(&points) {
        // Clip to the y range so fixed ranges show blow-ups leaving the frame.
        let pts: Vec<(f64, f64)> = pts.iter().map(|&(a, b)| (a, b.clamp(y.0, y.1))).collect();
        let color = series.color;
        let style = ShapeStyle::from(&color).stroke_width(2);
        let anno = if series.dashed {
            ctx.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))
                .map_err(|e| anyhow!("{e}"))?
        } else {
            ctx.draw_series(LineSeries::new(pts.clone(), style))
                .map_err(|e| anyhow!("{e}"))?
        };
        anno.label(series.label.clone()).legend(move |(x, y)| {
            PathElement::new(
                vec![(x, y), (x + 18, y)],
                ShapeStyle::from(&color).stroke_width(2),
            )
        });
        if series.markers {
            ctx.draw_series(
                pts.iter()
                    .map(|&p| Circle::new(p, 3, ShapeStyle::from(&color).filled())),
            )
            .map_err(|e| anyhow!("{e}"))?;
        }
    }
    ctx.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .label_font((FAMILY, 11))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| anyhow!("chart '{}': {e}", chart.title))?;
    Ok(())
}

/// Saves `panels` as one SVG, stacked in `columns` columns, each panel
/// `w × h` pixels.
pub fn save_svg(path: &Path, panels: &[Chart], columns: usize, (w, h): (u32, u32)) -> Result<()> {
    ensure_fonts();
    let columns = columns.max(1);
    let rows = panels.len().div_ceil(columns);
    let size = (w * columns as u32, h * rows.max(1) as u32);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let areas = root.split_evenly((rows.max(1), columns));
    for (area, chart) in areas.iter().zip(panels) {
        draw(area, chart)?;
    }
    root.present()
        .map_err(|e| anyhow!("{e}"))
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}
