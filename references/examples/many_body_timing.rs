//! Informal timing of the two many-body adapters (Box2D through boxdd,
//! rapier2d-f64) on Box2D's pyramid layout, by the benchmark protocol: dt
//! 1/60 s, 4 substeps, sleeping off, one thread, step 0 untimed, engines run
//! alternately in one process, the minimum over repeats. Not a test (no
//! timing belongs in `cargo test`); the harness's benchmark is the real one.
//!
//! ```text
//! cargo run --release -p references --example many_body_timing -- [base steps repeats]...
//! ```
//! Without arguments: base 20 for 500 steps and base 100 for 300 steps, 3
//! repeats each. After the runs it prints the quality figures of the last
//! repeat: the top box's sink (m), the largest speed (m/s), the deepest
//! overlap from the poses (m) and the engine's own contact counts.

use references::box2d_world::Box2dWorld;
use references::many_body::{ManyBodyEngine, ManyBodyScene, deepest_overlap, pyramid};
use references::rapier_many::RapierManyWorld;
use std::time::Instant;

fn build(which: usize, scene: &ManyBodyScene) -> Box<dyn ManyBodyEngine> {
    match which {
        0 => Box::new(Box2dWorld::new(scene).expect("Box2D builds the pyramid")),
        _ => Box::new(RapierManyWorld::new(scene).expect("rapier builds the pyramid")),
    }
}

/// Runs `steps` steps (step 0 untimed) and returns ms per timed step.
fn time_run(engine: &mut dyn ManyBodyEngine, steps: usize) -> f64 {
    engine.step().expect("step 0");
    let start = Instant::now();
    for _ in 1..steps {
        engine.step().expect("step");
    }
    start.elapsed().as_secs_f64() * 1e3 / (steps - 1) as f64
}

fn quality(engine: &mut dyn ManyBodyEngine, scene: &ManyBodyScene) -> String {
    let mut s = Vec::new();
    engine.samples(&mut s).expect("samples");
    let top = scene.bodies.len() - 1;
    let sink = scene.bodies[top].position[1] - s[top].position[1];
    let vmax = s.iter().map(|q| q.speed()).fold(0.0, f64::max);
    let overlap = deepest_overlap(&scene.bodies, &s).map_or(0.0, |o| o.depth);
    let c = engine.contact_counts().expect("contacts");
    format!(
        "top sink {sink:.4} m, max speed {vmax:.4} m/s, deepest overlap (poses) {overlap:.5} m; \
         engine: {} pairs, {} points, {} penetrating, deepest {:.5} m",
        c.touching_pairs, c.points, c.penetrating_points, c.deepest_penetration
    )
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| {
            a.parse()
                .expect("arguments are whole numbers: base steps repeats")
        })
        .collect();
    let runs: Vec<[usize; 3]> = if args.is_empty() {
        vec![[20, 500, 3], [100, 300, 3]]
    } else {
        assert!(
            args.len().is_multiple_of(3),
            "arguments come in threes: base steps repeats"
        );
        args.chunks(3).map(|c| [c[0], c[1], c[2]]).collect()
    };
    for [base, steps, repeats] in runs {
        assert!(
            base >= 1 && steps >= 2 && repeats >= 1,
            "base ≥ 1, steps ≥ 2, repeats ≥ 1"
        );
        let scene = pyramid(base);
        let boxes = scene.bodies.len() - 1;
        let mut best = [f64::INFINITY; 2];
        let mut all = [Vec::new(), Vec::new()];
        let mut last = [String::new(), String::new()];
        let mut names = [""; 2];
        for _ in 0..repeats {
            for which in 0..2 {
                let mut engine = build(which, &scene);
                names[which] = engine.name();
                let ms = time_run(engine.as_mut(), steps);
                best[which] = best[which].min(ms);
                all[which].push(ms);
                last[which] = quality(engine.as_mut(), &scene);
            }
        }
        println!("pyramid base {base} ({boxes} boxes), {steps} steps, {repeats} repeats:");
        for which in 0..2 {
            let runs: Vec<String> = all[which].iter().map(|m| format!("{m:.3}")).collect();
            println!(
                "  {:<24} min {:.3} ms/step (runs: {})",
                names[which],
                best[which],
                runs.join(", ")
            );
            println!("  {:<24} {}", "", last[which]);
        }
        println!("  rapier / Box2D = {:.2}", best[1] / best[0]);
    }
}
