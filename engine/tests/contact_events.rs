//! The soft step's events, sensors, filters, hooks and per-part materials,
//! through the public API: small worlds, each checking one rule.

use etalon2d::prelude::*;
use etalon2d::{CompoundPart, EngineError, ShapeOverrides};

fn soft_world() -> World {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
}

fn ground(world: &mut World) -> BodyId {
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(40.0, 1.0).unwrap()),
        ))
        .unwrap()
}

const DT: f64 = 1.0 / 60.0;

#[test]
fn a_dropped_box_begins_touching_once_with_a_hit_at_its_landing_speed() {
    let mut world = soft_world();
    let g = ground(&mut world);
    // Dropped from 1.25 m above contact: lands at √(2 g 1.25) = 5 m/s.
    let b = world
        .add_body(
            BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(0.0, 1.75)),
        )
        .unwrap();
    let (mut began, mut hits) = (Vec::new(), Vec::new());
    for _ in 0..90 {
        world.step(DT).unwrap();
        let e = world.step_events().unwrap();
        began.extend(e.touch_began.iter().copied());
        hits.extend(e.hits.iter().copied());
        assert!(e.touch_ended.is_empty());
    }
    assert_eq!(began.len(), 1);
    let pair = [began[0].a.body, began[0].b.body];
    assert!(pair.contains(&g) && pair.contains(&b));
    assert_eq!(hits.len(), 1);
    // The approach speed is the speed before the solve of the step that
    // met the ground: the free-fall speed at that step's start within one
    // step's gain g dt (symplectic Euler leads by at most that).
    let speed = hits[0].approach_speed;
    assert!((speed - 5.0).abs() <= 10.0 * DT, "{speed}");
    assert!((hits[0].normal.y.abs() - 1.0).abs() < 1e-12);
    // Resting, its contact carries its weight each step (1 kg, 10 m/s²).
    let carried: f64 = world
        .contact_data()
        .unwrap()
        .map(|c| {
            c.points()
                .iter()
                .map(|p| p.total_normal_impulse)
                .sum::<f64>()
        })
        .sum();
    // The soft model's fixed point carries it exactly; after 1.5 s the box
    // is at rest to one part in a million (the harness's criterion).
    assert!((carried - 10.0 * DT).abs() < 1e-6 * 10.0 * DT, "{carried}");
}

#[test]
fn sensors_on_static_kinematic_and_dynamic_bodies_detect_without_pushing() {
    let mut world = soft_world();
    ground(&mut world);
    let square = || Shape::rectangle(1.0, 1.0).unwrap();
    // A static sensor a falling ball passes through.
    let fixed = world
        .add_body(
            BodyDef::fixed("static sensor", Vector2::new(-5.0, 3.0), Some(square())).as_sensor(),
        )
        .unwrap();
    let ball = world
        .add_body(
            BodyDef::rigid("ball", 1.0, Shape::circle(0.2).unwrap())
                .with_position(Vector2::new(-5.0, 5.0)),
        )
        .unwrap();
    // A kinematic sensor sweeping over a box resting on the ground.
    let kinematic = world
        .add_body(
            BodyDef::kinematic(
                "kinematic sensor",
                Vector2::new(5.0, 0.5),
                square(),
                Vector2::new(2.0, 0.0),
                0.0,
            )
            .as_sensor(),
        )
        .unwrap();
    let resting = world
        .add_body(BodyDef::rigid("resting", 1.0, square()).with_position(Vector2::new(8.0, 0.5)))
        .unwrap();
    // Its twin, out of the sensor's way, settles the same way.
    let twin = world
        .add_body(BodyDef::rigid("twin", 1.0, square()).with_position(Vector2::new(16.0, 0.5)))
        .unwrap();
    // A dynamic sensor falling onto the ground through a static sensor: it
    // detects the ground, passes through it (a sensor never pushes nor is
    // pushed) and does not detect the other sensor.
    let falling = world
        .add_body(
            BodyDef::rigid("dynamic sensor", 1.0, Shape::circle(0.2).unwrap())
                .with_position(Vector2::new(-5.0, 4.2))
                .as_sensor(),
        )
        .unwrap();
    let mut began = Vec::new();
    for _ in 0..120 {
        world.step(DT).unwrap();
        for e in &world.step_events().unwrap().sensor_began {
            began.push((e.sensor.body, e.visitor.body));
        }
    }
    assert!(began.contains(&(fixed, ball)), "{began:?}");
    assert!(began.contains(&(kinematic, resting)), "{began:?}");
    assert!(began.contains(&(falling, 0)), "{began:?}");
    assert!(!began.contains(&(fixed, falling)) && !began.contains(&(falling, fixed)));
    let s = world.states();
    // The ball rests on the ground; the resting box did not move; the
    // dynamic sensor fell through the ground.
    assert!((s[ball].position.y - 0.2).abs() < 1e-3, "{:?}", s[ball]);
    let moved = |id: BodyId, x: f64| s[id].position - Vector2::new(x, 0.5);
    assert!(
        (moved(resting, 8.0) - moved(twin, 16.0)).norm() < 1e-12,
        "{:?} {:?}",
        s[resting],
        s[twin]
    );
    assert!(s[falling].position.y < -1.0, "{:?}", s[falling]);
}

