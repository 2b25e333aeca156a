//! The revolute joint: a point shared by two bodies, about which they turn
//! freely, with optional angle limits, a motor and a rotational spring
//! (Box2D's `revolute_joint.c`).
//!
//! Rows, in the order solved (notation of [`super::frame`]; θ the joint
//! angle θB − θA − θref, ω_rel = ω_B − ω_A, k_θ = 1/(i_A + i_B)):
//!
//! | row | C | J v | effective mass | softness |
//! |---|---|---|---|---|
//! | spring | wrap(θ − θ_target) | ω_rel | k_θ | the spring's f, ζ, both passes |
//! | motor | — | ω_rel − ω_motor | k_θ | none; \|λ\| ≤ h τ_max |
//! | lower limit | θ − θ_lo ≥ 0 | ω_rel | k_θ | speculative / rigid rows'; λ ≥ 0 |
//! | upper limit | θ_hi − θ ≥ 0 | −ω_rel | k_θ | speculative / rigid rows'; λ ≥ 0 |
//! | point (2 rows) | p_B − p_A | v_B + ω_B × r_B − v_A − ω_A × r_A | K⁻¹ | rigid rows' |
//!
//! with the point rows' 2 × 2 mass matrix
//!
//! K = [[m_A + m_B + i_A r_Ay² + i_B r_By², −i_A r_Ax r_Ay − i_B r_Bx r_By],
//!      [−i_A r_Ax r_Ay − i_B r_Bx r_By, m_A + m_B + i_A r_Ax² + i_B r_Bx²]],
//!
//! and the point's separation C = (c_B − c_A) + (Δp_B − Δp_A) + r_B − r_A
//! updated from the bodies' motion in each substep. The angular rows are
//! skipped when neither body can turn. The accumulated angular impulse
//! λ_spring + λ_motor + λ_lo − λ_hi is applied as −λ to A and +λ to B.

use super::frame::{JointFrame, RowScale, limit_row};
use super::{JointSpring, finite, invalid, ordered, positive, wrap_angle};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;
use nalgebra::Vector2;

/// Largest |limit| (rad): the joint angle is measured in [−π, π), so a
/// limit at ±π could be crossed by wrapping (Box2D's bound).
pub const MAX_LIMIT_ANGLE: f64 = 0.99 * std::f64::consts::PI;

/// A revolute joint's motor.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RevoluteMotor {
    /// Target relative angular velocity ω_B − ω_A (rad/s), any sign.
    pub speed: f64,
    /// Largest torque it applies (N·m), > 0: under a larger load it slips.
    /// `f64::INFINITY`: unbounded (a prescribed speed; under the exact
    /// model the joint angle is prescribed, `crate::exact::joints`).
    pub max_torque: f64,
}

/// The parameters of a revolute joint ([`super::JointDef::revolute`]).
/// `Default`: free rotation, no limits, no motor, no spring.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Revolute {
    /// `[lower, upper]` joint angle (rad), lower ≤ upper, each within
    /// ±0.99π ([`MAX_LIMIT_ANGLE`]). Default none.
    pub limits: Option<(f64, f64)>,
    /// A motor driving ω_B − ω_A to its speed. Default none.
    pub motor: Option<RevoluteMotor>,
    /// A rotational spring pulling the joint angle toward
    /// `spring_target`. Default none.
    pub spring: Option<JointSpring>,
    /// The spring's rest angle (rad), finite. Default 0.
    pub spring_target: f64,
}

impl Revolute {
    pub(super) fn check(&self, name: &str) -> Result<()> {
        if let Some((lo, hi)) = self.limits {
            ordered(name, "angle limit", "rad", (lo, hi))?;
            for v in [lo, hi] {
                if v.abs() > MAX_LIMIT_ANGLE {
                    return Err(invalid(
                        name,
                        format!(
                            "angle limit {} rad is beyond ±0.99π = ±{:.6} rad (the joint angle is measured in [−π, π))",
                            crate::error::readable(v),
                            MAX_LIMIT_ANGLE
                        ),
                    ));
                }
            }
        }
        if let Some(m) = self.motor {
            finite(name, "motor speed (rad/s)", m.speed)?;
            // +∞: unbounded (a prescribed speed; under the exact model a
            // prescribed angle, `crate::exact::joints`).
            if m.max_torque != f64::INFINITY {
                positive(name, "largest motor torque (N·m)", m.max_torque)?;
            }
        }
        if let Some(s) = self.spring {
            s.check(name, "spring")?;
        }
        finite(name, "spring target angle (rad)", self.spring_target)?;
        Ok(())
    }
}

