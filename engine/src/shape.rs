//! Shapes and their mass properties (seed §4.1.1 convex polygon, §4.2.5
//! inertia).
//!
//! A polygon is stored counter-clockwise and checked convex on
//! construction; mass properties (area, centroid, second moment) come from
//! the geometry. When a shape is attached to a body, the body's position is
//! its centre of mass: a polygon is re-centred on its centroid.
//!
//! Segments, capsules and rounded polygons are one type, a convex core
//! inflated by a radius ([`rounded`]); every convex shape has the
//! "core + radius" view [`Shape::convex_core`].

pub mod chain;
pub mod decompose;
pub mod rounded;

pub use rounded::{ConvexCore, RoundedConvex, RoundedKind};

pub use chain::{Chain, ChainSegment};

use crate::error::{EngineError, Result, require_positive};
use crate::material::ShapeOverrides;
use nalgebra::Vector2;

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

/// A convex polygon, counter-clockwise, in its body's frame (m).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ConvexPolygon {
    vertices: Vec<Vector2<f64>>,
}

impl ConvexPolygon {
    /// A polygon from vertices listed counter-clockwise. Refuses fewer than
    /// three vertices, non-finite coordinates, repeated or collinear vertices,
    /// a clockwise order and a non-convex outline, naming the first bad vertex.
    pub fn new(vertices: Vec<Vector2<f64>>) -> Result<Self> {
        let n = vertices.len();
        if n < 3 {
            return Err(EngineError::InvalidPolygon {
                vertex: n,
                reason: "a polygon needs at least 3 vertices",
            });
        }
        if let Some(i) = vertices
            .iter()
            .position(|v| !(v.x.is_finite() && v.y.is_finite()))
        {
            return Err(EngineError::InvalidPolygon {
                vertex: i,
                reason: "non-finite coordinate",
            });
        }
        for i in 0..n {
            if vertices[i] == vertices[(i + n - 1) % n] {
                return Err(EngineError::InvalidPolygon {
                    vertex: i,
                    reason: "repeated vertex",
                });
            }
        }
        let vertices_in = vertices;
        let vertices = rescaled(&vertices_in);
        let signed_area: f64 = (0..n)
            .map(|i| cross(vertices[i], vertices[(i + 1) % n]))
            .sum();
        for i in 0..n {
            let prev = vertices[(i + n - 1) % n];
            let next = vertices[(i + 1) % n];
            let turn = turn(prev, vertices[i], next);
            if turn == Turn::Straight {
                return Err(EngineError::InvalidPolygon {
                    vertex: i,
                    reason: "collinear vertex",
                });
            }
            if turn == Turn::Right {
                return Err(EngineError::InvalidPolygon {
                    vertex: i,
                    reason: if signed_area < 0.0 {
                        "vertices are clockwise (list them counter-clockwise)"
                    } else {
                        "polygon is not convex"
                    },
                });
            }
        }
        // All turns left is not enough: a star winds twice. A convex CCW
        // polygon's edge directions turn by exactly 2π in total.
        let winding: f64 = (0..n)
            .map(|i| {
                let a = vertices[(i + 1) % n] - vertices[i];
                let b = vertices[(i + 2) % n] - vertices[(i + 1) % n];
                cross(a, b).atan2(a.dot(&b))
            })
            .sum();
        if winding > 2.0 * std::f64::consts::PI + 1e-6 {
            return Err(EngineError::InvalidPolygon {
                vertex: 0,
                reason: "polygon is not convex (self-intersecting)",
            });
        }
        Ok(Self {
            vertices: vertices_in,
        })
    }

    /// The axis-aligned rectangle `width × height` (m) centred on the origin.
    pub fn rectangle(width: f64, height: f64) -> Result<Self> {
        let hw = 0.5 * require_positive("box width", width)?;
        let hh = 0.5 * require_positive("box height", height)?;
        Self::new(vec![
            Vector2::new(-hw, -hh),
            Vector2::new(hw, -hh),
            Vector2::new(hw, hh),
            Vector2::new(-hw, hh),
        ])
    }

    /// The convex hull of a point cloud (Andrew's monotone chain), CCW,
    /// collinear points dropped.
    pub fn convex_hull(points: &[Vector2<f64>]) -> Result<Self> {
        let mut pts: Vec<Vector2<f64>> = points.to_vec();
        if let Some(i) = pts
            .iter()
            .position(|v| !(v.x.is_finite() && v.y.is_finite()))
        {
            return Err(EngineError::InvalidPolygon {
                vertex: i,
                reason: "non-finite coordinate",
            });
        }
        pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        pts.dedup();
        if pts.len() < 3 {
            return Err(EngineError::InvalidPolygon {
                vertex: pts.len(),
                reason: "a hull needs at least 3 distinct points",
            });
        }
        let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(2 * pts.len());
        for pass in 0..2 {
            let start = hull.len();
            let iter: Box<dyn Iterator<Item = &Vector2<f64>>> = if pass == 0 {
                Box::new(pts.iter())
            } else {
                Box::new(pts.iter().rev())
            };
            for p in iter {
                while hull.len() >= start + 2
                    && cross(
                        hull[hull.len() - 1] - hull[hull.len() - 2],
                        p - hull[hull.len() - 2],
                    ) <= 0.0
                {
                    hull.pop();
                }
                hull.push(*p);
            }
            hull.pop();
        }
        Self::new(hull)
    }

