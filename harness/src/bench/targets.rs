//! The benchmark targets of the project (the many-body benchmark issue,
//! and the single-thread lead over Box2D's release build: [`box2d_targets`]),
//! each judged on the ratios measured side by side in one run. They are
//! reported as met or not met with the measured figure; they are not rows
//! of `summary.json`, so noise never fails the main command.

use super::figures::{DEEPEST_OVERLAP, FASTEST_AT_END, Figures, TOP_DRIFT, TOP_SINK};
use super::measure::{BenchRow, SceneResult};
use super::quality_probe::QualityProbe;
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
    /// For a missed target: what would close it, from the measured
    /// figures: for a speed target against Box2D the stages
    /// ([`super::stages::Gap::describe`]), for a quality target the probes
    /// ([`QualityProbe::describe`]).
    pub to_close: Option<String>,
}

/// The row of engine `index` of scene `id`: 0 this engine, 1 rapier2d
/// (always the first two rows), 2 Box2D's release build, f32 with AVX2
/// (found by its build: it is missing on a CPU without AVX2).
fn row<'a>(results: &'a [SceneResult], id: &str, index: usize) -> Option<&'a BenchRow> {
    let r = results.iter().find(|r| r.scene.id == id)?;
    match index {
        0 | 1 => r.rows.get(index),
        _ => box2d_avx2(r),
    }
}

/// Box2D's f32 AVX2 row of a scene (its release build), if measured.
pub fn box2d_avx2(result: &SceneResult) -> Option<&BenchRow> {
    box2d_avx2_of(&result.rows)
}

/// Box2D's f32 AVX2 row among a scene's `rows`, if measured.
fn box2d_avx2_of(rows: &[BenchRow]) -> Option<&BenchRow> {
    rows.iter().find(|b| {
        b.engine.starts_with("Box2D") && b.precision == "f32" && b.engine.contains(" AVX2 ")
    })
}

/// A quality figure counts as at least as good as the reference's when it
/// is no worse by more than the last digit a report shows (1 %) or by
/// more than 1 µm / 1 µm/s / 1 µrad in absolute terms.
pub fn at_least_as_good(a: f64, b: f64) -> bool {
    a <= b * 1.01 || a <= b + 1e-6
}

/// A quality target: this engine's figure at least as good as a
/// reference engine's on a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct QualityTarget {
    /// The figure's name ([`super::figures`]).
    pub figure: &'static str,
    /// The reference engine's name (its row's).
    pub reference: String,
    /// This engine's figure.
    pub ours: f64,
    /// The reference's figure.
    pub theirs: f64,
}

impl QualityTarget {
    /// Whether it holds ([`at_least_as_good`]).
    pub fn met(&self) -> bool {
        at_least_as_good(self.ours, self.theirs)
    }

    /// Its row in a target table, with what would close it from `probe`
    /// when missed.
    fn target(&self, id: &str, against: &str, probe: Option<&QualityProbe>) -> Target {
        let met = self.met();
        Target {
            target: format!("{id}: {} at least as good as {against}'s", self.figure),
            measured: format!("{:.3e} against {:.3e}", self.ours, self.theirs),
            met,
            to_close: if met {
                None
            } else {
                probe.and_then(|p| p.describe(self.figure, &self.reference))
            },
        }
    }
}

/// The scenes whose quality figures are set against rapier2d's (the
/// many-body benchmark issue's pyramid series and stack).
pub const RAPIER_QUALITY_SCENES: [&str; 6] = [
    "pyramid_10",
    "pyramid_20",
    "pyramid_40",
    "pyramid_70",
    "large_pyramid",
    "stack",
];

