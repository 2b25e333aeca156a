//! Bad input gets a typed `EngineError` naming what is wrong, never a panic
//! and never a silent default (docs/design.md, "Principles").

use etalon2d::forces::{Attachment, Gravity, QuadraticDrag, Spring, Torque};
use etalon2d::{
    BodyDef, ConvexPolygon, EngineError, EventSpec, FnSystem, Method, Shape, TimeWindow, Tolerance,
    World, integrate_fixed,
};
use nalgebra::Vector2;

fn world_with_particle() -> World {
    let mut world = World::new(Method::Rk4).unwrap();
    world
        .add_body(BodyDef::particle("ball", 1.0, Vector2::zeros()))
        .unwrap();
    world
}

/// Asserts an `InvalidParameter` whose `what` contains `what`, whose value
/// is `value` (NaN matches NaN), and whose message names both.
fn assert_invalid<T: std::fmt::Debug>(result: Result<T, EngineError>, what: &str, value: f64) {
    let err = result.expect_err("bad input must be refused");
    let message = err.to_string();
    match &err {
        EngineError::InvalidParameter {
            what: w, value: v, ..
        } => {
            assert!(w.contains(what), "{what:?} not in {w:?}");
            assert!(
                v.to_bits() == value.to_bits() || v == &value,
                "value {v} != {value}"
            );
        }
        other => panic!("expected InvalidParameter for {what}, got {other:?}"),
    }
    assert!(
        message.contains(what),
        "message {message:?} does not name {what:?}"
    );
}

fn assert_polygon(result: Result<ConvexPolygon, EngineError>, vertex: usize, reason: &str) {
    let err = result.expect_err("bad polygon must be refused");
    let message = err.to_string();
    match err {
        EngineError::InvalidPolygon {
            vertex: v,
            reason: r,
        } => {
            assert_eq!(v, vertex, "{message}");
            assert!(r.contains(reason), "{reason:?} not in {r:?}");
        }
        other => panic!("expected InvalidPolygon, got {other:?}"),
    }
    assert!(message.contains(reason) && message.contains(&format!("vertex {vertex}")));
}

#[test]
fn non_positive_or_missing_mass_is_refused() {
    let mut world = World::new(Method::Rk4).unwrap();
    for mass in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let def = BodyDef::particle("ball", mass, Vector2::zeros());
        assert_invalid(world.add_body(def), "mass of body 'ball'", mass);
    }
    let def = BodyDef {
        mass: None,
        ..BodyDef::particle("ghost", 1.0, Vector2::zeros())
    };
    let err = world.add_body(def).unwrap_err();
    assert!(err.to_string().contains("needs a mass"), "{err}");
    let def = BodyDef {
        inertia: Some(-1.0),
        ..BodyDef::particle("spinner", 1.0, Vector2::zeros())
    };
    assert_invalid(world.add_body(def), "inertia of body 'spinner'", -1.0);
    assert!(world.bodies().is_empty(), "nothing refused was added");
}

#[test]
fn non_finite_state_is_refused() {
    let mut world = World::new(Method::Rk4).unwrap();
    let def = BodyDef::particle("ball", 1.0, Vector2::new(f64::NAN, 0.0));
    assert_invalid(world.add_body(def), "x of body 'ball'", f64::NAN);
    let def = BodyDef::particle("ball", 1.0, Vector2::zeros())
        .with_velocity(Vector2::new(0.0, f64::INFINITY));
    assert_invalid(world.add_body(def), "vy of body 'ball'", f64::INFINITY);
    let def = BodyDef::fixed("ground", Vector2::new(0.0, f64::NAN), None);
    assert_invalid(world.add_body(def), "y of body 'ground'", f64::NAN);
}

#[test]
fn non_positive_steps_and_durations_are_refused() {
    for dt in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let mut world = world_with_particle();
        assert_invalid(world.step(dt), "dt", dt);
        assert_invalid(world.run(1.0, dt), "dt", dt);
        assert_eq!(world.time(), 0.0, "a refused step does not move time");
    }
    let mut world = world_with_particle();
    assert_invalid(world.run(0.0, 0.1), "run duration", 0.0);
    assert_invalid(world.run(-1.0, 0.1), "run duration", -1.0);
    assert_invalid(world.step_to(-1.0), "step end time", -1.0);
    let mut sys = FnSystem::new(1, |_t: f64, y: &[f64], dy: &mut [f64]| dy[0] = -y[0]);
    for h in [0.0, -0.1, f64::NAN] {
        assert_invalid(
            integrate_fixed(&mut sys, Method::Rk4, 0.0, &[1.0], h, 10),
            "step",
            h,
        );
    }
}

#[test]
fn more_than_1e8_steps_is_refused_up_front() {
    let mut world = world_with_particle();
    // 100 s / 1e-7 s = 1e9 steps: refused before the first step.
    assert_invalid(world.run(100.0, 1e-7), "number of steps", 1e9);
    assert_eq!(world.time(), 0.0);
    assert_eq!(world.stats().steps, 0);
    let err = world.run(100.0, 1e-7).unwrap_err();
    assert!(err.to_string().contains("1e8"), "{err}");
}

