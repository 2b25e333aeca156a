//! Joints of a [`ManyBodyScene`]: what connects two bodies (or a body and
//! the world), described once for every engine.
//!
//! # Conventions
//!
//! - **Bodies** by their index in [`ManyBodyScene::bodies`]; `None` is the
//!   world: a fixed frame at the origin with angle 0 (each adapter adds a
//!   static body without shapes for it). A static scene body may serve
//!   instead. At least one of the two bodies is dynamic.
//! - **Anchors in world coordinates at t = 0**: `anchor_a` is the point of
//!   body A, `anchor_b` the point of body B, both given where they are when
//!   the scene starts, each then carried by its body. They coincide for a
//!   joint built in place (the usual case); if they do not, the joint
//!   starts violated and the engine pulls them together (Box2D's Falling
//!   Hinges do that). Each adapter converts them to body coordinates with
//!   the body's initial pose: local = R(−θ0)(anchor − p0).
//! - **Angles** counter-clockwise, rad. A revolute joint's angle is
//!   θB − θA − `reference_angle` (principal value), θ the bodies' angles
//!   (the world's is 0): with `reference_angle` = θB0 − θA0 it starts at 0.
//!   Its limits and spring target are in that angle.
//! - **Prismatic and weld joints hold the relative angle the bodies have at
//!   t = 0** (θB − θA stays θB0 − θA0). A prismatic axis is a world
//!   direction at t = 0, fixed in body A afterwards; its translation is
//!   (pB − pA)·axis with pA, pB the two anchors' current positions, 0 at
//!   t = 0 for coincident anchors.
//! - **Softness** in Hz and damping ratio ζ (Box2D's and Catto's soft
//!   constraint: ω = 2π f, bias rate ω/(2ζ + hω), mass scale
//!   hω(2ζ + hω)/(1 + hω(2ζ + hω)) per substep h), independent of mass:
//!   a spring of `hertz` f acting on a constraint of effective mass m_eff
//!   has stiffness m_eff ω² and damping 2 ζ m_eff ω.
//! - `collide_connected` (default false): whether the two bodies' shapes
//!   still collide with each other.
//!
//! Units: SI (m, s, kg, N, N·m, rad, Hz).
//!
//! [`ManyBodyScene`]: super::ManyBodyScene
//! [`ManyBodyScene::bodies`]: super::ManyBodyScene::bodies

use super::{BodyKind, BodySample, ManyBodyError, SceneBody};
use std::f64::consts::PI;

/// A motor: drives the joint's coordinate at a target speed with a bounded
/// force (Box2D's joint motor: a rigid velocity constraint whose impulse
/// per substep is at most `max_force` × h). With speed 0 it acts as joint
/// friction (the ragdolls' joints).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motor {
    /// Target speed: rad/s for a revolute joint, m/s for a prismatic one.
    pub speed: f64,
    /// Largest torque (N·m, revolute) or force (N, prismatic), ≥ 0.
    pub max_force: f64,
}

/// A spring on the joint's coordinate, toward `target`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// Natural frequency f, Hz (> 0).
    pub hertz: f64,
    /// Damping ratio ζ (≥ 0; 1 is critical).
    pub damping_ratio: f64,
    /// Rest value of the coordinate: rad (revolute joint angle), m
    /// (prismatic translation, distance joint length).
    pub target: f64,
}

/// Softness of a constraint that would otherwise be rigid (a weld), as a
/// spring of natural frequency `hertz` and damping ratio `damping_ratio`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Softness {
    /// Natural frequency f, Hz (> 0).
    pub hertz: f64,
    /// Damping ratio ζ (≥ 0).
    pub damping_ratio: f64,
}

