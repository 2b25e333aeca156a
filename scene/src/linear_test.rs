//! The scalar stiff test of a `[linear_test]` scene (seed §4.3, after
//! Hoffman; docs/cases.md "Stiff test"), as an [`engine::OdeSystem`].
//!
//! Representation: a small `Copy` struct rather than an
//! [`engine::FnSystem`] closure, so that it can be stored in a
//! [`crate::Scene`], compared, printed, and carry its exact solution next to
//! its right-hand side:
//!
//! y' = λ (y − g(t)) + g'(t),  g(t) = g0 + g1·t,  y(0) = y0,
//! y(t) = g(t) + (y0 − g(0)) e^(λt).
//!
//! The seed's problem is λ = −1000 s⁻¹, y0 = 1, g(t) = t + 2:
//! y' = −1000(y − (t + 2)) + 1, y = t + 2 − e^(−1000t).

use engine::{Method, OdeSystem, Solution};

/// y' = λ (y − g(t)) + g'(t) with g(t) = `forcing_offset` + `forcing_slope`·t.
/// A first-order system of dimension 1 (time in s, y dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearTest {
    /// λ (s⁻¹).
    pub lambda: f64,
    /// y(0).
    pub y0: f64,
    /// g(0).
    pub forcing_offset: f64,
    /// g' (s⁻¹).
    pub forcing_slope: f64,
}

impl LinearTest {
    /// The seed's problem: λ = −1000 s⁻¹, y0 = 1, g(t) = t + 2.
    pub const fn hoffman() -> Self {
        Self {
            lambda: -1000.0,
            y0: 1.0,
            forcing_offset: 2.0,
            forcing_slope: 1.0,
        }
    }

    /// The forcing g(t) = g0 + g1·t, the slow solution the transient decays
    /// to when λ < 0.
    pub fn forcing(&self, t: f64) -> f64 {
        self.forcing_offset + self.forcing_slope * t
    }

    /// The right-hand side f(t, y) = λ (y − g(t)) + g'(t).
    pub fn rhs(&self, t: f64, y: f64) -> f64 {
        self.lambda * (y - self.forcing(t)) + self.forcing_slope
    }

    /// The exact solution y(t) = g(t) + (y0 − g(0)) e^(λt).
    pub fn exact(&self, t: f64) -> f64 {
        self.forcing(t) + (self.y0 - self.forcing_offset) * (self.lambda * t).exp()
    }

    /// Checks that the exact solution stays a finite number over
    /// `[0, duration]` (s), so that the exact value and the error of a run
    /// can be printed: e^(λt) overflows f64 once λt > ln(f64::MAX) ≈ 709.78.
    /// Each term of y(t) = g(t) + (y0 − g(0)) e^(λt) is monotone in t, so
    /// checking both ends covers the whole interval. `Err` says why, in
    /// words.
    pub fn check_horizon(&self, duration: f64) -> Result<(), String> {
        let transient = |t: f64| (self.y0 - self.forcing_offset) * (self.lambda * t).exp();
        for t in [0.0, duration] {
            let parts = [self.forcing(t), transient(t), self.exact(t)];
            if parts.iter().any(|v| !v.is_finite()) {
                return Err(format!(
                    "the exact solution y = g(t) + (y0 − g(0)) e^(λt) overflows f64 at t = {} s (λt = {}; e^(λt) overflows past λt ≈ 709.78): shorten the run or reduce lambda",
                    engine::error::readable(t),
                    engine::error::readable(self.lambda * t)
                ));
            }
        }
        Ok(())
    }

    /// Integrates from t = 0 to `duration` (s) in steps of `dt` (s) with
    /// `method`, with the step semantics of [`engine::World::run`]: times
    /// `i·dt` from an integer count, the last step shortened to end exactly
    /// at `duration` when `dt` does not divide it. With `dormand_prince`,
    /// `dt` is the output interval. Records every step.
    ///
    /// A blow-up (non-finite y) is an [`engine::EngineError::BlowUp`]; a finite but
    /// huge y (explicit Euler just past its limit) is returned for the
    /// caller to judge. Refuses `semi_implicit_euler` and `velocity_verlet`
    /// ([`engine::EngineError::MethodNeedsSecondOrder`]): this system is first order.
    pub fn solve(&self, method: Method, dt: f64, duration: f64) -> engine::Result<Solution> {
        let mut sys = *self;
        engine::integrate_to(&mut sys, method, 0.0, &[self.y0], duration, dt)
    }
}

impl OdeSystem for LinearTest {
    fn dimension(&self) -> usize {
        1
    }

    fn derivative(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = self.rhs(t, y[0]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_solution_solves_the_ode() {
        let p = LinearTest::hoffman();
        assert_eq!(p.exact(0.0), 1.0);
        for t in [0.0005, 0.003, 0.5] {
            let h = 1e-7;
            let slope = (p.exact(t + h) - p.exact(t - h)) / (2.0 * h);
            let rel = (slope - p.rhs(t, p.exact(t))).abs() / slope.abs().max(1.0);
            assert!(rel < 1e-6, "t = {t}: {rel}");
        }
    }

    #[test]
    fn rk4_inside_its_limit_tracks_the_exact_solution() {
        let p = LinearTest::hoffman();
        let s = p.solve(Method::Rk4, 0.001, 1.0).unwrap();
        assert_eq!(s.t.len(), 1001);
        assert_eq!(*s.t.last().unwrap(), 1.0);
        let y = s.y.last().unwrap()[0];
        assert!((y - p.exact(1.0)).abs() < 1e-9, "{y}");
    }

    #[test]
    fn last_step_is_shortened_to_end_at_the_duration() {
        let s = LinearTest::hoffman()
            .solve(Method::ImplicitEuler, 0.0019, 1.0)
            .unwrap();
        assert_eq!(s.t.len(), 528);
        assert_eq!(*s.t.last().unwrap(), 1.0);
    }
}
