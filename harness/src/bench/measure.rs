//! One benchmark scene in every engine, run alternately (Box2D's
//! protocol): for each repeat, each engine builds the scene afresh, takes
//! step 0 untimed, then the timed steps (Box2D's own count for the scene
//! in `harness bench`); the time per step is the minimum, the median and
//! the maximum over the repeats. Each repeat starts one engine further
//! along the list (repeat r runs them from the (r mod n)-th on), so no
//! engine always follows the same other one or runs first in a fresh
//! process state. The engines are this engine, rapier2d and
//! the Box2D linked here, in this process, and the other Box2D builds
//! asked for, each run as a child process ([`super::child`]) in its turn.
//! Each row carries the engine's build: precision, the SIMD path it takes
//! on this CPU, its compiler settings, and its thread count: every
//! engine at one thread, then (with [`BenchSettings::threads`] above one)
//! this engine, rapier2d and Box2D again at that count (ours on its pool,
//! rapier2d's `parallel` paths in a rayon pool of that size, Box2D's
//! built-in scheduler through boxdd's `worker_count`), each with the CPU
//! time of the process over the wall time of its timed steps
//! (`getrusage`), which says how busy the threads kept the cores.
//! The quality figures are
//! read from every engine's last run the same way: the watched top body's
//! sink and sideways drift, the fastest body at the end, and the deepest
//! overlap of any pair that can collide, computed from the final poses by
//! the same exact geometry for every engine; in a scene with joints, the largest joint
//! separation (how far apart the anchors a joint holds together are) and
//! the largest excess over a joint's limits, from the final poses through
//! the scene's joints ([`ManyBodyScene::joint_states`]), also the same for
//! every engine. After the repeats, separate profiled runs of this engine
//! and of the linked Box2D (at one thread, and at the larger count) say
//! where each one's step goes, stage by stage ([`super::stages`]); and,
//! where this engine misses a quality target, the probes of what would
//! close it ([`super::quality_probe`]).

use super::child::{self, ChildBuild};
use super::convert::many_body_scene;
use super::figures::Figures;
use super::ours::SoftStepEngine;
use super::quality_probe::{self, QualityProbe};
use super::scenes::BenchScene;
use super::stages::{self, StageComparison};
use super::targets::{QualityTarget, box2d_quality, rapier_quality};
use anyhow::{Context, Result, bail};
use references::box2d_world::Box2dWorld;
use references::box2d_world::build::Box2dBuild;
use references::many_body::{BodySample, ManyBodyEngine, ManyBodyScene};
use references::rapier_many::RapierManyWorld;
use scene::Scene;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// How many steps each run times.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Steps {
    /// The same count in every scene.
    Fixed(usize),
    /// Box2D's own count for the scene ([`BenchScene::box2d_steps`]):
    /// like Box2D's `benchmark/main.c`, which takes one untimed step and
    /// times the other `totalStepCount − 1`, the run takes step 0 untimed
    /// and times `box2d_steps − 1`.
    Box2d,
}

/// How long the benchmark runs, and what else it measures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchSettings {
    /// Timed steps per run (after the untimed step 0).
    pub steps: Steps,
    /// Runs per engine; the time is the minimum over them, with the median
    /// and the maximum.
    pub repeats: usize,
    /// Full sizes (`bench --full`): the scenes' full files.
    pub full: bool,
    /// Also Box2D's SSE2 build, from the child build ([`super::child`]).
    pub box2d_sse2: bool,
    /// Also Box2D's double-precision build, from the child build.
    pub box2d_double: bool,
    /// Also the peak memory of the large scenes ([`super::memory`]).
    pub memory: bool,
    /// Threads of the multi-threaded rows (this engine, rapier2d, Box2D
    /// again at this count); 1: the one-thread rows only.
    pub threads: usize,
    /// Whether a scene where this engine misses a quality target is run
    /// again to say what would close it ([`super::quality_probe`]).
    pub quality_probes: bool,
}

