//! The same shape queries in parry2d-f64 0.31, to judge the engine's
//! collision detection against (docs/cases.md case III, seed §7.2).
//!
//! Engine shapes and poses are converted to parry's: a
//! [`ConvexPolygon`](engine::ConvexPolygon) becomes a parry
//! `ConvexPolygon` with the *same* vertices (built with
//! `from_convex_polyline_unmodified`: parry's usual constructor drops
//! vertices whose edges turn by less than ~1.5e-4 rad, which would change the
//! shape), a circle becomes a `Ball`, and an [`Isometry2`] becomes a parry
//! `Pose` (glam types through `glamx`; converted component by component so
//! that no crate feature is needed). The engine's shapes are only read as
//! data: nothing here calls the engine's collision code.
//!
//! What parry computes, and how:
//! - [`parry_contact`]: `query::contact`, GJK with EPA for overlapping
//!   convex polygons (exact in theory for polytopes), closed forms for balls;
//! - [`parry_intersects`]: `query::intersection_test` (GJK);
//! - [`parry_distance`]: `query::distance` (GJK), 0 when overlapping;
//! - [`parry_time_of_impact`]: `query::cast_shapes` (linear motion, GJK ray
//!   cast on the Minkowski difference) when neither body spins, otherwise
//!   `query::cast_shapes_nonlinear` (conservative advancement with
//!   bisection, rotation about the body origin).
//!
//! Units are SI: m, s, rad, m/s, rad/s.

use engine::{RoundedKind, Shape};
use nalgebra::{Isometry2, Vector2};
use parry2d_f64::math::{Pose, Rotation, Vector};
use parry2d_f64::query::{
    self, NonlinearRigidMotion, ShapeCastHit, ShapeCastOptions, ShapeCastStatus,
};
use parry2d_f64::shape::{Ball, ConvexPolygon, SharedShape};

pub mod exact;
#[cfg(test)]
mod tests;
pub mod world_queries;

/// A parry vector from a nalgebra one.
pub fn to_parry_vector(v: &Vector2<f64>) -> Vector {
    Vector::new(v.x, v.y)
}

/// A nalgebra vector from a parry one.
pub fn from_parry_vector(v: Vector) -> Vector2<f64> {
    Vector2::new(v.x, v.y)
}

/// A parry pose from a nalgebra isometry (same translation, same unit
/// complex rotation).
pub fn to_parry_pose(pose: &Isometry2<f64>) -> Pose {
    Pose {
        rotation: Rotation::from_cos_sin_unchecked(pose.rotation.re, pose.rotation.im),
        translation: to_parry_vector(&pose.translation.vector),
    }
}

/// The parry shape with the same geometry as an engine shape.
pub fn to_parry_shape(shape: &Shape) -> SharedShape {
    match shape {
        Shape::Polygon(p) => {
            let points = p.vertices().iter().map(to_parry_vector).collect();
            let polygon = ConvexPolygon::from_convex_polyline_unmodified(points)
                .expect("an engine polygon has at least 3 distinct vertices");
            SharedShape::new(polygon)
        }
        Shape::Circle(c) => SharedShape::new(Ball::new(c.radius)),
        // A segment, capsule or rounded polygon: parry's shape of each kind
        // (a rounded polygon is parry's convex polygon with a border).
        Shape::Rounded(r) => {
            let core: Vec<_> = r.core().iter().map(to_parry_vector).collect();
            match r.kind() {
                RoundedKind::Segment => SharedShape::segment(core[0], core[1]),
                RoundedKind::Capsule => SharedShape::capsule(core[0], core[1], r.radius()),
                RoundedKind::RoundedPolygon => SharedShape::round_convex_polyline(core, r.radius())
                    .expect("an engine rounded polygon's core has at least 3 distinct vertices"),
            }
        }
        Shape::Compound(c) => SharedShape::compound(
            c.parts()
                .iter()
                .map(|p| {
                    let pose = Isometry2::new(p.offset, p.angle);
                    (to_parry_pose(&pose), to_parry_shape(&p.shape))
                })
                .collect(),
        ),
        // parry's polyline is two-sided and has no ghost points: the
        // chain's solid part (an open chain's first and last points only
        // guide its end segments; a loop closes).
        Shape::Chain(c) => {
            let points = c.points();
            let solid = if c.is_loop() {
                points
            } else {
                &points[1..points.len() - 1]
            };
            let n = solid.len() as u32;
            let mut indices: Vec<[u32; 2]> = (0..n - 1).map(|i| [i, i + 1]).collect();
            if c.is_loop() {
                indices.push([n - 1, 0]);
            }
            SharedShape::polyline(solid.iter().map(to_parry_vector).collect(), Some(indices))
        }
    }
}

/// parry's contact between two shapes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParryContact {
    /// Penetration depth (m): > 0 when overlapping, < 0 for a gap within
    /// the prediction distance (parry's `-dist`).
    pub depth: f64,
    /// Unit normal from A to B (parry's `normal1`, world frame).
    pub normal: Vector2<f64>,
    /// Witness point on A (world, m).
    pub point_a: Vector2<f64>,
    /// Witness point on B (world, m).
    pub point_b: Vector2<f64>,
}