/// A revolute joint's parameters, per-step values and impulses (N·m·s and
/// N·s, accumulated over a substep and warm-started).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct RevoluteRows {
    pub joint: Revolute,
    pub(super) spring_softness: Softness,
    pub(super) axial_mass: f64,
    pub linear: Vector2<f64>,
    pub spring: f64,
    pub motor: f64,
    pub lower: f64,
    pub upper: f64,
}

impl RevoluteRows {
    pub(super) fn new(joint: Revolute) -> Self {
        Self {
            joint,
            spring_softness: Softness::RIGID,
            axial_mass: 0.0,
            linear: Vector2::zeros(),
            spring: 0.0,
            motor: 0.0,
            lower: 0.0,
            upper: 0.0,
        }
    }

    /// The accumulated angular impulse on B (N·m·s).
    pub fn axial_impulse(&self) -> f64 {
        self.spring + self.motor + self.lower - self.upper
    }

    /// The step's values, the spring's softness `spring` (rigid without a
    /// spring) computed by the caller for the substep; the impulses zeroed
    /// unless `warm`.
    pub(super) fn prepare(&mut self, frame: &JointFrame, spring: Softness, warm: bool) {
        self.axial_mass = frame.axial_mass();
        self.spring_softness = spring;
        if !warm {
            *self = Self {
                linear: Vector2::zeros(),
                spring: 0.0,
                motor: 0.0,
                lower: 0.0,
                upper: 0.0,
                ..*self
            };
        }
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let anchors = f.anchors(a, b);
        f.apply(a, b, anchors, self.linear, self.axial_impulse());
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        (h, inv_h): (f64, f64),
        use_bias: bool,
    ) {
        if !f.fixed_rotation() {
            let k = self.axial_mass;
            let angle = f.angle_now(a, b);
            if self.joint.spring.is_some() {
                let row = RowScale::soft(&self.spring_softness);
                let c = wrap_angle(angle - self.joint.spring_target);
                let d = row.increment(k, b.w - a.w, c, self.spring);
                self.spring += d;
                f.apply_angular(a, b, d);
            }
            if let Some(m) = self.joint.motor {
                let max = h * m.max_torque;
                let old = self.motor;
                self.motor = (old - k * (b.w - a.w - m.speed)).clamp(-max, max);
                f.apply_angular(a, b, self.motor - old);
            }
            if let Some((lo, hi)) = self.joint.limits {
                let s = &f.softness;
                let d = limit_row(
                    &mut self.lower,
                    (k, b.w - a.w, angle - lo),
                    s,
                    use_bias,
                    inv_h,
                );
                f.apply_angular(a, b, d);
                let d = limit_row(
                    &mut self.upper,
                    (k, a.w - b.w, hi - angle),
                    s,
                    use_bias,
                    inv_h,
                );
                f.apply_angular(a, b, -d);
            }
        }
        let anchors = f.anchors(a, b);
        let cdot = f.anchor_velocity(a, b, anchors);
        let row = RowScale::rigid_row(&f.softness, use_bias);
        let bias = if use_bias {
            row.bias_rate * f.separation(a, b, anchors)
        } else {
            Vector2::zeros()
        };
        let (k11, k12, k22) = f.point_mass_matrix(anchors);
        let x = super::frame::solve_2x2(k11, k12, k22, row.mass_scale * cdot + bias);
        let d = -x - row.impulse_scale * self.linear;
        self.linear += d;
        f.apply(a, b, anchors, d, 0.0);
    }
}
