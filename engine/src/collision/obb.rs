//! Oriented bounding boxes and the seed's OBB overlap test (seed §7.2, Fig.
//! 7.5–7.6).
//!
//! For two boxes with centres c_a, c_b, half extents (m) and unit axes
//! (a_x, a_y), (b_x, b_y), let T = c_b − c_a. Along a unit axis L, box A
//! projects to a half-length `r_a = h_ax |a_x·L| + h_ay |a_y·L|` around
//! `c_a·L`, and likewise B. The seed's test: the boxes are **separated iff
//! `|T·L| > r_a + r_b` on one of the four axes** L ∈ {a_x, a_y, b_x, b_y}
//! (the edge normals of both boxes, so this is SAT specialised to boxes,
//! using only the centres and half extents, "the midpoints", not the
//! vertices).
//!
//! [`Obb::enclosing`] builds the box the seed wraps around a complex shape:
//! the minimum-area rectangle, which has a side on an edge of the convex
//! polygon (Freeman and Shapira, 1975), found by trying every edge.

use crate::shape::ConvexPolygon;
use nalgebra::{Isometry2, Vector2};

/// `max_L (|T·L| − r_a − r_b)` over the four axes of the two boxes (m): > 0
/// iff they are separated, −(penetration depth) when they overlap; equal to
/// the polygon SAT separation of the two boxes.
pub fn obb_separation(
    half_a: &Vector2<f64>,
    pose_a: &Isometry2<f64>,
    half_b: &Vector2<f64>,
    pose_b: &Isometry2<f64>,
) -> f64 {
    let t = pose_b.translation.vector - pose_a.translation.vector;
    let (ra, rb) = (pose_a.rotation, pose_b.rotation);
    let axes_a = [ra * Vector2::x(), ra * Vector2::y()];
    let axes_b = [rb * Vector2::x(), rb * Vector2::y()];
    let radius = |half: &Vector2<f64>, axes: &[Vector2<f64>; 2], l: &Vector2<f64>| {
        half.x * axes[0].dot(l).abs() + half.y * axes[1].dot(l).abs()
    };
    axes_a
        .iter()
        .chain(&axes_b)
        .map(|l| t.dot(l).abs() - radius(half_a, &axes_a, l) - radius(half_b, &axes_b, l))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The seed's OBB test: true when the boxes (half extents in m, centred at
/// their poses) overlap or touch, false iff `|T·L| > r_a + r_b` on one of
/// the four axes.
pub fn obb_overlap(
    half_a: &Vector2<f64>,
    pose_a: &Isometry2<f64>,
    half_b: &Vector2<f64>,
    pose_b: &Isometry2<f64>,
) -> bool {
    obb_separation(half_a, pose_a, half_b, pose_b) <= 0.0
}

/// An oriented box in a body's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    /// Half width and half height (m) along the box's own axes.
    pub half_extents: Vector2<f64>,
    /// Centre and orientation of the box in the body's frame.
    pub local_pose: Isometry2<f64>,
}

impl Obb {
    /// The minimum-area box enclosing `polygon` (in the polygon's frame):
    /// one side lies on an edge of the polygon; every edge is tried
    /// (O(n²), fine for the 3–12 vertices of a body's shape).
    pub fn enclosing(polygon: &ConvexPolygon) -> Self {
        let v = polygon.vertices();
        let n = v.len();
        let mut best: Option<(f64, Self)> = None;
        for i in 0..n {
            let u = (v[(i + 1) % n] - v[i]).normalize();
            let w = Vector2::new(-u.y, u.x);
            let (mut lo, mut hi) = (
                Vector2::repeat(f64::INFINITY),
                Vector2::repeat(f64::NEG_INFINITY),
            );
            for p in v {
                let q = Vector2::new(u.dot(p), w.dot(p));
                lo = lo.inf(&q);
                hi = hi.sup(&q);
            }
            let size = hi - lo;
            let area = size.x * size.y;
            if best.as_ref().is_none_or(|(a, _)| area < *a) {
                let mid = 0.5 * (lo + hi);
                let centre = mid.x * u + mid.y * w;
                best = Some((
                    area,
                    Self {
                        half_extents: 0.5 * size,
                        local_pose: Isometry2::new(centre, u.y.atan2(u.x)),
                    },
                ));
            }
        }
        best.map(|(_, b)| b)
            .expect("a polygon has at least 3 edges")
    }

