//! What the collision cases (docs/cases.md case III, ids `collision_*`) share:
//! running a collision scene in the engine (with its contact events and
//! per-phase profile) and in rapier2d-f64, and the text form of contact
//! events for snapshots.

use crate::rapier_scene::rapier_body;
use crate::row::RowSink;
use crate::scenes;
use crate::snapshot::round_sig;
use anyhow::{Context, Result, bail};
use engine::{Body, BodyKind, ContactEvent, ContactEventKind, SoftStepSettings, Trace, World};
use nalgebra::Vector2;
use references::rapier_contacts::{
    RapierContactBody, RapierContactRun, RapierContactScene, run_contact_scene,
};
use references::rapier_world::RapierSettings;
use scene::Scene;
use scene::format::ForceSpec;
use std::fmt::Write as _;

/// Method id of rapier rows.
pub const RAPIER: &str = "rapier2d";

/// Method id of the rows of the engine's soft-step contact model (it
/// integrates by semi-implicit Euler per substep).
pub const SOFT_STEP: &str = "soft_step";

/// A collision scene run in the engine with the scene's own method.
pub struct EngineRun {
    /// The scene.
    pub scene: Scene,
    /// The world at the end of the run.
    pub world: World,
    /// The run's samples and located events.
    pub trace: Trace,
}

impl EngineRun {
    /// Contact events of one kind.
    pub fn events(&self, kind: ContactEventKind) -> Vec<ContactEvent> {
        self.world
            .contact_events()
            .into_iter()
            .filter(|e| e.kind == kind)
            .collect()
    }

    /// The id of body `name`.
    pub fn body(&self, name: &str) -> Result<usize> {
        self.scene
            .body_id(name)
            .with_context(|| format!("{}: no body '{name}'", self.scene.origin()))
    }

    /// A note on where the run spent its time (per phase, min of one run:
    /// indicative only).
    pub fn profile_note(&self, id: &str) -> String {
        let p = self.world.profile();
        format!(
            "`{id}` engine profile ({} build, one run): {} steps, {} candidate pairs, {} \
             time-of-impact/stick searches ({} evaluations), {} contact events; integrate {:.3} ms, \
             broad phase {:.3} ms, narrow phase {:.3} ms, time of impact {:.3} ms, respond {:.3} ms.",
            if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            },
            p.steps,
            p.candidate_pairs,
            p.toi_searches,
            p.toi_evaluations,
            self.world.contact_events().len(),
            1e3 * p.integrate.as_secs_f64(),
            1e3 * p.broad_phase.as_secs_f64(),
            1e3 * p.narrow_phase.as_secs_f64(),
            1e3 * p.toi.as_secs_f64(),
            1e3 * p.respond.as_secs_f64(),
        )
    }
}

/// Loads scene `id`, builds it with its own method and contact settings,
/// and runs it to its duration with per-phase profiling on.
pub fn run_engine(id: &str) -> Result<EngineRun> {
    let scene = scenes::load(id)?;
    let mut world = scene.build_world(None)?;
    if !world.has_contacts() {
        bail!("{id}: the scene runs no contacts (a [contact] table and two shapes are needed)");
    }
    world.set_profiling(true);
    let trace = world
        .run(scene.duration(), scene.dt())
        .with_context(|| format!("running {id}"))?;
    Ok(EngineRun {
        scene,
        world,
        trace,
    })
}

/// The soft-step model at its defaults for a collision scene: the scene's
/// restitution and friction become the bodies' own (the soft step mixes
/// per-body values; equal values mix to themselves), everything else is
/// [`SoftStepSettings::default`] (4 substeps, 30 Hz contacts, ζ = 10,
/// restitution threshold 1 m/s, speculative distance 0.02 m).
pub fn soft_step_settings(scene: &Scene) -> Result<SoftStepSettings> {
    let exact = exact_contact(scene)?;
    Ok(SoftStepSettings {
        restitution: exact.restitution,
        friction: exact.friction,
        ..SoftStepSettings::default()
    })
}

/// Loads collision scene `id` and runs it under the soft-step model at its
/// defaults ([`soft_step_settings`]), at the scene's step, with profiling
/// on.
pub fn run_soft_step(id: &str) -> Result<EngineRun> {
    let scene = scenes::load(id)?;
    let mut world = scene.build_world(Some(engine::Method::SemiImplicitEuler))?;
    world.set_contact_model(engine::ContactModel::SoftStep(soft_step_settings(&scene)?))?;
    world.set_profiling(true);
    let trace = world
        .run(scene.duration(), scene.dt())
        .with_context(|| format!("running {id} under the soft step"))?;
    Ok(EngineRun {
        scene,
        world,
        trace,
    })
}

