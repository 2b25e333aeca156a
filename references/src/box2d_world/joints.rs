//! The scene's joints as Box2D 3.2 joints (`b2RevoluteJointDef`,
//! `b2PrismaticJointDef`, `b2DistanceJointDef`, `b2WeldJointDef`, read in
//! the vendored `src/joint.c`, `revolute_joint.c`, `prismatic_joint.c`,
//! `distance_joint.c`, `weld_joint.c`).
//!
//! # What each setting is, and what is changed from Box2D's defaults
//!
//! Every joint keeps Box2D's default base (`b2DefaultJointDef`): constraint
//! softness 60 Hz with damping ratio 2 (`constraintHertz`,
//! `constraintDampingRatio`), which Box2D clamps to a quarter of the
//! substep rate (min(60, 0.25/h) = 60 Hz at h = 1/240 s) and applies in
//! the biased pass of each substep only (the relax pass solves the joint
//! rigidly, without position bias); force and torque thresholds infinite;
//! warm starting on (world default). Set from the scene:
//! - the local frames: each anchor in its body's frame from the body's
//!   initial pose, R(−θ0)(anchor − p0), rounded to f32. A revolute joint's
//!   frame A is turned by `reference_angle` (Box2D's joint angle is the
//!   angle between the two frames, so θB − θA − reference); a prismatic
//!   joint's frames both point along the axis (frame A turned by the
//!   axis's angle in A, frame B by the same world angle in B), which also
//!   makes Box2D hold the initial relative angle; a weld's frames carry
//!   the bodies' initial orientations the same way;
//! - `collideConnected` = the scene's `collide_connected` (default false in
//!   both);
//! - revolute: `enableLimit`, `lowerAngle`, `upperAngle` (Box2D refuses
//!   limits beyond ±0.99π: such a joint is refused here); `enableMotor`,
//!   `motorSpeed`, `maxMotorTorque` (a rigid velocity row, impulse clamped
//!   to h × max torque per substep); `enableSpring`, `hertz`,
//!   `dampingRatio`, `targetAngle`;
//! - prismatic: the same on the translation (`lowerTranslation`,
//!   `upperTranslation`, `maxMotorForce`, `targetTranslation`);
//! - distance: a rigid rod is `enableSpring` false at `length`; a rope is
//!   `enableSpring` true with `hertz` 0 (no spring force) and
//!   `enableLimit` with `minLength`, `maxLength` (Box2D raises a minimum
//!   below its linear slop, 0.005 m, to it); a spring is `enableSpring`
//!   with `hertz`, `dampingRatio`, `length` = the rest length, and
//!   `enableLimit` if the scene limits it; spring force bounds stay
//!   infinite (Box2D's default);
//! - weld: rigid is `linearHertz` = `angularHertz` = 0 (Box2D then uses the
//!   joint's constraint softness, 60 Hz, ζ 2, in the biased pass); soft is
//!   both set to the scene's frequency and damping ratio (then soft in
//!   both passes);
//! - wheel (`b2WheelJointDef`): frame A's x axis along the scene's axis
//!   (as a prismatic's); `enableSpring` with `hertz`, `dampingRatio` (Box2D
//!   enables a 1 Hz spring by default: off when the scene has none);
//!   `enableLimit`, `lowerTranslation`, `upperTranslation`; `enableMotor`,
//!   `motorSpeed`, `maxMotorTorque`;
//! - motor (`b2MotorJointDef`, v3.2's): frame A at the linear offset from
//!   A's centre, turned by the angular offset, frame B at B's centre;
//!   `linearHertz`, `linearDampingRatio`, `maxSpringForce`,
//!   `angularHertz`, `angularDampingRatio`, `maxSpringTorque` from the
//!   scene; the velocity part off (`maxVelocityForce` =
//!   `maxVelocityTorque` = 0).
//!
//! A joint to the world (`None`) is attached to one static body without
//! shapes at the origin, created for that purpose.
//!
//! # What cannot be mapped exactly, and Box2D's own approximations
//!
//! - Box2D measures joint angles (revolute limits and springs, weld and
//!   prismatic angular rows) with `b2Atan2` (`math_functions.c`), a
//!   minimax polynomial for atan of error up to 2.8e-5 rad: a limit holds
//!   the *true* angle up to that far from its set value (measured: a bar
//!   resting on a −0.5 rad limit sits 1.74e-5 rad beyond it on top of its
//!   soft sag, as the polynomial predicts).
//! - Limits are speculative (a limit row acts as soon as the angle would
//!   reach it within the substep), soft at the joint's constraint softness
//!   when violated.
//! - The joint's constraint softness is Box2D's default for every joint:
//!   the scene has no per-joint setting (Box2D's Falling Hinges use a
//!   damping ratio of 0 instead of 2).
//! - Everything is f32: anchors in body coordinates, limits, speeds,
//!   torques and spring constants are rounded once (relative 6e-8).

