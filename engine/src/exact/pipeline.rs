//! The contact pipeline of a world: what happens at the start of every piece
//! of step ([`ContactPipeline::settle`]) and how a step is cut at its first
//! contact event ([`ContactPipeline::first_event`]).
//!
//! **Settle** (the response, seed §7.2 "calculer l'état après la
//! collision"), at a time t where the world stands still:
//! 1. broad phase: bounding boxes grown by ε, sort-and-sweep; a pair of
//!    bodies a joint keeps apart (`collide_connected` off, the default:
//!    the soft step's filter, Box2D's `b2ShouldShapesCollide`) is skipped
//!    here and in the search of the first event;
//! 2. narrow phase: the manifold of every candidate pair within ε, with the
//!    features it is made of;
//! 3. projection: a pair overlapping by more than [`PROJECTION_SLOP`] ε is
//!    pushed apart along its normal (positions only, velocities untouched,
//!    so no energy is injected the way a Baumgarte velocity bias would),
//!    every other touching pair sinking no deeper (nothing goes through a
//!    static body); repeated, with the narrow phase, until none is that
//!    deep (bodies created inside each other need a few passes);
//! 4. impulses: for every touching point, the relative normal velocity
//!    v_n. A point approaching faster than the resting speed gets the
//!    restitution target v_n' = −e v_n (seed eq. 7.10), unless that rebound
//!    is itself slower than the resting speed; every other touching point
//!    the target v_n' ≥ 0, and one left separating slower than the resting
//!    speed is held at v_n' = 0; with friction, one friction row per
//!    manifold (Coulomb impulse, |j_t| ≤ μ Σ j_n). Solved simultaneously per
//!    island ([`super::solver`]); for one frictionless point this is
//!    exactly seed eq. 7.15;
//! 5. classification: a touching pair whose points no longer separate
//!    *rests*: it is held by contact forces during the next piece of step
//!    ([`super::resting`]), sticking or sliding, followed by the features of
//!    its resting points (module `persistent`).
//!
//! **First event** (module `search`) of a trial step from t to t + h
//! (integrated with the resting pairs' forces): the earliest of
//! - a time of impact: a pair separated at t and overlapping by more than ε
//!   at t + h is located by the seed's bisection of the step (seed Fig.
//!   7.7–7.8: each probe is the integrator's own step from t of a shorter
//!   length) until the separation is within ±ε; a pair apart at both ends
//!   that moved fast enough to have gone deep in between, by conservative
//!   advancement (the swept search, [`super::ToiMethod::Swept`]); a pair
//!   that was touching at t and overlaps by more than ε at t + h (a second
//!   corner coming down) is located until its overlap is between ε and 2ε;
//! - a release: a resting point whose separation rises above 2ε, located
//!   between ε and 2ε;
//! - a stick time: a sliding pair's tangential velocity reaching zero, by
//!   root finding on the same sub-steps.
//!
//! The world then integrates to that time, settles, and goes on with the
//! rest of the step: several contacts in one step are handled in time order.

use super::joints::ExactJoints;
use super::ode::{Layout, WorldOde};
use crate::body::{Body, BodyState};
use crate::collision::features::ContactFeatures;
use crate::collision::narrow_phase::{collide_on_face, equally_deep};
use crate::collision::polygon_polygon::Face;
use crate::collision::{Aabb, Manifold, SweepAndPrune};
use crate::contact::ContactSettings;
use crate::contact::constrained;
use crate::contact::resting::{
    FrictionMode, RestingContacts, RestingPair, features_of, islands, manifold_rows, pose,
};
use crate::contact::rows::{BodyView, Row, RowKind, Side, effective_mass, perp};
use crate::contact::solver::{MAX_CONTACT_ROWS, solve};
use crate::contact::{ContactEvent, ContactEventKind};
use crate::error::{EngineError, Result};
use crate::profile::{Phase, Profiler};
use crate::soft_step::joints::JointSet;
use nalgebra::Vector2;

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub use crate::tunables::PROJECTION_SLOP;

use crate::tunables::PROJECTION_PASSES;

