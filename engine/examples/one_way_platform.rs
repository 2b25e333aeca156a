//! A one-way platform: a pre-solve hook disables the contact between a
//! ball and a platform while the contact normal says the ball is below the
//! platform (or coming up through it), so the ball, thrown up from below,
//! passes through it and then lands on it.
//!
//! ```sh
//! cargo run --release -p etalon2d --example one_way_platform
//! ```

use etalon2d::prelude::*;

/// Lets the platform hold only what comes down on it from above.
#[derive(Clone)]
struct OneWay {
    platform: BodyId,
    disabled: usize,
}

impl ContactHooks for OneWay {
    fn pre_solve(&mut self, contact: &PreSolveContact) -> bool {
        // The normal points from `a` to `b`: as seen from the platform, it
        // must point up for the other shape to rest on it.
        let up = if contact.a.body == self.platform {
            contact.normal.y
        } else if contact.b.body == self.platform {
            -contact.normal.y
        } else {
            return true;
        };
        // Also refuse a contact that is still deep (the ball is partway
        // through): only a touch at the surface from above holds.
        let deepest = contact.points[..contact.count]
            .iter()
            .map(|p| p.1)
            .fold(f64::INFINITY, f64::min);
        let keep = up > 0.5 && deepest > -0.05;
        if !keep {
            self.disabled += 1;
        }
        keep
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The sweep of fast bodies against static shapes does not ask the
    // pre-solve hook (as Box2D's): the ball, moving more than half its
    // radius per step, would be stopped under the platform. Off here.
    let settings = SoftStepSettings {
        continuous: false,
        ..SoftStepSettings::default()
    };
    let mut world = World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings))?;
    world.set_gravity(Vector2::new(0.0, -10.0))?;
    world.add_body(BodyDef::fixed(
        "ground",
        Vector2::new(0.0, -0.5),
        Some(Shape::rectangle(20.0, 1.0)?),
    ))?;
    // A platform 0.2 m thick, its top face at y = 3 m.
    let platform = world.add_body(BodyDef::fixed(
        "platform",
        Vector2::new(0.0, 2.9),
        Some(Shape::rectangle(4.0, 0.2)?),
    ))?;
    // A ball thrown up from the ground at 9 m/s: it would rise to
    // 0.25 + 81/20 = 4.3 m, through the platform.
    let ball = world.add_body(
        BodyDef::rigid("ball", 1.0, Shape::circle(0.25)?)
            .with_position(Vector2::new(0.0, 0.25))
            .with_velocity(Vector2::new(0.0, 9.0)),
    )?;
    world.set_contact_hooks(OneWay {
        platform,
        disabled: 0,
    })?;
    let dt = 1.0 / 60.0;
    let mut highest: f64 = 0.0;
    for step in 0..180 {
        world.step(dt)?;
        let y = world.states()[ball].position.y;
        highest = highest.max(y);
        for e in &world.step_events()?.touch_began {
            if e.a.body == platform || e.b.body == platform {
                println!(
                    "t = {:.3} s: the ball lands on the platform at y = {y:.3} m",
                    world.time()
                );
            }
        }
        if step % 30 == 29 {
            println!("t = {:.2} s: ball at y = {y:.3} m", world.time());
        }
    }
    let y = world.states()[ball].position.y;
    println!("highest point {highest:.3} m; at rest on the platform at y = {y:.4} m");
    // It went through on the way up and rests on the top face (3 m) after.
    assert!(highest > 4.0, "{highest}");
    assert!((y - 3.25).abs() < 1e-3, "{y}");
    Ok(())
}
