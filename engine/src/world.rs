//! The world (the seed's `GScene`, §3): bodies, force generators, events,
//! and the contact model that advances them ([`crate::ContactModel`]).
//!
//! [`World::step_to`] splits the interval at every force-window edge inside
//! it, so no integrator stage or substep straddles a switch-on or
//! switch-off, then hands each segment to the world's model:
//!
//! - the **exact** model (also a world without contacts) integrates the
//!   world as one ODE by the chosen [`Method`], locates events and impacts
//!   inside the step by root finding, and reports blow-ups as typed errors
//!   (module `exact_model`);
//! - the **soft step** ([`crate::soft_step`]) runs Box2D v3's soft step on
//!   the segment: contact pairs, manifolds, substeps of soft constraints,
//!   relax, restitution.
//!
//! Adding a body is O(1) amortized under both models: the exact model
//! rebuilds its state layout once at the next step, the soft step inserts
//! the body's proxy into its broad phase.

use crate::body::{Body, BodyDef, BodyId, BodyState};
use crate::contact::{ContactEvent, ContactSettings};
use crate::contact_model::ContactModel;
use crate::error::{EngineError, Result, require_positive};
use crate::events::{EventRecord, EventSpec};
use crate::exact::ExactModel;
use crate::forces::{Force, Gravity, TimeWindow};
use crate::integrators::{Method, Stats};
use crate::profile::StepProfile;
use crate::soft_step::joints::{JointDef, JointId, JointState};
use crate::soft_step::{ContactData, ContactHooks, SoftStep, StepEvents};
use crate::time_grid::{grid_time, step_count};
use crate::trace::{Sample, Trace};
use crate::world_core::{BodyControl, ForceEntry, ForceId, WorldCore};
use nalgebra::Vector2;
use std::sync::Arc;

mod control;
mod dynamics;
pub(crate) mod islands;
mod snapshot;

#[cfg(feature = "serde")]
pub(crate) use dynamics::Dynamics;
pub(crate) use snapshot::{deserialize_forces, serialize_forces};

use crate::tunables::EDGE_RESOLUTION_ULPS;

/// The error of a soft-step-only call under the exact model.
fn exact_refuses(what: &str) -> EngineError {
    EngineError::Unsupported {
        what: format!("{what} under the exact contact model"),
        reason: "the soft_step contact model collects them; the exact model reports its \
                 contact events through contact_events()",
    }
}

/// A simulated world.
///
/// A clone is a snapshot in memory: it holds everything the next step
/// reads (states, contacts with their warm-starting impulses, the broad
/// phase's trees, islands and sleep timers, joint impulses), so stepping
/// the clone and the original alike gives the same bits
/// ([`World::state_hash`]). The forces are shared between clones (they
/// are immutable once added). With the `serde` feature (default) a world
/// is also `Serialize` and `Deserialize`, with the same guarantee; what
/// cannot be written is listed at [`World::check_serializable`].
#[derive(Debug, Clone)]
pub struct World {
    core: WorldCore,
    model: Dynamics,
    scratch_edges: Vec<f64>,
}

impl World {
    /// An empty world at t = 0 integrated by `method`, contacts off (add
    /// them with [`World::set_contact_model`]).
    pub fn new(method: Method) -> Result<Self> {
        Ok(Self {
            core: WorldCore::default(),
            model: Dynamics::Exact(Box::new(ExactModel::new(method)?)),
            scratch_edges: Vec::new(),
        })
    }

    /// An empty world at t = 0 running `model`: the exact model integrates
    /// with `method`; the soft step integrates by itself and accepts only
    /// [`Method::SemiImplicitEuler`] (its own scheme).
    pub fn with_model(method: Method, model: ContactModel) -> Result<Self> {
        let mut world = Self::new(method)?;
        world.set_contact_model(model)?;
        Ok(world)
    }

