//! `--compare rapier|box2d`: the reference engine beside the engine, on
//! the same scene, stepped in sync (one reference step after each of the
//! engine's, so both panels always show the same step count).
//!
//! The reference is built by the adapters `harness simulate --compare`
//! uses (`crate::simulate::compare::adapters`: the same neutral scene,
//! the scene's dt and substeps, each engine's defaults otherwise), and
//! only by the many-body ones, which step alongside the engine
//! (`references::rapier_many`, `references::box2d_world`): rapier's
//! adapters for a scene without contacts and for the exact model run a
//! whole run at once, so the view refuses those and says to use
//! `simulate --compare rapier`. A scene the adapter refuses is refused
//! with its reason and the view does not open.
//!
//! Not mirrored: a drag, a dropped body and a switch of contact model act
//! on the engine's world only; the reference runs the scene as it was
//! given (docs/view.md).

use super::cpu_time::thread_cpu;
use super::frame::{Frame, Status};
use super::meter::WINDOW;
use crate::simulate::CompareWith;
use crate::simulate::compare::adapters::{Adapter, prepare};
use anyhow::{Result, bail};
use engine::BodyState;
use nalgebra::Vector2;
use references::box2d_world::build::Box2dBuild;
use references::many_body::{BodySample, ManyBodyEngine};
use scene::Scene;
use serde::Serialize;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The build of this binary's Rust code ("release" or "debug").
pub fn rust_build() -> &'static str {
    if cfg!(debug_assertions) {
        "debug build"
    } else {
        "release build"
    }
}

/// The reference engine's run.
pub struct Reference {
    engine: Box<dyn ManyBodyEngine>,
    /// Engine and version.
    name: &'static str,
    /// How it was built.
    build: String,
    /// Substeps per step.
    substeps: usize,
    samples: Vec<BodySample>,
    states: Vec<BodyState>,
    steps: u64,
    /// Wall and CPU time of its steps since the start or the last reset.
    stepping: Duration,
    stepping_cpu: Option<Duration>,
    /// The current averaging window: start, steps, wall time.
    window: (Option<Instant>, u64, Duration),
    step_ms: Option<f64>,
    /// Why it stopped (it then stays where it was).
    failure: Option<String>,
}

impl std::fmt::Debug for Reference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Reference")
            .field("name", &self.name)
            .field("steps", &self.steps)
            .finish_non_exhaustive()
    }
}

/// The reference's state, as `--state-out` writes it.
#[derive(Debug, Clone, Serialize)]
pub struct ReferenceDump {
    /// Engine and version.
    pub engine: String,
    /// How it was built.
    pub build: String,
    /// Substeps per step.
    pub substeps: usize,
    /// Steps since the start or the last reset.
    pub steps: u64,
    /// Wall time of those steps (s).
    pub stepping_seconds: f64,
    /// CPU time of those steps (s), where the platform says.
    pub stepping_cpu_seconds: Option<f64>,
    /// Why it stopped, if it did.
    pub failure: Option<String>,
    /// Every body of the scene, in its order: `[x, y, angle]` (m, m, rad;
    /// the angle as the engine reports it, a principal value).
    pub bodies: Vec<[f64; 3]>,
}

impl Reference {
    /// `with` set up for `scene`, at t = 0; refuses a scene its adapter
    /// cannot represent, or one its adapter runs only whole.
    pub fn new(scene: &Scene, with: CompareWith) -> Result<Self> {
        let option = match with {
            CompareWith::Rapier => "rapier",
            CompareWith::Box2d => "box2d",
        };
        let prepared = prepare(scene, with, scene.dt())
            .map_err(|e| e.context(format!("--compare {option}")))?;
        let Adapter::Many(mut engine) = prepared.adapter else {
            bail!(
                "--compare {option}: {}: {} takes this scene ({}) only as a whole run, computed at \
                 once, which a live view cannot step beside the engine; `harness simulate {} \
                 --compare {option}` compares it",
                scene.origin(),
                prepared.name,
                match scene.contact() {
                    None => "one body, contacts off",
                    Some(_) => "the exact contact model",
                },
                scene.origin()
            );
        };
        let mut samples = Vec::new();
        engine
            .samples(&mut samples)
            .map_err(|e| anyhow::anyhow!(e).context(format!("--compare {option}")))?;
        let build = match with {
            CompareWith::Box2d => {
                let b = Box2dBuild::linked();
                format!(
                    "{} {} {}{}",
                    b.precision,
                    b.simd,
                    b.optimisation,
                    if b.ndebug { " NDEBUG" } else { " with asserts" }
                )
            }
            CompareWith::Rapier => format!("f64, {}", rust_build()),
        };
        let mut reference = Self {
            engine,
            name: prepared.name,
            build,
            substeps: prepared.substeps,
            samples,
            states: Vec::new(),
            steps: 0,
            stepping: Duration::ZERO,
            stepping_cpu: Some(Duration::ZERO),
            window: (None, 0, Duration::ZERO),
            step_ms: None,
            failure: None,
        };
        reference.convert();
        Ok(reference)
    }