#[test]
fn forces_and_events_naming_a_missing_body_are_refused() {
    let mut world = world_with_particle();
    let unknown = |index| EngineError::UnknownBody { index, count: 1 };
    let err = world
        .add_force(Torque {
            body: 5,
            torque: 1.0,
        })
        .unwrap_err();
    assert_eq!(err, unknown(5));
    assert!(err.to_string().contains("unknown body index 5"), "{err}");
    let spring = Spring {
        a: Attachment::center_of(0),
        b: Attachment::center_of(7),
        stiffness: 1.0,
        rest_length: 1.0,
        axis: None,
    };
    assert_eq!(world.add_force(spring).unwrap_err(), unknown(7));
    let drag = QuadraticDrag {
        body: 1,
        coefficient: 0.1,
    };
    assert_eq!(world.add_force(drag).unwrap_err(), unknown(1));
    assert_eq!(world.add_event(EventSpec::apex(3)).unwrap_err(), unknown(3));
    // Nothing was added: the world still runs, with no force at all.
    let trace = world.run(1.0, 0.5).unwrap();
    assert_eq!(trace.last().unwrap().states[0].position, Vector2::zeros());
}

#[test]
fn a_force_on_static_bodies_only_is_refused() {
    let mut world = World::new(Method::Rk4).unwrap();
    let a = world
        .add_body(BodyDef::fixed("left", Vector2::zeros(), None))
        .unwrap();
    let b = world
        .add_body(BodyDef::fixed("right", Vector2::x(), None))
        .unwrap();
    let spring = Spring {
        a: Attachment::center_of(a),
        b: Attachment::center_of(b),
        stiffness: 1.0,
        rest_length: 1.0,
        axis: None,
    };
    let err = world.add_force(spring).unwrap_err();
    assert_eq!(
        err,
        EngineError::ForceOnStaticBodies {
            force: "spring".into()
        }
    );
    assert!(err.to_string().contains("spring"), "{err}");
}

#[test]
fn bad_polygons_are_refused_naming_the_vertex() {
    let v = Vector2::new;
    // Clockwise triangle.
    let cw = ConvexPolygon::new(vec![v(0.0, 0.0), v(0.0, 1.0), v(1.0, 0.0)]);
    assert_polygon(cw, 0, "clockwise");
    // A dart: vertex 2 turns right.
    let dart = vec![
        v(0.0, 0.0),
        v(2.0, 0.0),
        v(1.0, 0.5),
        v(2.0, 2.0),
        v(0.0, 2.0),
    ];
    assert_polygon(ConvexPolygon::new(dart), 2, "not convex");
    // A pentagram turns left at every vertex but winds twice.
    let star: Vec<_> = (0..5)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_2 + 4.0 * std::f64::consts::PI * i as f64 / 5.0;
            v(a.cos(), a.sin())
        })
        .collect();
    assert_polygon(ConvexPolygon::new(star), 0, "self-intersecting");
    assert_polygon(
        ConvexPolygon::new(vec![v(0.0, 0.0), v(1.0, 0.0)]),
        2,
        "at least 3",
    );
    let collinear = vec![v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0), v(1.0, 1.0)];
    assert_polygon(ConvexPolygon::new(collinear), 1, "collinear");
    let nan = vec![v(0.0, 0.0), v(1.0, 0.0), v(f64::NAN, 1.0)];
    assert_polygon(ConvexPolygon::new(nan), 2, "non-finite");
    assert_invalid(Shape::rectangle(0.0, 1.0), "box width", 0.0);
    assert_invalid(Shape::rectangle(1.0, -2.0), "box height", -2.0);
}

#[test]
fn bad_force_parameters_are_refused() {
    let mut world = world_with_particle();
    let spring = |stiffness, rest_length, axis| Spring {
        a: Attachment::World(Vector2::zeros()),
        b: Attachment::center_of(0),
        stiffness,
        rest_length,
        axis,
    };
    assert_invalid(
        world.add_force(spring(-50.0, 50.0, None)),
        "spring stiffness",
        -50.0,
    );
    assert_invalid(
        world.add_force(spring(f64::NAN, 50.0, None)),
        "spring stiffness",
        f64::NAN,
    );
    assert_invalid(
        world.add_force(spring(50.0, -1.0, None)),
        "spring rest length",
        -1.0,
    );
    let skew = Some(Vector2::new(1.0, 1.0));
    assert_invalid(
        world.add_force(spring(50.0, 1.0, skew)),
        "spring axis",
        2f64.sqrt(),
    );
    let drag = QuadraticDrag {
        body: 0,
        coefficient: -0.003,
    };
    assert_invalid(world.add_force(drag), "drag coefficient", -0.003);
    let gravity = Gravity {
        g: Vector2::new(0.0, f64::NAN),
    };
    assert_invalid(world.add_force(gravity), "gravity y", f64::NAN);
    assert_invalid(TimeWindow::new(1.0, 0.0), "time window", 0.0);
    // A NaN start is refused too (the error reports the end it compared).
    let err = TimeWindow::new(f64::NAN, 1.0).unwrap_err();
    assert!(err.to_string().contains("time window"), "{err}");
    assert_invalid(world.set_energy_limit(Some(-1.0)), "energy limit", -1.0);
}

