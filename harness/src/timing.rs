//! Wall time of a run (on one thread, so the time the run occupied a
//! CPU and any time it waited), measured as the minimum over repeated
//! runs (the machines are shared and noisy; the minimum is the run least
//! disturbed). Only meaningful in a release build, and only as ratios
//! between runs of the same harness invocation.

use anyhow::Result;
use std::time::Instant;

/// Stop repeating once the runs have taken this long together (s), so long
/// runs are timed fewer times than short ones.
const BUDGET_SECONDS: f64 = 0.5;

/// The minimum wall time (s) of up to `runs` runs of `f` (at least one).
pub fn min_time(runs: usize, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let mut best = f64::INFINITY;
    let mut total = 0.0;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        f()?;
        let elapsed = start.elapsed().as_secs_f64();
        best = best.min(elapsed);
        total += elapsed;
        if total > BUDGET_SECONDS {
            break;
        }
    }
    Ok(best)
}
