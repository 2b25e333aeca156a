//! Saving and restoring a world, and its state hash.
//!
//! **In memory**: [`World`] is `Clone`; the clone holds everything the
//! next step reads, so the clone and the original, stepped alike, give the
//! same bits (rollback, "run on from here with another setting").
//!
//! **As bytes** (cargo feature `serde`, on by default): `World` implements
//! serde's `Serialize` and `Deserialize`, for any serde format that keeps
//! an f64's bits, infinities included (a binary one: CBOR through
//! `ciborium`, bincode, postcard; JSON does not keep infinities). What is
//! written is what the next step reads and nothing else: bodies, states,
//! forces, events, the program's controls, and the soft step's persistent
//! state (per-body records, colliders, the broad phase's trees and move
//! buffer, the contacts with their manifolds and warm-starting impulses,
//! the islands and sleep timers, the joints with their impulses); the
//! per-step scratch (constraint records, colourings) is rebuilt by the
//! next step, and the profile restarts at zero. A world restored from
//! bytes steps to the same bits as the world it was written from (tested
//! on a settling pyramid with joints, `engine/tests/snapshot.rs`, and the
//! harness's `snapshot_restore` case).
//!
//! What cannot be written is refused with a typed error, before anything
//! is written ([`World::check_serializable`]): a force of the program's
//! own type ([`Force::builtin`] returns `None` for it: the engine cannot
//! know its data; clone the world in memory instead, or remove the force,
//! write the world and add it back after restoring), and a world under the
//! exact contact model (its integrator caches and event-driven contact
//! state are not serializable yet; clone it in memory).
//!
//! Bytes from another version of the engine are refused by a format
//! number; bytes that are not a world are refused by the format or by the
//! consistency checks of [`World`]'s `Deserialize` (lengths of the per-body
//! tables). Those checks do not prove that every index inside (a contact's
//! bodies, a proxy's node) is in range: read only bytes this engine
//! wrote, as with any in-memory image.
//!
//! The state hash ([`World::state_hash`], Box2D's `b2World_GetStateHash`)
//! is FNV-1a over the bits of every body's x, y and angle, in id order: two
//! worlds with the same hash are, with overwhelming likelihood, at the same
//! poses to the bit.

use super::Dynamics;
use super::World;
use crate::error::{EngineError, Result};

/// The FNV-1a offset basis and prime (64 bits).
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0100_0000_01b3;

impl World {
    /// A hash of every body's pose bits (x, y, angle, in id order; FNV-1a,
    /// 64 bits), as Box2D's `b2World_GetStateHash`: equal hashes mean, with
    /// overwhelming likelihood, bit-identical poses. For determinism tests
    /// and for checking that a restored world follows the original.
    pub fn state_hash(&self) -> u64 {
        let mut h = FNV_OFFSET;
        for s in &self.core.states {
            for x in [s.position.x, s.position.y, s.angle] {
                for b in x.to_bits().to_le_bytes() {
                    h ^= u64::from(b);
                    h = h.wrapping_mul(FNV_PRIME);
                }
            }
        }
        h
    }

    /// Whether this world can be written as bytes (feature `serde`):
    /// [`EngineError::NotSerializable`] naming the first force of the
    /// program's own type ([`crate::Force::builtin`] returns `None`), or
    /// [`EngineError::Unsupported`] under the exact contact model. Writing
    /// the world calls it first, so a refused world writes nothing.
    pub fn check_serializable(&self) -> Result<()> {
        if let Dynamics::Exact(_) = self.model {
            return Err(EngineError::Unsupported {
                what: "writing a world under the exact contact model as bytes".into(),
                reason: "the exact model's integrator caches and event-driven contact state \
                         are not serializable; clone the world in memory (World: Clone), or \
                         use the soft_step contact model",
            });
        }
        for f in &self.core.forces {
            if f.force.builtin().is_none() {
                return Err(EngineError::NotSerializable {
                    what: format!(
                        "force '{}' is of the program's own type (Force::builtin returns \
                         None); clone the world in memory instead, or remove the force \
                         before writing and add it back after restoring",
                        f.force.name()
                    ),
                });
            }
        }
        Ok(())
    }
}

