//! Joints under the exact model: holonomic constraints C(q) = 0 solved
//! with the bodies' equations of motion, so that every integrator keeps
//! its order on a jointed system (`docs/joints.md#joints-under-the-exact-model`).
//!
//! The joints themselves (definitions, validation, anchors in the bodies'
//! frames, reference angles, removal) are the soft step's
//! ([`crate::soft_step::joints`], one [`JointSet`]); this module turns the
//! ones it supports into constraint rows:
//!
//! | joint | rows | C |
//! |---|---|---|
//! | revolute | point (2) | p_B − p_A |
//! | distance, rigid | length (1) | (\|d\|² − L²)/(2L), d = p_B − p_A |
//! | prismatic | line (1), angle (1) | n·d with n A's axis normal; θ_B − θ_A − θref |
//! | weld | point (2), angle (1) | p_B − p_A; θ_B − θ_A − θref |
//! | wheel | line (1) | n·d with n A's axis normal (rotation free) |
//! | motor | none | (its bounded springs are applied forces) |
//! | revolute, driven | point (2), drive (1) | p_B − p_A; θ_B − θ_A − θref − φ(t) |
//!
//! with p = c + R(θ) r the anchor of a body (r in its frame). Every row
//! has a Jacobian J (its partial derivatives in the bodies' x, y, θ) and a
//! velocity term γ with C̈ = J a + γ.
//!
//! # The formulation (index 1)
//!
//! In every evaluation of the right-hand side, with a₀ = M⁻¹ f the
//! accelerations of the applied forces, the constraint forces Jᵀ λ are
//! those for which the accelerations keep every row's second derivative
//! zero:
//!
//! (J M⁻¹ Jᵀ) λ = −(J a₀ + γ),   a = a₀ + M⁻¹ Jᵀ λ.
//!
//! The system is then an ODE in (q, v) whose solutions that start on the
//! manifolds C = 0, J v = 0 stay on them, and any method integrates it at
//! its own order. The matrix K = J M⁻¹ Jᵀ is symmetric positive
//! semi-definite; it is factored by Cholesky with a pivot below 1e-12 of
//! its diagonal taken as a redundant row (its λ is 0: a consistent
//! redundant row asks nothing the others do not).
//!
//! # Drift control (projection)
//!
//! The numerical solution leaves the manifolds by the method's local
//! error per step. After each accepted step the state is projected back,
//! as in Hairer, Lubich & Wanner (*Geometric Numerical Integration*,
//! §IV.4): the positions by Newton iterations of the mass-weighted
//! closest point, Δq = −M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ C, until |C| stops shrinking
//! (at most [`MAX_PROJECTIONS`] iterations; from a drift of the local
//! error it takes one or two), then the velocities onto J v = 0 at the
//! projected positions, exactly (one linear solve). A projection of an
//! order-p step moves the state by the step's local error, O(h^{p+1}), so
//! the order is kept. The largest |C| removed is recorded
//! ([`ExactJoints::largest_drift`]).
//!
//! # Driven revolute joints (rheonomic)
//!
//! A revolute joint whose motor has an unbounded torque
//! (`max_torque = f64::INFINITY`) prescribes its angle: the drive row
//! C = θ_B − θ_A − θref − φ(t), φ(t) = φ₀ + s (t − t₀) (s the motor
//! speed, rad/s; φ₀ = 0 and t₀ the world time when the joint is added;
//! [`ExactJoints::set_motor_speed`] rebases φ₀, t₀ to the world's current
//! time, so φ stays continuous). Its J is −1 on θ_A and 1 on θ_B, its
//! γ = 0 (φ̈ = 0), and its time derivative ∂C/∂t = −s enters the velocity
//! projection (J v = s). The position projection reads C at the time of
//! the step's end.
//!
//! # Force laws
//!
//! A wheel's suspension spring and a motor joint's bounded springs are
//! applied forces, added to a₀ before the constraint forces are solved
//! ([`crate::exact::joint_forces`]).
//!
//! # Not supported
//!
//! Limits (one-sided rows, which need events), motors with a bounded
//! torque or force (velocity rows with a force bound), the other joints' springs, ropes, spring distance joints
//! and target joints: each is refused when added, by a typed
//! [`EngineError::Unsupported`] naming the joint and the option.

