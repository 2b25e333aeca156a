//! rapier2d-f64 (0.36) running the single-body ballistic and spring scenes of
//! `docs/cases.md` (case I `spring`, case II `projectile`, `torque`,
//! `projectile_drag`, `angular_drag`), configured as close to ideal
//! rigid-body physics as rapier allows, so the harness can set a widely used
//! engine beside ours and report what differs.
//!
//! # Configuration (every change from rapier's defaults)
//!
//! [`IntegrationParameters`] (world):
//! - `dt` = [`RapierSettings::dt`] (default 1/60 s);
//! - `num_solver_iterations` = [`RapierSettings::substeps`] (default 4). In
//!   0.36 this is the number of *substeps* of a step, not only of solver
//!   iterations: the island solver runs `num_solver_iterations` substeps of
//!   length `dt / num_solver_iterations` (`staged_island_solver/init.rs`);
//! - `normalized_max_linear_velocity` = `f64::MAX` (default 400 m/s: the
//!   solver clamps |v| after every substep; `f64::MAX` is the documented
//!   "disabled" value, tested in `worker.rs` before the clamp);
//! - `contact_recycling` = `false` (default `true`). It has no effect here
//!   (no collider), it is set so every rapier run of the project uses the
//!   same parameters (`docs/cases.md`);
//! - gravity = the sum of the scene's [`RapierForce::Gravity`] terms, zero if
//!   none ([`PhysicsWorld`]'s default is (0, −9.81) m/s²).
//!
//! [`RigidBodyBuilder`] (the body):
//! - `linear_damping(0)`, `angular_damping(0)`: already 0 by default in 0.36,
//!   set explicitly. Rapier damps once per step at write-back,
//!   v ← v/(1 + dt·c); with c = 0 the factor is exactly 1;
//! - `can_sleep(false)` (default `true`): sleeping would freeze a body at the
//!   apex or at a spring turning point;
//! - `allow_fast_rotation(true)` (exists in 0.36, default `false`): without
//!   it the solver clamps |ω| after every substep to (π/4)/dt (78.5 rad/s at
//!   dt = 0.01 s; 3.9 rad/s at dt = 0.2 s, which the 7 rad/s of the torque
//!   case would exceed);
//! - `additional_mass_properties(MassProperties::new(0, m, I))` with **no
//!   collider**, so the mass and inertia are exactly the scene's (rapier adds
//!   collider-derived mass to the additional one; with no collider there is
//!   none). [`RapierBody::inertia`] `None` gives `lock_rotations()` (rapier
//!   then zeroes the effective inverse inertia: no angular motion at all).
//!   [`run_single_body`] reads the mass and inertia back after the first step
//!   and refuses to continue if they differ by more than a few ulps.
//!
//! Not changed: `gravity_scale` 1, CCD (`max_ccd_substeps` 1; with no
//! collider there is nothing to sweep), `length_unit` 1, the contact and
//! joint softness, warm-starting, PGS/stabilisation iteration counts (no
//! constraint exists, so the solver passes do nothing). Friction and
//! restitution do not arise: no collider.
//!
//! # What one rapier step does to a free body (read in the 0.36.1 source)
//!
//! 1. `compute_effective_force_and_torque` (`rigid_body_components.rs`):
//!    F = user_force + m·g·gravity_scale, τ = user_torque, once per step.
//! 2. The solver bakes a per-substep velocity increment once per step,
//!    Δv = F·(1/m)·h, Δω = τ·(1/I)·h with h = dt/substeps
//!    (`staged_island_solver/worker.rs`, first stage). **External forces are
//!    therefore constant over the substeps of a step**: a spring or a drag
//!    computed from the state at the start of the step is held for the whole
//!    step, whatever the substep count.
//! 3. Each substep: v += Δv, ω += Δω; clamp |v| and |ω| (disabled here);
//!    then the pose advances with the *new* velocity (symplectic Euler):
//!    x += v·h and the rotation is advanced *linearised*,
//!    (cos θ, sin θ) ← normalise(cos θ − ωh·sin θ, sin θ + ωh·cos θ)
//!    (`integrate_linearized`), i.e. θ += atan(ωh) instead of ωh.
//! 4. Write-back: v, ω ← v/(1 + dt·c_lin), ω/(1 + dt·c_ang) (identity here).
//!
//! Over one step of s substeps with the force held at a = F/m this gives
//! v' = v + a·dt and x' = x + v·dt + a·dt²·(s + 1)/(2s): the substeps refine
//! the position update of a constant acceleration, not the force. For a
//! spring u'' = −ω²u this one-step map has determinant
//! 1 + (s − 1)/(2s)·(ω·dt)², greater than 1 for every s ≥ 2: the amplitude
//! grows by √det per step (for s = 1 it is the area-preserving semi-implicit
//! Euler). See the tests for the measured consequences.
//!
//! # Forces beyond gravity
//!
//! Before every step [`run_single_body`] calls `reset_forces`/`reset_torques`
//! and `add_force`/`add_torque` with the spring, drag and torque evaluated at
//! the state at the start of the step (user forces are *not* cleared by
//! rapier between steps; they persist until reset).
//!
//! A [`RapierForce::Torque`] window is decided per step, because rapier holds
//! a force for a whole step: step n covers [n·dt, (n + 1)·dt] (times are n·dt
//! from an integer step count, never accumulated) and the torque acts during
//! it iff `start ≤ (n + ½)·dt < end` — the step's midpoint is inside the
//! window. When the window edges fall on step boundaries (the seed's 0.7 s at
//! dt = 0.01 s, equal to 70·dt up to round-off) this is exact and immune to
//! that round-off, since the midpoint is half a step away from every edge.
//! An edge inside a step is rounded to the nearer step boundary.
//!
//! Units: SI throughout (m, s, kg, N, rad).

