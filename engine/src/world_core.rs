//! What every contact model of a [`crate::World`] works on: the bodies and
//! their states, the force generators with their windows, the events to
//! locate, the clock, and the per-phase profiler. The world owns one
//! [`WorldCore`] and hands it to its model ([`crate::ContactModel`]) at
//! every step; the models never see each other.

use crate::body::{Body, BodyState};
use crate::contact::pipeline::Profiler;
use crate::error::{EngineError, Result};
use crate::events::EventSpec;
use crate::forces::{Force, ForceContext, TimeWindow};

/// A force generator with the window in which it acts.
pub(crate) struct ForceEntry {
    pub force: Box<dyn Force>,
    pub window: TimeWindow,
    /// Whether this entry is the world's gravity setting
    /// ([`crate::World::set_gravity`]) rather than a force the user added.
    pub world_gravity: bool,
}

impl std::fmt::Debug for ForceEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} during {:?}", self.force.name(), self.window)
    }
}

/// The state a contact model advances.
#[derive(Debug, Default)]
pub(crate) struct WorldCore {
    pub bodies: Vec<Body>,
    pub states: Vec<BodyState>,
    pub forces: Vec<ForceEntry>,
    pub events: Vec<EventSpec>,
    /// Current time (s).
    pub time: f64,
    /// Whether a terminal event stopped the run.
    pub stopped: bool,
    /// Bound on |total energy| (J) past which a step is a blow-up.
    pub energy_limit: Option<f64>,
    pub profiler: Profiler,
    /// Per body: whether it was removed ([`crate::World::remove_body`]).
    pub removed: Vec<bool>,
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
