//! The force laws of joints under the exact model: a wheel's suspension
//! spring and a motor joint's two bounded springs, applied forces of the
//! equations of motion (added to a₀ = M⁻¹ f before the constraint forces
//! are solved, [`crate::exact::joints`]), the continuous-time limit of the
//! soft step's spring rows (`docs/joints.md#wheel-and-motor-joints-under-the-exact-model`).
//!
//! A spring of frequency f and ratio ζ on a row of effective mass m_eff =
//! (J M⁻¹ Jᵀ)⁻¹ (J its Jacobian, C its value) is the generalized force
//!
//! Q = Jᵀ F,   F = −m_eff (ω² C + 2ζω J v),   ω = 2πf,
//!
//! the limit h → 0 of the soft row Δλ = −mass scale · m (J v + bias rate
//! · C) − impulse scale · λ (Box2D's soft constraint is the implicit
//! integration of this spring-damper). m_eff depends smoothly on q, so the
//! right-hand side stays smooth and every method keeps its order:
//!
//! - **wheel**: C = s = u·d, the translation along the axis u fixed in A,
//!   J = [−u, −a₁; u, a₂] (a₁ = (d + r_A) × u, a₂ = r_B × u), m_eff =
//!   1/(m_A + m_B + i_A a₁² + i_B a₂²);
//! - **motor joint**: C = e = c_B − (p_A + R(θ_A) o) (2 rows, K the point
//!   rows' 2 × 2 mass matrix at the arms r_A = R(θ_A)(a_A + o), r_B), F =
//!   −K⁻¹ (ω² e + 2ζω ė), scaled back onto |F| ≤ F_max; and C = θ_B − θ_A −
//!   θ_offset, τ = −(ω² C + 2ζω Ċ)/(i_A + i_B), clamped to |τ| ≤ τ_max.
//!
//! The motor joint's bounds make its force law piecewise smooth: Lipschitz
//! continuous, with a kink where a bound engages or releases. A method of
//! order p loses it in the step containing a kink (local error O(h²)
//! there), so a run through k such instants has a global error of O(h^p)
//! + k·O(h²); the `motor_joint` case measures it.

use crate::body::{Body, BodyState};
use crate::exact::ode::Layout;
use crate::soft_step::joints::{JointId, JointRows, JointSet, wrap_angle};
use nalgebra::Vector2;

/// (−r_y, r_x).
fn perp(r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-r.y, r.x)
}

/// r turned by θ.
fn turn(angle: f64, r: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = angle.sin_cos();
    Vector2::new(c * r.x - s * r.y, s * r.x + c * r.y)
}

/// A body as the force laws read it: its pose, velocity, inverse mass and
/// inertia, and its slot in the state (the world and static bodies: none,
/// inverse masses 0).
#[derive(Debug, Clone, Copy)]
struct Side {
    position: Vector2<f64>,
    angle: f64,
    velocity: Vector2<f64>,
    omega: f64,
    inv_mass: f64,
    inv_inertia: f64,
    slot: Option<(usize, bool)>,
}

impl Side {
    fn of(body: Option<usize>, bodies: &[Body], layout: &Layout, states: &[BodyState]) -> Self {
        let Some(id) = body else {
            return Side {
                position: Vector2::zeros(),
                angle: 0.0,
                velocity: Vector2::zeros(),
                omega: 0.0,
                inv_mass: 0.0,
                inv_inertia: 0.0,
                slot: None,
            };
        };
        let s = &states[id];
        let slot = layout.slots[id].map(|sl| (sl.offset, sl.rotates));
        let (inv_mass, inv_inertia) = match slot {
            None => (0.0, 0.0),
            Some((_, rotates)) => (
                1.0 / bodies[id].mass,
                if rotates {
                    bodies[id].inertia.map_or(0.0, |i| 1.0 / i)
                } else {
                    0.0
                },
            ),
        };
        Side {
            position: s.position,
            angle: s.angle,
            velocity: s.velocity,
            omega: s.angular_velocity,
            inv_mass,
            inv_inertia,
            slot,
        }
    }

    /// Adds the force `f` (N) and torque `tau` (N·m) as accelerations.
    fn push(&self, accel: &mut [f64], f: Vector2<f64>, tau: f64) {
        let Some((o, rotates)) = self.slot else {
            return;
        };
        accel[o] += self.inv_mass * f.x;
        accel[o + 1] += self.inv_mass * f.y;
        if rotates {
            accel[o + 2] += self.inv_inertia * tau;
        }
    }
}

/// What a joint's force law applied in the last evaluation: the force on
/// B (N, world frame; A gets its opposite) and the torque on B (N·m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct AppliedJointForce {
    pub joint: JointId,
    pub force: Vector2<f64>,
    pub torque: f64,
}

