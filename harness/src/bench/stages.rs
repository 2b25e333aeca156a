//! Where a step's time goes in this engine and in Box2D, stage by stage,
//! and what would close a missed speed target.
//!
//! # The profiled runs
//!
//! After a scene's timed repeats, each engine runs the scene again,
//! profiled, apart from the timing (its own timers cost a little): built
//! afresh, step 0 untimed, then the same number of steps; a few times,
//! alternating between the engines, keeping each one's fastest run
//! ([`PROFILED_REPEATS`]). This engine
//! sums its phases over the steps ([`engine::StepProfile`], on for this
//! run only); Box2D's timers are always on and hold the last step only
//! (`b2Profile`, [`references::box2d_world::profile`]), so the run reads
//! them after every step and sums them. Each sum over the steps, divided
//! by the steps, is a stage's ms per step. The run also times its steps
//! on the wall clock (Box2D's: around each step call only, not the
//! readings); the wall time per step less the sum of the stages is the
//! row *outside the stages*: the call into the engine, the timers' own
//! cost, and work no timer covers (for Box2D, the arena frees after its
//! stages). The stages and that row thus add up to the profiled run's
//! wall time per step, for each engine. This is done at one thread, and
//! at the run's larger thread count when it has one (this engine on its
//! pool, Box2D with that many workers).
//!
//! # The correspondence
//!
//! | stage | this engine | Box2D (`b2Profile` fields) |
//! | --- | --- | --- |
//! | pairs | `pairs` | `pairs` |
//! | collide | `collide` | `collide` |
//! | prepare | `prepare` | `solver_setup` + `prepare_constraints` |
//! | integrate | `integrate` | `integrate_velocities` + `integrate_positions` |
//! | warm_start | `warm_start` | `warm_start` |
//! | solve | `solve` | `solve_impulses` |
//! | relax | `relax` | `relax_impulses` |
//! | restitution | `restitution` | `apply_restitution` |
//! | store | `store` | `store_impulses` |
//! | finalize | `continuous` | `transforms` + `refit` + `bullets` |
//! | other | `sleep` (and any other phase) | `joint_events` + `hit_events` + `sensor_hits` + `sensors` + `sleep_islands` |
//!
//! Where the boundaries differ: [`BOUNDARIES`] (printed in the report
//! too, so written once).
//!
//! # What would close a missed target
//!
//! [`Gap`]: from the target's own figures (the minima of the timed runs),
//! the ms per step this engine must lose to meet it (ours − factor ×
//! Box2D's), and the stages where this engine's profiled time exceeds
//! Box2D's, largest first, with their excess.

use super::ours::SoftStepEngine;
use anyhow::Result;
use references::box2d_world::Box2dWorld;
use references::box2d_world::profile::LEAVES;
use references::many_body::{ManyBodyEngine, ManyBodyScene};
use scene::Scene;
use serde::Serialize;
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

/// The common stages in step order, each with this engine's phases and
/// Box2D's timers that make it (the module documentation's table; this
/// engine's phases not listed count in `other`).
pub const STAGES: [(&str, &[&str], &[&str]); 11] = [
    ("pairs", &["pairs"], &["pairs"]),
    ("collide", &["collide"], &["collide"]),
    (
        "prepare",
        &["prepare"],
        &["solver_setup", "prepare_constraints"],
    ),
    (
        "integrate",
        &["integrate"],
        &["integrate_velocities", "integrate_positions"],
    ),
    ("warm_start", &["warm_start"], &["warm_start"]),
    ("solve", &["solve"], &["solve_impulses"]),
    ("relax", &["relax"], &["relax_impulses"]),
    ("restitution", &["restitution"], &["apply_restitution"]),
    ("store", &["store"], &["store_impulses"]),
    (
        "finalize",
        &["continuous"],
        &["transforms", "refit", "bullets"],
    ),
    (
        "other",
        &["sleep"],
        &[
            "joint_events",
            "hit_events",
            "sensor_hits",
            "sensors",
            "sleep_islands",
        ],
    ),
];

