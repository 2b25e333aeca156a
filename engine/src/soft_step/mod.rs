//! The soft-step contact model: Box2D v3's "soft step" (Catto's Solver2D
//! study, "TGS soft"; the family of rapier's TGS-soft solver), in f64, for
//! scenes of thousands of bodies (seed §2.2). It is the seed's second way
//! of handling contact (§7.1, after Mirtich and Canny: a series of
//! impulses), beside the exact model's contact forces.
//!
//! One step of length dt with n substeps of h = dt/n, in order (each stage
//! timed into the [`crate::StepProfile`] under its name when profiling is
//! on):
//!
//! 1. **pairs**: the broad phase ([`broad_phase`]) queries the bodies whose
//!    bounding box left its enlarged box; each new overlapping pair becomes
//!    a persistent contact ([`contacts`]);
//! 2. **collide**: every contact of an awake body gets its manifold at the
//!    current poses ([`manifold`]: up to two points with feature ids,
//!    speculative points within [`SoftStepSettings::speculative_distance`]),
//!    each point keeping the impulses of last step's point with the same id;
//!    pairs whose enlarged boxes parted are destroyed;
//! 3. **prepare**: a constraint per touching contact ([`contact_solver`]):
//!    anchors, effective masses, inherited impulses, approach speed;
//! 4. n times: **integrate velocities** (gravity and every force generator
//!    active in the step, evaluated at the substep's start state),
//!    **warm start**, **solve** with the soft bias
//!    ([`softness`]), **integrate positions** (symplectic Euler:
//!    x += h v, θ += h ω), **relax** (solve again without bias, with
//!    friction);
//! 5. **restitution**: points that approached faster than the threshold
//!    bounce with their restitution;
//! 6. **store**: impulses back into the contacts, states into the world,
//!    bounding boxes into the broad phase;
//! 7. **continuous**: fast bodies swept against static ones
//!    ([`continuous`]);
//! 8. **sleep** (when on): islands at rest fall asleep ([`islands`]).
//!
//! Events (landing, apex) are located inside each substep by linear
//! interpolation, exact for positions (they move linearly in a substep).
//!
//! Nothing is allocated per step once the contact and constraint arrays
//! have grown to the scene's size.

mod bodies;
mod broad_phase;
mod colouring;
mod contact_solver;
mod contacts;
mod continuous;
mod geometry;
mod islands;
mod lanes;
#[cfg(target_arch = "x86_64")]
mod lanes_avx;
mod manifold;
mod settings;
mod softness;
mod wide_solver;

pub use settings::SoftStepSettings;
pub use softness::Softness;

use crate::body::{BodyId, BodyKind, BodyState};
use crate::contact::pipeline::Phase;
use crate::error::{EngineError, Result};
use crate::events::EventRecord;
use crate::forces::{ForceContext, Wrench};
use crate::integrators::Stats;
use crate::world_core::{WorldCore, check_energy_value};
use bodies::{BodyMass, BodySim, SolverBody, solver_body, solver_index};
use broad_phase::BroadPhase;
use colouring::{Colouring, Slot};
use contact_solver::{ContactConstraint, PairMass};
use contacts::{ContactSet, Side, TouchChange};
use geometry::Collider;
use nalgebra::{Isometry2, Translation2, UnitComplex, Vector2};
use wide_solver::{WideConstraint, WideExtra};

