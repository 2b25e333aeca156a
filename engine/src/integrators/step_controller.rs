//! The PI step-size controller of Dormand–Prince (Hairer & Wanner's
//! `dopri5`, Gustafsson's stabilisation): `h_new = h · clamp(s · err^(−α) ·
//! err_prev^β)`, with α = 0.2 − 0.75 β, β = 0.04, safety s = 0.9, the factor
//! clamped to [0.2, 10] (to at most 1 right after a rejection).

use crate::tunables::STEP_CONTROLLER_ALPHA as ALPHA;
use crate::tunables::STEP_CONTROLLER_BETA as BETA;
use crate::tunables::STEP_CONTROLLER_MAX_FACTOR as MAX_FACTOR;
use crate::tunables::STEP_CONTROLLER_MIN_FACTOR as MIN_FACTOR;
use crate::tunables::STEP_CONTROLLER_SAFETY as SAFETY;

/// Remembers the last accepted error so the next step can use it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepController {
    previous_error: f64,
    rejected_last: bool,
}

impl Default for StepController {
    fn default() -> Self {
        Self {
            previous_error: 1e-4,
            rejected_last: false,
        }
    }
}

impl StepController {
    /// Whether the attempt with scaled error `err` is accepted, and the next
    /// step size to try.
    pub(crate) fn judge(&mut self, h: f64, err: f64) -> (bool, f64) {
        if err <= 1.0 {
            let err = err.max(1e-10);
            let mut factor = SAFETY * err.powf(-ALPHA) * self.previous_error.powf(BETA);
            factor = factor.clamp(MIN_FACTOR, MAX_FACTOR);
            if self.rejected_last {
                factor = factor.min(1.0);
            }
            self.previous_error = err;
            self.rejected_last = false;
            (true, h * factor)
        } else {
            let factor = if err.is_finite() {
                (SAFETY * err.powf(-ALPHA)).max(MIN_FACTOR)
            } else {
                MIN_FACTOR
            };
            self.rejected_last = true;
            (false, h * factor)
        }
    }
}
