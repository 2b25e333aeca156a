//! The exact contact model (seed §7.1 after Baraff; `docs/design.md`): the
//! world is one ODE integrated by the chosen [`Method`], contacts are found
//! by time of impact inside the step, impacts get the impulses of seed
//! eq. 7.15, and resting pairs are held by contact forces inside the
//! right-hand side ([`crate::contact`]). Exact to round-off on the
//! validation cases; meant for a few bodies. With contacts off it is the
//! plain ODE integration of the seed's cases I and II.
//!
//! One step, in order:
//! 1. **split** the interval at every force-window edge inside it (done by
//!    the world), so no integrator stage straddles a switch-on or
//!    switch-off;
//! 2. **integrate** each segment with the forces active at its midpoint
//!    (the adaptive method takes as many controlled steps as it needs);
//! 3. **locate events** inside every accepted step by root finding
//!    ([`crate::events`]); a terminal event ends the run at its exact time;
//! 4. **guard**: a non-finite state, or an energy past the optional bound,
//!    is a typed [`EngineError::BlowUp`] naming the time and the step.
//!
//! A world with contacts on and at least two shapes, one of them on a
//! moving body, also handles contacts. A step is then, per force segment,
//! a list of pieces, each one flat list of named stages (functions of this
//! file, like the soft step's stage list), each timed into a
//! [`crate::StepProfile`] when profiling is on:
//! 1. **respond** (`stage_settle`, [`pipeline`]'s settle): at the piece's
//!    start, projection of pairs that sank, impulses for the touching pairs
//!    that approach (seed eq. 7.15 with restitution), and the choice of the
//!    resting pairs whose contact forces enter the right-hand side, with
//!    the features they are followed by (seed §7.1 after Baraff); the
//!    integrator's cached derivative is dropped when anything changed;
//! 2. **integrate** (`stage_trial_step`) a trial step to the end of the
//!    step (or segment), with the resting pairs' forces;
//! 3. **broad phase** (sort-and-sweep of bounding boxes), **narrow phase**
//!    (exact distances) and **time of impact** (`stage_cut`, the
//!    pipeline's `first_event` in `search.rs`): the first contact event
//!    inside the trial step: a pair that overlaps at its end, by the
//!    seed's bisection (Fig. 7.7–7.8), one apart at both ends that moved
//!    fast enough to have gone deep in between, by conservative advancement
//!    (the default swept search; [`crate::ToiMethod`]), a resting point that
//!    leaves, and the first stop of a sliding contact, by root finding; the
//!    step is redone up to it;
//! 4. **locate events** and **guard** (`stage_accept`) in the piece kept;
//!    the next piece starts with a settle. Several contacts in one step are
//!    so handled in time order.
//!
//! Without contacts a piece is one accepted step: **integrate**
//! (`stage_step`), then **locate events** and **guard** (`stage_accept`).
//!
//! The files of the model: this one (the step), `ode.rs` (the world as one
//! ODE: the state-vector layout and the right-hand side with contact and
//! joint forces), `pipeline.rs` and `search.rs` (the contact phases of a
//! piece), `contact/` (the response: impulses, resting contact, friction,
//! the complementarity solver; published as [`crate::validation::contact`]),
//! `joints.rs` (joints as constraints), `world_seam.rs` (the world's calls,
//! [`crate::contact_model`]). Its tunables are in `tunables.rs`.

pub mod contact;
pub(crate) mod joint_forces;
pub(crate) mod joints;
pub(crate) mod ode;
pub(crate) mod pipeline;
mod search;
mod world_seam;

use crate::body::{Body, BodyKind, BodyState};
use crate::contact::resting::RestingContacts;
use crate::contact::{ContactEvent, ContactSettings};
use crate::error::{EngineError, Result};
use crate::events::{EventRecord, EventSpec};
use crate::integrators::{Integrator, Method, Stats};
use crate::profile::{Phase, Profiler};
use crate::root_finding::illinois;
use crate::world_core::{ForceEntry, WorldCore, check_energy_value, total_energy};
use joints::ExactJoints;
use ode::{ActiveForce, Layout, WorldOde};
use pipeline::ContactPipeline;

