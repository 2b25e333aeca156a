//! Shapes: the one [`Shape`] enum and its dispatch; each kind's geometry in
//! its own file (seed §4.1.1 convex polygon, §4.2.5 inertia).
//!
//! - [`polygon`]: convex polygons, counter-clockwise, checked convex on
//!   construction;
//! - [`circle`]: circles about their frame's origin;
//! - [`rounded`]: segments, capsules and rounded polygons, one type, a
//!   convex core inflated by a radius;
//! - [`chain`]: one-sided polylines for static ground and walls;
//! - [`compound`]: rigid unions of convex parts;
//! - [`decompose`]: concave outlines cut into convex parts.
//!
//! A kind's file holds everything about it that the rest of the engine
//! reads: mass properties (area, centroid, second moment, from the
//! geometry), bounds at a pose, inner radius and extent, and, for a convex
//! kind, its convex core (vertices) and radius at a pose. The rest of the
//! engine reads shapes only through [`Shape`]'s kind-independent methods
//! ([`Shape::bounds`], [`Shape::convex_core`], [`Shape::rounding_radius`],
//! [`Shape::inner_radius`], [`Shape::rotation_radius`], ...) and the pair
//! table of `collision/pair_table.rs`. When a shape is attached to a body,
//! the body's position is its centre of mass: a shape is re-centred on its
//! centroid ([`Shape::centered`]).

pub mod chain;
pub mod circle;
pub mod compound;
pub mod decompose;
pub mod polygon;
pub mod rounded;

pub use chain::{Chain, ChainSegment};
pub use circle::Circle;
pub use compound::{Compound, CompoundPart};
pub use polygon::ConvexPolygon;
pub use rounded::{ConvexCore, RoundedConvex, RoundedKind};

use crate::error::Result;
use nalgebra::{Isometry2, Vector2};

/// 2D cross product `a × b = a.x b.y − a.y b.x` (a scalar in 2D).
#[inline]
pub fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Bound on the rounding error of a turn `cross(e1, e2)` computed in f64,
/// relative to `|e1.x e2.y| + |e1.y e2.x|`.
///
/// The vertices are exact (rescaled by a power of two, which is exact), so
/// each edge component carries one rounding (relative error ≤ u = ε/2), each
/// product one more, and the final difference one more: the computed turn is
/// within γ₄ (|e1.x e2.y| + |e1.y e2.x|) of the true one, γ₄ = 4u/(1 − 4u)
/// ≈ 2ε (Higham, *Accuracy and Stability of Numerical Algorithms*, §3.1).
/// Doubled to 4ε so that the bound's own evaluation in f64 cannot make it
/// too small. A turn within this bound has no trustworthy sign: the three
/// vertices are collinear as far as f64 can tell.
const TURN_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// Which way a path `a → b → c` turns at `b`, as far as f64 can tell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Turn {
    /// Counter-clockwise: `c` is strictly left of the line `a → b`.
    Left,
    /// Clockwise: `c` is strictly right of it.
    Right,
    /// Within the rounding of [`TURN_ROUNDING`]: the three points are
    /// collinear as far as f64 can tell.
    Straight,
}

/// The turn of `a → b → c` at `b`: the sign of `(b − a) × (c − b)`, or
/// [`Turn::Straight`] when that cross product is within its rounding bound.
/// Exact points of comparable magnitude (see [`rescaled`]) are assumed.
pub(crate) fn turn(a: Vector2<f64>, b: Vector2<f64>, c: Vector2<f64>) -> Turn {
    let (e1, e2) = (b - a, c - b);
    let value = cross(e1, e2);
    let rounding = TURN_ROUNDING * ((e1.x * e2.y).abs() + (e1.y * e2.x).abs());
    if value.abs() <= rounding {
        Turn::Straight
    } else if value > 0.0 {
        Turn::Left
    } else {
        Turn::Right
    }
}

/// The axis-aligned bounds (m, world frame) of `points` (m, the shape's
/// frame) placed at `pose`: the least and the greatest coordinates.
pub(crate) fn placed_bounds(
    points: &[Vector2<f64>],
    pose: &Isometry2<f64>,
) -> (Vector2<f64>, Vector2<f64>) {
    let mut min = Vector2::repeat(f64::INFINITY);
    let mut max = Vector2::repeat(f64::NEG_INFINITY);
    for w in placed(points, pose) {
        min = min.inf(&w);
        max = max.sup(&w);
    }
    (min, max)
}

/// The index of the first of `points` with a non-finite coordinate, if
/// any: the check every outline's constructor makes first.
pub(crate) fn first_non_finite(points: &[Vector2<f64>]) -> Option<usize> {
    points
        .iter()
        .position(|v| !(v.x.is_finite() && v.y.is_finite()))
}