use super::ode::Layout;
use crate::body::{Body, BodyState};
use crate::error::{EngineError, Result};
use crate::exact::joint_forces::{self, AppliedJointForce};
use crate::soft_step::joints::{
    Distance, JointDef, JointId, JointKind, JointRows, JointSet, JointState, world_point,
    wrap_angle,
};
use crate::world_core::WorldCore;
use nalgebra::Vector2;

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub use crate::tunables::JOINT_MAX_PROJECTIONS as MAX_PROJECTIONS;

use crate::tunables::REDUNDANT_PIVOT;

/// Why the exact model refuses an option of a joint.
const EXACT_JOINTS_SUPPORT: &str = "the exact contact model solves revolute, prismatic, rigid \
     distance, rigid weld and wheel joints as holonomic constraints, a revolute motor of unbounded \
     torque (max_torque = inf) as a prescribed angle, a wheel's suspension spring and motor \
     joints as force laws, without limits, bounded motors (velocity rows with a bounded force) \
     or the other springs; use the soft_step contact model for the rest";

/// One constraint of the exact model, from one joint.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Constraint {
    /// p_B − p_A = 0 (two rows).
    Point,
    /// (|d|² − L²)/(2L) = 0 (one row).
    Length(f64),
    /// n·d = 0, n the normal of A's axis (the axis in A's frame) (one row).
    Line(Vector2<f64>),
    /// θ_B − θ_A − θref = 0 (one row).
    Angle,
    /// θ_B − θ_A − θref − φ(t) = 0 (one row), φ of [`Drive`].
    Drive(Drive),
}

/// The prescribed angle of a driven revolute joint: φ(t) = phase +
/// speed · (t − since) (rad, rad/s, s).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Drive {
    phase: f64,
    speed: f64,
    since: f64,
}

impl Drive {
    fn at(&self, t: f64) -> f64 {
        self.phase + self.speed * (t - self.since)
    }
}

/// A constraint of joint `joint` with its bodies and anchors.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Held {
    joint: JointId,
    a: Option<usize>,
    b: Option<usize>,
    local_a: Vector2<f64>,
    local_b: Vector2<f64>,
    reference_angle: f64,
    constraint: Constraint,
}

impl Held {
    fn rows(&self) -> usize {
        match self.constraint {
            Constraint::Point => 2,
            _ => 1,
        }
    }
}

/// One side of a row: its body's slot (offset of x, whether θ follows)
/// and the row's partial derivatives in (x, y, θ).
#[derive(Debug, Clone, Copy, Default)]
struct Partials {
    slot: Option<(usize, bool)>,
    d: [f64; 3],
}

/// One row at a state: its value C (m or rad), its partials on each side,
/// and its velocity term γ (C̈ = J a + γ).
#[derive(Debug, Clone, Copy, Default)]
struct RowAt {
    c: f64,
    a: Partials,
    b: Partials,
    gamma: f64,
    /// ∂C/∂t (m/s or rad/s): nonzero for a drive row only.
    rate: f64,
}

/// A body's pose and velocity as a row reads them (the world: at rest at
/// the origin).
#[derive(Debug, Clone, Copy)]
struct Pose {
    position: Vector2<f64>,
    angle: f64,
    velocity: Vector2<f64>,
    omega: f64,
    slot: Option<(usize, bool)>,
}

/// (−r_y, r_x): ∂(R(θ) r)/∂θ for a world-frame arm r.
fn perp(r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-r.y, r.x)
}

/// The joints of an exact-model world, and the scratch of their solves.
#[derive(Debug, Clone, Default)]
pub(crate) struct ExactJoints {
    /// The definitions, validated and resolved as the soft step does.
    pub set: JointSet,
    /// The constraints of the live joints, rebuilt when joints change.
    held: Vec<Held>,
    stale: bool,
    /// Rows in all.
    rows: usize,
    /// Scratch: the rows at the current state, J (rows × positions),
    /// M⁻¹ (positions), K and its factor (rows × rows), right-hand side
    /// and multipliers (rows).
    at: Vec<RowAt>,
    jac: Vec<f64>,
    inv_mass: Vec<f64>,
    k: Vec<f64>,
    rhs: Vec<f64>,
    lambda: Vec<f64>,
    /// Scratch: whether each row is independent of the ones before it.
    keep: Vec<bool>,
    /// Multipliers of the last right-hand side, per row: the constraint
    /// force (N) or torque (N·m) of each row.
    last_lambda: Vec<f64>,
    /// The largest |C| a projection removed (m or rad).
    largest_drift: f64,
    /// The force laws' forces of the last right-hand side.
    applied: Vec<AppliedJointForce>,
    /// Per joint id: its prescribed angle when it is a driven revolute.
    drives: Vec<Option<Drive>>,
    /// The world time (s) of the last projection (or of the last joint
    /// added): the time at which the drive rows' C is evaluated.
    now: f64,
}

