//! Two scenes of revolute joints from Box2D v3.2's test code: the
//! `joint_grid` benchmark (`shared/benchmarks.c`, `CreateJointGrid`) and
//! the Falling Hinges determinism scene (`shared/determinism.c`,
//! `CreateFallingHinges`).

use super::{BENCHMARK_DT, BENCHMARK_GRAVITY, BENCHMARK_SUBSTEPS};
use crate::many_body::{JointKind, ManyBodyScene, Motor, Pose, SceneBody, SceneJoint, Spring};
use engine::{ConvexPolygon, Shape};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// Radius of the joint grid's circles, m.
pub const JOINT_GRID_RADIUS: f64 = 0.4;

/// The collision group of the joint grid's circles (Box2D gives them
/// category 2 and mask ~2: they never collide with each other, and the
/// scene has nothing else).
pub const JOINT_GRID_GROUP: u32 = 0;

/// Box2D's `CreateJointGrid` with `n` × `n` circles (the benchmark uses
/// 100, 20 in Box2D's debug build): circles of radius 0.4 m, density
/// 1 kg/m², 1 m apart, column k and row i at (k, −i) m; body index
/// k·n + i (Box2D's creation order). Each circle is joined to the one
/// above it (anchor midway, (k, −i + 0.5)) and to the one on its left
/// ((k − 0.5, −i)) by a free revolute joint. In the top row (i = 0) the
/// seven circles with n/2 − 3 ≤ k ≤ n/2 + 3 are static, as in Box2D (so
/// for n ≤ 7 the whole top row); the grid hangs from them. The circles
/// never collide with each other (one collision group, Box2D's category
/// and mask bits). Sleeping off, gravity (0, −10), dt 1/60 s, 4 substeps.
///
/// One difference: Box2D also joins neighbouring static circles of the
/// top row to each other; those joints connect two static bodies, do
/// nothing, and are left out (a scene joint needs a dynamic body).
pub fn joint_grid(n: usize) -> ManyBodyScene {
    let circle = Shape::circle(JOINT_GRID_RADIUS).expect("a positive radius");
    let fixed = |k: usize, i: usize| {
        let (k, half) = (k as i64, (n / 2) as i64);
        i == 0 && k >= half - 3 && k <= half + 3
    };
    let mut bodies = Vec::with_capacity(n * n);
    let mut joints = Vec::with_capacity(2 * n * n);
    for k in 0..n {
        for i in 0..n {
            let p = [k as f64, -(i as f64)];
            let mut b = if fixed(k, i) {
                SceneBody::fixed(circle.clone(), p)
            } else {
                SceneBody::dynamic(circle.clone(), p, 1.0)
            };
            b.collision_group = Some(JOINT_GRID_GROUP);
            bodies.push(b);
            let index = k * n + i;
            if i > 0 && !(fixed(k, i - 1) && fixed(k, i)) {
                joints.push(SceneJoint::revolute(
                    Some(index - 1),
                    Some(index),
                    [p[0], p[1] + 0.5],
                    0.0,
                ));
            }
            if k > 0 && !(fixed(k - 1, i) && fixed(k, i)) {
                joints.push(SceneJoint::revolute(
                    Some(index - n),
                    Some(index),
                    [p[0] - 0.5, p[1]],
                    0.0,
                ));
            }
        }
    }
    ManyBodyScene {
        gravity: BENCHMARK_GRAVITY,
        dt: BENCHMARK_DT,
        substeps: BENCHMARK_SUBSTEPS,
        bodies,
        joints,
    }
}

/// Half-extent of the Falling Hinges boxes, m (`h` in Box2D's source).
pub const HINGE_HALF_EXTENT: f64 = 0.25;

