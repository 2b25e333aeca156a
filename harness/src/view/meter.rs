//! The live numbers: over windows of [`WINDOW`] of wall time, the wall
//! time per step, the speed achieved, and the engine's step profile
//! (`World::profile`, `engine::StepProfile`) turned into per-step means:
//! the time of each phase and the work counters.

use super::frame::Status;
use engine::{StepProfile, World};
use std::time::{Duration, Instant};

/// How long the numbers are averaged over.
pub const WINDOW: Duration = Duration::from_millis(500);

/// Sums over the current window.
#[derive(Debug, Clone, Default)]
pub struct Meter {
    /// When the window began, the world's time and profile then.
    start: Option<(Instant, f64, StepProfile)>,
    steps: u64,
    stepping: Duration,
}

impl Meter {
    /// Counts one step that took `took` of wall time.
    pub fn add_step(&mut self, took: Duration) {
        self.steps += 1;
        self.stepping += took;
    }

    /// At the end of a window, writes its means into `status` and starts
    /// the next one; otherwise leaves `status` as it was.
    pub fn report(&mut self, world: &World, timings: bool, status: &mut Status, now: Instant) {
        let profile = world.profile();
        let Some((began, t0, p0)) = self.start else {
            self.start = Some((now, world.time(), profile));
            return;
        };
        let wall = now.saturating_duration_since(began);
        if wall < WINDOW {
            return;
        }
        status.achieved_speed = Some((world.time() - t0) / wall.as_secs_f64());
        means(status, (&p0, &profile), self.steps, self.stepping, timings);
        self.start = Some((now, world.time(), profile));
        self.steps = 0;
        self.stepping = Duration::ZERO;
    }
}

/// Writes into `status` the means per step of `steps` steps that took
/// `stepping` of wall time, between the profiles `then` and `now`: wall
/// time per step, each phase's time per step (when `timings`: the engine
/// measured them), the counters per step.
pub fn means(
    status: &mut Status,
    (then, now): (&StepProfile, &StepProfile),
    steps: u64,
    stepping: Duration,
    timings: bool,
) {
    let per = steps.max(1) as f64;
    status.step_ms = (steps > 0).then(|| 1e3 * stepping.as_secs_f64() / per);
    status.phases.clear();
    let added = now.since(then);
    if timings && steps > 0 {
        for (name, d) in added.phases() {
            let ms = 1e3 * d.as_secs_f64() / per;
            if ms > 0.0 {
                status.phases.push((name, ms));
            }
        }
    }
    let per_step = |n: u64| n as f64 / per;
    status.counters = vec![
        ("candidate pairs", per_step(added.candidate_pairs)),
        ("contacts", per_step(added.contacts)),
        ("touching", per_step(added.touching)),
        ("points", per_step(added.points)),
    ];
}
