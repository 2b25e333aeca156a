//! Charts of the collision cases, drawn with the shared chart model of
//! [`crate::plots`] (same font, colours per curve: closed form, engine,
//! rapier2d), written into `reports/` by release runs of the harness only: a
//! debug build (the tests) draws nothing, so running the tests never
//! rewrites the committed report.

use crate::plots::{Chart, save_svg};
use anyhow::Result;
use plotters::style::RGBColor;
use std::path::PathBuf;

/// Width and height of one panel (px).
const PANEL: (u32, u32) = (550, 460);

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

fn curves(series: &[Series]) -> Vec<crate::plots::Series> {
    series
        .iter()
        .zip(COLOURS)
        .map(|(s, c)| crate::plots::Series::new(s.name.clone(), c, s.points.clone()))
        .collect()
}

/// Writes `panels` side by side into `reports/<file>` and returns `file`
/// (the path relative to the report's README).
pub fn write_chart(file: &str, panels: &[Chart]) -> Result<String> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("reports");
    save_svg(&dir.join(file), panels, panels.len(), PANEL)?;
    Ok(file.to_string())
}

/// Apex per bounce: e = 1 (apex / h0, linear) beside e = 0.8 (apex in m,
/// log scale), each with the closed form, the engine and rapier2d.
pub fn apex_chart(elastic: &[Series; 3], damped: &[Series; 3]) -> [Chart; 2] {
    [
        Chart {
            title: "e = 1: apex / h0 per bounce".into(),
            x_label: "bounce n".into(),
            y_label: "apex / h0".into(),
            series: curves(elastic),
            ..Chart::default()
        },
        Chart {
            title: "e = 0.8: apex per bounce".into(),
            x_label: "bounce n".into(),
            y_label: "apex (m)".into(),
            log_y: true,
            series: curves(damped),
            ..Chart::default()
        },
    ]
}

/// A time series chart: one panel, x = time (s).
pub fn time_chart(title: &str, y_label: &str, series: &[Series]) -> Chart {
    Chart {
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: y_label.into(),
        series: curves(series).into_iter().map(|s| s.plain()).collect(),
        ..Chart::default()
    }
}