/// Adds the force laws of the live wheel and motor joints of `set` at
/// `states` to `accel` (the velocity block of the derivative, positions
/// long), recording each joint's force and torque in `out`.
pub(crate) fn apply(
    set: &JointSet,
    (bodies, layout, states): (&[Body], &Layout, &[BodyState]),
    accel: &mut [f64],
    out: &mut Vec<AppliedJointForce>,
) {
    use std::f64::consts::TAU;
    out.clear();
    for (id, (info, sim)) in set.infos.iter().zip(&set.sims).enumerate() {
        if info.removed {
            continue;
        }
        let (a, b) = (
            Side::of(info.body_a, bodies, layout, states),
            Side::of(info.body_b, bodies, layout, states),
        );
        let arm = |side: &Side, body: Option<usize>, local: Vector2<f64>| {
            if body.is_some() {
                turn(side.angle, local)
            } else {
                Vector2::zeros()
            }
        };
        let point = |side: &Side, body: Option<usize>, r: Vector2<f64>, local: Vector2<f64>| {
            if body.is_some() {
                side.position + r
            } else {
                local
            }
        };
        match &sim.rows {
            JointRows::Wheel(w) => {
                let Some(spring) = w.joint.spring else {
                    continue;
                };
                let ra = arm(&a, info.body_a, info.local_a);
                let rb = arm(&b, info.body_b, info.local_b);
                let d = point(&b, info.body_b, rb, info.local_b)
                    - point(&a, info.body_a, ra, info.local_a);
                let u = if info.body_a.is_some() {
                    turn(a.angle, w.local_axis)
                } else {
                    w.local_axis
                };
                let (a1, a2) = (crate::shape::cross(d + ra, u), crate::shape::cross(rb, u));
                let k = a.inv_mass + b.inv_mass + a.inv_inertia * a1 * a1 + b.inv_inertia * a2 * a2;
                if k <= 0.0 {
                    continue;
                }
                let s = u.dot(&d);
                let s_dot = u.dot(&(b.velocity - a.velocity)) + a2 * b.omega - a1 * a.omega;
                let omega = TAU * spring.hertz;
                let f = -(omega * omega * s + 2.0 * spring.damping_ratio * omega * s_dot) / k;
                a.push(accel, -f * u, -f * a1);
                b.push(accel, f * u, f * a2);
                out.push(AppliedJointForce {
                    joint: id,
                    force: f * u,
                    torque: 0.0,
                });
            }
            JointRows::Motor(m) => {
                let j = &m.joint;
                let ra = arm(&a, info.body_a, info.local_a + j.linear_offset);
                let ra = if info.body_a.is_some() {
                    ra
                } else {
                    // The world's side: its anchor and offset are world
                    // points, and it does not turn.
                    Vector2::zeros()
                };
                let target = if info.body_a.is_some() {
                    a.position + ra
                } else {
                    info.local_a + j.linear_offset
                };
                let rb = arm(&b, info.body_b, info.local_b);
                let pb = point(&b, info.body_b, rb, info.local_b);
                let e = pb - target;
                let e_dot = b.velocity + b.omega * perp(rb) - a.velocity - a.omega * perp(ra);
                let (ma, mb, ia, ib) = (a.inv_mass, b.inv_mass, a.inv_inertia, b.inv_inertia);
                let k11 = ma + mb + ia * ra.y * ra.y + ib * rb.y * rb.y;
                let k12 = -ia * ra.x * ra.y - ib * rb.x * rb.y;
                let k22 = ma + mb + ia * ra.x * ra.x + ib * rb.x * rb.x;
                let det = k11 * k22 - k12 * k12;
                let mut force = Vector2::zeros();
                if det > 0.0 {
                    let (w, z) = (TAU * j.linear_spring.hertz, j.linear_spring.damping_ratio);
                    let rhs = w * w * e + 2.0 * z * w * e_dot;
                    force =
                        -Vector2::new(k22 * rhs.x - k12 * rhs.y, k11 * rhs.y - k12 * rhs.x) / det;
                    let size = force.norm();
                    if size > j.max_force {
                        force *= j.max_force / size;
                    }
                }
                let mut torque = 0.0;
                let ki = ia + ib;
                if ki > 0.0 {
                    let (w, z) = (TAU * j.angular_spring.hertz, j.angular_spring.damping_ratio);
                    let c = wrap_angle(b.angle - a.angle - info.reference_angle);
                    let c_dot = b.omega - a.omega;
                    torque = (-(w * w * c + 2.0 * z * w * c_dot) / ki)
                        .clamp(-j.max_torque, j.max_torque);
                }
                a.push(accel, -force, -(crate::shape::cross(ra, force) + torque));
                b.push(accel, force, crate::shape::cross(rb, force) + torque);
                out.push(AppliedJointForce {
                    joint: id,
                    force,
                    torque,
                });
            }
            _ => {}
        }
    }
}
