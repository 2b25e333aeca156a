//! The bodies as the soft step's substeps see them: velocities and the
//! motion since the step began, in one compact record per body that the
//! contact solver reads and writes, and the per-body constants (inverse
//! mass and inertia, shape, extents) that it only reads.
//!
//! Solver index 0 is a body that never moves (zero velocity, infinite
//! mass): every contact with a static body points there, so the solver
//! needs no branch for them. The body with world id `i` has solver index
//! `i + 1`.

use super::geometry::Collider;
use crate::body::{Body, BodyKind, BodyState};
use nalgebra::{UnitComplex, Vector2};
use std::ops::Range;

/// A body's velocity and its motion since the start of the step: what one
/// substep reads and writes (64 bytes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SolverBody {
    /// Linear velocity of the centre of mass (m/s).
    pub v: Vector2<f64>,
    /// Angular velocity (rad/s).
    pub w: f64,
    /// Displacement of the centre of mass since the step began (m).
    pub dp: Vector2<f64>,
    /// Rotation since the step began (rad).
    pub dtheta: f64,
    /// cos and sin of `dtheta`.
    pub dq: (f64, f64),
}

impl SolverBody {
    /// A body at rest that has not moved.
    pub const AT_REST: SolverBody = SolverBody {
        v: Vector2::new(0.0, 0.0),
        w: 0.0,
        dp: Vector2::new(0.0, 0.0),
        dtheta: 0.0,
        dq: (1.0, 0.0),
    };

    /// `r` turned by this body's rotation since the step began.
    #[inline(always)]
    pub fn rotate(&self, r: Vector2<f64>) -> Vector2<f64> {
        let (c, s) = self.dq;
        Vector2::new(c * r.x - s * r.y, s * r.x + c * r.y)
    }
}

/// What the soft step keeps about a body besides its velocity.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BodySim {
    pub kind: BodyKind,
    /// 1/m (1/kg); 0 for static and kinematic bodies.
    pub inv_mass: f64,
    /// 1/I (1/(kg·m²)); 0 for static, kinematic and non-rotating bodies.
    pub inv_inertia: f64,
    /// Its colliders (indices into the model's collider list); empty
    /// without a shape.
    pub colliders: Range<usize>,
    /// Largest distance from the centre of mass to a point of its shapes
    /// (m).
    pub max_extent: f64,
    /// Smallest distance from the centre of a shape to its boundary (m):
    /// moving less than a fraction of it, the body cannot jump over a
    /// thin wall.
    pub min_extent: f64,
    /// Its rotation at the end of the last step (cos θ, sin θ).
    pub rotation: UnitComplex<f64>,
    /// Friction coefficient (its own, or the settings' default).
    pub friction: f64,
    /// Restitution (its own, or the settings' default).
    pub restitution: f64,
    /// Whether the body sleeps (its island is at rest).
    pub asleep: bool,
    /// How long (s) the body has been slower than the sleep threshold.
    pub sleep_time: f64,
}

impl BodySim {
    /// The solver's view of `body` at angle `angle` (rad), whose colliders
    /// are `colliders` (at indices `range`), with the materials' defaults.
    pub(crate) fn new(
        body: &Body,
        angle: f64,
        (colliders, range): (&[Collider], Range<usize>),
        friction: f64,
        restitution: f64,
    ) -> Self {
        let max_extent = colliders
            .iter()
            .map(|c| c.offset.map_or(0.0, |o| o.translation.vector.norm()) + c.max_extent)
            .fold(0.0, f64::max);
        let min_extent = colliders
            .iter()
            .map(|c| c.shape.min_extent())
            .fold(f64::INFINITY, f64::min);
        let min_extent = if min_extent.is_finite() {
            min_extent
        } else {
            0.0
        };
        let dynamic = body.kind == BodyKind::Dynamic;
        Self {
            kind: body.kind,
            inv_mass: if dynamic { 1.0 / body.mass } else { 0.0 },
            inv_inertia: match (dynamic, body.inertia) {
                (true, Some(i)) => 1.0 / i,
                _ => 0.0,
            },
            colliders: range,
            max_extent,
            min_extent,
            rotation: UnitComplex::new(angle),
            friction: body.friction.unwrap_or(friction),
            restitution: body.restitution.unwrap_or(restitution),
            asleep: false,
            sleep_time: 0.0,
        }
    }

    /// Whether the solver moves this body (dynamic or kinematic, awake).
    pub(crate) fn moving(&self) -> bool {
        self.kind != BodyKind::Static && !self.asleep
    }
}

/// The solver index of world body `id` of kind `kind`: 0 for a static one.
pub(crate) fn solver_index(id: usize, kind: BodyKind) -> usize {
    if kind == BodyKind::Static { 0 } else { id + 1 }
}

/// The solver record of a body whose state is `s`.
pub(crate) fn solver_body(s: &BodyState, kind: BodyKind) -> SolverBody {
    if kind == BodyKind::Static {
        return SolverBody::AT_REST;
    }
    SolverBody {
        v: s.velocity,
        w: s.angular_velocity,
        ..SolverBody::AT_REST
    }
}
