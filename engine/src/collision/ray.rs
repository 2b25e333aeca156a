//! A ray against one [`ConvexProxy`]: where it first enters the core
//! inflated by the radius.
//!
//! The inflated shape is the union of the core, one rectangle per core
//! edge (the edge pushed out by the radius) and one disc per core vertex.
//! The first entry into a union is the earliest entry into its pieces, and
//! only two kinds of entry can be first: through a flat face (an edge
//! pushed out by r, found by clipping the ray against the offset edge
//! planes, Cyrus–Beck, and kept only if it lies within that edge's extent)
//! or through a vertex disc (a closed-form ray–circle intersection). With
//! r = 0 the clip alone is the answer (a polygon); with a single core
//! vertex the disc alone (a circle). Exact up to rounding: no iteration.
//!
//! A ray that starts inside (or on) the shape reports nothing, as Box2D's
//! world ray casts do.

use super::convex::ConvexProxy;
use nalgebra::Vector2;

/// Where a ray enters a proxy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ProxyRayHit {
    /// Distance along the unit direction (m).
    pub t: f64,
    /// Outward unit normal of the proxy at the hit point.
    pub normal: Vector2<f64>,
    /// The core feature hit: the point `(1 − u) v[edge] + u v[edge + 1]`
    /// of the core lies at `hit − radius · normal` (u = 0 for a vertex).
    pub edge: usize,
    /// See `edge`.
    pub u: f64,
}

/// The first entry of the ray `origin + t dir`, 0 ≤ t ≤ `max_t` (m;
/// `dir` a unit vector), into `proxy`; `None` when it misses or starts
/// inside.
pub(crate) fn ray_cast(
    proxy: &ConvexProxy,
    origin: Vector2<f64>,
    dir: Vector2<f64>,
    max_t: f64,
) -> Option<ProxyRayHit> {
    let v = &proxy.vertices;
    let n = v.len();
    let r = proxy.radius;
    let mut best: Option<ProxyRayHit> = None;
    if n >= 2 {
        best = flat_entry(proxy, origin, dir, max_t);
    }
    if r > 0.0 {
        for (k, c) in v.iter().enumerate() {
            let limit = best.map_or(max_t, |b| b.t);
            match ray_circle(origin, dir, *c, r) {
                Some(t) if t <= limit => {
                    let normal = (origin + t * dir - c) / r;
                    best = Some(ProxyRayHit {
                        t,
                        normal,
                        edge: k,
                        u: 0.0,
                    });
                }
                _ => {}
            }
        }
    }
    // A ray starting inside (or on) the proxy reports nothing. Tested last,
    // and only when there is an entry to discard: the answer is the same
    // as testing first, and most candidates a ray's box test passes are
    // missed.
    if best.is_some() && contains(proxy, origin) {
        return None;
    }
    best
}

/// The entry through a flat face: the ray clipped against every offset
/// edge plane `n_k · x ≤ n_k · v_k + r`; the entering plane's face if the
/// entry point lies within its edge's extent (always, when r = 0).
fn flat_entry(
    proxy: &ConvexProxy,
    origin: Vector2<f64>,
    dir: Vector2<f64>,
    max_t: f64,
) -> Option<ProxyRayHit> {
    let v = &proxy.vertices;
    let n = v.len();
    let r = proxy.radius;
    let (mut lower, mut upper) = (0.0, max_t);
    let mut entering = None;
    for k in 0..n {
        let normal = proxy.edge_normal(k);
        let gap = normal.dot(&v[k]) + r - normal.dot(&origin);
        let rate = normal.dot(&dir);
        if rate == 0.0 {
            if gap < 0.0 {
                return None; // parallel to the plane, outside it
            }
        } else {
            let t = gap / rate;
            if rate < 0.0 {
                if t > lower || entering.is_none() && t >= lower {
                    lower = t;
                    entering = Some((k, normal));
                }
            } else if t < upper {
                upper = t;
            }
            if lower > upper {
                return None;
            }
        }
    }
    let (k, normal) = entering?;
    let edge = v[(k + 1) % n] - v[k];
    let core_point = origin + lower * dir - r * normal;
    let u = (core_point - v[k]).dot(&edge) / edge.norm_squared();
    // A corner region: the vertex discs decide. A bare segment (2
    // vertices, r = 0) has no discs, and its two edge planes are the same
    // line, unbounded along it: past its ends the ray misses.
    if (r > 0.0 || n == 2) && !(0.0..=1.0).contains(&u) {
        return None;
    }
    Some(ProxyRayHit {
        t: lower,
        normal,
        edge: k,
        u: u.clamp(0.0, 1.0),
    })
}

