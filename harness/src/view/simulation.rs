//! The simulation behind the view: a scene's world stepped at the scene's
//! `dt` in real time (times the speed asked for), and the commands a user
//! gives it (run, pause, step, reset, speed, drag, drop a body, switch the
//! contact model). It runs on its own thread in the window
//! (`super::physics_thread`) and directly for `--screenshot`.
//!
//! Real time: the clock is anchored at (wall time, simulated time) when
//! the run starts; every call to [`Simulation::advance`] takes the steps
//! that bring the world up to the anchor's simulated time plus the wall
//! time since, times the speed. A world that cannot keep up (a step
//! slower than `dt`) is re-anchored once it lags by [`MAX_LAG`] of wall
//! time, so it runs slower than real time instead of piling up work; the
//! corner shows the speed achieved. Step k ends at k·dt, an integer count
//! (as `World::run` does), so the run's times are the scene's.

use super::cpu_time::thread_cpu;
use super::drag::Drag;
use super::frame::{BodyLook, Frame, colour_of};
use super::meter::Meter;
use super::reference::{Reference, ReferenceDump};
use super::snapshot;
use crate::simulate::CompareWith;
use engine::{BodyDef, BodyKind, ContactModel, ContactSettings, Shape, SoftStepSettings, World};
use nalgebra::Vector2;
use scene::{Colour, Scene};
use serde::Serialize;
use std::collections::{HashSet, VecDeque};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The largest lag (wall seconds) of the world behind real time before the
/// clock is re-anchored (the world then runs slower than real time).
pub const MAX_LAG: Duration = Duration::from_millis(100);
/// The longest one [`Simulation::advance`] steps before returning, so
/// that a frame is published at least this often even when behind.
const MAX_STEPPING: Duration = Duration::from_millis(50);
/// Speeds offered (simulated seconds per wall second).
const SPEED_RANGE: (f64, f64) = (1.0 / 64.0, 16.0);
/// Paths are kept for this many dynamic bodies (the first in id order)...
pub const PATH_BODIES: usize = 256;
/// ...over this many frames (3 s at 60 frames per second).
pub const PATH_POINTS: usize = 180;

/// What the overlays being shown need the simulation to copy out.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Needs {
    /// Contact points and normals.
    pub contacts: bool,
    /// Joint anchors.
    pub joints: bool,
    /// Recent paths.
    pub paths: bool,
    /// The soft step's islands (the sleeping overlay).
    pub islands: bool,
    /// The step profile's timings (the engine reads the clock around every
    /// phase only when asked).
    pub profile: bool,
}

/// The shapes a user drops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drop {
    /// A square.
    Box,
    /// A circle.
    Circle,
}

/// A user's command.
#[derive(Debug, Clone)]
pub enum Command {
    /// Run or pause.
    TogglePause,
    /// One step (pausing first if running).
    Step,
    /// Back to the scene at t = 0.
    Reset,
    /// Multiply the speed by this factor.
    Speed(f64),
    /// Grab body `body` at world point `at` (m).
    Grab {
        /// The body.
        body: usize,
        /// The grabbed point (m).
        at: Vector2<f64>,
    },
    /// Move the grabbed point's target (m).
    DragTo(Vector2<f64>),
    /// Let the body go.
    Release,
    /// Drop a body at rest at world point `at` (m); `size` (m) is used
    /// when the scene has no dynamic body to take a size from.
    Drop {
        /// Box or circle.
        shape: Drop,
        /// Where (m).
        at: Vector2<f64>,
        /// Fallback size (m).
        size: f64,
    },
    /// The next contact model the engine accepts for this world.
    SwitchModel,
    /// What the overlays need.
    Needs(Needs),
    /// Send the bodies' states back.
    Dump(std::sync::mpsc::Sender<StateDump>),
    /// End the thread.
    Quit,
}