/// A hinge: the two anchors are held together; the bodies turn freely
/// about them, within optional limits, driven by an optional motor, pulled
/// toward a rest angle by an optional spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RevoluteJoint {
    /// Body A's anchor, world coordinates at t = 0, m.
    pub anchor_a: [f64; 2],
    /// Body B's anchor, world coordinates at t = 0, m (normally =
    /// `anchor_a`).
    pub anchor_b: [f64; 2],
    /// The joint angle is θB − θA − `reference_angle`, rad.
    pub reference_angle: f64,
    /// `[lower, upper]` joint angle, rad, lower ≤ upper, both in [−π, π]
    /// (Box2D takes at most ±0.99π).
    pub limits: Option<[f64; 2]>,
    /// Motor on the joint angle (speed rad/s, torque N·m).
    pub motor: Option<Motor>,
    /// Rotational spring toward `target` rad.
    pub spring: Option<Spring>,
}

/// A slider: body B moves along an axis fixed in body A, without relative
/// rotation, within optional limits, with an optional motor and spring on
/// the translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrismaticJoint {
    /// Body A's anchor, world coordinates at t = 0, m.
    pub anchor_a: [f64; 2],
    /// Body B's anchor, world coordinates at t = 0, m.
    pub anchor_b: [f64; 2],
    /// The axis, a world direction at t = 0 (normalised by the adapters;
    /// must not be zero).
    pub axis: [f64; 2],
    /// `[lower, upper]` translation, m, lower ≤ upper.
    pub limits: Option<[f64; 2]>,
    /// Motor on the translation (speed m/s, force N).
    pub motor: Option<Motor>,
    /// Linear spring toward `target` m.
    pub spring: Option<Spring>,
}

/// What a distance joint holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DistanceMode {
    /// A massless rigid rod: |pB − pA| = `length` (m, > 0).
    Rigid {
        /// m.
        length: f64,
    },
    /// A rope (or a strut with play): free while `min_length` ≤ |pB − pA|
    /// ≤ `max_length`, held at the bound it reaches (m, 0 ≤ min ≤ max,
    /// max > 0).
    Rope {
        /// m.
        min_length: f64,
        /// m.
        max_length: f64,
    },
    /// A spring toward the length `spring.target` (m, > 0), optionally
    /// stopped at `limits` = `[min, max]` lengths.
    Spring {
        /// Stiffness as frequency and damping ratio; `target` is the rest
        /// length.
        spring: Spring,
        /// Optional `[min, max]` length, m.
        limits: Option<[f64; 2]>,
    },
}

/// A distance constraint between two anchors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistanceJoint {
    /// Body A's anchor, world coordinates at t = 0, m.
    pub anchor_a: [f64; 2],
    /// Body B's anchor, world coordinates at t = 0, m (must differ from
    /// `anchor_a`: the direction between them is the constraint's axis).
    pub anchor_b: [f64; 2],
    /// Rigid, rope or spring.
    pub mode: DistanceMode,
}

/// A weld: body B is held at its pose relative to body A at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeldJoint {
    /// The weld point, world coordinates at t = 0, m (where the engines
    /// measure the linear error).
    pub anchor: [f64; 2],
    /// `None`: rigid (at the engine's own constraint softness). Some: a
    /// spring of that frequency and damping on both the linear and the
    /// angular error.
    pub softness: Option<Softness>,
}

/// A wheel (Box2D's wheel joint): body B's anchor (the axle) stays on
/// the line through A's anchor along `axis` (fixed in A), B turns freely,
/// a spring along the axis (rest: the anchors level, translation 0), with
/// optional limits on the translation and a motor on the rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelJoint {
    /// Body A's anchor, world coordinates at t = 0, m.
    pub anchor_a: [f64; 2],
    /// Body B's anchor, world coordinates at t = 0, m.
    pub anchor_b: [f64; 2],
    /// The suspension's axis, a world direction at t = 0 (normalised by
    /// the adapters; must not be zero).
    pub axis: [f64; 2],
    /// The suspension spring (mass-independent: f and ζ on the axial
    /// effective mass); `None`: the axis is free.
    pub spring: Option<Softness>,
    /// `[lower, upper]` translation, m.
    pub limits: Option<[f64; 2]>,
    /// Motor on the relative rotation (speed rad/s, torque N·m).
    pub motor: Option<Motor>,
}