impl ExactJoints {
    /// Whether the world holds a live joint.
    pub(crate) fn any(&self) -> bool {
        self.set.infos.iter().any(|i| !i.removed)
    }

    /// Validates `def` (as the soft step does), refuses what this model
    /// does not solve, and adds it.
    pub(crate) fn add(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId> {
        let refuse = |option: &str| {
            Err(EngineError::Unsupported {
                what: format!(
                    "joint '{}' ({}) {option} under the exact contact model",
                    def.name,
                    def.joint_type().id()
                ),
                reason: EXACT_JOINTS_SUPPORT,
            })
        };
        if def.force_threshold.is_some() || def.torque_threshold.is_some() {
            return refuse("with a force or torque threshold (joint events are the soft step's)");
        }
        match &def.kind {
            JointKind::Revolute(j) => {
                if j.limits.is_some() {
                    return refuse("with angle limits");
                }
                if j.motor.is_some_and(|m| m.max_torque != f64::INFINITY) {
                    return refuse(
                        "with a motor of bounded torque (only max_torque = inf, a prescribed \
                         speed, is solved)",
                    );
                }
                if j.spring.is_some() {
                    return refuse("with a spring");
                }
            }
            JointKind::Prismatic(j) => {
                if j.limits.is_some() {
                    return refuse("with translation limits");
                }
                if j.motor.is_some() {
                    return refuse("with a motor");
                }
                if j.spring.is_some() {
                    return refuse("with a spring");
                }
            }
            JointKind::Distance(Distance::Rigid { .. }) => {}
            JointKind::Distance(Distance::Rope { .. }) => return refuse("as a rope"),
            JointKind::Distance(Distance::Spring { .. }) => return refuse("as a spring"),
            JointKind::Weld(w) => {
                if w.linear_spring.is_some() || w.angular_spring.is_some() {
                    return refuse("with a spring");
                }
            }
            JointKind::Target(_) => return refuse("(a spring to a target)"),
            JointKind::Wheel(w) => {
                if w.limits.is_some() {
                    return refuse("with translation limits");
                }
                if w.motor.is_some() {
                    return refuse("with a motor");
                }
            }
            // Bounded springs: a force law (`joint_forces`).
            JointKind::Motor(_) => {}
        }
        self.set.know_bodies(core.bodies.len());
        let id = self.set.add(core, def)?;
        self.now = core.time;
        let drive = match &def.kind {
            JointKind::Revolute(j) => j.motor.map(|m| Drive {
                phase: 0.0,
                speed: m.speed,
                since: core.time,
            }),
            _ => None,
        };
        self.drives.resize(id, None);
        self.drives.push(drive);
        self.stale = true;
        Ok(id)
    }

    /// Sets the motor speed of joint `id` (as the soft step's set does);
    /// a driven revolute's prescribed angle φ is rebased at the world's
    /// current time, so that it stays continuous.
    pub(crate) fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        self.set.check(id)?;
        self.set.set_motor_speed(id, speed)?;
        if let Some(Some(d)) = self.drives.get_mut(id) {
            *d = Drive {
                phase: d.at(self.now),
                speed,
                since: self.now,
            };
            self.stale = true;
        }
        Ok(())
    }

    /// Removes joint `id` (it stays, inert).
    pub(crate) fn remove(&mut self, id: JointId) -> Result<()> {
        self.set.check(id)?;
        self.set.remove(id);
        self.stale = true;
        Ok(())
    }

