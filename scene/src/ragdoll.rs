//! The `ragdoll` generator: Box2D's "human" (its samples' ragdoll and the
//! `rain` benchmark's, `shared/human.c`): 11 bones on 10 revolute joints,
//! each joint with Box2D's angle limits, a motor at speed 0 whose largest
//! torque is the joint friction (scaled per bone), and a rotational spring.
//!
//! Box2D's bones are capsules; this engine has none, so each is a convex
//! octagon: the capsule's straight sides and, at each end, the three
//! chords of its half circle at 0°, 60°, 120°, 180° (area about 95 % of
//! the capsule's for these proportions, so the bones are a little
//! lighter). A lower leg carries its foot (Box2D's hull, without its
//! 1.5 cm rounding) as a second part. The bones of one ragdoll share a
//! collision group, so they never collide with each other (Box2D's
//! negative group index); Box2D's feet also ignore other ragdolls, and
//! its heads and lower arms have linear damping: not here. All bones of a
//! ragdoll start upright at rest (or at the generator's velocity).

use crate::Colour;
use crate::build::{Checked, non_negative, positive};
use crate::error::{FieldPath, Problem};
use crate::generate::generated_body;
use engine::{
    BodyDef, BodyId, BodyState, Compound, CompoundPart, ConvexPolygon, JointDef, JointSpring,
    Revolute, RevoluteMotor, Shape,
};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// Bones per ragdoll.
pub const BONES: usize = 11;

/// Box2D's colours: trousers, shirt, skin.
const PANTS: Colour = Colour::rgb(0x1e, 0x90, 0xff);
const SHIRT: Colour = Colour::rgb(0x48, 0xd1, 0xcc);
const SKIN: Colour = Colour::rgb(0xff, 0xde, 0xad);

/// One bone at scale 1 (m), in Box2D's body frame: the body origin's
/// height above the ragdoll's position, the capsule's segment ends and
/// radius, whether it carries a foot; its joint to its parent.
struct Bone {
    name: &'static str,
    height: f64,
    capsule: (f64, f64, f64),
    foot: bool,
    colour: Colour,
    joint: Option<BoneJoint>,
}

/// A bone's joint: the parent bone, the pivot's height, the limits (in
/// units of π), the share of the joint friction, the reference angle.
struct BoneJoint {
    parent: usize,
    pivot: f64,
    limits: (f64, f64),
    friction_scale: f64,
    reference: f64,
}

const fn bone(
    name: &'static str,
    height: f64,
    capsule: (f64, f64, f64),
    colour: Colour,
    joint: Option<BoneJoint>,
) -> Bone {
    Bone {
        name,
        height,
        capsule,
        foot: false,
        colour,
        joint,
    }
}

const fn hinge(parent: usize, pivot: f64, limits: (f64, f64), friction_scale: f64) -> BoneJoint {
    BoneJoint {
        parent,
        pivot,
        limits,
        friction_scale,
        reference: 0.0,
    }
}

