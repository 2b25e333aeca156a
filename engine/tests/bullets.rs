//! Bullets under the soft step (`engine/src/soft_step/bullets.rs`): a fast
//! box flagged `bullet` stops at a thin dynamic plate; without the flag it
//! passes through it in one step (the reason bullets exist); the bullet
//! pass gives the same bits on one and two threads; the runtime setter
//! refuses bad ids with a typed error and leaves the world intact.
//!
//! The scene (also `scenes/bullet_plate.toml`, the harness's case): a
//! 0.1 m box of 0.1 kg at 500 m/s along x, 2 m before a 5 cm thick, 1 m
//! tall plate of 50 kg standing on the ground. At dt = 1/60 s the box moves 8.33 m per step:
//! 167 plate thicknesses, so no discrete contact can see the plate.

use etalon2d::{
    BodyDef, BodyId, ContactModel, ContactSettings, EngineError, Method, Shape, SoftStepSettings,
    World,
};
use nalgebra::Vector2;

const DT: f64 = 1.0 / 60.0;
/// Plate thickness (m).
const PLATE: f64 = 0.05;
/// The box's side (m).
const SIDE: f64 = 0.1;

/// The world under the soft step on `threads` threads, and the ids of
/// the box and the plate.
fn plate_world(bullet: bool, threads: usize) -> (World, BodyId, BodyId) {
    let model = ContactModel::SoftStep(SoftStepSettings {
        threads,
        ..SoftStepSettings::default()
    });
    plate_world_under(model, Method::SemiImplicitEuler, bullet)
}

/// The world under `model` and `method`.
fn plate_world_under(model: ContactModel, method: Method, bullet: bool) -> (World, BodyId, BodyId) {
    let mut world = World::with_model(method, model).unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(40.0, 1.0).unwrap()),
        ))
        .unwrap();
    let plate = world
        .add_body(BodyDef {
            density: Some(1000.0),
            mass: None,
            ..BodyDef::rigid("plate", 1.0, Shape::rectangle(PLATE, 1.0).unwrap())
                .with_position(Vector2::new(0.0, 0.5))
        })
        .unwrap();
    let mut def = BodyDef {
        density: Some(10.0),
        mass: None,
        ..BodyDef::rigid("box", 1.0, Shape::rectangle(SIDE, SIDE).unwrap())
            .with_position(Vector2::new(-2.0, 0.5))
            .with_velocity(Vector2::new(500.0, 0.0))
    };
    def.bullet = bullet;
    let shot = world.add_body(def).unwrap();
    (world, shot, plate)
}

/// Steps `world` 30 times (0.5 s) and returns, per step, the box's centre
/// x minus the plate's centre x (m).
fn gaps(world: &mut World, shot: BodyId, plate: BodyId) -> Vec<f64> {
    (0..30)
        .map(|_| {
            world.step(DT).unwrap();
            let s = world.states();
            s[shot].position.x - s[plate].position.x
        })
        .collect()
}

/// Passing the plate means the box's centre crossing the plate's middle
/// plane (gap ≥ 0): a box stopped by the plate keeps its centre at least
/// half its side plus half the plate behind it, less the contact's
/// penetration (millimetres), so a gap below zero at every step is the
/// plain criterion with no tolerance to choose.
#[test]
fn a_bullet_stops_at_a_thin_dynamic_plate() {
    let (mut world, shot, plate) = plate_world(true, 1);
    let gaps = gaps(&mut world, shot, plate);
    for (k, gap) in gaps.iter().enumerate() {
        assert!(
            *gap < 0.0,
            "step {}: the bullet passed the plate (gap {gap} m)",
            k + 1
        );
    }
    // It did hit the plate (not merely fall short): the plate, 500 times
    // heavier, takes about 1 m/s from it (momentum 0.1 kg × 500 m/s over
    // 50.1 kg) and slides or tips: more than a centimetre in 0.5 s.
    let p = world.states()[plate];
    let moved = p.position.x.abs() + 0.5 * p.angle.abs();
    assert!(moved > 0.01, "the plate was not pushed: {moved} m");
}

