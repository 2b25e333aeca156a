//! Narrow phase: the exact test of a candidate pair, dispatched on the pair
//! of shapes (seed §7.2: once the broad phase has named the candidates, "the
//! second phase decides whether each pair interpenetrates").
//!
//! A compound is split into its parts here; every pair of single shapes is
//! answered by its cell of the one pair table (`pair_table.rs`): the exact
//! manifold ([`collide`]) and the manifold with the features the exact
//! model's persistent contacts follow. The signed distance ([`proximity`])
//! is written once for every pair, on the shapes' convex proxies
//! (`convex.rs`, `minkowski.rs`).

use super::convex::ConvexProxy;
use super::features::ContactFeatures;
use super::manifold::{Manifold, Proximity};
use super::minkowski::separation;
use super::pair_table::pair;
use super::polygon_polygon::{Face, equally_deep_faces};
use crate::shape::Shape;
use nalgebra::{Isometry2, Vector2};

/// The contact manifold of shapes `a` at `pose_a` and `b` at `pose_b` when
/// they touch, overlap, or are closer than `margin` (m; 0 for touching
/// only, > 0 for speculative contacts whose depth is then negative).
/// The normal points from A to B. A compound's deepest part speaks for
/// it; a chain (one-sided, the soft step's) reports none.
pub fn collide(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<Manifold> {
    if let Shape::Compound(c) = a {
        // The part with the deepest contact speaks for the compound.
        return c
            .parts()
            .iter()
            .filter_map(|p| collide(&p.shape, &part_pose(pose_a, p), b, pose_b, margin))
            .max_by(|x, y| x.max_depth().total_cmp(&y.max_depth()));
    }
    if let Shape::Compound(_) = b {
        return collide(b, pose_b, a, pose_a, margin).map(|m| m.flipped());
    }
    let cell = pair(a, b).expect("compounds are split above");
    (cell.manifold)(a, pose_a, b, pose_b, margin)
}

/// The manifold of shapes `a` at `pose_a` and `b` at `pose_b` within
/// `margin` (m), as [`collide`] gives it, with its features. `None` when
/// they are apart, or for a compound shape (the exact model, the only
/// user, refuses compounds).
pub(crate) fn collide_with_features(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    collide_on_face(a, pose_a, b, pose_b, margin, None)
}

/// [`collide_with_features`] clipped on the reference face `face` instead
/// of the best one (faces of polygons and rounded cores; ignored for a
/// circle's pairs).
pub(crate) fn collide_on_face(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
    margin: f64,
    face: Option<Face>,
) -> Option<(Manifold, ContactFeatures)> {
    let cell = pair(a, b)?;
    (cell.features)(a, pose_a, b, pose_b, margin, face)
}

/// The faces along which two polygons are equally deep, to `tolerance` (m),
/// best first, each with its normal from A to B ([`equally_deep_faces`]);
/// empty unless both shapes are polygons.
pub(crate) fn equally_deep(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
    tolerance: f64,
) -> Vec<(Face, Vector2<f64>)> {
    match (a, b) {
        (Shape::Polygon(pa), Shape::Polygon(pb)) => {
            equally_deep_faces(pa, pose_a, pb, pose_b, tolerance)
        }
        _ => Vec::new(),
    }
}

/// The pose of a compound's part, given the compound's.
fn part_pose(pose: &Isometry2<f64>, part: &crate::shape::CompoundPart) -> Isometry2<f64> {
    pose * Isometry2::new(part.offset, part.angle)
}

/// The exact signed distance of two shapes (m): the gap when apart, 0 when
/// touching, −(penetration depth) when overlapping, with its normal from A
/// to B and witness points. Every pair of convex shapes is one question
/// about their convex proxies (core and radius), answered through their
/// Minkowski difference (`minkowski::separation`, exact up to rounding); a
/// compound's nearest (or deepest) part speaks for it; a chain (one-sided,
/// bounding no region, refused by the exact model) is infinitely far, with
/// a placeholder normal (+x) and the poses' origins as witnesses; a
/// non-finite pose gives a NaN distance.
pub fn proximity(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
) -> Proximity {
    if let Shape::Compound(c) = a {
        // The nearest (or deepest) part.
        return c
            .parts()
            .iter()
            .map(|p| proximity(&p.shape, &part_pose(pose_a, p), b, pose_b))
            .min_by(|x, y| x.distance.total_cmp(&y.distance))
            .expect("a compound has at least one part");
    }
    if let Shape::Compound(_) = b {
        return proximity(b, pose_b, a, pose_a).flipped();
    }
    // Compounds are split above, so a shape without a proxy is a chain.
    let (Some(pa), Some(pb)) = (
        ConvexProxy::convex(a, pose_a),
        ConvexProxy::convex(b, pose_b),
    ) else {
        return Proximity {
            distance: f64::INFINITY,
            normal: Vector2::x(),
            point_a: pose_a.translation.vector,
            point_b: pose_b.translation.vector,
        };
    };
    if !(pa.is_finite() && pb.is_finite()) {
        let nan = Vector2::repeat(f64::NAN);
        return Proximity {
            distance: f64::NAN,
            normal: nan,
            point_a: nan,
            point_b: nan,
        };
    }
    separation(&pa, &pb).into()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Circle;
    use nalgebra::Vector2;

    #[test]
    fn circle_against_polygon_is_the_flipped_polygon_against_circle() {
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        let ball = Shape::Circle(Circle::new(0.5).unwrap());
        let (pb, pc) = (
            Isometry2::new(Vector2::zeros(), 0.3),
            Isometry2::translation(0.9, 0.2),
        );
        let pc_m = collide(&square, &pb, &ball, &pc, 0.0).unwrap();
        let cp_m = collide(&ball, &pc, &square, &pb, 0.0).unwrap();
        assert_eq!(cp_m.normal, -pc_m.normal);
        assert_eq!(cp_m.points(), pc_m.points());
        let d1 = proximity(&square, &pb, &ball, &pc);
        let d2 = proximity(&ball, &pc, &square, &pb);
        assert_eq!(d1.distance, d2.distance);
        assert_eq!(d1.point_a, d2.point_b);
    }

    /// The one signed distance against closed forms, for every kind of
    /// answer: circles apart, overlapping and concentric, boxes at known
    /// gaps and depths (face and corner), a box and a circle at a corner, a
    /// compound's nearest part, a chain, a non-finite pose. The shapes sit
    /// within 5 m of the origin, and each closed form is a few operations
    /// on them: a few ulps of 5 m, below 1e-14 m (and 1e-15 on a unit
    /// normal).
    #[test]
    fn the_one_distance_meets_closed_forms() {
        let close = |p: &Proximity, distance: f64, normal: Vector2<f64>| {
            assert!((p.distance - distance).abs() < 1e-14, "{p:?}");
            assert!((p.normal - normal).norm() < 1e-15, "{p:?}");
            assert!(
                (p.point_b - p.point_a - p.distance * p.normal).norm() < 1e-14,
                "{p:?}"
            );
        };
        let at = |x: f64, y: f64, angle: f64| Isometry2::new(Vector2::new(x, y), angle);
        let circle = |r: f64| Shape::circle(r).unwrap();
        // Circles: centres 5 m apart along (3, 4)/5, radii 2 and 4: depth
        // 1; A's surface point (1, 1) + 2 n, B's (4, 5) − 4 n.
        let p = proximity(
            &circle(2.0),
            &at(1.0, 1.0, 0.7),
            &circle(4.0),
            &at(4.0, 5.0, 0.1),
        );
        close(&p, -1.0, Vector2::new(0.6, 0.8));
        assert!((p.point_a - Vector2::new(2.2, 2.6)).norm() < 1e-14, "{p:?}");
        assert!((p.point_b - Vector2::new(1.6, 1.8)).norm() < 1e-14, "{p:?}");
        let p = proximity(
            &circle(1.0),
            &at(0.0, 0.0, 0.0),
            &circle(0.5),
            &at(0.0, 2.0, 0.0),
        );
        close(&p, 0.5, Vector2::y());
        // Concentric: pushed along +y, as the contact manifolds push them.
        let p = proximity(
            &circle(1.0),
            &at(1.0, 1.0, 0.0),
            &circle(1.0),
            &at(1.0, 1.0, 0.0),
        );
        assert_eq!((p.distance, p.normal), (-2.0, Vector2::y()));
        // Unit boxes: B 0.25 m to the right of A's right face, 0.3 up; sunk
        // 0.1 into it; corner to corner at (1.5, 1.5): 0.5 √2.
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        let origin = at(0.0, 0.0, 0.0);
        close(
            &proximity(&square, &origin, &square, &at(1.25, 0.3, 0.0)),
            0.25,
            Vector2::x(),
        );
        close(
            &proximity(&square, &origin, &square, &at(0.9, 0.2, 0.0)),
            -0.1,
            Vector2::x(),
        );
        let diagonal = Vector2::new(1.0, 1.0) / 2f64.sqrt();
        let p = proximity(&square, &origin, &square, &at(1.5, 1.5, 0.0));
        close(&p, 0.5 * 2f64.sqrt(), diagonal);
        assert!((p.point_a - Vector2::new(0.5, 0.5)).norm() < 1e-15, "{p:?}");
        // The same boxes turned by 90° and moved: the same answers, turned.
        let turn = at(2.0, -1.0, std::f64::consts::FRAC_PI_2);
        let p = proximity(&square, &turn, &square, &(turn * at(1.25, 0.3, 0.0)));
        close(&p, 0.25, Vector2::y());
        // A circle of radius 0.25 beyond a box's corner: √2 − 0.25, and the
        // same seen from the circle.
        let p = proximity(&square, &origin, &circle(0.25), &at(1.5, 1.5, 0.0));
        close(&p, 2f64.sqrt() - 0.25, diagonal);
        let q = proximity(&circle(0.25), &at(1.5, 1.5, 0.0), &square, &origin);
        close(&q, 2f64.sqrt() - 0.25, -diagonal);
        // A compound of unit boxes at x = ±2 and a ball of radius 0.5 at
        // x = 0.25: the right part is nearer, 0.75 m, normal −x.
        let part =
            |x: f64| crate::shape::CompoundPart::new(Vector2::new(x, 0.0), 0.0, square.clone());
        let pair =
            Shape::Compound(crate::shape::Compound::new(vec![part(-2.0), part(2.0)]).unwrap());
        close(
            &proximity(&pair, &origin, &circle(0.5), &at(0.25, 0.0, 0.0)),
            0.75,
            -Vector2::x(),
        );
        close(
            &proximity(&circle(0.5), &at(0.25, 0.0, 0.0), &pair, &origin),
            0.75,
            Vector2::x(),
        );
        // A chain is infinitely far; a non-finite pose gives NaN.
        let points = [-1.5, -0.5, 0.5, 1.5]
            .map(|x| Vector2::new(x, 0.0))
            .to_vec();
        let chain = Shape::chain(points, false).unwrap();
        assert_eq!(
            proximity(&square, &origin, &chain, &origin).distance,
            f64::INFINITY
        );
        assert_eq!(
            proximity(&chain, &origin, &square, &origin).distance,
            f64::INFINITY
        );
        let nowhere = at(f64::NAN, 0.0, 0.0);
        assert!(
            proximity(&square, &origin, &circle(1.0), &nowhere)
                .distance
                .is_nan()
        );
    }

    #[test]
    fn rotation_radius_of_a_unit_box_is_its_half_diagonal() {
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        assert!((square.rotation_radius() - 0.5f64.hypot(0.5)).abs() < 1e-16);
        assert_eq!(
            Shape::Circle(Circle::new(2.0).unwrap()).rotation_radius(),
            0.0
        );
    }
}