/// One body's state, as `--state-out` writes it.
#[derive(Debug, Clone, Serialize)]
pub struct BodyDump {
    /// Id (index in the world).
    pub id: usize,
    /// Name.
    pub name: String,
    /// `dynamic`, `static` or `kinematic`.
    pub kind: &'static str,
    /// Centre of mass (m).
    pub x: f64,
    /// Centre of mass (m).
    pub y: f64,
    /// Angle (rad).
    pub angle: f64,
    /// Velocity (m/s).
    pub vx: f64,
    /// Velocity (m/s).
    pub vy: f64,
    /// Angular velocity (rad/s).
    pub omega: f64,
    /// Whether it sleeps.
    pub asleep: bool,
}

/// The world's state, as `--state-out` writes it.
#[derive(Debug, Clone, Serialize)]
pub struct StateDump {
    /// The scene file.
    pub scene: String,
    /// Simulated time (s).
    pub time: f64,
    /// Steps since the start or the last reset.
    pub steps: u64,
    /// Whether the simulation was running (false: paused).
    pub running: bool,
    /// The contact model (`soft_step`, `exact`, `off`).
    pub model: String,
    /// The body being dragged, if any.
    pub dragging: Option<usize>,
    /// Wall time spent in the engine's steps since the start or the last
    /// reset (s).
    pub stepping_seconds: f64,
    /// CPU time of the same steps (s), where the platform says.
    pub stepping_cpu_seconds: Option<f64>,
    /// Every body.
    pub bodies: Vec<BodyDump>,
    /// The reference engine's run, with `--compare`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceDump>,
}

/// A scene's world and the view's control of it.
#[derive(Debug)]
pub struct Simulation {
    scene: Scene,
    world: World,
    looks: Arc<Vec<BodyLook>>,
    dt: f64,
    steps: u64,
    running: bool,
    speed: f64,
    /// (wall time, simulated time) of the real-time anchor, while running.
    clock: Option<(Instant, f64)>,
    drag: Option<Drag>,
    dropped: usize,
    /// A dropped body's size (m) and density (kg/m²): the median dynamic
    /// body's of the scene, if any.
    drop_size: Option<(f64, f64)>,
    failed: bool,
    message: String,
    needs: Needs,
    paths: Vec<(usize, VecDeque<Vector2<f64>>)>,
    /// The pairs of bodies (lower id first) the scene's joints keep from
    /// colliding.
    joined: HashSet<(usize, usize)>,
    meter: Meter,
    /// Wall time spent in steps since the start or the last reset.
    stepping: Duration,
    /// CPU time of the same steps, where the platform says.
    stepping_cpu: Option<Duration>,
    /// Whether anything changed since the last frame was published.
    dirty: bool,
    /// The engine of `--compare`, stepped after each of the world's steps.
    compare: Option<CompareWith>,
    reference: Option<Reference>,
}

impl Simulation {
    /// The world of `scene` at t = 0, paused or running, and the engine of
    /// `compare` beside it (refused, with the reason, where its adapter
    /// cannot run the scene step by step: [`super::reference`]).
    pub fn new(scene: Scene, running: bool, compare: Option<CompareWith>) -> anyhow::Result<Self> {
        if scene.is_linear_test() {
            anyhow::bail!(
                "{}: a [linear_test] scene has no bodies to view (`harness simulate` draws its curve)",
                scene.origin()
            );
        }
        let world = scene.build_world(None)?;
        let reference = compare
            .map(|with| Reference::new(&scene, with))
            .transpose()?;
        let drop_size = median_body(&world);
        let joined = scene
            .joints()
            .filter(|j| !j.collide_connected)
            .filter_map(|j| Some((j.body_a?, j.body_b?)))
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        let mut sim = Self {
            dt: scene.dt(),
            looks: Arc::new(Vec::new()),
            scene,
            world,
            steps: 0,
            running,
            speed: 1.0,
            clock: None,
            drag: None,
            dropped: 0,
            drop_size,
            failed: false,
            message: String::new(),
            needs: Needs::default(),
            paths: Vec::new(),
            joined,
            meter: Meter::default(),
            stepping: Duration::ZERO,
            stepping_cpu: Some(Duration::ZERO),
            dirty: true,
            compare,
            reference,
        };
        sim.rebuild_looks();
        Ok(sim)
    }