/// Writes body `i`'s velocities into the state vector.
fn write_velocity(layout: &Layout, y: &mut [f64], i: usize, s: &BodyState) {
    if let Some(slot) = layout.slots[i] {
        let o = layout.positions + slot.offset;
        y[o] = s.velocity.x;
        y[o + 1] = s.velocity.y;
        if slot.rotates {
            y[o + 2] = s.angular_velocity;
        }
    }
}

/// Writes body `i`'s pose into the state vector.
fn write_pose(layout: &Layout, y: &mut [f64], i: usize, s: &BodyState) {
    if let Some(slot) = layout.slots[i] {
        let o = slot.offset;
        y[o] = s.position.x;
        y[o + 1] = s.position.y;
        if slot.rotates {
            y[o + 2] = s.angle;
        }
    }
}

/// A manifold found at a settle, with where its rows are.
struct Found {
    a: usize,
    b: usize,
    manifold: Manifold,
    features: ContactFeatures,
    impact: bool,
    rows: (usize, usize),
    before: f64,
}

/// The contact machinery of a world that has at least two collidable
/// shapes (docs/design.md: a scene without them runs none of it).
#[derive(Debug, Clone)]
pub(crate) struct ContactPipeline {
    pub settings: ContactSettings,
    pub events: Vec<ContactEvent>,
    pub(super) broad: SweepAndPrune,
    /// Bodies with a shape, ascending.
    collidable: Vec<usize>,
    aabbs: Vec<Aabb>,
    views: Vec<BodyView>,
    rows: Vec<Row>,
    k: Vec<f64>,
    b: Vec<f64>,
    lambda: Vec<f64>,
    out: Vec<(Vector2<f64>, f64)>,
    /// Scratch of the constrained impact: the columns P W_cᵀ.
    columns: Vec<f64>,
    pub(super) states_a: Vec<BodyState>,
    pub(super) states_b: Vec<BodyState>,
    pub(super) probe_states: Vec<BodyState>,
}

impl ContactPipeline {
    /// The pipeline of `bodies`, or `None` when fewer than two bodies have
    /// a shape or none of those moves.
    /// Whether a world of `bodies` needs collision code: at least two
    /// shapes, one of them on a dynamic body.
    pub(crate) fn applies_to(bodies: &[Body]) -> bool {
        let mut shapes = bodies.iter().filter(|b| b.shape.is_some());
        let count = shapes.clone().count();
        count >= 2 && shapes.any(|b| b.is_dynamic())
    }

    pub(crate) fn new(bodies: &[Body], settings: ContactSettings) -> Option<Self> {
        let collidable: Vec<usize> = (0..bodies.len())
            .filter(|&i| bodies[i].shape.is_some())
            .collect();
        Self::applies_to(bodies).then(|| Self {
            settings,
            events: Vec::new(),
            broad: SweepAndPrune::new(),
            collidable,
            aabbs: Vec::new(),
            views: Vec::new(),
            rows: Vec::new(),
            k: Vec::new(),
            b: Vec::new(),
            lambda: Vec::new(),
            out: Vec::new(),
            columns: Vec::new(),
            states_a: Vec::new(),
            states_b: Vec::new(),
            probe_states: Vec::new(),
        })
    }