/// A motor joint (Box2D v3.2's, its spring part): B's centre driven to
/// A's centre plus `linear_offset` (A's frame) and θB − θA to
/// `angular_offset` by springs of bounded force and torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorJoint {
    /// A's centre (the world: the origin), world coordinates at t = 0, m.
    pub anchor_a: [f64; 2],
    /// B's centre, world coordinates at t = 0, m.
    pub anchor_b: [f64; 2],
    /// Target of B's centre from A's in A's frame, m.
    pub linear_offset: [f64; 2],
    /// Target θB − θA, rad.
    pub angular_offset: f64,
    /// Largest force, N (> 0).
    pub max_force: f64,
    /// Largest torque, N·m (> 0).
    pub max_torque: f64,
    /// The linear spring.
    pub linear: Softness,
    /// The angular spring.
    pub angular: Softness,
}

/// The kind of a [`SceneJoint`] and its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointKind {
    /// A hinge.
    Revolute(RevoluteJoint),
    /// A slider.
    Prismatic(PrismaticJoint),
    /// A rod, rope or spring between two points.
    Distance(DistanceJoint),
    /// A rigid or soft weld.
    Weld(WeldJoint),
    /// A wheel on a suspension.
    Wheel(WheelJoint),
    /// A body driven to an offset from another.
    Motor(MotorJoint),
}

/// A joint of a [`super::ManyBodyScene`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneJoint {
    /// Body A by index, `None` for the world.
    pub body_a: Option<usize>,
    /// Body B by index, `None` for the world.
    pub body_b: Option<usize>,
    /// Type and parameters.
    pub kind: JointKind,
    /// Whether the two bodies still collide with each other (default
    /// false, as in Box2D; rapier's `contacts_enabled`).
    pub collide_connected: bool,
}

impl SceneJoint {
    /// A free hinge at `anchor` (world, t = 0) between `body_a` and
    /// `body_b`, with the joint angle measured from `reference_angle`
    /// (rad; pass θB0 − θA0 to start at 0), no limit, motor or spring.
    pub fn revolute(
        body_a: Option<usize>,
        body_b: Option<usize>,
        anchor: [f64; 2],
        reference_angle: f64,
    ) -> Self {
        Self::new(
            body_a,
            body_b,
            JointKind::Revolute(RevoluteJoint {
                anchor_a: anchor,
                anchor_b: anchor,
                reference_angle,
                limits: None,
                motor: None,
                spring: None,
            }),
        )
    }

    /// A free slider at `anchor` along the world direction `axis` (t = 0).
    pub fn prismatic(
        body_a: Option<usize>,
        body_b: Option<usize>,
        anchor: [f64; 2],
        axis: [f64; 2],
    ) -> Self {
        Self::new(
            body_a,
            body_b,
            JointKind::Prismatic(PrismaticJoint {
                anchor_a: anchor,
                anchor_b: anchor,
                axis,
                limits: None,
                motor: None,
                spring: None,
            }),
        )
    }

    /// A rigid rod between `anchor_a` and `anchor_b` (world, t = 0), of
    /// their distance at t = 0.
    pub fn rod(
        body_a: Option<usize>,
        body_b: Option<usize>,
        anchor_a: [f64; 2],
        anchor_b: [f64; 2],
    ) -> Self {
        let length = (anchor_b[0] - anchor_a[0]).hypot(anchor_b[1] - anchor_a[1]);
        Self::new(
            body_a,
            body_b,
            JointKind::Distance(DistanceJoint {
                anchor_a,
                anchor_b,
                mode: DistanceMode::Rigid { length },
            }),
        )
    }

    /// A rigid weld at `anchor` (world, t = 0).
    pub fn weld(body_a: Option<usize>, body_b: Option<usize>, anchor: [f64; 2]) -> Self {
        Self::new(
            body_a,
            body_b,
            JointKind::Weld(WeldJoint {
                anchor,
                softness: None,
            }),
        )
    }

