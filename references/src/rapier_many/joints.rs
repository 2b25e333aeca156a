//! The scene's joints as rapier 0.36 impulse joints (`ImpulseJointSet`,
//! stepped with the bodies by `PhysicsWorld::step`), and the scene's
//! collision groups as rapier interaction groups.
//!
//! # How each joint is built (read in `src/dynamics/joint/` and
//! `src/dynamics/solver/joint_constraint/`)
//!
//! Every joint is a [`GenericJoint`] with the scene's anchors in each
//! body's frame (R(−θ0)(anchor − p0), f64), `contacts_enabled` =
//! `collide_connected` (rapier's default is true, Box2D's and the scene's
//! false), and rapier's own joint softness for its locked axes and limits
//! (`SpringCoefficients::joint_defaults`: 1e6 Hz, ζ = 1, i.e. rigid, the
//! error removed in one substep; in the biased pass only, like Box2D's).
//! Joint warm starting stays off (`warmstart_joints` false, rapier's
//! default; Box2D warm-starts its joints).
//!
//! - Revolute: `LOCKED_REVOLUTE_AXES` (the two linear axes), frame 1 turned
//!   by the reference angle (rapier's joint angle is the angle between the
//!   two frames, as Box2D's); limits on `AngX`.
//! - Prismatic: `LOCKED_PRISMATIC_AXES` (the perpendicular linear axis and
//!   the rotation), frame axes along the scene axis expressed in each body
//!   at t = 0, so the rotation lock holds the initial relative angle;
//!   limits on `LinX`.
//! - Weld: `LOCKED_FIXED_AXES`, frames carrying the bodies' initial
//!   orientations; a soft weld sets the joint's softness to the scene's
//!   frequency and damping ratio (rapier applies it to every locked axis,
//!   its bias in the biased pass only and its compliance in both; Box2D's
//!   soft weld keeps the bias in the relax pass too).
//! - Distance: no locked axis; the two linear axes coupled (rapier's
//!   `RopeJoint`/`SpringJoint` form: one row along the line between the
//!   anchors). A rope is a limit on `LinX` at the maximum length (rapier
//!   handles only the maximum of a coupled limit: a minimum length > 0 is
//!   refused). A spring, and a *rigid rod* (rapier has no rigid distance
//!   joint), are a position motor on `LinX` toward the length, unbounded
//!   force; the rod's stiffness and damping are rapier's joint softness
//!   (1e6 Hz, ζ 1) in the form below, which makes it rigid to ~1e-9 of
//!   the error per substep, but kept in the relax pass too (a motor row
//!   has no bias to remove).
//!
//! # Springs and motors: the exact mapping from Hz and ratio
//!
//! Box2D's spring of frequency f and damping ratio ζ on a row of effective
//! mass m_eff is, per substep h, ω = 2πf, Δλ = −m_eff s_m (Cdot + b C) −
//! s_i λ with b = ω/(2ζ + hω), s_m = a/(1 + a), s_i = 1/(1 + a),
//! a = hω(2ζ + hω): a spring of stiffness m_eff ω² and damping
//! 2 ζ m_eff ω. Rapier's motor in its `AccelerationBased` model (its
//! default) with stiffness k and damping c multiplies both by the row's
//! effective mass and solves with erp/h = k/(hk + c) and a compliance
//! 1/(h²k + hc) per unit effective mass (`MotorModel::combine_coefficients`,
//! `finalize_constraints`). With **k = ω² and c = 2ζω** these are exactly
//! b and 1/a, so Δλ is Box2D's: the mapping is exact and needs no body
//! mass (in `ForceBased` form, which `SpringJoint` uses by default, it
//! would be k = m_eff ω², c = 2 ζ m_eff ω, e.g. m ω² for a point mass m
//! hanging from the world).
//!
//! A motor (target speed, maximum force) is a velocity motor: stiffness 0,
//! damping [`RIGID_MOTOR_DAMPING`] (compliance 1/(h c) < 1e-12 per unit
//! effective mass: Box2D's rigid velocity row), impulse bounded by h ×
//! max force. Rapier has one motor per axis: when a joint has both a
//! spring and a motor (the ragdolls, Falling Hinges), the spring is the
//! main joint's motor and the motor a second impulse joint between the
//! same bodies with the same frames and no locked axis, carrying only that
//! row, so both act as in Box2D (which solves spring, then motor, then
//! limits, then the point; rapier's order within a joint is motors,
//! locks, limits).
//!
//! A joint to the world (`None`) is attached to one fixed body without
//! collider at the origin.
//!
//! # What differs from Box2D's joints
//!
//! - Angular limits engage only once the angle is past the limit (the row
//!   is inactive inside the range: no speculative margin) and their bias
//!   is capped at the corrective speed: a fast approach overshoots by up
//!   to ω h per substep before the row acts. Measured: a ragdoll landing
//!   from 0.3 m overshoots its hip–torso limit by 0.7–1.7 rad and stays
//!   there, pinned by its ground contacts (Box2D holds every limit; the
//!   torso alone, hinged to a fixed hip, holds its limit in rapier too).
//! - A rope's minimum length and a spring's minimum length are refused
//!   (the coupled limit stops only the maximum).
//! - Joint angles are exact (`Rot2::angle`), where Box2D uses its atan2
//!   approximation.
//!
//! # Collision groups
//!
//! Each distinct scene group gets one bit of rapier's 32 interaction
//! groups (in order of first appearance): a body of group g is a member of
//! bit g and filters out bit g, so two bodies collide iff their groups
//! differ (rapier's `And` test); a body without group is a member of every
//! bit and filters none. More than 32 distinct groups are refused.