/// Box2D's `CreateFallingHinges`: on a static ground box of 80 m × 2 m
/// centred at (0, −1) m, 4 columns of 20 boxes of 0.5 m (density 1 kg/m²,
/// friction 0.6), column j, row i at x = −3.75 + 2.5 j + 0.1 i,
/// y = 0.25 + 0.5 i m, turned by −0.1 rad (even i) or +0.1 rad (odd i);
/// each even box is hinged to the odd box above it (10 pairs per column,
/// the pairs not joined to each other) at its own local point (−0.25, 0.25)
/// and the upper box's local point (−0.25, −0.25), which do not coincide at
/// t = 0 (0.11 m apart: the joint pulls them together as the boxes fall).
/// Each hinge: joint angle θB − θA (Box2D's frames are unrotated:
/// reference angle 0), limits [−0.1π, 0.2π] rad, a spring of 1 Hz, ζ = 1
/// toward angle 0, and a motor of speed 0 and maximum torque 0.25 N·m
/// (joint friction). Body 0 is the ground; box (j, i) is body 1 + 20 j + i.
/// Gravity (0, −10), dt 1/60 s, 4 substeps (Box2D's determinism test
/// steps at 60 Hz with 4 substeps).
///
/// Differences from Box2D's scene:
/// - the boxes are `b2MakeRoundedBox(0.225, 0.225, 0.025)` there (a
///   0.45 m square with a 0.025 m rounding radius: outer size 0.5 m);
///   here octagons: the 0.5 m square with its corners cut at the
///   rounding's tangent points ((±0.225, ±0.25), (±0.25, ±0.225)), area
///   0.24875 m² against Box2D's 0.24946 m²;
/// - Box2D sets these joints' constraint damping ratio to 0 (its default
///   is 2); this description has no per-joint constraint softness, so
///   every engine uses its own default;
/// - Box2D runs the scene until every body sleeps and hashes the poses
///   then; with sleeping off (the adapters' setting) "at rest" must be
///   decided by the caller (e.g. every speed below a threshold).
pub fn falling_hinges() -> ManyBodyScene {
    let h = HINGE_HALF_EXTENT;
    let r = 0.1 * h;
    let octagon = Shape::Polygon(
        ConvexPolygon::new(vec![
            Vector2::new(h - r, -h),
            Vector2::new(h, -(h - r)),
            Vector2::new(h, h - r),
            Vector2::new(h - r, h),
            Vector2::new(-(h - r), h),
            Vector2::new(-h, h - r),
            Vector2::new(-h, -(h - r)),
            Vector2::new(-(h - r), -h),
        ])
        .expect("a convex octagon"),
    );
    let (columns, rows) = (4, 20);
    let mut bodies = vec![SceneBody::fixed(
        Shape::rectangle(80.0, 2.0).expect("positive extents"),
        [0.0, -1.0],
    )];
    let mut joints = Vec::new();
    let (offset, dx) = (0.4 * h, 10.0 * h);
    let x_base = -0.5 * dx * (columns as f64 - 1.0);
    for j in 0..columns {
        let x = x_base + j as f64 * dx;
        for i in 0..rows {
            let mut b = SceneBody::dynamic(
                octagon.clone(),
                [x + offset * i as f64, h + 2.0 * h * i as f64],
                1.0,
            );
            b.angle = if i % 2 == 0 { -0.1 } else { 0.1 };
            bodies.push(b);
            if i % 2 == 1 {
                let (a, bb) = (bodies.len() - 2, bodies.len() - 1);
                let pose = |k: usize| Pose {
                    position: bodies[k].position,
                    angle: bodies[k].angle,
                };
                let mut joint = SceneJoint::revolute(Some(a), Some(bb), [0.0, 0.0], 0.0);
                if let JointKind::Revolute(rj) = &mut joint.kind {
                    rj.anchor_a = pose(a).to_world([-h, h]);
                    rj.anchor_b = pose(bb).to_world([-h, -h]);
                    rj.limits = Some([-0.1 * PI, 0.2 * PI]);
                    rj.spring = Some(Spring {
                        hertz: 1.0,
                        damping_ratio: 1.0,
                        target: 0.0,
                    });
                    rj.motor = Some(Motor {
                        speed: 0.0,
                        max_force: 0.25,
                    });
                }
                joints.push(joint);
            }
        }
    }
    ManyBodyScene {
        gravity: BENCHMARK_GRAVITY,
        dt: BENCHMARK_DT,
        substeps: BENCHMARK_SUBSTEPS,
        bodies,
        joints,
    }
}
