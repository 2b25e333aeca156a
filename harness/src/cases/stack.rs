//! `stack` (Solver2D's vertical stack, `docs/soft_step.md#behaviour-scenes`):
//! 15 boxes of 1 m, each shifted sideways by up to ±0.01 m, friction 0.3,
//! under the soft-step model at its defaults for 10 s. It must stand, and
//! its top sinks by the sum of its contacts' static compressions.

use super::soft_step_common::{SoftRun, inverse_point_mass, point_compression};
use super::{Case, CaseReport, Headline};
use crate::row::RowKind;
use anyhow::Result;

/// The vertical stack.
pub const CASE: Case = Case {
    scenes: &["stack"],
    headline: &[Headline::new("top_sink", "soft_step")],
    ..Case::new(
        "stack",
        "Soft step: a stack of 15 boxes (±0.01 m jitter, mu 0.3) stands for 10 s",
        run,
    )
};

/// Runs `stack`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("stack")?;
    let mut report = CaseReport::default();
    let n = 15;
    let ids: Vec<usize> = (0..n)
        .map(|k| run.body(&format!("stack_{k}")))
        .collect::<Result<_>>()?;
    let last = run.trace.last().expect("samples");
    let first = &run.trace.samples[0];
    let (m, g) = (1.0, 10.0);
    // A unit box: 1/m = 1 /kg, 1/I = 6 /(kg·m²), arms ±0.5 m across the
    // normal. Each contact's two points share its load (the weight above):
    // compression load/2 × (1/m_i)/ω² per point, the same at both to first
    // order in the tilt, so the top sinks by their sum.
    let unit = (1.0 / m, 6.0 / m);
    let ground = point_compression(
        0.5 * n as f64 * m * g,
        inverse_point_mass((0.0, 0.0), 0.0, unit, 0.5),
        run.omega(true),
    );
    let between: f64 = (1..n)
        .map(|k| {
            point_compression(
                0.5 * (n - k) as f64 * m * g,
                inverse_point_mass(unit, 0.5, unit, 0.5),
                run.omega(false),
            )
        })
        .sum();
    let expected = ground + between;
    let top = ids[n - 1];
    let sink = first.states[top].position.y - last.states[top].position.y;
    let jitter = 0.01;
    let mut rows = run.sink("stack", &mut report.rows);
    rows.within(
        RowKind::Validation,
        "top_sink",
        sink,
        expected,
        4.0 * jitter * expected,
        format!(
            "the sum of the 15 contacts' static compressions, (load/2)(1/m_i)/ω² per point \
             (30 Hz between boxes, 60 Hz on the ground, 1/m_i = 5 and 2.5 /kg for arms of \
             0.5 m): {expected:.6} m. The jitter moves a contact's arms by up to ±0.01 m, \
             changing 1/m_i (quadratic in the arm) by up to 4 × 0.01/1 relative: tolerance \
             4 % of the sum"
        ),
    );
    // Standing: every box's centre stays over the face of the one below
    // (half a box to either side of its centre), the ground's for the first.
    let worst = (1..n)
        .map(|k| (last.states[ids[k]].position.x - last.states[ids[k - 1]].position.x).abs())
        .fold(last.states[ids[0]].position.x.abs(), f64::max);
    rows.at_most(
        RowKind::Criterion,
        "largest_offset",
        worst,
        0.0,
        0.5,
        "the largest sideways offset of a box from the one below (or the first from the \
         ground's middle) after 10 s: a box whose centre passes the edge of its support \
         topples, so the stack stands iff every offset stays under half a box, 0.5 m",
    );
    let sway = run
        .trace
        .samples
        .iter()
        .map(|s| (s.states[top].position.x - first.states[top].position.x).abs())
        .fold(0.0, f64::max);
    report.notes.push(format!(
        "`stack`: the top box sank {sink:.6} m (the compressions' sum {expected:.6} m) and \
         swayed sideways by up to {sway:.4} m over 10 s, moving at {:.2e} m/s at the end \
         (the benchmark report measures the other engines on its stacks).",
        run.fastest_at_end()
    ));
    Ok(report)
}
