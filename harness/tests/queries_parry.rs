//! `queries_parry` on a reduced run (4 worlds, 100 rays and 20 other
//! queries of each kind per world): every row passes. The harness runs the
//! full 100 000 rays.

use harness::cases::failing_rows;
use harness::cases::queries_parry::{measure, report};

#[test]
fn world_queries_agree_with_parry_on_a_reduced_run() {
    let tally = measure(4, 100, 20);
    assert_eq!(tally.rays, 400);
    let report = report(&tally, 400);
    let failed = failing_rows(&report.rows);
    assert!(failed.is_empty(), "failing rows:\n{}", failed.join("\n"));
}