/// `points` (m, the shape's frame) placed at `pose` (m, world frame).
pub(crate) fn placed<'a>(
    points: &'a [Vector2<f64>],
    pose: &'a Isometry2<f64>,
) -> impl Iterator<Item = Vector2<f64>> + 'a {
    points
        .iter()
        .map(|p| pose.transform_point(&nalgebra::Point2::from(*p)).coords)
}

/// The vertices multiplied by the power of two that brings the largest
/// coordinate magnitude into [1, 2): exact (barring underflow of
/// coordinates some 2^1000 times smaller than the largest, far below any
/// turn's rounding), and it keeps the products of the convexity test from
/// overflowing (coordinates of ±1e300) or underflowing (±1e-300).
pub(crate) fn rescaled(vertices: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    let largest = vertices
        .iter()
        .map(|v| v.x.abs().max(v.y.abs()))
        .fold(0.0, f64::max);
    if largest == 0.0 {
        return vertices.to_vec();
    }
    // floor(log2(largest)) from the exponent bits, exact for normal numbers;
    // a subnormal largest gives an exponent a little too high, still exact.
    let exponent = largest.log2().floor() as i32;
    // 2^-exponent in two factors, each representable (|exponent| ≤ 1074).
    let half = -exponent / 2;
    let (a, b) = (2f64.powi(half), 2f64.powi(-exponent - half));
    vertices.iter().map(|v| v * a * b).collect()
}

/// The shapes a body can carry.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Shape {
    /// A convex polygon (a box is a polygon built by [`ConvexPolygon::rectangle`]).
    Polygon(ConvexPolygon),
    /// A circle.
    Circle(Circle),
    /// Several polygons and circles making one rigid body (soft-step model
    /// only).
    Compound(Compound),
    /// A one-sided polyline, open or a loop: ground and walls on static
    /// bodies only (soft-step model only; no area, no mass).
    Chain(Chain),
    /// A segment, capsule or rounded polygon: a convex core inflated by a
    /// radius ([`RoundedConvex`]). Collided by both contact models.
    Rounded(RoundedConvex),
}

impl Shape {
    /// An axis-aligned box `width × height` (m).
    pub fn rectangle(width: f64, height: f64) -> Result<Self> {
        Ok(Shape::Polygon(ConvexPolygon::rectangle(width, height)?))
    }

    /// A circle of `radius` (m).
    pub fn circle(radius: f64) -> Result<Self> {
        Ok(Shape::Circle(Circle::new(radius)?))
    }

    /// A chain through `points` (m), closed when `is_loop` (see [`Chain`]).
    pub fn chain(points: Vec<Vector2<f64>>, is_loop: bool) -> Result<Self> {
        Ok(Shape::Chain(Chain::new(points, is_loop)?))
    }

    /// A convex polygon from vertices listed counter-clockwise (m).
    pub fn polygon(vertices: Vec<Vector2<f64>>) -> Result<Self> {
        Ok(Shape::Polygon(ConvexPolygon::new(vertices)?))
    }

    /// A capsule: cap centres `length` (m) apart on the x axis, `radius`
    /// (m); both finite and > 0.
    pub fn capsule(length: f64, radius: f64) -> Result<Self> {
        Ok(Shape::Rounded(RoundedConvex::capsule(length, radius)?))
    }

    /// The segment from `a` to `b` (m), two distinct finite points. It has
    /// no area, so no mass: a dynamic body needs another shape, or an
    /// explicit mass and inertia.
    pub fn segment(a: Vector2<f64>, b: Vector2<f64>) -> Result<Self> {
        Ok(Shape::Rounded(RoundedConvex::segment(a, b)?))
    }

    /// The convex polygon of `vertices` (counter-clockwise, m) inflated by
    /// `radius` (m, finite and > 0).
    pub fn rounded_polygon(vertices: Vec<Vector2<f64>>, radius: f64) -> Result<Self> {
        Ok(Shape::Rounded(RoundedConvex::rounded_polygon(
            ConvexPolygon::new(vertices)?,
            radius,
        )?))
    }

    /// The box `width × height` (m) centred on the origin inflated by
    /// `radius` (m): outer size `width + 2 radius` by `height + 2 radius`.
    pub fn rounded_box(width: f64, height: f64, radius: f64) -> Result<Self> {
        Ok(Shape::Rounded(RoundedConvex::rounded_polygon(
            ConvexPolygon::rectangle(width, height)?,
            radius,
        )?))
    }

