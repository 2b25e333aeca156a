//! Every joint of a soft-step world: the definitions as resolved when they
//! were added (bodies, anchors in the bodies' frames, reference angle),
//! the solver records (rows and impulses, one enum per joint), the
//! joints of each body (for the collision filter and for removal), and the
//! passes over them: prepare once per step, then warm start, solve and
//! relax in every substep, and the impulses stored back after the step.
//!
//! Prepare colours the active revolute joints (the most common type) by
//! their dynamic bodies, as the contacts are coloured
//! ([`crate::soft_step::colouring`], its own instance), and writes each
//! into its lane of a four-lane record of its colour
//! ([`super::wide_revolute`]); the other types and the revolute joints
//! that find no colour stay scalar. Each pass solves the scalar joints one
//! at a time in the order added, then the records colour after colour:
//! another valid order of the same Gauss–Seidel iteration, whose lanes
//! give the scalar solver's bits.

use super::super::contact_events::JointEvent;
use super::distance::DistanceRows;
use super::frame::JointFrame;
use super::motor_joint::MotorJointRows;
use super::prismatic::PrismaticRows;
use super::revolute::RevoluteRows;
use super::target::TargetRows;
use super::weld::WeldRows;
use super::wheel::WheelRows;
use super::wide_revolute::{self, WideAxial, WideRevolute};
use super::{
    Distance, JointDef, JointId, JointKind, JointState, JointType, Target, invalid, world_point,
    wrap_angle,
};
use crate::body::{BodyId, BodyKind, BodyState};
use crate::error::{EngineError, Result};
use crate::soft_step::Softness;
use crate::soft_step::bodies::{BodyMass, BodySim, SolverBody, solver_index};
use crate::soft_step::colouring::{Colouring, Slot};
use crate::soft_step::lanes::LANES;
use crate::soft_step::pool::{Pool, SharedSlice, Worker};
use crate::world_core::WorldCore;
use nalgebra::Vector2;
use smallvec::SmallVec;

/// The rows of one joint, by type.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum JointRows {
    Revolute(RevoluteRows),
    Prismatic(PrismaticRows),
    Distance(DistanceRows),
    Weld(WeldRows),
    Target(TargetRows),
    Wheel(WheelRows),
    Motor(MotorJointRows),
}

/// A joint's solver record (its frame for the step is in the scalar list
/// or its lane).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointSim {
    /// Whether it is solved this step (not removed, an awake body).
    pub active: bool,
    pub rows: JointRows,
}

/// A joint's definition as resolved when it was added.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointInfo {
    pub name: String,
    pub body_a: Option<BodyId>,
    pub body_b: Option<BodyId>,
    /// Anchors in the bodies' frames, from each centre of mass (a world
    /// point on the world side) (m).
    pub local_a: Vector2<f64>,
    pub local_b: Vector2<f64>,
    /// θref (rad).
    pub reference_angle: f64,
    pub collide_connected: bool,
    pub constraint_hertz: f64,
    pub constraint_damping_ratio: f64,
    /// Reported at or above these (N, N·m); `None`: never.
    pub force_threshold: Option<f64>,
    pub torque_threshold: Option<f64>,
    pub removed: bool,
}

/// A joint's measured state ([`JointState`] without its identity).
struct Measures {
    joint_type: JointType,
    anchor_a: Vector2<f64>,
    anchor_b: Vector2<f64>,
    angle: f64,
    translation: f64,
    linear_error: f64,
    angular_error: f64,
    force: Vector2<f64>,
    torque: f64,
    motor: f64,
}

/// A joint as one of its bodies sees it: which joint, the body at its
/// other end, and whether it keeps the two from colliding (what the pair
/// filter reads, without touching the joint itself).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct JointEdge {
    joint: u32,
    /// The other body, [`WORLD`] for the world.
    other: u32,
    keeps_apart: bool,
}

/// The other end of a joint to the world.
const WORLD: u32 = u32::MAX;

