//! Convex polygon against circle: exact (seed §7.2 treats polygons; a
//! circle is the polygon's limit and gets its own closed form).
//!
//! In the polygon's frame, with circle centre c and radius r (m), and for
//! each edge i (vertices v_i, v_{i+1}, outward unit normal n_i) the
//! separation `s_i = n_i · (c − v_i)`:
//! - if every `s_i ≤ 0` the centre is inside; the nearest edge is the one of
//!   largest `s_i`, the normal is its `n_i` and the depth is `r − max s_i`
//!   (the circle must move out by the distance of its centre to the boundary
//!   plus its radius);
//! - otherwise the centre is outside and the closest point q of the
//!   polygon is the nearest point over its edge segments (interior of an
//!   edge or a vertex); the normal is `(c − q)/|c − q|` and the signed
//!   distance `|c − q| − r`.

use super::manifold::{Manifold, Proximity};
use crate::shape::{Circle, ConvexPolygon};
use nalgebra::{Isometry2, Point2, Vector2};

/// Outward unit normal of the CCW edge from `p` to `q`.
pub(crate) fn edge_normal(p: Vector2<f64>, q: Vector2<f64>) -> Vector2<f64> {
    let e = q - p;
    Vector2::new(e.y, -e.x) / e.norm()
}

/// The closest point to `c` on the segment `[p, q]`.
pub(crate) fn closest_on_segment(
    c: Vector2<f64>,
    p: Vector2<f64>,
    q: Vector2<f64>,
) -> Vector2<f64> {
    closest_on_segment_at(c, p, q).0
}

/// The closest point to `c` on the segment `[p, q]`, and the unclamped
/// parameter `t` of the foot of `c` on its line (`p + t (q − p)`).
fn closest_on_segment_at(c: Vector2<f64>, p: Vector2<f64>, q: Vector2<f64>) -> (Vector2<f64>, f64) {
    let e = q - p;
    let t = (c - p).dot(&e) / e.norm_squared();
    (p + t.clamp(0.0, 1.0) * e, t)
}

/// Exact signed distance (m) from a convex polygon (A) to a circle (B), with
/// the normal from the polygon to the circle and witness points.
pub fn distance_polygon_circle(
    polygon: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    circle: &Circle,
    pose_b: &Isometry2<f64>,
) -> Proximity {
    closest_polygon_circle(polygon, pose_a, circle, pose_b).0
}

/// The polygon's feature nearest a circle's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PolygonFeature {
    /// The edge from vertex i to vertex i + 1 (the centre's foot lies on it,
    /// or the centre is inside and this edge is the nearest).
    Edge(usize),
    /// Vertex i.
    Vertex(usize),
}

/// [`distance_polygon_circle`] and the polygon's feature it is attained at.
pub(crate) fn closest_polygon_circle(
    polygon: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    circle: &Circle,
    pose_b: &Isometry2<f64>,
) -> (Proximity, PolygonFeature) {
    let v = polygon.vertices();
    let n = v.len();
    let c = pose_a
        .inverse_transform_point(&Point2::from(pose_b.translation.vector))
        .coords;
    let (mut best_edge, mut best_s) = (0, f64::NEG_INFINITY);
    for i in 0..n {
        let s = edge_normal(v[i], v[(i + 1) % n]).dot(&(c - v[i]));
        if s > best_s {
            (best_edge, best_s) = (i, s);
        }
    }
    let (distance, normal, on_polygon, feature) = if best_s <= 0.0 {
        // Centre inside (or on the boundary): push out through the nearest
        // edge; its foot lies on that edge.
        let normal = edge_normal(v[best_edge], v[(best_edge + 1) % n]);
        (
            best_s - circle.radius,
            normal,
            c - best_s * normal,
            PolygonFeature::Edge(best_edge),
        )
    } else {
        let feature_of = |i: usize, t: f64| {
            if t <= 0.0 {
                PolygonFeature::Vertex(i)
            } else if t >= 1.0 {
                PolygonFeature::Vertex((i + 1) % n)
            } else {
                PolygonFeature::Edge(i)
            }
        };
        let (mut q, t) = closest_on_segment_at(c, v[0], v[1]);
        let mut feature = feature_of(0, t);
        for i in 1..n {
            let (qi, t) = closest_on_segment_at(c, v[i], v[(i + 1) % n]);
            if (c - qi).norm_squared() < (c - q).norm_squared() {
                q = qi;
                feature = feature_of(i, t);
            }
        }
        let d = c - q;
        let len = d.norm();
        // len > 0 since the centre is strictly outside.
        (len - circle.radius, d / len, q, feature)
    };
    let rotation = pose_a.rotation;
    let normal = rotation * normal;
    let point_a = pose_a.transform_point(&Point2::from(on_polygon)).coords;
    (
        Proximity {
            distance,
            normal,
            point_a,
            point_b: pose_b.translation.vector - circle.radius * normal,
        },
        feature,
    )
}

