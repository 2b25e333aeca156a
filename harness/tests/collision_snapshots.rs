//! Snapshots of the contact events of every collision scene (CASES.md case
//! III): time, kind, bodies, point, normal and impulses, rounded to
//! significant digits (`harness::snapshot`), each paired with its case's
//! rows: the snapshot catches any change, the rows catch wrongness.
//!
//! CI runs with `INSTA_UPDATE=no`: a changed event list fails. Update on
//! purpose (`INSTA_UPDATE=always`), read the diff, commit it with the reason.

use harness::cases::collision_common::{render_contact_events, run_engine, thin_events};
use harness::cases::collision_parry::{agreement, report};
use harness::cases::{CaseReport, failing_rows, find};

fn assert_rows_pass(id: &str, report: &CaseReport) {
    let failed = failing_rows(&report.rows);
    assert!(
        failed.is_empty(),
        "{id}: failing rows:\n{}",
        failed.join("\n")
    );
    assert!(!report.rows.is_empty(), "{id} produced no rows");
}

/// Runs case `id` (asserting its rows) and snapshots the contact events of
/// each of its scenes.
fn check(id: &str, scenes: &[&str]) {
    let case = find(id).expect("case exists");
    let report = (case.run)().expect("case runs");
    assert_rows_pass(id, &report);
    for scene in scenes {
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
fn head_on_events() {
    check(
        "collision_head_on",
        &["collision_head_on", "collision_head_on_half"],
    );
}

#[test]
fn off_centre_events() {
    check(
        "collision_off_centre",
        &["collision_off_centre", "collision_off_centre_half"],
    );
}

#[test]
fn bounce_events() {
    check(
        "collision_bounce",
        &["collision_bounce", "collision_bounce_08"],
    );
}

#[test]
fn slide_events() {
    check("collision_slide", &["collision_slide"]);
}

#[test]
fn incline_events() {
    check(
        "collision_incline",
        &["collision_incline_slide", "collision_incline_hold"],
    );
}

#[test]
fn rest_events() {
    check("collision_rest", &["collision_rest"]);
}

#[test]
fn toi_events() {
    check(
        "collision_toi",
        &["collision_toi", "collision_toi_rotating"],
    );
}

/// The parry comparison on 2 000 + 2 000 pairs (the harness's release run
/// does 100 000 + 20 000): the same rows must pass.
#[test]
fn detection_agrees_with_parry_on_a_sample() {
    let (random, near) = agreement(2_000, 2_000);
    assert_rows_pass("collision_parry", &report(&random, &near));
}