/// The joints of a world.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointSet {
    pub sims: Vec<JointSim>,
    pub infos: Vec<JointInfo>,
    /// Per body: its joints.
    body_joints: Vec<SmallVec<[JointEdge; 4]>>,
    /// 1/h of the last step's substep (1/s), for the reaction forces.
    inv_h: f64,
    /// The step's colouring of the active revolute joints, in the order
    /// added.
    #[cfg_attr(feature = "serde", serde(skip))]
    colouring: Colouring,
    /// The joints coloured, in the order added (the colouring's order).
    #[cfg_attr(feature = "serde", serde(skip))]
    coloured: Vec<u32>,
    /// The joints solved one at a time, in the order added, with their
    /// frames for the step: every active joint but the revolute joints in
    /// a lane.
    #[cfg_attr(feature = "serde", serde(skip))]
    scalar: Vec<(u32, JointFrame)>,
    /// The revolute joints of the step's colours, four per record, colour
    /// after colour, and their angle rows.
    #[cfg_attr(feature = "serde", serde(skip))]
    wide: Vec<WideRevolute>,
    #[cfg_attr(feature = "serde", serde(skip))]
    axial: Vec<WideAxial>,
    /// Scratch of prepare on threads: the joint of each lane
    /// (`u32::MAX`: padding), and the joints solved one at a time.
    #[cfg_attr(feature = "serde", serde(skip))]
    lane_source: Vec<u32>,
    #[cfg_attr(feature = "serde", serde(skip))]
    scalar_ids: Vec<u32>,
}

/// A body's pose and masses as prepare reads them.
struct Side {
    index: usize,
    inv_mass: f64,
    inv_inertia: f64,
    position: Vector2<f64>,
    angle: f64,
    rotation: (f64, f64),
}

impl Side {
    const WORLD: Side = Side {
        index: 0,
        inv_mass: 0.0,
        inv_inertia: 0.0,
        position: Vector2::new(0.0, 0.0),
        angle: 0.0,
        rotation: (1.0, 0.0),
    };

    fn rotate(&self, r: Vector2<f64>) -> Vector2<f64> {
        let (c, s) = self.rotation;
        Vector2::new(c * r.x - s * r.y, s * r.x + c * r.y)
    }
}

/// What prepare reads to build a joint's frame and rows (shared by the
/// threads).
struct FrameInputs<'a> {
    masses: &'a [BodyMass],
    sims: &'a [BodySim],
    /// The world's body states (poses at the start of the step).
    states: &'a [BodyState],
    /// The substep (s).
    h: f64,
    /// Whether the impulses are kept (warm starting).
    warm: bool,
}

impl FrameInputs<'_> {
    /// Body `body`'s pose and masses, the world's for `None`.
    fn side(&self, body: Option<BodyId>) -> Side {
        let Some(id) = body else {
            return Side::WORLD;
        };
        let m = &self.masses[id];
        let s = &self.states[id];
        let q = self.sims[id].rotation;
        Side {
            index: solver_index(id, m.kind),
            inv_mass: m.inv_mass,
            inv_inertia: m.inv_inertia,
            position: s.position,
            angle: s.angle,
            rotation: (q.re, q.im),
        }
    }

    /// The frame of joint (`sim`, `info`) for the step, its rows prepared
    /// (`caches`: the rigid rows' and the revolute springs' softness).
    fn prepare_joint(
        &self,
        sim: &mut JointSim,
        info: &JointInfo,
        (rigid, springs): &mut (SoftnessCache, SoftnessCache),
    ) -> JointFrame {
        let (h, warm) = (self.h, self.warm);
        let (a, b) = (self.side(info.body_a), self.side(info.body_b));
        let hertz = info.constraint_hertz.min(0.25 / h);
        let frame = JointFrame {
            a: a.index,
            b: b.index,
            ma: a.inv_mass,
            ia: a.inv_inertia,
            mb: b.inv_mass,
            ib: b.inv_inertia,
            ra: a.rotate(info.local_a),
            rb: b.rotate(info.local_b),
            delta_center: b.position - a.position,
            angle: wrap_angle(b.angle - a.angle - info.reference_angle),
            softness: rigid.get(hertz, info.constraint_damping_ratio),
        };
        match &mut sim.rows {
            JointRows::Revolute(r) => {
                let spring = r
                    .joint
                    .spring
                    .map_or(Softness::RIGID, |s| springs.get(s.hertz, s.damping_ratio));
                r.prepare(&frame, spring, warm);
            }
            JointRows::Prismatic(p) => p.prepare(h, a.rotation, warm),
            JointRows::Distance(d) => d.prepare(h, warm),
            JointRows::Weld(w) => w.prepare(&frame, h, warm),
            JointRows::Target(t) => t.prepare(h, warm),
            JointRows::Wheel(w) => w.prepare(h, a.rotation, warm),
            JointRows::Motor(m) => m.prepare(h, a.rotation, warm),
        }
        frame
    }
}

/// The softness of the last (frequency, damping ratio) asked for, for
/// substeps of `h`: joints mostly share theirs, and [`Softness::new`]
/// divides twice (the same inputs give the same bits either way).
struct SoftnessCache {
    h: f64,
    key: (f64, f64),
    value: Softness,
}

