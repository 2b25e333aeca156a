//! Polygon against polygon in A's frame, written once for both contact
//! models: the separating axes, the reference and incident edges, and the
//! incident edge clipped to the reference edge, each clipped point with its
//! separation and the pair of features that made it. The exact model
//! (`polygon_polygon.rs`: exact depth and normal mapped to the world, its
//! persistent features) and the soft step (`soft_step/manifold.rs`:
//! speculative cut-off, the vertex–vertex rule when apart) apply their own
//! policies to what this file finds.
//!
//! **Shapes.** A [`RoundPolygon`] is a convex core of 2 or more vertices
//! (counter-clockwise; 2 make a segment, whose two edges are its two sides)
//! with a radius: the set of points within `radius` of the core. A polygon
//! has radius 0, a capsule is a 2-vertex core with its radius, a rounded box
//! a 4-vertex core with its corner radius. Separations are between the
//! rounded surfaces (the cores' minus the two radii) and each point lies
//! midway between them.
//!
//! **Frame.** B's core is mapped into A's frame by `xf` (B's frame in A's),
//! and both are shifted by an origin of the caller's choice (the soft step
//! takes A's first vertex: round-off then stays relative to the pair, not
//! to where A's frame is). Every point here is in that shifted frame;
//! [`Placed::origin`] maps it back.
//!
//! **Algorithm** (Box2D v3's `b2CollidePolygons` and the separating axis
//! theorem of seed §7.2, written anew):
//!
//! 1. separating axes ([`separating_axes`]): the largest separation of B's
//!    vertices along A's edge normals, and of A's along B's; exactly the
//!    signed distance of the cores when they overlap (−(penetration depth)),
//!    a lower bound of it when apart;
//! 2. the polygon with the larger separation gives the **reference edge**
//!    (A on a tie), the other the **incident edge**, its edge most
//!    anti-parallel to the reference normal ([`Placed::faces`]);
//! 3. the incident edge is clipped to the reference edge's extent along
//!    its tangent ([`Placed::clip`]): two points, each with its separation
//!    from the reference surface, or none when the edges do not face each
//!    other.

use super::feature_id::{Feature, FeatureId};
use nalgebra::{Isometry2, Vector2};

/// A convex core and a radius, in its own frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RoundPolygon<'a> {
    /// The core's vertices, counter-clockwise, 2 or more (m).
    pub vertices: &'a [Vector2<f64>],
    /// `normals[i]`: outward unit normal of the edge from `vertices[i]` to
    /// `vertices[i + 1]` (for 2 vertices, the segment's two sides).
    pub normals: &'a [Vector2<f64>],
    /// Radius around the core (m), 0 for a sharp polygon.
    pub radius: f64,
}

/// Where a clipped point comes from on the incident polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum IncidentPoint {
    /// Vertex i of the incident polygon.
    Vertex(usize),
    /// The incident edge cut by the side plane through the reference edge's
    /// first (0) or second (1) vertex.
    Clip(u8),
}

/// An incident point as a feature of the one scheme.
impl From<IncidentPoint> for Feature {
    fn from(p: IncidentPoint) -> Self {
        match p {
            IncidentPoint::Vertex(i) => Feature::Vertex(i),
            IncidentPoint::Clip(k) => Feature::Clip(k as usize),
        }
    }
}

/// The unused slots of an empty [`Clipped`] read vertex 0.
impl Default for IncidentPoint {
    fn default() -> Self {
        IncidentPoint::Vertex(0)
    }
}

/// Buffers reused by every pair (no allocation once grown): both cores in
/// A's shifted frame.
#[derive(Debug, Clone, Default)]
pub(crate) struct Scratch {
    a_vertices: Vec<Vector2<f64>>,
    b_vertices: Vec<Vector2<f64>>,
    b_normals: Vec<Vector2<f64>>,
}

