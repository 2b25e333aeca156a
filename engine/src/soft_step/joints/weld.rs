//! The weld joint: two bodies held at their relative pose, rigidly or
//! through a linear and an angular spring (Box2D's `weld_joint.c`, its
//! row-by-row form).
//!
//! Rows, in the order solved (notation of [`super::frame`]):
//!
//! | row | C | J v | effective mass | softness |
//! |---|---|---|---|---|
//! | angle | θ = θB − θA − θref | ω_B − ω_A | 1/(i_A + i_B) | the angular spring's f, ζ (both passes), else the rigid rows' |
//! | point (2 rows) | p_B − p_A | v_B + ω_B × r_B − v_A − ω_A × r_A | K⁻¹ | the linear spring's f, ζ (both passes), else the rigid rows' |
//!
//! with K the revolute's point matrix ([`super::revolute`]). The rows are
//! solved one after the other rather than as one 3 × 3 block (Box2D's
//! choice: the block form mixes stiffnesses badly when only one side is
//! sprung); a rigid weld therefore holds its pose to the rigid rows'
//! softness, not exactly.

use super::JointSpring;
use super::frame::{JointFrame, RowScale, solve_2x2};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;
use nalgebra::Vector2;

/// The parameters of a weld ([`super::JointDef::weld`]). `Default`: rigid.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Weld {
    /// A spring on the anchors' separation instead of the rigid point rows.
    /// Default none.
    pub linear_spring: Option<JointSpring>,
    /// A spring on the relative angle instead of the rigid angle row.
    /// Default none.
    pub angular_spring: Option<JointSpring>,
}

impl Weld {
    pub(super) fn check(&self, name: &str) -> Result<()> {
        if let Some(s) = self.linear_spring {
            s.check(name, "linear spring")?;
        }
        if let Some(s) = self.angular_spring {
            s.check(name, "angular spring")?;
        }
        Ok(())
    }
}

/// A weld's parameters, per-step values and impulses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct WeldRows {
    pub joint: Weld,
    linear_softness: Softness,
    angular_softness: Softness,
    axial_mass: f64,
    pub linear: Vector2<f64>,
    pub angular: f64,
}

impl WeldRows {
    pub(super) fn new(joint: Weld) -> Self {
        Self {
            joint,
            linear_softness: Softness::RIGID,
            angular_softness: Softness::RIGID,
            axial_mass: 0.0,
            linear: Vector2::zeros(),
            angular: 0.0,
        }
    }

    pub(super) fn prepare(&mut self, f: &JointFrame, h: f64, warm: bool) {
        let soft = |s: Option<JointSpring>| match s {
            Some(s) => Softness::new(s.hertz, s.damping_ratio, h),
            None => f.softness,
        };
        self.linear_softness = soft(self.joint.linear_spring);
        self.angular_softness = soft(self.joint.angular_spring);
        self.axial_mass = f.axial_mass();
        if !warm {
            self.linear = Vector2::zeros();
            self.angular = 0.0;
        }
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let anchors = f.anchors(a, b);
        f.apply(a, b, anchors, self.linear, self.angular);
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        use_bias: bool,
    ) {
        let sprung = |s: &Option<JointSpring>| use_bias || s.is_some();
        if !f.fixed_rotation() {
            let (row, c) = if sprung(&self.joint.angular_spring) {
                (RowScale::soft(&self.angular_softness), f.angle_now(a, b))
            } else {
                (RowScale::RIGID, 0.0)
            };
            let d = row.increment(self.axial_mass, b.w - a.w, c, self.angular);
            self.angular += d;
            f.apply_angular(a, b, d);
        }
        let anchors = f.anchors(a, b);
        let cdot = f.anchor_velocity(a, b, anchors);
        let (row, bias) = if sprung(&self.joint.linear_spring) {
            let row = RowScale::soft(&self.linear_softness);
            (row, row.bias_rate * f.separation(a, b, anchors))
        } else {
            (RowScale::RIGID, Vector2::zeros())
        };
        let (k11, k12, k22) = f.point_mass_matrix(anchors);
        let x = solve_2x2(k11, k12, k22, row.mass_scale * cdot + bias);
        let d = -x - row.impulse_scale * self.linear;
        self.linear += d;
        f.apply(a, b, anchors, d, 0.0);
    }
}
