//! The exact model's contacts of a rounded shape (segment,
//! capsule, rounded polygon: [`crate::shape::RoundedConvex`]) against a
//! circle, a polygon or another rounded shape, built on the geometry
//! written once for both contact models: `polygon_polygon_local.rs` (cores
//! of 2 or more vertices, each with its radius) and `polygon_circle_local`.
//!
//! **Cores.** Every convex shape but the circle is a [`Core`]: a polygon's
//! vertices with radius 0, a rounded shape's core with its radius (a
//! 2-vertex core is a segment, its two edges its two sides). The shape is
//! every point within the radius of the core, so its signed distance to
//! another is the cores' signed distance less both radii.
//!
//! **Core against core** ([`core_pair`]):
//!
//! - the separating axes of the cores (their edge normals): when the
//!   cores overlap the best axis gives the exact penetration depth (the
//!   axes are the face normals of the cores' Minkowski difference), and
//!   the incident edge clipped to the reference edge gives up to two
//!   points, each with its separation between the rounded surfaces;
//! - when the cores are apart the best axis is only a lower bound of their
//!   distance, so the nearest points of the cores are found exactly (each
//!   vertex of one against each edge of the other, O(n·m)), to choose the
//!   features the contact is built on. A vertex nearest the interior of an
//!   edge makes that edge the reference face (its normal is then the
//!   exact direction), clipped as above: a capsule lying on a box keeps
//!   two points. A vertex nearest a vertex (a capsule's cap against a box
//!   corner) is a round contact along the line between the two vertices,
//!   one point, Box2D v3's vertex–vertex case of `b2CollidePolygons`.
//!
//! **Core against circle** ([`core_circle`]): `polygon_circle_local` with
//! the radii summed, its core point moved out by the core's radius.
//!
//! The features of each contact are those of `features.rs` with the
//! rounding folded in: a reference face on a rounded core is its core edge
//! moved out by the core's radius (`face_point`), the incident shape's
//! radius is the Face's `radius`, and a vertex–vertex contact is a
//! [`ContactFeatures::Round`] of two vertices with their radii, identified
//! by `FeatureId::vertex_pair` (`feature_id.rs`).

use super::feature_id::FeatureId;
use super::features::{ContactFeatures, polygon_circle_features};
use super::manifold::{Manifold, ManifoldPoint, Proximity};
use super::polygon_circle::{PolygonFeature, edge_normal, polygon_circle_local};
use super::polygon_polygon::Face;
use super::polygon_polygon_local::{
    Faces, IncidentPoint, Placed, RoundPolygon, Scratch, separating_axes,
};
use nalgebra::{Isometry2, Point2, Vector2};

/// A convex core of 2 or more vertices (counter-clockwise, its shape's
/// frame, m) and its radius (m): a polygon (radius 0) or a rounded shape.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Core<'a> {
    /// The vertices (m).
    pub vertices: &'a [Vector2<f64>],
    /// The radius (m), ≥ 0.
    pub radius: f64,
}

/// The outward unit normals of a core's edges (both sides of a segment).
fn normals_of(v: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    (0..v.len())
        .map(|i| edge_normal(v[i], v[(i + 1) % v.len()]))
        .collect()
}

/// Where the cores of a pair are nearest, when they are apart.
#[derive(Debug, Clone, Copy)]
enum Nearest {
    /// A vertex nearest the interior of an edge: the edge is the reference
    /// face, on A (`reference_is_a`) or B.
    Face { reference_is_a: bool, edge: usize },
    /// A vertex of A nearest a vertex of B.
    Vertices { vertex_a: usize, vertex_b: usize },
}

/// The nearest points of two cores that do not overlap (A's frame, m), and
/// the features they lie on.
fn nearest(placed: &Placed) -> (Vector2<f64>, Vector2<f64>, Nearest) {
    let mut best = (
        f64::INFINITY,
        Vector2::zeros(),
        Vector2::zeros(),
        Nearest::Vertices {
            vertex_a: 0,
            vertex_b: 0,
        },
    );
    for from_is_a in [true, false] {
        let (from, to, to_normals) = if from_is_a {
            (placed.a_vertices, placed.b_vertices, placed.b_normals)
        } else {
            (placed.b_vertices, placed.a_vertices, placed.a_normals)
        };
        let m = to.len();
        for (k, w) in from.iter().enumerate() {
            for i in 0..m {
                let (p, q) = (to[i], to[(i + 1) % m]);
                // The edge's own side only: a segment's two sides are the
                // same points, and the one facing the vertex is the face.
                if to_normals[i].dot(&(w - p)) < 0.0 {
                    continue;
                }
                let e = q - p;
                let t = (w - p).dot(&e) / e.norm_squared();
                let (on, feature) = if t <= 0.0 || t >= 1.0 {
                    let j = if t <= 0.0 { i } else { (i + 1) % m };
                    let (vertex_a, vertex_b) = if from_is_a { (k, j) } else { (j, k) };
                    (to[j], Nearest::Vertices { vertex_a, vertex_b })
                } else {
                    (
                        p + t * e,
                        Nearest::Face {
                            reference_is_a: !from_is_a,
                            edge: i,
                        },
                    )
                };
                let d2 = (w - on).norm_squared();
                if d2 < best.0 {
                    best = if from_is_a {
                        (d2, *w, on, feature)
                    } else {
                        (d2, on, *w, feature)
                    };
                }
            }
        }
    }
    (best.1, best.2, best.3)
}

