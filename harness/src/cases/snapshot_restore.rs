//! `snapshot_restore`: a world written to bytes mid-run and read back
//! follows the uninterrupted run to the bit. The world
//! (`engine/tests/snapshot/scene.rs`, included here and by the engine's
//! test): a pyramid of 10 boxes hit just after step 40 by a pendulum of
//! three boxes on two revolute joints and a weld, sleeping on, a spring
//! force, one body's gravity scaled and damped. At step 40 (1/60 s) it is
//! written as CBOR
//! (through ciborium, which keeps every f64's bits) and read back, and
//! cloned in memory; all three are stepped 80 more steps.
//!
//! Regression and consistency evidence, not a validation against a
//! reference: the soft step is deterministic, so the restored world, given
//! the same bits, must take the same operations and give the same bits;
//! any difference (one ulp) would mean the snapshot missed state that the
//! next step reads (a warm-starting impulse, the broad phase's tree order,
//! a sleep timer). Hence tolerance 0.

use crate::row::RowKind;
use super::soft_step_common::SOFT_STEP;
use super::{Case, CaseReport};
use crate::row::RowSink;
use anyhow::{Context, Result};
use engine::World;

// SNAPSHOT_STEP, STEPS_AFTER and pyramid_with_joints: one copy for the
// engine's test and this case.
include!("../../../engine/tests/snapshot/scene.rs");

/// A pyramid with joints snapshot mid-run, restored, bit-identical.
pub const CASE: Case = Case::new(
    "snapshot_restore",
    "Snapshots: a pyramid with joints written to bytes mid-run and restored steps to the same bits as the uninterrupted run",
    run,
);

const DT: f64 = 1.0 / 60.0;

/// The largest |difference| between two worlds' states (positions,
/// angles, velocities, angular velocities) of every body.
fn max_difference(a: &World, b: &World) -> f64 {
    a.states()
        .iter()
        .zip(b.states())
        .flat_map(|(x, y)| {
            [
                x.position.x - y.position.x,
                x.position.y - y.position.y,
                x.angle - y.angle,
                x.velocity.x - y.velocity.x,
                x.velocity.y - y.velocity.y,
                x.angular_velocity - y.angular_velocity,
            ]
        })
        // A NaN difference counts as infinitely large.
        .map(|d| if d.is_nan() { f64::INFINITY } else { d.abs() })
        .fold(0.0, f64::max)
}

/// Runs `snapshot_restore`.
pub fn run() -> Result<CaseReport> {
    let mut original = pyramid_with_joints();
    for _ in 0..SNAPSHOT_STEP {
        original.step(DT)?;
    }
    let at_snapshot = original.clone();
    let mut bytes = Vec::new();
    ciborium::into_writer(&original, &mut bytes).context("writing the world as CBOR")?;
    let mut restored: World =
        ciborium::from_reader(&bytes[..]).context("reading the world back from CBOR")?;
    let mut cloned = original.clone();
    let (mut restored_worst, mut cloned_worst, mut hash_mismatches) = (0.0f64, 0.0f64, 0);
    for _ in 0..STEPS_AFTER {
        original.step(DT)?;
        restored.step(DT)?;
        cloned.step(DT)?;
        restored_worst = restored_worst.max(max_difference(&original, &restored));
        cloned_worst = cloned_worst.max(max_difference(&original, &cloned));
        if original.state_hash() != restored.state_hash() {
            hash_mismatches += 1;
        }
    }
    let moved = PYRAMID
        .filter(|&id| {
            (original.states()[id].position - at_snapshot.states()[id].position).norm() > 0.01
        })
        .count();

    let mut report = CaseReport::default();
    let mut rows = RowSink {
        case: "snapshot_restore",
        method: SOFT_STEP,
        dt: DT,
        rows: &mut report.rows,
    };
    const WHY_ZERO: &str = "regression/consistency evidence, not a validation against a \
         reference: the soft step is deterministic, so a world restored with the same bits \
         takes the same operations and must give the same bits; one ulp of difference would \
         mean the snapshot missed state the next step reads (warm-starting impulses, the broad \
         phase's tree, islands, sleep timers, joint impulses), hence tolerance 0";
    rows.within(
        RowKind::Consistency,
        "restored_max_state_difference",
        restored_worst,
        0.0,
        0.0,
        format!(
            "largest |difference| of any body's x, y, angle or velocity (m, rad, m/s, rad/s) \
             between the world read back from {} bytes of CBOR at step {SNAPSHOT_STEP} and the \
             uninterrupted run, over the {STEPS_AFTER} steps after: {WHY_ZERO}",
            bytes.len()
        ),
    );
    rows.within(
        RowKind::Consistency,
        "restored_hash_mismatches",
        f64::from(hash_mismatches),
        0.0,
        0.0,
        format!(
            "steps (of {STEPS_AFTER}) after which World::state_hash (FNV-1a of every body's \
             pose bits) of the restored world differs from the uninterrupted run's: {WHY_ZERO}"
        ),
    );
    rows.within(
        RowKind::Consistency,
        "clone_max_state_difference",
        cloned_worst,
        0.0,
        0.0,
        format!(
            "the same for a clone in memory (World: Clone) taken at step {SNAPSHOT_STEP}: \
             {WHY_ZERO}"
        ),
    );
    rows.at_least(
        RowKind::Criterion,
        "pyramid_boxes_moved_after_snapshot",
        moved as f64,
        5.0,
        0.0,
        "pyramid boxes (of 10) that moved more than 1 cm in the steps after the snapshot, \
         when the pendulum hits the pyramid: at least half, so that the comparison covers \
         contacts made and broken after the restore and is not that of a world at rest (a \
         bound on the test's coverage, not a physical prediction)",
    );
    report.notes.push(format!(
        "Written at step {SNAPSHOT_STEP} (t = {:.3} s) as {} bytes of CBOR; {} bodies, {} \
         joints; {moved} of the 10 pyramid boxes moved more than 1 cm in the {STEPS_AFTER} steps \
         after.",
        SNAPSHOT_STEP as f64 * DT,
        bytes.len(),
        original.bodies().len(),
        original.joint_count()
    ));
    Ok(report)
}
