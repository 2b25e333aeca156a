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
//! 1. **pairs**: the broad phase (`broad_phase.rs`) queries the bodies whose
//!    bounding box left its enlarged box; each new overlapping pair becomes
//!    a persistent contact (`contacts.rs`);
//! 2. **collide** (`collide.rs`): every contact of an awake body gets its manifold at the
//!    current poses (`manifold.rs`: up to two points with feature ids,
//!    speculative points within [`SoftStepSettings::speculative_distance`]),
//!    each point keeping the impulses of last step's point with the same id;
//!    pairs whose enlarged boxes parted are destroyed;
//! 3. **prepare** (`prepare.rs`): the touching contacts of awake bodies are
//!    coloured (`colouring.rs`: no two constraints of a colour share a
//!    dynamic body) and each becomes a constraint (`contact_solver.rs`:
//!    anchors, effective masses, inherited impulses, approach speed),
//!    written into its lane of an eight-lane record of its colour
//!    (`wide_solver.rs`); the few that find no colour (the overflow) stay
//!    scalar; each joint of an awake body gets its frame for the step
//!    ([`joints`]);
//! 4. n times: **integrate velocities** (gravity and every force generator
//!    active in the step, evaluated at the substep's start state),
//!    **warm start**, **solve** with the soft bias
//!    (`softness.rs`), **integrate positions** (symplectic Euler:
//!    x += h v, θ += h ω), **relax** (solve again without bias, with
//!    friction); each solver pass runs the joints one at a time
//!    ([`joints`]), the contact overflow one constraint at a time
//!    (`contact_solver.rs`), then the records, colour after colour, eight
//!    constraints at a time (`wide_solver.rs`: eight lanes at once with
//!    AVX-512, four and four with AVX or SSE2);
//! 5. **restitution**: points that approached faster than the threshold
//!    bounce with their restitution (overflow, then records);
//! 6. **store**: impulses back into the contacts, states into the world;
//! 7. **continuous** (`finalize.rs`): bounding boxes into the broad phase,
//!    fast bodies swept against static ones (`continuous.rs`), then fast
//!    bullets against every body's final pose (`bullets.rs`);
//! 8. **sleep** (when on): islands at rest fall asleep (`islands.rs`;
//!    jointed bodies share an island).
//!
//! With [`SoftStepSettings::threads`] above one, the manifolds of collide
//! (`collide.rs`), prepare (the contacts' and the revolute joints'
//! lanes; the contacts' colouring beside their push demands), the substeps' integration and passes (each colour's records,
//! the contacts' and the joints', split among the threads), restitution,
//! the store and the per-body part of continuous (`finalize.rs`) run on a
//! pool of threads (`pool.rs`, `parallel.rs`), with the serial stages'
//! bits (docs/soft_step.md, "Threads"); a step with less work than
//! [`SoftStepSettings::min_work_per_thread`] per thread runs on one.
//!
//! Events (landing, apex) are located inside each substep by linear
//! interpolation, exact for positions (they move linearly in a substep;
//! `events.rs`).
//!
//! Nothing is allocated per step once the contact and constraint arrays
//! have grown to the scene's size.
//!
//! # Speed
//!
//! What was done to make it fast, each change with the instruction counts
//! that justified it (callgrind), is in `docs/soft_step.md`, section
//! "Speed: what was done, as measured".

mod bodies;
mod broad_phase;
mod bullets;
mod collide;
mod colouring;
pub mod contact_events;
mod contact_solver;
mod contacts;
mod continuous;
mod control;
mod events;
mod finalize;
mod geometry;
mod integrate;
mod islands;
pub mod joints;
mod lanes;
#[cfg(target_arch = "x86_64")]
mod lanes_avx;
#[cfg(target_arch = "x86_64")]
mod lanes_avx512;
mod manifold;
mod parallel;
mod pool;
mod prepare;
mod report;
mod settings;
mod shape_data;
mod sleep;
mod softness;
#[cfg(test)]
mod test_numbers;
mod wide_solver;
mod world_joints;
mod world_seam;

pub use contact_events::{
    ContactData, ContactHooks, ContactPointData, HitEvent, JointEvent, PreSolveContact,
    SensorEvent, ShapeId, StepEvents, TouchEvent,
};
pub use settings::SoftStepSettings;
pub use softness::Softness;

