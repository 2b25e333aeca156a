//! Segments, capsules and rounded polygons at the world's door: a dynamic
//! body cannot take its mass from a segment; both contact models take
//! these shapes (the exact model collides them in `exact_rounded.rs`, the
//! soft step in `soft_step_rounded.rs`) and switching between the models
//! keeps the world; without contacts they integrate and world queries see
//! them.

use etalon2d::{
    BodyDef, ContactModel, ContactSettings, Method, QueryFilter, Shape, SoftStepSettings, World,
};
use nalgebra::Vector2;

fn ground() -> Shape {
    Shape::segment(Vector2::new(-5.0, 0.0), Vector2::new(5.0, 0.0)).unwrap()
}

#[test]
fn a_dynamic_segment_has_no_mass() {
    let mut world = World::new(Method::Rk4).unwrap();
    let err = world
        .add_body(BodyDef::rigid("rod", 1.0, ground()))
        .unwrap_err();
    assert!(err.to_string().contains("segment has no area"), "{err}");
    assert!(err.to_string().contains("'rod'"), "{err}");
    assert!(world.bodies().is_empty(), "a refused body is not added");
    // Static, it is fine; so is a dynamic one given a mass and an inertia.
    world
        .add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(ground())))
        .unwrap();
    let mut rod = BodyDef::rigid("rod", 1.0, ground());
    rod.inertia = Some(2.0);
    world.add_body(rod).unwrap();
}

#[test]
fn the_soft_step_takes_each_kind() {
    let mut soft = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    soft.add_body(BodyDef::rigid(
        "pill",
        1.0,
        Shape::capsule(1.0, 0.25).unwrap(),
    ))
    .unwrap();
    soft.add_body(BodyDef::rigid(
        "tile",
        1.0,
        Shape::rounded_box(1.0, 0.5, 0.05).unwrap(),
    ))
    .unwrap();
    soft.add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(ground())))
        .unwrap();
    assert_eq!(soft.bodies().len(), 3);
}

#[test]
fn both_models_take_a_capsule_and_switching_keeps_the_world() {
    // Without contacts the exact model integrates a capsule (it only gives
    // the body its mass properties).
    let mut world = World::new(Method::SemiImplicitEuler).unwrap();
    world.set_gravity(Vector2::new(0.0, -9.81)).unwrap();
    world
        .add_body(BodyDef::rigid(
            "pill",
            2.0,
            Shape::capsule(1.0, 0.25).unwrap(),
        ))
        .unwrap();
    world.step(0.01).unwrap();
    // The exact model collides it.
    world
        .set_contact_model(ContactModel::Exact(ContactSettings::default()))
        .unwrap();
    world.step(0.01).unwrap();
    assert!(matches!(
        world.contact_model(),
        Some(ContactModel::Exact(_))
    ));
    // So does the soft step, and the body is still there.
    world
        .set_contact_model(ContactModel::SoftStep(SoftStepSettings::default()))
        .unwrap();
    world.step(0.01).unwrap();
    assert_eq!(world.bodies().len(), 1);
    assert!(world.states()[0].position.y < 0.0, "it falls under gravity");
}

/// A ray straight down at a static capsule (length 2, radius 0.25) lying
/// at height 1 meets its top at y = 1.25; a ray at x = 1.1 (over the right
/// cap, 0.1 past its centre at x = 1) meets the cap at y = 1 + √(r² −
/// 0.1²). Exact geometry; the tolerance is a few ulps of the 10 m path.
#[test]
fn rays_meet_a_capsule_where_its_geometry_is() {
    let mut world = World::new(Method::Rk4).unwrap();
    world
        .add_body(BodyDef::fixed(
            "pill",
            Vector2::new(0.0, 1.0),
            Some(Shape::capsule(2.0, 0.25).unwrap()),
        ))
        .unwrap();
    let down = Vector2::new(0.0, -1.0);
    for (x, y) in [(0.0, 1.25), (1.1, 1.0 + (0.0625f64 - 0.01).sqrt())] {
        let hit = world
            .cast_ray(Vector2::new(x, 10.0), down, 20.0, QueryFilter::default())
            .unwrap()
            .expect("the ray meets the capsule");
        assert!(
            (hit.point.y - y).abs() < 1e-14,
            "x = {x}: {} vs {y}",
            hit.point.y
        );
    }
}