/// The rows of the soft-step model of case `case` at the scene's step.
pub fn soft_step_sink<'a>(
    rows: &'a mut Vec<crate::row::Row>,
    case: &'a str,
    run: &EngineRun,
) -> RowSink<'a> {
    RowSink {
        case,
        method: SOFT_STEP,
        dt: run.scene.dt(),
        rows,
    }
}

/// The soft step's substep h = dt / substeps (s) of a run.
pub fn soft_substep(run: &EngineRun) -> f64 {
    match run.world.contact_model() {
        Some(engine::ContactModel::SoftStep(s)) => run.scene.dt() / s.substeps as f64,
        _ => run.scene.dt(),
    }
}

/// The rapier description of a collision scene: its bodies with their
/// shapes, mass and inertia (as the engine computes them from the file),
/// gravity, restitution and friction. Other forces are refused.
pub fn rapier_scene(scene: &Scene) -> Result<RapierContactScene> {
    let mut bodies = Vec::new();
    for def in scene.bodies() {
        let (body, state): (Body, _) = Body::from_def(def)?;
        let shape = body
            .shape
            .clone()
            .with_context(|| format!("body '{}' has no shape", body.name))?;
        bodies.push(match body.kind {
            BodyKind::Static => RapierContactBody::Fixed {
                position: [state.position.x, state.position.y],
                angle: state.angle,
                shape,
            },
            BodyKind::Dynamic => RapierContactBody::Dynamic {
                body: rapier_body(&body, &state),
                shape,
            },
            BodyKind::Kinematic => bail!(
                "{}: kinematic body '{}' has no counterpart in the rapier collision scenes",
                scene.origin(),
                body.name
            ),
        });
    }
    let mut gravity = [0.0, 0.0];
    for f in &scene.file().forces {
        match f {
            ForceSpec::Gravity { g, window: None } => {
                gravity[0] += g.x;
                gravity[1] += g.y;
            }
            other => bail!(
                "{}: a force of type '{}' has no counterpart in the rapier collision scenes \
                 (only gravity without a window has)",
                scene.origin(),
                force_type(other)
            ),
        }
    }
    let contact = exact_contact(scene)?;
    Ok(RapierContactScene {
        bodies,
        gravity,
        restitution: contact.restitution,
        friction: contact.friction,
    })
}

/// The exact model's settings of a collision scene's `[contact]` table.
pub fn exact_contact(scene: &Scene) -> Result<engine::ContactSettings> {
    match scene.contact() {
        Some(engine::ContactModel::Exact(settings)) => Ok(settings),
        Some(other) => bail!(
            "{}: [contact] model = \"{}\", expected \"exact\"",
            scene.origin(),
            other.id()
        ),
        None => bail!("{}: no [contact] table", scene.origin()),
    }
}

/// The `type` of a force as the scene file writes it.
fn force_type(force: &ForceSpec) -> &'static str {
    match force {
        ForceSpec::Gravity { .. } => "gravity",
        ForceSpec::Spring { .. } => "spring",
        ForceSpec::Drag { .. } => "drag",
        ForceSpec::AngularDrag { .. } => "angular_drag",
        ForceSpec::PointForce { .. } => "point_force",
        ForceSpec::Torque { .. } => "torque",
    }
}

/// rapier's step for a scene: the scene's dt, rapier's default 4 substeps.
pub fn rapier_settings(scene: &Scene) -> RapierSettings {
    RapierSettings::new(scene.dt())
}

/// Runs scene `scene` in rapier over its duration.
pub fn run_rapier(scene: &Scene) -> Result<RapierContactRun> {
    let r = rapier_scene(scene)?;
    Ok(run_contact_scene(
        &r,
        &rapier_settings(scene),
        scene.duration(),
    )?)
}

/// Kinetic energy ½ m v² + ½ I ω² of every dynamic body of `bodies` in
/// `states` (J).
pub fn kinetic_energy(bodies: &[Body], states: &[engine::BodyState]) -> f64 {
    bodies
        .iter()
        .zip(states)
        .map(|(b, s)| b.kinetic_energy(s))
        .sum()
}

/// A row of rapier beside the engine: `|rapier − expected| ≤ bound`, where
/// `bound` is a documented property of rapier's contact model (its
/// soft-contact or step quantisation), not an accuracy goal.
#[allow(clippy::too_many_arguments)]
pub fn rapier_row(
    kind: crate::row::RowKind,
    rows: &mut Vec<crate::row::Row>,
    case: &str,
    dt: f64,
    check: &str,
    value: f64,
    expected: f64,
    bound: f64,
    reason: impl Into<String>,
) {
    RowSink {
        case,
        method: RAPIER,
        dt,
        rows,
    }
    .within(kind, check, value, expected, bound, reason);
}

