//! A sensor gate counting falling balls: a static sensor band across the
//! air, balls dropped above it one after the other. The sensor never
//! pushes; it reports each ball entering and leaving (sensor events, read
//! after every step), and the program counts them.
//!
//! ```sh
//! cargo run --release -p etalon2d --example sensor_gate
//! ```

use etalon2d::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )?;
    world.set_gravity(Vector2::new(0.0, -10.0))?;
    world.add_body(BodyDef::fixed(
        "ground",
        Vector2::new(0.0, -0.5),
        Some(Shape::rectangle(20.0, 1.0)?),
    ))?;
    // The gate: a band 0.2 m thick, its top face at y = 2 m.
    let gate = world.add_body(
        BodyDef::fixed(
            "gate",
            Vector2::new(0.0, 1.9),
            Some(Shape::rectangle(20.0, 0.2)?),
        )
        .as_sensor(),
    )?;
    // Five balls, 0.1 m radius, their lowest points 0.5 m to 2.5 m above it.
    for k in 0..5 {
        let drop = 0.5 * (k + 1) as f64;
        world.add_body(
            BodyDef::rigid("ball", 0.1, Shape::circle(0.1)?)
                .with_position(Vector2::new(-4.0 + 2.0 * k as f64, 2.1 + drop)),
        )?;
    }
    let dt = 1.0 / 60.0;
    let (mut inside, mut passed) = (0, 0);
    for _ in 0..120 {
        world.step(dt)?;
        let events = world.step_events()?;
        for e in &events.sensor_began {
            assert_eq!(e.sensor.body, gate);
            inside += 1;
            let drop = (world.time() - dt) * (world.time() - dt) * 5.0;
            println!(
                "t = {:.3} s: ball {} enters the gate (free fall of about {drop:.2} m)",
                world.time(),
                e.visitor.body
            );
        }
        for e in &events.sensor_ended {
            inside -= 1;
            passed += 1;
            println!(
                "t = {:.3} s: ball {} leaves the gate",
                world.time(),
                e.visitor.body
            );
        }
    }
    println!("{passed} balls passed the gate, {inside} still inside it");
    // Every ball fell through and rests on the ground: the sensor pushed
    // nothing.
    for (body, state) in world.bodies().iter().zip(world.states()) {
        if body.name == "ball" {
            assert!((state.position.y - 0.1).abs() < 1e-3, "{state:?}");
        }
    }
    assert_eq!((passed, inside), (5, 0));
    Ok(())
}
