//! The soft step's settings, each with its unit, default and effect (Box2D
//! v3's `b2WorldDef` defaults unless said otherwise).

use crate::error::{EngineError, Result, require_non_negative, require_positive};
use crate::material::MixingRule;
use crate::tunables;

/// Settings of the soft-step contact model. `Default` gives Box2D v3's
/// defaults with sleeping off.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SoftStepSettings {
    /// Substeps per step (≥ 1). Each substep integrates velocities, warm
    /// starts, solves the contacts with their soft bias, integrates
    /// positions and relaxes. More substeps make contacts stiffer and
    /// stacks steadier at a cost linear in the count. Default 4 (Box2D's).
    pub substeps: usize,
    /// Natural frequency f (Hz, > 0) of the spring that pushes overlapping
    /// dynamic bodies apart. It is capped at a quarter of the Nyquist
    /// frequency of the substep, 1/(8h), so that it stays stable: at 60 Hz
    /// with 4 substeps the cap is 30 Hz. Contacts against static and
    /// kinematic bodies use twice this value (Box2D's rule, so a pile is not
    /// pushed into the ground). A resting body sinks by about
    /// g/(2πf)² below its support (0.28 mm at 30 Hz and g = 10 m/s²,
    /// against a 60 Hz static contact 0.07 mm). Default 30 Hz.
    pub contact_hertz: f64,
    /// Damping ratio ζ (≥ 0, dimensionless) of that spring: 1 is critical;
    /// Box2D's 10 is heavily over-damped, so an overlap is removed without
    /// bounce. Default 10.
    pub contact_damping_ratio: f64,
    /// Largest speed (m/s, > 0) at which the soft bias pushes overlapping
    /// bodies apart: bounds the energy a deep overlap can inject. A body
    /// deep inside several others shares it among those contacts (see
    /// `docs/soft_step.md`, the contact update). Default 3 m/s.
    pub push_out_speed: f64,
    /// Relative normal speed (m/s, ≥ 0) below which no restitution is
    /// applied: slow contacts do not bounce, so a resting pile of
    /// restitution e > 0 settles. Default 1 m/s.
    pub restitution_threshold: f64,
    /// Speculative distance (m, ≥ 0): shapes closer than this get contact
    /// points before they touch, with their separation in the bias (the
    /// solver lets them close the gap in one substep and no more), so a
    /// body arriving at moderate speed stops on contact instead of
    /// overlapping first. Default 0.02 m (4 × Box2D's linear slop).
    pub speculative_distance: f64,
    /// Largest margin (m, > 0) by which a moving body's bounding box is
    /// enlarged in the broad phase: a body that moves less than its margin
    /// stays in its box and costs no broad-phase work. Each shape's margin
    /// is this, but at most 1/8 of the shape's extent (Box2D v3.2's rule):
    /// small shapes packed closer than this would otherwise all overlap
    /// their neighbours' boxes and each such pair cost a contact. Default
    /// 0.1 m.
    pub aabb_margin: f64,
    /// Friction coefficient μ (≥ 0) of a body that does not give its own.
    /// A pair uses the geometric mean √(μa μb) (Box2D's rule). Default 0.6
    /// (Box2D's shape default).
    pub friction: f64,
    /// Restitution e ∈ [0, 1] of a body that does not give its own. A pair
    /// uses the larger of the two (Box2D's rule). Default 0.
    pub restitution: f64,
    /// Contact recycling distance (m, ≥ 0): when the relative pose of a
    /// pair moved by less than this (and turned by less than about 11.5°)
    /// since its manifold was last computed, the manifold is kept and only
    /// its separations are updated from the bodies' motion, as inside the
    /// substeps (after Box2D v3.2). 0 recomputes every manifold every step.
    /// Default 0.05 m (10 × Box2D's linear slop).
    pub recycle_distance: f64,
    /// Whether fast bodies are swept against static ones after each step
    /// (time of impact), so that a small fast body cannot pass through a
    /// thin wall between two steps. Default on.
    pub continuous: bool,
    /// Whether islands of bodies at rest fall asleep (are no longer
    /// simulated until something touches them). Default off: no sleeping
    /// the scene did not ask for, and the benchmarks and validation rows
    /// measure every body.
    pub sleeping: bool,
    /// Speed (m/s, > 0) below which a body counts as at rest for sleeping
    /// (its largest point speed). Default 0.05 m/s (Box2D's).
    pub sleep_threshold: f64,
    /// Time (s, > 0) every body of an island must have been at rest before
    /// the island sleeps. Default 0.5 s (Box2D's).
    pub time_to_sleep: f64,
    /// Whether each point starts a step with the impulses it ended the last
    /// one with (warm starting). Default on; off only to study the solver.
    pub warm_starting: bool,
    /// How a pair mixes its two shapes' friction coefficients. Default the
    /// geometric mean √(μa μb) (Box2D's).
    pub friction_mixing: MixingRule,
    /// How a pair mixes its two shapes' restitutions. Default the larger
    /// (Box2D's).
    pub restitution_mixing: MixingRule,
    /// Rolling resistance coefficient (≥ 0, dimensionless) of a shape that
    /// does not give its own ([`crate::material`]). Default 0 (Box2D's).
    pub rolling_resistance: f64,
    /// Approach speed (m/s, ≥ 0) above which a pair that begins touching
    /// reports a hit event ([`super::StepEvents::hits`]). Default 1 m/s
    /// (Box2D's `hitEventThreshold`).
    pub hit_event_threshold: f64,
    /// Threads (≥ 1) that run the step's stages that scale (collide,
    /// prepare, each colour's constraints in the solver passes,
    /// integration, store, continuous), on a pool the model keeps
    /// (docs/soft_step.md, "Threads"). Every count gives the same bits: the
    /// results do not depend on it, only the time. Default 1.
    #[cfg_attr(feature = "serde", serde(default = "one_thread"))]
    pub threads: usize,
    /// The least work per thread for which a step of several `threads`
    /// runs its stages on them: the step's contacts, joints and bodies
    /// (counted after the pairs stage), divided by `threads`. A smaller
    /// step runs on the calling thread alone, with the same bits: a
    /// parallel substep meets at a barrier after every colour (about a
    /// hundred a step), which costs more than the split saves on a small
    /// scene (`harness bench`, 2 threads against 1: the 56-box pyramid,
    /// 201 such items, 0.70×; the 211-box one, 801 items, 1.04×).
    /// 0: always on the threads. Default 256.
    #[cfg_attr(feature = "serde", serde(default = "default_min_work"))]
    pub min_work_per_thread: usize,
}

