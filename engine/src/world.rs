//! The world (the seed's `GScene`, §3): bodies, force generators, events and
//! an integrator, advanced by [`World::step`].
//!
//! One step, in order:
//! 1. **split** the interval at every force-window edge inside it, so no
//!    integrator stage straddles a switch-on or switch-off;
//! 2. **integrate** each segment with the forces active at its midpoint
//!    (the adaptive method takes as many controlled steps as it needs);
//! 3. **locate events** inside every accepted step by root finding
//!    ([`crate::events`]); a terminal event ends the run at its exact time;
//! 4. **guard**: a non-finite state, or an energy past the optional bound,
//!    is a typed [`EngineError::BlowUp`] naming the time and the step.
//!
//! A world that asked for contacts ([`World::set_contact_settings`]) and
//! has at least two shapes, one of them on a moving body, also handles
//! contacts ([`crate::contact`]); each piece of step is then, in
//! order, one flat list of named phases, each timed into a
//! [`StepProfile`] when profiling is on:
//! 1. **respond** (settle): at the piece's start, impulses for the touching
//!    pairs that approach (seed eq. 7.15 with restitution), projection of
//!    pairs that sank, and the choice of the resting pairs whose contact
//!    forces enter the right-hand side (seed §7.1 after Baraff); the
//!    integrator's cached derivative is dropped when anything changed;
//! 2. **integrate** a trial step to the end of the step (or segment);
//! 3. **broad phase** (sort-and-sweep of bounding boxes) and **narrow
//!    phase** (exact distances) at the trial step's end;
//! 4. **time of impact**: the first contact inside the trial step, by the
//!    seed's bisection (Fig. 7.7–7.8) or conservative advancement, and the
//!    first stop of a sliding contact, by root finding; the step is cut
//!    there, events are located in the piece kept, and the next piece
//!    starts with a settle. Several contacts in one step are so handled in
//!    time order. A world without contacts runs none of this.

use crate::body::{Body, BodyDef, BodyId, BodyState};
use crate::contact::pipeline::{ContactPipeline, Phase, Profiler};
use crate::contact::resting::RestingContacts;
use crate::contact::{ContactEvent, ContactSettings, StepProfile};
use crate::error::{EngineError, Result, require_positive};
use crate::events::{EventRecord, EventSpec};
use crate::forces::{Force, ForceContext, TimeWindow, Wrench};
use crate::integrators::{Integrator, Method, Stats};
use crate::root_finding::illinois;
use crate::time_grid::{grid_time, step_count};
use crate::trace::{Sample, Trace};
use crate::world_ode::{ActiveForce, Layout, WorldOde};

/// Relative width (of the step) to which event times are located: a few
/// ulps of the time, far below any tolerance the harness applies.
const EVENT_TIME_TOLERANCE: f64 = 1e-15;

/// How many ulps of the current time separate a force-window edge from a
/// step end before the step is split there.
const EDGE_RESOLUTION_ULPS: f64 = 16.0;

struct ForceEntry {
    force: Box<dyn Force>,
    window: TimeWindow,
}

impl std::fmt::Debug for ForceEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} during {:?}", self.force.name(), self.window)
    }
}

/// A simulated world.
#[derive(Debug)]
pub struct World {
    bodies: Vec<Body>,
    states: Vec<BodyState>,
    forces: Vec<ForceEntry>,
    events: Vec<EventSpec>,
    integrator: Integrator,
    layout: Layout,
    time: f64,
    stopped: bool,
    energy_limit: Option<f64>,
    contact_settings: ContactSettings,
    /// Whether contacts were asked for ([`World::set_contact_settings`]).
    contacts_enabled: bool,
    /// Present iff contacts are enabled and the world has two collidable
    /// shapes (one moving).
    contacts: Option<ContactPipeline>,
    /// The resting pairs, read by the right-hand side.
    resting: RestingContacts,
    /// Contact events of pipelines replaced when bodies were added.
    earlier_contact_events: Vec<ContactEvent>,
    profiler: Profiler,
    // Scratch buffers reused by every step.
    y: Vec<f64>,
    y_start: Vec<f64>,
    scratch_edges: Vec<f64>,
    y_probe: Vec<f64>,
    scratch_states: Vec<BodyState>,
    scratch_wrenches: Vec<Wrench>,
}