    /// A joint of `kind` between the two bodies, `collide_connected` false.
    pub fn new(body_a: Option<usize>, body_b: Option<usize>, kind: JointKind) -> Self {
        Self {
            body_a,
            body_b,
            kind,
            collide_connected: false,
        }
    }

    /// The two anchors, world coordinates at t = 0 (a weld's twice).
    pub fn anchors(&self) -> ([f64; 2], [f64; 2]) {
        match &self.kind {
            JointKind::Revolute(j) => (j.anchor_a, j.anchor_b),
            JointKind::Prismatic(j) => (j.anchor_a, j.anchor_b),
            JointKind::Distance(j) => (j.anchor_a, j.anchor_b),
            JointKind::Weld(j) => (j.anchor, j.anchor),
            JointKind::Wheel(j) => (j.anchor_a, j.anchor_b),
            JointKind::Motor(j) => (j.anchor_a, j.anchor_b),
        }
    }

    /// The kind's name, for errors and reports.
    pub fn kind_name(&self) -> &'static str {
        match self.kind {
            JointKind::Revolute(_) => "revolute",
            JointKind::Prismatic(_) => "prismatic",
            JointKind::Distance(_) => "distance",
            JointKind::Weld(_) => "weld",
            JointKind::Wheel(_) => "wheel",
            JointKind::Motor(_) => "motor",
        }
    }
}

/// A body's pose (position of the origin, m; angle, rad); the world's is
/// the identity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// m.
    pub position: [f64; 2],
    /// rad.
    pub angle: f64,
}

impl Pose {
    /// The world frame: origin, angle 0.
    pub const WORLD: Pose = Pose {
        position: [0.0, 0.0],
        angle: 0.0,
    };

    /// `p` (world) in this frame's coordinates: R(−θ)(p − position).
    pub fn to_local(&self, p: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        let (dx, dy) = (p[0] - self.position[0], p[1] - self.position[1]);
        [c * dx + s * dy, -s * dx + c * dy]
    }

    /// `p` (this frame) in world coordinates: position + R(θ) p.
    pub fn to_world(&self, p: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        [
            self.position[0] + c * p[0] - s * p[1],
            self.position[1] + s * p[0] + c * p[1],
        ]
    }

    /// The direction `d` of this frame in world axes: R(θ) d.
    pub fn to_world_direction(&self, d: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        [c * d[0] - s * d[1], s * d[0] + c * d[1]]
    }

    /// The world direction `d` in this frame's axes: R(−θ) d.
    pub fn direction_to_local(&self, d: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        [c * d[0] + s * d[1], -s * d[0] + c * d[1]]
    }
}

/// The pose of joint body `b` at t = 0: the scene body's, or the world's.
pub(crate) fn initial_pose(bodies: &[SceneBody], b: Option<usize>) -> Pose {
    match b {
        None => Pose::WORLD,
        Some(i) => Pose {
            position: bodies[i].position,
            angle: bodies[i].angle,
        },
    }
}

/// `x` wrapped to (−π, π].
pub fn wrap_angle(x: f64) -> f64 {
    let y = x.rem_euclid(2.0 * PI);
    if y > PI { y - 2.0 * PI } else { y }
}

/// A joint's state as read from the bodies' poses: the same computation
/// for every engine ([`joint_states`]), so the engines are compared on
/// equal terms.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointState {
    /// The joint's coordinate: the revolute joint angle (rad), the
    /// prismatic translation (m), the distance between the anchors (m);
    /// 0 for a weld.
    pub coordinate: f64,
    /// How far the anchors are from where the joint holds them, m:
    /// |pB − pA| for a revolute joint and a weld; the distance of pB from
    /// A's axis line for a prismatic joint; ||pB − pA| − length| for a
    /// rigid rod; the excess over the length bounds for a rope or a
    /// limited spring (0 inside them, and always 0 for a free spring).
    pub separation: f64,
    /// How far the relative rotation is from where the joint holds it,
    /// rad: |θB − θA − (θB0 − θA0)| (wrapped) for prismatic joints and
    /// welds; 0 for revolute and distance joints (free to turn).
    pub angular_error: f64,
    /// How far the coordinate is outside its limits (rad or m; 0 inside,
    /// or without limits). For a distance joint the excess over its length
    /// bounds is already in `separation`, and this is 0.
    pub limit_violation: f64,
}