/// Where the two engines' stage boundaries differ, one caveat a sentence
/// (the one statement of them: the report prints them, the
/// documentation points here).
pub const BOUNDARIES: [&str; 6] = [
    "pairs: with one worker Box2D rebuilds its dynamic tree inside `pairs`; with more, \
     alongside the narrow phase and the solver, waited for in `refit` (finalize); this \
     engine rebuilds its tree before the queries, inside `pairs`, at every thread count.",
    "prepare: Box2D's `solver_setup` (the awake contacts gathered, the graph colours' blocks \
     and the solver's stages laid out) is counted with its constraint preparation; this \
     engine's `prepare` also loads the bodies into the solver's records and prepares the \
     joints.",
    "store: this engine's `store` also writes the bodies' states back to the world and \
     reports the touches; Box2D writes its bodies back in `transforms` (finalize) and reports \
     events in `other`.",
    "finalize: both finalize the poses and the shapes' boxes, sweep fast bodies against static \
     ones and move the proxies of the broad phase.",
    "On several threads this engine times the substeps as one (its pool runs integrate, warm \
     start, solve and relax as one parallel stage) and stores the contact impulses with \
     restitution; so the comparison there merges integrate, warm_start, solve and relax into \
     substeps, and restitution and store into restitution and store, for both engines.",
    "Box2D's `split_islands` is not counted: inside `solver_setup` with one worker, alongside \
     the solver with more, and only with sleeping on (off in the benchmark).",
];

/// Profiled runs per engine and thread count (at most; no more than the
/// timing's repeats), alternating between the engines; each engine's
/// fastest run (least wall time per step) is kept, as the timing keeps its
/// minimum: on a shared machine one run can be slowed several times over
/// by other work, which a single run would print as the engine's profile.
/// Three keeps the profiled runs under a third of the timed ones (10
/// repeats in `harness bench`).
pub const PROFILED_REPEATS: usize = 3;

/// `run`, or `kept` if that was faster (less wall time per step).
pub fn faster(kept: Option<ProfiledRun>, run: ProfiledRun) -> ProfiledRun {
    match kept {
        Some(k) if k.wall_ms <= run.wall_ms => k,
        _ => run,
    }
}

/// The row of the wall time no stage covers.
pub const OUTSIDE: &str = "outside the stages";