impl SoftnessCache {
    fn new(h: f64) -> Self {
        Self {
            h,
            key: (f64::NAN, f64::NAN),
            value: Softness::RIGID,
        }
    }

    #[inline]
    fn get(&mut self, hertz: f64, damping_ratio: f64) -> Softness {
        if self.key != (hertz, damping_ratio) {
            self.key = (hertz, damping_ratio);
            self.value = Softness::new(hertz, damping_ratio, self.h);
        }
        self.value
    }
}

impl JointSet {
    /// Registers the next body.
    pub(crate) fn body_added(&mut self) {
        self.body_joints.push(SmallVec::new());
    }

    /// Registers bodies until the set knows `count` of them (the exact
    /// model's joints, whose world adds bodies without telling the set).
    pub(crate) fn know_bodies(&mut self, count: usize) {
        while self.body_joints.len() < count {
            self.body_added();
        }
    }

    /// How many joints were added (removed ones included).
    pub(crate) fn len(&self) -> usize {
        self.infos.len()
    }

    /// The first joint of `body`, if it has any.
    pub(crate) fn first_of_body(&self, body: BodyId) -> Option<JointId> {
        self.body_joints[body].first().map(|e| e.joint as usize)
    }

    /// Whether a joint between `a` and `b` keeps them from colliding:
    /// walks the shorter of the two bodies' joint lists (Box2D's
    /// `b2ShouldBodiesCollide`); nothing to walk for bodies without joints.
    #[inline]
    pub(crate) fn keeps_apart(&self, a: BodyId, b: BodyId) -> bool {
        let (ja, jb) = (&self.body_joints[a], &self.body_joints[b]);
        if ja.is_empty() || jb.is_empty() {
            return false;
        }
        let (list, other) = if ja.len() <= jb.len() {
            (ja, b)
        } else {
            (jb, a)
        };
        list.iter()
            .any(|e| e.keeps_apart && e.other as usize == other)
    }