/// The state of every joint of `joints` given the bodies' current poses
/// (`samples`, in scene order; `bodies` the scene's bodies at t = 0, for
/// the anchors in body coordinates).
pub fn joint_states(
    bodies: &[SceneBody],
    joints: &[SceneJoint],
    samples: &[BodySample],
) -> Vec<JointState> {
    let pose = |b: Option<usize>| match b {
        None => Pose::WORLD,
        Some(i) => Pose {
            position: samples[i].position,
            angle: samples[i].angle,
        },
    };
    joints
        .iter()
        .map(|j| {
            let (a0, b0) = (
                initial_pose(bodies, j.body_a),
                initial_pose(bodies, j.body_b),
            );
            let (pa, pb) = (pose(j.body_a), pose(j.body_b));
            let (anchor_a, anchor_b) = j.anchors();
            let wa = pa.to_world(a0.to_local(anchor_a));
            let wb = pb.to_world(b0.to_local(anchor_b));
            let d = [wb[0] - wa[0], wb[1] - wa[1]];
            let dist = d[0].hypot(d[1]);
            let relative = pb.angle - pa.angle;
            let held = wrap_angle(relative - (b0.angle - a0.angle)).abs();
            let excess = |x: f64, l: Option<[f64; 2]>| match l {
                Some([lo, hi]) => (lo - x).max(x - hi).max(0.0),
                None => 0.0,
            };
            match &j.kind {
                JointKind::Revolute(r) => {
                    let angle = wrap_angle(relative - r.reference_angle);
                    JointState {
                        coordinate: angle,
                        separation: dist,
                        angular_error: 0.0,
                        limit_violation: excess(angle, r.limits),
                    }
                }
                JointKind::Prismatic(p) => {
                    let n = p.axis[0].hypot(p.axis[1]);
                    let axis0 = [p.axis[0] / n, p.axis[1] / n];
                    let axis = pa.to_world_direction(a0.direction_to_local(axis0));
                    let along = d[0] * axis[0] + d[1] * axis[1];
                    let across = (d[0] * axis[1] - d[1] * axis[0]).abs();
                    JointState {
                        coordinate: along,
                        separation: across,
                        angular_error: held,
                        limit_violation: excess(along, p.limits),
                    }
                }
                JointKind::Distance(dj) => {
                    let separation = match dj.mode {
                        DistanceMode::Rigid { length } => (dist - length).abs(),
                        DistanceMode::Rope {
                            min_length,
                            max_length,
                        } => excess(dist, Some([min_length, max_length])),
                        DistanceMode::Spring { limits, .. } => excess(dist, limits),
                    };
                    JointState {
                        coordinate: dist,
                        separation,
                        angular_error: 0.0,
                        limit_violation: 0.0,
                    }
                }
                JointKind::Weld(_) => JointState {
                    coordinate: 0.0,
                    separation: dist,
                    angular_error: held,
                    limit_violation: 0.0,
                },
                JointKind::Wheel(w) => {
                    let n = w.axis[0].hypot(w.axis[1]);
                    let axis0 = [w.axis[0] / n, w.axis[1] / n];
                    let axis = pa.to_world_direction(a0.direction_to_local(axis0));
                    let along = d[0] * axis[0] + d[1] * axis[1];
                    let across = (d[0] * axis[1] - d[1] * axis[0]).abs();
                    JointState {
                        coordinate: along,
                        separation: across,
                        angular_error: 0.0,
                        limit_violation: excess(along, w.limits),
                    }
                }
                JointKind::Motor(m) => {
                    let o = pa.to_world_direction(m.linear_offset);
                    let e = [d[0] - o[0], d[1] - o[1]];
                    JointState {
                        coordinate: 0.0,
                        separation: e[0].hypot(e[1]),
                        angular_error: wrap_angle(relative - m.angular_offset).abs(),
                        limit_violation: 0.0,
                    }
                }
            }
        })
        .collect()
}

