//! The wheel joint: B's anchor (the axle) stays on a line fixed in A (the
//! suspension's axis), B turns freely about it, a spring-damper acts along
//! the axis, with optional translation limits and a motor on the relative
//! rotation (Box2D's `wheel_joint.c`: A is the chassis, B the wheel).
//!
//! With u the axis turned with A (u = R(Δθ_A) u₀), n = (−u_y, u_x) its
//! normal, d = p_B − p_A the anchors' separation (updated from the bodies'
//! motion in each substep), the translation s = u·d, and the arms
//! a₁ = (d + r_A) × u, a₂ = r_B × u, s₁ = (d + r_A) × n, s₂ = r_B × n, the
//! rows in the order solved:
//!
//! | row | C | J v | effective mass | softness |
//! |---|---|---|---|---|
//! | motor | — | ω_B − ω_A − ω_motor | 1/(i_A + i_B) | none; \|λ\| ≤ h τ_max |
//! | spring | s | u·(v_B − v_A) + a₂ ω_B − a₁ ω_A | 1/k_u | the spring's f, ζ, both passes |
//! | lower limit | s − s_lo ≥ 0 | (same) | 1/k_u | speculative / rigid rows'; λ ≥ 0 |
//! | upper limit | s_hi − s ≥ 0 | −(same) | 1/k_u | speculative / rigid rows'; λ ≥ 0 |
//! | point on line | n·d | n·(v_B − v_A) + s₂ ω_B − s₁ ω_A | 1/k_n | rigid rows' |
//!
//! with k_u = m_A + m_B + i_A a₁² + i_B a₂² and k_n = m_A + m_B + i_A s₁² +
//! i_B s₂². The spring's rest is s = 0 (the anchors level along the axis,
//! Box2D's), and its stiffness and damping are those of its frequency f
//! and ratio ζ on the axial effective mass 1/k_u: k = ω²/k_u, c = 2ζω/k_u,
//! ω = 2πf (a chassis of mass m on a fixed axle bounces at f whatever m).
//! An impulse λ along u applies −λu, −λa₁ to A and +λu, +λa₂ to B; one
//! along n, −λn, −λs₁ and +λn, +λs₂. Without a spring the axis is free
//! (Box2D's wheel without suspension).

use super::frame::{JointFrame, RowScale, cross, limit_row};
use super::{JointSpring, direction, finite, ordered, positive};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;
use nalgebra::Vector2;

/// A wheel joint's motor on the wheel's rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WheelMotor {
    /// Target relative angular velocity ω_B − ω_A (rad/s), any sign.
    pub speed: f64,
    /// Largest torque it applies (N·m), > 0: under a larger load it slips.
    pub max_torque: f64,
}

/// The parameters of a wheel joint ([`super::JointDef::wheel`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Wheel {
    /// The suspension's axis in the world frame when the joint is added
    /// (normalized; finite and not zero), then fixed in A's frame. Default
    /// y (Box2D's).
    pub axis: Vector2<f64>,
    /// The suspension spring along the axis (Box2D's default 1 Hz,
    /// ζ = 0.7); `None`: the axis is free.
    pub spring: Option<JointSpring>,
    /// `[lower, upper]` translation of B's anchor from A's along the axis
    /// (m), lower ≤ upper. Default none.
    pub limits: Option<(f64, f64)>,
    /// A motor driving the wheel's rotation relative to A. Default none.
    pub motor: Option<WheelMotor>,
}

impl Default for Wheel {
    fn default() -> Self {
        Self {
            axis: Vector2::y(),
            spring: Some(JointSpring::new(1.0, 0.7)),
            limits: None,
            motor: None,
        }
    }
}

impl Wheel {
    /// A wheel whose suspension along `axis` (world frame) is a spring of
    /// `hertz` (Hz) and `damping_ratio`, without limits or motor.
    pub fn suspension(axis: Vector2<f64>, hertz: f64, damping_ratio: f64) -> Self {
        Self {
            axis,
            spring: Some(JointSpring::new(hertz, damping_ratio)),
            limits: None,
            motor: None,
        }
    }

    pub(super) fn check(&self, name: &str) -> Result<()> {
        direction(name, self.axis)?;
        if let Some(s) = self.spring {
            s.check(name, "suspension spring")?;
        }
        if let Some(l) = self.limits {
            ordered(name, "translation limit", "m", l)?;
        }
        if let Some(m) = self.motor {
            finite(name, "motor speed (rad/s)", m.speed)?;
            positive(name, "largest motor torque (N·m)", m.max_torque)?;
        }
        Ok(())
    }
}

