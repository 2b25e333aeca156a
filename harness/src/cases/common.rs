//! Helpers every case uses: the methods it runs, Dormand–Prince's error
//! bound, sampling and picking samples of a trace, and the failing rows of a
//! report for an assertion message.

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
