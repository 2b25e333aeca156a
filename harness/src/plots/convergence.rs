//! Convergence plot: log error against log step per fixed-step method, with
//! dashed guides of slope 1, 2 and 4.

use super::{Chart, Series, method_color, save_svg};
use crate::sweep::Sweep;
use anyhow::Result;
use engine::Method;
use plotters::style::RGBColor;
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
            (!pts.is_empty()).then(|| Series::new(m.id(), method_color(m.id()), pts))
        })
        .collect();
    // Guides of slope p through the coarsest RK4-sized error, so a method's
    // curve can be read against its nominal order.
    let h: Vec<f64> = sweep
        .points
        .iter()
        .filter(|p| p.tolerance.is_none())
        .map(|p| p.h)
        .collect();
    let (h_min, h_max) = h
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
    if h_max > 0.0 {
        let anchor = sweep.scale * 1e-3;
        for p in [1, 2, 4] {
            let e = |h: f64| anchor * (h / h_max).powi(p);
            series.push(
                Series::new(
                    format!("slope {p}"),
                    RGBColor(160, 160, 160),
                    vec![(h_min, e(h_min)), (h_max, e(h_max))],
                )
                .dashed()
                .plain(),
            );
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
