//! The soft step's island membership, read through `World::islands` and
//! `World::island_of`: two stacks apart are two islands, touching bodies
//! share one, static bodies belong to none, a settled island reports
//! asleep, and the queries are refused where the engine keeps no islands.

use etalon2d::{
    BodyDef, ContactModel, ContactSettings, EngineError, Method, Shape, SoftStepSettings, World,
};
use nalgebra::Vector2;

const DT: f64 = 1.0 / 60.0;

fn world(sleeping: bool) -> World {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings {
            sleeping,
            ..SoftStepSettings::default()
        }),
    )
    .unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
}

fn unit_box(name: &str, x: f64, y: f64) -> BodyDef {
    BodyDef {
        mass: None,
        density: Some(1.0),
        ..BodyDef::rigid(name, 1.0, Shape::rectangle(1.0, 1.0).unwrap())
    }
    .with_position(Vector2::new(x, y))
}

/// A ground and two stacks of two boxes, 6 m apart (never touching).
fn two_stacks(world: &mut World) -> (usize, [usize; 2], [usize; 2]) {
    let ground = world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(20.0, 1.0).unwrap()),
        ))
        .unwrap();
    let left = [
        world.add_body(unit_box("l0", -3.0, 0.5)).unwrap(),
        world.add_body(unit_box("l1", -3.0, 1.5)).unwrap(),
    ];
    let right = [
        world.add_body(unit_box("r0", 3.0, 0.5)).unwrap(),
        world.add_body(unit_box("r1", 3.0, 1.5)).unwrap(),
    ];
    (ground, left, right)
}

#[test]
fn two_stacks_are_two_islands_that_fall_asleep() {
    let mut world = world(true);
    let (ground, left, right) = two_stacks(&mut world);
    // Before any step no contact touches: every dynamic body alone.
    assert_eq!(world.islands().unwrap().count(), 4);
    for _ in 0..5 {
        world.step(DT).unwrap();
    }
    // The boxes touch at rest from the first step (placed face to face).
    let island = |b| world.island_of(b).unwrap();
    assert_eq!(island(ground), None, "a static body belongs to no island");
    assert!(island(left[0]).is_some() && island(right[0]).is_some());
    assert_eq!(island(left[0]), island(left[1]), "touching: one island");
    assert_eq!(island(right[0]), island(right[1]), "touching: one island");
    assert_ne!(island(left[0]), island(right[0]), "apart: two islands");
    let islands: Vec<_> = world.islands().unwrap().collect();
    assert_eq!(islands.len(), 2);
    for i in &islands {
        let mut bodies = i.bodies.to_vec();
        bodies.sort_unstable();
        assert!(bodies == left || bodies == right, "{bodies:?}");
        assert!(!i.asleep, "0.08 s in: still settling");
    }
    // Time to sleep 0.5 s (the default) once both stacks are at rest:
    // asleep within 1.5 s, as engine/tests/soft_step.rs finds.
    for _ in 0..90 {
        world.step(DT).unwrap();
    }
    for i in world.islands().unwrap() {
        assert!(i.asleep, "island {:?} still awake", i.id);
        for &b in i.bodies {
            assert!(world.is_asleep(b), "the island's bodies sleep with it");
        }
    }
    assert_eq!(world.islands().unwrap().count(), 2);
    // A box dropped on the left stack wakes and joins its island only.
    let c = world.add_body(unit_box("c", -3.0, 4.0)).unwrap();
    for _ in 0..40 {
        world.step(DT).unwrap();
    }
    let left_island = world.island_of(left[0]).unwrap();
    assert_eq!(world.island_of(c).unwrap(), left_island);
    let state = |id| {
        world
            .islands()
            .unwrap()
            .find(|i| Some(i.id) == id)
            .map(|i| i.asleep)
    };
    assert_eq!(state(left_island), Some(false), "hit: awake");
    assert_eq!(state(world.island_of(right[0]).unwrap()), Some(true));
}

#[test]
fn islands_are_refused_where_the_engine_keeps_none() {
    let mut awake = world(false);
    two_stacks(&mut awake);
    assert!(matches!(
        awake.islands().err(),
        Some(EngineError::Unsupported { .. })
    ));
    assert!(matches!(
        awake.island_of(1),
        Err(EngineError::Unsupported { .. })
    ));
    let mut sleeping = world(true);
    two_stacks(&mut sleeping);
    assert!(matches!(
        sleeping.island_of(99),
        Err(EngineError::UnknownBody { index: 99, .. })
    ));
    let mut exact = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::Exact(ContactSettings::default()),
    )
    .unwrap();
    exact.add_body(unit_box("a", 0.0, 0.5)).unwrap();
    assert!(matches!(
        exact.island_of(0),
        Err(EngineError::Unsupported { .. })
    ));
}