    /// Validates `def` against the world in `core` and adds it.
    pub(crate) fn add(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId> {
        def.check_numbers()?;
        let name = def.name.as_str();
        let count = core.bodies.len();
        for (side, body) in [("A", def.body_a), ("B", def.body_b)] {
            if let Some(id) = body {
                if id >= count {
                    return Err(invalid(
                        name,
                        format!("body {side} is index {id}, and the world has {count} bodies"),
                    ));
                }
                if core.removed[id] {
                    return Err(invalid(
                        name,
                        format!("body {side} '{}' was removed", core.bodies[id].name),
                    ));
                }
            }
        }
        if def.body_a.is_some() && def.body_a == def.body_b {
            return Err(invalid(
                name,
                format!(
                    "it joins body '{}' to itself: give two different bodies (or the world)",
                    core.bodies[def.body_a.unwrap_or(0)].name
                ),
            ));
        }
        let dynamic = |b: Option<BodyId>| b.is_some_and(|id| core.bodies[id].is_dynamic());
        if !dynamic(def.body_a) && !dynamic(def.body_b) {
            let say = |b: Option<BodyId>| match b {
                None => "the world".to_string(),
                Some(id) => {
                    let kind = match core.bodies[id].kind {
                        BodyKind::Static => "static",
                        BodyKind::Kinematic => "kinematic",
                        BodyKind::Dynamic => "dynamic",
                    };
                    format!("the {kind} body '{}'", core.bodies[id].name)
                }
            };
            return Err(invalid(
                name,
                format!(
                    "it joins {} and {}: at least one body must be dynamic",
                    say(def.body_a),
                    say(def.body_b)
                ),
            ));
        }
        if let JointKind::Target(_) = def.kind {
            Target::check_sides(name, def.body_a, def.body_b)?;
        }
        let (local_a, local_b) = def.local_anchors(&core.states);
        let angle = |b: Option<BodyId>| b.map_or(0.0, |id| core.states[id].angle);
        // A motor joint's angle is measured from its angular offset.
        let reference_angle = match &def.kind {
            JointKind::Motor(m) => m.angular_offset,
            _ => def
                .reference_angle
                .unwrap_or_else(|| angle(def.body_b) - angle(def.body_a)),
        };
        let local_axis = |axis: Vector2<f64>| {
            let u = axis.normalize();
            let (s, c) = angle(def.body_a).sin_cos();
            Vector2::new(c * u.x + s * u.y, -s * u.x + c * u.y)
        };
        let pa = world_point(def.body_a, local_a, &core.states);
        let pb = world_point(def.body_b, local_b, &core.states);
        let rows = match &def.kind {
            JointKind::Revolute(j) => JointRows::Revolute(RevoluteRows::new(*j)),
            JointKind::Prismatic(j) => {
                let u = j.axis.normalize();
                let (s, c) = angle(def.body_a).sin_cos();
                let local = Vector2::new(c * u.x + s * u.y, -s * u.x + c * u.y);
                JointRows::Prismatic(PrismaticRows::new(*j, local))
            }
            JointKind::Distance(j) => {
                let measured = (pb - pa).norm();
                let needs_length = !matches!(j, Distance::Rope { .. });
                // The anchors are finite (checked above): so is `measured`.
                if needs_length && j.length().is_none() && measured <= 1e-9 {
                    return Err(invalid(
                        name,
                        format!(
                            "its anchors coincide (at [{}, {}] m): give a length, or anchors apart",
                            crate::error::readable(pa.x),
                            crate::error::readable(pa.y)
                        ),
                    ));
                }
                JointRows::Distance(DistanceRows::new(j, measured))
            }
            JointKind::Weld(j) => JointRows::Weld(WeldRows::new(*j)),
            JointKind::Target(j) => JointRows::Target(TargetRows::new(*j)),
            JointKind::Wheel(j) => JointRows::Wheel(WheelRows::new(*j, local_axis(j.axis))),
            JointKind::Motor(j) => JointRows::Motor(MotorJointRows::new(*j)),
        };
        let id = self.infos.len();
        self.infos.push(JointInfo {
            name: def.name.clone(),
            body_a: def.body_a,
            body_b: def.body_b,
            local_a,
            local_b,
            reference_angle,
            collide_connected: def.collide_connected,
            constraint_hertz: def.constraint_hertz,
            constraint_damping_ratio: def.constraint_damping_ratio,
            force_threshold: def.force_threshold,
            torque_threshold: def.torque_threshold,
            removed: false,
        });
        self.sims.push(JointSim {
            active: false,
            rows,
        });
        let end = |b: Option<BodyId>| b.map_or(WORLD, |id| id as u32);
        for (body, other) in [(def.body_a, def.body_b), (def.body_b, def.body_a)] {
            if let Some(body) = body {
                self.body_joints[body].push(JointEdge {
                    joint: id as u32,
                    other: end(other),
                    keeps_apart: !def.collide_connected,
                });
            }
        }
        Ok(id)
    }

    /// Checks that joint `id` exists.
    pub(crate) fn check(&self, id: JointId) -> Result<()> {
        if id < self.infos.len() {
            Ok(())
        } else {
            Err(EngineError::UnknownJoint {
                index: id,
                count: self.infos.len(),
            })
        }
    }

    /// Removes joint `id` (it stays, inert); returns whether it was there.
    pub(crate) fn remove(&mut self, id: JointId) -> bool {
        let info = &mut self.infos[id];
        if info.removed {
            return false;
        }
        info.removed = true;
        self.sims[id].active = false;
        for body in [info.body_a, info.body_b].into_iter().flatten() {
            self.body_joints[body].retain(|e| e.joint as usize != id);
        }
        true
    }

    /// Moves joint `id`'s target (a target joint only).
    pub(crate) fn set_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<BodyId> {
        let name = &self.infos[id].name;
        if !(target.x.is_finite() && target.y.is_finite()) {
            return Err(invalid(name, "the target must be a finite point".into()));
        }
        let JointRows::Target(_) = self.sims[id].rows else {
            return Err(invalid(
                name,
                "only a target joint has a target to move".into(),
            ));
        };
        self.infos[id].local_a = target;
        Ok(self.infos[id].body_b.unwrap_or(0))
    }

    /// Sets joint `id`'s motor speed (rad/s or m/s): a revolute or
    /// prismatic joint with a motor.
    pub(crate) fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        let name = &self.infos[id].name;
        super::finite(name, "motor speed", speed)?;
        match &mut self.sims[id].rows {
            JointRows::Revolute(RevoluteRows {
                joint: super::Revolute { motor: Some(m), .. },
                ..
            }) => m.speed = speed,
            JointRows::Prismatic(PrismaticRows {
                joint: super::Prismatic { motor: Some(m), .. },
                ..
            }) => m.speed = speed,
            JointRows::Wheel(WheelRows {
                joint: super::Wheel { motor: Some(m), .. },
                ..
            }) => m.speed = speed,
            _ => {
                return Err(invalid(
                    name,
                    "it has no motor (only a revolute, prismatic or wheel joint with a motor has a speed)"
                        .into(),
                ));
            }
        }
        Ok(())
    }

