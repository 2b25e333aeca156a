//! The engine's internals that the harness checks one by one against
//! independent references: collision detection, the exact contact model's
//! machinery and the root finder that locates events. A simulation needs
//! none of them directly ([`crate::World`] runs them); they are public so
//! that their results can be validated on their own (`docs/cases.md`, the
//! `collision_*` cases) and read by tools such as the harness's pictures.
//!
//! Semver-exempt: these items change with the engine's internals.

#[path = "collision/mod.rs"]
pub mod collision;
pub use crate::exact::contact;
#[path = "root_finding.rs"]
pub mod root_finding;