use rapier2d_f64::dynamics::{
    IntegrationParameters, MassProperties, RigidBodyBuilder, RigidBodyHandle,
};
use rapier2d_f64::math::Vector;
use rapier2d_f64::pipeline::PhysicsWorld;
use thiserror::Error;

/// The single body of a scene, at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierBody {
    /// Mass m, kg (> 0).
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m² (> 0); `None` for a
    /// particle: rotations are locked and the angle stays at its initial
    /// value.
    pub inertia: Option<f64>,
    /// Position of the centre of mass, m.
    pub position: [f64; 2],
    /// Orientation θ, rad (counter-clockwise).
    pub angle: f64,
    /// Linear velocity of the centre of mass, m/s.
    pub velocity: [f64; 2],
    /// Angular velocity ω, rad/s (counter-clockwise); ignored for a particle.
    pub angular_velocity: f64,
}

/// A force acting on the body. Gravity goes to rapier's world gravity; the
/// others are external forces recomputed before every step from the state
/// at the start of the step and held by rapier for the whole step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RapierForce {
    /// Uniform gravitational acceleration, m/s² (rapier applies m·g to every
    /// dynamic body). Several terms add up.
    Gravity([f64; 2]),
    /// A one-dimensional spring between a fixed `anchor` (m) and the centre
    /// of mass, along `axis` (normalised here; must be non-zero): with
    /// d = x − anchor and u = axis/|axis|, extension ψ = d·u − l0 and force
    /// −k·ψ·u (seed §5.2, eq. 5.2). `stiffness` k in N/m, `rest_length` l0
    /// in m.
    AxialSpring {
        /// Fixed end of the spring, m.
        anchor: [f64; 2],
        /// Direction of the spring (any non-zero length).
        axis: [f64; 2],
        /// Stiffness k, N/m (≥ 0).
        stiffness: f64,
        /// Rest length l0, m.
        rest_length: f64,
    },
    /// A distance spring between a fixed `anchor` (m) and the centre of
    /// mass: with d = x − anchor, extension ψ = |d| − l0 and force
    /// −k·ψ·d/|d| (none when d = 0, as in the engine). `stiffness` k in
    /// N/m, `rest_length` l0 in m.
    DistanceSpring {
        /// Fixed end of the spring, m.
        anchor: [f64; 2],
        /// Stiffness k, N/m (≥ 0).
        stiffness: f64,
        /// Rest length l0, m.
        rest_length: f64,
    },
    /// Quadratic air drag −D·|v|·v at the centre of mass (seed eq. 6.7–6.8),
    /// `coefficient` D in kg/m (≥ 0).
    QuadraticDrag {
        /// D, kg/m.
        coefficient: f64,
    },
    /// Angular drag torque −D·ω·|ω|, `coefficient` D in kg·m² (≥ 0)
    /// (`docs/cases.md` `angular_drag`).
    AngularDrag {
        /// D, kg·m².
        coefficient: f64,
    },
    /// A pure couple `torque` (N·m, counter-clockwise) during
    /// `start ≤ t < end` (s), decided per step by the step's midpoint (see
    /// the module documentation).
    Torque {
        /// τ, N·m.
        torque: f64,
        /// Start of the window, s.
        start: f64,
        /// End of the window, s (may be `f64::INFINITY`).
        end: f64,
    },
}

