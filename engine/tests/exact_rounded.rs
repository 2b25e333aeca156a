//! Segments, capsules and rounded polygons under the exact contact model,
//! against closed forms: a capsule bouncing flat with restitution, sliding
//! down a frictionless incline, resting on a segment ground, a rounded box
//! resting at its half-height plus its radius, and a capsule's cap striking
//! a box's corner along the line between the corner and the cap's centre.
//!
//! Shared numbers behind the tolerances: the exact model locates a contact
//! to within ε = `ContactSettings::tolerance` = 1e-10 m of touching; RK4
//! integrates a free flight or a constant acceleration exactly (the motion
//! is a polynomial of degree 2 in t), so what is left is ε and the
//! round-off of a few hundred steps on coordinates of order 1 m (ulp(1) =
//! 2.2e-16; 1000 steps give 2.2e-13 at most).

use etalon2d::forces::Gravity;
use etalon2d::{BodyDef, ContactSettings, EventSpec, Method, Shape, World};
use nalgebra::Vector2;

const G: f64 = 9.80665;

/// The contact tolerance ε of the default settings (m).
const EPS: f64 = 1e-10;

fn gravity(world: &mut World) {
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -G),
        })
        .unwrap();
}

/// A static ground box 100 m × 1 m with its top at y = 0.
fn ground_box(world: &mut World) {
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(100.0, 1.0).unwrap()),
        ))
        .unwrap();
}

fn settings(restitution: f64, friction: f64) -> ContactSettings {
    let s = ContactSettings::new(restitution, friction);
    assert_eq!(s.tolerance, EPS);
    s
}

/// A capsule (length 1, radius 0.1) dropped flat from h0 = 1 m (its lowest
/// point above the ground) with e = 0.8: both caps land together, the two
/// contact points get equal impulses and the capsule does not turn; apex n
/// is e^(2n) h0, as for a ball.
///
/// Tolerance: each landing is located within ε of touching, so a rebound
/// starts at most ε from the true contact height and apex n is off by at
/// most Σ ε e^(2k) < ε / (1 − e²) = 2.8 ε from the errors of all bounces
/// before it; the apex event is located where v_y = 0 and a time error δ
/// there moves the height by ½ g δ², negligible. We allow 3 ε plus the
/// round-off of 600 steps at 1 m, 1.4e-13: 5e-10 m absolute.
#[test]
fn a_flat_capsule_bounces_to_the_geometric_apex_sequence() {
    let (e, h0, r) = (0.8, 1.0, 0.1);
    let mut world = World::new(Method::Rk4).unwrap();
    ground_box(&mut world);
    let pill = world
        .add_body(
            BodyDef::rigid("pill", 1.0, Shape::capsule(1.0, r).unwrap())
                .with_position(Vector2::new(0.3, h0 + r)),
        )
        .unwrap();
    gravity(&mut world);
    world.add_event(EventSpec::apex(pill)).unwrap();
    world.set_contact_settings(settings(e, 0.0)).unwrap();
    let trace = world.run(6.0, 0.01).unwrap();
    let apexes: Vec<f64> = trace
        .events
        .iter()
        .filter(|ev| ev.name == "apex")
        .map(|ev| ev.states[pill].position.y - r)
        .collect();
    assert!(apexes.len() >= 10, "{apexes:?}");
    for (n, h) in apexes.iter().take(10).enumerate() {
        let expected = (e * e).powi(n as i32 + 1) * h0;
        assert!(
            (h - expected).abs() < 5e-10,
            "bounce {}: {h} vs {expected} ({:e})",
            n + 1,
            h - expected
        );
    }
    // The impulses were symmetric: no turn (round-off only).
    let s = world.states()[pill];
    assert!(s.angle.abs() < 1e-12, "{s:?}");
}

/// A capsule (length 0.8, radius 0.1) lying along a frictionless incline
/// of θ = 0.5 rad (a static box turned by θ) slides with a = g sin θ and
/// does not turn: after t = 2 s it has gone ½ a t² along the slope.
///
/// Tolerance: the contact force is constant (m g cos θ, shared by two
/// points), so the motion is a polynomial of degree 2 and RK4 follows it
/// exactly; what is left is the round-off of 200 steps on a 9.6 m
/// distance (200 · ulp(16) ≈ 7e-13, 1e-13 relative) and of the contact
/// solve: 1e-9 relative, as for the box on the incline (contacts.rs).
#[test]
fn a_capsule_slides_down_a_frictionless_incline_at_g_sin_theta() {
    let (theta, r) = (0.5f64, 0.1);
    let normal = Vector2::new(-theta.sin(), theta.cos());
    let mut world = World::new(Method::Rk4).unwrap();
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
    let pill = world
        .add_body(
            BodyDef::rigid("pill", 1.0, Shape::capsule(0.8, r).unwrap())
                .with_position(r * normal)
                .with_rotation(theta, 0.0),
        )
        .unwrap();
    gravity(&mut world);
    world.set_contact_settings(settings(0.0, 0.0)).unwrap();
    let t = 2.0;
    world.run(t, 0.01).unwrap();
    let s = world.states()[pill];
    let down = Vector2::new(-theta.cos(), -theta.sin());
    let along = (s.position - r * normal).dot(&down);
    let a = G * theta.sin();
    let measured = 2.0 * along / (t * t);
    assert!(((measured - a) / a).abs() < 1e-9, "{measured} vs {a}");
    // Still on the slope (its centre r above it) and not turned.
    let off = (s.position - r * normal).dot(&normal);
    assert!(off.abs() < 2.0 * EPS, "{off:e}");
    assert!((s.angle - theta).abs() < 1e-12, "{}", s.angle - theta);
}

