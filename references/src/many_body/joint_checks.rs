//! Joint descriptions without dynamics: the joint scenes' layouts against
//! Box2D's sources, validation errors, what each engine refuses, the
//! collision groups, and the joint-state readings on known poses.

use super::joint_tests::{dropped_ragdoll, engines, pendulum};
use super::*;
use crate::box2d_world::Box2dWorld;
use crate::rapier_many::RapierManyWorld;
use std::f64::consts::PI;

/// A free revolute joint at the origin, changed by `f`.
fn revolute_with(f: impl FnOnce(&mut RevoluteJoint)) -> JointKind {
    let mut r = RevoluteJoint {
        anchor_a: [0.0, 0.0],
        anchor_b: [0.0, 0.0],
        reference_angle: 0.0,
        limits: None,
        motor: None,
        spring: None,
    };
    f(&mut r);
    JointKind::Revolute(r)
}

/// `pendulum(1, 10°)` with its joint replaced by `kind`.
fn with_joint(kind: JointKind) -> ManyBodyScene {
    let mut scene = pendulum(1.0, 0.1, 4, false);
    scene.joints[0].kind = kind;
    scene
}

#[test]
fn joint_scenes_have_box2d_layouts() {
    // joint_grid(20), Box2D's debug size: 400 circles, 7 static in the
    // top row, 2·20·19 joints less the 6 between static neighbours.
    let g = joint_grid(20);
    g.validate().unwrap();
    assert_eq!(g.bodies.len(), 400);
    let fixed: Vec<usize> = (0..400)
        .filter(|&i| g.bodies[i].kind == BodyKind::Static)
        .collect();
    assert_eq!(fixed, (7..=13).map(|k| k * 20).collect::<Vec<_>>());
    assert_eq!(g.joints.len(), 2 * 20 * 19 - 6);
    assert_eq!(g.bodies[21].position, [1.0, -1.0]);
    assert!(g.bodies.iter().all(|b| b.collision_group == Some(0)));
    // Every anchor midway between its two circles.
    for j in &g.joints {
        let (a, b) = (
            g.bodies[j.body_a.unwrap()].position,
            g.bodies[j.body_b.unwrap()].position,
        );
        let (p, _) = j.anchors();
        assert_eq!(p, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
    }
    // The ragdoll: 11 bones, 10 joints to their parents, Box2D's limits.
    let r = dropped_ragdoll();
    assert_eq!((r.bodies.len(), r.joints.len()), (1 + scenes::BONES, 10));
    let parents: Vec<usize> = r.joints.iter().map(|j| j.body_a.unwrap() - 1).collect();
    assert_eq!(parents, vec![0, 1, 0, 3, 0, 5, 1, 7, 1, 9]);
    match r.joints[7].kind {
        JointKind::Revolute(j) => {
            assert_eq!(j.reference_angle, 0.25 * PI);
            assert_eq!(j.limits, Some([-0.2 * PI, 0.3 * PI]));
            assert_eq!(j.motor.unwrap().max_force, 0.1 * 0.05);
            assert_eq!(j.spring.unwrap().hertz, 5.0);
        }
        _ => panic!("revolute expected"),
    }
    // Total mass: Box2D's capsules less their caps' missing area.
    let mass: f64 = r.bodies[1..].iter().map(SceneBody::mass).sum();
    assert!(mass > 0.3 && mass < 0.45, "{mass}");
    // rain at Box2D's debug size: 3 rows of 201 tiles, 60 ragdolls.
    let rain = scenes::rain(&scenes::RainParams::BOX2D_DEBUG);
    rain.validate().unwrap();
    assert_eq!(rain.bodies.len(), 3 * 201 + 60 * scenes::BONES);
    assert_eq!(rain.joints.len(), 60 * 10);
    let first = 3 * 201;
    assert_eq!(rain.bodies[first].collision_group, Some(1));
    assert_eq!(rain.bodies[first + scenes::BONES].collision_group, Some(2));
    assert_eq!(
        rain.bodies[first + 2 * scenes::BONES].collision_group,
        Some(1)
    );
    // Falling Hinges: 1 ground + 80 boxes, 40 hinges, pairs (even, odd).
    let f = falling_hinges();
    assert_eq!((f.bodies.len(), f.joints.len()), (81, 40));
    assert_eq!((f.joints[0].body_a, f.joints[0].body_b), (Some(1), Some(2)));
    assert_eq!(f.bodies[2].angle, 0.1);
}

#[test]
fn rain_builds_and_steps_in_both_engines() {
    // Box2D's debug-build size (660 bones, 603 tiles): built, two steps.
    let scene = scenes::rain(&scenes::RainParams::BOX2D_DEBUG);
    for mut e in engines(&scene) {
        e.step().unwrap();
        e.step().unwrap();
        let mut out = Vec::new();
        e.samples(&mut out).unwrap();
        // Free fall for 2 steps: the hip has dropped by the substeps'
        // symplectic-Euler sum g h² (1 + 2 + … + 8) = 36 g h² = 6.25 mm;
        // the joints settling the lower arms into their limits move it by
        // less than 1 mm.
        let k = 3 * 201;
        let drop = scene.bodies[k].position[1] - out[k].position[1];
        assert!(
            (drop - 10.0 * (1.0f64 / 240.0).powi(2) * 36.0).abs() < 1e-3,
            "{drop}"
        );
    }
}

#[test]
fn bodies_of_one_group_do_not_collide() {
    // Two overlapping boxes resting on the ground: in one group they pass
    // through each other (stay overlapped, no push), in different groups
    // they are pushed apart.
    for same in [true, false] {
        let mut scene = super::scenes::pyramid(0);
        for x in [0.0, 0.3] {
            let mut b = SceneBody::dynamic(Shape::rectangle(1.0, 1.0).unwrap(), [x, 0.5], 1.0);
            b.collision_group = Some(if same || x == 0.0 { 7 } else { 8 });
            scene.bodies.push(b);
        }
        for mut e in engines(&scene) {
            let mut out = Vec::new();
            for _ in 0..30 {
                e.step().unwrap();
            }
            e.samples(&mut out).unwrap();
            let gap = out[2].position[0] - out[1].position[0];
            if same {
                // No contact between them: they sit on the ground where
                // they were (f32: a few spacings of 0.3 m).
                assert!((gap - 0.3).abs() < 1e-6, "{}: {gap}", e.name());
            } else {
                assert!(gap > 0.5, "{}: {gap}", e.name());
            }
        }
    }
}

#[test]
fn bad_joints_are_refused_naming_the_joint_and_the_field() {
    let check = |scene: ManyBodyScene, needle: &str| {
        let e = scene.validate().unwrap_err().to_string();
        assert!(
            e.starts_with("many-body scene, joint 0: ") && e.contains(needle),
            "{e}"
        );
    };
    let mut s = pendulum(1.0, 0.1, 4, false);
    s.joints[0].body_b = Some(3);
    check(s, "body B = 3 names no body");
    let mut s = pendulum(1.0, 0.1, 4, false);
    s.joints[0].body_a = Some(0);
    check(s, "must differ from body A");
    let mut s = pendulum(1.0, 0.1, 4, false);
    s.bodies[0] = SceneBody::fixed(Shape::circle(0.1).unwrap(), [0.0, -1.0]);
    check(s, "at least one dynamic body");
    check(
        with_joint(revolute_with(|r| r.limits = Some([0.5, -0.5]))),
        "angle limits = 0.5 lower bound must not exceed",
    );
    check(
        with_joint(revolute_with(|r| r.limits = Some([-4.0, 0.0]))),
        "must lie in [-pi, pi]",
    );
    check(
        with_joint(revolute_with(|r| {
            r.spring = Some(Spring {
                hertz: -1.0,
                damping_ratio: 0.5,
                target: 0.0,
            })
        })),
        "spring frequency (Hz) = -1",
    );
    check(
        with_joint(revolute_with(|r| {
            r.motor = Some(Motor {
                speed: 1.0,
                max_force: -2.0,
            })
        })),
        "motor maximum force or torque = -2",
    );
    check(
        with_joint(revolute_with(|r| r.anchor_b = [f64::NAN, 0.0])),
        "anchor B x = NaN must be finite",
    );
    let mut s = pendulum(1.0, 0.1, 4, false);
    s.joints[0] = SceneJoint::prismatic(None, Some(0), [0.0, 0.0], [0.0, 0.0]);
    check(s, "axis length = 0 must be > 0");
    let rope = |min_length, max_length| {
        JointKind::Distance(DistanceJoint {
            anchor_a: [0.0, 0.0],
            anchor_b: [0.0, -1.0],
            mode: DistanceMode::Rope {
                min_length,
                max_length,
            },
        })
    };
    check(with_joint(rope(1.2, 1.0)), "rope lengths = 1.2 lower bound");
    check(with_joint(rope(-0.5, 1.0)), "need 0 <= minimum");
    let mut s = pendulum(1.0, 0.1, 4, false);
    s.joints[0] = SceneJoint::rod(None, Some(0), [0.0, 0.0], [0.0, 0.0]);
    check(s, "distance between the anchors at t = 0 = 0 must be > 0");
    // Valid joints of every kind pass.
    for kind in [
        rope(0.0, 1.0),
        JointKind::Weld(WeldJoint {
            anchor: [0.0, 0.0],
            softness: Some(Softness {
                hertz: 5.0,
                damping_ratio: 0.7,
            }),
        }),
    ] {
        with_joint(kind).validate().unwrap();
    }
}

#[test]
fn each_engine_refuses_what_it_cannot_represent() {
    // Box2D takes revolute limits within ±0.99π.
    let s = with_joint(revolute_with(|r| r.limits = Some([-3.12, 0.0])));
    s.validate().unwrap();
    let e = Box2dWorld::new(&s).err().unwrap().to_string();
    assert!(
        e.contains("cannot represent joint 0") && e.contains("0.99 pi"),
        "{e}"
    );
    assert!(RapierManyWorld::new(&s).is_ok());
    // rapier's coupled distance limit has no minimum.
    let s = with_joint(JointKind::Distance(DistanceJoint {
        anchor_a: [0.0, 0.0],
        anchor_b: [0.0, -1.0],
        mode: DistanceMode::Rope {
            min_length: 0.5,
            max_length: 1.0,
        },
    }));
    let e = RapierManyWorld::new(&s).err().unwrap().to_string();
    assert!(
        e.contains("cannot represent joint 0") && e.contains("minimum length"),
        "{e}"
    );
    assert!(Box2dWorld::new(&s).is_ok());
    // rapier has 32 interaction groups.
    let mut s = super::scenes::pyramid(0);
    for g in 0..33u32 {
        let mut b = SceneBody::dynamic(Shape::circle(0.1).unwrap(), [g as f64, 1.0], 1.0);
        b.collision_group = Some(g);
        s.bodies.push(b);
    }
    let e = RapierManyWorld::new(&s).err().unwrap().to_string();
    assert!(
        e.contains("body 33") && e.contains("32 interaction groups"),
        "{e}"
    );
    assert!(Box2dWorld::new(&s).is_ok());
}

#[test]
fn joint_state_readings_are_zero_at_t0_and_exact_for_known_poses() {
    // At t = 0 every coincident joint reads 0 separation, and the ragdoll's
    // lower arms read their reference offset (−π/4) below 0.
    let r = dropped_ragdoll();
    let start: Vec<BodySample> = r
        .bodies
        .iter()
        .map(|b| BodySample {
            position: b.position,
            angle: b.angle,
            ..Default::default()
        })
        .collect();
    let states = r.joint_states(&start);
    assert!(states.iter().all(|s| s.separation < 1e-15));
    crate::test_support::assert_close(states[7].coordinate, -0.25 * PI, 1e-15, "lower arm");
    crate::test_support::assert_close(states[7].limit_violation, 0.05 * PI, 1e-15, "violation");
    // A prismatic joint along (1, 1)/√2: moving body B by (0.3, 0.3) + (0.1, −0.1)
    // and turning it by 0.2 rad reads translation 0.3√2, perpendicular
    // separation 0.1√2, angular error 0.2.
    let mut s = pendulum(1.0, 0.1, 4, false);
    s.joints[0] = SceneJoint::prismatic(None, Some(0), s.bodies[0].position, [1.0, 1.0]);
    let p0 = s.bodies[0].position;
    let moved = [BodySample {
        position: [p0[0] + 0.4, p0[1] + 0.2],
        angle: 0.2,
        ..Default::default()
    }];
    let j = s.joint_states(&moved)[0];
    let r2 = 2f64.sqrt();
    // The anchor is the body origin, so rotation does not move it.
    crate::test_support::assert_close(j.coordinate, 0.3 * r2, 1e-15, "translation");
    crate::test_support::assert_close(j.separation, 0.1 * r2, 1e-15, "perpendicular");
    crate::test_support::assert_close(j.angular_error, 0.2, 1e-15, "angle");
}