use super::ENGINE;
use crate::many_body::joints::initial_pose;
use crate::many_body::{
    DistanceMode, JointKind, ManyBodyError, ManyBodyScene, SceneBody, SceneJoint,
};
use rapier2d_f64::dynamics::{
    GenericJoint, ImpulseJointHandle, JointAxesMask, JointAxis, MotorModel, RigidBodyBuilder,
    RigidBodyHandle, SpringCoefficients,
};
use rapier2d_f64::geometry::{Group, InteractionGroups, InteractionTestMode};
use rapier2d_f64::math::{Pose, Rotation, Vector};
use rapier2d_f64::pipeline::PhysicsWorld;
use std::f64::consts::TAU;

/// Damping (s⁻¹, per unit effective mass) of a velocity motor: its
/// compliance 1/(h c) is below 1e-12 at any substep h ≥ 1e-3 s, so the
/// motor is a rigid velocity constraint up to its force bound, as Box2D's.
pub const RIGID_MOTOR_DAMPING: f64 = 1e15;

fn refused(joint: usize, message: impl Into<String>) -> ManyBodyError {
    ManyBodyError::JointRefused {
        engine: ENGINE,
        joint,
        message: message.into(),
    }
}

/// Stiffness and damping (per unit effective mass) of rapier's
/// `AccelerationBased` motor equal to Box2D's soft spring of `hertz` and
/// `damping_ratio`: (ω², 2ζω), ω = 2π f.
pub fn acceleration_spring(hertz: f64, damping_ratio: f64) -> (f64, f64) {
    let omega = TAU * hertz;
    (omega * omega, 2.0 * damping_ratio * omega)
}

fn vector(p: [f64; 2]) -> Vector {
    Vector::new(p[0], p[1])
}

/// Builds every joint of `scene` in `world` (bodies `bodies`, scene
/// order). Returns, per scene joint, its impulse joints (the main one
/// first, then the separate motor if any).
pub(super) fn build_joints(
    world: &mut PhysicsWorld,
    scene: &ManyBodyScene,
    bodies: &[RigidBodyHandle],
) -> Result<Vec<Vec<ImpulseJointHandle>>, ManyBodyError> {
    let ground = if scene
        .joints
        .iter()
        .any(|j| j.body_a.is_none() || j.body_b.is_none())
    {
        Some(world.insert_body(RigidBodyBuilder::fixed()))
    } else {
        None
    };
    let handle = |b: Option<usize>| match b {
        Some(i) => bodies[i],
        None => ground.expect("inserted above when a joint names the world"),
    };
    let mut out = Vec::with_capacity(scene.joints.len());
    for (i, j) in scene.joints.iter().enumerate() {
        let (main, motor) = generic_joints(i, j, &scene.bodies)?;
        let (a, b) = (handle(j.body_a), handle(j.body_b));
        let mut handles = vec![world.insert_impulse_joint(a, b, main)];
        if let Some(m) = motor {
            handles.push(world.insert_impulse_joint(a, b, m));
        }
        out.push(handles);
    }
    Ok(out)
}

