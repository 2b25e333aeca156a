//! `pyramid` (Box2D's benchmark pyramid, `docs/soft_step.md#benchmark-scenes`):
//! base 20, 210 boxes of 1 m, friction 0.6, under the soft-step model at
//! its defaults for 10 s. The criterion for standing: the top box
//! within 0.05 m of its resting height and no box faster than 0.01 m/s at
//! the end.

use super::soft_step_common::SoftRun;
use super::{Case, CaseReport, Headline};
use crate::row::RowKind;
use anyhow::Result;

/// The base-20 pyramid.
pub const CASE: Case = Case {
    scenes: &["pyramid_20"],
    headline: &[Headline::new("top_sink", "soft_step")],
    ..Case::new(
        "pyramid",
        "Soft step: a pyramid of base 20 (210 boxes) stands for 10 s",
        run,
    )
};

/// The bound on the top box's sink (m): a box of 1 m whose
/// contacts compress by millimetres each.
const TOP_SINK: f64 = 0.05;

/// The bound on the fastest box at the end (m/s).
const AT_REST: f64 = 0.01;

/// Runs `pyramid`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("pyramid_20")?;
    let mut report = CaseReport::default();
    let top = run.body("pyramid_209")?;
    let first = &run.trace.samples[0];
    let last = run.trace.last().expect("samples");
    let sink = first.states[top].position.y - last.states[top].position.y;
    let drift = (last.states[top].position.x - first.states[top].position.x).abs();
    let fastest = run.fastest_at_end();
    let mut rows = run.sink("pyramid", &mut report.rows);
    rows.at_most(
        RowKind::Criterion,
        "top_sink",
        sink,
        0.0,
        TOP_SINK,
        "the top box's descent below its ideal resting height (19.5 m) after 10 s: the \
         compressions of the 20 contacts below it (30 Hz springs carrying up to ten boxes' \
         weight, millimetres each) add to centimetres; the issue's criterion for a standing \
         pyramid, 0.05 m",
    );
    rows.at_most(
        RowKind::Criterion,
        "fastest_at_end",
        fastest,
        0.0,
        AT_REST,
        "the largest body speed after 10 s: the pyramid has come to rest (no jitter); the \
         issue's criterion, 0.01 m/s",
    );
    rows.at_most(
        RowKind::Criterion,
        "top_drift",
        drift,
        0.0,
        0.5,
        "the top box's sideways drift: it stays over the two boxes below it (their faces meet \
         under its centre, half a box to either side), 0.5 m",
    );
    report.notes.push(format!(
        "`pyramid`: top box sank {sink:.5} m and drifted {drift:.2e} m sideways; fastest body \
         at the end {fastest:.2e} m/s. The same scene in Box2D v3 and rapier2d: see the \
         benchmark report."
    ));
    Ok(report)
}
