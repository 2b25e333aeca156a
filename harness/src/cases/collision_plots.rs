//! Charts of the collision cases, drawn with the shared chart model of
//! [`crate::plots`]: the closed form as a wide pale line under the engine
//! (the rk4 style, as in every chart) and rapier2d (its 4-substep style).
//! Where the engine's curve lies on the closed form, a panel of the
//! difference to the closed form shows what the values panel cannot. A
//! case returns its charts as [`CaseFigure`]s; the report writer saves them
//! into the report folder, so a run without one writes nothing.

use super::CaseFigure;
use crate::plots::{Chart, method_style};

/// Width and height of one panel (px).
const PANEL: (u32, u32) = (550, 420);

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

/// The closed form, the engine and rapier2d, in that order, as chart
/// series.
fn curves(series: &[Series]) -> Vec<crate::plots::Series> {
    series
        .iter()
        .enumerate()
        .map(|(i, s)| match i {
            0 => crate::plots::Series::reference(s.name.clone(), s.points.clone()),
            1 => crate::plots::Series::new(s.name.clone(), method_style("rk4"), s.points.clone()),
            _ => crate::plots::Series::new(
                s.name.clone(),
                method_style("rapier2d_4sub"),
                s.points.clone(),
            ),
        })
        .collect()
}

/// The figure `file` (`.svg`) of `panels`, `columns` to a row, with its
/// alternative text and caption.
pub fn figure(
    file: &str,
    alt: &str,
    caption: String,
    panels: Vec<Chart>,
    columns: usize,
) -> CaseFigure {
    CaseFigure {
        file: file.into(),
        alt: alt.into(),
        caption,
        panels,
        columns,
        panel_size: PANEL,
    }
}

/// The engine's and rapier2d's relative difference to the closed form at
/// the closed form's own x values (bounce numbers), log scale.
fn relative_difference(title: &str, series: &[Series; 3]) -> Chart {
    let closed = &series[0].points;
    let diff = |s: &Series| -> Vec<(f64, f64)> {
        s.points
            .iter()
            .filter_map(|&(x, v)| {
                let &(_, c) = closed.iter().find(|p| p.0 == x)?;
                Some((x, ((v - c) / c).abs()))
            })
            .collect()
    };
    let mut lines = curves(series);
    lines.remove(0);
    lines[0].points = diff(&series[1]);
    lines[1].points = diff(&series[2]);
    Chart {
        title: title.into(),
        x_label: "bounce n".into(),
        y_label: "|apex − closed form| / closed form".into(),
        log_y: true,
        series: lines,
        ..Chart::default()
    }
}

/// Apex per bounce: e = 1 (apex / h0, linear) beside e = 0.8 (apex in m,
/// log scale), each with the closed form, the engine and rapier2d; under
/// each, the relative difference to the closed form (the engine's lies on
/// the closed form in the panels above).
pub fn apex_chart(elastic: &[Series; 3], damped: &[Series; 3]) -> [Chart; 4] {
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
        relative_difference("e = 1: relative difference to h0", elastic),
        relative_difference("e = 0.8: relative difference to 0.64^n h0", damped),
    ]
}

/// A time series chart: one panel, x = time (s), the closed form, the
/// engine and rapier2d as dense curves.
pub fn time_chart(title: &str, y_label: &str, series: &[Series]) -> Chart {
    Chart {
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: y_label.into(),
        series: curves(series).into_iter().map(|s| s.line()).collect(),
        ..Chart::default()
    }
}

/// The engine's and rapier2d's |difference| to the closed form against
/// time, log scale (`engine`, `rapier` already hold the differences, in
/// `unit`); an exact 0 goes to the band labelled 0.
pub fn difference_chart(title: &str, unit: &str, engine: Series, rapier: Series) -> Chart {
    let mut lines = curves(&[Series::new("", Vec::new()), engine, rapier]);
    lines.remove(0);
    Chart {
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: format!("|difference to the closed form| ({unit})"),
        log_y: true,
        series: lines.into_iter().map(|s| s.line()).collect(),
        ..Chart::default()
    }
}