    /// The vertices, counter-clockwise, in the body frame (m).
    pub fn vertices(&self) -> &[Vector2<f64>] {
        &self.vertices
    }

    /// Area (m²).
    pub fn area(&self) -> f64 {
        let n = self.vertices.len();
        0.5 * (0..n)
            .map(|i| cross(self.vertices[i], self.vertices[(i + 1) % n]))
            .sum::<f64>()
    }

    /// Centroid (m), in the polygon's frame.
    pub fn centroid(&self) -> Vector2<f64> {
        let n = self.vertices.len();
        let mut c = Vector2::zeros();
        let mut area2 = 0.0;
        // Triangles fanned from vertex 0 keep the sums well conditioned.
        let o = self.vertices[0];
        for i in 1..n - 1 {
            let (a, b) = (self.vertices[i] - o, self.vertices[i + 1] - o);
            let w = cross(a, b);
            area2 += w;
            c += w * (a + b) / 3.0;
        }
        o + c / area2
    }

    /// Second moment of area about the centroid, `∫ |r − c|² dA` (m⁴).
    /// Times the density it is the moment of inertia.
    pub fn polar_moment_about_centroid(&self) -> f64 {
        let n = self.vertices.len();
        let c = self.centroid();
        (0..n)
            .map(|i| {
                let (a, b) = (self.vertices[i] - c, self.vertices[(i + 1) % n] - c);
                cross(a, b) * (a.dot(&a) + a.dot(&b) + b.dot(&b)) / 12.0
            })
            .sum()
    }

    /// The same polygon translated so that its centroid is the origin.
    pub fn centered(&self) -> Self {
        let c = self.centroid();
        Self {
            vertices: self.vertices.iter().map(|v| v - c).collect(),
        }
    }
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

/// A circle of given radius (m) centred on its body's origin.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Circle {
    /// Radius (m), > 0.
    pub radius: f64,
}

impl Circle {
    /// A circle; the radius must be finite and > 0.
    pub fn new(radius: f64) -> Result<Self> {
        Ok(Self {
            radius: require_positive("circle radius", radius)?,
        })
    }
}

/// One part of a [`Compound`]: a polygon or a circle placed in the body
/// frame.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CompoundPart {
    /// Where the part's own origin sits in the body frame (m).
    pub offset: Vector2<f64>,
    /// The part's orientation in the body frame (rad), counter-clockwise.
    pub angle: f64,
    /// The part, in its own frame: any shape but a compound.
    pub shape: Shape,
    /// What the part sets for itself instead of taking its body's (filter,
    /// sensor flag, material); the default inherits everything.
    pub overrides: ShapeOverrides,
}

impl CompoundPart {
    /// A part `shape` placed at `offset` (m) and turned by `angle` (rad) in
    /// the body frame, inheriting its body's filter and material.
    pub fn new(offset: Vector2<f64>, angle: f64, shape: Shape) -> Self {
        Self {
            offset,
            angle,
            shape,
            overrides: ShapeOverrides::default(),
        }
    }

    /// Sets what the part overrides of its body's filter and material.
    pub fn with_overrides(mut self, overrides: ShapeOverrides) -> Self {
        self.overrides = overrides;
        self
    }

    /// Maps a point of the part's frame into the body frame (m).
    pub fn to_body(&self, p: Vector2<f64>) -> Vector2<f64> {
        let (s, c) = self.angle.sin_cos();
        self.offset + Vector2::new(c * p.x - s * p.y, s * p.x + c * p.y)
    }

    /// The part's centroid in the body frame (m).
    pub fn centroid(&self) -> Vector2<f64> {
        match &self.shape {
            Shape::Polygon(p) => self.to_body(p.centroid()),
            Shape::Rounded(r) => self.to_body(r.centroid()),
            _ => self.offset,
        }
    }
}

/// A rigid union of convex parts (a hollow box, an L): one body, several
/// shapes, of uniform density. Supported by the soft-step contact model;
/// the exact model refuses it.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Compound {
    parts: Vec<CompoundPart>,
}

