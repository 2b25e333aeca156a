//! Informal side-by-side timing of this engine's soft step, Box2D v3.2
//! (through boxdd, f32) and rapier2d-f64 0.36 on Box2D's pyramid layout
//! ([`references::many_body::pyramid`]), by Box2D's benchmark protocol:
//! dt 1/60 s, 4 substeps, gravity (0, −10) m/s², sleeping off, one thread,
//! step 0 untimed, the three engines run alternately in one process (so a
//! busy machine slows all three alike), the minimum over repeats. Not a test
//! (no timing belongs in `cargo test`).
//!
//! ```text
//! cargo run --release -p references --example three_engine_timing -- [base steps repeats]...
//! ```
//! Without arguments: bases 20, 40 and 100 for 300 steps, 3 repeats each.
//! It prints ms per step for each engine, the ratios of this engine to the
//! other two, and the cost per body (µs) so the growth over the series can
//! be read; then the quality of this engine's last run (top box's sink,
//! largest speed).

use engine::{BodyDef, ContactModel, Method, SoftStepSettings, World};
use nalgebra::Vector2;
use references::box2d_world::Box2dWorld;
use references::many_body::{BodyKind, ManyBodyEngine, ManyBodyScene, pyramid};
use references::rapier_many::RapierManyWorld;
use std::time::Instant;

/// This engine with the soft step at its defaults (4 substeps, sleeping
/// off), built from the scene's bodies in order.
fn soft_step_world(scene: &ManyBodyScene) -> World {
    let settings = SoftStepSettings {
        substeps: scene.substeps,
        ..SoftStepSettings::default()
    };
    let mut world = World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings))
        .expect("valid settings");
    world
        .set_gravity(Vector2::new(scene.gravity[0], scene.gravity[1]))
        .expect("finite gravity");
    for body in &scene.bodies {
        let position = Vector2::new(body.position[0], body.position[1]);
        let def = match body.kind {
            BodyKind::Static => BodyDef::fixed("ground", position, Some(body.shape.clone())),
            BodyKind::Dynamic => BodyDef {
                density: Some(body.density),
                mass: None,
                ..BodyDef::rigid("box", 1.0, body.shape.clone())
            }
            .with_position(position),
            BodyKind::Kinematic => panic!("the pyramid has no kinematic body"),
        }
        .with_rotation(body.angle, body.angular_velocity)
        .with_material(body.friction, body.restitution);
        world.add_body(def).expect("a valid body");
    }
    world
}

/// Runs `steps` steps of engine `which` (0 this engine, 1 Box2D, 2 rapier)
/// on `scene`, step 0 untimed; returns ms per timed step and, for this
/// engine, the top box's sink (m) and the largest speed (m/s).
fn time_run(which: usize, scene: &ManyBodyScene, steps: usize) -> (f64, Option<(f64, f64)>) {
    if which == 0 {
        let mut world = soft_step_world(scene);
        let dt = scene.dt;
        world.step(dt).expect("step 0");
        let start = Instant::now();
        for _ in 1..steps {
            world.step(dt).expect("step");
        }
        let ms = start.elapsed().as_secs_f64() * 1e3 / (steps - 1) as f64;
        let top = scene.bodies.len() - 1;
        let sink = scene.bodies[top].position[1] - world.states()[top].position.y;
        let fastest = world
            .states()
            .iter()
            .map(|s| s.velocity.norm())
            .fold(0.0, f64::max);
        return (ms, Some((sink, fastest)));
    }
    let mut engine: Box<dyn ManyBodyEngine> = if which == 1 {
        Box::new(Box2dWorld::new(scene).expect("Box2D builds the pyramid"))
    } else {
        Box::new(RapierManyWorld::new(scene).expect("rapier builds the pyramid"))
    };
    engine.step().expect("step 0");
    let start = Instant::now();
    for _ in 1..steps {
        engine.step().expect("step");
    }
    (
        start.elapsed().as_secs_f64() * 1e3 / (steps - 1) as f64,
        None,
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
        vec![[20, 300, 3], [40, 300, 3], [100, 300, 3]]
    } else {
        assert!(
            args.len().is_multiple_of(3),
            "arguments come in threes: base steps repeats"
        );
        args.chunks(3).map(|c| [c[0], c[1], c[2]]).collect()
    };
    let names = [
        "soft step (this engine)",
        "Box2D 3.2 (f32)",
        "rapier2d-f64 0.36",
    ];
    for [base, steps, repeats] in runs {
        assert!(
            base >= 1 && steps >= 2 && repeats >= 1,
            "base ≥ 1, steps ≥ 2, repeats ≥ 1"
        );
        let scene = pyramid(base);
        let boxes = scene.bodies.len() - 1;
        let mut best = [f64::INFINITY; 3];
        let mut all: [Vec<f64>; 3] = Default::default();
        let mut quality = None;
        for _ in 0..repeats {
            for which in 0..3 {
                let (ms, q) = time_run(which, &scene, steps);
                best[which] = best[which].min(ms);
                all[which].push(ms);
                if q.is_some() {
                    quality = q;
                }
            }
        }
        println!("pyramid base {base} ({boxes} boxes), {steps} steps, {repeats} repeats:");
        for which in 0..3 {
            let runs: Vec<String> = all[which].iter().map(|m| format!("{m:.3}")).collect();
            println!(
                "  {:<24} min {:8.3} ms/step, {:6.3} µs/body (runs: {})",
                names[which],
                best[which],
                1e3 * best[which] / boxes as f64,
                runs.join(", ")
            );
        }
        println!(
            "  this / Box2D = {:.2}, this / rapier = {:.2}, rapier / Box2D = {:.2}",
            best[0] / best[1],
            best[0] / best[2],
            best[2] / best[1]
        );
        if let Some((sink, fastest)) = quality {
            println!("  this engine: top box sank {sink:.4} m, fastest {fastest:.2e} m/s");
        }
    }
}
