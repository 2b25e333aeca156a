//! The one convex proxy every query works on: a convex *core* (one point,
//! a segment, or a convex polygon, counter-clockwise) inflated by a radius.
//!
//! A circle is a point core of radius r, a polygon its vertices with radius
//! 0, a segment (or a chain's solid segment) its two ends with radius 0, a
//! capsule the same with its radius, a rounded polygon its core with its
//! radius; the queries written on it (ray casts in [`super::ray`],
//! distances and shape casts in [`super::minkowski`]) serve them all
//! unchanged, and the world queries, the continuous collision and the
//! time of impact use them from here. Coordinates are world-frame metres.

use crate::shape::Shape;
use nalgebra::{Isometry2, Point2, Vector2};
use smallvec::SmallVec;

/// Core vertices kept inline: a Minkowski difference of two octagons fits.
const INLINE: usize = 16;

/// A convex core inflated by `radius`, placed in the world.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ConvexProxy {
    /// The core: 1 point, 2 (a segment) or ≥ 3 vertices counter-clockwise
    /// (m, world frame).
    pub vertices: SmallVec<[Vector2<f64>; INLINE]>,
    /// The inflation radius (m), ≥ 0; > 0 when the core is a single point
    /// (a 2-vertex core of radius 0 is a segment, a line without area).
    pub radius: f64,
}

impl ConvexProxy {
    /// The proxy of a convex shape placed at `pose`: its convex core and
    /// radius ([`Shape::convex_core_at`]).
    ///
    /// # Panics
    /// On a compound or a chain (take their pieces with [`piece_proxy`]).
    pub(crate) fn of(shape: &Shape, pose: &Isometry2<f64>) -> Self {
        Self::convex(shape, pose)
            .expect("a compound is queried part by part, a chain segment by segment")
    }

    /// The proxy of `shape` placed at `pose` when it is convex; `None` for
    /// a compound or a chain.
    pub(crate) fn convex(shape: &Shape, pose: &Isometry2<f64>) -> Option<Self> {
        let (vertices, radius) = shape.convex_core_at(pose)?;
        Some(Self { vertices, radius })
    }

    /// Whether every core coordinate and the radius are finite (what the
    /// queries of [`super::minkowski`] assume).
    pub(crate) fn is_finite(&self) -> bool {
        self.radius.is_finite()
            && self
                .vertices
                .iter()
                .all(|v| v.x.is_finite() && v.y.is_finite())
    }

    /// The tightest axis-aligned box around the proxy (m).
    pub(crate) fn aabb(&self) -> crate::collision::Aabb {
        let mut min = Vector2::repeat(f64::INFINITY);
        let mut max = Vector2::repeat(f64::NEG_INFINITY);
        for v in &self.vertices {
            min = min.inf(v);
            max = max.sup(v);
        }
        let r = Vector2::repeat(self.radius);
        crate::collision::Aabb::new(min - r, max + r)
    }

    /// The outward unit normal of core edge `i` (from vertex `i` to
    /// `i + 1`): the edge direction turned clockwise. For a segment core
    /// the two "edges" are its two sides.
    pub(crate) fn edge_normal(&self, i: usize) -> Vector2<f64> {
        let n = self.vertices.len();
        let e = self.vertices[(i + 1) % n] - self.vertices[i];
        Vector2::new(e.y, -e.x) / e.norm()
    }
}

/// Convex piece `part` of `shape`, placed at `pose` (its body's pose):
/// the shape itself (part 0), a compound's part, or a chain's solid
/// segment `part` (a core of its two points, radius 0; one-sided, which
/// each query reads its own way: see [`crate::World::cast_ray`]). `None`
/// past the last.
pub(crate) fn piece_proxy(
    shape: &Shape,
    part: usize,
    pose: &Isometry2<f64>,
) -> Option<ConvexProxy> {
    match shape {
        Shape::Compound(c) => c
            .parts()
            .get(part)
            .map(|p| ConvexProxy::of(&p.shape, &(pose * Isometry2::new(p.offset, p.angle)))),
        Shape::Chain(c) => c.segment(part).map(|s| ConvexProxy {
            vertices: [s.point1, s.point2]
                .iter()
                .map(|v| pose.transform_point(&Point2::from(*v)).coords)
                .collect(),
            radius: 0.0,
        }),
        other => (part == 0).then(|| ConvexProxy::of(other, pose)),
    }
}

/// How many convex pieces `shape` has: its parts for a compound, its
/// solid segments for a chain, else 1.
pub(crate) fn piece_count(shape: &Shape) -> usize {
    match shape {
        Shape::Compound(c) => c.parts().len(),
        Shape::Chain(c) => c.segment_count(),
        _ => 1,
    }
}
