//! Rounded convex shapes: a convex core inflated by a radius.
//!
//! One type, [`RoundedConvex`], holds the three kinds Box2D and rapier
//! also have: a **segment** (a core of 2 vertices, radius 0), a
//! **capsule** (2 vertices, radius > 0: a segment inflated by its radius)
//! and a **rounded polygon** (a convex polygon of ≥ 3 vertices inflated by
//! a radius > 0). The shape is every point within `radius` of the core.
//! With the circle (a core of 1 vertex) and the plain polygon (radius 0),
//! every convex shape of the engine is "a convex core of 1..N vertices and
//! a radius" ([`ConvexCore`], from [`Shape::convex_core`](super::Shape::convex_core)): the one view a
//! radius-aware collision core needs.
//!
//! # Mass properties of a rounded polygon, exactly
//!
//! Let the core P have vertices `v_i` counter-clockwise, edges
//! `e_i = v_{i+1} − v_i` of length `L_i`, unit directions `d_i = e_i / L_i`
//! and outward normals `n_i` (`d_i` turned clockwise), and let `φ_i` be
//! the exterior angle at `v_i` (from `n_{i−1}` to `n_i`, in (0, π];
//! Σ φ_i = 2π). The inflated shape is the disjoint union (up to
//! boundaries) of
//!
//! - the core P (area `A_P`, centroid `c_P`, polar moment `J_P` about `c_P`);
//! - one rectangle per edge, `L_i × r`, on the outside of edge `i`: its
//!   centre is `m_i + (r/2) n_i` with `m_i` the edge's midpoint;
//! - one circular sector per vertex, of radius `r` and angle `φ_i`,
//!   centred on `v_i`, spanning the directions from `n_{i−1}` to `n_i`.
//!
//! **Area.** `A = A_P + r Σ L_i + (r²/2) Σ φ_i = A_P + r·perimeter + π r²`.
//!
//! **First moment** (about any origin; the code takes `c_P` as origin, so
//! the core's own term vanishes). A rectangle contributes `r L_i (m_i +
//! (r/2) n_i)`; since `Σ L_i n_i = 0` (the edges of a closed polygon,
//! turned), the `n_i` terms cancel. A sector about its vertex contributes
//! `∫∫ ρ (cos θ, sin θ) ρ dρ dθ = (r³/3) (sin θ₁ − sin θ₀, cos θ₀ − cos θ₁)`
//! for θ from θ₀ to θ₁; with `n = (cos θ, sin θ)` and `d = n` turned
//! counter-clockwise that is `(r³/3)(d_{i−1} − d_i)`, which telescopes to
//! 0 over the vertices. What is left:
//! `Q = A_P c_P + r Σ L_i m_i + (r²/2) Σ φ_i v_i`, and the centroid is
//! `c = Q / A`.
//!
//! **Polar moment** `J_O = ∫ |p|² dA` about the origin O:
//!
//! - core: `J_P + A_P |c_P|²` (parallel axis);
//! - rectangle `i`: `L_i r (L_i² + r²)/12 + L_i r |m_i + (r/2) n_i|²`
//!   (its own polar moment, then parallel axis);
//! - sector `i`: `∫ |v_i + ρ u|² dA = (φ_i r²/2)|v_i|² + 2 v_i · (r³/3)(d_{i−1}
//!   − d_i) + φ_i r⁴/4`, expanding the square (the last term is
//!   `∫ ρ² ρ dρ dθ`).
//!
//! and about the centroid `J = J_O − A |c − O|²`. Summed over the sectors,
//! `φ_i r⁴/4` gives `π r⁴/2`, a disc's moment, as it should.
//!
//! A capsule is the same with a core of two vertices `a`, `b` read as a
//! closed polygon of two edges (`a → b` and back), core area and moment
//! 0, and both exterior angles π: `A = 2 r L + π r²` and, about the
//! midpoint, `J = (2rL)(L² + 4r²)/12 + π r⁴/2 + π r² L²/4 + 4 r³ L/3`. A
//! segment (r = 0) has area, mass and moment 0: as in Box2D, it gives a
//! body no mass, so a dynamic body needs another shape (or an explicit
//! mass and inertia); its centroid is its midpoint.

