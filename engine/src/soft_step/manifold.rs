//! The soft step's narrow phase: the contact manifold of two shapes in the
//! frame of the first, each point carrying a **feature id** that names the
//! pair of features (a reference edge and an incident vertex) that made it,
//! in the one scheme both models use (`collision/feature_id.rs`), so the
//! next step's point from the same features inherits its impulses (warm
//! starting).
//!
//! Every convex shape but the circle is a core of 2 or more vertices and a
//! radius (`geometry.rs`'s `Polygon`: a polygon has radius 0; a segment,
//! capsule or rounded polygon is its core and radius). Separations are
//! between the rounded surfaces and every point lies midway between them.
//!
//! Two cores of which at least one has 3 or more vertices go through the
//! geometry both models share (`collision/polygon_polygon_local.rs`:
//! separating axes, reference and incident edges, the clipped points midway
//! between the surfaces with their separations, each radius taken off),
//! and this file applies the soft step's policy, Box2D v3's
//! (`b2CollidePolygons`, which Box2D also uses for a capsule or segment
//! against a polygon): beyond the speculative distance (plus both radii,
//! between the cores) there is no manifold; when the cores are apart
//! (separation over a tenth of the linear slop) and two vertices are
//! substantially closer than the clipped points, a single vertex–vertex
//! point along the line between them.
//!
//! Two 2-vertex cores (segments and capsules) cannot go that way: the
//! separating axes of two parallel segments are only their common normal,
//! which does not part two capsules lying end to end on one line. They take
//! the closest points of the two segments instead (as Box2D's
//! `b2CollideCapsules`, written anew): two clipped points when the segments
//! overlap along each other's direction and the clipped points are about as
//! near as the closest ones, else one point between the closest points.
//!
//! A core against a circle takes the edge of least penetration, or the
//! nearest vertex when the centre lies beyond it (`polygon_circle_local`,
//! with the circle's radius grown by the core's); a 2-vertex core takes the
//! point of its segment nearest the centre (its two sides would miss a
//! centre on its line past an end); two circles meet along the line of
//! centres (`circle_circle_local`). These make one-point manifolds.
//!
//! A chain's segment against a core goes through
//! `collision/chain_segment.rs` (one-sided and smooth, the core's radius
//! taken off as Box2D's `b2CollideChainSegmentAndPolygon` does), or against
//! a circle through its circle function.
//!
//! Every point is at the middle of the overlap, so it is the same whichever
//! shape is called A; the normal points from A to B; lengths are in m.

use super::geometry::{Polygon, SolverShape};
use crate::collision::chain_segment::{
    SegmentManifold, chain_segment_circle_local, chain_segment_polygon_local,
};
use crate::collision::circle_circle::circle_circle_local;
use crate::collision::feature_id::{Feature, FeatureId};
use crate::collision::manifold::LocalProximity;
use crate::collision::polygon_circle::polygon_circle_local;
use crate::collision::polygon_polygon_local::{Clipped, Placed, RoundPolygon, separating_axes};
use crate::collision::segment_distance::segment_distance;
use nalgebra::{Isometry2, Vector2};

/// Buffers reused by every polygon pair (no allocation once grown).
pub(crate) use crate::collision::polygon_polygon_local::Scratch;

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub(crate) use crate::tunables::LINEAR_SLOP;

/// A point of a [`LocalManifold`], in A's frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct LocalPoint {
    /// Midway between the surfaces (m), A's frame, from A's origin.
    pub point: Vector2<f64>,
    /// Signed distance along the normal (m): < 0 overlapping.
    pub separation: f64,
    /// The features of A and B that made the point
    /// ([`FeatureId::pair`] of the one scheme, `collision/feature_id.rs`).
    pub id: FeatureId,
}

/// A manifold in A's frame: 0, 1 or 2 points sharing a normal.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct LocalManifold {
    /// Unit normal from A to B, A's frame.
    pub normal: Vector2<f64>,
    pub count: usize,
    pub points: [LocalPoint; 2],
}

