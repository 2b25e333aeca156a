//! Convex polygon against circle, written once for both contact models
//! (seed §7.2 treats polygons; a circle is the polygon's limit and gets its
//! own closed form). `polygon_circle_local` works in the polygon's frame
//! and is Box2D v3's `b2CollidePolygonAndCircle`; the soft step turns its
//! result into a speculative point (`soft_step/manifold.rs`), the exact
//! model into its one-point manifold and the feature it persists on.
//!
//! With circle centre c and radius r (m), and for each edge i (vertices
//! v_i, v_{i+1}, outward unit normal n_i) the separation
//! `s_i = n_i · (c − v_i)`:
//! - the edge of largest `s_i` is the reference; if the centre is inside
//!   (max `s_i ≤ ε`) or its foot falls within that edge, the normal is
//!   `n_i` and the signed distance `s_i − r`;
//! - otherwise the centre is beyond one of that edge's ends and the
//!   vertex is the closest point q of the polygon: the normal is
//!   `(c − q)/|c − q|` and the signed distance `|c − q| − r`.

use super::feature_id::Feature;
use super::manifold::{LocalProximity, Manifold, Proximity};
use crate::shape::{Circle, ConvexPolygon};
use nalgebra::{Isometry2, Point2, Vector2};

/// Outward unit normal of the CCW edge from `p` to `q`.
pub(crate) fn edge_normal(p: Vector2<f64>, q: Vector2<f64>) -> Vector2<f64> {
    let e = q - p;
    Vector2::new(e.y, -e.x) / e.norm()
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

/// A polygon's feature as a feature of the one scheme.
impl From<PolygonFeature> for Feature {
    fn from(f: PolygonFeature) -> Self {
        match f {
            PolygonFeature::Vertex(i) => Feature::Vertex(i),
            PolygonFeature::Edge(i) => Feature::Edge(i),
        }
    }
}

/// The contact of a convex polygon (A) and a circle of `radius` (m) centred
/// at `center` (A's frame), written once for both contact models (Box2D
/// v3's `b2CollidePolygonAndCircle`): the edge i of largest separation
/// `s_i = n_i · (c − v_i)` (`normal_of(i)` gives n_i); when the centre is
/// outside (s_i > ε) and beyond one of that edge's ends, that vertex is the
/// closest feature (for a convex polygon the closest point of an outside
/// centre lies on the edge of largest separation or one of its ends: any
/// other edge's normal is further from the direction to the centre), else
/// the edge. `None` as soon as the separation exceeds `beyond` (m).
pub(crate) fn polygon_circle_local(
    vertices: &[Vector2<f64>],
    normal_of: impl Fn(usize) -> Vector2<f64>,
    radius: f64,
    center: Vector2<f64>,
    beyond: f64,
) -> Option<(LocalProximity, PolygonFeature)> {
    let n = vertices.len();
    let (mut best, mut separation) = (0, f64::NEG_INFINITY);
    for (i, v) in vertices.iter().enumerate() {
        let s = normal_of(i).dot(&(center - v));
        if s > separation {
            separation = s;
            best = i;
        }
    }
    if separation > radius + beyond {
        return None;
    }
    let next = (best + 1) % n;
    let (v1, v2) = (vertices[best], vertices[next]);
    let u1 = (center - v1).dot(&(v2 - v1));
    let u2 = (center - v2).dot(&(v1 - v2));
    let vertex = |v: Vector2<f64>| {
        let d = center - v;
        let distance = d.norm();
        let normal = d / distance;
        LocalProximity {
            distance: distance - radius,
            normal,
            point_a: v,
            point_b: center - radius * normal,
        }
    };
    // The centre is beyond a vertex (and outside the polygon, so the
    // direction to it is defined): the vertex is the closest feature.
    let (contact, feature) = if u1 < 0.0 && separation > f64::EPSILON {
        (vertex(v1), PolygonFeature::Vertex(best))
    } else if u2 < 0.0 && separation > f64::EPSILON {
        (vertex(v2), PolygonFeature::Vertex(next))
    } else {
        let normal = normal_of(best);
        let contact = LocalProximity {
            distance: separation - radius,
            normal,
            point_a: center - (center - v1).dot(&normal) * normal,
            point_b: center - radius * normal,
        };
        (contact, PolygonFeature::Edge(best))
    };
    if contact.distance > beyond {
        return None;
    }
    Some((contact, feature))
}

/// The exact model's polygon–circle contact, before its margin: the signed
/// distance, normal and witness points of `polygon_circle_local` in the
/// polygon's frame, turned to the world, and the polygon's feature they
/// are attained at (which the persistent contact follows). The manifold
/// is made of these (`collide_polygon_circle_with_margin`, and
/// `features.rs` with the feature); the distance of two shapes in general
/// is [`super::proximity`].
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
    let normal_of = |i: usize| edge_normal(v[i], v[(i + 1) % n]);
    let Some((local, feature)) =
        polygon_circle_local(v, normal_of, circle.radius, c, f64::INFINITY)
    else {
        unreachable!("no separation exceeds an infinite bound")
    };
    let normal = pose_a.rotation * local.normal;
    (
        Proximity {
            distance: local.distance,
            normal,
            point_a: pose_a.transform_point(&Point2::from(local.point_a)).coords,
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
    let (p, _) = closest_polygon_circle(polygon, pose_a, circle, pose_b);
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
        let (p, _) = closest_polygon_circle(&unit_box(), &at(0.0, 0.0), &c, &at(1.5, 1.5));
        assert!((p.distance - (SQRT_2 - 0.25)).abs() < 1e-15);
        assert!((p.point_a - Vector2::new(0.5, 0.5)).norm() < 1e-15);
        assert!((p.point_b - p.point_a - p.distance * p.normal).norm() < 1e-15);
    }
}