/// The lane arithmetic the wide solver passes take on this CPU, as the
/// dispatch in `lanes.rs` chooses it at run time: "AVX-512 (8 f64 lanes)"
/// when the CPU has AVX-512F, "AVX (4 f64 lanes)" when it has AVX, "SSE2
/// (4 f64 lanes)" otherwise on x86-64, the portable 4-lane type elsewhere
/// (records of eight lanes in every case, visited four by four by the
/// 4-lane types). Every path gives the same bits; this says which one runs
/// (for benchmark reports).
pub fn lanes_in_use() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if lanes_avx512::detected() {
        return "AVX-512 (8 f64 lanes)";
    }
    #[cfg(target_arch = "x86_64")]
    if lanes_avx::detected() {
        return "AVX (4 f64 lanes)";
    }
    if cfg!(target_arch = "x86_64") {
        "SSE2 (4 f64 lanes)"
    } else {
        "portable (4 f64 lanes)"
    }
}

use crate::body::{BodyId, BodyKind, BodyState};
use crate::error::{EngineError, Result};
use crate::events::EventRecord;
use crate::forces::Wrench;
use crate::integrators::Stats;
use crate::profile::Phase;
use crate::world_core::{WorldCore, check_energy_value};
use bodies::{BodyMass, BodySim, SolverBody, solver_body};
use broad_phase::BroadPhase;
use colouring::Colouring;
use contact_events::Hooks;
use contact_solver::ContactConstraint;
use contacts::ContactSet;
use geometry::Collider;
use nalgebra::{Isometry2, Translation2, Vector2};
use shape_data::{PairMaterial, ShapeData};
use wide_solver::{WideConstraint, WideExtra};

/// The soft step's state: per-body solver records, broad phase, contacts,
/// constraints, islands.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SoftStep {
    settings: SoftStepSettings,
    sims: Vec<BodySim>,
    /// The prepare stage's copy of the bodies' masses (see [`BodyMass`]).
    #[cfg_attr(feature = "serde", serde(skip))]
    masses: Vec<BodyMass>,
    /// The same masses by solver index, as the wide passes gather them
    /// ([`wide_solver::BodyMasses`]).
    #[cfg_attr(feature = "serde", serde(skip))]
    lane_masses: Vec<[f64; 2]>,
    /// One per convex shape; a body's are contiguous.
    colliders: Vec<Collider>,
    /// Each collider's filter, sensor flag and material.
    shape_data: Vec<ShapeData>,
    /// The events of the last world step.
    events: StepEvents,
    /// The program's filter and pre-solve hooks (code, not state: not
    /// written to bytes).
    #[cfg_attr(feature = "serde", serde(skip))]
    hooks: Hooks,
    /// Whether a constraint of the step's records has a tangent speed or
    /// rolling resistance (prepare's, [`wide_solver::is_rare`]; the wide
    /// passes read those fields only then).
    rare: bool,
    /// The two softnesses of the step's contacts (prepare's; the records
    /// keep which one each lane takes).
    softness: wide_solver::StepSoftness,
    /// Solver records; index 0 is the static dummy, body `i` is `i + 1`.
    bodies: Vec<SolverBody>,
    broad: BroadPhase,
    contacts: ContactSet,
    /// The constraints of the step's colours, eight per record, colour
    /// after colour.
    #[cfg_attr(feature = "serde", serde(skip))]
    wide: Vec<WideConstraint>,
    #[cfg_attr(feature = "serde", serde(skip))]
    wide_extra: Vec<WideExtra>,
    /// The overflow constraints (no free colour), solved one at a time.
    #[cfg_attr(feature = "serde", serde(skip))]
    constraints: Vec<ContactConstraint>,
    #[cfg_attr(feature = "serde", serde(skip))]
    colouring: Colouring,
    /// The contact of each constraint, in contact order (the colouring's
    /// order).
    #[cfg_attr(feature = "serde", serde(skip))]
    constrained: Vec<usize>,
    /// Per world body, the push-out speed (m/s) its contacts with other
    /// dynamic bodies ask for this step (prepare's sum, for sharing the
    /// push-out speed among them).
    #[cfg_attr(feature = "serde", serde(skip))]
    push_demand: Vec<f64>,
    islands: islands::Islands,
    joints: joints::JointSet,
    stats: Stats,
    // Scratch reused by every step.
    #[cfg_attr(feature = "serde", serde(skip))]
    wrenches: Vec<Wrench>,
    #[cfg_attr(feature = "serde", serde(skip))]
    force_states: Vec<BodyState>,
    #[cfg_attr(feature = "serde", serde(skip))]
    substep_start: Vec<SolverBody>,
    #[cfg_attr(feature = "serde", serde(skip))]
    touching_pairs: Vec<(BodyId, BodyId)>,
    #[cfg_attr(feature = "serde", serde(skip))]
    resting: Vec<usize>,
    /// The threads of the parallel stages (none for one thread).
    #[cfg_attr(feature = "serde", serde(skip))]
    pool: pool::PoolCell,
    /// The collide stage's buffers, one per thread.
    #[cfg_attr(feature = "serde", serde(skip))]
    scratches: Vec<manifold::Scratch>,
    /// Per contact, what the collide stage's threads found (`collide.rs`).
    #[cfg_attr(feature = "serde", serde(skip))]
    collided: Vec<collide::Collided>,
    /// Per collider, its box at the end of the step (the continuous
    /// stage's, `finalize.rs`).
    #[cfg_attr(feature = "serde", serde(skip))]
    collider_boxes: Vec<crate::collision::Aabb>,
    /// Per body, the pose a sweep put it back to (the continuous stage's
    /// threads').
    #[cfg_attr(feature = "serde", serde(skip))]
    impacts: Vec<Option<finalize::Impact>>,
    /// Per thread of the continuous stage, the bodies of its share the
    /// serial pass has work for, in body order (`finalize.rs`).
    #[cfg_attr(feature = "serde", serde(skip))]
    finalize_pending: Vec<Vec<BodyId>>,
    /// The fast bullets of the step, in body order, whose sweeps wait for
    /// the other bodies' end poses (`bullets.rs`).
    #[cfg_attr(feature = "serde", serde(skip))]
    fast_bullets: Vec<BodyId>,
}