    /// Candidate pairs `(a < b)`, at least one dynamic, whose boxes at
    /// `states` grown by `margin` overlap; with `swept = Some((start, h))`
    /// the boxes cover the whole motion from `start` over a step of `h`.
    /// A pair that a live joint of `joints` keeps apart (its
    /// `collide_connected` off, Box2D's default) is no candidate: the
    /// soft step's pair filter, [`JointSet::keeps_apart`].
    pub(super) fn candidates(
        &mut self,
        bodies: &[Body],
        states: &[BodyState],
        margin: f64,
        swept: Option<(&[BodyState], f64)>,
        joints: Option<&JointSet>,
        profiler: &mut Profiler,
    ) -> Vec<(usize, usize)> {
        let started = profiler.start();
        self.aabbs.clear();
        for &i in &self.collidable {
            let shape = bodies[i]
                .shape
                .as_ref()
                .expect("collidable bodies have shapes");
            let mut bx = Aabb::of_shape(shape, &pose(&states[i]));
            if let Some((start, h)) = swept {
                let s0 = &start[i];
                let spin = s0
                    .angular_velocity
                    .abs()
                    .max(states[i].angular_velocity.abs());
                // The shape sweeps between its two boxes, off the chord by
                // at most r·|ω|max·h (rotation) and |Δv| h / 8 (curvature).
                let off = shape.rotation_radius() * spin * h
                    + (states[i].velocity - s0.velocity).norm() * h / 8.0;
                bx = bx.merged(&Aabb::of_shape(shape, &pose(s0))).loosened(off);
            }
            self.aabbs.push(bx.loosened(margin));
        }
        let pairs = self.broad.pairs(&self.aabbs);
        profiler.stop(Phase::Broad, started);
        let collidable = &self.collidable;
        let pairs: Vec<(usize, usize)> = pairs
            .into_iter()
            .map(|(i, j)| (collidable[i], collidable[j]))
            .filter(|&(a, b)| bodies[a].is_dynamic() || bodies[b].is_dynamic())
            .filter(|&(a, b)| !joints.is_some_and(|j| j.keeps_apart(a, b)))
            .collect();
        profiler.profile.candidate_pairs += pairs.len() as u64;
        pairs
    }

    /// The response at time `t`: impulses, projection, and the resting
    /// pairs of the next piece of step (see the module docs). Returns
    /// whether the state or the resting pairs changed (the integrator's
    /// cached derivative is then stale).
    pub(crate) fn settle(
        &mut self,
        sys: &mut WorldOde<'_>,
        t: f64,
        y: &mut [f64],
        profiler: &mut Profiler,
    ) -> Result<bool> {
        let bodies = sys.bodies;
        let layout = sys.layout;
        layout.unpack(y, sys.states);
        let eps = self.settings.tolerance;
        let mut found = self.touching(bodies, sys.states, joint_set(sys), profiler);
        // Pairs that sank by more than the slop are pushed apart first, as
        // often as it takes (the projection is linearised: deep overlaps,
        // bodies created inside each other, need a few passes), then the
        // impulses act on what touches.
        let mut moved = false;
        for _ in 0..PROJECTION_PASSES {
            if !found
                .iter()
                .any(|f| f.manifold.max_depth() > PROJECTION_SLOP * eps)
            {
                break;
            }
            let started = profiler.start();
            let pushed = self.project(bodies, layout, sys.states, &found, y, t)?;
            profiler.stop(Phase::Respond, started);
            if !pushed {
                break;
            }
            moved = true;
            found = self.touching(bodies, sys.states, joint_set(sys), profiler);
        }
        let started = profiler.start();
        let resting = sys
            .contacts
            .as_deref_mut()
            .expect("a world with contacts carries its resting pairs");
        let joints = sys.joints.as_deref_mut().filter(|j| j.any());
        let changed = self.respond(
            bodies, layout, sys.states, &mut found, y, t, resting, joints,
        )?;
        profiler.stop(Phase::Respond, started);
        Ok(changed || moved)
    }

    /// The manifolds (with their features) of the pairs within ε at
    /// `states` (none between bodies `joints` keeps apart).
    fn touching(
        &mut self,
        bodies: &[Body],
        states: &[BodyState],
        joints: Option<&JointSet>,
        profiler: &mut Profiler,
    ) -> Vec<Found> {
        let eps = self.settings.tolerance;
        let pairs = self.candidates(bodies, states, eps, None, joints, profiler);
        let started = profiler.start();
        let mut found: Vec<Found> = Vec::new();
        for (a, b) in pairs {
            if let Some((manifold, features)) = features_of(bodies, states, a, b, eps) {
                found.push(Found {
                    a,
                    b,
                    manifold,
                    features,
                    impact: false,
                    rows: (0, 0),
                    before: 0.0,
                });
            }
        }
        profiler.stop(Phase::Narrow, started);
        found
    }