/// The main generic joint of scene joint `i`, and the separate motor joint
/// when it has both a spring and a motor.
fn generic_joints(
    i: usize,
    j: &SceneJoint,
    bodies: &[SceneBody],
) -> Result<(GenericJoint, Option<GenericJoint>), ManyBodyError> {
    let (pa, pb) = (
        initial_pose(bodies, j.body_a),
        initial_pose(bodies, j.body_b),
    );
    let (anchor_a, anchor_b) = j.anchors();
    let (la, lb) = (vector(pa.to_local(anchor_a)), vector(pb.to_local(anchor_b)));
    let mut g = GenericJoint {
        contacts_enabled: j.collide_connected,
        ..GenericJoint::default()
    };
    let velocity_motor = |g: &mut GenericJoint, axis: JointAxis, speed: f64, max: f64| {
        g.set_motor_model(axis, MotorModel::AccelerationBased);
        g.set_motor_velocity(axis, speed, RIGID_MOTOR_DAMPING);
        g.set_motor_max_force(axis, max);
    };
    let spring_motor = |g: &mut GenericJoint, axis: JointAxis, target: f64, hz: f64, z: f64| {
        let (k, c) = acceleration_spring(hz, z);
        g.set_motor_model(axis, MotorModel::AccelerationBased);
        g.set_motor_position(axis, target, k, c);
    };
    // The separate motor row: same frames, nothing locked, only the motor.
    let motor_only = |g: &GenericJoint, axis: JointAxis, speed: f64, max: f64| {
        let mut m = GenericJoint {
            locked_axes: JointAxesMask::empty(),
            limit_axes: JointAxesMask::empty(),
            motor_axes: JointAxesMask::empty(),
            ..*g
        };
        velocity_motor(&mut m, axis, speed, max);
        m
    };
    let mut extra = None;
    match &j.kind {
        JointKind::Revolute(r) => {
            g.lock_axes(JointAxesMask::LOCKED_REVOLUTE_AXES);
            g.local_frame1 = Pose::from_parts(la, Rotation::new(r.reference_angle));
            g.local_frame2 = Pose::from_parts(lb, Rotation::new(0.0));
            if let Some(l) = r.limits {
                g.set_limits(JointAxis::AngX, l);
            }
            match (r.spring, r.motor) {
                (Some(s), motor) => {
                    spring_motor(&mut g, JointAxis::AngX, s.target, s.hertz, s.damping_ratio);
                    extra = motor.map(|m| motor_only(&g, JointAxis::AngX, m.speed, m.max_force));
                }
                (None, Some(m)) => velocity_motor(&mut g, JointAxis::AngX, m.speed, m.max_force),
                (None, None) => {}
            }
        }
        JointKind::Prismatic(p) => {
            g.lock_axes(JointAxesMask::LOCKED_PRISMATIC_AXES);
            let n = p.axis[0].hypot(p.axis[1]);
            let axis = [p.axis[0] / n, p.axis[1] / n];
            g.local_frame1.translation = la;
            g.local_frame2.translation = lb;
            g.set_local_axis1(vector(pa.direction_to_local(axis)));
            g.set_local_axis2(vector(pb.direction_to_local(axis)));
            if let Some(l) = p.limits {
                g.set_limits(JointAxis::LinX, l);
            }
            match (p.spring, p.motor) {
                (Some(s), motor) => {
                    spring_motor(&mut g, JointAxis::LinX, s.target, s.hertz, s.damping_ratio);
                    extra = motor.map(|m| motor_only(&g, JointAxis::LinX, m.speed, m.max_force));
                }
                (None, Some(m)) => velocity_motor(&mut g, JointAxis::LinX, m.speed, m.max_force),
                (None, None) => {}
            }
        }
        JointKind::Weld(w) => {
            g.lock_axes(JointAxesMask::LOCKED_FIXED_AXES);
            g.local_frame1 = Pose::from_parts(la, Rotation::new(-pa.angle));
            g.local_frame2 = Pose::from_parts(lb, Rotation::new(-pb.angle));
            if let Some(s) = w.softness {
                g.softness = SpringCoefficients::new(s.hertz, s.damping_ratio);
            }
        }
        JointKind::Wheel(w) => {
            // The prismatic's frames with the rotation free: only the
            // linear axis across the suspension is locked.
            g.lock_axes(JointAxesMask::LIN_Y);
            let n = w.axis[0].hypot(w.axis[1]);
            let axis = [w.axis[0] / n, w.axis[1] / n];
            g.local_frame1.translation = la;
            g.local_frame2.translation = lb;
            g.set_local_axis1(vector(pa.direction_to_local(axis)));
            g.set_local_axis2(vector(pb.direction_to_local(axis)));
            if let Some(l) = w.limits {
                g.set_limits(JointAxis::LinX, l);
            }
            if let Some(s) = w.spring {
                spring_motor(&mut g, JointAxis::LinX, 0.0, s.hertz, s.damping_ratio);
            }
            if let Some(m) = w.motor {
                velocity_motor(&mut g, JointAxis::AngX, m.speed, m.max_force);
            }
        }
        JointKind::Motor(m) => {
            // Nothing locked: a position motor on each axis of frame 1
            // (at the offset, turned by the angular offset) toward frame
            // 2 (B's centre), each bounded by the largest force or torque
            // (rapier bounds each axis: the linear force up to √2 F_max).
            let target = [la.x + m.linear_offset[0], la.y + m.linear_offset[1]];
            g.local_frame1 = Pose::from_parts(vector(target), Rotation::new(m.angular_offset));
            g.local_frame2 = Pose::from_parts(lb, Rotation::new(0.0));
            for axis in [JointAxis::LinX, JointAxis::LinY] {
                spring_motor(&mut g, axis, 0.0, m.linear.hertz, m.linear.damping_ratio);
                g.set_motor_max_force(axis, m.max_force);
            }
            spring_motor(
                &mut g,
                JointAxis::AngX,
                0.0,
                m.angular.hertz,
                m.angular.damping_ratio,
            );
            g.set_motor_max_force(JointAxis::AngX, m.max_torque);
        }
        JointKind::Distance(d) => {
            g.coupled_axes = JointAxesMask::LIN_AXES;
            g.local_frame1.translation = la;
            g.local_frame2.translation = lb;
            let no_minimum = |min: f64| {
                if min > 0.0 {
                    Err(refused(
                        i,
                        format!(
                            "minimum length {min} m: rapier's coupled distance limit \
                             only stops the maximum"
                        ),
                    ))
                } else {
                    Ok(())
                }
            };
            match d.mode {
                DistanceMode::Rigid { length } => {
                    let s = SpringCoefficients::<f64>::joint_defaults();
                    spring_motor(
                        &mut g,
                        JointAxis::LinX,
                        length,
                        s.natural_frequency,
                        s.damping_ratio,
                    );
                }
                DistanceMode::Rope {
                    min_length,
                    max_length,
                } => {
                    no_minimum(min_length)?;
                    g.set_limits(JointAxis::LinX, [0.0, max_length]);
                }
                DistanceMode::Spring { spring, limits } => {
                    spring_motor(
                        &mut g,
                        JointAxis::LinX,
                        spring.target,
                        spring.hertz,
                        spring.damping_ratio,
                    );
                    if let Some([lo, hi]) = limits {
                        no_minimum(lo)?;
                        g.set_limits(JointAxis::LinX, [0.0, hi]);
                    }
                }
            }
        }
    }
    Ok((g, extra))
}

/// Rapier's interaction groups for each body of `bodies`, implementing
/// "same group never collides" (see the module documentation).
pub(super) fn interaction_groups(
    bodies: &[SceneBody],
) -> Result<Vec<InteractionGroups>, ManyBodyError> {
    let mut seen: Vec<u32> = Vec::new();
    bodies
        .iter()
        .enumerate()
        .map(|(i, b)| match b.collision_group {
            None => Ok(InteractionGroups::new(
                Group::ALL,
                Group::ALL,
                InteractionTestMode::And,
            )),
            Some(g) => {
                let bit = match seen.iter().position(|&s| s == g) {
                    Some(k) => k,
                    None => {
                        seen.push(g);
                        seen.len() - 1
                    }
                };
                if bit >= 32 {
                    return Err(ManyBodyError::BodyRefused {
                        engine: ENGINE,
                        body: i,
                        message: format!(
                            "collision group {g} is the 33rd distinct group; rapier has 32 \
                             interaction groups"
                        ),
                    });
                }
                let member = Group::from_bits_truncate(1 << bit);
                Ok(InteractionGroups::new(
                    member,
                    Group::ALL.difference(member),
                    InteractionTestMode::And,
                ))
            }
        })
        .collect()
}
