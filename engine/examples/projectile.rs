//! The seed's projectile with quadratic air drag (case II, `docs/cases.md#projectile_drag`):
//! a 0.1 m box of 0.3 kg thrown at 60 m/s, 45°, integrated by RK4 at
//! h = 0.01 s, its landing located inside the step by root finding.
//!
//! ```sh
//! cargo run --release -p etalon2d --example projectile
//! ```

use etalon2d::prelude::*;

fn main() -> Result<()> {
    let mut world = World::new(Method::Rk4)?;
    let v = 60.0 * std::f64::consts::FRAC_1_SQRT_2;
    let projectile = world.add_body(
        BodyDef::rigid("box", 0.3, Shape::rectangle(0.1, 0.1)?).with_velocity(Vector2::new(v, v)),
    )?;
    world.set_gravity(Vector2::new(0.0, -9.80655))?; // the seed's value
    world.add_force(QuadraticDrag {
        body: projectile,
        coefficient: 0.003, // D = ρ C A / 2, kg/m
    })?;
    world.add_event(EventSpec::apex(projectile))?;
    world.add_event(EventSpec::landing(projectile, 0.0))?;
    let trace = world.run(10.0, 0.01)?;
    for e in &trace.events {
        let s = &e.states[projectile];
        println!(
            "{:<8} t = {:.9} s   x = {:.9} m   y = {:.9} m",
            e.name, e.t, s.position.x, s.position.y
        );
    }
    // The reference (docs/cases.md): T = 5.854653263330 s, R = 113.8638433141 m.
    Ok(())
}
