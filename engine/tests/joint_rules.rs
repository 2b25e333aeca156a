//! What joints do to the rest of the world, and what the engine refuses:
//! jointed bodies do not collide unless asked, sleep and wake as one
//! island, lose their joints when removed; every bad definition is a
//! typed error naming the joint; joints stay with the contact model they
//! were added to.

use etalon2d::EngineError;
use etalon2d::prelude::*;

const DT: f64 = 1.0 / 60.0;

fn world(settings: SoftStepSettings, g: f64) -> World {
    let mut world =
        World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap();
    world.set_gravity(Vector2::new(0.0, -g)).unwrap();
    world
}

fn unit_box(name: &str, x: f64, y: f64) -> BodyDef {
    BodyDef::rigid(name, 1.0, Shape::rectangle(1.0, 1.0).unwrap()).with_position(Vector2::new(x, y))
}

/// Two unit boxes overlapping by half, at rest, no gravity, tied by a
/// slack rope (which pulls on nothing while they overlap): how far apart
/// their centres are after a second.
fn overlapping_pair(collide_connected: bool) -> f64 {
    let mut world = world(SoftStepSettings::default(), 0.0);
    let a = world.add_body(unit_box("a", 0.0, 0.0)).unwrap();
    let b = world.add_body(unit_box("b", 0.5, 0.0)).unwrap();
    world
        .add_joint(
            JointDef::distance(
                "tie",
                (Some(a), Vector2::zeros()),
                (Some(b), Vector2::new(0.5, 0.0)),
                Distance::rope(5.0),
            )
            .with_collide_connected(collide_connected),
        )
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    (world.states()[b].position - world.states()[a].position).norm()
}

#[test]
fn jointed_bodies_do_not_collide_unless_asked() {
    // Filtered: no contact, so nothing moves at all.
    assert_eq!(overlapping_pair(false), 0.5);
    // Allowed: the contact pushes the overlap out (to about 1 m apart).
    let apart = overlapping_pair(true);
    assert!(apart > 0.9, "{apart}");
}

#[test]
fn a_joint_added_between_touching_bodies_ends_their_contact() {
    // A box resting on another: a weld added later (collide_connected off)
    // takes the contact's place. The contact's impulse is gone, the weld
    // carries the weight.
    let mut world = world(SoftStepSettings::default(), 9.81);
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(10.0, 1.0).unwrap()),
        ))
        .unwrap();
    let low = world.add_body(unit_box("low", 0.0, 0.5)).unwrap();
    let high = world.add_body(unit_box("high", 0.0, 1.5)).unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let weld = world
        .add_joint(JointDef::weld(
            "glue",
            Some(low),
            Some(high),
            Vector2::new(0.0, 1.0),
            Weld::default(),
        ))
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let s = world.joint(weld).unwrap();
    // The weld now holds the top box's weight: 9.81 N upward on it.
    assert!((s.force.y - 9.81).abs() < 1e-3, "{s:?}");
    // Removing the weld lets the contact come back: the box stays put.
    world.remove_joint(weld).unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let y = world.states()[high].position.y;
    assert!((y - 1.5).abs() < 1e-3, "the top box fell to {y}");
}

/// Two boxes resting on the ground 3 m apart, tied by a rope when `tied`,
/// sleeping on. Returns the world and the step at which each fell asleep.
fn resting_pair(tied: bool) -> (World, [Option<usize>; 2]) {
    let settings = SoftStepSettings {
        sleeping: true,
        ..SoftStepSettings::default()
    };
    let mut world = world(settings, 9.81);
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(20.0, 1.0).unwrap()),
        ))
        .unwrap();
    // The right box starts a little higher: it settles later.
    let a = world.add_body(unit_box("a", -1.5, 0.5)).unwrap();
    let b = world.add_body(unit_box("b", 1.5, 0.8)).unwrap();
    if tied {
        world
            .add_joint(JointDef::distance(
                "rope",
                (Some(a), Vector2::new(-1.5, 0.5)),
                (Some(b), Vector2::new(1.5, 0.8)),
                Distance::rope(4.0),
            ))
            .unwrap();
    }
    let mut asleep = [None, None];
    for step in 0..300 {
        world.step(DT).unwrap();
        for (k, id) in [a, b].into_iter().enumerate() {
            if asleep[k].is_none() && world.is_asleep(id) {
                asleep[k] = Some(step);
            }
        }
    }
    (world, asleep)
}