    /// Prepare: the joints of an awake body are coloured (the revolute
    /// ones, [`Self::colour`]), then each gets its frame for a step of
    /// substeps `h` (s) and its rows: a revolute joint with a colour is
    /// written into its lane, every other one joins the scalar list with
    /// its frame. With `pool`, the records are written on its threads (each
    /// its share of the records, lane after lane) while thread 0 also
    /// prepares the scalar joints, in the order added: each joint's rows
    /// and lane are computed by the same formulas from the same inputs, so
    /// the bits do not depend on the thread count.
    #[inline(never)]
    pub(crate) fn prepare(
        &mut self,
        core: &WorldCore,
        (masses, sims): (&[BodyMass], &[BodySim]),
        (h, warm): (f64, bool),
        pool: Option<&Pool>,
    ) {
        self.inv_h = 1.0 / h;
        self.colour(masses);
        let inputs = FrameInputs {
            masses,
            sims,
            states: &core.states,
            h,
            warm,
        };
        self.scalar.clear();
        if let Some(pool) = pool {
            self.prepare_on_threads(pool, &inputs);
            return;
        }
        // Most joints share their softness: computed once per value.
        let mut caches = (SoftnessCache::new(h), SoftnessCache::new(h));
        let mut coloured = 0;
        for (id, (sim, info)) in self.sims.iter_mut().zip(&self.infos).enumerate() {
            if !sim.active {
                continue;
            }
            let frame = inputs.prepare_joint(sim, info, &mut caches);
            if let JointRows::Revolute(r) = &sim.rows {
                let slot = self.colouring.slot(coloured);
                coloured += 1;
                if let Slot::Lane { record, lane } = slot {
                    wide_revolute::set_lane(
                        (&mut self.wide[record], &mut self.axial[record]),
                        lane,
                        (&frame, r),
                        h,
                    );
                    continue;
                }
            }
            self.scalar.push((id as u32, frame));
        }
        for (record, lane) in self.colouring.padding() {
            wide_revolute::set_padding_lane(
                (&mut self.wide[record], &mut self.axial[record]),
                lane,
            );
        }
    }

