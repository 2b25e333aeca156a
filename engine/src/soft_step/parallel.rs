//! The soft step's stages on several threads ([`super::pool`]), used when
//! [`super::SoftStepSettings::threads`] is above 1; each gives the bits of
//! its serial stage in `mod.rs`, `integrate.rs` and `prepare.rs`.
//!
//! - **Substep** (one job per substep): integrate velocities (bodies split
//!   among the threads), then each pass (warm start, solve, relax) in the
//!   serial pass's order: the scalar joints on thread 0, the revolute
//!   joints' colours, the contacts' overflow on thread 0, the contacts'
//!   colours; each colour's records split among the threads with a
//!   barrier after each colour (and one after thread 0's work, when it had
//!   any); integrate positions between solve and relax. Within a colour
//!   no two constraints share a dynamic body ([`super::colouring`]), and a
//!   record's static or kinematic bodies are never written back
//!   ([`super::wide_solver::FIXED`], in the joints' records too), so the
//!   threads write disjoint bodies and the order in which they do so does
//!   not change a bit.
//! - **Restitution and store**: restitution as a pass; the impulses back
//!   into the contacts, constraints split among the threads (each writes
//!   its own contacts).
//!
//! The collide and continuous stages split their per-contact and per-body
//! work the same way, in their own files (`collide.rs`, `finalize.rs`).

use super::SoftStep;
use super::colouring::{COLOURS, Colouring, Slot};
use super::contact_solver;
use super::integrate::{integrate_position, integrate_velocity};
use super::joints::wide_revolute;
use super::pool::{Pool, SharedSlice, Worker};
use super::wide_solver::{self, Bodies};
use crate::world_core::WorldCore;
use nalgebra::Vector2;
use std::ops::Range;

/// Which pass over the constraints.
#[derive(Clone, Copy)]
enum Pass {
    WarmStart,
    Solve,
    Relax,
}

impl SoftStep {
    /// Whether this step has work enough for `threads` threads
    /// ([`super::SoftStepSettings::min_work_per_thread`]): its contacts,
    /// joints and bodies, counted after the pairs stage. A function of the
    /// world's state alone, and both answers give the same bits.
    pub(super) fn enough_work_for(&self, threads: usize) -> bool {
        let work = self.contacts.contacts.len() + self.joints.len() + self.sims.len();
        work >= self.settings.min_work_per_thread.saturating_mul(threads)
    }

