//! The fuzz target's bounded run (`harness::fuzz`: arbitrary and mutated
//! scene text and random small worlds under both contact models, through
//! loading and a few steps; no panic, bounded work, nothing non-finite
//! returned as success, every refusal located and in the user's words).
//!
//! `cargo test -p harness --test fuzz_scenes` runs [`DEFAULT_CASES`] cases
//! (a few seconds in the debug test profile); the harness's full run runs
//! more and reports the figure (case `fuzz_scenes`). A longer run:
//!
//! ```text
//! FUZZ_CASES=100000 cargo test --release -p harness --test fuzz_scenes -- --nocapture
//! ```
//!
//! (`FUZZ_SEED=n` picks another deterministic sequence.) Every failing case
//! is counted by kind and the first few are printed with their text (panics
//! first, or those whose reason starts with `FUZZ_SHOW`), so one run reports
//! all the kinds of failure, not just the first.

use harness::fuzz;

/// Cases run by a plain `cargo test`.
const DEFAULT_CASES: u64 = 300;
/// Failing cases printed in full (the rest are counted).
const SHOWN: usize = 8;

#[test]
fn mutated_and_random_scenes_are_refused_clearly_or_run_finite() {
    let cases: u64 = std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_CASES);
    let seed: u64 = std::env::var("FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x5ce4e);
    let (index, count) = match std::env::var("FUZZ_SHARD") {
        Ok(v) => {
            let shard: harness::shard::Shard =
                v.parse().unwrap_or_else(|e| panic!("FUZZ_SHARD={v}: {e}"));
            (shard.index as u64, shard.count as u64)
        }
        Err(_) => (1, 1),
    };
    let mut summary = fuzz::run_share(cases, seed, &fuzz::seeds(), index, count);
    let cases = summary.cases;
    println!(
        "fuzz: shard {index}/{count}, {cases} cases ({} loaded, {} refused; {} random worlds, {} of them loaded), {} \
         failures",
        summary.loaded,
        summary.refused,
        summary.worlds,
        summary.worlds_loaded,
        summary.failures.len()
    );
    for (kind, count) in &summary.kinds() {
        println!("  {count:>6}  {kind}");
    }
    // Panics first: they are the worst.
    summary.failures.sort_by_key(|(why, _)| {
        !why.starts_with(std::env::var("FUZZ_SHOW").as_deref().unwrap_or("panicked"))
    });
    for (why, text) in summary.failures.iter().take(SHOWN) {
        println!("--- {why}\n{text}\n");
    }
    assert!(
        summary.failures.is_empty(),
        "{} of {cases} cases failed; first: {}",
        summary.failures.len(),
        summary.failures[0].0
    );
}
