//! Every case of the registry whose declaration says
//! `Snapshots::ContactEvents` (`harness::cases::CASES`): its rows must all
//! pass, and the contact events of each of its scenes (time, kind, bodies,
//! point, normal and impulses, rounded to significant digits,
//! `harness::snapshot`) must match their snapshot,
//! `collision_snapshots__collision_events__<scene>.snap`: the snapshot
//! catches any change, the rows catch wrongness.
//!
//! CI runs with `INSTA_UPDATE=no`: a changed event list fails. Update on
//! purpose (`INSTA_UPDATE=always`), read the diff, commit it with the reason.

use harness::cases::collision_common::{render_contact_events, run_engine, thin_events};
use harness::cases::collision_parry::{agreement, report};
use harness::cases::{CASES, Case, CaseReport, Snapshots, failing_rows};
use std::panic::{AssertUnwindSafe, catch_unwind};

fn assert_rows_pass(id: &str, report: &CaseReport) {
    let failed = failing_rows(&report.rows);
    assert!(
        failed.is_empty(),
        "{id}: failing rows:\n{}",
        failed.join("\n")
    );
    assert!(!report.rows.is_empty(), "{id} produced no rows");
}

/// Runs `case` (asserting its rows) and snapshots the contact events of
/// each of its scenes.
fn check(case: &Case) {
    let report = (case.run)().expect("case runs");
    assert_rows_pass(case.id, &report);
    assert!(
        !case.scenes.is_empty(),
        "{} declares contact-event snapshots but no scene",
        case.id
    );
    for scene in case.scenes {
        let run = run_engine(scene).expect("scene runs");
        let events = run.world.contact_events();
        let (kept, left_out) = thin_events(&events, 8, 4);
        let mut text = render_contact_events(&run.scene, &kept);
        if left_out > 0 {
            text.push_str(&format!(
                "... {left_out} events left out between the first 8 and the last 4 ({} in all)\n",
                events.len()
            ));
        }
        insta::assert_snapshot!(format!("collision_events__{scene}"), text);
    }
}

#[test]
fn every_collision_case_passes_its_rows_and_matches_its_event_snapshots() {
    let cases: Vec<&Case> = CASES
        .iter()
        .filter(|c| c.snapshots == Snapshots::ContactEvents)
        .collect();
    assert!(
        !cases.is_empty(),
        "no case declares contact-event snapshots"
    );
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

/// The parry comparison on 2 000 + 2 000 pairs (the harness's release run
/// does 100 000 + 20 000): the same rows must pass.
#[test]
fn detection_agrees_with_parry_on_a_sample() {
    let (random, near) = agreement(2_000, 2_000);
    assert_rows_pass("collision_parry", &report(&random, &near));
}