/// The manifold of `a` and `b`, where `xf` maps B's frame into A's, with
/// points kept while their separation is at most `speculative` (m).
/// Polygon–circle pairs take the polygon as A: the caller orders them.
/// Inlined into the collide stage's loop (`contacts.rs`'s
/// `update_contact`): a call there puts the pair's poses in memory on
/// every contact, the recycled ones included.
#[inline(always)]
pub(crate) fn collide(
    a: &SolverShape,
    b: &SolverShape,
    xf: &Isometry2<f64>,
    speculative: f64,
    scratch: &mut Scratch,
) -> LocalManifold {
    match (a, b) {
        (SolverShape::Polygon(pa), SolverShape::Polygon(pb)) => {
            if pa.is_segment() && pb.is_segment() {
                collide_capsules(pa, pb, xf, speculative)
            } else {
                collide_polygons(pa, pb, xf, speculative, scratch)
            }
        }
        (SolverShape::Polygon(p), SolverShape::Circle { radius }) => {
            let center = xf.translation.vector;
            if p.is_segment() {
                return capsule_circle(p, *radius, center, speculative);
            }
            let normal_of = |i: usize| p.normals[i];
            if p.radius == 0.0 {
                return polygon_circle_local(&p.vertices, normal_of, *radius, center, speculative)
                    .map_or_else(LocalManifold::default, |(contact, _)| one_point(contact));
            }
            // A rounded core: the circle grown by the core's radius against
            // the core; the point then moves out to midway between the
            // rounded surfaces (both witnesses lie `p.radius` inside them).
            let grown = *radius + p.radius;
            polygon_circle_local(&p.vertices, normal_of, grown, center, speculative).map_or_else(
                LocalManifold::default,
                |(contact, _)| {
                    let mut m = one_point(contact);
                    m.points[0].point += p.radius * contact.normal;
                    m
                },
            )
        }
        (SolverShape::Circle { radius: ra }, SolverShape::Circle { radius: rb }) => {
            circle_circle_local(*ra, *rb, xf.translation.vector, speculative)
                .map_or_else(LocalManifold::default, one_point)
        }
        (SolverShape::Circle { .. }, SolverShape::Polygon(_)) => {
            unreachable!("pairs are ordered polygon first")
        }
        (SolverShape::ChainSegment(s), SolverShape::Polygon(p)) => from_segment_manifold(
            chain_segment_polygon_local(s, (&p.vertices, &p.normals, p.radius), xf, speculative),
        ),
        (SolverShape::ChainSegment(s), SolverShape::Circle { radius }) => {
            chain_segment_circle_local(s, *radius, xf.translation.vector, speculative)
                .map_or_else(LocalManifold::default, one_point)
        }
        // Chains are on static bodies, which never pair with each other.
        (SolverShape::ChainSegment(_), SolverShape::ChainSegment(_)) => LocalManifold::default(),
        (_, SolverShape::ChainSegment(_)) => unreachable!("pairs are ordered chain segment first"),
    }
}

/// A chain segment's manifold (`collision/chain_segment.rs`) as the soft
/// step's.
fn from_segment_manifold(m: SegmentManifold) -> LocalManifold {
    let point = |p: &crate::collision::chain_segment::SegmentPoint| LocalPoint {
        point: p.point,
        separation: p.separation,
        id: p.id,
    };
    LocalManifold {
        normal: m.normal,
        count: m.count,
        points: [point(&m.points[0]), point(&m.points[1])],
    }
}

/// The one-point manifold of a circle pair's [`LocalProximity`]: the point
/// midway between the surfaces, [`FeatureId::ONE_POINT`] (nothing to tell
/// apart, as Box2D's circle manifolds).
fn one_point(contact: LocalProximity) -> LocalManifold {
    LocalManifold {
        normal: contact.normal,
        count: 1,
        points: [
            LocalPoint {
                point: 0.5 * (contact.point_a + contact.point_b),
                separation: contact.distance,
                id: FeatureId::ONE_POINT,
            },
            LocalPoint::default(),
        ],
    }
}

/// Two cores with their radii (a sharp polygon has radius 0, which keeps
/// the bits of the sharp pair: every radius term adds or takes off +0).
fn collide_polygons(
    pa: &Polygon,
    pb: &Polygon,
    xf: &Isometry2<f64>,
    speculative: f64,
    scratch: &mut Scratch,
) -> LocalManifold {
    let a = RoundPolygon {
        vertices: &pa.vertices,
        normals: &pa.normals,
        radius: pa.radius,
    };
    let b = RoundPolygon {
        vertices: &pb.vertices,
        normals: &pb.normals,
        radius: pb.radius,
    };
    let radius = a.radius + b.radius;
    let origin = pa.vertices[0];
    let Some(placed) = separating_axes(&a, &b, xf, origin, speculative + radius, scratch) else {
        return LocalManifold::default();
    };
    let mut manifold = if placed.axis_a.1 > 0.1 * LINEAR_SLOP || placed.axis_b.1 > 0.1 * LINEAR_SLOP
    {
        apart(&placed, speculative)
    } else {
        local_manifold(placed.clip(placed.faces()))
    };
    for p in &mut manifold.points[..manifold.count] {
        p.point += placed.origin;
    }
    manifold
}