/// Both cores in A's frame shifted to A's first vertex, with the best
/// separating axis of each.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Placed<'s> {
    /// The shift, A's frame (m): add it to a point here to have it in A's
    /// frame.
    pub origin: Vector2<f64>,
    /// A's vertices, shifted.
    pub a_vertices: &'s [Vector2<f64>],
    /// A's normals.
    pub a_normals: &'s [Vector2<f64>],
    /// B's vertices in A's shifted frame.
    pub b_vertices: &'s [Vector2<f64>],
    /// B's normals in A's frame.
    pub b_normals: &'s [Vector2<f64>],
    /// A's radius (m).
    pub radius_a: f64,
    /// B's radius (m).
    pub radius_b: f64,
    /// A's edge of largest separation of B's core, and that separation (m).
    pub axis_a: (usize, f64),
    /// B's edge of largest separation of A's core, and that separation (m).
    pub axis_b: (usize, f64),
}

/// A reference edge and the incident edge facing it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Faces {
    /// Whether the reference edge is B's (else A's).
    pub flip: bool,
    /// A's edge (reference or incident).
    pub edge_a: usize,
    /// B's edge (reference or incident).
    pub edge_b: usize,
}

/// A point of the incident edge clipped to the reference edge, in A's
/// shifted frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct ClipPoint {
    /// Midway between the two rounded surfaces (m).
    pub point: Vector2<f64>,
    /// The point on the incident core, before it is moved midway (m).
    pub incident: Vector2<f64>,
    /// Signed distance of the rounded surfaces along the normal (m): < 0
    /// overlapping.
    pub separation: f64,
    /// The features behind the point: A's vertex (the reference edge's end
    /// on the point's side, or the incident vertex) and B's
    /// ([`FeatureId::pair`] of two vertices; the soft step's id).
    pub id: FeatureId,
    /// Where the point comes from on the incident polygon.
    pub side: IncidentPoint,
}

/// The incident edge clipped to the reference edge.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Clipped {
    /// Unit normal from A to B, A's frame.
    pub normal: Vector2<f64>,
    /// 2, or 0 when the edges do not face each other.
    pub count: usize,
    /// The points: the reference edge's first side first when A holds it,
    /// its second side first when B does (so that, read from A, the points
    /// run the same way whichever holds it).
    pub points: [ClipPoint; 2],
}

/// The largest separation of `vertices` along the edge normals of the
/// polygon (`reference_vertices`, `reference_normals`), and the edge that
/// gives it; `None` as soon as an edge separates them by more than
/// `beyond`. The values are finite, so the minimum is a plain comparison
/// (`f64::min`'s NaN handling costs two instructions more in this O(n·m)
/// loop; signs of zero do not matter: only comparisons read the result);
/// a NaN vertex leaves a separation of +∞, so non-finite input reports no
/// contact.
#[inline]
fn max_separation(
    reference_vertices: &[Vector2<f64>],
    reference_normals: &[Vector2<f64>],
    vertices: &[Vector2<f64>],
    beyond: f64,
) -> Option<(usize, f64)> {
    let mut best = (0, f64::NEG_INFINITY);
    for (i, (n, v)) in reference_normals.iter().zip(reference_vertices).enumerate() {
        let mut si = f64::INFINITY;
        for w in vertices {
            let d = n.dot(&(w - v));
            if d < si {
                si = d;
            }
        }
        if si > best.1 {
            if si > beyond {
                return None;
            }
            best = (i, si);
        }
    }
    Some(best)
}

/// The separation of `vertices` from the half-plane of edge `edge` of the
/// polygon (`reference_vertices`, `reference_normals`) (m, cores).
pub(crate) fn edge_separation(
    reference_vertices: &[Vector2<f64>],
    reference_normals: &[Vector2<f64>],
    vertices: &[Vector2<f64>],
    edge: usize,
) -> f64 {
    let (v, n) = (reference_vertices[edge], reference_normals[edge]);
    let mut s = f64::INFINITY;
    for w in vertices {
        let d = n.dot(&(w - v));
        if d < s {
            s = d;
        }
    }
    s
}

