//! A chain's segment against a convex polygon or a circle, in the
//! segment's frame (the chain's body frame), for the soft step's narrow
//! phase (`soft_step/manifold.rs`). The segment is one-sided and smooth:
//! it pushes shapes only towards its right (`shape/chain.rs`), and it
//! refuses the contact normals a smooth chain cannot have at its joins, so
//! a shape sliding along a chain of segments meets no **ghost collision**
//! (the bump a box gets from the corner of the next segment when each
//! segment is collided alone).
//!
//! Notation: the segment runs from p1 to p2, direction e1 = (p2 − p1)/|p2 −
//! p1|, normal n1 = e1 turned clockwise (its right); the previous segment
//! (ghost1 → p1) has normal n0, the next (p2 → ghost2) n2. A join is
//! **convex** when the chain turns left there by more than
//! `CHAIN_CONVEX_SIN` (seen from the free side, a ridge). The normals a
//! segment admits run from n0 (if its p1 join is convex; else n1) through
//! n1 to n2 (if its p2 join is convex; else n1): at a convex join the
//! surface's normal turns from one segment's to the next, at a flat or
//! concave join it does not.
//!
//! **Circle.** The point of the segment nearest the centre, unless the
//! centre is behind the segment (left of it: one-sided), or beyond an end
//! and over the neighbour segment (that neighbour owns it). Past a convex
//! join, in the wedge neither segment's interior faces, both segments give
//! the same vertex point (as Box2D's `b2CollideChainSegmentAndCircle`).
//!
//! **Polygon.** Separating axes, restricted:
//! 1. nothing when the polygon's centre is behind the segment and behind
//!    each convex neighbour;
//! 2. the segment's separation along n1, and along n0 / n2 at convex joins
//!    (when a neighbour's normal separates more, the neighbour owns the
//!    contact); the polygon's separations along its own edge normals, of
//!    which only the **admitted** ones (inside the cone above, within
//!    `CHAIN_ADMIT_SIN`) may become the contact normal. A normal outside
//!    the cone is what makes a ghost collision: at a flat join a box's side
//!    normal is refused and the segment's normal is used instead;
//! 3. the larger separation gives the reference edge (the segment's unless
//!    an admitted polygon edge separates more by a tenth of the linear
//!    slop, the tolerance `soft_step/manifold.rs` gives two polygons), the
//!    other shape's nearest edge is clipped to it, and each point is
//!    placed midway between the surfaces; points beyond `speculative` (m)
//!    are dropped.
//!
//! **Rounded polygon, capsule.** A polygon of radius r > 0 (a capsule is a
//! core of 2 vertices, its two sides as edges) is its core in all of the
//! above, its separations the core's less r, and its points midway between
//! the segment and its rounded surface (as Box2D's
//! `b2CollideChainSegmentAndPolygon` takes the polygon's radius); the
//! speculative cut-off applies to the rounded surface.
//!
//! Lengths are in m; normals point from the segment (A) to the other shape
//! (B). Feature ids are pairs of the one scheme (`feature_id.rs`), A's
//! feature and B's, as the soft step's polygon pairs: for the segment as
//! reference, the segment's edge and the incident vertex; for a polygon
//! edge as reference, the segment's end (a vertex) and the polygon's edge,
//! so that a point never keeps the impulse of a point made the other way
//! round.
//!
//! Box2D v3.2's `b2CollideChainSegmentAndPolygon` decides the same cone
//! with the closest points of a distance query; this file uses separating
//! axes throughout (the polygon pairs of the soft step do too).

use super::feature_id::{Feature, FeatureId};
use super::manifold::LocalProximity;
use crate::shape::ChainSegment;
use crate::tunables::{CHAIN_ADMIT_SIN, CHAIN_CONVEX_SIN, LINEAR_SLOP};
use nalgebra::{Isometry2, Vector2};
use smallvec::SmallVec;

/// A point of a [`SegmentManifold`], in the segment's frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct SegmentPoint {
    /// Midway between the surfaces (m).
    pub point: Vector2<f64>,
    /// Signed distance along the normal (m): < 0 overlapping.
    pub separation: f64,
    /// Feature id (see the module documentation).
    pub id: FeatureId,
}

/// A segment–polygon manifold: 0, 1 or 2 points sharing a normal.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct SegmentManifold {
    /// Unit normal from the segment to the polygon.
    pub normal: Vector2<f64>,
    /// How many of `points` are used.
    pub count: usize,
    /// The points; the first `count` are used.
    pub points: [SegmentPoint; 2],
}