/// The two cores placed in A's frame (B by `pose_a⁻¹ pose_b`, no shift),
/// `None` when an axis separates the cores by more than `beyond` (m).
fn place<'s>(
    a: Core<'s>,
    normals_a: &'s [Vector2<f64>],
    b: Core<'_>,
    normals_b: &[Vector2<f64>],
    xf: &Isometry2<f64>,
    beyond: f64,
    scratch: &'s mut Scratch,
) -> Option<Placed<'s>> {
    let ra = RoundPolygon {
        vertices: a.vertices,
        normals: normals_a,
        radius: a.radius,
    };
    let rb = RoundPolygon {
        vertices: b.vertices,
        normals: normals_b,
        radius: b.radius,
    };
    separating_axes(&ra, &rb, xf, Vector2::zeros(), beyond, scratch)
}

/// The contact of cores `a` at `pose_a` and `b` at `pose_b` when their
/// rounded surfaces are within `margin` (m), with its features (see the
/// module docs); clipped on the reference face `face` instead of the best
/// one when given.
pub(crate) fn core_pair(
    a: Core,
    pose_a: &Isometry2<f64>,
    b: Core,
    pose_b: &Isometry2<f64>,
    margin: f64,
    face: Option<Face>,
) -> Option<(Manifold, ContactFeatures)> {
    let (na, nb) = (normals_of(a.vertices), normals_of(b.vertices));
    let mut scratch = Scratch::default();
    let xf = pose_a.inverse() * pose_b;
    let beyond = if face.is_none() {
        margin + a.radius + b.radius
    } else {
        f64::INFINITY
    };
    let placed = place(a, &na, b, &nb, &xf, beyond, &mut scratch)?;
    let faces = match face {
        Some((reference_is_a, edge)) => placed.faces_on(!reference_is_a, edge),
        None if placed.core_separation() > 0.0 => match nearest(&placed).2 {
            Nearest::Face {
                reference_is_a,
                edge,
            } => placed.faces_on(!reference_is_a, edge),
            Nearest::Vertices { vertex_a, vertex_b } => {
                return vertex_pair(a, b, vertex_a, vertex_b, pose_a, pose_b, margin);
            }
        },
        None => placed.faces(),
    };
    clip_on(a, b, &placed, faces, &xf, pose_a, margin)
}

/// The round contact of A's core vertex `vertex_a` and B's `vertex_b`,
/// within `margin` (m).
fn vertex_pair(
    a: Core,
    b: Core,
    vertex_a: usize,
    vertex_b: usize,
    pose_a: &Isometry2<f64>,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    let (point_a, point_b) = (a.vertices[vertex_a], b.vertices[vertex_b]);
    let qa = pose_a.transform_point(&Point2::from(point_a)).coords;
    let qb = pose_b.transform_point(&Point2::from(point_b)).coords;
    let length = (qb - qa).norm();
    let distance = length - a.radius - b.radius;
    if distance.is_nan() || distance > margin || length == 0.0 {
        return None;
    }
    let n = (qb - qa) / length;
    let id = FeatureId::vertex_pair(vertex_a, vertex_b);
    Some((
        Manifold::one(
            n,
            ManifoldPoint {
                point: qa + (a.radius + 0.5 * distance) * n,
                depth: -distance,
            },
        ),
        ContactFeatures::Round {
            point_a,
            radius_a: a.radius,
            point_b,
            radius_b: b.radius,
            id,
        },
    ))
}

