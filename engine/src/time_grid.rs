//! The time grid of a run: `n` steps of `dt` from an integer count (times
//! `t0 + i·dt`, never an accumulated `t += dt`), the last step shortened
//! when `dt` does not divide the span. [`crate::World::run`] and
//! [`crate::integrators::integrate_to`] share it.

use crate::error::{EngineError, Result, require_positive};

/// Most steps a single run may take; beyond it the request is refused up
/// front rather than left to run for hours.
pub const MAX_RUN_STEPS: f64 = 1e8;

/// The number of steps over `span` (s) with step `dt` (s): exact when `dt`
/// divides `span` to within round-off (1e-9 relative), else one more, the
/// last one shortened. Refuses non-positive or non-finite inputs and more
/// than [`MAX_RUN_STEPS`] steps.
pub fn step_count(span: f64, dt: f64) -> Result<u64> {
    require_positive("dt", dt)?;
    require_positive("run duration", span)?;
    let ratio = span / dt;
    let steps = if (ratio - ratio.round()).abs() <= 1e-9 * ratio {
        ratio.round()
    } else {
        ratio.ceil()
    };
    if steps > MAX_RUN_STEPS {
        return Err(EngineError::InvalidParameter {
            what: "number of steps (duration / dt)".into(),
            value: steps,
            reason: "more than 1e8 steps: raise dt or shorten the run",
        });
    }
    Ok((steps as u64).max(1))
}

/// The time at the end of step `i` (1-based) of `steps`: `t0 + i·dt`, and
/// exactly `t_end` for the last one.
pub fn grid_time(t0: f64, t_end: f64, dt: f64, i: u64, steps: u64) -> f64 {
    if i >= steps {
        t_end
    } else {
        t0 + i as f64 * dt
    }
}
