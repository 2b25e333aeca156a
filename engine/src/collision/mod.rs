//! Collision detection (seed §7.2, case III of `docs/cases.md`): which pairs of
//! shapes touch, where, how deep, and when in a step they first meet.
//!
//! Everything here is a pure function of shapes and poses. A pose is an
//! [`Isometry2`](nalgebra::Isometry2): the body's position (m, its centre of
//! mass, the origin of its shape's frame) and orientation (rad). Units are SI
//! throughout; lengths are in m, times in s.
//!
//! The pipeline, in the order a world runs it:
//!
//! 1. **Broad phase** ([`broad_phase`], seed §7.2 and Fig. 7.1): the
//!    candidate pairs, those whose axis-aligned bounding boxes ([`aabb`])
//!    overlap, by a sort-and-sweep over x-intervals in O(n log n) (the modern
//!    form of the Fortune-style sweep the seed cites). The brute-force O(n²)
//!    test is kept as its oracle. The exact contact model uses it.
//!
//!    For scenes of thousands of bodies the broad phase must be
//!    incremental: the [`dynamic_tree`] keeps one leaf per shape with a
//!    *fat* box (its box enlarged by a margin, m) in a balanced tree of
//!    box unions. A shape that stays inside its fat box costs nothing; only
//!    a shape that left it is moved in the tree (O(log n)) and queried
//!    against it for new candidate pairs. This is the broad phase of the
//!    soft-step contact model.
//! 2. **Narrow phase** ([`narrow_phase`], seed §7.2, Fig. 7.2–7.6): for each
//!    candidate, the separating axis theorem over the edge normals of both
//!    polygons ([`polygon_polygon`]; boxes take the same path, the seed's
//!    OBB test being that test restricted to two boxes' four normals), and
//!    exact tests for circles ([`polygon_circle`], [`circle_circle`]). A touching pair gives a contact [`Manifold`]: one
//!    normal and up to two points with their depths ([`manifold`]). The
//!    signed distance of any two convex shapes ([`proximity`]) is written
//!    once, on their convex proxies (a core and a radius, `convex.rs`),
//!    through their Minkowski difference (`minkowski.rs`).
//! 3. **Time of impact** ([`time_of_impact`], seed §7.2, Fig. 7.7–7.8): when
//!    a pair interpenetrates at the end of a step, the first time in the step
//!    at which its separation is within a tolerance ε, by the seed's
//!    bisection of the step, or by conservative advancement. The soft
//!    step's continuous sweeps take the time alone, and leave at t = 0 a
//!    pair that a cheap bound already puts within ε (`surely_within.rs`: a
//!    core vertex of one near the other's core).
//!
//! The response (impulses with restitution, seed eq. 7.1–7.16, friction,
//! resting contact) consumes the manifolds; it lives with the world.
//!
//! Conventions, shared by every function of this module:
//! - a normal is a unit vector pointing from shape A (the first argument)
//!   towards shape B;
//! - a depth is > 0 when the shapes interpenetrate, < 0 for a gap (only
//!   reported within a caller's margin);
//! - a signed distance (or separation) is the opposite: > 0 for a gap,
//!   −depth when they overlap, 0 when they touch.

pub mod aabb;
pub mod broad_phase;
pub(crate) mod chain_segment;
pub mod circle_circle;
pub(crate) mod convex;
pub mod dynamic_tree;
pub(crate) mod feature_id;
pub(crate) mod features;
pub mod manifold;
pub(crate) mod minkowski;
pub mod narrow_phase;
pub(crate) mod pair_table;
pub mod polygon_circle;
pub mod polygon_polygon;
pub(crate) mod polygon_polygon_local;
pub(crate) mod ray;
pub(crate) mod rounded_pair;
pub(crate) mod segment_distance;
pub(crate) mod surely_within;
pub mod time_of_impact;

#[cfg(test)]
pub(crate) mod test_rng;

pub use aabb::Aabb;
pub use broad_phase::{SweepAndPrune, brute_force_pairs};
pub use circle_circle::{collide_circle_circle, collide_circle_circle_with_margin};
pub use dynamic_tree::{DynamicTree, ProxyId};
pub use manifold::{Contact, Manifold, ManifoldPoint, Proximity};
pub use narrow_phase::{collide, proximity};
pub use polygon_circle::{collide_polygon_circle, collide_polygon_circle_with_margin};
pub use polygon_polygon::{
    SeparatingAxis, collide_polygon_polygon, collide_polygon_polygon_with_margin,
    separation_polygon_polygon,
};
pub use time_of_impact::{
    Impact, Motion, ToiError, ToiOptions, toi_bisection, toi_chain_segment,
    toi_conservative_advancement,
};