    /// Removes the joints of body `body`.
    pub(crate) fn body_removed(&mut self, body: usize) {
        let ids: Vec<JointId> = (0..self.set.len())
            .filter(|&id| {
                let info = &self.set.infos[id];
                !info.removed && (info.body_a == Some(body) || info.body_b == Some(body))
            })
            .collect();
        for id in ids {
            self.set.remove(id);
        }
        self.stale = true;
    }

    /// The layout changed (bodies added or removed): rebuild the rows.
    pub(crate) fn invalidate(&mut self) {
        self.stale = true;
    }

    /// The largest constraint error a projection removed so far (m for
    /// point, length and line rows, rad for angle rows).
    pub(crate) fn largest_drift(&self) -> f64 {
        self.largest_drift
    }

    /// Joint `id` now, with the constraint force and torque of the last
    /// right-hand side evaluated.
    pub(crate) fn state(&self, id: JointId, states: &[BodyState]) -> Result<JointState> {
        self.set.check(id)?;
        let mut state = self.set.state(id, states);
        for f in self.applied.iter().filter(|f| f.joint == id) {
            state.force += f.force;
            state.torque += f.torque;
        }
        let mut row = 0;
        for h in &self.held {
            let n = h.rows();
            if h.joint == id && row + n <= self.last_lambda.len() {
                let l = &self.last_lambda[row..row + n];
                match h.constraint {
                    Constraint::Point => state.force += Vector2::new(l[0], l[1]),
                    Constraint::Length(length) => {
                        let pa = world_point(h.a, h.local_a, states);
                        let pb = world_point(h.b, h.local_b, states);
                        state.force += l[0] * (pb - pa) / length;
                    }
                    Constraint::Line(local_normal) => {
                        let angle = h.a.map_or(0.0, |a| states[a].angle);
                        let (s, c) = angle.sin_cos();
                        let n = Vector2::new(
                            c * local_normal.x - s * local_normal.y,
                            s * local_normal.x + c * local_normal.y,
                        );
                        state.force += l[0] * n;
                    }
                    Constraint::Angle | Constraint::Drive(_) => state.torque += l[0],
                }
            }
            row += n;
        }
        Ok(state)
    }

    fn rebuild(&mut self) {
        self.held.clear();
        for (id, info) in self.set.infos.iter().enumerate() {
            if info.removed {
                continue;
            }
            let base = Held {
                joint: id,
                a: info.body_a,
                b: info.body_b,
                local_a: info.local_a,
                local_b: info.local_b,
                reference_angle: info.reference_angle,
                constraint: Constraint::Point,
            };
            let with = |constraint| Held { constraint, ..base };
            match &self.set.sims[id].rows {
                JointRows::Revolute(_) => {
                    self.held.push(base);
                    if let Some(Some(d)) = self.drives.get(id) {
                        self.held.push(with(Constraint::Drive(*d)));
                    }
                }
                JointRows::Weld(_) => {
                    self.held.push(base);
                    self.held.push(with(Constraint::Angle));
                }
                JointRows::Distance(r) => {
                    self.held.push(with(Constraint::Length(r.length)));
                }
                JointRows::Prismatic(p) => {
                    let u = p.local_axis;
                    self.held.push(with(Constraint::Line(perp(u))));
                    self.held.push(with(Constraint::Angle));
                }
                JointRows::Wheel(w) => {
                    self.held.push(with(Constraint::Line(perp(w.local_axis))));
                }
                // A force law (`joint_forces`); targets are refused.
                JointRows::Motor(_) | JointRows::Target(_) => {}
            }
        }
        self.rows = self.held.iter().map(Held::rows).sum();
        self.last_lambda.clear();
        self.stale = false;
    }