/// Time stepping of a rapier run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierSettings {
    /// Step length dt, s (> 0): rapier's `IntegrationParameters::dt`.
    pub dt: f64,
    /// Substeps per step (≥ 1): rapier's `num_solver_iterations`, default 4.
    /// Each substep is a symplectic-Euler update of length dt/substeps with
    /// the external forces of the step held constant.
    pub substeps: usize,
}

impl RapierSettings {
    /// Step `dt` (s) with rapier's default 4 substeps.
    pub const fn new(dt: f64) -> Self {
        Self { dt, substeps: 4 }
    }
}

/// The body's state at time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierSample {
    /// Time n·dt, s.
    pub t: f64,
    /// Centre of mass, m.
    pub position: [f64; 2],
    /// Orientation, rad, unwrapped (continuous, not reduced to (−π, π]).
    pub angle: f64,
    /// Linear velocity, m/s.
    pub velocity: [f64; 2],
    /// Angular velocity, rad/s.
    pub angular_velocity: f64,
}

/// Why a rapier run could not be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RapierError {
    /// An input is out of its domain.
    #[error("invalid {what}: {value} ({reason})")]
    InvalidParameter {
        /// Which input.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// The duration is not a whole number of steps.
    #[error("duration {duration} s is not a whole number of steps of {dt} s")]
    DurationNotWholeSteps {
        /// Requested duration, s.
        duration: f64,
        /// Step, s.
        dt: f64,
    },
    /// Rapier's body does not have the requested mass properties.
    #[error("rapier body {what} is {got}, expected {expected}")]
    MassPropertiesMismatch {
        /// `"mass"` or `"inertia"`.
        what: &'static str,
        /// Requested value (kg or kg·m²).
        expected: f64,
        /// Value read back from rapier.
        got: f64,
    },
    /// The state or a force became NaN or infinite, or rapier quarantined the
    /// body (its containment of non-finite state).
    #[error("rapier state became non-finite at t = {t} s")]
    NonFinite {
        /// Time of the step that failed, s.
        t: f64,
    },
}

fn invalid(what: &'static str, value: f64, reason: &'static str) -> RapierError {
    RapierError::InvalidParameter {
        what,
        value,
        reason,
    }
}

fn require_finite(what: &'static str, value: f64) -> Result<(), RapierError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(invalid(what, value, "must be finite"))
    }
}

fn require_non_negative(what: &'static str, value: f64) -> Result<(), RapierError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(invalid(what, value, "must be finite and ≥ 0"))
    }
}

