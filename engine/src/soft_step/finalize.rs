//! The continuous stage (stage 7): each moving body's sleep timer, its end
//! pose swept against the static shapes when it moved fast
//! (`continuous.rs`), its colliders' bounding boxes at that pose; then the
//! boxes into the broad phase.
//!
//! A fast bullet is not swept here: the loop lists it, and once every
//! other body's end pose is final and in the broad phase, `bullets.rs`
//! sweeps the listed bullets against them, serially in body order.
//!
//! The first part is per body ([`finalize_body`]): it reads the body's
//! solver record, its colliders, the world's states and the broad phase's
//! static tree, and writes only the body's own timer, rotation, corrected
//! pose and boxes. The second ([`BroadPhase::update`]) changes the trees
//! and the move buffer, whose order is the next step's pair order, and
//! runs serially in body order. On one thread each body does both in turn,
//! as before; on several (after Box2D v3's `b2FinalizeBodiesTask`), the
//! bodies' first parts run on the pool's threads (contiguous shares of the
//! bodies), then the serial pass writes the corrected poses and updates
//! the broad phase in body order. The bits are those of one thread: a
//! sweep reads only the static tree and static bodies' states, which the
//! stage does not change.

use super::SoftStep;
use super::bodies::{BodySim, SolverBody};
use super::broad_phase::BroadPhase;
use super::continuous;
use super::geometry::Collider;
use super::pool::{Pool, SharedSlice, Worker};
use super::settings::SoftStepSettings;
use super::shape_data::ShapeData;
use crate::body::{Body, BodyKind, BodyState};
use crate::collision::Aabb;
use crate::world_core::WorldCore;
use nalgebra::{Isometry2, Translation2, UnitComplex, Vector2};

/// A pose a sweep put a body back to: position (m), angle (rad).
pub(super) type Impact = (Vector2<f64>, f64);

/// What [`finalize_body`] reads.
#[derive(Clone, Copy)]
struct FinalizeInputs<'a> {
    settings: &'a SoftStepSettings,
    solver: &'a [SolverBody],
    colliders: &'a [Collider],
    shape_data: &'a [ShapeData],
    broad: &'a BroadPhase,
    bodies: &'a [Body],
    states: &'a [BodyState],
    /// The step (s).
    dt: f64,
}