fn joint_error(
    joint: usize,
    field: &'static str,
    value: f64,
    reason: &'static str,
) -> ManyBodyError {
    ManyBodyError::InvalidJoint {
        joint,
        field,
        value,
        reason,
    }
}

fn finite(joint: usize, fields: &[(&'static str, f64)]) -> Result<(), ManyBodyError> {
    for &(field, v) in fields {
        if !v.is_finite() {
            return Err(joint_error(joint, field, v, "must be finite"));
        }
    }
    Ok(())
}

fn ordered(
    joint: usize,
    field: &'static str,
    l: Option<[f64; 2]>,
    bound: Option<f64>,
) -> Result<(), ManyBodyError> {
    if let Some([lo, hi]) = l {
        finite(joint, &[(field, lo), (field, hi)])?;
        if lo > hi {
            return Err(joint_error(
                joint,
                field,
                lo,
                "lower bound must not exceed the upper bound",
            ));
        }
        if let Some(b) = bound
            && (lo < -b || hi > b)
        {
            return Err(joint_error(
                joint,
                field,
                if lo < -b { lo } else { hi },
                "an angle limit must lie in [-pi, pi]",
            ));
        }
    }
    Ok(())
}

fn motor(joint: usize, m: Option<Motor>) -> Result<(), ManyBodyError> {
    if let Some(m) = m {
        finite(joint, &[("motor speed", m.speed)])?;
        if !(m.max_force.is_finite() && m.max_force >= 0.0) {
            return Err(joint_error(
                joint,
                "motor maximum force or torque",
                m.max_force,
                "must be finite and >= 0",
            ));
        }
    }
    Ok(())
}

fn softness(joint: usize, hertz: f64, damping_ratio: f64) -> Result<(), ManyBodyError> {
    if !(hertz.is_finite() && hertz > 0.0) {
        return Err(joint_error(
            joint,
            "spring frequency (Hz)",
            hertz,
            "must be finite and > 0",
        ));
    }
    if !(damping_ratio.is_finite() && damping_ratio >= 0.0) {
        return Err(joint_error(
            joint,
            "spring damping ratio",
            damping_ratio,
            "must be finite and >= 0",
        ));
    }
    Ok(())
}

fn spring(joint: usize, s: Option<Spring>) -> Result<(), ManyBodyError> {
    if let Some(s) = s {
        softness(joint, s.hertz, s.damping_ratio)?;
        finite(joint, &[("spring target", s.target)])?;
    }
    Ok(())
}

/// Checks joint `index` of a scene with `bodies`: bodies that exist,
/// distinct, at least one dynamic; finite anchors; ordered limits (angles
/// within [−π, π]); a non-zero axis; lengths > 0; motors with a force ≥ 0;
/// springs with a frequency > 0 and a damping ratio ≥ 0.
pub(crate) fn validate_joint(
    index: usize,
    j: &SceneJoint,
    bodies: &[SceneBody],
) -> Result<(), ManyBodyError> {
    for (field, b) in [("body A", j.body_a), ("body B", j.body_b)] {
        if let Some(i) = b
            && i >= bodies.len()
        {
            return Err(joint_error(
                index,
                field,
                i as f64,
                "names no body of the scene",
            ));
        }
    }
    if j.body_a == j.body_b {
        return Err(joint_error(
            index,
            "body B",
            j.body_b.map_or(-1.0, |i| i as f64),
            "must differ from body A (-1: the world)",
        ));
    }
    let dynamic = |b: Option<usize>| b.is_some_and(|i| bodies[i].kind == BodyKind::Dynamic);
    if !(dynamic(j.body_a) || dynamic(j.body_b)) {
        return Err(joint_error(
            index,
            "body A",
            j.body_a.map_or(-1.0, |i| i as f64),
            "a joint needs at least one dynamic body",
        ));
    }
    let (a, b) = j.anchors();
    finite(
        index,
        &[
            ("anchor A x", a[0]),
            ("anchor A y", a[1]),
            ("anchor B x", b[0]),
            ("anchor B y", b[1]),
        ],
    )?;
    match &j.kind {
        JointKind::Revolute(r) => {
            finite(index, &[("reference angle", r.reference_angle)])?;
            ordered(index, "angle limits", r.limits, Some(PI))?;
            motor(index, r.motor)?;
            spring(index, r.spring)?;
        }
        JointKind::Prismatic(p) => {
            finite(index, &[("axis x", p.axis[0]), ("axis y", p.axis[1])])?;
            let n = p.axis[0].hypot(p.axis[1]);
            if !(n > 0.0 && n.is_finite()) {
                return Err(joint_error(index, "axis length", n, "must be > 0"));
            }
            ordered(index, "translation limits", p.limits, None)?;
            motor(index, p.motor)?;
            spring(index, p.spring)?;
        }
        JointKind::Distance(d) => {
            let span = (b[0] - a[0]).hypot(b[1] - a[1]);
            if span == 0.0 {
                return Err(joint_error(
                    index,
                    "distance between the anchors at t = 0",
                    span,
                    "must be > 0 (it gives the joint's axis)",
                ));
            }
            match d.mode {
                DistanceMode::Rigid { length } => {
                    if !(length.is_finite() && length > 0.0) {
                        return Err(joint_error(
                            index,
                            "length",
                            length,
                            "must be finite and > 0",
                        ));
                    }
                }
                DistanceMode::Rope {
                    min_length,
                    max_length,
                } => {
                    ordered(index, "rope lengths", Some([min_length, max_length]), None)?;
                    if min_length < 0.0 || max_length <= 0.0 {
                        return Err(joint_error(
                            index,
                            "rope lengths",
                            min_length.min(max_length),
                            "need 0 <= minimum <= maximum and maximum > 0",
                        ));
                    }
                }
                DistanceMode::Spring { spring: s, limits } => {
                    spring(index, Some(s))?;
                    if s.target <= 0.0 {
                        return Err(joint_error(
                            index,
                            "spring rest length",
                            s.target,
                            "must be > 0",
                        ));
                    }
                    ordered(index, "length limits", limits, None)?;
                    if let Some([lo, _]) = limits
                        && lo < 0.0
                    {
                        return Err(joint_error(
                            index,
                            "length limits",
                            lo,
                            "a length bound must be >= 0",
                        ));
                    }
                }
            }
        }
        JointKind::Weld(w) => {
            if let Some(s) = w.softness {
                softness(index, s.hertz, s.damping_ratio)?;
            }
        }
        JointKind::Wheel(w) => {
            finite(index, &[("axis x", w.axis[0]), ("axis y", w.axis[1])])?;
            let n = w.axis[0].hypot(w.axis[1]);
            if !(n > 0.0 && n.is_finite()) {
                return Err(joint_error(index, "axis length", n, "must be > 0"));
            }
            ordered(index, "translation limits", w.limits, None)?;
            motor(index, w.motor)?;
            if let Some(s) = w.spring {
                softness(index, s.hertz, s.damping_ratio)?;
            }
        }
        JointKind::Motor(m) => {
            finite(
                index,
                &[
                    ("linear offset x", m.linear_offset[0]),
                    ("linear offset y", m.linear_offset[1]),
                    ("angular offset", m.angular_offset),
                ],
            )?;
            for (field, v) in [
                ("maximum force", m.max_force),
                ("maximum torque", m.max_torque),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(joint_error(index, field, v, "must be finite and > 0"));
                }
            }
            softness(index, m.linear.hertz, m.linear.damping_ratio)?;
            softness(index, m.angular.hertz, m.angular.damping_ratio)?;
        }
    }
    Ok(())
}
