//! A pyramid of boxes on the ground, stepped by the soft-step contact model
//! (Box2D's benchmark layout: base n, boxes of 1 m side by side, each row
//! offset by half a box).
//!
//! ```sh
//! cargo run --release -p etalon2d --example pyramid -- 20 600 [threads]
//! ```

use etalon2d::{BodyDef, ContactModel, Method, Shape, SoftStepSettings, World};
use nalgebra::Vector2;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let base: usize = args.next().map_or(Ok(20), |a| a.parse())?;
    let steps: usize = args.next().map_or(Ok(600), |a| a.parse())?;
    let threads: usize = args.next().map_or(Ok(1), |a| a.parse())?;
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings {
            threads,
            ..SoftStepSettings::default()
        }),
    )?;
    world.set_gravity(Vector2::new(0.0, -10.0))?;
    world.add_body(BodyDef::fixed(
        "ground",
        Vector2::new(0.0, -1.0),
        Some(Shape::rectangle(2.0 * base as f64 + 20.0, 2.0)?),
    ))?;
    let size = 1.0;
    let mut top = 0;
    for row in 0..base {
        for column in 0..base - row {
            let x = (column as f64 - (base - row) as f64 / 2.0 + 0.5) * size;
            let y = (row as f64 + 0.5) * size;
            let def = BodyDef {
                density: Some(1.0),
                mass: None,
                ..BodyDef::rigid("box", 1.0, Shape::rectangle(size, size)?)
            }
            .with_position(Vector2::new(x, y))
            .with_material(0.6, 0.0);
            top = world.add_body(def)?;
        }
    }
    let dt = 1.0 / 60.0;
    world.step(dt)?;
    world.set_profiling(true);
    world.reset_profile();
    let started = Instant::now();
    for _ in 1..steps {
        world.step(dt)?;
    }
    let elapsed = started.elapsed().as_secs_f64();
    let top_y = world.states()[top].position.y;
    let ideal = (base as f64 - 0.5) * size;
    let fastest = world
        .states()
        .iter()
        .map(|s| s.velocity.norm())
        .fold(0.0, f64::max);
    println!(
        "pyramid base {base}: {} bodies, {:.3} ms/step over {} steps; top box at {top_y:.4} m (ideal {ideal}), fastest {fastest:.2e} m/s",
        world.bodies().len(),
        1e3 * elapsed / (steps - 1) as f64,
        steps - 1
    );
    let p = world.profile();
    let n = p.steps.max(1) as f64;
    for (name, d) in p.phases() {
        if !d.is_zero() {
            println!("  {name:<12} {:.3} ms/step", 1e3 * d.as_secs_f64() / n);
        }
    }
    println!(
        "  {:.0} contacts, {:.0} touching, {:.0} points per step",
        p.contacts as f64 / n,
        p.touching as f64 / n,
        p.points as f64 / n
    );
    Ok(())
}
