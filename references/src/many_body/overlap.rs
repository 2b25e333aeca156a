//! The deepest overlap between the bodies of a scene, computed from poses
//! alone, so that every engine's penetration is judged by the same geometry
//! code at the same instant.
//!
//! The engines' own contact data ([`super::ContactCounts`]) are of their
//! last collision pass, at the start of the last step, and with contact
//! recycling may be older still; this measure uses the poses the engine
//! reports after the step. Pairs are found by sweep and prune on x (sort the
//! bodies' bounding boxes by their lower x, then test each box against the
//! following ones until they start beyond its upper x), then parry2d-f64
//! computes each candidate pair's penetration depth (`query::contact`, the
//! GJK and EPA of [`crate::parry_queries`]). Pairs that never collide are
//! skipped: two bodies that are not dynamic (walls and ground may overlap
//! each other by design), two bodies of one collision group, and (through
//! [`super::ManyBodyScene::deepest_overlap`]) two bodies held by a joint
//! that keeps them apart (a ragdoll's bones overlap at their joints by
//! design). Cost: O(n log n) plus the candidate pairs.

use super::{BodyKind, BodySample, SceneBody};
use crate::parry_queries::{to_parry_pose, to_parry_shape};
use engine::Shape;
use nalgebra::{Isometry2, Vector2};
use parry2d_f64::query;
use parry2d_f64::shape::SharedShape;

/// The deepest overlapping pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// Penetration depth, m (> 0).
    pub depth: f64,
    /// First body (scene index; the smaller of the two).
    pub body_a: usize,
    /// Second body (scene index).
    pub body_b: usize,
}

/// Axis-aligned bounding box of `shape` at `pose`: (min, max), m.
fn bounds(shape: &Shape, pose: &Isometry2<f64>) -> ([f64; 2], [f64; 2]) {
    match shape {
        Shape::Circle(c) => {
            let p = pose.translation.vector;
            (
                [p.x - c.radius, p.y - c.radius],
                [p.x + c.radius, p.y + c.radius],
            )
        }
        Shape::Polygon(poly) => {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for v in poly.vertices() {
                let w = pose * nalgebra::Point2::from(*v);
                lo = [lo[0].min(w.x), lo[1].min(w.y)];
                hi = [hi[0].max(w.x), hi[1].max(w.y)];
            }
            (lo, hi)
        }
        // The core's box grown by the radius.
        Shape::Rounded(r) => {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for v in r.core() {
                let w = pose * nalgebra::Point2::from(*v);
                lo = [lo[0].min(w.x - r.radius()), lo[1].min(w.y - r.radius())];
                hi = [hi[0].max(w.x + r.radius()), hi[1].max(w.y + r.radius())];
            }
            (lo, hi)
        }
        Shape::Compound(c) => c
            .parts()
            .iter()
            .map(|p| bounds(&p.shape, &(pose * Isometry2::new(p.offset, p.angle))))
            .reduce(|(lo1, hi1), (lo2, hi2)| {
                (
                    [lo1[0].min(lo2[0]), lo1[1].min(lo2[1])],
                    [hi1[0].max(hi2[0]), hi1[1].max(hi2[1])],
                )
            })
            .expect("a compound has at least one part"),
        Shape::Chain(c) => {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for v in c.points() {
                let w = pose * nalgebra::Point2::from(*v);
                lo = [lo[0].min(w.x), lo[1].min(w.y)];
                hi = [hi[0].max(w.x), hi[1].max(w.y)];
            }
            (lo, hi)
        }
    }
}

/// The deepest overlap among the bodies of a scene at the poses of
/// `samples` (one per body, in scene order), or `None` if no pair that can
/// collide (a dynamic body, not both of one collision group) overlaps.
/// Pairs that merely touch (depth 0) are not overlaps.
///
/// # Panics
/// If `samples` and `bodies` differ in length (a programming error of the
/// caller, not a user input).
pub fn deepest_overlap(bodies: &[SceneBody], samples: &[BodySample]) -> Option<Overlap> {
    deepest_overlap_except(bodies, samples, |_, _| false)
}

