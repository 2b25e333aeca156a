//! What the joint cases (`pendulum`, `physical_pendulum`,
//! `double_pendulum`, `chain`, `slider`, `joint_motor_limit`;
//! `docs/cases.md#joints`) share: running one scene file in each engine
//! that has joints (this engine's soft step, rapier2d, Box2D) with the
//! same readings, the soft rows' closed forms, and the measurements made
//! on the samples (zero crossings located inside steps, turning points).
//!
//! Every engine runs the *same file*: the soft step builds its world from
//! the scene, rapier2d and Box2D the neutral description the harness
//! converts it to (`bench::convert::many_body_scene`, joints included).
//! Every engine is read the same way, from its body states after every
//! step ([`BodySample`]), and its joints from those poses
//! ([`ManyBodyScene::joint_states`]).
//!
//! The exact contact model's joints (constraints of the equations of
//! motion) are run by `pendulum_exact` and `double_pendulum` on their own
//! worlds; a soft-step world with joints refuses to switch to it.

use crate::bench::convert::many_body_scene;
use anyhow::{Context, Result, bail};
use engine::{ContactModel, World};
use references::box2d_world::Box2dWorld;
use references::many_body::{BodySample, ManyBodyEngine, ManyBodyScene};
use references::rapier_many::RapierManyWorld;
use scene::Scene;
use std::f64::consts::PI;
use std::time::Instant;

/// An engine with joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// This engine's soft step (f64).
    SoftStep,
    /// rapier2d-f64 0.36 (impulse joints).
    Rapier,
    /// Box2D v3.2 through boxdd 0.6 (f32).
    Box2d,
}

impl Engine {
    /// Every engine, this one first.
    pub const ALL: [Engine; 3] = [Engine::SoftStep, Engine::Rapier, Engine::Box2d];

    /// The engines a case runs: this one, then Box2D and rapier2d when
    /// `reference_engines` (the full run; the reduced tests run the soft
    /// step alone).
    pub fn of_run(reference_engines: bool) -> &'static [Engine] {
        if reference_engines {
            &[Engine::SoftStep, Engine::Box2d, Engine::Rapier]
        } else {
            &[Engine::SoftStep]
        }
    }

    /// The method id of its rows.
    pub fn id(self) -> &'static str {
        match self {
            Engine::SoftStep => "soft_step",
            Engine::Rapier => "rapier2d",
            Engine::Box2d => "box2d",
        }
    }

    /// Its name in notes and legends.
    pub fn label(self) -> &'static str {
        match self {
            Engine::SoftStep => "soft step",
            Engine::Rapier => "rapier2d",
            Engine::Box2d => "Box2D",
        }
    }
}

/// How to run a scene: the engine, the step, the substeps and, for the soft
/// step, the frequency of the joints' rigid rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Config {
    /// The engine.
    pub engine: Engine,
    /// Step (s).
    pub dt: f64,
    /// Substeps per step.
    pub substeps: usize,
    /// Soft step only: every joint's constraint frequency (Hz) instead of
    /// the scene's (the step-doubling runs set it to 1/(4h)).
    pub joint_hertz: Option<f64>,
}

impl Config {
    /// `engine` at the scene's own step and substeps.
    pub fn of(scene: &Scene, engine: Engine) -> Result<Self> {
        Ok(Self {
            engine,
            dt: scene.dt(),
            substeps: soft_settings(scene)?.substeps,
            joint_hertz: None,
        })
    }

    /// The substep h = dt/substeps (s).
    pub fn substep(&self) -> f64 {
        self.dt / self.substeps as f64
    }

    /// The soft step at half the substep, its joints at a quarter of the
    /// new substep rate, 1/(4 h/2) Hz: the next member of the family the
    /// defaults belong to (Box2D's joint frequency min(60 Hz, 1/(4h)) is
    /// exactly 1/(4h) at the default h = 1/240 s), on which the
    /// step-doubling estimates of the joint cases are made.
    pub fn halved(&self) -> Self {
        let substeps = 2 * self.substeps;
        let h = self.dt / substeps as f64;
        Self {
            substeps,
            joint_hertz: Some(0.25 / h),
            ..*self
        }
    }
}

/// The soft-step settings of a jointed scene.
pub fn soft_settings(scene: &Scene) -> Result<engine::SoftStepSettings> {
    match scene.contact() {
        Some(ContactModel::SoftStep(s)) => Ok(s),
        _ => bail!(
            "{}: a joint case runs the soft-step contact model",
            scene.origin()
        ),
    }
}

