//! The same scene and settings give bit-identical traces (docs/design.md,
//! "Principles"). Compared bit for bit (`f64::to_bits`), which `==` is not:
//! it equates 0.0 with −0.0 and never equates NaN.

use etalon2d::forces::{
    AngularDrag, Attachment, Gravity, PointForce, QuadraticDrag, Spring, Torque,
};
use etalon2d::{
    BodyDef, BodyState, EventSpec, FnSystem, Method, Shape, TimeWindow, Tolerance, Trace, World,
    integrate_fixed,
};
use nalgebra::Vector2;

/// A scene touching every moving part: two rigid boxes and a particle,
/// gravity, a distance spring between body points, quadratic and angular
/// drag, a windowed torque and point force (step splitting), and events.
fn busy_scene(method: Method) -> Trace {
    let mut world = World::new(method).unwrap();
    let shape = Shape::rectangle(0.1, 0.1).unwrap();
    let a = world
        .add_body(BodyDef::rigid("a", 0.3, shape.clone()).with_velocity(Vector2::new(42.0, 42.0)))
        .unwrap();
    let b = world
        .add_body(
            BodyDef::rigid("b", 0.5, shape)
                .with_position(Vector2::new(1.0, 0.5))
                .with_rotation(0.3, -2.0),
        )
        .unwrap();
    let c = world
        .add_body(BodyDef::particle("c", 2.0, Vector2::new(-1.0, 3.0)))
        .unwrap();
    world
        .add_body(BodyDef::fixed("anchor", Vector2::new(0.0, 5.0), None))
        .unwrap();
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -9.80655),
        })
        .unwrap();
    world
        .add_force(Spring {
            a: Attachment::Body {
                body: a,
                local_point: Vector2::new(0.05, 0.0),
            },
            b: Attachment::Body {
                body: b,
                local_point: Vector2::new(-0.05, 0.05),
            },
            stiffness: 3.0,
            rest_length: 1.0,
            axis: None,
        })
        .unwrap();
    world
        .add_force(Spring {
            a: Attachment::World(Vector2::new(0.0, 5.0)),
            b: Attachment::center_of(c),
            stiffness: 40.0,
            rest_length: 2.0,
            axis: None,
        })
        .unwrap();
    world
        .add_force(QuadraticDrag {
            body: a,
            coefficient: 0.003,
        })
        .unwrap();
    world
        .add_force(AngularDrag {
            body: b,
            coefficient: 0.003,
        })
        .unwrap();
    world
        .add_force_during(
            Box::new(Torque::from_lever(
                a,
                Vector2::new(0.05, 0.05),
                Vector2::new(0.3, 0.4),
            )),
            TimeWindow::first(0.7).unwrap(),
        )
        .unwrap();
    world
        .add_force_during(
            Box::new(PointForce {
                body: b,
                force: Vector2::new(1.0, 2.0),
                local_point: Vector2::new(0.05, -0.05),
            }),
            TimeWindow::new(0.333, 1.234).unwrap(),
        )
        .unwrap();
    world.add_event(EventSpec::apex(a)).unwrap();
    world.add_event(EventSpec::landing(a, 0.0)).unwrap();
    world.run(4.0, 0.01).unwrap()
}

fn state_bits(s: &BodyState) -> [u64; 6] {
    [
        s.position.x.to_bits(),
        s.position.y.to_bits(),
        s.angle.to_bits(),
        s.velocity.x.to_bits(),
        s.velocity.y.to_bits(),
        s.angular_velocity.to_bits(),
    ]
}

/// Every number of a trace as bits, in order.
fn trace_bits(trace: &Trace) -> Vec<u64> {
    let mut bits = Vec::new();
    for s in &trace.samples {
        bits.push(s.t.to_bits());
        bits.push(s.energy.to_bits());
        bits.extend(s.states.iter().flat_map(state_bits));
    }
    for e in &trace.events {
        bits.push(e.t.to_bits());
        bits.extend(e.states.iter().flat_map(state_bits));
    }
    bits
}

#[test]
fn two_identical_world_runs_give_bit_identical_traces() {
    for method in Method::FIXED_STEP
        .into_iter()
        .chain([Method::DormandPrince(Tolerance::uniform(1e-10))])
    {
        let first = busy_scene(method);
        let second = busy_scene(method);
        // The scene really moved and fired its events (two apexes, then the
        // terminal landing near 2.7 s), so there was something to disagree on.
        assert!(first.samples.len() > 100, "{}", method.id());
        assert_eq!(first.events.len(), 3, "{}", method.id());
        assert!(first.event("landing").is_some(), "{}", method.id());
        let names = |t: &Trace| t.events.iter().map(|e| e.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&first), names(&second), "{}", method.id());
        assert_eq!(first.stats, second.stats, "{}", method.id());
        assert!(
            trace_bits(&first) == trace_bits(&second),
            "{}: traces differ",
            method.id()
        );
    }
}

#[test]
fn two_identical_ode_integrations_give_bit_identical_solutions() {
    for method in [
        Method::ImplicitEuler,
        Method::DormandPrince(Tolerance::uniform(1e-9)),
    ] {
        let solve = || {
            let mut sys = FnSystem::new(1, |t: f64, y: &[f64], dy: &mut [f64]| {
                dy[0] = -1000.0 * (y[0] - (t + 2.0)) + 1.0;
            });
            integrate_fixed(&mut sys, method, 0.0, &[1.0], 0.01, 100).unwrap()
        };
        let (first, second) = (solve(), solve());
        assert_eq!(first.stats, second.stats);
        let bits = |s: &etalon2d::Solution| {
            s.t.iter()
                .chain(s.y.iter().flatten())
                .map(|v| v.to_bits())
                .collect::<Vec<_>>()
        };
        assert!(bits(&first) == bits(&second), "{}", method.id());
    }
}