/// The bones in Box2D's order (`human.h`): hip, torso, head, upper and
/// lower left leg, upper and lower right leg, upper and lower left arm,
/// upper and lower right arm.
const SKELETON: [Bone; BONES] = [
    bone("hip", 0.95, (-0.02, 0.02, 0.095), PANTS, None),
    bone(
        "torso",
        1.2,
        (-0.135, 0.135, 0.09),
        SHIRT,
        Some(hinge(0, 1.0, (-0.25, 0.0), 0.5)),
    ),
    bone(
        "head",
        1.475,
        (-0.038, 0.039, 0.075),
        SKIN,
        Some(hinge(1, 1.4, (-0.3, 0.1), 0.25)),
    ),
    bone(
        "upper_left_leg",
        0.775,
        (-0.125, 0.125, 0.06),
        PANTS,
        Some(hinge(0, 0.9, (-0.05, 0.4), 1.0)),
    ),
    Bone {
        foot: true,
        ..bone(
            "lower_left_leg",
            0.475,
            (-0.155, 0.125, 0.045),
            PANTS,
            Some(hinge(3, 0.625, (-0.5, -0.02), 0.5)),
        )
    },
    bone(
        "upper_right_leg",
        0.775,
        (-0.125, 0.125, 0.06),
        PANTS,
        Some(hinge(0, 0.9, (-0.05, 0.4), 1.0)),
    ),
    Bone {
        foot: true,
        ..bone(
            "lower_right_leg",
            0.475,
            (-0.155, 0.125, 0.045),
            PANTS,
            Some(hinge(5, 0.625, (-0.5, -0.02), 0.5)),
        )
    },
    bone(
        "upper_left_arm",
        1.225,
        (-0.125, 0.125, 0.035),
        SHIRT,
        Some(hinge(1, 1.35, (-0.1, 0.8), 0.5)),
    ),
    bone(
        "lower_left_arm",
        0.975,
        (-0.125, 0.125, 0.03),
        SKIN,
        Some(BoneJoint {
            reference: 0.25,
            ..hinge(7, 1.1, (-0.2, 0.3), 0.1)
        }),
    ),
    bone(
        "upper_right_arm",
        1.225,
        (-0.125, 0.125, 0.035),
        SHIRT,
        Some(hinge(1, 1.35, (-0.1, 0.8), 0.5)),
    ),
    bone(
        "lower_right_arm",
        0.975,
        (-0.125, 0.125, 0.03),
        SKIN,
        Some(BoneJoint {
            reference: 0.25,
            ..hinge(9, 1.1, (-0.2, 0.3), 0.1)
        }),
    ),
];

/// A vertical capsule from y0 to y1 of radius r as a convex octagon (m).
fn capsule(y0: f64, y1: f64, r: f64) -> engine::Result<ConvexPolygon> {
    let (c, s) = (0.5 * r, 0.5 * 3f64.sqrt() * r);
    ConvexPolygon::new(vec![
        Vector2::new(r, y0),
        Vector2::new(r, y1),
        Vector2::new(c, y1 + s),
        Vector2::new(-c, y1 + s),
        Vector2::new(-r, y1),
        Vector2::new(-r, y0),
        Vector2::new(-c, y0 - s),
        Vector2::new(c, y0 - s),
    ])
}

/// A bone's shape at scale `k`, in Box2D's body frame (not centred).
fn bone_shape(b: &Bone, k: f64) -> engine::Result<Shape> {
    let (y0, y1, r) = b.capsule;
    let leg = capsule(k * y0, k * y1, k * r)?;
    if !b.foot {
        return Ok(Shape::Polygon(leg));
    }
    let foot = ConvexPolygon::convex_hull(&[
        Vector2::new(-0.03 * k, -0.185 * k),
        Vector2::new(0.11 * k, -0.185 * k),
        Vector2::new(0.11 * k, -0.16 * k),
        Vector2::new(-0.03 * k, -0.14 * k),
    ])?;
    let part = |p: ConvexPolygon| CompoundPart::new(Vector2::zeros(), 0.0, Shape::Polygon(p));
    Ok(Shape::Compound(Compound::new(vec![part(leg), part(foot)])?))
}

/// The centroid of a shape in its own frame (m).
fn centroid(shape: &Shape) -> Vector2<f64> {
    shape.frame_centroid().unwrap_or_else(Vector2::zeros)
}

/// What a ragdoll generator asks for, checked by the caller except the
/// joint parameters.
pub(crate) struct RagdollSpec {
    pub(crate) scale: f64,
    pub(crate) joint_friction: f64,
    pub(crate) joint_hertz: f64,
    pub(crate) joint_damping_ratio: f64,
    pub(crate) density: f64,
    pub(crate) velocity: Vector2<f64>,
}