    /// Chooses the contact model and its settings (validated); they apply
    /// from the next step. Switching models keeps the bodies, forces,
    /// events and time, and drops what the old model remembered (resting
    /// pairs, warm-starting impulses).
    ///
    /// The soft step owns its integration (symplectic Euler per substep):
    /// it refuses a world built with another [`Method`], rather than
    /// silently replacing it.
    pub fn set_contact_model(&mut self, model: ContactModel) -> Result<()> {
        model.validate()?;
        match model {
            ContactModel::Exact(settings) => {
                self.refuse_joints_leaving_soft_step()?;
                self.refuse_controls_leaving_soft_step()?;
                // Every body is checked before the model changes, so a
                // refusal leaves the world as it was.
                for body in &self.core.bodies {
                    ExactModel::check_body(body, true)?;
                }
                if let Dynamics::SoftStep(_) = self.model {
                    self.model =
                        Dynamics::Exact(Box::new(ExactModel::new(Method::SemiImplicitEuler)?));
                }
                let Dynamics::Exact(exact) = &mut self.model else {
                    unreachable!("the exact model was just installed");
                };
                exact.set_contact_settings(settings);
            }
            ContactModel::SoftStep(settings) => {
                if let Dynamics::Exact(exact) = &self.model {
                    exact.refuse_joints_leaving()?;
                }
                let method = self.model.method();
                if method != Method::SemiImplicitEuler {
                    return Err(EngineError::Unsupported {
                        what: format!(
                            "the {} method under the soft_step contact model",
                            method.id()
                        ),
                        reason: "the soft step integrates by symplectic (semi-implicit) Euler per \
                                 substep; use semi_implicit_euler, or the exact contact model",
                    });
                }
                match &mut self.model {
                    Dynamics::SoftStep(s) => s.set_settings(&self.core, settings),
                    Dynamics::Exact(_) => {
                        self.model =
                            Dynamics::SoftStep(Box::new(SoftStep::new(&self.core, settings)));
                    }
                }
            }
        }
        Ok(())
    }

    /// The contact model and its settings; `None` when contacts are off.
    pub fn contact_model(&self) -> Option<ContactModel> {
        self.model.model()
    }

    /// Turns the exact contact model on with these settings (restitution,
    /// friction, tolerances: see [`ContactSettings`]):
    /// `set_contact_model(ContactModel::Exact(settings))`. Contacts are off
    /// in a world built by [`World::new`]: shapes then pass through each
    /// other (model no more than the scene asks for), and a world with
    /// fewer than two shapes, or none on a moving body, runs no collision
    /// code even when on.
    pub fn set_contact_settings(&mut self, settings: ContactSettings) -> Result<()> {
        self.set_contact_model(ContactModel::Exact(settings))
    }

    /// The error of leaving the soft step while joints need it, naming the
    /// first joint still in the world.
    fn refuse_joints_leaving_soft_step(&self) -> Result<()> {
        if let Dynamics::Exact(_) = self.model {
            return Ok(());
        }
        let live = (0..self.model.joint_count())
            .find_map(|id| self.model.joint(&self.core, id).ok().filter(|j| !j.removed));
        match live {
            Some(joint) => Err(EngineError::Unsupported {
                what: format!(
                    "leaving the soft_step contact model with joint '{}' ({})",
                    joint.name,
                    joint.joint_type.id()
                ),
                reason: crate::contact_model::JOINTS_NEED_SOFT_STEP,
            }),
            None => Ok(()),
        }
    }

    /// Turns contact handling off (the exact model's resting pairs are
    /// dropped, the events recorded so far are kept); a soft-step world
    /// becomes an exact-model world integrated by semi-implicit Euler,
    /// which it refuses while it holds joints (they need the soft step).
    pub fn disable_contacts(&mut self) -> Result<()> {
        self.refuse_joints_leaving_soft_step()?;
        self.refuse_controls_leaving_soft_step()?;
        match &mut self.model {
            Dynamics::Exact(exact) => exact.disable_contacts(),
            Dynamics::SoftStep(_) => {
                self.model = Dynamics::Exact(Box::new(
                    ExactModel::new(Method::SemiImplicitEuler)
                        .expect("semi-implicit Euler needs no parameter"),
                ));
            }
        }
        Ok(())
    }

