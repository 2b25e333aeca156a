//! The soft-step contact model on small scenes (debug-build friendly): a
//! box at rest sinks by exactly the static spring's compression, a stack
//! and a pyramid stand, friction on a slope gives the closed-form
//! acceleration, a fast box does not pass a thin wall, kinematic bodies
//! move at their velocity, islands sleep and wake, removal, determinism,
//! forces and events under the soft step.

use etalon2d::forces::QuadraticDrag;
use etalon2d::{
    BodyDef, ContactModel, EngineError, EventSpec, Method, Shape, SoftStepSettings, World,
};
use nalgebra::Vector2;
use std::f64::consts::PI;

const G: f64 = 10.0;
const DT: f64 = 1.0 / 60.0;

fn soft_world(settings: SoftStepSettings) -> World {
    let mut world = World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings))
        .expect("valid settings");
    world.set_gravity(Vector2::new(0.0, -G)).unwrap();
    world
}

fn ground(world: &mut World, width: f64) -> usize {
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(width, 1.0).unwrap()),
        ))
        .unwrap()
}

fn unit_box(name: &str, x: f64, y: f64) -> BodyDef {
    BodyDef {
        mass: None,
        density: Some(1.0),
        ..BodyDef::rigid(name, 1.0, Shape::rectangle(1.0, 1.0).unwrap())
    }
    .with_position(Vector2::new(x, y))
}

fn run(world: &mut World, steps: usize) {
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
}

fn fastest(world: &World) -> f64 {
    world
        .states()
        .iter()
        .map(|s| s.velocity.norm())
        .fold(0.0, f64::max)
}

#[test]
fn a_box_on_the_ground_sinks_by_the_static_springs_compression() {
    // Against a static body the contact spring has 2 × 30 Hz (the cap
    // 1/(8h) = 30 Hz at h = 1/240 s is not exceeded by 30 Hz itself). At
    // rest each of the two points carries half the weight, its warm-started
    // impulse is λ = m g h / 2, and the soft update
    // Δλ = −m_i ms (v + br s) − is λ vanishes at v = 0 when
    // s = −is λ / (m_i ms br) = −(λ / (m_i h)) / ω², ω = 2π·60 rad/s, with
    // m_i the point's effective mass 1/(1/m + (w/2)²/I): for a unit box
    // (I = m/6) 1/m_i = 2.5/m, so the sink is 1.25 g/ω².
    let mut world = soft_world(SoftStepSettings::default());
    ground(&mut world, 10.0);
    let b = world.add_body(unit_box("box", 0.0, 0.5)).unwrap();
    run(&mut world, 120);
    let omega = 2.0 * PI * 60.0;
    let expected = 0.5 - 1.25 * G / (omega * omega);
    let y = world.states()[b].position.y;
    // The soft update converges geometrically (factor impulse_scale ≈ 0.06
    // per substep): after 480 substeps only round-off of y (~1e-16 m) is
    // left; 1e-12 m leaves room for the sum over steps.
    assert!((y - expected).abs() < 1e-12, "y = {y}, expected {expected}");
    assert!(fastest(&world) < 1e-12);
}

#[test]
fn a_stack_of_five_and_a_pyramid_of_base_five_stand() {
    let mut world = soft_world(SoftStepSettings::default());
    ground(&mut world, 20.0);
    let mut stack = Vec::new();
    for i in 0..5 {
        stack.push(world.add_body(unit_box("s", -5.0, 0.5 + i as f64)).unwrap());
    }
    let mut top = 0;
    for row in 0..5 {
        for col in 0..5 - row {
            let x = 3.0 + col as f64 - (5 - row) as f64 / 2.0;
            top = world.add_body(unit_box("p", x, 0.5 + row as f64)).unwrap();
        }
    }
    run(&mut world, 120);
    // Each contact compresses by at most the weight it carries over its
    // spring (≤ 5 m g on 30 Hz: 5 × 0.28 mm), so the tops sink by
    // millimetres; 1 cm means they stood. At rest every body is slower
    // than 1 mm/s.
    // The stack stands at x = −5: each contact lets the box above creep
    // sideways by at most its compression while it settles (its two
    // points are solved one after the other: the first push turns the box
    // by at most the compression over its half-width, and its corner
    // slides by no more before friction holds it), so the top's creep is
    // at most the sum of the compressions, which the 1 cm on y bounds.
    let s = &world.states()[*stack.last().unwrap()];
    assert!(
        (s.position.y - 4.5).abs() < 0.01 && (s.position.x + 5.0).abs() < 0.01,
        "{s:?}"
    );
    let p = &world.states()[top];
    assert!(
        (p.position.y - 4.5).abs() < 0.01 && (p.position.x - 2.5).abs() < 1e-3,
        "{p:?}"
    );
    assert!(fastest(&world) < 1e-3, "{}", fastest(&world));
}