/// A run: the state of every body after every step (the first at t = 0)
/// and the wall time of the steps alone (s).
#[derive(Debug, Clone)]
pub struct Run {
    /// Step (s).
    pub dt: f64,
    /// `samples[k][b]`: body `b` at t = k dt.
    pub samples: Vec<Vec<BodySample>>,
    /// Wall time of the steps, reading excluded (s).
    pub seconds: f64,
}

impl Run {
    /// The time of sample `k` (s).
    pub fn time(&self, k: usize) -> f64 {
        k as f64 * self.dt
    }
}

/// A scene and its neutral description, loaded once.
pub struct JointScene {
    /// The scene file.
    pub scene: Scene,
    /// What rapier2d and Box2D build (bodies in file order).
    pub neutral: ManyBodyScene,
}

impl JointScene {
    /// Loads `scenes/<id>.toml` and converts it.
    pub fn load(id: &str) -> Result<Self> {
        let scene = crate::scenes::load(id)?;
        let neutral = many_body_scene(&scene).with_context(|| format!("converting {id}"))?;
        Ok(Self { scene, neutral })
    }

    /// The id of body `name`.
    pub fn body(&self, name: &str) -> Result<usize> {
        self.scene
            .body_id(name)
            .with_context(|| format!("{}: no body '{name}'", self.scene.origin()))
    }

    /// Mass (kg) and moment of inertia about the centre (kg·m²) of body `b`
    /// as the scene gives them (for energies; the closed forms compute
    /// their own).
    pub fn mass(&self, b: usize) -> (f64, f64) {
        let body = &self.neutral.bodies[b];
        (body.mass(), body.inertia())
    }

    /// The scene's gravity (m/s²), which must point along −y.
    pub fn gravity(&self) -> Result<f64> {
        let [gx, gy] = self.neutral.gravity;
        if gx != 0.0 || gy >= 0.0 {
            bail!("{}: gravity must point along -y", self.scene.origin());
        }
        Ok(-gy)
    }

    /// The world of the soft step under `config`.
    pub fn soft_world(&self, config: &Config) -> Result<World> {
        let mut world = self.scene.build_world(None)?;
        world.set_energy_limit(None)?;
        let settings = soft_settings(&self.scene)?;
        world.set_contact_model(ContactModel::SoftStep(engine::SoftStepSettings {
            substeps: config.substeps,
            ..settings
        }))?;
        if let Some(hertz) = config.joint_hertz {
            let defs: Vec<engine::JointDef> = self.scene.joints().cloned().collect();
            for (id, def) in defs.into_iter().enumerate() {
                let ratio = def.constraint_damping_ratio;
                world.remove_joint(id)?;
                world.add_joint(def.with_constraint_softness(hertz, ratio))?;
            }
        }
        Ok(world)
    }

    /// Runs `steps` steps under `config`.
    pub fn run(&self, config: &Config, steps: usize) -> Result<Run> {
        let mut samples = Vec::with_capacity(steps + 1);
        let mut seconds = 0.0;
        match config.engine {
            Engine::SoftStep => {
                let mut world = self.soft_world(config)?;
                samples.push(soft_samples(&world));
                for _ in 0..steps {
                    let started = Instant::now();
                    world.step(config.dt).with_context(|| {
                        format!("{}: step at t = {} s", self.scene.origin(), world.time())
                    })?;
                    seconds += started.elapsed().as_secs_f64();
                    samples.push(soft_samples(&world));
                }
            }
            Engine::Rapier | Engine::Box2d => {
                let neutral = ManyBodyScene {
                    dt: config.dt,
                    substeps: config.substeps,
                    ..self.neutral.clone()
                };
                let mut engine: Box<dyn ManyBodyEngine> = match config.engine {
                    Engine::Rapier => Box::new(RapierManyWorld::new(&neutral)?),
                    _ => Box::new(Box2dWorld::new(&neutral)?),
                };
                let mut buffer = Vec::new();
                engine.samples(&mut buffer)?;
                samples.push(buffer.clone());
                for _ in 0..steps {
                    let started = Instant::now();
                    engine.step()?;
                    seconds += started.elapsed().as_secs_f64();
                    engine.samples(&mut buffer)?;
                    samples.push(buffer.clone());
                }
            }
        }
        Ok(Run {
            dt: config.dt,
            samples,
            seconds,
        })
    }

