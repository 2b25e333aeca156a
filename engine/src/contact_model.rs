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
//! What a world asks of its model is the trait [`ContactModelStep`]: each
//! model implements it beside its own code (`exact/world_seam.rs`,
//! `soft_step/world_seam.rs`), and the world's `Dynamics`
//! (`world/dynamics.rs`) turns the model a world holds into that trait
//! object in one place, so
//! the world's calls (`self.model.advance(..)`, `self.model.body_added(..)`)
//! read the same for every model. A third model is a module implementing
//! the trait, plus a variant here, in `Dynamics` and in that one match.

use crate::body::{Body, BodyId};
use crate::contact::{ContactEvent, ContactSettings};
use crate::error::Result;
use crate::events::EventRecord;
use crate::integrators::{Method, Stats};
use crate::soft_step::SoftStepSettings;
use crate::soft_step::joints::{JointDef, JointId, JointState};
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

/// What a world asks of its contact model: the body and joint changes it
/// must hear of, the step itself, and what it reports. Implemented by
/// the exact model (`exact/world_seam.rs`) and the soft step
/// (`soft_step/world_seam.rs`); the defaults are what a model without
/// sleeping, joints of its own or contact events answers.
pub(crate) trait ContactModelStep {
    /// Refuses a body the model cannot simulate.
    fn check_body(&self, _body: &Body) -> Result<()> {
        Ok(())
    }

    /// A body was added to `core` (it is the last one).
    fn body_added(&mut self, core: &WorldCore, id: BodyId);

    /// Body `id` of `core` was removed (made inert).
    fn body_removed(&mut self, core: &WorldCore, id: BodyId);

    /// Body `id`'s [`Body`] in `core` changed (kind, mass, inertia,
    /// shape set or cleared).
    fn body_changed(&mut self, core: &WorldCore, id: BodyId);

    /// Body `id` was moved to the pose in `core.states[id]`.
    fn pose_changed(&mut self, core: &WorldCore, id: BodyId);

    /// Body `id`'s velocity was set or kicked: the exact model drops its
    /// resting pairs (they are chosen again at the next step from the new
    /// velocities), the soft step wakes the body.
    fn velocity_changed(&mut self, id: BodyId);

    /// Wakes body `id` (nothing sleeps under a model without sleeping).
    fn wake(&mut self, _id: BodyId) {}

    /// Body `id`'s bullet flag ([`Body::bullet`]) changed. The exact model
    /// ignores it (its swept contact search covers every pair); the soft
    /// step copies it into its body record.
    fn bullet_changed(&mut self, _core: &WorldCore, _id: BodyId) {}

    /// The joints of body `id` that are not removed, with the other body
    /// of each (`None`: the world).
    fn joints_of(&self, _id: BodyId) -> Vec<(JointId, Option<BodyId>)> {
        Vec::new()
    }

    /// Whether body `id` sleeps.
    fn is_asleep(&self, _id: BodyId) -> bool {
        false
    }

    /// Advances `core` over the force segments ending at `edges`,
    /// recording located events in `found`.
    fn advance(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        found: &mut Vec<EventRecord>,
    ) -> Result<()>;

    /// The model and its settings; `None` for a world without contacts.
    fn model(&self) -> Option<ContactModel>;

    /// Whether collision code runs for these bodies.
    fn has_contacts(&self, bodies: &[Body]) -> bool;

    /// The contact events so far, in time order (the exact model's).
    fn contact_events(&self) -> Vec<ContactEvent> {
        Vec::new()
    }

    /// Work done by the integrator.
    fn stats(&self) -> Stats;

    /// Adds a joint, or refuses a type the model does not solve with a
    /// typed error naming the joint.
    fn add_joint(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId>;

    /// How many joints the world holds (removed ones included).
    fn joint_count(&self) -> usize;

    /// Joint `id`'s state.
    fn joint(&self, core: &WorldCore, id: JointId) -> Result<JointState>;

    /// Removes joint `id`.
    fn remove_joint(&mut self, id: JointId) -> Result<()>;

    /// Moves a target joint's target (m, world frame).
    fn set_joint_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<()>;

    /// Sets a joint motor's speed (rad/s or m/s).
    fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()>;

    /// The largest constraint error a projection removed from the joints
    /// (m or rad); `None` for a model that does not project.
    fn joint_drift(&self) -> Option<f64> {
        None
    }

    /// The integration method.
    fn method(&self) -> Method;
}
