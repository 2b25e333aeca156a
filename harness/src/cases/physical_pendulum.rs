//! `physical_pendulum` (`docs/cases.md#physical_pendulum`): two uniform
//! boxes of 1 m × 0.5 m pinned at a corner by a revolute joint to the
//! world, released at rest from 10° and 90° (`scenes/physical_pendulum.toml`),
//! each against the period of the simple pendulum of equivalent length
//! I_pivot/(m d) = 2 √(b² + h²)/3, the box's moment of inertia about the
//! pivot computed by the references from its vertices
//! (`PhysicalPendulum::polygon`), under the soft step at its defaults,
//! with rapier2d and Box2D on the same file. The rows and their
//! tolerances are the pendulum's ([`super::pendulum_swing`]).

use super::pendulum_swing::{self, Size};
use super::{Case, CaseReport, Headline, Snapshots};
use anyhow::Result;

/// Two boxes pivoted at a corner.
pub const CASE: Case = Case {
    scenes: &["physical_pendulum"],
    snapshots: Snapshots::HarnessOnly(
        "100 periods in three engines take a second in a release build; \
         harness/tests/joint_cases.rs checks a reduced run (10 periods, the soft step alone) \
         with the same rows",
    ),
    headline: &[Headline::new("period_first_box_90", "soft_step")],
    ..Case::new(
        "physical_pendulum",
        "Joints: a 1 m × 0.5 m box pivoted at a corner, from 10° and 90°, against the physical pendulum's period",
        run,
    )
};

/// Runs `physical_pendulum`.
pub fn run() -> Result<CaseReport> {
    run_sized(Size::FULL)
}

/// Runs `physical_pendulum` at `size`.
pub fn run_sized(size: Size) -> Result<CaseReport> {
    let (mut report, _, specs) =
        pendulum_swing::run_case("physical_pendulum", "physical_pendulum", size)?;
    let lengths: Vec<String> = specs
        .iter()
        .map(|p| {
            format!(
                "{}: L_eq = {:.12} m, T(θ0) = {:.12} s",
                p.name,
                p.closed.length,
                p.closed.period()
            )
        })
        .collect();
    report.notes.insert(
        0,
        format!(
            "The closed form: a rigid body about a fixed pivot at d from its centre swings as a \
             simple pendulum of L_eq = I_pivot/(m d), here 2 √(b² + h²)/3 for a b × h box about \
             a corner ({}; docs/cases.md quotes 0.7453559924999299 m, 1.735220743804285 s and \
             2.044252717622318 s).",
            lengths.join("; ")
        ),
    );
    Ok(report)
}
