//! Work-precision diagrams: error against run time, one curve per method
//! (Dormand–Prince over its tolerances, rapier2d-f64 dashed over its steps
//! at 1, 4 and 16 substeps), and this engine's methods against derivative
//! evaluations (rapier2d-f64 evaluates its forces once a step and holds
//! them over its substeps, so its work is not counted in evaluations: it
//! is only in the time panel).

use super::{Chart, Series, method_style, save_svg};
use crate::sweep::{Sweep, SweepPoint};
use anyhow::Result;
use std::path::Path;

fn labels(sweep: &Sweep) -> Vec<String> {
    let mut labels: Vec<String> = sweep.points.iter().map(|p| p.method.clone()).collect();
    labels.dedup();
    labels
}

fn curves(
    sweep: &Sweep,
    keep: impl Fn(&str) -> bool,
    x: impl Fn(&SweepPoint) -> f64,
) -> Vec<Series> {
    labels(sweep)
        .into_iter()
        .filter(|m| keep(m))
        .map(|m| {
            let pts = sweep
                .points
                .iter()
                .filter(|p| p.method == m && p.stable)
                .map(|p| (x(p), p.max_error))
                .collect();
            Series::new(m.clone(), method_style(&m), pts)
        })
        .collect()
}

/// The time axis's label: what the harness measures (`crate::timing`).
pub const TIME_LABEL: &str = "wall time per run (s), min over repeated runs";

/// Writes `<dir>/work_precision_<case>.svg`: error against run time
/// (left) and this engine's methods against evaluations (right).
pub fn write(dir: &Path, sweep: &Sweep) -> Result<String> {
    let file = format!("work_precision_{}.svg", sweep.case);
    let time = Chart {
        title: format!("{}: error vs time", sweep.case),
        x_label: TIME_LABEL.into(),
        y_label: format!("max {}", sweep.error_label),
        log_x: true,
        log_y: true,
        series: curves(sweep, |_| true, |p| p.cpu_seconds),
        y_range: None,
    };
    let evals = Chart {
        title: format!("{}: error vs evaluations (this engine)", sweep.case),
        x_label: "derivative evaluations per run".into(),
        series: curves(
            sweep,
            |m| !m.starts_with("rapier2d"),
            |p| p.evaluations as f64,
        ),
        ..time.clone()
    };
    save_svg(&dir.join(&file), &[time, evals], 2, (640, 480))?;
    Ok(file)
}
