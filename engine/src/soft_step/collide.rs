//! The collide stage: every contact of a moving body gets its manifold at
//! the current poses ([`super::contacts::update_contact`]); the contacts
//! whose enlarged boxes parted are destroyed.
//!
//! The stage is two kinds of work. The manifold of one contact
//! ([`manifold_of`]) reads the bodies' poses, the colliders and the broad
//! phase's fat boxes and writes only that contact, so the contacts can be
//! updated in any order, on any thread. What follows from each result
//! (the touching changes for the islands, the end events, the pre-solve
//! hook, the wakes, the destruction, which moves the last contact into the
//! freed slot) depends on the order and runs serially, in contact order
//! ([`SoftStep::apply_collided`]).
//!
//! On one thread each contact is updated and applied in turn. On several
//! (after Box2D v3's `b2Collide`, a task over the contact array, then a
//! serial pass that applies the begin and end flags), every contact is
//! updated first on the pool's threads (contiguous shares of the array,
//! each thread with its own scratch), its result kept in a list parallel
//! to the contacts, then the serial pass applies the results in the same
//! order the one-thread loop visits the contacts. The bits are those of
//! one thread: a manifold depends only on the contact and the poses, which
//! this stage does not change; the one thing the serial pass changes that
//! the updates read is whether a body sleeps, and a wake only turns
//! skipped contacts into moving ones, which the serial pass then updates
//! itself, at the point of the loop where one thread would have.

use super::SoftStep;
use super::bodies::BodySim;
use super::broad_phase::BroadPhase;
use super::contacts::{Contact, Side, TouchChange, update_contact};
use super::geometry::Collider;
use super::manifold::Scratch;
use super::pool::{Pool, SharedSlice, Worker};
use super::report;
use super::settings::SoftStepSettings;
use crate::body::{BodyId, BodyKind, BodyState};
use nalgebra::{Isometry2, Translation2};

/// What updating one contact found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Collided {
    /// Neither body moves (asleep or static): left as it was.
    #[default]
    Skipped,
    /// The enlarged boxes no longer overlap: to be destroyed (not updated).
    Parted,
    /// The manifold was updated; whether the contact was touching before.
    Updated { was_touching: bool },
    /// The manifold was updated on a pool's thread and the serial pass
    /// has nothing to do for it: its touching state did not change, and
    /// if it touches, it is not a sensor's, no pre-solve hook is set and
    /// neither body sleeps (so nothing to wake; a body awake when the
    /// threads ran is still awake in the serial pass, which only wakes).
    Quiet,
}

/// What the manifold of a contact reads (shared by every thread).
#[derive(Clone, Copy)]
pub(crate) struct CollideInputs<'a> {
    pub sims: &'a [BodySim],
    pub colliders: &'a [Collider],
    pub broad: &'a BroadPhase,
    /// The world's body states (poses at the start of the step).
    pub states: &'a [BodyState],
    /// The speculative and the recycle distance (m).
    pub speculative: f64,
    pub recycle_distance: f64,
    /// A pre-solve hook is set: every touching contact goes to the serial
    /// pass.
    pub has_hooks: bool,
}