/// The stage of the comparison on several threads that a fine stage
/// counts in (see the module documentation).
pub fn coarse(stage: &'static str) -> &'static str {
    match stage {
        "integrate" | "warm_start" | "solve" | "relax" => "substeps",
        "restitution" | "store" => "restitution and store",
        s => s,
    }
}

/// One engine's profiled run: its timers' sums and its wall time, each
/// divided by the steps (ms per step).
#[derive(Debug, Clone, PartialEq)]
pub struct ProfiledRun {
    /// The engine's own timers by its own names.
    pub timers: Vec<(&'static str, f64)>,
    /// Wall time per step.
    pub wall_ms: f64,
}

/// One stage in both engines (ms per step).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageTime {
    /// The common stage.
    pub stage: &'static str,
    /// This engine's time in it.
    pub ours_ms: f64,
    /// Box2D's time in it.
    pub box2d_ms: f64,
}

/// Both engines' profiled runs at one thread count, stage by stage.
#[derive(Debug, Clone, PartialEq)]
pub struct StageComparison {
    /// Threads of both runs (Box2D's workers).
    pub threads: usize,
    /// The stages in step order, then [`OUTSIDE`].
    pub stages: Vec<StageTime>,
}

/// `run`'s time in each stage (`run` is this engine's when `ours`, else
/// Box2D's), merged into the coarse stages when `merge`, with the
/// remainder of the wall time last.
fn stage_times(run: &ProfiledRun, ours: bool, merge: bool) -> Vec<(&'static str, f64)> {
    let mut out: Vec<(&'static str, f64)> = Vec::new();
    let mut add = |stage: &'static str, ms: f64| {
        let stage = if merge { coarse(stage) } else { stage };
        match out.iter_mut().find(|(s, _)| *s == stage) {
            Some(slot) => slot.1 += ms,
            None => out.push((stage, ms)),
        }
    };
    for (stage, our_names, box2d_names) in STAGES {
        add(stage, 0.0);
        for &(name, ms) in &run.timers {
            let mapped = if ours {
                our_names.contains(&name)
                    || (stage == "other" && !STAGES.iter().any(|s| s.1.contains(&name)))
            } else {
                box2d_names.contains(&name)
            };
            if mapped {
                add(stage, ms);
            }
        }
    }
    let counted: f64 = if ours {
        run.timers.iter().map(|t| t.1).sum()
    } else {
        run.timers
            .iter()
            .filter(|t| LEAVES.contains(&t.0))
            .map(|t| t.1)
            .sum()
    };
    out.push((OUTSIDE, run.wall_ms - counted));
    out
}

impl StageComparison {
    /// The comparison of `ours` and `box2d` at `threads` (the coarse
    /// stages above one thread).
    pub fn new(threads: usize, ours: &ProfiledRun, box2d: &ProfiledRun) -> Self {
        let merge = threads > 1;
        let a = stage_times(ours, true, merge);
        let b = stage_times(box2d, false, merge);
        let stages = a
            .iter()
            .zip(&b)
            .map(|(&(stage, ours_ms), &(_, box2d_ms))| StageTime {
                stage,
                ours_ms,
                box2d_ms,
            })
            .collect();
        Self { threads, stages }
    }

    /// One engine's stages as a map (ms per step), for its JSON row:
    /// `time` picks this engine's ([`StageTime::ours_ms`]) or Box2D's.
    pub fn map(&self, time: fn(&StageTime) -> f64) -> BTreeMap<String, f64> {
        self.stages
            .iter()
            .map(|s| (s.stage.to_string(), time(s)))
            .collect()
    }
}

/// What would close a missed speed target.
#[derive(Debug, Clone, PartialEq)]
pub struct Gap {
    /// ms per step this engine must lose: its time less the target's
    /// (factor × Box2D's).
    pub needed_ms: f64,
    /// The stages where this engine's profiled time exceeds the target's
    /// share (Box2D's, or for a speed-up its one-thread time over the
    /// factor), by how much (ms per step), largest first; those under
    /// 0.5 µs (which print as zero) left out.
    pub excess: Vec<(&'static str, f64)>,
    /// What the excess is measured against, in words.
    pub against: &'static str,
    /// What to say when no stage exceeds it.
    pub none: &'static str,
}

/// The [`Gap`] of the target "at most `factor` × Box2D's ms per step",
/// this engine at `ours_ms` and Box2D at `box2d_ms`, with the profiled
/// `stages`.
pub fn gap(ours_ms: f64, box2d_ms: f64, factor: f64, stages: &[StageTime]) -> Gap {
    let mut excess: Vec<(&'static str, f64)> = stages
        .iter()
        .map(|s| (s.stage, s.ours_ms - s.box2d_ms))
        .filter(|(_, d)| *d >= 0.5e-3)
        .collect();
    excess.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(b.0)));
    Gap {
        needed_ms: ours_ms - factor * box2d_ms,
        excess,
        against: "slower stages in the profiled runs",
        none: "no stage of this engine's profiled run is slower than Box2D's",
    }
}

/// The [`Gap`] of the target "on several threads at least `factor` times
/// faster than on one" for this engine at `one_ms` on one thread and
/// `many_ms` on several: the ms to lose on several threads, and the
/// stages of its profiled runs that fall short of the speed-up (the
/// several-thread time less the one-thread time over `factor`; the
/// one-thread stages `one` summed into the coarse stages of `many`).
pub fn speedup_gap(
    one_ms: f64,
    many_ms: f64,
    factor: f64,
    one: &[StageTime],
    many: &[StageTime],
) -> Gap {
    let mut excess: Vec<(&'static str, f64)> = many
        .iter()
        .map(|m| {
            let alone: f64 = one
                .iter()
                .filter(|o| coarse(o.stage) == m.stage)
                .map(|o| o.ours_ms)
                .sum();
            (m.stage, m.ours_ms - alone / factor)
        })
        .filter(|(_, d)| *d >= 0.5e-3)
        .collect();
    excess.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(b.0)));
    Gap {
        needed_ms: many_ms - one_ms / factor,
        excess,
        against: "stages short of the speed-up in the profiled runs (their time on several \
                  threads less their one-thread time over the factor)",
        none: "every stage of the profiled runs reaches the speed-up",
    }
}

impl Gap {
    /// In words: "needs −0.520 ms per step; slower stages in the profiled
    /// runs: prepare +0.350, relax +0.120 (sum +0.470 ms)".
    pub fn describe(&self) -> String {
        let mut out = format!("needs −{:.3} ms per step", self.needed_ms);
        if self.excess.is_empty() {
            out += &format!("; {}", self.none);
        } else {
            let stages: Vec<String> = self
                .excess
                .iter()
                .map(|(s, d)| format!("{s} +{d:.3}"))
                .collect();
            let sum: f64 = self.excess.iter().map(|e| e.1).sum();
            out += &format!(
                "; {}: {} (sum +{sum:.3} ms)",
                self.against,
                stages.join(", ")
            );
        }
        out
    }
}