impl Compound {
    /// A compound of at least one part; parts are any shape but a compound
    /// (polygons, circles, segments, capsules, rounded polygons), with
    /// finite offsets and angles.
    pub fn new(parts: Vec<CompoundPart>) -> Result<Self> {
        if parts.is_empty() {
            return Err(EngineError::InvalidParameter {
                what: "compound shape".into(),
                value: 0.0,
                reason: "needs at least one part",
            });
        }
        for (i, p) in parts.iter().enumerate() {
            if let Shape::Compound(_) = p.shape {
                return Err(EngineError::InvalidParameter {
                    what: format!("part {i} of a compound shape"),
                    value: f64::NAN,
                    reason: "a part cannot be a compound itself",
                });
            }
            for v in [p.offset.x, p.offset.y, p.angle] {
                crate::error::require_finite(
                    format!("placement of part {i} of a compound shape"),
                    v,
                )?;
            }
        }
        let compound = Self { parts };
        if compound.area() == 0.0 {
            return Err(EngineError::InvalidParameter {
                what: "compound shape".into(),
                value: 0.0,
                reason: "its parts have no area (segments only): it would have no centroid",
            });
        }
        Ok(compound)
    }

    /// A hollow rectangle: four walls of thickness `wall` (m) around an
    /// inside of `width × height` (m), centred on the origin.
    pub fn hollow_box(width: f64, height: f64, wall: f64) -> Result<Self> {
        let (w, h, t) = (
            require_positive("hollow box width", width)?,
            require_positive("hollow box height", height)?,
            require_positive("hollow box wall", wall)?,
        );
        let part = |x: f64, y: f64, pw: f64, ph: f64| -> Result<CompoundPart> {
            Ok(CompoundPart::new(
                Vector2::new(x, y),
                0.0,
                Shape::rectangle(pw, ph)?,
            ))
        };
        Self::new(vec![
            part(0.0, -0.5 * (h + t), w + 2.0 * t, t)?,
            part(0.0, 0.5 * (h + t), w + 2.0 * t, t)?,
            part(-0.5 * (w + t), 0.0, t, h)?,
            part(0.5 * (w + t), 0.0, t, h)?,
        ])
    }

    /// The parts.
    pub fn parts(&self) -> &[CompoundPart] {
        &self.parts
    }

    /// Total area (m²).
    pub fn area(&self) -> f64 {
        self.parts.iter().map(|p| p.shape.area()).sum()
    }

    /// Centroid of the union (m, body frame), area-weighted.
    pub fn centroid(&self) -> Vector2<f64> {
        let mut c = Vector2::zeros();
        for p in &self.parts {
            c += p.shape.area() * p.centroid();
        }
        c / self.area()
    }