use super::ConvexPolygon;
use crate::error::{EngineError, Result, require_finite, require_positive};
use nalgebra::{Isometry2, Vector2};
use smallvec::SmallVec;

/// Which of the rounded kinds a [`RoundedConvex`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RoundedKind {
    /// A core of 2 vertices, radius 0.
    Segment,
    /// A core of 2 vertices, radius > 0.
    Capsule,
    /// A convex core of ≥ 3 vertices, radius > 0.
    RoundedPolygon,
}

impl RoundedKind {
    /// The kind's name in messages and scene files' terms.
    pub fn name(self) -> &'static str {
        match self {
            RoundedKind::Segment => "segment",
            RoundedKind::Capsule => "capsule",
            RoundedKind::RoundedPolygon => "rounded polygon",
        }
    }
}

/// A convex core of 2..N vertices inflated by a radius (m): a segment, a
/// capsule or a rounded polygon (see the [module docs](self)), in its
/// body's frame.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RoundedConvex {
    /// The core: 2 vertices, or ≥ 3 counter-clockwise and convex (m).
    core: Vec<Vector2<f64>>,
    /// The inflation radius (m): 0 for a segment, > 0 otherwise.
    radius: f64,
}

/// The "convex core + radius" view of any convex shape: a circle is a core
/// of 1 vertex, a segment or capsule of 2, a polygon of ≥ 3
/// (counter-clockwise); the shape is every point within `radius` of the
/// core's convex hull.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexCore {
    /// The core's vertices in the shape's frame (m).
    pub vertices: SmallVec<[Vector2<f64>; 8]>,
    /// The inflation radius (m), ≥ 0.
    pub radius: f64,
}

impl RoundedConvex {
    /// A capsule whose two cap centres are `length` (m) apart on the x
    /// axis, centred on the origin, of `radius` (m). Both must be finite
    /// and > 0 (a capsule of length 0 is a circle: use one).
    pub fn capsule(length: f64, radius: f64) -> Result<Self> {
        let half = 0.5 * require_positive("capsule length", length)?;
        let radius = require_positive("capsule radius", radius)?;
        Ok(Self {
            core: vec![Vector2::new(-half, 0.0), Vector2::new(half, 0.0)],
            radius,
        })
    }

    /// A capsule around the segment `a`–`b` (m) of `radius` (m): finite
    /// ends that differ, radius finite and > 0.
    pub fn capsule_between(a: Vector2<f64>, b: Vector2<f64>, radius: f64) -> Result<Self> {
        let radius = require_positive("capsule radius", radius)?;
        Ok(Self {
            core: checked_ends("capsule", a, b)?,
            radius,
        })
    }

    /// The segment from `a` to `b` (m): finite ends that differ.
    pub fn segment(a: Vector2<f64>, b: Vector2<f64>) -> Result<Self> {
        Ok(Self {
            core: checked_ends("segment", a, b)?,
            radius: 0.0,
        })
    }

    /// `polygon` inflated by `radius` (m), finite and > 0.
    pub fn rounded_polygon(polygon: ConvexPolygon, radius: f64) -> Result<Self> {
        let radius = require_positive("rounded polygon radius", radius)?;
        Ok(Self {
            core: polygon.vertices().to_vec(),
            radius,
        })
    }

    /// The kind: segment, capsule or rounded polygon.
    pub fn kind(&self) -> RoundedKind {
        match (self.core.len(), self.radius > 0.0) {
            (2, false) => RoundedKind::Segment,
            (2, true) => RoundedKind::Capsule,
            _ => RoundedKind::RoundedPolygon,
        }
    }

    /// The core's vertices (m): the two ends of a segment or capsule, or a
    /// rounded polygon's core counter-clockwise.
    pub fn core(&self) -> &[Vector2<f64>] {
        &self.core
    }