use crate::tunables::EVENT_TIME_TOLERANCE;

/// The exact model's state: the integrator, the state-vector layout, and
/// the contact pipeline when contacts are on.
#[derive(Debug, Clone)]
pub(crate) struct ExactModel {
    integrator: Integrator,
    layout: Layout,
    /// Bodies were added since the layout and pipeline were built: they are
    /// rebuilt at the next step, so adding n bodies costs O(n) in all.
    stale: bool,
    pub(crate) settings: ContactSettings,
    /// Whether contacts were asked for.
    contacts_enabled: bool,
    /// Present iff contacts are enabled and the world has two collidable
    /// shapes (one moving).
    contacts: Option<ContactPipeline>,
    /// The resting pairs, read by the right-hand side.
    resting: RestingContacts,
    /// Contact events of pipelines replaced when bodies were added.
    earlier_contact_events: Vec<ContactEvent>,
    /// The joints, held by constraint forces in the right-hand side and
    /// projected after every accepted step ([`crate::exact::joints`]).
    pub(crate) joints: ExactJoints,
    // Scratch buffers reused by every step.
    y: Vec<f64>,
    y_start: Vec<f64>,
    y_probe: Vec<f64>,
    scratch_states: Vec<BodyState>,
    scratch_wrenches: Vec<crate::forces::Wrench>,
}

impl ExactModel {
    /// A model integrating with `method`, contacts off.
    pub(crate) fn new(method: Method) -> Result<Self> {
        Ok(Self {
            integrator: Integrator::new(method)?,
            layout: Layout::default(),
            stale: true,
            settings: ContactSettings::default(),
            contacts_enabled: false,
            contacts: None,
            resting: RestingContacts::default(),
            earlier_contact_events: Vec::new(),
            joints: ExactJoints::default(),
            y: Vec::new(),
            y_start: Vec::new(),
            y_probe: Vec::new(),
            scratch_states: Vec::new(),
            scratch_wrenches: Vec::new(),
        })
    }

    /// Refuses a body this model cannot simulate. A shape that is not
    /// convex (a compound) is refused only when `contacts` are on (the
    /// model collides single convex shapes of every kind); without
    /// contacts a shape only gives the body its mass properties, and any
    /// shape but a chain integrates.
    pub(crate) fn check_body(body: &Body, contacts: bool) -> Result<()> {
        let refuse = |what: String, reason| Err(EngineError::Unsupported { what, reason });
        if body.kind == BodyKind::Kinematic {
            return refuse(
                format!("kinematic body '{}'", body.name),
                "the exact contact model integrates dynamic and static bodies only; \
                 use the soft_step contact model",
            );
        }
        if let Some(crate::shape::Shape::Chain(_)) = &body.shape {
            return refuse(
                format!("the chain shape of body '{}'", body.name),
                "the exact contact model collides single convex shapes; \
                 use the soft_step contact model",
            );
        }
        // The pair table collides single convex shapes of every kind.
        if let (true, Some(shape)) = (contacts, &body.shape)
            && !shape.is_convex()
        {
            return refuse(
                format!("the {} shape of body '{}'", shape.kind_name(), body.name),
                "the exact contact model collides single convex shapes; \
                 use the soft_step contact model",
            );
        }
        if body.friction.is_some() || body.restitution.is_some() {
            return refuse(
                format!("the friction or restitution of body '{}'", body.name),
                "the exact contact model takes one friction and one restitution for the \
                 whole world (its contact settings); use the soft_step contact model for \
                 per-body materials",
            );
        }
        if body.has_soft_step_only_shape_data() {
            return refuse(
                format!(
                    "the filter, sensor flag, rolling resistance or tangent speed of body '{}'",
                    body.name
                ),
                "the exact contact model collides every pair of shapes with one material; \
                 use the soft_step contact model for filters, sensors and per-shape materials",
            );
        }
        Ok(())
    }