impl<'a> FinalizeInputs<'a> {
    fn new(
        (settings, solver, colliders): (&'a SoftStepSettings, &'a [SolverBody], &'a [Collider]),
        (shape_data, broad): (&'a [ShapeData], &'a BroadPhase),
        core: &'a WorldCore,
        dt: f64,
    ) -> Self {
        Self {
            settings,
            solver,
            colliders,
            shape_data,
            broad,
            bodies: &core.bodies,
            states: &core.states,
            dt,
        }
    }
}

/// Body `id`'s part of the stage: its sleep timer, and for a body with
/// colliders its end pose, swept back to the first impact with a static
/// shape when it moved fast, its rotation set to that pose's. Returns the
/// end pose, and whether the sweep corrected it (then the caller writes
/// it into the world's state; position in m, angle in rad). Inlined: on
/// one thread it is the body of the stage's loop.
#[inline(always)]
fn finalize_body(
    id: usize,
    sim: &mut BodySim,
    inputs: &FinalizeInputs<'_>,
) -> Option<(Isometry2<f64>, Option<Impact>)> {
    let settings = inputs.settings;
    let dt = inputs.dt;
    let r = inputs.solver[id + 1];
    if settings.sleeping {
        let speed = r.v.norm() + sim.max_extent * r.w.abs();
        if sim.kind == BodyKind::Dynamic && speed < settings.sleep_threshold {
            sim.sleep_time += dt;
        } else {
            sim.sleep_time = 0.0;
        }
    }
    let state = &inputs.states[id];
    if sim.colliders.is_empty() {
        // No shape, but its joints' anchors turn with it.
        if r.dtheta != 0.0 {
            sim.rotation = UnitComplex::new(state.angle);
        }
        return None;
    }
    // The end pose's rotation, kept unless an impact moves the body.
    let mut rotation = UnitComplex::new(state.angle);
    let mut position = state.position;
    let mut corrected = None;
    // Only static shapes are swept against: none, nothing to do. A fast
    // bullet's sweep waits for the other bodies' end poses (`bullets.rs`).
    if inputs.broad.has_static() && is_fast(settings, sim, &r) && !sim.bullet {
        let sweep = continuous::Sweep {
            start: (state.position - r.dp, state.angle - r.dtheta),
            end: (state.position, state.angle),
            dt,
        };
        let start = Isometry2::new(sweep.start.0, sweep.start.1);
        let end = Isometry2::from_parts(Translation2::from(sweep.end.0), rotation);
        let swept = sim
            .colliders
            .clone()
            .map(|c| {
                let collider = &inputs.colliders[c];
                collider
                    .shape
                    .aabb_at(&collider.pose(&start))
                    .merged(&collider.shape.aabb_at(&collider.pose(&end)))
            })
            .reduce(|a, b| a.merged(&b))
            .expect("a body with colliders");
        let (colliders, data) = (inputs.colliders, inputs.shape_data);
        let own = sim.colliders.clone();
        let blocks = |other: usize| {
            let d = &data[other];
            let stops = !d.sensor
                && own
                    .clone()
                    .any(|c| !data[c].sensor && data[c].filter.should_collide(&d.filter));
            stops.then_some((colliders[other].body, d.part))
        };
        if let Some(toi) = continuous::first_impact(
            &inputs.bodies[id],
            &sweep,
            start,
            &swept,
            inputs.broad,
            inputs.bodies,
            inputs.states,
            blocks,
        ) {
            let f = toi / dt;
            position = sweep.start.0 + f * (sweep.end.0 - sweep.start.0);
            let angle = sweep.start.1 + f * (sweep.end.1 - sweep.start.1);
            rotation = UnitComplex::new(angle);
            corrected = Some((position, angle));
        }
    }
    sim.rotation = rotation;
    let pose = Isometry2::from_parts(Translation2::from(position), rotation);
    Some((pose, corrected))
}

/// Whether dynamic body `sim`, of solver record `r`, moved fast this step
/// (more than [`continuous::FAST_FRACTION`] of its smallest extent) with
/// continuous collision on: then its motion is swept.
#[inline(always)]
pub(super) fn is_fast(settings: &SoftStepSettings, sim: &BodySim, r: &SolverBody) -> bool {
    settings.continuous
        && sim.kind == BodyKind::Dynamic
        && r.dp.norm() + sim.max_extent * r.dtheta.abs()
            > continuous::FAST_FRACTION * sim.min_extent
}

/// `collider`'s box at its body's `pose`, grown by the speculative
/// distance (m): what the broad phase is given.
#[inline(always)]
pub(super) fn speculative_box(
    collider: &Collider,
    pose: &Isometry2<f64>,
    speculative: f64,
) -> Aabb {
    collider
        .shape
        .aabb_at(&collider.pose(pose))
        .loosened(speculative)
}

impl SoftStep {
    /// Stage 7: bounding boxes into the broad phase, fast bodies swept
    /// against static ones, sleep timers; with `pool`, the bodies' own
    /// parts on its threads first (see the module docs).
    #[inline(never)]
    pub(super) fn finalize_bodies(&mut self, core: &mut WorldCore, dt: f64, pool: Option<&Pool>) {
        let (speculative, margin) = (
            self.settings.speculative_distance,
            self.settings.aabb_margin,
        );
        if let Some(pool) = pool {
            self.parallel_finalize(pool, core, dt);
            // The threads' results, in body order: only the bodies they
            // listed (a fast bullet, a corrected pose, or a box that left
            // its fat box) have anything to do here.
            let mut pending = std::mem::take(&mut self.finalize_pending);
            for &id in pending.iter().flatten() {
                if self.sims[id].bullet
                    && is_fast(&self.settings, &self.sims[id], &self.bodies[id + 1])
                {
                    self.fast_bullets.push(id);
                }
                if let Some((position, angle)) = self.impacts[id] {
                    let state = &mut core.states[id];
                    state.position = position;
                    state.angle = angle;
                }
                for c in self.sims[id].colliders.clone() {
                    let aabb = self.collider_boxes[c];
                    self.broad
                        .update(c, &aabb, self.colliders[c].aabb_margin(margin));
                }
            }
            pending.iter_mut().for_each(Vec::clear);
            self.finalize_pending = pending;
        }
        // On one thread: every moving body here, in body order.
        let serial = pool.is_none();
        for id in (0..self.sims.len()).filter(|_| serial) {
            if !self.sims[id].moving() {
                continue;
            }
            if self.sims[id].bullet && is_fast(&self.settings, &self.sims[id], &self.bodies[id + 1])
            {
                self.fast_bullets.push(id);
            }
            let inputs = FinalizeInputs::new(
                (&self.settings, &self.bodies, &self.colliders),
                (&self.shape_data, &self.broad),
                core,
                dt,
            );
            let Some((pose, impact)) = finalize_body(id, &mut self.sims[id], &inputs) else {
                continue;
            };
            if let Some((position, angle)) = impact {
                let state = &mut core.states[id];
                state.position = position;
                state.angle = angle;
            }
            for c in self.sims[id].colliders.clone() {
                let collider = &self.colliders[c];
                let aabb = speculative_box(collider, &pose, speculative);
                self.broad.update(c, &aabb, collider.aabb_margin(margin));
            }
        }
        if !self.fast_bullets.is_empty() {
            self.sweep_bullets(core, dt);
        }
    }

