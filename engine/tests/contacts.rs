//! Contact response in a world (docs/cases.md case III): impacts against the
//! closed forms, bounces, resting, sliding and holding with friction, and
//! several contacts in one step.

use etalon2d::forces::Gravity;
use etalon2d::validation::contact::{ImpactBody, Velocities, impact_eq_7_15};
use etalon2d::{
    BodyDef, Circle, ContactEventKind, ContactSettings, EventSpec, Method, Shape, ToiMethod, World,
};
use nalgebra::Vector2;

const G: f64 = 9.80665;

fn disc(radius: f64) -> Shape {
    Shape::Circle(Circle::new(radius).unwrap())
}

fn ground(world: &mut World) -> usize {
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(100.0, 1.0).unwrap()),
        ))
        .unwrap()
}

fn gravity(world: &mut World) {
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -G),
        })
        .unwrap();
}

/// docs/cases.md: m1 = 1 kg at +2 m/s, m2 = 3 kg at rest; e = 1 gives −1, +1 and
/// e = 0.5 gives −0.25, +0.75, momentum kept to 1e-12.
#[test]
fn head_on_discs_leave_with_the_closed_form_velocities() {
    for (e, v1, v2) in [(1.0, -1.0, 1.0), (0.5, -0.25, 0.75)] {
        let mut world = World::new(Method::Rk4).unwrap();
        let a = world
            .add_body(
                BodyDef::rigid("m1", 1.0, disc(0.5))
                    .with_position(Vector2::new(-2.0, 0.0))
                    .with_velocity(Vector2::new(2.0, 0.0)),
            )
            .unwrap();
        let b = world
            .add_body(BodyDef::rigid("m2", 3.0, disc(0.5)).with_position(Vector2::new(1.0, 0.0)))
            .unwrap();
        world
            .set_contact_settings(ContactSettings::new(e, 0.0))
            .unwrap();
        assert!(world.has_contacts());
        world.run(2.0, 0.01).unwrap();
        let s = world.states();
        assert!((s[a].velocity.x - v1).abs() < 1e-12, "{}", s[a].velocity.x);
        assert!((s[b].velocity.x - v2).abs() < 1e-12, "{}", s[b].velocity.x);
        let p = s[a].velocity.x + 3.0 * s[b].velocity.x;
        assert!((p - 2.0).abs() < 1e-12);
        let impacts: Vec<_> = world
            .contact_events()
            .into_iter()
            .filter(|e| e.kind == ContactEventKind::Impact)
            .collect();
        assert_eq!(impacts.len(), 1);
        // Gap 2 m closed at 2 m/s: t = 1 s, within ε / (2 m/s).
        let eps = world.contact_settings().tolerance;
        assert!((impacts[0].t - 1.0).abs() <= eps / 2.0, "{}", impacts[0].t);
        assert!((impacts[0].normal_impulse - 2.0 * (1.0 + e) * 0.75).abs() < 1e-12);
    }
}

