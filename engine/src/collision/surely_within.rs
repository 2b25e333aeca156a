//! A cheap test that two shapes are certainly within a distance of each
//! other, for the searches that only need to know that (the soft step's
//! continuous sweeps leave a pair within the linear slop at the start of
//! the step to the speculative contacts: most of the pairs they meet rest
//! on the ground they are swept against).
//!
//! The bound: for any point v of A's core and its nearest point c on B's
//! core, the disk of radius r_A about v lies in A and the disk of radius
//! r_B about c in B, so the two shapes are no farther apart than
//! |v − c| − r_A − r_B; and when that is negative they overlap at least
//! that deep (separating them moves the two disks apart, by at least
//! r_A + r_B − |v − c|). So the signed distance of
//! [`proximity`](super::proximity) (the gap, or minus the penetration
//! depth) is at most `|v − c| − r_A − r_B` for every core vertex v of
//! either shape against the other's core, and the test passes when one of
//! them is within `reach` less a slack. The slack covers the rounding of
//! both computations (see [`slack`]), so a pass means the exact signed
//! distance, as computed, is within `reach` too; a fail says nothing (the
//! caller computes the distance).

use super::convex::ConvexProxy;
use crate::shape::{Shape, cross};
use nalgebra::{Isometry2, Vector2};

/// Whether `a` at `pose_a` and `b` at `pose_b` are certainly within
/// `reach` (m) of each other: some core vertex of a convex piece of one
/// (a compound's part) lies within `reach` − [`slack`] of a piece of the
/// other (see the module docs). `false` says nothing; so does a chain
/// (it has no convex core: never certified).
pub(crate) fn surely_within(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
    reach: f64,
) -> bool {
    any_piece(a, pose_a, &mut |pa| {
        any_piece(b, pose_b, &mut |pb| proxies_within(pa, pb, reach))
    })
}

/// Whether `test` holds for one of `shape`'s convex pieces placed at
/// `pose` (the shape itself, or a compound's parts); false for a chain.
fn any_piece(
    shape: &Shape,
    pose: &Isometry2<f64>,
    test: &mut dyn FnMut(&ConvexProxy) -> bool,
) -> bool {
    match shape {
        Shape::Compound(c) => c.parts().iter().any(|p| {
            let part = pose * Isometry2::new(p.offset, p.angle);
            ConvexProxy::convex(&p.shape, &part).is_some_and(|q| test(&q))
        }),
        _ => ConvexProxy::convex(shape, pose).is_some_and(|q| test(&q)),
    }
}

/// The margin (m) taken off the reach for proxies whose coordinates and
/// radii are at most `scale` (m) in magnitude: 1e-9 m, or 1e-9 of the
/// scale beyond 1 m. Both the bound and the exact distance are a few
/// dozen roundings of such numbers (a pose applied to a vertex, a
/// Minkowski sum, a projection and a norm), each within half an ulp,
/// 1.1e-16 of the scale: together under about 1e-14 of it, which the
/// margin exceeds some 10⁵-fold. Beside a reach of millimetres (the
/// linear slop, 5 mm) it is negligible up to kilometres from the origin;
/// farther out the test passes less often, never wrongly.
pub(crate) fn slack(scale: f64) -> f64 {
    1e-9 * scale.max(1.0)
}

/// Whether a core vertex of `a` or of `b` is within `reach` − slack of
/// the other's shape, by the bound of the module docs.
fn proxies_within(a: &ConvexProxy, b: &ConvexProxy, reach: f64) -> bool {
    let scale = a
        .vertices
        .iter()
        .chain(&b.vertices)
        .map(|v| v.x.abs().max(v.y.abs()))
        .fold(a.radius.max(b.radius), f64::max);
    // The largest distance from a vertex to the other core that passes.
    let limit = reach - slack(scale) + a.radius + b.radius;
    if limit.is_nan() || limit < 0.0 {
        return false;
    }
    let limit_squared = limit * limit;
    let near = |p: &ConvexProxy, q: &ConvexProxy| {
        p.vertices
            .iter()
            .any(|&v| near_core(&q.vertices, v, limit_squared))
    };
    near(a, b) || near(b, a)
}

