//! The seam between a [`crate::World`] and the way it handles contacts: a
//! world runs one contact model, chosen per world (a scene's
//! `[contact] model`), and the model owns everything that differs between
//! them: how bodies are integrated, how contacts are found and answered.
//!
//! - [`ContactModel::Exact`] (seed §7.1 after Baraff): the world is one ODE
//!   integrated by the chosen [`crate::Method`]; impacts are located inside
//!   the step by time of impact and answered by the impulses of seed
//!   eq. 7.15, resting contacts by contact forces inside the right-hand
//!   side. Exact to round-off on the validation cases; meant for a few
//!   bodies. Module `exact_model`. A world without contacts runs this
//!   model's integration with collisions off.
//! - [`ContactModel::SoftStep`] (seed §7.1 after Mirtich and Canny's series
//!   of impulses; Box2D v3's soft step): persistent contact manifolds with
//!   warm starting, substeps of soft constraints, relax and restitution
//!   passes, speculative contacts. Meant for thousands of bodies (seed
//!   §2.2). Module [`crate::soft_step`].
//!
//! A third model is a module plus a variant here and in `Dynamics`.

use crate::body::{Body, BodyId};
use crate::contact::{ContactEvent, ContactSettings};
use crate::error::Result;
use crate::events::EventRecord;
use crate::exact::ExactModel;
use crate::integrators::{Method, Stats};
use crate::soft_step::joints::{JointDef, JointId, JointState};
use crate::soft_step::{SoftStep, SoftStepSettings};
use crate::world_core::WorldCore;
use nalgebra::Vector2;

/// How a world handles contacts, with the model's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactModel {
    /// The exact, event-driven model (seed §7.1 after Baraff).
    Exact(ContactSettings),
    /// The soft-step solver (Box2D v3's soft step) for many bodies.
    SoftStep(SoftStepSettings),
}

impl ContactModel {
    /// The model's id in scene files and reports: `"exact"` or
    /// `"soft_step"`.
    pub fn id(&self) -> &'static str {
        match self {
            ContactModel::Exact(_) => "exact",
            ContactModel::SoftStep(_) => "soft_step",
        }
    }

    /// Checks every setting's domain.
    pub fn validate(&self) -> Result<()> {
        match self {
            ContactModel::Exact(s) => s.validate(),
            ContactModel::SoftStep(s) => s.validate(),
        }
    }
}

/// Why a world refuses to leave the soft step with joints.
pub(crate) const JOINTS_NEED_SOFT_STEP: &str = "a world's joints stay with the contact model \
     they were added to (the soft step's are not carried over to the exact model): build the \
     world with the model first (in a scene file, [contact] model = \"exact\" or \"soft_step\")";

/// The model a world runs, with its state.
#[derive(Debug, Clone)]
pub(crate) enum Dynamics {
    /// The exact model; also a world without contacts.
    Exact(Box<ExactModel>),
    /// The soft step.
    SoftStep(Box<SoftStep>),
}

impl Dynamics {
    /// Refuses a body the model cannot simulate.
    pub(crate) fn check_body(&self, body: &Body) -> Result<()> {
        match self {
            Dynamics::Exact(_) => ExactModel::check_body(body),
            Dynamics::SoftStep(_) => Ok(()),
        }
    }

    /// A body was added to `core` (it is the last one).
    pub(crate) fn body_added(&mut self, core: &WorldCore, id: BodyId) {
        match self {
            Dynamics::Exact(m) => m.bodies_changed(),
            Dynamics::SoftStep(s) => s.body_added(core, id),
        }
    }

    /// Body `id` of `core` was removed (made inert).
    pub(crate) fn body_removed(&mut self, core: &WorldCore, id: BodyId) {
        match self {
            Dynamics::Exact(m) => {
                m.joints.body_removed(id);
                m.bodies_changed();
            }
            Dynamics::SoftStep(s) => s.body_removed(core, id),
        }
    }

    /// Body `id`'s [`Body`] in `core` changed (kind, mass, inertia,
    /// shape set or cleared).
    pub(crate) fn body_changed(&mut self, core: &WorldCore, id: BodyId) {
        match self {
            Dynamics::Exact(m) => m.bodies_changed(),
            Dynamics::SoftStep(s) => s.body_changed(core, id),
        }
    }

    /// Body `id` was moved to the pose in `core.states[id]`.
    pub(crate) fn pose_changed(&mut self, core: &WorldCore, id: BodyId) {
        match self {
            Dynamics::Exact(m) => m.bodies_changed(),
            Dynamics::SoftStep(s) => s.pose_changed(core, id),
        }
    }

