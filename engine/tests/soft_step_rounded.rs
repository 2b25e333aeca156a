//! Segments, capsules and rounded polygons under the soft step (issue 19):
//! they rest where their geometry says on boxes and chains, slide along a
//! chain without bumps, stack, and give the same bits on 1 and 2 threads.
//!
//! **Tolerance of a resting height.** The soft step resolves a contact to
//! within its linear slop, `LINEAR_SLOP` = 5 mm (Box2D v3.2's
//! `B2_LINEAR_SLOP`, `engine/src/tunables.rs`): the scale below which its
//! contact geometry does not tell positions apart (the vertex–vertex rule,
//! the reference-edge choice and the chain's edge preference all work to a
//! tenth of it). The soft contact spring's own static sink is far smaller:
//! g / (2π f)² = 10 / (2π · 30 Hz)² = 0.28 mm at the default contact
//! stiffness. So a body resting on k contacts stacked is within k × 5 mm of
//! the height its geometry gives.

use etalon2d::forces::Gravity;
use etalon2d::{BodyDef, ContactModel, Method, Shape, SoftStepSettings, World};
use nalgebra::Vector2;

/// The soft step's linear slop (m): see the module documentation.
const LINEAR_SLOP: f64 = 0.005;

/// Gravity (m/s²) of every world here.
const G: f64 = 10.0;

/// Step (s).
const DT: f64 = 1.0 / 60.0;

fn soft_world(settings: SoftStepSettings) -> World {
    let mut world =
        World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap();
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -G),
        })
        .unwrap();
    world
}

/// A static box 40 m wide whose top is y = 0.
fn box_ground(world: &mut World) {
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(40.0, 1.0).unwrap()),
        ))
        .unwrap();
}

/// A static chain along y = 0 from x = 20 to x = −20 in 1 m segments
/// (listed right to left: solid from above), its ends ghosts.
fn chain_ground(world: &mut World) {
    let points = (-21..=21)
        .rev()
        .map(|x| Vector2::new(f64::from(x), 0.0))
        .collect();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::zeros(),
            Some(Shape::chain(points, false).unwrap()),
        ))
        .unwrap();
}

/// A dynamic body of 1 kg with `shape` at (x, y), at rest.
fn body_at(name: &str, shape: Shape, x: f64, y: f64) -> BodyDef {
    let mut def = BodyDef::rigid(name, 1.0, shape);
    def.state.position = Vector2::new(x, y);
    def
}

fn run(world: &mut World, seconds: f64) {
    for _ in 0..(seconds / DT).round() as usize {
        world.step(DT).unwrap();
    }
}

/// A capsule (length 1 m, radius 0.25 m) dropped lying on a box ground
/// rests with its axis at y = r; a rounded box (core 1 × 0.5 m, radius
/// 0.05 m) rests at half its core height plus its radius, 0.3 m; both
/// level and still. Resting heights within the linear slop (module docs);
/// speeds below 1 mm/s and angles below 1 mrad are what "at rest" reads
/// after 2 s of a 30 Hz contact with damping ratio 10 (its transients die
/// within a few of its periods, 33 ms each).
#[test]
fn a_capsule_and_a_rounded_box_rest_on_a_box_at_their_geometric_height() {
    let mut world = soft_world(SoftStepSettings::default());
    box_ground(&mut world);
    let capsule = world
        .add_body(body_at(
            "capsule",
            Shape::capsule(1.0, 0.25).unwrap(),
            -2.0,
            0.5,
        ))
        .unwrap();
    let rounded = world
        .add_body(body_at(
            "rounded",
            Shape::rounded_box(1.0, 0.5, 0.05).unwrap(),
            2.0,
            0.6,
        ))
        .unwrap();
    run(&mut world, 2.0);
    for (id, height) in [(capsule, 0.25), (rounded, 0.25 + 0.05)] {
        let s = &world.states()[id];
        assert!(
            (s.position.y - height).abs() < LINEAR_SLOP,
            "{} vs {height}",
            s.position.y
        );
        assert!(s.velocity.norm() < 1e-3, "{:?}", s.velocity);
        assert!(s.angle.abs() < 1e-3, "{}", s.angle);
    }
}

/// A capsule standing upright on a box ground (its axis vertical, a
/// cap down) rests with its centre at half its length plus its radius:
/// the cap against the face, a single point.
#[test]
fn an_upright_capsule_rests_on_its_cap() {
    let mut world = soft_world(SoftStepSettings::default());
    box_ground(&mut world);
    let mut def = body_at("pill", Shape::capsule(1.0, 0.25).unwrap(), 0.0, 0.8);
    def.state.angle = std::f64::consts::FRAC_PI_2;
    let id = world.add_body(def).unwrap();
    run(&mut world, 1.0);
    let s = &world.states()[id];
    assert!(
        (s.position.y - 0.75).abs() < LINEAR_SLOP,
        "{}",
        s.position.y
    );
}

