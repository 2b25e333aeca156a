//! Read-only island membership of the soft step, for a program that shows
//! or inspects how the bodies are grouped for sleeping
//! ([`World::islands`], [`World::island_of`]).
//!
//! An island is a set of dynamic bodies linked by touching contacts or
//! joints (`soft_step/islands.rs`): it falls asleep as a whole when every
//! one of its bodies has been at rest for the time to sleep. Static and
//! kinematic bodies belong to no island. The engine keeps islands as its
//! sleep needs them: two bodies that begin touching merge their islands at
//! once, but an island whose contacts stopped touching is split into its
//! connected parts only when it is at rest and about to sleep, so an
//! awake island may still hold bodies that no longer touch. A sleeping
//! island is always connected.

use super::World;
use crate::body::BodyId;
use crate::error::{EngineError, Result};
use crate::soft_step::SoftStep;

/// An island's id: its slot in the engine's island table. Stable while the
/// island lives; the slot of an island merged into another is reused by a
/// later one, so an id names an island only between two steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct IslandId(pub usize);

/// One island as the engine holds it after the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Island<'a> {
    /// The island.
    pub id: IslandId,
    /// Its bodies (dynamic ones only), in no particular order.
    pub bodies: &'a [BodyId],
    /// Whether it sleeps (its bodies are not integrated, collided or
    /// solved until something wakes it).
    pub asleep: bool,
}

impl World {
    /// Every island in use (soft-step contact model with sleeping on,
    /// [`crate::SoftStepSettings::sleeping`]). Refused with
    /// [`EngineError::Unsupported`] under the exact model and with
    /// sleeping off, where the engine keeps no islands.
    pub fn islands(&self) -> Result<impl Iterator<Item = Island<'_>> + '_> {
        Ok(self
            .kept_islands()?
            .islands()
            .in_use()
            .map(|(i, bodies, asleep)| Island {
                id: IslandId(i),
                bodies,
                asleep,
            }))
    }

    /// The island of body `id`: `None` for a static, kinematic or removed
    /// body. Refused as [`World::islands`] is, and for an unknown body.
    pub fn island_of(&self, id: BodyId) -> Result<Option<IslandId>> {
        self.check_body(id)?;
        Ok(self.kept_islands()?.islands().island(id).map(IslandId))
    }

    /// The soft step, if it keeps islands (sleeping on).
    fn kept_islands(&self) -> Result<&SoftStep> {
        let soft = self.soft_step("island membership")?;
        if soft.settings().sleeping {
            Ok(soft)
        } else {
            Err(EngineError::Unsupported {
                what: "island membership".into(),
                reason: "the soft step keeps islands only while sleeping is on \
                         (SoftStepSettings::sleeping)",
            })
        }
    }
}
