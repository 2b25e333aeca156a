//! Distances and shape casts between two [`ConvexProxy`]s through their
//! Minkowski difference, built explicitly.
//!
//! For a shape A and a shape B, the core of `M = B ⊖ A = {b − a}` is the
//! convex polygon whose edges are the edges of B's core and of A's
//! reflected core merged by direction (O(n + m), a point or a segment when
//! both cores are), and its radius is the sum of theirs. Every question
//! about the pair is then a question about M and the origin:
//!
//! - **separation**: the distance from the origin to M's core minus the
//!   radius, or, when the origin is inside the core, minus the depth (the
//!   distance to the nearest edge line, as the origin is inside a convex
//!   polygon); the normal is M's outward normal there, which is B's
//!   outward normal pointing towards A;
//! - **shape cast**: A moved by `s · v` first touches B when `s v` enters
//!   M: a ray cast from the origin along `v` ([`super::ray`]);
//! - **overlap**: the origin inside M.
//!
//! Each vertex of M remembers the pair of core vertices it came from, so a
//! point of M's core maps back to the points of A and B it is the
//! difference of (a linear interpolation along the edge: along an edge of
//! M one of the two indices advances, or both for parallel edges).
//! Compared with GJK, the answer is exact up to rounding with no iteration
//! and no termination tolerance; the cost is building M, a few dozen
//! operations for the engine's polygons.

use super::convex::ConvexProxy;
use super::manifold::Proximity;
use super::ray::{ProxyRayHit, ray_cast};
use crate::shape::cross;
use nalgebra::Vector2;
use smallvec::SmallVec;

/// The Minkowski difference `B ⊖ A` of two proxies, with the core vertex
/// pair (index in A, index in B) of each of its core vertices.
#[derive(Debug, Clone)]
pub(crate) struct Difference {
    pub proxy: ConvexProxy,
    pub pairs: SmallVec<[(u16, u16); 16]>,
}

/// The point of a core nearest to a point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CoreClosest {
    /// The nearest point of the core (m); the point itself when inside.
    pub point: Vector2<f64>,
    /// The point lies inside a polygon core (≥ 3 vertices, closed).
    pub inside: bool,
    /// The nearest point is `(1 − u) v[edge] + u v[edge + 1]` (for a
    /// polygon core containing the point: of the nearest edge).
    pub edge: usize,
    /// See `edge`.
    pub u: f64,
}

/// The bottom-most (then left-most) vertex: where the merge by edge
/// direction starts, so that both edge sequences begin at angle ≥ 0.
fn lowest(points: &[Vector2<f64>]) -> usize {
    (0..points.len())
        .min_by(|&i, &j| {
            (points[i].y, points[i].x)
                .partial_cmp(&(points[j].y, points[j].x))
                .expect("finite coordinates")
        })
        .expect("a core has a vertex")
}

/// `B ⊖ A`, its core the merge of B's core edges and −A's.
pub(crate) fn difference(a: &ConvexProxy, b: &ConvexProxy) -> Difference {
    let p: SmallVec<[Vector2<f64>; 16]> = b.vertices.iter().copied().collect();
    let q: SmallVec<[Vector2<f64>; 16]> = a.vertices.iter().map(|v| -v).collect();
    let (n, m) = (p.len(), q.len());
    let (ps, qs) = (lowest(&p), lowest(&q));
    let mut vertices = SmallVec::new();
    let mut pairs = SmallVec::new();
    let (mut i, mut j) = (0, 0);
    while i < n || j < m {
        let (ip, iq) = ((ps + i) % n, (qs + j) % m);
        vertices.push(p[ip] + q[iq]);
        pairs.push((iq as u16, ip as u16));
        let ep = p[(ip + 1) % n] - p[ip];
        let eq = q[(iq + 1) % m] - q[iq];
        let turn = cross(ep, eq);
        let advance_p = turn >= 0.0 && i < n;
        let advance_q = turn <= 0.0 && j < m;
        // Past the end of one outline, its first edge comes round again
        // at an angle above every remaining edge of the other: the other
        // advances (the test above gives that unless rounding says
        // otherwise, which this guards against).
        match (advance_p, advance_q) {
            (false, false) => {
                if i < n {
                    i += 1
                } else {
                    j += 1
                }
            }
            _ => {
                i += usize::from(advance_p);
                j += usize::from(advance_q);
            }
        }
    }
    Difference {
        proxy: ConvexProxy {
            vertices,
            radius: a.radius + b.radius,
        },
        pairs,
    }
}

