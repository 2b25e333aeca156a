//! World queries: ask a [`World`](crate::World) what lies along a ray,
//! under a swept shape, inside a box or a shape, at a point, or nearest a
//! shape, without stepping it.
//!
//! ```
//! use etalon2d::prelude::*;
//! let mut world = World::with_model(
//!     Method::SemiImplicitEuler,
//!     ContactModel::SoftStep(SoftStepSettings::default()),
//! )?;
//! let ground = world.add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(Shape::rectangle(20.0, 1.0)?)))?;
//! // Straight down from 10 m above the ground's top face (y = 0.5 m).
//! let hit = world
//!     .cast_ray(Vector2::new(1.0, 10.5), Vector2::new(0.0, -1.0), 100.0, QueryFilter::DEFAULT)?
//!     .expect("the ray meets the ground");
//! assert_eq!(hit.shape.body, ground);
//! assert_eq!(hit.distance, 10.0); // m
//! assert_eq!(hit.normal, Vector2::new(0.0, 1.0));
//! # Ok::<(), EngineError>(())
//! ```
//!
//! **What is searched.** Every convex piece of every body's shape (a
//! compound's parts one by one, a chain's solid segments one by one, each
//! named by a [`ShapeRef`]) that the query's
//! [`QueryFilter`](crate::QueryFilter) accepts. Under the soft step the
//! candidates come from its broad phase, the dynamic AABB trees it keeps
//! anyway (a ray walks the trees nearer child first, both axes of its box
//! test in one SIMD register, and stops descending past the nearest hit so
//! far, as in the module `collision::dynamic_tree::ray`; a box or a shape
//! queries them with its box); under the exact
//! model, made for a few bodies, every piece is tested against its own
//! box, a linear scan. The fat boxes only select candidates: every answer
//! is computed on the exact geometry at the bodies' current poses.
//!
//! **Chains.** A chain's segment is a core of its two points with radius
//! 0. Rays hit it only from its solid side, as Box2D's
//! (see [`World::cast_ray`](crate::World::cast_ray)); the other queries
//! see it as a two-sided line, as Box2D's shape casts and overlap tests
//! do (a swept shape coming from behind a ground chain stops on it; the
//! soft step would push it through, but a query answers geometry). A point
//! is inside a segment only on it: a chain bounds no area.
//!
//! **How.** Every piece, and every query shape, becomes one convex proxy
//! (`collision::convex`, shared with the continuous collision): a core (a
//! point, a segment or a convex polygon) inflated by a radius (a circle is
//! a point of radius r, a polygon its vertices with radius 0, a capsule or
//! a rounded polygon its core with its radius). A ray meets a proxy in
//! closed form (module `collision::ray`); two proxies are compared through
//! their Minkowski difference built explicitly (`collision::minkowski`): the
//! signed distance, the witness points and the time of impact of a swept
//! shape are then a point-to-polygon distance and a ray cast, exact up to
//! rounding without iterations. The harness case `queries_parry` checks
//! them against parry2d on 100 000 random queries.
//!
//! **Cost.** A query allocates nothing but what it returns (the overlap
//! lists, `cast_ray_all`'s hits; a compound query shape's pieces). A
//! candidate's proxy is built from its body's pose when tested (one
//! `sin_cos` and its vertices transformed, in the world frame, so that
//! every query reads the same geometry bit for bit); a ray's tree walk
//! tests many more boxes than pieces, which is why the box test is the
//! tuned part. A ray's inside test (the start point inside a piece) runs only
//! when the piece is entered, since the answer is then dropped either way;
//! a shape cast's overlap test at the start is the inside test of its ray
//! cast on the Minkowski difference, so it is not computed separately.
//!
//! **Conventions.** World frame, SI units: lengths and distances in m, a
//! shape cast's time of impact as the fraction of the translation covered.
//! A normal is a unit vector on the surface of the world's shape, pointing
//! out of it (towards where the ray came from, towards the query shape).
//! A ray or a swept shape that starts inside (or touching) a piece does
//! not report it, as in Box2D; [`World::overlap_shape`](crate::World::overlap_shape)
//! and [`World::closest_shape`](crate::World::closest_shape) do. Touching
//! counts as overlapping. Results are ordered: by distance (then body and
//! part) for [`World::cast_ray_all`](crate::World::cast_ray_all), by body
//! and part for the overlap queries.
//!
//! **Filters.** A piece is reported when `filter.accepts(&its filter)`
//! ([`QueryFilter::accepts`](crate::QueryFilter::accepts), Box2D's
//! `b2QueryFilter`).

mod source;
mod world_queries;

#[cfg(test)]
mod tests;

use crate::body::BodyId;
use nalgebra::Vector2;

/// One convex piece of a body's shape: the shape itself (part 0) or one
/// part of a compound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ShapeRef {
    /// The body.
    pub body: BodyId,
    /// The index of the compound part or of the chain's solid segment
    /// ([`Chain::segment`](crate::shape::Chain::segment)); 0 for any other
    /// shape.
    pub part: usize,
}

/// Where a ray meets a shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// The piece hit.
    pub shape: ShapeRef,
    /// Distance from the ray's origin along its (unit) direction (m).
    pub distance: f64,
    /// The hit point, on the piece's surface (m).
    pub point: Vector2<f64>,
    /// The piece's outward unit normal at the hit point.
    pub normal: Vector2<f64>,
}

/// Where a swept shape first touches a shape of the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeCastHit {
    /// The piece touched.
    pub shape: ShapeRef,
    /// The fraction of the translation covered at the first touch, in
    /// [0, 1]: the swept shape then sits at its start pose moved by
    /// `fraction · translation`.
    pub fraction: f64,
    /// The touching point, on the piece's surface (m).
    pub point: Vector2<f64>,
    /// The piece's outward unit normal at the touching point.
    pub normal: Vector2<f64>,
}

/// How far a query shape is from one shape of the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeDistance {
    /// The world's piece.
    pub shape: ShapeRef,
    /// Signed distance (m): the gap between the two surfaces when > 0,
    /// minus the penetration depth (the shortest translation of the query
    /// shape that separates them) when < 0, 0 when touching.
    pub distance: f64,
    /// The point of the world piece's surface nearest the query shape
    /// (deepest inside it when they overlap), m.
    pub point_on_shape: Vector2<f64>,
    /// The point of the query shape's surface nearest the piece (deepest
    /// inside it when they overlap), m.
    pub point_on_query: Vector2<f64>,
    /// The piece's outward unit normal at `point_on_shape`, pointing
    /// towards the query shape: moving the query shape by
    /// `-distance · normal` makes them touch.
    pub normal: Vector2<f64>,
}