/// The quality targets against rapier2d on scene `id` of `rows` (this
/// engine's and rapier2d's one-thread rows first): the top body's sink and
/// drift, the fastest body and the deepest overlap, on the scenes of
/// [`RAPIER_QUALITY_SCENES`].
pub fn rapier_quality(id: &str, rows: &[BenchRow]) -> Vec<QualityTarget> {
    let (Some(ours), Some(rapier)) = (rows.first(), rows.get(1)) else {
        return Vec::new();
    };
    if !RAPIER_QUALITY_SCENES.contains(&id) {
        return Vec::new();
    }
    let theirs = Figures::of_row(rapier);
    Figures::of_row(ours)
        .named()
        .into_iter()
        .filter(|(name, _)| [TOP_SINK, TOP_DRIFT, FASTEST_AT_END, DEEPEST_OVERLAP].contains(name))
        .filter_map(|(figure, a)| {
            theirs.get(figure).map(|b| QualityTarget {
                figure,
                reference: rapier.engine.clone(),
                ours: a,
                theirs: b,
            })
        })
        .collect()
}

/// The quality targets against Box2D's release build (f32 AVX2) in
/// `rows`: every figure both rows have.
pub fn box2d_quality(rows: &[BenchRow]) -> Vec<QualityTarget> {
    let (Some(ours), Some(b2)) = (rows.first(), box2d_avx2_of(rows)) else {
        return Vec::new();
    };
    let theirs = Figures::of_row(b2);
    Figures::of_row(ours)
        .named()
        .into_iter()
        .filter_map(|(figure, a)| {
            theirs.get(figure).map(|b| QualityTarget {
                figure,
                reference: b2.engine.clone(),
                ours: a,
                theirs: b,
            })
        })
        .collect()
}

/// The single-thread lead over Box2D's release build: on every scene, at
/// most 0.9× its ms per step (minimum over the repeats, one thread each,
/// the same substeps), and every quality figure at least as good as its.
pub fn box2d_targets(results: &[SceneResult]) -> Vec<Target> {
    let mut out = Vec::new();
    for r in results {
        let (Some(ours), Some(b2)) = (r.rows.first(), box2d_avx2(r)) else {
            continue;
        };
        let ratio = ours.ms_per_step_min / b2.ms_per_step_min;
        out.push(Target {
            target: format!(
                "{}: at most 0.9× {}'s ms per step, one thread each",
                r.scene.id, b2.engine
            ),
            measured: format!(
                "{:.3} ms against {:.3} ms: {ratio:.2}×",
                ours.ms_per_step_min, b2.ms_per_step_min
            ),
            met: ratio <= 0.9,
            to_close: to_close(r, ours.ms_per_step_min, b2, 0.9, ratio <= 0.9),
        });
        let probe = ours.quality_probe.as_ref();
        for q in box2d_quality(&r.rows) {
            out.push(q.target(r.scene.id, "Box2D", probe));
        }
    }
    out
}

/// What would close the missed target "at most `factor` × Box2D's ms per
/// step" (`met`: nothing to close), this engine at `ours_ms`, against
/// Box2D's row `b2`: the [`super::stages::Gap`] with the stages of the
/// profiled runs at `b2`'s thread count (when `b2` is the profiled
/// linked build: its row carries the stages).
fn to_close(
    r: &SceneResult,
    ours_ms: f64,
    b2: &BenchRow,
    factor: f64,
    met: bool,
) -> Option<String> {
    if met || b2.stages.is_none() {
        return None;
    }
    let c = r.stages.iter().find(|c| c.threads == b2.threads)?;
    Some(super::stages::gap(ours_ms, b2.ms_per_step_min, factor, &c.stages).describe())
}

