//! `conveyor` (issue 17): a box set at rest on a belt whose surface moves
//! at u (the belt's `tangent_speed`, Box2D v3's) is dragged by kinetic
//! friction at μ g until it moves with the belt: it reaches u at
//! T = u/(μ g), having slid d = u²/(2 μ g), then rides at u.
//!
//! Under the soft step the box, set exactly on the belt, gets a normal
//! impulse of m g h in every substep (the contact stops what gravity added:
//! nothing to push out), so the relax pass's friction, clamped to μ m g h,
//! adds exactly μ g h to its speed each substep until the target speed u
//! is reached within a substep. Positions follow symplectic Euler,
//! x_n = μ g h² n(n+1)/2: ahead of the continuous d by μ g T h/2.

use crate::row::RowKind;
use super::soft_step_common::SoftRun;
use super::{Case, CaseReport};
use anyhow::Result;

/// The box on the belt.
pub const CASE: Case = Case {
    scenes: &["conveyor"],
    ..Case::new(
        "conveyor",
        "Soft step: a box on a conveyor belt reaches the belt's speed after u/(mu g), sliding u²/(2 mu g)",
        run,
    )
};

/// Runs `conveyor`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("conveyor")?;
    let boxed = run.body("box")?;
    let (u, mu, g) = (2.0, 0.5, 10.0);
    let dt = run.scene.dt();
    let h = run.substep();
    let t_reach = u / (mu * g);
    let slide = u * u / (2.0 * mu * g);
    let x0 = run.trace.samples[0].states[boxed].position.x;
    // The first sample at which the box moves with the belt: sliding, it
    // gains μ g h per substep, so a step end still sliding is at least
    // that short of u; one within it has caught up.
    let caught = mu * g * h;
    let reached = run
        .trace
        .samples
        .iter()
        .find(|s| (s.states[boxed].velocity.x - u).abs() < caught)
        .map(|s| s.t);
    let mut report = CaseReport::default();
    let mut rows = run.sink("conveyor", &mut report.rows);
    let seen = reached.unwrap_or(f64::NAN);
    rows.within(
        RowKind::Validation,
        "time_to_belt_speed",
        seen,
        t_reach + 0.5 * dt,
        0.5 * dt + 1e-9,
        format!(
            "validation against the closed form u/(μ g) = {t_reach:.6} s (u = 2 m/s, μ = \
             √(0.5 · 0.5) = 0.5): the first step end at which the box moves at u (within \
             μ g h, one substep's gain while sliding), in [T, T + dt] since steps are sampled \
             at their ends (T = 0.4 s is a step end here: 1e-9 s for its rounding)"
        ),
    );
    // Where the box is at the step end that first shows it at u: the slide
    // to T, plus riding at u for the rest of that step.
    let at = |t: f64| {
        run.trace
            .samples
            .iter()
            .find(|s| (s.t - t).abs() < 1e-9)
            .map(|s| s.states[boxed].position.x - x0)
    };
    let travelled = reached.and_then(at).unwrap_or(f64::NAN);
    let expected = slide + u * (seen - t_reach);
    rows.within(
        RowKind::Validation,
        "distance_at_belt_speed",
        travelled,
        expected,
        0.5 * mu * g * t_reach * h + u * h,
        format!(
            "validation against the closed form u²/(2 μ g) = {slide:.6} m slid until T, \
             plus u (t − T) ridden to the step end t that showed it: {expected:.6} m. \
             Tolerance μ g T h/2 + u h (symplectic Euler's lead over the continuous slide, \
             plus the substep in which the speed reaches u)"
        ),
    );
    let last = run.trace.last().expect("samples");

    rows.within(
        RowKind::Criterion,
        "riding_speed",
        last.states[boxed].velocity.x,
        u,
        1e-6,
        "criterion: after T the box rides at the belt's speed u. Static friction holds its \
         contact points at u; its centre differs by the turn sliding gave the box (friction \
         acts below the centre), which the over-damped contacts then remove: at 1 s its \
         speed is within 1e-6 m/s of u",
    );
    Ok(report)
}