/// The soft step's state: per-body solver records, broad phase, contacts,
/// constraints, islands.
#[derive(Debug)]
pub struct SoftStep {
    settings: SoftStepSettings,
    sims: Vec<BodySim>,
    /// The prepare stage's copy of the bodies' masses (see [`BodyMass`]).
    masses: Vec<BodyMass>,
    /// One per convex shape; a body's are contiguous.
    colliders: Vec<Collider>,
    /// Solver records; index 0 is the static dummy, body `i` is `i + 1`.
    bodies: Vec<SolverBody>,
    broad: BroadPhase,
    contacts: ContactSet,
    /// The constraints of the step's colours, four per record, colour
    /// after colour.
    wide: Vec<WideConstraint>,
    wide_extra: Vec<WideExtra>,
    /// The overflow constraints (no free colour), solved one at a time.
    constraints: Vec<ContactConstraint>,
    colouring: Colouring,
    /// The contact of each constraint, in contact order (the colouring's
    /// order).
    constrained: Vec<usize>,
    islands: islands::Islands,
    stats: Stats,
    // Scratch reused by every step.
    wrenches: Vec<Wrench>,
    force_states: Vec<BodyState>,
    substep_start: Vec<SolverBody>,
    touching_pairs: Vec<(BodyId, BodyId)>,
    resting: Vec<usize>,
}

impl SoftStep {
    /// The model for the bodies already in `core`.
    pub(crate) fn new(core: &WorldCore, settings: SoftStepSettings) -> Self {
        let mut model = Self {
            settings,
            sims: Vec::new(),
            masses: Vec::new(),
            colliders: Vec::new(),
            bodies: vec![SolverBody::AT_REST],
            broad: BroadPhase::default(),
            contacts: ContactSet::default(),
            wide: Vec::new(),
            wide_extra: Vec::new(),
            constraints: Vec::new(),
            colouring: Colouring::default(),
            constrained: Vec::new(),
            islands: islands::Islands::default(),
            stats: Stats::default(),
            wrenches: Vec::new(),
            force_states: Vec::new(),
            substep_start: Vec::new(),
            touching_pairs: Vec::new(),
            resting: Vec::new(),
        };
        for id in 0..core.bodies.len() {
            model.body_added(core, id);
        }
        model
    }

    /// The settings.
    pub fn settings(&self) -> &SoftStepSettings {
        &self.settings
    }

    /// Replaces the settings (validated by the caller). Materials of bodies
    /// without their own take the new defaults; turning sleeping on builds
    /// the islands from the contacts touching now.
    pub(crate) fn set_settings(&mut self, core: &WorldCore, settings: SoftStepSettings) {
        let was_sleeping = self.settings.sleeping;
        self.settings = settings;
        for (sim, body) in self.sims.iter_mut().zip(&core.bodies) {
            sim.friction = body.friction.unwrap_or(settings.friction);
            sim.restitution = body.restitution.unwrap_or(settings.restitution);
        }
        if settings.sleeping && !was_sleeping {
            self.rebuild_islands();
        }
        if !settings.sleeping {
            for sim in &mut self.sims {
                sim.asleep = false;
                sim.sleep_time = 0.0;
            }
        }
    }

    fn rebuild_islands(&mut self) {
        self.islands = islands::Islands::default();
        for (id, sim) in self.sims.iter().enumerate() {
            self.islands.add_body(id, sim.kind == BodyKind::Dynamic);
        }
        for c in &self.contacts.contacts {
            if c.touching {
                self.islands.link(c.body_a, c.body_b);
            }
        }
    }

    /// Work done: steps and force evaluations (one per substep).
    pub(crate) fn stats(&self) -> Stats {
        self.stats
    }

    /// Body `id` was appended to `core`: O(log n) (a proxy inserted in the
    /// broad phase's tree).
    pub(crate) fn body_added(&mut self, core: &WorldCore, id: BodyId) {
        let body = &core.bodies[id];
        let state = &core.states[id];
        let first = self.colliders.len();
        if let Some(shape) = &body.shape {
            self.colliders.extend(Collider::of(id, shape));
        }
        let range = first..self.colliders.len();
        let sim = BodySim::new(
            body,
            state.angle,
            (&self.colliders[range.clone()], range.clone()),
            self.settings.friction,
            self.settings.restitution,
        );
        let is_static = body.kind == BodyKind::Static;
        let margin = if is_static {
            0.0
        } else {
            self.settings.aabb_margin
        };
        let pose = Isometry2::from_parts(Translation2::from(state.position), sim.rotation);
        for c in range {
            let aabb = self.colliders[c]
                .shape
                .aabb_at(&self.colliders[c].pose(&pose))
                .loosened(self.settings.speculative_distance);
            self.broad.add(c, Some(aabb.loosened(margin)), is_static);
        }
        self.bodies.push(solver_body(state, body.kind));
        self.islands.add_body(id, body.kind == BodyKind::Dynamic);
        self.sims.push(sim);
    }