    fn rebuild_looks(&mut self) {
        let colours = self.scene.colours();
        let looks = self
            .world
            .bodies()
            .iter()
            .enumerate()
            .map(|(id, body)| {
                let colour = colours
                    .get(id)
                    .copied()
                    .unwrap_or_else(|| Colour::default_for(id));
                BodyLook::of(body, colour_of(colour))
            })
            .collect();
        self.looks = Arc::new(looks);
    }

    /// Whether the world runs (not paused, not failed, not stopped by a
    /// terminal event).
    pub fn is_running(&self) -> bool {
        self.running && !self.failed && !self.world.is_stopped()
    }

    /// Whether a frame should be published (something changed).
    pub fn is_dirty(&self) -> bool {
        self.dirty
    }

    /// The wall time until the next step is due, while running.
    pub fn next_step_in(&self, now: Instant) -> Option<Duration> {
        let (wall, sim) = self.clock?;
        if !self.is_running() {
            return None;
        }
        let due = wall + Duration::from_secs_f64(((self.next_time() - sim) / self.speed).max(0.0));
        Some(due.saturating_duration_since(now))
    }

    fn next_time(&self) -> f64 {
        (self.steps + 1) as f64 * self.dt
    }

    /// One step; a failure pauses the world and says why.
    fn step_once(&mut self) -> bool {
        let started = Instant::now();
        let cpu = thread_cpu();
        let result = self.world.step_to(self.next_time());
        let took = started.elapsed();
        self.meter.add_step(took);
        self.stepping += took;
        self.stepping_cpu = match (self.stepping_cpu, cpu, thread_cpu()) {
            (Some(sum), Some(a), Some(b)) => Some(sum + b.saturating_sub(a)),
            _ => None,
        };
        self.dirty = true;
        match result {
            Ok(_) => {
                self.steps += 1;
                if let Some(reference) = &mut self.reference {
                    reference.step();
                }
                if self.world.is_stopped() {
                    self.message = format!(
                        "a terminal event stopped the world at t = {:.6} s",
                        self.world.time()
                    );
                }
                true
            }
            Err(e) => {
                self.failed = true;
                self.message = format!("step {} failed: {e} (R resets)", self.steps + 1);
                false
            }
        }
    }

    /// Takes `n` steps now, whatever the clock (for `--screenshot`).
    pub fn step_n(&mut self, n: u64) -> anyhow::Result<()> {
        for _ in 0..n {
            if !self.step_once() {
                anyhow::bail!("{}: {}", self.scene.origin(), self.message);
            }
            if self.world.is_stopped() {
                break;
            }
        }
        Ok(())
    }

    /// Takes the steps real time asks for at wall time `now`.
    pub fn advance(&mut self, now: Instant) {
        if !self.is_running() {
            self.clock = None;
            return;
        }
        let (wall, sim) = *self.clock.get_or_insert((now, self.world.time()));
        let target = sim + now.saturating_duration_since(wall).as_secs_f64() * self.speed;
        let started = Instant::now();
        while self.next_time() <= target && self.is_running() {
            self.step_once();
            if started.elapsed() > MAX_STEPPING {
                break;
            }
        }
        let lag = (target - self.world.time()) / self.speed;
        if lag > MAX_LAG.as_secs_f64() {
            self.clock = Some((now, self.world.time()));
        }
    }

    /// Applies a user's command.
    pub fn apply(&mut self, command: Command) {
        self.dirty = true;
        match command {
            Command::TogglePause => {
                self.running = !self.running;
                self.clock = None;
            }
            Command::Step => {
                self.running = false;
                self.clock = None;
                if !self.failed && !self.world.is_stopped() {
                    self.step_once();
                }
            }
            Command::Reset => self.reset(),
            Command::Speed(factor) => {
                self.speed = (self.speed * factor).clamp(SPEED_RANGE.0, SPEED_RANGE.1);
                self.clock = None;
            }
            Command::Grab { body, at } => self.grab(body, at),
            Command::DragTo(to) => {
                if let Some(drag) = &mut self.drag
                    && let Err(e) = drag.move_to(&mut self.world, to)
                {
                    self.message = format!("drag: {e}");
                }
            }
            Command::Release => {
                if let Some(drag) = self.drag.take()
                    && let Err(e) = drag.release(&mut self.world)
                {
                    self.message = format!("release: {e}");
                }
            }
            Command::Drop { shape, at, size } => self.drop_body(shape, at, size),
            Command::SwitchModel => self.switch_model(),
            Command::Needs(needs) => {
                self.needs = needs;
                self.world.set_profiling(needs.profile);
                if !needs.paths {
                    self.paths.clear();
                }
            }
            Command::Dump(reply) => {
                let _ = reply.send(self.dump());
            }
            Command::Quit => {}
        }
    }

