//! Joints of the soft step: bodies held together (or to the world) by
//! constraints solved in the same substeps as the contacts, after Box2D
//! v3.2's joint solvers (`joint.c`, `revolute_joint.c`, ...), written anew
//! for f64.
//!
//! Seven types, one file each, with its constraint rows written out:
//!
//! | type | holds | options |
//! |---|---|---|
//! | [`Revolute`] | a shared point (2 rows) | angle limits, motor, rotational spring |
//! | [`Prismatic`] | a line and the relative angle (2 rows) | translation limits, motor, linear spring |
//! | [`Distance`] | the distance of two points (1 row) | rigid, rope (limits only), spring with limits |
//! | [`Weld`] | the relative pose (3 rows) | linear and angular springs instead of rigid rows |
//! | [`Target`] | a body point pulled to a target (2 rows) | a spring with a bounded force |
//! | [`Wheel`] | a point on a line (1 row), free rotation | suspension spring, translation limits, motor |
//! | [`MotorJoint`] | B's pose relative to A, driven (3 rows) | bounded linear and angular springs |
//!
//! Build a [`JointDef`] and give it to [`crate::World::add_joint`], which
//! validates it (the bodies exist and differ, at least one is dynamic,
//! every number in its domain, limits in order, a non-zero axis, ...) and
//! returns a [`JointId`] or an [`crate::EngineError::InvalidJoint`] naming
//! the joint. Read a joint back with [`crate::World::joint`] (a
//! [`JointState`]: its anchors now, the constraint error, the angle or
//! translation, the reaction force and torque); steer it with
//! [`crate::World::set_joint_target`] and
//! [`crate::World::set_motor_speed`]. The exact contact model solves the
//! revolute, prismatic, rigid distance and rigid weld joints as constraints
//! of its equations of motion (module `exact::joints`) and refuses the rest
//! by name ([`crate::EngineError::Unsupported`]).
//!
//! A bead on a massless rod of 1 m, released horizontal:
//!
//! ```
//! use etalon2d::prelude::*;
//! let mut world = World::with_model(
//!     Method::SemiImplicitEuler,
//!     ContactModel::SoftStep(SoftStepSettings::default()),
//! )?;
//! world.set_gravity(Vector2::new(0.0, -9.81))?;
//! let bead = world.add_body(BodyDef::particle("bead", 1.0, Vector2::new(1.0, 0.0)))?;
//! let rod = world.add_joint(JointDef::distance(
//!     "rod",
//!     (None, Vector2::zeros()),                  // the world, at the origin
//!     (Some(bead), Vector2::new(1.0, 0.0)),      // the bead's centre
//!     Distance::default(),                       // rigid, at the anchors' distance
//! ))?;
//! world.run(0.59, 1.0 / 60.0)?; // a quarter swing from 90° (period 2.37 s)
//! let rod_now = world.joint(rod)?;
//! assert!(rod_now.linear_error < 1e-3); // the rod keeps its 1 m (to its soft sink)
//! assert!(world.states()[bead].position.x.abs() < 0.05); // at the bottom
//! # Ok::<(), EngineError>(())
//! ```
//!
//! # Anchors and frames
//!
//! An anchor is given in world coordinates ([`Anchor::World`], taken at the
//! bodies' poses when the joint is added) or in the body's frame
//! ([`Anchor::Local`], from its centre of mass, which is the body's
//! position). The side of a joint with no body (`None`) is the world: its
//! anchor is a fixed world point. The joint's angle is θB − θA − θref,
//! with the reference angle θref the bodies' relative angle when the joint
//! is added unless given ([`JointDef::reference_angle`]), measured in
//! [−π, π).
//!
//! # One step with joints
//!
//! In the soft step's stage order ([`super`]), per step of length dt with
//! n substeps h = dt/n:
//!
//! 1. **prepare** (once per step): each joint of an awake body gets its
//!    anchors r_A, r_B in the world frame from each centre of mass, the
//!    distance of the centres c_B − c_A, its angle, its effective masses and
//!    the softness of its rows for the substep h; impulses are kept from
//!    the last step (warm starting; zeroed when warm starting is off);
//! 2. n times: integrate velocities; **warm start** the joints then the
//!    contacts (apply the accumulated impulses); **solve** the joints then
//!    the contacts, with the soft bias (`use_bias`); integrate positions;
//!    **relax** the joints then the contacts, without bias;
//! 3. restitution (contacts only); the impulses stay in the joints.
//!
//! Inside the substeps the anchors follow the bodies' motion since the step
//! began, as the contact points do: r = R(Δθ) r₀ and the separation of the
//! anchors is (c_B − c_A) + (Δp_B − Δp_A) + r_B − r_A, so no joint is
//! re-prepared between substeps.
//!
//! # Rows and softness
//!
//! Every row is a velocity constraint J v + b = 0 with an effective mass
//! m = 1/(J M⁻¹ Jᵀ) (a 2 × 2 matrix K = J M⁻¹ Jᵀ for the point rows), and
//! is solved by sequential impulses: Δλ = −m (J v + b), λ += Δλ, v += M⁻¹
//! Jᵀ Δλ. The *rigid* rows (a revolute's point, a weld, a limit, a rigid
//! distance) are soft in the solve pass, like a contact
//! ([`super::Softness`]: bias rate, mass scale, impulse scale from a
//! frequency f and damping ratio ζ, [`JointDef::constraint_hertz`], default
//! Box2D's 60 Hz and ζ = 2, capped at a quarter of the substep rate
//! 1/(4h)):
//!
//! Δλ = −mass scale · m (J v + bias rate · C) − impulse scale · λ,
//!
//! and rigid without bias in the relax pass (Δλ = −m J v), which removes
//! the velocity the bias added. A limit whose error C is positive (not yet
//! reached) is speculative: bias C/h, rigid, λ ≥ 0 — it lets the gap close
//! within the substep and no further. *Springs* (a revolute's or
//! prismatic's, a distance spring, a weld's springs, the target) are real
//! springs: the same formula with their own frequency, in both passes. A
//! *motor* drives J v to its speed with |λ| ≤ h × its largest torque or
//! force. A spring's equilibrium sink under a load F on effective mass m
//! is F/(m ω²), ω = 2πf (for the rigid rows at 60 Hz and g = 9.81 m/s²,
//! 69 µm).
//!
//! # Speed
//!
//! Joints are solved one at a time (scalar Gauss–Seidel), before the
//! contacts in each pass, each an enum over its type (no dynamic
//! dispatch), its parameters and impulses in one record read in memory
//! order; what a substep does not change (anchors at the step's start,
//! masses, softness, the prismatic's axis) is computed once per step.
//! Nothing is allocated per step. The colouring of the contacts
//! (module `colouring`) could take the joints too, as Box2D does, and
//! solve four at a time in lanes: not done yet.
//!
//! # Not done
//!
//! Box2D's filter joint; the velocity part of Box2D v3.2's motor joint;
//! joint breaking (force
//! thresholds); the spring force bounds of Box2D's distance joint; angular
//! damping on the target joint (a body pulled by one point swings about it
//! freely); limits, motors and springs under the exact contact model.

