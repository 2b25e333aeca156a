//! The target joint (Box2D's mouse joint, now its motor joint's linear
//! spring): a point of one body pulled toward a world point, the target,
//! by a spring whose force is bounded. The target moves when the program
//! says so ([`crate::World::set_joint_target`]).
//!
//! Side A is the world, its anchor the target t; B's anchor p_B. Two rows,
//! solved as a block, in both passes (a real spring):
//!
//! | row | C | J v | effective mass | softness |
//! |---|---|---|---|---|
//! | point (2 rows) | p_B − t | v_B + ω_B × r_B | K⁻¹ | the joint's f, ζ |
//!
//! with K = [[m_B + i_B r_By², −i_B r_Bx r_By], [−i_B r_Bx r_By, m_B +
//! i_B r_Bx²]]. After each increment the accumulated impulse is scaled
//! back onto the disc |λ| ≤ h F_max, so the force on the body never
//! exceeds F_max. The body's rotation is not damped: pulled by one point
//! it swings about it.

use super::frame::JointFrame;
use super::{JointSpring, invalid, positive};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;
use nalgebra::Vector2;

/// The parameters of a target joint ([`super::JointDef::target`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Target {
    /// Largest force on the body (N), finite and > 0.
    pub max_force: f64,
    /// The pull's stiffness and damping. Default 4 Hz, ζ = 1 (Box2D's
    /// mouse joint).
    pub spring: JointSpring,
}

impl Target {
    /// A pull of at most `max_force` (N) with Box2D's 4 Hz and ζ = 1.
    pub fn new(max_force: f64) -> Self {
        Self {
            max_force,
            spring: JointSpring::new(4.0, 1.0),
        }
    }

    pub(super) fn check(&self, name: &str) -> Result<()> {
        positive(name, "largest force (N)", self.max_force)?;
        self.spring.check(name, "spring")
    }

    /// Refuses a target joint whose sides are not the world (A) and a body
    /// (B).
    pub(super) fn check_sides(name: &str, a: Option<usize>, b: Option<usize>) -> Result<()> {
        if a.is_some() || b.is_none() {
            return Err(invalid(
                name,
                "a target joint pulls one body (B) toward a world point (A): its body A must be the world"
                    .into(),
            ));
        }
        Ok(())
    }
}

/// A target joint's parameters, per-step values and impulse (N·s).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct TargetRows {
    pub joint: Target,
    softness: Softness,
    pub linear: Vector2<f64>,
}

impl TargetRows {
    pub(super) fn new(joint: Target) -> Self {
        Self {
            joint,
            softness: Softness::RIGID,
            linear: Vector2::zeros(),
        }
    }

    pub(super) fn prepare(&mut self, h: f64, warm: bool) {
        let s = self.joint.spring;
        self.softness = Softness::new(s.hertz, s.damping_ratio, h);
        if !warm {
            self.linear = Vector2::zeros();
        }
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let anchors = f.anchors(a, b);
        f.apply(a, b, anchors, self.linear, 0.0);
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        h: f64,
    ) {
        let anchors = f.anchors(a, b);
        let error = f.separation(a, b, anchors);
        let max = h * self.joint.max_force;
        f.solve_bounded_point(a, b, anchors, &self.softness, error, &mut self.linear, max);
    }
}
