//! The collision impulse of seed eq. 7.1–7.16, as docs/cases.md corrects it,
//! for one contact point — the closed form the harness checks the solver
//! against.
//!
//! With N the unit normal of B's boundary at P, pointing out of B (towards
//! A), `v_ab = v_ap − v_bp` the relative velocity of the contact points
//! (eq. 7.1–7.7, `v_p = v + ω × r`) and e the restitution (eq. 7.10,
//! `v_ab' · N = −e v_ab · N`):
//!
//! ```text
//! j = −(1 + e)(v_ab · N) / (1/m_a + 1/m_b + (r_ap × N)²/I_a + (r_bp × N)²/I_b)   (7.15)
//! v_a' = v_a + j N / m_a,        v_b' = v_b − j N / m_b                           (7.11–7.12)
//! ω_a' = ω_a + (r_ap × j N)/I_a, ω_b' = ω_b − (r_bp × j N)/I_b                    (7.13–7.14)
//! ```
//!
//! The seed prints the denominator with the fractions misplaced (7.15) and
//! keeps B's terms in the immovable case (7.16), and its 7.14 lacks the
//! minus sign; an immovable body has m, I → ∞ and its terms vanish. The
//! engine's own normal points from A to B, so N = −n.

use super::rows::perp;
use crate::shape::cross;
use nalgebra::Vector2;

/// The velocities of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Velocities {
    /// Linear velocity of the centre of mass (m/s).
    pub linear: Vector2<f64>,
    /// Angular velocity (rad/s).
    pub angular: f64,
}

/// A body's side of an impact: mass (kg) and inertia (kg·m²), infinite for
/// an immovable body, lever arm from its centre of mass to the contact
/// point (m), and velocities before the impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactBody {
    /// Mass (kg); `f64::INFINITY` for an immovable body.
    pub mass: f64,
    /// Moment of inertia (kg·m²); `f64::INFINITY` for an immovable body.
    pub inertia: f64,
    /// r_p: from the centre of mass to the contact point P (m).
    pub arm: Vector2<f64>,
    /// Velocities before the impact.
    pub velocities: Velocities,
}

/// The result of seed eq. 7.15 and 7.11–7.14.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactOutcome {
    /// j (N·s): the impulse magnitude along N on A (and −j N on B). Zero
    /// when the points are already separating (v_ab · N ≥ 0).
    pub impulse: f64,
    /// A's velocities after.
    pub a: Velocities,
    /// B's velocities after.
    pub b: Velocities,
}

/// Seed eq. 7.15 (corrected) for bodies `a` and `b` touching at one point,
/// `normal_b_to_a` the unit normal N of B's boundary pointing towards A,
/// restitution `e`. An immovable body (infinite mass and inertia) drops its
/// terms.
pub fn impact_eq_7_15(
    a: &ImpactBody,
    b: &ImpactBody,
    normal_b_to_a: Vector2<f64>,
    e: f64,
) -> ImpactOutcome {
    let n = normal_b_to_a;
    let inv = |x: f64| if x.is_infinite() { 0.0 } else { 1.0 / x };
    let (ima, imb, iia, iib) = (inv(a.mass), inv(b.mass), inv(a.inertia), inv(b.inertia));
    let v_ap = a.velocities.linear + a.velocities.angular * perp(a.arm);
    let v_bp = b.velocities.linear + b.velocities.angular * perp(b.arm);
    let vn = (v_ap - v_bp).dot(&n);
    let denominator = ima + imb + cross(a.arm, n).powi(2) * iia + cross(b.arm, n).powi(2) * iib;
    let j = if vn < 0.0 {
        -(1.0 + e) * vn / denominator
    } else {
        0.0
    };
    ImpactOutcome {
        impulse: j,
        a: Velocities {
            linear: a.velocities.linear + j * n * ima,
            angular: a.velocities.angular + cross(a.arm, j * n) * iia,
        },
        b: Velocities {
            linear: b.velocities.linear - j * n * imb,
            angular: b.velocities.angular - cross(b.arm, j * n) * iib,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn disc(mass: f64, vx: f64) -> ImpactBody {
        ImpactBody {
            mass,
            inertia: 0.5 * mass * 0.25,
            arm: Vector2::zeros(),
            velocities: Velocities {
                linear: Vector2::new(vx, 0.0),
                angular: 0.0,
            },
        }
    }

    /// docs/cases.md case III: m1 = 1 kg at +2 m/s hits m2 = 3 kg at rest.
    #[test]
    fn head_on_gives_the_cases_md_velocities() {
        // A = the 1 kg body on the left, B on its right: N points from B
        // to A, i.e. −x.
        for (e, v1, v2) in [(1.0, -1.0, 1.0), (0.5, -0.25, 0.75)] {
            let out = impact_eq_7_15(&disc(1.0, 2.0), &disc(3.0, 0.0), -Vector2::x(), e);
            assert!((out.a.linear.x - v1).abs() < 1e-15, "{out:?}");
            assert!((out.b.linear.x - v2).abs() < 1e-15, "{out:?}");
            let p = out.a.linear.x + 3.0 * out.b.linear.x;
            assert!((p - 2.0).abs() < 1e-15);
        }
    }

    #[test]
    fn immovable_body_drops_its_terms_and_reflects_the_velocity() {
        let wall = ImpactBody {
            mass: f64::INFINITY,
            inertia: f64::INFINITY,
            arm: Vector2::new(0.3, 5.0),
            velocities: Velocities {
                linear: Vector2::zeros(),
                angular: 0.0,
            },
        };
        let out = impact_eq_7_15(&disc(2.0, -4.0), &wall, Vector2::x(), 0.8);
        assert!((out.a.linear.x - 3.2).abs() < 1e-15);
        assert_eq!(out.b.linear, Vector2::zeros());
        assert!((out.impulse - 2.0 * 4.0 * 1.8).abs() < 1e-14);
    }

    #[test]
    fn off_centre_elastic_impact_keeps_momentum_and_energy() {
        let a = ImpactBody {
            mass: 1.5,
            inertia: 0.2,
            arm: Vector2::new(0.4, 0.3),
            velocities: Velocities {
                linear: Vector2::new(2.0, -0.5),
                angular: 1.0,
            },
        };
        let b = ImpactBody {
            mass: 2.5,
            inertia: 0.6,
            arm: Vector2::new(-0.5, 0.35),
            velocities: Velocities {
                linear: Vector2::new(-0.3, 0.1),
                angular: -0.4,
            },
        };
        let n = Vector2::new(-1.0, 0.0);
        let out = impact_eq_7_15(&a, &b, n, 1.0);
        assert!(out.impulse > 0.0);
        let p0 = a.mass * a.velocities.linear + b.mass * b.velocities.linear;
        let p1 = a.mass * out.a.linear + b.mass * out.b.linear;
        assert!((p0 - p1).norm() < 1e-14);
        let energy = |la: Vector2<f64>, wa: f64, lb: Vector2<f64>, wb: f64| {
            0.5 * a.mass * la.norm_squared()
                + 0.5 * a.inertia * wa * wa
                + 0.5 * b.mass * lb.norm_squared()
                + 0.5 * b.inertia * wb * wb
        };
        let e0 = energy(
            a.velocities.linear,
            a.velocities.angular,
            b.velocities.linear,
            b.velocities.angular,
        );
        let e1 = energy(out.a.linear, out.a.angular, out.b.linear, out.b.angular);
        assert!((e0 - e1).abs() < 1e-14 * e0, "{e0} {e1}");
    }
}
