//! The prismatic joint: B slides along an axis fixed in A, without turning
//! relative to it, with optional translation limits, a motor and a linear
//! spring (Box2D's `prismatic_joint.c`).
//!
//! With u the axis turned with A (u = R(Δθ_A) u₀), n = (−u_y, u_x) its
//! normal, d = p_B − p_A the anchors' separation (updated from the bodies'
//! motion in each substep), the translation s = u·d, and the arms
//! a₁ = (d + r_A) × u, a₂ = r_B × u, s₁ = (d + r_A) × n, s₂ = r_B × n (the
//! force along the axis acts at B's anchor), the rows in the order solved:
//!
//! | row | C | J v | effective mass | softness |
//! |---|---|---|---|---|
//! | spring | s − s_target | u·(v_B − v_A) + a₂ ω_B − a₁ ω_A | 1/k_u | the spring's f, ζ, both passes |
//! | motor | — | (same) − v_motor | 1/k_u | none; \|λ\| ≤ h F_max |
//! | lower limit | s − s_lo ≥ 0 | (same) | 1/k_u | speculative / rigid rows'; λ ≥ 0 |
//! | upper limit | s_hi − s ≥ 0 | −(same) | 1/k_u | speculative / rigid rows'; λ ≥ 0 |
//! | line and angle (2 rows) | (n·d, θ) | (n·(v_B − v_A) + s₂ ω_B − s₁ ω_A, ω_B − ω_A) | K⁻¹ | rigid rows' |
//!
//! with k_u = m_A + m_B + i_A a₁² + i_B a₂² and
//!
//! K = [[m_A + m_B + i_A s₁² + i_B s₂², i_A s₁ + i_B s₂],
//!      [i_A s₁ + i_B s₂, i_A + i_B]]   (k₂₂ = 1 when neither body turns).
//!
//! An impulse λ along u applies −λu, −λ a₁ to A and +λu, +λ a₂ to B; the
//! block's (λ_n, λ_θ) applies −λ_n n, −(λ_n s₁ + λ_θ) to A and +λ_n n,
//! +(λ_n s₂ + λ_θ) to B. The axis is given in the world frame when the
//! joint is added and kept in A's frame; it is turned into the world frame
//! once per step. Unlike Box2D, a limit row is not skipped beyond a quarter
//! of the limits' span: its speculative bias s/h already keeps it from
//! pushing until the slider would reach it within the substep.

use super::frame::{JointFrame, RowScale, cross, limit_row, solve_2x2};
use super::{JointSpring, direction, finite, ordered, positive};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;
use nalgebra::Vector2;

/// A prismatic joint's motor.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrismaticMotor {
    /// Target speed of B along the axis relative to A (m/s), any sign.
    pub speed: f64,
    /// Largest force it applies (N), > 0.
    pub max_force: f64,
}

/// The parameters of a prismatic joint ([`super::JointDef::prismatic`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Prismatic {
    /// The sliding direction in the world frame when the joint is added
    /// (normalized; finite and not zero), then fixed in A's frame. Default
    /// x.
    pub axis: Vector2<f64>,
    /// `[lower, upper]` translation of B's anchor from A's along the axis
    /// (m), lower ≤ upper. Default none.
    pub limits: Option<(f64, f64)>,
    /// A motor driving the translation speed. Default none.
    pub motor: Option<PrismaticMotor>,
    /// A spring pulling the translation toward `spring_target`. Default
    /// none.
    pub spring: Option<JointSpring>,
    /// The spring's rest translation (m), finite. Default 0.
    pub spring_target: f64,
}

impl Default for Prismatic {
    fn default() -> Self {
        Self {
            axis: Vector2::x(),
            limits: None,
            motor: None,
            spring: None,
            spring_target: 0.0,
        }
    }
}

impl Prismatic {
    /// A free slider along `axis` (world frame).
    pub fn along(axis: Vector2<f64>) -> Self {
        Self {
            axis,
            ..Self::default()
        }
    }

    pub(super) fn check(&self, name: &str) -> Result<()> {
        direction(name, self.axis)?;
        if let Some(l) = self.limits {
            ordered(name, "translation limit", "m", l)?;
        }
        if let Some(m) = self.motor {
            finite(name, "motor speed (m/s)", m.speed)?;
            positive(name, "largest motor force (N)", m.max_force)?;
        }
        if let Some(s) = self.spring {
            s.check(name, "spring")?;
        }
        finite(name, "spring target translation (m)", self.spring_target)?;
        Ok(())
    }
}

