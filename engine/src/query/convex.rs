//! The one convex proxy every query works on: a convex *core* (one point,
//! a segment, or a convex polygon, counter-clockwise) inflated by a radius.
//!
//! A circle is a point core of radius r, a polygon its vertices with radius
//! 0; a capsule (a segment core) or a rounded polygon would be the same
//! proxy with both, so the queries written on it (ray casts in
//! [`super::ray`], distances and shape casts in [`super::minkowski`]) serve
//! them unchanged. Coordinates are world-frame metres.

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
    /// The inflation radius (m), ≥ 0; > 0 when the core has fewer than 3
    /// vertices.
    pub radius: f64,
}

impl ConvexProxy {
    /// The proxy of a polygon or a circle placed at `pose`.
    ///
    /// # Panics
    /// On a compound (take its parts with [`piece`]).
    pub(crate) fn of(shape: &Shape, pose: &Isometry2<f64>) -> Self {
        match shape {
            Shape::Circle(c) => Self {
                vertices: SmallVec::from_slice(&[pose.translation.vector]),
                radius: c.radius,
            },
            Shape::Polygon(p) => Self {
                vertices: p
                    .vertices()
                    .iter()
                    .map(|v| pose.transform_point(&Point2::from(*v)).coords)
                    .collect(),
                radius: 0.0,
            },
            Shape::Rounded(r) => Self {
                vertices: r
                    .core()
                    .iter()
                    .map(|v| pose.transform_point(&Point2::from(*v)).coords)
                    .collect(),
                radius: r.radius(),
            },
            Shape::Compound(_) => unreachable!("a compound is queried part by part"),
            Shape::Chain(_) => unreachable!("a chain has no convex pieces to query"),
        }
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

/// Convex piece `part` of `shape` with its placement in the body frame:
/// the shape itself (part 0) or a compound's part. `None` past the last.
pub(crate) fn piece(shape: &Shape, part: usize) -> Option<(Isometry2<f64>, &Shape)> {
    match shape {
        Shape::Compound(c) => c
            .parts()
            .get(part)
            .map(|p| (Isometry2::new(p.offset, p.angle), &p.shape)),
        // Not queried yet: a chain's segments are one-sided, zero-radius
        // cores the proxy does not model (docs/design.md, queries).
        Shape::Chain(_) => None,
        other => (part == 0).then(|| (Isometry2::identity(), other)),
    }
}

/// How many convex pieces `shape` has (its parts for a compound, none for
/// a chain, else 1).
pub(crate) fn piece_count(shape: &Shape) -> usize {
    match shape {
        Shape::Compound(c) => c.parts().len(),
        Shape::Chain(_) => 0,
        _ => 1,
    }
}