    /// The error of leaving this model while it holds joints (they are
    /// not carried over to another model), naming the first live one.
    pub(crate) fn refuse_joints_leaving(&self) -> Result<()> {
        match self.joints.set.infos.iter().find(|i| !i.removed) {
            Some(info) => Err(EngineError::Unsupported {
                what: format!("leaving the exact contact model with joint '{}'", info.name),
                reason: "a world's joints stay with the contact model they were added to: \
                         choose the model before adding joints",
            }),
            None => Ok(()),
        }
    }

    /// Bodies changed: rebuild the layout and the pipeline before the next
    /// step.
    pub(crate) fn bodies_changed(&mut self) {
        self.stale = true;
    }

    fn rebuild(&mut self, bodies: &[Body]) {
        self.layout = Layout::new(bodies);
        if let Some(old) = self.contacts.take() {
            self.earlier_contact_events.extend(old.events);
        }
        self.contacts = if self.contacts_enabled {
            ContactPipeline::new(bodies, self.settings)
        } else {
            None
        };
        self.resting.pairs.clear();
        self.resting.friction = self.settings.friction;
        self.resting.tolerance = self.settings.tolerance;
        self.joints.invalidate();
        // The contact search asks the joints about every body's pairs.
        self.joints.set.know_bodies(bodies.len());
        self.stale = false;
    }

    /// Turns contacts on with `settings` (validated by the caller).
    pub(crate) fn set_contact_settings(&mut self, settings: ContactSettings) {
        self.settings = settings;
        if self.contacts_enabled {
            if let Some(p) = self.contacts.as_mut() {
                p.settings = settings;
            }
        } else {
            self.contacts_enabled = true;
            self.stale = true;
        }
        self.resting.friction = settings.friction;
        self.resting.tolerance = settings.tolerance;
    }

    /// Turns contacts off.
    pub(crate) fn disable_contacts(&mut self) {
        self.contacts_enabled = false;
        self.stale = true;
    }

    /// Whether contacts are on.
    pub(crate) fn contacts_enabled(&self) -> bool {
        self.contacts_enabled
    }

    /// Whether collision code runs: contacts on, two shapes, one moving.
    pub(crate) fn has_contacts(&self, bodies: &[Body]) -> bool {
        self.contacts_enabled && ContactPipeline::applies_to(bodies)
    }

    /// The contact events so far, in time order.
    pub(crate) fn contact_events(&self) -> Vec<ContactEvent> {
        let mut all = self.earlier_contact_events.clone();
        if let Some(p) = &self.contacts {
            all.extend(p.events.iter().copied());
        }
        all
    }

    /// Work done by the integrator.
    pub(crate) fn stats(&self) -> Stats {
        self.integrator.stats()
    }

    /// The integration method.
    pub(crate) fn method(&self) -> Method {
        self.integrator.method()
    }

    /// Advances `core` over the force segments ending at `edges` (the last
    /// is the step's end), recording located events in `found`.
    pub(crate) fn advance(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        if self.stale {
            self.rebuild(&core.bodies);
        }
        let mut y = std::mem::take(&mut self.y);
        self.layout.pack(&core.states, &mut y);
        let result = self.integrate_segments(core, edges, &mut y, found);
        self.y = y;
        result
    }