impl BenchSettings {
    /// The main run's (a short check that every engine runs every scene;
    /// `harness bench` is the benchmark): 120 timed steps (2 s of
    /// simulated time), 3 repeats, no extra builds, no memory runs.
    pub const DEFAULT: BenchSettings = BenchSettings {
        steps: Steps::Fixed(120),
        repeats: 3,
        full: false,
        box2d_sse2: false,
        box2d_double: false,
        memory: false,
        threads: 1,
        quality_probes: false,
    };
    /// `harness bench`: Box2D's step counts, 10 repeats, the peak memory of
    /// the large scenes, the quality probes.
    pub const BENCH: BenchSettings = BenchSettings {
        steps: Steps::Box2d,
        repeats: 10,
        full: false,
        box2d_sse2: false,
        box2d_double: false,
        memory: true,
        threads: 2,
        quality_probes: true,
    };
    /// `harness bench --full`: as [`Self::BENCH`] at the full sizes.
    pub const FULL: BenchSettings = BenchSettings {
        full: true,
        ..Self::BENCH
    };

    /// Timed steps per run of `scene`.
    pub fn timed_steps(&self, scene: &BenchScene) -> usize {
        match self.steps {
            Steps::Fixed(n) => n,
            Steps::Box2d => scene.box2d_steps.saturating_sub(1).max(1),
        }
    }
}

/// One engine on one scene: a row of `benchmarks.json`.
#[derive(Debug, Clone, Serialize)]
pub struct BenchRow {
    /// Scene id.
    pub scene: String,
    /// Engine name, with its build (precision, SIMD, C flags for Box2D).
    pub engine: String,
    /// Threads the engine steps with.
    pub threads: usize,
    /// Floating-point precision of the engine's state.
    pub precision: String,
    /// The SIMD path the engine takes on this CPU.
    pub simd: String,
    /// The engine's build flags (compiler settings, features).
    pub build: String,
    /// Bodies of the scene.
    pub bodies: usize,
    /// Timed steps per run.
    pub steps: usize,
    /// Runs timed.
    pub repeats: usize,
    /// Substeps per step.
    pub substeps: usize,
    /// Minimum over the repeats of the time per step (ms).
    pub ms_per_step_min: f64,
    /// Median over the repeats of the time per step (ms).
    pub ms_per_step_median: f64,
    /// Maximum over the repeats of the time per step (ms).
    pub ms_per_step_max: f64,
    /// This engine's minimum over this engine's (the project's) minimum
    /// at the same thread count.
    pub ratio_to_engine: f64,
    /// CPU time of the process (every thread, user and system) over the
    /// wall time of the timed steps, in the run that gave the minimum: 1
    /// for one busy thread, up to the thread count (a child build: not
    /// measured, 0).
    pub cpu_over_wall: f64,
    /// Pairs with contact points after the last step.
    pub touching_pairs: usize,
    /// Contact points after the last step.
    pub points: usize,
    /// The top body's descent below its starting height (m), if watched.
    pub top_sink: Option<f64>,
    /// The top body's sideways drift from its starting position (m).
    pub top_drift: Option<f64>,
    /// The largest dynamic body speed at the end (m/s).
    pub fastest_at_end: f64,
    /// The deepest overlap of any pair at the end (m), from the poses.
    pub deepest_overlap: f64,
    /// Joints of the scene.
    pub joints: usize,
    /// The largest separation of a joint's anchors at the end (m), from
    /// the poses; `None` without joints.
    pub joint_separation_max: Option<f64>,
    /// The largest excess of a joint's coordinate over its limits at the
    /// end (rad for a revolute joint), from the poses; `None` without
    /// joints.
    pub joint_limit_excess_max: Option<f64>,
    /// The engine's ms per step in each common stage of its profiled run
    /// ([`super::stages`]), for this engine's and the linked Box2D's rows
    /// when both were profiled at the row's thread count; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stages: Option<BTreeMap<String, f64>>,
    /// What would close each quality target this engine missed on the
    /// scene ([`super::quality_probe`]): on this engine's one-thread row,
    /// when the run probes ([`BenchSettings::quality_probes`]) and a
    /// quality target was missed; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quality_probe: Option<QualityProbe>,
}

