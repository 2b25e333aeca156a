//! `mass_ratio` (Solver2D's high mass ratio,
//! `docs/soft_step.md#behaviour-scenes`): a 4 m × 1 m box of 100 kg resting
//! on two 1 kg boxes, under the soft-step model. A soft contact's stiffness
//! is set per point by its effective mass, so the heavy box compresses its
//! supports by the same static formula as any load: centimetres, not
//! through them.

use super::soft_step_common::{SoftRun, inverse_point_mass, point_compression};
use super::{Case, CaseReport, Headline};
use crate::row::RowKind;
use anyhow::Result;

/// The heavy box on two light ones.
pub const CASE: Case = Case {
    scenes: &["mass_ratio"],
    headline: &[Headline::new("heavy_descent", "soft_step")],
    ..Case::new(
        "mass_ratio",
        "Soft step: a box 100 times heavier rests on two small ones without sinking through",
        run,
    )
};

/// Runs `mass_ratio`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("mass_ratio")?;
    let mut report = CaseReport::default();
    let heavy = run.body("heavy")?;
    let g = 10.0;
    let (m_small, m_heavy) = (1.0, 100.0);
    let small = (1.0 / m_small, 12.0 / (m_small * 2.0)); // 1 × 1 m: I = m/6
    let big = (1.0 / m_heavy, 12.0 / (m_heavy * 17.0)); // 4 × 1 m: I = 17 m/12
    // The heavy box's points sit at x = ±1 and ±2 m from its centre (the
    // small boxes span 1 to 2 m on either side), at ±0.5 m on the small
    // ones. The heavy box translates without turning (symmetry), so all four
    // points compress alike: loads in proportion to 1/(1/m_i), summing to
    // 500 N per small box.
    let inner = inverse_point_mass(small, 0.5, big, 1.0);
    let outer = inverse_point_mass(small, 0.5, big, 2.0);
    let load_inner = 0.5 * m_heavy * g * outer / (inner + outer);
    let top = point_compression(load_inner, inner, run.omega(false));
    let ground = point_compression(
        0.5 * (0.5 * m_heavy + m_small) * g,
        inverse_point_mass((0.0, 0.0), 0.0, small, 0.5),
        run.omega(true),
    );
    let expected = top + ground;
    let start = run.trace.samples[0].states[heavy].position.y;
    let end = run.trace.last().expect("samples").states[heavy].position.y;
    let spread = top * (outer - inner) / inner;
    let mut rows = run.sink("mass_ratio", &mut report.rows);
    rows.within(
        RowKind::Validation,
        "heavy_descent",
        start - end,
        expected,
        spread,
        format!(
            "the heavy box's descent: its points' compression on the small boxes (30 Hz, \
             {top:.6} m) plus the small boxes' on the ground (60 Hz, {ground:.6} m) = \
             {expected:.6} m. Tolerance: the spread of the four points' effective masses \
             ({:.2} % — the small boxes may tilt by that much of the compression)",
            100.0 * (outer - inner) / inner
        ),
    );
    rows.at_most(
        RowKind::Criterion,
        "fastest_at_end",
        run.fastest_at_end(),
        0.0,
        0.01,
        "the pile is at rest after 5 s: largest body speed at most 0.01 m/s (the pyramid's \
         criterion)",
    );
    Ok(report)
}