/// Feature of a capsule's core for the point between the closest points
/// of two segments at `fraction` along it: its first end (vertex 0), its
/// second (vertex 1), or its inside (edge 0). A clipped point names the
/// reference segment's edge 0 and the incident end as a clip, which none of
/// these pairs is, so that it never takes over the impulse of a
/// closest-point one.
fn segment_feature(fraction: f64) -> Feature {
    if fraction == 0.0 {
        Feature::Vertex(0)
    } else if fraction == 1.0 {
        Feature::Vertex(1)
    } else {
        Feature::Edge(0)
    }
}

/// Two segments or capsules (2-vertex cores, `xf` mapping B's frame into
/// A's): see the module documentation. Lengths in m.
fn collide_capsules(
    pa: &Polygon,
    pb: &Polygon,
    xf: &Isometry2<f64>,
    speculative: f64,
) -> LocalManifold {
    // A's first end is the origin: round-off stays relative to the pair.
    let origin = pa.vertices[0];
    let shift = xf.translation.vector - origin;
    let (p1, q1) = (Vector2::zeros(), pa.vertices[1] - origin);
    let (p2, q2) = (
        xf.rotation * pb.vertices[0] + shift,
        xf.rotation * pb.vertices[1] + shift,
    );
    let (ra, rb) = (pa.radius, pb.radius);
    let radius = ra + rb;
    let closest = segment_distance(p1, q1, p2, q2);
    let reach = speculative + radius;
    if closest.distance_squared > reach * reach {
        return LocalManifold::default();
    }
    let distance = closest.distance_squared.sqrt();
    let mut manifold = clip_capsules((p1, q1, ra), (p2, q2, rb), distance, speculative)
        .unwrap_or_else(|| {
            // One point between the closest points.
            let c1 = p1 + closest.fraction_a * (q1 - p1);
            let c2 = p2 + closest.fraction_b * (q2 - p2);
            let normal = if distance > 0.0 {
                (c2 - c1) / distance
            } else {
                // Crossing cores: A's side normal (its first edge's).
                pa.normals[0]
            };
            LocalManifold {
                normal,
                count: 1,
                points: [
                    LocalPoint {
                        point: 0.5 * ((c1 + ra * normal) + (c2 - rb * normal)),
                        separation: distance - radius,
                        id: FeatureId::pair(
                            segment_feature(closest.fraction_a),
                            segment_feature(closest.fraction_b),
                        ),
                    },
                    LocalPoint::default(),
                ],
            }
        });
    for p in &mut manifold.points[..manifold.count] {
        p.point += origin;
    }
    manifold
}