fn validate(
    body: &RapierBody,
    forces: &[RapierForce],
    settings: &RapierSettings,
    duration: f64,
) -> Result<usize, RapierError> {
    if !(body.mass.is_finite() && body.mass > 0.0) {
        return Err(invalid("mass", body.mass, "must be finite and > 0"));
    }
    if let Some(i) = body.inertia
        && !(i.is_finite() && i > 0.0)
    {
        return Err(invalid("inertia", i, "must be finite and > 0"));
    }
    for (what, v) in [
        ("position x", body.position[0]),
        ("position y", body.position[1]),
        ("angle", body.angle),
        ("velocity x", body.velocity[0]),
        ("velocity y", body.velocity[1]),
        ("angular velocity", body.angular_velocity),
    ] {
        require_finite(what, v)?;
    }
    for force in forces {
        match *force {
            RapierForce::Gravity(g) => {
                require_finite("gravity x", g[0])?;
                require_finite("gravity y", g[1])?;
            }
            RapierForce::AxialSpring {
                anchor,
                axis,
                stiffness,
                rest_length,
            } => {
                require_finite("spring anchor x", anchor[0])?;
                require_finite("spring anchor y", anchor[1])?;
                require_finite("spring axis x", axis[0])?;
                require_finite("spring axis y", axis[1])?;
                let n = axis[0].hypot(axis[1]);
                if !(n > 0.0 && n.is_finite()) {
                    return Err(invalid("spring axis length", n, "must be > 0"));
                }
                require_non_negative("spring stiffness", stiffness)?;
                require_finite("spring rest length", rest_length)?;
            }
            RapierForce::DistanceSpring {
                anchor,
                stiffness,
                rest_length,
            } => {
                require_finite("spring anchor x", anchor[0])?;
                require_finite("spring anchor y", anchor[1])?;
                require_non_negative("spring stiffness", stiffness)?;
                require_finite("spring rest length", rest_length)?;
            }
            RapierForce::QuadraticDrag { coefficient } => {
                require_non_negative("quadratic drag coefficient", coefficient)?;
            }
            RapierForce::AngularDrag { coefficient } => {
                require_non_negative("angular drag coefficient", coefficient)?;
            }
            RapierForce::Torque { torque, start, end } => {
                require_finite("torque", torque)?;
                if start.is_nan() || end.is_nan() || end <= start {
                    return Err(invalid(
                        "torque window end",
                        end,
                        "must be a number greater than the start",
                    ));
                }
            }
        }
    }
    if !(settings.dt.is_finite() && settings.dt > 0.0) {
        return Err(invalid("dt", settings.dt, "must be finite and > 0"));
    }
    if settings.substeps == 0 {
        return Err(invalid("substeps", 0.0, "must be ≥ 1"));
    }
    if !(duration.is_finite() && duration >= 0.0) {
        return Err(invalid("duration", duration, "must be finite and ≥ 0"));
    }
    let steps = (duration / settings.dt).round();
    if (steps * settings.dt - duration).abs() > 1e-9 * duration.max(settings.dt)
        || steps > u32::MAX as f64
    {
        return Err(RapierError::DurationNotWholeSteps {
            duration,
            dt: settings.dt,
        });
    }
    Ok(steps as usize)
}

/// Rapier's world parameters for `settings`: [`IntegrationParameters`]
/// defaults with `dt`, `num_solver_iterations` = substeps,
/// `normalized_max_linear_velocity` = `f64::MAX` and `contact_recycling` =
/// `false`. Public so that other rapier scenes of the project (collisions)
/// start from the same configuration.
pub fn integration_parameters(settings: &RapierSettings) -> IntegrationParameters {
    IntegrationParameters {
        dt: settings.dt,
        num_solver_iterations: settings.substeps,
        normalized_max_linear_velocity: f64::MAX,
        contact_recycling: false,
        ..IntegrationParameters::default()
    }
}

/// Rapier's body for `body`: dynamic, zero damping, no sleeping, fast
/// rotation allowed, mass properties exactly `body`'s (attach no collider,
/// or only colliders of density 0, to keep them), rotations locked for a
/// particle.
pub fn rigid_body_builder(body: &RapierBody) -> RigidBodyBuilder {
    let inertia = body.inertia.unwrap_or(0.0);
    let builder = RigidBodyBuilder::dynamic()
        .translation(Vector::new(body.position[0], body.position[1]))
        .rotation(body.angle)
        .linvel(Vector::new(body.velocity[0], body.velocity[1]))
        .angvel(if body.inertia.is_some() {
            body.angular_velocity
        } else {
            0.0
        })
        .additional_mass_properties(MassProperties::new(Vector::ZERO, body.mass, inertia))
        .linear_damping(0.0)
        .angular_damping(0.0)
        .can_sleep(false)
        .allow_fast_rotation(true);
    if body.inertia.is_some() {
        builder
    } else {
        builder.lock_rotations()
    }
}

/// One paragraph for the report: every rapier setting changed from its
/// defaults for these runs, and what rapier's step does.
pub fn configuration_summary(settings: &RapierSettings) -> String {
    format!(
        "rapier2d-f64 0.36.1, one dynamic body with no collider. World \
         (IntegrationParameters): dt = {dt} s (default 1/60 s); \
         num_solver_iterations = {s} (default 4), which in 0.36 is the number of \
         substeps, each of length dt/{s} = {h} s; normalized_max_linear_velocity = \
         f64::MAX (default 400 m/s, a speed clamp after every substep); \
         contact_recycling = false (default true; no effect without colliders); \
         gravity = the scene's (PhysicsWorld default (0, -9.81) m/s²). Body \
         (RigidBodyBuilder): linear_damping = angular_damping = 0 (also the 0.36 \
         defaults); can_sleep(false) (default true); allow_fast_rotation(true) \
         (default false: |ω| clamped to (π/4)/dt = {wmax:.4} rad/s); \
         additional_mass_properties(MassProperties::new(0, m, I)) with no \
         collider, so mass and inertia are exactly the scene's (checked by \
         reading them back); lock_rotations() for a particle. Everything else \
         (CCD, contact softness, solver iterations per substep, length_unit) is \
         at its default and inert without contacts. Rapier's integrator is \
         symplectic Euler per substep (v += a·h, then x += v·h) with the \
         rotation advanced linearised (θ += atan(ω·h)); gravity, and the spring, \
         drag and torque forces this adapter evaluates from the state at the start \
         of each step (reset_forces + add_force / add_torque), are held constant \
         over the {s} substeps of the step. A torque window is applied to the \
         steps whose midpoint lies inside it.",
        dt = settings.dt,
        s = settings.substeps,
        h = settings.dt / settings.substeps.max(1) as f64,
        wmax = std::f64::consts::FRAC_PI_4 / settings.dt,
    )
}

