//! Shapes as the soft step's narrow phase reads them: a convex core of 2
//! or more vertices with its outward edge normals computed once and its
//! radius (a polygon has radius 0; a segment, capsule or rounded polygon
//! is its core and radius, `shape/rounded.rs`), a circle, or a chain's
//! segment; their bounding boxes and extents, the radius included; and the
//! [`Collider`]s that place them on bodies (one per shape, or one per part
//! of a compound shape).
//!
//! A collider's shape is in its own frame (m); the collider's offset places
//! that frame in its body's frame, whose origin is the body's centre of
//! mass.

use crate::body::BodyId;
use crate::collision::Aabb;
use crate::shape::{ChainSegment, Shape};
use nalgebra::{Isometry2, Vector2};
use smallvec::SmallVec;

/// Vertices of a polygon kept inside its collider (no separate heap
/// block) up to this count: the step reads every moving body's vertices
/// for its bounding box, and a pointer to a block elsewhere cost a cache
/// miss per body on large scenes (72% of that stage's time on the
/// base-100 pyramid before; boxes have 4).
const INLINE_VERTICES: usize = 8;

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub(crate) use crate::tunables::MARGIN_FRACTION;

/// A polygon's points or edge normals (m, or unit vectors).
pub(crate) type Points = SmallVec<[Vector2<f64>; INLINE_VERTICES]>;

/// A convex core with its outward unit edge normals and its radius:
/// `normals[i]` is the normal of the edge from `vertices[i]` to
/// `vertices[i + 1]`. A core of 2 vertices (a segment or capsule) has two
/// edges, its two sides. The shape is every point within `radius` of the
/// core.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Polygon {
    pub vertices: Points,
    pub normals: Points,
    /// Radius around the core (m): 0 for a polygon.
    pub radius: f64,
}

impl Polygon {
    /// `vertices` (counter-clockwise, 2 or more) with their edge normals
    /// and `radius` (m).
    fn new(vertices: Points, radius: f64) -> Self {
        let n = vertices.len();
        let normals = (0..n)
            .map(|i| {
                let e = vertices[(i + 1) % n] - vertices[i];
                Vector2::new(e.y, -e.x).normalize()
            })
            .collect();
        Polygon {
            vertices,
            normals,
            radius,
        }
    }

    /// Whether its core is a segment (2 vertices): a segment or capsule.
    #[inline]
    pub(crate) fn is_segment(&self) -> bool {
        self.vertices.len() == 2
    }
}

/// A shape ready for the narrow phase.
#[derive(Debug, Clone, PartialEq)]
#[expect(
    clippy::large_enum_variant,
    reason = "the polygon's points are inline on purpose (see INLINE_VERTICES)"
)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum SolverShape {
    /// A polygon, segment, capsule or rounded polygon: a core and a radius.
    Polygon(Polygon),
    Circle {
        radius: f64,
    },
    /// One segment of a chain with its ghost points (`shape/chain.rs`),
    /// in its body's frame.
    ChainSegment(ChainSegment),
}

/// A convex shape fixed to a body.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Collider {
    pub body: BodyId,
    /// The shape's frame in the body frame; `None` when it is the body
    /// frame itself (a body with one shape).
    pub offset: Option<Isometry2<f64>>,
    pub shape: SolverShape,
    /// Largest distance from the collider's origin to its shape (m).
    pub max_extent: f64,
}

impl Collider {
    /// One collider per convex piece of `shape` (its parts for a
    /// compound), all on `body`.
    pub(crate) fn of(body: BodyId, shape: &Shape) -> Vec<Collider> {
        if let Shape::Chain(chain) = shape {
            // One collider per segment, as Box2D makes each chain segment
            // a shape: each has its own box in the broad phase.
            return chain
                .segments()
                .into_iter()
                .map(|segment| {
                    let shape = SolverShape::ChainSegment(segment);
                    Collider {
                        body,
                        offset: None,
                        max_extent: shape.max_extent(),
                        shape,
                    }
                })
                .collect();
        }
        shape
            .pieces()
            .into_iter()
            .map(|(offset, angle, piece)| {
                let shape = SolverShape::new(piece);
                Collider {
                    body,
                    offset: (offset != Vector2::zeros() || angle != 0.0)
                        .then(|| Isometry2::new(offset, angle)),
                    max_extent: shape.max_extent(),
                    shape,
                }
            })
            .collect()
    }

    /// The margin (m) its box is enlarged by in the broad phase: `cap` (the
    /// setting), but at most [`MARGIN_FRACTION`] of its extent, so that
    /// small shapes packed closer than the cap do not all overlap their
    /// neighbours' boxes (Box2D v3.2's rule).
    #[inline]
    pub(crate) fn aabb_margin(&self, cap: f64) -> f64 {
        cap.min(MARGIN_FRACTION * self.max_extent)
    }