    /// The inflation radius (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The core as a polygon, for a rounded polygon (`None` for a segment
    /// or capsule).
    pub fn core_polygon(&self) -> Option<ConvexPolygon> {
        // Checked convex on construction (the fields are this module
        // tree's): no second check.
        (self.core.len() >= 3).then(|| ConvexPolygon {
            vertices: self.core.clone(),
        })
    }

    /// The core's own area (m²), centroid (m) and polar moment about that
    /// centroid (m⁴): those of the polygon, or 0, the midpoint, 0 for a
    /// 2-vertex core.
    fn core_mass(&self) -> (f64, Vector2<f64>, f64) {
        match self.core_polygon() {
            Some(p) => (p.area(), p.centroid(), p.polar_moment_about_centroid()),
            None => (0.0, 0.5 * (self.core[0] + self.core[1]), 0.0),
        }
    }

    /// Area (m²): core area + perimeter · r + π r² (module docs).
    pub fn area(&self) -> f64 {
        let (core_area, _, _) = self.core_mass();
        let perimeter: f64 = self.edges().map(|(a, b)| (b - a).norm()).sum();
        core_area + perimeter * self.radius + std::f64::consts::PI * self.radius * self.radius
    }

    /// The closed polygon's edges `(v_i, v_{i+1})`; a 2-vertex core gives
    /// its two sides `a → b` and `b → a`.
    fn edges(&self) -> impl Iterator<Item = (Vector2<f64>, Vector2<f64>)> + '_ {
        let n = self.core.len();
        (0..n).map(move |i| (self.core[i], self.core[(i + 1) % n]))
    }

    /// Area (m²), offset of the centroid from the core's centroid (m) and
    /// polar moment about the centroid (m⁴), by the sums of the module
    /// docs taken about the core's centroid.
    fn mass_about_core_centroid(&self) -> (f64, Vector2<f64>, f64) {
        let (core_area, core_centroid, core_moment) = self.core_mass();
        let r = self.radius;
        let n = self.core.len();
        let u: Vec<Vector2<f64>> = self.core.iter().map(|v| v - core_centroid).collect();
        let direction = |i: usize| (u[(i + 1) % n] - u[i]).normalize();
        let mut area = core_area + std::f64::consts::PI * r * r;
        let mut first = Vector2::zeros();
        let mut moment = core_moment + 0.5 * std::f64::consts::PI * r * r * r * r;
        for i in 0..n {
            // Edge i's rectangle.
            let (a, b) = (u[i], u[(i + 1) % n]);
            let length = (b - a).norm();
            let d = direction(i);
            let normal = Vector2::new(d.y, -d.x);
            let middle = 0.5 * (a + b);
            let rect_area = length * r;
            area += rect_area;
            first += rect_area * middle;
            moment += rect_area * (length * length + r * r) / 12.0
                + rect_area * (middle + 0.5 * r * normal).norm_squared();
            // Vertex i's sector (its φ r⁴/4 is in the disc term above).
            let d_prev = direction((i + n - 1) % n);
            let phi = if n == 2 {
                std::f64::consts::PI
            } else {
                super::cross(d_prev, d).atan2(d_prev.dot(&d))
            };
            let sector_area = 0.5 * phi * r * r;
            first += sector_area * u[i];
            moment +=
                sector_area * u[i].norm_squared() + 2.0 * r * r * r / 3.0 * u[i].dot(&(d_prev - d));
        }
        if area == 0.0 {
            return (0.0, Vector2::zeros(), 0.0);
        }
        let offset = first / area;
        (area, offset, moment - area * offset.norm_squared())
    }

    /// Centroid (m) in the shape's frame; a segment's is its midpoint.
    pub fn centroid(&self) -> Vector2<f64> {
        let (_, core_centroid, _) = self.core_mass();
        core_centroid + self.mass_about_core_centroid().1
    }

    /// Second moment of area about the centroid, `∫ |p − c|² dA` (m⁴); 0
    /// for a segment.
    pub fn polar_moment_about_centroid(&self) -> f64 {
        self.mass_about_core_centroid().2
    }

    /// The outline as a polygon inscribed in it, counter-clockwise (m):
    /// each corner arc (a capsule's cap) cut into chords of at most
    /// `2π / chords_per_turn` rad, joined by the straight sides. For
    /// pictures and tests; a segment's outline is its two ends.
    pub fn outline(&self, chords_per_turn: usize) -> Vec<Vector2<f64>> {
        let (core, r) = (&self.core, self.radius);
        let n = core.len();
        if r == 0.0 {
            return core.clone();
        }
        let turn = std::f64::consts::TAU;
        let angle_of_normal = |a: Vector2<f64>, b: Vector2<f64>| {
            let e = b - a;
            e.y.atan2(e.x) - 0.25 * turn
        };
        let mut outline = Vec::new();
        for i in 0..n {
            let (prev, v, next) = (core[(i + n - 1) % n], core[i], core[(i + 1) % n]);
            let start = angle_of_normal(prev, v);
            let mut end = angle_of_normal(v, next);
            while end <= start {
                end += turn;
            }
            let chords = ((end - start) / turn * chords_per_turn.max(3) as f64).ceil() as usize;
            for k in 0..=chords {
                let t = start + (end - start) * k as f64 / chords as f64;
                outline.push(v + r * Vector2::new(t.cos(), t.sin()));
            }
        }
        outline
    }

    /// The tightest axis-aligned bounds of the shape placed at `pose` (m,
    /// world frame): its core's, grown by the radius.
    pub fn bounds(&self, pose: &Isometry2<f64>) -> (Vector2<f64>, Vector2<f64>) {
        let (min, max) = super::placed_bounds(&self.core, pose);
        let radius = Vector2::repeat(self.radius);
        (min - radius, max + radius)
    }

    /// Its convex core placed at `pose` (m, world frame), to be inflated by
    /// [`radius`](Self::radius).
    pub(crate) fn core_at<'a>(
        &'a self,
        pose: &'a Isometry2<f64>,
    ) -> impl Iterator<Item = Vector2<f64>> + 'a {
        super::placed(&self.core, pose)
    }

    /// The radius (m) of the largest circle about the frame's origin inside
    /// the shape: the core's own inner radius (a 2-vertex core is thin:
    /// minus the origin's distance to it) plus the rounding, at least 0.
    pub fn inner_radius(&self) -> f64 {
        let v = &self.core;
        let core = if v.len() >= 3 {
            super::polygon::inner_radius_of(v)
        } else {
            let (a, b) = (v[0], v[1]);
            let t = (-a.dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
            -(a + t * (b - a)).norm()
        };
        (core + self.radius).max(0.0)
    }

    /// The largest distance from the frame's origin to the shape (m): its
    /// farthest core vertex plus the radius.
    pub fn max_extent(&self) -> f64 {
        self.core.iter().map(|v| v.norm()).fold(0.0, f64::max) + self.radius
    }

    /// The same shape translated so that its centroid is the origin.
    pub fn centered(&self) -> Self {
        let c = self.centroid();
        Self {
            core: self.core.iter().map(|v| v - c).collect(),
            radius: self.radius,
        }
    }
}

