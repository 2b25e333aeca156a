//! The benchmark targets of the project (the many-body benchmark issue),
//! each judged on the ratios measured side by side in one run. They are
//! reported as met or not met with the measured figure; they are not rows
//! of `summary.json`, so noise never fails the main command.

use super::measure::{BenchRow, SceneResult};
use serde::Serialize;

/// A target and its verdict.
#[derive(Debug, Clone, Serialize)]
pub struct Target {
    /// What is asked.
    pub target: String,
    /// What was measured, in words and numbers.
    pub measured: String,
    /// Whether it holds.
    pub met: bool,
}

/// The row of engine `index` (0 this engine, 1 rapier2d, 2 Box2D) of scene
/// `id`.
fn row<'a>(results: &'a [SceneResult], id: &str, index: usize) -> Option<&'a BenchRow> {
    results
        .iter()
        .find(|r| r.scene.id == id)
        .and_then(|r| r.rows.get(index))
}

/// The least-squares slope of log(ms per step) against log(bodies) over
/// the scaling scenes, for engine `index`.
pub fn scaling_slope(results: &[SceneResult], index: usize) -> Option<f64> {
    let points: Vec<(f64, f64)> = results
        .iter()
        .filter(|r| r.scene.scaling)
        .filter_map(|r| r.rows.get(index))
        .map(|b| ((b.bodies as f64).ln(), b.ms_per_step_min.ln()))
        .collect();
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    Some(sxy / sxx)
}

/// Every target with its verdict.
pub fn targets(results: &[SceneResult]) -> Vec<Target> {
    let mut out = Vec::new();
    for id in ["pyramid_20", "pyramid_40", "large_pyramid"] {
        if let (Some(ours), Some(rapier)) = (row(results, id, 0), row(results, id, 1)) {
            let ratio = ours.ms_per_step_min / rapier.ms_per_step_min;
            out.push(Target {
                target: format!("{id}: at most 1.0× rapier2d-f64's ms per step"),
                measured: format!(
                    "{:.3} ms against {:.3} ms: {ratio:.2}×",
                    ours.ms_per_step_min, rapier.ms_per_step_min
                ),
                met: ratio <= 1.0,
            });
        }
    }
    if let (Some(ours), Some(b2)) = (
        row(results, "large_pyramid", 0),
        row(results, "large_pyramid", 2),
    ) {
        let ratio = ours.ms_per_step_min / b2.ms_per_step_min;
        out.push(Target {
            target: "large_pyramid: at most 2× Box2D v3's ms per step".into(),
            measured: format!(
                "{:.3} ms against {:.3} ms: {ratio:.2}×",
                ours.ms_per_step_min, b2.ms_per_step_min
            ),
            met: ratio <= 2.0,
        });
        out.push(Target {
            target:
                "large_pyramid (5050 boxes): faster than real time at 60 Hz, under 16.7 ms per step"
                    .into(),
            measured: format!("{:.3} ms per step", ours.ms_per_step_min),
            met: ours.ms_per_step_min < 1e3 / 60.0,
        });
    }
    if let Some(slope) = scaling_slope(results, 0) {
        out.push(Target {
            target: "cost grows no faster than n log n over the pyramid series: slope at most 1.15 on log-log axes".into(),
            measured: format!("slope {slope:.3}"),
            met: slope <= 1.15,
        });
    }
    for id in [
        "pyramid_10",
        "pyramid_20",
        "pyramid_40",
        "pyramid_70",
        "large_pyramid",
        "stack",
    ] {
        let (Some(ours), Some(rapier)) = (row(results, id, 0), row(results, id, 1)) else {
            continue;
        };
        let figures = [
            ("top sink (m)", ours.top_sink, rapier.top_sink),
            ("top drift (m)", ours.top_drift, rapier.top_drift),
            (
                "fastest at the end (m/s)",
                Some(ours.fastest_at_end),
                Some(rapier.fastest_at_end),
            ),
            (
                "deepest overlap (m)",
                Some(ours.deepest_overlap),
                Some(rapier.deepest_overlap),
            ),
        ];
        for (name, a, b) in figures {
            if let (Some(a), Some(b)) = (a, b) {
                // A figure counts as at least as good when it is no worse
                // than rapier's by more than the last digit a report shows
                // (1 %) or by more than 1 µm / 1 µm/s in absolute terms.
                let met = a <= b * 1.01 || a <= b + 1e-6;
                out.push(Target {
                    target: format!("{id}: {name} at least as good as rapier2d's"),
                    measured: format!("{a:.3e} against {b:.3e}"),
                    met,
                });
            }
        }
    }
    out
}