/// A prismatic joint's parameters, per-step values and impulses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct PrismaticRows {
    pub joint: Prismatic,
    /// The unit axis in A's frame.
    pub local_axis: Vector2<f64>,
    /// The axis in the world frame at the step's start.
    axis: Vector2<f64>,
    spring_softness: Softness,
    /// (λ_n, λ_θ) of the line and angle rows.
    pub block: Vector2<f64>,
    pub spring: f64,
    pub motor: f64,
    pub lower: f64,
    pub upper: f64,
}

/// The axis and arms of a prismatic joint in a substep.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Geometry {
    anchors: (Vector2<f64>, Vector2<f64>),
    d: Vector2<f64>,
    axis: Vector2<f64>,
    a1: f64,
    a2: f64,
}

impl PrismaticRows {
    pub(super) fn new(joint: Prismatic, local_axis: Vector2<f64>) -> Self {
        Self {
            joint,
            local_axis,
            axis: local_axis,
            spring_softness: Softness::RIGID,
            block: Vector2::zeros(),
            spring: 0.0,
            motor: 0.0,
            lower: 0.0,
            upper: 0.0,
        }
    }

    /// The accumulated impulse along the axis (N·s).
    pub fn axial_impulse(&self) -> f64 {
        self.spring + self.motor + self.lower - self.upper
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
            self.block = Vector2::zeros();
            (self.spring, self.motor, self.lower, self.upper) = (0.0, 0.0, 0.0, 0.0);
        }
    }

    fn geometry(&self, f: &JointFrame, a: &SolverBody, b: &SolverBody) -> Geometry {
        let anchors = f.anchors(a, b);
        let d = f.separation(a, b, anchors);
        let axis = a.rotate(self.axis);
        Geometry {
            anchors,
            d,
            axis,
            a1: cross(d + anchors.0, axis),
            a2: cross(anchors.1, axis),
        }
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let g = self.geometry(f, a, b);
        let n = Vector2::new(-g.axis.y, g.axis.x);
        let s1 = cross(g.d + g.anchors.0, n);
        let s2 = cross(g.anchors.1, n);
        let axial = self.axial_impulse();
        let p = axial * g.axis + self.block.x * n;
        let la = axial * g.a1 + self.block.x * s1 + self.block.y;
        let lb = axial * g.a2 + self.block.x * s2 + self.block.y;
        f.apply_arms(a, b, p, (la, lb));
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        (h, inv_h): (f64, f64),
        use_bias: bool,
    ) {
        let g = self.geometry(f, a, b);
        let (u, a1, a2) = (g.axis, g.a1, g.a2);
        let translation = u.dot(&g.d);
        let k = f.ma + f.mb + f.ia * a1 * a1 + f.ib * a2 * a2;
        let mass = if k > 0.0 { 1.0 / k } else { 0.0 };
        let speed = |a: &SolverBody, b: &SolverBody| u.dot(&(b.v - a.v)) + a2 * b.w - a1 * a.w;
        let push = |a: &mut SolverBody, b: &mut SolverBody, d: f64| {
            f.apply_arms(a, b, d * u, (d * a1, d * a2));
        };
        if self.joint.spring.is_some() {
            let row = RowScale::soft(&self.spring_softness);
            let c = translation - self.joint.spring_target;
            let d = row.increment(mass, speed(a, b), c, self.spring);
            self.spring += d;
            push(a, b, d);
        }
        if let Some(m) = self.joint.motor {
            let max = h * m.max_force;
            let old = self.motor;
            self.motor = (old + mass * (m.speed - speed(a, b))).clamp(-max, max);
            push(a, b, self.motor - old);
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
        let n = Vector2::new(-u.y, u.x);
        let s1 = cross(g.d + g.anchors.0, n);
        let s2 = cross(g.anchors.1, n);
        let cdot = Vector2::new(n.dot(&(b.v - a.v)) + s2 * b.w - s1 * a.w, b.w - a.w);
        let row = RowScale::rigid_row(&f.softness, use_bias);
        let bias = if use_bias {
            row.bias_rate * Vector2::new(n.dot(&g.d), f.angle_now(a, b))
        } else {
            Vector2::zeros()
        };
        let k11 = f.ma + f.mb + f.ia * s1 * s1 + f.ib * s2 * s2;
        let k12 = f.ia * s1 + f.ib * s2;
        let k22 = if f.fixed_rotation() { 1.0 } else { f.ia + f.ib };
        let x = solve_2x2(k11, k12, k22, row.mass_scale * cdot + bias);
        let d = -x - row.impulse_scale * self.block;
        self.block += d;
        f.apply_arms(a, b, d.x * n, (d.x * s1 + d.y, d.x * s2 + d.y));
    }
}