impl World {
    /// An empty world at t = 0 integrated by `method`.
    pub fn new(method: Method) -> Result<Self> {
        Ok(Self {
            bodies: Vec::new(),
            states: Vec::new(),
            forces: Vec::new(),
            events: Vec::new(),
            integrator: Integrator::new(method)?,
            layout: Layout::default(),
            time: 0.0,
            stopped: false,
            energy_limit: None,
            contact_settings: ContactSettings::default(),
            contacts_enabled: false,
            contacts: None,
            resting: RestingContacts::default(),
            earlier_contact_events: Vec::new(),
            profiler: Profiler::default(),
            y: Vec::new(),
            y_start: Vec::new(),
            scratch_edges: Vec::new(),
            y_probe: Vec::new(),
            scratch_states: Vec::new(),
            scratch_wrenches: Vec::new(),
        })
    }

    /// Adds a body after validating it; returns its id.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyId> {
        let (body, state) = Body::from_def(&def)?;
        self.bodies.push(body);
        self.states.push(state);
        self.layout = Layout::new(&self.bodies);
        self.rebuild_contacts();
        Ok(self.bodies.len() - 1)
    }

    fn rebuild_contacts(&mut self) {
        if let Some(old) = self.contacts.take() {
            self.earlier_contact_events.extend(old.events);
        }
        self.contacts = if self.contacts_enabled {
            ContactPipeline::new(&self.bodies, self.contact_settings)
        } else {
            None
        };
        self.resting.pairs.clear();
        self.resting.friction = self.contact_settings.friction;
        self.resting.tolerance = self.contact_settings.tolerance;
    }

    /// Turns contact handling on with these settings (restitution,
    /// friction, tolerances: see [`ContactSettings`]), validated; they apply
    /// from the next step. Off by default: a world built without contact
    /// settings lets shapes pass through each other (DESIGN.md: model no
    /// more than the scene asks for), and a world with fewer than two
    /// shapes, or none on a moving body, runs no collision code even when
    /// on.
    pub fn set_contact_settings(&mut self, settings: ContactSettings) -> Result<()> {
        settings.validate()?;
        self.contact_settings = settings;
        if self.contacts_enabled {
            if let Some(p) = self.contacts.as_mut() {
                p.settings = settings;
            }
        } else {
            self.contacts_enabled = true;
            self.rebuild_contacts();
        }
        self.resting.friction = settings.friction;
        self.resting.tolerance = settings.tolerance;
        Ok(())
    }

    /// Turns contact handling off (resting pairs are dropped; the events
    /// recorded so far are kept).
    pub fn disable_contacts(&mut self) {
        self.contacts_enabled = false;
        self.rebuild_contacts();
    }

    /// The contact settings.
    pub fn contact_settings(&self) -> ContactSettings {
        self.contact_settings
    }

    /// Whether the world runs collision code: contacts are on and it has at
    /// least two bodies with a shape, one of them dynamic (DESIGN.md: "a
    /// scene without two collidable shapes runs no collision code").
    pub fn has_contacts(&self) -> bool {
        self.contacts.is_some()
    }

    /// The contact events so far (impacts, rest, release, stick, slip), in
    /// time order.
    pub fn contact_events(&self) -> Vec<ContactEvent> {
        let mut all = self.earlier_contact_events.clone();
        if let Some(p) = &self.contacts {
            all.extend(p.events.iter().copied());
        }
        all
    }

    /// Turns per-phase timing on or off (off by default: reading the clock
    /// around every phase costs more than a cheap step). The counters of
    /// the [`StepProfile`] move either way.
    pub fn set_profiling(&mut self, on: bool) {
        self.profiler.on = on;
    }

    /// Time spent per phase and work counters since the world was built or
    /// the profile was reset.
    pub fn profile(&self) -> StepProfile {
        self.profiler.profile
    }

    /// Zeroes the profile.
    pub fn reset_profile(&mut self) {
        self.profiler.profile = StepProfile::default();
    }

    /// Adds a force active at all times.
    pub fn add_force(&mut self, force: impl Force + 'static) -> Result<()> {
        self.add_force_during(Box::new(force), TimeWindow::ALWAYS)
    }

    /// Adds a force active during `window` only. Refuses a force naming a
    /// body that does not exist.
    pub fn add_force_during(&mut self, force: Box<dyn Force>, window: TimeWindow) -> Result<()> {
        force.validate()?;
        for body in force.bodies() {
            self.check_body(body)?;
        }
        let acts = force.bodies();
        if !acts.is_empty() && acts.iter().all(|&b| !self.bodies[b].is_dynamic()) {
            return Err(EngineError::ForceOnStaticBodies {
                force: force.name().into(),
            });
        }
        self.forces.push(ForceEntry { force, window });
        Ok(())
    }

    /// Adds an event to locate.
    pub fn add_event(&mut self, event: EventSpec) -> Result<()> {
        self.check_body(event.body)?;
        crate::error::require_finite(format!("level of event '{}'", event.name), event.level)?;
        self.events.push(event);
        Ok(())
    }

    /// Reports a blow-up when |total energy| exceeds `limit` (J). Off by
    /// default.
    pub fn set_energy_limit(&mut self, limit: Option<f64>) -> Result<()> {
        if let Some(l) = limit {
            require_positive("energy limit", l)?;
        }
        self.energy_limit = limit;
        Ok(())
    }

    fn check_body(&self, body: BodyId) -> Result<()> {
        if body < self.bodies.len() {
            Ok(())
        } else {
            Err(EngineError::UnknownBody {
                index: body,
                count: self.bodies.len(),
            })
        }
    }

    /// Current time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The bodies, indexed by id.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// Every body's current state, indexed by id.
    pub fn states(&self) -> &[BodyState] {
        &self.states
    }

    /// Whether a terminal event has stopped the world.
    pub fn is_stopped(&self) -> bool {
        self.stopped
    }

    /// Work done by the integrator so far.
    pub fn stats(&self) -> Stats {
        self.integrator.stats()
    }

    /// The integration method.
    pub fn method(&self) -> Method {
        self.integrator.method()
    }

    /// Total energy now: kinetic plus every active force's potential (J).
    pub fn energy(&self) -> f64 {
        self.energy_of(self.time, &self.states)
    }

    fn energy_of(&self, t: f64, states: &[BodyState]) -> f64 {
        total_energy(&self.bodies, &self.forces, t, states)
    }

    /// Advances by `dt` (s). See [`World::step_to`].
    pub fn step(&mut self, dt: f64) -> Result<Vec<EventRecord>> {
        require_positive("dt", dt)?;
        self.step_to(self.time + dt)
    }

    /// Advances to `t_end` (s), returning the events located on the way. A
    /// terminal event stops the world at its exact time; later calls do
    /// nothing.
    pub fn step_to(&mut self, t_end: f64) -> Result<Vec<EventRecord>> {
        if !(t_end.is_finite() && t_end > self.time) {
            return Err(EngineError::InvalidParameter {
                what: "step end time".into(),
                value: t_end,
                reason: "must be finite and after the current time",
            });
        }
        let mut found = Vec::new();
        if self.stopped {
            return Ok(found);
        }
        // Edges within a few ulps of either end are taken as the end itself:
        // a segment of 1e-16 s only loses the switch time to round-off, and
        // would otherwise ask the integrator for a step below resolution.
        let resolution =
            EDGE_RESOLUTION_ULPS * f64::EPSILON * self.time.abs().max(t_end.abs()).max(1.0);
        let mut edges = std::mem::take(&mut self.scratch_edges);
        edges.clear();
        edges.extend(
            self.forces
                .iter()
                .flat_map(|f| f.window.edges())
                .filter(|&e| e > self.time + resolution && e < t_end - resolution),
        );
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        edges.push(t_end);
        let mut y = std::mem::take(&mut self.y);
        self.layout.pack(&self.states, &mut y);
        let result = self.integrate_segments(&edges, &mut y, &mut found);
        self.y = y;
        self.scratch_edges = edges;
        result.map(|()| found)
    }

    fn integrate_segments(
        &mut self,
        edges: &[f64],
        y: &mut Vec<f64>,
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        let mut t = self.time;
        for &segment_end in edges {
            let middle = 0.5 * (t + segment_end);
            let mut pipeline = self.contacts.take();
            let mut sys = WorldOde {
                bodies: &self.bodies,
                forces: self
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
            };
            sys.states.clone_from(&self.states);
            // The right-hand side may differ from the last segment's.
            self.integrator.invalidate_cache();
            if let Some(p) = pipeline.as_mut() {
                let outcome = contact_segment(
                    SegmentParts {
                        integrator: &mut self.integrator,
                        events: &self.events,
                        forces: &self.forces,
                        template: &self.states,
                        energy_limit: self.energy_limit,
                        y_start: &mut self.y_start,
                        y_probe: &mut self.y_probe,
                        profiler: &mut self.profiler,
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
                        self.layout.unpack(y, &mut self.states);
                        self.time = t_stop;
                        self.stopped = true;
                        return Ok(());
                    }
                }
                continue;
            }
            while t < segment_end {
                // Event location restarts from the step's start state.
                if !self.events.is_empty() {
                    self.y_start.clone_from(y);
                }
                let started = self.profiler.start();
                let h = self.integrator.advance(&mut sys, t, y, segment_end - t)?;
                self.profiler.stop(Phase::Integrate, started);
                self.profiler.profile.steps += 1;
                // A step that used all the room left lands exactly on the edge.
                let t_next = if h == segment_end - t {
                    segment_end
                } else {
                    t + h
                };
                if !self.events.is_empty() {
                    let stop = locate_events(
                        &self.events,
                        &mut self.integrator,
                        &mut sys,
                        &self.states,
                        (t, &self.y_start),
                        (t_next, y),
                        &mut self.y_probe,
                        found,
                    )?;
                    if let Some(t_stop) = stop {
                        y.clone_from(&self.y_probe);
                        self.layout.unpack(y, &mut self.states);
                        self.time = t_stop;
                        self.stopped = true;
                        return Ok(());
                    }
                }
                if let Some(limit) = self.energy_limit {
                    check_energy(
                        &self.bodies,
                        &self.forces,
                        &self.layout,
                        &mut sys,
                        y,
                        (t, t_next),
                        self.integrator.stats().steps - 1,
                        limit,
                    )?;
                }
                t = t_next;
            }
        }
        self.layout.unpack(y, &mut self.states);
        self.time = t;
        Ok(())
    }

    /// Runs from the current time to `until` (s) in steps of `dt` (s), at
    /// times `t0 + i·dt` (an integer count, not `t += dt`; the last step is
    /// shortened if `dt` does not divide the span), sampling after every
    /// step. Stops early at a terminal event.
    pub fn run(&mut self, until: f64, dt: f64) -> Result<Trace> {
        let t0 = self.time;
        let steps = step_count(until - t0, dt)?;
        let mut trace = Trace::default();
        trace.samples.push(self.sample());
        for i in 1..=steps {
            let events = self.step_to(grid_time(t0, until, dt, i, steps))?;
            trace.events.extend(events);
            trace.samples.push(self.sample());
            if self.stopped {
                break;
            }
        }
        trace.stats = self.stats();
        Ok(trace)
    }

    /// The current time, states and energy.
    pub fn sample(&self) -> Sample {
        Sample {
            t: self.time,
            states: self.states.clone(),
            energy: self.energy(),
        }
    }
}