/// The measurements of one scene.
#[derive(Debug, Clone)]
pub struct SceneResult {
    /// The scene.
    pub scene: BenchScene,
    /// One row per engine, in [`Contenders::list`]'s order: this engine,
    /// rapier2d, the linked Box2D (unless this CPU cannot run it), then the
    /// child builds asked for.
    pub rows: Vec<BenchRow>,
    /// This engine's time per phase (ms per step) from a separate
    /// profiled run, in the order of [`engine::StepProfile::phases`].
    pub profile: Vec<(&'static str, f64)>,
    /// This engine and the linked Box2D stage by stage, from their
    /// profiled runs ([`super::stages`]): at one thread, then at the run's
    /// larger thread count if it has one; empty when that Box2D is not
    /// measured (a CPU without its SIMD).
    pub stages: Vec<StageComparison>,
    /// Each engine's configuration paragraph.
    pub configurations: Vec<(String, String)>,
}

/// What the run of one engine leaves.
pub(super) struct Run {
    /// Wall time per timed step.
    pub(super) per_step: Duration,
    /// CPU time over wall time of the timed steps (0: not measured).
    cpu_over_wall: f64,
    /// The bodies' final states.
    pub(super) samples: Vec<BodySample>,
    touching: usize,
    points: usize,
}

/// Step 0 of `engine` untimed, then `steps` timed steps.
pub(super) fn run_engine(engine: &mut dyn ManyBodyEngine, steps: usize) -> Result<Run> {
    engine.step()?;
    let cpu = cpu_time()?;
    let started = Instant::now();
    for _ in 0..steps {
        engine.step()?;
    }
    let wall = started.elapsed();
    let cpu_over_wall = (cpu_time()? - cpu).as_secs_f64() / wall.as_secs_f64().max(1e-9);
    let per_step = wall / steps.max(1) as u32;
    let mut samples = Vec::new();
    engine.samples(&mut samples)?;
    let counts = engine.contact_counts()?;
    Ok(Run {
        per_step,
        cpu_over_wall,
        samples,
        touching: counts.touching_pairs,
        points: counts.points,
    })
}

/// The CPU time of this process so far, every thread, user and system
/// (`getrusage(RUSAGE_SELF)`).
fn cpu_time() -> Result<Duration> {
    // SAFETY: an all-zero `rusage` is a valid value of the plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `usage` is a valid, writable `rusage`.
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) } != 0 {
        bail!("getrusage: {}", std::io::Error::last_os_error());
    }
    let time = |t: libc::timeval| {
        Duration::from_secs(t.tv_sec.max(0) as u64) + Duration::from_micros(t.tv_usec.max(0) as u64)
    };
    Ok(time(usage.ru_utime) + time(usage.ru_stime))
}

/// An engine of the benchmark.
#[derive(Debug, Clone, PartialEq)]
pub enum Contender {
    /// This engine's soft step on this many threads.
    Ours(usize),
    /// rapier2d-f64 on this many threads.
    Rapier(usize),
    /// The Box2D linked into the harness, with this many workers.
    Box2d(usize),
    /// Another Box2D build, run as a child process (its binary).
    Child(ChildBuild, PathBuf),
}

impl Contender {
    /// The engine's name in messages.
    fn label(&self) -> String {
        match self {
            Contender::Ours(n) => format!("this engine on {n} thread(s)"),
            Contender::Rapier(n) => format!("rapier2d on {n} thread(s)"),
            Contender::Box2d(n) => {
                format!("{} with {n} worker(s)", Box2dBuild::linked().bench_name())
            }
            Contender::Child(build, _) => format!("Box2D's {} build", build.label()),
        }
    }

    /// The threads it runs on.
    pub fn threads(&self) -> usize {
        match self {
            Contender::Ours(n) | Contender::Rapier(n) | Contender::Box2d(n) => *n,
            Contender::Child(..) => 1,
        }
    }
}

