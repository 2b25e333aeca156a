//! What every joint type's rows share: the two bodies' solver indices and
//! inverse masses, the anchors and the centres' distance at the step's
//! start, the joint angle then, and the softness of the rigid rows
//! ([`JointFrame`]); the substep's view of them (current anchors,
//! separation and angle from the bodies' motion since the step began);
//! and applying an impulse to both bodies.
//!
//! Notation of the joint files: body A and B with inverse mass m_A, m_B
//! and inverse inertia i_A, i_B (0 for the world, static, kinematic or
//! non-rotating bodies); r_A, r_B the anchors from each centre of mass in
//! the world frame; v, ω the velocities; a × b = a_x b_y − a_y b_x and
//! ω × r = (−ω r_y, ω r_x).

use super::super::bodies::SolverBody;
use crate::soft_step::Softness;
use nalgebra::Vector2;

/// 2D cross product of vectors (the shape module's).
pub(super) use crate::shape::cross;

/// ω × r for a scalar ω.
#[inline(always)]
pub(super) fn cross_sv(w: f64, r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-w * r.y, w * r.x)
}

/// The solution x of the symmetric 2 × 2 system [[k11, k12], [k12, k22]]
/// x = b, or 0 when the matrix is singular (a joint between two bodies
/// that cannot move along it).
#[inline(always)]
pub(super) fn solve_2x2(k11: f64, k12: f64, k22: f64, b: Vector2<f64>) -> Vector2<f64> {
    let det = k11 * k22 - k12 * k12;
    if det == 0.0 {
        return Vector2::zeros();
    }
    let inv = 1.0 / det;
    Vector2::new(inv * (k22 * b.x - k12 * b.y), inv * (k11 * b.y - k12 * b.x))
}

/// The substep's coefficients of a row: rigid (mass scale 1, impulse scale
/// 0, no bias) or soft.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct RowScale {
    /// Rate at which the error is removed (1/s), times the mass scale.
    pub bias_rate: f64,
    pub mass_scale: f64,
    pub impulse_scale: f64,
}

impl RowScale {
    /// A rigid row without bias (the relax pass).
    pub const RIGID: RowScale = RowScale {
        bias_rate: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// The row of a soft constraint.
    #[inline(always)]
    pub fn soft(s: &Softness) -> Self {
        RowScale {
            bias_rate: s.mass_scale * s.bias_rate,
            mass_scale: s.mass_scale,
            impulse_scale: s.impulse_scale,
        }
    }

    /// A rigid row of the solve pass when `use_bias`, else [`Self::RIGID`].
    #[inline(always)]
    pub fn rigid_row(s: &Softness, use_bias: bool) -> Self {
        if use_bias { Self::soft(s) } else { Self::RIGID }
    }

    /// The increment of a scalar row of effective mass `mass` (J v = `cdot`,
    /// error `c`, accumulated impulse `impulse`).
    #[inline(always)]
    pub fn increment(&self, mass: f64, cdot: f64, c: f64, impulse: f64) -> f64 {
        -mass * (self.mass_scale * cdot + self.bias_rate * c) - self.impulse_scale * impulse
    }

    /// The coefficients of a one-sided limit row whose error is `c` (≥ 0
    /// when the limit holds): speculative while it holds (bias c/h, rigid,
    /// it may close the gap in this substep and no more), soft in the solve
    /// pass when violated, rigid without bias in the relax pass.
    #[inline(always)]
    pub fn limit(c: f64, s: &Softness, use_bias: bool, inv_h: f64) -> (Self, f64) {
        if c > 0.0 {
            (
                RowScale {
                    bias_rate: inv_h,
                    mass_scale: 1.0,
                    impulse_scale: 0.0,
                },
                c,
            )
        } else if use_bias {
            (Self::soft(s), c)
        } else {
            (Self::RIGID, 0.0)
        }
    }
}

/// A one-sided limit row on a scalar of effective mass `mass`: error `c`
/// (≥ 0 while the limit holds), speed `cdot` of that scalar; returns the
/// impulse increment, keeping the accumulated `impulse` ≥ 0.
#[inline(always)]
pub(super) fn limit_row(
    impulse: &mut f64,
    (mass, cdot, c): (f64, f64, f64),
    s: &Softness,
    use_bias: bool,
    inv_h: f64,
) -> f64 {
    let (row, c) = RowScale::limit(c, s, use_bias, inv_h);
    let old = *impulse;
    *impulse = (old + row.increment(mass, cdot, c, old)).max(0.0);
    *impulse - old
}

/// A joint's two bodies and what its rows read of them, fixed for a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct JointFrame {
    /// Solver indices of A and B (0: the world or a static body).
    pub a: usize,
    pub b: usize,
    /// Inverse masses (1/kg) and inertias (1/(kg·m²)).
    pub ma: f64,
    pub ia: f64,
    pub mb: f64,
    pub ib: f64,
    /// Anchors from each centre of mass at the step's start, world frame
    /// (m).
    pub ra: Vector2<f64>,
    pub rb: Vector2<f64>,
    /// c_B − c_A at the step's start (m).
    pub delta_center: Vector2<f64>,
    /// θB − θA − θref at the step's start, wrapped into [−π, π) (rad).
    pub angle: f64,
    /// Softness of the rigid rows in the solve pass.
    pub softness: Softness,
}