/// Kinetic energy plus the potentials of the forces active at `t` (J).
fn total_energy(bodies: &[Body], forces: &[ForceEntry], t: f64, states: &[BodyState]) -> f64 {
    let ctx = ForceContext { t, bodies, states };
    let kinetic: f64 = bodies
        .iter()
        .zip(states)
        .map(|(b, s)| b.kinetic_energy(s))
        .sum();
    let potential: f64 = forces
        .iter()
        .filter(|f| f.window.contains(t))
        .filter_map(|f| f.force.potential_energy(&ctx))
        .sum();
    kinetic + potential
}

/// The energy guard after the step `(t, t_next)`: a NaN energy or one
/// beyond `limit` (J) is a blow-up naming the step (its start time and
/// 0-based index), as the non-finite check does.
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
    if energy.is_nan() || energy.abs() > limit {
        return Err(EngineError::BlowUp {
            t,
            step,
            reason: format!("energy {energy:e} J at t = {t_next} s beyond the bound {limit:e} J"),
        });
    }
    Ok(())
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
    if pipeline.settle(sys, t, y, profiler) {
        integrator.invalidate_cache();
    }
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
        let started = profiler.start();
        let h = integrator.advance(sys, t, y, segment_end - t)?;
        profiler.stop(Phase::Integrate, started);
        profiler.profile.steps += 1;
        let t_next = if h == segment_end - t {
            segment_end
        } else {
            t + h
        };
        let cut = pipeline.first_event(sys, integrator, t, y_start, y, h, y_probe, profiler)?;
        let t_kept = match cut {
            Some(s) if s < h => {
                let started = profiler.start();
                integrator.single_step(sys, t, y_start, s, y)?;
                profiler.stop(Phase::Integrate, started);
                t + s
            }
            _ => t_next,
        };
        if !events.is_empty() {
            let stop = locate_events(
                events,
                integrator,
                sys,
                template,
                (t, y_start),
                (t_kept, y),
                y_probe,
                found,
            )?;
            if let Some(t_stop) = stop {
                y.clone_from(y_probe);
                return Ok(Segment::Stopped(t_stop));
            }
        }
        if let Some(limit) = energy_limit {
            let step = integrator.stats().steps - 1;
            check_energy(
                sys.bodies,
                forces,
                sys.layout,
                sys,
                y,
                (t, t_kept),
                step,
                limit,
            )?;
        }
        t = t_kept;
        if pipeline.settle(sys, t, y, profiler) {
            integrator.invalidate_cache();
        }
    }
    profiler.profile.events = pipeline.events.len() as u64;
    Ok(Segment::Reached(t))
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
