//! Concave polygons cut into convex parts.
//!
//! The contact code handles convex pieces only, so a simple polygon that is
//! not convex becomes a [`Compound`] of convex polygons in the same frame.
//! Three stages:
//!
//! 1. **Check the outline** ([`check_outline`]): at least three finite
//!    vertices, no point listed twice, no vertex collinear with its two
//!    neighbours (a straight vertex, or a spike of zero width), no two
//!    edges that cross or touch (a simple polygon), and counter-clockwise
//!    (the same rule as [`ConvexPolygon::new`]: for an outline the order is
//!    its meaning, as it is for Box2D's one-sided chains, so a clockwise
//!    one is refused with the fix rather than silently reversed). Each
//!    refusal is an [`OutlineError`] naming the vertex or edges.
//! 2. **Triangulate by ear clipping**: repeatedly cut off a vertex whose
//!    triangle with its two neighbours turns left at all three corners and
//!    holds no other vertex that is not convex (inside or on its boundary).
//!    A simple polygon always has such an ear (Meisters' two-ears theorem),
//!    so n − 2 triangles come out.
//! 3. **Merge (Hertel–Mehlhorn)**: remove each diagonal of the
//!    triangulation, in the order the triangles were cut, when the two
//!    pieces on its sides merge into a polygon that still turns left at
//!    both ends of the diagonal. The result has at most four times the
//!    fewest convex parts any partition by diagonals can have (Hertel and
//!    Mehlhorn, 1983); an L has 2, a five-pointed star 5 or 6.
//!
//! Every sign is `turn`, the predicate [`ConvexPolygon::new`] uses, on the
//! vertices rescaled by a power of two (`rescaled`, exact): a turn within
//! its rounding bound counts as straight, so an ear or a merge is only made
//! when its corners are convex beyond doubt, and every part passes
//! [`ConvexPolygon::new`]. Near-degenerate outlines (edges within rounding
//! of touching) are refused rather than guessed at.
//!
//! Cost: the edge-crossing check is O(n²) pairs and ear clipping O(n²·r)
//! for r reflex vertices; meant for hand-written outlines of tens to
//! hundreds of vertices. No crate was taken for this: earcut ports
//! triangulate but do not merge into convex parts, and the engine keeps its
//! dependencies to numerics.

use super::{Compound, CompoundPart, ConvexPolygon, Shape, Turn, rescaled, turn};
use nalgebra::Vector2;
use std::collections::HashMap;
use thiserror::Error;

/// Why an outline cannot be a polygon shape. Vertex and edge indices are
/// 0-based positions in the list given; edge `i` runs from vertex `i` to
/// vertex `i + 1` (the last one back to vertex 0).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum OutlineError {
    /// Fewer than three vertices.
    #[error("a polygon needs at least 3 vertices, got {count}")]
    TooFewVertices {
        /// How many were given.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("non-finite coordinate at vertex {vertex}")]
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// The same point is listed twice (next to each other: a repeated
    /// vertex; apart: the outline touches itself there).
    #[error("repeated vertex at vertex {second} (the same point as vertex {first})")]
    RepeatedVertex {
        /// The earlier listing.
        first: usize,
        /// The later one.
        second: usize,
    },
    /// A vertex on the line through its two neighbours: a straight vertex,
    /// a spike of zero width, or (all of them) an outline of zero area.
    #[error(
        "collinear vertex at vertex {vertex} (on the line through its neighbours: zero area there)"
    )]
    CollinearVertex {
        /// The vertex.
        vertex: usize,
    },
    /// Two edges cross or touch: the outline is not a simple polygon.
    #[error(
        "self-intersecting outline: edge {edge} crosses or touches edge {other} at vertex {edge}"
    )]
    SelfIntersecting {
        /// The first edge (and the vertex it starts from).
        edge: usize,
        /// The edge it meets.
        other: usize,
    },
    /// The outline runs clockwise.
    #[error(
        "vertices are clockwise (list them counter-clockwise): the outline turns right at vertex {vertex}, its lowest-leftmost"
    )]
    Clockwise {
        /// The lowest-leftmost vertex, where a clockwise outline turns right.
        vertex: usize,
    },
    /// Edges within f64's rounding of touching left no vertex that could be
    /// cut off or made a convex part beyond doubt.
    #[error(
        "the outline is too close to degenerate near vertex {vertex} to be cut into convex parts in f64 (edges within rounding of touching)"
    )]
    NearlyDegenerate {
        /// A vertex of the piece that could not be cut.
        vertex: usize,
    },
}

