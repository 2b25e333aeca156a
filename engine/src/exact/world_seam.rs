//! The exact model's side of the world seam
//! ([`crate::contact_model::ContactModelStep`]): any change to the bodies
//! rebuilds the layout and the pipeline at the next step; the joints are
//! the holonomic ones of [`super::joints`].

use super::ExactModel;
use crate::body::{Body, BodyId};
use crate::contact::ContactEvent;
use crate::contact_model::{ContactModel, ContactModelStep};
use crate::error::Result;
use crate::events::EventRecord;
use crate::integrators::{Method, Stats};
use crate::soft_step::joints::{JointDef, JointId, JointState};
use crate::world_core::WorldCore;
use nalgebra::Vector2;

impl ContactModelStep for ExactModel {
    fn check_body(&self, body: &Body) -> Result<()> {
        ExactModel::check_body(body, self.contacts_enabled())
    }

    fn body_added(&mut self, _core: &WorldCore, _id: BodyId) {
        self.bodies_changed();
    }

    fn body_removed(&mut self, _core: &WorldCore, id: BodyId) {
        self.joints.body_removed(id);
        self.bodies_changed();
    }

    fn body_changed(&mut self, _core: &WorldCore, _id: BodyId) {
        self.bodies_changed();
    }

    fn pose_changed(&mut self, _core: &WorldCore, _id: BodyId) {
        self.bodies_changed();
    }

    fn velocity_changed(&mut self, _id: BodyId) {
        self.bodies_changed();
    }

    fn advance(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        ExactModel::advance(self, core, edges, found)
    }

    fn model(&self) -> Option<ContactModel> {
        self.contacts_enabled()
            .then_some(ContactModel::Exact(self.settings))
    }

    fn has_contacts(&self, bodies: &[Body]) -> bool {
        ExactModel::has_contacts(self, bodies)
    }

    fn contact_events(&self) -> Vec<ContactEvent> {
        ExactModel::contact_events(self)
    }

    fn stats(&self) -> Stats {
        ExactModel::stats(self)
    }

    /// The holonomic joints it solves ([`super::joints`]); the rest are
    /// refused with a typed error naming the joint.
    fn add_joint(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId> {
        self.joints.add(core, def)
    }

    fn joint_count(&self) -> usize {
        self.joints.set.len()
    }

    fn joint(&self, core: &WorldCore, id: JointId) -> Result<JointState> {
        self.joints.state(id, &core.states)
    }

    fn remove_joint(&mut self, id: JointId) -> Result<()> {
        self.joints.remove(id)
    }

    /// The exact model holds no target joint: its refusal names the joint.
    fn set_joint_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<()> {
        self.joints.set.check(id)?;
        self.joints.set.set_target(id, target).map(|_| ())
    }

    /// The exact model holds no motor: its refusal names the joint.
    fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        self.joints.set_motor_speed(id, speed)
    }

    fn joint_drift(&self) -> Option<f64> {
        Some(self.joints.largest_drift())
    }

    fn method(&self) -> Method {
        ExactModel::method(self)
    }
}