/// Whether step `n` (covering [n·dt, (n + 1)·dt]) is inside the window
/// `start ≤ t < end`: its midpoint (n + ½)·dt is.
fn step_in_window(n: usize, dt: f64, start: f64, end: f64) -> bool {
    let mid = (n as f64 + 0.5) * dt;
    start <= mid && mid < end
}

/// The external force (N) and torque (N·m) of step `n` from the state at its
/// start; gravity excluded (it is rapier's world gravity).
fn external_wrench(
    forces: &[RapierForce],
    n: usize,
    dt: f64,
    position: [f64; 2],
    velocity: [f64; 2],
    angular_velocity: f64,
) -> ([f64; 2], f64) {
    let mut f = [0.0, 0.0];
    let mut tau = 0.0;
    for force in forces {
        match *force {
            RapierForce::Gravity(_) => {}
            RapierForce::AxialSpring {
                anchor,
                axis,
                stiffness,
                rest_length,
            } => {
                let norm = axis[0].hypot(axis[1]);
                let u = [axis[0] / norm, axis[1] / norm];
                let d = [position[0] - anchor[0], position[1] - anchor[1]];
                let psi = d[0] * u[0] + d[1] * u[1] - rest_length;
                f[0] -= stiffness * psi * u[0];
                f[1] -= stiffness * psi * u[1];
            }
            RapierForce::DistanceSpring {
                anchor,
                stiffness,
                rest_length,
            } => {
                let d = [position[0] - anchor[0], position[1] - anchor[1]];
                let length = d[0].hypot(d[1]);
                if length > 0.0 {
                    let scale = stiffness * (length - rest_length) / length;
                    f[0] -= scale * d[0];
                    f[1] -= scale * d[1];
                }
            }
            RapierForce::QuadraticDrag { coefficient } => {
                let speed = velocity[0].hypot(velocity[1]);
                f[0] -= coefficient * speed * velocity[0];
                f[1] -= coefficient * speed * velocity[1];
            }
            RapierForce::AngularDrag { coefficient } => {
                tau -= coefficient * angular_velocity * angular_velocity.abs();
            }
            RapierForce::Torque { torque, start, end } => {
                if step_in_window(n, dt, start, end) {
                    tau += torque;
                }
            }
        }
    }
    (f, tau)
}

/// A body in a rapier world configured as the module documentation says.
struct SingleBodyWorld {
    world: PhysicsWorld,
    handle: RigidBodyHandle,
}

impl SingleBodyWorld {
    fn new(body: &RapierBody, forces: &[RapierForce], settings: &RapierSettings) -> Self {
        crate::serial_rayon();
        let mut world = PhysicsWorld::new();
        let gravity = forces.iter().fold([0.0, 0.0], |g, f| match f {
            RapierForce::Gravity(a) => [g[0] + a[0], g[1] + a[1]],
            _ => g,
        });
        world.gravity = Vector::new(gravity[0], gravity[1]);
        world.integration_parameters = integration_parameters(settings);
        let handle = world.bodies.insert(rigid_body_builder(body));
        Self { world, handle }
    }

    /// (mass, inertia) as rapier holds them, kg and kg·m²; the inertia is the
    /// effective one (0 when rotations are locked).
    fn mass_properties(&self) -> (f64, f64) {
        let rb = &self.world.bodies[self.handle];
        let mprops = rb.mass_properties();
        let inv_i = mprops.effective_world_inv_inertia;
        let inertia = if inv_i == 0.0 { 0.0 } else { 1.0 / inv_i };
        (rb.mass(), inertia)
    }