mod distance;
mod frame;
mod motor_joint;
mod prismatic;
mod revolute;
mod set;
mod target;
mod weld;
mod wheel;
pub(crate) mod wide_revolute;

pub use distance::Distance;
pub use motor_joint::MotorJoint;
pub use prismatic::{Prismatic, PrismaticMotor};
pub use revolute::{MAX_LIMIT_ANGLE, Revolute, RevoluteMotor};
pub use target::Target;
pub use weld::Weld;
pub use wheel::{Wheel, WheelMotor};

pub(crate) use set::{JointRows, JointSet};

use crate::body::{BodyId, BodyState};
use crate::error::{EngineError, Result};
use nalgebra::Vector2;

/// Index of a joint in its [`crate::World`], in the order added. Ids never
/// shift: a removed joint keeps its id.
pub type JointId = usize;

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub use crate::tunables::DEFAULT_CONSTRAINT_DAMPING_RATIO;
/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub use crate::tunables::DEFAULT_CONSTRAINT_HERTZ;

/// Where a joint attaches to one of its bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Anchor {
    /// A point in world coordinates (m), taken at the bodies' poses when
    /// the joint is added.
    World(Vector2<f64>),
    /// A point in the body's frame, from its centre of mass (m). On the
    /// world side of a joint, a world point.
    Local(Vector2<f64>),
}

