//! A validated 2D rigid-body physics engine, after the 2006 design report
//! by J. Schmaltz, « Développement d'un moteur physique permettant la
//! simulation du comportement dynamique des corps rigides » (ÉTS), cited as
//! "seed §N" and "seed eq. N" (an English guide to it: `docs/seed.md`).
//!
//! Start with the [`prelude`]. A box thrown up from the ground with the
//! soft-step contact model (the one for piles of bodies): the program
//! kicks it ([`World::apply_linear_impulse`]), reads the hit it makes when
//! it lands ([`World::step_events`]), then asks where a ray straight down
//! meets it ([`query`]):
//!
//! ```
//! use etalon2d::prelude::*;
//! let mut world = World::with_model(
//!     Method::SemiImplicitEuler,
//!     ContactModel::SoftStep(SoftStepSettings::default()),
//! )?;
//! world.set_gravity(Vector2::new(0.0, -9.81))?;
//! let ground = world.add_body(BodyDef::fixed("ground", Vector2::new(0.0, -0.5), Some(Shape::rectangle(20.0, 1.0)?)))?;
//! let boxed = world.add_body(
//!     BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0)?).with_position(Vector2::new(0.0, 0.5)),
//! )?;
//! // A kick of 5 N·s up through its centre: 5 m/s up, back down at about
//! // 5 m/s (the hit threshold is 1 m/s).
//! world.apply_linear_impulse(boxed, Vector2::new(0.0, 5.0), Vector2::new(0.0, 0.5))?;
//! let mut landing = None;
//! for _ in 0..180 {
//!     world.step(1.0 / 60.0)?; // 3 s in steps of 1/60 s
//!     for hit in &world.step_events()?.hits {
//!         assert!([hit.a.body, hit.b.body].contains(&ground));
//!         landing.get_or_insert(hit.approach_speed);
//!     }
//! }
//! let speed = landing.expect("it lands with a hit event");
//! assert!((speed - 5.0).abs() < 0.5, "{speed} m/s");
//! let y = world.states()[boxed].position.y;
//! assert!((y - 0.5).abs() < 1e-3); // resting on the ground again
//!
//! // A ray cast straight down from 10 m meets the box's top face (y ≈ 1 m).
//! let hit = world
//!     .cast_ray(Vector2::new(0.2, 10.0), Vector2::new(0.0, -1.0), 20.0, QueryFilter::DEFAULT)?
//!     .expect("the ray meets the box");
//! assert_eq!(hit.shape.body, boxed);
//! assert!((hit.point.y - (y + 0.5)).abs() < 1e-9);
//! # Ok::<(), EngineError>(())
//! ```
//!
//! And the seed's mass-spring (case I, `docs/cases.md#spring`) integrated by
//! RK4 at h = 0.2 s, no contacts:
//!
//! ```
//! use etalon2d::prelude::*;
//! let mut world = World::new(Method::Rk4)?;
//! let mass = world.add_body(BodyDef::particle("mass", 20.0, Vector2::new(100.0, 0.0)))?;
//! world.add_force(Spring {
//!     a: Attachment::World(Vector2::zeros()),
//!     b: Attachment::center_of(mass),
//!     stiffness: 50.0,
//!     rest_length: 50.0,
//!     axis: Some(Vector2::x()),
//! })?;
//! let trace = world.run(57.2, 0.2)?;
//! let x = trace.last().unwrap().states[mass].position.x;
//! assert!((x - 10.95756).abs() < 1e-4);
//! # Ok::<(), EngineError>(())
//! ```
//!
//! The parts:
//!
//! - [`World`]: bodies, forces, events and a contact model
//!   ([`ContactModel`]): the **exact** model (seed §7.1 after Baraff,
//!   event-driven, exact to round-off on a few bodies, integrated by any of
//!   the seven [`Method`]s) or the **soft step** ([`soft_step`], Box2D v3's
//!   solver, for thousands of bodies); without contacts, shapes pass
//!   through each other;
//! - [`integrators`]: explicit and semi-implicit Euler, midpoint RK2, RK4,
//!   velocity Verlet, implicit Euler, adaptive Dormand–Prince 5(4), all on
//!   the generic [`OdeSystem`] (seed §4.3);
//! - [`body`], [`shape`]: particles, rigid, static and kinematic bodies;
//!   convex polygons, boxes, circles and compounds, with mass properties
//!   from the geometry;
//! - [`forces`]: gravity, springs, quadratic and angular drag, point forces,
//!   torques, each with an optional time window; the [`Force`] trait;
//! - [`validation`]: the internals the harness validates on their own:
//!   detection (broad phase, separating axes, time of impact) and the exact
//!   model's response (impulses with restitution, resting contact, Coulomb
//!   friction), seed §7, and the event root finder;
//! - [`joints`]: revolute, prismatic, distance, weld, target, wheel and
//!   motor joints under the soft step, and the revolute, prismatic, rigid
//!   distance, weld and wheel joints as constraints of the exact model,
//!   with a wheel's spring and motor joints as force laws
//!   ([`World::add_joint`]).
//! - [`query`]: ray casts, shape casts, overlap, point and distance
//!   queries on a world, through the soft step's broad phase.
//!
//! Between steps a program drives the world: [`World::set_pose`],
//! [`World::set_velocity`], [`World::apply_force`],
//! [`World::apply_linear_impulse`], [`World::set_target_pose`],
//! [`World::set_body_kind`], [`World::set_enabled`],
//! [`World::set_gravity_scale`], [`World::set_damping`],
//! [`World::set_fixed_rotation`], [`World::set_mass_properties`],
//! [`World::set_user_value`], [`World::remove_force`]; each refuses bad
//! input with an [`EngineError`] and leaves the world as it was. A
//! [`World`] is `Clone` (a snapshot in memory) and, with the default
//! `serde` feature, serializable: restored, it steps to the same bits
//! ([`World::state_hash`], [`World::check_serializable`]).

