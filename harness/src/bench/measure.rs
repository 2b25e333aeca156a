//! One benchmark scene in the three engines, run alternately in this
//! process (Box2D's protocol): for each repeat, each engine builds the scene
//! afresh, takes step 0 untimed, then the timed steps; the time per step is
//! the minimum (and the median) over the repeats. The quality figures are
//! read from every engine's last run the same way: the watched top body's
//! sink and sideways drift, the fastest body at the end, and the deepest
//! overlap of any pair that can collide, computed from the final poses by
//! the same exact geometry for every engine; in a scene with joints, the largest joint
//! separation (how far apart the anchors a joint holds together are) and
//! the largest excess over a joint's limits, from the final poses through
//! the scene's joints ([`ManyBodyScene::joint_states`]), also the same for
//! every engine.

use super::convert::many_body_scene;
use super::ours::SoftStepEngine;
use super::scenes::BenchScene;
use anyhow::{Context, Result};
use references::box2d_world::Box2dWorld;
use references::many_body::{BodySample, JointState, ManyBodyEngine, ManyBodyScene};
use references::rapier_many::RapierManyWorld;
use scene::Scene;
use serde::Serialize;
use std::time::{Duration, Instant};

/// How long the benchmark runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchSettings {
    /// Timed steps per run (after the untimed step 0).
    pub steps: usize,
    /// Runs per engine; the time is the minimum over them.
    pub repeats: usize,
    /// Full sizes (`bench --full`): the scenes' full files.
    pub full: bool,
}

impl BenchSettings {
    /// The main run's: 120 timed steps (2 s of simulated time), 3 repeats.
    pub const DEFAULT: BenchSettings = BenchSettings {
        steps: 120,
        repeats: 3,
        full: false,
    };
    /// `bench --full`: 500 timed steps, 3 repeats, full-size scenes.
    pub const FULL: BenchSettings = BenchSettings {
        steps: 500,
        repeats: 3,
        full: true,
    };
}

/// One engine on one scene: a row of `benchmarks.json`.
#[derive(Debug, Clone, Serialize)]
pub struct BenchRow {
    /// Scene id.
    pub scene: String,
    /// Engine name.
    pub engine: String,
    /// Bodies of the scene.
    pub bodies: usize,
    /// Timed steps per run.
    pub steps: usize,
    /// Substeps per step.
    pub substeps: usize,
    /// Minimum over the repeats of the time per step (ms).
    pub ms_per_step_min: f64,
    /// Median over the repeats of the time per step (ms).
    pub ms_per_step_median: f64,
    /// This engine's minimum over this engine's (the project's) minimum.
    pub ratio_to_engine: f64,
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
}

