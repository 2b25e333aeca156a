//! What every contact model of a [`crate::World`] works on: the bodies and
//! their states, the force generators with their windows, the events to
//! locate, the clock, and the per-phase profiler. The world owns one
//! [`WorldCore`] and hands it to its model ([`crate::ContactModel`]) at
//! every step; the models never see each other.

use crate::body::{Body, BodyState};
use crate::error::{EngineError, Result};
use crate::events::EventSpec;
use crate::forces::{Force, ForceContext, TimeWindow, Wrench};
use crate::profile::Profiler;
use nalgebra::Vector2;
use std::sync::Arc;

/// The id [`crate::World::add_force`] returns, for
/// [`crate::World::remove_force`]. Ids are never reused within a world.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ForceId(pub(crate) u64);

/// A force generator with the window in which it acts. Forces are
/// immutable once added (every [`Force`] method takes `&self`), so a
/// cloned world shares them.
#[derive(Clone)]
pub(crate) struct ForceEntry {
    pub force: Arc<dyn Force>,
    pub window: TimeWindow,
    /// Whether this entry is the world's gravity setting
    /// ([`crate::World::set_gravity`]) rather than a force the user added.
    pub world_gravity: bool,
    /// Its id (the world's gravity setting has one too, never returned).
    pub id: ForceId,
}

/// What a program sets on a body after creating it
/// ([`crate::World::set_gravity_scale`] and its neighbours), beside its
/// [`Body`]: the defaults change nothing.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BodyControl {
    /// Factor on the world's uniform gravity for this body (1 by default).
    pub gravity_scale: f64,
    /// Linear damping rate c (1/s): v ← v / (1 + h c) per substep.
    pub linear_damping: f64,
    /// Angular damping rate (1/s): ω ← ω / (1 + h c) per substep.
    pub angular_damping: f64,
    /// The program's own value for this body.
    pub user_value: u64,
    /// Whether its rotation is locked (its inertia is then `None`).
    pub fixed_rotation: bool,
    /// Its mass (kg) and inertia (kg·m²) as a dynamic body, kept while it
    /// is static or kinematic (whose mass is infinite) or its rotation is
    /// locked; `None` for a body created static or kinematic and never
    /// given any.
    pub dynamic_mass: Option<(f64, Option<f64>)>,
    /// While the body is disabled: the body itself, its velocity (m/s) and
    /// angular velocity (rad/s) (the world holds an inert static body
    /// without a shape, at rest, in its place).
    pub disabled: Option<(Body, Vector2<f64>, f64)>,
}

impl BodyControl {
    /// The control of a body just created as `body`.
    pub(crate) fn of(body: &Body) -> Self {
        Self {
            gravity_scale: 1.0,
            linear_damping: 0.0,
            angular_damping: 0.0,
            user_value: 0,
            fixed_rotation: false,
            dynamic_mass: body.is_dynamic().then_some((body.mass, body.inertia)),
            disabled: None,
        }
    }

    /// Whether the soft step's velocity stage must read this control
    /// (gravity scaled or velocities damped).
    pub(crate) fn acts(&self) -> bool {
        self.gravity_scale != 1.0 || self.linear_damping != 0.0 || self.angular_damping != 0.0
    }
}

impl std::fmt::Debug for ForceEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} during {:?}", self.force.name(), self.window)
    }
}

/// The state a contact model advances.
#[derive(Debug, Default, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct WorldCore {
    pub bodies: Vec<Body>,
    pub states: Vec<BodyState>,
    #[cfg_attr(
        feature = "serde",
        serde(
            serialize_with = "crate::world::serialize_forces",
            deserialize_with = "crate::world::deserialize_forces"
        )
    )]
    pub forces: Vec<ForceEntry>,
    pub events: Vec<EventSpec>,
    /// Current time (s).
    pub time: f64,
    /// Whether a terminal event stopped the run.
    pub stopped: bool,
    /// Bound on |total energy| (J) past which a step is a blow-up.
    pub energy_limit: Option<f64>,
    /// Not written as bytes: a restored world's profile starts at zero.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub profiler: Profiler,
    /// Per body: whether it was removed ([`crate::World::remove_body`]).
    pub removed: Vec<bool>,
    /// Per body: what the program set on it after creating it.
    pub controls: Vec<BodyControl>,
    /// Whether some body's control scales its gravity or damps it (the
    /// soft step's velocity stage then reads the controls).
    pub controls_act: bool,
    /// The id the next force added gets.
    pub next_force_id: u64,
    /// Per body: the force and torque a program applied for the next step
    /// ([`crate::World::apply_force`]); empty when none is pending.
    pub applied: Vec<Wrench>,
    /// Per joint: the program's own value (grown when one is set).
    pub joint_user_values: Vec<u64>,
}

impl WorldCore {
    /// Total energy at `t` for `states` (J).
    pub(crate) fn energy_of(&self, t: f64, states: &[BodyState]) -> f64 {
        total_energy(&self.bodies, &self.forces, t, states)
    }
}

/// Kinetic energy plus the potentials of the forces active at `t` (J).
pub(crate) fn total_energy(
    bodies: &[Body],
    forces: &[ForceEntry],
    t: f64,
    states: &[BodyState],
) -> f64 {
    let ctx = ForceContext { t, bodies, states };
    let kinetic: f64 = bodies
        .iter()
        .zip(states)
        .map(|(b, s)| b.kinetic_energy(s))
        .sum();
    let potential: f64 = forces
        .iter()
        .filter(|f| f.window.contains(t))
        .filter_map(|f| f.force.potential_energy(&ctx))
        .sum();
    kinetic + potential
}

/// The energy guard after the step `(t, t_next)`: a NaN energy or one
/// beyond `limit` (J) is a blow-up naming the step (its start time and
/// 0-based index), as the non-finite check does.
pub(crate) fn check_energy_value(
    energy: f64,
    (t, t_next): (f64, f64),
    step: u64,
    limit: f64,
    (bodies, states): (&[Body], &[BodyState]),
) -> Result<()> {
    if energy.is_nan() || energy.abs() > limit {
        return Err(EngineError::BlowUp {
            t,
            step,
            reason: format!(
                "energy {} J at t = {} s beyond {}{}",
                crate::error::readable(energy),
                crate::error::readable(t_next),
                if limit == f64::MAX {
                    // The guard of a world built from a scene: finite.
                    "the largest finite f64, 1.8e308 J".to_owned()
                } else {
                    format!("the bound {} J", crate::error::readable(limit))
                },
                culprit(bodies, states)
            ),
        });
    }
    Ok(())
}

/// `"; body 'x' carries the most kinetic energy (… J, … m/s)"`: the body a
/// blow-up most likely comes from, or nothing without dynamic bodies.
fn culprit(bodies: &[Body], states: &[BodyState]) -> String {
    let worst = bodies
        .iter()
        .zip(states)
        .filter(|(b, _)| b.is_dynamic())
        .map(|(b, s)| (b, s, b.kinetic_energy(s)))
        .max_by(|x, y| {
            // A NaN energy is the worst of all.
            let key = |e: f64| if e.is_nan() { f64::INFINITY } else { e };
            key(x.2).total_cmp(&key(y.2))
        });
    match worst {
        Some((b, s, e)) => format!(
            "; body '{}' carries the most kinetic energy ({} J, speed {} m/s)",
            b.name,
            crate::error::approximate(e),
            crate::error::approximate(s.velocity.norm())
        ),
        None => String::new(),
    }
}
