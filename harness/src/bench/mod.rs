//! The many-body benchmark (`harness bench`, and a short section of the
//! main run): this engine's soft step, rapier2d-f64 0.36 and Box2D v3.2 on
//! the same scenes, built from the same scene files, measured side by side
//! (Box2D's protocol and step counts, [`measure`]), Box2D built as it
//! ships (-O3, NDEBUG, AVX2) and, when asked, its SSE2 and double builds
//! as child processes ([`child`]), with the quality figures read the same
//! way from every engine ([`figures`]), and for each quality target this
//! engine misses what would close it ([`quality_probe`]); the peak memory of the large scenes
//! ([`memory`]); the contact work-precision study ([`contact_precision`]);
//! `reports/benchmarks.md`, `benchmarks.json` and the charts ([`report`],
//! `crate::plots::bench`).

pub mod child;
pub mod contact_precision;
pub mod convert;
pub mod figures;
pub mod measure;
pub mod memory;
pub mod neutral_joints;
pub mod ours;
pub mod quality_probe;
pub mod queries;
pub mod report;
pub mod scenes;
pub mod stages;
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
    let selected = select(only);
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
        let result = measure_scene(bench, settings, &contenders)?;
        bar.inc(1);
        // Printed on stdout even when the bar is hidden (CI, pipes).
        bar.suspend(|| print_scene(&result));
        results.push(result);
    }
    let precision = if only.is_empty() {
        bar.set_message("bench contact precision");
        contact_precision::run(settings)?
    } else {
        Vec::new()
    };
    bar.finish_and_clear();
    let queries = queries::measure(settings.repeats.max(5))?;
    write(
        dir,
        settings,
        &contenders,
        Measured {
            scenes: results.clone(),
            precision,
            queries,
            memory: memory.unwrap_or_default(),
        },
    )?;
    Ok(results)
}

/// The benchmark scenes whose ids are `only` (every scene when empty).
fn select(only: &[String]) -> Vec<&'static scenes::BenchScene> {
    scenes::SCENES
        .iter()
        .filter(|s| only.is_empty() || only.iter().any(|id| id == s.id))
        .collect()
}

/// Measures benchmark scene `bench` in every contender.
fn measure_scene(
    bench: &scenes::BenchScene,
    settings: BenchSettings,
    contenders: &measure::Contenders,
) -> Result<SceneResult> {
    let file = match (settings.full, bench.full) {
        (true, Some(full)) => full,
        _ => bench.file,
    };
    let scene =
        crate::scenes::load(file).with_context(|| format!("benchmark scene {}", bench.id))?;
    measure::measure(*bench, file, &scene, settings, contenders)
}

/// The console line of a scene's result.
fn print_scene(result: &SceneResult) {
    println!(
        "bench {:<14} {:>6} bodies, {} steps: {}",
        result.scene.id,
        result.rows[0].bodies,
        result.rows[0].steps,
        result
            .rows
            .iter()
            .map(|r| format!("{} {:.3} ms", short(&r.engine), r.ms_per_step_min))
            .collect::<Vec<_>>()
            .join(", ")
    );
    if let Some(p) = result.rows.first().and_then(|r| r.quality_probe.as_ref()) {
        for m in &p.misses {
            println!(
                "  {} against {}: {}",
                m.figure,
                short(&m.reference),
                m.describe(p.shift_m)
            );
        }
    }
}

/// Everything a benchmark measured, for its report ([`write`]).
#[derive(Debug, Clone, Default)]
pub struct Measured {
    /// One result per scene, in [`scenes::SCENES`]'s order.
    pub scenes: Vec<SceneResult>,
    /// The contact work-precision study (empty when not run).
    pub precision: Vec<contact_precision::CaseResult>,
    /// The ray-cast timings.
    pub queries: Vec<queries::QueryTiming>,
    /// The peak memory of the large scenes, if measured.
    pub memory: Vec<memory::PeakMemory>,
}