/// The edge of `normals` most anti-parallel to `direction` (the first on a
/// tie).
#[inline]
pub(crate) fn incident_edge(normals: &[Vector2<f64>], direction: Vector2<f64>) -> usize {
    let mut best = (0, f64::INFINITY);
    for (i, n) in normals.iter().enumerate() {
        let d = direction.dot(n);
        if d < best.1 {
            best = (i, d);
        }
    }
    best.0
}

/// Places `a` and `b` (B's frame mapped into A's by `xf`) in A's frame
/// shifted by `origin` and finds the best separating axis of each; `None`
/// as soon as an axis separates the **cores** by more than `beyond` (m):
/// pass the cut-off distance plus both radii. B's normals are only rotated
/// once A's axes leave the pair in play (most pairs of the broad phase end
/// there).
///
/// `origin` (A's frame, m) is where the shifted frame's origin lies: A's
/// first vertex keeps round-off relative to the pair (the soft step's
/// choice, Box2D's); zero keeps A's frame itself, and with it the bits of
/// the exact model's distances (`v − 0` and `t − 0` are `v` and `t`).
///
/// Inlined (as [`Placed::clip`]) into the soft step's collide stage: a call
/// returns the placement through memory, 14% more instructions in the
/// polygon pairs of the 5050-box pyramid (callgrind).
#[inline(always)]
pub(crate) fn separating_axes<'s>(
    a: &RoundPolygon<'s>,
    b: &RoundPolygon<'_>,
    xf: &Isometry2<f64>,
    origin: Vector2<f64>,
    beyond: f64,
    scratch: &'s mut Scratch,
) -> Option<Placed<'s>> {
    let shift = xf.translation.vector - origin;
    scratch.a_vertices.clear();
    scratch
        .a_vertices
        .extend(a.vertices.iter().map(|v| v - origin));
    scratch.b_vertices.clear();
    scratch
        .b_vertices
        .extend(b.vertices.iter().map(|v| xf.rotation * v + shift));
    let axis_a = max_separation(&scratch.a_vertices, a.normals, &scratch.b_vertices, beyond)?;
    scratch.b_normals.clear();
    scratch
        .b_normals
        .extend(b.normals.iter().map(|n| xf.rotation * n));
    let axis_b = max_separation(
        &scratch.b_vertices,
        &scratch.b_normals,
        &scratch.a_vertices,
        beyond,
    )?;
    Some(Placed {
        origin,
        a_vertices: &scratch.a_vertices,
        a_normals: a.normals,
        b_vertices: &scratch.b_vertices,
        b_normals: &scratch.b_normals,
        radius_a: a.radius,
        radius_b: b.radius,
        axis_a,
        axis_b,
    })
}