/// The incident edge of `faces` clipped to its reference edge: the points
/// within `margin` (the deepest incident vertex when none is), in the
/// world, and their features.
fn clip_on(
    a: Core,
    b: Core,
    placed: &Placed,
    faces: Faces,
    xf: &Isometry2<f64>,
    pose_a: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    let reference_is_a = !faces.flip;
    let (reference, edge, incident) = if reference_is_a {
        (a, faces.edge_a, b)
    } else {
        (b, faces.edge_b, a)
    };
    // The reference normal in A's frame, the normal from A to B.
    let n = if reference_is_a {
        placed.a_normals[edge]
    } else {
        placed.b_normals[edge]
    };
    let normal = if reference_is_a { n } else { -n };
    let clipped = placed.clip(faces);
    // (point midway, depth, incident core point, its origin), A's frame.
    let mut kept: Vec<(Vector2<f64>, f64, Vector2<f64>, IncidentPoint)> = clipped.points
        [..clipped.count]
        .iter()
        .filter(|p| p.separation <= margin)
        .map(|p| (p.point, -p.separation, p.incident, p.side))
        .collect();
    if kept.is_empty() {
        // The edges do not face each other: the deepest incident vertex.
        let (vertices, on_reference) = if reference_is_a {
            (placed.b_vertices, placed.a_vertices[edge])
        } else {
            (placed.a_vertices, placed.b_vertices[edge])
        };
        let deepest = (0..vertices.len())
            .min_by(|&i, &j| n.dot(&vertices[i]).total_cmp(&n.dot(&vertices[j])))
            .expect("a core has vertices");
        let p = vertices[deepest];
        let s = n.dot(&(p - on_reference));
        let separation = s - reference.radius - incident.radius;
        if separation.is_nan() || separation > margin {
            return None;
        }
        let point = p - 0.5 * (s - reference.radius + incident.radius) * n;
        kept.push((point, -separation, p, IncidentPoint::Vertex(deepest)));
    }
    let world = |p: Vector2<f64>| pose_a.transform_point(&Point2::from(p)).coords;
    let to_point =
        |&(p, depth, _, _): &(Vector2<f64>, f64, Vector2<f64>, IncidentPoint)| ManifoldPoint {
            point: world(p),
            depth,
        };
    // The incident points from A's frame to the incident shape's.
    let to_incident = |p: Vector2<f64>| {
        if reference_is_a {
            xf.inverse_transform_point(&Point2::from(p)).coords
        } else {
            p
        }
    };
    let world_normal = pose_a.rotation * normal;
    let (first, last) = (kept[0], kept[kept.len() - 1]);
    let manifold = match &kept[..] {
        [p] => Manifold::one(world_normal, to_point(p)),
        [p, q] => Manifold::two(world_normal, to_point(p), to_point(q)),
        _ => unreachable!("one or two points: the fallback pushes one, the clip gives two"),
    };
    // The reference face in its own frame, moved out by its radius.
    let v = reference.vertices;
    let face_normal = edge_normal(v[edge], v[(edge + 1) % v.len()]);
    Some((
        manifold,
        ContactFeatures::Face {
            reference_is_a,
            normal: face_normal,
            face_point: v[edge] + reference.radius * face_normal,
            points: [to_incident(first.2), to_incident(last.2)],
            count: kept.len(),
            radius: incident.radius,
            id: FeatureId::face(reference_is_a, edge, first.3.into(), last.3.into()),
        },
    ))
}

/// A core (A) against a circle of `circle_radius` (m) at `pose_b`: the
/// signed distance, normal and witnesses the contact is made of, and the
/// core's feature nearest the centre (which the persistent contact
/// follows).
fn core_circle_closest(
    core: Core,
    pose_a: &Isometry2<f64>,
    circle_radius: f64,
    pose_b: &Isometry2<f64>,
) -> (Proximity, PolygonFeature) {
    let v = core.vertices;
    let c = pose_a
        .inverse_transform_point(&Point2::from(pose_b.translation.vector))
        .coords;
    let normal_of = |i: usize| edge_normal(v[i], v[(i + 1) % v.len()]);
    let Some((local, feature)) =
        polygon_circle_local(v, normal_of, core.radius + circle_radius, c, f64::INFINITY)
    else {
        unreachable!("no separation exceeds an infinite bound")
    };
    let normal = pose_a.rotation * local.normal;
    let point_a = local.point_a + core.radius * local.normal;
    (
        Proximity {
            distance: local.distance,
            normal,
            point_a: pose_a.transform_point(&Point2::from(point_a)).coords,
            point_b: pose_b.translation.vector - circle_radius * normal,
        },
        feature,
    )
}