    /// One substep on `pool`'s threads: integrate velocities (unless
    /// `velocities_done`: the serial stage ran, force generators act), warm
    /// start, solve, integrate positions, relax.
    pub(super) fn parallel_substep(
        &mut self,
        pool: &Pool,
        core: &WorldCore,
        (h, inv_h): (f64, f64),
        gravity: Vector2<f64>,
        velocities_done: bool,
    ) {
        let controls = core.controls_act.then_some(core.controls.as_slice());
        let sims = &self.sims;
        let (rare, softness, masses) = (self.rare, &self.softness, &self.lane_masses);
        let colouring = &self.colouring;
        let bodies = Bodies::new(&mut self.bodies);
        let wide = SharedSlice::new(&mut self.wide);
        // What thread 0 solves alone before the colours; whether there is
        // any decides the barriers, the same way on every thread.
        let overflow_empty = self.constraints.is_empty();
        let extra = SharedSlice::new(&mut self.wide_extra);
        let overflow = SharedSlice::new(std::slice::from_mut(&mut self.constraints));
        let (mut scalar_joints, wide_joints) = self.joints.split_for_threads();
        let scalar_empty = scalar_joints.is_empty();
        let scalar_joints = SharedSlice::new(std::slice::from_mut(&mut scalar_joints));
        let joint_colouring = wide_joints.colouring;
        let joint_colours = !wide_joints.records.is_empty();
        let joint_records = SharedSlice::new(wide_joints.records);
        let joint_axial = SharedSlice::new(wide_joints.axial);
        pool.run(&|w: &Worker<'_>| {
            if !velocities_done {
                for id in w.share(sims.len()) {
                    // SAFETY: each thread its own bodies.
                    let r = unsafe { bodies.get_mut(id + 1) };
                    integrate_velocity(id, &sims[id], r, (controls, None), h, gravity);
                }
                w.sync();
            }
            for pass in [Pass::WarmStart, Pass::Solve, Pass::Relax] {
                // The serial order of a pass: the scalar joints, the joint
                // colours, the contacts' overflow, the contact colours.
                // Whether thread 0 wrote bodies since the last barrier.
                let mut unsynced = false;
                if !scalar_empty {
                    if w.index == 0 {
                        // SAFETY: the other threads wait at the next barrier.
                        let (all, joints) =
                            unsafe { (bodies.slice(0..bodies.len()), scalar_joints.get_mut(0)) };
                        match pass {
                            Pass::WarmStart => joints.warm_start(all),
                            Pass::Solve => joints.solve(all, h, true),
                            Pass::Relax => joints.solve(all, h, false),
                        }
                    }
                    unsynced = true;
                }
                if joint_colours {
                    if unsynced {
                        w.sync();
                    }
                    each_colour_share(w, joint_colouring, |mine| {
                        // SAFETY: the threads' shares of a colour are
                        // disjoint and their joints share no moved body
                        // (a body they do not move carries `FIXED`).
                        let (records, axial) =
                            unsafe { (joint_records.slice(mine.clone()), joint_axial.slice(mine)) };
                        match pass {
                            Pass::WarmStart => {
                                wide_revolute::warm_start_shared(records, axial, bodies);
                            }
                            Pass::Solve => {
                                wide_revolute::solve_shared(records, axial, bodies, inv_h);
                            }
                            Pass::Relax => {
                                wide_revolute::relax_shared(records, axial, bodies, inv_h);
                            }
                        }
                    });
                    unsynced = false;
                }
                if !overflow_empty {
                    if w.index == 0 {
                        // SAFETY: the other threads wait at the next barrier.
                        let (all, overflow) =
                            unsafe { (bodies.slice(0..bodies.len()), overflow.get_mut(0)) };
                        match pass {
                            Pass::WarmStart => contact_solver::warm_start(overflow, all),
                            Pass::Solve => contact_solver::solve(overflow, all, inv_h, true),
                            Pass::Relax => contact_solver::solve(overflow, all, inv_h, false),
                        }
                    }
                    unsynced = true;
                }
                if unsynced {
                    w.sync();
                }
                each_colour_share(w, colouring, |mine| {
                    // SAFETY: the threads' shares of a colour are disjoint;
                    // see the module docs for the bodies.
                    let records = unsafe { wide.slice(mine.clone()) };
                    // SAFETY: as the records (the same share).
                    let extras = rare.then(|| unsafe { extra.slice(mine) });
                    match pass {
                        Pass::WarmStart => {
                            wide_solver::warm_start_shared(records, extras, bodies, masses)
                        }
                        Pass::Solve => {
                            wide_solver::solve_shared(records, bodies, masses, inv_h, softness)
                        }
                        Pass::Relax => {
                            wide_solver::relax_shared(records, extras, bodies, masses, inv_h)
                        }
                    }
                });
                if let Pass::Solve = pass {
                    for id in w.share(sims.len()) {
                        // SAFETY: each thread its own bodies.
                        let r = unsafe { bodies.get_mut(id + 1) };
                        integrate_position(&sims[id], r, h);
                    }
                    w.sync();
                }
            }
        });
    }

    /// Restitution (overflow, then colour after colour) and the impulses
    /// back into the contacts, on `pool`'s threads.
    pub(super) fn parallel_restitution_and_store(&mut self, pool: &Pool, threshold: f64) {
        let colouring = &self.colouring;
        let constrained = &self.constrained;
        let (extras, masses) = (&self.wide_extra, &self.lane_masses);
        let bodies = Bodies::new(&mut self.bodies);
        let wide = SharedSlice::new(&mut self.wide);
        let overflow = SharedSlice::new(std::slice::from_mut(&mut self.constraints));
        let contacts = SharedSlice::new(&mut self.contacts.contacts);
        pool.run(&|w: &Worker<'_>| {
            if w.index == 0 {
                // SAFETY: the other threads wait at the next barrier.
                let (all, overflow) =
                    unsafe { (bodies.slice(0..bodies.len()), overflow.get_mut(0)) };
                contact_solver::restitution(overflow, all, threshold);
            }
            w.sync();
            each_colour_share(w, colouring, |mine| {
                // SAFETY: disjoint shares of one colour.
                let part = unsafe { wide.slice(mine.clone()) };
                wide_solver::restitution_shared(part, &extras[mine], bodies, masses, threshold);
            });
            // Store: the overflow on thread 0 while the others wait, then
            // the lanes, each constraint's contact its own.
            if w.index == 0 {
                // SAFETY: the other threads wait at the next barrier.
                let (overflow, all) =
                    unsafe { (overflow.get(0), contacts.slice(0..contacts.len())) };
                contact_solver::store_impulses(overflow, all);
            }
            w.sync();
            for i in w.share(constrained.len()) {
                if let Slot::Lane { record, lane } = colouring.slot(i) {
                    // SAFETY: one constraint per contact; the records are
                    // only read in this phase.
                    let (contact, record, extra) = unsafe {
                        (
                            contacts.get_mut(constrained[i]),
                            wide.get(record),
                            &extras[record],
                        )
                    };
                    wide_solver::store_lane((record, extra), lane, contact);
                }
            }
        });
    }
}

/// Colour after colour, this thread's share of the colour's records
/// (indices into the wide records) given to `each`, then a barrier: within
/// a colour the threads' shares touch disjoint bodies, and a colour starts
/// only when every thread has finished the one before.
#[inline(always)]
fn each_colour_share(w: &Worker<'_>, colouring: &Colouring, mut each: impl FnMut(Range<usize>)) {
    for colour in 0..COLOURS {
        let records = colouring.records(colour);
        if records.is_empty() {
            continue;
        }
        let mine = w.share(records.len());
        each(records.start + mine.start..records.start + mine.end);
        w.sync();
    }
}
