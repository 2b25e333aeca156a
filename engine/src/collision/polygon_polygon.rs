//! Convex polygon against convex polygon: the separating axis theorem with
//! reference-face clipping (seed §7.2, Fig. 7.2–7.4; the clipping after Erin
//! Catto's Box2D-lite).
//!
//! **SAT.** Two convex polygons are disjoint iff their projections on some
//! axis are disjoint, and the axes worth testing are the edge normals of
//! both (seed Fig. 7.2). For edge i of A (vertex a_i, outward unit normal
//! n_i) the separation along n_i is `s_i = min_j n_i · (b_j − a_i)` over the
//! vertices b_j of B: the gap between B and the half-plane of that edge. The
//! largest `s` over the edges of both polygons is
//! - positive exactly when the polygons are apart (it is then a lower bound of
//!   their distance, equal to it when the closest features are a vertex and
//!   an edge whose foot lies on that edge);
//! - −(penetration depth) when they overlap: the edge normals of both are the
//!   face normals of the Minkowski difference A − B, so the shortest
//!   translation separating the polygons is along the best axis and has
//!   length −s. This is exact, not an approximation.
//!
//! **Clipping.** The best axis's edge is the *reference face*; the edge of
//! the other polygon most anti-parallel to it is the *incident face*. The
//! incident face is clipped to the slab bounded by the side planes of the
//! reference face, and the clipped points below the reference face (within a
//! margin) are the contact points: two for an edge on an edge, one for a
//! vertex on an edge. In the rare case where clipping keeps no point (a
//! vertex against a vertex), the deepest vertex of the incident polygon is
//! the contact point.
//!
//! No hysteresis is applied when the axes of A and B tie: the larger
//! separation wins, A on an exact tie, so the depth and normal are the
//! exact ones (a world may add frame-to-frame persistence on top).
//!
//! The geometry (axes, faces, clipping) is the one both models share,
//! `polygon_polygon_local.rs`, computed in A's frame (B mapped by
//! `pose_a⁻¹ pose_b`, no shift); this file applies
//! the exact model's policy to it: the exact SAT depth and normal, the
//! clipped points within the margin (the deepest incident vertex when none
//! is), mapped back to the world frame.

use super::manifold::{Manifold, ManifoldPoint};
use super::polygon_circle::edge_normal;
pub(crate) use super::polygon_polygon_local::IncidentPoint;
use super::polygon_polygon_local::{Faces, Placed, RoundPolygon, Scratch, separating_axes};
use crate::shape::ConvexPolygon;
use nalgebra::{Isometry2, Point2, Vector2};

/// The best separating axis of two polygons by SAT.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeparatingAxis {
    /// Largest separation over the edge normals of both polygons (m): > 0
    /// when apart (a lower bound of the distance), −(penetration depth)
    /// when overlapping, 0 when touching.
    pub separation: f64,
    /// The axis, a unit vector from A to B (world frame).
    pub normal: Vector2<f64>,
}

/// The outward unit edge normals of a polygon, its frame.
fn normals_of(polygon: &ConvexPolygon) -> Vec<Vector2<f64>> {
    let v = polygon.vertices();
    (0..v.len())
        .map(|i| edge_normal(v[i], v[(i + 1) % v.len()]))
        .collect()
}

/// The buffers of one polygon pair: both polygons' normals (their frames)
/// and the shared geometry's scratch.
struct Pair {
    a_normals: Vec<Vector2<f64>>,
    b_normals: Vec<Vector2<f64>>,
    scratch: Scratch,
}

impl Pair {
    fn of(a: &ConvexPolygon, b: &ConvexPolygon) -> Self {
        Self {
            a_normals: normals_of(a),
            b_normals: normals_of(b),
            scratch: Scratch::default(),
        }
    }

    /// Both polygons in A's frame (unshifted: the exact model's distances
    /// and times of impact keep the bits they had before the geometry was
    /// shared) with their best axes, `None` when an axis separates them by
    /// more than `beyond` (m).
    fn place<'s>(
        &'s mut self,
        a: &'s ConvexPolygon,
        pose_a: &Isometry2<f64>,
        b: &ConvexPolygon,
        pose_b: &Isometry2<f64>,
        beyond: f64,
    ) -> Option<Placed<'s>> {
        let ra = RoundPolygon {
            vertices: a.vertices(),
            normals: &self.a_normals,
            radius: 0.0,
        };
        let rb = RoundPolygon {
            vertices: b.vertices(),
            normals: &self.b_normals,
            radius: 0.0,
        };
        let xf = pose_a.inverse() * pose_b;
        separating_axes(&ra, &rb, &xf, Vector2::zeros(), beyond, &mut self.scratch)
    }
}

