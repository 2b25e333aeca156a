//! The chain cases' soft-step rows (issue 19): `ghost_collisions` run
//! without the reference engines, every row passing.

#[test]
fn a_box_slides_over_a_chain_without_a_bump_and_is_thrown_by_boxes() {
    let report = harness::cases::ghost_collisions::run_sized(false).expect("ghost_collisions runs");
    let failed = harness::cases::failing_rows(&report.rows);
    assert!(failed.is_empty(), "ghost_collisions: {}", failed.join("\n"));
    // The chain's and the long box's rows (speed and spin) and the boxes'.
    assert_eq!(report.rows.len(), 5);
}