/// The same box without the flag is swept against static shapes only and
/// jumps the plate in its first step: this test fails if anything else
/// starts stopping fast bodies at dynamic ones.
#[test]
fn a_box_that_is_not_a_bullet_passes_through_the_plate() {
    let (mut world, shot, plate) = plate_world(false, 1);
    let gaps = gaps(&mut world, shot, plate);
    assert!(gaps[0] > 5.0, "gap after one step {} m", gaps[0]);
    // Untouched, the plate only settles on its 5 cm foot (tens of
    // micrometres); the stopping hit of the test above moves it by
    // centimetres. A millimetre tells the two apart.
    let x = world.states()[plate].position.x;
    assert!(x.abs() < 1e-3, "the plate moved: {x} m");
}

/// Three bullets, a plate each, and a small pile (so that the pool has
/// shares to split): every state bit for bit the same on one and two
/// threads, every step.
#[test]
fn bullets_give_the_same_bits_on_one_and_two_threads() {
    let run = |threads: usize| {
        let (mut world, _, _) = plate_world(true, threads);
        for k in 1..3 {
            let y = 0.5 + 1.5 * k as f64;
            world
                .add_body(BodyDef {
                    density: Some(1000.0),
                    mass: None,
                    ..BodyDef::rigid("plate", 1.0, Shape::rectangle(PLATE, 1.0).unwrap())
                        .with_position(Vector2::new(0.3 * k as f64, y))
                })
                .unwrap();
            world
                .add_body(
                    BodyDef {
                        density: Some(10.0),
                        mass: None,
                        ..BodyDef::rigid("box", 1.0, Shape::rectangle(SIDE, SIDE).unwrap())
                            .with_position(Vector2::new(-3.0, y + 0.2))
                            .with_velocity(Vector2::new(400.0 + 50.0 * k as f64, -5.0))
                            .with_rotation(0.3, 20.0)
                    }
                    .as_bullet(),
                )
                .unwrap();
        }
        for k in 0..20 {
            world
                .add_body(
                    BodyDef::rigid("pile", 1.0, Shape::rectangle(0.4, 0.4).unwrap()).with_position(
                        Vector2::new(5.0 + 0.5 * (k % 5) as f64, 0.2 + 0.45 * (k / 5) as f64),
                    ),
                )
                .unwrap();
        }
        (0..40)
            .map(|_| {
                world.step(DT).unwrap();
                world
                    .states()
                    .iter()
                    .flat_map(|s| [s.position.x, s.position.y, s.angle, s.velocity.x])
                    .map(f64::to_bits)
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>()
    };
    let (one, two) = (run(1), run(2));
    for (k, (a, b)) in one.iter().zip(&two).enumerate() {
        assert_eq!(
            a,
            b,
            "step {}: the bits differ between 1 and 2 threads",
            k + 1
        );
    }
}

/// The flag set at run time acts at the next step; bad ids are refused
/// with a typed error and change nothing.
#[test]
fn the_runtime_setter_acts_and_refuses_bad_ids() {
    let (mut world, shot, plate) = plate_world(false, 1);
    assert!(!world.is_bullet(shot).unwrap());
    world.set_bullet(shot, true).unwrap();
    assert!(world.is_bullet(shot).unwrap());
    let gaps = gaps(&mut world, shot, plate);
    assert!(gaps.iter().all(|g| *g < 0.0), "gaps {gaps:?}");

    let hash = world.state_hash();
    assert!(matches!(
        world.set_bullet(99, true),
        Err(EngineError::UnknownBody { .. })
    ));
    world.set_enabled(plate, false).unwrap();
    assert!(world.set_bullet(plate, true).is_err());
    assert!(!world.is_bullet(plate).unwrap());
    world.set_enabled(plate, true).unwrap();
    assert_eq!(world.state_hash(), hash);
}

/// The exact model accepts the flag and ignores it: its swept contact
/// search (the default) finds the plate inside the step whether or not
/// the box is a bullet.
#[test]
fn the_exact_model_stops_the_box_with_or_without_the_flag() {
    for bullet in [false, true] {
        let (mut world, shot, plate) = plate_world_under(
            ContactModel::Exact(ContactSettings::default()),
            Method::Rk4,
            bullet,
        );
        assert_eq!(world.is_bullet(shot).unwrap(), bullet);
        let gaps: Vec<f64> = (0..3)
            .map(|_| {
                world.step(DT).unwrap();
                let s = world.states();
                s[shot].position.x - s[plate].position.x
            })
            .collect();
        assert!(
            gaps.iter().all(|g| *g < 0.0),
            "bullet {bullet}: gaps {gaps:?}"
        );
    }
}