    fn convert(&mut self) {
        self.states.clear();
        self.states.extend(self.samples.iter().map(|s| BodyState {
            position: Vector2::new(s.position[0], s.position[1]),
            angle: s.angle,
            velocity: Vector2::new(s.velocity[0], s.velocity[1]),
            angular_velocity: s.angular_velocity,
        }));
    }

    /// One step of the scene's dt; a failure stops the reference (the
    /// engine runs on) and is said in its panel.
    pub fn step(&mut self) {
        if self.failure.is_some() {
            return;
        }
        let started = Instant::now();
        let cpu = thread_cpu();
        let result = self.engine.step();
        let took = started.elapsed();
        self.stepping += took;
        self.stepping_cpu = match (self.stepping_cpu, cpu, thread_cpu()) {
            (Some(sum), Some(a), Some(b)) => Some(sum + b.saturating_sub(a)),
            _ => None,
        };
        self.window.1 += 1;
        self.window.2 += took;
        let read = result.and_then(|()| self.engine.samples(&mut self.samples));
        match read {
            Ok(()) => {
                self.steps += 1;
                self.convert();
            }
            Err(e) => {
                self.failure = Some(format!(
                    "{} stopped at step {}: {e} (R resets)",
                    self.name,
                    self.steps + 1
                ))
            }
        }
    }

    /// Copies the reference into `frame`: the engine's looks for the
    /// scene's bodies (the reference holds no other), its states, its
    /// numbers.
    pub fn publish(&mut self, frame: &mut Frame, ours: &Frame, now: Instant) {
        let (start, steps, took) = self.window;
        match start {
            None => self.window = (Some(now), 0, Duration::ZERO),
            Some(began) if now.saturating_duration_since(began) >= WINDOW => {
                if steps > 0 {
                    self.step_ms = Some(1e3 * took.as_secs_f64() / steps as f64);
                }
                self.window = (Some(now), 0, Duration::ZERO);
            }
            Some(_) => {}
        }
        frame.looks = Arc::clone(&ours.looks);
        frame.states.clone_from(&self.states);
        frame.removed.clear();
        frame.removed.resize(self.states.len(), false);
        frame.asleep.clear();
        frame.islands.clear();
        frame.island_of.clear();
        frame.islands_missing = None;
        frame.joints.clear();
        frame.contacts.clear();
        frame.paths.clear();
        frame.drag = None;
        frame.reference = None;
        let s = &ours.status;
        frame.status = Status {
            label: format!("{} · {}", self.name, self.build),
            time: self.steps as f64 * s.dt,
            steps: self.steps,
            dt: s.dt,
            running: s.running,
            speed: s.speed,
            achieved_speed: None,
            model: format!("{} substeps, its defaults", self.substeps),
            bodies: self.states.len(),
            asleep: 0,
            joints: 0,
            step_ms: self.step_ms,
            phases: Vec::new(),
            counters: Vec::new(),
            message: self.failure.clone().unwrap_or_default(),
            impulse_scale: None,
        };
    }

    /// The state for `--state-out`.
    pub fn dump(&self) -> ReferenceDump {
        ReferenceDump {
            engine: self.name.to_owned(),
            build: self.build.clone(),
            substeps: self.substeps,
            steps: self.steps,
            stepping_seconds: self.stepping.as_secs_f64(),
            stepping_cpu_seconds: self.stepping_cpu.map(|d| d.as_secs_f64()),
            failure: self.failure.clone(),
            bodies: self
                .states
                .iter()
                .map(|s| [s.position.x, s.position.y, s.angle])
                .collect(),
        }
    }
}