    #[allow(clippy::too_many_arguments)]
    fn respond(
        &mut self,
        bodies: &[Body],
        layout: &Layout,
        states: &mut [BodyState],
        found: &mut [Found],
        y: &mut [f64],
        t: f64,
        resting: &mut RestingContacts,
        mut joints: Option<&mut ExactJoints>,
    ) -> Result<bool> {
        let s = self.settings;
        let mut changed = false;
        self.views.clear();
        self.views.extend(
            bodies
                .iter()
                .zip(states.iter())
                .map(|(b, st)| BodyView::new(b, st)),
        );
        // Impulses, one island at a time.
        self.rows.clear();
        let resting_speed = s.resting_speed;
        let e = s.restitution;
        for f in found.iter_mut() {
            let start = self.rows.len();
            let mut before = f64::INFINITY;
            let mut impact = false;
            manifold_rows(
                &self.views,
                f.a,
                f.b,
                &f.manifold,
                (s.friction, FrictionMode::Sticking),
                |_, vn| {
                    before = before.min(vn);
                    if vn < -resting_speed {
                        impact = true;
                        // A rebound slower than the resting speed is given
                        // up: the point rests.
                        let rebound = -e * vn;
                        if rebound > resting_speed {
                            rebound
                        } else {
                            0.0
                        }
                    } else {
                        0.0
                    }
                },
                &mut self.rows,
            );
            f.rows = (start, self.rows.len());
            f.impact = impact;
            f.before = before;
        }
        self.lambda.clear();
        self.lambda.resize(self.rows.len(), 0.0);
        let mut keys: Vec<(usize, usize)> = found.iter().map(|f| (f.a, f.b)).collect();
        // Jointed bodies share an island: an impulse on one moves the
        // others through the joints (module `constrained`).
        if let Some(j) = joints.as_deref() {
            keys.extend(constrained::joint_pairs(j));
        }
        let island = islands(&self.views, &keys);
        let mut order: Vec<usize> = (0..found.len()).collect();
        order.sort_by_key(|&i| island[i]);
        self.out.clear();
        self.out.resize(bodies.len(), (Vector2::zeros(), 0.0));
        let mut start = 0;
        let mut rows = Vec::new();
        let mut lambda = Vec::new();
        while start < order.len() {
            let mut end = start + 1;
            while end < order.len() && island[order[end]] == island[order[start]] {
                end += 1;
            }
            rows.clear();
            let mut index = Vec::new();
            for &i in &order[start..end] {
                let (r0, r1) = found[i].rows;
                let offset = rows.len() as isize - r0 as isize;
                for r in r0..r1 {
                    let mut row = self.rows[r];
                    if let RowKind::Friction { mu, normals } = row.kind {
                        let shift = |x: usize| (x as isize + offset) as usize;
                        row.kind = RowKind::Friction {
                            mu,
                            normals: (shift(normals.0), shift(normals.1)),
                        };
                    }
                    rows.push(row);
                    index.push(r);
                }
            }
            check_size(rows.len(), end - start, t)?;
            self.b.clear();
            self.b
                .extend(rows.iter().map(|r| r.velocity(&self.views) - r.target));
            match joints.as_deref_mut() {
                // The joints held through the impact: K = J_c P W_cᵀ.
                Some(j) => {
                    constrained::effective_mass(
                        j,
                        bodies,
                        layout,
                        states,
                        &rows,
                        &mut self.k,
                        &mut self.columns,
                    );
                    constrained::drop_locked(&rows, &self.views, &mut self.k, &mut self.b);
                }
                None => effective_mass(&rows, &self.views, &mut self.k),
            }
            solve(&rows, &self.k, &self.b, &mut lambda);
            // A touching point the impulses leave separating slower than the
            // resting speed (and faster than the sliding speed, the speed
            // contacts count as zero) rests: its separation is cancelled too
            // (a hold row, which may pull), as an approach that slow is. A
            // bounce (a restitution target) is left alone. Without it a box
            // dropped flat rocks on its corners forever at the scale of ε
            // (each corner falling back through the tolerance band picks up
            // √(2 a ε)). Cancelling a relative velocity only removes kinetic
            // energy (the velocities are projected onto a cone of admissible
            // ones that contains rest).
            loop {
                let n = rows.len();
                let mut held = false;
                for (j, row) in rows.iter_mut().enumerate() {
                    if row.kind != RowKind::Normal || row.target != 0.0 {
                        continue;
                    }
                    let after =
                        self.b[j] + (0..n).map(|i| self.k[j * n + i] * lambda[i]).sum::<f64>();
                    if after > s.sliding_speed && after <= resting_speed {
                        row.kind = RowKind::Hold;
                        held = true;
                    }
                }
                if !held {
                    break;
                }
                solve(&rows, &self.k, &self.b, &mut lambda);
            }
            for ((row, &l), &r) in rows.iter().zip(&lambda).zip(&index) {
                self.lambda[r] = l;
                if l != 0.0 {
                    row.apply(l, &mut self.out);
                }
            }
            start = end;
        }
        if let Some(j) = joints {
            changed |= constrained::apply_impulses(
                j,
                bodies,
                layout,
                states,
                &mut self.views,
                &self.out,
                y,
            );
            self.out.clear();
        }
        for (i, (dv, dw)) in self.out.iter().enumerate() {
            let v = &mut self.views[i];
            if (dv.x != 0.0 || dv.y != 0.0 || *dw != 0.0) && v.inv_mass > 0.0 {
                v.velocity += v.inv_mass * dv;
                v.omega += v.inv_inertia * dw;
                states[i].velocity = v.velocity;
                if bodies[i].rotates() {
                    states[i].angular_velocity = v.omega;
                }
                write_velocity(layout, y, i, &states[i]);
                changed = true;
            }
        }
        // Impact events.
        for f in found.iter() {
            if f.impact {
                let event = self.event(t, ContactEventKind::Impact, f);
                self.events.push(event);
            }
        }
        // The resting pairs of the next piece of step.
        let mut next: Vec<RestingPair> = Vec::new();
        for f in found.iter() {
            // The points that rest (a slow separation was cancelled above);
            // a point that bounces or leaves faster than the resting speed
            // is not held (holding keeps a speed of separation: d'' ≥ 0,
            // module `persistent`), and one that comes back is an impact.
            let (r0, _) = f.rows;
            let count = f.manifold.points().len();
            let mut kept = [false; 2];
            for (k, keep) in kept.iter_mut().enumerate().take(count) {
                let row = &self.rows[r0 + k];
                *keep = row.target == 0.0 && row.velocity(&self.views) <= resting_speed;
            }
            let Some(features) = f.features.retain(kept) else {
                continue;
            };
            let friction = if s.friction > 0.0 {
                let (sum, n) = f
                    .manifold
                    .points()
                    .iter()
                    .zip(kept)
                    .filter(|(_, k)| *k)
                    .fold((Vector2::zeros(), 0.0), |(sum, n), (p, _)| {
                        (sum + p.point, n + 1.0)
                    });
                let centre = sum / n;
                let v = self.views[f.b].point_velocity(centre - self.views[f.b].position)
                    - self.views[f.a].point_velocity(centre - self.views[f.a].position);
                let tangent = perp(f.manifold.normal);
                let vt = tangent.dot(&v);
                if vt.abs() <= s.sliding_speed {
                    FrictionMode::Sticking
                } else {
                    FrictionMode::Sliding {
                        direction: vt.signum() * tangent,
                    }
                }
            } else {
                FrictionMode::Frictionless
            };
            next.push(RestingPair {
                a: f.a,
                b: f.b,
                friction,
                features,
            });
        }
        next.sort_by_key(|p| (p.a, p.b));
        // Events of the resting set: begins, ends, stick, slip.
        for p in &next {
            let old = resting.pairs.iter().find(|q| (q.a, q.b) == (p.a, p.b));
            let f = found
                .iter()
                .find(|f| (f.a, f.b) == (p.a, p.b))
                .expect("resting pairs come from the manifolds");
            let kind = match (old.map(|q| q.friction), p.friction) {
                (None, _) => Some(ContactEventKind::Rest),
                (Some(FrictionMode::Sliding { .. }), FrictionMode::Sticking) => {
                    Some(ContactEventKind::Stick)
                }
                (Some(FrictionMode::Sticking), FrictionMode::Sliding { .. }) => {
                    Some(ContactEventKind::Slip)
                }
                _ => None,
            };
            if let Some(kind) = kind {
                let event = self.event(t, kind, f);
                self.events.push(event);
            }
        }
        for q in &resting.pairs {
            if !next.iter().any(|p| (p.a, p.b) == (q.a, q.b)) {
                let f = found.iter().find(|f| (f.a, f.b) == (q.a, q.b));
                let (point, normal, points) = match f {
                    Some(f) => (
                        f.manifold.points()[0].point,
                        f.manifold.normal,
                        f.manifold.points().len(),
                    ),
                    None => (
                        0.5 * (states[q.a].position + states[q.b].position),
                        Vector2::zeros(),
                        0,
                    ),
                };
                self.events.push(ContactEvent {
                    t,
                    kind: ContactEventKind::Release,
                    body_a: q.a,
                    body_b: q.b,
                    point,
                    normal,
                    points,
                    normal_impulse: 0.0,
                    tangent_impulse: 0.0,
                    normal_velocity_before: f64::NAN,
                    normal_velocity_after: f64::NAN,
                });
            }
        }
        // The features move with the bodies: always take the new ones, but
        // only a change of pairs, friction modes or features stales the
        // integrator's cached derivative.
        changed |= next != resting.pairs;
        resting.pairs = next;
        resting.friction = s.friction;
        resting.tolerance = s.tolerance;
        Ok(changed)
    }

