//! Case II (`projectile`): the projectile in vacuum, in closed form.
//!
//! Seed §6.2, eq. 6.1–6.3 and Table 6.1: launched from the origin at speed v0
//! and angle α above the +x axis, under constant gravity g along −y, no drag:
//!
//! x(t) = v0·cos α·t,   y(t) = v0·sin α·t − g·t²/2.
//!
//! Landing (y = 0, t > 0) at T = 2·v0·sin α / g, range R = v0·cos α·T, apex at
//! t = T/2 with height H = (v0·sin α)²/(2g).
//!
//! Gravity is the seed's g = 9.80655 m/s² ([`SEED_GRAVITY`]), not standard
//! gravity 9.80665 m/s²: `docs/cases.md` keeps the seed's value for case II.

/// The seed's gravitational acceleration, m/s² (seed Table 6.1 and 6.2).
///
/// Standard gravity is 9.80665 m/s²; the seed prints 9.80655 and `docs/cases.md`
/// keeps it for every case-II reference (`projectile`, `projectile_drag`), so
/// that the numbers quoted there are reproducible.
pub const SEED_GRAVITY: f64 = 9.80655;

/// A point projectile in vacuum, launched from the origin (`docs/cases.md` case II
/// `projectile`, seed §6).
///
/// Requires `gravity > 0` and `0 < angle < π` for the landing and apex
/// quantities to be meaningful; position and velocity hold for any input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projectile {
    /// Launch speed v0, m/s.
    pub speed: f64,
    /// Launch angle α above the +x axis, rad.
    pub angle: f64,
    /// Gravitational acceleration g (acting along −y), m/s².
    pub gravity: f64,
}

impl Projectile {
    /// The seed configuration (seed Table 6.1, `docs/cases.md` case II):
    /// v0 = 60 m/s, α = 45° (π/4 rad), g = [`SEED_GRAVITY`] = 9.80655 m/s².
    pub const fn seed() -> Self {
        Self {
            speed: 60.0,
            angle: std::f64::consts::FRAC_PI_4,
            gravity: SEED_GRAVITY,
        }
    }

    /// Initial velocity (v0·cos α, v0·sin α), m/s.
    pub fn initial_velocity(&self) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        [self.speed * c, self.speed * s]
    }

    /// Position (x, y) at time t (s), m: (v0·cos α·t, v0·sin α·t − g·t²/2).
    pub fn position(&self, t: f64) -> [f64; 2] {
        let [vx, vy] = self.initial_velocity();
        [vx * t, vy * t - 0.5 * self.gravity * t * t]
    }

    /// Velocity (vx, vy) at time t (s), m/s: (v0·cos α, v0·sin α − g·t).
    pub fn velocity(&self, t: f64) -> [f64; 2] {
        let [vx, vy] = self.initial_velocity();
        [vx, vy - self.gravity * t]
    }

    /// Landing time T = 2·v0·sin α / g (s): the positive root of y(t) = 0.
    /// Seed value: 8.652667222 s.
    pub fn landing_time(&self) -> f64 {
        2.0 * self.initial_velocity()[1] / self.gravity
    }

    /// Range R = v0·cos α·T (m), the x of the landing point. Seed value:
    /// 367.1015801 m.
    pub fn range(&self) -> f64 {
        self.initial_velocity()[0] * self.landing_time()
    }

    /// Apex time v0·sin α / g (s), where vy = 0. Seed value: 4.326333611 s.
    pub fn apex_time(&self) -> f64 {
        self.initial_velocity()[1] / self.gravity
    }

    /// Apex height H = (v0·sin α)² / (2g), m. Seed value: 91.77539502 m.
    pub fn apex_height(&self) -> f64 {
        let vy = self.initial_velocity()[1];
        vy * vy / (2.0 * self.gravity)
    }

    /// Apex abscissa R/2 = v0·cos α · v0·sin α / g, m.
    pub fn apex_x(&self) -> f64 {
        self.initial_velocity()[0] * self.apex_time()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;

    #[test]
    fn landing_range_apex_match_cases_md() {
        let p = Projectile::seed();
        // 8.652667222 has 9 decimals: half a unit of the last digit is 5e-10.
        assert_close(p.landing_time(), 8.652667222, 5e-10, "T");
        // 367.1015801 has 7 decimals: half a unit is 5e-8.
        assert_close(p.range(), 367.1015801, 5e-8, "R");
        // 91.77539502 has 8 decimals: half a unit is 5e-9.
        assert_close(p.apex_height(), 91.77539502, 5e-9, "H");
        // 4.326333611 has 9 decimals: half a unit is 5e-10.
        assert_close(p.apex_time(), 4.326333611, 5e-10, "apex time");
        // Internal consistency, to round-off.
        assert_close(p.apex_x(), p.range() / 2.0, 1e-12, "apex x");
    }

    #[test]
    fn events_are_consistent_with_position_and_velocity() {
        let p = Projectile::seed();
        let t_land = p.landing_time();
        let [x, y] = p.position(t_land);
        assert_close(y, 0.0, 1e-12, "y(T)");
        assert_close(x, p.range(), 1e-12, "x(T)");
        let ta = p.apex_time();
        assert_close(p.velocity(ta)[1], 0.0, 1e-13, "vy(apex)");
        assert_close(p.position(ta)[1], p.apex_height(), 1e-12, "y(apex)");
        assert_eq!(p.position(0.0), [0.0, 0.0]);
        assert_eq!(p.velocity(0.0), p.initial_velocity());
    }
}
