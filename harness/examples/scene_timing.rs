//! Steps one benchmark scene (an id under scenes/, e.g. `bench/rain`) in this engine alone, or in the three
//! engines side by side (Box2D's protocol as in `harness bench`: step 0
//! untimed, then the timed steps; the engines alternate, the minimum over
//! the repeats), and prints ms per step and (with `all`) this engine's time per phase
//! from a separate profiled run (`phases`: this engine alone, then its
//! phases). This engine runs on `threads` threads (default 1), the
//! others on one.
//! For instruction counts, run the `ours` mode under callgrind with
//! `--collect-atstart=no --toggle-collect=*timed_steps*`: only the timed
//! steps are counted.
//!
//! ```text
//! cargo run --release -p harness --example scene_timing -- bench/tumbler [steps repeats all|ours|phases [watched body|- [threads]]]
//! ```

use harness::bench::convert::many_body_scene;
use harness::bench::ours::SoftStepEngine;
use references::box2d_world::Box2dWorld;
use references::many_body::ManyBodyEngine;
use references::rapier_many::RapierManyWorld;
use std::time::Instant;

/// The timed steps (a separate function so that callgrind can count them
/// alone).
#[inline(never)]
fn timed_steps(engine: &mut dyn ManyBodyEngine, steps: usize) {
    for _ in 0..steps {
        engine.step().expect("a step");
    }
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let file = args.first().map(String::as_str).unwrap_or("bench/tumbler");
    let scene = harness::scenes::load(file)?;
    let steps: usize = args.get(1).map_or(Ok(120), |a| a.parse())?;
    let repeats: usize = args.get(2).map_or(Ok(3), |a| a.parse())?;
    let mode = args.get(3).map_or("all", String::as_str);
    let all = mode == "all";
    let phases = all || mode == "phases";
    let threads: usize = args.get(5).map_or(Ok(1), |a| a.parse())?;
    // A body to watch (the bench's top box): its sink and sideways drift
    // after this engine's run are printed.
    let watched = match args.get(4).filter(|name| *name != "-") {
        Some(name) => Some(
            scene
                .body_id(name)
                .ok_or_else(|| anyhow::anyhow!("{file}: no body named '{name}'"))?,
        ),
        None => None,
    };
    let neutral = many_body_scene(&scene)?;
    let engines = if all { 3 } else { 1 };
    let mut best = [f64::INFINITY; 3];
    let names = ["ours", "rapier2d", "Box2D"];
    for _ in 0..repeats {
        for (e, best) in best.iter_mut().enumerate().take(engines) {
            let mut engine: Box<dyn ManyBodyEngine> = match e {
                0 => Box::new(SoftStepEngine::with_threads(&scene, false, threads)?),
                1 => Box::new(RapierManyWorld::new(&neutral)?),
                _ => Box::new(Box2dWorld::new(&neutral)?),
            };
            engine.step()?;
            let started = Instant::now();
            timed_steps(engine.as_mut(), steps);
            let ms = 1e3 * started.elapsed().as_secs_f64() / steps as f64;
            *best = best.min(ms);
            if let (0, Some(i)) = (e, watched) {
                let mut samples = Vec::new();
                engine.samples(&mut samples)?;
                let (start, end) = (neutral.bodies[i].position, samples[i].position);
                let fastest = samples.iter().map(|s| s.speed()).fold(0.0, f64::max);
                println!(
                    "  watched: sink {:.4e} m, drift {:.4e} m; fastest {:.4e} m/s",
                    start[1] - end[1],
                    (end[0] - start[0]).abs(),
                    fastest
                );
            }
        }
    }
    for e in 0..engines {
        let on = if e == 0 { threads } else { 1 };
        println!(
            "{file}: {:<8} {:.3} ms/step (min of {repeats}, {on} thread(s))",
            names[e], best[e]
        );
    }
    if !phases {
        return Ok(());
    }
    // This engine's phases, in a separate profiled run.
    let mut engine = SoftStepEngine::with_threads(&scene, true, threads)?;
    engine.step()?;
    timed_steps(&mut engine, steps);
    let p = engine.world().profile();
    let n = p.steps.max(1) as f64;
    let phases: Vec<String> = p
        .phases()
        .into_iter()
        .filter(|(_, d)| !d.is_zero())
        .map(|(name, d)| format!("{name} {:.3}", 1e3 * d.as_secs_f64() / n))
        .collect();
    println!("  phases (ms/step): {}", phases.join(", "));
    println!(
        "  per step: {:.0} contacts, {:.0} touching, {:.0} points",
        p.contacts as f64 / n,
        p.touching as f64 / n,
        p.points as f64 / n
    );
    Ok(())
}