    /// The record of manifold `f` after the impulses.
    fn event(&self, t: f64, kind: ContactEventKind, f: &Found) -> ContactEvent {
        let (r0, r1) = f.rows;
        let mut normal_impulse = 0.0;
        let mut tangent_impulse = 0.0;
        let mut weighted = Vector2::zeros();
        let mut centre = Vector2::zeros();
        let mut after = f64::INFINITY;
        let mut count = 0;
        for r in r0..r1 {
            let row = &self.rows[r];
            let l = self.lambda[r];
            match row.kind {
                RowKind::Normal | RowKind::Hold => {
                    let p = self.views[row.sides[1].body].position + row.sides[1].arm;
                    normal_impulse += l;
                    weighted += l * p;
                    centre += p;
                    count += 1;
                    after = after.min(row.velocity(&self.views));
                }
                RowKind::Friction { .. } => tangent_impulse += l,
            }
        }
        let point = if normal_impulse > 0.0 {
            weighted / normal_impulse
        } else {
            centre / count.max(1) as f64
        };
        ContactEvent {
            t,
            kind,
            body_a: f.a,
            body_b: f.b,
            point,
            normal: f.manifold.normal,
            points: count,
            normal_impulse,
            tangent_impulse,
            normal_velocity_before: f.before,
            normal_velocity_after: after,
        }
    }