/// The reference normal of `faces` in A's frame, and the normal from A to
/// B.
fn reference_normal(placed: &Placed, faces: Faces) -> (Vector2<f64>, Vector2<f64>) {
    if faces.flip {
        let n = placed.b_normals[faces.edge_b];
        (n, -n)
    } else {
        let n = placed.a_normals[faces.edge_a];
        (n, n)
    }
}

/// Signed separation of two convex polygons along their best SAT axis:
/// positive when apart (a lower bound of the distance, see
/// [`super::proximity`] for the exact one), −(penetration depth)
/// when overlapping; the axis points from A to B.
pub fn separation_polygon_polygon(
    a: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    b: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
) -> SeparatingAxis {
    let mut pair = Pair::of(a, b);
    let Some(placed) = pair.place(a, pose_a, b, pose_b, f64::INFINITY) else {
        // Only a non-finite pose leaves no axis: no separation to report.
        return SeparatingAxis {
            separation: f64::NAN,
            normal: Vector2::new(f64::NAN, f64::NAN),
        };
    };
    let (_, normal) = reference_normal(&placed, placed.faces());
    SeparatingAxis {
        separation: placed.core_separation(),
        normal: pose_a.rotation * normal,
    }
}

/// The contact manifold of two convex polygons whose SAT separation is ≤
/// `margin` (m), by SAT and reference-face clipping; points whose gap
/// exceeds `margin` are dropped. The normal is the best SAT axis from A to
/// B; each point is midway between the incident polygon's boundary and the
/// reference face, with its depth along the normal (m).
pub fn collide_polygon_polygon_with_margin(
    a: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    b: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<Manifold> {
    clip_polygon_polygon(a, pose_a, b, pose_b, margin).map(|(m, _)| m)
}

/// The features behind a polygon–polygon manifold: the reference face and
/// the incident polygon's points, in A's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ClippedFeatures {
    /// Whether the reference face is A's (else B's).
    pub reference_is_a: bool,
    /// The reference face: the edge from vertex `edge` to `edge + 1` of the
    /// reference polygon.
    pub edge: usize,
    /// The incident polygon's points, in A's frame (m), before they are
    /// moved midway to the reference face; `count` of them.
    pub points: [Vector2<f64>; 2],
    /// Where each point comes from.
    pub ids: [IncidentPoint; 2],
    /// 1 or 2.
    pub count: usize,
}

/// [`collide_polygon_polygon_with_margin`] and the features of its points.
pub(crate) fn clip_polygon_polygon(
    a: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    b: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ClippedFeatures)> {
    clip_polygon_polygon_on(a, pose_a, b, pose_b, margin, None)
}

/// A reference face: whether it is A's (else B's), and its edge index.
pub(crate) type Face = (bool, usize);

/// The faces of either polygon whose SAT separation is within `tolerance`
/// (m) of the best one, best first: the axes along which the pair is
/// equally deep, to the contact tolerance (every axis of two coincident
/// squares), each with its unit normal from A to B (world frame).
pub(crate) fn equally_deep_faces(
    a: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    b: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
    tolerance: f64,
) -> Vec<(Face, Vector2<f64>)> {
    let mut pair = Pair::of(a, b);
    let Some(placed) = pair.place(a, pose_a, b, pose_b, f64::INFINITY) else {
        return Vec::new();
    };
    let best = placed.faces();
    let best_separation = placed.core_separation();
    let face_of = |f: Faces| (!f.flip, if f.flip { f.edge_b } else { f.edge_a });
    let mut faces = vec![(face_of(best), reference_normal(&placed, best).1)];
    for (flip, edges) in [
        (false, placed.a_vertices.len()),
        (true, placed.b_vertices.len()),
    ] {
        for edge in 0..edges {
            let candidate = placed.faces_on(flip, edge);
            if face_of(candidate) == face_of(best) {
                continue;
            }
            if placed.separation_on(candidate) >= best_separation - tolerance {
                faces.push((face_of(candidate), reference_normal(&placed, candidate).1));
            }
        }
    }
    faces
        .into_iter()
        .map(|(face, n)| (face, pose_a.rotation * n))
        .collect()
}