/// Three capsules (length 1 m, radius 0.25 m) dropped one over another
/// stack at 0.25, 0.75 and 1.25 m: the k-th within k linear slops (one per
/// contact under it, module docs), level and still.
#[test]
fn capsules_stack() {
    let mut world = soft_world(SoftStepSettings::default());
    box_ground(&mut world);
    let ids: Vec<_> = (0..3)
        .map(|k| {
            let y = 0.3 + 0.55 * f64::from(k);
            world
                .add_body(body_at(
                    &format!("pill{k}"),
                    Shape::capsule(1.0, 0.25).unwrap(),
                    0.0,
                    y,
                ))
                .unwrap()
        })
        .collect();
    run(&mut world, 3.0);
    for (k, id) in ids.into_iter().enumerate() {
        let s = &world.states()[id];
        let height = 0.25 + 0.5 * k as f64;
        let contacts = (k + 1) as f64;
        assert!(
            (s.position.y - height).abs() < contacts * LINEAR_SLOP,
            "capsule {k}: {} vs {height}",
            s.position.y
        );
        assert!(
            s.position.x.abs() < contacts * LINEAR_SLOP,
            "{}",
            s.position.x
        );
        assert!(s.velocity.norm() < 1e-3, "{:?}", s.velocity);
    }
}

/// A capsule rests on a chain at y = r, then, pushed along it at 5 m/s
/// without friction, crosses 10 joins between segments: no ghost
/// collision. At each join a collided-alone segment would offer the next
/// segment's end as a corner, and a capsule's cap meeting it at 5 m/s is
/// thrown up at a good fraction of that speed (metres per second, as a
/// box's 1.94 m/s on tiled boxes in issue 19). The bound: the upward
/// speed stays below what one step of gravity gives, g·dt = 0.17 m/s,
/// divided by 10 (a soft contact that only holds the capsule against
/// gravity never exceeds that one-step speed; a tenth of it leaves a
/// bump of a thousandth of the ghost's no room), and the spin below the
/// spin that upward speed would give at the cap's end, (g·dt / 10) /
/// (L/2 + r).
#[test]
fn a_capsule_on_a_chain_rests_and_slides_without_bumps() {
    let mut world = soft_world(SoftStepSettings::default());
    chain_ground(&mut world);
    let mut def = body_at("pill", Shape::capsule(1.0, 0.25).unwrap(), -8.0, 0.26);
    def.friction = Some(0.0);
    let id = world.add_body(def).unwrap();
    run(&mut world, 1.0);
    let s = world.states()[id];
    assert!(
        (s.position.y - 0.25).abs() < LINEAR_SLOP,
        "{}",
        s.position.y
    );
    world.set_velocity(id, Vector2::new(5.0, 0.0), 0.0).unwrap();
    let bound = G * DT / 10.0;
    let spin_bound = bound / (0.5 + 0.25);
    let (mut up, mut spin) = (0.0f64, 0.0f64);
    for _ in 0..120 {
        world.step(DT).unwrap();
        let s = &world.states()[id];
        up = up.max(s.velocity.y);
        spin = spin.max(s.angular_velocity.abs());
    }
    let s = &world.states()[id];
    assert!(s.position.x > 1.0, "crossed 9 joins: {}", s.position.x);
    assert!(up < bound, "upward speed {up} m/s");
    assert!(spin < spin_bound, "spin {spin} rad/s");
    assert!(
        (s.position.y - 0.25).abs() < LINEAR_SLOP,
        "{}",
        s.position.y
    );
    // Frictionless: the speed along the chain is kept, to the solver's
    // relaxation of a contact it only holds up (below 1 mm/s).
    assert!((s.velocity.x - 5.0).abs() < 1e-3, "{}", s.velocity.x);
}

/// A rain of capsules, rounded boxes, segments-on-bodies and boxes into a
/// box container, with every pair kind (capsule–capsule, capsule–polygon,
/// capsule–circle, rounded–rounded, chain–capsule): the same state hash at
/// 1 and 2 threads (the soft step's results do not depend on the thread
/// count, `SoftStepSettings::threads`), with the work split forced
/// (`min_work_per_thread` 0).
#[test]
fn the_same_bits_on_one_and_two_threads() {
    let hash = |threads: usize| {
        let mut world = soft_world(SoftStepSettings {
            threads,
            min_work_per_thread: 0,
            ..SoftStepSettings::default()
        });
        chain_ground(&mut world);
        for (name, x) in [("left", -3.0), ("right", 3.0)] {
            world
                .add_body(BodyDef::fixed(
                    name,
                    Vector2::new(x, 2.0),
                    Some(Shape::rectangle(0.2, 4.0).unwrap()),
                ))
                .unwrap();
        }
        for k in 0..24 {
            let x = -2.4 + 0.4 * f64::from(k % 12);
            let y = 0.6 + 0.7 * f64::from(k / 12) + 0.05 * f64::from(k % 3);
            let shape = match k % 4 {
                0 => Shape::capsule(0.4, 0.12).unwrap(),
                1 => Shape::rounded_box(0.2, 0.15, 0.04).unwrap(),
                2 => Shape::circle(0.15).unwrap(),
                _ => Shape::rectangle(0.25, 0.2).unwrap(),
            };
            let mut def = body_at(&format!("b{k}"), shape, x, y);
            def.state.angle = 0.3 * f64::from(k);
            world.add_body(def).unwrap();
        }
        run(&mut world, 1.5);
        world.state_hash()
    };
    assert_eq!(hash(1), hash(2));
}
