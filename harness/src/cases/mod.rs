//! The validation cases. Each runs every method at the seed's step, compares
//! with its reference, and returns rows and sampled traces.

mod angular_drag;
mod collision_bounce;
pub mod collision_common;
mod collision_friction;
mod collision_impacts;
pub mod collision_parry;
mod collision_plots;
mod collision_toi;
mod hoffman;
mod projectile;
mod projectile_drag;
mod spring;
mod torque;

use crate::row::Row;
use anyhow::Result;
use engine::{Method, Tolerance};

/// Tolerance given to Dormand–Prince in every case: tight, so it serves as
/// the engine's own high-accuracy solution.
pub const DP_TOLERANCE: f64 = 1e-12;

/// Every method, fixed-step ones first, then Dormand–Prince at [`DP_TOLERANCE`].
pub fn all_methods() -> Vec<Method> {
    Method::FIXED_STEP
        .into_iter()
        .chain([Method::DormandPrince(Tolerance::uniform(DP_TOLERANCE))])
        .collect()
}

/// A global error bound for Dormand–Prince: each accepted step keeps its
/// local error within `tol × scale`, and at most `steps` of them add up.
pub fn dp_global_bound(steps: u64, scale: f64) -> f64 {
    steps.max(1) as f64 * DP_TOLERANCE * scale.max(1.0)
}

/// The reason that goes with [`dp_global_bound`].
pub fn dp_reason(steps: u64) -> String {
    format!(
        "Dormand-Prince rtol = atol = {DP_TOLERANCE:e}: sum of {steps} local errors, each <= tol x max|y|"
    )
}

/// A trace sampled for snapshots and plots: column names and rows of values
/// (the first column is time, s).
#[derive(Debug, Clone, PartialEq)]
pub struct MethodTrace {
    /// Method id.
    pub method: String,
    /// Step (s).
    pub dt: f64,
    /// Column names, starting with `t`.
    pub columns: Vec<&'static str>,
    /// One row per sample.
    pub samples: Vec<Vec<f64>>,
}

/// What a case produces.
#[derive(Debug, Clone, Default)]
pub struct CaseReport {
    /// Validation rows.
    pub rows: Vec<Row>,
    /// One trace per method at the seed step.
    pub traces: Vec<MethodTrace>,
    /// Remarks for the report (methods not applicable, ...).
    pub notes: Vec<String>,
}

/// A validation case.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Stable id (CASES.md).
    pub id: &'static str,
    /// One-line description.
    pub title: &'static str,
    /// Runs it.
    pub run: fn() -> Result<CaseReport>,
}

/// Every case, in the order of CASES.md.
pub const CASES: [Case; 14] = [
    Case {
        id: "spring",
        title: "Case I: mass-spring, RK4 at h = 0.2 s over 57.2 s (seed §5)",
        run: spring::run,
    },
    Case {
        id: "projectile",
        title: "Case II: projectile in vacuum, h = 0.01 s (seed §6)",
        run: projectile::run,
    },
    Case {
        id: "torque",
        title: "Case II: a 0.7 s torque pulse on the box (seed eq. 6.16-6.20)",
        run: torque::run,
    },
    Case {
        id: "projectile_drag",
        title: "Case II: projectile with quadratic drag (seed Table 6.2)",
        run: projectile_drag::run,
    },
    Case {
        id: "angular_drag",
        title: "Case II: torque pulse with angular drag -D w|w|",
        run: angular_drag::run,
    },
    Case {
        id: "hoffman",
        title: "Stiff test y' = -1000(y - (t + 2)) + 1 (seed §4.3, after Hoffman)",
        run: hoffman::run,
    },
    Case {
        id: "collision_parry",
        title: "Case III: detection against parry2d on 100 000 random convex pairs and 20 000 near-touching ones",
        run: collision_parry::run,
    },
    Case {
        id: "collision_toi",
        title: "Case III: time of impact, 2.0 s and 1.8736370117 s with rotation (seed Fig. 7.7-7.8), against parry2d",
        run: collision_toi::run,
    },
    Case {
        id: "collision_head_on",
        title: "Case III: head-on impact, 1 kg at 2 m/s on 3 kg at rest, e = 1 and 0.5 (seed eq. 7.15)",
        run: collision_impacts::run_head_on,
    },
    Case {
        id: "collision_off_centre",
        title: "Case III: off-centre impact of two boxes against eq. 7.15, momentum and energy",
        run: collision_impacts::run_off_centre,
    },
    Case {
        id: "collision_bounce",
        title: "Case III: a ball bouncing on fixed ground, e = 1 (100 bounces) and e = 0.8 (apex 0.64^n h0)",
        run: collision_bounce::run,
    },
    Case {
        id: "collision_slide",
        title: "Case III: a box sliding to a stop with Coulomb friction, v0²/(2 mu g)",
        run: collision_friction::run_slide,
    },
    Case {
        id: "collision_incline",
        title: "Case III: a box on an incline on both sides of tan θ = mu",
        run: collision_friction::run_incline,
    },
    Case {
        id: "collision_rest",
        title: "Case III: a box resting on the ground for 10 s (seed §7.1, after Baraff)",
        run: collision_friction::run_rest,
    },
];

/// The case with this id.
pub fn find(id: &str) -> Option<&'static Case> {
    CASES.iter().find(|c| c.id == id)
}

/// One line per row that fails, for an assertion message: check, method,
/// step (s), then value vs expected ± tolerance (in the value's unit). Empty
/// when every row passes.
pub fn failing_rows(rows: &[Row]) -> Vec<String> {
    rows.iter()
        .filter(|r| !r.pass)
        .map(|r| {
            format!(
                "{} {} dt={}: {} vs {} ± {}",
                r.check, r.method, r.dt, r.value, r.expected, r.tolerance
            )
        })
        .collect()
}

/// Keeps about `count` evenly spaced samples of a trace (always the last).
pub fn thin<T: Clone>(samples: &[T], count: usize) -> Vec<T> {
    if samples.len() <= count {
        return samples.to_vec();
    }
    let stride = samples.len().div_ceil(count);
    let mut out: Vec<T> = samples.iter().step_by(stride).cloned().collect();
    if !(samples.len() - 1).is_multiple_of(stride) {
        out.push(samples[samples.len() - 1].clone());
    }
    out
}

/// The sample of a trace taken at time `t` (s), within round-off of the
/// integer step count that produced it.
pub fn sample_at(trace: &engine::Trace, t: f64) -> Result<&engine::Sample> {
    trace
        .samples
        .iter()
        .find(|s| (s.t - t).abs() <= 1e-9 * t.abs().max(1.0))
        .ok_or_else(|| anyhow::anyhow!("no sample at t = {t} s"))
}
