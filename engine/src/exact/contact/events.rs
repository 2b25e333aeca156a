//! The record of what contact handling did: impacts with their impulses,
//! contacts beginning and ending, sticking and slipping, and the time spent
//! in each phase of a step.

use crate::body::BodyId;
use nalgebra::Vector2;
use std::time::Duration;

/// What happened at a contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactEventKind {
    /// An impact: some point approached faster than the resting speed and
    /// got an impulse with restitution (seed eq. 7.15).
    Impact,
    /// A pair came to rest in contact (a resting contact began): it is now
    /// held by contact forces inside the integration.
    Rest,
    /// A resting pair separated (its contact ended).
    Release,
    /// A sliding contact stopped sliding: its tangential velocity reached
    /// zero (located by root finding) and static friction now holds it.
    Stick,
    /// A sticking contact started to slide.
    Slip,
}

impl ContactEventKind {
    /// A short stable name for reports and snapshots.
    pub fn id(&self) -> &'static str {
        match self {
            ContactEventKind::Impact => "impact",
            ContactEventKind::Rest => "rest",
            ContactEventKind::Release => "release",
            ContactEventKind::Stick => "stick",
            ContactEventKind::Slip => "slip",
        }
    }
}

/// One contact event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// When (s).
    pub t: f64,
    /// What happened.
    pub kind: ContactEventKind,
    /// The pair, `body_a < body_b`.
    pub body_a: BodyId,
    /// The second body of the pair.
    pub body_b: BodyId,
    /// Where (m, world frame): the contact point, or with two points their
    /// centre weighted by the normal impulses (their midpoint when no
    /// impulse was applied).
    pub point: Vector2<f64>,
    /// Unit contact normal, from `body_a` towards `body_b`.
    pub normal: Vector2<f64>,
    /// Number of contact points of the manifold (1 or 2).
    pub points: usize,
    /// Total normal impulse on `body_b` (N·s, ≥ 0); `body_a` gets the
    /// opposite. It is the j of seed eq. 7.15 for a single point.
    pub normal_impulse: f64,
    /// Total friction impulse on `body_b` along the tangent
    /// `(−normal.y, normal.x)` (N·s).
    pub tangent_impulse: f64,
    /// Relative normal velocity of the points before (m/s, < 0 when
    /// approaching): the most negative over the manifold's points.
    pub normal_velocity_before: f64,
    /// The same after the response (m/s).
    pub normal_velocity_after: f64,
}

/// Time spent in each phase of a step, and how often each ran, summed over
/// every step since the world was built (or the profile was reset). Filled
/// only when profiling is on ([`crate::World::set_profiling`]); otherwise
/// only the counters move.
///
/// The exact model fills `integrate`, `broad_phase`, `narrow_phase`, `toi`
/// and `respond`; the soft step fills `pairs`, `collide`, `prepare`,
/// `integrate` (velocities and positions, every substep), `warm_start`,
/// `solve`, `relax`, `restitution`, `store`, `continuous` and `sleep`, in
/// the order it runs them.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepProfile {
    /// Integrator steps (exact model), including the trial steps that a
    /// contact cut short; velocity and position integration (soft step).
    pub integrate: Duration,
    /// Bounding boxes and the sort-and-sweep.
    pub broad_phase: Duration,
    /// Exact tests of candidate pairs (distances and manifolds) outside the
    /// time-of-impact searches.
    pub narrow_phase: Duration,
    /// Time-of-impact and stick-time searches (each of their evaluations
    /// integrates a sub-step and measures a distance or a velocity).
    pub toi: Duration,
    /// Impulses, position projection, contact classification.
    pub respond: Duration,
    /// Soft step: new pairs from the broad phase's move buffer.
    pub pairs: Duration,
    /// Soft step: manifolds of every contact (narrow phase), destroying
    /// the pairs whose boxes parted.
    pub collide: Duration,
    /// Soft step: building the contact constraints.
    pub prepare: Duration,
    /// Soft step: applying the stored impulses, every substep.
    pub warm_start: Duration,
    /// Soft step: the biased solve, every substep.
    pub solve: Duration,
    /// Soft step: the relax pass (no bias, friction), every substep.
    pub relax: Duration,
    /// Soft step: the restitution pass.
    pub restitution: Duration,
    /// Soft step: storing impulses, writing states back, moving proxies.
    pub store: Duration,
    /// Soft step: time-of-impact sweeps of fast bodies.
    pub continuous: Duration,
    /// Soft step: islands and sleeping.
    pub sleep: Duration,
    /// Accepted integrator steps (a step cut at a contact counts once per
    /// piece).
    pub steps: u64,
    /// Candidate pairs handed to the narrow phase.
    pub candidate_pairs: u64,
    /// Time-of-impact or stick-time searches run.
    pub toi_searches: u64,
    /// Evaluations made by those searches.
    pub toi_evaluations: u64,
    /// Contact events recorded.
    pub events: u64,
    /// Soft step: contacts (pairs whose boxes overlap), summed over steps.
    pub contacts: u64,
    /// Soft step: touching contacts solved, summed over steps.
    pub touching: u64,
    /// Soft step: contact points solved, summed over steps.
    pub points: u64,
    /// Soft step: manifolds recycled instead of recomputed.
    pub recycled: u64,
}

impl StepProfile {
    /// Every phase with its name, in the order a step runs them (the
    /// exact model's, then the soft step's).
    pub fn phases(&self) -> [(&'static str, Duration); 15] {
        [
            ("broad_phase", self.broad_phase),
            ("narrow_phase", self.narrow_phase),
            ("toi", self.toi),
            ("respond", self.respond),
            ("pairs", self.pairs),
            ("collide", self.collide),
            ("prepare", self.prepare),
            ("integrate", self.integrate),
            ("warm_start", self.warm_start),
            ("solve", self.solve),
            ("relax", self.relax),
            ("restitution", self.restitution),
            ("store", self.store),
            ("continuous", self.continuous),
            ("sleep", self.sleep),
        ]
    }

    /// Total time of the phases (s).
    pub fn total_seconds(&self) -> f64 {
        self.phases().iter().map(|(_, d)| d.as_secs_f64()).sum()
    }
}