/// What would close a missed speed-up target of this engine: `many` (its
/// row on several threads) at least `factor` times faster than `one_ms`
/// (its one-thread minimum), from its profiled runs at both counts.
fn speedup_to_close(
    r: &SceneResult,
    one_ms: f64,
    many: &BenchRow,
    factor: f64,
    met: bool,
) -> Option<String> {
    if met {
        return None;
    }
    let at = |t: usize| r.stages.iter().find(|c| c.threads == t);
    let (one, several) = (at(1)?, at(many.threads)?);
    Some(
        super::stages::speedup_gap(
            one_ms,
            many.ms_per_step_min,
            factor,
            &one.stages,
            &several.stages,
        )
        .describe(),
    )
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
                to_close: None,
            });
        }
    }
    if let (Some(ours), Some(b2)) = (
        row(results, "large_pyramid", 0),
        row(results, "large_pyramid", 2),
    ) {
        let ratio = ours.ms_per_step_min / b2.ms_per_step_min;
        out.push(Target {
            target: format!("large_pyramid: at most 2× {}'s ms per step", b2.engine),
            measured: format!(
                "{:.3} ms against {:.3} ms: {ratio:.2}×",
                ours.ms_per_step_min, b2.ms_per_step_min
            ),
            met: ratio <= 2.0,
            to_close: None,
        });
        out.push(Target {
            target:
                "large_pyramid (5050 boxes): faster than real time at 60 Hz, under 16.7 ms per step"
                    .into(),
            measured: format!("{:.3} ms per step", ours.ms_per_step_min),
            met: ours.ms_per_step_min < 1e3 / 60.0,
            to_close: None,
        });
    }
    if let Some(slope) = scaling_slope(results, 0) {
        out.push(Target {
            target: "cost grows no faster than n log n over the pyramid series: slope at most 1.15 on log-log axes".into(),
            measured: format!("slope {slope:.3}"),
            met: slope <= 1.15,
            to_close: None,
        });
    }
    for r in results {
        let probe = r.rows.first().and_then(|b| b.quality_probe.as_ref());
        for q in rapier_quality(r.scene.id, &r.rows) {
            out.push(q.target(r.scene.id, "rapier2d", probe));
        }
    }
    out
}

/// The row of `engine_prefix` at `threads` threads in a scene (the linked
/// Box2D's f32 AVX2 build for "Box2D").
fn row_at<'a>(
    result: &'a SceneResult,
    engine_prefix: &str,
    threads: usize,
) -> Option<&'a BenchRow> {
    result.rows.iter().find(|b| {
        b.threads == threads
            && b.engine.starts_with(engine_prefix)
            && (engine_prefix != "Box2D" || (b.precision == "f32" && b.engine.contains(" AVX2 ")))
    })
}

/// The multi-threading targets (issue 21), for the largest thread count
/// measured above one: this engine on 2 threads at least 1.7× faster than
/// on 1 on large_pyramid; and this engine ahead of Box2D at the same
/// count on every scene.
pub fn thread_targets(results: &[SceneResult]) -> Vec<Target> {
    let mut out = Vec::new();
    let threads = results
        .iter()
        .flat_map(|r| r.rows.iter().map(|b| b.threads))
        .max()
        .unwrap_or(1);
    if threads < 2 {
        return out;
    }
    for r in results {
        let (Some(one), Some(many)) = (row_at(r, "this", 1), row_at(r, "this", threads)) else {
            continue;
        };
        let speedup = one.ms_per_step_min / many.ms_per_step_min;
        if r.scene.id == "large_pyramid" && threads == 2 {
            out.push(Target {
                target: "large_pyramid: 2 threads at least 1.7× faster than 1 (this engine)".into(),
                measured: format!(
                    "{:.3} ms → {:.3} ms: {speedup:.2}× (CPU/wall {:.2})",
                    one.ms_per_step_min, many.ms_per_step_min, many.cpu_over_wall
                ),
                met: speedup >= 1.7,
                to_close: speedup_to_close(r, one.ms_per_step_min, many, 1.7, speedup >= 1.7),
            });
        }
        if let Some(b2) = row_at(r, "Box2D", threads) {
            let ratio = many.ms_per_step_min / b2.ms_per_step_min;
            out.push(Target {
                target: format!(
                    "{}: ahead of Box2D with {threads} workers ({threads} threads each)",
                    r.scene.id
                ),
                measured: format!(
                    "{:.3} ms against {:.3} ms: {ratio:.2}× Box2D's time (speed-up from 1 \
                     thread: ours {speedup:.2}×, Box2D {:.2}×)",
                    many.ms_per_step_min,
                    b2.ms_per_step_min,
                    row_at(r, "Box2D", 1)
                        .map_or(f64::NAN, |b| b.ms_per_step_min / b2.ms_per_step_min)
                ),
                met: ratio < 1.0,
                to_close: to_close(r, many.ms_per_step_min, b2, 1.0, ratio < 1.0),
            });
        }
    }
    out
}
