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

use super::manifold::{LocalProximity, Manifold, Proximity};
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

/// [`distance_polygon_circle`] and the polygon's feature it is attained at:
/// [`polygon_circle_local`] in the polygon's frame, turned to the world.
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
pub(crate) mod old_reference {
    use super::*;

    /// The exact model's former polygon–circle distance (all edges' closest
    /// points), kept only as the reference the shared one is compared with.
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::test_rng::Rng;
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, SQRT_2};

    fn unit_box() -> ConvexPolygon {
        ConvexPolygon::rectangle(1.0, 1.0).unwrap()
    }

    fn at(x: f64, y: f64) -> Isometry2<f64> {
        Isometry2::translation(x, y)
    }

    #[test]
    fn shared_polygon_circle_agrees_with_the_former_exact_one() {
        // 20 000 random pairs (polygons of 3–8 hull points in a 2 m square,
        // radii 0.05–1 m, circle centres within 2.5 m, poses up to 10 m from
        // the origin). Inside the polygon and in a vertex's region both run
        // the same operations (bit for bit); in an edge's region outside,
        // the former one took the foot q = v1 + t e and |c − q|, the shared
        // one the edge normal's dot product (Box2D's), so they differ by
        // round-off: each is a chain of at most eight roundings of
        // quantities bounded by S = the largest coordinate, vertex distance,
        // radius or translation in play, each within ½ ulp, so
        // |Δ distance|, |Δ point| ≤ 2 · 8 · ε S (the bound below). The
        // normals are d/|d| and n: |Δ normal| |d| ≤ the same bound, with
        // |d| = the centre's distance to the polygon. The feature may
        // differ only where the centre is on the line between two regions
        // (u = 0, to round-off), and the points then agree to the bound.
        let mut rng = Rng::new(1919);
        let (mut compared, mut identical, mut worst) = (0, 0, 0.0_f64);
        while compared < 20_000 {
            let n = rng.int(3, 9);
            let pts: Vec<Vector2<f64>> = (0..n)
                .map(|_| Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
                .collect();
            let Ok(polygon) = ConvexPolygon::convex_hull(&pts) else {
                continue;
            };
            let polygon = polygon.centered();
            let circle = Circle::new(rng.range(0.05, 1.0)).unwrap();
            let base = Vector2::new(rng.range(-10.0, 10.0), rng.range(-10.0, 10.0));
            let pose_a = Isometry2::new(base, rng.range(-3.0, 3.0));
            let offset = Vector2::new(rng.range(-2.5, 2.5), rng.range(-2.5, 2.5));
            let pose_b = Isometry2::new(base + offset, rng.range(-3.0, 3.0));
            let (new, new_feature) = closest_polygon_circle(&polygon, &pose_a, &circle, &pose_b);
            let (old, old_feature) =
                old_reference::closest_polygon_circle(&polygon, &pose_a, &circle, &pose_b);
            compared += 1;
            if new == old && new_feature == old_feature {
                identical += 1;
                continue;
            }
            let scale = polygon
                .vertices()
                .iter()
                .map(|v| v.norm())
                .chain([circle.radius, base.norm(), (base + offset).norm()])
                .fold(0.0, f64::max);
            let bound = 16.0 * f64::EPSILON * scale;
            let to_polygon = (old.distance + circle.radius).max(f64::MIN_POSITIVE);
            let gap = (new.distance - old.distance)
                .abs()
                .max((new.point_a - old.point_a).norm())
                .max((new.normal - old.normal).norm() * to_polygon);
            worst = worst.max(gap / (f64::EPSILON * scale));
            assert!(gap <= bound, "{gap:e} > {bound:e}: {new:?} vs {old:?}");
            let radial = (new.point_b - old.point_b).norm();
            assert!(
                radial <= bound * (1.0 + circle.radius / to_polygon),
                "{radial:e}"
            );
        }
        println!("{identical} of {compared} bit for bit; worst {worst:.2} ε·S");
        assert!(identical > compared / 2, "only {identical} identical");
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
