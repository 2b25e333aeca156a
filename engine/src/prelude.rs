//! Everything a program needs to build and step a world, in one import:
//!
//! ```
//! use etalon2d::prelude::*;
//! let mut world = World::with_model(
//!     Method::SemiImplicitEuler,
//!     ContactModel::SoftStep(SoftStepSettings::default()),
//! )?;
//! world.set_gravity(Vector2::new(0.0, -9.81))?;
//! # Ok::<(), EngineError>(())
//! ```
//!
//! It re-exports the nalgebra types the API takes (`Vector2`, `Isometry2`),
//! so a program does not need its own `nalgebra` dependency.

pub use crate::body::{BodyDef, BodyId, BodyKind, BodyState};
pub use crate::contact::{ContactSettings, ToiMethod};
pub use crate::contact_model::ContactModel;
pub use crate::error::{EngineError, Result};
pub use crate::events::EventSpec;
pub use crate::filter::{Filter, QueryFilter};
pub use crate::forces::{
    AngularDrag, Attachment, Force, Gravity, PointForce, QuadraticDrag, Spring, TimeWindow, Torque,
};
pub use crate::integrators::Method;
pub use crate::material::{MixingRule, ShapeOverrides};
pub use crate::query::{RayHit, ShapeCastHit, ShapeDistance, ShapeRef};
pub use crate::shape::{Chain, Circle, Compound, CompoundPart, ConvexPolygon, Shape};
pub use crate::soft_step::SoftStepSettings;
pub use crate::soft_step::joints::{
    Distance, JointDef, JointId, JointSpring, MotorJoint, Prismatic, PrismaticMotor, Revolute,
    RevoluteMotor, Target, Weld, Wheel, WheelMotor,
};
pub use crate::soft_step::{
    ContactData, ContactHooks, HitEvent, JointEvent, PreSolveContact, SensorEvent, ShapeId,
    StepEvents, TouchEvent,
};
pub use crate::trace::{Sample, Trace};
pub use crate::world::World;
pub use crate::world_core::ForceId;
pub use nalgebra::{Isometry2, Vector2};