    fn integrate_segments(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        y: &mut Vec<f64>,
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        let mut t = core.time;
        let jointed = self.joints.any();
        for &segment_end in edges {
            let middle = 0.5 * (t + segment_end);
            let mut pipeline = self.contacts.take();
            let mut sys = WorldOde {
                bodies: &core.bodies,
                forces: core
                    .forces
                    .iter()
                    .map(|f| ActiveForce {
                        force: f.force.as_ref(),
                        active: f.window.contains(middle),
                    })
                    .collect(),
                layout: &self.layout,
                states: &mut self.scratch_states,
                wrenches: &mut self.scratch_wrenches,
                contacts: pipeline.is_some().then_some(&mut self.resting),
                joints: jointed.then_some(&mut self.joints),
            };
            sys.states.clone_from(&core.states);
            // A state given off the joints' manifolds (a length or a
            // velocity that breaks a joint) starts on them.
            sys.project_joints(y, t);
            // The right-hand side may differ from the last segment's.
            self.integrator.invalidate_cache();
            if let Some(p) = pipeline.as_mut() {
                let outcome = contact_segment(
                    SegmentParts {
                        integrator: &mut self.integrator,
                        events: &core.events,
                        forces: &core.forces,
                        template: &core.states,
                        energy_limit: core.energy_limit,
                        y_start: &mut self.y_start,
                        y_probe: &mut self.y_probe,
                        profiler: &mut core.profiler,
                    },
                    p,
                    &mut sys,
                    (t, segment_end),
                    y,
                    found,
                );
                self.contacts = pipeline;
                match outcome? {
                    Segment::Reached(t_end) => t = t_end,
                    Segment::Stopped(t_stop) => {
                        self.layout.unpack(y, &mut core.states);
                        core.time = t_stop;
                        core.stopped = true;
                        return Ok(());
                    }
                }
                continue;
            }
            // Without contacts, each piece is an accepted step.
            while t < segment_end {
                // Event location restarts from the step's start state.
                if !core.events.is_empty() {
                    self.y_start.clone_from(y);
                }
                let t_next = stage_step(
                    &mut self.integrator,
                    &mut sys,
                    (t, segment_end),
                    y,
                    &mut core.profiler,
                )?;
                let stop = stage_accept(
                    AcceptParts {
                        events: &core.events,
                        forces: &core.forces,
                        template: &core.states,
                        energy_limit: core.energy_limit,
                    },
                    &mut self.integrator,
                    &mut sys,
                    (t, &self.y_start),
                    (t_next, y),
                    &mut self.y_probe,
                    found,
                )?;
                if let Some(t_stop) = stop {
                    self.layout.unpack(y, &mut core.states);
                    core.time = t_stop;
                    core.stopped = true;
                    return Ok(());
                }
                t = t_next;
            }
        }
        self.layout.unpack(y, &mut core.states);
        core.time = t;
        Ok(())
    }
}

/// The energy guard after the step `(t, t_next)` of the exact model: a NaN
/// energy or one beyond `limit` (J) is a blow-up naming the step (its start
/// time and 0-based index), as the non-finite check does.
#[allow(clippy::too_many_arguments)]
fn check_energy(
    bodies: &[Body],
    forces: &[ForceEntry],
    layout: &Layout,
    sys: &mut WorldOde<'_>,
    y: &[f64],
    (t, t_next): (f64, f64),
    step: u64,
    limit: f64,
) -> Result<()> {
    layout.unpack(y, sys.states);
    let energy = total_energy(bodies, forces, t_next, sys.states);
    check_energy_value(energy, (t, t_next), step, limit, (bodies, sys.states))
}

/// The parts of a world a contact segment works with, besides the
/// right-hand side (which borrows the bodies and scratch states).
struct SegmentParts<'w> {
    integrator: &'w mut Integrator,
    events: &'w [EventSpec],
    forces: &'w [ForceEntry],
    template: &'w [BodyState],
    energy_limit: Option<f64>,
    y_start: &'w mut Vec<f64>,
    y_probe: &'w mut Vec<f64>,
    profiler: &'w mut Profiler,
}

/// How a contact segment ended.
enum Segment {
    /// At the segment's end (s).
    Reached(f64),
    /// At a terminal event (s); its state is in `y`.
    Stopped(f64),
}

