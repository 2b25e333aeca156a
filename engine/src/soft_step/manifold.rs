//! The soft step's narrow phase: the contact manifold of two shapes in the
//! frame of the first, each point carrying a **feature id** that names the
//! pair of features (a reference edge and an incident vertex) that made it,
//! so the next step's point from the same features inherits its impulses
//! (warm starting).
//!
//! Two polygons go through the geometry both models share
//! (`collision/polygon_polygon_local.rs`: separating axes, reference and
//! incident edges, the clipped points midway between the surfaces with
//! their separations), and this file applies the soft step's policy, Box2D
//! v3's (`b2CollidePolygons`): beyond the speculative distance there is no
//! manifold; when the polygons are apart (separation over a tenth of the
//! linear slop) and two vertices are substantially closer than the clipped
//! points, a single vertex–vertex point along the line between them.
//!
//! A polygon against a circle takes the edge of least penetration, or the
//! nearest vertex when the centre lies beyond it; two circles meet along
//! the line of centres. Both are written once for both contact models in
//! `collision/` (`polygon_circle_local`, `circle_circle_local`); this file
//! makes their speculative one-point manifolds.
//!
//! Every point is at the middle of the overlap, so it is the same whichever
//! shape is called A; the normal points from A to B; lengths are in m.

use super::geometry::{Polygon, SolverShape};
use crate::collision::chain_segment::{
    SegmentManifold, chain_segment_circle_local, chain_segment_polygon_local,
};
use crate::collision::circle_circle::circle_circle_local;
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
    /// Feature id: `(feature of A) << 16 | (feature of B)`.
    pub id: u32,
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

fn feature_id(a: usize, b: usize) -> u32 {
    ((a as u32) << 16) | b as u32
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
            collide_polygons(pa, pb, xf, speculative, scratch)
        }
        (SolverShape::Polygon(p), SolverShape::Circle { radius }) => {
            let normal_of = |i: usize| p.normals[i];
            let center = xf.translation.vector;
            polygon_circle_local(&p.vertices, normal_of, *radius, center, speculative)
                .map_or_else(LocalManifold::default, |(contact, _)| one_point(contact))
        }
        (SolverShape::Circle { radius: ra }, SolverShape::Circle { radius: rb }) => {
            circle_circle_local(*ra, *rb, xf.translation.vector, speculative)
                .map_or_else(LocalManifold::default, one_point)
        }
        (SolverShape::Circle { .. }, SolverShape::Polygon(_)) => {
            unreachable!("pairs are ordered polygon first")
        }
        (SolverShape::ChainSegment(s), SolverShape::Polygon(p)) => from_segment_manifold(
            chain_segment_polygon_local(s, &p.vertices, &p.normals, xf, speculative),
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
/// midway between the surfaces, feature id 0 (one point, nothing to tell
/// apart, as Box2D's circle manifolds).
fn one_point(contact: LocalProximity) -> LocalManifold {
    LocalManifold {
        normal: contact.normal,
        count: 1,
        points: [
            LocalPoint {
                point: 0.5 * (contact.point_a + contact.point_b),
                separation: contact.distance,
                id: 0,
            },
            LocalPoint::default(),
        ],
    }
}

/// Two polygons (radius 0: the soft step has no rounded shapes yet; a
/// rounded one passes its radius to the shared geometry).
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
        radius: 0.0,
    };
    let b = RoundPolygon {
        vertices: &pb.vertices,
        normals: &pb.normals,
        radius: 0.0,
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

/// The soft step's manifold of clipped points: all of them, with the
/// feature id of each.
#[inline]
fn local_manifold(clipped: Clipped) -> LocalManifold {
    let point = |k: usize| {
        let p = clipped.points[k];
        LocalPoint {
            point: p.point,
            separation: p.separation,
            id: feature_id(p.vertex_a, p.vertex_b),
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
                        id: feature_id(ia, ib),
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
        let ids1: Vec<u32> = m1.points[..m1.count].iter().map(|p| p.id).collect();
        let ids2: Vec<u32> = m2.points[..m2.count].iter().map(|p| p.id).collect();
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
}