/// The contact of a core (A) and a circle (B) within `margin` (m): one
/// point midway between the surfaces, and its features.
pub(crate) fn core_circle(
    core: Core,
    pose_a: &Isometry2<f64>,
    circle_radius: f64,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    let (proximity, feature) = core_circle_closest(core, pose_a, circle_radius, pose_b);
    // A NaN distance (non-finite input) reports no contact.
    (proximity.distance <= margin).then_some(())?;
    Some((
        proximity.one_point_manifold(),
        polygon_circle_features(core.vertices, core.radius, feature, circle_radius, true),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::proximity;
    use crate::shape::Shape;
    use std::f64::consts::FRAC_PI_2;

    fn at(x: f64, y: f64, angle: f64) -> Isometry2<f64> {
        Isometry2::new(Vector2::new(x, y), angle)
    }

    fn core(shape: &Shape) -> (Vec<Vector2<f64>>, f64) {
        let c = shape.convex_core().unwrap();
        (c.vertices.to_vec(), c.radius)
    }

    /// A capsule (L = 2, r = 0.25) lying 1 m above a segment ground: gap
    /// 0.75 m, normal straight up, two contact points when sunk (the
    /// capsule's core is parallel to the ground); standing upright across
    /// the ground line, its core crosses it: depth to the nearer end (0.6
    /// below) plus r. Exact geometry, a few ulps.
    #[test]
    fn a_capsule_over_a_segment() {
        let (g, gr) =
            core(&Shape::segment(Vector2::new(-5.0, 0.0), Vector2::new(5.0, 0.0)).unwrap());
        let (c, cr) = core(&Shape::capsule(2.0, 0.25).unwrap());
        let ground = Core {
            vertices: &g,
            radius: gr,
        };
        let pill = Core {
            vertices: &c,
            radius: cr,
        };
        let origin = at(0.0, 0.0, 0.0);
        let (ground_shape, pill_shape) = (
            Shape::segment(Vector2::new(-5.0, 0.0), Vector2::new(5.0, 0.0)).unwrap(),
            Shape::capsule(2.0, 0.25).unwrap(),
        );
        let p = proximity(&ground_shape, &origin, &pill_shape, &at(1.0, 1.0, 0.0));
        assert!((p.distance - 0.75).abs() < 1e-15, "{p:?}");
        assert!((p.normal - Vector2::y()).norm() < 1e-15, "{p:?}");
        let (m, _) = core_pair(ground, &origin, pill, &at(1.0, 0.15, 0.0), 0.0, None).unwrap();
        assert_eq!(m.points().len(), 2);
        for q in m.points() {
            assert!((q.depth - 0.1).abs() < 1e-15, "{m:?}");
            assert!((q.point.y + 0.05).abs() < 1e-15, "{m:?}");
        }
        let p = proximity(
            &ground_shape,
            &origin,
            &pill_shape,
            &at(0.0, 0.4, FRAC_PI_2),
        );
        assert!((p.distance + 0.6 + 0.25).abs() < 1e-12, "{p:?}");
        assert!((p.point_b - p.point_a - p.distance * p.normal).norm() < 1e-12);
    }

    /// A capsule's cap against a box's corner, cores apart and nearest at
    /// two vertices: the normal runs along the line between the corner and
    /// the cap's centre, the depth is the radius less their distance.
    #[test]
    fn a_cap_on_a_corner_is_a_vertex_pair() {
        let square = [
            Vector2::new(-0.5, -0.5),
            Vector2::new(0.5, -0.5),
            Vector2::new(0.5, 0.5),
            Vector2::new(-0.5, 0.5),
        ];
        let (c, cr) = core(&Shape::capsule(1.0, 0.3).unwrap());
        let boxed = Core {
            vertices: &square,
            radius: 0.0,
        };
        let pill = Core {
            vertices: &c,
            radius: cr,
        };
        // The capsule's left cap centre (its core's first vertex) at
        // corner + 0.2 (cos 30°, sin 30°): its body centre 0.5 m further
        // along its own axis, turned by 30°.
        let angle = 30f64.to_radians();
        let dir = Vector2::new(angle.cos(), angle.sin());
        let cap = Vector2::new(0.5, 0.5) + 0.2 * dir;
        let centre = cap + 0.5 * dir;
        let (m, f) = core_pair(
            boxed,
            &at(0.0, 0.0, 0.0),
            pill,
            &at(centre.x, centre.y, angle),
            0.0,
            None,
        )
        .unwrap();
        assert!((m.normal - dir).norm() < 1e-15, "{m:?}");
        assert_eq!(m.points().len(), 1);
        assert!((m.points()[0].depth - 0.1).abs() < 1e-15, "{m:?}");
        assert!(matches!(f, ContactFeatures::Round { id, .. } if id.is_vertex_pair()));
        let p = proximity(
            &Shape::rectangle(1.0, 1.0).unwrap(),
            &at(0.0, 0.0, 0.0),
            &Shape::capsule(1.0, 0.3).unwrap(),
            &at(centre.x, centre.y, angle),
        );
        assert!(
            (p.distance + 0.1).abs() < 1e-15 && (p.normal - dir).norm() < 1e-15,
            "{p:?}"
        );
    }
}