/// A joint spring's stiffness and damping, independent of the masses it
/// moves (Box2D's convention): it oscillates at `hertz` whatever it
/// carries.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointSpring {
    /// Natural frequency f (Hz), > 0.
    pub hertz: f64,
    /// Damping ratio ζ (dimensionless), ≥ 0: 1 is critical.
    pub damping_ratio: f64,
}

impl JointSpring {
    /// A spring of `hertz` (Hz) and `damping_ratio`.
    pub fn new(hertz: f64, damping_ratio: f64) -> Self {
        Self {
            hertz,
            damping_ratio,
        }
    }

    pub(crate) fn check(&self, joint: &str, what: &str) -> Result<()> {
        positive(joint, &format!("{what} frequency (Hz)"), self.hertz)?;
        non_negative(joint, &format!("{what} damping ratio"), self.damping_ratio)
    }
}

/// The type of a joint and its own parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum JointKind {
    /// A shared point.
    Revolute(Revolute),
    /// A shared line.
    Prismatic(Prismatic),
    /// A distance between two points.
    Distance(Distance),
    /// A shared pose.
    Weld(Weld),
    /// A body point pulled toward a target.
    Target(Target),
    /// A point on a line, free rotation, a suspension spring.
    Wheel(Wheel),
    /// B's pose relative to A driven by bounded springs.
    Motor(MotorJoint),
}

/// The type of a joint, without its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum JointType {
    /// [`Revolute`].
    Revolute,
    /// [`Prismatic`].
    Prismatic,
    /// [`Distance`].
    Distance,
    /// [`Weld`].
    Weld,
    /// [`Target`].
    Target,
    /// [`Wheel`].
    Wheel,
    /// [`MotorJoint`].
    Motor,
}

impl JointType {
    /// Its name in scene files and messages: `"revolute"`, ...
    pub fn id(self) -> &'static str {
        match self {
            JointType::Revolute => "revolute",
            JointType::Prismatic => "prismatic",
            JointType::Distance => "distance",
            JointType::Weld => "weld",
            JointType::Target => "target",
            JointType::Wheel => "wheel",
            JointType::Motor => "motor_joint",
        }
    }
}

impl JointKind {
    /// The type.
    pub fn joint_type(&self) -> JointType {
        match self {
            JointKind::Revolute(_) => JointType::Revolute,
            JointKind::Prismatic(_) => JointType::Prismatic,
            JointKind::Distance(_) => JointType::Distance,
            JointKind::Weld(_) => JointType::Weld,
            JointKind::Target(_) => JointType::Target,
            JointKind::Wheel(_) => JointType::Wheel,
            JointKind::Motor(_) => JointType::Motor,
        }
    }
}

