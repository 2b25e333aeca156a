//! The `shape_parry` case on a reduced run (40 random pairs of each of the
//! 21 pairs of kinds; the harness runs 2 000): every row passes, every
//! pair of kinds is there.

use harness::cases::shape_parry::{agreement, report};

#[test]
fn a_reduced_run_passes_on_every_pair_of_kinds() {
    let found = agreement(40);
    assert_eq!(found.len(), 21);
    let report = report(&found);
    assert_eq!(report.rows.len(), 21 * 4 + 1);
    let failing: Vec<_> = report.rows.iter().filter(|r| !r.pass).collect();
    assert!(failing.is_empty(), "{failing:#?}\n{:#?}", report.notes);
}