/// [`deepest_overlap`] without the pairs `(i, j)` (i < j) for which
/// `never_collide` holds.
pub(super) fn deepest_overlap_except(
    bodies: &[SceneBody],
    samples: &[BodySample],
    never_collide: impl Fn(usize, usize) -> bool,
) -> Option<Overlap> {
    assert_eq!(
        bodies.len(),
        samples.len(),
        "one sample per body, in scene order"
    );
    let poses: Vec<Isometry2<f64>> = samples
        .iter()
        .map(|s| Isometry2::new(Vector2::new(s.position[0], s.position[1]), s.angle))
        .collect();
    let boxes: Vec<([f64; 2], [f64; 2])> = bodies
        .iter()
        .zip(&poses)
        .map(|(b, p)| bounds(&b.shape, p))
        .collect();
    let mut order: Vec<usize> = (0..bodies.len()).collect();
    order.sort_by(|&i, &j| boxes[i].0[0].total_cmp(&boxes[j].0[0]));
    let shapes: Vec<SharedShape> = bodies.iter().map(|b| to_parry_shape(&b.shape)).collect();
    let parry_poses: Vec<_> = poses.iter().map(to_parry_pose).collect();

    let mut deepest: Option<Overlap> = None;
    for (k, &i) in order.iter().enumerate() {
        let (lo_i, hi_i) = boxes[i];
        for &j in &order[k + 1..] {
            let (lo_j, hi_j) = boxes[j];
            if lo_j[0] > hi_i[0] {
                break;
            }
            if lo_j[1] > hi_i[1] || lo_i[1] > hi_j[1] {
                continue;
            }
            let moving = |b: &SceneBody| b.kind == BodyKind::Dynamic;
            if !(moving(&bodies[i]) || moving(&bodies[j])) {
                continue;
            }
            let group = |b: &SceneBody| b.collision_group;
            if group(&bodies[i]).is_some() && group(&bodies[i]) == group(&bodies[j]) {
                continue;
            }
            if never_collide(i.min(j), i.max(j)) {
                continue;
            }
            let contact = query::contact(
                &parry_poses[i],
                &*shapes[i],
                &parry_poses[j],
                &*shapes[j],
                0.0,
            )
            .expect("parry supports convex polygons and balls");
            if let Some(c) = contact {
                let depth = -c.dist;
                if depth > 0.0 && deepest.is_none_or(|d| depth > d.depth) {
                    deepest = Some(Overlap {
                        depth,
                        body_a: i.min(j),
                        body_b: i.max(j),
                    });
                }
            }
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;
    use engine::Circle;

    fn at(x: f64, y: f64, angle: f64) -> BodySample {
        BodySample {
            position: [x, y],
            angle,
            ..BodySample::default()
        }
    }

    #[test]
    fn finds_the_deepest_pair_and_ignores_static_pairs() {
        let unit = Shape::rectangle(1.0, 1.0).unwrap();
        let disc = Shape::Circle(Circle::new(0.5).unwrap());
        let bodies = vec![
            SceneBody::fixed(Shape::rectangle(10.0, 1.0).unwrap(), [0.0, -0.5]),
            SceneBody::fixed(Shape::rectangle(1.0, 1.0).unwrap(), [0.0, -0.5]),
            SceneBody::dynamic(unit.clone(), [0.0, 0.5], 1.0),
            SceneBody::dynamic(disc, [3.0, 0.5], 1.0),
            SceneBody::dynamic(unit, [5.0, 0.5], 1.0),
        ];
        // Box on the ground sunk by 1 mm; the disc by 3 mm; the far box
        // 0.5 mm. The two static bodies overlap completely: not counted.
        let samples = vec![
            at(0.0, -0.5, 0.0),
            at(0.0, -0.5, 0.0),
            at(0.0, 0.499, 0.0),
            at(3.0, 0.497, 1.0),
            at(5.0, 0.4995, 0.0),
        ];
        let o = deepest_overlap(&bodies, &samples).expect("overlaps");
        assert_eq!((o.body_a, o.body_b), (0, 3));
        // Exact geometry: a disc 3 mm into a flat face; parry's ball-vs-
        // polygon contact is a closed form, exact to round-off of 0.5 m.
        assert_close(o.depth, 0.003, 1e-12, "disc depth");
        // Raised by 4 mm: no overlap anywhere (touching is not overlap).
        let lifted: Vec<BodySample> = samples
            .iter()
            .enumerate()
            .map(|(i, s)| {
                if i < 2 {
                    *s
                } else {
                    at(s.position[0], 0.501, 0.0)
                }
            })
            .collect();
        assert_eq!(deepest_overlap(&bodies, &lifted), None);
    }

    #[test]
    fn pairs_that_never_collide_are_skipped() {
        // Two unit boxes overlapping by 0.1 m.
        let unit = Shape::rectangle(1.0, 1.0).unwrap();
        let mut scene = super::super::ManyBodyScene {
            gravity: [0.0, 0.0],
            dt: 0.01,
            substeps: 4,
            bodies: vec![
                SceneBody::dynamic(unit.clone(), [0.0, 0.0], 1.0),
                SceneBody::dynamic(unit, [0.9, 0.0], 1.0),
            ],
            joints: Vec::new(),
        };
        let samples = [at(0.0, 0.0, 0.0), at(0.9, 0.0, 0.0)];
        let depth = |s: &super::super::ManyBodyScene| s.deepest_overlap(&samples).map(|o| o.depth);
        // Box-box penetration from parry's polygon clipping, exact to
        // round-off of the 1 m sides.
        assert_close(depth(&scene).unwrap(), 0.1, 1e-12, "free pair");
        // Jointed (collide_connected false): never collide.
        scene.joints.push(super::super::SceneJoint::revolute(
            Some(0),
            Some(1),
            [0.45, 0.0],
            0.0,
        ));
        assert_eq!(depth(&scene), None);
        scene.joints[0].collide_connected = true;
        assert!(depth(&scene).is_some());
        // One collision group: never collide either.
        for b in &mut scene.bodies {
            b.collision_group = Some(3);
        }
        assert_eq!(depth(&scene), None);
        assert_eq!(deepest_overlap(&scene.bodies, &samples), None);
    }
}