/// The bytes' format number: bumped whenever what is written changes.
#[cfg(feature = "serde")]
const FORMAT: u32 = 2;

#[cfg(feature = "serde")]
mod bytes {
    use super::*;
    use crate::forces::{BuiltinForce, TimeWindow};
    use crate::soft_step::SoftStep;
    use crate::world_core::{ForceEntry, ForceId, WorldCore};
    use serde::de::Error as _;
    use serde::ser::Error as _;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// A force as written: the engine's own forces only.
    #[derive(Serialize, Deserialize)]
    struct ForceData {
        force: BuiltinForce,
        window: TimeWindow,
        world_gravity: bool,
        id: ForceId,
    }

    /// The forces of a world core, written as [`ForceData`].
    pub(crate) fn serialize_forces<S: Serializer>(
        forces: &[ForceEntry],
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        let data = forces
            .iter()
            .map(|f| {
                let force = f.force.builtin().ok_or_else(|| {
                    S::Error::custom(format!(
                        "force '{}' is of the program's own type and cannot be serialized",
                        f.force.name()
                    ))
                })?;
                Ok(ForceData {
                    force,
                    window: f.window,
                    world_gravity: f.world_gravity,
                    id: f.id,
                })
            })
            .collect::<std::result::Result<Vec<_>, S::Error>>()?;
        data.serialize(serializer)
    }

    pub(crate) fn deserialize_forces<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Vec<ForceEntry>, D::Error> {
        let data = Vec::<ForceData>::deserialize(deserializer)?;
        Ok(data
            .into_iter()
            .map(|f| ForceEntry {
                force: f.force.into_force(),
                window: f.window,
                world_gravity: f.world_gravity,
                id: f.id,
            })
            .collect())
    }

    #[derive(Serialize)]
    struct WorldOut<'a> {
        format: u32,
        core: &'a WorldCore,
        soft_step: &'a SoftStep,
    }

    #[derive(Deserialize)]
    struct WorldIn {
        format: u32,
        core: WorldCore,
        soft_step: SoftStep,
    }

    impl Serialize for World {
        /// Writes the world (see the module docs); refuses what
        /// [`World::check_serializable`] refuses, with its message.
        fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
            self.check_serializable().map_err(S::Error::custom)?;
            let Dynamics::SoftStep(soft_step) = &self.model else {
                unreachable!("checked above: the soft step");
            };
            WorldOut {
                format: FORMAT,
                core: &self.core,
                soft_step,
            }
            .serialize(serializer)
        }
    }

    impl<'de> Deserialize<'de> for World {
        /// Reads a world written by [`World`]'s `Serialize` of this
        /// version of the engine; refuses another format number and
        /// per-body tables of different lengths.
        fn deserialize<D: Deserializer<'de>>(
            deserializer: D,
        ) -> std::result::Result<Self, D::Error> {
            let data = WorldIn::deserialize(deserializer)?;
            if data.format != FORMAT {
                return Err(D::Error::custom(format!(
                    "world bytes of format {} (this engine reads format {FORMAT})",
                    data.format
                )));
            }
            let core = data.core;
            let n = core.bodies.len();
            let lengths = [core.states.len(), core.removed.len(), core.controls.len()];
            if lengths.iter().any(|&l| l != n) || !data.soft_step.consistent_with(n) {
                return Err(D::Error::custom(format!(
                    "world bytes with {n} bodies but per-body tables of other lengths"
                )));
            }
            Ok(World {
                core,
                model: Dynamics::SoftStep(Box::new(data.soft_step)),
                scratch_edges: Vec::new(),
            })
        }
    }
}

#[cfg(feature = "serde")]
pub(crate) use bytes::{deserialize_forces, serialize_forces};
