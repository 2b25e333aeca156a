//! Narrow phase: the exact test of a candidate pair, dispatched on the pair
//! of shapes (seed §7.2: once the broad phase has named the candidates, "the
//! second phase decides whether each pair interpenetrates").
//!
//! A compound is split into its parts here; every pair of single shapes is
//! answered by its cell of the one pair table (`pair_table.rs`): the exact
//! manifold ([`collide`]), the manifold with the features the exact model's
//! persistent contacts follow, and the signed distance ([`proximity`]).

use super::features::ContactFeatures;
use super::manifold::{Manifold, Proximity};
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
/// to B and witness points. Exact for every pair of convex shapes
/// (segments, capsules and rounded polygons through their cores, less
/// their radii); a compound's nearest (or deepest) part speaks for it; a
/// chain (one-sided, bounding no region) is infinitely far.
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
    let cell = pair(a, b).expect("compounds are split above");
    (cell.proximity)(a, pose_a, b, pose_b)
}

/// The radius (m) of the largest circle about the body origin (the centre
/// of mass) inside the shape ([`Shape::inner_radius`]): half the thinnest
/// the shape can be across its centre.
pub fn inner_radius(shape: &Shape) -> f64 {
    shape.inner_radius()
}

/// The largest distance (m) from the body origin (the centre of rotation)
/// to a point of the shape whose position changes when the body turns
/// ([`Shape::rotation_radius`]). Bounds the speed of a boundary point:
/// `|ω| · rotation_radius`.
pub fn rotation_radius(shape: &Shape) -> f64 {
    shape.rotation_radius()
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

    #[test]
    fn rotation_radius_of_a_unit_box_is_its_half_diagonal() {
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        assert!((rotation_radius(&square) - 0.5f64.hypot(0.5)).abs() < 1e-16);
        assert_eq!(
            rotation_radius(&Shape::Circle(Circle::new(2.0).unwrap())),
            0.0
        );
    }
}