/// A rotated box hits a box at rest on a corner, off the line of centres:
/// the velocities after are seed eq. 7.15's, momentum is kept, and with
/// e = 1 the kinetic energy too.
#[test]
fn off_centre_box_impact_matches_eq_7_15() {
    let mut world = World::new(Method::Rk4).unwrap();
    let a = world
        .add_body(
            BodyDef::rigid("a", 1.0, Shape::rectangle(0.4, 0.2).unwrap())
                .with_position(Vector2::new(-2.0, 0.3))
                .with_rotation(0.5, 0.0)
                .with_velocity(Vector2::new(2.0, 0.0)),
        )
        .unwrap();
    let b = world
        .add_body(BodyDef::rigid(
            "b",
            2.0,
            Shape::rectangle(1.0, 1.0).unwrap(),
        ))
        .unwrap();
    world
        .set_contact_settings(ContactSettings::new(1.0, 0.0))
        .unwrap();
    world.run(1.0, 0.01).unwrap();
    let events = world.contact_events();
    let hit = events
        .iter()
        .find(|e| e.kind == ContactEventKind::Impact)
        .expect("an impact");
    assert_eq!(hit.points, 1);
    // The leading corner of A (the one farthest along +x) meets B's face
    // x = −0.5 with its y unchanged by the translation.
    let corner = [(0.2, 0.1), (0.2, -0.1), (-0.2, 0.1), (-0.2, -0.1)]
        .iter()
        .map(|&(x, y)| {
            let (s, c) = 0.5f64.sin_cos();
            Vector2::new(c * x - s * y, s * x + c * y)
        })
        .max_by(|p, q| p.x.total_cmp(&q.x))
        .unwrap();
    let t_hit = (-0.5 - (-2.0 + corner.x)) / 2.0;
    assert!((hit.t - t_hit).abs() < 1e-9, "{} vs {t_hit}", hit.t);
    let p = Vector2::new(-0.5, 0.3 + corner.y);
    assert!((hit.point - p).norm() < 1e-9, "{:?}", hit.point);
    let bodies = world.bodies();
    let expected = impact_eq_7_15(
        &ImpactBody {
            mass: 1.0,
            inertia: bodies[a].inertia.unwrap(),
            arm: p - Vector2::new(-2.0 + 2.0 * t_hit, 0.3),
            velocities: Velocities {
                linear: Vector2::new(2.0, 0.0),
                angular: 0.0,
            },
        },
        &ImpactBody {
            mass: 2.0,
            inertia: bodies[b].inertia.unwrap(),
            arm: p,
            velocities: Velocities {
                linear: Vector2::zeros(),
                angular: 0.0,
            },
        },
        -Vector2::x(),
        1.0,
    );
    let s = world.states();
    assert!((s[a].velocity - expected.a.linear).norm() < 1e-9);
    assert!((s[b].velocity - expected.b.linear).norm() < 1e-9);
    assert!((s[a].angular_velocity - expected.a.angular).abs() < 1e-8);
    assert!((s[b].angular_velocity - expected.b.angular).abs() < 1e-8);
    assert!((hit.normal_impulse - expected.impulse).abs() < 1e-9);
    let momentum = s[a].velocity + 2.0 * s[b].velocity;
    assert!((momentum - Vector2::new(2.0, 0.0)).norm() < 1e-12);
    let energy: f64 = world
        .bodies()
        .iter()
        .zip(s)
        .map(|(body, st)| body.kinetic_energy(st))
        .sum();
    assert!((energy - 2.0).abs() < 1e-12, "{energy}");
}

fn bouncing_ball(e: f64, h0: f64, method: Method) -> (World, usize) {
    let mut world = World::new(method).unwrap();
    ground(&mut world);
    let ball = world
        .add_body(BodyDef::rigid("ball", 1.0, disc(0.1)).with_position(Vector2::new(0.0, h0 + 0.1)))
        .unwrap();
    gravity(&mut world);
    world.add_event(EventSpec::apex(ball)).unwrap();
    world
        .set_contact_settings(ContactSettings::new(e, 0.0))
        .unwrap();
    (world, ball)
}

/// e = 1: the apex does not drift (docs/cases.md: 1e-9 relative per bounce).
#[test]
fn elastic_ball_keeps_its_apex() {
    for method in [
        Method::Rk4,
        Method::VelocityVerlet,
        Method::DormandPrince(etalon2d::Tolerance::uniform(1e-10)),
    ] {
        let (mut world, ball) = bouncing_ball(1.0, 1.0, method);
        let trace = world.run(9.5, 0.01).unwrap();
        let apexes: Vec<f64> = trace
            .events
            .iter()
            .filter(|e| e.name == "apex")
            .map(|e| e.states[ball].position.y - 0.1)
            .collect();
        assert_eq!(apexes.len(), 10, "{method:?}");
        for (n, h) in apexes.iter().enumerate() {
            assert!(
                (h - 1.0).abs() < 1e-9 * (n + 1) as f64,
                "{method:?} bounce {}: {h}",
                n + 1
            );
        }
    }
}

