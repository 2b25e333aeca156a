//! World queries on a small scene: a laser ray, a swept ball, an overlap
//! box, a point and the nearest shape, before and after the scene falls.
//!
//! ```sh
//! cargo run --release -p etalon2d --example ray_cast
//! ```
//!
//! Three boxes and a ball fall on the ground under the soft step; the
//! program asks the world what a horizontal laser at 0.25 m height meets,
//! where a ball thrown along it would first touch something, what lies in
//! a box around the pile, which shape holds a point, and how far a probe
//! circle is from its nearest shape. Units: m.

use etalon2d::prelude::*;

fn main() -> Result<()> {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )?;
    world.set_gravity(Vector2::new(0.0, -9.81))?;
    let mut names = Vec::new();
    let mut add = |world: &mut World, def: BodyDef| -> Result<BodyId> {
        names.push(def.name.clone());
        world.add_body(def)
    };
    add(
        &mut world,
        BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(20.0, 1.0)?),
        ),
    )?;
    for (k, x) in [2.0, 4.0, 6.0].into_iter().enumerate() {
        add(
            &mut world,
            BodyDef::rigid(&format!("box{k}"), 1.0, Shape::rectangle(0.5, 0.5)?)
                .with_position(Vector2::new(x, 1.0 + k as f64)),
        )?;
    }
    add(
        &mut world,
        BodyDef::rigid("ball", 1.0, Shape::circle(0.3)?).with_position(Vector2::new(8.0, 2.0)),
    )?;

    let all = QueryFilter::DEFAULT;
    for when in ["at the start", "after 2 s"] {
        if when != "at the start" {
            world.run(2.0, 1.0 / 60.0)?;
        }
        println!("{when} (t = {:.2} s):", world.time());
        let origin = Vector2::new(-5.0, 0.25);
        let laser = Vector2::new(1.0, 0.0);
        match world.cast_ray(origin, laser, 30.0, all)? {
            Some(hit) => println!(
                "  laser from (-5, 0.25) hits {} at x = {:.4} m, {:.4} m away, normal ({:.3}, {:.3})",
                names[hit.shape.body], hit.point.x, hit.distance, hit.normal.x, hit.normal.y
            ),
            None => println!("  laser from (-5, 0.25) meets nothing within 30 m"),
        }
        let all_hits = world.cast_ray_all(origin, laser, 30.0, all)?;
        let listed: Vec<String> = all_hits
            .iter()
            .map(|h| format!("{} at {:.3} m", names[h.shape.body], h.distance))
            .collect();
        println!("  every shape on the laser: [{}]", listed.join(", "));

        let ball = Shape::circle(0.2)?;
        let start = Isometry2::translation(-5.0, 0.3);
        match world.cast_shape(&ball, start, Vector2::new(20.0, 0.0), all)? {
            Some(hit) => println!(
                "  a 0.2 m ball rolled 20 m from (-5, 0.3) first touches {} after {:.4} m, at ({:.4}, {:.4})",
                names[hit.shape.body],
                hit.fraction * 20.0,
                hit.point.x,
                hit.point.y
            ),
            None => println!("  a 0.2 m ball rolled 20 m from (-5, 0.3) touches nothing"),
        }

        let inside: Vec<&str> = world
            .overlap_aabb(Vector2::new(1.5, 0.0), Vector2::new(6.5, 4.0), all)?
            .iter()
            .map(|s| names[s.body].as_str())
            .collect();
        println!("  shapes in the box [1.5, 6.5] x [0, 4]: {inside:?}");
        let at: Vec<&str> = world
            .shapes_at_point(Vector2::new(2.0, 0.25), all)?
            .iter()
            .map(|s| names[s.body].as_str())
            .collect();
        println!("  shapes holding the point (2, 0.25): {at:?}");
        let probe = Shape::circle(0.1)?;
        if let Some(near) =
            world.closest_shape(&probe, Isometry2::translation(3.0, 1.5), 5.0, all)?
        {
            println!(
                "  nearest shape to a 0.1 m probe at (3, 1.5): {}, {:.4} m away",
                names[near.shape.body], near.distance
            );
        }
    }
    Ok(())
}
