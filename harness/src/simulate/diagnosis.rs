//! Why a run failed, in terms the user can act on: the engine's error says
//! what happened (a step size underflow, a blow-up); this says which part
//! of the scene is the likely cause and what to change.
//!
//! - **Step size underflow** (`dormand_prince`): the adaptive step shrank
//!   to nothing, the mark of a stiff problem. Each force that can make a
//!   problem stiff gets a rate (1/s), the largest eigenvalue magnitude of
//!   its Jacobian at the state where the run stopped: quadratic drag
//!   2·D·|v|/m (with |v| at least the speed gravity gives in one `dt`, since
//!   a run that fails at rest fails on the speed of its first trial steps),
//!   angular drag 2·D·|ω|/I, a spring √(k/m). An explicit method needs
//!   steps below a few times 1/rate to stay stable: the force with the
//!   largest rate · dt is named.
//! - **Blow-up of the energy**: the state is finite but the energy is not.
//!   After the energy grew by orders of magnitude over many steps (more
//!   than [`UNSTABLE_GROWTH`] times its size at t = 0 when the failed step
//!   began), the method is unstable at this step: the step is blamed.
//!   Otherwise (the first step, or a scene whose numbers are already
//!   huge) the scene's magnitudes are, and the fastest body is named.
//! - **Blow-up of the state**: the method is unstable at this step.

use engine::error::readable;
use engine::{EngineError, World};
use scene::Scene;
use scene::format::ForceSpec;

/// The energy's growth (its size when the failed step began over its size
/// at t = 0) beyond which a blow-up is blamed on the method's instability
/// at this step rather than on the scene's magnitudes: six orders of
/// magnitude, far beyond what an accurate run does (energy drifts by
/// fractions) and what a stable but coarse one does, and reached only by
/// geometric growth.
pub const UNSTABLE_GROWTH: f64 = 1e6;

/// A step that failed, counted as the header counts them (from 1 to
/// `steps`), said once: the engine's error inside it numbers steps from
/// 0, so its own text is not repeated.
#[derive(Debug)]
pub struct StepFailed {
    /// The step that failed, from 1.
    pub step: u64,
    /// The run's steps.
    pub steps: u64,
    /// Time at the start of the failed step (s).
    pub t: f64,
    /// The engine's error.
    pub error: EngineError,
}

impl std::fmt::Display for StepFailed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (step, steps, t) = (self.step, self.steps, readable(self.t));
        match &self.error {
            EngineError::BlowUp { reason, .. } => write!(
                f,
                "the run failed in step {step} of {steps} (the step from t = {t} s): blow-up: {reason}"
            ),
            other => write!(
                f,
                "the run failed in step {step} of {steps} (t = {t} s): {other}"
            ),
        }
    }
}

impl std::error::Error for StepFailed {}

/// The engine's `error` in step `step` of `steps`, the world standing at
/// `t` (s) when it was refused.
pub(super) fn step_failed(error: EngineError, step: u64, steps: u64, t: f64) -> anyhow::Error {
    anyhow::Error::new(StepFailed {
        step,
        steps,
        t,
        error,
    })
}

/// `error` with a hint appended when its cause can be told.
pub(super) fn explain(
    error: anyhow::Error,
    scene: &Scene,
    world: &World,
    dt: f64,
) -> anyhow::Error {
    let failed = error.downcast_ref::<StepFailed>();
    let engine_error = failed
        .map(|f| &f.error)
        .or_else(|| error.downcast_ref::<EngineError>());
    let hint = match engine_error {
        Some(EngineError::StepSizeUnderflow { .. }) => Some(stiffness_hint(scene, world, dt)),
        Some(EngineError::BlowUp { reason, .. }) if reason.contains("energy") => Some(
            unstable_hint(scene, world, dt, failed.map_or(1, |f| f.step))
                .unwrap_or_else(|| energy_hint(scene, world)),
        ),
        Some(EngineError::BlowUp { .. }) => Some(format!(
            "{} is unstable with this step: use a smaller dt or --method implicit_euler",
            world.method().id()
        )),
        _ => None,
    };
    match hint {
        // After the cause, which anyhow's context would put it before.
        Some(hint) => anyhow::anyhow!("{error:#}\nhint: {hint}"),
        None => error,
    }
}

/// A stiff force and its rate (1/s).
struct Stiff {
    index: usize,
    what: String,
    rate: f64,
}