/// [`clip_polygon_polygon`] on the reference face `face`, or on the SAT's
/// best face when `None`.
pub(crate) fn clip_polygon_polygon_on(
    a: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    b: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
    margin: f64,
    face: Option<Face>,
) -> Option<(Manifold, ClippedFeatures)> {
    let mut pair = Pair::of(a, b);
    // A NaN separation (non-finite input) reports no contact: the shared
    // geometry then finds an axis beyond any `beyond`.
    let beyond = if face.is_none() {
        margin
    } else {
        f64::INFINITY
    };
    let placed = pair.place(a, pose_a, b, pose_b, beyond)?;
    let (faces, separation) = match face {
        None => (placed.faces(), placed.core_separation()),
        Some((reference_is_a, edge)) => {
            let faces = placed.faces_on(!reference_is_a, edge);
            (faces, placed.separation_on(faces))
        }
    };
    if separation.is_nan() || separation > margin {
        return None;
    }
    let clipped = placed.clip(faces);
    let (n, normal) = reference_normal(&placed, faces);
    // (point midway, depth, incident point, its origin), A's shifted frame.
    let mut kept: Vec<(Vector2<f64>, f64, Vector2<f64>, IncidentPoint)> = clipped.points
        [..clipped.count]
        .iter()
        .filter(|p| p.separation <= margin)
        .map(|p| (p.point, -p.separation, p.incident, p.side))
        .collect();
    if kept.is_empty() {
        // Vertex against vertex (or the edges do not face each other): the
        // deepest incident vertex, at the SAT separation itself.
        let (incident, reference_vertex) = if faces.flip {
            (placed.a_vertices, placed.b_vertices[faces.edge_b])
        } else {
            (placed.b_vertices, placed.a_vertices[faces.edge_a])
        };
        let mut deepest = 0;
        for (k, v) in incident.iter().enumerate() {
            if n.dot(v) < n.dot(&incident[deepest]) {
                deepest = k;
            }
        }
        let p = incident[deepest];
        let gap = n.dot(&(p - reference_vertex));
        kept.push((p - 0.5 * gap * n, -gap, p, IncidentPoint::Vertex(deepest)));
    }
    let to_world = |p: Vector2<f64>| {
        pose_a
            .transform_point(&Point2::from(p + placed.origin))
            .coords
    };
    let to_point =
        |&(p, depth, _, _): &(Vector2<f64>, f64, Vector2<f64>, IncidentPoint)| ManifoldPoint {
            point: to_world(p),
            depth,
        };
    let normal = pose_a.rotation * normal;
    let (first, last) = (kept[0], kept[kept.len() - 1]);
    let features = ClippedFeatures {
        reference_is_a: !faces.flip,
        edge: if faces.flip {
            faces.edge_b
        } else {
            faces.edge_a
        },
        points: [first.2 + placed.origin, last.2 + placed.origin],
        ids: [first.3, last.3],
        count: kept.len(),
    };
    let manifold = match &kept[..] {
        [p] => Manifold::one(normal, to_point(p)),
        [p, q] => Manifold::two(normal, to_point(p), to_point(q)),
        _ => unreachable!("one or two points: the fallback pushes one, the clip gives two"),
    };
    Some((manifold, features))
}

