//! `falling_hinges`: determinism with joints, after Box2D's "Falling
//! Hinges" test (`test/test_determinism.c`): `scenes/falling_hinges.toml`
//! (4 columns of 20 boxes hinged in pairs by revolute joints with limits,
//! springs and friction motors, falling onto the ground with sleeping on)
//! stepped at 1/60 s until every box sleeps, twice in this process. Rows:
//! the step at which it came to rest and the world's state hash (every
//! body's final pose bits) against the constants the engine's test asserts
//! (`engine/tests/falling_hinges/expected.rs`, included here), and the
//! second run giving the same step and hash as the first.

use super::soft_step_common::SOFT_STEP;
use super::{Case, CaseReport};
use crate::row::{RowKind, RowSink};
use anyhow::{Context, Result};

// REST_STEP, HINGES_HASH, UPDATE, run_to_rest: one copy for
// the engine's test, the scene crate's test and this case.
include!("../../../engine/tests/falling_hinges/expected.rs");

/// Falling Hinges to rest.
pub const CASE: Case = Case {
    scenes: &["falling_hinges"],
    ..Case::new(
        "falling_hinges",
        "Determinism: Box2D's Falling Hinges (80 boxes on 40 limited, sprung, motored hinges) to rest, twice, with the hash of every final pose",
        run,
    )
};

/// One run to rest: the step and the pose hash.
fn run_once() -> Result<(usize, u64)> {
    let scene = crate::scenes::load("falling_hinges")?;
    let mut world = scene.build_world(None)?;
    let step = run_to_rest(&mut world)
        .with_context(|| format!("{}: not at rest after 2000 steps", scene.origin()))?;
    Ok((step, world.state_hash()))
}

/// Runs `falling_hinges`.
pub fn run() -> Result<CaseReport> {
    let first = run_once()?;
    let second = run_once()?;
    let mut report = CaseReport::default();
    let mut rows = RowSink {
        case: "falling_hinges",
        method: SOFT_STEP,
        dt: 1.0 / 60.0,
        rows: &mut report.rows,
    };
    let (step, hash) = first;
    let verdict = |same: bool| if same { "" } else { "; " };
    rows.within(
        RowKind::Regression,
        "rest_step",
        step as f64,
        REST_STEP as f64,
        0.0,
        format!(
            "the step at which every box slept, against the engine test's constant: a \
             deterministic engine gives it exactly{}{}",
            verdict(step == REST_STEP),
            if step == REST_STEP { "" } else { UPDATE }
        ),
    );
    rows.within(
        RowKind::Regression,
        "pose_hash_matches",
        f64::from(u8::from(hash == HINGES_HASH)),
        1.0,
        0.0,
        format!(
            "1 when World::state_hash (FNV-1a of every body's final x, y, angle bits, the ground \
             included), {hash:#018x}, is the \
             engine test's {HINGES_HASH:#018x} (bits, so exactly){}{}",
            verdict(hash == HINGES_HASH),
            if hash == HINGES_HASH { "" } else { UPDATE }
        ),
    );
    rows.within(
        RowKind::Regression,
        "second_run_identical",
        f64::from(u8::from(second == first)),
        1.0,
        0.0,
        format!(
            "1 when a second run in this process rests at the same step with the same hash \
             (step {}, {:#018x}): the same input gives the same bits",
            second.0, second.1
        ),
    );
    report.notes.push(format!(
        "Came to rest at step {step} (t = {:.3} s) with pose hash `{hash:#018x}`; the engine's \
         test expects step {REST_STEP} and `{HINGES_HASH:#018x}` \
         (engine/tests/falling_hinges/expected.rs, also read by scene/tests/joints.rs for \
         scenes/falling_hinges.toml). Box2D's own test hashes its f32 poses of rounded boxes: \
         its constants are not comparable with these.",
        step as f64 / 60.0
    ));
    Ok(report)
}