/// The description of a joint, with Box2D's defaults: build one (the
/// constructors below), then [`crate::World::add_joint`] validates it.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointDef {
    /// Name used in errors and reports.
    pub name: String,
    /// The first body, `None` for the world.
    pub body_a: Option<BodyId>,
    /// The second body, `None` for the world. At least one of the two is a
    /// dynamic body; they differ.
    pub body_b: Option<BodyId>,
    /// Where the joint attaches to A (the target point of a
    /// [`Target`] joint).
    pub anchor_a: Anchor,
    /// Where the joint attaches to B.
    pub anchor_b: Anchor,
    /// θref (rad): the relative angle θB − θA at which the joint's angle
    /// is 0 (a revolute's limits and spring refer to it; a prismatic and a
    /// weld hold it). Default `None`: the bodies' relative angle when the
    /// joint is added. Only for revolute, prismatic and weld joints.
    pub reference_angle: Option<f64>,
    /// Whether the two bodies still collide with each other. Default
    /// false (Box2D's): the joint takes their place.
    pub collide_connected: bool,
    /// Stiffness of the joint's rigid rows in the solve pass (Hz, > 0),
    /// capped at a quarter of the substep rate. Default 60 Hz (Box2D's).
    pub constraint_hertz: f64,
    /// Damping ratio of the rigid rows (≥ 0). Default 2 (Box2D's).
    pub constraint_damping_ratio: f64,
    /// Force (N, > 0) at or above which the joint is reported in
    /// [`crate::soft_step::StepEvents::joints_exceeded`] after a step
    /// (Box2D v3's `forceThreshold`): a breakable joint is one the program
    /// removes on that event. Default `None`: never reported.
    pub force_threshold: Option<f64>,
    /// Torque (N·m, > 0) at or above which the joint is reported, in the
    /// same way (Box2D v3's `torqueThreshold`). Default `None`.
    pub torque_threshold: Option<f64>,
    /// The type and its parameters.
    pub kind: JointKind,
}

impl JointDef {
    fn base(
        name: &str,
        (body_a, anchor_a): (Option<BodyId>, Anchor),
        (body_b, anchor_b): (Option<BodyId>, Anchor),
        kind: JointKind,
    ) -> Self {
        Self {
            name: name.into(),
            body_a,
            body_b,
            anchor_a,
            anchor_b,
            reference_angle: None,
            collide_connected: false,
            constraint_hertz: DEFAULT_CONSTRAINT_HERTZ,
            constraint_damping_ratio: DEFAULT_CONSTRAINT_DAMPING_RATIO,
            force_threshold: None,
            torque_threshold: None,
            kind,
        }
    }

    /// A revolute joint of `a` and `b` (`None`: the world) at the world
    /// point `anchor` (m).
    pub fn revolute(
        name: &str,
        a: Option<BodyId>,
        b: Option<BodyId>,
        anchor: Vector2<f64>,
        joint: Revolute,
    ) -> Self {
        let at = Anchor::World(anchor);
        Self::base(name, (a, at), (b, at), JointKind::Revolute(joint))
    }

    /// A prismatic joint of `a` and `b` through the world point `anchor`
    /// (m), along `joint.axis`.
    pub fn prismatic(
        name: &str,
        a: Option<BodyId>,
        b: Option<BodyId>,
        anchor: Vector2<f64>,
        joint: Prismatic,
    ) -> Self {
        let at = Anchor::World(anchor);
        Self::base(name, (a, at), (b, at), JointKind::Prismatic(joint))
    }

    /// A distance joint between the world points `anchor_a` on `a` and
    /// `anchor_b` on `b` (m).
    pub fn distance(
        name: &str,
        (a, anchor_a): (Option<BodyId>, Vector2<f64>),
        (b, anchor_b): (Option<BodyId>, Vector2<f64>),
        joint: Distance,
    ) -> Self {
        Self::base(
            name,
            (a, Anchor::World(anchor_a)),
            (b, Anchor::World(anchor_b)),
            JointKind::Distance(joint),
        )
    }

    /// A weld of `a` and `b` at the world point `anchor` (m).
    pub fn weld(
        name: &str,
        a: Option<BodyId>,
        b: Option<BodyId>,
        anchor: Vector2<f64>,
        joint: Weld,
    ) -> Self {
        let at = Anchor::World(anchor);
        Self::base(name, (a, at), (b, at), JointKind::Weld(joint))
    }

