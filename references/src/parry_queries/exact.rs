//! Exact checks that decide which side is right when the engine and parry
//! disagree (docs/cases.md case III, "Reference checks"), and the deterministic
//! random convex polygons both are compared on.
//!
//! The checks use only the polygons' world vertices, with no iteration and
//! no tolerance, so they are exact up to round-off:
//! - [`signed_distance_to_polygon`]: a vertex of one polygon inside the
//!   other (signed distance < 0) proves an overlap; it also says how far
//!   parry's witness points lie off the boundaries;
//! - [`overlap_along`]: the penetration depth is the smallest overlap of the
//!   two polygons' projections over all directions, so of two candidate
//!   normals the one along which the projections overlap less is the better
//!   one.
//!
//! [`Rng`] draws the polygons and poses. It builds polygons with the
//! engine's [`ConvexPolygon::convex_hull`] (geometry construction only:
//! nothing here calls the engine's collision code).
//!
//! Units are SI: lengths and distances in m, angles in rad.

use engine::ConvexPolygon;
use nalgebra::{Isometry2, Point2, Vector2};
use std::f64::consts::PI;

/// Which hulls [`Rng::polygon`] accepts. The two callers draw differently
/// and each keeps its own sequence of polygons: both variants consume the
/// generator identically per attempt and differ only in which attempts are
/// kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hull {
    /// Redraw until every one of the k drawn points is a hull vertex, so
    /// the polygon has exactly k vertices, uniform over 3 to 12 (the
    /// harness case `collision_parry`).
    EveryPointAVertex,
    /// Accept the hull of the k drawn points as it comes: at least 3 and at
    /// most k vertices (the `parry_queries` unit tests).
    AsDrawn,
}

/// xorshift64*: deterministic, the same pairs on every machine, so a
/// failing pair can be replayed. The field is the state (the seed).
pub struct Rng(pub u64);

impl Rng {
    /// A uniform number in [0, 1).
    pub fn unit(&mut self) -> f64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        (x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniform number in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// A pose with translation uniform in [−half_width, half_width)² (m)
    /// and rotation uniform in [−π, π) (rad).
    pub fn pose(&mut self, half_width: f64) -> Isometry2<f64> {
        Isometry2::new(
            Vector2::new(
                self.range(-half_width, half_width),
                self.range(-half_width, half_width),
            ),
            self.range(-PI, PI),
        )
    }

    /// A convex polygon: the hull of k = 3 to 12 random points on an
    /// annulus of random size (outer radius 0.2 to 1.5 m, inner 0.85 of
    /// it), re-centred on its centroid as a body's shape is. `hull` says
    /// which hulls are kept (the others are redrawn).
    pub fn polygon(&mut self, hull: Hull) -> ConvexPolygon {
        loop {
            let k = 3 + (self.unit() * 10.0) as usize;
            let scale = self.range(0.2, 1.5);
            let points: Vec<Vector2<f64>> = (0..k)
                .map(|_| {
                    let (t, r) = (self.range(0.0, 2.0 * PI), scale * self.range(0.85, 1.0));
                    Vector2::new(r * t.cos(), r * t.sin())
                })
                .collect();
            if let Ok(p) = ConvexPolygon::convex_hull(&points)
                && (hull == Hull::AsDrawn || p.vertices().len() == k)
            {
                return p.centered();
            }
        }
    }
}

/// A polygon's vertices in world coordinates (m), in its own (CCW) order.
pub fn world_vertices(p: &ConvexPolygon, pose: &Isometry2<f64>) -> Vec<Vector2<f64>> {
    p.vertices()
        .iter()
        .map(|v| pose.transform_point(&Point2::from(*v)).coords)
        .collect()
}

/// Overlap (m) of the projections of A and B (world vertices) on unit axis
/// `n` (from A to B): `max_A n·x − min_B n·x`. The true penetration depth is
/// the smallest overlap over all axes, so of two candidate normals the one
/// with the smaller overlap is the better one.
pub fn overlap_along(wa: &[Vector2<f64>], wb: &[Vector2<f64>], n: &Vector2<f64>) -> f64 {
    let max_a = wa
        .iter()
        .map(|v| n.dot(v))
        .fold(f64::NEG_INFINITY, f64::max);
    let min_b = wb.iter().map(|v| n.dot(v)).fold(f64::INFINITY, f64::min);
    max_a - min_b
}

/// Signed distance (m) of a point to a convex polygon's boundary (world
/// vertices, CCW): > 0 outside, < 0 inside. Exact up to round-off.
pub fn signed_distance_to_polygon(w: &[Vector2<f64>], p: &Vector2<f64>) -> f64 {
    let n = w.len();
    let (mut max_s, mut min_d) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..n {
        let (a, b) = (w[i], w[(i + 1) % n]);
        let e = b - a;
        let normal = Vector2::new(e.y, -e.x) / e.norm();
        max_s = max_s.max(normal.dot(&(p - a)));
        let t = ((p - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
        min_d = min_d.min((p - (a + t * e)).norm());
    }
    if max_s > 0.0 { min_d } else { max_s }
}