const SUPPORTED: &str = "parry supports convex polygons and balls";

/// parry's contact of `a` at `pose_a` and `b` at `pose_b` if they are
/// closer than `prediction` (m), with its depth, normal and witness points.
pub fn parry_contact(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
    prediction: f64,
) -> Option<ParryContact> {
    let (sa, sb) = (to_parry_shape(a), to_parry_shape(b));
    query::contact(
        &to_parry_pose(pose_a),
        &*sa,
        &to_parry_pose(pose_b),
        &*sb,
        prediction,
    )
    .expect(SUPPORTED)
    .map(|c| ParryContact {
        depth: -c.dist,
        normal: from_parry_vector(c.normal1),
        point_a: from_parry_vector(c.point1),
        point_b: from_parry_vector(c.point2),
    })
}

/// parry's verdict: do the shapes touch or overlap?
pub fn parry_intersects(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
) -> bool {
    let (sa, sb) = (to_parry_shape(a), to_parry_shape(b));
    query::intersection_test(&to_parry_pose(pose_a), &*sa, &to_parry_pose(pose_b), &*sb)
        .expect(SUPPORTED)
        .intersecting
}

/// parry's distance between the shapes (m), 0 when they overlap.
pub fn parry_distance(
    a: &Shape,
    pose_a: &Isometry2<f64>,
    b: &Shape,
    pose_b: &Isometry2<f64>,
) -> f64 {
    let (sa, sb) = (to_parry_shape(a), to_parry_shape(b));
    query::distance(&to_parry_pose(pose_a), &*sa, &to_parry_pose(pose_b), &*sb)
        .expect(SUPPORTED)
        .distance
}

/// A body's motion for [`parry_time_of_impact`]: start pose, constant
/// linear velocity (m/s) and angular velocity about the body origin (rad/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParryMotion {
    /// Pose at t = 0.
    pub pose: Isometry2<f64>,
    /// Velocity of the body origin (m/s).
    pub linear_velocity: Vector2<f64>,
    /// Angular velocity (rad/s).
    pub angular_velocity: f64,
}

/// parry's time of impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParryImpact {
    /// Time of impact (s).
    pub time: f64,
    /// Unit normal from A to B at impact (world frame: parry's `normal1`,
    /// in A's frame, turned by A's rotation at the time of impact). When
    /// the nonlinear cast ends with status `Failed` it may be the normal of
    /// an earlier iterate: in the spinning-box case of docs/cases.md the time is
    /// right to 1e-15 s but the status is `Failed` (its last closest-point
    /// query finds the shapes closer than `f64::EPSILON`) and `normal1` is
    /// the one computed at t = 0.
    pub normal: Vector2<f64>,
    /// Which cast computed it: `"cast_shapes"` or `"cast_shapes_nonlinear"`.
    pub method: &'static str,
    /// parry's status (`Converged`, `OutOfIterations`, `Failed`,
    /// `PenetratingOrWithinTargetDist`).
    pub status: ShapeCastStatus,
}

/// parry's first time in [0, `t_max`] (s) at which the two moving shapes
/// touch: `cast_shapes` when both angular velocities are 0, otherwise
/// `cast_shapes_nonlinear` (which rotates each body about its origin).
/// `None` if they do not touch in that interval.
pub fn parry_time_of_impact(
    a: &Shape,
    motion_a: &ParryMotion,
    b: &Shape,
    motion_b: &ParryMotion,
    t_max: f64,
) -> Option<ParryImpact> {
    let (sa, sb) = (to_parry_shape(a), to_parry_shape(b));
    let (pa, pb) = (to_parry_pose(&motion_a.pose), to_parry_pose(&motion_b.pose));
    let linear = motion_a.angular_velocity == 0.0 && motion_b.angular_velocity == 0.0;
    let (hit, method): (Option<ShapeCastHit>, _) = if linear {
        let hit = query::cast_shapes(
            &pa,
            to_parry_vector(&motion_a.linear_velocity),
            &*sa,
            &pb,
            to_parry_vector(&motion_b.linear_velocity),
            &*sb,
            ShapeCastOptions::with_max_time_of_impact(t_max),
        )
        .expect(SUPPORTED);
        (hit, "cast_shapes")
    } else {
        let motion = |pose: Pose, m: &ParryMotion| {
            NonlinearRigidMotion::new(
                pose,
                Vector::ZERO,
                to_parry_vector(&m.linear_velocity),
                m.angular_velocity,
            )
        };
        let hit = query::cast_shapes_nonlinear(
            &motion(pa, motion_a),
            &*sa,
            &motion(pb, motion_b),
            &*sb,
            0.0,
            t_max,
            true,
        )
        .expect(SUPPORTED);
        (hit, "cast_shapes_nonlinear")
    };
    hit.map(|h| {
        // normal1 is in A's local frame at the time of impact.
        let angle_a = motion_a.angular_velocity * h.time_of_impact;
        let rotation = nalgebra::UnitComplex::new(angle_a) * motion_a.pose.rotation;
        ParryImpact {
            time: h.time_of_impact,
            normal: rotation * from_parry_vector(h.normal1),
            method,
            status: h.status,
        }
    })
}
