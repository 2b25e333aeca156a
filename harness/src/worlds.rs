//! The worlds of the seed's cases I and II, built from CASES.md's numbers.

use anyhow::Result;
use engine::forces::{AngularDrag, Attachment, Gravity, QuadraticDrag, Spring, Torque};
use engine::{BodyDef, EventSpec, Method, Shape, TimeWindow, World};
use nalgebra::Vector2;

/// Case I (seed §5): a 20 kg particle at x = 100 m on an axial spring
/// k = 50 N/m, l0 = 50 m anchored at the origin.
pub fn spring(method: Method) -> Result<World> {
    let mut world = World::new(method)?;
    let mass = world.add_body(BodyDef::particle("mass", 20.0, Vector2::new(100.0, 0.0)))?;
    world.add_force(Spring {
        a: Attachment::World(Vector2::zeros()),
        b: Attachment::center_of(mass),
        stiffness: 50.0,
        rest_length: 50.0,
        axis: Some(Vector2::x()),
    })?;
    Ok(world)
}

/// The seed's box (case II): 0.1 m × 0.1 m, 0.3 kg, I = 5e-4 kg·m².
fn seed_box(world: &mut World, velocity: Vector2<f64>) -> Result<usize> {
    let def = BodyDef::rigid("box", 0.3, Shape::rectangle(0.1, 0.1)?).with_velocity(velocity);
    Ok(world.add_body(def)?)
}

/// Launch velocity: 60 m/s at 45° (m/s).
fn launch() -> Vector2<f64> {
    let a = std::f64::consts::FRAC_PI_4;
    60.0 * Vector2::new(a.cos(), a.sin())
}

/// Case II `projectile` (seed §6): the box launched in vacuum, g = 9.80655.
/// With `drag`, case `projectile_drag`: D = 0.003 kg/m at the centre of mass.
pub fn projectile(method: Method, drag: bool) -> Result<World> {
    let mut world = World::new(method)?;
    let body = seed_box(&mut world, launch())?;
    world.add_force(Gravity {
        g: Vector2::new(0.0, -references::projectile::SEED_GRAVITY),
    })?;
    if drag {
        world.add_force(QuadraticDrag {
            body,
            coefficient: 0.003,
        })?;
    }
    world.add_event(EventSpec::landing(body, 0.0))?;
    world.add_event(EventSpec::apex(body))?;
    Ok(world)
}

/// Case II `torque` (seed eq. 6.16–6.20): the box at rest, a couple
/// τ = R × F = 0.005 N·m during [0, 0.7) s. With `drag`, case
/// `angular_drag`: −D ω|ω|, D = 0.003.
pub fn torque(method: Method, drag: bool) -> Result<World> {
    let mut world = World::new(method)?;
    let body = seed_box(&mut world, Vector2::zeros())?;
    let couple = Torque::from_lever(body, Vector2::new(0.05, 0.05), Vector2::new(0.3, 0.4));
    world.add_force_during(Box::new(couple), TimeWindow::first(0.7)?)?;
    if drag {
        world.add_force(AngularDrag {
            body,
            coefficient: 0.003,
        })?;
    }
    Ok(world)
}