/// What one job of the short benchmark of a run measured ([`jobs`]).
pub enum BenchPiece {
    /// A scene.
    Scene(SceneResult),
    /// The contact work-precision study.
    Precision(Vec<contact_precision::CaseResult>),
    /// The ray-cast timings.
    Queries(Vec<queries::QueryTiming>),
}

/// Expected wall time (s) of the short benchmark's jobs on one quiet core,
/// for the order in which a run starts them ([`crate::pool`]):
/// measured in one full run (2026-12-02, `RUST_LOG=info`, which logs
/// each job's wall and thread CPU time) on the 2-core development machine
/// shared with other work: the larger of the job's CPU time and a quarter
/// of its wall time (the run had about a quarter of a core per worker;
/// rapier2d's own pool thread is not the job's),
/// see [`job_cost`].
const BENCH_COSTS: &[(&str, f64)] = &[
    ("bench contact precision", 6.4),
    ("bench large_pyramid", 6.1),
    ("bench smash", 5.3),
    ("bench tumbler", 3.9),
    ("bench ragdoll_rain", 2.8),
    ("bench joint_grid", 2.3),
    ("bench many_pyramids", 1.4),
    ("bench pyramid_70", 1.2),
    ("bench shape_rain", 0.7),
    ("bench pyramid_40", 0.6),
];

/// The cost of a benchmark job without an estimate (s).
const DEFAULT_BENCH_COST: f64 = 1.0;

/// The expected cost (s) of the benchmark job `label`.
pub fn job_cost(label: &str) -> f64 {
    crate::pool::estimated_cost(BENCH_COSTS, label, DEFAULT_BENCH_COST)
}

/// The short benchmark of a run (every scene, no memory runs) as
/// independent jobs for the run's pool ([`crate::pool`]): one per scene,
/// one for the contact work-precision study, one for the ray casts; each
/// times its engines on its own worker. [`gather`] then [`write`] make the
/// report [`run`] makes.
pub fn jobs(
    settings: BenchSettings,
    contenders: &measure::Contenders,
) -> Vec<crate::pool::Job<'_, BenchPiece>> {
    use crate::pool::Job;
    let mut jobs = Vec::new();
    for bench in select(&[]) {
        let label = format!("bench {}", bench.id);
        jobs.push(Job::new(label.clone(), job_cost(&label), move || {
            let result = measure_scene(bench, settings, contenders)?;
            print_scene(&result);
            Ok(BenchPiece::Scene(result))
        }));
    }
    let label = "bench contact precision";
    jobs.push(Job::new(label, job_cost(label), move || {
        Ok(BenchPiece::Precision(contact_precision::run(settings)?))
    }));
    let label = "bench ray casts";
    jobs.push(Job::new(label, job_cost(label), move || {
        Ok(BenchPiece::Queries(queries::measure(
            settings.repeats.max(5),
        )?))
    }));
    jobs
}

/// The measurements of [`jobs`]' results, in their order; the first error
/// is the one returned.
pub fn gather(done: Vec<crate::pool::Done<BenchPiece>>) -> Result<Measured> {
    let mut measured = Measured::default();
    for d in done {
        match d.result? {
            BenchPiece::Scene(s) => measured.scenes.push(s),
            BenchPiece::Precision(p) => measured.precision = p,
            BenchPiece::Queries(q) => measured.queries = q,
        }
    }
    Ok(measured)
}

/// Writes the report of `measured` into `dir`: the charts,
/// `benchmarks.md` (its ray-cast section last) and `benchmarks.json`.
pub fn write(
    dir: &Path,
    settings: BenchSettings,
    contenders: &measure::Contenders,
    measured: Measured,
) -> Result<()> {
    let mut charts = crate::plots::bench::draw(dir, &measured.scenes)?;
    if !measured.precision.is_empty() {
        charts.push(contact_precision::chart(dir, &measured.precision)?);
    }
    let extras = report::Extras {
        notes: contenders.notes.clone(),
        memory: measured.memory,
    };
    report::write(
        dir,
        &measured.scenes,
        settings,
        &charts,
        &measured.precision,
        &extras,
    )?;
    queries::append(dir, &measured.queries, settings.repeats.max(5))
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
