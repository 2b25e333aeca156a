//! The soft-step solver on the base-20 (210 boxes) and base-40 (820 boxes)
//! pyramids of the benchmark (`scenes/pyramid_20.toml`,
//! `scenes/bench/pyramid_40.toml`), so that a change's effect on speed is
//! measured before it lands. Run with `cargo bench -p harness --bench
//! pyramids`; CI only compiles it.
//!
//! Each iteration steps a settled pyramid [`STEPS`] times: the world is
//! built and stepped 60 times (1 s, the pile settles) outside the timed
//! part, as the steady state is what a benchmark of a standing pile
//! measures. For instruction counts, repeatable on a shared machine, run
//! the `pyramid` example of the engine under `valgrind --tool=callgrind`.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use harness::scenes;
use std::hint::black_box;

/// Steps per timed batch.
const STEPS: u32 = 20;

fn pyramids(c: &mut Criterion) {
    for id in ["pyramid_20", "bench/pyramid_40"] {
        let scene = scenes::load(id).expect("benchmark scene");
        let dt = scene.dt();
        let mut group = c.benchmark_group(format!("soft_step_{}", id.trim_start_matches("bench/")));
        group.sample_size(10);
        group.bench_function(format!("{STEPS}_steps"), |b| {
            b.iter_batched(
                || {
                    let mut world = scene.build_world(None).expect("world");
                    world.set_energy_limit(None).expect("no limit");
                    for _ in 0..60 {
                        world.step(dt).expect("settling step");
                    }
                    world
                },
                |mut world| {
                    for _ in 0..STEPS {
                        black_box(world.step(dt).expect("step"));
                    }
                    world
                },
                BatchSize::LargeInput,
            )
        });
        group.finish();
    }
}

/// Criterion's charts go through plotters, built here with `ab_glyph` and
/// no system fonts: register the embedded font before criterion draws.
fn config() -> Criterion {
    harness::pictures::font::ensure_fonts();
    Criterion::default()
}

criterion_group! {
    name = benches;
    config = config();
    targets = pyramids
}
criterion_main!(benches);
