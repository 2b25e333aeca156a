//! This engine's soft step behind the benchmark's interface
//! ([`ManyBodyEngine`]), built from the scene file itself (the reference
//! engines get the same bodies through [`super::convert`]).

use anyhow::{Context, Result};
use engine::{ContactModel, StepProfile, World};
use references::many_body::{BodyMass, BodySample, ContactCounts, ManyBodyEngine, ManyBodyError};
use scene::Scene;

/// Engine name in the report.
pub const NAME: &str = "this engine (soft step, f64)";

/// A world stepping a scene with its own soft-step settings.
pub struct SoftStepEngine {
    world: World,
    dt: f64,
    steps: usize,
    /// Counters of the last step only.
    last: StepProfile,
}

impl SoftStepEngine {
    /// The world of `scene` (which uses the soft-step model), with the
    /// energy guard off (it costs a pass over the bodies per step that the
    /// reference engines do not make) and per-phase timing `profiled`.
    pub fn new(scene: &Scene, profiled: bool) -> Result<Self> {
        Self::with_threads(scene, profiled, 1)
    }

    /// [`SoftStepEngine::new`] stepping on `threads` threads (the soft
    /// step's [`engine::SoftStepSettings::threads`]).
    pub fn with_threads(scene: &Scene, profiled: bool, threads: usize) -> Result<Self> {
        let mut world = scene
            .build_world(None)
            .with_context(|| format!("building {}", scene.origin()))?;
        if let Some(ContactModel::SoftStep(settings)) = world.contact_model() {
            world.set_contact_model(ContactModel::SoftStep(engine::SoftStepSettings {
                threads,
                ..settings
            }))?;
        }
        Self::from_world(world, scene.dt(), profiled)
    }

    /// Steps of `dt` (s) of an already built `world` (any contact model).
    pub fn from_world(mut world: World, dt: f64, profiled: bool) -> Result<Self> {
        world.set_energy_limit(None)?;
        world.set_profiling(profiled);
        Ok(Self {
            world,
            dt,
            steps: 0,
            last: StepProfile::default(),
        })
    }

    /// The world (for the profile and the states).
    pub fn world(&self) -> &World {
        &self.world
    }

    fn failed(&self, message: String) -> ManyBodyError {
        ManyBodyError::Engine {
            engine: NAME,
            message,
        }
    }
}

impl ManyBodyEngine for SoftStepEngine {
    fn name(&self) -> &'static str {
        NAME
    }

    fn configuration(&self) -> String {
        match self.world.contact_model() {
            Some(ContactModel::SoftStep(s)) => format!(
                "f64 throughout; soft step with {} substeps; contact springs {} Hz (capped at \
                 1/(8h)), twice that against static bodies, damping ratio {}; push-out at most \
                 {} m/s; restitution threshold {} m/s; speculative distance {} m; contact \
                 recycling within {} m; continuous sweeps of fast bodies against static ones {}; \
                 sleeping {}; {} thread(s); warm starting {}.",
                s.substeps,
                s.contact_hertz,
                s.contact_damping_ratio,
                s.push_out_speed,
                s.restitution_threshold,
                s.speculative_distance,
                s.recycle_distance,
                if s.continuous { "on" } else { "off" },
                if s.sleeping { "on" } else { "off" },
                s.threads,
                if s.warm_starting { "on" } else { "off" },
            ),
            _ => "not a soft-step world".into(),
        }
    }

    fn body_count(&self) -> usize {
        self.world.bodies().len()
    }

    fn steps_taken(&self) -> usize {
        self.steps
    }

    fn step(&mut self) -> Result<(), ManyBodyError> {
        let before = self.world.profile();
        self.world
            .step(self.dt)
            .map_err(|e| self.failed(e.to_string()))?;
        self.last = self.world.profile().since(&before);
        self.steps += 1;
        Ok(())
    }

    fn samples(&mut self, out: &mut Vec<BodySample>) -> Result<(), ManyBodyError> {
        out.clear();
        for (body, s) in self.world.states().iter().enumerate() {
            let v = [
                s.position.x,
                s.position.y,
                s.angle,
                s.velocity.x,
                s.velocity.y,
            ];
            if !v.iter().chain([&s.angular_velocity]).all(|x| x.is_finite()) {
                return Err(ManyBodyError::NonFinite {
                    engine: NAME,
                    body,
                    steps: self.steps,
                });
            }
            // Principal value in (−π, π], as the other engines report it.
            let angle = s.angle.sin().atan2(s.angle.cos());
            out.push(BodySample {
                position: [s.position.x, s.position.y],
                angle,
                velocity: [s.velocity.x, s.velocity.y],
                angular_velocity: s.angular_velocity,
            });
        }
        Ok(())
    }

    fn mass_properties(&mut self) -> Result<Vec<BodyMass>, ManyBodyError> {
        Ok(self
            .world
            .bodies()
            .iter()
            .map(|b| {
                if b.is_dynamic() {
                    BodyMass {
                        mass: b.mass,
                        inertia: b.inertia.unwrap_or(0.0),
                    }
                } else {
                    BodyMass::default()
                }
            })
            .collect())
    }

    fn contact_counts(&mut self) -> Result<ContactCounts, ManyBodyError> {
        Ok(ContactCounts {
            touching_pairs: self.last.touching as usize,
            points: self.last.points as usize,
            penetrating_points: 0,
            deepest_penetration: 0.0,
        })
    }
}
