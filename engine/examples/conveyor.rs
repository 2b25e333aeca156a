//! A conveyor belt: a static belt whose surface moves at 2 m/s (its
//! tangent speed, Box2D's), and three boxes of different frictions set on
//! it at rest. Friction drags each toward the belt's speed at μ g; the
//! program prints when each one catches up, against u/(μ g).
//!
//! ```sh
//! cargo run --release -p etalon2d --example conveyor
//! ```

use etalon2d::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )?;
    let g = 10.0;
    world.set_gravity(Vector2::new(0.0, -g))?;
    let u = 2.0;
    world.add_body(BodyDef {
        friction: Some(1.0),
        tangent_speed: Some(u),
        ..BodyDef::fixed(
            "belt",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(40.0, 1.0)?),
        )
    })?;
    // Mixed by the geometric mean with the belt's 1: the pair's μ is the
    // box's square root, so μ² gives μ.
    let mus = [0.2, 0.4, 0.8];
    let boxes: Vec<BodyId> = mus
        .iter()
        .enumerate()
        .map(|(k, &mu)| {
            world.add_body(BodyDef {
                friction: Some(mu * mu),
                ..BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                    .with_position(Vector2::new(-15.0 + 3.0 * k as f64, 0.5))
            })
        })
        .collect::<Result<_>>()?;
    let dt = 1.0 / 60.0;
    // Sliding, a box gains mu g h per substep (h = dt/4): within that of u
    // it has caught up.
    let h = dt / 4.0;
    let mut caught = vec![None; boxes.len()];
    for _ in 0..120 {
        world.step(dt)?;
        for (k, &b) in boxes.iter().enumerate() {
            if caught[k].is_none() && (world.states()[b].velocity.x - u).abs() < mus[k] * g * h {
                caught[k] = Some(world.time());
            }
        }
    }
    for (k, &mu) in mus.iter().enumerate() {
        let t = caught[k].ok_or("a box never reached the belt's speed")?;
        let expected = u / (mu * g);
        println!(
            "mu = {mu}: moves with the belt from t = {t:.3} s (u/(mu g) = {expected:.3} s, \
             sampled at step ends)"
        );
        assert!(t >= expected - 1e-9 && t <= expected + dt + 1e-9, "{t}");
    }
    Ok(())
}