/// The default [`SoftStepSettings::min_work_per_thread`] (for worlds
/// written before the setting).
#[cfg(feature = "serde")]
fn default_min_work() -> usize {
    MIN_WORK_PER_THREAD_DEFAULT
}

/// The default of [`SoftStepSettings::min_work_per_thread`]: between the
/// 100 items a thread of the 56-box pyramid has on 2 threads (slower than
/// on one) and the 400 of the 211-box one (as fast).
pub const MIN_WORK_PER_THREAD_DEFAULT: usize = 256;

/// The default thread count (for worlds written before the setting).
#[cfg(feature = "serde")]
fn one_thread() -> usize {
    1
}

/// The most threads a step may use (far beyond what the stages scale to).
pub const MAX_THREADS: usize = 256;

impl Default for SoftStepSettings {
    fn default() -> Self {
        Self {
            substeps: tunables::SOFT_SUBSTEPS_DEFAULT,
            contact_hertz: tunables::SOFT_CONTACT_HERTZ_DEFAULT,
            contact_damping_ratio: tunables::SOFT_CONTACT_DAMPING_RATIO_DEFAULT,
            push_out_speed: tunables::SOFT_PUSH_OUT_SPEED_DEFAULT,
            restitution_threshold: tunables::SOFT_RESTITUTION_THRESHOLD_DEFAULT,
            speculative_distance: tunables::SOFT_SPECULATIVE_DISTANCE_DEFAULT,
            aabb_margin: tunables::SOFT_AABB_MARGIN_DEFAULT,
            friction: tunables::SOFT_FRICTION_DEFAULT,
            restitution: tunables::SOFT_RESTITUTION_DEFAULT,
            recycle_distance: tunables::SOFT_RECYCLE_DISTANCE_DEFAULT,
            continuous: true,
            sleeping: false,
            sleep_threshold: tunables::SOFT_SLEEP_THRESHOLD_DEFAULT,
            time_to_sleep: tunables::SOFT_TIME_TO_SLEEP_DEFAULT,
            warm_starting: true,
            friction_mixing: MixingRule::GeometricMean,
            restitution_mixing: MixingRule::Max,
            rolling_resistance: tunables::SOFT_ROLLING_RESISTANCE_DEFAULT,
            hit_event_threshold: tunables::SOFT_HIT_EVENT_THRESHOLD_DEFAULT,
            threads: 1,
            min_work_per_thread: MIN_WORK_PER_THREAD_DEFAULT,
        }
    }
}

impl SoftStepSettings {
    /// Checks every field's domain.
    pub fn validate(&self) -> Result<()> {
        if self.substeps == 0 || self.substeps > 1024 {
            return Err(EngineError::InvalidParameter {
                what: "substeps".into(),
                value: self.substeps as f64,
                reason: "must be between 1 and 1024",
            });
        }
        if self.threads == 0 || self.threads > MAX_THREADS {
            return Err(EngineError::InvalidParameter {
                what: "threads".into(),
                value: self.threads as f64,
                reason: "must be between 1 and 256",
            });
        }
        require_positive("contact hertz", self.contact_hertz)?;
        require_non_negative("contact damping ratio", self.contact_damping_ratio)?;
        require_positive("push-out speed", self.push_out_speed)?;
        require_non_negative("restitution threshold", self.restitution_threshold)?;
        require_non_negative("speculative distance", self.speculative_distance)?;
        require_positive("AABB margin", self.aabb_margin)?;
        require_non_negative("friction", self.friction)?;
        crate::error::require_unit_interval("restitution", self.restitution)?;
        require_non_negative("recycle distance", self.recycle_distance)?;
        require_positive("sleep threshold", self.sleep_threshold)?;
        require_positive("time to sleep", self.time_to_sleep)?;
        require_non_negative("rolling resistance", self.rolling_resistance)?;
        require_non_negative("hit event threshold", self.hit_event_threshold)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_box2d_like() {
        let s = SoftStepSettings::default();
        assert!(s.validate().is_ok());
        assert_eq!(
            (s.substeps, s.contact_hertz, s.contact_damping_ratio),
            (4, 30.0, 10.0)
        );
        assert!(!s.sleeping);
    }

    #[test]
    fn out_of_domain_settings_are_refused() {
        let d = SoftStepSettings::default();
        for bad in [
            SoftStepSettings { substeps: 0, ..d },
            SoftStepSettings { threads: 0, ..d },
            SoftStepSettings {
                contact_hertz: 0.0,
                ..d
            },
            SoftStepSettings {
                contact_hertz: f64::NAN,
                ..d
            },
            SoftStepSettings {
                push_out_speed: -1.0,
                ..d
            },
            SoftStepSettings {
                restitution: 1.5,
                ..d
            },
            SoftStepSettings {
                friction: -0.1,
                ..d
            },
            SoftStepSettings {
                aabb_margin: 0.0,
                ..d
            },
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }
}