impl JointFrame {
    /// An unprepared frame.
    pub const EMPTY: JointFrame = JointFrame {
        a: 0,
        b: 0,
        ma: 0.0,
        ia: 0.0,
        mb: 0.0,
        ib: 0.0,
        ra: Vector2::new(0.0, 0.0),
        rb: Vector2::new(0.0, 0.0),
        delta_center: Vector2::new(0.0, 0.0),
        angle: 0.0,
        softness: Softness::RIGID,
    };

    /// The anchors now: r₀ turned by each body's rotation since the step
    /// began.
    #[inline(always)]
    pub fn anchors(&self, a: &SolverBody, b: &SolverBody) -> (Vector2<f64>, Vector2<f64>) {
        (a.rotate(self.ra), b.rotate(self.rb))
    }

    /// p_B − p_A now, the anchors' separation (m), from the anchors `ra`,
    /// `rb` now.
    #[inline(always)]
    pub fn separation(
        &self,
        a: &SolverBody,
        b: &SolverBody,
        (ra, rb): (Vector2<f64>, Vector2<f64>),
    ) -> Vector2<f64> {
        (b.dp - a.dp) + self.delta_center + (rb - ra)
    }

    /// The joint angle now (rad; not wrapped within the step).
    #[inline(always)]
    pub fn angle_now(&self, a: &SolverBody, b: &SolverBody) -> f64 {
        self.angle + (b.dtheta - a.dtheta)
    }

    /// Whether neither body can turn (the angular rows have no mass).
    #[inline(always)]
    pub fn fixed_rotation(&self) -> bool {
        self.ia + self.ib == 0.0
    }

    /// 1/(i_A + i_B), the effective mass of a relative-angle row; 0 when
    /// neither body turns.
    #[inline(always)]
    pub fn axial_mass(&self) -> f64 {
        let k = self.ia + self.ib;
        if k > 0.0 { 1.0 / k } else { 0.0 }
    }

    /// The relative velocity of the anchors, v_B + ω_B × r_B − v_A − ω_A ×
    /// r_A (m/s).
    #[inline(always)]
    pub fn anchor_velocity(
        &self,
        a: &SolverBody,
        b: &SolverBody,
        (ra, rb): (Vector2<f64>, Vector2<f64>),
    ) -> Vector2<f64> {
        (b.v + cross_sv(b.w, rb)) - (a.v + cross_sv(a.w, ra))
    }

    /// K = J M⁻¹ Jᵀ of the two point rows at anchors `ra`, `rb`, as (k11,
    /// k12, k22).
    #[inline(always)]
    pub fn point_mass_matrix(&self, (ra, rb): (Vector2<f64>, Vector2<f64>)) -> (f64, f64, f64) {
        let (ma, ia, mb, ib) = (self.ma, self.ia, self.mb, self.ib);
        (
            ma + mb + ra.y * ra.y * ia + rb.y * rb.y * ib,
            -ra.y * ra.x * ia - rb.y * rb.x * ib,
            ma + mb + ra.x * ra.x * ia + rb.x * rb.x * ib,
        )
    }

