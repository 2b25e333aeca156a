//! What adding, removing and steering a joint does to the rest of the soft
//! step ([`super::joints`] holds the joints themselves): a joint that keeps
//! its bodies from colliding ends their contacts, and its removal lets the
//! broad phase find them again; jointed dynamic bodies share an island
//! (they sleep and wake together); steering a joint wakes its bodies.

use super::SoftStep;
use super::joints::{JointDef, JointId, JointState};
use crate::body::{BodyId, BodyKind};
use crate::error::Result;
use crate::world_core::WorldCore;
use nalgebra::Vector2;

impl SoftStep {
    /// Validates `def` against the world and adds it.
    pub(crate) fn add_joint(&mut self, core: &WorldCore, def: &JointDef) -> Result<JointId> {
        let id = self.joints.add(core, def)?;
        let bodies = [def.body_a, def.body_b];
        if let [Some(a), Some(b)] = bodies {
            if !def.collide_connected {
                self.end_contacts_between(a, b);
            }
            if self.settings.sleeping && self.both_dynamic(a, b) {
                self.islands.link(a, b);
            }
        }
        for body in bodies.into_iter().flatten() {
            self.wake_body(body);
        }
        Ok(id)
    }

    fn both_dynamic(&self, a: BodyId, b: BodyId) -> bool {
        self.sims[a].kind == BodyKind::Dynamic && self.sims[b].kind == BodyKind::Dynamic
    }

    /// Destroys the contacts between bodies `a` and `b` (a joint now keeps
    /// them apart).
    fn end_contacts_between(&mut self, a: BodyId, b: BodyId) {
        let mut i = 0;
        while i < self.contacts.contacts.len() {
            let c = &self.contacts.contacts[i];
            if (c.body_a, c.body_b) == (a, b) || (c.body_a, c.body_b) == (b, a) {
                if c.touching {
                    let sensor = c.sensor;
                    self.contact_ended(i);
                    if self.settings.sleeping && !sensor {
                        self.islands.unlink(a);
                    }
                }
                self.contacts.destroy(i);
            } else {
                i += 1;
            }
        }
    }

    /// Removes joint `id`; removing it again does nothing.
    pub(crate) fn remove_joint(&mut self, id: JointId) -> Result<()> {
        self.joints.check(id)?;
        let (a, b, collide) = {
            let info = &self.joints.infos[id];
            (info.body_a, info.body_b, info.collide_connected)
        };
        if !self.joints.remove(id) {
            return Ok(());
        }
        if let (Some(a), Some(b)) = (a, b) {
            if self.settings.sleeping && self.both_dynamic(a, b) {
                // The island may have split: checked when it wants to sleep.
                self.islands.unlink(a);
            }
            if !collide {
                // Their pair was filtered out of the broad phase: let it
                // look again.
                for body in [a, b] {
                    for c in self.sims[body].colliders.clone() {
                        self.broad.refresh(c);
                    }
                }
            }
        }
        for body in [a, b].into_iter().flatten() {
            self.wake_body(body);
        }
        Ok(())
    }

    /// Removes every joint of `body` (being removed).
    pub(super) fn remove_joints_of(&mut self, body: BodyId) {
        while let Some(j) = self.joints.first_of_body(body) {
            // Cannot fail: the id comes from the set.
            let _ = self.remove_joint(j);
        }
    }

    /// Joint `id` now.
    pub(crate) fn joint_state(&self, core: &WorldCore, id: JointId) -> Result<JointState> {
        self.joints.check(id)?;
        Ok(self.joints.state(id, &core.states))
    }

    /// How many joints were added (removed ones included).
    pub(crate) fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// Moves target joint `id`'s target (m) and wakes its body.
    pub(crate) fn set_joint_target(&mut self, id: JointId, target: Vector2<f64>) -> Result<()> {
        self.joints.check(id)?;
        let body = self.joints.set_target(id, target)?;
        self.wake_body(body);
        Ok(())
    }

    /// Sets joint `id`'s motor speed and wakes its bodies.
    pub(crate) fn set_motor_speed(&mut self, id: JointId, speed: f64) -> Result<()> {
        self.joints.check(id)?;
        self.joints.set_motor_speed(id, speed)?;
        let info = &self.joints.infos[id];
        let bodies = [info.body_a, info.body_b];
        for body in bodies.into_iter().flatten() {
            self.wake_body(body);
        }
        Ok(())
    }
}
