//! Case II (`torque`): a body spun up by a constant couple, in closed form.
//!
//! Seed §6.2–6.3, eq. 6.16–6.20: a torque τ = R × F (eq. 6.16) changes the
//! angular momentum L = Iω (eq. 6.17–6.18), with the box's moment of inertia
//! I = m(b² + h²)/12 (eq. 6.19). `docs/cases.md` fixes the seed's garbled numbers:
//! R = (0.05, 0.05) m and F = (0.3, 0.4) N give τ0 = 0.005 N·m (the seed
//! prints 0.0005 and degrees), and m = 0.3 kg, b = h = 0.1 m give
//! I = 5e-4 kg·m².
//!
//! The couple τ0 acts for t ∈ [0, t1) and is then removed, with no drag; the
//! body starts at rest with θ = 0:
//!
//! - t < 0: ω = 0, θ = 0 (nothing has happened yet);
//! - 0 ≤ t < t1: α = τ0/I, ω = α·t, θ = α·t²/2;
//! - t ≥ t1: ω = ω1 = α·t1, θ = α·t1²/2 + ω1·(t − t1).
//!
//! Seed values: α = 10 rad/s², ω(0.7) = 7 rad/s, θ(0.7) = 2.45 rad,
//! θ(8.7) = 58.45 rad.

/// Lever arm R from the centroid to the point of application of the seed's
/// spin-up force, m (seed §6.3, `docs/cases.md` case II `torque`).
pub const SEED_LEVER_ARM: [f64; 2] = [0.05, 0.05];

/// The seed's spin-up force F, N (seed §6.3, `docs/cases.md` case II `torque`).
/// R × F = 0.05·0.4 − 0.05·0.3 = 0.005 N·m.
pub const SEED_FORCE: [f64; 2] = [0.3, 0.4];

/// Moment of inertia of a uniform b × h rectangle about its centroid,
/// I = m(b² + h²)/12 (seed eq. 6.19), kg·m². `mass` in kg, `width` b and
/// `height` h in m. The seed's box (0.3 kg, 0.1 m × 0.1 m) gives 5e-4 kg·m².
pub fn rectangle_inertia(mass: f64, width: f64, height: f64) -> f64 {
    mass * (width * width + height * height) / 12.0
}

/// The 2D cross product R × F = Rx·Fy − Ry·Fx (seed eq. 6.16): the torque,
/// N·m, of force `f` (N) applied at lever arm `r` (m).
pub fn cross(r: [f64; 2], f: [f64; 2]) -> f64 {
    r[0] * f[1] - r[1] * f[0]
}

/// A constant couple applied for a finite time to a body at rest, no drag
/// (`docs/cases.md` case II `torque`, seed eq. 6.16–6.20).
///
/// Requires `inertia > 0` and `duration ≥ 0`; otherwise the results are NaN
/// or infinite (no panic).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorquePulse {
    /// Applied couple τ0, N·m (positive = counter-clockwise).
    pub torque: f64,
    /// Moment of inertia I about the centre of mass, kg·m².
    pub inertia: f64,
    /// Time t1 at which the couple is removed, s; it acts on [0, t1).
    pub duration: f64,
}

impl TorquePulse {
    /// The seed configuration (`docs/cases.md` case II): τ0 = 0.005 N·m,
    /// I = 5e-4 kg·m², t1 = 0.7 s.
    pub const fn seed() -> Self {
        Self {
            torque: 0.005,
            inertia: 5e-4,
            duration: 0.7,
        }
    }

    /// Angular acceleration τ0/I while the couple acts, rad/s². Seed: 10.
    pub fn angular_acceleration(&self) -> f64 {
        self.torque / self.inertia
    }

    /// Angular velocity ω(t), rad/s, at time t (s): α·t clamped to [0, t1].
    pub fn omega(&self, t: f64) -> f64 {
        self.angular_acceleration() * t.clamp(0.0, self.duration.max(0.0))
    }

    /// Rotation angle θ(t), rad, at time t (s): α·t²/2 while driven, then
    /// θ1 + ω1·(t − t1); 0 for t < 0.
    pub fn theta(&self, t: f64) -> f64 {
        let a = self.angular_acceleration();
        let t1 = self.duration.max(0.0);
        if t <= 0.0 {
            0.0
        } else if t < t1 {
            0.5 * a * t * t
        } else {
            0.5 * a * t1 * t1 + a * t1 * (t - t1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;

    #[test]
    fn seed_torque_and_inertia() {
        // τ0 = 0.005 and I = 5e-4 are quoted as exact decimals; f64 round-off
        // of the products is a few ulps, so allow 1e-15 relative.
        assert_close(
            cross(SEED_LEVER_ARM, SEED_FORCE),
            0.005,
            1e-15 * 0.005 + f64::EPSILON * 0.02,
            "R x F",
        );
        assert_close(rectangle_inertia(0.3, 0.1, 0.1), 5e-4, 1e-15 * 5e-4, "I");
        assert_close(
            TorquePulse::seed().angular_acceleration(),
            10.0,
            1e-14,
            "alpha",
        );
    }

    #[test]
    fn omega_and_theta_match_cases_md() {
        let p = TorquePulse::seed();
        // ω(0.7) = 7 printed with no decimals: the docs/cases.md rule would allow
        // 0.5; it is exact up to round-off, so 1e-13 is asked instead.
        assert_close(p.omega(0.7), 7.0, 1e-13, "omega(0.7)");
        // 2.45 has 2 decimals (half unit 5e-3); exact up to round-off.
        assert_close(p.theta(0.7), 2.45, 1e-13, "theta(0.7)");
        // 58.45 has 2 decimals (half unit 5e-3); exact up to round-off.
        assert_close(p.theta(8.7), 58.45, 1e-12, "theta(8.7)");
        assert_close(p.omega(8.7), 7.0, 1e-13, "omega(8.7)");
        assert_eq!(p.omega(-1.0), 0.0);
        assert_eq!(p.theta(-1.0), 0.0);
    }

    #[test]
    fn theta_is_continuous_at_t1_and_integrates_omega() {
        let p = TorquePulse::seed();
        let t1 = p.duration;
        let below = p.theta(t1 * (1.0 - 1e-15));
        assert_close(below, p.theta(t1), 1e-13, "theta continuity");
        // Centred differences away from the kink at t1 (θ is quadratic/linear
        // there, so the difference is exact up to round-off ~1e-16/h).
        let h = 1e-6;
        for &t in &[0.1, 0.35, 0.6, 1.0, 5.0] {
            let d = (p.theta(t + h) - p.theta(t - h)) / (2.0 * h);
            assert_close(d, p.omega(t), 1e-7, "dtheta/dt");
        }
    }
}