    /// The largest of each joint's anchor separation over `run` (m), read
    /// from the poses (`ManyBodyScene::joint_states`).
    pub fn largest_separations(&self, run: &Run) -> Vec<f64> {
        let mut worst = vec![0.0_f64; self.neutral.joints.len()];
        for s in &run.samples {
            for (w, j) in worst.iter_mut().zip(self.neutral.joint_states(s)) {
                *w = w.max(j.separation);
            }
        }
        worst
    }
}

fn soft_samples(world: &World) -> Vec<BodySample> {
    world
        .states()
        .iter()
        .map(|s| BodySample {
            position: [s.position.x, s.position.y],
            angle: s.angle,
            velocity: [s.velocity.x, s.velocity.y],
            angular_velocity: s.angular_velocity,
        })
        .collect()
}

/// The steps of `duration` s at `dt` s.
pub fn steps(duration: f64, dt: f64) -> usize {
    (duration / dt).round() as usize
}

/// The soft rows of a joint at frequency `hertz` (Hz, capped at a quarter
/// of the substep rate 1/(4h), Box2D's rule) and damping ratio `zeta`,
/// substep `h` (s): ω = 2πf and a₃ = 1/(1 + a₂) of the soft step's
/// softness (a₁ = 2ζ + hω, a₂ = hω a₁; `docs/joints.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftRows {
    /// ω (rad/s).
    pub omega: f64,
    /// a₃: the fraction h²ω²a₃ of a separation the bias removes per
    /// substep.
    pub a3: f64,
}

impl SoftRows {
    /// The rows of `hertz` and `zeta` at substep `h`.
    pub fn new(hertz: f64, zeta: f64, h: f64) -> Self {
        let omega = 2.0 * PI * hertz.min(0.25 / h);
        let a1 = 2.0 * zeta + h * omega;
        Self {
            omega,
            a3: 1.0 / (1.0 + h * omega * a1),
        }
    }

    /// The soft step's default rigid rows (60 Hz, ζ = 2) at substep `h`.
    pub fn defaults(h: f64) -> Self {
        Self::new(
            engine::joints::DEFAULT_CONSTRAINT_HERTZ,
            engine::joints::DEFAULT_CONSTRAINT_DAMPING_RATIO,
            h,
        )
    }

    /// The largest separation of a row under the load acceleration
    /// `a_load` with anchors of centripetal acceleration `a_c` (m/s²):
    /// (a_load + a_c (1 + 1/(2 a₃)))/ω² (`docs/joints.md`: the static sink
    /// a/ω², plus the drift ½ h² a_c of each substep of which the bias
    /// removes the fraction h²ω²a₃).
    pub fn separation_bound(&self, a_load: f64, a_c: f64) -> f64 {
        (a_load + a_c * (1.0 + 0.5 / self.a3)) / (self.omega * self.omega)
    }

    /// The static sink a/ω² (m or rad) of a row under the load
    /// acceleration `a`.
    pub fn sink(&self, a: f64) -> f64 {
        a / (self.omega * self.omega)
    }
}

/// The times (s) at which the sampled `values` (one per step of `dt` s,
/// the first at t = 0) change sign, each located inside its step by linear
/// interpolation between the two samples around it.
pub fn crossings(values: &[f64], dt: f64) -> Vec<f64> {
    (1..values.len())
        .filter(|&i| (values[i - 1] < 0.0) != (values[i] < 0.0))
        .map(|i| {
            let f = values[i - 1] / (values[i - 1] - values[i]);
            (i as f64 - 1.0 + f) * dt
        })
        .collect()
}

/// A bound (s) on the error of a crossing located by [`crossings`] for a
/// coordinate x with x'' = 0 at its zero (a pendulum's horizontal offset
/// at the bottom), |x'''/x'| ≤ `rate` (s⁻²) there: linear interpolation
/// misplaces a simple root by at most (dt²/8) max|x''|/|x'|, and
/// max|x''| ≤ |x'''| dt within the step, so by dt³ rate/8.
pub fn crossing_error(dt: f64, rate: f64) -> f64 {
    dt.powi(3) * rate / 8.0
}

/// The turning values of the sampled `values`: at each local maximum of
/// |value|, the vertex of the parabola through the three samples around it
/// (m or rad, positive).
pub fn turning_values(values: &[f64]) -> Vec<f64> {
    (1..values.len().saturating_sub(1))
        .filter_map(|i| {
            let (a, b, c) = (values[i - 1].abs(), values[i].abs(), values[i + 1].abs());
            (b >= a && b > c).then(|| {
                let curvature = a - 2.0 * b + c;
                if curvature == 0.0 {
                    b
                } else {
                    b - (a - c) * (a - c) / (8.0 * curvature)
                }
            })
        })
        .collect()
}