/// e = 0.8: apex n is 0.64^n h0.
#[test]
fn ball_with_restitution_follows_the_geometric_apex_sequence() {
    let (mut world, ball) = bouncing_ball(0.8, 1.0, Method::Rk4);
    let trace = world.run(6.0, 0.01).unwrap();
    let apexes: Vec<f64> = trace
        .events
        .iter()
        .filter(|e| e.name == "apex")
        .map(|e| e.states[ball].position.y - 0.1)
        .collect();
    assert!(apexes.len() >= 12, "{}", apexes.len());
    for (n, h) in apexes.iter().take(12).enumerate() {
        let expected = 0.64f64.powi(n as i32 + 1);
        assert!(
            ((h - expected) / expected).abs() < 1e-6,
            "bounce {}: {h} vs {expected}",
            n + 1
        );
    }
    // In the end it rests: the bounces below the resting speed are given up.
    let s = world.states()[ball];
    assert!((s.position.y - 0.1).abs() < 1e-9, "{:?}", s);
    assert!(s.velocity.norm() < 1e-12);
}

fn box_on_ground(mu: f64, v0: f64) -> (World, usize) {
    let mut world = World::new(Method::Rk4).unwrap();
    ground(&mut world);
    let b = world
        .add_body(
            BodyDef::rigid("box", 2.0, Shape::rectangle(0.5, 0.5).unwrap())
                .with_position(Vector2::new(0.0, 0.25))
                .with_velocity(Vector2::new(v0, 0.0)),
        )
        .unwrap();
    gravity(&mut world);
    world
        .set_contact_settings(ContactSettings::new(0.0, mu))
        .unwrap();
    (world, b)
}

/// docs/cases.md: a box resting 10 s moves less than 1e-9 m.
#[test]
fn resting_box_neither_sinks_nor_jitters() {
    let (mut world, b) = box_on_ground(0.5, 0.0);
    world.run(10.0, 0.01).unwrap();
    let s = world.states()[b];
    let moved = (s.position - Vector2::new(0.0, 0.25)).norm();
    assert!(moved < 1e-9, "{moved:e}");
    assert!(s.angle.abs() < 1e-12);
    let events = world.contact_events();
    assert_eq!(events.len(), 1, "{events:?}");
    assert_eq!(events[0].kind, ContactEventKind::Rest);
}

/// docs/cases.md: sliding at v0 with friction μ stops after v0²/(2μg) in
/// v0/(μg).
#[test]
fn sliding_box_stops_at_the_closed_form_distance() {
    let (mu, v0) = (0.5, 3.0);
    let (mut world, b) = box_on_ground(mu, v0);
    world.run(2.0, 0.01).unwrap();
    let s = world.states()[b];
    let distance = v0 * v0 / (2.0 * mu * G);
    assert!(
        ((s.position.x - distance) / distance).abs() < 1e-9,
        "{} vs {distance}",
        s.position.x
    );
    assert!(s.velocity.norm() < 1e-12, "{:?}", s.velocity);
    let stick = world
        .contact_events()
        .into_iter()
        .find(|e| e.kind == ContactEventKind::Stick)
        .expect("a stick event");
    assert!((stick.t - v0 / (mu * G)).abs() < 1e-12, "{}", stick.t);
}

fn box_on_incline(theta: f64, mu: f64) -> (World, usize) {
    let mut world = World::new(Method::Rk4).unwrap();
    let normal = Vector2::new(-theta.sin(), theta.cos());
    world
        .add_body(
            BodyDef::fixed(
                "incline",
                -0.5 * normal,
                Some(Shape::rectangle(100.0, 1.0).unwrap()),
            )
            .with_rotation(theta, 0.0),
        )
        .unwrap();
    let b = world
        .add_body(
            BodyDef::rigid("box", 1.0, Shape::rectangle(0.4, 0.4).unwrap())
                .with_position(0.2 * normal)
                .with_rotation(theta, 0.0),
        )
        .unwrap();
    gravity(&mut world);
    world
        .set_contact_settings(ContactSettings::new(0.0, mu))
        .unwrap();
    (world, b)
}