/// The point of `core` (1, 2 or ≥ 3 vertices, counter-clockwise) nearest
/// to `p`.
pub(crate) fn closest_on_core(core: &[Vector2<f64>], p: Vector2<f64>) -> CoreClosest {
    let n = core.len();
    if n == 1 {
        return CoreClosest {
            point: core[0],
            inside: false,
            edge: 0,
            u: 0.0,
        };
    }
    if n >= 3 {
        // Inside when behind every edge line; then the nearest edge line.
        let mut deepest = (f64::NEG_INFINITY, 0);
        for k in 0..n {
            let e = core[(k + 1) % n] - core[k];
            let outward = Vector2::new(e.y, -e.x) / e.norm();
            let s = outward.dot(&(p - core[k]));
            if s > 0.0 {
                deepest = (f64::NAN, 0);
                break;
            }
            if s > deepest.0 {
                deepest = (s, k);
            }
        }
        if !deepest.0.is_nan() {
            let k = deepest.1;
            let e = core[(k + 1) % n] - core[k];
            let u = ((p - core[k]).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
            return CoreClosest {
                point: p,
                inside: true,
                edge: k,
                u,
            };
        }
    }
    let edges = if n == 2 { 1 } else { n };
    let mut best = CoreClosest {
        point: core[0],
        inside: false,
        edge: 0,
        u: 0.0,
    };
    let mut best_d2 = f64::INFINITY;
    for k in 0..edges {
        let (s, e) = (core[k], core[(k + 1) % n] - core[k]);
        let u = ((p - s).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
        let q = s + u * e;
        let d2 = (p - q).norm_squared();
        if d2 < best_d2 {
            best_d2 = d2;
            best = CoreClosest {
                point: q,
                inside: false,
                edge: k,
                u,
            };
        }
    }
    best
}

/// How two proxies sit relative to each other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Separation {
    /// Signed distance (m): the gap when > 0, minus the penetration depth
    /// when < 0.
    pub distance: f64,
    /// Unit normal, B's outward normal pointing towards A.
    pub normal: Vector2<f64>,
    /// The point of A's surface nearest B (deepest in B when overlapping),
    /// m.
    pub point_a: Vector2<f64>,
    /// The point of B's surface nearest A (m).
    pub point_b: Vector2<f64>,
}

impl Difference {
    /// The points of A's and B's cores whose difference is the core point
    /// `(1 − u) v[edge] + u v[edge + 1]`.
    fn witnesses(
        &self,
        a: &ConvexProxy,
        b: &ConvexProxy,
        edge: usize,
        u: f64,
    ) -> (Vector2<f64>, Vector2<f64>) {
        let n = self.pairs.len();
        let (ia0, ib0) = self.pairs[edge];
        let (ia1, ib1) = self.pairs[(edge + 1) % n];
        let mix = |p: Vector2<f64>, q: Vector2<f64>| (1.0 - u) * p + u * q;
        (
            mix(a.vertices[ia0 as usize], a.vertices[ia1 as usize]),
            mix(b.vertices[ib0 as usize], b.vertices[ib1 as usize]),
        )
    }
}

/// The signed distance between `a` and `b`, its normal and witness
/// points.
pub(crate) fn separation(a: &ConvexProxy, b: &ConvexProxy) -> Separation {
    let m = difference(a, b);
    let core = &m.proxy.vertices;
    let closest = closest_on_core(core, Vector2::zeros());
    let n = core.len();
    let (core_distance, normal) = if closest.inside {
        let normal = m.proxy.edge_normal(closest.edge);
        (-normal.dot(&core[closest.edge]), normal)
    } else {
        let d = closest.point.norm();
        let interior = n >= 2 && closest.u > 0.0 && closest.u < 1.0;
        let normal = if interior {
            let normal = m.proxy.edge_normal(closest.edge);
            // A segment core's "edge 0" may face away from the origin.
            if normal.dot(&closest.point) > 0.0 {
                -normal
            } else {
                normal
            }
        } else if d > 0.0 {
            -closest.point / d
        } else {
            // Cores meeting at a point (concentric circles): any direction
            // is one; −y, so that the normal from A to B is +y, the
            // direction the contact manifolds push concentric circles
            // apart (`circle_circle.rs`).
            -Vector2::y()
        };
        (d, normal)
    };
    let (core_a, core_b) = m.witnesses(a, b, closest.edge, closest.u);
    Separation {
        distance: core_distance - m.proxy.radius,
        normal,
        point_a: core_a - a.radius * normal,
        point_b: core_b + b.radius * normal,
    }
}

/// The same answer in the narrow phase's terms: the normal from A to B
/// (the opposite of [`Separation::normal`]), the rest unchanged.
impl From<Separation> for Proximity {
    fn from(s: Separation) -> Self {
        Proximity {
            distance: s.distance,
            normal: -s.normal,
            point_a: s.point_a,
            point_b: s.point_b,
        }
    }
}

/// Where `a`, moved by `s · translation` (0 ≤ s ≤ 1), first touches `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CastHit {
    /// The fraction s of the translation at the first touch.
    pub fraction: f64,
    /// B's outward unit normal at the touching point.
    pub normal: Vector2<f64>,
    /// The touching point, on B's surface (m).
    pub point: Vector2<f64>,
}

