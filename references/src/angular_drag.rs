//! Case II (`angular_drag`): a driven spin under quadratic angular drag, in
//! closed form.
//!
//! Seed §6.2, eq. 6.21 adds the seed's "angular friction" to the spin-up of
//! eq. 6.20. The seed writes I·Δω/dt − D|ω|² = τ, which has the drag's sign
//! backwards; `docs/cases.md` states the physics: a drag torque −D·ω|ω| with the
//! linear drag's D = 0.003 (seed Table 6.2), on top of the couple τ0 that acts
//! for t ∈ [0, t1):
//!
//! I·ω' = τ(t) − D·ω|ω|,   θ' = ω,   ω(0) = θ(0) = 0,   τ(t) = τ0 for
//! t < t1, 0 after.
//!
//! For τ0 > 0 (ω ≥ 0 throughout):
//!
//! - while driven (0 ≤ t < t1), with k = √(τ0·D)/I and ω∞ = √(τ0/D):
//!   ω(t) = ω∞·tanh(kt),   θ(t) = (I/D)·ln cosh(kt);
//! - after t1, with ω1 = ω(t1), θ1 = θ(t1):
//!   ω(t) = ω1 / (1 + (D/I)·ω1·(t − t1)),
//!   θ(t) = θ1 + (I/D)·ln(1 + (D/I)·ω1·(t − t1)).
//!
//! A negative τ0 mirrors this (ω and θ change sign). Seed values:
//! k = 7.745966692 s⁻¹, ω∞ = 1.290994449 rad/s, ω(0.7) = 1.290944064 rad/s,
//! θ(0.7) = 0.7881748364 rad, ω(8.7) = 0.02050246334 rad/s,
//! θ(8.7) = 1.478605506 rad.
//!
//! I is tiny, so D/I = 6 s⁻¹·(rad/s)⁻¹ makes this the stiffest term of case II
//! (`docs/cases.md`).

/// A couple τ0 applied on [0, t1) to a body at rest, against the quadratic
/// drag torque −D·ω|ω| (`docs/cases.md` case II `angular_drag`, seed eq. 6.21).
///
/// Requires `inertia > 0`, `drag > 0` and `duration ≥ 0`; otherwise the
/// results are NaN or infinite (no panic). With no drag use
/// [`TorquePulse`](crate::TorquePulse).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngularDrag {
    /// Applied couple τ0, N·m (positive = counter-clockwise).
    pub torque: f64,
    /// Moment of inertia I about the centre of mass, kg·m².
    pub inertia: f64,
    /// Angular drag coefficient D, N·m·s² (drag torque −D·ω|ω|, ω in rad/s).
    pub drag: f64,
    /// Time t1 at which the couple is removed, s; it acts on [0, t1).
    pub duration: f64,
}

/// ln cosh x without overflow for large |x| and without cancellation for
/// small |x|.
fn ln_cosh(x: f64) -> f64 {
    let a = x.abs();
    if a < 1.0 {
        // cosh x − 1 = 2·sinh²(x/2), exact in relative terms.
        let s = (0.5 * a).sinh();
        (2.0 * s * s).ln_1p()
    } else {
        a + (-2.0 * a).exp().ln_1p() - std::f64::consts::LN_2
    }
}

impl AngularDrag {
    /// The seed configuration (`docs/cases.md` case II): τ0 = 0.005 N·m,
    /// I = 5e-4 kg·m², D = 0.003, t1 = 0.7 s.
    pub const fn seed() -> Self {
        Self {
            torque: 0.005,
            inertia: 5e-4,
            drag: 0.003,
            duration: 0.7,
        }
    }

    /// Rate constant k = √(|τ0|·D)/I of the driven phase, s⁻¹.
    /// Seed value: 7.745966692 s⁻¹.
    pub fn k(&self) -> f64 {
        (self.torque.abs() * self.drag).sqrt() / self.inertia
    }

    /// Terminal angular velocity sign(τ0)·√(|τ0|/D), rad/s, approached while
    /// driven. Seed value: 1.290994449 rad/s.
    pub fn terminal_omega(&self) -> f64 {
        (self.torque.abs() / self.drag).sqrt().copysign(self.torque)
    }

    fn t1(&self) -> f64 {
        self.duration.max(0.0)
    }

    /// Angular velocity ω(t), rad/s, at time t (s); 0 for t ≤ 0.
    pub fn omega(&self, t: f64) -> f64 {
        let t1 = self.t1();
        if t <= 0.0 {
            0.0
        } else if t < t1 {
            self.terminal_omega() * (self.k() * t).tanh()
        } else {
            let w1 = self.terminal_omega() * (self.k() * t1).tanh();
            w1 / (1.0 + self.drag / self.inertia * w1.abs() * (t - t1))
        }
    }

