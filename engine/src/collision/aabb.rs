//! Axis-aligned bounding boxes (seed §7.2, Fig. 7.5 "AABB"): the cheap,
//! loose bound the broad phase sorts and sweeps.
//!
//! A box is the product of two closed intervals `[min.x, max.x] × [min.y,
//! max.y]` (m, world frame). Two boxes that only touch count as overlapping,
//! so a pair in exact contact is never dropped by the broad phase.

use crate::shape::{Circle, ConvexPolygon, Shape};
use nalgebra::{Isometry2, Vector2};

/// An axis-aligned box in the world frame (m).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Aabb {
    /// Lower-left corner (m).
    pub min: Vector2<f64>,
    /// Upper-right corner (m).
    pub max: Vector2<f64>,
}

impl Aabb {
    /// The box with the given corners (m). No check is made that
    /// `min ≤ max`; an inverted box overlaps nothing.
    pub fn new(min: Vector2<f64>, max: Vector2<f64>) -> Self {
        Self { min, max }
    }

    /// The tightest box around `polygon` placed at `pose`: the extremes of
    /// its vertices in world coordinates.
    pub fn of_polygon(polygon: &ConvexPolygon, pose: &Isometry2<f64>) -> Self {
        let (min, max) = polygon.bounds(pose);
        Self { min, max }
    }

    /// The box around `circle` centred at `pose`'s translation: centre ± r.
    pub fn of_circle(circle: &Circle, pose: &Isometry2<f64>) -> Self {
        let (min, max) = circle.bounds(pose);
        Self { min, max }
    }

    /// The tightest box around `shape` placed at `pose` ([`Shape::bounds`]).
    pub fn of_shape(shape: &Shape, pose: &Isometry2<f64>) -> Self {
        let (min, max) = shape.bounds(pose);
        Self { min, max }
    }