/// The first touch of `a` swept by `translation` (m) against `b`;
/// `None` when they overlap at the start, never touch, or touch only
/// beyond the translation.
pub(crate) fn shape_cast(
    a: &ConvexProxy,
    b: &ConvexProxy,
    translation: Vector2<f64>,
) -> Option<CastHit> {
    let length = translation.norm();
    let m = difference(a, b);
    let hit: ProxyRayHit = if length == 0.0 {
        return None;
    } else {
        ray_cast(&m.proxy, Vector2::zeros(), translation / length, length)?
    };
    let (_, core_b) = m.witnesses(a, b, hit.edge, hit.u);
    Some(CastHit {
        fraction: hit.t / length,
        normal: hit.normal,
        point: core_b + b.radius * hit.normal,
    })
}

/// Whether `a` and `b` overlap (touching counts).
pub(crate) fn overlap(a: &ConvexProxy, b: &ConvexProxy) -> bool {
    super::ray::contains(&difference(a, b).proxy, Vector2::zeros())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Shape;
    use nalgebra::Isometry2;

    fn boxed(w: f64, h: f64, x: f64, y: f64, angle: f64) -> ConvexProxy {
        ConvexProxy::of(
            &Shape::rectangle(w, h).unwrap(),
            &Isometry2::new(Vector2::new(x, y), angle),
        )
    }

    #[test]
    fn difference_of_two_boxes_is_their_size_sum() {
        let m = difference(
            &boxed(2.0, 2.0, 0.0, 0.0, 0.0),
            &boxed(4.0, 2.0, 10.0, 0.0, 0.0),
        );
        // Parallel edges merge: a 6 × 4 rectangle centred at (10, 0).
        assert_eq!(m.proxy.vertices.len(), 4);
        let mut xs: Vec<f64> = m.proxy.vertices.iter().map(|v| v.x).collect();
        xs.sort_by(f64::total_cmp);
        assert_eq!(xs, vec![7.0, 7.0, 13.0, 13.0]);
    }

    #[test]
    fn separation_of_boxes_circles_and_a_box_with_a_circle() {
        let s = separation(
            &boxed(2.0, 2.0, 0.0, 0.0, 0.0),
            &boxed(2.0, 2.0, 5.0, 0.5, 0.0),
        );
        assert_eq!(s.distance, 3.0);
        assert_eq!(s.normal, Vector2::new(-1.0, 0.0));
        assert_eq!(s.point_a.x, 1.0);
        assert_eq!(s.point_b.x, 4.0);
        let circle = |x: f64, r: f64| {
            ConvexProxy::of(&Shape::circle(r).unwrap(), &Isometry2::translation(x, 0.0))
        };
        let s = separation(&circle(0.0, 1.0), &circle(3.0, 0.5));
        assert_eq!((s.distance, s.point_a.x, s.point_b.x), (1.5, 1.0, 2.5));
        // Overlapping: minus the depth.
        let s = separation(&boxed(2.0, 2.0, 0.0, 0.0, 0.0), &circle(1.5, 1.0));
        assert_eq!(s.distance, -0.5);
        assert_eq!(s.normal, Vector2::new(-1.0, 0.0));
    }

    #[test]
    fn a_box_swept_onto_a_box_stops_at_the_gap() {
        let hit = shape_cast(
            &boxed(2.0, 2.0, 0.0, 0.0, 0.0),
            &boxed(2.0, 2.0, 5.0, 0.5, 0.0),
            Vector2::new(6.0, 0.0),
        )
        .unwrap();
        assert_eq!(hit.fraction, 0.5);
        assert_eq!(hit.normal, Vector2::new(-1.0, 0.0));
        assert_eq!(hit.point.x, 4.0);
        // Too short, or sideways: no touch.
        assert!(
            shape_cast(
                &boxed(2.0, 2.0, 0.0, 0.0, 0.0),
                &boxed(2.0, 2.0, 5.0, 0.5, 0.0),
                Vector2::new(2.9, 0.0)
            )
            .is_none()
        );
        assert!(
            shape_cast(
                &boxed(2.0, 2.0, 0.0, 0.0, 0.0),
                &boxed(2.0, 2.0, 5.0, 0.5, 0.0),
                Vector2::new(0.0, 6.0)
            )
            .is_none()
        );
    }

    #[test]
    fn overlap_counts_touching() {
        let a = boxed(2.0, 2.0, 0.0, 0.0, 0.0);
        assert!(overlap(&a, &boxed(2.0, 2.0, 2.0, 0.0, 0.0)));
        assert!(!overlap(&a, &boxed(2.0, 2.0, 2.0 + 1e-12, 0.0, 0.0)));
    }
}
