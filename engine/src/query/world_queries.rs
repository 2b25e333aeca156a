//! The queries as methods of [`World`]: input checks, candidates from
//! [`super::source`], exact answers from [`crate::collision::ray`] and
//! [`crate::collision::minkowski`].

use super::source::Source;
use super::{RayHit, ShapeCastHit, ShapeDistance, ShapeRef};
use crate::collision::Aabb;
use crate::collision::convex::{ConvexProxy, piece_count, piece_proxy};
use crate::collision::minkowski::{overlap, separation, shape_cast};
use crate::collision::ray::{ProxyRayHit, contains, ray_cast, starts_behind};
use crate::error::{EngineError, Result, require_finite};
use crate::filter::QueryFilter;
use crate::shape::Shape;
use crate::world::World;
use nalgebra::{Isometry2, Vector2};
use smallvec::SmallVec;

/// Checks that both components of a point or vector are finite. The
/// error's text is written only on failure: a query allocates nothing
/// when its input is good.
fn require_finite_vector(what: &str, v: Vector2<f64>) -> Result<Vector2<f64>> {
    if v.x.is_finite() && v.y.is_finite() {
        return Ok(v);
    }
    require_finite(format!("{what} (x)"), v.x)?;
    require_finite(format!("{what} (y)"), v.y)?;
    Ok(v)
}

/// Checks a pose: finite translation, a finite unit rotation.
fn require_pose(pose: &Isometry2<f64>) -> Result<()> {
    require_finite_vector("query shape position", pose.translation.vector)?;
    let (re, im) = (pose.rotation.re, pose.rotation.im);
    require_finite("query shape rotation (cos)", re)?;
    require_finite("query shape rotation (sin)", im)?;
    let norm = (re * re + im * im).sqrt();
    if (norm - 1.0).abs() > 1e-9 {
        return Err(EngineError::InvalidParameter {
            what: "query shape rotation (|(cos, sin)|)".into(),
            value: norm,
            reason: "must be a unit complex number (build it with Isometry2::new)",
        });
    }
    Ok(())
}

/// The unit direction of a ray, refusing a zero or non-finite one.
fn unit_direction(direction: Vector2<f64>) -> Result<Vector2<f64>> {
    require_finite_vector("ray direction", direction)?;
    let length = direction.norm();
    if length == 0.0 || !length.is_finite() {
        return Err(EngineError::InvalidParameter {
            what: "ray direction length".into(),
            value: length,
            reason: "must be finite and > 0",
        });
    }
    Ok(direction / length)
}

/// The proxies of a query shape's convex pieces at `pose` (one, inline,
/// for a circle or a polygon: no allocation).
fn query_proxies(shape: &Shape, pose: &Isometry2<f64>) -> SmallVec<[ConvexProxy; 1]> {
    (0..piece_count(shape))
        .map(|k| piece_proxy(shape, k, pose).expect("k < piece count"))
        .collect()
}

/// The box around several proxies.
fn union_box(proxies: &[ConvexProxy]) -> Aabb {
    proxies
        .iter()
        .map(ConvexProxy::aabb)
        .reduce(|a, b| a.merged(&b))
        .expect("a shape has a piece")
}