/// Relative size of the round-off of the few operations that compute an
/// impulse and the velocities after it from O(1) numbers (a dozen roundings
/// of 1.1e-16): 1e-12 is docs/cases.md's bound and sits four orders above.
pub const IMPULSE_ROUND_OFF: f64 = 1e-12;

/// docs/cases.md: the stopping distance and the incline's acceleration within
/// 1e-6 relative of their closed forms.
pub const CLOSED_FORM_RELATIVE: f64 = 1e-6;

/// docs/cases.md: a box that must not move moves less than 1e-9 m in 10 s.
pub const STILL: f64 = 1e-9;

/// The magnitude of the scene's gravity (m/s²).
pub fn gravity(run: &EngineRun) -> Result<f64> {
    run.scene
        .file()
        .forces
        .iter()
        .find_map(|f| match f {
            ForceSpec::Gravity { g, .. } => Some(g.vector().norm()),
            _ => None,
        })
        .context("the scene has no gravity")
}

/// The scene's friction coefficient μ (from its `[contact]` table).
pub fn friction(run: &EngineRun) -> Result<f64> {
    Ok(exact_contact(&run.scene)?.friction)
}

/// Largest distance (m) of the body from where it was at `t_from` (s) over
/// the rest of the run, in the engine's samples.
pub fn engine_motion_after(run: &EngineRun, body: usize, t_from: f64) -> f64 {
    let start = run
        .trace
        .samples
        .iter()
        .find(|s| s.t >= t_from)
        .map(|s| s.states[body].position);
    start.map_or(f64::NAN, |p0| {
        run.trace
            .samples
            .iter()
            .filter(|s| s.t >= t_from)
            .map(|s| (s.states[body].position - p0).norm())
            .fold(0.0, f64::max)
    })
}

/// Position (m) of body `body` at rapier2d's sample `k`.
pub fn rapier_position(run: &RapierContactRun, k: usize, body: usize) -> Vector2<f64> {
    let p = run.samples[k][body].position;
    Vector2::new(p[0], p[1])
}

/// Coordinates (m) under this print as 0 in event snapshots: a contact
/// point lies midway between surfaces that may be up to ε = 1e-10 m apart
/// when the time of impact is located, so its last digits below ~1e-9 m
/// are the search's residual, not physics.
pub const POINT_FLOOR: f64 = 1e-9;

/// Impulses (N·s) under this print as 0: those that cancel a round-off
/// approach speed at a resting contact.
pub const IMPULSE_FLOOR: f64 = 1e-12;

fn floored(v: f64, floor: f64) -> String {
    if v.abs() < floor {
        "0".into()
    } else {
        round_sig(v)
    }
}

/// The contact events as text for snapshots: one line per event with its
/// time, kind, bodies, point, normal and impulses, numbers rounded to
/// significant digits (`crate::snapshot`), points and normals under
/// [`POINT_FLOOR`] and impulses under [`IMPULSE_FLOOR`] as 0.
pub fn render_contact_events(scene: &Scene, events: &[ContactEvent]) -> String {
    let names = scene.body_names();
    let mut out = String::from(
        "t\tkind\tbody_a\tbody_b\tpoints\tpoint_x\tpoint_y\tnormal_x\tnormal_y\tnormal_impulse\ttangent_impulse\n",
    );
    for e in events {
        let _ = writeln!(
            out,
            "{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}",
            round_sig(e.t),
            e.kind.id(),
            names[e.body_a],
            names[e.body_b],
            e.points,
            floored(e.point.x, POINT_FLOOR),
            floored(e.point.y, POINT_FLOOR),
            floored(e.normal.x, POINT_FLOOR),
            floored(e.normal.y, POINT_FLOOR),
            floored(e.normal_impulse, IMPULSE_FLOOR),
            floored(e.tangent_impulse, IMPULSE_FLOOR),
        );
    }
    out
}

/// At most `head` events, then the last `tail`, with a line saying how many
/// were left out (a 100-bounce run has 100 impacts).
pub fn thin_events(
    events: &[ContactEvent],
    head: usize,
    tail: usize,
) -> (Vec<ContactEvent>, usize) {
    if events.len() <= head + tail {
        return (events.to_vec(), 0);
    }
    let mut kept = events[..head].to_vec();
    kept.extend_from_slice(&events[events.len() - tail..]);
    (kept, events.len() - head - tail)
}
