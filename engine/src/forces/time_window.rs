//! The optional time window of a force (the seed's torque acts "pendant un
//! court instant", §6.1 step 3).

use crate::error::{EngineError, Result};

/// A force is active for `start ≤ t < end` (s). The world splits its steps
/// at both edges, so a window edge never falls inside a step and the
/// integrator never differentiates across a discontinuity.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TimeWindow {
    /// Start of activity (s).
    pub start: f64,
    /// End of activity (s), may be `f64::INFINITY`.
    pub end: f64,
}

impl TimeWindow {
    /// Always active.
    pub const ALWAYS: TimeWindow = TimeWindow {
        start: f64::NEG_INFINITY,
        end: f64::INFINITY,
    };

    /// Active for `start ≤ t < end`; refuses NaN and `end ≤ start`.
    pub fn new(start: f64, end: f64) -> Result<Self> {
        if start.is_nan() {
            return Err(EngineError::InvalidParameter {
                what: "force time window start".into(),
                value: start,
                reason: "must be a number",
            });
        }
        if end.is_nan() || end <= start {
            return Err(EngineError::InvalidParameter {
                what: "force time window end".into(),
                value: end,
                reason: "must be a number greater than the start",
            });
        }
        Ok(Self { start, end })
    }

    /// From time 0 (s) for `duration` seconds.
    pub fn first(duration: f64) -> Result<Self> {
        Self::new(0.0, duration)
    }

    /// Whether the force is active at `t`.
    pub fn contains(&self, t: f64) -> bool {
        self.start <= t && t < self.end
    }

    /// The finite edges of the window.
    pub fn edges(&self) -> impl Iterator<Item = f64> {
        [self.start, self.end].into_iter().filter(|e| e.is_finite())
    }
}
