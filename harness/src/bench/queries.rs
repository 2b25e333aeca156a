//! World ray casts timed (issue 17 part 4): this engine's
//! [`World::cast_ray`] (through the soft step's AABB trees), rapier2d-f64
//! 0.36's query pipeline (`PhysicsWorld::cast_ray`, its BVH broad phase)
//! and Box2D v3.2's `b2World_CastRayClosest` (boxdd 0.6), on one world of
//! static circles, boxes and convex polygons, the same rays for all three,
//! each the closest hit within 20 m. Min of N: the engines run alternately,
//! each casting every ray once per repeat; the time per ray is the minimum
//! over the repeats (and the median). Appended to `benchmarks.md` by the
//! bench command.
//!
//! Semantics differ slightly and are stated with the table: a ray starting
//! inside a shape is skipped by this engine and Box2D but hits at distance
//! 0 in rapier (`solid = true`); Box2D computes in f32. The hit counts are
//! printed so the workloads can be compared.

use anyhow::{Context, Result};
use engine::prelude::*;
use references::box2d_world::Box2dWorld;
use references::many_body::{ManyBodyEngine, ManyBodyScene, SceneBody};
use references::parry_queries::exact::Rng;
use references::rapier_many::RapierManyWorld;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Static bodies in the world.
pub const BODIES: usize = 2000;
/// Half-width of the square they and the ray origins are drawn in (m).
const HALF_WIDTH: f64 = 100.0;
/// Rays per repeat.
pub const RAYS: usize = 10_000;
/// Ray length (m).
pub const RAY_LENGTH: f64 = 20.0;

/// One engine's time per ray.
#[derive(Debug, Clone)]
pub struct QueryTiming {
    /// Engine name.
    pub engine: &'static str,
    /// Minimum over the repeats of the time per ray (ns).
    pub ns_min: f64,
    /// Median over the repeats (ns).
    pub ns_median: f64,
    /// Rays with a hit.
    pub hits: usize,
}

/// A random circle, box or convex polygon (at most 8 vertices, Box2D's
/// limit), centred on its centroid.
fn random_shape(rng: &mut Rng) -> Shape {
    let kind = rng.unit();
    let shape = if kind < 1.0 / 3.0 {
        Shape::circle(rng.range(0.2, 1.5))
    } else if kind < 2.0 / 3.0 {
        Shape::rectangle(rng.range(0.3, 3.0), rng.range(0.3, 3.0))
    } else {
        let n = 3 + (rng.unit() * 6.0) as usize;
        let scale = rng.range(0.3, 1.5);
        let points: Vec<Vector2<f64>> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * (k as f64 + rng.range(-0.2, 0.2)) / n as f64;
                let r = scale * rng.range(0.8, 1.0);
                Vector2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        ConvexPolygon::convex_hull(&points).map(Shape::Polygon)
    };
    shape.expect("valid random shape").centered()
}

/// The benchmark's bodies: (shape, position, angle).
fn bodies() -> Vec<(Shape, Vector2<f64>, f64)> {
    let mut rng = Rng(0xB0D1E5);
    (0..BODIES)
        .map(|_| {
            let pose = rng.pose(HALF_WIDTH);
            (
                random_shape(&mut rng),
                pose.translation.vector,
                pose.rotation.angle(),
            )
        })
        .collect()
}

/// The rays: (origin, unit direction).
fn rays() -> Vec<(Vector2<f64>, Vector2<f64>)> {
    let mut rng = Rng(0x5A7);
    (0..RAYS)
        .map(|_| {
            let origin = rng.pose(HALF_WIDTH).translation.vector;
            let a = rng.range(0.0, std::f64::consts::TAU);
            (origin, Vector2::new(a.cos(), a.sin()))
        })
        .collect()
}

/// The benchmark's world in the three engines (each stepped once, so
/// that every broad phase holds the shapes) and its rays: the workload of
/// [`measure`], also run alone by `examples/ray_timing.rs` (callgrind).
pub struct Workload {
    /// This engine's world (soft step).
    pub ours: World,
    /// rapier2d-f64's.
    pub rapier: RapierManyWorld,
    /// Box2D's.
    pub box2d: Box2dWorld,
    /// The rays: (origin, unit direction), m.
    pub rays: Vec<(Vector2<f64>, Vector2<f64>)>,
}

