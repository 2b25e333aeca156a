//! Stage 8 of the soft step, **sleep**, and waking: islands of bodies
//! linked by touching contacts or joints ([`super::islands`]) fall asleep
//! when every body has been at rest for the time to sleep, and wake when
//! something touches one of them (or a joint is steered).

use super::SoftStep;
use super::bodies::SolverBody;
use super::islands;
use crate::body::{BodyId, BodyKind};
use crate::world_core::WorldCore;
use nalgebra::Vector2;

impl SoftStep {
    /// The islands from scratch: every dynamic body, linked by the contacts
    /// touching now and by the joints.
    pub(super) fn rebuild_islands(&mut self) {
        self.islands = islands::Islands::default();
        for (id, sim) in self.sims.iter().enumerate() {
            self.islands.add_body(id, sim.kind == BodyKind::Dynamic);
        }
        for c in &self.contacts.contacts {
            if c.touching && !c.sensor {
                self.islands.link(c.body_a, c.body_b);
            }
        }
        for (a, b) in self.joints.dynamic_pairs(&self.sims) {
            self.islands.link(a, b);
        }
    }

    /// Whether `k` is a kinematic body that moves now.
    fn moving_kinematic(&self, k: BodyId) -> bool {
        let r = &self.bodies[k + 1];
        self.sims[k].kind == BodyKind::Kinematic && (r.v.norm() > 0.0 || r.w != 0.0)
    }

    /// Stage 8: islands whose every body has been at rest for the time to
    /// sleep fall asleep.
    #[inline(never)]
    pub(super) fn sleep(&mut self, core: &mut WorldCore) {
        self.touching_pairs.clear();
        for c in &self.contacts.contacts {
            if c.touching
                && !c.sensor
                && self.sims[c.body_a].kind == BodyKind::Dynamic
                && self.sims[c.body_b].kind == BodyKind::Dynamic
            {
                self.touching_pairs.push((c.body_a, c.body_b));
            }
        }
        // Jointed bodies stay in one island when it splits.
        let joined = self.joints.dynamic_pairs(&self.sims);
        self.touching_pairs.extend(joined);
        // A moving kinematic body keeps the bodies it touches or holds
        // awake.
        for c in &self.contacts.contacts {
            if !c.touching || c.sensor {
                continue;
            }
            for (k, other) in [(c.body_a, c.body_b), (c.body_b, c.body_a)] {
                if self.moving_kinematic(k) {
                    self.sims[other].sleep_time = 0.0;
                }
            }
        }
        for j in 0..self.joints.len() {
            let info = &self.joints.infos[j];
            if info.removed {
                continue;
            }
            if let (Some(a), Some(b)) = (info.body_a, info.body_b) {
                for (k, other) in [(a, b), (b, a)] {
                    if self.moving_kinematic(k) {
                        self.sims[other].sleep_time = 0.0;
                    }
                }
            }
        }
        let time_to_sleep = self.settings.time_to_sleep;
        let sims = &self.sims;
        self.islands.resting(
            |b| sims[b].sleep_time >= time_to_sleep,
            &self.touching_pairs,
            &mut self.resting,
        );
        for k in 0..self.resting.len() {
            let island = self.resting[k];
            self.islands.set_asleep(island, true);
            for &b in self.islands.bodies(island) {
                self.sims[b].asleep = true;
                self.bodies[b + 1] = SolverBody::AT_REST;
                core.states[b].velocity = Vector2::zeros();
                core.states[b].angular_velocity = 0.0;
            }
        }
    }

    /// Wakes the island of `body` if it sleeps.
    pub(super) fn wake_body(&mut self, body: BodyId) {
        if !self.sims[body].asleep {
            return;
        }
        let Some(island) = self.islands.island(body) else {
            self.sims[body].asleep = false;
            return;
        };
        self.islands.set_asleep(island, false);
        for &b in self.islands.bodies(island) {
            self.sims[b].asleep = false;
            self.sims[b].sleep_time = 0.0;
        }
    }

    /// Whether body `id` sleeps now.
    pub(crate) fn is_asleep(&self, id: BodyId) -> bool {
        self.sims[id].asleep
    }
}
