//! The chain cases' soft-step rows (issue 19): `ghost_collisions` run
//! without the reference engines, every row passing; `bowl`, whose open
//! row (docs/cases.md#bowl) must be exactly the one failing.

#[test]
fn a_box_and_a_capsule_slide_over_a_chain_without_a_bump_and_are_thrown_by_boxes() {
    let report = harness::cases::ghost_collisions::run_sized(false).expect("ghost_collisions runs");
    let failed = harness::cases::failing_rows(&report.rows);
    assert!(failed.is_empty(), "ghost_collisions: {}", failed.join("\n"));
    // The chain's and the long box's rows (speed and spin) and the boxes',
    // for the box and for the capsule.
    assert_eq!(report.rows.len(), 10);
}

#[test]
fn a_disc_in_a_bowl_converges_with_one_row_open() {
    let report = harness::cases::bowl::run().expect("bowl runs");
    assert_eq!(report.rows.len(), 5);
    let failing: Vec<&str> = report
        .rows
        .iter()
        .filter(|r| !r.pass)
        .map(|r| r.check.as_str())
        .collect();
    // The open finding of docs/cases.md#bowl: a change either way (a fix,
    // or another row failing) must update that section.
    assert_eq!(failing, ["period_n32"]);
}
