//! `fuzz_scenes`: the fuzz target ([`crate::fuzz`]) run at the size of the
//! harness, so that its figure (cases run, failures) is in the report:
//! arbitrary and mutated scene text and random small worlds under both
//! contact models, through loading and a few steps. A failure is a panic,
//! a non-finite state or energy returned as success, or a refusal without a
//! line, in Rust's or serde's words, or with a number of dozens of digits.

use super::{Case, CaseReport, Snapshots};
use crate::fuzz;
use crate::row::{RowKind, RowSink};
use anyhow::Result;
use std::time::Instant;

/// The fuzz target's figure.
pub const CASE: Case = Case {
    snapshots: Snapshots::HarnessOnly(
        "10 000 cases; `tests/fuzz_scenes.rs` runs 300 of the same sequence",
    ),
    ..Case::new(
        "fuzz_scenes",
        "Hostile input: 10 000 fuzzed scene files and random worlds, refused clearly or run finite",
        run,
    )
};

/// Cases of the harness's run (a few seconds).
pub const CASES: u64 = 10_000;

/// The sequence the test and the harness run (`FUZZ_SEED` in the test).
pub const SEED: u64 = 0x5ce4e;

/// Runs `fuzz_scenes`.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    let started = Instant::now();
    let summary = fuzz::run(CASES, SEED, &fuzz::seeds());
    let elapsed = started.elapsed();
    let mut sink = RowSink {
        case: "fuzz_scenes",
        method: "fuzz",
        dt: 0.0,
        rows: &mut report.rows,
    };
    sink.at_most(
        RowKind::Criterion,
        "failures",
        summary.failures.len() as f64,
        0.0,
        0.0,
        format!(
            "of {CASES} cases ({} loaded and stepped, {} refused; {} random worlds, {} of them \
             loaded): none may panic, return a non-finite state or energy as success, or be \
             refused without a line, in Rust's or serde's words, or with a number of dozens of \
             digits",
            summary.loaded, summary.refused, summary.worlds, summary.worlds_loaded
        ),
    );
    report.notes.push(format!(
        "Fuzz target (`harness/src/fuzz.rs`): {CASES} cases of sequence {SEED:#x} in {:.1} s: \
         {} loaded and stepped, {} refused, {} random worlds ({} loaded), {} failures{}. \
         `cargo test` runs 300 of them; a long run: `FUZZ_CASES=100000 cargo test --release -p \
         harness --test fuzz_scenes -- --nocapture` (`FUZZ_SEED=n` for another sequence).",
        elapsed.as_secs_f64(),
        summary.loaded,
        summary.refused,
        summary.worlds,
        summary.worlds_loaded,
        summary.failures.len(),
        if summary.failures.is_empty() {
            String::new()
        } else {
            let kinds: Vec<String> = summary
                .kinds()
                .iter()
                .map(|(kind, n)| format!("{n} × {kind}"))
                .collect();
            format!(" ({})", kinds.join("; "))
        }
    ));
    Ok(report)
}
