//! Stiff test (`hoffman`): Hoffman's scalar stiff ODE, in closed form.
//!
//! Seed §4.3 (after Hoffman, seed ref. \[14\]):
//!
//! y' = λ·(y − (t + 2)) + 1,   y(0) = y0,   λ = −1000 s⁻¹, y0 = 1,
//!
//! whose solution is y(t) = t + 2 + (y0 − 2)·e^(λt); with the seed's y0 = 1,
//! y(t) = t + 2 − e^(−1000t) (`docs/cases.md`, stiff test). The transient dies in
//! ~5 ms, after which the solution is the smooth line t + 2, but an explicit
//! method still has to keep h·λ inside its stability region: explicit Euler is
//! stable iff h ≤ 2/|λ| = 0.002 s, RK4 iff h ≤ 2.785293563/|λ| s.

/// Real-axis stability boundary of classical RK4: the negative real root of
/// R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 = 1, i.e. of z³ + 4z² + 12z + 24 = 0
/// (dimensionless h·λ). Value from a 30-digit polynomial root
/// (−2.78529356340528162352975918976881), rounded to f64. `docs/cases.md` quotes
/// −2.78529356.
pub const RK4_REAL_STABILITY_BOUNDARY: f64 = -2.785_293_563_405_282;

/// Real-axis stability boundary of explicit Euler: R(z) = 1 + z = −1 at
/// z = h·λ = −2 (dimensionless).
pub const EULER_REAL_STABILITY_BOUNDARY: f64 = -2.0;

/// Hoffman's linear stiff test problem y' = λ·(y − (t + 2)) + 1 (seed §4.3,
/// `docs/cases.md` stiff test). Time in s, y dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hoffman {
    /// Stiffness eigenvalue λ, s⁻¹ (seed: −1000).
    pub lambda: f64,
    /// Initial value y(0) (seed: 1).
    pub y0: f64,
}

impl Hoffman {
    /// The seed configuration: λ = −1000 s⁻¹, y(0) = 1.
    pub const fn seed() -> Self {
        Self {
            lambda: -1000.0,
            y0: 1.0,
        }
    }

    /// The right-hand side f(t, y) = λ·(y − (t + 2)) + 1 at time t (s).
    pub fn rhs(&self, t: f64, y: f64) -> f64 {
        self.lambda * (y - (t + 2.0)) + 1.0
    }

    /// Exact solution y(t) = t + 2 + (y0 − 2)·e^(λt) at time t (s); with the
    /// seed values, t + 2 − e^(−1000t).
    pub fn exact(&self, t: f64) -> f64 {
        t + 2.0 + (self.y0 - 2.0) * (self.lambda * t).exp()
    }

    /// Exact derivative y'(t) = 1 + λ·(y0 − 2)·e^(λt) at time t (s).
    pub fn exact_derivative(&self, t: f64) -> f64 {
        1.0 + self.lambda * (self.y0 - 2.0) * (self.lambda * t).exp()
    }

    /// Largest stable explicit-Euler step, s: 2/|λ| (0.002 s for the seed).
    pub fn euler_max_stable_step(&self) -> f64 {
        EULER_REAL_STABILITY_BOUNDARY / self.lambda
    }

    /// Largest stable classical-RK4 step, s:
    /// [`RK4_REAL_STABILITY_BOUNDARY`]/λ (0.0027852936 s for the seed).
    pub fn rk4_max_stable_step(&self) -> f64 {
        RK4_REAL_STABILITY_BOUNDARY / self.lambda
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;

    #[test]
    fn exact_solution_solves_the_ode() {
        let h = Hoffman::seed();
        assert_eq!(h.exact(0.0), 1.0);
        for i in 0..=200 {
            let t = 1e-4 * f64::from(i * i);
            let y = h.exact(t);
            assert_close(h.exact_derivative(t), h.rhs(t, y), 1e-12, "y' = f(t, y)");
            assert_close(y, t + 2.0 - (-1000.0 * t).exp(), 1e-15, "formula");
        }
    }

    #[test]
    fn stability_limits_match_cases_md() {
        let h = Hoffman::seed();
        // docs/cases.md: explicit Euler stable iff h ≤ 0.002 (exact).
        assert_close(h.euler_max_stable_step(), 0.002, 1e-18, "Euler h_max");
        // docs/cases.md: RK4 stable iff h ≤ 0.0027852936 (10 decimals: half a
        // unit of the last digit is 5e-11).
        assert_close(h.rk4_max_stable_step(), 0.0027852936, 5e-11, "RK4 h_max");
        // The boundary is a root of z³ + 4z² + 12z + 24 (|R(z)| = 1).
        let z = RK4_REAL_STABILITY_BOUNDARY;
        let p = ((z + 4.0) * z + 12.0) * z + 24.0;
        assert_close(p, 0.0, 1e-13, "cubic residual");
        let r = 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
        assert_close(r, 1.0, 1e-14, "R(z)");
    }
}