    /// Evaluates every row at `states` into `self.at`, J into `self.jac`
    /// and M⁻¹ into `self.inv_mass`.
    fn evaluate(&mut self, bodies: &[Body], layout: &Layout, states: &[BodyState]) {
        if self.stale {
            self.rebuild();
        }
        let n = layout.positions;
        self.inv_mass.clear();
        self.inv_mass.resize(n, 0.0);
        for (slot, body) in layout.slots.iter().zip(bodies) {
            let Some(slot) = slot else { continue };
            let o = slot.offset;
            self.inv_mass[o] = 1.0 / body.mass;
            self.inv_mass[o + 1] = 1.0 / body.mass;
            if slot.rotates {
                self.inv_mass[o + 2] = body.inertia.map_or(0.0, |i| 1.0 / i);
            }
        }
        self.at.clear();
        let pose = |b: Option<usize>| match b {
            None => Pose {
                position: Vector2::zeros(),
                angle: 0.0,
                velocity: Vector2::zeros(),
                omega: 0.0,
                slot: None,
            },
            Some(id) => {
                let s = &states[id];
                Pose {
                    position: s.position,
                    angle: s.angle,
                    velocity: s.velocity,
                    omega: s.angular_velocity,
                    slot: layout.slots[id].map(|sl| (sl.offset, sl.rotates)),
                }
            }
        };
        for h in &self.held {
            let (a, b) = (pose(h.a), pose(h.b));
            let arm = |p: &Pose, body: Option<usize>, local: Vector2<f64>| {
                if body.is_none() {
                    return Vector2::zeros();
                }
                let (s, c) = p.angle.sin_cos();
                Vector2::new(c * local.x - s * local.y, s * local.x + c * local.y)
            };
            // Arms from each centre (the world side: its anchor is a point).
            let ra = arm(&a, h.a, h.local_a);
            let rb = arm(&b, h.b, h.local_b);
            let pa = if h.a.is_some() {
                a.position + ra
            } else {
                h.local_a
            };
            let pb = if h.b.is_some() {
                b.position + rb
            } else {
                h.local_b
            };
            let d = pb - pa;
            // ḋ and the velocity part of d̈ (−ω² r of each anchor).
            let d_dot = b.velocity + b.omega * perp(rb) - a.velocity - a.omega * perp(ra);
            let centripetal = -b.omega * b.omega * rb + a.omega * a.omega * ra;
            let side = |p: &Pose, d: [f64; 3]| Partials { slot: p.slot, d };
            match h.constraint {
                Constraint::Point => {
                    for k in 0..2 {
                        let e: Vector2<f64> = if k == 0 { Vector2::x() } else { Vector2::y() };
                        self.at.push(RowAt {
                            c: d[k],
                            a: side(&a, [-e.x, -e.y, -e.dot(&perp(ra))]),
                            b: side(&b, [e.x, e.y, e.dot(&perp(rb))]),
                            gamma: centripetal[k],
                            rate: 0.0,
                        });
                    }
                }
                Constraint::Length(length) => {
                    let g = d / length;
                    self.at.push(RowAt {
                        c: 0.5 * (d.norm_squared() - length * length) / length,
                        a: side(&a, [-g.x, -g.y, -g.dot(&perp(ra))]),
                        b: side(&b, [g.x, g.y, g.dot(&perp(rb))]),
                        gamma: (d.dot(&centripetal) + d_dot.norm_squared()) / length,
                        rate: 0.0,
                    });
                }
                Constraint::Line(local_normal) => {
                    let (s, c) = a.angle.sin_cos();
                    let nrm = if h.a.is_some() {
                        Vector2::new(
                            c * local_normal.x - s * local_normal.y,
                            s * local_normal.x + c * local_normal.y,
                        )
                    } else {
                        local_normal
                    };
                    let turn = perp(nrm);
                    self.at.push(RowAt {
                        c: nrm.dot(&d),
                        a: side(&a, [-nrm.x, -nrm.y, turn.dot(&d) - nrm.dot(&perp(ra))]),
                        b: side(&b, [nrm.x, nrm.y, nrm.dot(&perp(rb))]),
                        gamma: -a.omega * a.omega * nrm.dot(&d)
                            + 2.0 * a.omega * turn.dot(&d_dot)
                            + nrm.dot(&centripetal),
                        rate: 0.0,
                    });
                }
                Constraint::Angle => {
                    self.at.push(RowAt {
                        c: wrap_angle(b.angle - a.angle - h.reference_angle),
                        a: side(&a, [0.0, 0.0, -1.0]),
                        b: side(&b, [0.0, 0.0, 1.0]),
                        gamma: 0.0,
                        rate: 0.0,
                    });
                }
                Constraint::Drive(drive) => {
                    let phi = drive.at(self.now);
                    self.at.push(RowAt {
                        c: wrap_angle(b.angle - a.angle - h.reference_angle - phi),
                        a: side(&a, [0.0, 0.0, -1.0]),
                        b: side(&b, [0.0, 0.0, 1.0]),
                        gamma: 0.0,
                        rate: -drive.speed,
                    });
                }
            }
        }
        // The dense Jacobian (a particle's θ column does not exist).
        let m = self.at.len();
        self.jac.clear();
        self.jac.resize(m * n, 0.0);
        for (i, row) in self.at.iter().enumerate() {
            for p in [&row.a, &row.b] {
                let Some((o, rotates)) = p.slot else { continue };
                let r = &mut self.jac[i * n..(i + 1) * n];
                r[o] += p.d[0];
                r[o + 1] += p.d[1];
                if rotates {
                    r[o + 2] += p.d[2];
                }
            }
        }
    }