use super::ENGINE;
use crate::many_body::joints::{Pose, initial_pose};
use crate::many_body::{DistanceMode, JointKind, ManyBodyError, ManyBodyScene, SceneJoint};
use boxdd::{
    BodyId, BodyType, DistanceJointDef, JointId, MotorJointDef, PrismaticJointDef,
    RevoluteJointDef, Transform, WeldJointDef, WheelJointDef, World,
};

/// Box2D's largest revolute limit magnitude (boxdd's check, Box2D's
/// assertion in `b2RevoluteJoint_SetLimits`), rad.
pub const REVOLUTE_LIMIT_MAX: f64 = 0.99 * std::f64::consts::PI;

fn refused(joint: usize, message: impl Into<String>) -> ManyBodyError {
    ManyBodyError::JointRefused {
        engine: ENGINE,
        joint,
        message: message.into(),
    }
}

/// A joint value rounded to f32, refused if it does not fit.
fn jf32(joint: usize, field: &'static str, x: f64) -> Result<f32, ManyBodyError> {
    let y = x as f32;
    if y.is_finite() || x.is_infinite() {
        Ok(y)
    } else {
        Err(ManyBodyError::InvalidJoint {
            joint,
            field,
            value: x,
            reason: "is beyond Box2D's single-precision range",
        })
    }
}

fn frame(joint: usize, p: [f64; 2], angle: f64) -> Result<Transform, ManyBodyError> {
    let p = [jf32(joint, "anchor", p[0])?, jf32(joint, "anchor", p[1])?];
    Transform::from_pos_angle(p, angle as f32).map_err(|e| refused(joint, e.to_string()))
}

/// Builds every joint of `scene` in `world`, whose bodies are `bodies`
/// (scene order). Returns the joint ids in scene order and the world body
/// if one was needed.
pub(super) fn build_joints(
    world: &mut World,
    scene: &ManyBodyScene,
    bodies: &[BodyId],
) -> Result<(Vec<JointId>, Option<BodyId>), ManyBodyError> {
    let mut ground = None;
    if scene
        .joints
        .iter()
        .any(|j| j.body_a.is_none() || j.body_b.is_none())
    {
        let def = world
            .body_builder()
            .body_type(BodyType::Static)
            .build()
            .map_err(|e| refused(0, e.to_string()))?;
        ground = Some(
            world
                .create_body(def)
                .map_err(|e| refused(0, e.to_string()))?,
        );
    }
    let id = |b: Option<usize>| match b {
        Some(i) => bodies[i],
        None => ground.expect("created above when a joint names the world"),
    };
    let mut ids = Vec::with_capacity(scene.joints.len());
    for (i, j) in scene.joints.iter().enumerate() {
        ids.push(build_joint(world, scene, i, j, id(j.body_a), id(j.body_b))?);
    }
    Ok((ids, ground))
}