    fn reset(&mut self) {
        match self.scene.build_world(None) {
            Ok(world) => {
                self.world = world;
                self.world.set_profiling(self.needs.profile);
                self.steps = 0;
                self.drag = None;
                self.failed = false;
                self.clock = None;
                self.paths.clear();
                self.meter = Meter::default();
                self.stepping = Duration::ZERO;
                self.stepping_cpu = Some(Duration::ZERO);
                self.rebuild_looks();
                self.message = "reset to t = 0".into();
                if let Some(with) = self.compare {
                    match Reference::new(&self.scene, with) {
                        Ok(reference) => self.reference = Some(reference),
                        Err(e) => {
                            self.reference = None;
                            self.message = format!("reset: {e:#}");
                        }
                    }
                }
            }
            Err(e) => self.message = format!("reset: {e}"),
        }
    }

    fn grab(&mut self, body: usize, at: Vector2<f64>) {
        if let Some(old) = self.drag.take() {
            let _ = old.release(&mut self.world);
        }
        match Drag::grab(&mut self.world, body, at) {
            Ok(drag) => self.drag = Some(drag),
            Err(e) => {
                self.message = format!(
                    "cannot drag '{}': {e} (the drag is a target joint: M switches the contact model)",
                    self.world.bodies()[body].name
                )
            }
        }
    }

    fn drop_body(&mut self, shape: Drop, at: Vector2<f64>, size: f64) {
        let (size, density) = self.drop_size.unwrap_or((size, 1.0));
        self.dropped += 1;
        let (name, shape) = match shape {
            Drop::Box => (
                format!("dropped box {}", self.dropped),
                Shape::rectangle(size, size),
            ),
            Drop::Circle => (
                format!("dropped circle {}", self.dropped),
                Shape::circle(0.5 * size),
            ),
        };
        let def = shape.map(|shape| BodyDef {
            mass: None,
            density: Some(density),
            ..BodyDef::rigid(&name, 1.0, shape).with_position(at)
        });
        match def.and_then(|def| self.world.add_body(def)) {
            Ok(_) => {
                self.rebuild_looks();
                self.message = format!("{name} at ({:.3}, {:.3}) m", at.x, at.y);
            }
            Err(e) => self.message = format!("cannot drop {name}: {e}"),
        }
    }

    /// Cycles soft step → exact → off → soft step, skipping what the
    /// engine refuses for this world (joints need the soft step; the soft
    /// step needs semi-implicit Euler; the exact model refuses compound
    /// shapes), and says what it did.
    fn switch_model(&mut self) {
        if let Some(drag) = self.drag.take() {
            let _ = drag.release(&mut self.world);
        }
        let order = ["soft_step", "exact", "off"];
        let now = model_name(&self.world);
        let start = order.iter().position(|m| *m == now).unwrap_or(2);
        let mut refused = Vec::new();
        for k in 1..order.len() {
            let next = order[(start + k) % order.len()];
            let result = match next {
                "soft_step" => self
                    .world
                    .set_contact_model(ContactModel::SoftStep(SoftStepSettings::default())),
                "exact" => self
                    .world
                    .set_contact_model(ContactModel::Exact(ContactSettings::default())),
                _ => self.world.disable_contacts(),
            };
            match result {
                Ok(()) => {
                    let how = if next == "off" {
                        "bodies pass through each other"
                    } else {
                        "at the engine's defaults"
                    };
                    self.message = format!(
                        "contact model: {next} ({how}){}",
                        if refused.is_empty() {
                            String::new()
                        } else {
                            format!("; refused: {}", refused.join("; "))
                        }
                    );
                    return;
                }
                Err(e) => refused.push(format!("{next}: {e}")),
            }
        }
        self.message = format!("the model stays {now}: {}", refused.join("; "));
    }

