//! The soft step's side of the world seam
//! ([`crate::contact_model::ContactModelStep`]): body changes update its
//! broad phase, solver bodies and sleep state in place; it takes every
//! joint type and every shape (no `check_body` refusal: segments, capsules
//! and rounded polygons collide through `manifold.rs`).

use super::SoftStep;
use crate::body::{Body, BodyId};
use crate::contact_model::{ContactModel, ContactModelStep};
use crate::error::Result;
use crate::events::EventRecord;
use crate::integrators::{Method, Stats};
use crate::soft_step::joints::{JointDef, JointId, JointState};
use crate::world_core::WorldCore;
use nalgebra::Vector2;

impl ContactModelStep for SoftStep {
    fn body_added(&mut self, core: &WorldCore, id: BodyId) {
        SoftStep::body_added(self, core, id);
    }

    fn body_removed(&mut self, core: &WorldCore, id: BodyId) {
        SoftStep::body_removed(self, core, id);
    }

    fn body_changed(&mut self, core: &WorldCore, id: BodyId) {
        SoftStep::body_changed(self, core, id);
    }

    fn pose_changed(&mut self, core: &WorldCore, id: BodyId) {
        SoftStep::pose_changed(self, core, id);
    }

    fn velocity_changed(&mut self, id: BodyId) {
        SoftStep::velocity_changed(self, id);
    }

    fn wake(&mut self, id: BodyId) {
        SoftStep::velocity_changed(self, id);
    }

    fn bullet_changed(&mut self, core: &WorldCore, id: BodyId) {
        SoftStep::bullet_changed(self, core, id);
    }

    fn joints_of(&self, id: BodyId) -> Vec<(JointId, Option<BodyId>)> {
        SoftStep::joints_of(self, id)
    }

    fn is_asleep(&self, id: BodyId) -> bool {
        SoftStep::is_asleep(self, id)
    }

    fn advance(
        &mut self,
        core: &mut WorldCore,
        edges: &[f64],
        found: &mut Vec<EventRecord>,
    ) -> Result<()> {
        SoftStep::advance(self, core, edges, found)
    }

    fn model(&self) -> Option<ContactModel> {
        Some(ContactModel::SoftStep(*self.settings()))
    }

    fn has_contacts(&self, _bodies: &[Body]) -> bool {
        true
    }

    fn stats(&self) -> Stats {
        SoftStep::stats(self)
    }

    fn add_joint(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId> {
        SoftStep::add_joint(self, core, def)
    }

    fn joint_count(&self) -> usize {
        SoftStep::joint_count(self)
    }

    fn joint(&self, core: &WorldCore, id: JointId) -> Result<JointState> {
        self.joint_state(core, id)
    }

    fn remove_joint(&mut self, id: JointId) -> Result<()> {
        SoftStep::remove_joint(self, id)
    }

    fn set_joint_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<()> {
        SoftStep::set_joint_target(self, id, target)
    }

    fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        SoftStep::set_motor_speed(self, id, speed)
    }

    /// The soft step runs at one velocity-then-position update per
    /// substep (semi-implicit Euler).
    fn method(&self) -> Method {
        Method::SemiImplicitEuler
    }
}
