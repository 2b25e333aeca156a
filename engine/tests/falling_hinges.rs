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
//! The world's state hash at rest ([`World::state_hash`]: every body's
//! final pose bits) and the step at which all came to rest are asserted against constants (in `falling_hinges/expected.rs`,
//! shared with the scene crate's test of `scenes/falling_hinges.toml` and
//! the harness's main run), so that any change to the soft step's results
//! (joints or contacts) is seen.

use etalon2d::prelude::*;
use std::f64::consts::PI;

// The expected values are shared with the harness and the scene tests,
// which name this crate `engine`.
use etalon2d as engine;
include!("falling_hinges/expected.rs");

fn falling_hinges() -> World {
    falling_hinges_on(1)
}

/// The scene, stepped on `threads` threads.
fn falling_hinges_on(threads: usize) -> World {
    let settings = SoftStepSettings {
        sleeping: true,
        threads,
        // On the threads however small the scene: what is compared.
        min_work_per_thread: 0,
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

/// Steps until every box sleeps; returns the step count then and the
/// hash of the poses.
fn run_to_rest_hashed() -> (usize, u64) {
    let mut world = falling_hinges();
    let step = run_to_rest(&mut world).expect("the falling hinges come to rest within 2000 steps");
    (step, world.state_hash())
}

#[test]
fn the_falling_hinges_come_to_rest_with_the_same_bits() {
    let first = run_to_rest_hashed();
    assert_eq!(
        first,
        run_to_rest_hashed(),
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

#[test]
fn the_falling_hinges_give_the_same_bits_on_1_2_3_and_4_threads() {
    // Every step's pose hash, until the boxes rest (the serial run's rest
    // step), on 1 to 4 threads: the parallel stages must give the serial
    // stages' bits (docs/soft_step.md, "Threads").
    // One world at a time (its pool's workers stay busy between steps;
    // several pools alive at once would oversubscribe the machine's cores),
    // every step's hash compared with the serial run's.
    let hashes_on = |threads: usize| -> Vec<u64> {
        let mut world = falling_hinges_on(threads);
        let hashes = (0..=REST_STEP)
            .map(|_| {
                world.step(1.0 / 60.0).unwrap();
                world.state_hash()
            })
            .collect();
        assert!((1..world.bodies().len()).all(|id| world.is_asleep(id)));
        hashes
    };
    let serial = hashes_on(1);
    for threads in 2..=4 {
        let parallel = hashes_on(threads);
        if let Some(step) = (0..serial.len()).find(|&k| parallel[k] != serial[k]) {
            panic!("step {step}: {threads} threads differ from 1");
        }
    }
}
