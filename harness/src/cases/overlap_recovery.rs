//! `overlap_recovery` (Solver2D's overlap recovery,
//! `docs/soft_step.md#behaviour-scenes`): a 10-row pyramid of 1 m boxes
//! started with every box overlapping its neighbours by 25 %, under the
//! soft-step model. The soft contacts push overlapping bodies apart no
//! faster than the push-out speed, relative to each other, so the pile
//! expands into a heap instead of exploding.

use super::soft_step_common::{SoftRun, inverse_point_mass, point_compression};
use super::{Case, CaseReport, Headline};
use crate::row::RowKind;
use anyhow::Result;
use engine::validation::collision::proximity;
use nalgebra::Isometry2;

/// The overlapped pyramid.
pub const CASE: Case = Case {
    scenes: &["overlap_recovery"],
    headline: &[Headline::new("fastest_while_separating", "soft_step")],
    ..Case::new(
        "overlap_recovery",
        "Soft step: a 10-row pyramid started 25 % overlapped separates without exploding",
        run,
    )
};

/// The deepest overlap (m) of any pair of shaped bodies in `states`, by the
/// exact narrow phase (`engine::validation::collision::proximity`, validated against
/// parry2d by `collision_parry`).
fn deepest_overlap(run: &SoftRun, states: &[engine::BodyState]) -> f64 {
    let bodies = run.world.bodies();
    let pose = |i: usize| Isometry2::new(states[i].position, states[i].angle);
    let mut deepest = 0.0f64;
    for i in 0..bodies.len() {
        for j in i + 1..bodies.len() {
            let (Some(a), Some(b)) = (&bodies[i].shape, &bodies[j].shape) else {
                continue;
            };
            if !(bodies[i].is_dynamic() || bodies[j].is_dynamic()) {
                continue;
            }
            let d = proximity(a, &pose(i), b, &pose(j)).distance;
            deepest = deepest.max(-d);
        }
    }
    deepest
}

/// Runs `overlap_recovery`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("overlap_recovery")?;
    let mut report = CaseReport::default();
    let rows_of_boxes = 10.0;
    let push = run.settings.push_out_speed;
    let g = 10.0;
    let separation_time = 1.0;
    let fastest = run
        .trace
        .samples
        .iter()
        .filter(|s| s.t <= separation_time)
        .flat_map(|s| s.states.iter().map(|x| x.velocity.norm()))
        .fold(0.0, f64::max);
    let start = deepest_overlap(&run, &run.trace.samples[0].states);
    let end = deepest_overlap(&run, &run.trace.last().expect("samples").states);
    let bodies = run.world.bodies().iter().filter(|b| b.is_dynamic()).count();
    // The most a contact can carry: every box's weight on one point, on a
    // 30 Hz spring between two unit boxes.
    let heaviest = point_compression(
        bodies as f64 * g,
        inverse_point_mass((1.0, 6.0), 0.5, (1.0, 6.0), 0.5),
        run.omega(false),
    );
    let mut rows = run.sink("overlap_recovery", &mut report.rows);
    rows.at_most(
        RowKind::Validation,
        "fastest_while_separating",
        fastest,
        0.0,
        rows_of_boxes * push + g * separation_time,
        format!(
            "the largest body speed in the first {separation_time} s: each contact pushes its pair \
             apart at no more than the push-out speed ({push} m/s) relative to each other, so a \
             box ten contacts above the ground moves at most 10 × {push} m/s, plus g t of fall"
        ),
    );
    rows.at_most(
        RowKind::Validation,
        "deepest_overlap_at_end",
        end,
        0.0,
        heaviest,
        format!(
            "the deepest overlap of any pair after {} s (it was {start:.3} m at the start): \
             separated down to static compressions, each at most that of a point carrying the \
             whole pile's weight on a 30 Hz spring, {heaviest:.4} m",
            run.scene.duration()
        ),
    );
    report.notes.push(format!(
        "`overlap_recovery`: deepest overlap {start:.3} m at the start, {end:.2e} m after {} s; \
         fastest body {fastest:.2} m/s while separating.",
        run.scene.duration()
    ));
    Ok(report)
}