    /// The bodies' states now.
    pub fn dump(&self) -> StateDump {
        StateDump {
            scene: self.scene.origin().to_owned(),
            time: self.world.time(),
            steps: self.steps,
            running: self.is_running(),
            model: model_name(&self.world).to_owned(),
            dragging: self.drag.map(|d| d.body),
            stepping_seconds: self.stepping.as_secs_f64(),
            stepping_cpu_seconds: self.stepping_cpu.map(|d| d.as_secs_f64()),
            bodies: self
                .world
                .bodies()
                .iter()
                .zip(self.world.states())
                .enumerate()
                .map(|(id, (body, s))| BodyDump {
                    id,
                    name: body.name.clone(),
                    kind: kind_name(body.kind),
                    x: s.position.x,
                    y: s.position.y,
                    angle: s.angle,
                    vx: s.velocity.x,
                    vy: s.velocity.y,
                    omega: s.angular_velocity,
                    asleep: self.world.is_asleep(id),
                })
                .collect(),
            reference: self.reference.as_ref().map(Reference::dump),
        }
    }

    /// The means per step of every step since the start or the last reset
    /// (for `--screenshot`, whose steps are taken at once).
    pub fn whole_run_means(&self, status: &mut super::frame::Status) {
        let profile = self.world.profile();
        let start = engine::StepProfile::default();
        super::meter::means(
            status,
            (&start, &profile),
            self.steps,
            self.stepping,
            self.needs.profile,
        );
    }

    /// Copies what the view shows into `frame` (reusing its buffers).
    pub fn publish(&mut self, frame: &mut Frame) {
        self.dirty = false;
        frame.looks = Arc::clone(&self.looks);
        if self.needs.paths {
            snapshot::record_paths(&mut self.paths, &self.world);
        }
        snapshot::fill(frame, &self.world, self.needs, &self.paths, &self.joined);
        frame.drag = self.drag.map(|d| {
            let joint = self.world.joint(d.joint);
            (joint.map_or(d.target, |j| j.anchor_b), d.target)
        });
        let status = &mut frame.status;
        status.time = self.world.time();
        status.steps = self.steps;
        status.dt = self.dt;
        status.running = self.is_running();
        status.speed = self.speed;
        status.model = format!("{} ({})", model_name(&self.world), self.world.method().id());
        status.message.clone_from(&self.message);
        status.label = format!(
            "etalon2d (this engine) · {}",
            super::reference::rust_build()
        );
        let now = Instant::now();
        self.meter
            .report(&self.world, self.needs.profile, status, now);
        match &mut self.reference {
            Some(reference) => {
                let mut side = frame.reference.take().unwrap_or_default();
                reference.publish(&mut side, frame, now);
                frame.reference = Some(side);
            }
            None => frame.reference = None,
        }
    }
}

/// The world's contact model as the engine names it, `off` without.
fn model_name(world: &World) -> &'static str {
    world.contact_model().map_or("off", |m| m.id())
}

fn kind_name(kind: BodyKind) -> &'static str {
    match kind {
        BodyKind::Dynamic => "dynamic",
        BodyKind::Static => "static",
        BodyKind::Kinematic => "kinematic",
    }
}

/// The size (m: twice the distance of its farthest point from its centre
/// over √2, a square of the same reach) and density (kg/m²) of the median
/// dynamic body with a shape, by size.
fn median_body(world: &World) -> Option<(f64, f64)> {
    let mut bodies: Vec<(f64, f64)> = world
        .bodies()
        .iter()
        .filter(|b| b.kind == BodyKind::Dynamic)
        .filter_map(|b| {
            let shape = b.shape.as_ref()?;
            let look = BodyLook::of(b, 0);
            Some((
                look.radius * std::f64::consts::SQRT_2,
                b.mass / shape.area(),
            ))
        })
        .filter(|(size, density)| size.is_finite() && *size > 0.0 && density.is_finite())
        .collect();
    bodies.sort_by(|a, b| a.0.total_cmp(&b.0));
    bodies.get(bodies.len() / 2).copied()
}
