//! Time per stage of the soft step at several thread counts, side by side:
//! one world per count, stepped in turns (a round of `steps` steps on each
//! in turn, `rounds` rounds), each stage's time per step kept as the
//! smallest over the rounds (min-of-N: a busy machine only adds time).
//!
//! ```text
//! cargo build --release -p scene --example stage_times
//! target/release/examples/stage_times scenes/bench/large_pyramid.toml 20 15 1,2
//! ```
//! The worlds are stepped alike, so every round compares the same part of
//! the run. The substep stages run as one job on several threads and are
//! timed as one there ("substeps": integrate, warm start, solve, relax);
//! at one thread they are timed apart and summed into the same row.

use std::error::Error;
use std::time::Instant;

type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// Rows of the table: a name and the profile phases summed into it.
const ROWS: [(&str, &[&str]); 9] = [
    ("pairs", &["pairs"]),
    ("collide", &["collide"]),
    ("prepare", &["prepare"]),
    ("substeps", &["integrate", "warm_start", "solve", "relax"]),
    ("restitution", &["restitution"]),
    ("store", &["store"]),
    ("continuous", &["continuous"]),
    ("sleep", &["sleep"]),
    ("total", &[]),
];

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let usage = "usage: stage_times SCENE.toml [STEPS=20] [ROUNDS=10] [THREADS=1,2]";
    let file = args.next().ok_or(usage)?;
    let steps: usize = args.next().map_or(Ok(20), |s| s.parse())?;
    let rounds: usize = args.next().map_or(Ok(10), |s| s.parse())?;
    let counts: Vec<usize> = args
        .next()
        .unwrap_or_else(|| "1,2".into())
        .split(',')
        .map(|s| s.parse())
        .collect::<std::result::Result<_, _>>()?;
    let scene = scene::Scene::load(&file)?;
    let mut worlds = Vec::new();
    for &threads in &counts {
        let mut world = scene.build_world(None)?;
        if let Some(engine::ContactModel::SoftStep(settings)) = world.contact_model() {
            world.set_contact_model(engine::ContactModel::SoftStep(engine::SoftStepSettings {
                threads,
                ..settings
            }))?;
        }
        world.set_energy_limit(None)?;
        world.set_profiling(true);
        world.step(scene.dt())?;
        worlds.push(world);
    }
    // best[count][row]: ms per step, the smallest over the rounds.
    let mut best = vec![[f64::INFINITY; ROWS.len()]; counts.len()];
    for _ in 0..rounds {
        for (world, best) in worlds.iter_mut().zip(&mut best) {
            world.reset_profile();
            let started = Instant::now();
            for _ in 0..steps {
                world.step(scene.dt())?;
            }
            let wall = 1e3 * started.elapsed().as_secs_f64() / steps as f64;
            let phases = world.profile().phases();
            for (slot, (_, names)) in best.iter_mut().zip(ROWS) {
                let ms = if names.is_empty() {
                    wall
                } else {
                    phases
                        .iter()
                        .filter(|(n, _)| names.contains(n))
                        .map(|(_, d)| 1e3 * d.as_secs_f64() / steps as f64)
                        .sum()
                };
                *slot = slot.min(ms);
            }
        }
    }
    println!(
        "{file}: {} bodies, {steps} steps x {rounds} rounds, min over rounds, ms per step",
        worlds[0].bodies().len()
    );
    print!("| stage |");
    for c in &counts {
        print!(" {c} thread(s) |");
    }
    println!(" ratio 1st/last |");
    for (row, (name, _)) in ROWS.iter().enumerate() {
        print!("| {name} |");
        for b in &best {
            print!(" {:.3} |", b[row]);
        }
        println!(" {:.2} |", best[0][row] / best[best.len() - 1][row]);
    }
    Ok(())
}
