//! Contact constraints as rows of a small linear complementarity problem,
//! at the velocity level (impulses) or the acceleration level (forces).
//!
//! A row measures the relative motion of two material points along a
//! direction `u`: with `A` and `B` the two bodies, `r_A`, `r_B` the lever
//! arms from their centres of mass to the contact point P,
//!
//! `J·v = u · [(v_B + ω_B × r_B) − (v_A + ω_A × r_A)]`
//!
//! (seed eq. 7.1–7.7: the relative velocity of the contact point, here B
//! relative to A along a normal from A to B). Its *force column* `w` is the
//! direction along which it pushes: `+λ w` on B at P and `−λ w` on A. For a
//! normal row `w = u = n`, except while the contact slides with friction,
//! when the kinetic friction `−μ λ s t` rides on the normal force:
//! `w = n − μ s t` (s = ±1 the sliding direction along the tangent t).
//!
//! The effective-mass matrix of the rows is `K_kj = J_k M⁻¹ W_j`:
//!
//! `K_kj = Σ_bodies σ_k σ_j [ (u_k · w_j)/m + (r_k × u_k)(r_j × w_j)/I ]`
//!
//! with σ = +1 on B and −1 on A. For a single normal row it is the
//! denominator of seed eq. 7.15, `1/m_a + 1/m_b + (r_a × n)²/I_a +
//! (r_b × n)²/I_b`. An immovable body has 1/m = 1/I = 0 and drops out.

use crate::body::{Body, BodyState};
use crate::shape::cross;
use nalgebra::Vector2;

/// What the solver needs of one body: inverse mass and inertia (0 for an
/// immovable body), pose and velocities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodyView {
    pub inv_mass: f64,
    pub inv_inertia: f64,
    pub position: Vector2<f64>,
    pub velocity: Vector2<f64>,
    pub omega: f64,
}

impl BodyView {
    pub(crate) fn new(body: &Body, state: &BodyState) -> Self {
        let dynamic = body.is_dynamic();
        Self {
            inv_mass: if dynamic { 1.0 / body.mass } else { 0.0 },
            inv_inertia: match (dynamic, body.inertia) {
                (true, Some(i)) => 1.0 / i,
                _ => 0.0,
            },
            position: state.position,
            velocity: if dynamic {
                state.velocity
            } else {
                Vector2::zeros()
            },
            omega: if dynamic { state.angular_velocity } else { 0.0 },
        }
    }

    /// Velocity of the material point at lever arm `r` (m/s).
    pub(crate) fn point_velocity(&self, r: Vector2<f64>) -> Vector2<f64> {
        self.velocity + self.omega * perp(r)
    }
}

/// `ω × r` for ω = 1: the vector r turned by +90°.
pub(crate) fn perp(r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-r.y, r.x)
}

/// One end of a row: the body, its sign (−1 for A, +1 for B) and lever arm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Side {
    pub body: usize,
    pub sign: f64,
    pub arm: Vector2<f64>,
}

/// Which constraint a row expresses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RowKind {
    /// Non-penetration at one point: λ ≥ 0, and the measured relative
    /// normal motion ≥ its target, complementary.
    Normal,
    /// A touching point held at its target (a resting point that was left
    /// separating slower than the resting speed): λ of either sign, and the
    /// measured motion equal to the target.
    Hold,
    /// Static friction of one manifold: |λ| ≤ μ Σ λ of the normal rows
    /// `normals`, and the measured tangential motion equal to its target
    /// while inside the cone.
    Friction { mu: f64, normals: (usize, usize) },
}

/// A constraint row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Row {
    pub kind: RowKind,
    pub sides: [Side; 2],
    /// Measured direction u.
    pub measure: Vector2<f64>,
    /// Force direction w.
    pub push: Vector2<f64>,
    /// Target of the measured quantity (restitution target −e·v_n at an
    /// impact; 0 otherwise).
    pub target: f64,
}

impl Row {
    /// `u · (relative velocity of the points)` (m/s).
    pub(crate) fn velocity(&self, bodies: &[BodyView]) -> f64 {
        self.sides
            .iter()
            .map(|s| s.sign * self.measure.dot(&bodies[s.body].point_velocity(s.arm)))
            .sum()
    }

    /// `u · (relative acceleration of the points)` (m/s²) given each body's
    /// linear and angular acceleration; includes the centripetal terms
    /// −ω² r of both points.
    pub(crate) fn acceleration(
        &self,
        bodies: &[BodyView],
        accelerations: &[(Vector2<f64>, f64)],
    ) -> f64 {
        self.sides
            .iter()
            .map(|s| {
                let b = &bodies[s.body];
                let (a, alpha) = accelerations[s.body];
                let point = a + alpha * perp(s.arm) - b.omega * b.omega * s.arm;
                s.sign * self.measure.dot(&point)
            })
            .sum()
    }

    /// `J_self M⁻¹ W_other`.
    pub(crate) fn coupling(&self, other: &Row, bodies: &[BodyView]) -> f64 {
        let mut k = 0.0;
        for s in &self.sides {
            for o in &other.sides {
                if s.body != o.body {
                    continue;
                }
                let b = &bodies[s.body];
                k += s.sign
                    * o.sign
                    * (b.inv_mass * self.measure.dot(&other.push)
                        + b.inv_inertia * cross(s.arm, self.measure) * cross(o.arm, other.push));
            }
        }
        k
    }

    /// Adds `λ` times this row's generalized force to per-body
    /// `(linear, angular)` accumulators (impulses in N·s or forces in N).
    pub(crate) fn apply(&self, lambda: f64, out: &mut [(Vector2<f64>, f64)]) {
        for s in &self.sides {
            let f = s.sign * lambda * self.push;
            out[s.body].0 += f;
            out[s.body].1 += cross(s.arm, f);
        }
    }
}

/// The dense effective-mass matrix `K` (row-major) of `rows`.
pub(crate) fn effective_mass(rows: &[Row], bodies: &[BodyView], k: &mut Vec<f64>) {
    let n = rows.len();
    k.clear();
    k.resize(n * n, 0.0);
    for (i, ri) in rows.iter().enumerate() {
        for (j, rj) in rows.iter().enumerate() {
            k[i * n + j] = ri.coupling(rj, bodies);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(m: f64, i: f64, x: f64, y: f64) -> BodyView {
        BodyView {
            inv_mass: 1.0 / m,
            inv_inertia: 1.0 / i,
            position: Vector2::new(x, y),
            velocity: Vector2::zeros(),
            omega: 0.0,
        }
    }

    #[test]
    fn single_normal_row_has_the_denominator_of_eq_7_15() {
        let bodies = [view(2.0, 0.5, 0.0, 0.0), view(3.0, 0.25, 1.0, 0.0)];
        let n = Vector2::new(0.6, 0.8);
        let (ra, rb) = (Vector2::new(0.3, 0.2), Vector2::new(-0.5, 0.1));
        let row = Row {
            kind: RowKind::Normal,
            sides: [
                Side {
                    body: 0,
                    sign: -1.0,
                    arm: ra,
                },
                Side {
                    body: 1,
                    sign: 1.0,
                    arm: rb,
                },
            ],
            measure: n,
            push: n,
            target: 0.0,
        };
        let expected =
            1.0 / 2.0 + 1.0 / 3.0 + cross(ra, n).powi(2) / 0.5 + cross(rb, n).powi(2) / 0.25;
        assert!((row.coupling(&row, &bodies) - expected).abs() < 1e-15);
    }
}