impl Placed<'_> {
    /// The larger of the two axes' separations (m, cores): the SAT
    /// separation.
    #[inline]
    pub(crate) fn core_separation(&self) -> f64 {
        if self.axis_a.1 < self.axis_b.1 {
            self.axis_b.1
        } else {
            self.axis_a.1
        }
    }

    /// The reference edge of the best axis (B's when its separation is
    /// larger, A's on a tie) and the incident edge facing it.
    #[inline]
    pub(crate) fn faces(&self) -> Faces {
        let flip = self.axis_a.1 < self.axis_b.1;
        if flip {
            self.faces_on(true, self.axis_b.0)
        } else {
            self.faces_on(false, self.axis_a.0)
        }
    }

    /// Reference edge `edge` of B (`flip`) or of A, and the incident edge
    /// facing it.
    #[inline]
    pub(crate) fn faces_on(&self, flip: bool, edge: usize) -> Faces {
        if flip {
            Faces {
                flip,
                edge_a: incident_edge(self.a_normals, self.b_normals[edge]),
                edge_b: edge,
            }
        } else {
            Faces {
                flip,
                edge_a: edge,
                edge_b: incident_edge(self.b_normals, self.a_normals[edge]),
            }
        }
    }

    /// The core separation along the reference edge of `faces` (m).
    pub(crate) fn separation_on(&self, faces: Faces) -> f64 {
        if faces.flip {
            edge_separation(
                self.b_vertices,
                self.b_normals,
                self.a_vertices,
                faces.edge_b,
            )
        } else {
            edge_separation(
                self.a_vertices,
                self.a_normals,
                self.b_vertices,
                faces.edge_a,
            )
        }
    }

    /// Clips the incident edge of `faces` to the reference edge (Box2D's
    /// `b2ClipPolygons`, written anew): two points, each moved from the
    /// incident core midway between the rounded surfaces, or none when the
    /// edges' extents along the reference tangent do not overlap. Inlined:
    /// a caller that reads only some fields (the soft step) then never
    /// computes or stores the others.
    #[inline(always)]
    pub(crate) fn clip(&self, faces: Faces) -> Clipped {
        // Reference polygon 1, incident polygon 2.
        let (v1, n1, e1, r1, v2, e2, r2) = if faces.flip {
            let (bv, bn) = (self.b_vertices, self.b_normals);
            (
                bv,
                bn,
                faces.edge_b,
                self.radius_b,
                self.a_vertices,
                faces.edge_a,
                self.radius_a,
            )
        } else {
            let (av, an) = (self.a_vertices, self.a_normals);
            (
                av,
                an,
                faces.edge_a,
                self.radius_a,
                self.b_vertices,
                faces.edge_b,
                self.radius_b,
            )
        };
        let (i11, i12) = (e1, (e1 + 1) % v1.len());
        let (i21, i22) = (e2, (e2 + 1) % v2.len());
        let normal = n1[i11];
        let (v11, v12, v21, v22) = (v1[i11], v1[i12], v2[i21], v2[i22]);
        let tangent = Vector2::new(-normal.y, normal.x);
        let (lower1, upper1) = (0.0, (v12 - v11).dot(&tangent));
        // The incident edge runs against the tangent (both are CCW).
        let upper2 = (v21 - v11).dot(&tangent);
        let lower2 = (v22 - v11).dot(&tangent);
        if upper2 < lower1 || upper1 < lower2 {
            return Clipped::default();
        }
        let span = upper2 - lower2;
        let (v_lower, side_lower) = if lower2 < lower1 && span > f64::EPSILON {
            (
                v22 + (lower1 - lower2) / span * (v21 - v22),
                IncidentPoint::Clip(0),
            )
        } else {
            (v22, IncidentPoint::Vertex(i22))
        };
        let (v_upper, side_upper) = if upper2 > upper1 && span > f64::EPSILON {
            (
                v22 + (upper1 - lower2) / span * (v21 - v22),
                IncidentPoint::Clip(1),
            )
        } else {
            (v21, IncidentPoint::Vertex(i21))
        };
        // Midway between the reference surface (r1 out of its core) and
        // the incident one (r2 in from the incident point); the radii are
        // subtracted from the core separation whole so that, with radius 0,
        // the bits are those of the sharp polygon's `v − ½ s n`.
        let (half_offset, radius) = (r1 - r2, r1 + r2);
        let point = |v: Vector2<f64>, side: IncidentPoint, (ia, ib): (usize, usize)| {
            let s = (v - v11).dot(&normal);
            ClipPoint {
                point: v - 0.5 * (s - half_offset) * normal,
                incident: v,
                separation: s - radius,
                id: FeatureId::pair(Feature::Vertex(ia), Feature::Vertex(ib)),
                side,
            }
        };
        if faces.flip {
            Clipped {
                normal: -normal,
                count: 2,
                points: [
                    point(v_upper, side_upper, (i21, i12)),
                    point(v_lower, side_lower, (i22, i11)),
                ],
            }
        } else {
            Clipped {
                normal,
                count: 2,
                points: [
                    point(v_lower, side_lower, (i11, i22)),
                    point(v_upper, side_upper, (i12, i21)),
                ],
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A core's outward unit normals, as both models compute them.
    fn normals(vertices: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
        let n = vertices.len();
        (0..n)
            .map(|i| {
                let e = vertices[(i + 1) % n] - vertices[i];
                Vector2::new(e.y, -e.x).normalize()
            })
            .collect()
    }

    fn square(half: f64) -> Vec<Vector2<f64>> {
        vec![
            Vector2::new(-half, -half),
            Vector2::new(half, -half),
            Vector2::new(half, half),
            Vector2::new(-half, half),
        ]
    }

    /// Clips `a` against `b` placed by `xf`, within `beyond` of the cores;
    /// the points back in A's frame.
    fn collide(
        (va, ra): (&[Vector2<f64>], f64),
        (vb, rb): (&[Vector2<f64>], f64),
        xf: Isometry2<f64>,
        beyond: f64,
    ) -> Option<Clipped> {
        let (na, nb) = (normals(va), normals(vb));
        let a = RoundPolygon {
            vertices: va,
            normals: &na,
            radius: ra,
        };
        let b = RoundPolygon {
            vertices: vb,
            normals: &nb,
            radius: rb,
        };
        let mut scratch = Scratch::default();
        let placed = separating_axes(&a, &b, &xf, va[0], beyond + ra + rb, &mut scratch)?;
        let mut clipped = placed.clip(placed.faces());
        for p in &mut clipped.points {
            p.point += placed.origin;
            p.incident += placed.origin;
        }
        Some(clipped)
    }

    #[test]
    fn rounded_boxes_subtract_both_radii_and_meet_midway_between_surfaces() {
        // Cores of half-width 0.4 with radius 0.1 (a unit box with rounded
        // corners) and 0.05, B's core 0.95 m above A's: the cores are 0.15
        // apart, the surfaces overlap by 0.15 − 0.1 − 0.05 = 0.
        // Sunk by 0.01 more: separation −0.01, points midway between A's
        // surface (y = 0.5) and B's (y = 0.49).
        let (a, b) = (square(0.4), square(0.4));
        let m = collide(
            (&a, 0.1),
            (&b, 0.05),
            Isometry2::translation(0.2, 0.94),
            0.0,
        )
        .unwrap();
        assert_eq!(m.count, 2);
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        // The cores' x-overlap, [−0.2, 0.4], from the reference edge's first
        // vertex (A's top edge runs from x = 0.4 to −0.4).
        let xs = [m.points[0].point.x, m.points[1].point.x];
        assert!(
            (xs[0] - 0.4).abs() < 1e-15 && (xs[1] + 0.2).abs() < 1e-15,
            "{xs:?}"
        );
        for p in &m.points {
            assert!((p.separation + 0.01).abs() < 1e-15, "{p:?}");
            assert!((p.point.y - 0.495).abs() < 1e-15, "{p:?}");
            // The incident point stays on B's core (y = 0.94 − 0.4).
            assert!((p.incident.y - 0.54).abs() < 1e-15, "{p:?}");
        }
        // Within the 0.02 m cut-off at a 0.01 m gap of the surfaces, beyond
        // it at 0.05 m.
        assert!(
            collide(
                (&a, 0.1),
                (&b, 0.05),
                Isometry2::translation(0.0, 0.96),
                0.02
            )
            .is_some()
        );
        assert!(
            collide(
                (&a, 0.1),
                (&b, 0.05),
                Isometry2::translation(0.0, 1.0),
                0.02
            )
            .is_none()
        );
    }

    #[test]
    fn a_capsule_on_a_box_is_a_two_vertex_core_with_a_radius() {
        // A horizontal capsule (core from x = −0.3 to 0.3, radius 0.1) as B,
        // lying 0.005 m into a unit box: its core at y = 0.5 + 0.1 − 0.005.
        let segment = [Vector2::new(-0.3, 0.0), Vector2::new(0.3, 0.0)];
        let b = square(0.5);
        let xf = Isometry2::translation(0.1, 0.595);
        let m = collide((&b, 0.0), (&segment, 0.1), xf, 0.0).unwrap();
        assert_eq!(m.count, 2);
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        let mut xs = [m.points[0].point.x, m.points[1].point.x];
        xs.sort_by(f64::total_cmp);
        assert!(
            (xs[0] + 0.2).abs() < 1e-15 && (xs[1] - 0.4).abs() < 1e-15,
            "{xs:?}"
        );
        for p in &m.points {
            assert!((p.separation + 0.005).abs() < 1e-15, "{p:?}");
            assert!((p.point.y - 0.4975).abs() < 1e-15, "{p:?}");
        }
        // The capsule as A: the same contact seen from the other side.
        let m = collide((&segment, 0.1), (&b, 0.0), xf.inverse(), 0.0).unwrap();
        assert!((m.normal + Vector2::y()).norm() < 1e-15);
        for p in &m.points {
            assert!((p.separation + 0.005).abs() < 1e-15, "{p:?}");
        }
    }

    #[test]
    fn a_tilted_capsule_end_on_a_capsule() {
        // Segments of radius 0.05: A horizontal from x = −1 to 1, B from its
        // origin to (0.5, 0.5), its origin placed 0.08 above A's core at
        // x = 0.25. A's upper side is the reference edge; B's lower side,
        // unclipped, gives its two vertices: the near one 0.08 − 0.1 =
        // −0.02 from A's surface, midway between the surfaces at y = 0.04;
        // the far one 0.58 − 0.1 = 0.48.
        let a = [Vector2::new(-1.0, 0.0), Vector2::new(1.0, 0.0)];
        let b = [Vector2::new(0.0, 0.0), Vector2::new(0.5, 0.5)];
        let xf = Isometry2::translation(0.25, 0.08);
        let m = collide((&a, 0.05), (&b, 0.05), xf, 1.0).unwrap();
        assert_eq!(m.count, 2);
        assert!((m.normal - Vector2::y()).norm() < 1e-15);
        let [far, near] = m.points;
        assert_eq!(
            (near.side, far.side),
            (IncidentPoint::Vertex(0), IncidentPoint::Vertex(1))
        );
        assert!((near.separation + 0.02).abs() < 1e-15, "{near:?}");
        assert!(
            (near.point - Vector2::new(0.25, 0.04)).norm() < 1e-15,
            "{near:?}"
        );
        assert!((far.separation - 0.48).abs() < 1e-15, "{far:?}");
        assert!(
            (far.point - Vector2::new(0.75, 0.29)).norm() < 1e-15,
            "{far:?}"
        );
    }

    #[test]
    fn radius_zero_gives_the_sharp_formulas_bits() {
        // The rounded formulas with radius 0 are the sharp ones bit for bit
        // (the point v − ½ s n, the separation s itself), the property both
        // models' trace tests rely on. Checked in the shifted frame, on
        // either polygon as the reference.
        let (va, vb) = (square(0.5), square(0.45));
        let (na, nb) = (normals(&va), normals(&vb));
        let a = RoundPolygon {
            vertices: &va,
            normals: &na,
            radius: 0.0,
        };
        let b = RoundPolygon {
            vertices: &vb,
            normals: &nb,
            radius: 0.0,
        };
        let xf = Isometry2::new(Vector2::new(0.3137, 0.9071), 0.0123);
        let mut scratch = Scratch::default();
        let placed = separating_axes(&a, &b, &xf, va[0], 0.0, &mut scratch).unwrap();
        for faces in [placed.faces_on(false, 2), placed.faces_on(true, 0)] {
            let m = placed.clip(faces);
            assert_eq!(m.count, 2);
            let (v11, n) = if faces.flip {
                (
                    placed.b_vertices[faces.edge_b],
                    placed.b_normals[faces.edge_b],
                )
            } else {
                (
                    placed.a_vertices[faces.edge_a],
                    placed.a_normals[faces.edge_a],
                )
            };
            for p in &m.points {
                let s = (p.incident - v11).dot(&n);
                assert_eq!(p.separation.to_bits(), s.to_bits());
                assert_eq!(p.point, p.incident - 0.5 * s * n);
            }
        }
    }
}
