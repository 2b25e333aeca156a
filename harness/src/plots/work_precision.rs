//! Work-precision diagrams: error against CPU time and against derivative
//! evaluations, one curve per method (Dormand–Prince over its tolerances,
//! rapier2d-f64 dashed over its steps and substeps).

use super::{Chart, Series, method_color, save_svg};
use crate::sweep::Sweep;
use anyhow::Result;
use std::path::Path;

fn labels(sweep: &Sweep) -> Vec<String> {
    let mut labels: Vec<String> = sweep.points.iter().map(|p| p.method.clone()).collect();
    labels.dedup();
    labels
}

fn curves(sweep: &Sweep, x: impl Fn(&crate::sweep::SweepPoint) -> f64) -> Vec<Series> {
    labels(sweep)
        .into_iter()
        .map(|m| {
            let pts = sweep
                .points
                .iter()
                .filter(|p| p.method == m && p.stable)
                .map(|p| (x(p), p.max_error))
                .collect();
            let s = Series::new(m.clone(), method_color(&m), pts);
            if m.starts_with("rapier2d") {
                s.dashed()
            } else {
                s
            }
        })
        .collect()
}

/// Writes `<dir>/work_precision_<case>.svg`: error against CPU time (left)
/// and against evaluations (right).
pub fn write(dir: &Path, sweep: &Sweep) -> Result<String> {
    let file = format!("work_precision_{}.svg", sweep.case);
    let time = Chart {
        title: format!("{}: error vs CPU time", sweep.case),
        x_label: "CPU time per run (s, min of N, release)".into(),
        y_label: format!("max {}", sweep.error_label),
        log_x: true,
        log_y: true,
        series: curves(sweep, |p| p.cpu_seconds),
        y_range: None,
    };
    let evals = Chart {
        title: format!("{}: error vs evaluations", sweep.case),
        x_label: "derivative evaluations (rapier2d: steps)".into(),
        series: curves(sweep, |p| p.evaluations as f64),
        ..time.clone()
    };
    save_svg(&dir.join(&file), &[time, evals], 2, (640, 480))?;
    Ok(file)
}