/// The two ends of a segment or capsule, checked finite and distinct.
fn checked_ends(kind: &str, a: Vector2<f64>, b: Vector2<f64>) -> Result<Vec<Vector2<f64>>> {
    for (what, v) in [("a.x", a.x), ("a.y", a.y), ("b.x", b.x), ("b.y", b.y)] {
        require_finite(format!("{kind} end {what}"), v)?;
    }
    if a == b {
        return Err(EngineError::InvalidParameter {
            what: format!("{kind} ends"),
            value: (b - a).norm(),
            reason: "the two ends coincide (a = b): a segment needs two distinct ends",
        });
    }
    Ok(vec![a, b])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn capsule_mass_is_a_rectangle_and_a_disc() {
        // L = 2, r = 0.5: A = 2 r L + π r² = 2 + π/4. About the centre:
        // rectangle 2 × 1: 2 (4 + 1)/12; two half discs: π r⁴/2 + π r² L²/4
        // + 4 r³ L/3 (half-disc centroid 4r/3π past each end, parallel axis).
        let c = RoundedConvex::capsule(2.0, 0.5).unwrap();
        assert_eq!(c.kind(), RoundedKind::Capsule);
        assert!((c.area() - (2.0 + PI / 4.0)).abs() < 1e-15);
        assert!(c.centroid().norm() < 1e-16);
        let expected = 2.0 * 5.0 / 12.0 + PI / 32.0 + PI / 4.0 + 4.0 * 0.125 * 2.0 / 3.0;
        let j = c.polar_moment_about_centroid();
        assert!((j - expected).abs() < 1e-14, "{j} vs {expected}");
    }

    #[test]
    fn a_segment_has_no_mass_and_refuses_equal_ends() {
        let s = RoundedConvex::segment(Vector2::new(0.0, 0.0), Vector2::new(4.0, 0.0)).unwrap();
        assert_eq!(s.kind(), RoundedKind::Segment);
        assert_eq!(s.area(), 0.0);
        assert_eq!(s.polar_moment_about_centroid(), 0.0);
        assert_eq!(s.centroid(), Vector2::new(2.0, 0.0));
        let e = RoundedConvex::segment(Vector2::new(1.0, 1.0), Vector2::new(1.0, 1.0));
        assert!(e.unwrap_err().to_string().contains("a = b"));
        let e = RoundedConvex::segment(Vector2::new(f64::NAN, 1.0), Vector2::new(1.0, 1.0));
        assert!(e.unwrap_err().to_string().contains("segment end a.x"));
    }

    #[test]
    fn bad_radii_are_refused_by_name() {
        for r in [-0.1, 0.0, f64::NAN, f64::INFINITY] {
            let e = RoundedConvex::capsule(1.0, r).unwrap_err().to_string();
            assert!(e.contains("capsule radius"), "{e}");
            let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
            let e = RoundedConvex::rounded_polygon(square, r)
                .unwrap_err()
                .to_string();
            assert!(e.contains("rounded polygon radius"), "{e}");
        }
        let e = RoundedConvex::capsule(-1.0, 0.1).unwrap_err().to_string();
        assert!(e.contains("capsule length"), "{e}");
    }

    /// An off-centre rounded right triangle against the inscribed polygon
    /// of its outline ([`RoundedConvex::outline`], N = 4096 chords per
    /// full turn), whose mass properties come from [`ConvexPolygon`]'s own
    /// (tested) formulas: independent of the sums above. The polygon lacks
    /// only the circular segments under its chords, Δ = π r² − (N/2) r²
    /// sin(2π/N) in area (≈ 8e-8 m² here); the first and second moments
    /// about the origin lack at most Δ·|p|max and Δ·|p|²max. Twice those
    /// are the tolerances (the centroid and the moment about it are
    /// compared through the moments about the origin).
    #[test]
    fn rounded_triangle_matches_its_inscribed_polygon() {
        let core = vec![
            Vector2::new(0.3, 0.2),
            Vector2::new(1.3, 0.2),
            Vector2::new(0.3, 1.7),
        ];
        let r = 0.25;
        let shape = RoundedConvex::rounded_polygon(ConvexPolygon::new(core).unwrap(), r).unwrap();
        let n_turn = 4096usize;
        let outline = shape.outline(n_turn);
        let polygon = ConvexPolygon::new(outline).unwrap();
        let deficit = PI * r * r - 0.5 * n_turn as f64 * r * r * (2.0 * PI / n_turn as f64).sin();
        let (p_max, p2_max) = (2.0, 4.0); // |p| < 2 m over the shape.
        let (a, c) = (shape.area(), shape.centroid());
        let (ap, cp) = (polygon.area(), polygon.centroid());
        assert!((a - ap).abs() < 2.0 * deficit, "{a} {ap}");
        assert!((a * c - ap * cp).norm() < 2.0 * deficit * p_max, "{c} {cp}");
        let second = shape.polar_moment_about_centroid() + a * c.norm_squared();
        let second_p = polygon.polar_moment_about_centroid() + ap * cp.norm_squared();
        assert!(
            (second - second_p).abs() < 2.0 * deficit * p2_max,
            "{second} {second_p}"
        );
    }
}