#[test]
fn jointed_bodies_sleep_and_wake_together() {
    let (mut untied, alone) = resting_pair(false);
    let (mut tied, together) = resting_pair(true);
    // Untied, each sleeps on its own; tied, they sleep at the same step.
    assert!(alone[0].is_some() && alone[1].is_some(), "{alone:?}");
    assert_ne!(alone[0], alone[1], "{alone:?}");
    assert!(together[0].is_some(), "{together:?}");
    assert_eq!(together[0], together[1]);
    // A box dropped from 0.1 m onto the left one wakes it (within 20
    // steps, 0.33 s, less than the 0.5 s it takes to fall asleep again);
    // through the rope the right one wakes too, and only then.
    for world in [&mut untied, &mut tied] {
        world.add_body(unit_box("drop", -1.5, 1.6)).unwrap();
        for _ in 0..20 {
            world.step(DT).unwrap();
        }
        assert!(!world.is_asleep(1), "the box hit did not wake");
    }
    assert!(untied.is_asleep(2), "an untouched untied box woke");
    assert!(!tied.is_asleep(2), "the tied box slept through");
}

#[test]
fn removing_a_body_removes_its_joints() {
    let mut world = world(SoftStepSettings::default(), 9.81);
    let bob = world
        .add_body(BodyDef::particle("bob", 1.0, Vector2::new(0.0, -1.0)))
        .unwrap();
    let rod = world
        .add_joint(JointDef::distance(
            "rod",
            (None, Vector2::zeros()),
            (Some(bob), Vector2::new(0.0, -1.0)),
            Distance::default(),
        ))
        .unwrap();
    world.step(DT).unwrap();
    assert!(!world.joint(rod).unwrap().removed);
    world.remove_body(bob).unwrap();
    let s = world.joint(rod).unwrap();
    assert!(s.removed, "{s:?}");
    // Removing it again, or stepping, is harmless.
    world.remove_joint(rod).unwrap();
    world.step(DT).unwrap();
    assert_eq!(world.joint_count(), 1);
}

/// The message of the error `world.add_joint(def)` gives, checked to be an
/// [`EngineError::InvalidJoint`] naming the joint and saying `words`.
fn refused(world: &mut World, def: JointDef, words: &str) {
    let name = def.name.clone();
    match world.add_joint(def) {
        Err(EngineError::InvalidJoint { joint, reason }) => {
            assert_eq!(joint, name);
            assert!(reason.contains(words), "'{reason}' does not say '{words}'");
        }
        other => panic!("joint '{name}': expected InvalidJoint saying '{words}', got {other:?}"),
    }
}