    /// Second moment of area about the centroid (m⁴): each part's own
    /// moment plus its area times the squared distance of its centroid
    /// (parallel axis theorem).
    pub fn polar_moment_about_centroid(&self) -> f64 {
        let c = self.centroid();
        self.parts
            .iter()
            .map(|p| {
                let a = p.shape.area();
                a * p.shape.inertia_per_unit_mass() + a * (p.centroid() - c).norm_squared()
            })
            .sum()
    }
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
    /// radius ([`RoundedConvex`]). Collided by the exact contact model; the
    /// soft step refuses it while contacts are on. It gives a body its mass
    /// properties and answers world queries.
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
            Shape::Circle(c) => std::f64::consts::PI * c.radius * c.radius,
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
            Shape::Circle(c) => 0.5 * c.radius * c.radius,
            Shape::Compound(c) => c.polar_moment_about_centroid() / c.area(),
            // No mass to spread: a chain is on a static body.
            Shape::Chain(_) => 0.0,
            Shape::Rounded(r) => match r.area() {
                0.0 => 0.0,
                area => r.polar_moment_about_centroid() / area,
            },
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
            Shape::Compound(c) => {
                let centroid = c.centroid();
                Shape::Compound(Compound {
                    parts: c
                        .parts
                        .iter()
                        .map(|p| CompoundPart {
                            offset: p.offset - centroid,
                            ..p.clone()
                        })
                        .collect(),
                })
            }
        }
    }

    /// The convex pieces of the shape with their placement in the body
    /// frame: the shape itself at the origin, or a compound's parts; none
    /// for a chain (its segments are not shapes: see [`Chain::segments`]).
    pub fn pieces(&self) -> Vec<(Vector2<f64>, f64, &Shape)> {
        match self {
            Shape::Chain(_) => Vec::new(),
            Shape::Compound(c) => c
                .parts
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
    fn clockwise_polygon_is_refused() {
        let cw = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(1.0, 0.0),
        ];
        let err = ConvexPolygon::new(cw).unwrap_err();
        assert!(err.to_string().contains("clockwise"), "{err}");
    }

    #[test]
    fn non_convex_polygon_names_the_vertex() {
        let dart = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(2.0, 0.0),
            Vector2::new(1.0, 0.5),
            Vector2::new(2.0, 2.0),
            Vector2::new(0.0, 2.0),
        ];
        match ConvexPolygon::new(dart).unwrap_err() {
            EngineError::InvalidPolygon { vertex, .. } => assert_eq!(vertex, 2),
            e => panic!("unexpected {e}"),
        }
    }

    #[test]
    fn hull_of_a_square_with_inner_points_is_the_square() {
        let pts = [
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.5, 0.5),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(0.5, 0.0),
        ];
        let hull = ConvexPolygon::convex_hull(&pts).unwrap();
        assert_eq!(hull.vertices().len(), 4);
        assert!((hull.area() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_hollow_box_has_the_mass_properties_of_its_walls() {
        // Inside 2 × 2, walls 1 thick: the outer 4 × 4 square minus the
        // inner 2 × 2 one. Area 16 − 4 = 12; polar moment about the centre
        // (4⁴ − 2⁴)/6 = 40 m⁴ (a square of side a has a⁴/6).
        let c = Compound::hollow_box(2.0, 2.0, 1.0).unwrap();
        assert!((c.area() - 12.0).abs() < 1e-12);
        assert!(c.centroid().norm() < 1e-12);
        assert!((c.polar_moment_about_centroid() - 40.0).abs() < 1e-12);
        let shape = Shape::Compound(c);
        assert!((shape.inertia_per_unit_mass() - 40.0 / 12.0).abs() < 1e-12);
        // Off-centre, it re-centres on its centroid.
        let part = CompoundPart::new(Vector2::new(3.0, 1.0), 0.4, Shape::circle(0.5).unwrap());
        let moved = Shape::Compound(Compound::new(vec![part]).unwrap()).centered();
        let Shape::Compound(m) = &moved else { panic!() };
        assert!(m.centroid().norm() < 1e-15);
    }

    #[test]
    fn off_centre_triangle_centroid_and_inertia() {
        // Right triangle legs 3 and 6: centroid (1, 2); I_c/A = (a² + b²)/18.
        let t = ConvexPolygon::new(vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(3.0, 0.0),
            Vector2::new(0.0, 6.0),
        ])
        .unwrap();
        assert!((t.centroid() - Vector2::new(1.0, 2.0)).norm() < 1e-14);
        let per_area = t.polar_moment_about_centroid() / t.area();
        assert!((per_area - 45.0 / 18.0).abs() < 1e-13, "{per_area}");
    }

    fn polygon(points: &[[f64; 2]]) -> Result<ConvexPolygon> {
        ConvexPolygon::new(points.iter().map(|p| Vector2::new(p[0], p[1])).collect())
    }

    fn reason(points: &[[f64; 2]]) -> (usize, &'static str) {
        match polygon(points).unwrap_err() {
            EngineError::InvalidPolygon { vertex, reason } => (vertex, reason),
            e => panic!("unexpected {e}"),
        }
    }

    #[test]
    fn thin_boxes_are_valid() {
        for (w, h) in [(1.0, 1e-7), (1000.0, 0.001), (1e-7, 1.0), (1e6, 1e-9)] {
            let b = ConvexPolygon::rectangle(w, h).unwrap();
            assert!((b.area() - w * h).abs() <= 1e-15 * w * h, "{w} x {h}");
        }
    }

    #[test]
    fn huge_and_tiny_coordinates_are_judged_by_their_shape() {
        let huge = polygon(&[[-1e300, -1e300], [1e300, -1e300], [0.0, 1e300]]);
        assert!(huge.is_ok(), "{huge:?}");
        let tiny = polygon(&[[-1e-300, -1e-300], [1e-300, -1e-300], [0.0, 1e-300]]);
        assert!(tiny.is_ok(), "{tiny:?}");
        let far = polygon(&[[1e6, 1e6], [1e6 + 1e-3, 1e6], [1e6, 1e6 + 1e-3]]);
        assert!(far.is_ok(), "{far:?}");
    }

    #[test]
    fn a_duplicated_vertex_is_a_repeated_vertex() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(reason(&square), (2, "repeated vertex"));
        assert_eq!(
            reason(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]).1,
            "repeated vertex"
        );
    }

    #[test]
    fn collinear_vertices_are_refused_at_any_scale() {
        for s in [1.0, 1e-300, 1e300] {
            let points = [[0.0, 0.0], [s, 0.0], [2.0 * s, 0.0], [s, s]];
            assert_eq!(reason(&points), (1, "collinear vertex"), "scale {s}");
        }
        // The vertices are exact: a dent of 1e-17 m in a 1 m edge is a real
        // dent, far above the turn's rounding (about 1e-32 m² here).
        let points = [[0.0, 0.0], [0.5, 1e-17], [1.0, 0.0], [0.5, 1.0]];
        assert_eq!(reason(&points), (1, "polygon is not convex"));
    }
}
