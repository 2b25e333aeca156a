//! Small generators of [`ManyBodyScene`]s for tests and benchmarks, laid out
//! as Box2D v3's `shared/benchmarks.c` lays them out, with its benchmark
//! protocol's settings: dt = 1/60 s, 4 substeps, gravity (0, −10) m/s²,
//! Box2D's default material (friction 0.6, restitution 0).
//!
//! Scenes with joints: [`joint_grid`] and [`falling_hinges`] (in
//! `scenes/hinges.rs`), [`ragdoll`] and [`rain`] (in `scenes/ragdoll.rs`),
//! each documented with its Box2D source and what differs from it.

use super::{BodyKind, ManyBodyScene, SceneBody};
use engine::Shape;

mod hinges;
mod ragdoll;

pub use hinges::{
    HINGE_HALF_EXTENT, JOINT_GRID_GROUP, JOINT_GRID_RADIUS, falling_hinges, joint_grid,
};
pub use ragdoll::{BONE_FRICTION, BONES, RAIN_TILE, RagdollParams, RainParams, ragdoll, rain};

/// The benchmark step, s (Box2D's `benchmark/main.c`: 60 Hz).
pub const BENCHMARK_DT: f64 = 1.0 / 60.0;
/// The benchmark substep count (Box2D's default `subStepCount`).
pub const BENCHMARK_SUBSTEPS: usize = 4;
/// The benchmark gravity, m/s² (Box2D's `b2DefaultWorldDef`).
pub const BENCHMARK_GRAVITY: [f64; 2] = [0.0, -10.0];

/// Side of the boxes of the pyramids and stacks, m (`b2MakeSquare(0.5)`).
pub const BOX_SIDE: f64 = 1.0;

/// The static ground of `CreateLargePyramid`: a box of half-extents
/// (100, 1) m centred at (0, −1), so its top face is the line y = 0. Wider
/// when a pyramid's base needs it (half-width `max(100, base)` m).
fn ground(base: usize) -> SceneBody {
    let half_width = (base as f64).max(100.0);
    SceneBody::fixed(
        Shape::rectangle(2.0 * half_width, 2.0).expect("positive, finite extents"),
        [0.0, -1.0],
    )
}

fn unit_box() -> Shape {
    Shape::rectangle(BOX_SIDE, BOX_SIDE).expect("positive, finite extents")
}

/// Box2D's `CreateLargePyramid` with a base of `base` boxes (the benchmark
/// uses 100: 5050 boxes): boxes of 1 m, density 1 kg/m², resting side by
/// side, row i (from 0 at the bottom) at y = i + 0.5 m holding `base − i`
/// boxes, each row shifted by half a box, centred on x = 0, on the ground
/// of the benchmark. Body 0 is the ground; the top box is the last body.
/// `base` 0 gives the ground alone.
pub fn pyramid(base: usize) -> ManyBodyScene {
    let a = 0.5 * BOX_SIDE;
    let mut bodies = Vec::with_capacity(1 + base * (base + 1) / 2);
    bodies.push(ground(base));
    for i in 0..base {
        let y = (2.0 * i as f64 + 1.0) * a;
        for j in i..base {
            // benchmarks.c: x = (i + 1)·a + 2(j − i)·a − a·base.
            let x = (i as f64 + 1.0) * a + 2.0 * (j - i) as f64 * a - a * base as f64;
            bodies.push(SceneBody::dynamic(unit_box(), [x, y], 1.0));
        }
    }
    benchmark_scene(bodies)
}

/// A vertical stack of `count` boxes of 1 m (density 1 kg/m², friction
/// `friction`) on the benchmark ground, box k resting on box k − 1 at
/// y = k + 0.5 m and shifted sideways by `jitter` m with alternating sign
/// (+, −, +, …), the deterministic stand-in for Solver2D's random ±0.01 m.
/// Body 0 is the ground; the top box is the last body.
pub fn vertical_stack(count: usize, friction: f64, jitter: f64) -> ManyBodyScene {
    let mut bodies = Vec::with_capacity(1 + count);
    let mut floor = ground(0);
    floor.friction = friction;
    bodies.push(floor);
    for k in 0..count {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        let mut b = SceneBody::dynamic(unit_box(), [sign * jitter, k as f64 + 0.5], 1.0);
        b.friction = friction;
        bodies.push(b);
    }
    benchmark_scene(bodies)
}

/// Box2D's `CreateTumbler` with a `grid` × `grid` block of boxes of 0.25 m
/// (the benchmark uses 45: 2025 boxes; density 1 kg/m²) inside a hollow
/// 20 m square box turning at 25°/s about (0, 10) m.
///
/// One difference from Box2D's scene: there the hollow box is a *dynamic*
/// body of density 50 kg/m² with four shapes, driven through a revolute
/// joint by a motor of speed 25°/s and maximum torque 1e8 N·m, which this
/// description (one shape per body, no joints) cannot express. Here its
/// four walls are four *kinematic* bodies, all with their origin on the
/// axis (0, 10) m and angular velocity 25°/s, each with one off-centre wall
/// polygon (walls 1 m thick centred 10 m from the axis): the same rigid
/// rotation, imposed exactly instead of through a joint the load could
/// slow by a little. Bodies 0–3 are the walls (right, left, top, bottom).
pub fn tumbler(grid: usize) -> ManyBodyScene {
    use nalgebra::Vector2;
    let omega = 25f64.to_radians();
    let wall = |cx: f64, cy: f64, hw: f64, hh: f64| {
        let v = vec![
            Vector2::new(cx - hw, cy - hh),
            Vector2::new(cx + hw, cy - hh),
            Vector2::new(cx + hw, cy + hh),
            Vector2::new(cx - hw, cy + hh),
        ];
        let polygon = engine::ConvexPolygon::new(v).expect("a non-degenerate rectangle");
        SceneBody::kinematic(Shape::Polygon(polygon), [0.0, 10.0], [0.0, 0.0], omega)
    };
    let mut bodies = vec![
        wall(10.0, 0.0, 0.5, 10.0),
        wall(-10.0, 0.0, 0.5, 10.0),
        wall(0.0, 10.0, 10.0, 0.5),
        wall(0.0, -10.0, 10.0, 0.5),
    ];
    let small = Shape::rectangle(0.25, 0.25).expect("positive, finite extents");
    let mut y = -0.2 * grid as f64 + 10.0;
    for _ in 0..grid {
        let mut x = -0.2 * grid as f64;
        for _ in 0..grid {
            bodies.push(SceneBody::dynamic(small.clone(), [x, y], 1.0));
            x += 0.4;
        }
        y += 0.4;
    }
    benchmark_scene(bodies)
}