fn stiffness_hint(scene: &Scene, world: &World, dt: f64) -> String {
    let gravity: f64 = scene
        .file()
        .forces
        .iter()
        .map(|f| match f {
            ForceSpec::Gravity { g, .. } => g.vector().norm(),
            _ => 0.0,
        })
        .sum();
    let bodies = world.bodies();
    let states = world.states();
    let mut candidates: Vec<Stiff> = Vec::new();
    for (index, force) in scene.file().forces.iter().enumerate() {
        let id = |name: &str| scene.body_id(name);
        let stiff = match force {
            ForceSpec::Drag {
                body, coefficient, ..
            } => id(body).map(|i| {
                let speed = states[i].velocity.norm().max(gravity * dt);
                Stiff {
                    index,
                    what: format!(
                        "drag on '{body}', coefficient {} kg/m: rate 2·D·|v|/m",
                        readable(*coefficient)
                    ),
                    rate: 2.0 * coefficient * speed / bodies[i].mass,
                }
            }),
            ForceSpec::AngularDrag {
                body, coefficient, ..
            } => id(body).and_then(|i| {
                let inertia = bodies[i].inertia?;
                Some(Stiff {
                    index,
                    what: format!(
                        "angular drag on '{body}', coefficient {} N·m·s²: rate 2·D·|ω|/I",
                        readable(*coefficient)
                    ),
                    rate: 2.0 * coefficient * states[i].angular_velocity.abs() / inertia,
                })
            }),
            ForceSpec::Spring {
                body,
                other_body,
                stiffness,
                ..
            } => {
                let masses = [Some(body), other_body.as_ref()]
                    .into_iter()
                    .flatten()
                    .filter_map(|b| id(b))
                    .filter(|i| bodies[*i].is_dynamic())
                    .map(|i| bodies[i].mass);
                masses
                    .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.min(v))))
                    .map(|mass| Stiff {
                        index,
                        what: format!(
                            "spring on '{body}', stiffness {} N/m: rate √(k/m)",
                            readable(*stiffness)
                        ),
                        rate: (stiffness / mass).sqrt(),
                    })
            }
            _ => None,
        };
        candidates.extend(stiff.filter(|s| s.rate.is_finite()));
    }
    let worst = candidates
        .into_iter()
        .max_by(|a, b| a.rate.total_cmp(&b.rate));
    match worst {
        Some(s) if s.rate * dt > 1.0 => format!(
            "the problem is stiff: forces[{}] ({}) ≈ {:.2e} 1/s, {:.2e} times 1/dt (dt = {} s); an explicit method's steps must stay below a few times 1/rate. Use a fixed-step implicit method (--method implicit_euler, stable at any step), or a smaller coefficient",
            s.index,
            s.what,
            s.rate,
            s.rate * dt,
            readable(dt)
        ),
        _ => "dormand_prince could not meet its tolerance with any step here: the forces change too fast; try --method implicit_euler or a looser tolerance".into(),
    }
}

/// The hint of an energy that overflowed after growing by more than
/// [`UNSTABLE_GROWTH`] times its size at t = 0, in a step after the first;
/// `None` otherwise. `world` stands at the start of the failed step.
fn unstable_hint(scene: &Scene, world: &World, dt: f64, step: u64) -> Option<String> {
    if step <= 1 {
        return None;
    }
    let initial = scene.build_world(None).ok()?.energy();
    let before = world.energy();
    let size = initial.abs();
    let grown = before.abs() / size;
    (size > 0.0 && initial.is_finite() && grown > UNSTABLE_GROWTH).then(|| {
        format!(
            "the energy grew from {} J at t = 0 to {} J when the failed step began ({} times), \
             the mark of a method unstable at this step: {} with dt = {} s amplifies the motion at \
             every step. Use a smaller dt, or --method implicit_euler (stable at any step)",
            engine::error::approximate(initial),
            engine::error::approximate(before),
            engine::error::approximate(grown),
            world.method().id(),
            readable(dt)
        )
    })
}

fn energy_hint(scene: &Scene, world: &World) -> String {
    let names = scene.body_names();
    let fastest = world
        .states()
        .iter()
        .enumerate()
        .filter(|(i, _)| world.bodies()[*i].is_dynamic())
        .max_by(|a, b| a.1.velocity.norm().total_cmp(&b.1.velocity.norm()));
    // The world is left at the start of the failed step.
    let body = fastest.map_or(String::new(), |(i, s)| {
        format!(
            " (the fastest body when the step began: '{}', at {} m/s)",
            names[i],
            engine::error::approximate(s.velocity.norm())
        )
    });
    format!(
        "the total energy is no longer a finite number{body}: the masses, speeds, distances or forces of the scene are too large together for f64 (1.8e308)"
    )
}
