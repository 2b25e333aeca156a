//! Cost of one step per method on the spring (case I) and the drag
//! projectile (case II). Run with `cargo bench -p harness`; CI only compiles
//! it. Ratios between methods are meaningful within one run; absolute times
//! depend on the machine.

use criterion::{Criterion, criterion_group, criterion_main};
use engine::forces::{Gravity, QuadraticDrag};
use engine::{BodyDef, Shape, World};
use harness::cases::all_methods;
use harness::scenes;
use nalgebra::Vector2;
use std::hint::black_box;

fn spring_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("spring_step");
    for method in all_methods() {
        let mut world = scenes::world("spring", method).expect("spring world");
        group.bench_function(method.id(), |b| {
            b.iter(|| black_box(world.step(0.2).expect("step")))
        });
    }
    group.finish();
}

/// The drag projectile without its landing event, so it can be stepped
/// indefinitely (it falls at terminal speed after a few seconds).
fn drag_world(method: engine::Method) -> World {
    let mut world = World::new(method).expect("world");
    let body = world
        .add_body(
            BodyDef::rigid("box", 0.3, Shape::rectangle(0.1, 0.1).expect("box"))
                .with_velocity(Vector2::new(42.42640687119285, 42.42640687119285)),
        )
        .expect("body");
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -9.80655),
        })
        .expect("gravity");
    world
        .add_force(QuadraticDrag {
            body,
            coefficient: 0.003,
        })
        .expect("drag");
    world
}

fn drag_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("projectile_drag_step");
    for method in all_methods() {
        let mut world = drag_world(method);
        group.bench_function(method.id(), |b| {
            b.iter(|| black_box(world.step(0.01).expect("step")))
        });
    }
    group.finish();
}

criterion_group!(benches, spring_step, drag_step);
criterion_main!(benches);
