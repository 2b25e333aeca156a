//! The joint cases at a size a debug build runs in seconds
//! (`docs/cases.md#joints`): each declares `Snapshots::HarnessOnly` in the
//! registry because its full run (three engines, long runs, sweeps) is too
//! heavy for `cargo test`; here the soft step alone runs the same scene
//! files with the same rows, reduced, and every row must pass. Each
//! reduced report's rows are snapshotted too (value, expected and
//! tolerance to six significant digits): the snapshot catches any change,
//! the rows catch wrongness.
//!
//! CI runs with `INSTA_UPDATE=no`: a changed row fails. Update on purpose
//! (`INSTA_UPDATE=always`), read the diff, commit it with the reason.

use harness::cases::pendulum_swing::Size;
use harness::cases::{CaseReport, failing_rows};
use harness::snapshot::round_sig;

/// Asserts that every row of `report` passes, and renders them.
fn rows_of(id: &str, report: &CaseReport) -> String {
    let failed = failing_rows(&report.rows);
    assert!(
        failed.is_empty(),
        "{id}: failing rows:\n{}",
        failed.join("\n")
    );
    assert!(!report.rows.is_empty(), "{id} produced no rows");
    report
        .rows
        .iter()
        .map(|r| {
            format!(
                "{} {} {} {} {}",
                r.check,
                r.method,
                round_sig(r.value),
                round_sig(r.expected),
                round_sig(r.tolerance)
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn pendulums_over_ten_periods_keep_their_rows() {
    let report = harness::cases::pendulum::run_sized(Size::REDUCED).expect("pendulum runs");
    // 6 pendulums × 5 rows (the exact model's rows run in the full case
    // only; tests/exact_joints.rs of the engine checks the model).
    assert_eq!(report.rows.len(), 30);
    insta::assert_snapshot!("pendulum_reduced", rows_of("pendulum", &report));
}

#[test]
fn boxes_pivoted_at_a_corner_over_ten_periods_keep_their_rows() {
    let report = harness::cases::physical_pendulum::run_sized(Size::REDUCED)
        .expect("physical_pendulum runs");
    assert_eq!(report.rows.len(), 10);
    insta::assert_snapshot!(
        "physical_pendulum_reduced",
        rows_of("physical_pendulum", &report)
    );
}

#[test]
fn a_double_pendulum_follows_its_reference_up_to_the_horizon() {
    let report =
        harness::cases::double_pendulum::run_sized(harness::cases::double_pendulum::Size::REDUCED)
            .expect("double_pendulum runs");
    insta::assert_snapshot!(
        "double_pendulum_reduced",
        rows_of("double_pendulum", &report)
    );
}

#[test]
fn a_chain_rests_on_its_elastic_equilibrium() {
    let report = harness::cases::chain::run_sized(false).expect("chain runs");
    assert_eq!(report.rows.len(), 2);
    insta::assert_snapshot!("chain_reduced", rows_of("chain", &report));
}

#[test]
fn a_sprung_slider_oscillates_and_rests_where_it_must() {
    let report = harness::cases::slider::run_sized(false).expect("slider runs");
    assert_eq!(report.rows.len(), 5);
    insta::assert_snapshot!("slider_reduced", rows_of("slider", &report));
}

#[test]
fn motors_and_a_limit_do_what_their_rows_say() {
    let report = harness::cases::joint_motor_limit::run_sized(false).expect("case runs");
    assert_eq!(report.rows.len(), 7);
    insta::assert_snapshot!(
        "joint_motor_limit_reduced",
        rows_of("joint_motor_limit", &report)
    );
}

#[test]
fn a_driven_slider_crank_follows_its_closed_form() {
    // The full case (about 0.3 s in release): every row must pass; no
    // snapshot, its exact rows sit at round-off.
    let report = harness::cases::slider_crank::run().unwrap();
    let failed = failing_rows(&report.rows);
    assert!(failed.is_empty(), "slider_crank: {}", failed.join("\n"));
    assert_eq!(report.rows.len(), 3);
}
