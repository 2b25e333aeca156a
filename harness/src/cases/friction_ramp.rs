//! `friction_ramp` (Solver2D's friction ramp,
//! `docs/soft_step.md#behaviour-scenes`): five boxes on a 0.25 rad slope
//! with friction 0, 0.1, 0.35, 0.5 and 0.75, under the soft-step model.
//! Coulomb: a box slides iff mu < tan 0.25 = 0.2553, with
//! a = g (sin θ − mu cos θ); the others hold.

use super::soft_step_common::SoftRun;
use super::{Case, CaseReport, Headline};
use crate::cases::collision_common::{CLOSED_FORM_RELATIVE, STILL};
use crate::row::RowKind;
use anyhow::Result;
use nalgebra::Vector2;

/// The friction ramp.
pub const CASE: Case = Case {
    scenes: &["friction_ramp"],
    headline: &[Headline::new("acceleration_mu_0.1", "soft_step")],
    ..Case::new(
        "friction_ramp",
        "Soft step: boxes with mu 0 to 0.75 on a 0.25 rad slope slide or hold as Coulomb says",
        run,
    )
};

/// Runs `friction_ramp`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("friction_ramp")?;
    let mut report = CaseReport::default();
    let (theta, g) = (0.25f64, 10.0);
    let down = Vector2::new(-theta.cos(), -theta.sin());
    let t1 = 1.0;
    let early = crate::cases::sample_at(&run.trace, t1)?;
    let last = run.trace.last().expect("samples");
    let t_end = last.t;
    let mut rows = run.sink("friction_ramp", &mut report.rows);
    for mu in [0.0, 0.1, 0.35, 0.5, 0.75] {
        let b = run.body(&format!("mu_{mu}"))?;
        let slides = mu < theta.tan();
        if slides {
            let a = g * (theta.sin() - mu * theta.cos());
            let measured = (last.states[b].velocity - early.states[b].velocity).dot(&down)
                / (t_end - t1);
            rows.within(
                RowKind::Validation,
                &format!("acceleration_mu_{mu}"),
                measured,
                a,
                CLOSED_FORM_RELATIVE * a.max(1.0),
                format!(
                    "g (sin θ − mu cos θ) = {a:.9} m/s² (mu = {mu} < tan θ): velocity gained \
                     along the slope from 1 s to 3 s over the time. Once the soft contact has \
                     settled each substep adds exactly that times h, so it holds to \
                     round-off; 1e-6 relative"
                ),
            );
        } else {
            let moved = (last.states[b].position - early.states[b].position).norm();
            rows.at_most(
                RowKind::Validation,
                &format!("motion_mu_{mu}"),
                moved,
                0.0,
                STILL,
                format!(
                    "distance moved from 1 s to 3 s: mu = {mu} > tan θ = {:.4}, the relax \
                     pass's friction holds the box within the cone; 1e-9 m",
                    theta.tan()
                ),
            );
        }
    }
    Ok(report)
}