/// The entry distance of the ray `origin + t dir` (unit `dir`) into the
/// circle of `centre` and `radius`, t ≥ 0; `None` if it misses or starts
/// inside.
fn ray_circle(
    origin: Vector2<f64>,
    dir: Vector2<f64>,
    centre: Vector2<f64>,
    radius: f64,
) -> Option<f64> {
    let m = origin - centre;
    let b = m.dot(&dir);
    let c = m.norm_squared() - radius * radius;
    if c <= 0.0 || b > 0.0 {
        return None;
    }
    // The half chord squared, r² − |offset of the line from the centre|²:
    // not b² − c, which cancels between two squares of the origin's
    // distance (~1e-13 m² of rounding 30 m away) where a grazing ray's
    // half chord is small (Haines et al., "Precision improvements for
    // ray/sphere intersection", Ray Tracing Gems, 2019).
    let offset = m - b * dir;
    let disc = radius * radius - offset.norm_squared();
    if disc < 0.0 {
        return None;
    }
    Some((-b - disc.sqrt()).max(0.0))
}

/// Whether `origin` lies strictly behind a segment core `v[0] → v[1]`: on
/// the left of its direction, the side a one-sided (chain) segment does
/// not push shapes towards, where Box2D's one-sided ray cast lets a ray
/// through.
pub(crate) fn starts_behind(segment: &ConvexProxy, origin: Vector2<f64>) -> bool {
    let (p1, p2) = (segment.vertices[0], segment.vertices[1]);
    crate::shape::cross(origin - p1, p2 - p1) < 0.0
}

/// Whether `p` lies in the proxy (closed: on the boundary counts).
pub(crate) fn contains(proxy: &ConvexProxy, p: Vector2<f64>) -> bool {
    let closest = super::minkowski::closest_on_core(&proxy.vertices, p);
    closest.inside || (p - closest.point).norm_squared() <= proxy.radius * proxy.radius
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Shape;
    use nalgebra::Isometry2;

    fn unit_box() -> ConvexProxy {
        ConvexProxy::of(&Shape::rectangle(2.0, 2.0).unwrap(), &Isometry2::identity())
    }

    #[test]
    fn ray_hits_a_box_face_with_its_normal() {
        let hit = ray_cast(&unit_box(), Vector2::new(-5.0, 0.5), Vector2::x(), 10.0).unwrap();
        assert_eq!(hit.t, 4.0);
        assert_eq!(hit.normal, Vector2::new(-1.0, 0.0));
        // Short of the box, pointing away, or starting inside: nothing.
        assert!(ray_cast(&unit_box(), Vector2::new(-5.0, 0.5), Vector2::x(), 3.9).is_none());
        assert!(ray_cast(&unit_box(), Vector2::new(-5.0, 0.5), -Vector2::x(), 10.0).is_none());
        assert!(ray_cast(&unit_box(), Vector2::new(0.2, 0.5), Vector2::x(), 10.0).is_none());
    }

    #[test]
    fn ray_hits_a_circle_and_a_rounded_corner() {
        let circle = ConvexProxy::of(
            &Shape::circle(1.0).unwrap(),
            &Isometry2::translation(3.0, 0.0),
        );
        let hit = ray_cast(&circle, Vector2::zeros(), Vector2::x(), 10.0).unwrap();
        assert_eq!((hit.t, hit.normal), (2.0, Vector2::new(-1.0, 0.0)));
        // A box rounded by 0.5, hit diagonally at its corner (1, 1):
        // the disc there is met at distance |(3,3) - (1,1)| - 0.5.
        let rounded = ConvexProxy {
            radius: 0.5,
            ..unit_box()
        };
        let d = Vector2::new(-1.0, -1.0).normalize();
        let hit = ray_cast(&rounded, Vector2::new(3.0, 3.0), d, 10.0).unwrap();
        // A few roundings on lengths of about 3 m: within 1e-14.
        assert!((hit.t - (8f64.sqrt() - 0.5)).abs() < 1e-14);
        assert!((hit.normal - (-d)).norm() < 1e-14);
        // A flat face of the rounded box.
        let hit = ray_cast(&rounded, Vector2::new(0.0, 5.0), -Vector2::y(), 10.0).unwrap();
        assert_eq!((hit.t, hit.normal), (3.5, Vector2::y()));
    }

    #[test]
    fn ray_through_a_capsule() {
        // A segment core from (-1, 0) to (1, 0) with radius 0.25.
        let capsule = ConvexProxy {
            vertices: smallvec::smallvec![Vector2::new(-1.0, 0.0), Vector2::new(1.0, 0.0)],
            radius: 0.25,
        };
        let hit = ray_cast(&capsule, Vector2::new(0.5, 2.0), -Vector2::y(), 5.0).unwrap();
        assert_eq!((hit.t, hit.normal), (1.75, Vector2::y()));
        let hit = ray_cast(&capsule, Vector2::new(3.0, 0.0), -Vector2::x(), 5.0).unwrap();
        assert_eq!((hit.t, hit.normal), (1.75, Vector2::x()));
    }
}
