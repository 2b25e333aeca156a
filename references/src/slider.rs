//! A box on a frictionless prismatic joint inclined at θ, held by a
//! spring: the `slider` case, in closed form.
//!
//! The joint's axis is the world direction (cos θ, sin θ) (θ above the
//! horizontal, so gravity pulls the box along it with −m g sin θ); the box
//! cannot turn. x is its displacement along the axis from the spring's
//! rest position (the anchor), v = x'. A spring of stiffness k (N/m) and
//! damping c (N·s/m) toward x = 0 gives the damped oscillator
//!
//!   m x'' = −k x − c x' − m g sin θ,
//!
//! with ω = √(k/m), ζ = c/(2√(k m)), equilibrium x_eq = −m g sin θ / k
//! (the spring stretched down the slope by m g sin θ / k), and for
//! 0 ≤ ζ < 1, with ω_d = ω √(1 − ζ²) and y = x − x_eq (Thomson,
//! *Theory of Vibration with Applications*, §2.6):
//!
//!   y(t) = e^(−ζωt) (y0 cos ω_d t + (v0 + ζ ω y0)/ω_d sin ω_d t).
//!
//! An engine spring given as a frequency f (Hz) and damping ratio ζ on a
//! row of effective mass m_eff (Box2D's and the scene's form) has
//! k = m_eff (2πf)² and c = 2 ζ m_eff (2πf); for this slider (the box
//! alone on the axis, its rotation locked) m_eff = m, so f = ω/(2π)
//! ([`Slider::spring_hertz`]).
//!
//! Units: SI (m, s, kg, N, rad).

use std::f64::consts::TAU;

/// The inclined slider (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slider {
    /// m, kg (> 0).
    pub mass: f64,
    /// k, N/m (> 0).
    pub stiffness: f64,
    /// ζ, the damping ratio (0 ≤ ζ < 1).
    pub damping_ratio: f64,
    /// θ, the axis's angle above the horizontal, rad.
    pub angle: f64,
    /// g, m/s².
    pub gravity: f64,
    /// x(0) from the spring's rest position, m.
    pub x0: f64,
    /// v(0), m/s.
    pub v0: f64,
}

impl Slider {
    /// ω = √(k/m), rad/s.
    pub fn omega(&self) -> f64 {
        (self.stiffness / self.mass).sqrt()
    }

    /// The spring's frequency f = ω/(2π), Hz, for an engine whose spring
    /// acts on the box's mass alone.
    pub fn spring_hertz(&self) -> f64 {
        self.omega() / TAU
    }

    /// The period 2π/ω_d, s.
    pub fn period(&self) -> f64 {
        TAU / self.damped_omega()
    }

    /// ω_d = ω √(1 − ζ²), rad/s.
    pub fn damped_omega(&self) -> f64 {
        assert!(
            (0.0..1.0).contains(&self.damping_ratio),
            "closed form for 0 <= zeta < 1"
        );
        self.omega() * (1.0 - self.damping_ratio * self.damping_ratio).sqrt()
    }

    /// x_eq = −m g sin θ / k, m.
    pub fn equilibrium(&self) -> f64 {
        -self.mass * self.gravity * self.angle.sin() / self.stiffness
    }

    /// (x(t), v(t)), m and m/s.
    pub fn state(&self, t: f64) -> (f64, f64) {
        let (w, z, wd) = (self.omega(), self.damping_ratio, self.damped_omega());
        let y0 = self.x0 - self.equilibrium();
        let b = (self.v0 + z * w * y0) / wd;
        let (s, c) = (wd * t).sin_cos();
        let e = (-z * w * t).exp();
        let y = e * (y0 * c + b * s);
        let v = e * (-z * w * (y0 * c + b * s) + wd * (-y0 * s + b * c));
        (self.equilibrium() + y, v)
    }

    /// Energy ½ m v² + ½ k x² + m g sin θ x, J: constant when ζ = 0.
    pub fn energy(&self, x: f64, v: f64) -> f64 {
        0.5 * self.mass * v * v
            + 0.5 * self.stiffness * x * x
            + self.mass * self.gravity * self.angle.sin() * x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;

    fn slider(zeta: f64) -> Slider {
        Slider {
            mass: 2.0,
            stiffness: 50.0,
            damping_ratio: zeta,
            angle: 30f64.to_radians(),
            gravity: 9.81,
            x0: 0.0,
            v0: 0.0,
        }
    }

    #[test]
    fn closed_form_values() {
        let s = slider(0.0);
        // ω = √(50/2) = 5 rad/s, x_eq = −2·9.81·0.5/50 = −0.1962 m.
        assert_close(s.omega(), 5.0, 1e-15, "omega");
        assert_close(s.equilibrium(), -0.1962, 1e-15, "equilibrium");
        assert_close(s.spring_hertz(), 5.0 / TAU, 1e-16, "hertz");
        // Released at the rest position: it swings to 2 x_eq and back.
        let (x, v) = s.state(0.5 * s.period());
        assert_close(x, 2.0 * s.equilibrium(), 1e-15, "lowest point");
        assert_close(v, 0.0, 1e-14, "turning point");
        let (x, _) = s.state(s.period());
        assert_close(x, 0.0, 1e-15, "back at the top");
    }

    #[test]
    fn closed_form_solves_the_equation_of_motion() {
        // Central differences of x(t) against m x'' = −k x − c x' − m g
        // sin θ: the second difference's truncation (h²/12)|x''''| with
        // h = 1e-4 s and x'''' ≤ ω⁴ |y0| ~ 1e2 m/s⁴ is 1e-7 m/s², and its
        // round-off 4 ε |x| / h² ≈ 2e-8: 1e-6 m/s² covers both.
        for zeta in [0.0, 0.3] {
            let mut s = slider(zeta);
            s.x0 = 0.05;
            s.v0 = -0.4;
            let (x, v) = s.state(0.0);
            assert_close(x, 0.05, 1e-16, "x0");
            assert_close(v, -0.4, 1e-15, "v0");
            let c = 2.0 * zeta * (s.stiffness * s.mass).sqrt();
            let h = 1e-4;
            for t in [0.1, 0.7, 1.9] {
                let (xm, _) = s.state(t - h);
                let (x, v) = s.state(t);
                let (xp, _) = s.state(t + h);
                let acc = (xp - 2.0 * x + xm) / (h * h);
                let rhs = (-s.stiffness * x - c * v - s.mass * s.gravity * s.angle.sin()) / s.mass;
                assert_close(acc, rhs, 1e-6, "x''");
                assert_close((xp - xm) / (2.0 * h), v, 1e-7, "x'");
            }
            if zeta == 0.0 {
                let e0 = s.energy(s.x0, s.v0);
                for t in [0.3, 2.2, 7.5] {
                    let (x, v) = s.state(t);
                    assert_close(s.energy(x, v), e0, 1e-14, "energy");
                }
            }
        }
    }
}