#[test]
fn every_bad_joint_definition_is_a_typed_error_naming_the_joint() {
    let mut world = world(SoftStepSettings::default(), 9.81);
    let wall = world
        .add_body(BodyDef::fixed("wall", Vector2::new(-2.0, 0.0), None))
        .unwrap();
    let bob = world.add_body(unit_box("bob", 0.0, 0.0)).unwrap();
    let gone = world.add_body(unit_box("gone", 5.0, 0.0)).unwrap();
    world.remove_body(gone).unwrap();
    let at = Vector2::zeros();
    let pin = |name: &str, a, b, joint: Revolute| JointDef::revolute(name, a, b, at, joint);
    let free = Revolute::default();
    refused(&mut world, pin("missing", None, Some(9), free), "index 9");
    refused(
        &mut world,
        pin("removed", None, Some(gone), free),
        "was removed",
    );
    refused(
        &mut world,
        pin("twice", Some(bob), Some(bob), free),
        "to itself",
    );
    refused(
        &mut world,
        pin("static", None, Some(wall), free),
        "must be dynamic",
    );
    refused(
        &mut world,
        pin("nothing", None, None, free),
        "must be dynamic",
    );
    let limits = |lo, hi| Revolute {
        limits: Some((lo, hi)),
        ..free
    };
    refused(
        &mut world,
        pin("order", None, Some(bob), limits(0.5, -0.5)),
        "above the upper",
    );
    refused(
        &mut world,
        pin("wide", None, Some(bob), limits(-4.0, 0.0)),
        "0.99π",
    );
    refused(
        &mut world,
        pin("nan", None, Some(bob), limits(f64::NAN, 0.0)),
        "finite",
    );
    let motor = |speed, max_torque| Revolute {
        motor: Some(RevoluteMotor { speed, max_torque }),
        ..free
    };
    refused(
        &mut world,
        pin("weak", None, Some(bob), motor(1.0, 0.0)),
        "torque",
    );
    refused(
        &mut world,
        pin("wild", None, Some(bob), motor(f64::INFINITY, 1.0)),
        "speed",
    );
    let spring = |hertz, zeta| Revolute {
        spring: Some(JointSpring::new(hertz, zeta)),
        ..free
    };
    refused(
        &mut world,
        pin("soft", None, Some(bob), spring(-1.0, 0.5)),
        "frequency",
    );
    refused(
        &mut world,
        pin("damp", None, Some(bob), spring(1.0, -0.5)),
        "damping",
    );
    let stiff = pin("stiff", None, Some(bob), free).with_constraint_softness(0.0, 2.0);
    refused(&mut world, stiff, "constraint frequency");
    let far = JointDef::revolute("far", None, Some(bob), Vector2::new(f64::NAN, 0.0), free);
    refused(&mut world, far, "not finite");
    let slide = |name: &str, joint| JointDef::prismatic(name, None, Some(bob), at, joint);
    refused(
        &mut world,
        slide("flat", Prismatic::along(Vector2::zeros())),
        "no direction",
    );
    let rail = Prismatic {
        limits: Some((1.0, 0.0)),
        ..Prismatic::default()
    };
    refused(&mut world, slide("rail", rail), "above the upper");
    let rod = |name: &str, joint| {
        JointDef::distance(name, (None, at), (Some(bob), Vector2::new(1.0, 0.0)), joint)
    };
    refused(&mut world, rod("rope", Distance::rope(0.0)), "rope");
    let inverted = Distance::Rope {
        min_length: 2.0,
        max_length: 1.0,
    };
    refused(
        &mut world,
        rod("inverted", inverted),
        "at least the shortest",
    );
    let short = Distance::Rigid { length: Some(-1.0) };
    refused(&mut world, rod("short", short), "length");
    let point = JointDef::distance("point", (None, at), (Some(bob), at), Distance::default());
    refused(&mut world, point, "coincide");
    let turned = rod("turned", Distance::default()).with_reference_angle(1.0);
    refused(&mut world, turned, "no reference angle");
    let hand = JointDef::target("hand", bob, at, at, Target::new(-1.0));
    refused(&mut world, hand, "largest force");
    let mut grip = JointDef::target("grip", bob, at, at, Target::new(1.0));
    grip.body_a = Some(wall);
    refused(&mut world, grip, "must be the world");
    let weld = Weld {
        angular_spring: Some(JointSpring::new(f64::NAN, 1.0)),
        ..Weld::default()
    };
    refused(
        &mut world,
        JointDef::weld("weld", None, Some(bob), at, weld),
        "angular spring",
    );
    assert_eq!(world.joint_count(), 0, "a refused joint was added");

    // Steering what cannot be steered, or a joint that is not there.
    let pivot = world
        .add_joint(pin("pivot", None, Some(bob), free))
        .unwrap();
    assert!(matches!(
        world.set_joint_target(pivot, Vector2::zeros()),
        Err(EngineError::InvalidJoint { .. })
    ));
    assert!(matches!(
        world.set_motor_speed(pivot, 1.0),
        Err(EngineError::InvalidJoint { .. })
    ));
    assert!(matches!(
        world.joint(7),
        Err(EngineError::UnknownJoint { index: 7, count: 1 })
    ));
}

#[test]
fn joints_stay_with_their_model() {
    // The exact model refuses what it does not solve (here a motor),
    // saying what to use (its own joints: tests/exact_joints.rs).
    let mut exact = World::new(Method::Rk4).unwrap();
    let bob = exact.add_body(unit_box("bob", 0.0, 0.0)).unwrap();
    let def = JointDef::revolute(
        "pin",
        None,
        Some(bob),
        Vector2::zeros(),
        Revolute::default(),
    );
    let motored = Revolute {
        motor: Some(etalon2d::RevoluteMotor {
            speed: 1.0,
            max_torque: 1.0,
        }),
        ..Revolute::default()
    };
    let error = exact
        .add_joint(JointDef::revolute(
            "pin",
            None,
            Some(bob),
            Vector2::zeros(),
            motored,
        ))
        .unwrap_err();
    assert!(matches!(error, EngineError::Unsupported { .. }), "{error}");
    let message = error.to_string();
    assert!(message.contains("joint 'pin'"), "{message}");
    assert!(message.contains("soft_step"), "{message}");
    // A soft-step world with a joint refuses to leave the soft step.
    let mut soft = world(SoftStepSettings::default(), 0.0);
    let bob = soft.add_body(unit_box("bob", 0.0, 0.0)).unwrap();
    soft.add_joint(JointDef {
        body_b: Some(bob),
        ..def
    })
    .unwrap();
    let error = soft
        .set_contact_model(ContactModel::Exact(ContactSettings::default()))
        .unwrap_err();
    assert!(error.to_string().contains("joint 'pin'"), "{error}");
    assert!(soft.disable_contacts().is_err());
    assert!(matches!(
        soft.contact_model(),
        Some(ContactModel::SoftStep(_))
    ));
    assert!(matches!(
        soft.joint(0).unwrap().joint_type,
        etalon2d::JointType::Revolute
    ));
}