/// A wheel joint's parameters, per-step values and impulses (N·s, N·m·s).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct WheelRows {
    pub joint: Wheel,
    /// The unit axis in A's frame.
    pub local_axis: Vector2<f64>,
    /// The axis in the world frame at the step's start.
    axis: Vector2<f64>,
    spring_softness: Softness,
    pub perpendicular: f64,
    pub spring: f64,
    pub motor: f64,
    pub lower: f64,
    pub upper: f64,
}

impl WheelRows {
    pub(super) fn new(joint: Wheel, local_axis: Vector2<f64>) -> Self {
        Self {
            joint,
            local_axis,
            axis: local_axis,
            spring_softness: Softness::RIGID,
            perpendicular: 0.0,
            spring: 0.0,
            motor: 0.0,
            lower: 0.0,
            upper: 0.0,
        }
    }

    /// The accumulated impulse along the axis (N·s).
    pub fn axial_impulse(&self) -> f64 {
        self.spring + self.lower - self.upper
    }

    /// `rotation_a`: (cos, sin) of A's angle at the step's start.
    pub(super) fn prepare(&mut self, h: f64, rotation_a: (f64, f64), warm: bool) {
        let (c, s) = rotation_a;
        let u = self.local_axis;
        self.axis = Vector2::new(c * u.x - s * u.y, s * u.x + c * u.y);
        self.spring_softness = match self.joint.spring {
            Some(s) => Softness::new(s.hertz, s.damping_ratio, h),
            None => Softness::RIGID,
        };
        if !warm {
            (self.perpendicular, self.spring, self.motor) = (0.0, 0.0, 0.0);
            (self.lower, self.upper) = (0.0, 0.0);
        }
    }

    /// The axis, its normal, d and the arms (a₁, a₂, s₁, s₂) now.
    fn geometry(
        &self,
        f: &JointFrame,
        a: &SolverBody,
        b: &SolverBody,
    ) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>, [f64; 4]) {
        let anchors = f.anchors(a, b);
        let d = f.separation(a, b, anchors);
        let u = a.rotate(self.axis);
        let n = Vector2::new(-u.y, u.x);
        let arms = [
            cross(d + anchors.0, u),
            cross(anchors.1, u),
            cross(d + anchors.0, n),
            cross(anchors.1, n),
        ];
        (u, n, d, arms)
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let (u, n, _, [a1, a2, s1, s2]) = self.geometry(f, a, b);
        let axial = self.axial_impulse();
        let p = axial * u + self.perpendicular * n;
        let la = axial * a1 + self.perpendicular * s1 + self.motor;
        let lb = axial * a2 + self.perpendicular * s2 + self.motor;
        f.apply_arms(a, b, p, (la, lb));
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        (h, inv_h): (f64, f64),
        use_bias: bool,
    ) {
        if let Some(m) = self.joint.motor {
            let max = h * m.max_torque;
            let old = self.motor;
            let cdot = b.w - a.w - m.speed;
            self.motor = (old - f.axial_mass() * cdot).clamp(-max, max);
            f.apply_angular(a, b, self.motor - old);
        }
        let (u, n, d, [a1, a2, s1, s2]) = self.geometry(f, a, b);
        let translation = u.dot(&d);
        let k = f.ma + f.mb + f.ia * a1 * a1 + f.ib * a2 * a2;
        let mass = if k > 0.0 { 1.0 / k } else { 0.0 };
        let speed = |a: &SolverBody, b: &SolverBody| u.dot(&(b.v - a.v)) + a2 * b.w - a1 * a.w;
        let push = |a: &mut SolverBody, b: &mut SolverBody, d: f64| {
            f.apply_arms(a, b, d * u, (d * a1, d * a2));
        };
        if self.joint.spring.is_some() {
            let row = RowScale::soft(&self.spring_softness);
            let d = row.increment(mass, speed(a, b), translation, self.spring);
            self.spring += d;
            push(a, b, d);
        }
        if let Some((lo, hi)) = self.joint.limits {
            let s = &f.softness;
            let c = (mass, speed(a, b), translation - lo);
            let d = limit_row(&mut self.lower, c, s, use_bias, inv_h);
            push(a, b, d);
            let c = (mass, -speed(a, b), hi - translation);
            let d = limit_row(&mut self.upper, c, s, use_bias, inv_h);
            push(a, b, -d);
        }
        let kn = f.ma + f.mb + f.ia * s1 * s1 + f.ib * s2 * s2;
        let mass_n = if kn > 0.0 { 1.0 / kn } else { 0.0 };
        let cdot = n.dot(&(b.v - a.v)) + s2 * b.w - s1 * a.w;
        let row = RowScale::rigid_row(&f.softness, use_bias);
        let c = if use_bias { n.dot(&d) } else { 0.0 };
        let d = row.increment(mass_n, cdot, c, self.perpendicular);
        self.perpendicular += d;
        f.apply_arms(a, b, d * n, (d * s1, d * s2));
    }
}