    /// [`Self::prepare`]'s frames, rows and lanes on `pool`'s threads.
    fn prepare_on_threads(&mut self, pool: &Pool, inputs: &FrameInputs<'_>) {
        // Which joint each lane holds, and the joints solved one at a
        // time, in the order added (a serial pass over the joints, reading
        // only whether each is active and whether it has a lane).
        let records = self.wide.len();
        self.lane_source.clear();
        self.lane_source.resize(records * LANES, u32::MAX);
        for (i, &id) in self.coloured.iter().enumerate() {
            if let Slot::Lane { record, lane } = self.colouring.slot(i) {
                self.lane_source[record * LANES + lane] = id;
            }
        }
        self.scalar_ids.clear();
        let mut coloured = 0;
        for (id, sim) in self.sims.iter().enumerate() {
            if !sim.active {
                continue;
            }
            if let JointRows::Revolute(_) = sim.rows {
                let slot = self.colouring.slot(coloured);
                coloured += 1;
                if let Slot::Lane { .. } = slot {
                    continue;
                }
            }
            self.scalar_ids.push(id as u32);
        }
        let (infos, source, scalar_ids, h) =
            (&self.infos, &self.lane_source, &self.scalar_ids, inputs.h);
        let joints = SharedSlice::new(&mut self.sims);
        let wide = SharedSlice::new(&mut self.wide);
        let axial = SharedSlice::new(&mut self.axial);
        let scalar = SharedSlice::new(std::slice::from_mut(&mut self.scalar));
        pool.run(&|w: &Worker<'_>| {
            let mut caches = (SoftnessCache::new(h), SoftnessCache::new(h));
            if w.index == 0 {
                // SAFETY: only thread 0 touches the scalar list and these
                // joints (none of them has a lane).
                let scalar = unsafe { scalar.get_mut(0) };
                for &id in scalar_ids {
                    let sim = unsafe { joints.get_mut(id as usize) };
                    let frame = inputs.prepare_joint(sim, &infos[id as usize], &mut caches);
                    scalar.push((id, frame));
                }
            }
            for record in w.share(records) {
                // SAFETY: each thread its own records, and the joints of
                // their lanes (a joint has one lane).
                let (r, x) = unsafe { (wide.get_mut(record), axial.get_mut(record)) };
                for lane in 0..LANES {
                    let id = source[record * LANES + lane];
                    if id == u32::MAX {
                        // Padding lanes come last in their record.
                        wide_revolute::set_padding_lane((r, x), lane);
                        continue;
                    }
                    // SAFETY: as above.
                    let sim = unsafe { joints.get_mut(id as usize) };
                    let frame = inputs.prepare_joint(sim, &infos[id as usize], &mut caches);
                    if let JointRows::Revolute(rows) = &sim.rows {
                        wide_revolute::set_lane((r, x), lane, (&frame, rows), h);
                    }
                }
            }
        });
    }

    /// Marks the joints solved this step (not removed, an awake body) and
    /// colours the active revolute joints by their dynamic bodies, in the
    /// order added; lays out their records. Nothing is allocated once the
    /// lists have grown to the scene's size.
    fn colour(&mut self, masses: &[BodyMass]) {
        let dynamic = |body: Option<BodyId>| body.filter(|&b| masses[b].kind == BodyKind::Dynamic);
        let moving = |body: Option<BodyId>| body.is_some_and(|b| masses[b].moving);
        self.colouring.clear(masses.len());
        self.coloured.clear();
        for (id, (sim, info)) in self.sims.iter_mut().zip(&self.infos).enumerate() {
            sim.active = !info.removed && (moving(info.body_a) || moving(info.body_b));
            if sim.active && matches!(sim.rows, JointRows::Revolute(_)) {
                self.colouring
                    .add_in_order(dynamic(info.body_a), dynamic(info.body_b));
                self.coloured.push(id as u32);
            }
        }
        let records = self.colouring.finish();
        self.wide.resize(records, WideRevolute::default());
        self.axial.resize(records, WideAxial::default());
        for w in &mut self.wide {
            w.axial = false;
        }
    }

    /// The impulses of the joints in lanes back into their records, after
    /// the step (for the next step's warm start and the joints' states).
    #[inline(never)]
    pub(crate) fn store_impulses(&mut self) {
        for (i, &id) in self.coloured.iter().enumerate() {
            let Slot::Lane { record, lane } = self.colouring.slot(i) else {
                continue;
            };
            if let JointRows::Revolute(rows) = &mut self.sims[id as usize].rows {
                wide_revolute::store_lane((&self.wide[record], &self.axial[record]), lane, rows);
            }
        }
    }

    /// Applies every active joint's accumulated impulses: the scalar
    /// joints, then the records.
    #[inline(never)]
    pub(crate) fn warm_start(&self, bodies: &mut [SolverBody]) {
        warm_start_scalar(&self.scalar, &self.sims, bodies);
        wide_revolute::warm_start(&self.wide, &self.axial, bodies);
    }

    /// One pass of sequential impulses over the active joints (the scalar
    /// ones, then the records), with the rigid rows' soft bias
    /// (`use_bias`, the solve pass) or without (the relax pass), for
    /// substeps of `h` (s).
    #[inline(never)]
    pub(crate) fn solve(&mut self, bodies: &mut [SolverBody], h: f64, use_bias: bool) {
        solve_scalar(&self.scalar, &mut self.sims, bodies, h, use_bias);
        let inv_h = 1.0 / h;
        if use_bias {
            wide_revolute::solve(&mut self.wide, &mut self.axial, bodies, inv_h);
        } else {
            wide_revolute::relax(&mut self.wide, &mut self.axial, bodies, inv_h);
        }
    }

    /// The passes' data split for the threads (`soft_step::parallel`): the
    /// scalar joints (solved on one thread, first), and the records with
    /// their colouring (each colour's records split among the threads).
    pub(crate) fn split_for_threads(&mut self) -> (ScalarJoints<'_>, WideJoints<'_>) {
        (
            ScalarJoints {
                list: &self.scalar,
                sims: &mut self.sims,
            },
            WideJoints {
                colouring: &self.colouring,
                records: &mut self.wide,
                axial: &mut self.axial,
            },
        )
    }

    /// Joint `id` now, from the bodies' `states`.
    pub(crate) fn state(&self, id: JointId, states: &[BodyState]) -> JointState {
        let info = &self.infos[id];
        let m = self.measures(id, states);
        JointState {
            name: info.name.clone(),
            joint_type: m.joint_type,
            body_a: info.body_a,
            body_b: info.body_b,
            local_anchor_a: info.local_a,
            local_anchor_b: info.local_b,
            anchor_a: m.anchor_a,
            anchor_b: m.anchor_b,
            angle: m.angle,
            translation: m.translation,
            linear_error: m.linear_error,
            angular_error: m.angular_error,
            force: m.force,
            torque: m.torque,
            motor: m.motor,
            removed: info.removed,
        }
    }

    /// Appends to `out` every live joint whose force or torque in the last
    /// substep reached its threshold (no allocation once `out` has grown).
    pub(crate) fn exceeded(&self, states: &[BodyState], out: &mut Vec<JointEvent>) {
        for (id, info) in self.infos.iter().enumerate() {
            if info.removed || (info.force_threshold.is_none() && info.torque_threshold.is_none()) {
                continue;
            }
            let m = self.measures(id, states);
            let over_force = info.force_threshold.is_some_and(|f| m.force.norm() >= f);
            let over_torque = info.torque_threshold.is_some_and(|t| m.torque.abs() >= t);
            if over_force || over_torque {
                out.push(JointEvent {
                    joint: id,
                    force: m.force,
                    torque: m.torque,
                });
            }
        }
    }

    /// What [`JointSet::state`] reports of joint `id`, without its name.
    fn measures(&self, id: JointId, states: &[BodyState]) -> Measures {
        let info = &self.infos[id];
        let sim = &self.sims[id];
        let pa = world_point(info.body_a, info.local_a, states);
        let pb = world_point(info.body_b, info.local_b, states);
        let angle_of = |b: Option<BodyId>| b.map_or(0.0, |id| states[id].angle);
        let angle =
            wrap_angle(angle_of(info.body_b) - angle_of(info.body_a) - info.reference_angle);
        let d = pb - pa;
        let inv_h = self.inv_h;
        let beyond = |v: f64, (lo, hi): (f64, f64)| (lo - v).max(v - hi).max(0.0);
        let (joint_type, translation, linear_error, angular_error, force, torque, motor) =
            match &sim.rows {
                JointRows::Revolute(r) => (
                    JointType::Revolute,
                    0.0,
                    d.norm(),
                    r.joint.limits.map_or(0.0, |l| beyond(angle, l)),
                    inv_h * r.linear,
                    inv_h * r.axial_impulse(),
                    inv_h * r.motor,
                ),
                JointRows::Prismatic(p) => {
                    let (s, c) = angle_of(info.body_a).sin_cos();
                    let u = p.local_axis;
                    let axis = Vector2::new(c * u.x - s * u.y, s * u.x + c * u.y);
                    let normal = Vector2::new(-axis.y, axis.x);
                    (
                        JointType::Prismatic,
                        axis.dot(&d),
                        normal.dot(&d).abs(),
                        angle.abs(),
                        inv_h * (p.axial_impulse() * axis + p.block.x * normal),
                        inv_h * p.block.y,
                        inv_h * p.motor,
                    )
                }
                JointRows::Distance(r) => {
                    let length = d.norm();
                    let error = if r.is_rigid() {
                        (length - r.length).abs()
                    } else {
                        beyond(length, (r.min_length, r.max_length))
                    };
                    let u = if length > 0.0 {
                        d / length
                    } else {
                        Vector2::zeros()
                    };
                    (
                        JointType::Distance,
                        length,
                        error,
                        0.0,
                        inv_h * r.axial_impulse() * u,
                        0.0,
                        0.0,
                    )
                }
                JointRows::Weld(w) => (
                    JointType::Weld,
                    0.0,
                    d.norm(),
                    angle.abs(),
                    inv_h * w.linear,
                    inv_h * w.angular,
                    0.0,
                ),
                JointRows::Target(t) => (
                    JointType::Target,
                    0.0,
                    d.norm(),
                    0.0,
                    inv_h * t.linear,
                    0.0,
                    0.0,
                ),
                JointRows::Wheel(w) => {
                    let (s, c) = angle_of(info.body_a).sin_cos();
                    let u = w.local_axis;
                    let axis = Vector2::new(c * u.x - s * u.y, s * u.x + c * u.y);
                    let normal = Vector2::new(-axis.y, axis.x);
                    let translation = axis.dot(&d);
                    (
                        JointType::Wheel,
                        translation,
                        normal
                            .dot(&d)
                            .abs()
                            .max(w.joint.limits.map_or(0.0, |l| beyond(translation, l))),
                        0.0,
                        inv_h * (w.axial_impulse() * axis + w.perpendicular * normal),
                        inv_h * w.motor,
                        inv_h * w.motor,
                    )
                }
                JointRows::Motor(m) => {
                    // The target of B's centre: A's centre plus the offset
                    // turned with A.
                    let (s, c) = angle_of(info.body_a).sin_cos();
                    let o = m.joint.linear_offset;
                    let error = d - Vector2::new(c * o.x - s * o.y, s * o.x + c * o.y);
                    (
                        JointType::Motor,
                        0.0,
                        error.norm(),
                        angle.abs(),
                        inv_h * m.linear,
                        inv_h * m.angular,
                        0.0,
                    )
                }
            };
        Measures {
            joint_type,
            anchor_a: pa,
            anchor_b: pb,
            angle,
            translation,
            linear_error,
            angular_error,
            force: if self.inv_h > 0.0 {
                force
            } else {
                Vector2::zeros()
            },
            torque: if self.inv_h > 0.0 { torque } else { 0.0 },
            motor: if self.inv_h > 0.0 { motor } else { 0.0 },
        }
    }

    /// The pairs of dynamic bodies held by an active joint, for the islands.
    pub(crate) fn dynamic_pairs<'a>(
        &'a self,
        sims: &'a [BodySim],
    ) -> impl Iterator<Item = (BodyId, BodyId)> + 'a {
        self.infos.iter().filter_map(move |info| {
            let (a, b) = (info.body_a?, info.body_b?);
            let dynamic = |id: BodyId| sims[id].kind == BodyKind::Dynamic;
            (!info.removed && dynamic(a) && dynamic(b)).then_some((a, b))
        })
    }
}