    /// A target joint pulling the point of `body` now at the world point
    /// `point` (m) toward the world point `target` (m).
    pub fn target(
        name: &str,
        body: BodyId,
        point: Vector2<f64>,
        target: Vector2<f64>,
        joint: Target,
    ) -> Self {
        Self::base(
            name,
            (None, Anchor::World(target)),
            (Some(body), Anchor::World(point)),
            JointKind::Target(joint),
        )
    }

    /// A wheel joint of `a` (the chassis) and `b` (the wheel) at the world
    /// point `anchor` (m, the axle), its suspension along `joint.axis`.
    pub fn wheel(
        name: &str,
        a: Option<BodyId>,
        b: Option<BodyId>,
        anchor: Vector2<f64>,
        joint: Wheel,
    ) -> Self {
        let at = Anchor::World(anchor);
        Self::base(name, (a, at), (b, at), JointKind::Wheel(joint))
    }

    /// A motor joint driving `b`'s centre to `joint.linear_offset` from
    /// `a`'s centre (in A's frame; `None`: the world, its origin) and its
    /// angle to `joint.angular_offset` from A's. The anchors are the
    /// bodies' centres (`Anchor::Local` zero).
    pub fn motor(name: &str, a: Option<BodyId>, b: Option<BodyId>, joint: MotorJoint) -> Self {
        let at = Anchor::Local(Vector2::zeros());
        Self::base(name, (a, at), (b, at), JointKind::Motor(joint))
    }

    /// The anchors given in the bodies' frames instead (m, from each
    /// centre of mass; a world point on the world side).
    pub fn with_local_anchors(mut self, a: Vector2<f64>, b: Vector2<f64>) -> Self {
        self.anchor_a = Anchor::Local(a);
        self.anchor_b = Anchor::Local(b);
        self
    }

    /// Sets [`JointDef::collide_connected`].
    pub fn with_collide_connected(mut self, collide: bool) -> Self {
        self.collide_connected = collide;
        self
    }

    /// Sets [`JointDef::reference_angle`] (rad).
    pub fn with_reference_angle(mut self, angle: f64) -> Self {
        self.reference_angle = Some(angle);
        self
    }

    /// Sets the stiffness (Hz) and damping ratio of the rigid rows.
    pub fn with_constraint_softness(mut self, hertz: f64, damping_ratio: f64) -> Self {
        self.constraint_hertz = hertz;
        self.constraint_damping_ratio = damping_ratio;
        self
    }

    /// Sets [`JointDef::force_threshold`] (N) and
    /// [`JointDef::torque_threshold`] (N·m); `None` for never.
    pub fn with_thresholds(mut self, force: Option<f64>, torque: Option<f64>) -> Self {
        self.force_threshold = force;
        self.torque_threshold = torque;
        self
    }

    /// The type.
    pub fn joint_type(&self) -> JointType {
        self.kind.joint_type()
    }

    /// The anchors in the bodies' frames, resolving world anchors at the
    /// bodies' states `states` (indexed by body id; the world side keeps a
    /// world point). The anchors are not validated.
    pub fn local_anchors(&self, states: &[BodyState]) -> (Vector2<f64>, Vector2<f64>) {
        (
            local_point(self.body_a, self.anchor_a, states),
            local_point(self.body_b, self.anchor_b, states),
        )
    }