/// The engines a benchmark runs, decided once before the scenes.
#[derive(Debug, Clone)]
pub struct Contenders {
    /// In row order.
    pub list: Vec<Contender>,
    /// Why an engine was left out (a CPU without the build's SIMD), printed
    /// and reported.
    pub notes: Vec<String>,
}

impl Contenders {
    /// This engine, rapier2d, the linked Box2D if this CPU runs it, and the
    /// child builds `settings` asks for (built here, before any timing).
    pub fn for_settings(settings: &BenchSettings) -> Result<Self> {
        let mut list = vec![Contender::Ours(1), Contender::Rapier(1)];
        let mut notes = Vec::new();
        let linked = Box2dBuild::linked();
        match linked.runnable() {
            Ok(()) => list.push(Contender::Box2d(1)),
            Err(why) => {
                let note = format!("{} left out: {why}", linked.bench_name());
                eprintln!("bench: {note}");
                notes.push(note);
            }
        }
        for (asked, build) in [
            (settings.box2d_sse2, ChildBuild::Sse2),
            (settings.box2d_double, ChildBuild::Double),
        ] {
            if asked {
                let (binary, seconds) = child::build(build)?;
                eprintln!(
                    "bench: Box2D's {} build ({}) built in {seconds:.0} s, before the timing",
                    build.label(),
                    binary.display()
                );
                list.push(Contender::Child(build, binary));
            }
        }
        // The multi-threaded rows after every one-thread row (the targets
        // and charts find the one-thread rows first).
        let n = settings.threads;
        if n > 1 {
            list.push(Contender::Ours(n));
            list.push(Contender::Rapier(n));
            if list.contains(&Contender::Box2d(1)) {
                list.push(Contender::Box2d(n));
            }
        }
        Ok(Self { list, notes })
    }
}

/// The build of an engine of this process, for its rows.
struct Build {
    name: String,
    configuration: String,
    precision: String,
    simd: String,
    flags: String,
}

/// The release profile's settings common to the Rust engines (the
/// workspace's Cargo.toml): opt-level 3, one codegen unit for the engine and
/// for rapier2d-f64's crates; the target's baseline features.
fn rust_flags() -> String {
    let mut features = vec!["sse2"];
    if cfg!(target_feature = "avx") {
        features.push("avx");
    }
    if cfg!(target_feature = "avx2") {
        features.push("avx2");
    }
    if cfg!(target_feature = "fma") {
        features.push("fma");
    }
    format!(
        "rustc {} profile, opt-level 3, codegen-units 1; target {} with {} at compile time",
        crate::provenance::profile(),
        std::env::consts::ARCH,
        features.join(", ")
    )
}

/// The build of `contender` (not a child: a child reports its own).
fn build_of(contender: &Contender, engine: &dyn ManyBodyEngine) -> Build {
    let configuration = engine.configuration();
    match contender {
        Contender::Ours(_) => Build {
            name: engine.name().to_string(),
            configuration,
            precision: "f64".into(),
            simd: engine::soft_step::lanes_in_use().into(),
            flags: format!("{}; AVX lanes chosen at run time", rust_flags()),
        },
        Contender::Rapier(n) => Build {
            name: engine.name().to_string(),
            configuration,
            precision: "f64".into(),
            simd: "scalar f64 (rapier2d-f64 0.36 has no SIMD option for f64)".into(),
            flags: format!(
                "{}; features dim2, f64, std, block-solver (its defaults) and parallel \
                 (stepped in a rayon pool of {n} thread(s)), enhanced-determinism off",
                rust_flags()
            ),
        },
        _ => {
            let b = Box2dBuild::linked();
            Build {
                name: b.bench_name(),
                configuration,
                precision: b.precision.into(),
                simd: b.simd_at_run_time(),
                flags: b.flags,
            }
        }
    }
}

/// The engine of `contender` on the scene (not a child).
fn build(
    contender: &Contender,
    scene: &Scene,
    neutral: &ManyBodyScene,
) -> Result<Box<dyn ManyBodyEngine>> {
    Ok(match contender {
        Contender::Ours(n) => Box::new(SoftStepEngine::with_threads(scene, false, *n)?),
        Contender::Rapier(n) => Box::new(RapierManyWorld::with_threads(neutral, *n)?),
        Contender::Box2d(n) => Box::new(Box2dWorld::with_workers(neutral, *n)?),
        Contender::Child(..) => bail!("a child build runs in its own process"),
    })
}