impl OutlineError {
    /// The vertex the error is about (for a located message), if one.
    pub fn vertex(&self) -> Option<usize> {
        match *self {
            OutlineError::TooFewVertices { .. } => None,
            OutlineError::NonFinite { vertex }
            | OutlineError::CollinearVertex { vertex }
            | OutlineError::Clockwise { vertex }
            | OutlineError::NearlyDegenerate { vertex } => Some(vertex),
            OutlineError::RepeatedVertex { second, .. } => Some(second),
            OutlineError::SelfIntersecting { edge, .. } => Some(edge),
        }
    }
}

impl Shape {
    /// The shape of a simple polygon listed counter-clockwise (m): a
    /// [`Shape::Polygon`] if it is convex, else a [`Shape::Compound`] of
    /// its convex parts ([`convex_parts`]), all in the same frame.
    pub fn simple_polygon(vertices: &[Vector2<f64>]) -> Result<Shape, OutlineError> {
        let mut parts = convex_parts(vertices)?;
        if parts.len() == 1 {
            return Ok(Shape::Polygon(parts.remove(0)));
        }
        let parts = parts
            .into_iter()
            .map(|p| CompoundPart::new(Vector2::zeros(), 0.0, Shape::Polygon(p)))
            .collect();
        // At least two parts of finite placement: Compound::new accepts them.
        Compound::new(parts)
            .map(Shape::Compound)
            .map_err(|_| OutlineError::NearlyDegenerate { vertex: 0 })
    }
}

/// The convex parts of a simple polygon listed counter-clockwise (m): the
/// polygon itself if it is convex, else the Hertel–Mehlhorn merge of an
/// ear-clipping triangulation (see the module documentation). The parts
/// cover the polygon exactly, without overlap, and their vertices are the
/// outline's own.
pub fn convex_parts(vertices: &[Vector2<f64>]) -> Result<Vec<ConvexPolygon>, OutlineError> {
    let points = check_outline(vertices)?;
    let n = points.len();
    let convex =
        (0..n).all(|i| turn(points[(i + n - 1) % n], points[i], points[(i + 1) % n]) == Turn::Left);
    let pieces = if convex {
        vec![(0..n).collect()]
    } else {
        merge(&points, triangulate(&points)?)
    };
    pieces
        .into_iter()
        .map(|piece: Vec<usize>| {
            ConvexPolygon::new(piece.iter().map(|&i| vertices[i]).collect())
                .map_err(|_| OutlineError::NearlyDegenerate { vertex: piece[0] })
        })
        .collect()
}

/// Checks that `vertices` outline a simple polygon counter-clockwise and
/// returns them rescaled by a power of two (exact; see `rescaled`).
pub fn check_outline(vertices: &[Vector2<f64>]) -> Result<Vec<Vector2<f64>>, OutlineError> {
    let n = vertices.len();
    if n < 3 {
        return Err(OutlineError::TooFewVertices { count: n });
    }
    if let Some(vertex) = super::first_non_finite(vertices) {
        return Err(OutlineError::NonFinite { vertex });
    }
    if let Some((first, second)) = first_repeat(vertices) {
        return Err(OutlineError::RepeatedVertex { first, second });
    }
    let points = rescaled(vertices);
    for i in 0..n {
        if turn(points[(i + n - 1) % n], points[i], points[(i + 1) % n]) == Turn::Straight {
            return Err(OutlineError::CollinearVertex { vertex: i });
        }
    }
    // Edges next to each other share a vertex and, no vertex being
    // straight, nothing else; every other pair must not meet at all.
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (p1, p2) = (points[i], points[(i + 1) % n]);
            let (q1, q2) = (points[j], points[(j + 1) % n]);
            if segments_meet(p1, p2, q1, q2) {
                return Err(OutlineError::SelfIntersecting { edge: i, other: j });
            }
        }
    }
    // A simple outline: the shoelace sum's sign is its orientation, and
    // the lowest-leftmost vertex (on the hull) turns the same way.
    let twice_area: f64 = (0..n)
        .map(|i| super::cross(points[i], points[(i + 1) % n]))
        .sum();
    if twice_area < 0.0 {
        let lowest = (0..n)
            .min_by(|&a, &b| {
                (points[a].y, points[a].x)
                    .partial_cmp(&(points[b].y, points[b].x))
                    .expect("finite")
            })
            .expect("n ≥ 3");
        return Err(OutlineError::Clockwise { vertex: lowest });
    }
    Ok(points)
}

