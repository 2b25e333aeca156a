//! A validated 2D rigid-body physics engine, after the 2006 design report
//! in `shared/seed/` (cited as "seed §N" and "seed eq. N").
//!
//! - [`integrators`]: explicit and semi-implicit Euler, midpoint RK2, RK4,
//!   velocity Verlet, implicit Euler, adaptive Dormand–Prince 5(4), all on
//!   the generic [`OdeSystem`] (seed §4.3);
//! - [`body`], [`shape`]: particles, rigid and static bodies, convex
//!   polygons, boxes and circles with mass properties from the geometry;
//! - [`forces`]: gravity, springs, quadratic and angular drag, point forces,
//!   torques, each with an optional time window; the [`Force`] trait;
//! - [`collision`], [`contact`]: detection (broad phase, separating axes,
//!   time of impact) and response (impulses with restitution, resting
//!   contact, Coulomb friction) of seed §7;
//! - [`World`]: steps them, splits steps at force switches, locates events
//!   (landing, apex) by root finding, cuts steps at contacts, and reports
//!   blow-ups as typed errors.
//!
//! ```
//! use engine::{BodyDef, World, Method, forces::{Spring, Attachment}};
//! use nalgebra::Vector2;
//! // The seed's mass-spring (CASES.md case I), RK4 at h = 0.2 s.
//! let mut world = World::new(Method::Rk4).unwrap();
//! let mass = world.add_body(BodyDef::particle("mass", 20.0, Vector2::new(100.0, 0.0))).unwrap();
//! world.add_force(Spring {
//!     a: Attachment::World(Vector2::zeros()),
//!     b: Attachment::center_of(mass),
//!     stiffness: 50.0,
//!     rest_length: 50.0,
//!     axis: Some(Vector2::x()),
//! }).unwrap();
//! let trace = world.run(57.2, 0.2).unwrap();
//! let x = trace.last().unwrap().states[mass].position.x;
//! assert!((x - 10.95756).abs() < 1e-4);
//! ```

#![warn(missing_docs)]

pub mod body;
pub mod collision;
pub mod contact;
mod contact_model;
pub mod error;
pub mod events;
mod exact_model;
pub mod forces;
pub mod integrators;
pub mod ode;
pub mod root_finding;
pub mod shape;
pub mod soft_step;
pub mod time_grid;
pub mod trace;
mod world;
mod world_core;
mod world_ode;

pub use body::{Body, BodyDef, BodyId, BodyKind, BodyState};
pub use contact::{ContactEvent, ContactEventKind, ContactSettings, StepProfile, ToiMethod};
pub use contact_model::ContactModel;
pub use error::{EngineError, Result};
pub use events::{Crossing, EventRecord, EventSpec, Quantity};
pub use forces::{Force, ForceContext, TimeWindow, Wrench};
pub use integrators::{
    Integrator, Method, Solution, Stats, Tolerance, integrate_fixed, integrate_to,
};
pub use ode::{FnSystem, OdeSystem, Structure};
pub use shape::{Circle, Compound, CompoundPart, ConvexPolygon, Shape};
pub use soft_step::SoftStepSettings;
pub use time_grid::{MAX_RUN_STEPS, step_count};
pub use trace::{Sample, Trace};
pub use world::World;
