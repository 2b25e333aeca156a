//! The PI step-size controller of Dormand–Prince (Hairer & Wanner's
//! `dopri5`, Gustafsson's stabilisation): `h_new = h · clamp(s · err^(−α) ·
//! err_prev^β)`, with α = 0.2 − 0.75 β, β = 0.04, safety s = 0.9, the factor
//! clamped to [0.2, 10] (to at most 1 right after a rejection).

/// Exponent β of the previous error (stabilisation of the PI controller).
const BETA: f64 = 0.04;
/// Exponent α of the current error, for an order-5 pair.
const ALPHA: f64 = 0.2 - BETA * 0.75;
/// Safety factor applied to the optimal step.
const SAFETY: f64 = 0.9;
/// Smallest allowed shrink factor.
const MIN_FACTOR: f64 = 0.2;
/// Largest allowed growth factor.
const MAX_FACTOR: f64 = 10.0;

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
