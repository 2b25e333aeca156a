//! The motor joint: drives B's pose relative to A toward a target offset
//! (a linear offset in A's frame and an angular offset) by a linear and an
//! angular spring whose force and torque are bounded (Box2D v3.2's
//! `motor_joint.c`, its spring part: v3.2 replaced v3.0's correction
//! factor by these springs' frequency and damping ratio).
//!
//! The anchors are the bodies' centres (the world side: the origin); the
//! target of B's centre is p_A + R(θ_A) o, o the linear offset in A's
//! frame, so the arm of A's side is r_A = R(θ_A) o (turned with A in each
//! substep) and the error e = c_B − (c_A + r_A). The angle error is
//! θ_B − θ_A − θ_offset (the joint's reference angle is the angular
//! offset). Rows, in the order solved (Box2D's):
//!
//! | row | C | J v | effective mass | softness | bound |
//! |---|---|---|---|---|---|
//! | angular spring | θ_B − θ_A − θ_offset | ω_B − ω_A | 1/(i_A + i_B) | its f, ζ, both passes | \|λ\| ≤ h τ_max |
//! | linear spring (2 rows) | e | v_B − v_A − ω_A × r_A | K⁻¹ | its f, ζ, both passes | \|λ\| ≤ h F_max |
//!
//! K = [[m_A + m_B + i_A r_Ay², −i_A r_Ax r_Ay],
//!      [−i_A r_Ax r_Ay, m_A + m_B + i_A r_Ax²]] (B's arm is 0). The angular impulse is clamped to
//! [−h τ_max, h τ_max]; the linear one is scaled back onto the disc
//! |λ| ≤ h F_max after each increment (as the target joint's): the force
//! and torque on B never exceed F_max and τ_max. Unbounded (far from the
//! bounds) each spring is a damped oscillator of its f and ζ on its
//! effective mass: a body released at an offset e₀ from its target with
//! ζ = 1 reaches it as e₀ (1 + ωt) e^{−ωt}.

use super::frame::{JointFrame, RowScale};
use super::{JointSpring, finite, positive};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;
use nalgebra::Vector2;

/// The parameters of a motor joint ([`super::JointDef::motor`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MotorJoint {
    /// Target position of B's centre relative to A's centre, in A's frame
    /// (m), finite.
    pub linear_offset: Vector2<f64>,
    /// Target relative angle θ_B − θ_A (rad), finite.
    pub angular_offset: f64,
    /// Largest force on B (N), finite and > 0.
    pub max_force: f64,
    /// Largest torque on B (N·m), finite and > 0.
    pub max_torque: f64,
    /// The linear spring. Default 4 Hz, ζ = 1.
    pub linear_spring: JointSpring,
    /// The angular spring. Default 4 Hz, ζ = 1.
    pub angular_spring: JointSpring,
}

impl MotorJoint {
    /// A motor joint driving B to `linear_offset` (m, A's frame) and
    /// `angular_offset` (rad) from A with at most `max_force` (N) and
    /// `max_torque` (N·m), its springs at 4 Hz and ζ = 1 (critically
    /// damped).
    pub fn new(
        linear_offset: Vector2<f64>,
        angular_offset: f64,
        max_force: f64,
        max_torque: f64,
    ) -> Self {
        Self {
            linear_offset,
            angular_offset,
            max_force,
            max_torque,
            linear_spring: JointSpring::new(4.0, 1.0),
            angular_spring: JointSpring::new(4.0, 1.0),
        }
    }

    pub(super) fn check(&self, name: &str) -> Result<()> {
        finite(name, "linear offset x (m)", self.linear_offset.x)?;
        finite(name, "linear offset y (m)", self.linear_offset.y)?;
        finite(name, "angular offset (rad)", self.angular_offset)?;
        positive(name, "largest force (N)", self.max_force)?;
        positive(name, "largest torque (N·m)", self.max_torque)?;
        self.linear_spring.check(name, "linear spring")?;
        self.angular_spring.check(name, "angular spring")
    }
}

/// A motor joint's parameters, per-step values and impulses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct MotorJointRows {
    pub joint: MotorJoint,
    /// The linear offset in the world frame at the step's start (m).
    offset: Vector2<f64>,
    linear_softness: Softness,
    angular_softness: Softness,
    pub linear: Vector2<f64>,
    pub angular: f64,
}

impl MotorJointRows {
    pub(super) fn new(joint: MotorJoint) -> Self {
        Self {
            joint,
            offset: joint.linear_offset,
            linear_softness: Softness::RIGID,
            angular_softness: Softness::RIGID,
            linear: Vector2::zeros(),
            angular: 0.0,
        }
    }

    /// `rotation_a`: (cos, sin) of A's angle at the step's start.
    pub(super) fn prepare(&mut self, h: f64, rotation_a: (f64, f64), warm: bool) {
        let (c, s) = rotation_a;
        let o = self.joint.linear_offset;
        self.offset = Vector2::new(c * o.x - s * o.y, s * o.x + c * o.y);
        let (l, r) = (self.joint.linear_spring, self.joint.angular_spring);
        self.linear_softness = Softness::new(l.hertz, l.damping_ratio, h);
        self.angular_softness = Softness::new(r.hertz, r.damping_ratio, h);
        if !warm {
            self.linear = Vector2::zeros();
            self.angular = 0.0;
        }
    }

    /// A's arm (the target point from A's centre) and B's (the anchor from
    /// B's centre, as the joint was given) now.
    fn arms(&self, f: &JointFrame, a: &SolverBody, b: &SolverBody) -> (Vector2<f64>, Vector2<f64>) {
        let (ra, rb) = f.anchors(a, b);
        (ra + a.rotate(self.offset), rb)
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let arms = self.arms(f, a, b);
        f.apply(a, b, arms, self.linear, self.angular);
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        h: f64,
    ) {
        if !f.fixed_rotation() {
            let row = RowScale::soft(&self.angular_softness);
            let c = f.angle_now(a, b);
            let old = self.angular;
            let max = h * self.joint.max_torque;
            let d = row.increment(f.axial_mass(), b.w - a.w, c, old);
            self.angular = (old + d).clamp(-max, max);
            f.apply_angular(a, b, self.angular - old);
        }
        let arms = self.arms(f, a, b);
        let (ra, rb) = arms;
        let e = (b.dp - a.dp) + f.delta_center + rb - ra;
        let max = h * self.joint.max_force;
        f.solve_bounded_point(a, b, arms, &self.linear_softness, e, &mut self.linear, max);
    }
}