/// One run of `contender`, and its build on the first repeat.
fn run_once(
    contender: &Contender,
    bench: &BenchScene,
    file: &str,
    scene: &Scene,
    neutral: &ManyBodyScene,
    steps: usize,
    first: bool,
) -> Result<(Run, Option<Build>)> {
    if let Contender::Child(kind, binary) = contender {
        let child = child::run(binary, file, steps)?;
        if !kind.is_named(&child.name) {
            bail!(
                "{} reports the build {}, not Box2D's {} build",
                binary.display(),
                child.name,
                kind.label()
            );
        }
        let run = Run {
            per_step: Duration::from_secs_f64(child.ms_per_step / 1e3),
            cpu_over_wall: 0.0,
            samples: child.samples(),
            touching: child.touching,
            points: child.points,
        };
        if run.samples.len() != neutral.bodies.len() {
            bail!(
                "{} returned {} bodies for {} ({} expected)",
                child.name,
                run.samples.len(),
                bench.id,
                neutral.bodies.len()
            );
        }
        let built = first.then_some(Build {
            name: child.name,
            configuration: child.configuration,
            precision: child.precision,
            simd: child.simd,
            flags: child.flags,
        });
        return Ok((run, built));
    }
    let mut engine = build(contender, scene, neutral)?;
    let built = first.then(|| build_of(contender, engine.as_ref()));
    let run = run_engine(engine.as_mut(), steps)?;
    Ok((run, built))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Measures `bench` (loaded as `scene` from `file`, relative to the scenes
/// folder) under `settings`, with `contenders`.
pub fn measure(
    bench: BenchScene,
    file: &str,
    scene: &Scene,
    settings: BenchSettings,
    contenders: &Contenders,
) -> Result<SceneResult> {
    let neutral = many_body_scene(scene)?;
    let steps = settings.timed_steps(&bench);
    let n = contenders.list.len();
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); n];
    let mut cpu: Vec<(f64, f64)> = vec![(f64::INFINITY, 0.0); n];
    let mut last: Vec<Option<Run>> = (0..n).map(|_| None).collect();
    let mut builds: Vec<Option<Build>> = (0..n).map(|_| None).collect();
    for repeat in 0..settings.repeats.max(1) {
        // Rotated each repeat (the module documentation).
        for e in (0..n).map(|k| (k + repeat) % n) {
            let contender = &contenders.list[e];
            let (run, built) =
                run_once(contender, &bench, file, scene, &neutral, steps, repeat == 0)
                    .with_context(|| format!("{} on {}", contender.label(), bench.id))?;
            if let Some(b) = built {
                builds[e] = Some(b);
            }
            let ms = 1e3 * run.per_step.as_secs_f64();
            if ms < cpu[e].0 {
                cpu[e] = (ms, run.cpu_over_wall);
            }
            times[e].push(ms);
            last[e] = Some(run);
        }
    }
    let top = match bench.top {
        Some(name) => Some(
            scene
                .body_id(name)
                .with_context(|| format!("{}: no body '{name}' to watch", bench.id))?,
        ),
        None => None,
    };
    // This engine's minimum at each thread count.
    let ours = |threads: usize| {
        contenders
            .list
            .iter()
            .position(|c| *c == Contender::Ours(threads))
            .or_else(|| (threads != 1).then_some(0))
            .map_or(f64::NAN, |i| {
                times[i].iter().copied().fold(f64::INFINITY, f64::min)
            })
    };
    let mut rows = Vec::new();
    let mut configurations = Vec::new();
    for e in 0..n {
        let run = last[e].take().context("a run per engine")?;
        let built = builds[e].take().context("a build per engine")?;
        configurations.push((built.name.clone(), built.configuration.clone()));
        let min = times[e].iter().copied().fold(f64::INFINITY, f64::min);
        let max = times[e].iter().copied().fold(0.0, f64::max);
        let figures = Figures::of(&neutral, top, &run.samples);
        rows.push(BenchRow {
            scene: bench.id.to_string(),
            engine: built.name,
            threads: contenders.list[e].threads(),
            precision: built.precision,
            simd: built.simd,
            build: built.flags,
            bodies: neutral.bodies.len(),
            steps,
            repeats: times[e].len(),
            substeps: neutral.substeps,
            ms_per_step_min: min,
            ms_per_step_median: median(times[e].clone()),
            ms_per_step_max: max,
            ratio_to_engine: min / ours(contenders.list[e].threads()),
            cpu_over_wall: cpu[e].1,
            touching_pairs: run.touching,
            points: run.points,
            top_sink: figures.top_sink,
            top_drift: figures.top_drift,
            fastest_at_end: figures.fastest_at_end,
            deepest_overlap: figures.deepest_overlap,
            joints: neutral.joints.len(),
            joint_separation_max: figures.joint_separation_max,
            joint_limit_excess_max: figures.joint_limit_excess_max,
            stages: None,
            quality_probe: None,
        });
    }
    // Separate profiled runs: where this engine's time goes, and, with the
    // linked Box2D measured, where Box2D's goes, stage by stage, at one
    // thread and at the run's larger count; each engine's fastest of a few
    // runs, alternating ([`stages::PROFILED_REPEATS`]).
    let repeats = settings.repeats.clamp(1, stages::PROFILED_REPEATS);
    let counts = if settings.threads > 1 {
        vec![1, settings.threads]
    } else {
        vec![1]
    };
    let mut ours_one = None;
    let mut comparisons = Vec::new();
    for threads in counts {
        let with_box2d = contenders.list.contains(&Contender::Box2d(threads));
        if threads > 1 && !with_box2d {
            continue;
        }
        let (mut ours, mut box2d) = (None, None);
        for _ in 0..repeats {
            let run = stages::profile_ours(scene, steps, threads).with_context(|| {
                format!(
                    "this engine's profiled run of {} on {threads} thread(s)",
                    bench.id
                )
            })?;
            ours = Some(stages::faster(ours, run));
            if with_box2d {
                let run = stages::profile_box2d(&neutral, steps, threads).with_context(|| {
                    format!(
                        "Box2D's profiled run of {} with {threads} worker(s)",
                        bench.id
                    )
                })?;
                box2d = Some(stages::faster(box2d, run));
            }
        }
        if let (Some(o), Some(b)) = (&ours, &box2d) {
            comparisons.push(StageComparison::new(threads, o, b));
        }
        if threads == 1 {
            ours_one = ours;
        }
    }
    let profile = ours_one
        .context("this engine's profiled run at one thread")?
        .timers
        .into_iter()
        .filter(|(_, ms)| *ms > 0.0)
        .collect();
    for (row, contender) in rows.iter_mut().zip(&contenders.list) {
        let at = |t: usize| comparisons.iter().find(|c| c.threads == t);
        row.stages = match contender {
            Contender::Ours(t) => at(*t).map(|c| c.map(|s| s.ours_ms)),
            Contender::Box2d(t) => at(*t).map(|c| c.map(|s| s.box2d_ms)),
            _ => None,
        };
    }
    if settings.quality_probes {
        let misses: Vec<QualityTarget> = rapier_quality(bench.id, &rows)
            .into_iter()
            .chain(box2d_quality(&rows))
            .filter(|q| !q.met())
            .collect();
        let started = Instant::now();
        let probe = quality_probe::probe(scene, &neutral, top, steps, &rows, &misses)
            .with_context(|| format!("the quality probe of {}", bench.id))?;
        if probe.is_some() {
            eprintln!(
                "bench {}: quality probe {:.1} s",
                bench.id,
                started.elapsed().as_secs_f64()
            );
        }
        if let Some(ours) = rows.first_mut() {
            ours.quality_probe = probe;
        }
    }
    Ok(SceneResult {
        scene: bench,
        rows,
        profile,
        stages: comparisons,
        configurations,
    })
}