fn build_joint(
    world: &mut World,
    scene: &ManyBodyScene,
    i: usize,
    j: &SceneJoint,
    a: BodyId,
    b: BodyId,
) -> Result<JointId, ManyBodyError> {
    let (pa, pb): (Pose, Pose) = (
        initial_pose(&scene.bodies, j.body_a),
        initial_pose(&scene.bodies, j.body_b),
    );
    let (anchor_a, anchor_b) = j.anchors();
    let (la, lb) = (pa.to_local(anchor_a), pb.to_local(anchor_b));
    // Frame angles: a revolute joint's frame A carries the reference
    // angle; prismatic and weld frames share one world orientation at
    // t = 0 (the axis's, or 0) so Box2D holds the initial relative angle.
    let (angle_a, angle_b) = match &j.kind {
        JointKind::Revolute(r) => (r.reference_angle, 0.0),
        JointKind::Prismatic(p) => {
            let world_angle = p.axis[1].atan2(p.axis[0]);
            (world_angle - pa.angle, world_angle - pb.angle)
        }
        JointKind::Weld(_) => (-pa.angle, -pb.angle),
        JointKind::Distance(_) => (0.0, 0.0),
        JointKind::Wheel(w) => {
            let world_angle = w.axis[1].atan2(w.axis[0]);
            (world_angle - pa.angle, world_angle - pb.angle)
        }
        JointKind::Motor(m) => (m.angular_offset, 0.0),
    };
    // A motor joint's frame A is at the target: the offset from A's centre.
    let la = match &j.kind {
        JointKind::Motor(m) => [la[0] + m.linear_offset[0], la[1] + m.linear_offset[1]],
        _ => la,
    };
    let base = world
        .joint_base(a, b)
        .map_err(|e| refused(i, e.to_string()))?
        .with_local_frames(frame(i, la, angle_a)?, frame(i, lb, angle_b)?)
        .with_collide_connected(j.collide_connected);
    let err = |e: boxdd::Error| refused(i, e.to_string());
    match &j.kind {
        JointKind::Revolute(r) => {
            let mut def = RevoluteJointDef::new(base);
            if let Some([lo, hi]) = r.limits {
                if lo < -REVOLUTE_LIMIT_MAX || hi > REVOLUTE_LIMIT_MAX {
                    return Err(refused(
                        i,
                        format!(
                            "angle limits [{lo}, {hi}] rad: Box2D takes limits within \
                             +-0.99 pi = +-{REVOLUTE_LIMIT_MAX:.6} rad"
                        ),
                    ));
                }
                def = def
                    .enable_limit(true)
                    .lower_angle(jf32(i, "lower angle", lo)?)
                    .upper_angle(jf32(i, "upper angle", hi)?);
            }
            if let Some(m) = r.motor {
                def = def
                    .enable_motor(true)
                    .motor_speed(jf32(i, "motor speed", m.speed)?)
                    .max_motor_torque(jf32(i, "motor torque", m.max_force)?);
            }
            if let Some(s) = r.spring {
                def = def
                    .enable_spring(true)
                    .hertz(jf32(i, "spring frequency", s.hertz)?)
                    .damping_ratio(jf32(i, "spring damping ratio", s.damping_ratio)?)
                    .target_angle(jf32(i, "spring target", s.target)?);
            }
            world.create_revolute_joint(&def).map_err(err)
        }
        JointKind::Prismatic(p) => {
            let mut def = PrismaticJointDef::new(base);
            if let Some([lo, hi]) = p.limits {
                def = def
                    .enable_limit(true)
                    .lower_translation(jf32(i, "lower translation", lo)?)
                    .upper_translation(jf32(i, "upper translation", hi)?);
            }
            if let Some(m) = p.motor {
                def = def
                    .enable_motor(true)
                    .motor_speed(jf32(i, "motor speed", m.speed)?)
                    .max_motor_force(jf32(i, "motor force", m.max_force)?);
            }
            if let Some(s) = p.spring {
                def = def
                    .enable_spring(true)
                    .hertz(jf32(i, "spring frequency", s.hertz)?)
                    .damping_ratio(jf32(i, "spring damping ratio", s.damping_ratio)?)
                    .translation(jf32(i, "spring target", s.target)?);
            }
            world.create_prismatic_joint(&def).map_err(err)
        }
        JointKind::Distance(d) => {
            let def = DistanceJointDef::new(base);
            let def = match d.mode {
                DistanceMode::Rigid { length } => {
                    def.enable_spring(false).length(jf32(i, "length", length)?)
                }
                DistanceMode::Rope {
                    min_length,
                    max_length,
                } => def
                    .length(jf32(i, "maximum length", max_length)?)
                    .enable_spring(true)
                    .hertz(0.0)
                    .enable_limit(true)
                    .min_length(jf32(i, "minimum length", min_length)?)
                    .max_length(jf32(i, "maximum length", max_length)?),
                DistanceMode::Spring { spring, limits } => {
                    let def = def
                        .length(jf32(i, "rest length", spring.target)?)
                        .enable_spring(true)
                        .hertz(jf32(i, "spring frequency", spring.hertz)?)
                        .damping_ratio(jf32(i, "spring damping ratio", spring.damping_ratio)?);
                    match limits {
                        Some([lo, hi]) => def
                            .enable_limit(true)
                            .min_length(jf32(i, "minimum length", lo)?)
                            .max_length(jf32(i, "maximum length", hi)?),
                        None => def.enable_limit(false),
                    }
                }
            };
            world.create_distance_joint(&def).map_err(err)
        }
        JointKind::Weld(w) => {
            let mut def = WeldJointDef::new(base);
            if let Some(s) = w.softness {
                let hz = jf32(i, "weld frequency", s.hertz)?;
                let z = jf32(i, "weld damping ratio", s.damping_ratio)?;
                def = def
                    .linear_hertz(hz)
                    .angular_hertz(hz)
                    .linear_damping_ratio(z)
                    .angular_damping_ratio(z);
            }
            world.create_weld_joint(&def).map_err(err)
        }
        JointKind::Wheel(w) => {
            let mut def = WheelJointDef::new(base).enable_spring(false);
            if let Some(s) = w.spring {
                def = def
                    .enable_spring(true)
                    .hertz(jf32(i, "spring frequency", s.hertz)?)
                    .damping_ratio(jf32(i, "spring damping ratio", s.damping_ratio)?);
            }
            if let Some([lo, hi]) = w.limits {
                def = def
                    .enable_limit(true)
                    .lower_translation(jf32(i, "lower translation", lo)?)
                    .upper_translation(jf32(i, "upper translation", hi)?);
            }
            if let Some(m) = w.motor {
                def = def
                    .enable_motor(true)
                    .motor_speed(jf32(i, "motor speed", m.speed)?)
                    .max_motor_torque(jf32(i, "motor torque", m.max_force)?);
            }
            world.create_wheel_joint(&def).map_err(err)
        }
        JointKind::Motor(m) => {
            let def = MotorJointDef::new(base)
                .max_velocity_force(0.0)
                .max_velocity_torque(0.0)
                .linear_hertz(jf32(i, "linear frequency", m.linear.hertz)?)
                .linear_damping_ratio(jf32(i, "linear damping ratio", m.linear.damping_ratio)?)
                .max_spring_force(jf32(i, "maximum force", m.max_force)?)
                .angular_hertz(jf32(i, "angular frequency", m.angular.hertz)?)
                .angular_damping_ratio(jf32(i, "angular damping ratio", m.angular.damping_ratio)?)
                .max_spring_torque(jf32(i, "maximum torque", m.max_torque)?);
            world.create_motor_joint(&def).map_err(err)
        }
    }
}

/// The scene's collision group as Box2D's group index: bodies sharing a
/// negative group index never collide (`b2ShouldShapesCollide`), so group
/// g becomes −(g + 1).
pub(super) fn group_index(body: usize, group: Option<u32>) -> Result<i32, ManyBodyError> {
    match group {
        None => Ok(0),
        Some(g) if g < i32::MAX as u32 => Ok(-(g as i32) - 1),
        Some(g) => Err(ManyBodyError::BodyRefused {
            engine: ENGINE,
            body,
            message: format!(
                "collision group {g}: Box2D's group index is an i32, groups up to {} fit",
                i32::MAX - 1
            ),
        }),
    }
}
