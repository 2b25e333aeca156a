//! Chain shapes (issue 19) through the public API: what a world refuses,
//! and what a chain does to bodies on it under the soft step.

use etalon2d::forces::Gravity;
use etalon2d::{
    BodyDef, BodyKind, ContactModel, ContactSettings, EngineError, Method, Shape, SoftStepSettings,
    World,
};
use nalgebra::Vector2;

/// A flat ground from x = 10 to x = −10 (listed right to left: solid from
/// above), the first and last points ghosts.
fn ground() -> Shape {
    let points = (-11..=11)
        .rev()
        .map(|x| Vector2::new(f64::from(x), 0.0))
        .collect();
    Shape::chain(points, false).unwrap()
}

/// A dynamic body of 1 kg with `shape`, centred at (x, y), at rest.
fn body_at(name: &str, shape: Shape, x: f64, y: f64) -> BodyDef {
    let mut def = BodyDef::rigid(name, 1.0, shape);
    def.state.position = Vector2::new(x, y);
    def
}

fn soft_world() -> World {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -10.0),
        })
        .unwrap();
    world
}

#[test]
fn the_exact_model_refuses_a_chain_naming_the_body_and_the_model() {
    let mut world = soft_world();
    world
        .add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(ground())))
        .unwrap();
    let refused = world
        .set_contact_model(ContactModel::Exact(ContactSettings::default()))
        .expect_err("the exact model does not collide chains");
    assert!(
        matches!(refused, EngineError::Unsupported { .. }),
        "{refused:?}"
    );
    let message = refused.to_string();
    assert!(
        message.contains("'ground'") && message.contains("exact"),
        "{message}"
    );
    assert!(
        matches!(world.contact_model(), Some(ContactModel::SoftStep(_))),
        "a refused switch leaves the soft step in place"
    );
    // And a world already under the exact model refuses the body.
    let mut exact = World::new(Method::Rk4).unwrap();
    exact
        .set_contact_model(ContactModel::Exact(ContactSettings::default()))
        .unwrap();
    assert!(
        exact
            .add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(ground())))
            .is_err()
    );
    assert_eq!(exact.bodies().len(), 0);
}

#[test]
fn a_chain_goes_on_static_bodies_only() {
    let mut world = soft_world();
    let refused = world
        .add_body(BodyDef::rigid("rope", 1.0, ground()))
        .expect_err("a chain has no mass");
    assert!(
        matches!(refused, EngineError::Unsupported { .. }),
        "{refused:?}"
    );
    assert!(refused.to_string().contains("static"), "{refused}");
    assert_eq!(world.bodies().len(), 0);
    // Nor can a static chain be made to move later.
    let id = world
        .add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(ground())))
        .unwrap();
    assert!(world.set_body_kind(id, BodyKind::Dynamic).is_err());
    assert!(world.set_body_kind(id, BodyKind::Kinematic).is_err());
    assert_eq!(world.bodies()[id].kind, BodyKind::Static);
}

#[test]
fn bad_chains_are_typed_errors() {
    let two = vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)];
    assert!(matches!(
        Shape::chain(two, false),
        Err(EngineError::InvalidChain { point: 2, .. })
    ));
    let nan = vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(2.0, f64::NAN),
        Vector2::new(3.0, 0.0),
    ];
    assert!(matches!(
        Shape::chain(nan, true),
        Err(EngineError::InvalidChain { point: 2, .. })
    ));
}

/// A box dropped on the chain from above rests on it (pushed to the right
/// of the segments' direction: up); one started below the chain falls
/// through it (one-sided); a disc rests too.
#[test]
fn a_chain_holds_from_its_right_side_only() {
    let mut world = soft_world();
    world
        .add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(ground())))
        .unwrap();
    let above = world
        .add_body(body_at(
            "above",
            Shape::rectangle(1.0, 1.0).unwrap(),
            0.3,
            1.0,
        ))
        .unwrap();
    let below = world
        .add_body(body_at(
            "below",
            Shape::rectangle(1.0, 1.0).unwrap(),
            4.0,
            -0.45,
        ))
        .unwrap();
    let disc = world
        .add_body(body_at("disc", Shape::circle(0.5).unwrap(), -4.0, 1.0))
        .unwrap();
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    let s = world.states();
    // At rest on y = 0: centres at 0.5 m, within the soft contact's sink
    // (millimetres) and the speculative margin.
    assert!(
        (s[above].position.y - 0.5).abs() < 0.01,
        "{:?}",
        s[above].position
    );
    assert!(s[above].velocity.norm() < 1e-3, "{:?}", s[above].velocity);
    assert!(
        (s[disc].position.y - 0.5).abs() < 0.01,
        "{:?}",
        s[disc].position
    );
    // Free fall from −0.45 m for 2 s: far below.
    assert!(s[below].position.y < -10.0, "{:?}", s[below].position);
}
