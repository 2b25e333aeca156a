//! Save a world and restore it: a pile of boxes hit by a swinging chain
//! is written to bytes mid-run (CBOR through ciborium; any serde format
//! that keeps f64 bits will do), read back, and both worlds are stepped on
//! side by side. The restored one follows the original to the bit, which
//! the program prints as the worlds' state hashes step after step; a
//! clone in memory does the same without bytes.
//!
//! ```sh
//! cargo run --release -p etalon2d --example save_restore
//! ```

use etalon2d::prelude::*;

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let dt = 1.0 / 60.0;
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )?;
    world.set_gravity(Vector2::new(0.0, -10.0))?;
    world.add_body(BodyDef::fixed(
        "ground",
        Vector2::new(0.0, -0.5),
        Some(Shape::rectangle(40.0, 1.0)?),
    ))?;
    for row in 0..4 {
        for k in 0..4 - row {
            let x = (k as f64 - 0.5 * (3 - row) as f64) * 0.55;
            world.add_body(
                BodyDef::rigid("box", 1.0, Shape::rectangle(0.5, 0.5)?)
                    .with_position(Vector2::new(x, 0.25 + 0.5 * row as f64)),
            )?;
        }
    }
    let mut previous = None;
    for k in 0..3 {
        let center = Vector2::new(-2.6 + 0.8 * k as f64, 3.0);
        let link = world.add_body(
            BodyDef::rigid("link", 2.0, Shape::rectangle(0.8, 0.2)?).with_position(center),
        )?;
        let anchor = center - Vector2::new(0.4, 0.0);
        world.add_joint(JointDef::revolute(
            "hinge",
            previous,
            Some(link),
            anchor,
            Revolute::default(),
        ))?;
        previous = Some(link);
    }

    world.run(0.5, dt)?;
    let mut bytes = Vec::new();
    ciborium::into_writer(&world, &mut bytes)?;
    let mut restored: World = ciborium::from_reader(&bytes[..])?;
    let mut cloned = world.clone();
    println!(
        "saved at t = {:.3} s: {} bodies, {} joints, {} bytes",
        world.time(),
        world.bodies().len(),
        world.joint_count(),
        bytes.len()
    );
    for step in 1..=60 {
        world.step(dt)?;
        restored.step(dt)?;
        cloned.step(dt)?;
        if step % 15 == 0 {
            println!(
                "step {step:2}: original {:#018x}  restored {:#018x}  clone {:#018x}",
                world.state_hash(),
                restored.state_hash(),
                cloned.state_hash()
            );
        }
    }
    let same = world.states() == restored.states() && world.states() == cloned.states();
    println!(
        "after 60 more steps the three worlds are {}",
        if same {
            "identical to the bit"
        } else {
            "DIFFERENT"
        }
    );
    if !same {
        return Err("the restored world did not follow the original".into());
    }
    Ok(())
}
