//! Charts of the collision cases, drawn with the shared chart model of
//! [`crate::plots`] (same font, colours per curve: closed form, engine,
//! rapier2d). A case returns them as [`CaseFigure`]s; the report writer
//! saves them into the report folder, so a run without one writes nothing.

use super::CaseFigure;
use crate::plots::Chart;
use plotters::style::RGBColor;

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

/// The figure `file` (`.svg`) of `panels` side by side, with its
/// alternative text and caption.
pub fn figure(file: &str, alt: &str, caption: String, panels: Vec<Chart>) -> CaseFigure {
    CaseFigure {
        file: file.into(),
        alt: alt.into(),
        caption,
        panels,
        panel_size: PANEL,
    }
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