#![warn(missing_docs)]

// The crate README's example, compiled and run as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

pub mod body;
mod contact_model;
pub mod error;
pub mod events;
mod exact;
pub mod filter;
pub mod forces;
pub mod integrators;
pub mod material;
pub mod ode;
pub mod prelude;
mod profile;
pub mod query;
pub mod shape;
pub mod soft_step;
pub mod time_grid;
pub mod trace;
mod tunables;
pub mod validation;
mod world;
mod world_core;

// The validation modules under their old paths, for the engine itself.
pub(crate) use validation::{collision, contact, root_finding};

pub use body::{Body, BodyDef, BodyId, BodyKind, BodyState};
pub use contact::{ContactEvent, ContactEventKind, ContactSettings, ToiMethod};
pub use contact_model::ContactModel;
pub use error::{EngineError, Result};
pub use events::{Crossing, EventRecord, EventSpec, Quantity};
pub use filter::{Filter, QueryFilter};
pub use forces::{BuiltinForce, Force, ForceContext, TimeWindow, Wrench};
pub use integrators::{
    Integrator, Method, Solution, Stats, Tolerance, integrate_fixed, integrate_to,
};
pub use material::{MixingRule, ShapeOverrides};
pub use ode::{FnSystem, OdeSystem, Structure};
pub use profile::StepProfile;
pub use query::{RayHit, ShapeCastHit, ShapeDistance, ShapeRef};
pub use shape::{
    Chain, ChainSegment, Circle, Compound, CompoundPart, ConvexCore, ConvexPolygon, RoundedConvex,
    RoundedKind, Shape,
};
pub use soft_step::SoftStepSettings;
pub use soft_step::joints::{
    self as joints, Anchor, Distance, JointDef, JointId, JointKind, JointSpring, JointState,
    JointType, MotorJoint, Prismatic, PrismaticMotor, Revolute, RevoluteMotor, Target, Weld, Wheel,
    WheelMotor,
};
pub use soft_step::{
    ContactData, ContactHooks, ContactPointData, HitEvent, JointEvent, PreSolveContact,
    SensorEvent, ShapeId, StepEvents, TouchEvent,
};
pub use time_grid::{MAX_RUN_STEPS, step_count};
pub use trace::{Sample, Trace};
pub use world::World;
pub use world::islands::{Island, IslandId};
pub use world_core::ForceId;