    /// True when the two closed boxes share at least one point (touching
    /// counts). False if either holds a NaN.
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
    }

    /// The smallest box containing both, their union (used for the swept
    /// box of a moving shape: the union of its boxes at the start and end of
    /// a step is a bound on its path only for a pure translation; add
    /// [`Aabb::loosened`] by the rotation's sweep otherwise).
    ///
    /// Symmetric, and a NaN coordinate is ignored: the other box's
    /// coordinate is kept (NaN only if both are NaN). A box holding a NaN
    /// overlaps nothing, so leaving it out of a union never hides a hit.
    pub fn merged(&self, other: &Aabb) -> Self {
        // f64::min/max return the non-NaN operand; nalgebra's inf/sup would
        // keep or drop a NaN depending on the argument order.
        Self {
            min: Vector2::new(self.min.x.min(other.min.x), self.min.y.min(other.min.y)),
            max: Vector2::new(self.max.x.max(other.max.x), self.max.y.max(other.max.y)),
        }
    }

    /// True when `other` lies inside this closed box (a shared edge
    /// counts). False if either holds a NaN.
    pub fn contains(&self, other: &Aabb) -> bool {
        self.min.x <= other.min.x
            && self.min.y <= other.min.y
            && other.max.x <= self.max.x
            && other.max.y <= self.max.y
    }

    /// The perimeter 2·(width + height) (m): the 2D surface-area measure
    /// the dynamic tree minimises. Negative for an inverted box.
    pub fn perimeter(&self) -> f64 {
        let e = self.extents();
        2.0 * (e.x + e.y)
    }

    /// The box grown by `margin` (m) on every side (shrunk if negative).
    pub fn loosened(&self, margin: f64) -> Self {
        let m = Vector2::repeat(margin);
        Self {
            min: self.min - m,
            max: self.max + m,
        }
    }

    /// True when the point (m) lies in the closed box.
    pub fn contains_point(&self, p: &Vector2<f64>) -> bool {
        self.min.x <= p.x && p.x <= self.max.x && self.min.y <= p.y && p.y <= self.max.y
    }

    /// Width and height (m).
    pub fn extents(&self) -> Vector2<f64> {
        self.max - self.min
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_unit_square_has_a_diagonal_wide_box() {
        let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
        let pose = Isometry2::new(Vector2::new(2.0, -1.0), std::f64::consts::FRAC_PI_4);
        let b = Aabb::of_polygon(&square, &pose);
        let h = std::f64::consts::SQRT_2 / 2.0;
        assert!((b.min - Vector2::new(2.0 - h, -1.0 - h)).norm() < 1e-15);
        assert!((b.max - Vector2::new(2.0 + h, -1.0 + h)).norm() < 1e-15);
    }

    #[test]
    fn circle_box_ignores_rotation() {
        let c = Circle::new(0.5).unwrap();
        let b = Aabb::of_circle(&c, &Isometry2::new(Vector2::new(1.0, 2.0), 1.3));
        assert_eq!(b.min, Vector2::new(0.5, 1.5));
        assert_eq!(b.max, Vector2::new(1.5, 2.5));
    }

    #[test]
    fn touching_boxes_overlap_and_nan_boxes_do_not() {
        let a = Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0));
        let b = Aabb::new(Vector2::new(1.0, 0.5), Vector2::new(2.0, 2.0));
        assert!(a.overlaps(&b) && b.overlaps(&a));
        let c = Aabb::new(Vector2::new(1.0 + 1e-12, 0.0), Vector2::new(2.0, 1.0));
        assert!(!a.overlaps(&c));
        let nan = Aabb::new(Vector2::new(f64::NAN, 0.0), Vector2::new(2.0, 1.0));
        assert!(!a.overlaps(&nan) && !nan.overlaps(&a));
    }

    #[test]
    fn merged_and_loosened_contain_their_inputs() {
        let a = Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0));
        let b = Aabb::new(Vector2::new(3.0, -1.0), Vector2::new(4.0, 0.5));
        let m = a.merged(&b).loosened(0.1);
        assert!((m.min - Vector2::new(-0.1, -1.1)).norm() < 1e-15);
        assert!((m.max - Vector2::new(4.1, 1.1)).norm() < 1e-15);
        assert!(m.contains_point(&Vector2::new(2.0, 0.0)));
        assert!((m.extents() - Vector2::new(4.2, 2.2)).norm() < 1e-14);
    }

    #[test]
    fn merged_is_symmetric_and_ignores_nan_coordinates() {
        let a = Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0));
        let nan = Aabb::new(Vector2::new(f64::NAN, -2.0), Vector2::new(0.5, f64::NAN));
        let expected = Aabb::new(Vector2::new(0.0, -2.0), Vector2::new(1.0, 1.0));
        assert_eq!(a.merged(&nan), expected);
        assert_eq!(nan.merged(&a), expected);
        let both = nan.merged(&nan);
        assert!(both.min.x.is_nan() && both.max.y.is_nan());
        assert_eq!((both.min.y, both.max.x), (-2.0, 0.5));
    }

    #[test]
    fn contains_is_closed_and_false_for_nan() {
        let outer = Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(2.0, 1.0));
        // Sharing the whole boundary still counts: a box contains itself.
        assert!(outer.contains(&outer));
        let inner = Aabb::new(Vector2::new(0.0, 0.25), Vector2::new(1.0, 1.0));
        assert!(outer.contains(&inner) && !inner.contains(&outer));
        let poking_out = Aabb::new(Vector2::new(1.0, 0.25), Vector2::new(2.0 + 1e-12, 0.5));
        assert!(!outer.contains(&poking_out));
        let point = Aabb::new(Vector2::new(2.0, 1.0), Vector2::new(2.0, 1.0));
        assert!(outer.contains(&point));
        let nan = Aabb::new(Vector2::new(f64::NAN, 0.5), Vector2::new(1.0, 0.5));
        assert!(!outer.contains(&nan) && !nan.contains(&outer));
    }

    #[test]
    fn perimeter_is_twice_width_plus_height() {
        let b = Aabb::new(Vector2::new(-1.0, 2.0), Vector2::new(2.0, 2.5));
        assert_eq!(b.perimeter(), 7.0);
        let point = Aabb::new(Vector2::new(3.0, 3.0), Vector2::new(3.0, 3.0));
        assert_eq!(point.perimeter(), 0.0);
    }
}