    /// Solves K λ = rhs (K = J M⁻¹ Jᵀ of the last [`Self::evaluate`])
    /// into `self.lambda`, a redundant row getting 0.
    fn solve(&mut self, n: usize) {
        let m = self.at.len();
        let (jac, w) = (&self.jac, &self.inv_mass);
        self.k.clear();
        self.k.resize(m * m, 0.0);
        for i in 0..m {
            for j in 0..=i {
                let (ri, rj) = (&jac[i * n..(i + 1) * n], &jac[j * n..(j + 1) * n]);
                let v: f64 = (0..n).map(|c| ri[c] * w[c] * rj[c]).sum();
                self.k[i * m + j] = v;
                self.k[j * m + i] = v;
            }
        }
        // Cholesky, in place in the lower triangle, dropping redundant rows.
        let k = &mut self.k;
        let keep = &mut self.keep;
        keep.clear();
        keep.resize(m, true);
        for j in 0..m {
            let diagonal = k[j * m + j];
            let mut pivot = diagonal;
            for c in 0..j {
                pivot -= k[j * m + c] * k[j * m + c];
            }
            // A NaN pivot is not independent either.
            let independent = pivot > REDUNDANT_PIVOT * diagonal.abs() && pivot > 0.0;
            if !independent {
                keep[j] = false;
                for r in j..m {
                    k[r * m + j] = 0.0;
                }
                continue;
            }
            let l = pivot.sqrt();
            k[j * m + j] = l;
            for r in j + 1..m {
                let mut v = k[r * m + j];
                for c in 0..j {
                    v -= k[r * m + c] * k[j * m + c];
                }
                k[r * m + j] = v / l;
            }
        }
        // L y = rhs, then Lᵀ λ = y.
        let lambda = &mut self.lambda;
        lambda.clear();
        lambda.extend_from_slice(&self.rhs);
        for i in 0..m {
            if !keep[i] {
                lambda[i] = 0.0;
                continue;
            }
            let mut v = lambda[i];
            for c in 0..i {
                v -= k[i * m + c] * lambda[c];
            }
            lambda[i] = v / k[i * m + i];
        }
        for i in (0..m).rev() {
            if !keep[i] {
                lambda[i] = 0.0;
                continue;
            }
            let mut v = lambda[i];
            for r in i + 1..m {
                v -= k[r * m + i] * lambda[r];
            }
            lambda[i] = v / k[i * m + i];
        }
    }

    /// Adds M⁻¹ Jᵀ λ (λ of the last solve) to `out` (positions long).
    fn apply(&self, n: usize, out: &mut [f64]) {
        for (i, l) in self.lambda.iter().enumerate() {
            if *l == 0.0 {
                continue;
            }
            let r = &self.jac[i * n..(i + 1) * n];
            for c in 0..n {
                out[c] += self.inv_mass[c] * r[c] * l;
            }
        }
    }

    /// The constrained accelerations: `accel` (the velocity block of the
    /// derivative, positions long) holds a₀ = M⁻¹ f on entry and
    /// a₀ + M⁻¹ Jᵀ λ on exit, with (J M⁻¹ Jᵀ) λ = −(J a₀ + γ).
    pub(crate) fn accelerate(
        &mut self,
        bodies: &[Body],
        layout: &Layout,
        states: &[BodyState],
        accel: &mut [f64],
    ) {
        self.constrain(bodies, layout, states, accel);
        self.last_lambda.clone_from(&self.lambda);
    }