    /// Every moving body's [`finalize_body`] on `pool`'s threads, each a
    /// contiguous share of the bodies; the corrected poses into
    /// `self.impacts` (by body; written for the listed bodies only), and
    /// each thread's list of the bodies the serial pass has work for into
    /// `self.finalize_pending` (the lists in thread order are in body
    /// order).
    fn parallel_finalize(&mut self, pool: &Pool, core: &WorldCore, dt: f64) {
        let n = self.sims.len();
        self.impacts.resize(n, None);
        if self.finalize_pending.len() < pool.threads() {
            self.finalize_pending.resize_with(pool.threads(), Vec::new);
        }
        let empty = Aabb::new(Vector2::zeros(), Vector2::zeros());
        self.collider_boxes.resize(self.colliders.len(), empty);
        let inputs = FinalizeInputs::new(
            (&self.settings, &self.bodies, &self.colliders),
            (&self.shape_data, &self.broad),
            core,
            dt,
        );
        let speculative = self.settings.speculative_distance;
        let sims = SharedSlice::new(&mut self.sims);
        let impacts = SharedSlice::new(&mut self.impacts);
        let boxes = SharedSlice::new(&mut self.collider_boxes);
        let pending = SharedSlice::new(&mut self.finalize_pending);
        pool.run(&|w: &Worker<'_>| {
            // SAFETY: each thread its own list.
            let pending = unsafe { pending.get_mut(w.index) };
            for id in w.share(n) {
                // SAFETY: each body (its record, its impact, its colliders'
                // boxes: a body's colliders are its own contiguous range)
                // on one thread.
                let (sim, impact) = unsafe { (sims.get_mut(id), impacts.get_mut(id)) };
                if !sim.moving() {
                    continue;
                }
                let fast_bullet =
                    sim.bullet && is_fast(inputs.settings, sim, &inputs.solver[id + 1]);
                let Some((pose, corrected)) = finalize_body(id, sim, &inputs) else {
                    if fast_bullet {
                        *impact = None;
                        pending.push(id);
                    }
                    continue;
                };
                *impact = corrected;
                // SAFETY: as above.
                let own = unsafe { boxes.slice(sim.colliders.clone()) };
                let mut left_fat = false;
                for (c, aabb) in sim.colliders.clone().zip(own) {
                    *aabb = speculative_box(&inputs.colliders[c], &pose, speculative);
                    left_fat |= !inputs.broad.fat_contains(c, aabb);
                }
                if fast_bullet || corrected.is_some() || left_fat {
                    pending.push(id);
                }
            }
        });
    }
}