#[test]
fn friction_on_a_slope_gives_the_closed_form_acceleration() {
    // A slope of 0.25 rad as a tilted static box; boxes with mu below
    // tan 0.25 = 0.2553 slide with a = g (sin θ − mu cos θ), the others
    // hold. The soft contact settles in a few steps, then the body slides
    // at constant acceleration: measure it between 0.5 s and 1 s.
    let theta: f64 = 0.25;
    for (mu, slides) in [(0.1, true), (0.0, true), (0.35, false), (0.75, false)] {
        let mut world = soft_world(SoftStepSettings::default());
        let (s, c) = theta.sin_cos();
        world
            .add_body(
                BodyDef::fixed(
                    "slope",
                    Vector2::new(0.0, -0.5 / c),
                    Some(Shape::rectangle(200.0, 1.0).unwrap()),
                )
                .with_rotation(theta, 0.0)
                .with_material(mu, 0.0),
            )
            .unwrap();
        let b = world
            .add_body(
                unit_box("box", -0.5 * s, 0.5 * c)
                    .with_rotation(theta, 0.0)
                    .with_material(mu, 0.0),
            )
            .unwrap();
        run(&mut world, 30);
        let v0 = world.states()[b].velocity;
        run(&mut world, 30);
        let v1 = world.states()[b].velocity;
        let along = Vector2::new(-c, -s); // down the slope
        let a = (v1 - v0).dot(&along) / (30.0 * DT);
        let expected = if slides { G * (s - mu * c) } else { 0.0 };
        // Symplectic Euler is exact for a constant acceleration; what is
        // left is the settling of the soft contact (its normal impulse
        // converges geometrically), far below 1e-6 m/s².
        assert!(
            (a - expected).abs() < 1e-6,
            "mu {mu}: a = {a}, expected {expected}"
        );
    }
}

#[test]
fn a_fast_box_does_not_pass_a_thin_wall() {
    // 0.5 m box at 500 m/s toward a static wall 0.05 m thick: it moves
    // 8.3 m per step, so only the continuous sweep can catch it.
    let mut world = soft_world(SoftStepSettings {
        restitution: 0.5,
        ..SoftStepSettings::default()
    });
    world.set_gravity(Vector2::zeros()).unwrap();
    world
        .add_body(BodyDef::fixed(
            "wall",
            Vector2::new(10.0, 0.0),
            Some(Shape::rectangle(0.05, 4.0).unwrap()),
        ))
        .unwrap();
    let b = world
        .add_body(
            BodyDef::rigid("bullet", 1.0, Shape::rectangle(0.5, 0.5).unwrap())
                .with_velocity(Vector2::new(500.0, 0.0)),
        )
        .unwrap();
    run(&mut world, 10);
    let s = world.states()[b];
    assert!(
        s.position.x < 10.0 - 0.025 - 0.25 + 0.01,
        "went through: {s:?}"
    );
    // It bounced (restitution 0.5 at 500 m/s is far above the threshold).
    assert!(s.velocity.x < -100.0, "{s:?}");
}

#[test]
fn a_kinematic_body_moves_at_its_velocity_and_pushes() {
    let mut world = soft_world(SoftStepSettings::default());
    world.set_gravity(Vector2::zeros()).unwrap();
    let k = world
        .add_body(BodyDef::kinematic(
            "paddle",
            Vector2::new(-2.0, 0.0),
            Shape::rectangle(1.0, 1.0).unwrap(),
            Vector2::new(1.0, 0.0),
            0.5,
        ))
        .unwrap();
    let b = world.add_body(unit_box("box", 0.0, 0.0)).unwrap();
    run(&mut world, 180);
    let s = world.states()[k];
    // Symplectic Euler moves it by v h exactly each substep; 720 substeps
    // of round-off.
    assert!(
        (s.position.x - 1.0).abs() < 1e-12 && (s.angle - 1.5).abs() < 1e-12,
        "{s:?}"
    );
    assert!(world.states()[b].position.x > 0.5, "not pushed");
}

#[test]
fn resting_islands_sleep_and_wake_when_hit() {
    let mut world = soft_world(SoftStepSettings {
        sleeping: true,
        ..SoftStepSettings::default()
    });
    ground(&mut world, 20.0);
    let a = world.add_body(unit_box("a", 0.0, 0.5)).unwrap();
    let b = world.add_body(unit_box("b", 0.0, 1.5)).unwrap();
    let far = world.add_body(unit_box("far", 6.0, 0.5)).unwrap();
    // Time to sleep 0.5 s after the stack settles: asleep within 1.5 s.
    run(&mut world, 90);
    assert!(world.is_asleep(a) && world.is_asleep(b) && world.is_asleep(far));
    let y = world.states()[b].position.y;
    // A box dropped onto the stack wakes it.
    let c = world.add_body(unit_box("c", 0.0, 4.0)).unwrap();
    // It falls 1.5 m: it touches after sqrt(2·1.5/g) = 0.55 s (33 steps).
    run(&mut world, 40);
    assert!(!world.is_asleep(a) && !world.is_asleep(b) && !world.is_asleep(c));
    assert!(
        world.is_asleep(far),
        "an island nobody touched stays asleep"
    );
    run(&mut world, 120);
    assert!((world.states()[b].position.y - y).abs() < 0.01);
    assert!((world.states()[c].position.y - 2.5).abs() < 0.01);
}

