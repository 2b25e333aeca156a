//! What the soft step does when a program changes a body between steps
//! ([`crate::World`]'s control calls): a new pose moves the body's
//! proxies; a new kind, mass, shape set (disabling) or locked rotation
//! rebuilds the body's record, proxies, contacts and island. Each wakes
//! what it touches, as Box2D's `b2Body_SetTransform` and `b2Body_SetType`
//! do.

use super::SoftStep;
use super::bodies::{BodySim, solver_body};
use super::geometry::Collider;
use super::shape_data::ShapeData;
use crate::body::{BodyId, BodyKind};
use crate::world_core::WorldCore;
use nalgebra::{Isometry2, Translation2, UnitComplex};

impl SoftStep {
    /// Body `id`'s velocity changed: it wakes (its island with it).
    pub(crate) fn velocity_changed(&mut self, id: BodyId) {
        self.wake_body(id);
    }

    /// Body `id` was moved to the pose in `core.states[id]`: its rotation
    /// and proxies follow; it and the bodies it touched wake. Its contacts
    /// stay and get their manifolds at the new pose at the next collide
    /// stage (or end there, if the boxes parted).
    pub(crate) fn pose_changed(&mut self, core: &WorldCore, id: BodyId) {
        let state = &core.states[id];
        let rotation = UnitComplex::new(state.angle);
        self.sims[id].rotation = rotation;
        let margin = if self.sims[id].kind == BodyKind::Static {
            0.0
        } else {
            self.settings.aabb_margin
        };
        let pose = Isometry2::from_parts(Translation2::from(state.position), rotation);
        for c in self.sims[id].colliders.clone() {
            let collider = &self.colliders[c];
            let aabb = collider
                .shape
                .aabb_at(&collider.pose(&pose))
                .loosened(self.settings.speculative_distance);
            let margin = collider.aabb_margin(margin);
            self.broad.update(c, &aabb, margin);
        }
        self.wake_with_partners(id);
    }

    /// Body `id`'s bullet flag changed: its record takes it (a dynamic
    /// body's; a static or kinematic one's waits in its [`crate::Body`]
    /// until it is made dynamic). Nothing else changes, as with Box2D's
    /// `b2Body_SetBullet`.
    pub(crate) fn bullet_changed(&mut self, core: &WorldCore, id: BodyId) {
        let body = &core.bodies[id];
        self.sims[id].bullet = body.kind == BodyKind::Dynamic && body.bullet;
    }

    /// Body `id`'s [`crate::Body`] in `core` changed (kind, mass, inertia,
    /// shape set or cleared): its record is rebuilt from it, its proxies
    /// go into the tree of its kind, its contacts end (the broad phase
    /// finds its pairs again at the next step) and it gets an island of
    /// its own (a dynamic body) or none. The bodies it touched wake, and
    /// so do the bodies it is jointed to.
    pub(crate) fn body_changed(&mut self, core: &WorldCore, id: BodyId) {
        self.wake_with_partners(id);
        let body = &core.bodies[id];
        let state = &core.states[id];
        let old = self.sims[id].colliders.clone();
        for c in old.clone() {
            self.broad.remove(c);
        }
        self.contacts.destroy_body(id);
        // A body keeps its colliders (its shape never changes); one that
        // had none gets new ones at the end of the list.
        let range = match &body.shape {
            None => old.start..old.start,
            Some(_) if !old.is_empty() => old,
            Some(shape) => {
                let first = self.colliders.len();
                self.colliders.extend(Collider::of(id, shape));
                self.shape_data.extend(ShapeData::of(body, &self.settings));
                for c in first..self.colliders.len() {
                    self.broad.add(c, None, body.kind);
                }
                first..self.colliders.len()
            }
        };
        let sim = BodySim::new(
            body,
            state.angle,
            (&self.colliders[range.clone()], range.clone()),
        );
        let margin = if body.kind == BodyKind::Static {
            0.0
        } else {
            self.settings.aabb_margin
        };
        let pose = Isometry2::from_parts(Translation2::from(state.position), sim.rotation);
        for c in range {
            let collider = &self.colliders[c];
            let aabb = collider
                .shape
                .aabb_at(&collider.pose(&pose))
                .loosened(self.settings.speculative_distance);
            let fat = aabb.loosened(collider.aabb_margin(margin));
            self.broad.replace(c, Some(fat), body.kind);
        }
        self.sims[id] = sim;
        self.bodies[id + 1] = solver_body(state, body.kind);
        self.islands.reset_body(id, body.kind == BodyKind::Dynamic);
        if self.settings.sleeping {
            // Its joints link it again (the contacts do when they touch).
            let pairs: Vec<_> = self
                .joints
                .dynamic_pairs(&self.sims)
                .filter(|&(a, b)| a == id || b == id)
                .collect();
            for (a, b) in pairs {
                self.islands.link(a, b);
            }
        }
        self.wake_with_partners(id);
    }

    /// The joints of body `id` that are not removed, with the other body
    /// of each (`None`: the world).
    pub(crate) fn joints_of(&self, id: BodyId) -> Vec<(crate::JointId, Option<BodyId>)> {
        self.joints
            .infos
            .iter()
            .enumerate()
            .filter(|(_, info)| !info.removed)
            .filter_map(|(j, info)| {
                if info.body_a == Some(id) {
                    Some((j, info.body_b))
                } else if info.body_b == Some(id) {
                    Some((j, info.body_a))
                } else {
                    None
                }
            })
            .collect()
    }

    /// Whether the per-body tables are those of a world of `n` bodies
    /// (read back from bytes).
    #[cfg(feature = "serde")]
    pub(crate) fn consistent_with(&self, n: usize) -> bool {
        self.sims.len() == n && self.bodies.len() == n + 1
    }

    /// Wakes body `id` and every body it touches or is jointed to.
    fn wake_with_partners(&mut self, id: BodyId) {
        self.wake_body(id);
        for k in 0..self.contacts.contacts.len() {
            let c = &self.contacts.contacts[k];
            if c.touching && (c.body_a == id || c.body_b == id) {
                let other = if c.body_a == id { c.body_b } else { c.body_a };
                self.wake_body(other);
            }
        }
        for j in 0..self.joints.len() {
            let info = &self.joints.infos[j];
            if info.removed {
                continue;
            }
            let (a, b) = (info.body_a, info.body_b);
            if a == Some(id) || b == Some(id) {
                for other in [a, b].into_iter().flatten() {
                    self.wake_body(other);
                }
            }
        }
    }
}
