//! Where a step's time goes: the phases both contact models run, timed
//! into a [`StepProfile`] when profiling is on
//! ([`crate::World::set_profiling`]). Shared by the exact model
//! (module `exact`'s pipeline) and the soft step
//! ([`crate::soft_step`]), so neither imports the other to time itself.

use std::time::{Duration, Instant};

/// Per-phase timing, on only when asked (an `Instant::now` per phase would
/// otherwise cost more than a cheap step).
#[derive(Debug, Clone, Default)]
pub(crate) struct Profiler {
    pub on: bool,
    pub profile: StepProfile,
}

/// A phase of the step.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Phase {
    Integrate,
    Broad,
    Narrow,
    Toi,
    Respond,
    Pairs,
    Collide,
    Prepare,
    WarmStart,
    Solve,
    Relax,
    Restitution,
    Store,
    Continuous,
    Sleep,
}

impl Profiler {
    pub(crate) fn start(&self) -> Option<Instant> {
        self.on.then(Instant::now)
    }

    pub(crate) fn stop(&mut self, phase: Phase, started: Option<Instant>) {
        if let Some(s) = started {
            let d = s.elapsed();
            let slot: &mut Duration = match phase {
                Phase::Integrate => &mut self.profile.integrate,
                Phase::Broad => &mut self.profile.broad_phase,
                Phase::Narrow => &mut self.profile.narrow_phase,
                Phase::Toi => &mut self.profile.toi,
                Phase::Respond => &mut self.profile.respond,
                Phase::Pairs => &mut self.profile.pairs,
                Phase::Collide => &mut self.profile.collide,
                Phase::Prepare => &mut self.profile.prepare,
                Phase::WarmStart => &mut self.profile.warm_start,
                Phase::Solve => &mut self.profile.solve,
                Phase::Relax => &mut self.profile.relax,
                Phase::Restitution => &mut self.profile.restitution,
                Phase::Store => &mut self.profile.store,
                Phase::Continuous => &mut self.profile.continuous,
                Phase::Sleep => &mut self.profile.sleep,
            };
            *slot += d;
        }
    }
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

    /// What was added since `earlier` (an earlier reading of the same
    /// profile): every phase's time and every counter, each this reading's
    /// less `earlier`'s, at least zero (a profile reset in between reads
    /// as nothing added, not as a negative time).
    pub fn since(&self, earlier: &StepProfile) -> StepProfile {
        let t = |a: Duration, b: Duration| a.saturating_sub(b);
        let n = |a: u64, b: u64| a.saturating_sub(b);
        let e = earlier;
        StepProfile {
            integrate: t(self.integrate, e.integrate),
            broad_phase: t(self.broad_phase, e.broad_phase),
            narrow_phase: t(self.narrow_phase, e.narrow_phase),
            toi: t(self.toi, e.toi),
            respond: t(self.respond, e.respond),
            pairs: t(self.pairs, e.pairs),
            collide: t(self.collide, e.collide),
            prepare: t(self.prepare, e.prepare),
            warm_start: t(self.warm_start, e.warm_start),
            solve: t(self.solve, e.solve),
            relax: t(self.relax, e.relax),
            restitution: t(self.restitution, e.restitution),
            store: t(self.store, e.store),
            continuous: t(self.continuous, e.continuous),
            sleep: t(self.sleep, e.sleep),
            steps: n(self.steps, e.steps),
            candidate_pairs: n(self.candidate_pairs, e.candidate_pairs),
            toi_searches: n(self.toi_searches, e.toi_searches),
            toi_evaluations: n(self.toi_evaluations, e.toi_evaluations),
            events: n(self.events, e.events),
            contacts: n(self.contacts, e.contacts),
            touching: n(self.touching, e.touching),
            points: n(self.points, e.points),
            recycled: n(self.recycled, e.recycled),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn since_is_each_field_less_the_earlier_reading_never_below_zero() {
        let ms = Duration::from_millis;
        let earlier = StepProfile {
            solve: ms(3),
            sleep: ms(9),
            steps: 2,
            points: 10,
            recycled: 7,
            ..StepProfile::default()
        };
        let now = StepProfile {
            solve: ms(5),
            sleep: ms(4),
            prepare: ms(1),
            steps: 5,
            points: 16,
            recycled: 3,
            ..StepProfile::default()
        };
        let d = now.since(&earlier);
        // By hand: 5 − 3 ms, 1 − 0 ms, 5 − 2 steps, 16 − 10 points; the
        // sleep time and the recycled count went down (a reset): zero.
        assert_eq!((d.solve, d.prepare, d.sleep), (ms(2), ms(1), ms(0)));
        assert_eq!((d.steps, d.points, d.recycled), (3, 6, 0));
        assert_eq!(now.since(&StepProfile::default()), now);
        assert_eq!(now.since(&now), StepProfile::default());
    }
}