impl SoftStep {
    /// The model for the bodies already in `core`.
    pub(crate) fn new(core: &WorldCore, settings: SoftStepSettings) -> Self {
        let mut model = Self {
            settings,
            sims: Vec::new(),
            masses: Vec::new(),
            lane_masses: Vec::new(),
            colliders: Vec::new(),
            shape_data: Vec::new(),
            events: StepEvents::default(),
            hooks: Hooks::default(),
            rare: false,
            softness: [Softness::RIGID; 2],
            bodies: vec![SolverBody::AT_REST],
            broad: BroadPhase::default(),
            contacts: ContactSet::default(),
            wide: Vec::new(),
            wide_extra: Vec::new(),
            constraints: Vec::new(),
            colouring: Colouring::default(),
            constrained: Vec::new(),
            push_demand: Vec::new(),
            islands: islands::Islands::default(),
            joints: joints::JointSet::default(),
            stats: Stats::default(),
            wrenches: Vec::new(),
            force_states: Vec::new(),
            substep_start: Vec::new(),
            touching_pairs: Vec::new(),
            resting: Vec::new(),
            pool: pool::PoolCell::default(),
            scratches: Vec::new(),
            collided: Vec::new(),
            collider_boxes: Vec::new(),
            impacts: Vec::new(),
            finalize_pending: Vec::new(),
            fast_bullets: Vec::new(),
        };
        for id in 0..core.bodies.len() {
            model.body_added(core, id);
        }
        model
    }

    /// The broad phase's trees, for world queries (module `query`).
    pub(crate) fn query_trees(&self) -> [&crate::collision::DynamicTree; 3] {
        self.broad.trees()
    }