/// Box2D's `CreateSmash`: zero gravity, an 8 m box of density 8 kg/m² at
/// (−20, 0) m moving at 40 m/s into a block of `columns` × `rows` boxes of
/// 0.4 m (density 1 kg/m²) at x = 30 + 0.4 i, y = 0.4 (j − rows/2) m (the
/// benchmark uses 120 × 80). Box2D creates the block asleep; with sleeping
/// off, as here, it is awake from the start. Body 0 is the big box.
pub fn smash(columns: usize, rows: usize) -> ManyBodyScene {
    let mut big = SceneBody::dynamic(
        Shape::rectangle(8.0, 8.0).expect("positive, finite extents"),
        [-20.0, 0.0],
        8.0,
    );
    big.velocity = [40.0, 0.0];
    let mut bodies = vec![big];
    let d = 0.4;
    let small = Shape::rectangle(d, d).expect("positive, finite extents");
    for i in 0..columns {
        for j in 0..rows {
            let position = [i as f64 * d + 30.0, (j as f64 - rows as f64 / 2.0) * d];
            bodies.push(SceneBody::dynamic(small.clone(), position, 1.0));
        }
    }
    ManyBodyScene {
        gravity: [0.0, 0.0],
        ..benchmark_scene(bodies)
    }
}

fn benchmark_scene(bodies: Vec<SceneBody>) -> ManyBodyScene {
    ManyBodyScene {
        gravity: BENCHMARK_GRAVITY,
        dt: BENCHMARK_DT,
        substeps: BENCHMARK_SUBSTEPS,
        bodies,
        joints: Vec::new(),
    }
}

/// Indices of the dynamic bodies of `scene`.
pub fn dynamic_indices(scene: &ManyBodyScene) -> Vec<usize> {
    scene
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| b.kind == BodyKind::Dynamic)
        .map(|(i, _)| i)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_layout_matches_box2d_benchmark() {
        let s = pyramid(4);
        s.validate().unwrap();
        assert_eq!(s.bodies.len(), 1 + 10);
        // Bottom row: base boxes side by side, touching, centred on 0.
        let xs: Vec<f64> = s.bodies[1..5].iter().map(|b| b.position[0]).collect();
        assert_eq!(xs, vec![-1.5, -0.5, 0.5, 1.5]);
        assert!(s.bodies[1..5].iter().all(|b| b.position[1] == 0.5));
        // Next row shifted by half a box, one box up.
        assert_eq!(s.bodies[5].position, [-1.0, 1.5]);
        // Top box on the axis.
        assert_eq!(s.bodies.last().unwrap().position, [0.0, 3.5]);
        assert_eq!(s.bodies[0].kind, BodyKind::Static);
        assert_eq!(dynamic_indices(&s).len(), 10);
        // Mass: 10 boxes of 1 m² at 1 kg/m².
        assert_eq!(s.dynamic_mass(), 10.0);
    }

    #[test]
    fn tumbler_and_smash_layouts() {
        let t = tumbler(3);
        t.validate().unwrap();
        assert_eq!(t.bodies.len(), 4 + 9);
        assert!(t.bodies[..4].iter().all(|b| b.kind == BodyKind::Kinematic
            && b.position == [0.0, 10.0]
            && b.angular_velocity == 25f64.to_radians()));
        // The block sits inside the walls' inner faces (±9.5 m about the axis).
        assert!(
            t.bodies[4..]
                .iter()
                .all(|b| b.position[0].abs() < 9.0 && (b.position[1] - 10.0).abs() < 9.0)
        );
        let s = smash(3, 2);
        s.validate().unwrap();
        assert_eq!(s.gravity, [0.0, 0.0]);
        assert_eq!(s.bodies.len(), 1 + 6);
        assert_eq!(s.bodies[0].mass(), 8.0 * 64.0);
        assert_eq!(s.bodies[1].position, [30.0, -0.4]);
        assert_eq!(s.bodies[6].position[0], 30.8);
    }

    #[test]
    fn stack_layout() {
        let s = vertical_stack(3, 0.3, 0.01);
        s.validate().unwrap();
        let p: Vec<[f64; 2]> = s.bodies[1..].iter().map(|b| b.position).collect();
        assert_eq!(p, vec![[0.01, 0.5], [-0.01, 1.5], [0.01, 2.5]]);
        assert!(s.bodies.iter().all(|b| b.friction == 0.3));
    }
}