    /// The collider's pose given its body's.
    #[inline]
    pub(crate) fn pose(&self, body: &Isometry2<f64>) -> Isometry2<f64> {
        match &self.offset {
            None => *body,
            Some(offset) => body * offset,
        }
    }
}

impl SolverShape {
    /// The solver form of a convex shape (its own frame), read from its
    /// convex core and radius ([`Shape::convex_core`]): a core of 2 or
    /// more vertices is a [`Polygon`] with that radius, a 1-vertex core (at
    /// the origin: a circle) a circle of that radius.
    ///
    /// # Panics
    /// On a compound or a chain: split it into [`Collider`]s first.
    pub(crate) fn new(shape: &Shape) -> Self {
        let core = shape
            .convex_core()
            .expect("compounds and chains are split into colliders");
        if core.vertices.len() == 1 {
            debug_assert_eq!(core.vertices[0], Vector2::zeros(), "a circle's centre");
            SolverShape::Circle {
                radius: core.radius,
            }
        } else {
            SolverShape::Polygon(Polygon::new(core.vertices, core.radius))
        }
    }

    /// The largest distance from the body origin to a point of the shape
    /// (m): bounds how far a point moves when the body turns.
    pub(crate) fn max_extent(&self) -> f64 {
        match self {
            SolverShape::Circle { radius } => *radius,
            SolverShape::Polygon(p) => {
                p.vertices.iter().map(|v| v.norm()).fold(0.0, f64::max) + p.radius
            }
            SolverShape::ChainSegment(s) => s.point1.norm().max(s.point2.norm()),
        }
    }

    /// The smallest distance from the body origin to the shape's boundary
    /// (m): a body that moves less than a fraction of this in a step cannot
    /// jump over anything thicker than itself.
    pub(crate) fn min_extent(&self) -> f64 {
        match self {
            SolverShape::Circle { radius } => *radius,
            SolverShape::Polygon(p) => {
                p.vertices
                    .iter()
                    .zip(&p.normals)
                    .map(|(v, n)| n.dot(v))
                    .fold(f64::INFINITY, f64::min)
                    + p.radius
            }
            // No inside: a segment is thin (and static, never swept).
            SolverShape::ChainSegment(_) => 0.0,
        }
    }

    /// The bounding box of the shape at `pose`.
    pub(crate) fn aabb_at(&self, pose: &Isometry2<f64>) -> Aabb {
        let (c, s) = (pose.rotation.re, pose.rotation.im);
        self.aabb(pose.translation.vector, (c, s))
    }

    /// The bounding box of the shape at position `p` (m) and rotation
    /// `(cos θ, sin θ)`.
    pub(crate) fn aabb(&self, p: Vector2<f64>, (c, s): (f64, f64)) -> Aabb {
        match self {
            SolverShape::Circle { radius } => {
                let r = Vector2::repeat(*radius);
                Aabb::new(p - r, p + r)
            }
            SolverShape::Polygon(poly) => {
                let mut min = Vector2::repeat(f64::INFINITY);
                let mut max = Vector2::repeat(f64::NEG_INFINITY);
                for v in &poly.vertices {
                    let w = Vector2::new(c * v.x - s * v.y + p.x, s * v.x + c * v.y + p.y);
                    min = min.inf(&w);
                    max = max.sup(&w);
                }
                if poly.radius > 0.0 {
                    let r = Vector2::repeat(poly.radius);
                    (min, max) = (min - r, max + r);
                }
                Aabb::new(min, max)
            }
            SolverShape::ChainSegment(segment) => {
                let at = |v: Vector2<f64>| {
                    Vector2::new(c * v.x - s * v.y + p.x, s * v.x + c * v.y + p.y)
                };
                let (a, b) = (at(segment.point1), at(segment.point2));
                Aabb::new(a.inf(&b), a.sup(&b))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_normals_extents_and_box() {
        let s = SolverShape::new(&Shape::rectangle(2.0, 1.0).unwrap());
        let SolverShape::Polygon(p) = &s else {
            panic!()
        };
        // CCW from (-1, -0.5): bottom, right, top, left edges.
        let expected = [(0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)];
        for (n, e) in p.normals.iter().zip(expected) {
            assert!((n - Vector2::new(e.0, e.1)).norm() < 1e-15, "{n}");
        }
        assert!((s.max_extent() - 1.25f64.sqrt()).abs() < 1e-15);
        assert!((s.min_extent() - 0.5).abs() < 1e-15);
        let (c, sn) = std::f64::consts::FRAC_PI_2.sin_cos();
        // Turned by 90°: 1 wide, 2 high.
        let b = s.aabb(Vector2::new(3.0, 4.0), (sn, c));
        assert!((b.min - Vector2::new(2.5, 3.0)).norm() < 1e-12);
        assert!((b.max - Vector2::new(3.5, 5.0)).norm() < 1e-12);
    }
}
