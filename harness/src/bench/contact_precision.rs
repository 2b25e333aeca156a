//! What a contact model's accuracy costs: on the validation contact cases
//! (`docs/cases.md`: the e = 1 bounce, the slide to a stop, the resting box,
//! the incline slide), the error against the closed form against the wall
//! time of the run, for the exact model, the soft step at 1 to 32
//! substeps, rapier2d at 1 to 32 substeps and Box2D at 1 to 32 substeps —
//! the chart none of the three engines publishes.
//!
//! Every engine runs the same scene file at its step (0.01 s) and is read
//! the same way, from its state after every step. rapier2d and Box2D run at
//! their defaults (the benchmark's configuration, `references::rapier_many`
//! and `references::box2d_world`) with the scene's friction and restitution.
//! The time is the minimum over [`REPEATS`] runs of the whole scene.

use super::measure::BenchSettings;
use super::ours::SoftStepEngine;
use crate::plots::bench::engine_style;
use crate::plots::{Chart, Series, palette, save_svg};
use anyhow::{Context, Result, bail};
use engine::{Body, BodyKind, ContactModel, Method, SoftStepSettings};
use references::box2d_world::Box2dWorld;
use references::many_body::{self, BodySample, ManyBodyEngine, ManyBodyScene, SceneBody};
use references::rapier_many::RapierManyWorld;
use scene::Scene;
use scene::format::ForceSpec;
use std::path::Path;
use std::time::Instant;

/// Runs per configuration; the time is the minimum.
pub const REPEATS: usize = 3;

/// Substep counts swept for the soft step, rapier2d and Box2D.
pub const SUBSTEPS: [usize; 6] = [1, 2, 4, 8, 16, 32];

/// One configuration's point: wall time (s) and error (in the case's unit).
#[derive(Debug, Clone)]
pub struct Point {
    /// Model or engine: `exact`, `soft_step`, `rapier2d`, `Box2D`.
    pub model: &'static str,
    /// Substeps (1 for the exact model).
    pub substeps: usize,
    /// Wall time of the run (s), the minimum over the repeats.
    pub seconds: f64,
    /// Error against the closed form.
    pub error: f64,
}

/// One case's points.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// Case id (the scene's).
    pub case: &'static str,
    /// What the error measures, with its unit.
    pub error_label: &'static str,
    /// The points.
    pub points: Vec<Point>,
}

/// A validation contact case of the study.
struct Case {
    scene: &'static str,
    error_label: &'static str,
    /// Simulated time (s).
    duration: f64,
    /// The error of a run from its samples after every step (the first is
    /// t = 0), given the scene.
    error: fn(&Scene, &[Vec<BodySample>]) -> Result<f64>,
}

const CASES: [Case; 4] = [
    Case {
        scene: "collision_bounce",
        error_label: "apex loss per bounce over 5 bounces, e = 1 (-)",
        duration: 4.6,
        error: bounce_error,
    },
    Case {
        scene: "collision_slide",
        error_label: "|stopping distance − v0²/(2 mu g)| (m)",
        duration: 2.0,
        error: slide_error,
    },
    Case {
        scene: "collision_rest",
        error_label: "|displacement of the resting box after 2 s| (m)",
        duration: 2.0,
        error: rest_error,
    },
    Case {
        scene: "collision_incline_slide",
        error_label: "|acceleration − g (sin θ − mu cos θ)| (m/s²)",
        duration: 2.0,
        error: incline_error,
    },
];

fn gravity(scene: &Scene) -> Result<f64> {
    scene
        .file()
        .forces
        .iter()
        .find_map(|f| match f {
            ForceSpec::Gravity { g, .. } => Some(g.vector().norm()),
            _ => None,
        })
        .context("the scene has no gravity")
}

fn body(scene: &Scene, name: &str) -> Result<usize> {
    scene
        .body_id(name)
        .with_context(|| format!("{}: no body '{name}'", scene.origin()))
}