    /// Rotation angle θ(t), rad, at time t (s); 0 for t ≤ 0.
    pub fn theta(&self, t: f64) -> f64 {
        let t1 = self.t1();
        let sign = if self.torque < 0.0 { -1.0 } else { 1.0 };
        let i_over_d = self.inertia / self.drag;
        if t <= 0.0 {
            0.0
        } else if t < t1 {
            sign * i_over_d * ln_cosh(self.k() * t)
        } else {
            let theta1 = sign * i_over_d * ln_cosh(self.k() * t1);
            let w1 = self.terminal_omega() * (self.k() * t1).tanh();
            theta1 + sign * i_over_d * (w1.abs() * (t - t1) / i_over_d).ln_1p()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;

    #[test]
    fn constants_match_cases_md() {
        let a = AngularDrag::seed();
        // 7.745966692 has 9 decimals: half a unit of the last digit is 5e-10.
        assert_close(a.k(), 7.745966692, 5e-10, "k");
        // 1.290994449 has 9 decimals: half a unit is 5e-10.
        assert_close(a.terminal_omega(), 1.290994449, 5e-10, "terminal omega");
    }

    #[test]
    fn omega_and_theta_match_cases_md() {
        let a = AngularDrag::seed();
        // 1.290944064 has 9 decimals: half a unit is 5e-10.
        assert_close(a.omega(0.7), 1.290944064, 5e-10, "omega(0.7)");
        // 0.7881748364 has 10 decimals: half a unit is 5e-11.
        assert_close(a.theta(0.7), 0.7881748364, 5e-11, "theta(0.7)");
        // 0.02050246334 has 11 decimals: half a unit is 5e-12.
        assert_close(a.omega(8.7), 0.02050246334, 5e-12, "omega(8.7)");
        // 1.478605506 has 9 decimals: half a unit is 5e-10.
        assert_close(a.theta(8.7), 1.478605506, 5e-10, "theta(8.7)");
    }

    #[test]
    fn closed_form_solves_the_ode() {
        for a in [
            AngularDrag::seed(),
            AngularDrag {
                torque: -0.005,
                ..AngularDrag::seed()
            },
        ] {
            assert_eq!(a.omega(0.0), 0.0);
            assert_eq!(a.theta(0.0), 0.0);
            // Continuity at t1 (θ and ω are continuous; ω' jumps).
            let t1 = a.duration;
            let below = t1 * (1.0 - 1e-15);
            assert_close(a.omega(below), a.omega(t1), 1e-13, "omega continuity");
            assert_close(a.theta(below), a.theta(t1), 1e-13, "theta continuity");
            // Centred differences (step 1e-6 s: truncation ~h²·|ω'''| ≲ 1e-9,
            // round-off ~1e-16/h = 1e-10), away from the kink at t1.
            let h = 1e-6;
            for &t in &[0.01, 0.1, 0.3, 0.69, 0.71, 1.0, 3.0, 8.7] {
                let dw = (a.omega(t + h) - a.omega(t - h)) / (2.0 * h);
                let dth = (a.theta(t + h) - a.theta(t - h)) / (2.0 * h);
                let w = a.omega(t);
                let drive = if t < t1 { a.torque } else { 0.0 };
                let rhs = (drive - a.drag * w * w.abs()) / a.inertia;
                assert_close(dw, rhs, 1e-7, "I dw/dt = tau - D w|w|");
                assert_close(dth, w, 1e-8, "dtheta/dt = omega");
            }
        }
    }

    #[test]
    fn ln_cosh_is_accurate_across_ranges() {
        // Small x: the series x²/2 − x⁴/12 + x⁶/45 − 17x⁸/2520 (next term
        // ~2e-3·x¹⁰, below 1e-20 relative for x ≤ 1e-3).
        for &x in &[1e-8, 1e-5, 1e-3] {
            let x2: f64 = x * x;
            let series =
                x2 / 2.0 - x2 * x2 / 12.0 + x2 * x2 * x2 / 45.0 - 17.0 * x2 * x2 * x2 * x2 / 2520.0;
            assert_close(ln_cosh(x), series, 4.0 * f64::EPSILON * series, "small");
        }
        // Moderate x: direct ln(cosh x) carries an absolute error ~ε from
        // the rounding of cosh x, plus ~ε relative from the logarithm.
        for &x in &[0.5, 0.999, 1.0, 3.0, 20.0] {
            let direct = f64::cosh(x).ln();
            let tol = 4.0 * f64::EPSILON * (1.0 + direct);
            assert_close(ln_cosh(x), direct, tol, "direct");
        }
        // No overflow where cosh itself overflows.
        assert_close(
            ln_cosh(1000.0),
            1000.0 - std::f64::consts::LN_2,
            1e-12,
            "big",
        );
    }
}
