//! The harness: runs every validation case of docs/cases.md against its
//! reference and writes `reports/`. The binary (`cargo run --release -p
//! harness`) is a thin command line over this library, which the snapshot
//! tests and the benches use too.

pub mod bench;
pub mod cases;
pub mod clip;
pub mod convergence;
pub mod fuzz;
pub mod interrupt;
pub mod links;
pub mod pictures;
pub mod plots;
pub mod pool;
pub mod progress;
pub mod provenance;
pub mod rapier_scene;
pub mod replay;
pub mod replay_cases;
pub mod report;
pub mod row;
pub mod scenes;
pub mod shard;
pub mod simulate;
pub mod snapshot;
pub mod stability;
pub mod study;
pub mod sweep;
pub mod timing;
pub mod tolerance;
#[cfg(feature = "view")]
pub mod view;
pub mod workspace;
