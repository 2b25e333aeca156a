//! Snapshots of every case's traces, one per case and method, each paired
//! with the case's tolerance assertions: the snapshot catches any change,
//! the rows catch wrongness.
//!
//! CI runs with `INSTA_UPDATE=no`: a changed trace fails. Update on purpose
//! (`cargo insta review` or `INSTA_UPDATE=always`), read the diff, and
//! commit it with the reason.

use harness::cases::{CaseReport, MethodTrace, failing_rows, find};
use harness::snapshot::render;

fn check_case(id: &str) {
    let case = find(id).expect("case exists");
    let report: CaseReport = (case.run)().expect("case runs");
    let failed = failing_rows(&report.rows);
    assert!(
        failed.is_empty(),
        "{id}: failing rows:\n{}",
        failed.join("\n")
    );
    assert!(!report.rows.is_empty(), "{id} produced no rows");
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
fn spring_traces() {
    check_case("spring");
}

#[test]
fn projectile_traces() {
    check_case("projectile");
}

#[test]
fn torque_traces() {
    check_case("torque");
}

#[test]
fn projectile_drag_traces() {
    check_case("projectile_drag");
}

#[test]
fn angular_drag_traces() {
    check_case("angular_drag");
}

#[test]
fn hoffman_traces() {
    check_case("hoffman");
}