    /// The "convex core + radius" view of a convex shape (a circle is one
    /// vertex at its centre, a polygon has radius 0); `None` for a
    /// compound (take its parts) and a chain (take its segments).
    pub fn convex_core(&self) -> Option<ConvexCore> {
        match self {
            Shape::Circle(c) => Some(ConvexCore {
                vertices: smallvec::smallvec![Vector2::zeros()],
                radius: c.radius,
            }),
            Shape::Polygon(p) => Some(ConvexCore {
                vertices: p.vertices().iter().copied().collect(),
                radius: 0.0,
            }),
            Shape::Rounded(r) => Some(ConvexCore {
                vertices: r.core().iter().copied().collect(),
                radius: r.radius(),
            }),
            Shape::Compound(_) | Shape::Chain(_) => None,
        }
    }

    /// The convex core of a convex shape placed at `pose` (m, world frame)
    /// and its radius, collected into `C`: what [`Shape::convex_core`]
    /// gives, placed. `None` for a compound (take its parts) and a chain
    /// (take its segments).
    pub(crate) fn convex_core_at<C: FromIterator<Vector2<f64>>>(
        &self,
        pose: &Isometry2<f64>,
    ) -> Option<(C, f64)> {
        match self {
            Shape::Circle(c) => Some((c.core_at(pose).collect(), c.radius)),
            Shape::Polygon(p) => Some((p.core_at(pose).collect(), 0.0)),
            Shape::Rounded(r) => Some((r.core_at(pose).collect(), r.radius())),
            Shape::Compound(_) | Shape::Chain(_) => None,
        }
    }

    /// Whether the shape is a single convex shape (it has a
    /// [`convex_core`](Self::convex_core)): false for a compound and a
    /// chain.
    pub fn is_convex(&self) -> bool {
        !matches!(self, Shape::Compound(_) | Shape::Chain(_))
    }

    /// The tightest axis-aligned bounds of the shape placed at `pose` (m,
    /// world frame): the lower and upper corners.
    pub fn bounds(&self, pose: &Isometry2<f64>) -> (Vector2<f64>, Vector2<f64>) {
        match self {
            Shape::Polygon(p) => p.bounds(pose),
            Shape::Circle(c) => c.bounds(pose),
            Shape::Rounded(r) => r.bounds(pose),
            Shape::Compound(c) => c.bounds(pose),
            Shape::Chain(c) => c.bounds(pose),
        }
    }

    /// The rounding radius (m): how far the shape reaches beyond its convex
    /// core (a circle's radius, a capsule's or rounded polygon's radius; 0
    /// for a polygon, a segment, a chain and a compound). Box2D's
    /// `b2GetShapeRadius`, read by rolling resistance.
    pub fn rounding_radius(&self) -> f64 {
        match self {
            Shape::Circle(c) => c.radius,
            Shape::Rounded(r) => r.radius(),
            Shape::Polygon(_) | Shape::Compound(_) | Shape::Chain(_) => 0.0,
        }
    }

    /// The radius (m) of the largest circle about the frame's origin (a
    /// body's centre of mass) inside the shape: a circle's radius, the
    /// smallest distance from the origin to a polygon's edge lines, the
    /// largest over a compound's parts of their own less their offsets (0
    /// if none contains the origin), 0 for a chain. Half the thinnest the
    /// shape can be across its centre.
    pub fn inner_radius(&self) -> f64 {
        match self {
            Shape::Circle(c) => c.radius,
            Shape::Polygon(p) => p.inner_radius(),
            Shape::Compound(c) => c.inner_radius(),
            Shape::Chain(_) => 0.0,
            Shape::Rounded(r) => r.inner_radius(),
        }
    }

    /// The largest distance from the frame's origin to a point of the
    /// shape (m): a circle's radius, a polygon's farthest vertex, a rounded
    /// shape's farthest core vertex plus its radius.
    pub fn max_extent(&self) -> f64 {
        match self {
            Shape::Circle(c) => c.radius,
            Shape::Polygon(p) => p.max_extent(),
            Shape::Rounded(r) => r.max_extent(),
            Shape::Compound(c) => c.max_extent(),
            Shape::Chain(c) => c.max_extent(),
        }
    }

    /// The largest distance (m) from the frame's origin (the centre of
    /// rotation) to a point of the shape whose position changes when the
    /// body turns: [`Shape::max_extent`], but 0 for a circle (centred on
    /// the origin, a rotation leaves it in place). Bounds the speed of a
    /// boundary point: `|ω| · rotation_radius`.
    pub fn rotation_radius(&self) -> f64 {
        match self {
            Shape::Circle(_) => 0.0,
            other => other.max_extent(),
        }
    }