#[test]
fn a_pre_solve_hook_that_refuses_lets_a_box_fall_through_the_ground() {
    #[derive(Clone)]
    struct Refuse(usize);
    impl ContactHooks for Refuse {
        fn pre_solve(&mut self, _: &PreSolveContact) -> bool {
            self.0 += 1;
            false
        }
    }
    let mut world = soft_world();
    ground(&mut world);
    let b = world
        .add_body(
            BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(0.0, 0.5)),
        )
        .unwrap();
    world.set_contact_hooks(Refuse(0)).unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
        // Disabled before touching: no event, no contact data.
        let e = world.step_events().unwrap();
        assert!(e.touch_began.is_empty() && e.hits.is_empty());
        assert_eq!(world.contact_data().unwrap().count(), 0);
    }
    assert!(world.states()[b].position.y < -1.0);
}

#[test]
fn a_pair_filter_hook_refuses_pairs_before_they_get_a_contact() {
    #[derive(Clone)]
    struct NotTheGround;
    impl ContactHooks for NotTheGround {
        fn should_collide(&mut self, a: ShapeId, b: ShapeId) -> bool {
            a.body != 0 && b.body != 0
        }
    }
    let mut world = soft_world();
    ground(&mut world);
    let b = world
        .add_body(
            BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(0.0, 0.6)),
        )
        .unwrap();
    world.set_contact_hooks(NotTheGround).unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    assert!(world.states()[b].position.y < -1.0);
}

#[test]
fn a_compound_part_overrides_its_bodys_filter_sensor_flag_and_friction() {
    let mut world = soft_world();
    ground(&mut world);
    // An L of two boxes: its foot is a sensor part (detects, never
    // pushes), so the body falls until its solid part (0.5 m above the
    // foot's bottom) rests on the ground.
    let part = |y: f64, overrides: ShapeOverrides| {
        CompoundPart::new(
            Vector2::new(0.0, y),
            0.0,
            Shape::rectangle(1.0, 0.5).unwrap(),
        )
        .with_overrides(overrides)
    };
    let foot = ShapeOverrides {
        sensor: Some(true),
        ..ShapeOverrides::default()
    };
    let body = Shape::Compound(
        Compound::new(vec![part(0.0, foot), part(0.5, ShapeOverrides::default())]).unwrap(),
    );
    let l = world
        .add_body(BodyDef::rigid("l", 1.0, body).with_position(Vector2::new(0.0, 1.0)))
        .unwrap();
    let mut sensed = Vec::new();
    for _ in 0..120 {
        world.step(DT).unwrap();
        for e in &world.step_events().unwrap().sensor_began {
            sensed.push(e.sensor);
        }
    }
    assert_eq!(sensed, [ShapeId { body: l, part: 0 }]);
    // The solid part's bottom on the ground: the body's centre of mass
    // (midway between the parts, 0.25 m below the solid one's centre, so at
    // its bottom) at y = 0 m, less the soft sink (< 1 mm); with the foot
    // solid it would be 0.5 m.
    let y = world.states()[l].position.y;
    assert!(y.abs() < 1e-3, "{y}");
    // A bad override is refused by name.
    let bad = ShapeOverrides {
        friction: Some(-1.0),
        ..ShapeOverrides::default()
    };
    let shape = Shape::Compound(Compound::new(vec![part(0.0, bad)]).unwrap());
    let e = world
        .add_body(BodyDef::rigid("bad", 1.0, shape))
        .unwrap_err()
        .to_string();
    assert!(e.contains("friction of part 0 of body 'bad'"), "{e}");
}