impl<'a> CollideInputs<'a> {
    fn new(
        (sims, colliders, broad): (&'a [BodySim], &'a [Collider], &'a BroadPhase),
        states: &'a [BodyState],
        settings: &SoftStepSettings,
    ) -> Self {
        Self {
            sims,
            colliders,
            broad,
            states,
            speculative: settings.speculative_distance,
            recycle_distance: settings.recycle_distance,
            has_hooks: false,
        }
    }
}

/// Updates `contact`'s manifold at the bodies' current poses, unless
/// neither body moves or the pair's enlarged boxes parted; writes nothing
/// but `contact` and `scratch`. Inlined: on one thread it is the body of
/// the stage's loop, as it was before the stage was split.
#[inline(always)]
pub(crate) fn manifold_of(
    contact: &mut Contact,
    inputs: &CollideInputs<'_>,
    scratch: &mut Scratch,
) -> Collided {
    let (a, b, body_a, body_b) = (contact.a, contact.b, contact.body_a, contact.body_b);
    let (sa, sb) = (&inputs.sims[body_a], &inputs.sims[body_b]);
    if !sa.moving() && !sb.moving() {
        // Both asleep (or one static): nothing moved.
        return Collided::Skipped;
    }
    if !inputs.broad.fat_overlap(a, b) {
        return Collided::Parted;
    }
    let states = inputs.states;
    let body_pose = |id: BodyId, sim: &BodySim| {
        Isometry2::from_parts(Translation2::from(states[id].position), sim.rotation)
    };
    let (pose_a, pose_b) = (body_pose(body_a, sa), body_pose(body_b, sb));
    let (ca, cb) = (&inputs.colliders[a], &inputs.colliders[b]);
    let extent = |c: &Collider, s: &BodySim| {
        if s.kind == BodyKind::Static {
            0.0
        } else {
            c.max_extent
        }
    };
    let max_extent = extent(ca, sa).max(extent(cb, sb));
    let side_a = Side {
        shape: &ca.shape,
        collider: ca.pose(&pose_a),
        body: pose_a,
    };
    let side_b = Side {
        shape: &cb.shape,
        collider: cb.pose(&pose_b),
        body: pose_b,
    };
    let was_touching = update_contact(
        contact,
        (side_a, side_b),
        (max_extent, inputs.speculative, inputs.recycle_distance),
        scratch,
    );
    Collided::Updated { was_touching }
}

/// [`Collided::Quiet`] for an update the serial pass would do nothing
/// with (see there), else `found` unchanged.
#[inline(always)]
fn quiet_or(found: Collided, contact: &Contact, inputs: &CollideInputs<'_>) -> Collided {
    let Collided::Updated { was_touching } = found else {
        return found;
    };
    let touching = contact.touching;
    let asleep = inputs.sims[contact.body_a].asleep || inputs.sims[contact.body_b].asleep;
    let serial_work = touching && !contact.sensor && (inputs.has_hooks || asleep);
    if touching == was_touching && !serial_work {
        Collided::Quiet
    } else {
        found
    }
}

impl SoftStep {
    /// Stage 2: manifolds; destroys the contacts whose fat boxes parted.
    /// With `pool`, the manifolds are computed on its threads first (see
    /// the module docs).
    #[inline(never)]
    pub(super) fn collide(&mut self, states: &[BodyState], pool: Option<&Pool>) {
        self.contacts.changes.clear();
        let threads = pool.map_or(1, Pool::threads);
        if self.scratches.len() < threads {
            self.scratches.resize_with(threads, Scratch::default);
        }
        if let Some(pool) = pool {
            self.parallel_manifolds(pool, states);
        }
        let mut i = 0;
        while i < self.contacts.contacts.len() {
            if pool.is_some() {
                // Past the quiet ones: nothing to apply (most of a resting
                // pile's contacts).
                let quiet = self.collided[i..]
                    .iter()
                    .take_while(|&&c| c == Collided::Quiet)
                    .count();
                i += quiet;
                if i == self.contacts.contacts.len() {
                    break;
                }
            }
            let found = match pool.map(|_| self.collided[i]) {
                // Computed on the threads (a skipped contact is tried again:
                // a wake earlier in this loop may have made it moving).
                Some(found) if found != Collided::Skipped => found,
                _ => {
                    let inputs = CollideInputs::new(
                        (&self.sims, &self.colliders, &self.broad),
                        states,
                        &self.settings,
                    );
                    manifold_of(
                        &mut self.contacts.contacts[i],
                        &inputs,
                        &mut self.scratches[0],
                    )
                }
            };
            if found == Collided::Parted && pool.is_some() {
                // The results follow their contacts.
                self.collided.swap_remove(i);
            }
            if self.apply_collided(i, found) {
                i += 1;
            }
        }
        if self.settings.sleeping {
            self.apply_touch_changes();
        }
    }