/// The segment's directions and the normals it admits, in a frame whose
/// origin is p1 (round-off stays relative to the segment, not to where the
/// chain sits).
struct Smooth {
    /// p2 − p1 (m).
    p2: Vector2<f64>,
    /// Unit direction of the segment.
    e1: Vector2<f64>,
    /// Unit normals of the previous segment, this one and the next.
    n0: Vector2<f64>,
    n1: Vector2<f64>,
    n2: Vector2<f64>,
    /// Whether the joins at p1 and p2 are convex.
    convex1: bool,
    convex2: bool,
}

/// How a chain segment treats a candidate contact normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum NormalClass {
    /// Inside the cone of normals the smooth chain has here.
    Admit,
    /// Towards a flat or concave join: the segment's own normal stands.
    Snap,
    /// Past a convex neighbour's normal: that neighbour owns it.
    Skip,
}

/// The right-hand normal of a direction: `d` turned clockwise by 90°.
fn right(d: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(d.y, -d.x)
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

impl Smooth {
    fn of(s: &ChainSegment) -> Self {
        let e0 = (s.point1 - s.ghost1).normalize();
        let e1 = (s.point2 - s.point1).normalize();
        let e2 = (s.ghost2 - s.point2).normalize();
        Self {
            p2: s.point2 - s.point1,
            e1,
            n0: right(e0),
            n1: right(e1),
            n2: right(e2),
            convex1: cross(e0, e1) >= CHAIN_CONVEX_SIN,
            convex2: cross(e1, e2) >= CHAIN_CONVEX_SIN,
        }
    }

    /// The cone test of the module documentation for a unit `normal`
    /// (from the segment outwards).
    fn classify(&self, normal: Vector2<f64>) -> NormalClass {
        if normal.dot(&self.e1) <= 0.0 {
            // Leaning towards p1's join.
            match self.convex1 {
                true if cross(normal, self.n0) > CHAIN_ADMIT_SIN => NormalClass::Skip,
                true => NormalClass::Admit,
                false => NormalClass::Snap,
            }
        } else {
            match self.convex2 {
                true if cross(self.n2, normal) > CHAIN_ADMIT_SIN => NormalClass::Skip,
                true => NormalClass::Admit,
                false => NormalClass::Snap,
            }
        }
    }
}

/// A chain segment (A) against a circle of `radius` (m) centred at
/// `center` (m, the segment's frame): the signed distance, the normal and
/// the nearest points, or `None` when the circle is behind the segment,
/// owned by a neighbour, or farther than `speculative` (m).
pub(crate) fn chain_segment_circle_local(
    segment: &ChainSegment,
    radius: f64,
    center: Vector2<f64>,
    speculative: f64,
) -> Option<LocalProximity> {
    let (p1, p2) = (segment.point1, segment.point2);
    let e = p2 - p1;
    let q = center - p1;
    if right(e).dot(&q) < 0.0 {
        return None;
    }
    let t = e.dot(&q);
    let nearest = if t <= 0.0 {
        // Before p1: the previous segment's if the centre faces it.
        if (p1 - segment.ghost1).dot(&q) <= 0.0 {
            return None;
        }
        Vector2::zeros()
    } else if t >= e.norm_squared() {
        // Past p2: the next segment's if the centre faces it.
        if (segment.ghost2 - p2).dot(&(center - p2)) > 0.0 {
            return None;
        }
        e
    } else {
        e * (t / e.norm_squared())
    };
    let d = q - nearest;
    let distance = d.norm();
    let normal = if distance > 0.0 {
        d / distance
    } else {
        right(e).normalize()
    };
    let separation = distance - radius;
    if separation > speculative {
        return None;
    }
    Some(LocalProximity {
        distance: separation,
        normal,
        point_a: p1 + nearest,
        point_b: center - radius * normal,
    })
}

/// The part of the edge `a → b` whose projection on `tangent` lies in
/// `[low, high]`: its two ends (the one nearer `a` first), or `None` when
/// the edge lies wholly outside.
fn clip_to_slab(
    a: Vector2<f64>,
    b: Vector2<f64>,
    tangent: Vector2<f64>,
    low: f64,
    high: f64,
) -> Option<(Vector2<f64>, Vector2<f64>)> {
    let (ua, ub) = (tangent.dot(&a), tangent.dot(&b));
    if ua == ub {
        return (low..=high).contains(&ua).then_some((a, b));
    }
    let (s_low, s_high) = ((low - ua) / (ub - ua), (high - ua) / (ub - ua));
    let first = s_low.min(s_high).max(0.0);
    let last = s_low.max(s_high).min(1.0);
    if first > last {
        return None;
    }
    let at = |s: f64| {
        if s == 0.0 {
            a
        } else if s == 1.0 {
            b
        } else {
            a + s * (b - a)
        }
    };
    Some((at(first), at(last)))
}

/// A chain segment (A) against a convex polygon (B) given in its own frame
/// as `(vertices, normals, radius)`: `vertices` counter-clockwise (2 for a
/// capsule), `normals[i]` the outward unit normal of the edge from vertex i
/// to i + 1, `radius` (m) around that core, 0 for a sharp polygon; `xf`
/// maps B's frame into A's; points kept while their separation is at most
/// `speculative` (m).
pub(crate) fn chain_segment_polygon_local(
    segment: &ChainSegment,
    (vertices, normals, radius): (&[Vector2<f64>], &[Vector2<f64>], f64),
    xf: &Isometry2<f64>,
    speculative: f64,
) -> SegmentManifold {
    let none = SegmentManifold::default();
    let smooth = Smooth::of(segment);
    let origin = segment.point1;
    let shift = xf.translation.vector - origin;
    // B in A's frame, shifted so that p1 is the origin.
    let v: SmallVec<[Vector2<f64>; 8]> = vertices.iter().map(|w| xf.rotation * w + shift).collect();
    let m: SmallVec<[Vector2<f64>; 8]> = normals.iter().map(|n| xf.rotation * n).collect();
    let count = v.len();
    let centre = v.iter().sum::<Vector2<f64>>() / count as f64;
    let Smooth { p2, n0, n1, n2, .. } = smooth;

    // 1. One-sided: behind the segment and each convex neighbour.
    let behind1 = n1.dot(&centre) < 0.0;
    let behind0 = !smooth.convex1 || n0.dot(&centre) < 0.0;
    let behind2 = !smooth.convex2 || n2.dot(&(centre - p2)) < 0.0;
    if behind0 && behind1 && behind2 {
        return none;
    }

    // 2. The segment's axes: its own normal, and its convex neighbours'.
    let lowest = |n: Vector2<f64>, at: Vector2<f64>| {
        v.iter()
            .enumerate()
            .map(|(i, w)| (i, n.dot(&(w - at))))
            .fold(
                (0, f64::INFINITY),
                |best, x| if x.1 < best.1 { x } else { best },
            )
    };
    let (deepest, mut edge_separation) = lowest(n1, Vector2::zeros());
    let mut neighbour_owns = false;
    if smooth.convex1 {
        let s0 = lowest(n0, Vector2::zeros()).1;
        if s0 > edge_separation {
            (edge_separation, neighbour_owns) = (s0, true);
        }
    }
    if smooth.convex2 {
        let s2 = lowest(n2, p2).1;
        if s2 > edge_separation {
            (edge_separation, neighbour_owns) = (s2, true);
        }
    }
    // The cut-off between the cores (`+ 0` for a sharp polygon keeps its
    // bits).
    let reach = speculative + radius;
    if edge_separation > reach {
        return none;
    }

    // The polygon's axes: any of them separating by more than
    // `speculative` parts the pair; only admitted ones may be the normal.
    let mut polygon_best: Option<(usize, f64)> = None;
    for j in 0..count {
        let s = m[j].dot(&(-v[j])).min(m[j].dot(&(p2 - v[j])));
        if s > reach {
            return none;
        }
        if smooth.classify(-m[j]) == NormalClass::Admit && polygon_best.is_none_or(|b| s > b.1) {
            polygon_best = Some((j, s));
        }
    }

    // 3. The reference edge, clipping, points midway.
    let mut manifold = match polygon_best {
        Some((j, s)) if s > edge_separation + 0.1 * LINEAR_SLOP => {
            let normal = m[j];
            let (a1, a2) = (v[j], v[(j + 1) % count]);
            // The segment's end deeper along this normal: if the
            // neighbour there faces the polygon's edge more squarely, the
            // neighbour is the incident edge, not this segment.
            let (d1, d2) = (normal.dot(&(-a1)), normal.dot(&(p2 - a1)));
            let (neighbour, end_normal) = if d1 < d2 {
                (smooth.convex1, n0)
            } else {
                (smooth.convex2, n2)
            };
            if neighbour && end_normal.dot(&normal) < n1.dot(&normal) {
                return none;
            }
            let tangent = a2 - a1;
            let Some((q1, q2)) = clip_to_slab(
                Vector2::zeros(),
                p2,
                tangent,
                tangent.dot(&a1),
                tangent.dot(&a2),
            ) else {
                return none;
            };
            let mut out = SegmentManifold {
                normal: -normal,
                ..none
            };
            for (end, q) in [(0, q1), (1, q2)] {
                // From the rounded surface; midway between it and the
                // segment is then `q` less half of it.
                let separation = normal.dot(&(q - a1)) - radius;
                if separation <= speculative {
                    out.points[out.count] = SegmentPoint {
                        point: q - 0.5 * separation * normal,
                        separation,
                        id: FeatureId::pair(Feature::Vertex(end), Feature::Edge(j)),
                    };
                    out.count += 1;
                }
            }
            out
        }
        _ if neighbour_owns => return none,
        _ => {
            // The segment is the reference; the incident edge is the one
            // beside the deepest vertex that faces n1 the most.
            let before = (deepest + count - 1) % count;
            let (i1, i2) = if m[before].dot(&n1) < m[deepest].dot(&n1) {
                (before, deepest)
            } else {
                (deepest, (deepest + 1) % count)
            };
            let e1 = smooth.e1;
            let Some((q1, q2)) = clip_to_slab(v[i1], v[i2], e1, 0.0, e1.dot(&p2)) else {
                return none;
            };
            let mut out = SegmentManifold { normal: n1, ..none };
            for (vertex, q) in [(i1, q1), (i2, q2)] {
                let core = n1.dot(&q);
                let separation = core - radius;
                if separation <= speculative {
                    // Midway between the segment and the rounded surface,
                    // `radius` below the core's point `q`.
                    let lift = if radius > 0.0 { core + radius } else { core };
                    out.points[out.count] = SegmentPoint {
                        point: q - 0.5 * lift * n1,
                        separation,
                        id: FeatureId::pair(Feature::Edge(0), Feature::Vertex(vertex)),
                    };
                    out.count += 1;
                }
            }
            out
        }
    };
    for p in &mut manifold.points[..manifold.count] {
        p.point += origin;
    }
    manifold
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat ground listed right to left (solid from above): segment from
    /// (1, 0) to (0, 0), ghosts (2, 0) and (−1, 0).
    fn flat() -> ChainSegment {
        ChainSegment {
            ghost1: Vector2::new(2.0, 0.0),
            point1: Vector2::new(1.0, 0.0),
            point2: Vector2::new(0.0, 0.0),
            ghost2: Vector2::new(-1.0, 0.0),
        }
    }

    fn unit_box() -> (Vec<Vector2<f64>>, Vec<Vector2<f64>>) {
        let v = vec![
            Vector2::new(-0.5, -0.5),
            Vector2::new(0.5, -0.5),
            Vector2::new(0.5, 0.5),
            Vector2::new(-0.5, 0.5),
        ];
        let n = vec![
            Vector2::new(0.0, -1.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(-1.0, 0.0),
        ];
        (v, n)
    }

    #[test]
    fn a_box_resting_on_the_segment_gets_the_segment_normal_and_two_points() {
        let (v, n) = unit_box();
        // Box centred at x = 0.5, bottom 1 mm into the ground.
        let xf = Isometry2::translation(0.5, 0.499);
        let m = chain_segment_polygon_local(&flat(), (&v, &n, 0.0), &xf, 0.02);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::new(0.0, 1.0));
        for p in &m.points {
            assert!((p.separation + 0.001).abs() < 1e-12, "{p:?}");
            // Midway: half the overlap below the box's bottom.
            assert!((p.point.y - (-0.0005)).abs() < 1e-12, "{p:?}");
        }
    }

    #[test]
    fn a_capsule_lying_on_the_segment_sinks_by_its_rounded_surface() {
        // A capsule core (±0.25, its two sides) of radius 0.1 lying 1 mm
        // into the ground (its axis at 0.099), centred at x = 0.5; beyond
        // the speculative distance (axis at 0.1 + 0.03) it is dropped.
        let v = vec![Vector2::new(-0.25, 0.0), Vector2::new(0.25, 0.0)];
        let n = vec![Vector2::new(0.0, -1.0), Vector2::new(0.0, 1.0)];
        let xf = Isometry2::translation(0.5, 0.099);
        let m = chain_segment_polygon_local(&flat(), (&v, &n, 0.1), &xf, 0.02);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::new(0.0, 1.0));
        for p in &m.points {
            assert!((p.separation + 0.001).abs() < 1e-12, "{p:?}");
            // Midway between the ground and the capsule's bottom.
            assert!((p.point.y - (-0.0005)).abs() < 1e-12, "{p:?}");
        }
        let xs = [m.points[0].point.x, m.points[1].point.x];
        assert!((xs[0].min(xs[1]) - 0.25).abs() < 1e-12, "{xs:?}");
        assert!((xs[0].max(xs[1]) - 0.75).abs() < 1e-12, "{xs:?}");
        let far = Isometry2::translation(0.5, 0.13);
        let m = chain_segment_polygon_local(&flat(), (&v, &n, 0.1), &far, 0.02);
        assert_eq!(m.count, 0);
    }

    #[test]
    fn a_box_over_a_flat_join_gets_no_side_normal() {
        // The box straddles the join at x = 0 and sinks 1 mm: taken alone,
        // the segment's end (0, 0) is 0.5 m deep along the box's left side
        // normal and 1 mm along the ground's; a box's side normal is the
        // ghost collision. Here the segment's normal stands, with the part
        // of the bottom edge over this segment.
        let (v, n) = unit_box();
        let xf = Isometry2::translation(0.3, 0.499);
        let m = chain_segment_polygon_local(&flat(), (&v, &n, 0.0), &xf, 0.02);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::new(0.0, 1.0));
        let xs = [m.points[0].point.x, m.points[1].point.x];
        assert!(
            xs.iter().all(|x| (-1e-12..=0.8 + 1e-12).contains(x)),
            "{xs:?}"
        );
        // A box 0.1 m past the join, sunk 0.05 m (a corner caught on the
        // end): still the ground's normal, never the box side's.
        let xf = Isometry2::translation(-0.4, 0.45);
        let m = chain_segment_polygon_local(&flat(), (&v, &n, 0.0), &xf, 0.02);
        assert!(m.count > 0);
        assert_eq!(m.normal, Vector2::new(0.0, 1.0));
    }

    #[test]
    fn the_segment_is_one_sided() {
        let (v, n) = unit_box();
        // Below the ground, overlapping it: nothing.
        let xf = Isometry2::translation(0.5, -0.45);
        assert_eq!(
            chain_segment_polygon_local(&flat(), (&v, &n, 0.0), &xf, 0.02).count,
            0
        );
        assert!(chain_segment_circle_local(&flat(), 0.5, Vector2::new(0.5, -0.1), 0.02).is_none());
        // Above it: a circle resting 1 mm deep.
        let c = chain_segment_circle_local(&flat(), 0.5, Vector2::new(0.5, 0.499), 0.02).unwrap();
        assert!((c.distance + 0.001).abs() < 1e-12);
        assert_eq!(c.normal, Vector2::new(0.0, 1.0));
    }

    #[test]
    fn a_circle_past_an_end_over_the_neighbour_belongs_to_the_neighbour() {
        // Centre over the next segment (x < 0): the next one owns it.
        assert!(chain_segment_circle_local(&flat(), 0.5, Vector2::new(-0.2, 0.49), 0.02).is_none());
        // At a convex join (the next segment goes down-left), the wedge past
        // both segments is this one's too: the vertex point.
        let mut ridge = flat();
        ridge.ghost2 = Vector2::new(-1.0, -1.0);
        let c = chain_segment_circle_local(&ridge, 0.5, Vector2::new(-0.3, 0.3), 0.02).unwrap();
        assert!((c.point_a - Vector2::zeros()).norm() < 1e-15);
        let expected = Vector2::new(-0.3, 0.3).normalize();
        assert!((c.normal - expected).norm() < 1e-12);
    }

    #[test]
    fn a_box_tipped_over_a_convex_join_takes_its_own_edge_normal() {
        // Ridge at p2 = (0, 0): the next segment goes down-left at 45°. A
        // box turned by 22.5° rests its bottom edge across the corner: its
        // normal is inside the cone [n1, n2] and is admitted.
        let mut ridge = flat();
        ridge.ghost2 = Vector2::new(-1.0, -1.0);
        let (v, n) = unit_box();
        let angle = std::f64::consts::PI / 8.0;
        let rotation = nalgebra::UnitComplex::new(angle);
        // Bottom edge's middle at the corner, 1 mm deep along its normal.
        let down = rotation * Vector2::new(0.0, -1.0);
        let centre = -down * 0.499;
        let xf = Isometry2::from_parts(nalgebra::Translation2::from(centre), rotation);
        let m = chain_segment_polygon_local(&ridge, (&v, &n, 0.0), &xf, 0.02);
        assert!(m.count > 0);
        assert!((m.normal - (-down)).norm() < 1e-12, "{:?}", m.normal);
    }
}
