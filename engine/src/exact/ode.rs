//! The world seen as one ODE system in mechanical form `y = [q, v]`.
//!
//! Each dynamic body owns a slot: `x, y` (and `θ` when it rotates) in the
//! position block, the matching velocities at the same offset in the
//! velocity block. Particles carry no angle; static bodies are not in the
//! state at all (docs/design.md: "model no more than a scene needs").

use super::joints::ExactJoints;
use crate::body::{Body, BodyState};
use crate::contact::resting::RestingContacts;
use crate::forces::{Force, ForceContext, Wrench};
use crate::ode::{OdeSystem, Structure};

/// Where one dynamic body lives in the state vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Slot {
    /// Offset of `x` in the position block.
    pub offset: usize,
    /// Whether `θ` follows `y`.
    pub rotates: bool,
}

/// The map from bodies to state entries.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Layout {
    /// One entry per body; `None` for static bodies.
    pub slots: Vec<Option<Slot>>,
    /// Number of position coordinates (half the state).
    pub positions: usize,
}

impl Layout {
    pub(crate) fn new(bodies: &[Body]) -> Self {
        let mut positions = 0;
        let slots = bodies
            .iter()
            .map(|b| {
                b.is_dynamic().then(|| {
                    let slot = Slot {
                        offset: positions,
                        rotates: b.rotates(),
                    };
                    positions += if slot.rotates { 3 } else { 2 };
                    slot
                })
            })
            .collect();
        Self { slots, positions }
    }

    /// Writes the dynamic bodies' states into `y` (length `2 × positions`).
    pub(crate) fn pack(&self, states: &[BodyState], y: &mut Vec<f64>) {
        let n = self.positions;
        y.clear();
        y.resize(2 * n, 0.0);
        for (slot, s) in self.slots.iter().zip(states) {
            let Some(slot) = slot else { continue };
            let o = slot.offset;
            y[o] = s.position.x;
            y[o + 1] = s.position.y;
            y[n + o] = s.velocity.x;
            y[n + o + 1] = s.velocity.y;
            if slot.rotates {
                y[o + 2] = s.angle;
                y[n + o + 2] = s.angular_velocity;
            }
        }
    }

    /// Reads the dynamic bodies' states back from `y`; static ones keep theirs.
    pub(crate) fn unpack(&self, y: &[f64], states: &mut [BodyState]) {
        for (slot, s) in self.slots.iter().zip(states.iter_mut()) {
            if let Some(slot) = slot {
                self.read_slot(y, *slot, s);
            }
        }
    }

    /// One body's state in `y` (a static body's is `template[body]`),
    /// without unpacking the others.
    pub(crate) fn state_of(&self, y: &[f64], template: &[BodyState], body: usize) -> BodyState {
        let mut s = template[body];
        if let Some(slot) = self.slots[body] {
            self.read_slot(y, slot, &mut s);
        }
        s
    }

    fn read_slot(&self, y: &[f64], slot: Slot, s: &mut BodyState) {
        let (n, o) = (self.positions, slot.offset);
        s.position.x = y[o];
        s.position.y = y[o + 1];
        s.velocity.x = y[n + o];
        s.velocity.y = y[n + o + 1];
        if slot.rotates {
            s.angle = y[o + 2];
            s.angular_velocity = y[n + o + 2];
        }
    }
}

/// A force with the flag saying whether it acts during the current segment.
pub(crate) struct ActiveForce<'a> {
    pub force: &'a dyn Force,
    pub active: bool,
}

/// The world's right-hand side: Newton–Euler for every dynamic body,
/// `ẍ = F/m`, `θ̈ = τ/I` (seed §4.2.3–4.2.4), the forces including the
/// contact forces of resting pairs when the world has contacts (seed §7.1,
/// [`crate::contact`]) and the constraint forces of the joints
/// ([`crate::exact::joints`]).
pub(crate) struct WorldOde<'a> {
    pub bodies: &'a [Body],
    pub forces: Vec<ActiveForce<'a>>,
    pub layout: &'a Layout,
    /// Scratch: every body's state (static ones fixed).
    pub states: &'a mut Vec<BodyState>,
    /// Scratch: accumulated wrenches.
    pub wrenches: &'a mut Vec<Wrench>,
    /// The resting pairs and their contact forces; `None` in a world
    /// without contacts (no collision code runs then).
    pub contacts: Option<&'a mut RestingContacts>,
    /// The joints, held by constraint forces ([`crate::exact::joints`]);
    /// `None` in a world without joints.
    pub joints: Option<&'a mut ExactJoints>,
}

impl WorldOde<'_> {
    /// Projects `y` back onto the joints' position and velocity manifolds
    /// at time `t` (s) after an accepted step ([`ExactJoints::project`]);
    /// returns whether it changed. Nothing without joints.
    pub(crate) fn project_joints(&mut self, y: &mut [f64], t: f64) -> bool {
        match self.joints.as_deref_mut() {
            Some(joints) => joints.project(self.bodies, self.layout, self.states, y, t),
            None => false,
        }
    }
}

impl OdeSystem for WorldOde<'_> {
    fn dimension(&self) -> usize {
        2 * self.layout.positions
    }

    fn structure(&self) -> Structure {
        Structure::SecondOrder {
            positions: self.layout.positions,
        }
    }

    fn derivative(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.layout.positions;
        self.layout.unpack(y, self.states);
        self.wrenches.clear();
        self.wrenches.resize(self.bodies.len(), Wrench::default());
        let ctx = ForceContext {
            t,
            bodies: self.bodies,
            states: self.states,
        };
        for f in self.forces.iter().filter(|f| f.active) {
            f.force.apply(&ctx, self.wrenches);
        }
        if let Some(contacts) = self.contacts.as_deref_mut() {
            // With joints, the contact forces are solved with them.
            let joints = self.joints.as_deref_mut().map(|j| (j, self.layout));
            contacts.apply(self.bodies, self.states, self.wrenches, joints);
        }
        dydt[..n].copy_from_slice(&y[n..]);
        for ((slot, body), w) in self
            .layout
            .slots
            .iter()
            .zip(self.bodies)
            .zip(self.wrenches.iter())
        {
            let Some(slot) = slot else { continue };
            let o = n + slot.offset;
            dydt[o] = w.force.x / body.mass;
            dydt[o + 1] = w.force.y / body.mass;
            if let (true, Some(inertia)) = (slot.rotates, body.inertia) {
                dydt[o + 2] = w.torque / inertia;
            }
        }
        if let Some(joints) = self.joints.as_deref_mut() {
            joints.accelerate(self.bodies, self.layout, self.states, &mut dydt[n..]);
        }
    }
}
