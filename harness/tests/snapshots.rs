//! Every case of the registry whose declaration says `Snapshots::Traces`
//! or `Snapshots::RowsOnly` (`harness::cases::CASES`): its rows must all
//! pass, and its traces must match their snapshots, one per case and
//! method (`snapshots__<case>__<method>.snap`): the snapshot catches any
//! change, the rows catch wrongness. Contact events are snapshotted in
//! `collision_snapshots.rs`.
//!
//! CI runs with `INSTA_UPDATE=no`: a changed trace fails. Update on purpose
//! (`cargo insta review` or `INSTA_UPDATE=always`), read the diff, and
//! commit it with the reason.

use harness::cases::{CASES, Case, CaseReport, MethodTrace, Snapshots, failing_rows};
use harness::snapshot::render;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `case`, asserts its rows, and snapshots its traces when it says so.
fn check(case: &Case) {
    let id = case.id;
    let report: CaseReport = (case.run)().expect("case runs");
    let failed = failing_rows(&report.rows);
    assert!(
        failed.is_empty(),
        "{id}: failing rows:\n{}",
        failed.join("\n")
    );
    assert!(!report.rows.is_empty(), "{id} produced no rows");
    if case.snapshots != Snapshots::Traces {
        return;
    }
    assert!(
        !report.traces.is_empty(),
        "{id} declares traces but has none"
    );
    let mut methods: Vec<&str> = report.traces.iter().map(|t| t.method.as_str()).collect();
    methods.dedup();
    for method in methods {
        let traces: Vec<&MethodTrace> = report
            .traces
            .iter()
            .filter(|t| t.method == method)
            .collect();
        insta::assert_snapshot!(format!("{id}__{method}"), render(&traces));
    }
}

#[test]
fn every_case_passes_its_rows_and_matches_its_trace_snapshots() {
    let cases: Vec<&Case> = CASES
        .iter()
        .filter(|c| matches!(c.snapshots, Snapshots::Traces | Snapshots::RowsOnly))
        .collect();
    assert!(!cases.is_empty(), "no case declares trace snapshots");
    // Every case is checked; the failures are listed together at the end.
    let failed: Vec<&str> = cases
        .iter()
        .filter(|case| catch_unwind(AssertUnwindSafe(|| check(case))).is_err())
        .map(|case| case.id)
        .collect();
    assert!(
        failed.is_empty(),
        "cases that failed (see above): {failed:?}"
    );
}

#[test]
fn a_case_too_heavy_for_the_tests_says_where_it_is_checked() {
    for case in CASES {
        if let Snapshots::HarnessOnly(reason) = case.snapshots {
            assert!(
                reason.contains("tests/"),
                "case '{}' is left to the harness: its reason must name the test that checks a reduced run ({reason:?})",
                case.id
            );
        }
    }
}