/// The joints solved one at a time in a pass, and their solver records.
pub(crate) struct ScalarJoints<'a> {
    list: &'a [(u32, JointFrame)],
    sims: &'a mut [JointSim],
}

impl ScalarJoints<'_> {
    /// Whether there are none this step.
    pub(crate) fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Their warm start ([`JointSet::warm_start`]'s first part).
    pub(crate) fn warm_start(&self, bodies: &mut [SolverBody]) {
        warm_start_scalar(self.list, self.sims, bodies);
    }

    /// Their pass ([`JointSet::solve`]'s first part).
    pub(crate) fn solve(&mut self, bodies: &mut [SolverBody], h: f64, use_bias: bool) {
        solve_scalar(self.list, self.sims, bodies, h, use_bias);
    }
}

/// The revolute joints in lanes: their records, colour after colour.
pub(crate) struct WideJoints<'a> {
    pub colouring: &'a Colouring,
    pub records: &'a mut [WideRevolute],
    pub axial: &'a mut [WideAxial],
}

/// Applies the accumulated impulses of the joints of `list` (in order).
fn warm_start_scalar(list: &[(u32, JointFrame)], sims: &[JointSim], bodies: &mut [SolverBody]) {
    for (id, f) in list {
        let sim = &sims[*id as usize];
        let (mut a, mut b) = (bodies[f.a], bodies[f.b]);
        match &sim.rows {
            JointRows::Revolute(r) => r.warm_start(f, &mut a, &mut b),
            JointRows::Prismatic(p) => p.warm_start(f, &mut a, &mut b),
            JointRows::Distance(d) => d.warm_start(f, &mut a, &mut b),
            JointRows::Weld(w) => w.warm_start(f, &mut a, &mut b),
            JointRows::Target(t) => t.warm_start(f, &mut a, &mut b),
            JointRows::Wheel(w) => w.warm_start(f, &mut a, &mut b),
            JointRows::Motor(m) => m.warm_start(f, &mut a, &mut b),
        }
        store(bodies, f, &a, &b);
    }
}