    /// The kind's name in messages: "polygon", "circle", "compound",
    /// "chain", "segment", "capsule" or "rounded polygon".
    pub fn kind_name(&self) -> &'static str {
        match self {
            Shape::Polygon(_) => "polygon",
            Shape::Circle(_) => "circle",
            Shape::Compound(_) => "compound",
            Shape::Chain(_) => "chain",
            Shape::Rounded(r) => r.kind().name(),
        }
    }

    /// Area (m²); 0 for a segment.
    pub fn area(&self) -> f64 {
        match self {
            Shape::Polygon(p) => p.area(),
            Shape::Circle(c) => c.area(),
            Shape::Compound(c) => c.area(),
            Shape::Chain(_) => 0.0,
            Shape::Rounded(r) => r.area(),
        }
    }

    /// Moment of inertia about the centroid per unit mass (m²): `I / m`.
    /// A box b × h gives (b² + h²)/12. A segment, which has no mass,
    /// gives 0 (so it adds nothing inside a compound).
    pub fn inertia_per_unit_mass(&self) -> f64 {
        match self {
            Shape::Polygon(p) => p.polar_moment_about_centroid() / p.area(),
            Shape::Circle(c) => c.inertia_per_unit_mass(),
            Shape::Compound(c) => c.polar_moment_about_centroid() / c.area(),
            // No mass to spread: a chain is on a static body.
            Shape::Chain(_) => 0.0,
            Shape::Rounded(r) => match r.area() {
                0.0 => 0.0,
                area => r.polar_moment_about_centroid() / area,
            },
        }
    }

    /// The centroid in the shape's own frame (m); `None` when it is the
    /// frame's origin by construction (a circle) or the shape has none (a
    /// chain).
    pub fn frame_centroid(&self) -> Option<Vector2<f64>> {
        match self {
            Shape::Polygon(p) => Some(p.centroid()),
            Shape::Rounded(r) => Some(r.centroid()),
            Shape::Compound(c) => Some(c.centroid()),
            Shape::Circle(_) | Shape::Chain(_) => None,
        }
    }

    /// The shape re-centred on its centroid (what a body stores).
    pub fn centered(&self) -> Self {
        match self {
            Shape::Polygon(p) => Shape::Polygon(p.centered()),
            Shape::Circle(c) => Shape::Circle(*c),
            // No centroid: the chain stays where its static body puts it.
            Shape::Chain(c) => Shape::Chain(c.clone()),
            Shape::Rounded(r) => Shape::Rounded(r.centered()),
            Shape::Compound(c) => Shape::Compound(c.centered()),
        }
    }

    /// The convex pieces of the shape with their placement in the body
    /// frame: the shape itself at the origin, or a compound's parts; none
    /// for a chain (its segments are not shapes: see [`Chain::segments`]).
    pub fn pieces(&self) -> Vec<(Vector2<f64>, f64, &Shape)> {
        match self {
            Shape::Chain(_) => Vec::new(),
            Shape::Compound(c) => c
                .parts()
                .iter()
                .map(|p| (p.offset, p.angle, &p.shape))
                .collect(),
            other => vec![(Vector2::zeros(), 0.0, other)],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_box_has_the_inertia_of_cases_md() {
        // 0.1 m × 0.1 m, 0.3 kg: I = m (b² + h²)/12 = 5e-4 kg·m² exactly in
        // real numbers; the polygon formula sums four terms, so allow a few ulps.
        let shape = Shape::rectangle(0.1, 0.1).unwrap();
        let inertia = 0.3 * shape.inertia_per_unit_mass();
        assert!((inertia - 5e-4).abs() < 1e-18, "{inertia}");
    }

    #[test]
    fn inner_radius_is_the_largest_circle_about_the_origin_inside() {
        // A 4 m × 1 m box about its centre: half its short side; each edge's
        // distance is one product and one division of exact halves, so the
        // tolerance is a few ulps of 0.5.
        let rectangle = Shape::rectangle(4.0, 1.0).unwrap();
        assert!((rectangle.inner_radius() - 0.5).abs() < 1e-15);
        assert_eq!(Shape::Circle(Circle::new(0.3).unwrap()).inner_radius(), 0.3);
        // A compound: a 1 m square part 0.2 m from the origin holds a circle
        // of 0.5 − 0.2 = 0.3 m about the origin; a part whose own circle
        // does not reach the origin adds nothing.
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        let compound = Compound::new(vec![
            CompoundPart::new(Vector2::new(0.2, 0.0), 0.0, square.clone()),
            CompoundPart::new(Vector2::new(3.0, 0.0), 0.0, square),
        ])
        .unwrap();
        let r = Shape::Compound(compound).inner_radius();
        assert!((r - 0.3).abs() < 1e-15, "{r}");
    }
}