/// Two segments that overlap along each other's direction: the one whose
/// side normal separates the other more is the reference, the other is
/// clipped to its extent, and the two clipped points each carry their
/// separation, placed midway between the rounded surfaces; `None` when
/// they do not overlap so, or when both clipped points are more than the
/// linear slop farther than the closest points' `distance` (m: the
/// segments then cross at an angle, and one point tells better). A clipped
/// point beyond the `speculative` distance (m) is dropped, as the chain's
/// (`collision/chain_segment.rs`). Each segment is `(first end, second end,
/// radius)`, A's frame.
fn clip_capsules(
    (p1, q1, ra): (Vector2<f64>, Vector2<f64>, f64),
    (p2, q2, rb): (Vector2<f64>, Vector2<f64>, f64),
    distance: f64,
    speculative: f64,
) -> Option<LocalManifold> {
    let (d1, d2) = (q1 - p1, q2 - p2);
    let (length1, length2) = (d1.norm(), d2.norm());
    let (u1, u2) = (d1 / length1, d2 / length2);
    // Where each segment's ends lie along the other's direction.
    let (fp2, fq2) = (u1.dot(&(p2 - p1)), u1.dot(&(q2 - p1)));
    let (fp1, fq1) = (u2.dot(&(p1 - p2)), u2.dot(&(q1 - p2)));
    let outside =
        |f: f64, g: f64, length: f64| (f <= 0.0 && g <= 0.0) || (f >= length && g >= length);
    if outside(fp2, fq2, length1) || outside(fp1, fq1, length2) {
        return None;
    }
    // The side normal of a segment facing the other, and the other's
    // least separation along it.
    let side = |u: Vector2<f64>, from: Vector2<f64>, (p, q): (Vector2<f64>, Vector2<f64>)| {
        let n = Vector2::new(-u.y, u.x);
        let (sp, sq) = (n.dot(&(p - from)), n.dot(&(q - from)));
        let (up, down) = (sp.min(sq), (-sp).min(-sq));
        if up > down { (n, up) } else { (-n, down) }
    };
    let (normal_a, separation_a) = side(u1, p1, (p2, q2));
    let (normal_b, separation_b) = side(u2, p2, (p1, q1));
    // The incident segment (p, q) clipped to the reference one, whose ends
    // lie at 0 and `length` along it, the incident ends at `fp`, `fq`.
    let clip = |(p, q): (Vector2<f64>, Vector2<f64>), (fp, fq): (f64, f64), length: f64| {
        let (mut cp, mut cq) = (p, q);
        if fp < 0.0 && fq > 0.0 {
            cp = p + (-fp / (fq - fp)) * (q - p);
        } else if fq < 0.0 && fp > 0.0 {
            cq = q + (-fq / (fp - fq)) * (p - q);
        }
        if fp > length && fq < length {
            cp = p + ((fp - length) / (fp - fq)) * (q - p);
        } else if fq > length && fp < length {
            cq = q + ((fq - length) / (fq - fp)) * (p - q);
        }
        (cp, cq)
    };
    let radius = ra + rb;
    let (normal, points) = if separation_a >= separation_b {
        let (cp, cq) = clip((p2, q2), (fp2, fq2), length1);
        let (sp, sq) = (normal_a.dot(&(cp - p1)), normal_a.dot(&(cq - p1)));
        if sp > distance + LINEAR_SLOP && sq > distance + LINEAR_SLOP {
            return None;
        }
        // Each incident point moved from B's core to midway between A's
        // surface (ra out of A's core) and B's (rb in from the point).
        let at = |c: Vector2<f64>, s: f64, end: usize| LocalPoint {
            point: c + 0.5 * (ra - rb - s) * normal_a,
            separation: s - radius,
            id: FeatureId::pair(Feature::Edge(0), Feature::Clip(end)),
        };
        (normal_a, [at(cp, sp, 0), at(cq, sq, 1)])
    } else {
        let (cp, cq) = clip((p1, q1), (fp1, fq1), length2);
        let (sp, sq) = (normal_b.dot(&(cp - p2)), normal_b.dot(&(cq - p2)));
        if sp > distance + LINEAR_SLOP && sq > distance + LINEAR_SLOP {
            return None;
        }
        let at = |c: Vector2<f64>, s: f64, end: usize| LocalPoint {
            point: c + 0.5 * (rb - ra - s) * normal_b,
            separation: s - radius,
            id: FeatureId::pair(Feature::Clip(end), Feature::Edge(0)),
        };
        (-normal_b, [at(cp, sp, 0), at(cq, sq, 1)])
    };
    let mut manifold = LocalManifold {
        normal,
        ..LocalManifold::default()
    };
    for p in points {
        if p.separation <= speculative {
            manifold.points[manifold.count] = p;
            manifold.count += 1;
        }
    }
    (manifold.count > 0).then_some(manifold)
}