impl World {
    fn source(&self, filter: QueryFilter) -> Source<'_> {
        let (core, soft) = self.query_view();
        Source { core, soft, filter }
    }

    /// The nearest shape the ray from `origin` (m) along `direction` (any
    /// non-zero length; normalized) meets within `max_distance` (m, ≥ 0;
    /// may be infinite), with the filter's approval. Shapes containing the
    /// origin are skipped.
    ///
    /// A chain's segment is hit only from its solid side, as Box2D casts
    /// rays at chain segments (`b2RayCastSegment` called one-sided): a ray
    /// whose origin lies strictly behind the segment's line (left of
    /// `point2 − point1`, the side shapes are not pushed towards) passes
    /// through it, wherever it is going; from the front, or from on the
    /// line, it hits, with the segment's normal facing the ray. So a ray
    /// cast up from under a ground chain listed right to left reaches what
    /// stands on it, and one cast down from above stops on the chain.
    /// Errors: a non-finite origin or direction, a
    /// zero direction, a negative or NaN distance.
    pub fn cast_ray(
        &self,
        origin: Vector2<f64>,
        direction: Vector2<f64>,
        max_distance: f64,
        filter: QueryFilter,
    ) -> Result<Option<RayHit>> {
        let (origin, dir) = self.check_ray(origin, direction, max_distance)?;
        let source = self.source(filter);
        let mut best: Option<RayHit> = None;
        source.along_ray(origin, dir, max_distance, |shape, max_t| {
            if let Some(hit) = piece_ray(&source, shape, origin, dir, max_t) {
                let better = best.is_none_or(|b| (hit.t, shape) < (b.distance, b.shape));
                if better {
                    best = Some(ray_hit(shape, origin, dir, hit));
                }
            }
            best.map_or(max_t, |b| b.distance)
        });
        Ok(best)
    }

    /// Every shape the ray meets within `max_distance` (m), nearest first
    /// (ties by body and part), each once; same inputs and errors as
    /// [`World::cast_ray`].
    pub fn cast_ray_all(
        &self,
        origin: Vector2<f64>,
        direction: Vector2<f64>,
        max_distance: f64,
        filter: QueryFilter,
    ) -> Result<Vec<RayHit>> {
        let (origin, dir) = self.check_ray(origin, direction, max_distance)?;
        let source = self.source(filter);
        let mut hits = Vec::new();
        source.along_ray(origin, dir, max_distance, |shape, max_t| {
            if let Some(hit) = piece_ray(&source, shape, origin, dir, max_t) {
                hits.push(ray_hit(shape, origin, dir, hit));
            }
            max_t
        });
        hits.sort_by(|a, b| {
            a.distance
                .total_cmp(&b.distance)
                .then(a.shape.cmp(&b.shape))
        });
        Ok(hits)
    }

    fn check_ray(
        &self,
        origin: Vector2<f64>,
        direction: Vector2<f64>,
        max_distance: f64,
    ) -> Result<(Vector2<f64>, Vector2<f64>)> {
        require_finite_vector("ray origin", origin)?;
        let dir = unit_direction(direction)?;
        if max_distance.is_nan() || max_distance < 0.0 {
            return Err(EngineError::InvalidParameter {
                what: "ray maximum distance".into(),
                value: max_distance,
                reason: "must be >= 0 (infinity allowed)",
            });
        }
        Ok((origin, dir))
    }

    /// The first shape that `shape`, placed at `pose` and moved by
    /// `translation` (m), touches, with the fraction of the translation
    /// covered then. Shapes it overlaps (or touches) at the start are
    /// skipped. A compound query shape is swept part by part. Errors: a
    /// non-finite pose or translation.
    pub fn cast_shape(
        &self,
        shape: &Shape,
        pose: Isometry2<f64>,
        translation: Vector2<f64>,
        filter: QueryFilter,
    ) -> Result<Option<ShapeCastHit>> {
        require_pose(&pose)?;
        require_finite_vector("shape cast translation", translation)?;
        let moving = query_proxies(shape, &pose);
        let start = union_box(&moving);
        let end = Aabb::new(start.min + translation, start.max + translation);
        let swept = start.merged(&end);
        let source = self.source(filter);
        let mut best: Option<ShapeCastHit> = None;
        source.overlapping(&swept, |s| {
            let target = source.proxy(s);
            for m in &moving {
                // A piece overlapping (or touching) at the start is skipped:
                // `shape_cast` reports nothing then (its ray starts inside
                // the Minkowski difference).
                if let Some(hit) = shape_cast(m, &target, translation) {
                    let better = best.is_none_or(|b| (hit.fraction, s) < (b.fraction, b.shape));
                    if better {
                        best = Some(ShapeCastHit {
                            shape: s,
                            fraction: hit.fraction,
                            point: hit.point,
                            normal: hit.normal,
                        });
                    }
                }
            }
        });
        Ok(best)
    }

    /// The shapes overlapping the box `[min, max]` (m; touching counts),
    /// by body and part: their exact geometry, not only their bounding
    /// box. Errors: a non-finite corner, or `min > max` on an axis.
    pub fn overlap_aabb(
        &self,
        min: Vector2<f64>,
        max: Vector2<f64>,
        filter: QueryFilter,
    ) -> Result<Vec<ShapeRef>> {
        require_finite_vector("box minimum corner", min)?;
        require_finite_vector("box maximum corner", max)?;
        for axis in 0..2 {
            if min[axis] > max[axis] {
                return Err(EngineError::InvalidParameter {
                    what: format!("box extent along {}", ["x", "y"][axis]),
                    value: max[axis] - min[axis],
                    reason: "the maximum corner must not be below the minimum one",
                });
            }
        }
        let corners = [
            min,
            Vector2::new(max.x, min.y),
            max,
            Vector2::new(min.x, max.y),
        ];
        // A degenerate box (zero width or height) is a segment or a point:
        // keep its distinct corners as the core.
        let mut vertices: smallvec::SmallVec<[Vector2<f64>; 16]> = smallvec::SmallVec::new();
        for c in corners {
            if !vertices.contains(&c) {
                vertices.push(c);
            }
        }
        let query = ConvexProxy {
            vertices,
            radius: 0.0,
        };
        let source = self.source(filter);
        let mut found = Vec::new();
        source.overlapping(&Aabb::new(min, max), |s| {
            let target = source.proxy(s);
            // A degenerate box (a segment, a point) works too: the
            // target's core makes the difference a polygon or a rounded core.
            let hit = overlap(&query, &target);
            if hit {
                found.push(s);
            }
        });
        found.sort();
        found.dedup();
        Ok(found)
    }

    /// The shapes that `shape` at `pose` overlaps (touching counts), by
    /// body and part. Errors: a non-finite pose.
    pub fn overlap_shape(
        &self,
        shape: &Shape,
        pose: Isometry2<f64>,
        filter: QueryFilter,
    ) -> Result<Vec<ShapeRef>> {
        require_pose(&pose)?;
        let query = query_proxies(shape, &pose);
        let source = self.source(filter);
        let mut found = Vec::new();
        source.overlapping(&union_box(&query), |s| {
            let target = source.proxy(s);
            if query.iter().any(|q| overlap(q, &target)) {
                found.push(s);
            }
        });
        found.sort();
        found.dedup();
        Ok(found)
    }

    /// The shapes containing `point` (m; on the boundary counts), by body
    /// and part. Errors: a non-finite point.
    pub fn shapes_at_point(
        &self,
        point: Vector2<f64>,
        filter: QueryFilter,
    ) -> Result<Vec<ShapeRef>> {
        require_finite_vector("query point", point)?;
        let source = self.source(filter);
        let mut found = Vec::new();
        source.overlapping(&Aabb::new(point, point), |s| {
            if contains(&source.proxy(s), point) {
                found.push(s);
            }
        });
        found.sort();
        found.dedup();
        Ok(found)
    }

    /// The world's shape nearest to `shape` at `pose`, among those within
    /// `max_distance` (m, finite, ≥ 0) of it, with the signed distance,
    /// the two nearest points and the normal ([`ShapeDistance`]); an
    /// overlapping shape has a negative distance (minus its penetration
    /// depth), so the deepest overlap wins. Ties go to the lower body and
    /// part. Errors: a non-finite pose, a negative or non-finite distance.
    pub fn closest_shape(
        &self,
        shape: &Shape,
        pose: Isometry2<f64>,
        max_distance: f64,
        filter: QueryFilter,
    ) -> Result<Option<ShapeDistance>> {
        require_pose(&pose)?;
        crate::error::require_non_negative("closest shape maximum distance", max_distance)?;
        let query = query_proxies(shape, &pose);
        let source = self.source(filter);
        let mut best: Option<ShapeDistance> = None;
        source.overlapping(&union_box(&query).loosened(max_distance), |s| {
            let target = source.proxy(s);
            for q in &query {
                let sep = separation(q, &target);
                if sep.distance > max_distance {
                    continue;
                }
                let better = best.is_none_or(|b| (sep.distance, s) < (b.distance, b.shape));
                if better {
                    best = Some(ShapeDistance {
                        shape: s,
                        distance: sep.distance,
                        point_on_shape: sep.point_b,
                        point_on_query: sep.point_a,
                        normal: sep.normal,
                    });
                }
            }
        });
        Ok(best)
    }
}

/// Where the ray meets piece `shape`, chain segments one-sided (see
/// [`World::cast_ray`]).
fn piece_ray(
    source: &Source<'_>,
    shape: ShapeRef,
    origin: Vector2<f64>,
    dir: Vector2<f64>,
    max_t: f64,
) -> Option<ProxyRayHit> {
    let proxy = source.proxy(shape);
    if source.is_chain_segment(shape) && starts_behind(&proxy, origin) {
        return None;
    }
    ray_cast(&proxy, origin, dir, max_t)
}

/// The public hit of a proxy hit.
fn ray_hit(shape: ShapeRef, origin: Vector2<f64>, dir: Vector2<f64>, hit: ProxyRayHit) -> RayHit {
    RayHit {
        shape,
        distance: hit.t,
        point: origin + hit.t * dir,
        normal: hit.normal,
    }
}
