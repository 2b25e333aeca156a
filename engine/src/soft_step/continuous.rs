//! Continuous collision for fast bodies (after Box2D v3's
//! `b2SolveContinuous`): a dynamic body that moved more than half its
//! smallest extent in a step could have jumped over a thin static body, so
//! its motion over the step (constant velocities from its start pose to its
//! end pose) is swept against every static shape its path's box touches,
//! by conservative advancement ([`crate::collision::toi_conservative_advancement`]),
//! whatever the two convex shapes (circle, polygon, segment, capsule,
//! rounded polygon, a compound part by part), and against a chain segment
//! by segment, one-sided ([`crate::collision::toi_chain_segment`]: a body
//! whose centre crossed a segment's line from its solid side in the step).
//! Only the time is computed (`toi_time_conservative_advancement` and
//! `toi_time_chain_segment`, the same search without the contact manifold
//! the validation's sweeps return). At the first time of impact the body
//! is put back there, velocities unchanged: the next step's speculative
//! contact then stops it at the surface, with its restitution.
//!
//! Pairs already within the linear slop at the start of the step are left
//! to the speculative contacts (sweeping them would freeze the body where
//! it is); moving bodies are not swept against each other (a bullet is
//! swept against them: `bullets.rs`). Static sensor shapes and static
//! shapes the body's filters refuse are not swept against; the pre-solve hook is not asked (a one-way platform lets
//! through only bodies slower than half their size per step, or runs with
//! `continuous` off).

use super::broad_phase::BroadPhase;
use super::manifold::LINEAR_SLOP;
use crate::body::{Body, BodyState};
use crate::collision::time_of_impact::{toi_time_chain_segment, toi_time_conservative_advancement};
use crate::collision::{Aabb, Motion, ToiOptions};
use crate::shape::Shape;
use nalgebra::{Isometry2, Vector2};

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub(crate) use crate::tunables::FAST_FRACTION;

use crate::tunables::SWEEP_MAX_ITERATIONS as MAX_ITERATIONS;

/// A fast body's motion over the step of `dt` (s), from `start` (position
/// in m, angle in rad) to `end`.
pub(crate) struct Sweep {
    pub start: (Vector2<f64>, f64),
    pub end: (Vector2<f64>, f64),
    pub dt: f64,
}

impl Sweep {
    /// The constant-velocity motion from `start` (this sweep's start pose,
    /// `Isometry2::new(self.start.0, self.start.1)`) to its end over `dt`.
    pub(crate) fn motion(&self, start: Isometry2<f64>) -> Motion {
        Motion::new(
            start,
            (self.end.0 - self.start.0) / self.dt,
            (self.end.1 - self.start.1) / self.dt,
        )
    }
}

/// The earliest time of impact in [0, dt] (s) of `body` moving along
/// `sweep` (whose start pose is `start`, the caller's
/// `Isometry2::new(sweep.start.0, sweep.start.1)`) with any static shape
/// its swept box overlaps, if any. `blocks` maps a static collider to its
/// body and part (a compound's part, a chain's segment) when it can stop
/// this one (not a sensor, not refused by the filters), else `None`.
#[expect(
    clippy::too_many_arguments,
    reason = "the sweep's inputs, each from a different part of the model"
)]
pub(crate) fn first_impact(
    body: &Body,
    sweep: &Sweep,
    start: Isometry2<f64>,
    swept_box: &Aabb,
    broad: &BroadPhase,
    bodies: &[Body],
    states: &[BodyState],
    blocks: impl Fn(usize) -> Option<(usize, usize)>,
) -> Option<f64> {
    let shape = body.shape.as_ref()?;
    let motion = sweep.motion(start);
    let options = ToiOptions {
        tolerance: LINEAR_SLOP,
        max_iterations: MAX_ITERATIONS,
    };
    let mut first: Option<f64> = None;
    broad.query_static(swept_box, |collider| {
        // The static body of that collider and its part, if it can stop
        // this one.
        let Some((other, part)) = blocks(collider) else {
            return;
        };
        let Some(other_shape) = bodies[other].shape.as_ref() else {
            return;
        };
        let s = &states[other];
        let pose = Isometry2::new(s.position, s.angle);
        let limit = first.unwrap_or(sweep.dt);
        let impact = match other_shape {
            // One collider per solid segment: the collider's part names it.
            Shape::Chain(chain) => chain.segment(part).map_or(Ok(None), |segment| {
                toi_time_chain_segment(shape, &motion, &segment, &pose, limit, &options)
            }),
            _ => {
                let fixed = Motion::fixed(pose);
                toi_time_conservative_advancement(
                    shape,
                    &motion,
                    other_shape,
                    &fixed,
                    limit,
                    &options,
                )
            }
        };
        if let Ok(Some(time)) = impact
            && time > 0.0
        {
            first = Some(time);
        }
    });
    first
}
