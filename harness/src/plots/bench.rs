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
        // One thread each (the rows at more threads follow them and have
        // their own chart, benchmark_threads.svg).
        let engines = series[0].rows.iter().filter(|r| r.threads == 1).count();
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
                        format!("{} (slope {slope:.2})", label(&series[0].rows[e])),
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
            y_label: "wall time per step in the phase (ms), the fastest profiled run".into(),
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
    if let Some(chart) = threads_chart(results) {
        let file = "benchmark_threads.svg";
        save_svg(&dir.join(file), &[chart], 1, (720, 460))?;
        out.push((
            file.to_string(),
            "speed-up from one thread to several, per engine, every scene (by its body count)"
                .to_string(),
        ));
    }
    Ok(out)
}

/// A row's engine, with its thread count when above one.
fn label(row: &crate::bench::BenchRow) -> String {
    if row.threads > 1 {
        format!(
            "{} on {} threads",
            crate::bench::short(&row.engine),
            row.threads
        )
    } else {
        row.engine.clone()
    }
}

/// Each engine's speed-up from one thread to the most measured (its ms per
/// step at one over at N), against the scene's body count; `None` when no
/// row has more than one thread.
fn threads_chart(results: &[SceneResult]) -> Option<Chart> {
    let threads = results
        .iter()
        .flat_map(|r| r.rows.iter().map(|b| b.threads))
        .max()?;
    if threads < 2 {
        return None;
    }
    let engines = ["this", "rapier", "Box2D"];
    let series = engines
        .iter()
        .enumerate()
        .map(|(e, prefix)| {
            let mut points: Vec<(f64, f64)> = results
                .iter()
                .filter_map(|r| {
                    let at = |n: usize| {
                        r.rows
                            .iter()
                            .find(|b| b.threads == n && b.engine.starts_with(prefix))
                    };
                    let (one, many) = (at(1)?, at(threads)?);
                    Some((
                        one.bodies as f64,
                        one.ms_per_step_min / many.ms_per_step_min,
                    ))
                })
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let name = results
                .first()
                .and_then(|r| r.rows.iter().find(|b| b.engine.starts_with(prefix)))
                .map_or(prefix.to_string(), |b| crate::bench::short(&b.engine));
            Series::new(
                format!("{name}: 1 → {threads} threads"),
                engine_style(e),
                points,
            )
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    Some(Chart {
        title: format!("speed-up from 1 to {threads} threads (1 = none, {threads} = perfect)"),
        x_label: "bodies of the scene".into(),
        y_label: format!("ms per step on 1 thread / on {threads}"),
        log_x: true,
        log_y: false,
        series,
        y_range: Some((0.0, threads as f64 + 0.25)),
    })
}
