//! Steps a scene file with this engine alone, for instruction counts of
//! the soft step: step 0 (which builds the contacts) first, then `steps`
//! steps inside [`measured`], the function to collect.
//!
//! ```text
//! cargo build --release -p scene --example step_scene
//! valgrind --tool=callgrind --toggle-collect='*step_scene::measured*' \
//!     target/release/examples/step_scene scenes/bench/joint_grid.toml 100
//! callgrind_annotate --inclusive=yes callgrind.out.<pid>
//! ```
//! Without valgrind it prints the wall time per step (one run: noisy;
//! `harness bench` is the measurement). It lives in the scene crate so
//! that a build with line tables for `callgrind_annotate --auto=yes`
//! (`CARGO_PROFILE_RELEASE_DEBUG=line-tables-only`, another target
//! folder) compiles the engine and the scene crate only.

use std::error::Error;
use std::time::Instant;

type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// The timed (or collected) steps.
#[inline(never)]
fn measured(world: &mut engine::World, dt: f64, steps: usize) -> Result<()> {
    for _ in 0..steps {
        world.step(dt)?;
    }
    Ok(())
}

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let file = args
        .next()
        .ok_or("usage: step_scene SCENE.toml [STEPS, default 100]")?;
    let steps: usize = args.next().map_or(Ok(100), |s| s.parse())?;
    let scene = scene::Scene::load(&file)?;
    let mut world = scene.build_world(None)?;
    world.set_energy_limit(None)?;
    world.step(scene.dt())?;
    let started = Instant::now();
    measured(&mut world, scene.dt(), steps)?;
    let ms = 1e3 * started.elapsed().as_secs_f64() / steps.max(1) as f64;
    println!(
        "{file}: {} bodies, {} joints, {steps} steps after step 0: {ms:.3} ms per step",
        world.bodies().len(),
        scene.joint_count()
    );
    Ok(())
}