    /// Every contact's [`manifold_of`] on `pool`'s threads, each thread a
    /// contiguous share of the contacts, into `self.collided`.
    fn parallel_manifolds(&mut self, pool: &Pool, states: &[BodyState]) {
        let n = self.contacts.contacts.len();
        self.collided.clear();
        self.collided.resize(n, Collided::Skipped);
        let inputs = CollideInputs {
            has_hooks: self.hooks.0.is_some(),
            ..CollideInputs::new(
                (&self.sims, &self.colliders, &self.broad),
                states,
                &self.settings,
            )
        };
        let contacts = SharedSlice::new(&mut self.contacts.contacts);
        let collided = SharedSlice::new(&mut self.collided);
        let scratches = SharedSlice::new(&mut self.scratches);
        pool.run(&|w: &Worker<'_>| {
            let mine = w.share(n);
            // SAFETY: the threads' shares are disjoint, and each thread has
            // its own scratch.
            let (contacts, collided, scratch) = unsafe {
                (
                    contacts.slice(mine.clone()),
                    collided.slice(mine),
                    scratches.get_mut(w.index),
                )
            };
            for (contact, found) in contacts.iter_mut().zip(collided) {
                *found = quiet_or(manifold_of(contact, &inputs, scratch), contact, &inputs);
            }
        });
    }

    /// What follows from contact `index`'s update, in contact order: a
    /// parted pair ends its touch and is destroyed (the last contact takes
    /// its place: returns false, the same index is visited again); an
    /// updated one records its touching change, meets the pre-solve hook
    /// and wakes the sleeping body it touches.
    fn apply_collided(&mut self, index: usize, found: Collided) -> bool {
        let contact = &self.contacts.contacts[index];
        let (body_a, body_b) = (contact.body_a, contact.body_b);
        match found {
            Collided::Skipped | Collided::Quiet => true,
            Collided::Parted => {
                if contact.touching {
                    self.contact_ended(index);
                    if self.settings.sleeping && !self.contacts.contacts[index].sensor {
                        self.islands.unlink(body_a);
                    }
                }
                self.contacts.destroy(index);
                false
            }
            Collided::Updated { was_touching } => {
                self.contacts.record_change(index, was_touching);
                let contact = &self.contacts.contacts[index];
                if contact.touching
                    && !contact.sensor
                    && let Some(hooks) = self.hooks.0.as_mut()
                {
                    let view = report::pre_solve_view(contact, (&self.colliders, &self.shape_data));
                    if !hooks.pre_solve(&view) {
                        self.contacts.disable(index);
                    }
                }
                let contact = &self.contacts.contacts[index];
                // A body touching an awake moving one cannot sleep through
                // it (a sensor does not wake what it detects).
                let (sa, sb) = (&self.sims[body_a], &self.sims[body_b]);
                if contact.touching && !contact.sensor && (sa.asleep || sb.asleep) {
                    self.wake_body(body_a);
                    self.wake_body(body_b);
                }
                true
            }
        }
    }

    /// The islands follow the touching changes of the stage (sleeping on).
    fn apply_touch_changes(&mut self) {
        for k in 0..self.contacts.changes.len() {
            let change = self.contacts.changes[k];
            let index = match change {
                TouchChange::Began(index) | TouchChange::Ended(index) => index,
            };
            if self.contacts.contacts[index].sensor {
                continue;
            }
            match change {
                TouchChange::Began(index) => {
                    let c = &self.contacts.contacts[index];
                    let (a, b) = (c.body_a, c.body_b);
                    self.wake_body(a);
                    self.wake_body(b);
                    self.islands.link(a, b);
                }
                TouchChange::Ended(index) => {
                    let a = self.contacts.contacts[index].body_a;
                    self.islands.unlink(a);
                }
            }
        }
    }
}