/// One pass of sequential impulses over the joints of `list` (in order),
/// with the rigid rows' bias or without, for substeps of `h` (s).
fn solve_scalar(
    list: &[(u32, JointFrame)],
    sims: &mut [JointSim],
    bodies: &mut [SolverBody],
    h: f64,
    use_bias: bool,
) {
    let inv_h = 1.0 / h;
    for (id, f) in list {
        let sim = &mut sims[*id as usize];
        let (mut a, mut b) = (bodies[f.a], bodies[f.b]);
        let pair = (&mut a, &mut b);
        match &mut sim.rows {
            JointRows::Revolute(r) => r.solve(f, pair, (h, inv_h), use_bias),
            JointRows::Prismatic(p) => p.solve(f, pair, (h, inv_h), use_bias),
            JointRows::Distance(d) => d.solve(f, pair, inv_h, use_bias),
            JointRows::Weld(w) => w.solve(f, pair, use_bias),
            JointRows::Target(t) => t.solve(f, pair, h),
            JointRows::Wheel(w) => w.solve(f, pair, (h, inv_h), use_bias),
            JointRows::Motor(m) => m.solve(f, pair, h),
        }
        store(bodies, f, &a, &b);
    }
}

/// Writes the two bodies' velocities back; the world's record at index 0
/// is unchanged by a joint (its inverse masses are 0).
#[inline(always)]
fn store(bodies: &mut [SolverBody], f: &JointFrame, a: &SolverBody, b: &SolverBody) {
    bodies[f.a].v = a.v;
    bodies[f.a].w = a.w;
    bodies[f.b].v = b.v;
    bodies[f.b].w = b.w;
}