    /// The seed's OBB test between this box on a body at `pose` and `other`
    /// on a body at `other_pose`.
    pub fn overlaps(
        &self,
        pose: &Isometry2<f64>,
        other: &Obb,
        other_pose: &Isometry2<f64>,
    ) -> bool {
        obb_overlap(
            &self.half_extents,
            &(pose * self.local_pose),
            &other.half_extents,
            &(other_pose * other.local_pose),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::polygon_polygon::separation_polygon_polygon;
    use crate::collision::test_rng::Rng;
    use nalgebra::Point2;
    use std::f64::consts::{FRAC_PI_4, PI, SQRT_2};

    #[test]
    fn seed_test_separates_along_the_right_axis() {
        let h = Vector2::new(0.5, 0.5);
        let a = Isometry2::translation(0.0, 0.0);
        // Side by side, 0.1 m apart, then touching, then overlapping.
        assert!(!obb_overlap(&h, &a, &h, &Isometry2::translation(1.1, 0.0)));
        assert!(obb_overlap(&h, &a, &h, &Isometry2::translation(1.0, 0.0)));
        assert!(obb_overlap(&h, &a, &h, &Isometry2::translation(0.9, 0.3)));
        // A diamond whose corner stops 0.05 m short of A's right face: A's
        // x axis separates them by exactly that gap.
        let diamond = Isometry2::new(Vector2::new(0.55 + SQRT_2 / 2.0, 0.0), FRAC_PI_4);
        assert!((obb_separation(&h, &a, &h, &diamond) - 0.05).abs() < 1e-15);
        // Corner to corner along the diagonal: separated along B's axis.
        let corner = Isometry2::new(Vector2::new(0.9, 0.9), FRAC_PI_4);
        let s = obb_separation(&h, &a, &h, &corner);
        assert!(
            (s - (0.9 * SQRT_2 - SQRT_2 / 2.0 - 0.5)).abs() < 1e-15,
            "{s}"
        );
    }

    #[test]
    fn obb_separation_equals_polygon_sat_on_random_boxes() {
        let mut rng = Rng::new(0x0BB);
        let mut overlaps = 0;
        for _ in 0..2000 {
            let ha = Vector2::new(rng.range(0.05, 1.0), rng.range(0.05, 1.0));
            let hb = Vector2::new(rng.range(0.05, 1.0), rng.range(0.05, 1.0));
            let pa = Isometry2::new(
                Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
                rng.range(-PI, PI),
            );
            let pb = Isometry2::new(
                Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
                rng.range(-PI, PI),
            );
            let box_a = ConvexPolygon::rectangle(2.0 * ha.x, 2.0 * ha.y).unwrap();
            let box_b = ConvexPolygon::rectangle(2.0 * hb.x, 2.0 * hb.y).unwrap();
            let sat = separation_polygon_polygon(&box_a, &pa, &box_b, &pb).separation;
            let obb = obb_separation(&ha, &pa, &hb, &pb);
            assert!((sat - obb).abs() < 1e-14, "{sat} vs {obb}");
            overlaps += usize::from(obb_overlap(&ha, &pa, &hb, &pb));
        }
        assert!(overlaps > 500 && overlaps < 1900, "{overlaps}");
    }

    #[test]
    fn enclosing_box_of_a_turned_rectangle_is_that_rectangle() {
        let pose = Isometry2::new(Vector2::new(0.3, -0.2), 0.4);
        let corners = ConvexPolygon::rectangle(2.0, 0.5).unwrap();
        let turned: Vec<Vector2<f64>> = corners
            .vertices()
            .iter()
            .map(|v| pose.transform_point(&Point2::from(*v)).coords)
            .collect();
        let obb = Obb::enclosing(&ConvexPolygon::new(turned).unwrap());
        let mut h = [obb.half_extents.x, obb.half_extents.y];
        h.sort_by(f64::total_cmp);
        assert!(
            (h[0] - 0.25).abs() < 1e-14 && (h[1] - 1.0).abs() < 1e-14,
            "{h:?}"
        );
        assert!((obb.local_pose.translation.vector - Vector2::new(0.3, -0.2)).norm() < 1e-14);
    }

    #[test]
    fn enclosing_box_contains_the_polygon_and_overlap_is_conservative() {
        let mut rng = Rng::new(5);
        for _ in 0..200 {
            let pts: Vec<Vector2<f64>> = (0..8)
                .map(|_| Vector2::new(rng.range(-1.0, 1.0), rng.range(-0.3, 0.3)))
                .collect();
            let Ok(poly) = ConvexPolygon::convex_hull(&pts) else {
                continue;
            };
            let obb = Obb::enclosing(&poly);
            let inv = obb.local_pose.inverse();
            for v in poly.vertices() {
                let q = inv.transform_point(&Point2::from(*v)).coords;
                assert!(
                    q.x.abs() <= obb.half_extents.x + 1e-12
                        && q.y.abs() <= obb.half_extents.y + 1e-12
                );
            }
            // Overlapping polygons always have overlapping boxes.
            let other = Isometry2::new(
                Vector2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)),
                rng.range(-PI, PI),
            );
            let id = Isometry2::identity();
            if separation_polygon_polygon(&poly, &id, &poly, &other).separation <= 0.0 {
                assert!(obb.overlaps(&id, &obb, &other));
            }
        }
    }
}
