//! The harness: runs every validation case of CASES.md against its
//! reference and writes `reports/`. The binary (`cargo run --release -p
//! harness`) is a thin command line over this library, which the snapshot
//! tests and the benches use too.

pub mod cases;
pub mod report;
pub mod row;
pub mod snapshot;
pub mod tolerance;
pub mod worlds;