/// One ragdoll standing at `position` (m), its bones bodies `first` … of
/// the world, named `{prefix}_{bone}`, in collision group `group`:
/// (bodies, their colours, joints).
pub(crate) fn expand(
    path: &FieldPath,
    spec: &RagdollSpec,
    position: Vector2<f64>,
    (prefix, first, group): (&str, BodyId, u32),
) -> Checked<(Vec<BodyDef>, Vec<Colour>, Vec<JointDef>)> {
    let k = positive(&path.key("scale"), spec.scale, "scale", "")?;
    let friction = non_negative(
        &path.key("joint_friction"),
        spec.joint_friction,
        "joint_friction",
        "N·m",
    )?;
    let hertz = non_negative(
        &path.key("joint_hertz"),
        spec.joint_hertz,
        "joint_hertz",
        "Hz",
    )?;
    let zeta = non_negative(
        &path.key("joint_damping_ratio"),
        spec.joint_damping_ratio,
        "joint_damping_ratio",
        "",
    )?;
    let mut bodies = Vec::with_capacity(BONES);
    let mut colours = Vec::with_capacity(BONES);
    let mut joints = Vec::with_capacity(BONES - 1);
    for (i, b) in SKELETON.iter().enumerate() {
        let shape = bone_shape(b, k).map_err(|e| Problem::engine(path, e))?;
        let origin = position + Vector2::new(0.0, k * b.height);
        let state = BodyState {
            position: origin + centroid(&shape),
            angle: 0.0,
            velocity: spec.velocity,
            angular_velocity: 0.0,
        };
        bodies.push(
            generated_body(
                format!("{prefix}_{}", b.name),
                shape,
                (spec.density, false),
                state,
            )
            .with_collision_group(group),
        );
        colours.push(b.colour);
        let Some(j) = &b.joint else {
            continue;
        };
        let torque = j.friction_scale * friction * k;
        let revolute = Revolute {
            limits: Some((j.limits.0 * PI, j.limits.1 * PI)),
            motor: (torque > 0.0).then_some(RevoluteMotor {
                speed: 0.0,
                max_torque: torque,
            }),
            spring: (hertz > 0.0).then_some(JointSpring::new(hertz, zeta)),
            spring_target: 0.0,
        };
        let pivot = position + Vector2::new(0.0, k * j.pivot);
        joints.push(
            JointDef::revolute(
                &format!("{prefix}_{}_joint", b.name),
                Some(first + j.parent),
                Some(first + i),
                pivot,
                revolute,
            )
            .with_reference_angle(j.reference * PI),
        );
    }
    Ok((bodies, colours, joints))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ragdoll_has_eleven_bones_on_ten_joints_within_their_limits() {
        let spec = RagdollSpec {
            scale: 1.0,
            joint_friction: 0.05,
            joint_hertz: 5.0,
            joint_damping_ratio: 0.5,
            density: 1.0,
            velocity: Vector2::zeros(),
        };
        let path = FieldPath::root().key("generate").index(0);
        let (bodies, colours, joints) =
            expand(&path, &spec, Vector2::new(1.0, 0.0), ("doll", 5, 5)).unwrap();
        assert_eq!((bodies.len(), colours.len(), joints.len()), (11, 11, 10));
        // Every joint's parent comes before its child, and the bones hang
        // from the hip.
        for j in &joints {
            assert!(j.body_a.unwrap() < j.body_b.unwrap());
        }
        assert_eq!(joints[0].body_a, Some(5));
        // The head is the highest bone, the lower legs the lowest.
        let y = |name: &str| {
            bodies
                .iter()
                .find(|b| b.name == format!("doll_{name}"))
                .unwrap()
                .state
                .position
                .y
        };
        assert!(y("head") > y("torso") && y("lower_left_leg") < y("upper_left_leg"));
        // The hip's octagon (Box2D's frame, not centred) tops out at its
        // upper chord, 0.02 + (√3/2) × 0.095 m.
        let Some(Shape::Polygon(hip)) = &bodies[0].shape else {
            panic!("the hip is a polygon");
        };
        let top = hip.vertices().iter().map(|v| v.y).fold(f64::MIN, f64::max);
        assert!((top - (0.02 + 0.5 * 3f64.sqrt() * 0.095)).abs() < 1e-12);
    }
}