/// The measurements of one scene.
#[derive(Debug, Clone)]
pub struct SceneResult {
    /// The scene.
    pub scene: BenchScene,
    /// One row per engine: this engine, rapier2d, Box2D.
    pub rows: Vec<BenchRow>,
    /// This engine's time per phase (ms per step) from a separate
    /// profiled run, in the order of [`engine::StepProfile::phases`].
    pub profile: Vec<(&'static str, f64)>,
    /// Each engine's configuration paragraph.
    pub configurations: Vec<(String, String)>,
}

/// What the run of one engine leaves.
struct Run {
    per_step: Duration,
    samples: Vec<BodySample>,
    touching: usize,
    points: usize,
}

fn run_engine(engine: &mut dyn ManyBodyEngine, steps: usize) -> Result<Run> {
    engine.step()?;
    let started = Instant::now();
    for _ in 0..steps {
        engine.step()?;
    }
    let per_step = started.elapsed() / steps.max(1) as u32;
    let mut samples = Vec::new();
    engine.samples(&mut samples)?;
    let counts = engine.contact_counts()?;
    Ok(Run {
        per_step,
        samples,
        touching: counts.touching_pairs,
        points: counts.points,
    })
}

/// The engine `index` (0 this engine, 1 rapier2d, 2 Box2D) on the scene.
fn build(index: usize, scene: &Scene, neutral: &ManyBodyScene) -> Result<Box<dyn ManyBodyEngine>> {
    Ok(match index {
        0 => Box::new(SoftStepEngine::new(scene, false)?),
        1 => Box::new(RapierManyWorld::new(neutral)?),
        _ => Box::new(Box2dWorld::new(neutral)?),
    })
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

/// Measures `bench` (loaded as `scene`) under `settings`.
pub fn measure(bench: BenchScene, scene: &Scene, settings: BenchSettings) -> Result<SceneResult> {
    let neutral = many_body_scene(scene)?;
    let mut times: [Vec<f64>; 3] = Default::default();
    let mut last: Vec<Option<Run>> = vec![None, None, None];
    let mut configurations = Vec::new();
    let mut names = [String::new(), String::new(), String::new()];
    for repeat in 0..settings.repeats {
        for e in 0..3 {
            let mut engine = build(e, scene, &neutral)
                .with_context(|| format!("building {} for engine {e}", bench.id))?;
            if repeat == 0 {
                names[e] = engine.name().to_string();
                configurations.push((engine.name().to_string(), engine.configuration()));
            }
            let run = run_engine(engine.as_mut(), settings.steps)
                .with_context(|| format!("{} on {}", names[e], bench.id))?;
            times[e].push(1e3 * run.per_step.as_secs_f64());
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
    let ours = times[0].iter().copied().fold(f64::INFINITY, f64::min);
    let mut rows = Vec::new();
    for e in 0..3 {
        let run = last[e].take().context("a run per engine")?;
        let min = times[e].iter().copied().fold(f64::INFINITY, f64::min);
        let (sink, drift) = match top {
            Some(i) => {
                let start = neutral.bodies[i].position;
                let end = run.samples[i].position;
                (Some(start[1] - end[1]), Some((end[0] - start[0]).abs()))
            }
            None => (None, None),
        };
        let fastest = neutral
            .bodies
            .iter()
            .zip(&run.samples)
            .filter(|(b, _)| b.kind == references::many_body::BodyKind::Dynamic)
            .map(|(_, s)| s.speed())
            .fold(0.0, f64::max);
        let overlap = neutral
            .deepest_overlap(&run.samples)
            .map_or(0.0, |o| o.depth);
        let joints = neutral.joint_states(&run.samples);
        let largest = |f: fn(&JointState) -> f64| {
            (!joints.is_empty()).then(|| joints.iter().map(f).fold(0.0, f64::max))
        };
        rows.push(BenchRow {
            scene: bench.id.to_string(),
            engine: names[e].clone(),
            bodies: neutral.bodies.len(),
            steps: settings.steps,
            substeps: neutral.substeps,
            ms_per_step_min: min,
            ms_per_step_median: median(times[e].clone()),
            ratio_to_engine: min / ours,
            touching_pairs: run.touching,
            points: run.points,
            top_sink: sink,
            top_drift: drift,
            fastest_at_end: fastest,
            deepest_overlap: overlap,
            joints: neutral.joints.len(),
            joint_separation_max: largest(|j| j.separation),
            joint_limit_excess_max: largest(|j| j.limit_violation),
        });
    }
    // A separate profiled run of this engine: where its time goes.
    let mut profiled = SoftStepEngine::new(scene, true)?;
    profiled.step()?;
    let before = profiled.world().profile();
    for _ in 0..settings.steps {
        profiled.step()?;
    }
    let after = profiled.world().profile();
    let n = settings.steps.max(1) as f64;
    let profile = after
        .phases()
        .iter()
        .zip(before.phases().iter())
        .map(|((name, a), (_, b))| (*name, 1e3 * (a.as_secs_f64() - b.as_secs_f64()) / n))
        .filter(|(_, ms)| *ms > 0.0)
        .collect();
    Ok(SceneResult {
        scene: bench,
        rows,
        profile,
        configurations,
    })
}
