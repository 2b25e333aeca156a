//! The exact signed distance of two convex shapes seen as "core + radius"
//! ([`crate::shape::ConvexCore`]): what [`super::proximity`] answers for a
//! pair with a segment, capsule or rounded polygon, until the
//! radius-aware collision core replaces it.
//!
//! Brute force over the cores, O(n m), exact for convex cores of 1..N
//! vertices (a 2-vertex core is read as a closed polygon of two edges, its
//! two sides):
//!
//! - The cores are apart when an axis separates their projections: the
//!   outward edge normals of either core, and for a 1- or 2-vertex core
//!   (which has too few edges to enclose anything) also its direction and
//!   the axis between the two cores' first vertices. Apart, their distance
//!   is the least distance from a vertex of one core to an edge (or the
//!   lone vertex) of the other, whose witnesses give the normal; the
//!   shapes' signed distance is that less both radii (negative when the
//!   roundings overlap).
//! - Otherwise the cores overlap, and their penetration depth is the
//!   least overlap of their projections on the Minkowski difference's
//!   face normals, the outward edge normals of A and the reversed ones of
//!   B; the shapes' signed distance is minus that, less both radii.

use super::manifold::Proximity;
use crate::shape::ConvexCore;
use nalgebra::{Isometry2, Point2, Vector2};

/// The core's vertices placed at `pose` (m, world frame).
fn placed(core: &ConvexCore, pose: &Isometry2<f64>) -> Vec<Vector2<f64>> {
    core.vertices
        .iter()
        .map(|v| (pose * Point2::from(*v)).coords)
        .collect()
}

/// The outward unit normals of a core's edges (none for a single vertex;
/// both sides of a 2-vertex core).
fn edge_normals(v: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    let n = v.len();
    if n < 2 {
        return Vec::new();
    }
    (0..n)
        .filter_map(|i| {
            let e = v[(i + 1) % n] - v[i];
            let length = e.norm();
            (length > 0.0).then(|| Vector2::new(e.y, -e.x) / length)
        })
        .collect()
}

/// The least and greatest projection of `v` on `axis`.
fn extent(v: &[Vector2<f64>], axis: Vector2<f64>) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let x = p.dot(&axis);
            (lo.min(x), hi.max(x))
        })
}

/// The point of segment `a`–`b` nearest `p`.
fn nearest_on_segment(p: Vector2<f64>, a: Vector2<f64>, b: Vector2<f64>) -> Vector2<f64> {
    let e = b - a;
    let length2 = e.norm_squared();
    if length2 == 0.0 {
        return a;
    }
    a + ((p - a).dot(&e) / length2).clamp(0.0, 1.0) * e
}

