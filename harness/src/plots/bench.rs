//! The benchmark's charts: ms per step against body count for the pyramid
//! series on log-log axes (three engines, slopes in the legend), and this
//! engine's time per phase along the same series (where the time goes, and
//! how each phase grows).

use super::{Chart, Series, Style, palette, save_svg};
use crate::bench::SceneResult;
use crate::bench::targets::scaling_slope;
use anyhow::Result;
use std::path::Path;

/// The style of an engine (this engine, rapier2d, Box2D), the same in
/// the contact work-precision chart.
pub fn engine_style(index: usize) -> Style {
    [
        palette(0),
        palette(2).dashed(),
        palette(1).dotted(),
        palette(3).dashed(),
        palette(4).dotted(),
    ][index % 5]
}

/// Writes the charts into `dir`; returns their file names and captions.
pub fn draw(dir: &Path, results: &[SceneResult]) -> Result<Vec<(String, String)>> {
    let series: Vec<&SceneResult> = results.iter().filter(|r| r.scene.scaling).collect();
    let mut out = Vec::new();
    if series.len() >= 2 {
        let engines = series[0].rows.len();
        let scaling = Chart {
            title: "pyramids of base 10 to 100: cost per step".into(),
            x_label: "bodies".into(),
            y_label: "wall time per step (ms), min over repeats".into(),
            log_x: true,
            log_y: true,
            series: (0..engines)
                .map(|e| {
                    let slope = scaling_slope(results, e).unwrap_or(f64::NAN);
                    Series::new(
                        format!("{} (slope {slope:.2})", series[0].rows[e].engine),
                        engine_style(e),
                        series
                            .iter()
                            .map(|r| (r.rows[e].bodies as f64, r.rows[e].ms_per_step_min))
                            .collect(),
                    )
                })
                .collect(),
            y_range: None,
        };
        let phases: Vec<&str> = series[series.len() - 1]
            .profile
            .iter()
            .map(|(name, _)| *name)
            .collect();
        let profile = Chart {
            title: "this engine's step, phase by phase".into(),
            x_label: "bodies".into(),
            y_label: "wall time per step in the phase (ms), one profiled run".into(),
            log_x: true,
            log_y: true,
            series: phases
                .iter()
                .enumerate()
                .map(|(i, phase)| {
                    Series::new(
                        *phase,
                        palette(i),
                        series
                            .iter()
                            .filter_map(|r| {
                                r.profile
                                    .iter()
                                    .find(|(n, _)| n == phase)
                                    .map(|(_, ms)| (r.rows[0].bodies as f64, *ms))
                            })
                            .collect(),
                    )
                })
                .collect(),
            y_range: None,
        };
        let file = "benchmark_scaling.svg";
        save_svg(&dir.join(file), &[scaling, profile], 2, (640, 440))?;
        out.push((
            file.to_string(),
            "ms per step against bodies over the pyramid series (left), and this engine's time per phase (right)".to_string(),
        ));
    }
    Ok(out)
}