    /// Checks the numbers of the definition that need no world.
    pub(crate) fn check_numbers(&self) -> Result<()> {
        let name = self.name.as_str();
        for (what, anchor) in [
            ("anchor of A", self.anchor_a),
            ("anchor of B", self.anchor_b),
        ] {
            let (Anchor::World(p) | Anchor::Local(p)) = anchor;
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(invalid(
                    name,
                    format!("{what} [{}, {}] m is not finite", show(p.x), show(p.y)),
                ));
            }
        }
        positive(name, "constraint frequency (Hz)", self.constraint_hertz)?;
        non_negative(
            name,
            "constraint damping ratio",
            self.constraint_damping_ratio,
        )?;
        if let Some(force) = self.force_threshold {
            positive(name, "force threshold (N)", force)?;
        }
        if let Some(torque) = self.torque_threshold {
            positive(name, "torque threshold (N·m)", torque)?;
        }
        if let Some(angle) = self.reference_angle {
            if !matches!(
                self.kind,
                JointKind::Revolute(_) | JointKind::Prismatic(_) | JointKind::Weld(_)
            ) {
                return Err(invalid(
                    name,
                    format!(
                        "a {} joint has no reference angle (it does not hold an angle)",
                        self.joint_type().id()
                    ),
                ));
            }
            finite(name, "reference angle (rad)", angle)?;
        }
        match &self.kind {
            JointKind::Revolute(j) => j.check(name),
            JointKind::Prismatic(j) => j.check(name),
            JointKind::Distance(j) => j.check(name),
            JointKind::Weld(j) => j.check(name),
            JointKind::Target(j) => j.check(name),
            JointKind::Wheel(j) => j.check(name),
            JointKind::Motor(j) => j.check(name),
        }
    }
}

/// Where a joint is now and what it does, read by [`crate::World::joint`].
#[derive(Debug, Clone, PartialEq)]
pub struct JointState {
    /// Its name.
    pub name: String,
    /// Its type.
    pub joint_type: JointType,
    /// Body A, `None` for the world.
    pub body_a: Option<BodyId>,
    /// Body B, `None` for the world.
    pub body_b: Option<BodyId>,
    /// The anchor on A in A's frame, from its centre of mass (m); on the
    /// world side (and the target of a target joint), a world point.
    pub local_anchor_a: Vector2<f64>,
    /// The anchor on B in B's frame (m).
    pub local_anchor_b: Vector2<f64>,
    /// The anchor on A in the world now (m).
    pub anchor_a: Vector2<f64>,
    /// The anchor on B in the world now (m).
    pub anchor_b: Vector2<f64>,
    /// The joint angle θB − θA − θref now, in [−π, π) (rad).
    pub angle: f64,
    /// A prismatic's or wheel's translation along its axis, or a distance
    /// joint's length |anchor_b − anchor_a| (m); 0 for the others.
    pub translation: f64,
    /// How far the position rows are from holding (m): the anchors'
    /// separation of a revolute or weld, a prismatic's offset across its
    /// axis, a distance joint's length error (a rope's or spring's excess
    /// beyond its limits), a target joint's distance to its target, a
    /// wheel's offset across its axis (or beyond its limits), a motor
    /// joint's distance of B's centre from its target.
    pub linear_error: f64,
    /// How far the angular rows are from holding (rad): a prismatic's or
    /// weld's |angle|, a revolute's angle beyond its limits, a motor
    /// joint's |angle error| (its angle is measured from its angular
    /// offset); else 0.
    pub angular_error: f64,
    /// Force of the joint on B at its anchor in the last substep (N), world
    /// frame (the force on A is its opposite): accumulated impulse / h.
    pub force: Vector2<f64>,
    /// Torque of the joint's angular rows on B in the last substep (N·m).
    pub torque: f64,
    /// The motor's torque (N·m, revolute or wheel) or force (N, prismatic)
    /// in the last substep; 0 without a motor.
    pub motor: f64,
    /// Whether the joint was removed (then it does nothing).
    pub removed: bool,
}

/// A body point given by `anchor` in the frame of `body` (`None`: a world
/// point), at the states `states`.
fn local_point(body: Option<BodyId>, anchor: Anchor, states: &[BodyState]) -> Vector2<f64> {
    match (body, anchor) {
        (_, Anchor::Local(p)) | (None, Anchor::World(p)) => p,
        (Some(id), Anchor::World(p)) => {
            let s = &states[id];
            let (sin, cos) = s.angle.sin_cos();
            let d = p - s.position;
            Vector2::new(cos * d.x + sin * d.y, -sin * d.x + cos * d.y)
        }
    }
}

