//! A box dropped on the ground: the smallest contact program.
//!
//! ```sh
//! cargo run --release -p etalon2d --example drop_box
//! ```
//!
//! The soft-step contact model (Box2D v3's solver) catches the box; it
//! comes to rest sunk into the ground by its contact spring's compression
//! (1.25 g/ω² for a unit box, ω = 2π·60 rad/s against a static body: about
//! 0.09 mm), which the program prints.

use etalon2d::prelude::*;

fn main() -> Result<()> {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )?;
    world.set_gravity(Vector2::new(0.0, -9.81))?;
    world.add_body(BodyDef::fixed(
        "ground",
        Vector2::new(0.0, -0.5),
        Some(Shape::rectangle(20.0, 1.0)?),
    ))?;
    let boxed = world.add_body(
        BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0)?)
            .with_position(Vector2::new(0.0, 3.0))
            .with_rotation(0.3, 0.0),
    )?;
    let trace = world.run(3.0, 1.0 / 60.0)?;
    for sample in trace.samples.iter().step_by(30) {
        let s = &sample.states[boxed];
        println!(
            "t = {:4.2} s   y = {:8.5} m   angle = {:8.5} rad   vy = {:8.4} m/s",
            sample.t, s.position.y, s.angle, s.velocity.y
        );
    }
    let last = &trace.last().expect("a run has samples").states[boxed];
    println!(
        "at rest: centre {:.3} mm below 0.5 m",
        1e3 * (0.5 - last.position.y)
    );
    Ok(())
}