    /// Position, unwrapped-ready angle in (−π, π], velocity, angular velocity.
    fn state(&self) -> ([f64; 2], f64, [f64; 2], f64) {
        let rb = &self.world.bodies[self.handle];
        let p = rb.translation();
        let v = rb.linvel();
        ([p.x, p.y], rb.rotation().angle(), [v.x, v.y], rb.angvel())
    }

    fn set_wrench(&mut self, force: [f64; 2], torque: f64) {
        let rb = &mut self.world.bodies[self.handle];
        rb.reset_forces(false);
        rb.reset_torques(false);
        rb.add_force(Vector::new(force[0], force[1]), false);
        rb.add_torque(torque, false);
    }

    fn healthy(&self) -> bool {
        let rb = &self.world.bodies[self.handle];
        self.world.quarantine().is_empty() && rb.is_enabled()
    }
}

/// Relative agreement of a value read back from rapier (it stores 1/m and
/// 1/I, so the round trip may cost an ulp or two).
fn close(got: f64, expected: f64) -> bool {
    (got - expected).abs() <= 8.0 * f64::EPSILON * expected.abs()
}

/// Runs `body` under `forces` in rapier for `duration` seconds (a whole
/// number of steps of `settings.dt`) and returns the state at t = n·dt for
/// n = 0, …, duration/dt (the first sample is the initial state).
///
/// Errors: invalid input ([`RapierError::InvalidParameter`],
/// [`RapierError::DurationNotWholeSteps`]), rapier's body not having the
/// requested mass or inertia, or a non-finite state (NaN, infinity, or a body
/// quarantined by rapier), reported with the time of the failing step.
pub fn run_single_body(
    body: &RapierBody,
    forces: &[RapierForce],
    settings: &RapierSettings,
    duration: f64,
) -> Result<Vec<RapierSample>, RapierError> {
    let steps = validate(body, forces, settings, duration)?;
    let dt = settings.dt;
    let mut sim = SingleBodyWorld::new(body, forces, settings);

    let mut samples = Vec::with_capacity(steps + 1);
    let mut position = body.position;
    let mut velocity = body.velocity;
    let mut angular_velocity = if body.inertia.is_some() {
        body.angular_velocity
    } else {
        0.0
    };
    let mut angle = body.angle;
    let mut raw_angle = sim.state().1;
    samples.push(RapierSample {
        t: 0.0,
        position,
        angle,
        velocity,
        angular_velocity,
    });

    for n in 0..steps {
        let (f, tau) = external_wrench(forces, n, dt, position, velocity, angular_velocity);
        let t_end = (n + 1) as f64 * dt;
        if !(f[0].is_finite() && f[1].is_finite() && tau.is_finite()) {
            return Err(RapierError::NonFinite { t: n as f64 * dt });
        }
        sim.set_wrench(f, tau);
        sim.world.step();
        if !sim.healthy() {
            return Err(RapierError::NonFinite { t: t_end });
        }
        if n == 0 {
            let (mass, inertia) = sim.mass_properties();
            if !close(mass, body.mass) {
                return Err(RapierError::MassPropertiesMismatch {
                    what: "mass",
                    expected: body.mass,
                    got: mass,
                });
            }
            let expected_inertia = body.inertia.unwrap_or(0.0);
            if !close(inertia, expected_inertia) {
                return Err(RapierError::MassPropertiesMismatch {
                    what: "inertia",
                    expected: expected_inertia,
                    got: inertia,
                });
            }
        }
        let (p, a, v, w) = sim.state();
        let finite =
            p.iter().chain(v.iter()).all(|x| x.is_finite()) && a.is_finite() && w.is_finite();
        if !finite {
            return Err(RapierError::NonFinite { t: t_end });
        }
        // Unwrap: of the branches a − raw_angle + 2πk, take the one nearest
        // ω·dt (the rotation of the step is close to it; exact unless the
        // step's rotation is off by more than π from ω·dt).
        let principal = a - raw_angle;
        let two_pi = std::f64::consts::TAU;
        let k = ((w * dt - principal) / two_pi).round();
        angle += principal + two_pi * k;
        raw_angle = a;
        position = p;
        velocity = v;
        angular_velocity = w;
        samples.push(RapierSample {
            t: t_end,
            position,
            angle,
            velocity,
            angular_velocity,
        });
    }
    Ok(samples)
}

#[cfg(test)]
mod tests;
