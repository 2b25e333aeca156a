//! Bullets: continuous collision of a fast body against moving bodies
//! (after Box2D v3's bullet bodies, `isBullet`, whose sweeps its
//! `b2SolveContinuous` runs once the other bodies are finalized).
//!
//! The continuous stage (`finalize.rs`, `continuous.rs`) sweeps a fast
//! dynamic body against the static shapes only: two fast bodies could
//! otherwise stop each other at poses neither reaches. So a fast body
//! still passes through a thin *dynamic* body (a plate, a wall of boxes)
//! in one step. A bullet ([`crate::BodyDef::bullet`]) is not swept with
//! the others: the stage's loop lists the fast bullets, in body order,
//! and once every other body's end pose is final (swept back itself if it
//! was fast) and in the broad phase, this pass sweeps each listed bullet,
//! in that order, against every shape its swept box touches: static,
//! kinematic and dynamic, those of other bullets excepted (their poses are
//! not final; Box2D skips them too). The other bodies are held at their
//! end poses over the step (Box2D's do not move either: a finalized body's
//! sweep starts where it ends). At the first time of impact the bullet is
//! put back there, velocities unchanged, and its boxes follow into the
//! broad phase; the next step's speculative contact then stops it at the
//! surface, as for a sweep against a static body.
//!
//! The pass is serial and ordered (the bullets in body order, the trees in
//! a fixed order), and reads only what the stage's serial loop has written
//! in body order: its bits are those of one thread at every thread count.
//! The list keeps its capacity: no allocation once it has held the most
//! fast bullets of a step. A world without bullets lists none, and the
//! pass is not entered.
//!
//! Any convex shape is swept against any (compounds part by part), and
//! against a chain segment by segment, one-sided, as in `continuous.rs`.
//!
//! What is swept against, as for static shapes in `continuous.rs`: shapes
//! that would make a contact with the bullet's (not sensors, not refused by
//! the filters, the program's filter hook or a joint that keeps the two
//! bodies apart); pairs already within the linear slop at the start of the
//! step are left to the speculative contacts.

use super::SoftStep;
use super::contact_events::ShapeId;
use super::continuous::Sweep;
use super::finalize::speculative_box;
use super::manifold::LINEAR_SLOP;
use crate::body::BodyId;
use crate::collision::time_of_impact::{toi_time_chain_segment, toi_time_conservative_advancement};
use crate::collision::{Motion, ToiOptions};
use crate::shape::Shape;
use crate::tunables::SWEEP_MAX_ITERATIONS;
use crate::world_core::WorldCore;
use nalgebra::{Isometry2, Translation2, UnitComplex};

impl SoftStep {
    /// The bullet pass (see the module docs): each fast bullet listed by
    /// the continuous stage, in body order, swept against the final poses
    /// of the bodies around it and put back to its first impact. Empties
    /// the list.
    pub(super) fn sweep_bullets(&mut self, core: &mut WorldCore, dt: f64) {
        let margin = self.settings.aabb_margin;
        let speculative = self.settings.speculative_distance;
        for k in 0..self.fast_bullets.len() {
            let id = self.fast_bullets[k];
            let r = self.bodies[id + 1];
            let state = &core.states[id];
            let sweep = Sweep {
                start: (state.position - r.dp, state.angle - r.dtheta),
                end: (state.position, state.angle),
                dt,
            };
            let Some(toi) = self.first_bullet_impact(core, id, &sweep) else {
                continue;
            };
            let f = toi / dt;
            let position = sweep.start.0 + f * (sweep.end.0 - sweep.start.0);
            let angle = sweep.start.1 + f * (sweep.end.1 - sweep.start.1);
            let rotation = UnitComplex::new(angle);
            let state = &mut core.states[id];
            state.position = position;
            state.angle = angle;
            self.sims[id].rotation = rotation;
            let pose = Isometry2::from_parts(Translation2::from(position), rotation);
            for c in self.sims[id].colliders.clone() {
                let collider = &self.colliders[c];
                let aabb = speculative_box(collider, &pose, speculative);
                self.broad.update(c, &aabb, collider.aabb_margin(margin));
            }
        }
        self.fast_bullets.clear();
    }

    /// The earliest time of impact in (0, dt] (s) of bullet `id` moving
    /// along `sweep` with any shape its swept box overlaps that can stop
    /// it (see the module docs), the other bodies at their poses in
    /// `core`; `None` if it hits nothing (or has no shape).
    fn first_bullet_impact(&mut self, core: &WorldCore, id: BodyId, sweep: &Sweep) -> Option<f64> {
        let shape = core.bodies[id].shape.as_ref()?;
        let own = self.sims[id].colliders.clone();
        if own.is_empty() {
            return None;
        }
        let start = Isometry2::new(sweep.start.0, sweep.start.1);
        let end = Isometry2::new(sweep.end.0, sweep.end.1);
        let swept = own
            .clone()
            .map(|c| {
                let collider = &self.colliders[c];
                collider
                    .shape
                    .aabb_at(&collider.pose(&start))
                    .merged(&collider.shape.aabb_at(&collider.pose(&end)))
            })
            .reduce(|a, b| a.merged(&b))?;
        let motion = sweep.motion(start);
        let options = ToiOptions {
            tolerance: LINEAR_SLOP,
            max_iterations: SWEEP_MAX_ITERATIONS,
        };
        let (colliders, data, sims) = (&self.colliders, &self.shape_data, &self.sims);
        let (joints, hooks) = (&self.joints, &mut self.hooks.0);
        let mut first: Option<f64> = None;
        self.broad.query_all(&swept, |other| {
            let body = colliders[other].body;
            // Itself, other bullets (not final yet), bodies a joint keeps
            // apart from it.
            if body == id || sims[body].bullet || joints.keeps_apart(id, body) {
                return;
            }
            let d = &data[other];
            let Some(mine) = own.clone().find(|&c| {
                !d.sensor && !data[c].sensor && data[c].filter.should_collide(&d.filter)
            }) else {
                return;
            };
            if let Some(hooks) = hooks.as_mut() {
                let a = ShapeId {
                    body: id,
                    part: data[mine].part,
                };
                let b = ShapeId { body, part: d.part };
                if !hooks.should_collide(a, b) {
                    return;
                }
            }
            let Some(other_shape) = core.bodies[body].shape.as_ref() else {
                return;
            };
            let s = &core.states[body];
            let pose = Isometry2::new(s.position, s.angle);
            let limit = first.unwrap_or(sweep.dt);
            let impact = match other_shape {
                // One collider per solid segment: its part names it.
                Shape::Chain(chain) => chain.segment(d.part).map_or(Ok(None), |segment| {
                    toi_time_chain_segment(shape, &motion, &segment, &pose, limit, &options)
                }),
                _ => {
                    let held = Motion::fixed(pose);
                    toi_time_conservative_advancement(
                        shape,
                        &motion,
                        other_shape,
                        &held,
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
}