#[test]
fn box_slides_down_a_steep_incline_with_the_closed_form_acceleration() {
    let (theta, mu) = (0.5f64, 0.3);
    assert!(theta.tan() > mu);
    let (mut world, b) = box_on_incline(theta, mu);
    world.run(2.0, 0.01).unwrap();
    let s = world.states()[b];
    let along = (s.position - 0.2 * Vector2::new(-theta.sin(), theta.cos()))
        .dot(&Vector2::new(-theta.cos(), -theta.sin()));
    let a = G * (theta.sin() - mu * theta.cos());
    let measured = 2.0 * along / 4.0;
    assert!(((measured - a) / a).abs() < 1e-9, "{measured} vs {a}");
    assert!((s.angle - theta).abs() < 1e-12);
}

#[test]
fn box_holds_on_a_shallow_incline() {
    let (theta, mu) = (0.3f64, 0.5);
    assert!(theta.tan() < mu);
    let (mut world, b) = box_on_incline(theta, mu);
    let start = world.states()[b].position;
    world.run(10.0, 0.01).unwrap();
    let moved = (world.states()[b].position - start).norm();
    assert!(moved < 1e-9, "{moved:e}");
}

/// Two balls hit two walls at different times inside one large step: both
/// impacts are found, in time order.
#[test]
fn several_contacts_in_one_step_are_handled_in_time_order() {
    let mut world = World::new(Method::Rk4).unwrap();
    world
        .set_contact_settings(ContactSettings::new(1.0, 0.0))
        .unwrap();
    for x in [-2.0, 2.0] {
        world
            .add_body(BodyDef::fixed(
                "wall",
                Vector2::new(x, 0.0),
                Some(Shape::rectangle(0.2, 4.0).unwrap()),
            ))
            .unwrap();
    }
    // Gaps 0.3 m at 1 m/s and 0.5 m at 2 m/s: impacts at 0.3 s and 0.25 s.
    let left = world
        .add_body(
            BodyDef::rigid("left", 1.0, disc(0.2))
                .with_position(Vector2::new(-1.4, 0.0))
                .with_velocity(Vector2::new(-1.0, 0.0)),
        )
        .unwrap();
    let right = world
        .add_body(
            BodyDef::rigid("right", 1.0, disc(0.2))
                .with_position(Vector2::new(1.2, 1.0))
                .with_velocity(Vector2::new(2.0, 0.0)),
        )
        .unwrap();
    world.step(0.5).unwrap();
    let impacts: Vec<_> = world
        .contact_events()
        .into_iter()
        .filter(|e| e.kind == ContactEventKind::Impact)
        .collect();
    assert_eq!(impacts.len(), 2);
    assert_eq!(impacts[0].body_b, right);
    assert!((impacts[0].t - 0.25).abs() < 1e-9);
    assert_eq!(impacts[1].body_b, left);
    assert!((impacts[1].t - 0.3).abs() < 1e-9);
    let s = world.states();
    assert!((s[left].velocity.x - 1.0).abs() < 1e-15);
    assert!((s[right].velocity.x + 2.0).abs() < 1e-15);
    // Positions after reflection at the walls: exact to ε.
    assert!((s[left].position.x - (-1.7 + 0.2)).abs() < 1e-9);
    assert!((s[right].position.x - (1.7 - 0.5)).abs() < 1e-9);
}