    /// Applies the impulse `p` (N·s) at the anchors (−p on A, +p on B) and
    /// the angular impulse `l` (N·m·s; −l on A, +l on B).
    #[inline(always)]
    pub fn apply(
        &self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        (ra, rb): (Vector2<f64>, Vector2<f64>),
        p: Vector2<f64>,
        l: f64,
    ) {
        a.v -= self.ma * p;
        a.w -= self.ia * (cross(ra, p) + l);
        b.v += self.mb * p;
        b.w += self.ib * (cross(rb, p) + l);
    }

    /// One soft point row (two axes) whose accumulated impulse is bounded
    /// in length by `max` (N·s): the target joint's and the motor joint's
    /// linear row. `error` is the anchors' separation the row drives to zero
    /// (m), `impulse` the accumulated impulse, updated and applied.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn solve_bounded_point(
        &self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        arms: (Vector2<f64>, Vector2<f64>),
        softness: &Softness,
        error: Vector2<f64>,
        impulse: &mut Vector2<f64>,
        max: f64,
    ) {
        let cdot = self.anchor_velocity(a, b, arms);
        let row = RowScale::soft(softness);
        let bias = row.bias_rate * error;
        let (k11, k12, k22) = self.point_mass_matrix(arms);
        let x = solve_2x2(k11, k12, k22, row.mass_scale * cdot + bias);
        let old = *impulse;
        let mut total = old - x - row.impulse_scale * old;
        let size = total.norm();
        if size > max {
            total *= max / size;
        }
        *impulse = total;
        self.apply(a, b, arms, total - old, 0.0);
    }

    /// Applies the angular impulse `l` alone (N·m·s; −l on A, +l on B).
    #[inline(always)]
    pub fn apply_angular(&self, a: &mut SolverBody, b: &mut SolverBody, l: f64) {
        a.w -= self.ia * l;
        b.w += self.ib * l;
    }

    /// Applies the linear impulse `p` (N·s; −p on A, +p on B) with the
    /// angular impulses `la` taken from A and `lb` given to B (N·m·s: the
    /// moments of `p` about each centre plus any pure angular impulse),
    /// for rows whose arms are not the anchors (the prismatic's).
    #[inline(always)]
    pub fn apply_arms(
        &self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        p: Vector2<f64>,
        (la, lb): (f64, f64),
    ) {
        a.v -= self.ma * p;
        a.w -= self.ia * la;
        b.v += self.mb * p;
        b.w += self.ib * lb;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_2x2_solve_inverts_the_matrix() {
        let (k11, k12, k22) = (3.0, 1.0, 2.0);
        let b = Vector2::new(1.0, -2.0);
        let x = solve_2x2(k11, k12, k22, b);
        let back = Vector2::new(k11 * x.x + k12 * x.y, k12 * x.x + k22 * x.y);
        assert!((back - b).norm() < 1e-15, "{back}");
        assert_eq!(solve_2x2(1.0, 1.0, 1.0, b), Vector2::zeros());
    }

    #[test]
    fn a_rigid_limit_stops_the_approach_at_the_limit() {
        // A row of unit mass 0.1 (rad) short of its limit, approaching at
        // 30 rad/s with h = 1/240 s: it may close the gap, 24 rad/s, and no
        // more.
        let (inv_h, s) = (240.0, Softness::RIGID);
        let mut impulse = 0.0;
        let cdot = -30.0;
        let d = limit_row(&mut impulse, (1.0, cdot, 0.1), &s, true, inv_h);
        assert!((cdot + d + 24.0).abs() < 1e-12, "{}", cdot + d);
        // Moving away: no impulse.
        let mut impulse = 0.0;
        assert_eq!(
            limit_row(&mut impulse, (1.0, 5.0, 0.1), &s, true, inv_h),
            0.0
        );
    }
}