/// The first pair of positions holding the same point, `(earlier, later)`
/// with the later one smallest, if any.
fn first_repeat(vertices: &[Vector2<f64>]) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..vertices.len()).collect();
    let key = |i: usize| (vertices[i].x, vertices[i].y);
    order.sort_by(|&a, &b| key(a).partial_cmp(&key(b)).expect("finite").then(a.cmp(&b)));
    order
        .windows(2)
        .filter(|w| vertices[w[0]] == vertices[w[1]])
        .map(|w| (w[0], w[1]))
        .min_by_key(|&(_, later)| later)
}

/// Whether segments `p1 p2` and `q1 q2` cross or touch, a point within
/// rounding of the other segment counting as touching.
fn segments_meet(p1: Vector2<f64>, p2: Vector2<f64>, q1: Vector2<f64>, q2: Vector2<f64>) -> bool {
    let opposite = |a: Turn, b: Turn| {
        matches!(
            (a, b),
            (Turn::Left, Turn::Right) | (Turn::Right, Turn::Left)
        )
    };
    let within_box = |a: Vector2<f64>, b: Vector2<f64>, p: Vector2<f64>| {
        p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
    };
    let (d1, d2) = (turn(p1, p2, q1), turn(p1, p2, q2));
    let (d3, d4) = (turn(q1, q2, p1), turn(q1, q2, p2));
    (opposite(d1, d2) && opposite(d3, d4))
        || (d1 == Turn::Straight && within_box(p1, p2, q1))
        || (d2 == Turn::Straight && within_box(p1, p2, q2))
        || (d3 == Turn::Straight && within_box(q1, q2, p1))
        || (d4 == Turn::Straight && within_box(q1, q2, p2))
}

/// Ear clipping of a checked outline: n − 2 triangles of vertex indices,
/// each counter-clockwise, in the order they were cut.
fn triangulate(points: &[Vector2<f64>]) -> Result<Vec<[usize; 3]>, OutlineError> {
    let mut ring: Vec<usize> = (0..points.len()).collect();
    let mut triangles = Vec::with_capacity(points.len() - 2);
    let mut start = 0;
    while ring.len() > 3 {
        let m = ring.len();
        let ear = (0..m)
            .map(|k| (start + k) % m)
            .find(|&k| is_ear(points, &ring, k));
        let Some(k) = ear else {
            return Err(OutlineError::NearlyDegenerate {
                vertex: ring[start % m],
            });
        };
        triangles.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
        ring.remove(k);
        // Keep cutting around the outline from the ear's left neighbour.
        start = (k + ring.len() - 1) % ring.len();
    }
    let last = [ring[0], ring[1], ring[2]];
    if !all_left(points, last) {
        return Err(OutlineError::NearlyDegenerate { vertex: last[0] });
    }
    triangles.push(last);
    Ok(triangles)
}

/// Whether the triangle `t` turns left at all three corners.
fn all_left(points: &[Vector2<f64>], [a, b, c]: [usize; 3]) -> bool {
    let (a, b, c) = (points[a], points[b], points[c]);
    turn(a, b, c) == Turn::Left && turn(b, c, a) == Turn::Left && turn(c, a, b) == Turn::Left
}