impl Workload {
    /// Builds the worlds and the rays.
    pub fn new() -> Result<Self> {
        let bodies = bodies();
        let mut ours = World::with_model(
            Method::SemiImplicitEuler,
            ContactModel::SoftStep(SoftStepSettings::default()),
        )?;
        let mut scene = ManyBodyScene {
            gravity: [0.0, 0.0],
            dt: 1.0 / 60.0,
            substeps: 4,
            bodies: Vec::new(),
            joints: Vec::new(),
        };
        for (k, (shape, position, angle)) in bodies.iter().enumerate() {
            let mut def = BodyDef::fixed(&format!("b{k}"), *position, Some(shape.clone()));
            def.state.angle = *angle;
            ours.add_body(def)?;
            let mut body = SceneBody::fixed(shape.clone(), [position.x, position.y]);
            body.angle = *angle;
            scene.bodies.push(body);
        }
        let mut rapier = RapierManyWorld::new(&scene).context("rapier world")?;
        let mut box2d = Box2dWorld::new(&scene).context("Box2D world")?;
        ours.step(scene.dt)?;
        rapier.step().context("rapier step")?;
        box2d.step().context("Box2D step")?;
        Ok(Workload {
            ours,
            rapier,
            box2d,
            rays: rays(),
        })
    }

    /// Casts every ray once in engine `e` (0 this engine, 1 rapier, 2
    /// Box2D), closest hit within the ray length; returns the rays that
    /// hit.
    pub fn cast_all(&self, e: usize) -> Result<usize> {
        let mut found = 0;
        for (o, d) in &self.rays {
            let hit = match e {
                0 => self
                    .ours
                    .cast_ray(*o, *d, RAY_LENGTH, QueryFilter::DEFAULT)?
                    .map(|h| h.distance),
                1 => self.rapier.cast_ray([o.x, o.y], [d.x, d.y], RAY_LENGTH),
                _ => self
                    .box2d
                    .cast_ray_closest([o.x, o.y], [RAY_LENGTH * d.x, RAY_LENGTH * d.y])
                    .context("Box2D ray")?,
            };
            found += usize::from(std::hint::black_box(hit).is_some());
        }
        Ok(found)
    }
}

/// Times the three engines on the same world and rays, `repeats` times.
pub fn measure(repeats: usize) -> Result<Vec<QueryTiming>> {
    let workload = Workload::new()?;
    let names = [
        "this engine (World::cast_ray)",
        "rapier2d-f64 0.36 (QueryPipeline::cast_ray)",
        "Box2D v3.2 (b2World_CastRayClosest, boxdd 0.6)",
    ];
    let mut times = vec![Vec::new(); 3];
    let mut hits = [0usize; 3];
    for _ in 0..repeats.max(1) {
        for (e, time) in times.iter_mut().enumerate() {
            let clock = Instant::now();
            hits[e] = workload.cast_all(e)?;
            time.push(clock.elapsed().as_secs_f64() * 1e9 / workload.rays.len() as f64);
        }
    }
    Ok(names
        .iter()
        .zip(times)
        .zip(hits)
        .map(|((engine, mut t), hits)| {
            t.sort_by(f64::total_cmp);
            QueryTiming {
                engine,
                ns_min: t[0],
                ns_median: t[t.len() / 2],
                hits,
            }
        })
        .collect())
}

/// The markdown section of `benchmarks.md`.
pub fn section(timings: &[QueryTiming], repeats: usize) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## World queries: ray casts\n");
    let _ = writeln!(
        md,
        "{RAYS} rays of {RAY_LENGTH} m (random origins and directions), closest hit, against \
         {BODIES} static circles, boxes and convex polygons in a {} m square, the same world \
         and rays in the three engines, which run alternately; ns per ray: the minimum over \
         {repeats} repeats (and the median); the ratio is the engine's minimum over this \
         engine's. A ray starting inside a shape skips it here and in Box2D, and hits it at \
         distance 0 in rapier (`solid = true`); Box2D computes in f32. The machine is shared \
         and noisy: compare ratios.\n",
        2.0 * HALF_WIDTH
    );
    let ours = timings.first().map_or(f64::NAN, |t| t.ns_min);
    let _ = writeln!(
        md,
        "| engine | ns per ray (min) | median | ratio to this engine | rays hitting |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|");
    for t in timings {
        let _ = writeln!(
            md,
            "| {} | {:.0} | {:.0} | {:.2} | {} |",
            t.engine,
            t.ns_min,
            t.ns_median,
            t.ns_min / ours,
            t.hits
        );
    }
    md.push('\n');
    md
}

/// Prints a line of `timings` (measured over `repeats` repeats) and
/// appends their section to `dir/benchmarks.md`.
pub fn append(dir: &Path, timings: &[QueryTiming], repeats: usize) -> Result<()> {
    println!(
        "bench ray casts {BODIES} shapes: {}",
        timings
            .iter()
            .map(|t| format!("{} {:.0} ns", super::short(t.engine), t.ns_min))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let path = dir.join("benchmarks.md");
    let mut md = std::fs::read_to_string(&path).unwrap_or_default();
    md.push_str(&section(timings, repeats));
    std::fs::write(&path, md)?;
    Ok(())
}