/// Integrates one force segment `(t, segment_end)` of a world with
/// contacts: settle, trial step, cut at the first contact event, locate
/// events in the piece kept, settle again, and so on (see the module docs).
fn contact_segment(
    parts: SegmentParts<'_>,
    pipeline: &mut ContactPipeline,
    sys: &mut WorldOde<'_>,
    (mut t, segment_end): (f64, f64),
    y: &mut Vec<f64>,
    found: &mut Vec<EventRecord>,
) -> Result<Segment> {
    let SegmentParts {
        integrator,
        events,
        forces,
        template,
        energy_limit,
        y_start,
        y_probe,
        profiler,
    } = parts;
    let limit = pipeline.settings.max_events_per_step;
    let events_before = pipeline.events.len();
    let mut pieces = 0usize;
    stage_settle(pipeline, integrator, sys, t, y, profiler)?;
    while t < segment_end {
        pieces += 1;
        if pieces > limit.saturating_add(1) {
            return Err(EngineError::Contact {
                t,
                reason: format!(
                    "more than {limit} contact events in one step ({} recorded): \
                     an endless sequence of impacts?",
                    pipeline.events.len() - events_before
                ),
            });
        }
        y_start.clone_from(y);
        let h = stage_trial_step(integrator, sys, (t, segment_end), y, profiler)?;
        let t_kept = stage_cut(
            pipeline,
            integrator,
            sys,
            (t, h, segment_end),
            y_start,
            y,
            y_probe,
            profiler,
        )?;
        let stop = stage_accept(
            AcceptParts {
                events,
                forces,
                template,
                energy_limit,
            },
            integrator,
            sys,
            (t, y_start),
            (t_kept, y),
            y_probe,
            found,
        )?;
        if let Some(t_stop) = stop {
            return Ok(Segment::Stopped(t_stop));
        }
        t = t_kept;
        stage_settle(pipeline, integrator, sys, t, y, profiler)?;
    }
    profiler.profile.events = pipeline.events.len() as u64;
    Ok(Segment::Reached(t))
}

/// The end of a step of length `h` begun at `t` that may not pass
/// `segment_end`: a step that used all the room left lands exactly on the
/// edge.
fn step_end(t: f64, h: f64, segment_end: f64) -> f64 {
    if h == segment_end - t {
        segment_end
    } else {
        t + h
    }
}

/// Stage **integrate** without contacts: one accepted step of the
/// integrator from `t` towards `segment_end`, projected onto the joints'
/// manifolds; returns the step's end time.
fn stage_step(
    integrator: &mut Integrator,
    sys: &mut WorldOde<'_>,
    (t, segment_end): (f64, f64),
    y: &mut [f64],
    profiler: &mut Profiler,
) -> Result<f64> {
    let started = profiler.start();
    let h = integrator.advance(sys, t, y, segment_end - t)?;
    let end = step_end(t, h, segment_end);
    sys.project_joints(y, end);
    profiler.stop(Phase::Integrate, started);
    profiler.profile.steps += 1;
    Ok(end)
}

/// Stage **respond** (settle, at the start of every piece with contacts):
/// projection, impulses and the choice of resting pairs
/// ([`ContactPipeline::settle`]); when anything changed, the state is put
/// back on the joints' manifolds and the integrator's cached derivative
/// dropped.
fn stage_settle(
    pipeline: &mut ContactPipeline,
    integrator: &mut Integrator,
    sys: &mut WorldOde<'_>,
    t: f64,
    y: &mut [f64],
    profiler: &mut Profiler,
) -> Result<()> {
    if pipeline.settle(sys, t, y, profiler)? {
        sys.project_joints(y, t);
        integrator.invalidate_cache();
    }
    Ok(())
}

/// Stage **integrate** with contacts: a trial step from `t` towards
/// `segment_end` with the resting pairs' forces; returns its length h (s).
fn stage_trial_step(
    integrator: &mut Integrator,
    sys: &mut WorldOde<'_>,
    (t, segment_end): (f64, f64),
    y: &mut [f64],
    profiler: &mut Profiler,
) -> Result<f64> {
    let started = profiler.start();
    let h = integrator.advance(sys, t, y, segment_end - t)?;
    profiler.stop(Phase::Integrate, started);
    profiler.profile.steps += 1;
    Ok(h)
}

/// Stages **broad phase**, **narrow phase** and **time of impact**: the
/// first contact event inside the trial step `(t, t + h)`
/// ([`ContactPipeline::first_event`], timed inside); the step is redone
/// from `y_start` up to it, and the state put back on the joints'
/// manifolds. Returns the end of the piece kept.
#[allow(clippy::too_many_arguments)]
fn stage_cut(
    pipeline: &mut ContactPipeline,
    integrator: &mut Integrator,
    sys: &mut WorldOde<'_>,
    (t, h, segment_end): (f64, f64, f64),
    y_start: &[f64],
    y: &mut [f64],
    y_probe: &mut Vec<f64>,
    profiler: &mut Profiler,
) -> Result<f64> {
    let cut = pipeline.first_event(sys, integrator, t, y_start, y, h, y_probe, profiler)?;
    let t_kept = match cut {
        Some(s) if s < h => {
            let started = profiler.start();
            integrator.single_step(sys, t, y_start, s, y)?;
            profiler.stop(Phase::Integrate, started);
            t + s
        }
        _ => step_end(t, h, segment_end),
    };
    sys.project_joints(y, t_kept);
    Ok(t_kept)
}