    /// The exact model's contact settings (its defaults when the world runs
    /// another model or none).
    pub fn contact_settings(&self) -> ContactSettings {
        match self.contact_model() {
            Some(ContactModel::Exact(s)) => s,
            _ => ContactSettings::default(),
        }
    }

    /// Whether the world runs collision code: contacts are on and, under
    /// the exact model, it has at least two bodies with a shape, one of them
    /// dynamic (model no more than a scene needs).
    pub fn has_contacts(&self) -> bool {
        self.model.has_contacts(&self.core.bodies)
    }

    /// The contact events so far (impacts, rest, release, stick, slip), in
    /// time order. The exact model records them; the soft step records
    /// none.
    pub fn contact_events(&self) -> Vec<ContactEvent> {
        self.model.contact_events()
    }

    /// The touch, hit and sensor events of the last [`World::step`] (see
    /// [`crate::soft_step::contact_events`]). The soft-step contact model
    /// only: the exact model reports its own through
    /// [`World::contact_events`] and refuses this with
    /// [`EngineError::Unsupported`].
    pub fn step_events(&self) -> Result<&StepEvents> {
        Ok(self.soft_step("step events")?.step_events())
    }

    /// Every touching pair of shapes with its normal, points and the
    /// impulses of the last step ([`ContactData`]; a point's
    /// `total_normal_impulse` / dt is its mean normal force). Soft-step
    /// contact model only, as [`World::step_events`].
    pub fn contact_data(&self) -> Result<impl Iterator<Item = ContactData> + '_> {
        Ok(self.soft_step("contact data")?.contact_data())
    }

    /// Gives the soft step the program's pair filter and pre-solve hook
    /// ([`ContactHooks`]), replacing any set before. Soft-step contact
    /// model only, as [`World::step_events`].
    pub fn set_contact_hooks(&mut self, hooks: impl ContactHooks + 'static) -> Result<()> {
        self.soft_step_mut("contact hooks")?
            .set_hooks(Some(Box::new(hooks)));
        Ok(())
    }

    /// The soft-step model, or the error naming the exact model for `what`.
    fn soft_step(&self, what: &str) -> Result<&SoftStep> {
        match &self.model {
            Dynamics::SoftStep(s) => Ok(s),
            Dynamics::Exact(_) => Err(exact_refuses(what)),
        }
    }

    /// [`World::soft_step`], to change it.
    fn soft_step_mut(&mut self, what: &str) -> Result<&mut SoftStep> {
        match &mut self.model {
            Dynamics::SoftStep(s) => Ok(s),
            Dynamics::Exact(_) => Err(exact_refuses(what)),
        }
    }

    /// Turns per-phase timing on or off (off by default: reading the clock
    /// around every phase costs more than a cheap step). The counters of
    /// the [`StepProfile`] move either way.
    pub fn set_profiling(&mut self, on: bool) {
        self.core.profiler.on = on;
    }

    /// Time spent per phase and work counters since the world was built or
    /// the profile was reset.
    pub fn profile(&self) -> StepProfile {
        self.core.profiler.profile
    }

    /// Zeroes the profile.
    pub fn reset_profile(&mut self) {
        self.core.profiler.profile = StepProfile::default();
    }

    /// Sets the world's uniform gravity g (m/s²), acting on every dynamic
    /// body (F = m g) at all times; replaces the previous setting. Zero by
    /// default. A [`Gravity`] force added with [`World::add_force`] adds to
    /// it.
    pub fn set_gravity(&mut self, g: Vector2<f64>) -> Result<()> {
        let gravity = Gravity { g };
        gravity.validate()?;
        self.core.forces.retain(|f| !f.world_gravity);
        if g != Vector2::zeros() {
            let id = self.next_force_id();
            self.core.forces.insert(
                0,
                ForceEntry {
                    force: Arc::new(gravity),
                    window: TimeWindow::ALWAYS,
                    world_gravity: true,
                    id,
                },
            );
        }
        Ok(())
    }

    /// The world's gravity setting (m/s²), not counting [`Gravity`] forces
    /// added with [`World::add_force`].
    pub fn gravity(&self) -> Vector2<f64> {
        self.core
            .forces
            .iter()
            .filter(|f| f.world_gravity)
            .filter_map(|f| f.force.uniform_acceleration())
            .sum()
    }

    /// Adds a body after validating it; returns its id. O(1) amortized.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyId> {
        let (body, state) = Body::from_def(&def)?;
        self.model.check_body(&body)?;
        self.core.bodies.push(body);
        self.core.states.push(state);
        self.core.removed.push(false);
        self.core.controls.push(BodyControl::of(
            self.core.bodies.last().expect("just pushed"),
        ));
        let id = self.core.bodies.len() - 1;
        self.model.body_added(&self.core, id);
        Ok(id)
    }

    /// Removes body `id` from the simulation. Its id stays valid (ids never
    /// shift): the body becomes an inert static body without a shape at its
    /// last position, [`World::is_removed`] says so, its contacts end, its
    /// joints are removed, and the forces and events that name it are
    /// dropped. Removing a body twice does nothing.
    pub fn remove_body(&mut self, id: BodyId) -> Result<()> {
        self.check_body(id)?;
        if self.core.removed[id] {
            return Ok(());
        }
        self.core.removed[id] = true;
        let body = &mut self.core.bodies[id];
        body.kind = crate::body::BodyKind::Static;
        body.shape = None;
        body.mass = f64::INFINITY;
        body.inertia = Some(f64::INFINITY);
        let state = &mut self.core.states[id];
        state.velocity = Vector2::zeros();
        state.angular_velocity = 0.0;
        self.core.forces.retain(|f| !f.force.bodies().contains(&id));
        self.core.controls[id].disabled = None;
        if let Some(w) = self.core.applied.get_mut(id) {
            *w = crate::forces::Wrench::default();
        }
        self.core.events.retain(|e| e.body != id);
        self.model.body_removed(&self.core, id);
        Ok(())
    }

    /// Adds a joint after validating it against the world (its bodies
    /// exist, differ and are not removed, at least one is dynamic, every
    /// parameter in its domain: see [`crate::joints`]); returns its id.
    /// The soft-step contact model only: the exact model refuses it with
    /// [`EngineError::Unsupported`]. A joint with `collide_connected` off
    /// ends the contacts between its bodies.
    pub fn add_joint(&mut self, def: JointDef) -> Result<JointId> {
        self.model.add_joint(&self.core, &def)
    }

    /// Removes joint `id`: it stops acting (its id stays valid and
    /// [`World::joint`] says `removed`), its bodies wake and may collide
    /// again. Removing it twice does nothing.
    pub fn remove_joint(&mut self, id: JointId) -> Result<()> {
        self.model.remove_joint(id)
    }

    /// Joint `id` now: its anchors, angle, translation, constraint errors
    /// and reaction force ([`JointState`]).
    pub fn joint(&self, id: JointId) -> Result<JointState> {
        self.model.joint(&self.core, id)
    }

    /// The largest constraint error (m, or rad for an angle row) the exact
    /// model's projection has removed from its joints after a step: the
    /// drift of the integrator off the joints' manifolds
    /// (`docs/joints.md`). `None` under the soft step.
    pub fn joint_drift(&self) -> Option<f64> {
        self.model.joint_drift()
    }

    /// How many joints were added (removed ones included; ids are
    /// `0..joint_count()`).
    pub fn joint_count(&self) -> usize {
        self.model.joint_count()
    }

    /// Moves the target of target joint `id` to `target` (world point, m)
    /// and wakes its body.
    pub fn set_joint_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<()> {
        self.model.set_joint_target(id, target)
    }

    /// Sets the speed (rad/s for a revolute, m/s for a prismatic joint) of
    /// joint `id`'s motor and wakes its bodies.
    pub fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        self.model.set_motor_speed(id, speed)
    }

    /// Whether body `id` was removed.
    pub fn is_removed(&self, id: BodyId) -> bool {
        self.core.removed.get(id).copied().unwrap_or(false)
    }

    /// Whether body `id` sleeps: only under the soft step with sleeping on
    /// ([`crate::SoftStepSettings::sleeping`]), when its island has been at
    /// rest long enough.
    pub fn is_asleep(&self, id: BodyId) -> bool {
        id < self.core.bodies.len() && self.model.is_asleep(id)
    }

    /// Adds a force active at all times; returns its id, for
    /// [`World::remove_force`].
    pub fn add_force(&mut self, force: impl Force + 'static) -> Result<ForceId> {
        self.add_force_during(Box::new(force), TimeWindow::ALWAYS)
    }

    /// Adds a force active during `window` only; returns its id. Refuses a
    /// force naming a body that does not exist.
    pub fn add_force_during(
        &mut self,
        force: Box<dyn Force>,
        window: TimeWindow,
    ) -> Result<ForceId> {
        force.validate()?;
        for body in force.bodies() {
            self.check_body(body)?;
        }
        let acts = force.bodies();
        if !acts.is_empty() && acts.iter().all(|&b| !self.core.bodies[b].is_dynamic()) {
            return Err(EngineError::ForceOnStaticBodies {
                force: force.name().into(),
            });
        }
        let id = self.next_force_id();
        self.core.forces.push(ForceEntry {
            force: Arc::from(force),
            window,
            world_gravity: false,
            id,
        });
        Ok(id)
    }

    /// Removes the force `id` that [`World::add_force`] or
    /// [`World::add_force_during`] returned; it acts no more from the next
    /// step. An id never returned by this world is refused with
    /// [`EngineError::UnknownForce`]; so is one already removed, or one
    /// dropped with its body by [`World::remove_body`].
    pub fn remove_force(&mut self, id: ForceId) -> Result<()> {
        let index = self
            .core
            .forces
            .iter()
            .position(|f| f.id == id && !f.world_gravity)
            .ok_or(EngineError::UnknownForce { id: id.0 })?;
        self.core.forces.remove(index);
        Ok(())
    }

    fn next_force_id(&mut self) -> ForceId {
        let id = ForceId(self.core.next_force_id);
        self.core.next_force_id += 1;
        id
    }

    /// Adds an event to locate.
    pub fn add_event(&mut self, event: EventSpec) -> Result<()> {
        self.check_body(event.body)?;
        crate::error::require_finite(format!("level of event '{}'", event.name), event.level)?;
        self.core.events.push(event);
        Ok(())
    }

    /// Reports a blow-up when |total energy| exceeds `limit` (J). Off by
    /// default.
    pub fn set_energy_limit(&mut self, limit: Option<f64>) -> Result<()> {
        if let Some(l) = limit {
            require_positive("energy limit", l)?;
        }
        self.core.energy_limit = limit;
        Ok(())
    }

    fn check_body(&self, body: BodyId) -> Result<()> {
        if body < self.core.bodies.len() {
            Ok(())
        } else {
            Err(EngineError::UnknownBody {
                index: body,
                count: self.core.bodies.len(),
            })
        }
    }

    /// What world queries read (module `query`): the bodies and states,
    /// and the soft step whose broad phase they walk, if it runs.
    pub(crate) fn query_view(&self) -> (&WorldCore, Option<&SoftStep>) {
        match &self.model {
            Dynamics::SoftStep(s) => (&self.core, Some(s)),
            Dynamics::Exact(_) => (&self.core, None),
        }
    }

    /// Current time (s).
    pub fn time(&self) -> f64 {
        self.core.time
    }

    /// The bodies, indexed by id.
    pub fn bodies(&self) -> &[Body] {
        &self.core.bodies
    }

    /// Every body's current state, indexed by id.
    pub fn states(&self) -> &[BodyState] {
        &self.core.states
    }

    /// Whether a terminal event has stopped the world.
    pub fn is_stopped(&self) -> bool {
        self.core.stopped
    }

    /// Work done so far (integrator steps and derivative evaluations; the
    /// soft step counts its steps and substeps).
    pub fn stats(&self) -> Stats {
        self.model.stats()
    }

    /// The integration method (semi-implicit Euler under the soft step).
    pub fn method(&self) -> Method {
        self.model.method()
    }

    /// Total energy now: kinetic plus every active force's potential (J).
    pub fn energy(&self) -> f64 {
        self.core.energy_of(self.core.time, &self.core.states)
    }

    /// Advances by `dt` (s). See [`World::step_to`].
    pub fn step(&mut self, dt: f64) -> Result<Vec<EventRecord>> {
        require_positive("dt", dt)?;
        self.step_to(self.core.time + dt)
    }

    /// Advances to `t_end` (s), returning the events located on the way. A
    /// terminal event stops the world at its exact time; later calls do
    /// nothing.
    pub fn step_to(&mut self, t_end: f64) -> Result<Vec<EventRecord>> {
        let time = self.core.time;
        if !(t_end.is_finite() && t_end > time) {
            return Err(EngineError::InvalidParameter {
                what: "step end time".into(),
                value: t_end,
                reason: "must be finite and after the current time",
            });
        }
        let mut found = Vec::new();
        if self.core.stopped {
            return Ok(found);
        }
        // Edges within a few ulps of either end are taken as the end itself:
        // a segment of 1e-16 s only loses the switch time to round-off, and
        // would otherwise ask the integrator for a step below resolution.
        let resolution = EDGE_RESOLUTION_ULPS * f64::EPSILON * time.abs().max(t_end.abs()).max(1.0);
        let mut edges = std::mem::take(&mut self.scratch_edges);
        edges.clear();
        edges.extend(
            self.core
                .forces
                .iter()
                .flat_map(|f| f.window.edges())
                .filter(|&e| e > time + resolution && e < t_end - resolution),
        );
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        edges.push(t_end);
        // The forces applied for this step act through it, then go.
        let applied = !self.core.applied.is_empty();
        if applied {
            let wrenches = std::mem::take(&mut self.core.applied);
            let id = self.next_force_id();
            self.core.forces.push(ForceEntry {
                force: Arc::new(control::AppliedWrenches(wrenches)),
                window: TimeWindow::ALWAYS,
                world_gravity: false,
                id,
            });
        }
        let result = self.model.advance(&mut self.core, &edges, &mut found);
        if applied {
            self.core.forces.pop();
        }
        self.scratch_edges = edges;
        result.map(|()| found)
    }

    /// Runs from the current time to `until` (s) in steps of `dt` (s), at
    /// times `t0 + i·dt` (an integer count, not `t += dt`; the last step is
    /// shortened if `dt` does not divide the span), sampling after every
    /// step. Stops early at a terminal event.
    ///
    /// A step longer than the whole run is refused: `run(0.01, 2.0)` is
    /// almost always `run(until, dt)` with its arguments swapped.
    pub fn run(&mut self, until: f64, dt: f64) -> Result<Trace> {
        let t0 = self.core.time;
        let span = until - t0;
        if dt.is_finite() && span.is_finite() && span > 0.0 && dt > span {
            return Err(EngineError::InvalidParameter {
                what: format!("step dt = {dt:e} s for a run from t = {t0:e} s to {until:e} s"),
                value: dt,
                reason: "the step is longer than the run: call run(until, dt) with the end \
                         time first and the step second (were they swapped?)",
            });
        }
        let steps = step_count(until - t0, dt)?;
        let mut trace = Trace::default();
        trace.samples.push(self.sample());
        for i in 1..=steps {
            let events = self.step_to(grid_time(t0, until, dt, i, steps))?;
            trace.events.extend(events);
            trace.samples.push(self.sample());
            if self.core.stopped {
                break;
            }
        }
        trace.stats = self.stats();
        Ok(trace)
    }

    /// The current time, states and energy.
    pub fn sample(&self) -> Sample {
        Sample {
            t: self.core.time,
            states: self.core.states.clone(),
            energy: self.energy(),
        }
    }
}