    /// The body of collider `c` and the index of its convex piece in the
    /// body's shape (its compound part, 0 otherwise).
    pub(crate) fn collider_owner(&self, c: usize) -> (BodyId, usize) {
        let body = self.colliders[c].body;
        (body, c - self.sims[body].colliders.start)
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
        for (c, data) in self.colliders.iter().zip(&mut self.shape_data) {
            data.resolve(&core.bodies[c.body], &settings);
        }
        // Pairs mix their materials when created; again now.
        for c in &mut self.contacts.contacts {
            let m = PairMaterial::mix(&self.shape_data[c.a], &self.shape_data[c.b], &settings);
            c.friction = m.friction;
            c.restitution = m.restitution;
            c.rolling_resistance = m.rolling_resistance;
            c.tangent_speed = m.tangent_speed;
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
        self.shape_data.extend(ShapeData::of(body, &self.settings));
        let range = first..self.colliders.len();
        let sim = BodySim::new(
            body,
            state.angle,
            (&self.colliders[range.clone()], range.clone()),
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
            let margin = self.colliders[c].aabb_margin(margin);
            self.broad.add(c, Some(aabb.loosened(margin)), body.kind);
        }
        self.bodies.push(solver_body(state, body.kind));
        self.islands.add_body(id, body.kind == BodyKind::Dynamic);
        self.joints.body_added();
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
        self.events.clear();
        let mut t = core.time;
        for &end in edges {
            self.step(core, t, end, found)?;
            if core.stopped {
                break;
            }
            t = end;
        }
        self.joints
            .exceeded(&core.states, &mut self.events.joints_exceeded);
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

        let pool = self.pool.get(settings.threads);

        let started = core.profiler.start();
        // The pairs by last step's count of contacts (this step's are not
        // known yet): the same pairs in the same order either way.
        let pairs_pool = pool
            .as_deref()
            .filter(|p| self.enough_work_for(p.threads()));
        self.update_pairs(pairs_pool);
        core.profiler.stop(Phase::Pairs, started);
        let pool = pool.filter(|p| self.enough_work_for(p.threads()));

        let started = core.profiler.start();
        self.collide(&core.states, pool.as_deref());
        core.profiler.stop(Phase::Collide, started);

        let started = core.profiler.start();
        self.load_bodies(core);
        self.prepare(core, h, pool.as_deref());
        let warm = settings.warm_starting;
        self.joints
            .prepare(core, (&self.masses, &self.sims), (h, warm), pool.as_deref());
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
            if let Some(pool) = &pool {
                // The same stages on the pool's threads (`parallel.rs`),
                // timed as one.
                let started = core.profiler.start();
                if watch_events {
                    self.substep_start.clone_from(&self.bodies);
                }
                if general {
                    self.integrate_velocities(core, h, gravity, Some((t_sub, middle)));
                }
                self.parallel_substep(pool, core, (h, inv_h), gravity, general);
                core.profiler.stop(Phase::Solve, started);
            } else {
                let started = core.profiler.start();
                if watch_events {
                    self.substep_start.clone_from(&self.bodies);
                }
                self.integrate_velocities(core, h, gravity, general.then_some((t_sub, middle)));
                core.profiler.stop(Phase::Integrate, started);

                let started = core.profiler.start();
                self.joints.warm_start(&mut self.bodies);
                contact_solver::warm_start(&mut self.constraints, &mut self.bodies);
                let rare = self.rare.then_some(&mut self.wide_extra[..]);
                wide_solver::warm_start(&mut self.wide, rare, &mut self.bodies, &self.lane_masses);
                core.profiler.stop(Phase::WarmStart, started);

                let started = core.profiler.start();
                self.joints.solve(&mut self.bodies, h, true);
                contact_solver::solve(&mut self.constraints, &mut self.bodies, inv_h, true);
                wide_solver::solve(
                    &mut self.wide,
                    &mut self.bodies,
                    &self.lane_masses,
                    inv_h,
                    &self.softness,
                );
                core.profiler.stop(Phase::Solve, started);

                let started = core.profiler.start();
                self.integrate_positions(h);
                core.profiler.stop(Phase::Integrate, started);

                let started = core.profiler.start();
                self.joints.solve(&mut self.bodies, h, false);
                contact_solver::solve(&mut self.constraints, &mut self.bodies, inv_h, false);
                let rare = self.rare.then_some(&mut self.wide_extra[..]);
                wide_solver::relax(
                    &mut self.wide,
                    rare,
                    &mut self.bodies,
                    &self.lane_masses,
                    inv_h,
                );
                core.profiler.stop(Phase::Relax, started);
            }
            self.stats.evaluations += 1;

            if watch_events {
                let t_end = if k + 1 == n { t1 } else { t_sub + h };
                if self.locate_events(core, (t_sub, t_end), found) {
                    self.joints.store_impulses();
                    self.report_touches();
                    return Ok(());
                }
            }
        }

        let started = core.profiler.start();
        if let Some(pool) = &pool {
            // Restitution and the impulses' store on the threads.
            self.parallel_restitution_and_store(pool, settings.restitution_threshold);
        } else {
            contact_solver::restitution(
                &mut self.constraints,
                &mut self.bodies,
                settings.restitution_threshold,
            );
            wide_solver::restitution(
                &mut self.wide,
                &self.wide_extra,
                &mut self.bodies,
                &self.lane_masses,
                settings.restitution_threshold,
            );
        }
        core.profiler.stop(Phase::Restitution, started);

        let started = core.profiler.start();
        if pool.is_none() {
            self.store_impulses();
        }
        self.joints.store_impulses();
        self.report_touches();
        let step = self.stats.steps;
        self.write_states(core, t0, step)?;
        core.profiler.stop(Phase::Store, started);

        let started = core.profiler.start();
        self.finalize_bodies(core, dt, pool.as_deref());
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
            check_energy_value(energy, (t0, t1), step, limit, (&core.bodies, &core.states))?;
        }
        Ok(())
    }

    /// Stage 1: contacts for the new overlapping pairs of colliders.
    #[inline(never)]
    fn update_pairs(&mut self, pool: Option<&pool::Pool>) {
        let sims = &self.sims;
        let colliders = &self.colliders;
        let data = &self.shape_data;
        let contacts = &mut self.contacts;
        let joints = &self.joints;
        let settings = &self.settings;
        let hooks = &mut self.hooks.0;
        self.broad.find_pairs(pool, |a, b| {
            let (ca, cb) = (&colliders[a], &colliders[b]);
            if ca.body == cb.body {
                return;
            }
            let (sa, sb) = (&sims[ca.body], &sims[cb.body]);
            let (da, db) = (&data[a], &data[b]);
            let sensor = da.sensor || db.sensor;
            // At least one dynamic body: static and kinematic bodies do not
            // push each other (a sensor needs one moving body). Sensors do
            // not detect sensors. Shapes whose filters refuse each other,
            // or held by a joint that does not let them collide, do not
            // either.
            let pushing = sa.kind == BodyKind::Dynamic || sb.kind == BodyKind::Dynamic;
            let moving = sa.kind != BodyKind::Static || sb.kind != BodyKind::Static;
            if !(pushing || (sensor && moving))
                || (da.sensor && db.sensor)
                || !da.filter.should_collide(&db.filter)
                || joints.keeps_apart(ca.body, cb.body)
            {
                return;
            }
            if contacts.contains(a, b) {
                return;
            }
            if let Some(hooks) = hooks.as_mut() {
                let id = |c: &Collider, d: &ShapeData| ShapeId {
                    body: c.body,
                    part: d.part,
                };
                if !hooks.should_collide(id(ca, da), id(cb, db)) {
                    return;
                }
            }
            let (first, second) = contacts::ordered((a, &ca.shape), (b, &cb.shape));
            let bodies = (colliders[first].body, colliders[second].body);
            let material = PairMaterial::mix(da, db, settings);
            contacts.create((first, second), bodies, material, sensor);
        });
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

    /// Body `id` was removed (it is now an inert static body without a
    /// shape): its joints, proxy, contacts and island membership go.
    pub(crate) fn body_removed(&mut self, core: &WorldCore, id: BodyId) {
        self.remove_joints_of(id);
        for c in self.sims[id].colliders.clone() {
            self.broad.remove(c);
        }
        for i in 0..self.contacts.contacts.len() {
            let c = &self.contacts.contacts[i];
            if c.touching && (c.body_a == id || c.body_b == id) {
                self.contact_ended(i);
            }
        }
        self.contacts.destroy_body(id);
        self.islands.remove_body(id);
        let empty = self.colliders.len();
        self.sims[id] = BodySim::new(&core.bodies[id], core.states[id].angle, (&[], empty..empty));
        self.bodies[id + 1] = SolverBody::AT_REST;
    }
}