/// The contact manifold of a polygon (A) and a circle (B) if their signed
/// distance is ≤ `margin` (m): one point midway between the surfaces.
pub fn collide_polygon_circle_with_margin(
    polygon: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    circle: &Circle,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<Manifold> {
    let p = distance_polygon_circle(polygon, pose_a, circle, pose_b);
    (p.distance <= margin).then(|| p.one_point_manifold())
}

/// The contact manifold of a touching or overlapping polygon (A) and
/// circle (B), `None` if they are apart.
pub fn collide_polygon_circle(
    polygon: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    circle: &Circle,
    pose_b: &Isometry2<f64>,
) -> Option<Manifold> {
    collide_polygon_circle_with_margin(polygon, pose_a, circle, pose_b, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, SQRT_2};

    fn unit_box() -> ConvexPolygon {
        ConvexPolygon::rectangle(1.0, 1.0).unwrap()
    }

    fn at(x: f64, y: f64) -> Isometry2<f64> {
        Isometry2::translation(x, y)
    }

    #[test]
    fn circle_near_a_vertex_is_pushed_along_the_diagonal() {
        // Centre 0.3·(1, 1) beyond the corner (0.5, 0.5): distance 0.3√2.
        let c = Circle::new(0.5).unwrap();
        let m = collide_polygon_circle(&unit_box(), &at(0.0, 0.0), &c, &at(0.8, 0.8)).unwrap();
        let n = Vector2::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2);
        assert!((m.normal - n).norm() < 1e-15);
        let p = m.points()[0];
        assert!((p.depth - (0.5 - 0.3 * SQRT_2)).abs() < 1e-15);
        // Midway between the corner and the circle's deepest point.
        let deepest = Vector2::new(0.8, 0.8) - 0.5 * n;
        let expected = 0.5 * (Vector2::new(0.5, 0.5) + deepest);
        assert!((p.point - expected).norm() < 1e-15);
    }

    #[test]
    fn circle_near_an_edge_is_pushed_along_its_normal() {
        let c = Circle::new(0.5).unwrap();
        let m = collide_polygon_circle(&unit_box(), &at(0.0, 0.0), &c, &at(0.9, 0.1)).unwrap();
        assert!((m.normal - Vector2::x()).norm() < 1e-15);
        assert!((m.points()[0].depth - 0.1).abs() < 1e-15);
        assert!((m.points()[0].point - Vector2::new(0.45, 0.1)).norm() < 1e-15);
    }

    #[test]
    fn circle_with_centre_inside_leaves_by_the_nearest_edge() {
        let c = Circle::new(0.1).unwrap();
        let m = collide_polygon_circle(&unit_box(), &at(0.0, 0.0), &c, &at(0.3, 0.1)).unwrap();
        assert!((m.normal - Vector2::x()).norm() < 1e-15);
        assert!((m.points()[0].depth - 0.3).abs() < 1e-15);
    }

    #[test]
    fn rotated_polygon_gives_a_rotated_normal() {
        // The box turned by 90°: its right face now points up.
        let c = Circle::new(0.5).unwrap();
        let pose = Isometry2::new(Vector2::new(1.0, 1.0), FRAC_PI_2);
        let m = collide_polygon_circle(&unit_box(), &pose, &c, &at(1.1, 1.9)).unwrap();
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        assert!((m.points()[0].depth - 0.1).abs() < 1e-14);
    }

    #[test]
    fn apart_circle_has_an_exact_distance_to_the_corner() {
        let c = Circle::new(0.25).unwrap();
        assert!(collide_polygon_circle(&unit_box(), &at(0.0, 0.0), &c, &at(1.5, 1.5)).is_none());
        let p = distance_polygon_circle(&unit_box(), &at(0.0, 0.0), &c, &at(1.5, 1.5));
        assert!((p.distance - (SQRT_2 - 0.25)).abs() < 1e-15);
        assert!((p.point_a - Vector2::new(0.5, 0.5)).norm() < 1e-15);
        assert!((p.point_b - p.point_a - p.distance * p.normal).norm() < 1e-15);
    }
}
