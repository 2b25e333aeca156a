//! Cost of a step per method on the scene of every case that declares
//! `bench: true` (the spring of case I and the drag projectile of case II),
//! built from its scene file. Run with
//! `cargo bench -p harness`; CI only compiles it. Ratios between methods are
//! meaningful within one run; absolute times depend on the machine.
//!
//! Each iteration runs [`STEPS`] steps from the scene's initial state (the
//! world is rebuilt outside the timed part), so a terminal event — the drag
//! projectile lands after 585 steps of 0.01 s — is never reached and every
//! iteration does the same work. Criterion reports the time of the
//! [`STEPS`]-step batch.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use harness::cases::{CASES, all_methods};
use harness::scenes;
use std::hint::black_box;

/// Steps per timed batch.
const STEPS: u32 = 100;

fn bench_scene(c: &mut Criterion, id: &str) {
    let scene = scenes::load(id).expect("case scene");
    let dt = scene.dt();
    let mut group = c.benchmark_group(format!("{id}_{STEPS}_steps"));
    for method in all_methods() {
        group.bench_function(method.id(), |b| {
            b.iter_batched(
                || {
                    let mut world = scene.build_world(Some(method)).expect("world");
                    // Timing the integration, not the energy check of user
                    // scenes (see scenes::timed_world).
                    world.set_energy_limit(None).expect("no limit");
                    world
                },
                |mut world| {
                    for i in 1..=STEPS {
                        black_box(world.step_to(f64::from(i) * dt).expect("step"));
                    }
                    world
                },
                BatchSize::SmallInput,
            )
        });
    }
    group.finish();
}

/// Every case that declares a bench, on its first scene.
fn declared(c: &mut Criterion) {
    for case in CASES.iter().filter(|case| case.bench) {
        let scene = case
            .scenes
            .first()
            .unwrap_or_else(|| panic!("case '{}' declares a bench but no scene", case.id));
        bench_scene(c, scene);
    }
}

/// Criterion's own charts go through plotters, which this workspace builds
/// with the `ab_glyph` feature (no system fonts): register the embedded
/// font before criterion draws.
fn config() -> Criterion {
    harness::pictures::font::ensure_fonts();
    Criterion::default()
}

criterion_group! {
    name = benches;
    config = config();
    targets = declared
}
criterion_main!(benches);