/// Apexes (the ball's bottom above the ground's top) from the samples: at
/// each step where vy turns from > 0 to ≤ 0, y + vy²/(2g).
fn bounce_error(scene: &Scene, s: &[Vec<BodySample>]) -> Result<f64> {
    let ball = body(scene, "ball")?;
    let g = gravity(scene)?;
    let (radius, h0) = (0.1, 1.0);
    let apexes: Vec<f64> = (0..s.len() - 1)
        .filter(|&k| s[k][ball].velocity[1] > 0.0 && s[k + 1][ball].velocity[1] <= 0.0)
        .map(|k| {
            let b = &s[k][ball];
            b.position[1] + b.velocity[1].powi(2) / (2.0 * g) - radius
        })
        .collect();
    if apexes.len() < 5 {
        return Ok(1.0);
    }
    Ok((1.0 - (apexes[4] / h0).powf(0.2)).abs())
}

fn contact_friction(scene: &Scene) -> Result<f64> {
    match scene.contact() {
        Some(ContactModel::Exact(c)) => Ok(c.friction),
        _ => bail!("{}: not an exact-model scene", scene.origin()),
    }
}

fn slide_error(scene: &Scene, s: &[Vec<BodySample>]) -> Result<f64> {
    let b = body(scene, "box")?;
    let (g, mu) = (gravity(scene)?, contact_friction(scene)?);
    let v0 = s[0][b].velocity[0];
    let travelled = s[s.len() - 1][b].position[0] - s[0][b].position[0];
    Ok((travelled - v0 * v0 / (2.0 * mu * g)).abs())
}

fn rest_error(scene: &Scene, s: &[Vec<BodySample>]) -> Result<f64> {
    let b = body(scene, "box")?;
    let (p0, p1) = (s[0][b].position, s[s.len() - 1][b].position);
    Ok((p1[0] - p0[0]).hypot(p1[1] - p0[1]))
}

fn incline_error(scene: &Scene, s: &[Vec<BodySample>]) -> Result<f64> {
    let b = body(scene, "box")?;
    let (g, mu) = (gravity(scene)?, contact_friction(scene)?);
    let theta = scene.bodies()[b].state.angle;
    let a = g * (theta.sin() - mu * theta.cos());
    // Between t = 1 s and the end, past the contacts' settling.
    let k1 = (s.len() - 1) / 2;
    let down = [-theta.cos(), -theta.sin()];
    let along = |v: [f64; 2]| v[0] * down[0] + v[1] * down[1];
    let dt = scene.dt();
    let measured = (along(s[s.len() - 1][b].velocity) - along(s[k1][b].velocity))
        / ((s.len() - 1 - k1) as f64 * dt);
    Ok((measured - a).abs())
}

