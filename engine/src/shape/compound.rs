//! Compounds: a rigid union of convex parts placed in the body frame, of
//! uniform density; mass properties by the parallel axis theorem.

use super::Shape;
use crate::error::{EngineError, Result, require_positive};
use crate::material::ShapeOverrides;
use nalgebra::{Isometry2, Vector2};

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
        match self.shape.frame_centroid() {
            Some(c) => self.to_body(c),
            // Centred on its own origin: the part's offset.
            None => self.offset,
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

    /// The compound re-centred on its centroid: every part's offset less
    /// the centroid.
    pub fn centered(&self) -> Self {
        let centroid = self.centroid();
        Self {
            parts: self
                .parts
                .iter()
                .map(|p| CompoundPart {
                    offset: p.offset - centroid,
                    ..p.clone()
                })
                .collect(),
        }
    }

    /// The tightest axis-aligned bounds of the compound placed at `pose`
    /// (m, world frame): the union of its parts' (a NaN coordinate of one
    /// part is ignored, as [`crate::collision::Aabb::merged`] does).
    pub fn bounds(&self, pose: &Isometry2<f64>) -> (Vector2<f64>, Vector2<f64>) {
        self.parts
            .iter()
            .map(|p| p.shape.bounds(&(pose * Isometry2::new(p.offset, p.angle))))
            .reduce(|(min_a, max_a), (min_b, max_b)| {
                // f64::min/max return the non-NaN operand.
                (
                    Vector2::new(min_a.x.min(min_b.x), min_a.y.min(min_b.y)),
                    Vector2::new(max_a.x.max(max_b.x), max_a.y.max(max_b.y)),
                )
            })
            .expect("a compound has at least one part")
    }

    /// The radius (m) of the largest circle about the body origin inside
    /// the compound: the largest over the parts of their own less their
    /// offsets (0 if none contains the origin).
    pub fn inner_radius(&self) -> f64 {
        self.parts
            .iter()
            .map(|p| p.shape.inner_radius() - p.offset.norm())
            .fold(0.0, f64::max)
    }

    /// The largest distance from the body origin to the compound (m): over
    /// the parts, the offset plus the part's own extent.
    pub fn max_extent(&self) -> f64 {
        self.parts
            .iter()
            .map(|p| p.offset.norm() + p.shape.max_extent())
            .fold(0.0, f64::max)
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