#[test]
fn a_body_without_a_shape_turns_its_anchor() {
    // A rigid body given by its mass and inertia alone (no shape), hung by
    // a revolute joint 1 m from its centre and released at 45°: its anchor
    // turns with it, so the pivot holds to the rigid rows' sink (a
    // fraction of a millimetre), not to the body's swing (metres).
    let mut world = world(SoftStepSettings::default(), 9.81);
    let angle = std::f64::consts::FRAC_PI_4;
    let bob = world
        .add_body(BodyDef {
            inertia: Some(0.1),
            ..BodyDef::particle("bob", 1.0, Vector2::new(angle.sin(), -angle.cos()))
        })
        .unwrap();
    let pin = world
        .add_joint(JointDef::revolute(
            "pin",
            None,
            Some(bob),
            Vector2::zeros(),
            Revolute::default(),
        ))
        .unwrap();
    let mut worst: f64 = 0.0;
    for _ in 0..120 {
        world.step(DT).unwrap();
        worst = worst.max(world.joint(pin).unwrap().linear_error);
    }
    assert!(world.states()[bob].angle.abs() > 0.1, "it did not swing");
    assert!(worst < 1e-3, "the pivot opened by {worst} m");
}

/// A hub turning on a pin, carrying 24 bobs on revolute joints at its
/// rim: more joints between dynamic bodies on one body than the colouring
/// has colours for them (20), so some go to the overflow and are solved
/// one at a time, the others four at a time in lanes. Returns the
/// largest anchor separation over a second of swinging.
fn hub_with_spokes() -> (f64, Vec<BodyState>) {
    let mut world = world(SoftStepSettings::default(), 9.81);
    let hub = world
        .add_body(BodyDef::rigid("hub", 1.0, Shape::circle(0.5).unwrap()))
        .unwrap();
    world
        .add_joint(JointDef::revolute(
            "pin",
            None,
            Some(hub),
            Vector2::zeros(),
            Revolute::default(),
        ))
        .unwrap();
    let mut joints = Vec::new();
    for k in 0..24 {
        let a = std::f64::consts::TAU * k as f64 / 24.0;
        let (rim, bob) = (0.5, 0.8);
        let at = |r: f64| Vector2::new(r * a.cos(), r * a.sin());
        let id = world
            .add_body(
                // The bobs pass through each other: only the joints act.
                BodyDef::rigid("bob", 0.1, Shape::circle(0.05).unwrap())
                    .with_position(at(bob))
                    .with_collision_group(1),
            )
            .unwrap();
        joints.push(
            world
                .add_joint(JointDef::revolute(
                    "spoke",
                    Some(hub),
                    Some(id),
                    at(rim),
                    Revolute::default(),
                ))
                .unwrap(),
        );
    }
    let mut worst: f64 = 0.0;
    for _ in 0..60 {
        world.step(DT).unwrap();
        for &j in &joints {
            worst = worst.max(world.joint(j).unwrap().linear_error);
        }
    }
    (worst, world.states().to_vec())
}

#[test]
fn a_body_on_more_joints_than_colours_holds_them_all() {
    // A point row's separation is at most (a_load + a_c (1 + 1/(2 a₃)))/ω²
    // (docs/joints.md, "What the softness costs"): rigid rows at 60 Hz,
    // ζ = 2, h = 1/240 s, so a₃ = 1/(1 + hω (2ζ + hω)); the bobs' load is
    // g, and their centripetal acceleration about their pivots (0.3 m
    // arms) at most v²/0.3 with v² ≤ 2 g × 1.6 m (a bob cannot fall more
    // than the rim's diameter plus two arms): 4.4 mm (1.3 mm measured).
    // A joint the solver skipped would let its bob fall free, 4.9 m in
    // the second.
    let (g, omega, h) = (9.81, std::f64::consts::TAU * 60.0, 1.0 / 240.0);
    let a3 = 1.0 / (1.0 + h * omega * (2.0 * 2.0 + h * omega));
    let centripetal = 2.0 * g * 1.6 / 0.3;
    let bound = (g + centripetal * (1.0 + 1.0 / (2.0 * a3))) / (omega * omega);
    let (worst, states) = hub_with_spokes();
    assert!(
        worst < bound,
        "a spoke opened by {worst} m, beyond {bound} m"
    );
    // The same bits on a second run.
    assert_eq!(states, hub_with_spokes().1);
}