/// A segment or capsule (A) against a circle of `radius` (m) centred at
/// `center` (A's frame): one point between the point of A's segment
/// nearest the centre and the centre, [`FeatureId::ONE_POINT`] (as the
/// circle pairs).
fn capsule_circle(
    p: &Polygon,
    radius: f64,
    center: Vector2<f64>,
    speculative: f64,
) -> LocalManifold {
    let (a, b) = (p.vertices[0], p.vertices[1]);
    let d = b - a;
    let t = ((center - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
    let nearest = a + t * d;
    let offset = center - nearest;
    let distance = offset.norm();
    let separation = distance - p.radius - radius;
    if separation > speculative {
        return LocalManifold::default();
    }
    let normal = if distance > 0.0 {
        offset / distance
    } else {
        // The centre on the core: A's side normal.
        p.normals[0]
    };
    LocalManifold {
        normal,
        count: 1,
        points: [
            LocalPoint {
                point: 0.5 * ((nearest + p.radius * normal) + (center - radius * normal)),
                separation,
                id: FeatureId::ONE_POINT,
            },
            LocalPoint::default(),
        ],
    }
}

/// The soft step's manifold of clipped points: all of them, with the
/// feature id of each.
#[inline]
fn local_manifold(clipped: Clipped) -> LocalManifold {
    let point = |k: usize| {
        let p = clipped.points[k];
        LocalPoint {
            point: p.point,
            separation: p.separation,
            id: p.id,
        }
    };
    LocalManifold {
        normal: clipped.normal,
        count: clipped.count,
        points: [point(0), point(1)],
    }
}

/// The polygons are apart: clip the edges, unless two vertices are
/// substantially closer than the clipped points, then one vertex–vertex
/// point (the distance between the cores, less the radii, along the line
/// between the vertices).
fn apart(placed: &Placed, speculative: f64) -> LocalManifold {
    let faces = placed.faces();
    let (av, bv) = (placed.a_vertices, placed.b_vertices);
    let (i11, i12) = (faces.edge_a, (faces.edge_a + 1) % av.len());
    let (i21, i22) = (faces.edge_b, (faces.edge_b + 1) % bv.len());
    let radius = placed.radius_a + placed.radius_b;
    let closest = segment_distance(av[i11], av[i12], bv[i21], bv[i22]);
    let distance = closest.distance_squared.sqrt();
    if distance - radius > speculative {
        return LocalManifold::default();
    }
    let manifold = local_manifold(placed.clip(faces));
    let min_separation = manifold.points[..manifold.count]
        .iter()
        .map(|p| p.separation)
        .fold(f64::INFINITY, f64::min);
    if distance - radius + 0.1 * LINEAR_SLOP < min_separation && distance > 0.0 {
        let ends = |f: f64| {
            if f == 0.0 {
                Some(0)
            } else if f == 1.0 {
                Some(1)
            } else {
                None
            }
        };
        if let (Some(ea), Some(eb)) = (ends(closest.fraction_a), ends(closest.fraction_b)) {
            let (ia, ib) = ([i11, i12][ea], [i21, i22][eb]);
            let normal = (bv[ib] - av[ia]) / distance;
            // Midway between the surfaces: ½(ra − rb) along the normal from
            // the vertices' midpoint (+0 for sharp polygons, which keeps
            // their bits).
            let offset = 0.5 * (placed.radius_a - placed.radius_b);
            return LocalManifold {
                normal,
                count: 1,
                points: [
                    LocalPoint {
                        point: 0.5 * (av[ia] + bv[ib]) + offset * normal,
                        separation: distance - radius,
                        // The clipped point's id: the same vertices.
                        id: FeatureId::pair(Feature::Vertex(ia), Feature::Vertex(ib)),
                    },
                    LocalPoint::default(),
                ],
            };
        }
    }
    manifold
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::{self, test_rng::Rng};
    use crate::shape::{Circle, ConvexPolygon, Shape};

    fn solver(shape: &Shape) -> SolverShape {
        SolverShape::new(shape)
    }

    fn unit_box() -> Shape {
        Shape::rectangle(1.0, 1.0).unwrap()
    }

    #[test]
    fn box_resting_on_a_box_gives_two_points_with_the_sink_as_separation() {
        // B 1 m above A's centre minus a 0.01 m overlap.
        let xf = Isometry2::new(Vector2::new(0.2, 0.99), 0.0);
        let m = collide(
            &solver(&unit_box()),
            &solver(&unit_box()),
            &xf,
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 2);
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        for p in &m.points {
            assert!((p.separation + 0.01).abs() < 1e-15, "{p:?}");
            // Midway between B's bottom (0.49) and A's top (0.5).
            assert!((p.point.y - 0.495).abs() < 1e-15);
        }
        let xs = [m.points[0].point.x, m.points[1].point.x];
        assert!((xs[0].min(xs[1]) + 0.3).abs() < 1e-15 && (xs[0].max(xs[1]) - 0.5).abs() < 1e-15);
        assert_ne!(m.points[0].id, m.points[1].id);
    }

    #[test]
    fn feature_ids_persist_under_a_small_motion() {
        let (a, b) = (solver(&unit_box()), solver(&unit_box()));
        let mut scratch = Scratch::default();
        let m1 = collide(
            &a,
            &b,
            &Isometry2::new(Vector2::new(0.1, 0.995), 0.0),
            0.02,
            &mut scratch,
        );
        let m2 = collide(
            &a,
            &b,
            &Isometry2::new(Vector2::new(0.11, 0.993), 0.01),
            0.02,
            &mut scratch,
        );
        let ids1: Vec<FeatureId> = m1.points[..m1.count].iter().map(|p| p.id).collect();
        let ids2: Vec<FeatureId> = m2.points[..m2.count].iter().map(|p| p.id).collect();
        assert_eq!(ids1, ids2);
    }

    #[test]
    fn beyond_the_speculative_distance_there_is_no_manifold() {
        let (a, b) = (solver(&unit_box()), solver(&unit_box()));
        let mut scratch = Scratch::default();
        let near = collide(
            &a,
            &b,
            &Isometry2::new(Vector2::new(0.0, 1.015), 0.0),
            0.02,
            &mut scratch,
        );
        assert_eq!(near.count, 2);
        assert!((near.points[0].separation - 0.015).abs() < 1e-14);
        let far = collide(
            &a,
            &b,
            &Isometry2::new(Vector2::new(0.0, 1.03), 0.0),
            0.02,
            &mut scratch,
        );
        assert_eq!(far.count, 0);
        let circle = solver(&Shape::Circle(Circle::new(0.5).unwrap()));
        let cc = collide(
            &circle,
            &circle,
            &Isometry2::new(Vector2::new(0.6, 0.8), 0.0),
            0.02,
            &mut scratch,
        );
        assert_eq!(cc.count, 1);
        assert!(cc.points[0].separation.abs() < 1e-15);
        assert!((cc.normal - Vector2::new(0.6, 0.8)).norm() < 1e-15);
    }

    #[test]
    fn corner_to_corner_gives_one_vertex_point() {
        // B's lower-left corner 0.01 m diagonally from A's upper-right one.
        let d = 0.01 / 2f64.sqrt();
        let xf = Isometry2::new(Vector2::new(1.0 + d, 1.0 + d), 0.0);
        let m = collide(
            &solver(&unit_box()),
            &solver(&unit_box()),
            &xf,
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 1);
        assert!((m.points[0].separation - 0.01).abs() < 1e-12);
        assert!((m.normal - Vector2::new(1.0, 1.0).normalize()).norm() < 1e-9);
    }

    #[test]
    fn deepest_point_and_normal_agree_with_the_exact_narrow_phase() {
        // The exact model's SAT (validated against parry2d by the harness) is
        // the oracle: same normal and same deepest overlap, to round-off.
        let mut rng = Rng::new(7);
        let mut scratch = Scratch::default();
        let mut compared = 0;
        for _ in 0..2000 {
            let random_polygon = |rng: &mut Rng| {
                let n = rng.int(3, 9);
                let pts: Vec<Vector2<f64>> = (0..n)
                    .map(|_| Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
                    .collect();
                ConvexPolygon::convex_hull(&pts).ok().map(Shape::Polygon)
            };
            let (Some(a), Some(b)) = (random_polygon(&mut rng), random_polygon(&mut rng)) else {
                continue;
            };
            let (a, b) = (a.centered(), b.centered());
            let pose_b = Isometry2::new(
                Vector2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)),
                rng.range(-3.0, 3.0),
            );
            let exact = collision::collide(&a, &Isometry2::identity(), &b, &pose_b, 0.0);
            let m = collide(&solver(&a), &solver(&b), &pose_b, 0.0, &mut scratch);
            let Some(exact) = exact else { continue };
            if exact.max_depth() < 1e-6 {
                continue; // grazing contacts may differ in the chosen feature
            }
            assert!(m.count > 0);
            assert!(
                (m.normal - exact.normal).norm() < 1e-9,
                "{} vs {}",
                m.normal,
                exact.normal
            );
            let deepest = m.points[..m.count]
                .iter()
                .map(|p| -p.separation)
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(
                (deepest - exact.max_depth()).abs() < 1e-9,
                "{deepest} vs {}",
                exact.max_depth()
            );
            compared += 1;
        }
        assert!(compared > 300, "only {compared} overlapping pairs");
    }

    fn capsule(length: f64, radius: f64) -> Shape {
        Shape::capsule(length, radius).unwrap()
    }

    /// The deepest separation of a manifold (m).
    fn deepest(m: &LocalManifold) -> f64 {
        m.points[..m.count]
            .iter()
            .map(|p| p.separation)
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn capsule_lying_on_a_box_gives_two_points_at_its_core_ends() {
        // Box top at y = 0.5; capsule (core ±0.5, r 0.25) 1 cm into it.
        let xf = Isometry2::new(Vector2::new(0.1, 0.74), 0.0);
        let m = collide(
            &solver(&unit_box()),
            &solver(&capsule(1.0, 0.25)),
            &xf,
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 2);
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        for p in &m.points {
            assert!((p.separation + 0.01).abs() < 1e-14, "{p:?}");
            // Midway between the box's top (0.5) and the capsule's bottom.
            assert!((p.point.y - 0.495).abs() < 1e-14, "{p:?}");
        }
        // Clipped to the box's top: x from −0.4 (the capsule's left core
        // end) to 0.5 (the box's corner).
        let xs = [m.points[0].point.x, m.points[1].point.x];
        assert!((xs[0].min(xs[1]) + 0.4).abs() < 1e-14, "{xs:?}");
        assert!((xs[0].max(xs[1]) - 0.5).abs() < 1e-14, "{xs:?}");
        // The same pair seen from the capsule: the same points and depths,
        // the normal reversed.
        let back = collide(
            &solver(&capsule(1.0, 0.25)),
            &solver(&unit_box()),
            &xf.inverse(),
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(back.count, 2);
        assert!((back.normal + Vector2::y()).norm() < 1e-14);
        assert!((deepest(&back) + 0.01).abs() < 1e-14);
    }

    #[test]
    fn capsule_feature_ids_persist_under_a_small_motion() {
        let pairs = [
            (solver(&unit_box()), solver(&capsule(1.0, 0.25))),
            (solver(&capsule(2.0, 0.1)), solver(&capsule(1.0, 0.25))),
        ];
        for (a, b) in &pairs {
            let mut scratch = Scratch::default();
            let y = match a {
                SolverShape::Polygon(p) if p.is_segment() => 0.345,
                _ => 0.745,
            };
            let m1 = collide(
                a,
                b,
                &Isometry2::new(Vector2::new(0.1, y), 0.0),
                0.02,
                &mut scratch,
            );
            let m2 = collide(
                a,
                b,
                &Isometry2::new(Vector2::new(0.11, y - 0.002), 0.005),
                0.02,
                &mut scratch,
            );
            assert_eq!(m1.count, 2);
            let ids1: Vec<FeatureId> = m1.points[..m1.count].iter().map(|p| p.id).collect();
            let ids2: Vec<FeatureId> = m2.points[..m2.count].iter().map(|p| p.id).collect();
            assert_eq!(ids1, ids2);
            assert_ne!(ids1[0], ids1[1]);
        }
    }

    #[test]
    fn capsules_end_to_end_on_one_line_meet_at_their_caps() {
        // Cores ±0.5 and radius 0.25 each: B's left cap 1 cm beyond A's
        // right cap along x. Their separating axes are only ±y; the
        // closest points part them.
        let xf = Isometry2::new(Vector2::new(1.51, 0.0), 0.0);
        let m = collide(
            &solver(&capsule(1.0, 0.25)),
            &solver(&capsule(1.0, 0.25)),
            &xf,
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 1);
        assert!((m.normal - Vector2::x()).norm() < 1e-15);
        assert!((m.points[0].separation - 0.01).abs() < 1e-14);
        assert!((m.points[0].point - Vector2::new(0.755, 0.0)).norm() < 1e-14);
        // Crossed at right angles, B's lower cap 1 cm into A: B's core
        // (±0.5 along its y) ends 0.49 above A's axis; one point.
        let crossed = Isometry2::new(Vector2::new(0.0, 0.99), std::f64::consts::FRAC_PI_2);
        let m = collide(
            &solver(&capsule(1.0, 0.25)),
            &solver(&capsule(1.0, 0.25)),
            &crossed,
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 1);
        assert!((m.normal - Vector2::y()).norm() < 1e-14);
        assert!((m.points[0].separation + 0.01).abs() < 1e-14);
    }

    #[test]
    fn a_circle_on_a_capsules_axis_meets_its_cap() {
        // A circle of radius 0.5 centred on the capsule's axis, 1 cm
        // beyond its right cap (at 0.5 + 0.25 + 0.01 + 0.5).
        let circle = solver(&Shape::circle(0.5).unwrap());
        let m = collide(
            &solver(&capsule(1.0, 0.25)),
            &circle,
            &Isometry2::new(Vector2::new(1.26, 0.0), 0.0),
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 1);
        assert!((m.normal - Vector2::x()).norm() < 1e-15);
        assert!((m.points[0].separation - 0.01).abs() < 1e-14);
        // A rounded box's corner: the circle's centre along the diagonal.
        let rounded = solver(&Shape::rounded_box(1.0, 1.0, 0.1).unwrap());
        let d = (0.1 + 0.5 + 0.01) / 2f64.sqrt();
        let m = collide(
            &rounded,
            &circle,
            &Isometry2::new(Vector2::new(0.5 + d, 0.5 + d), 0.0),
            0.02,
            &mut Scratch::default(),
        );
        assert_eq!(m.count, 1);
        assert!((m.points[0].separation - 0.01).abs() < 1e-14);
        // Midway between the rounded corner and the circle.
        let mid = Vector2::repeat(0.5) + (0.1 + 0.005) / 2f64.sqrt() * Vector2::repeat(1.0);
        assert!(
            (m.points[0].point - mid).norm() < 1e-14,
            "{:?}",
            m.points[0]
        );
    }

    #[test]
    fn rounded_pairs_agree_with_the_exact_signed_distance_where_the_cores_overlap_or_touch_faces() {
        // The exact signed distance of rounded shapes (the pair table's,
        // `collision::proximity`, checked against parry2d by the harness's
        // `shape_parry`) is the oracle: where the
        // shapes overlap, the manifold's normal and deepest point are
        // exact to round-off when the cores overlap (the separating axes
        // are then exact); apart, the manifold never reports a separation
        // below the true one by more than round-off.
        let mut rng = Rng::new(19);
        let mut scratch = Scratch::default();
        let mut compared = 0;
        for _ in 0..3000 {
            let random_shape = |rng: &mut Rng| -> Option<Shape> {
                let r = rng.range(0.02, 0.3);
                match rng.int(0, 4) {
                    0 => Some(capsule(rng.range(0.2, 1.5), r)),
                    1 => Some(Shape::circle(rng.range(0.1, 0.6)).unwrap()),
                    k => {
                        let n = rng.int(3, 7);
                        let pts: Vec<Vector2<f64>> = (0..n)
                            .map(|_| Vector2::new(rng.range(-0.7, 0.7), rng.range(-0.7, 0.7)))
                            .collect();
                        let p = ConvexPolygon::convex_hull(&pts).ok()?;
                        Some(if k == 2 {
                            Shape::Polygon(p).centered()
                        } else {
                            Shape::Rounded(crate::shape::RoundedConvex::rounded_polygon(p, r).ok()?)
                                .centered()
                        })
                    }
                }
            };
            let (Some(a), Some(b)) = (random_shape(&mut rng), random_shape(&mut rng)) else {
                continue;
            };
            let (mut a, mut b) = (a, b);
            if !matches!(a, Shape::Rounded(_)) && !matches!(b, Shape::Rounded(_)) {
                continue; // the sharp pairs have their own test above
            }
            let mut pose_b = Isometry2::new(
                Vector2::new(rng.range(-1.8, 1.8), rng.range(-1.8, 1.8)),
                rng.range(-3.0, 3.0),
            );
            // Circles go second (the contact set's order).
            if matches!(a, Shape::Circle(_)) {
                (a, b) = (b, a);
                pose_b = pose_b.inverse();
            }
            let exact = collision::proximity(&a, &Isometry2::identity(), &b, &pose_b);
            let m = collide(&solver(&a), &solver(&b), &pose_b, 0.02, &mut scratch);
            if exact.distance > 0.02 {
                continue;
            }
            let radii = |s: &Shape| match s {
                Shape::Rounded(r) => r.radius(),
                Shape::Circle(c) => c.radius,
                _ => 0.0,
            };
            let core_depth = -exact.distance - radii(&a) - radii(&b);
            if m.count > 0 {
                assert!(
                    deepest(&m) >= exact.distance - 1e-9,
                    "{} below the exact {}",
                    deepest(&m),
                    exact.distance
                );
            }
            // Two crossing capsule cores are deep only along directions
            // their closest points cannot tell (as Box2D's
            // `b2CollideCapsules`): their depth is not compared.
            let capsules = matches!((&a, &b), (Shape::Rounded(x), Shape::Rounded(y))
                if x.core().len() == 2 && y.core().len() == 2);
            if core_depth < 1e-6 || capsules {
                continue;
            }
            assert!(m.count > 0);
            assert!(
                (m.normal - exact.normal).norm() < 1e-9,
                "{} vs {}",
                m.normal,
                exact.normal
            );
            assert!(
                (deepest(&m) - exact.distance).abs() < 1e-9,
                "{} vs {}",
                deepest(&m),
                exact.distance
            );
            compared += 1;
        }
        assert!(compared > 200, "only {compared} overlapping pairs");
    }
}