/// Whether point `p` is inside `core` (1 point, a segment, or a convex
/// polygon, counter-clockwise; m) or its squared distance (m²) to it is at
/// most `limit_squared`.
fn near_core(core: &[Vector2<f64>], p: Vector2<f64>, limit_squared: f64) -> bool {
    let n = core.len();
    // Inside a polygon core: on the inner side of every edge.
    if n >= 3 && (0..n).all(|k| cross(core[(k + 1) % n] - core[k], p - core[k]) >= 0.0) {
        return true;
    }
    if n == 1 {
        return (p - core[0]).norm_squared() <= limit_squared;
    }
    let edges = if n == 2 { 1 } else { n };
    (0..edges).any(|k| {
        let (start, e) = (core[k], core[(k + 1) % n] - core[k]);
        let u = ((p - start).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
        (p - (start + u * e)).norm_squared() <= limit_squared
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::proximity;
    use crate::collision::test_rng::Rng;
    use crate::shape::{Circle, Compound, CompoundPart};

    fn shapes() -> Vec<Shape> {
        let l_piece = Compound::new(vec![
            CompoundPart::new(
                Vector2::new(-0.3, 0.0),
                0.0,
                Shape::rectangle(0.6, 0.2).unwrap(),
            ),
            CompoundPart::new(
                Vector2::new(0.0, 0.3),
                0.2,
                Shape::rectangle(0.2, 0.6).unwrap(),
            ),
        ])
        .unwrap();
        vec![
            Shape::rectangle(1.0, 0.4).unwrap(),
            Shape::capsule(0.8, 0.1).unwrap(),
            Shape::Circle(Circle::new(0.3).unwrap()),
            Shape::Compound(l_piece),
            Shape::rectangle(62.0, 1.0).unwrap(),
        ]
    }

    /// Never a pass where the exact signed distance exceeds the reach: many
    /// random poses of every pair of shapes near contact (gaps of ±2 cm
    /// around a 5 mm reach), some of them far from the origin; and the
    /// test does pass for most of those whose exact distance is well
    /// within the reach (resting and overlapping pairs: what it is for).
    #[test]
    fn a_pass_is_never_beyond_the_exact_distance() {
        let reach = 0.005;
        let mut rng = Rng::new(21);
        let shapes = shapes();
        let (mut passes, mut within) = (0, 0);
        for a in &shapes {
            for b in &shapes {
                for k in 0..120 {
                    let far = if k % 4 == 0 { 1e3 } else { 0.0 };
                    let base = Vector2::new(far + rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
                    let pose_b = Isometry2::new(base, rng.range(-3.2, 3.2));
                    // Put A near B: along a random direction from B, then
                    // pulled back until the gap is in [−2 cm, 2 cm].
                    let angle_a = rng.range(-3.2, 3.2);
                    let dir = rng.range(-3.2, 3.2);
                    let dir = Vector2::new(dir.cos(), dir.sin());
                    let target = rng.range(-0.02, 0.02);
                    let place = |s: f64| Isometry2::new(base + s * dir, angle_a);
                    // 40 halvings of 100 m: within 1e-10 m.
                    let (mut lo, mut hi) = (0.0, 100.0);
                    for _ in 0..40 {
                        let mid = 0.5 * (lo + hi);
                        if proximity(a, &place(mid), b, &pose_b).distance < target {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    let pose_a = place(lo);
                    let exact = proximity(a, &pose_a, b, &pose_b).distance;
                    let pass = surely_within(a, &pose_a, b, &pose_b, reach);
                    assert!(!pass || exact <= reach, "{a:?} {b:?} {exact}");
                    assert_eq!(pass, surely_within(b, &pose_b, a, &pose_a, reach));
                    if exact <= 0.0 {
                        within += 1;
                        passes += usize::from(pass);
                    }
                }
            }
        }
        // A vertex need not be the deepest point (two rounded sides, a
        // circle's edge), but for most touching pairs one is.
        assert!(passes * 2 > within, "{passes} of {within}");
    }

    /// The boundary: a box resting on the ground at gaps just inside and
    /// just outside the reach; the slack's size at and far from the origin.
    #[test]
    fn the_reach_less_the_slack_decides() {
        let ground = Shape::rectangle(10.0, 1.0).unwrap();
        let block = Shape::rectangle(1.0, 1.0).unwrap();
        let reach = 0.005;
        let at = |gap: f64| Isometry2::translation(0.0, 1.0 + gap);
        assert!(surely_within(
            &block,
            &at(0.004),
            &ground,
            &Isometry2::identity(),
            reach
        ));
        assert!(surely_within(
            &block,
            &at(-0.3),
            &ground,
            &Isometry2::identity(),
            reach
        ));
        assert!(!surely_within(
            &block,
            &at(0.006),
            &ground,
            &Isometry2::identity(),
            reach
        ));
        // Within the slack of the reach: not certified.
        let gap = reach - 0.5 * slack(5.0);
        assert!(!surely_within(
            &block,
            &at(gap),
            &ground,
            &Isometry2::identity(),
            reach
        ));
        assert_eq!(slack(0.5), 1e-9);
        assert!((slack(1e3) - 1e-6).abs() < 1e-21);
        // A chain has no core: never certified.
        let chain = Shape::Chain(
            crate::shape::Chain::new(
                vec![
                    Vector2::new(6.0, 0.0),
                    Vector2::new(5.0, 0.0),
                    Vector2::new(-5.0, 0.0),
                    Vector2::new(-6.0, 0.0),
                ],
                false,
            )
            .unwrap(),
        );
        assert!(!surely_within(
            &block,
            &at(-0.3),
            &chain,
            &Isometry2::identity(),
            reach
        ));
    }
}
