//! Continuous collision against chains under the soft step: a fast box
//! fired at a ground chain from its solid side stops on it instead of
//! passing it in one step, flagged `bullet` or not; with the continuous
//! stage off, the same box passes (the reason the sweep exists), and a
//! box fired up from under the chain passes it (a chain is one-sided).
//!
//! The scene: a flat ground chain from x = 10 m to x = −10 m (listed right
//! to left: solid from above), a 0.5 m box of 1 kg 3 m above it moving
//! at 300 m/s, no gravity. At dt = 1/60 s the box moves 5 m per step,
//! ten times its size: no discrete contact sees the chain.

use etalon2d::{BodyDef, BodyId, ContactModel, Method, Shape, SoftStepSettings, World};
use nalgebra::Vector2;

const DT: f64 = 1.0 / 60.0;
/// The box's side (m).
const SIDE: f64 = 0.5;

/// The world and the box's id: the box at (0, `y`) moving at `vy` (m/s).
fn fired(y: f64, vy: f64, bullet: bool, continuous: bool) -> (World, BodyId) {
    let settings = SoftStepSettings {
        continuous,
        ..SoftStepSettings::default()
    };
    let mut world =
        World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap();
    let points = [[11.0, 0.0], [10.0, 0.0], [-10.0, 0.0], [-11.0, 0.0]]
        .iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::zeros(),
            Some(Shape::chain(points, false).unwrap()),
        ))
        .unwrap();
    let mut def = BodyDef::rigid("box", 1.0, Shape::rectangle(SIDE, SIDE).unwrap())
        .with_position(Vector2::new(0.0, y))
        .with_velocity(Vector2::new(0.0, vy));
    def.bullet = bullet;
    let shot = world.add_body(def).unwrap();
    (world, shot)
}

/// The box's centre height (m) after each of 20 steps.
fn heights(world: &mut World, shot: BodyId) -> Vec<f64> {
    (0..20)
        .map(|_| {
            world.step(DT).unwrap();
            world.states()[shot].position.y
        })
        .collect()
}

/// Stopped on the chain means the box's centre never going below the
/// chain's line (y = 0): resting on it, the centre is half a side above,
/// less the contact's millimetres of penetration, so the sign alone is
/// the criterion, with no tolerance to choose.
#[test]
fn a_fast_box_stops_on_a_ground_chain() {
    for bullet in [false, true] {
        let (mut world, shot) = fired(3.0, -300.0, bullet, true);
        let heights = heights(&mut world, shot);
        for (k, y) in heights.iter().enumerate() {
            assert!(
                *y > 0.0,
                "bullet {bullet}, step {}: the box passed the chain (y = {y} m)",
                k + 1
            );
        }
        // It did reach the chain: its first step ends at the sweep's
        // impact, half a side above the line, within the linear slop
        // (5 mm) the sweep stops short by.
        let first = heights[0];
        assert!(
            (first - 0.5 * SIDE).abs() <= 0.005,
            "bullet {bullet}: first step ends at y = {first} m"
        );
    }
}

/// Without the continuous stage the same box is 2 m under the chain after
/// one step: this test fails if the box above were stopped by anything
/// but the sweep.
#[test]
fn without_continuous_collision_the_box_passes_the_chain() {
    let (mut world, shot) = fired(3.0, -300.0, false, false);
    let heights = heights(&mut world, shot);
    assert!(heights[0] < -1.0, "after one step y = {} m", heights[0]);
}

/// Fired up from 3 m under the chain, the box passes it: the chain is
/// solid from above only, and the sweep follows it.
#[test]
fn a_fast_box_from_below_passes_a_ground_chain() {
    let (mut world, shot) = fired(-3.0, 300.0, false, true);
    let heights = heights(&mut world, shot);
    assert!(heights[0] > 1.0, "after one step y = {} m", heights[0]);
}
