//! Force generators (the seed's `IGFunction`, §6.2): gravity, springs,
//! quadratic drag, angular drag, a force at a body point, a pure torque, and
//! the [`Force`] trait for user-defined ones.
//!
//! A force reads the state of every body through a [`ForceContext`] and adds
//! a [`Wrench`] (force and torque about the centre of mass) to the bodies it
//! acts on. A force that derives from a potential returns its potential
//! energy, so the world can report a total energy.

mod angular_drag;
mod applied;
mod gravity;
mod quadratic_drag;
mod spring;
mod time_window;

pub use angular_drag::AngularDrag;
pub use applied::{PointForce, Torque};
pub use gravity::Gravity;
pub use quadratic_drag::QuadraticDrag;
pub use spring::{Attachment, Spring};
pub use time_window::TimeWindow;

use crate::body::{Body, BodyId, BodyState};
use nalgebra::Vector2;

/// A force (N) and a torque about the centre of mass (N·m) on one body.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Wrench {
    /// Force through the centre of mass (N).
    pub force: Vector2<f64>,
    /// Torque about the centre of mass (N·m), counter-clockwise positive.
    pub torque: f64,
}

/// What a force may read when it is evaluated.
#[derive(Debug, Clone, Copy)]
pub struct ForceContext<'a> {
    /// Time (s).
    pub t: f64,
    /// The bodies (mass, inertia, kind), indexed by [`BodyId`].
    pub bodies: &'a [Body],
    /// Their current states, same indexing.
    pub states: &'a [BodyState],
}

/// A copy of one of the engine's own forces: what a world written as
/// bytes stores for each force ([`Force::builtin`]).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum BuiltinForce {
    /// [`Gravity`].
    Gravity(Gravity),
    /// [`Spring`].
    Spring(Spring),
    /// [`QuadraticDrag`].
    QuadraticDrag(QuadraticDrag),
    /// [`AngularDrag`].
    AngularDrag(AngularDrag),
    /// [`PointForce`].
    PointForce(PointForce),
    /// [`Torque`].
    Torque(Torque),
}

impl BuiltinForce {
    /// The force itself, to put back into a world.
    pub fn into_force(self) -> std::sync::Arc<dyn Force> {
        match self {
            BuiltinForce::Gravity(f) => std::sync::Arc::new(f),
            BuiltinForce::Spring(f) => std::sync::Arc::new(f),
            BuiltinForce::QuadraticDrag(f) => std::sync::Arc::new(f),
            BuiltinForce::AngularDrag(f) => std::sync::Arc::new(f),
            BuiltinForce::PointForce(f) => std::sync::Arc::new(f),
            BuiltinForce::Torque(f) => std::sync::Arc::new(f),
        }
    }
}

/// A force generator. Implement it to add your own forces to a world.
pub trait Force: std::fmt::Debug + Send + Sync {
    /// A short name for errors and reports.
    fn name(&self) -> &str;

    /// The bodies this force reads or acts on, for validation when it is
    /// added to a world (an empty list means "every dynamic body").
    fn bodies(&self) -> Vec<BodyId>;

    /// Checks the force's own parameters (finite, in their domain); called
    /// when the force is added to a world.
    fn validate(&self) -> crate::error::Result<()> {
        Ok(())
    }

    /// Adds this force's wrench on each body to `wrenches[body]`.
    fn apply(&self, ctx: &ForceContext<'_>, wrenches: &mut [Wrench]);

    /// The acceleration (m/s²) this force gives every dynamic body alike,
    /// whatever its state, when it is such a uniform field (gravity); `None`
    /// otherwise. A solver may apply it without evaluating [`Force::apply`].
    fn uniform_acceleration(&self) -> Option<Vector2<f64>> {
        None
    }

    /// A copy of this force when it is one of the engine's own, `None`
    /// (the default) for a force of the program's own type: a world
    /// holding such a force can be cloned ([`crate::World`] is `Clone`)
    /// but not written as bytes (serializing it fails with
    /// [`crate::EngineError::NotSerializable`] naming the force; see
    /// [`crate::World::check_serializable`]).
    fn builtin(&self) -> Option<BuiltinForce> {
        None
    }

    /// The potential energy (J) when the force derives from one.
    fn potential_energy(&self, _ctx: &ForceContext<'_>) -> Option<f64> {
        None
    }
}