#[test]
fn a_removed_body_no_longer_holds_anything_up() {
    let mut world = soft_world(SoftStepSettings::default());
    ground(&mut world, 20.0);
    let a = world.add_body(unit_box("a", 0.0, 0.5)).unwrap();
    let b = world.add_body(unit_box("b", 0.0, 1.5)).unwrap();
    run(&mut world, 30);
    world.remove_body(a).unwrap();
    assert!(world.is_removed(a) && !world.is_removed(b));
    run(&mut world, 60);
    // b falls 1 m onto the ground and rests there.
    assert!(
        (world.states()[b].position.y - 0.5).abs() < 0.01,
        "{:?}",
        world.states()[b]
    );
}

#[test]
fn the_same_scene_gives_the_same_bits() {
    let build = || {
        let mut world = soft_world(SoftStepSettings::default());
        ground(&mut world, 20.0);
        for i in 0..12 {
            let x = (i % 4) as f64 * 1.1 - 2.0 + 0.01 * i as f64;
            world
                .add_body(
                    unit_box("b", x, 0.6 + (i / 4) as f64 * 1.3).with_rotation(0.1 * i as f64, 0.0),
                )
                .unwrap();
        }
        run(&mut world, 90);
        world.states().to_vec()
    };
    assert_eq!(build(), build());
}

#[test]
fn forces_and_events_act_under_the_soft_step() {
    // A falling box with drag lands (centre through y = 0.5 + 1 m) and the
    // landing event stops the run inside a substep.
    let mut world = soft_world(SoftStepSettings::default());
    ground(&mut world, 20.0);
    let b = world.add_body(unit_box("box", 0.0, 10.0)).unwrap();
    world
        .add_force(QuadraticDrag {
            body: b,
            coefficient: 0.05,
        })
        .unwrap();
    world.add_event(EventSpec::landing(b, 1.5)).unwrap();
    let trace = world.run(5.0, DT).unwrap();
    let landing = trace.event("landing").expect("landed");
    assert!(world.is_stopped());
    let y = landing.states[b].position.y;
    assert!((y - 1.5).abs() < 1e-9, "{y}");
    // Free fall without drag would take sqrt(2·8.5/10) = 1.304 s; drag
    // makes it later.
    assert!(landing.t > 1.304, "{}", landing.t);
}

#[test]
fn other_methods_are_refused_not_replaced() {
    let err = World::with_model(
        Method::Rk4,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap_err();
    assert!(matches!(err, EngineError::Unsupported { .. }), "{err}");
    assert!(err.to_string().contains("rk4"), "{err}");
}

#[test]
fn a_turning_hollow_box_keeps_its_contents_inside() {
    // A tumbler in miniature: a kinematic hollow box (a compound of four
    // walls, inside 4 × 4 m) turning at 1 rad/s with nine small boxes in it.
    let mut world = soft_world(SoftStepSettings::default());
    let hollow = etalon2d::Compound::hollow_box(4.0, 4.0, 0.5).unwrap();
    world
        .add_body(BodyDef::kinematic(
            "tumbler",
            Vector2::zeros(),
            Shape::Compound(hollow),
            Vector2::zeros(),
            1.0,
        ))
        .unwrap();
    let mut inside = Vec::new();
    for i in 0..9 {
        let (x, y) = ((i % 3) as f64 - 1.0, (i / 3) as f64 - 1.0);
        let def = BodyDef::rigid("b", 0.25, Shape::rectangle(0.5, 0.5).unwrap())
            .with_position(Vector2::new(x, y));
        inside.push(world.add_body(def).unwrap());
    }
    run(&mut world, 180);
    for &b in &inside {
        let p = world.states()[b].position;
        // The inside reaches 2 m from the centre along the axes, 2.83 m at
        // the corners; a box's centre stays at least 0.25 m within.
        let local = nalgebra::Rotation2::new(-world.states()[0].angle) * p;
        assert!(
            local.x.abs() < 2.0 && local.y.abs() < 2.0,
            "box escaped to {p}"
        );
    }
    // They were carried round: someone moved.
    assert!(fastest(&world) > 0.1);
}