    /// Advances `core` over the force segments ending at `edges`, one soft
    /// step per segment.
    pub(crate) fn advance(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        let mut t = core.time;
        for &end in edges {
            self.step(core, t, end, found)?;
            if core.stopped {
                return Ok(());
            }
            t = end;
        }
        Ok(())
    }

    /// One soft step from `t0` to `t1` (s).
    fn step(
        &mut self,
        core: &mut WorldCore,
        t0: f64,
        t1: f64,
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        let dt = t1 - t0;
        let settings = self.settings;
        let n = settings.substeps;
        let h = dt / n as f64;
        let inv_h = 1.0 / h;

        let started = core.profiler.start();
        self.update_pairs();
        core.profiler.stop(Phase::Pairs, started);

        let started = core.profiler.start();
        self.collide(core);
        core.profiler.stop(Phase::Collide, started);

        let started = core.profiler.start();
        self.load_bodies(core);
        self.prepare(core, h);
        core.profiler.stop(Phase::Prepare, started);

        // Forces active during this segment (the world split the step at
        // every window edge, so the midpoint decides).
        let middle = 0.5 * (t0 + t1);
        let gravity: Vector2<f64> = core
            .forces
            .iter()
            .filter(|f| f.window.contains(middle))
            .filter_map(|f| f.force.uniform_acceleration())
            .sum();
        let general = core
            .forces
            .iter()
            .any(|f| f.window.contains(middle) && f.force.uniform_acceleration().is_none());
        let watch_events = !core.events.is_empty();

        for k in 0..n {
            let t_sub = t0 + k as f64 * h;
            let started = core.profiler.start();
            if watch_events {
                self.substep_start.clone_from(&self.bodies);
            }
            self.integrate_velocities(core, h, gravity, general.then_some((t_sub, middle)));
            core.profiler.stop(Phase::Integrate, started);

            let started = core.profiler.start();
            contact_solver::warm_start(&mut self.constraints, &mut self.bodies);
            wide_solver::warm_start(&mut self.wide, &mut self.bodies);
            core.profiler.stop(Phase::WarmStart, started);

            let started = core.profiler.start();
            contact_solver::solve(
                &mut self.constraints,
                &mut self.bodies,
                inv_h,
                settings.push_out_speed,
                true,
            );
            wide_solver::solve(
                &mut self.wide,
                &mut self.bodies,
                inv_h,
                settings.push_out_speed,
            );
            core.profiler.stop(Phase::Solve, started);

            let started = core.profiler.start();
            self.integrate_positions(h);
            core.profiler.stop(Phase::Integrate, started);

            let started = core.profiler.start();
            contact_solver::solve(
                &mut self.constraints,
                &mut self.bodies,
                inv_h,
                settings.push_out_speed,
                false,
            );
            wide_solver::relax(&mut self.wide, &mut self.bodies, inv_h);
            core.profiler.stop(Phase::Relax, started);
            self.stats.evaluations += 1;

            if watch_events {
                let t_end = if k + 1 == n { t1 } else { t_sub + h };
                if self.locate_events(core, (t_sub, t_end), found) {
                    return Ok(());
                }
            }
        }

        let started = core.profiler.start();
        contact_solver::restitution(
            &mut self.constraints,
            &mut self.bodies,
            settings.restitution_threshold,
        );
        wide_solver::restitution(
            &mut self.wide,
            &self.wide_extra,
            &mut self.bodies,
            settings.restitution_threshold,
        );
        core.profiler.stop(Phase::Restitution, started);

        let started = core.profiler.start();
        self.store_impulses();
        let step = self.stats.steps;
        self.write_states(core, t0, step)?;
        core.profiler.stop(Phase::Store, started);

        let started = core.profiler.start();
        self.finalize_bodies(core, dt);
        core.profiler.stop(Phase::Continuous, started);

        if settings.sleeping {
            let started = core.profiler.start();
            self.sleep(core);
            core.profiler.stop(Phase::Sleep, started);
        }

        core.time = t1;
        self.stats.steps += 1;
        core.profiler.profile.steps += 1;
        if let Some(limit) = core.energy_limit {
            let energy = core.energy_of(t1, &core.states);
            check_energy_value(energy, (t0, t1), step, limit)?;
        }
        Ok(())
    }

