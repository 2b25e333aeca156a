//! Convergence plot: log error against log step per fixed-step method,
//! with thin guides of slope 1, 2 and 4 (each its own dash, labelled
//! "order p" at its end) through the smallest error of any method, so a
//! method's curve can be read against its nominal order.

use super::{Chart, Dash, Series, method_style, save_svg};
use crate::sweep::Sweep;
use anyhow::Result;
use engine::Method;
use std::path::Path;

/// Writes `<dir>/convergence_<case>.svg`.
pub fn write(dir: &Path, sweep: &Sweep) -> Result<String> {
    let file = format!("convergence_{}.svg", sweep.case);
    let mut series: Vec<Series> = Method::FIXED_STEP
        .iter()
        .filter_map(|m| {
            let pts: Vec<(f64, f64)> = sweep
                .points
                .iter()
                .filter(|p| p.method == m.id() && p.stable)
                .map(|p| (p.h, p.max_error))
                .collect();
            (!pts.is_empty()).then(|| Series::new(m.id(), method_style(m.id()), pts))
        })
        .collect();
    // Through the smallest error of any method, fanning out from it: the
    // chart cuts each where it leaves, and its label is there.
    let lowest = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|&(h, e)| h > 0.0 && e > 0.0 && e.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1));
    let (h_min, h_max) = sweep
        .points
        .iter()
        .filter(|p| p.tolerance.is_none() && p.h > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.h), b.max(p.h))
        });
    if let Some((h0, e0)) = lowest.filter(|_| h_max > h_min) {
        for (p, dash) in [(1, Dash::Dotted), (2, Dash::Dashed), (4, Dash::Long)] {
            let e = |h: f64| e0 * (h / h0).powi(p);
            series.push(Series::guide(
                format!("order {p}"),
                dash,
                vec![(h_min, e(h_min)), (h_max, e(h_max))],
            ));
        }
    }
    let chart = Chart {
        title: format!("{}: convergence (max {})", sweep.case, sweep.error_label),
        x_label: "step h (s)".into(),
        y_label: format!("max {}", sweep.error_label),
        log_x: true,
        log_y: true,
        series,
        y_range: None,
    };
    save_svg(&dir.join(&file), &[chart], 1, (760, 560))?;
    Ok(file)
}
