//! Determinism with joints, after Box2D's "Falling Hinges" test
//! (`test/test_determinism.c`, scene in `shared/determinism.c`): 4
//! columns of 20 boxes of 0.5 m, each tilted by ±0.1 rad, each column
//! offset sideways by 0.1 m per box, boxes 2k and 2k + 1 of a column
//! joined at a corner by a revolute joint with limits [−0.1π, 0.2π], a
//! 1 Hz spring (ζ = 1), a motor of 0.25 N·m at speed 0 (joint friction)
//! and rigid rows at 60 Hz, ζ = 0, falling onto the ground with sleeping
//! on until every box sleeps. Box2D's full size, in f64, with plain boxes
//! instead of its rounded ones (radius 0.025 m): debug builds run it in
//! about a second.
//!
//! The hash of every box's final pose bits and the step at which all came
//! to rest is asserted against constants, so that any change to the soft
//! step's results (joints or contacts) is seen. The same scene is
//! `scenes/falling_hinges.toml` (checked to give these constants by the
//! scene crate's tests).

use engine::prelude::*;
use std::f64::consts::PI;

/// The step (0-based count of steps taken) at which every box slept.
const REST_STEP: usize = 276;
/// FNV-1a of the final poses (x, y, angle bits of every box in order).
const HINGES_HASH: u64 = 0xd725_f87a_6f54_95c1;

/// Where to update the constants, for the failure messages.
const UPDATE: &str = "if the soft step's results changed on purpose (a new solve order, a \
                      new default), update REST_STEP and HINGES_HASH in \
                      engine/tests/falling_hinges.rs and scene/tests/joints.rs from \
                      this message, and say why in the commit";

fn falling_hinges() -> World {
    let settings = SoftStepSettings {
        sleeping: true,
        ..SoftStepSettings::default()
    };
    let mut world =
        World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -1.0),
            Some(Shape::rectangle(80.0, 2.0).unwrap()),
        ))
        .unwrap();
    let (columns, rows, h) = (4, 20, 0.25);
    let dx = 10.0 * h;
    let x0 = -0.5 * dx * (columns as f64 - 1.0);
    let hinge = Revolute {
        limits: Some((-0.1 * PI, 0.2 * PI)),
        motor: Some(RevoluteMotor {
            speed: 0.0,
            max_torque: 0.25,
        }),
        spring: Some(JointSpring::new(1.0, 1.0)),
        spring_target: 0.0,
    };
    for column in 0..columns {
        let x = x0 + column as f64 * dx;
        let mut below = None;
        for row in 0..rows {
            let tilt = if row % 2 == 0 { -0.1 } else { 0.1 };
            let def = BodyDef {
                mass: None,
                density: Some(1.0),
                ..BodyDef::rigid("box", 1.0, Shape::rectangle(2.0 * h, 2.0 * h).unwrap())
            }
            .with_position(Vector2::new(
                x + 0.4 * h * row as f64,
                h + 2.0 * h * row as f64,
            ))
            .with_rotation(tilt, 0.0);
            let id = world.add_body(def).unwrap();
            match below.take() {
                None => below = Some(id),
                Some(a) => {
                    let joint =
                        JointDef::revolute("hinge", Some(a), Some(id), Vector2::zeros(), hinge)
                            .with_local_anchors(Vector2::new(-h, h), Vector2::new(-h, -h))
                            .with_constraint_softness(60.0, 0.0);
                    world.add_joint(joint).unwrap();
                }
            }
        }
    }
    world
}

/// Steps until every box sleeps (at most 2000 steps); returns the step
/// count then and the hash of the poses.
fn run_to_rest() -> (usize, u64) {
    let mut world = falling_hinges();
    let boxes = world.bodies().len();
    for step in 0..2000 {
        if (1..boxes).all(|id| world.is_asleep(id)) {
            return (step, pose_hash(&world));
        }
        world.step(1.0 / 60.0).unwrap();
    }
    panic!("the falling hinges did not come to rest in 2000 steps");
}

/// FNV-1a over the bits of every box's pose.
fn pose_hash(world: &World) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for s in &world.states()[1..] {
        for x in [s.position.x, s.position.y, s.angle] {
            for b in x.to_bits().to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

#[test]
fn the_falling_hinges_come_to_rest_with_the_same_bits() {
    let first = run_to_rest();
    assert_eq!(
        first,
        run_to_rest(),
        "two runs of the falling hinges differ: the soft step is not deterministic"
    );
    let (step, hash) = first;
    assert_eq!(
        (step, hash),
        (REST_STEP, HINGES_HASH),
        "the falling hinges came to rest at step {step} with pose hash {hash:#018x}; the test \
         expects step {REST_STEP} and {HINGES_HASH:#018x}: {UPDATE}"
    );
}