/// What the last stage reads of the world.
struct AcceptParts<'w> {
    events: &'w [EventSpec],
    forces: &'w [ForceEntry],
    template: &'w [BodyState],
    energy_limit: Option<f64>,
}

/// Stages **locate events** and **guard**, on the piece kept
/// `(t, t_kept)`: the events crossed in it, in time order; a terminal one
/// ends the run (its time returned, its state left in `y`). Then the
/// energy guard, when a bound is set.
#[allow(clippy::too_many_arguments)]
fn stage_accept(
    parts: AcceptParts<'_>,
    integrator: &mut Integrator,
    sys: &mut WorldOde<'_>,
    (t, y_start): (f64, &[f64]),
    (t_kept, y): (f64, &mut Vec<f64>),
    y_probe: &mut Vec<f64>,
    found: &mut Vec<EventRecord>,
) -> Result<Option<f64>> {
    if !parts.events.is_empty() {
        let stop = locate_events(
            parts.events,
            integrator,
            sys,
            parts.template,
            (t, y_start),
            (t_kept, y),
            y_probe,
            found,
        )?;
        if let Some(t_stop) = stop {
            y.clone_from(y_probe);
            return Ok(Some(t_stop));
        }
    }
    if let Some(limit) = parts.energy_limit {
        let step = integrator.stats().steps - 1;
        check_energy(
            sys.bodies,
            parts.forces,
            sys.layout,
            sys,
            y,
            (t, t_kept),
            step,
            limit,
        )?;
    }
    Ok(None)
}

/// Looks for every event crossing inside the accepted step `start → end`,
/// records them in time order, and returns the time of the first terminal
/// one (its state left in `probe`), if any.
#[allow(clippy::too_many_arguments)]
fn locate_events(
    specs: &[EventSpec],
    integrator: &mut Integrator,
    sys: &mut WorldOde<'_>,
    template: &[BodyState],
    (t_a, y_a): (f64, &[f64]),
    (t_b, y_b): (f64, &[f64]),
    probe: &mut Vec<f64>,
    found: &mut Vec<EventRecord>,
) -> Result<Option<f64>> {
    let layout = sys.layout;
    // g of one event at a state vector: only the watched body is read.
    let value = |spec: &EventSpec, y: &[f64]| {
        spec.quantity.of(&layout.state_of(y, template, spec.body)) - spec.level
    };
    let h = t_b - t_a;
    let mut hits: Vec<(f64, usize, Vec<BodyState>, Vec<f64>)> = Vec::new();
    for (index, spec) in specs.iter().enumerate() {
        let (ga, gb) = (value(spec, y_a), value(spec, y_b));
        if !spec.crossing.detects(ga, gb) {
            continue;
        }
        let mut g_at = |s: f64, probe: &mut Vec<f64>| -> Result<f64> {
            probe.resize(y_a.len(), 0.0);
            integrator.single_step(sys, t_a, y_a, s, probe)?;
            Ok(value(spec, probe))
        };
        let s = illinois(
            |s| g_at(s, probe),
            0.0,
            ga,
            h,
            gb,
            EVENT_TIME_TOLERANCE * h.max(t_b.abs()),
        )?;
        let y_event = if s == h {
            y_b.to_vec()
        } else {
            g_at(s, probe)?;
            probe.clone()
        };
        let mut event_states = template.to_vec();
        layout.unpack(&y_event, &mut event_states);
        let t_event = if s == h { t_b } else { t_a + s };
        hits.push((t_event, index, event_states, y_event));
    }
    hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    for (t, index, states, y) in hits {
        found.push(EventRecord {
            name: specs[index].name.clone(),
            t,
            states,
        });
        if specs[index].terminal {
            *probe = y;
            return Ok(Some(t));
        }
    }
    Ok(None)
}