/// The world position of the body point `local` of `body` (`None`: the
/// world point `local`) at the states `states` (m).
pub fn world_point(
    body: Option<BodyId>,
    local: Vector2<f64>,
    states: &[BodyState],
) -> Vector2<f64> {
    match body {
        None => local,
        Some(id) => states[id].position + states[id].to_world_offset(local),
    }
}

/// `a` wrapped into [−π, π) (rad).
pub(crate) fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::PI;
    if (-PI..PI).contains(&a) {
        a
    } else {
        (a + PI).rem_euclid(2.0 * PI) - PI
    }
}

fn show(v: f64) -> String {
    crate::error::readable(v)
}

/// The error of joint `joint`.
pub(crate) fn invalid(joint: &str, reason: String) -> EngineError {
    EngineError::InvalidJoint {
        joint: joint.into(),
        reason,
    }
}

pub(crate) fn finite(joint: &str, what: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(
            joint,
            format!("{what} must be finite, got {}", show(v)),
        ))
    }
}

pub(crate) fn positive(joint: &str, what: &str, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(
            joint,
            format!("{what} must be finite and > 0, got {}", show(v)),
        ))
    }
}

pub(crate) fn non_negative(joint: &str, what: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(invalid(
            joint,
            format!("{what} must be finite and >= 0, got {}", show(v)),
        ))
    }
}

/// Checks that `axis` of joint `joint` has a direction: finite, non-zero,
/// and finite once normalised (the prismatic's and the wheel's axis).
pub(crate) fn direction(joint: &str, axis: Vector2<f64>) -> Result<()> {
    let n = axis.norm();
    if !(n.is_finite() && n > 0.0 && (axis / n).iter().all(|c| c.is_finite())) {
        return Err(invalid(
            joint,
            format!(
                "the axis [{}, {}] has no direction: give a finite, non-zero vector",
                crate::error::readable(axis.x),
                crate::error::readable(axis.y)
            ),
        ));
    }
    Ok(())
}

/// Checks `[lower, upper]` limits: finite and in order.
pub(crate) fn ordered(joint: &str, what: &str, unit: &str, (lo, hi): (f64, f64)) -> Result<()> {
    finite(joint, &format!("lower {what} ({unit})"), lo)?;
    finite(joint, &format!("upper {what} ({unit})"), hi)?;
    if lo > hi {
        return Err(invalid(
            joint,
            format!(
                "the lower {what} {} {unit} is above the upper {what} {} {unit}: give [lower, upper]",
                show(lo),
                show(hi)
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_wrap_into_minus_pi_to_pi() {
        use std::f64::consts::PI;
        assert_eq!(wrap_angle(0.5), 0.5);
        assert!((wrap_angle(PI + 0.25) - (-PI + 0.25)).abs() < 1e-15);
        assert!((wrap_angle(-PI - 0.25) - (PI - 0.25)).abs() < 1e-15);
        assert!((wrap_angle(7.0 * PI) + PI).abs() < 1e-14);
    }

    #[test]
    fn world_anchors_become_body_points() {
        let state = BodyState {
            position: Vector2::new(1.0, 2.0),
            angle: std::f64::consts::FRAC_PI_2,
            ..BodyState::default()
        };
        let p = local_point(Some(0), Anchor::World(Vector2::new(1.0, 3.0)), &[state]);
        // One metre above the centre of a body turned by 90°: its local x.
        assert!((p - Vector2::new(1.0, 0.0)).norm() < 1e-15, "{p}");
        let back = world_point(Some(0), p, &[state]);
        assert!((back - Vector2::new(1.0, 3.0)).norm() < 1e-15);
        assert_eq!(local_point(None, Anchor::World(p), &[state]), p);
    }
}
