//! Contact response (seed §7.1–7.2, eq. 7.1–7.16; docs/cases.md case III): what
//! happens once detection ([`crate::collision`]) says two shapes touch.
//!
//! Three regimes, as the seed lays them out after Baraff and Mirtich:
//!
//! - **Impact** (the seed's « force impulsive »): the integrator is stopped
//!   at the first contact inside the step (located by the seed's bisection,
//!   Fig. 7.7–7.8, or by conservative advancement where a pair could have
//!   passed through another within the step), the velocities jump by
//!   the impulse of eq. 7.15 with restitution e (corrected as docs/cases.md
//!   states, see [`impact_eq_7_15`]), and the integrator restarts with the
//!   rest of the step, its cached derivative dropped. Several points, pairs
//!   or bodies touching at once are solved together, with Coulomb friction
//!   on the impulse.
//! - **Resting contact** (« force de contact »): a pair that touches without
//!   approaching faster than [`ContactSettings::resting_speed`] is held by
//!   contact forces computed inside every evaluation of the right-hand side
//!   so that its points neither approach nor accelerate into each other
//!   (module `resting`), followed through the piece of step by the features
//!   it was found with (module `persistent`). The integrator keeps its
//!   order; a box on the ground
//!   neither sinks nor jitters, because nothing is corrected after the fact.
//! - **Friction** (not in the seed): Coulomb, |F_t| ≤ μ F_n. A resting pair
//!   *sticks* (the friction holds it within the cone) or *slides* (kinetic
//!   friction μ F_n against the sliding direction); the time at which a
//!   sliding pair stops is located by root finding, like any event.
//!
//! Every contact problem (impulses at an impact, forces while resting,
//! projection of a pair that sank) is the same small complementarity
//! problem on rows of the effective-mass matrix (module `rows`), solved by
//! projected Gauss–Seidel and polished to machine precision (module
//! `solver`).
//!
//! The world runs it as named phases, each timed into a [`StepProfile`]:
//! integrate, broad phase, narrow phase, time of impact, respond (module
//! `pipeline`). Contacts are asked for with
//! [`crate::World::set_contact_settings`] (a scene's `[contact]` table); a
//! world that did not ask, or has fewer than two shapes, or no moving one,
//! runs none of it.

pub(crate) mod constrained;
mod events;
mod impulse;
mod persistent;
pub(crate) mod resting;
pub(crate) mod rows;
mod settings;
pub(crate) mod solver;

pub use crate::profile::StepProfile;
pub use crate::tunables::PROJECTION_SLOP;
pub use events::{ContactEvent, ContactEventKind};
pub use impulse::{ImpactBody, ImpactOutcome, Velocities, impact_eq_7_15};
pub use settings::{ContactSettings, ToiMethod};