#[test]
fn the_exact_model_refuses_the_soft_step_calls_by_name() {
    let mut world =
        World::with_model(Method::Rk4, ContactModel::Exact(ContactSettings::default())).unwrap();
    for e in [
        world.step_events().map(|_| ()).unwrap_err(),
        world.contact_data().map(|_| ()).unwrap_err(),
        world.set_contact_hooks(NoHooks).unwrap_err(),
    ] {
        assert!(matches!(e, EngineError::Unsupported { .. }), "{e}");
        assert!(e.to_string().contains("exact contact model"), "{e}");
    }
    // So are sensors and filters on its bodies.
    let e = world
        .add_body(BodyDef::rigid("s", 1.0, Shape::circle(1.0).unwrap()).as_sensor())
        .unwrap_err();
    assert!(matches!(e, EngineError::Unsupported { .. }), "{e}");
    assert!(world.bodies().is_empty());
}

#[derive(Clone)]
struct NoHooks;
impl ContactHooks for NoHooks {}

#[test]
fn mixing_rules_decide_the_pairs_friction() {
    // A box sliding at 2 m/s on the ground, friction 0.2 and 0.8: the
    // rules give 0.4 (geometric mean), 0.8 (max), 0.2 (min), 0.5 (average),
    // 0.16 (product); it stops after v/(μ g) within a step.
    for (rule, mu) in [
        (MixingRule::GeometricMean, 0.4),
        (MixingRule::Max, 0.8),
        (MixingRule::Min, 0.2),
        (MixingRule::Average, 0.5),
        (MixingRule::Product, 0.16),
    ] {
        let mut world = World::with_model(
            Method::SemiImplicitEuler,
            ContactModel::SoftStep(SoftStepSettings {
                friction_mixing: rule,
                ..SoftStepSettings::default()
            }),
        )
        .unwrap();
        world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
        world
            .add_body(BodyDef {
                friction: Some(0.2),
                ..BodyDef::fixed(
                    "ground",
                    Vector2::new(0.0, -0.5),
                    Some(Shape::rectangle(40.0, 1.0).unwrap()),
                )
            })
            .unwrap();
        let b = world
            .add_body(BodyDef {
                friction: Some(0.8),
                ..BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                    .with_position(Vector2::new(0.0, 0.5))
                    .with_velocity(Vector2::new(2.0, 0.0))
            })
            .unwrap();
        let expected = 2.0 / (mu * 10.0);
        // Sliding, it loses mu g h per substep (h = DT/4); within that of 0
        // it has stopped (the box then rocks back on its soft contacts).
        let stop = mu * 10.0 * DT / 4.0;
        let mut stopped = None;
        for k in 1..=120 {
            world.step(DT).unwrap();
            if stopped.is_none() && world.states()[b].velocity.x.abs() < stop {
                stopped = Some(k as f64 * DT);
            }
        }
        let t = stopped.expect("the box stops");
        assert!(
            t >= expected - 1e-9 && t <= expected + 2.0 * DT,
            "{rule:?}: stopped at {t} s, expected {expected} s"
        );
    }
}

/// A 2 kg box hanging at rest from a hinge: the joint carries its weight,
/// m g = 20 N (the soft rows settle within the first steps). A threshold
/// of 25 N is never reached; one of 15 N is reached every step once the
/// box hangs, and a program that removes the joint on that event (a
/// breakable joint) lets the box fall.
#[test]
fn a_joint_force_threshold_reports_the_joint_and_a_program_can_break_it() {
    for (threshold, breaks) in [(25.0, false), (15.0, true)] {
        let mut world = soft_world();
        let weight = 2.0 * 10.0;
        let b = world
            .add_body(
                BodyDef::rigid("box", 2.0, Shape::rectangle(0.5, 0.5).unwrap())
                    .with_position(Vector2::new(0.0, 5.0)),
            )
            .unwrap();
        let hinge = world
            .add_joint(
                JointDef::revolute(
                    "hinge",
                    None,
                    Some(b),
                    Vector2::new(0.0, 5.0),
                    Revolute::default(),
                )
                .with_thresholds(Some(threshold), None),
            )
            .unwrap();
        let mut broken_at = None;
        for step in 0..120 {
            world.step(DT).unwrap();
            let events = &world.step_events().unwrap().joints_exceeded;
            if let Some(e) = events.first() {
                assert_eq!(e.joint, hinge);
                // The force it reports is the one the joint state gives,
                // at least the threshold.
                assert!(e.force.norm() >= threshold, "{e:?}");
                assert_eq!(e.force, world.joint(hinge).unwrap().force);
                if broken_at.is_none() {
                    world.remove_joint(hinge).unwrap();
                    broken_at = Some(step);
                }
            }
        }
        let y = world.states()[b].position.y;
        if breaks {
            let step = broken_at.expect("the 15 N threshold is under the 20 N weight");
            assert!(step < 10, "reported at step {step}");
            // Falling freely since: far below the hinge.
            assert!(y < 0.0, "y = {y}");
        } else {
            assert_eq!(broken_at, None, "25 N is above the {weight} N weight");
            // Held: within a millimetre of the hinge.
            assert!((y - 5.0).abs() < 1e-3, "y = {y}");
        }
    }
}