#[test]
fn bad_tolerances_are_refused() {
    let tol = |rtol, atol| Method::DormandPrince(Tolerance { rtol, atol });
    assert_invalid(World::new(tol(0.0, 1e-6)), "relative tolerance", 0.0);
    assert_invalid(
        World::new(tol(1e-6, f64::NAN)),
        "absolute tolerance",
        f64::NAN,
    );
    let mut sys = FnSystem::new(1, |_t: f64, y: &[f64], dy: &mut [f64]| dy[0] = -y[0]);
    assert_invalid(
        integrate_fixed(&mut sys, tol(-1e-6, 1e-6), 0.0, &[1.0], 0.1, 1),
        "relative tolerance",
        -1e-6,
    );
}

#[test]
fn a_world_of_static_bodies_runs_with_every_explicit_method() {
    // Nothing to integrate: an empty state. Every method must cope.
    for method in [
        Method::ExplicitEuler,
        Method::SemiImplicitEuler,
        Method::Midpoint,
        Method::Rk4,
        Method::VelocityVerlet,
        Method::DormandPrince(Tolerance::uniform(1e-6)),
    ] {
        let mut world = World::new(method).unwrap();
        world
            .add_body(BodyDef::fixed("ground", Vector2::new(1.0, 2.0), None))
            .unwrap();
        let trace = world.run(1.0, 0.1).unwrap();
        assert_eq!(trace.samples.len(), 11, "{}", method.id());
        assert_eq!(
            trace.last().unwrap().states[0].position,
            Vector2::new(1.0, 2.0)
        );
    }
}

#[test]
fn a_world_of_static_bodies_runs_with_implicit_euler() {
    let mut world = World::new(Method::ImplicitEuler).unwrap();
    world
        .add_body(BodyDef::fixed("ground", Vector2::new(1.0, 2.0), None))
        .unwrap();
    let trace = world.run(1.0, 0.1).unwrap();
    assert_eq!(trace.samples.len(), 11);
    assert_eq!(
        trace.last().unwrap().states[0].position,
        Vector2::new(1.0, 2.0)
    );
}

/// A compound body (a concave outline cut into parts) under the exact
/// model: without contacts its shape only gives its mass properties, so it
/// falls as any body (x = ½ g t², RK4 exact on a quadratic to round-off);
/// turning the exact model's contacts on refuses it, naming the body, and
/// leaves the world as it was (still the soft step, the body kept).
#[test]
fn a_compound_runs_without_contacts_and_is_refused_when_exact_contacts_come_on() {
    use etalon2d::{Compound, CompoundPart, ContactModel, ContactSettings, SoftStepSettings};
    let compound = || {
        Shape::Compound(
            Compound::new(vec![
                CompoundPart::new(Vector2::zeros(), 0.0, Shape::rectangle(1.0, 0.2).unwrap()),
                CompoundPart::new(
                    Vector2::new(0.4, 0.3),
                    0.0,
                    Shape::rectangle(0.2, 0.4).unwrap(),
                ),
            ])
            .unwrap(),
        )
    };
    let mut world = World::new(Method::Rk4).unwrap();
    let body = world
        .add_body(BodyDef::rigid("l", 1.0, compound()))
        .expect("a compound without contacts integrates");
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -10.0),
        })
        .unwrap();
    for _ in 0..100 {
        world.step(0.01).unwrap();
    }
    let y = world.states()[body].position.y;
    // ½ g t² at t = 1 s; 100 RK4 steps of a constant acceleration are
    // exact up to the round-off of 100 additions (≈ 100 ε · 5 m).
    assert!((y + 5.0).abs() < 1e-12, "y = {y}");
    let refused = world.set_contact_model(ContactModel::Exact(ContactSettings::default()));
    let message = refused
        .expect_err("the exact model does not collide compounds")
        .to_string();
    assert!(message.contains("'l'"), "{message}");

    let mut soft = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    soft.add_body(BodyDef::rigid("l", 1.0, compound())).unwrap();
    let refused = soft.set_contact_model(ContactModel::Exact(ContactSettings::default()));
    assert!(refused.is_err());
    assert!(
        matches!(soft.contact_model(), Some(ContactModel::SoftStep(_))),
        "a refused switch leaves the soft step in place"
    );
    assert_eq!(soft.bodies().len(), 1);
}
