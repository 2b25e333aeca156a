//! parry2d's answers to the engine's world queries (`engine::query`), one
//! world shape at a time: the harness loops over every shape of a world
//! (no broad phase), so the reference is independent of the engine's
//! trees. Shapes and poses convert as in the parent module.
//!
//! The engine's conventions are applied to parry's answers here: a ray
//! skips a shape containing its origin (parry, with `solid = true`,
//! reports it at distance 0), and a swept shape skips a shape it overlaps
//! at the start (parry reports it as penetrating at time 0).
//!
//! Units: m; a shape cast's time as the fraction of the translation.

use super::{from_parry_vector, to_parry_pose, to_parry_shape, to_parry_vector};
use engine::Shape;
use nalgebra::{Isometry2, Vector2};
use parry2d_f64::query::{self, Ray, ShapeCastOptions, ShapeCastStatus};
use parry2d_f64::shape::SharedShape;

/// A world shape converted once, for many queries.
pub struct ParryBody {
    shape: SharedShape,
    pose: parry2d_f64::math::Pose,
    rotation: nalgebra::UnitComplex<f64>,
}

impl ParryBody {
    /// parry's copy of `shape` at `pose`.
    pub fn new(shape: &Shape, pose: &Isometry2<f64>) -> Self {
        Self {
            shape: to_parry_shape(shape),
            pose: to_parry_pose(pose),
            rotation: pose.rotation,
        }
    }

    /// Whether the shape contains `point` (parry's `contains_point`).
    pub fn contains(&self, point: Vector2<f64>) -> bool {
        self.shape
            .contains_point(&self.pose, to_parry_vector(&point))
    }

    /// Where the ray `origin + t dir` (unit `dir`, 0 ≤ t ≤ `max_t`, m)
    /// enters the shape: parry's `cast_ray_and_get_normal` (solid), with
    /// the distance (m) and the outward normal (world frame). `None` when
    /// parry says it misses or the shape contains the origin.
    pub fn ray(
        &self,
        origin: Vector2<f64>,
        dir: Vector2<f64>,
        max_t: f64,
    ) -> Option<(f64, Vector2<f64>)> {
        if self.contains(origin) {
            return None;
        }
        let ray = Ray::new(to_parry_vector(&origin), to_parry_vector(&dir));
        self.shape
            .cast_ray_and_get_normal(&self.pose, &ray, max_t, true)
            .map(|hit| (hit.time_of_impact, from_parry_vector(hit.normal)))
    }

    /// Whether `other` at `pose` overlaps this shape (parry's
    /// `intersection_test`).
    pub fn overlaps(&self, other: &Shape, pose: &Isometry2<f64>) -> bool {
        let shape = to_parry_shape(other);
        query::intersection_test(&to_parry_pose(pose), &*shape, &self.pose, &*self.shape)
            .expect("parry supports convex polygons and balls")
            .intersecting
    }

    /// The first touch of `moving` at `pose` swept by `translation` (m)
    /// against this shape: parry's `cast_shapes` over one unit of time,
    /// with the fraction of the translation and this shape's outward
    /// normal (world frame). `None` when parry finds no touch or the
    /// shapes overlap at the start (status `PenetratingOrWithinTargetDist`).
    pub fn cast(
        &self,
        moving: &Shape,
        pose: &Isometry2<f64>,
        translation: Vector2<f64>,
    ) -> Option<(f64, Vector2<f64>)> {
        let shape = to_parry_shape(moving);
        let hit = query::cast_shapes(
            &to_parry_pose(pose),
            to_parry_vector(&translation),
            &*shape,
            &self.pose,
            parry2d_f64::math::Vector::ZERO,
            &*self.shape,
            ShapeCastOptions::with_max_time_of_impact(1.0),
        )
        .expect("parry supports convex polygons and balls")?;
        if hit.status == ShapeCastStatus::PenetratingOrWithinTargetDist {
            return None;
        }
        Some((
            hit.time_of_impact,
            self.rotation * from_parry_vector(hit.normal2),
        ))
    }

    /// The signed distance (m, < 0 when overlapping) between `other` at
    /// `pose` and this shape, and this shape's outward normal towards it
    /// (world frame): parry's `contact` with a prediction of
    /// `max_distance`; `None` beyond it.
    pub fn separation(
        &self,
        other: &Shape,
        pose: &Isometry2<f64>,
        max_distance: f64,
    ) -> Option<(f64, Vector2<f64>)> {
        let shape = to_parry_shape(other);
        query::contact(
            &to_parry_pose(pose),
            &*shape,
            &self.pose,
            &*self.shape,
            max_distance,
        )
        .expect("parry supports convex polygons and balls")
        .map(|c| (c.dist, -from_parry_vector(c.normal1)))
    }
}