/// This engine's profiled run of `scene` on `threads` threads: step 0,
/// then `steps` steps.
pub fn profile_ours(scene: &Scene, steps: usize, threads: usize) -> Result<ProfiledRun> {
    let mut engine = SoftStepEngine::with_threads(scene, true, threads)?;
    engine.step()?;
    let before = engine.world().profile();
    let started = Instant::now();
    for _ in 0..steps {
        engine.step()?;
    }
    let wall = started.elapsed();
    let n = steps.max(1) as f64;
    let timers = engine
        .world()
        .profile()
        .since(&before)
        .phases()
        .iter()
        .map(|(name, d)| (*name, 1e3 * d.as_secs_f64() / n))
        .collect();
    Ok(ProfiledRun {
        timers,
        wall_ms: 1e3 * wall.as_secs_f64() / n,
    })
}

/// Box2D's (the linked build's) profiled run of `neutral` with `workers`
/// workers: step 0, then `steps` steps, its timers read after each.
pub fn profile_box2d(neutral: &ManyBodyScene, steps: usize, workers: usize) -> Result<ProfiledRun> {
    let mut world = Box2dWorld::with_workers(neutral, workers)?;
    world.step()?;
    let mut sums = world.last_step_profile()?.map(|(name, _)| (name, 0.0));
    let mut wall = Duration::ZERO;
    for _ in 0..steps {
        let started = Instant::now();
        world.step()?;
        wall += started.elapsed();
        let last = world.last_step_profile()?;
        for (sum, (name, ms)) in sums.iter_mut().zip(last) {
            debug_assert_eq!(sum.0, name);
            sum.1 += ms;
        }
    }
    let n = steps.max(1) as f64;
    Ok(ProfiledRun {
        timers: sums.iter().map(|&(name, ms)| (name, ms / n)).collect(),
        wall_ms: 1e3 * wall.as_secs_f64() / n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stage(stage: &'static str, ours_ms: f64, box2d_ms: f64) -> StageTime {
        StageTime {
            stage,
            ours_ms,
            box2d_ms,
        }
    }

    #[test]
    fn the_gap_is_the_target_less_ours_and_the_slower_stages_largest_first() {
        let stages = [
            stage("pairs", 0.10, 0.12),
            stage("collide", 0.50, 0.42),
            stage("prepare", 0.80, 0.45),
            stage("solve", 1.00, 1.00),
            stage("relax", 0.62, 0.50),
            stage("finalize", 0.30, 0.3004),
        ];
        let g = gap(3.32, 3.0, 0.9, &stages);
        // 3.32 − 0.9 × 3.0 = 3.32 − 2.70 = 0.62 ms by hand.
        assert!((g.needed_ms - 0.62).abs() < 1e-12, "{g:?}");
        // By hand: prepare 0.80 − 0.45 = 0.35, relax 0.62 − 0.50 = 0.12,
        // collide 0.50 − 0.42 = 0.08; pairs and finalize are faster, solve
        // equal (0, under the 0.5 µs cut).
        let names: Vec<&str> = g.excess.iter().map(|e| e.0).collect();
        assert_eq!(names, ["prepare", "relax", "collide"]);
        for ((_, got), want) in g.excess.iter().zip([0.35, 0.12, 0.08]) {
            assert!((got - want).abs() < 1e-12, "{g:?}");
        }
        assert_eq!(
            g.describe(),
            "needs −0.620 ms per step; slower stages in the profiled runs: prepare +0.350, \
             relax +0.120, collide +0.080 (sum +0.550 ms)"
        );
        // No slower stage: said so.
        let even = gap(1.0, 1.0, 0.9, &[stage("solve", 0.5, 0.6)]);
        assert_eq!(
            even.describe(),
            "needs −0.100 ms per step; no stage of this engine's profiled run is slower \
             than Box2D's"
        );
    }

    #[test]
    fn a_missed_speed_up_names_the_stages_that_fall_short() {
        // One thread: integrate 0.2 and solve 0.6 (substeps 0.8 together),
        // prepare 0.5, store 0.1; two threads: substeps 0.5, prepare 0.45,
        // restitution and store 0.05.
        let one = [
            stage("prepare", 0.5, 0.0),
            stage("integrate", 0.2, 0.0),
            stage("solve", 0.6, 0.0),
            stage("store", 0.1, 0.0),
        ];
        let many = [
            stage("prepare", 0.45, 0.0),
            stage("substeps", 0.5, 0.0),
            stage("restitution and store", 0.05, 0.0),
        ];
        let g = speedup_gap(2.0, 1.25, 2.0, &one, &many);
        // By hand: 1.25 − 2.0/2 = 0.25 ms to lose; prepare 0.45 − 0.5/2 =
        // 0.20, substeps 0.5 − 0.8/2 = 0.10; restitution and store
        // 0.05 − 0.1/2 = 0 (under the cut).
        assert!((g.needed_ms - 0.25).abs() < 1e-12, "{g:?}");
        let names: Vec<&str> = g.excess.iter().map(|e| e.0).collect();
        assert_eq!(names, ["prepare", "substeps"]);
        for ((_, got), want) in g.excess.iter().zip([0.20, 0.10]) {
            assert!((got - want).abs() < 1e-12, "{g:?}");
        }
        assert!(
            g.describe().starts_with(
                "needs −0.250 ms per step; stages short of the speed-up in the profiled runs"
            ),
            "{}",
            g.describe()
        );
        assert!(
            g.describe()
                .ends_with("prepare +0.200, substeps +0.100 (sum +0.300 ms)")
        );
    }

    #[test]
    fn the_stages_and_the_remainder_add_up_to_the_wall_time() {
        // Box2D's sums (`step`, `solve`, `constraints`) and `split_islands`
        // are not counted again; its leaves land in their stages.
        let box2d = ProfiledRun {
            timers: vec![
                ("step", 9.0),
                ("pairs", 0.5),
                ("collide", 1.0),
                ("solve", 7.0),
                ("solver_setup", 0.25),
                ("constraints", 6.0),
                ("prepare_constraints", 0.5),
                ("integrate_velocities", 0.75),
                ("integrate_positions", 0.25),
                ("split_islands", 0.125),
                ("transforms", 0.5),
                ("refit", 0.25),
                ("sensors", 0.0625),
            ],
            wall_ms: 10.0,
        };
        let ours = ProfiledRun {
            timers: vec![
                ("broad_phase", 0.0),
                ("pairs", 0.25),
                ("prepare", 1.0),
                ("integrate", 0.5),
                ("continuous", 0.75),
                ("sleep", 0.125),
            ],
            wall_ms: 3.0,
        };
        let one = StageComparison::new(1, &ours, &box2d);
        let get = |c: &StageComparison, s: &str| {
            let t = c.stages.iter().find(|t| t.stage == s).unwrap();
            (t.ours_ms, t.box2d_ms)
        };
        assert_eq!(get(&one, "prepare"), (1.0, 0.75));
        assert_eq!(get(&one, "integrate"), (0.5, 1.0));
        assert_eq!(get(&one, "finalize"), (0.75, 0.75));
        assert_eq!(get(&one, "other"), (0.125, 0.0625));
        // Box2D's leaves: 0.5 + 1 + 0.25 + 0.5 + 0.75 + 0.25 + 0.5 + 0.25
        // + 0.0625 = 4.0625 ms of 10; ours 2.625 of 3.
        assert_eq!(get(&one, OUTSIDE), (0.375, 5.9375));
        let total = |c: &StageComparison, ours: bool| -> f64 {
            c.stages
                .iter()
                .map(|t| if ours { t.ours_ms } else { t.box2d_ms })
                .sum()
        };
        assert_eq!((total(&one, true), total(&one, false)), (3.0, 10.0));
        assert_eq!(one.stages.len(), STAGES.len() + 1);
        // On two threads: the substeps as one, restitution with store.
        let two = StageComparison::new(2, &ours, &box2d);
        assert_eq!(get(&two, "substeps"), (0.5, 1.0));
        assert!(two.stages.iter().all(|t| t.stage != "integrate"));
        assert_eq!(two.stages.len(), STAGES.len() + 1 - 4);
        assert_eq!((total(&two, true), total(&two, false)), (3.0, 10.0));
    }
}