    /// Pushes apart (positions only) the pairs overlapping by more than
    /// [`PROJECTION_SLOP`] ε, by the linearised least motion that removes
    /// the overlap of their points while every other touching pair (a body
    /// resting on a static one, above all) sinks no deeper: nothing is
    /// pushed through a static body. Moving positions injects no kinetic
    /// energy. Returns whether anything moved.
    ///
    /// A deep pair of polygons that is as deep along several faces (two
    /// equal boxes created at the same place are 1 m deep along all eight)
    /// is separated along the one whose motion its bodies' contacts with
    /// immovable bodies oppose least: along the ground rather than into it
    /// or off it, the least motion (three coincident boxes on the ground
    /// end side by side, not stacked, with their energy unchanged).
    #[allow(clippy::too_many_arguments)]
    fn project(
        &mut self,
        bodies: &[Body],
        layout: &Layout,
        states: &mut [BodyState],
        found: &[Found],
        y: &mut [f64],
        t: f64,
    ) -> Result<bool> {
        let eps = self.settings.tolerance;
        let views: Vec<BodyView> = bodies
            .iter()
            .zip(states.iter())
            .map(|(b, st)| BodyView::new(b, st))
            .collect();
        let immovable = |i: usize| views[i].inv_mass == 0.0 && views[i].inv_inertia == 0.0;
        // Each dynamic body's supports: the normals of its contacts with
        // immovable bodies, pointing into it.
        let mut supports: Vec<(usize, Vector2<f64>)> = Vec::new();
        for f in found {
            if immovable(f.a) && !immovable(f.b) {
                supports.push((f.b, f.manifold.normal));
            } else if immovable(f.b) && !immovable(f.a) {
                supports.push((f.a, -f.manifold.normal));
            }
        }
        // How much the supports oppose separating (a, b) along n (A moves
        // along −n, B along +n).
        let opposed = |a: usize, b: usize, n: Vector2<f64>| -> f64 {
            supports
                .iter()
                .map(|&(body, u)| {
                    if body == a {
                        n.dot(&u).max(0.0)
                    } else if body == b {
                        (-n.dot(&u)).max(0.0)
                    } else {
                        0.0
                    }
                })
                .sum()
        };
        let mut rows = Vec::new();
        let mut b = Vec::new();
        for f in found {
            let deep = f.manifold.max_depth() > PROJECTION_SLOP * eps;
            let mut manifold = f.manifold;
            if deep && !immovable(f.a) && !immovable(f.b) {
                let (sa, sb) = (
                    bodies[f.a].shape.as_ref().expect("collidable"),
                    bodies[f.b].shape.as_ref().expect("collidable"),
                );
                let (pa, pb) = (pose(&states[f.a]), pose(&states[f.b]));
                let faces = equally_deep(sa, &pa, sb, &pb, eps);
                let mut best: Option<(f64, Face)> = None;
                for (face, n) in faces {
                    let cost = opposed(f.a, f.b, n);
                    if best.is_none_or(|(c, _)| cost < c) {
                        best = Some((cost, face));
                    }
                }
                let refaced = best.and_then(|(_, face)| {
                    collide_on_face(sa, &pa, sb, &pb, eps, Some(face)).map(|(m, _)| m)
                });
                manifold = refaced.unwrap_or(manifold);
            }
            for p in manifold.points() {
                let sides = [
                    Side {
                        body: f.a,
                        sign: -1.0,
                        arm: p.point - views[f.a].position,
                    },
                    Side {
                        body: f.b,
                        sign: 1.0,
                        arm: p.point - views[f.b].position,
                    },
                ];
                rows.push(Row {
                    kind: RowKind::Normal,
                    sides,
                    measure: manifold.normal,
                    push: manifold.normal,
                    target: 0.0,
                });
                // A deep point is pushed out; a touching one sinks no
                // deeper.
                b.push(if deep { -p.depth } else { 0.0 });
            }
        }
        check_size(rows.len(), found.len(), t)?;
        effective_mass(&rows, &views, &mut self.k);
        let mut lambda = Vec::new();
        solve(&rows, &self.k, &b, &mut lambda);
        let mut out = vec![(Vector2::zeros(), 0.0); bodies.len()];
        for (row, &l) in rows.iter().zip(&lambda) {
            row.apply(l, &mut out);
        }
        let mut moved = false;
        for (i, (dx, dth)) in out.iter().enumerate() {
            let v = &views[i];
            if v.inv_mass > 0.0 && (dx.norm() > 0.0 || *dth != 0.0) {
                states[i].position += v.inv_mass * dx;
                if bodies[i].rotates() {
                    states[i].angle += v.inv_inertia * dth;
                }
                write_pose(layout, y, i, &states[i]);
                moved = true;
            }
        }
        Ok(moved)
    }
}

/// The joints of `sys` whose `collide_connected` the contact search reads
/// (`None` without joints).
pub(super) fn joint_set<'s>(sys: &'s WorldOde<'_>) -> Option<&'s JointSet> {
    sys.joints.as_deref().map(|j| &j.set)
}

/// Refuses a contact problem of `rows` rows (over `pairs` touching pairs)
/// larger than [`MAX_CONTACT_ROWS`], naming the remedy.
fn check_size(rows: usize, pairs: usize, t: f64) -> Result<()> {
    if rows <= MAX_CONTACT_ROWS {
        return Ok(());
    }
    Err(EngineError::Contact {
        t,
        reason: format!(
            "{pairs} touching pairs make one contact problem of {rows} rows, more than the \
             {MAX_CONTACT_ROWS} the exact model's dense solver takes (it is meant for a few \
             bodies); use the soft_step contact model for many bodies in contact"
        ),
    })
}
