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
/// about their [`ConvexProxy`]s (core and radius), answered through their
/// Minkowski difference ([`separation`], exact up to rounding); a
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
    use crate::collision::test_rng::Rng;
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

    /// A random shape of kind `kind`: 0 a convex polygon (the hull of 3 to
    /// 8 points in a disc of radius 0.2–1.5 m), 1 a circle, 2 a segment, 3
    /// a capsule, 4 a rounded polygon.
    fn random_shape(rng: &mut Rng, kind: usize) -> Shape {
        let mut hull = || {
            let size = rng.range(0.2, 1.5);
            let points: Vec<Vector2<f64>> = (0..rng.int(3, 8))
                .map(|_| Vector2::new(rng.range(-size, size), rng.range(-size, size)))
                .collect();
            crate::shape::ConvexPolygon::convex_hull(&points).unwrap()
        };
        match kind {
            0 => Shape::Polygon(hull()),
            1 => Shape::circle(rng.range(0.1, 1.0)).unwrap(),
            2 => Shape::segment(
                Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
                Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
            )
            .unwrap(),
            3 => Shape::capsule(rng.range(0.1, 2.0), rng.range(0.05, 0.8)).unwrap(),
            _ => {
                let core = hull().vertices().to_vec();
                Shape::rounded_polygon(core, rng.range(0.05, 0.5)).unwrap()
            }
        }
    }

    /// The shortest core edge of a shape (m; infinite for a circle's point
    /// core).
    fn shortest_edge(shape: &Shape) -> f64 {
        let v = shape.convex_core().unwrap().vertices;
        (0..v.len())
            .filter(|_| v.len() > 1)
            .map(|i| (v[(i + 1) % v.len()] - v[i]).norm())
            .fold(f64::INFINITY, f64::min)
    }

    /// The one signed distance (the convex proxies' Minkowski difference)
    /// against the pair table's own distance functions, the reference while
    /// they exist, on 1 000 random pairs of every ordered pair of kinds.
    ///
    /// Both compute the same exact quantity from the same inputs, along
    /// different roundings: the table places B in A's frame
    /// (`pose_a⁻¹ pose_b`, then a rotation and a translation per vertex)
    /// and measures there; the proxy places both in the world and takes
    /// their vertex differences. Each path is some 12 roundings of
    /// quantities no larger than L (the largest world coordinate any point
    /// of the pair reaches, m), each off by at most u L = ε L / 2, so the
    /// distances differ by at most about 12 ε L; the bound is twice that
    /// for the operations not counted (the norms' square roots, the radii).
    /// A normal is an edge's direction (off by ≈ ε L / |edge|) or the
    /// direction between two nearest core points (off by ≈ ε L / gap), so
    /// the normals differ by at most 24 ε L / s, s the shorter of the
    /// cores' shortest edge and their gap; a witness point is a core point
    /// (≈ ε L) moved out by a radius r along the normal: 24 ε L (1 + r / s).
    #[test]
    fn the_one_distance_agrees_with_the_pair_functions_on_random_pairs() {
        use super::super::pair_table::pair;
        let names = ["polygon", "circle", "segment", "capsule", "rounded polygon"];
        let mut rng = Rng::new(0x5EED_D157);
        let eps = f64::EPSILON;
        for ka in 0..5 {
            for kb in 0..5 {
                let (mut worst_d, mut worst_n, mut worst_p) = (0.0f64, 0.0f64, 0.0f64);
                let mut overlapping = 0;
                for i in 0..1000 {
                    let (a, b) = (random_shape(&mut rng, ka), random_shape(&mut rng, kb));
                    let pa = Isometry2::new(
                        Vector2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
                        rng.range(-3.2, 3.2),
                    );
                    let pb = Isometry2::new(
                        pa.translation.vector
                            + Vector2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
                        rng.range(-3.2, 3.2),
                    );
                    let new = proximity(&a, &pa, &b, &pb);
                    let old = (pair(&a, &b).unwrap().proximity)(&a, &pa, &b, &pb);
                    let l = pa
                        .translation
                        .vector
                        .amax()
                        .max(pb.translation.vector.amax())
                        + a.max_extent()
                        + b.max_extent();
                    let (ra, rb) = (a.rounding_radius(), b.rounding_radius());
                    let gap = old.distance + ra + rb;
                    let s = shortest_edge(&a).min(shortest_edge(&b)).min(if gap > 0.0 {
                        gap
                    } else {
                        f64::INFINITY
                    });
                    let dd = (new.distance - old.distance).abs() / (eps * l);
                    let dn = (new.normal - old.normal).norm() / (eps * l / s);
                    let dp = (new.point_a - old.point_a)
                        .norm()
                        .max((new.point_b - old.point_b).norm())
                        / (eps * l * (1.0 + ra.max(rb) / s));
                    let case = format!(
                        "{} against {} #{i}: {a:?} at {pa:?}, {b:?} at {pb:?}: new {new:?}, old {old:?}",
                        names[ka], names[kb]
                    );
                    assert!(dd <= 24.0, "distance off by {dd} ε L: {case}");
                    assert!(dn <= 24.0, "normal off by {dn} ε L / s: {case}");
                    assert!(dp <= 24.0, "witness off by {dp} ε L (1 + r / s): {case}");
                    worst_d = worst_d.max(dd);
                    worst_n = worst_n.max(dn);
                    worst_p = worst_p.max(dp);
                    overlapping += usize::from(old.distance < 0.0);
                }
                println!(
                    "{} against {}: {overlapping} of 1000 overlapping; largest differences: \
                     distance {worst_d:.2} ε L, normal {worst_n:.2} ε L / s, \
                     witnesses {worst_p:.2} ε L (1 + r / s)",
                    names[ka], names[kb]
                );
            }
        }
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