/// A rounded box (core 1 × 0.5, radius 0.1) dropped from 0.2 m with e = 0
/// comes to rest with its centre at half-height plus radius, 0.35 m, not
/// turned, and stays there for 3 s.
///
/// Tolerance: the landing is located within ε of touching and the resting
/// contact then holds the separation (it is cancelled, not integrated
/// away): 2 ε.
#[test]
fn a_rounded_box_rests_at_its_half_height_plus_its_radius() {
    let mut world = World::new(Method::Rk4).unwrap();
    ground_box(&mut world);
    let block = world
        .add_body(
            BodyDef::rigid("block", 2.0, Shape::rounded_box(1.0, 0.5, 0.1).unwrap())
                .with_position(Vector2::new(-0.4, 0.35 + 0.2)),
        )
        .unwrap();
    gravity(&mut world);
    world.set_contact_settings(settings(0.0, 0.5)).unwrap();
    world.run(3.0, 0.01).unwrap();
    let s = world.states()[block];
    assert!(
        (s.position.y - 0.35).abs() < 2.0 * EPS,
        "{:e}",
        s.position.y - 0.35
    );
    assert!((s.position.x + 0.4).abs() < 1e-12, "{s:?}");
    assert!(s.angle.abs() < 1e-12, "{s:?}");
    assert!(s.velocity.norm() < 1e-12, "{s:?}");
}

/// A capsule (length 1, radius 0.25) dropped tilted by 0.3 rad onto a
/// static segment ground from (0, 1): it lands on its lower cap, rocks
/// down with e = 0 and friction 0.5, and rests flat with its centre at
/// the radius, 0.25 m.
///
/// Tolerance: as for the rounded box, the rest is held within ε of
/// touching; both caps touch at the end, so 2 ε on the height, and the
/// angle (a multiple of π; 0 here) within 2 ε / (half the length) = 4 ε.
#[test]
fn a_capsule_comes_to_rest_flat_on_a_segment_ground() {
    let mut world = World::new(Method::Rk4).unwrap();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::zeros(),
            Some(Shape::segment(Vector2::new(-5.0, 0.0), Vector2::new(5.0, 0.0)).unwrap()),
        ))
        .unwrap();
    let pill = world
        .add_body(
            BodyDef::rigid("pill", 1.0, Shape::capsule(1.0, 0.25).unwrap())
                .with_position(Vector2::new(0.0, 1.0))
                .with_rotation(0.3, 0.0),
        )
        .unwrap();
    gravity(&mut world);
    world.set_contact_settings(settings(0.0, 0.5)).unwrap();
    world.run(4.0, 0.01).unwrap();
    let s = world.states()[pill];
    assert!(
        (s.position.y - 0.25).abs() < 2.0 * EPS,
        "{:e}",
        s.position.y - 0.25
    );
    assert!(s.angle.abs() < 4.0 * EPS, "{:e}", s.angle);
    assert!(
        s.velocity.norm() < 1e-9 && s.angular_velocity.abs() < 1e-9,
        "{s:?}"
    );
}

/// A capsule (length 1, radius 0.2) moving straight down at 1 m/s without
/// gravity, its axis along n = (cos 60°, sin 60°) and its lower cap's
/// centre on the line through a static box's corner along n: the cap meets
/// the corner with normal n, the impulse passes through the centre of
/// mass, and with e = 1 against the fixed box the capsule leaves with
/// v − 2 (v·n) n and no spin.
///
/// Tolerance: the impact is located within ε of touching, so the cap's
/// centre is within ε of its true position and n within ε / r = 5e-10 rad
/// of the true normal; the reflected velocity then turns by twice that:
/// |Δv| ≤ 2 |v| ε / r = 1e-9 m/s, and the spin from the impulse's lever
/// arm ≤ (its magnitude 2 |v·n| m = 1.7 kg·m/s) · (ε / r · L/2) / I: we
/// allow 1e-9 m/s and 1e-8 rad/s.
#[test]
fn a_cap_on_a_corner_reflects_along_the_line_of_centres() {
    let (r, half) = (0.2, 0.5);
    let n = Vector2::new(60f64.to_radians().cos(), 60f64.to_radians().sin());
    let corner = Vector2::new(0.5, 0.5);
    let mut world = World::new(Method::Rk4).unwrap();
    world
        .add_body(BodyDef::fixed(
            "block",
            Vector2::zeros(),
            Some(Shape::rectangle(1.0, 1.0).unwrap()),
        ))
        .unwrap();
    // The cap's centre 0.1 m above its contact position.
    let cap = corner + r * n + Vector2::new(0.0, 0.1);
    let v = Vector2::new(0.0, -1.0);
    let pill = world
        .add_body(
            BodyDef::rigid("pill", 1.0, Shape::capsule(2.0 * half, r).unwrap())
                .with_position(cap + half * n)
                .with_rotation(60f64.to_radians(), 0.0)
                .with_velocity(v),
        )
        .unwrap();
    world.set_contact_settings(settings(1.0, 0.0)).unwrap();
    world.run(0.2, 0.01).unwrap();
    let s = world.states()[pill];
    let expected = v - 2.0 * v.dot(&n) * n;
    assert!(
        (s.velocity - expected).norm() < 1e-9,
        "{:?} vs {expected:?}",
        s.velocity
    );
    assert!(s.angular_velocity.abs() < 1e-8, "{s:?}");
}
