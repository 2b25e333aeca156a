//! `rolling_resistance` (issue 17): a disc rolling on flat ground with
//! Box2D v3's rolling resistance decelerates at the rate Box2D's model
//! predicts.
//!
//! The model (Box2D v3's `contact_solver.c`, written anew here): each
//! substep, after friction, an angular impulse opposes the pair's relative
//! rotation, clamped to c r λ_n, with c the larger rolling-resistance
//! coefficient, r the larger rounding radius (the disc's; a box has none)
//! and λ_n the pair's normal impulse (m g h at rest). About the contact
//! point the normal and friction impulses have no moment, so the disc's
//! angular momentum about it, (I + m r²) v / r, drops by c r m g h per
//! substep: a = c m g r² / (I + m r²) = (2/3) c g for a disc
//! (I = m r²/2).
//!
//! Measured from the velocity between 0.5 s and 2 s (the disc stops near
//! 3 s). Each substep's rolling impulse leaves the contact point slipping
//! by at most r Δω = r c r m g h / I = 2 c g h until the next friction
//! solve, so v at either end is off the rolling value by at most that;
//! the tolerance is twice it over the interval.

use crate::row::RowKind;
use super::soft_step_common::SoftRun;
use super::{Case, CaseReport};
use anyhow::Result;

/// The rolling disc.
pub const CASE: Case = Case {
    scenes: &["rolling_resistance"],
    ..Case::new(
        "rolling_resistance",
        "Soft step: a disc with rolling resistance c decelerates at (2/3) c g (Box2D v3's model)",
        run,
    )
};

/// Runs `rolling_resistance`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("rolling_resistance")?;
    let disc = run.body("disc")?;
    let (c, g) = (0.2, 10.0);
    let h = run.substep();
    let predicted = 2.0 / 3.0 * c * g;
    let (t1, t2) = (0.5, 2.0);
    let s1 = crate::cases::sample_at(&run.trace, t1)?;
    let s2 = crate::cases::sample_at(&run.trace, t2)?;
    let measured = -(s2.states[disc].velocity.x - s1.states[disc].velocity.x) / (t2 - t1);
    let slip = 2.0 * c * g * h;
    let mut report = CaseReport::default();
    let mut rows = run.sink("rolling_resistance", &mut report.rows);
    rows.within(
        RowKind::Validation,
        "deceleration",
        measured,
        predicted,
        2.0 * slip / (t2 - t1),
        format!(
            "validation against Box2D v3's model in closed form: a = c m g r² / (I + m r²) = \
             (2/3) c g = {predicted:.6} m/s² (c = 0.2, disc of radius 0.5 m), from the \
             velocity at 0.5 s and 2 s. Tolerance: the slip a rolling impulse leaves until the \
             next friction solve, 2 c g h = {slip:.5} m/s, at both ends, over 1.5 s"
        ),
    );
    let w = s2.states[disc].angular_velocity;
    let v = s2.states[disc].velocity.x;
    rows.within(
        RowKind::Criterion,
        "rolling_at_2s",
        v + w * 0.5,
        0.0,
        slip,
        "validation (criterion): the disc still rolls without slipping at 2 s, \
         v + ω r = 0 within the slip one rolling impulse leaves, 2 c g h",
    );
    Ok(report)
}