/// Thresholds are validated, and the exact model refuses them by name.
#[test]
fn joint_thresholds_are_checked() {
    let mut world = soft_world();
    let b = world
        .add_body(BodyDef::rigid(
            "box",
            1.0,
            Shape::rectangle(0.5, 0.5).unwrap(),
        ))
        .unwrap();
    let def = JointDef::revolute(
        "hinge",
        None,
        Some(b),
        Vector2::zeros(),
        Revolute::default(),
    );
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let error = world
            .add_joint(def.clone().with_thresholds(Some(bad), None))
            .unwrap_err();
        assert!(error.to_string().contains("force threshold"), "{error}");
    }
    assert_eq!(world.joint_count(), 0, "a refused joint is not added");
    let mut exact =
        World::with_model(Method::Rk4, ContactModel::Exact(ContactSettings::default())).unwrap();
    let b = exact
        .add_body(BodyDef::rigid(
            "box",
            1.0,
            Shape::rectangle(0.5, 0.5).unwrap(),
        ))
        .unwrap();
    let error = exact
        .add_joint(def_for(b).with_thresholds(None, Some(1.0)))
        .unwrap_err();
    assert!(
        matches!(error, EngineError::Unsupported { .. }) && error.to_string().contains("threshold"),
        "{error}"
    );
}

fn def_for(b: BodyId) -> JointDef {
    JointDef::revolute(
        "hinge",
        None,
        Some(b),
        Vector2::zeros(),
        Revolute::default(),
    )
}

#[test]
fn hooks_events_and_sleep_give_the_same_bits_on_every_thread_count() {
    // The collide stage updates the manifolds on the threads, then applies
    // the touching changes, the end events, the pre-solve hook and the
    // wakes serially in contact order (engine/src/soft_step/collide.rs):
    // the hook sees the same contacts in the same order, and the events
    // and states are the same bits, on 1, 2 and 3 threads. A pile of
    // boxes dropped with sleeping on; the hook refuses the pairs whose
    // body ids sum to a multiple of 5, so some contacts are disabled.
    use std::sync::{Arc, Mutex};
    #[derive(Clone)]
    struct Refuse(Arc<Mutex<Vec<(ShapeId, ShapeId)>>>);
    impl ContactHooks for Refuse {
        fn pre_solve(&mut self, c: &PreSolveContact) -> bool {
            self.0.lock().unwrap().push((c.a, c.b));
            !(c.a.body + c.b.body).is_multiple_of(5)
        }
    }
    let run = |threads: usize| {
        let settings = SoftStepSettings {
            sleeping: true,
            threads,
            // On the threads however small the pile: what is compared.
            min_work_per_thread: 0,
            ..SoftStepSettings::default()
        };
        let mut world =
            World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap();
        world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
        ground(&mut world);
        for k in 0..24 {
            let (column, row) = ((k % 4) as f64, (k / 4) as f64);
            let def = BodyDef::rigid("box", 1.0, Shape::rectangle(0.5, 0.5).unwrap())
                .with_position(Vector2::new(0.6 * column + 0.1 * row, 0.3 + 0.55 * row));
            world.add_body(def).unwrap();
        }
        let calls = Arc::new(Mutex::new(Vec::new()));
        world.set_contact_hooks(Refuse(calls.clone())).unwrap();
        let mut steps = Vec::new();
        for _ in 0..150 {
            world.step(DT).unwrap();
            steps.push((world.state_hash(), world.step_events().unwrap().clone()));
        }
        let calls = calls.lock().unwrap().clone();
        (steps, calls)
    };
    let (one, calls) = run(1);
    assert!(!calls.is_empty());
    assert!(one.iter().any(|(_, e)| !e.touch_began.is_empty()));
    for threads in [2, 3] {
        let (steps, their_calls) = run(threads);
        assert!(steps == one, "{threads} threads: states or events differ");
        assert!(their_calls == calls, "{threads} threads: hook calls differ");
    }
}