/// The contact manifold of two touching or overlapping convex polygons
/// (SAT separation ≤ 0), `None` if they are apart. See
/// [`collide_polygon_polygon_with_margin`].
pub fn collide_polygon_polygon(
    a: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    b: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
) -> Option<Manifold> {
    collide_polygon_polygon_with_margin(a, pose_a, b, pose_b, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::proximity;
    use crate::collision::test_rng::Rng;
    use crate::shape::Shape;
    use std::f64::consts::{FRAC_PI_4, PI, SQRT_2};

    fn unit_box() -> ConvexPolygon {
        ConvexPolygon::rectangle(1.0, 1.0).unwrap()
    }

    fn at(x: f64, y: f64, angle: f64) -> Isometry2<f64> {
        Isometry2::new(Vector2::new(x, y), angle)
    }

    fn sorted_x(m: &Manifold) -> Vec<ManifoldPoint> {
        let mut p = m.points().to_vec();
        p.sort_by(|a, b| a.point.x.total_cmp(&b.point.x));
        p
    }

    #[test]
    fn box_resting_on_box_has_two_points_at_the_corners() {
        // Upper box sunk 0.01 m into the lower one: the whole bottom face
        // touches, so two points at x = ±0.5, midway (y = 0.495), depth 0.01.
        let m = collide_polygon_polygon(
            &unit_box(),
            &at(0.0, 0.0, 0.0),
            &unit_box(),
            &at(0.0, 0.99, 0.0),
        )
        .unwrap();
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        let p = sorted_x(&m);
        assert_eq!(p.len(), 2);
        for (q, x) in p.iter().zip([-0.5, 0.5]) {
            assert!((q.point - Vector2::new(x, 0.495)).norm() < 1e-14, "{q:?}");
            assert!((q.depth - 0.01).abs() < 1e-14, "{q:?}");
        }
    }

    #[test]
    fn offset_box_on_box_is_clipped_to_the_overlap() {
        // Shifted by 0.3 m: the contact spans x ∈ [−0.2, 0.5].
        let m = collide_polygon_polygon(
            &unit_box(),
            &at(0.0, 0.0, 0.0),
            &unit_box(),
            &at(0.3, 0.98, 0.0),
        )
        .unwrap();
        let p = sorted_x(&m);
        assert!(
            (p[0].point - Vector2::new(-0.2, 0.49)).norm() < 1e-14,
            "{p:?}"
        );
        assert!(
            (p[1].point - Vector2::new(0.5, 0.49)).norm() < 1e-14,
            "{p:?}"
        );
        assert!(p.iter().all(|q| (q.depth - 0.02).abs() < 1e-14));
    }

    #[test]
    fn box_below_gives_the_reversed_normal() {
        // A above B: the normal from A to B points down.
        let m = collide_polygon_polygon(
            &unit_box(),
            &at(0.0, 0.99, 0.0),
            &unit_box(),
            &at(0.0, 0.0, 0.0),
        )
        .unwrap();
        assert!((m.normal + Vector2::y()).norm() < 1e-15);
        assert_eq!(m.points().len(), 2);
        assert!((m.max_depth() - 0.01).abs() < 1e-14);
    }

    #[test]
    fn diamond_corner_into_a_face_gives_one_point() {
        // A box turned by 45° with its lowest corner 0.05 m below the top
        // face of the lower box.
        let y = 0.5 + SQRT_2 / 2.0 - 0.05;
        let m = collide_polygon_polygon(
            &unit_box(),
            &at(0.0, 0.0, 0.0),
            &unit_box(),
            &at(0.1, y, FRAC_PI_4),
        )
        .unwrap();
        assert_eq!(m.points().len(), 1);
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        let p = m.points()[0];
        assert!((p.depth - 0.05).abs() < 1e-14);
        assert!((p.point - Vector2::new(0.1, 0.475)).norm() < 1e-14, "{p:?}");
    }

    #[test]
    fn separated_boxes_have_no_manifold_and_an_exact_distance() {
        // Corner to corner: the SAT separation (0.5 along x) underestimates
        // the distance √(0.5² + 0.5²).
        let (a, b) = (unit_box(), unit_box());
        let (pa, pb) = (at(0.0, 0.0, 0.0), at(1.5, 1.5, 0.0));
        assert!(collide_polygon_polygon(&a, &pa, &b, &pb).is_none());
        let s = separation_polygon_polygon(&a, &pa, &b, &pb);
        assert!((s.separation - 0.5).abs() < 1e-15);
        let (sa, sb) = (Shape::Polygon(a.clone()), Shape::Polygon(b.clone()));
        let d = proximity(&sa, &pa, &sb, &pb);
        assert!((d.distance - 0.5 * SQRT_2).abs() < 1e-15);
        assert!((d.point_a - Vector2::new(0.5, 0.5)).norm() < 1e-15);
        assert!((d.point_b - Vector2::new(1.0, 1.0)).norm() < 1e-15);
        // Within a margin, the corner-to-corner manifold falls back to the
        // deepest vertex.
        let m = collide_polygon_polygon_with_margin(&a, &pa, &b, &pb, 0.6).unwrap();
        assert_eq!(m.points().len(), 1);
        assert!((m.points()[0].depth + 0.5).abs() < 1e-15);
    }

    #[test]
    fn swapping_the_polygons_flips_the_normal_and_keeps_the_depth() {
        let mut rng = Rng::new(41);
        for _ in 0..500 {
            let a = random_polygon(&mut rng);
            let b = random_polygon(&mut rng);
            let pa = at(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-PI, PI),
            );
            let pb = at(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-PI, PI),
            );
            let ab = separation_polygon_polygon(&a, &pa, &b, &pb);
            let ba = separation_polygon_polygon(&b, &pb, &a, &pa);
            assert!((ab.separation - ba.separation).abs() < 1e-12);
            let (sa, sb) = (Shape::Polygon(a.clone()), Shape::Polygon(b.clone()));
            let dab = proximity(&sa, &pa, &sb, &pb);
            let dba = proximity(&sb, &pb, &sa, &pa);
            assert!((dab.distance - dba.distance).abs() < 1e-12);
            match (
                collide_polygon_polygon(&a, &pa, &b, &pb),
                collide_polygon_polygon(&b, &pb, &a, &pa),
            ) {
                (Some(x), Some(y)) => {
                    // Same reference face unless the two SAT axes tie.
                    if (x.normal + y.normal).norm() < 1e-12 {
                        assert!((x.max_depth() - y.max_depth()).abs() < 1e-12);
                    }
                }
                (None, None) => {}
                (x, y) => assert!(ab.separation.abs() < 1e-12, "{x:?} vs {y:?}"),
            }
        }
    }

    fn random_polygon(rng: &mut Rng) -> ConvexPolygon {
        loop {
            let k = rng.int(3, 12);
            let scale = rng.range(0.2, 1.0);
            let pts: Vec<Vector2<f64>> = (0..k)
                .map(|_| {
                    let (t, r) = (rng.range(0.0, 2.0 * PI), scale * rng.range(0.5, 1.0));
                    Vector2::new(r * t.cos(), r * t.sin())
                })
                .collect();
            if let Ok(p) = ConvexPolygon::convex_hull(&pts) {
                return p.centered();
            }
        }
    }

    /// A brute-force oracle for the penetration depth of overlapping
    /// polygons: the overlap of their projections along any direction is at
    /// least the depth, and along the SAT axis it equals it.
    #[test]
    fn depth_is_the_minimum_overlap_over_sampled_directions() {
        let mut rng = Rng::new(99);
        let mut overlapping = 0;
        for _ in 0..200 {
            let (a, b) = (random_polygon(&mut rng), random_polygon(&mut rng));
            let pa = at(0.0, 0.0, rng.range(-PI, PI));
            let pb = at(
                rng.range(-0.6, 0.6),
                rng.range(-0.6, 0.6),
                rng.range(-PI, PI),
            );
            let s = separation_polygon_polygon(&a, &pa, &b, &pb);
            if s.separation > 0.0 {
                // Apart: the best direction's gap is the distance, not s.
                continue;
            }
            overlapping += 1;
            let world = |p: &ConvexPolygon, pose: &Isometry2<f64>| -> Vec<Vector2<f64>> {
                p.vertices()
                    .iter()
                    .map(|v| pose.transform_point(&Point2::from(*v)).coords)
                    .collect()
            };
            let (wa, wb) = (world(&a, &pa), world(&b, &pb));
            // Gap along direction d: min over B − max over A.
            let gap = |d: Vector2<f64>| {
                let max_a = wa
                    .iter()
                    .map(|v| d.dot(v))
                    .fold(f64::NEG_INFINITY, f64::max);
                let min_b = wb.iter().map(|v| d.dot(v)).fold(f64::INFINITY, f64::min);
                min_b - max_a
            };
            assert!((gap(s.normal) - s.separation).abs() < 1e-12);
            for k in 0..720 {
                let t = k as f64 * PI / 360.0;
                assert!(gap(Vector2::new(t.cos(), t.sin())) <= s.separation + 1e-12);
            }
        }
        assert!(overlapping > 100, "{overlapping}");
    }
}
