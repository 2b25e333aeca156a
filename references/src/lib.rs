//! What the engine is judged against.
//!
//! This crate holds the reference solutions of the validation cases listed in
//! `docs/cases.md` (the authoritative list, at the root of the shared project
//! notes). Every item here is a pure function of its parameters: nothing in
//! this crate calls the engine, so an engine bug cannot leak into the
//! reference it is compared with.
//!
//! | case (`docs/cases.md`)          | seed report          | module                  |
//! |----------------------------|----------------------|-------------------------|
//! | I, `spring`                | §5, eq. 5.2–5.4      | [`spring`]              |
//! | II, `projectile`           | §6, eq. 6.1–6.3, Table 6.1 | [`projectile`]    |
//! | II, `torque`               | §6, eq. 6.16–6.20    | [`torque`]              |
//! | II, `angular_drag`         | §6, eq. 6.21         | [`angular_drag`]        |
//! | II, `projectile_drag`      | §6, eq. 6.4–6.15, Table 6.2 | [`drag_projectile`], [`drag_reference_values`] |
//! | stiff test, `hoffman`      | §4.3                 | [`hoffman`]             |
//! | `pendulum`, `physical_pendulum` | (not in the seed) | [`pendulum`]       |
//! | `double_pendulum`          | (not in the seed)    | [`double_pendulum`]     |
//! | `chain`                    | (not in the seed)    | [`catenary`], [`elastic_chain`] |
//! | `slider`                   | (not in the seed)    | [`slider`]              |
//!
//! The first five are closed forms. The quadratic-drag projectile has none in
//! 2D: [`drag_projectile`] solves it with DOP853 (crate `ode_solvers`) at a
//! tolerance of 1e-14 and locates its events by root-finding, and
//! [`drag_reference_values`] holds the 40-digit values `docs/cases.md` quotes, which
//! the DOP853 solve is tested against.
//!
//! The joint cases' references: the pendulum's period and motion by the
//! complete elliptic integral and Jacobi's functions (AGM and Landen),
//! the double pendulum of two rigid bodies by DOP853 with its error
//! estimate and chaos horizon, the catenary and the exact equilibrium of
//! a chain of rigid links (on rigid or on elastic pins), the inclined
//! spring slider in closed form.
//!
//! Other engines, run on the same scenes for comparison: rapier2d-f64
//! ([`rapier_world`] single bodies, [`rapier_contacts`] collision scenes),
//! parry2d-f64 shape queries ([`parry_queries`]), and for the many-body
//! benchmark an engine-agnostic scene description ([`many_body`], with
//! joints: [`many_body::joints`]) with adapters to Box2D v3.2 through boxdd
//! ([`box2d_world`]) and to rapier at its defaults ([`rapier_many`]).
//!
//! Units are SI throughout (m, s, kg, N, rad) and every quantity is `f64`.
//! "Seed" means the 2006 report `seed/000_03ad6f8b5a3a5bfa.txt`; its numbers
//! are used as `docs/cases.md` corrects them.
#![warn(missing_docs)]

pub mod angular_drag;
pub mod bowl;
pub mod box2d_world;
pub mod catenary;
pub mod double_pendulum;
pub mod drag_projectile;
pub mod drag_reference_values;
pub mod elastic_chain;
pub mod hoffman;
pub mod linear_stability;
pub mod many_body;
pub mod parry_queries;
pub mod pendulum;
pub mod projectile;
pub mod slider;
pub mod spring;
pub mod torque;

#[cfg(test)]
mod test_support;

pub use angular_drag::AngularDrag;
pub use drag_projectile::{DragError, DragParams, DragReference, SolverSettings};
pub use hoffman::Hoffman;
pub use projectile::{Projectile, SEED_GRAVITY};
pub use spring::SpringOscillator;
pub use torque::TorquePulse;
pub mod rapier_contacts;
pub mod rapier_many;
pub mod rapier_world;

/// Holds rayon's global pool at one thread (once per process; a later
/// call, or a pool already made, leaves it): rapier2d is built with its
/// `parallel` feature for the benchmark's multi-threaded rows, and its
/// other uses (the validation cases, the comparisons) stay on one thread
/// as before. Called by every rapier adapter's constructor.
pub fn serial_rayon() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // An error means the global pool exists already: nothing to do.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build_global();
    });
}
