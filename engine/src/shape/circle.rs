//! Circles: a radius about the frame's origin; as a convex core, one
//! vertex at the origin inflated by the radius.

use crate::error::{Result, require_positive};
use nalgebra::{Isometry2, Vector2};

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

    /// Area π r² (m²).
    pub fn area(&self) -> f64 {
        std::f64::consts::PI * self.radius * self.radius
    }

    /// Moment of inertia about the centre per unit mass, r²/2 (m²).
    pub fn inertia_per_unit_mass(&self) -> f64 {
        0.5 * self.radius * self.radius
    }

    /// The axis-aligned bounds of the circle centred at `pose`'s
    /// translation (m, world frame): centre ± r.
    pub fn bounds(&self, pose: &Isometry2<f64>) -> (Vector2<f64>, Vector2<f64>) {
        let c = pose.translation.vector;
        let r = Vector2::repeat(self.radius);
        (c - r, c + r)
    }

    /// Its convex core placed at `pose` (m, world frame): the centre, one
    /// vertex (inflated by the radius).
    pub(crate) fn core_at(&self, pose: &Isometry2<f64>) -> impl Iterator<Item = Vector2<f64>> {
        std::iter::once(pose.translation.vector)
    }
}
