//! The settings of contact handling, with their units, defaults and effect
//! (Box2D's definition structs; rapier's habit of documenting every
//! parameter).

use crate::error::{EngineError, Result, require_non_negative, require_positive};
use crate::tunables;

/// How the time of first contact inside a step is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ToiMethod {
    /// The seed's bisection for a pair that interpenetrates at the end of
    /// the step, and conservative advancement for a pair apart at both ends
    /// whose motion could have closed the gap inside the step: with B the
    /// bound on the speed at which its points approach (relative speed plus
    /// |ω| times the rotation radius of each shape, the larger of its
    /// values at both ends of the step) and d₀, d₁ the separations at both
    /// ends, the pair stays apart by more than ε over the whole step when
    /// d₀ + d₁ > B h + 2ε (its separation cannot fall faster than B, from
    /// either end), and is advanced otherwise. A pair whose end overlaps is
    /// located exactly as by [`ToiMethod::Bisection`], so nothing changes
    /// where the seed's search sees the contact; a body crossing a thin one
    /// within a step is caught. The bound takes the speeds at the step's
    /// ends: exact under constant accelerations (bodies under gravity), a
    /// guard otherwise. The default.
    #[default]
    Swept,
    /// The seed's bisection of the step (seed §7.2, Fig. 7.7–7.8): when a
    /// pair interpenetrates by more than ε at the end of a step, the
    /// integrator recomputes the state at t + Δt/2, then t + Δt/4 or
    /// t + 3Δt/4, and so on, until the separation is within ±ε. Looks only
    /// at the end of the step: a body crossing a thin one within one step is
    /// missed (tunnelling).
    Bisection,
    /// Conservative advancement on the integrator's own solution for every
    /// pair apart at the step's start: from the separation d at a time s
    /// inside the step, no point can close the gap faster than a bound on
    /// the relative speed of the two shapes' points (the larger of its
    /// values at both ends of the step), so the pair cannot touch before
    /// s + d/bound; advance to it and repeat until d ≤ ε. Stops in [0, ε]
    /// (never overlapping) and does not tunnel.
    ConservativeAdvancement,
}

/// Contact settings of a world. `Default` gives a perfectly elastic,
/// frictionless contact (no loss the scene did not ask for) with tolerances
/// far below every validation tolerance of the harness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings {
    /// Coefficient of restitution e ∈ [0, 1] (seed eq. 7.10): the normal
    /// relative velocity after an impact is −e times the one before.
    /// Default 1.
    pub restitution: f64,
    /// Coulomb friction coefficient μ ≥ 0 (static and kinetic alike): the
    /// tangential force is at most μ times the normal force, and equals it
    /// (against the sliding direction) while the contact slides. Default 0.
    pub friction: f64,
    /// ε (m) > 0: two shapes closer than ε (or overlapping by less than ε)
    /// touch (seed Fig. 7.7). The time of impact is located until the
    /// separation is within ±ε. Default 1e-10 m: about 1e4 ulps of a
    /// 100 m coordinate, so the bisection can always reach it, and small
    /// enough that the energy e=1 reflection never sees it (it reflects the
    /// velocity exactly whatever the residual gap).
    pub tolerance: f64,
    /// Approach speed (m/s) > 0 at or below which a touching contact is
    /// *resting*: no restitution is applied (the approach velocity is
    /// cancelled) and the pair is held by contact forces computed inside
    /// the integration (seed §7.1 after Baraff). Above it, an impact with
    /// restitution, unless the rebound e·v would itself be slower than the
    /// resting speed (the point then rests). A touching point left
    /// separating slower than the resting speed (and faster than
    /// [`Self::sliding_speed`]) after the impulses rests too: its
    /// separation is cancelled, which only removes energy. Default
    /// 1e-3 m/s: a bounce of at most v²/(2g) = 5e-8 m is then given up,
    /// which ends the infinite sequence of ever smaller bounces of e < 1
    /// (and of a box rocking on its corners) in finite time.
    pub resting_speed: f64,
    /// Tangential speed (m/s) ≥ 0 at or below which a resting contact with
    /// friction *sticks* (static friction holds it, within the cone);
    /// above it the contact slides with kinetic friction μ·N against the
    /// sliding direction until the tangential velocity reaches zero, a time
    /// located by root finding. Default 1e-9 m/s.
    pub sliding_speed: f64,
    /// How the first contact inside a step is found. Default
    /// [`ToiMethod::Swept`] (the seed's bisection, and conservative
    /// advancement where a pair could have touched inside the step).
    pub toi_method: ToiMethod,
    /// Most distance evaluations of one time-of-impact search before the
    /// step is refused with an error. Default 200.
    pub max_toi_iterations: usize,
    /// Most contact events (impacts, stick/slip changes) handled inside
    /// one step before it is refused with an error: a guard against an
    /// endless sequence of ever smaller impacts. Default 10 000.
    pub max_events_per_step: usize,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            restitution: tunables::EXACT_RESTITUTION_DEFAULT,
            friction: tunables::EXACT_FRICTION_DEFAULT,
            tolerance: tunables::EXACT_TOLERANCE_DEFAULT,
            resting_speed: tunables::EXACT_RESTING_SPEED_DEFAULT,
            sliding_speed: tunables::EXACT_SLIDING_SPEED_DEFAULT,
            toi_method: ToiMethod::Swept,
            max_toi_iterations: tunables::EXACT_MAX_TOI_ITERATIONS_DEFAULT,
            max_events_per_step: tunables::EXACT_MAX_EVENTS_PER_STEP_DEFAULT,
        }
    }
}

impl ContactSettings {
    /// The default settings with restitution `e` and friction `mu`.
    pub fn new(restitution: f64, friction: f64) -> Self {
        Self {
            restitution,
            friction,
            ..Self::default()
        }
    }

    /// Checks every field's domain.
    pub fn validate(&self) -> Result<()> {
        let e = self.restitution;
        if !(e.is_finite() && (0.0..=1.0).contains(&e)) {
            return Err(EngineError::InvalidParameter {
                what: "restitution".into(),
                value: e,
                reason: "must be in [0, 1]",
            });
        }
        require_non_negative("friction", self.friction)?;
        require_positive("contact tolerance", self.tolerance)?;
        require_positive("resting speed", self.resting_speed)?;
        require_non_negative("sliding speed", self.sliding_speed)?;
        if self.max_toi_iterations == 0 || self.max_events_per_step == 0 {
            return Err(EngineError::InvalidParameter {
                what: "contact iteration limits".into(),
                value: 0.0,
                reason: "must be >= 1",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_elastic_frictionless_and_valid() {
        let s = ContactSettings::default();
        assert_eq!((s.restitution, s.friction), (1.0, 0.0));
        assert!(s.validate().is_ok());
    }

    #[test]
    fn out_of_domain_settings_are_refused() {
        for bad in [
            ContactSettings::new(1.5, 0.0),
            ContactSettings::new(-0.1, 0.0),
            ContactSettings::new(f64::NAN, 0.0),
            ContactSettings::new(0.5, -1.0),
            ContactSettings {
                tolerance: 0.0,
                ..ContactSettings::default()
            },
            ContactSettings {
                max_toi_iterations: 0,
                ..ContactSettings::default()
            },
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }
}
