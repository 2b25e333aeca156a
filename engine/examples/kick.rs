//! A ball kicked from a program: an impulse off its centre sends it up
//! and spinning, a velocity set later sends it sideways, a target pose
//! drives a kinematic paddle; the smallest use of the control calls.
//!
//! ```sh
//! cargo run --release -p etalon2d --example kick
//! ```
//!
//! It prints the velocity the impulse gave (J/m, and (r × J)/I for the
//! spin), the highest point of the flight against the closed form
//! v²/(2g) above the start (the soft step's symplectic Euler lags it by
//! about v·h/2, h the substep, which it prints too), and the paddle
//! reaching its target.

use etalon2d::prelude::*;

fn main() -> Result<()> {
    let dt = 1.0 / 60.0;
    let g = 9.81;
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )?;
    world.set_gravity(Vector2::new(0.0, -g))?;
    world.add_body(BodyDef::fixed(
        "ground",
        Vector2::new(0.0, -0.5),
        Some(Shape::rectangle(40.0, 1.0)?),
    ))?;
    let ball = world.add_body(
        BodyDef::rigid("ball", 0.5, Shape::circle(0.25)?).with_position(Vector2::new(0.0, 0.25)),
    )?;
    let paddle = world.add_body(BodyDef::kinematic(
        "paddle",
        Vector2::new(-5.0, 3.0),
        Shape::rectangle(1.0, 0.2)?,
        Vector2::zeros(),
        0.0,
    ))?;
    world.run(0.5, dt)?; // settle on the ground

    // The kick: 4 N·s straight up, 0.1 m left of the centre.
    let start = world.states()[ball];
    let impulse = Vector2::new(0.0, 4.0);
    world.apply_linear_impulse(ball, impulse, start.position - Vector2::new(0.1, 0.0))?;
    let kicked = world.states()[ball];
    let body = &world.bodies()[ball];
    println!(
        "kick of {} N·s: vy = {:.4} m/s (J/m = {:.4}), spin = {:.4} rad/s ((r × J)/I = {:.4})",
        impulse.y,
        kicked.velocity.y,
        impulse.y / body.mass,
        kicked.angular_velocity,
        -0.1 * impulse.y / body.inertia.expect("a rigid ball"),
    );

    // Up to the apex.
    let v0 = kicked.velocity.y;
    let mut highest = start.position.y;
    while world.states()[ball].velocity.y > 0.0 {
        world.step(dt)?;
        highest = highest.max(world.states()[ball].position.y);
    }
    let closed = v0 * v0 / (2.0 * g);
    let h = dt / SoftStepSettings::default().substeps as f64;
    println!(
        "apex {:.4} m above the start; closed form v²/(2g) = {:.4} m; below it by {:.4} m \
         (symplectic Euler's lag v·h/2 = {:.4} m, h = dt/substeps)",
        highest - start.position.y,
        closed,
        closed - (highest - start.position.y),
        v0 * h / 2.0
    );

    // Sideways at 2 m/s from the apex, and the paddle to (−3, 4), 0.5 rad
    // in one step.
    world.set_velocity(ball, Vector2::new(2.0, 0.0), 0.0)?;
    world.set_target_pose(paddle, Vector2::new(-3.0, 4.0), 0.5, dt)?;
    world.step(dt)?;
    let p = world.states()[paddle];
    println!(
        "paddle after one step: ({:.6}, {:.6}) m at {:.6} rad (target (−3, 4) at 0.5)",
        p.position.x, p.position.y, p.angle
    );
    world.set_velocity(paddle, Vector2::zeros(), 0.0)?;
    world.run(world.time() + 1.0, dt)?;
    let s = world.states()[ball];
    println!(
        "ball one second later: x = {:.3} m, y = {:.3} m (2 m/s sideways since the apex)",
        s.position.x, s.position.y
    );
    Ok(())
}