/// The collision scene as the reference engines take it, with `substeps`.
fn neutral(scene: &Scene, substeps: usize) -> Result<ManyBodyScene> {
    let (e, mu) = match scene.contact() {
        Some(ContactModel::Exact(c)) => (c.restitution, c.friction),
        _ => bail!("{}: not an exact-model scene", scene.origin()),
    };
    let bodies = scene
        .bodies()
        .iter()
        .map(|def| {
            let (b, s) = Body::from_def(def)?;
            let shape = b.shape.clone().context("a collision body has a shape")?;
            let dynamic = b.kind == BodyKind::Dynamic;
            Ok(SceneBody {
                kind: if dynamic {
                    many_body::BodyKind::Dynamic
                } else {
                    many_body::BodyKind::Static
                },
                density: if dynamic { b.mass / shape.area() } else { 0.0 },
                shape,
                position: [s.position.x, s.position.y],
                angle: s.angle,
                velocity: [s.velocity.x, s.velocity.y],
                angular_velocity: s.angular_velocity,
                friction: mu,
                restitution: e,
                collision_group: None,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(ManyBodyScene {
        gravity: [0.0, -gravity(scene)?],
        dt: scene.dt(),
        substeps,
        bodies,
        joints: Vec::new(),
    })
}

/// The engine of `model` on `scene` with `substeps`.
fn build(model: &str, scene: &Scene, substeps: usize) -> Result<Box<dyn ManyBodyEngine>> {
    Ok(match model {
        "exact" => Box::new(SoftStepEngine::from_world(
            scene.build_world(None)?,
            scene.dt(),
            false,
        )?),
        "soft_step" => {
            let (e, mu) = match scene.contact() {
                Some(ContactModel::Exact(c)) => (c.restitution, c.friction),
                _ => bail!("{}: not an exact-model scene", scene.origin()),
            };
            let mut world = scene.build_world(Some(Method::SemiImplicitEuler))?;
            world.set_contact_model(ContactModel::SoftStep(SoftStepSettings {
                substeps,
                restitution: e,
                friction: mu,
                ..SoftStepSettings::default()
            }))?;
            Box::new(SoftStepEngine::from_world(world, scene.dt(), false)?)
        }
        "rapier2d" => Box::new(RapierManyWorld::new(&neutral(scene, substeps)?)?),
        _ => Box::new(Box2dWorld::new(&neutral(scene, substeps)?)?),
    })
}

/// One run: samples after every step, and its wall time (s).
fn run_once(
    model: &str,
    scene: &Scene,
    substeps: usize,
    duration: f64,
) -> Result<(Vec<Vec<BodySample>>, f64)> {
    let mut engine = build(model, scene, substeps)?;
    let steps = (duration / scene.dt()).round() as usize;
    let mut samples = Vec::with_capacity(steps + 1);
    let mut buffer = Vec::new();
    engine.samples(&mut buffer)?;
    samples.push(buffer.clone());
    let mut seconds = 0.0;
    for _ in 0..steps {
        let started = Instant::now();
        engine.step()?;
        seconds += started.elapsed().as_secs_f64();
        engine.samples(&mut buffer)?;
        samples.push(buffer.clone());
    }
    Ok((samples, seconds))
}

/// Runs the study.
pub fn run(_settings: BenchSettings) -> Result<Vec<CaseResult>> {
    let mut out = Vec::new();
    for case in &CASES {
        let scene = crate::scenes::load(case.scene)?;
        let mut points = Vec::new();
        let configurations = std::iter::once(("exact", 1)).chain(
            ["soft_step", "rapier2d", "Box2D"]
                .into_iter()
                .flat_map(|m| SUBSTEPS.iter().map(move |&s| (m, s))),
        );
        for (model, substeps) in configurations {
            let mut best = f64::INFINITY;
            let mut error = f64::NAN;
            for _ in 0..REPEATS {
                let (samples, seconds) = run_once(model, &scene, substeps, case.duration)
                    .with_context(|| format!("{model} ({substeps} substeps) on {}", case.scene))?;
                best = best.min(seconds);
                error = (case.error)(&scene, &samples)?;
            }
            points.push(Point {
                model,
                substeps,
                seconds: best,
                error,
            });
        }
        out.push(CaseResult {
            case: case.scene,
            error_label: case.error_label,
            points,
        });
    }
    Ok(out)
}

/// The chart: one panel per case, error against the run's wall time, a
/// series per model (substeps along it); returns its file name and
/// caption. An error of exactly 0 (the exact model on the resting box) is
/// drawn in the band labelled 0 under the log axis.
pub fn chart(dir: &Path, results: &[CaseResult]) -> Result<(String, String)> {
    let styles = [
        ("exact", palette(3)),
        ("soft_step", engine_style(0)),
        ("rapier2d", engine_style(1)),
        ("Box2D", engine_style(2)),
    ];
    let panels: Vec<Chart> = results
        .iter()
        .map(|r| Chart {
            title: r.case.to_string(),
            x_label: format!("wall time of the run (s), min of {REPEATS} runs"),
            y_label: r.error_label.to_string(),
            log_x: true,
            log_y: true,
            series: styles
                .iter()
                .map(|(model, style)| {
                    let label = if *model == "exact" {
                        "exact model (rk4)".to_string()
                    } else {
                        format!("{model}, 1 to 32 substeps")
                    };
                    Series::new(
                        label,
                        *style,
                        r.points
                            .iter()
                            .filter(|p| p.model == *model)
                            .map(|p| (p.seconds, p.error))
                            .collect(),
                    )
                })
                .collect(),
            y_range: None,
        })
        .collect();
    let file = "contact_work_precision.svg";
    save_svg(&dir.join(file), &panels, 2, (640, 420))?;
    Ok((
        file.to_string(),
        "contact work-precision: error against the closed form vs the run's wall time, per model and engine"
            .to_string(),
    ))
}