/// Whether vertex `ring[k]` is an ear of the polygon `ring`: its triangle
/// with its neighbours turns left at every corner and no vertex of the
/// ring that is not convex lies inside it or on its boundary.
fn is_ear(points: &[Vector2<f64>], ring: &[usize], k: usize) -> bool {
    let m = ring.len();
    let (ia, ib, ic) = (ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
    if !all_left(points, [ia, ib, ic]) {
        return false;
    }
    let (a, b, c) = (points[ia], points[ib], points[ic]);
    (0..m).all(|j| {
        let ip = ring[j];
        if ip == ia || ip == ib || ip == ic {
            return true;
        }
        let convex = turn(
            points[ring[(j + m - 1) % m]],
            points[ip],
            points[ring[(j + 1) % m]],
        ) == Turn::Left;
        let p = points[ip];
        let inside = turn(a, b, p) != Turn::Right
            && turn(b, c, p) != Turn::Right
            && turn(c, a, p) != Turn::Right;
        convex || !inside
    })
}

/// Hertel–Mehlhorn: the triangles merged across every diagonal whose
/// removal leaves both of its ends convex; pieces counter-clockwise.
fn merge(points: &[Vector2<f64>], triangles: Vec<[usize; 3]>) -> Vec<Vec<usize>> {
    let mut pieces: Vec<Option<Vec<usize>>> = triangles.iter().map(|t| Some(t.to_vec())).collect();
    // Which piece holds each directed edge.
    let mut owner: HashMap<(usize, usize), usize> = HashMap::new();
    let mut diagonals = Vec::new();
    for (id, t) in triangles.iter().enumerate() {
        for e in 0..3 {
            let (u, v) = (t[e], t[(e + 1) % 3]);
            owner.insert((u, v), id);
            if owner.contains_key(&(v, u)) {
                diagonals.push((v, u));
            }
        }
    }
    for (u, v) in diagonals {
        let (p, q) = (owner[&(u, v)], owner[&(v, u)]);
        let (pp, qq) = (
            pieces[p].as_ref().expect("live piece"),
            pieces[q].as_ref().expect("live piece"),
        );
        let (np, nq) = (pp.len(), qq.len());
        let pu = pp.iter().position(|&x| x == u).expect("edge of p");
        let qv = qq.iter().position(|&x| x == v).expect("edge of q");
        // p runs … u → v …, q runs … v → u …; removing u v joins them.
        let keeps_u = turn(
            points[pp[(pu + np - 1) % np]],
            points[u],
            points[qq[(qv + 2) % nq]],
        );
        let keeps_v = turn(
            points[qq[(qv + nq - 1) % nq]],
            points[v],
            points[pp[(pu + 2) % np]],
        );
        if keeps_u != Turn::Left || keeps_v != Turn::Left {
            continue;
        }
        // p from v round to u, then q's vertices strictly between u and v.
        let mut merged: Vec<usize> = (1..=np).map(|k| pp[(pu + k) % np]).collect();
        merged.extend((2..nq).map(|k| qq[(qv + k) % nq]));
        owner.remove(&(u, v));
        owner.remove(&(v, u));
        for k in 0..merged.len() {
            owner.insert((merged[k], merged[(k + 1) % merged.len()]), p);
        }
        pieces[p] = Some(merged);
        pieces[q] = None;
    }
    pieces.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outline(points: &[[f64; 2]]) -> Vec<Vector2<f64>> {
        points.iter().map(|p| Vector2::new(p[0], p[1])).collect()
    }

    /// Twice the shoelace area of an outline, written here apart from the
    /// shape code.
    fn shoelace(points: &[Vector2<f64>]) -> f64 {
        let n = points.len();
        (0..n)
            .map(|i| points[i].x * points[(i + 1) % n].y - points[(i + 1) % n].x * points[i].y)
            .sum::<f64>()
            / 2.0
    }

    fn star(tips: usize, outer: f64, inner: f64) -> Vec<Vector2<f64>> {
        (0..2 * tips)
            .map(|k| {
                let r = if k % 2 == 0 { outer } else { inner };
                let a = std::f64::consts::PI * k as f64 / tips as f64;
                Vector2::new(r * a.cos(), r * a.sin())
            })
            .collect()
    }

    #[test]
    fn an_l_is_two_parts() {
        let l = outline(&[[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]]);
        let parts = convex_parts(&l).unwrap();
        assert_eq!(parts.len(), 2);
        let area: f64 = parts.iter().map(|p| p.area()).sum();
        assert_eq!(area, 3.0);
    }

    #[test]
    fn a_convex_outline_is_itself() {
        let square = outline(&[[0., 0.], [1., 0.], [1., 1.], [0., 1.]]);
        assert_eq!(convex_parts(&square).unwrap().len(), 1);
        assert!(matches!(
            Shape::simple_polygon(&square),
            Ok(Shape::Polygon(_))
        ));
    }

    #[test]
    fn a_star_is_cut_into_convex_parts_of_its_area() {
        let s = star(5, 1.0, 0.4);
        let parts = convex_parts(&s).unwrap();
        // Each of the 5 reflex vertices needs a diagonal: at least 5 parts
        // (a tip and its neighbours' share), at most 4 × that and ≤ n − 2.
        assert!((5..=8).contains(&parts.len()), "{}", parts.len());
        let area: f64 = parts.iter().map(|p| p.area()).sum();
        assert!((area - shoelace(&s)).abs() < 1e-14, "{area}");
        let Shape::Compound(c) = Shape::simple_polygon(&s).unwrap() else {
            panic!("a star is a compound")
        };
        assert_eq!(c.parts().len(), parts.len());
    }

    #[test]
    fn a_comb_of_many_teeth_is_cut_and_keeps_its_area() {
        // 20 teeth [k + 0.5, k + 1] × [1, 2] on a 20 × 1 base: every
        // notch corner reflex.
        let mut points = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 2.0]];
        for k in (0..20).rev() {
            let x = k as f64;
            points.extend([[x + 0.5, 2.0], [x + 0.5, 1.0], [x, 1.0]]);
            if k > 0 {
                points.push([x, 2.0]);
            }
        }
        let comb = outline(&points);
        let parts = convex_parts(&comb).unwrap();
        let area: f64 = parts.iter().map(|p| p.area()).sum();
        assert!((area - shoelace(&comb)).abs() < 1e-12, "{area}");
        assert!(parts.len() <= comb.len() - 2);
    }

    #[test]
    fn bad_outlines_name_what_is_wrong() {
        let bowtie = outline(&[[0., 0.], [1., 1.], [1., 0.], [0., 1.]]);
        assert_eq!(
            convex_parts(&bowtie).unwrap_err(),
            OutlineError::SelfIntersecting { edge: 0, other: 2 }
        );
        let cw = outline(&[[0., 0.], [0., 1.], [1., 1.], [1., 0.]]);
        assert_eq!(
            convex_parts(&cw).unwrap_err(),
            OutlineError::Clockwise { vertex: 0 }
        );
        let flat = outline(&[[0., 0.], [1., 0.], [2., 0.]]);
        assert_eq!(
            convex_parts(&flat).unwrap_err(),
            OutlineError::CollinearVertex { vertex: 0 }
        );
        let pinched = outline(&[[0., 0.], [2., 0.], [1., 1.], [2., 2.], [0., 2.], [1., 1.]]);
        assert_eq!(
            convex_parts(&pinched).unwrap_err(),
            OutlineError::RepeatedVertex {
                first: 2,
                second: 5
            }
        );
        // A vertex resting on another edge: touching counts as crossing.
        let touching = outline(&[[0., 0.], [2., 0.], [2., 2.], [1., 0.], [0., 2.]]);
        assert!(matches!(
            convex_parts(&touching).unwrap_err(),
            OutlineError::SelfIntersecting { .. }
        ));
        let nan = outline(&[[0., 0.], [f64::NAN, 0.], [0., 1.]]);
        assert_eq!(
            convex_parts(&nan).unwrap_err(),
            OutlineError::NonFinite { vertex: 1 }
        );
        assert_eq!(
            convex_parts(&outline(&[[0., 0.], [1., 0.]])).unwrap_err(),
            OutlineError::TooFewVertices { count: 2 }
        );
    }

    #[test]
    fn huge_and_tiny_outlines_are_cut_alike() {
        let l = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];
        for s in [1e-300, 1e300] {
            let scaled: Vec<[f64; 2]> = l.iter().map(|p| [p[0] * s, p[1] * s]).collect();
            assert_eq!(
                convex_parts(&outline(&scaled)).unwrap().len(),
                2,
                "scale {s}"
            );
        }
    }
}
