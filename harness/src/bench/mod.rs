//! The many-body benchmark (`harness bench`, and a short section of the
//! main run): this engine's soft step, rapier2d-f64 0.36 and Box2D v3.2 on
//! the same scenes, built from the same scene files, measured side by side
//! (Box2D's protocol and step counts, [`measure`]), Box2D built as it
//! ships (-O3, NDEBUG, AVX2) and, when asked, its SSE2 and double builds
//! as child processes ([`child`]), with the quality figures read the same
//! way from every engine; the peak memory of the large scenes
//! ([`memory`]); the contact work-precision study ([`contact_precision`]);
//! `reports/benchmarks.md`, `benchmarks.json` and the charts ([`report`],
//! `crate::plots::bench`).

pub mod child;
pub mod contact_precision;
pub mod convert;
pub mod measure;
pub mod memory;
pub mod neutral_joints;
pub mod ours;
pub mod queries;
pub mod report;
pub mod scenes;
pub mod targets;

pub use measure::{BenchRow, BenchSettings, SceneResult, Steps};

use anyhow::{Context, Result};
use std::path::Path;

/// Runs every benchmark scene under `settings`, printing a line per scene,
/// then the contact work-precision study, and writes the report and charts
/// into `dir`.
pub fn run(dir: &Path, settings: BenchSettings) -> Result<Vec<SceneResult>> {
    run_selected(dir, settings, &[])
}

/// [`run`] of the scenes whose ids are `only` (every scene when empty; an
/// unknown id is refused before anything runs); a selection skips the
/// contact work-precision study.
pub fn run_selected(
    dir: &Path,
    settings: BenchSettings,
    only: &[String],
) -> Result<Vec<SceneResult>> {
    if let Some(unknown) = only
        .iter()
        .find(|id| !scenes::SCENES.iter().any(|s| s.id == id.as_str()))
    {
        let known: Vec<&str> = scenes::SCENES.iter().map(|s| s.id).collect();
        anyhow::bail!(
            "unknown benchmark '{unknown}'; the benchmarks are: {}",
            known.join(", ")
        );
    }
    // Memory first, while this process's own peak (which a child's reading
    // includes, see `memory`) is small.
    let memory = if settings.memory && only.is_empty() {
        let peaks = memory::measure_all()?;
        for p in peaks.iter().flatten() {
            println!(
                "memory {} ({} bodies, {} steps): peak {}{:.0} MB",
                p.command,
                p.bodies,
                p.steps,
                if p.exact { "" } else { "at most " },
                p.peak_mb
            );
        }
        peaks
    } else {
        None
    };
    let contenders = measure::Contenders::for_settings(&settings)?;
    let selected: Vec<_> = scenes::SCENES
        .iter()
        .filter(|s| only.is_empty() || only.iter().any(|id| id == s.id))
        .collect();
    // One unit per scene, and one for the contact-precision study (a full
    // benchmark); drawn on a terminal only (`crate::progress::bar`).
    let units = selected.len() + usize::from(only.is_empty());
    let bar = crate::progress::bar(units as u64, "bench");
    if crate::progress::enabled() {
        // A scene takes seconds: keep the elapsed time counting.
        bar.enable_steady_tick(crate::progress::REDRAW);
    }
    let mut results = Vec::new();
    for bench in selected {
        bar.set_message(format!("bench {}", bench.id));
        let file = match (settings.full, bench.full) {
            (true, Some(full)) => full,
            _ => bench.file,
        };
        let scene =
            crate::scenes::load(file).with_context(|| format!("benchmark scene {}", bench.id))?;
        let result = measure::measure(*bench, file, &scene, settings, &contenders)?;
        bar.inc(1);
        // Printed on stdout even when the bar is hidden (CI, pipes).
        bar.suspend(|| {
            println!(
                "bench {:<14} {:>6} bodies, {} steps: {}",
                bench.id,
                result.rows[0].bodies,
                result.rows[0].steps,
                result
                    .rows
                    .iter()
                    .map(|r| format!("{} {:.3} ms", short(&r.engine), r.ms_per_step_min))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        });
        results.push(result);
    }
    let precision = if only.is_empty() {
        bar.set_message("bench contact precision");
        contact_precision::run(settings)?
    } else {
        Vec::new()
    };
    bar.finish_and_clear();
    let mut charts = crate::plots::bench::draw(dir, &results)?;
    if !precision.is_empty() {
        charts.push(contact_precision::chart(dir, &precision)?);
    }
    let extras = report::Extras {
        notes: contenders.notes.clone(),
        memory: memory.unwrap_or_default(),
    };
    report::write(dir, &results, settings, &charts, &precision, &extras)?;
    queries::append(dir, settings.repeats.max(5))?;
    Ok(results)
}

/// A short engine name for the console and the README: "ours",
/// "rapier2d", or the Box2D build without the version ("Box2D f32 AVX2 -O3
/// NDEBUG").
pub fn short(engine: &str) -> String {
    if engine.starts_with("this") {
        "ours".into()
    } else if engine.starts_with("rapier") {
        "rapier2d".into()
    } else {
        engine.replacen("Box2D 3.2 ", "Box2D ", 1)
    }
}