/// Conservative advancement, and the default swept search, see a bullet
/// cross a thin wall inside one step; the seed's bisection, looking only at
/// the end, does not.
#[test]
fn the_default_search_catches_what_bisection_tunnels_through() {
    assert_eq!(ContactSettings::default().toi_method, ToiMethod::Swept);
    for (method, hits) in [
        (ToiMethod::Bisection, 0),
        (ToiMethod::ConservativeAdvancement, 1),
        (ToiMethod::Swept, 1),
    ] {
        let mut world = World::new(Method::Rk4).unwrap();
        world
            .add_body(BodyDef::fixed(
                "wall",
                Vector2::zeros(),
                Some(Shape::rectangle(0.02, 2.0).unwrap()),
            ))
            .unwrap();
        world
            .add_body(
                BodyDef::rigid("bullet", 0.1, Shape::rectangle(0.1, 0.1).unwrap())
                    .with_position(Vector2::new(-5.0, 0.0))
                    .with_velocity(Vector2::new(100.0, 0.0)),
            )
            .unwrap();
        world
            .set_contact_settings(ContactSettings {
                toi_method: method,
                ..ContactSettings::default()
            })
            .unwrap();
        world.run(0.1, 0.1).unwrap();
        let impacts: Vec<_> = world
            .contact_events()
            .into_iter()
            .filter(|e| e.kind == ContactEventKind::Impact)
            .collect();
        assert_eq!(impacts.len(), hits, "{method:?}");
        if hits == 1 {
            assert!((impacts[0].t - 0.0494).abs() < 1e-11, "{}", impacts[0].t);
        }
    }
}

/// docs/design.md: a scene without two collidable shapes runs no collision
/// code, and neither does one that did not ask for contacts.
#[test]
fn one_shape_runs_no_collision_code() {
    let mut off = World::new(Method::Rk4).unwrap();
    for x in [0.0, 0.5] {
        off.add_body(
            BodyDef::rigid("b", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(x, 0.0)),
        )
        .unwrap();
    }
    assert!(!off.has_contacts());
    off.set_contact_settings(ContactSettings::default())
        .unwrap();
    assert!(off.has_contacts());
    off.disable_contacts().unwrap();
    assert!(!off.has_contacts());
    let mut world = World::new(Method::Rk4).unwrap();
    world
        .set_contact_settings(ContactSettings::default())
        .unwrap();
    world
        .add_body(BodyDef::rigid(
            "box",
            1.0,
            Shape::rectangle(0.1, 0.1).unwrap(),
        ))
        .unwrap();
    world
        .add_body(BodyDef::particle("bead", 1.0, Vector2::new(0.0, 0.0)))
        .unwrap();
    assert!(!world.has_contacts());
    // Two static shapes and nothing moving: none either.
    let mut still = World::new(Method::Rk4).unwrap();
    still
        .set_contact_settings(ContactSettings::default())
        .unwrap();
    for x in [0.0, 0.5] {
        still
            .add_body(BodyDef::fixed(
                "s",
                Vector2::new(x, 0.0),
                Some(Shape::rectangle(1.0, 1.0).unwrap()),
            ))
            .unwrap();
    }
    assert!(!still.has_contacts());
}

/// docs/design.md: the same scene gives bit-identical traces, contacts included;
/// the profile counts the work whether or not it is timed.
#[test]
fn contact_runs_are_deterministic_and_profiled() {
    let run = |profiling: bool| {
        let (mut world, ball) = bouncing_ball(0.8, 1.0, Method::Rk4);
        world.set_profiling(profiling);
        world.run(3.0, 0.01).unwrap();
        let s = world.states()[ball];
        let events: Vec<u64> = world
            .contact_events()
            .iter()
            .flat_map(|e| [e.t.to_bits(), e.normal_impulse.to_bits()])
            .collect();
        (
            [s.position.y.to_bits(), s.velocity.y.to_bits()],
            events,
            world.profile(),
        )
    };
    let (a, b) = (run(true), run(false));
    assert_eq!(a.0, b.0);
    assert_eq!(a.1, b.1);
    assert_eq!(a.2.steps, b.2.steps);
    assert_eq!(a.2.toi_searches, b.2.toi_searches);
    assert!(a.2.toi_searches > 5 && a.2.candidate_pairs > 0);
    assert!(a.2.total_seconds() > 0.0);
    assert_eq!(b.2.total_seconds(), 0.0);
}