/// The nearest points `(on a, on b)` of two cores that do not overlap.
fn nearest_points(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> (Vector2<f64>, Vector2<f64>) {
    let mut best = (f64::INFINITY, a[0], b[0]);
    let mut consider = |pa: Vector2<f64>, pb: Vector2<f64>| {
        let d = (pb - pa).norm_squared();
        if d < best.0 {
            best = (d, pa, pb);
        }
    };
    // Each vertex of one core against each edge (or the lone vertex) of
    // the other.
    for (from, to, flip) in [(a, b, false), (b, a, true)] {
        let m = to.len();
        for &p in from {
            for j in 0..m {
                let q = nearest_on_segment(p, to[j], to[(j + 1) % m]);
                if flip {
                    consider(q, p);
                } else {
                    consider(p, q);
                }
            }
        }
    }
    (best.1, best.2)
}

/// The exact signed distance of core `a` at `pose_a` and core `b` at
/// `pose_b`, with its normal from A to B and witness points on both
/// boundaries (`point_b − point_a = distance · normal`).
pub(crate) fn proximity_of_cores(
    a: &ConvexCore,
    pose_a: &Isometry2<f64>,
    b: &ConvexCore,
    pose_b: &Isometry2<f64>,
) -> Proximity {
    let (va, vb) = (placed(a, pose_a), placed(b, pose_b));
    let (normals_a, normals_b) = (edge_normals(&va), edge_normals(&vb));
    // Separating axes, for thin cores their directions and the axis
    // between them too.
    let mut axes: Vec<Vector2<f64>> = normals_a.iter().chain(&normals_b).copied().collect();
    for v in [&va, &vb] {
        if v.len() == 2 && v[1] != v[0] {
            axes.push((v[1] - v[0]).normalize());
        }
    }
    if (va.len() < 3 || vb.len() < 3) && vb[0] != va[0] {
        axes.push((vb[0] - va[0]).normalize());
    }
    let apart = axes.iter().any(|&n| {
        let ((lo_a, hi_a), (lo_b, hi_b)) = (extent(&va, n), extent(&vb, n));
        lo_b > hi_a || lo_a > hi_b
    });
    let (ra, rb) = (a.radius, b.radius);
    if apart {
        let (pa, pb) = nearest_points(&va, &vb);
        let gap = (pb - pa).norm();
        let normal = (pb - pa) / gap;
        let distance = gap - ra - rb;
        return Proximity {
            distance,
            normal,
            point_a: pa + ra * normal,
            point_b: pa + ra * normal + distance * normal,
        };
    }
    // Overlapping cores: the least overlap over the face normals of the
    // Minkowski difference (A's outward normals, B's reversed).
    let faces = normals_a
        .iter()
        .copied()
        .chain(normals_b.iter().map(|n| -n));
    let (overlap, normal) = faces
        .map(|n| (extent(&va, n).1 - extent(&vb, n).0, n))
        .min_by(|x, y| x.0.total_cmp(&y.0))
        // Two coincident points: no face, any direction.
        .unwrap_or((0.0, Vector2::y()));
    let distance = -overlap - ra - rb;
    let deepest_b = vb
        .iter()
        .copied()
        .min_by(|p, q| p.dot(&normal).total_cmp(&q.dot(&normal)))
        .expect("a core has at least one vertex");
    let point_b = deepest_b - rb * normal;
    Proximity {
        distance,
        normal,
        point_a: point_b - distance * normal,
        point_b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Shape;

    fn core(shape: &Shape) -> ConvexCore {
        shape.convex_core().unwrap()
    }

    fn at(x: f64, y: f64, angle: f64) -> Isometry2<f64> {
        Isometry2::new(Vector2::new(x, y), angle)
    }

    /// A capsule (L = 2, r = 0.25) lying 1 m above a segment ground:
    /// gap 1 − 0.25 = 0.75 m, normal straight up; pushed 0.1 m into it,
    /// −0.1 m. Exact geometry, a few ulps.
    #[test]
    fn a_capsule_over_a_segment() {
        let ground = Shape::segment(Vector2::new(-5.0, 0.0), Vector2::new(5.0, 0.0)).unwrap();
        let pill = Shape::capsule(2.0, 0.25).unwrap();
        let p = proximity_of_cores(
            &core(&ground),
            &at(0.0, 0.0, 0.0),
            &core(&pill),
            &at(1.0, 1.0, 0.0),
        );
        assert!((p.distance - 0.75).abs() < 1e-15, "{p:?}");
        assert!((p.normal - Vector2::y()).norm() < 1e-15, "{p:?}");
        let p = proximity_of_cores(
            &core(&ground),
            &at(0.0, 0.0, 0.0),
            &core(&pill),
            &at(1.0, 0.15, 0.0),
        );
        assert!((p.distance + 0.1).abs() < 1e-15, "{p:?}");
        // Standing upright across the ground line, its core crosses it:
        // overlapping cores, depth to the nearer end (0.6 below) plus r.
        let p = proximity_of_cores(
            &core(&ground),
            &at(0.0, 0.0, 0.0),
            &core(&pill),
            &at(0.0, 0.4, std::f64::consts::FRAC_PI_2),
        );
        assert!((p.distance + 0.6 + 0.25).abs() < 1e-12, "{p:?}");
        assert!((p.point_b - p.point_a - p.distance * p.normal).norm() < 1e-12);
    }

    /// Against the existing exact polygon–circle distance: a rounded box
    /// is a box grown by r, so near a face its distance to a circle is the
    /// box's less r; a capsule's end cap against a circle is two circles.
    #[test]
    fn agrees_with_the_sharp_shapes_less_the_radius() {
        let rounded = Shape::rounded_box(1.0, 0.5, 0.1).unwrap();
        let sharp = Shape::rectangle(1.0, 0.5).unwrap();
        let ball = Shape::circle(0.2).unwrap();
        for (x, y) in [(0.0, 1.0), (0.2, -0.7), (1.0, 0.1), (0.3, 0.2)] {
            let pose = at(x, y, 0.0);
            let p = proximity_of_cores(&core(&rounded), &at(0.0, 0.0, 0.3), &core(&ball), &pose);
            let q = super::super::proximity(&sharp, &at(0.0, 0.0, 0.3), &ball, &pose);
            // These centres all face an edge of the turned box (or lie
            // inside it), where rounding moves the surface by exactly r.
            assert!(
                (p.distance - (q.distance - 0.1)).abs() < 1e-12,
                "{x} {y}: {p:?} {q:?}"
            );
        }
        let pill = Shape::capsule(2.0, 0.25).unwrap();
        let p = proximity_of_cores(
            &core(&pill),
            &at(0.0, 0.0, 0.0),
            &core(&ball),
            &at(2.0, 0.5, 0.0),
        );
        let centres: f64 = (Vector2::new(2.0, 0.5) - Vector2::new(1.0, 0.0)).norm();
        assert!((p.distance - (centres - 0.45)).abs() < 1e-15, "{p:?}");
    }
}