    /// The force laws' accelerations added to `accel` (positions long,
    /// a₀ = M⁻¹ f on entry), then the constraint forces' (J M⁻¹ Jᵀ) λ =
    /// −(J a₀ + γ): [`Self::accelerate`] without recording λ. The resting
    /// contacts read it to see the accelerations the joints leave their
    /// points (`crate::contact::resting`).
    pub(crate) fn constrain(
        &mut self,
        bodies: &[Body],
        layout: &Layout,
        states: &[BodyState],
        accel: &mut [f64],
    ) {
        joint_forces::apply(
            &self.set,
            (bodies, layout, states),
            accel,
            &mut self.applied,
        );
        self.evaluate(bodies, layout, states);
        let n = layout.positions;
        self.rhs.clear();
        for (i, row) in self.at.iter().enumerate() {
            let r = &self.jac[i * n..(i + 1) * n];
            let ja: f64 = r.iter().zip(accel.iter()).map(|(j, a)| j * a).sum();
            self.rhs.push(-(ja + row.gamma));
        }
        self.solve(n);
        self.apply(n, accel);
    }

    /// The constrained mobility at `states`: each of the `columns.len() / n`
    /// columns w (n = the layout's positions, a generalised impulse in
    /// N·s and N·m·s) becomes the velocity change P w it gives the bodies
    /// while the joints hold, P = M⁻¹ − M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ J M⁻¹, so that
    /// J P w = 0 (a redundant row dropped as in the right-hand side).
    /// Used by the constrained impact ([`crate::contact::constrained`]).
    pub(crate) fn mobility(
        &mut self,
        bodies: &[Body],
        layout: &Layout,
        states: &[BodyState],
        columns: &mut [f64],
    ) {
        self.evaluate(bodies, layout, states);
        let n = layout.positions;
        if n == 0 {
            return;
        }
        for w in columns.chunks_mut(n) {
            for (x, m) in w.iter_mut().zip(&self.inv_mass) {
                *x *= m;
            }
            self.rhs.clear();
            for i in 0..self.at.len() {
                let r = &self.jac[i * n..(i + 1) * n];
                self.rhs
                    .push(-r.iter().zip(w.iter()).map(|(j, x)| j * x).sum::<f64>());
            }
            self.solve(n);
            self.apply(n, w);
        }
    }

    /// Projects the state `y` = [q, v] at time `t` (s) back onto
    /// C(q, t) = 0 and J v + ∂C/∂t = 0 (see the module docs); `states` is
    /// scratch (every body's state, static ones fixed). Returns whether
    /// `y` changed.
    pub(crate) fn project(
        &mut self,
        bodies: &[Body],
        layout: &Layout,
        states: &mut [BodyState],
        y: &mut [f64],
        t: f64,
    ) -> bool {
        self.now = t;
        if self.stale {
            self.rebuild();
        }
        if self.rows == 0 {
            return false;
        }
        let n = layout.positions;
        let mut changed = false;
        let mut previous = f64::INFINITY;
        for iteration in 0..=MAX_PROJECTIONS {
            layout.unpack(y, states);
            self.evaluate(bodies, layout, states);
            let worst = self.at.iter().map(|r| r.c.abs()).fold(0.0, f64::max);
            if iteration == 0 {
                self.largest_drift = self.largest_drift.max(worst);
            }
            // Converged to round-off: a Newton step no longer halves |C|.
            if worst == 0.0 || worst > 0.5 * previous || iteration == MAX_PROJECTIONS {
                break;
            }
            previous = worst;
            self.rhs.clear();
            self.rhs.extend(self.at.iter().map(|r| -r.c));
            self.solve(n);
            self.apply(n, &mut y[..n]);
            changed = true;
        }
        // Velocities at the projected positions (evaluated last above).
        self.rhs.clear();
        for i in 0..self.at.len() {
            let r = &self.jac[i * n..(i + 1) * n];
            let jv: f64 = r.iter().zip(&y[n..]).map(|(j, v)| j * v).sum();
            self.rhs.push(-(jv + self.at[i].rate));
        }
        if self.rhs.iter().any(|v| *v != 0.0) {
            self.solve(n);
            self.apply(n, &mut y[n..]);
            changed = true;
        }
        changed
    }
}