    /// Body `id`'s velocity was set or kicked: the exact model drops its
    /// resting pairs (they are chosen again at the next step from the new
    /// velocities), the soft step wakes the body.
    pub(crate) fn velocity_changed(&mut self, id: BodyId) {
        match self {
            Dynamics::Exact(m) => m.bodies_changed(),
            Dynamics::SoftStep(s) => s.velocity_changed(id),
        }
    }

    /// Wakes body `id` (the soft step; nothing sleeps under the exact
    /// model).
    pub(crate) fn wake(&mut self, id: BodyId) {
        if let Dynamics::SoftStep(s) = self {
            s.velocity_changed(id);
        }
    }

    /// The joints of body `id` that are not removed, with the other body
    /// of each (`None`: the world).
    pub(crate) fn joints_of(&self, id: BodyId) -> Vec<(JointId, Option<BodyId>)> {
        match self {
            Dynamics::Exact(_) => Vec::new(),
            Dynamics::SoftStep(s) => s.joints_of(id),
        }
    }

    /// Whether body `id` sleeps (soft step with sleeping on).
    pub(crate) fn is_asleep(&self, id: BodyId) -> bool {
        match self {
            Dynamics::Exact(_) => false,
            Dynamics::SoftStep(s) => s.is_asleep(id),
        }
    }

    /// Advances `core` over the force segments ending at `edges`.
    pub(crate) fn advance(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        match self {
            Dynamics::Exact(m) => m.advance(core, edges, found),
            Dynamics::SoftStep(s) => s.advance(core, edges, found),
        }
    }

    /// The model and its settings; `None` for a world without contacts.
    pub(crate) fn model(&self) -> Option<ContactModel> {
        match self {
            Dynamics::Exact(m) => m
                .contacts_enabled()
                .then_some(ContactModel::Exact(m.settings)),
            Dynamics::SoftStep(s) => Some(ContactModel::SoftStep(*s.settings())),
        }
    }

    pub(crate) fn has_contacts(&self, bodies: &[Body]) -> bool {
        match self {
            Dynamics::Exact(m) => m.has_contacts(bodies),
            Dynamics::SoftStep(_) => true,
        }
    }

    pub(crate) fn contact_events(&self) -> Vec<ContactEvent> {
        match self {
            Dynamics::Exact(m) => m.contact_events(),
            Dynamics::SoftStep(_) => Vec::new(),
        }
    }

    pub(crate) fn stats(&self) -> Stats {
        match self {
            Dynamics::Exact(m) => m.stats(),
            Dynamics::SoftStep(s) => s.stats(),
        }
    }

    /// Adds a joint: the soft step takes every type; the exact model the
    /// holonomic ones it solves ([`crate::exact_joints`]), and refuses the
    /// rest with a typed error naming the joint.
    pub(crate) fn add_joint(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId> {
        match self {
            Dynamics::Exact(m) => m.joints.add(core, def),
            Dynamics::SoftStep(s) => s.add_joint(core, def),
        }
    }

    /// How many joints the world holds (removed ones included).
    pub(crate) fn joint_count(&self) -> usize {
        match self {
            Dynamics::Exact(m) => m.joints.set.len(),
            Dynamics::SoftStep(s) => s.joint_count(),
        }
    }

    pub(crate) fn joint(&self, core: &WorldCore, id: JointId) -> Result<JointState> {
        match self {
            Dynamics::Exact(m) => m.joints.state(id, &core.states),
            Dynamics::SoftStep(s) => s.joint_state(core, id),
        }
    }

    pub(crate) fn remove_joint(&mut self, id: JointId) -> Result<()> {
        match self {
            Dynamics::Exact(m) => m.joints.remove(id),
            Dynamics::SoftStep(s) => s.remove_joint(id),
        }
    }

    /// The exact model holds no target joint: its refusal names the joint.
    pub(crate) fn set_joint_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<()> {
        match self {
            Dynamics::Exact(m) => {
                m.joints.set.check(id)?;
                m.joints.set.set_target(id, target).map(|_| ())
            }
            Dynamics::SoftStep(s) => s.set_joint_target(id, target),
        }
    }

    /// The exact model holds no motor: its refusal names the joint.
    pub(crate) fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        match self {
            Dynamics::Exact(m) => {
                m.joints.set.check(id)?;
                m.joints.set.set_motor_speed(id, speed)
            }
            Dynamics::SoftStep(s) => s.set_motor_speed(id, speed),
        }
    }

    /// The largest constraint error the exact model's projection removed
    /// from its joints (m or rad); `None` under the soft step.
    pub(crate) fn joint_drift(&self) -> Option<f64> {
        match self {
            Dynamics::Exact(m) => Some(m.joints.largest_drift()),
            Dynamics::SoftStep(_) => None,
        }
    }

    pub(crate) fn method(&self) -> Method {
        match self {
            Dynamics::Exact(m) => m.method(),
            Dynamics::SoftStep(_) => Method::SemiImplicitEuler,
        }
    }
}