    /// Stage 1: contacts for the new overlapping pairs of colliders.
    #[inline(never)]
    fn update_pairs(&mut self) {
        let sims = &self.sims;
        let colliders = &self.colliders;
        let contacts = &mut self.contacts;
        self.broad.find_pairs(|a, b| {
            let (ca, cb) = (&colliders[a], &colliders[b]);
            if ca.body == cb.body {
                return;
            }
            let (sa, sb) = (&sims[ca.body], &sims[cb.body]);
            // At least one dynamic body: static and kinematic bodies do not
            // push each other.
            if sa.kind != BodyKind::Dynamic && sb.kind != BodyKind::Dynamic {
                return;
            }
            if contacts.contains(a, b) {
                return;
            }
            let (first, second) = contacts::ordered((a, &ca.shape), (b, &cb.shape));
            let bodies = (colliders[first].body, colliders[second].body);
            let friction = (sa.friction * sb.friction).sqrt();
            let restitution = sa.restitution.max(sb.restitution);
            contacts.create((first, second), bodies, friction, restitution);
        });
    }

    /// Stage 2: manifolds; destroys the contacts whose fat boxes parted.
    #[inline(never)]
    fn collide(&mut self, core: &WorldCore) {
        let settings = self.settings;
        self.contacts.changes.clear();
        let mut i = 0;
        while i < self.contacts.contacts.len() {
            let (a, b, body_a, body_b, touching) = {
                let c = &self.contacts.contacts[i];
                (c.a, c.b, c.body_a, c.body_b, c.touching)
            };
            let (sa, sb) = (&self.sims[body_a], &self.sims[body_b]);
            if !sa.moving() && !sb.moving() {
                // Both asleep (or one static): nothing moved.
                i += 1;
                continue;
            }
            if !self.broad.fat_overlap(a, b) {
                if touching && settings.sleeping {
                    self.islands.unlink(body_a);
                }
                self.contacts.destroy(i);
                continue;
            }
            let body_pose = |id: BodyId, sim: &BodySim| {
                Isometry2::from_parts(Translation2::from(core.states[id].position), sim.rotation)
            };
            let (pose_a, pose_b) = (body_pose(body_a, sa), body_pose(body_b, sb));
            let (ca, cb) = (&self.colliders[a], &self.colliders[b]);
            let extent = |c: &Collider, s: &BodySim| {
                if s.kind == BodyKind::Static {
                    0.0
                } else {
                    c.max_extent
                }
            };
            let max_extent = extent(ca, sa).max(extent(cb, sb));
            let friction = (sa.friction * sb.friction).sqrt();
            let restitution = sa.restitution.max(sb.restitution);
            let contact = &mut self.contacts.contacts[i];
            contact.friction = friction;
            contact.restitution = restitution;
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
            self.contacts.update(
                i,
                (side_a, side_b),
                max_extent,
                settings.speculative_distance,
                settings.recycle_distance,
            );
            // A body touching an awake moving one cannot sleep through it.
            if self.contacts.contacts[i].touching && (sa.asleep || sb.asleep) {
                self.wake_body(body_a);
                self.wake_body(body_b);
            }
            i += 1;
        }
        if settings.sleeping {
            for k in 0..self.contacts.changes.len() {
                let change = self.contacts.changes[k];
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

    /// Copies the world's velocities into the solver records and resets
    /// the motion since the step began.
    #[inline(never)]
    fn load_bodies(&mut self, core: &WorldCore) {
        self.masses.clear();
        self.masses.extend(self.sims.iter().map(BodyMass::of));
        for (id, sim) in self.sims.iter().enumerate() {
            let record = &mut self.bodies[id + 1];
            *record = if sim.moving() {
                solver_body(&core.states[id], sim.kind)
            } else {
                SolverBody::AT_REST
            };
        }
    }

    /// Stage 3: a constraint per touching contact with an awake body,
    /// coloured ([`colouring`]) and packed four by four for the wide
    /// solver; those that found no colour stay scalar (the overflow).
    #[inline(never)]
    fn prepare(&mut self, core: &mut WorldCore, h: f64) {
        let settings = &self.settings;
        // Contact stiffness capped at a quarter of the substep's Nyquist
        // frequency (1/(8h)), twice as stiff against static bodies.
        let hertz = settings.contact_hertz.min(0.125 / h);
        let soft = Softness::new(hertz, settings.contact_damping_ratio, h);
        let static_soft = Softness::new(2.0 * hertz, settings.contact_damping_ratio, h);
        let warm = if settings.warm_starting { 1.0 } else { 0.0 };
        self.colouring.clear(self.sims.len());
        self.constrained.clear();
        let mut points = 0;
        for (index, c) in self.contacts.contacts.iter().enumerate() {
            if c.count == 0 {
                continue;
            }
            let (sa, sb) = (&self.masses[c.body_a], &self.masses[c.body_b]);
            if !sa.moving && !sb.moving {
                continue;
            }
            let dynamic = |id: BodyId, s: &BodyMass| (s.kind == BodyKind::Dynamic).then_some(id);
            self.colouring
                .add(dynamic(c.body_a, sa), dynamic(c.body_b, sb));
            self.constrained.push(index);
            points += c.count;
        }
        let touching = self.constrained.len();
        let records = self.colouring.finish();
        // The records of the last step are overwritten lane by lane, every
        // field; only new ones are initialised first.
        self.wide.resize(records, WideConstraint::default());
        self.wide_extra.resize(records, WideExtra::default());
        self.constraints.clear();
        let (masses, contacts, bodies) = (&self.masses, &self.contacts.contacts, &self.bodies);
        // In contact order, so that the contacts are read in memory order;
        // each colour's records are written in order too.
        for (i, &index) in self.constrained.iter().enumerate() {
            let c = &contacts[index];
            let (sa, sb) = (&masses[c.body_a], &masses[c.body_b]);
            let mass = PairMass {
                a: solver_index(c.body_a, sa.kind),
                b: solver_index(c.body_b, sb.kind),
                inv_mass_a: sa.inv_mass,
                inv_inertia_a: sa.inv_inertia,
                inv_mass_b: sb.inv_mass,
                inv_inertia_b: sb.inv_inertia,
            };
            let softness = if sa.kind == BodyKind::Static || sb.kind == BodyKind::Static {
                static_soft
            } else {
                soft
            };
            let constraint = contact_solver::prepare(c, index, mass, softness, bodies, warm);
            match self.colouring.slot(i) {
                Slot::Lane { record, lane } => wide_solver::set_lane(
                    (&mut self.wide[record], &mut self.wide_extra[record]),
                    lane,
                    &constraint,
                ),
                // Overflow positions come in order.
                Slot::Overflow(_) => self.constraints.push(constraint),
            }
        }
        for (record, lane) in self.colouring.padding() {
            wide_solver::set_padding_lane(
                (&mut self.wide[record], &mut self.wide_extra[record]),
                lane,
            );
        }
        let profile = &mut core.profiler.profile;
        profile.contacts += self.contacts.contacts.len() as u64;
        profile.touching += touching as u64;
        profile.points += points as u64;
    }

    /// Stage 6 (first part): the impulses back into the contacts, for the
    /// next step's warm start and for the reports, in contact order.
    fn store_impulses(&mut self) {
        contact_solver::store_impulses(&self.constraints, &mut self.contacts.contacts);
        for (i, &index) in self.constrained.iter().enumerate() {
            if let Slot::Lane { record, lane } = self.colouring.slot(i) {
                let contact = &mut self.contacts.contacts[index];
                wide_solver::store_lane(
                    (&self.wide[record], &self.wide_extra[record]),
                    lane,
                    contact,
                );
            }
        }
    }

    /// v += h (g + F/m), ω += h τ/I for every awake dynamic body; the force
    /// generators (other than uniform fields) see the state at the
    /// substep's start, at time `t_sub`, active as at `middle`.
    #[inline(never)]
    fn integrate_velocities(
        &mut self,
        core: &WorldCore,
        h: f64,
        gravity: Vector2<f64>,
        general: Option<(f64, f64)>,
    ) {
        if let Some((t_sub, middle)) = general {
            self.force_states.clone_from(&core.states);
            for (id, sim) in self.sims.iter().enumerate() {
                if sim.moving() {
                    let r = &self.bodies[id + 1];
                    let s = &mut self.force_states[id];
                    s.position += r.dp;
                    s.angle += r.dtheta;
                    s.velocity = r.v;
                    s.angular_velocity = r.w;
                }
            }
            self.wrenches.clear();
            self.wrenches.resize(core.bodies.len(), Wrench::default());
            let ctx = ForceContext {
                t: t_sub,
                bodies: &core.bodies,
                states: &self.force_states,
            };
            for f in &core.forces {
                if f.window.contains(middle) && f.force.uniform_acceleration().is_none() {
                    f.force.apply(&ctx, &mut self.wrenches);
                }
            }
        }
        for (id, sim) in self.sims.iter().enumerate() {
            if sim.kind != BodyKind::Dynamic || sim.asleep {
                continue;
            }
            let r = &mut self.bodies[id + 1];
            r.v += h * gravity;
            if general.is_some() {
                let w = &self.wrenches[id];
                r.v += (h * sim.inv_mass) * w.force;
                r.w += h * sim.inv_inertia * w.torque;
            }
        }
    }

    /// x += h v, θ += h ω (symplectic Euler) for every awake moving body.
    #[inline(never)]
    fn integrate_positions(&mut self, h: f64) {
        for (sim, r) in self.sims.iter().zip(&mut self.bodies[1..]) {
            if !sim.moving() {
                continue;
            }
            r.dp += h * r.v;
            if r.w != 0.0 {
                r.dtheta += h * r.w;
                let (s, c) = bodies::small_sin_cos(r.dtheta);
                r.dq = (c, s);
            }
        }
    }

    /// Stage 6: the solver's motion into the world's states, with the
    /// non-finite guard naming the body.
    #[inline(never)]
    fn write_states(&mut self, core: &mut WorldCore, t0: f64, step: u64) -> Result<()> {
        for (id, sim) in self.sims.iter().enumerate() {
            if !sim.moving() {
                continue;
            }
            let r = &self.bodies[id + 1];
            let s = &mut core.states[id];
            s.position += r.dp;
            s.angle += r.dtheta;
            s.velocity = r.v;
            s.angular_velocity = r.w;
            let finite = [
                s.position.x,
                s.position.y,
                s.angle,
                s.velocity.x,
                s.velocity.y,
            ]
            .iter()
            .chain([&s.angular_velocity])
            .all(|x| x.is_finite());
            if !finite {
                return Err(EngineError::BlowUp {
                    t: t0,
                    step,
                    reason: format!("non-finite state of body '{}'", core.bodies[id].name),
                });
            }
        }
        Ok(())
    }

    /// Stage 7: bounding boxes into the broad phase, fast bodies swept
    /// against static ones, sleep timers.
    #[inline(never)]
    fn finalize_bodies(&mut self, core: &mut WorldCore, dt: f64) {
        let settings = self.settings;
        for id in 0..self.sims.len() {
            let sim = &self.sims[id];
            if !sim.moving() {
                continue;
            }
            let r = self.bodies[id + 1];
            if settings.sleeping {
                let speed = r.v.norm() + sim.max_extent * r.w.abs();
                let sim = &mut self.sims[id];
                if sim.kind == BodyKind::Dynamic && speed < settings.sleep_threshold {
                    sim.sleep_time += dt;
                } else {
                    sim.sleep_time = 0.0;
                }
            }
            let sim = &self.sims[id];
            if sim.colliders.is_empty() {
                continue;
            }
            let motion = r.dp.norm() + sim.max_extent * r.dtheta.abs();
            if settings.continuous
                && sim.kind == BodyKind::Dynamic
                && motion > continuous::FAST_FRACTION * sim.min_extent
            {
                let s = core.states[id];
                let sweep = continuous::Sweep {
                    start: (s.position - r.dp, s.angle - r.dtheta),
                    end: (s.position, s.angle),
                    dt,
                };
                let start = Isometry2::new(sweep.start.0, sweep.start.1);
                let end = Isometry2::new(sweep.end.0, sweep.end.1);
                let swept = sim
                    .colliders
                    .clone()
                    .map(|c| {
                        let collider = &self.colliders[c];
                        collider
                            .shape
                            .aabb_at(&collider.pose(&start))
                            .merged(&collider.shape.aabb_at(&collider.pose(&end)))
                    })
                    .reduce(|a, b| a.merged(&b))
                    .expect("a body with colliders");
                if let Some(toi) = continuous::first_impact(
                    &core.bodies[id],
                    &sweep,
                    &swept,
                    &self.broad,
                    &core.bodies,
                    &core.states,
                ) {
                    let f = toi / dt;
                    let state = &mut core.states[id];
                    state.position = sweep.start.0 + f * (sweep.end.0 - sweep.start.0);
                    state.angle = sweep.start.1 + f * (sweep.end.1 - sweep.start.1);
                }
            }
            let s = &core.states[id];
            let rotation = UnitComplex::new(s.angle);
            self.sims[id].rotation = rotation;
            let pose = Isometry2::from_parts(Translation2::from(s.position), rotation);
            for c in self.sims[id].colliders.clone() {
                let collider = &self.colliders[c];
                let aabb = collider
                    .shape
                    .aabb_at(&collider.pose(&pose))
                    .loosened(settings.speculative_distance);
                self.broad.update(c, &aabb, settings.aabb_margin);
            }
        }
    }

    /// Stage 8: islands whose every body has been at rest for the time to
    /// sleep fall asleep.
    #[inline(never)]
    fn sleep(&mut self, core: &mut WorldCore) {
        self.touching_pairs.clear();
        for c in &self.contacts.contacts {
            if c.touching
                && self.sims[c.body_a].kind == BodyKind::Dynamic
                && self.sims[c.body_b].kind == BodyKind::Dynamic
            {
                self.touching_pairs.push((c.body_a, c.body_b));
            }
        }
        // A moving kinematic body keeps the bodies it touches awake.
        for c in &self.contacts.contacts {
            if !c.touching {
                continue;
            }
            for (k, other) in [(c.body_a, c.body_b), (c.body_b, c.body_a)] {
                let r = &self.bodies[k + 1];
                if self.sims[k].kind == BodyKind::Kinematic && (r.v.norm() > 0.0 || r.w != 0.0) {
                    self.sims[other].sleep_time = 0.0;
                }
            }
        }
        let time_to_sleep = self.settings.time_to_sleep;
        let sims = &self.sims;
        self.islands.resting(
            |b| sims[b].sleep_time >= time_to_sleep,
            &self.touching_pairs,
            &mut self.resting,
        );
        for k in 0..self.resting.len() {
            let island = self.resting[k];
            self.islands.set_asleep(island, true);
            for &b in self.islands.bodies(island) {
                self.sims[b].asleep = true;
                self.bodies[b + 1] = SolverBody::AT_REST;
                core.states[b].velocity = Vector2::zeros();
                core.states[b].angular_velocity = 0.0;
            }
        }
    }

    /// Wakes the island of `body` if it sleeps.
    fn wake_body(&mut self, body: BodyId) {
        if !self.sims[body].asleep {
            return;
        }
        let Some(island) = self.islands.island(body) else {
            self.sims[body].asleep = false;
            return;
        };
        self.islands.set_asleep(island, false);
        for &b in self.islands.bodies(island) {
            self.sims[b].asleep = false;
            self.sims[b].sleep_time = 0.0;
        }
    }

    /// Whether body `id` sleeps now.
    pub(crate) fn is_asleep(&self, id: BodyId) -> bool {
        self.sims[id].asleep
    }

    /// Body `id` was removed (it is now an inert static body without a
    /// shape): its proxy, contacts and island membership go.
    pub(crate) fn body_removed(&mut self, core: &WorldCore, id: BodyId) {
        for c in self.sims[id].colliders.clone() {
            self.broad.remove(c);
        }
        self.contacts.destroy_body(id);
        self.islands.remove_body(id);
        let empty = self.colliders.len();
        self.sims[id] = BodySim::new(
            &core.bodies[id],
            core.states[id].angle,
            (&[], empty..empty),
            0.0,
            0.0,
        );
        self.bodies[id + 1] = SolverBody::AT_REST;
    }

    /// Events crossed during the substep `(t_a, t_b)`, located by linear
    /// interpolation between its start and end states; returns whether a
    /// terminal one stopped the world (its state written to `core`).
    fn locate_events(
        &mut self,
        core: &mut WorldCore,
        (t_a, t_b): (f64, f64),
        found: &mut Vec<EventRecord>,
    ) -> bool {
        let state_at = |records: &[SolverBody], id: BodyId| {
            let r = &records[id + 1];
            let s = core.states[id];
            if self.sims[id].moving() {
                BodyState {
                    position: s.position + r.dp,
                    angle: s.angle + r.dtheta,
                    velocity: r.v,
                    angular_velocity: r.w,
                }
            } else {
                s
            }
        };
        let mut hits: Vec<(f64, usize)> = Vec::new();
        for (index, spec) in core.events.iter().enumerate() {
            let ga = spec.quantity.of(&state_at(&self.substep_start, spec.body)) - spec.level;
            let gb = spec.quantity.of(&state_at(&self.bodies, spec.body)) - spec.level;
            if spec.crossing.detects(ga, gb) {
                let f = if gb == ga { 1.0 } else { ga / (ga - gb) };
                hits.push((f, index));
            }
        }
        if hits.is_empty() {
            return false;
        }
        hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut stop: Option<(f64, Vec<BodyState>)> = None;
        let interpolate = |f: f64| -> Vec<BodyState> {
            (0..core.states.len())
                .map(|id| {
                    let (a, b) = (
                        state_at(&self.substep_start, id),
                        state_at(&self.bodies, id),
                    );
                    BodyState {
                        position: a.position + f * (b.position - a.position),
                        angle: a.angle + f * (b.angle - a.angle),
                        velocity: a.velocity + f * (b.velocity - a.velocity),
                        angular_velocity: a.angular_velocity
                            + f * (b.angular_velocity - a.angular_velocity),
                    }
                })
                .collect()
        };
        for (f, index) in hits {
            let t = if f >= 1.0 { t_b } else { t_a + f * (t_b - t_a) };
            let states = interpolate(f);
            let spec = &core.events[index];
            let terminal = spec.terminal;
            found.push(EventRecord {
                name: spec.name.clone(),
                t,
                states: states.clone(),
            });
            if terminal {
                stop = Some((t, states));
                break;
            }
        }
        match stop {
            Some((t, states)) => {
                core.states = states;
                core.time = t;
                core.stopped = true;
                true
            }
            None => false,
        }
    }
}
