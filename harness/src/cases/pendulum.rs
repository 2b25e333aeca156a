//! `pendulum` (`docs/cases.md#pendulum`): six pendulums of 1 m released at
//! rest from 10°, 90° and 170° (`scenes/pendulum.toml`): a circle held at
//! its centre by a rigid distance joint (a point mass on a massless rod,
//! the closed form's own case) and the same circle pinned by a revolute
//! joint 1 m from its centre (a physical pendulum of the disc), each
//! against T = 4 √(L/g) K(sin(θ0/2)) under the soft step at its defaults,
//! with rapier2d and Box2D on the same file. The rows and their
//! tolerances are [`pendulum_swing`]'s; this case adds the exact model's
//! rows ([`pendulum_exact`]: the same pendulums with their joints as
//! constraints of the equations of motion, the period at RK4's error, the
//! observed order of every method, the drift; and the acceptance scene
//! `scenes/pendulum_exact.toml`, in the full run only) and the two charts
//! of [`pendulum_charts`]: the period error against wall time (every
//! engine, 1 to 32 substeps) and the constraint drift against the step.

use super::pendulum_swing::{self, Size};
use super::{Case, CaseReport, Headline, Snapshots, pendulum_charts, pendulum_exact};
use anyhow::Result;

/// Six pendulums from 10°, 90° and 170°.
pub const CASE: Case = Case {
    scenes: &["pendulum", "pendulum_exact"],
    snapshots: Snapshots::HarnessOnly(
        "100 periods in three engines and the charts' sweeps take seconds in a release build; \
         harness/tests/joint_cases.rs checks a reduced run (10 periods, the soft step alone) \
         with the same rows",
    ),
    headline: &[Headline::new("period_first_rod_90", "soft_step")],
    ..Case::new(
        "pendulum",
        "Joints: pendulums of 1 m from 10°, 90° and 170° on a rod and on a pin against the elliptic-integral period",
        run,
    )
};

/// Runs `pendulum`.
pub fn run() -> Result<CaseReport> {
    run_sized(Size::FULL)
}

/// Runs `pendulum` at `size` (the charts only at [`Size::FULL`]).
pub fn run_sized(size: Size) -> Result<CaseReport> {
    let (mut report, js, specs) = pendulum_swing::run_case("pendulum", "pendulum", size)?;
    if size.charts {
        pendulum_exact::rows(&js.scene, &specs, &mut report)?;
    }
    if size.charts {
        report
            .figures
            .push(pendulum_charts::work_precision(&js, &specs)?);
        report
            .figures
            .push(pendulum_charts::drift_against_step(&js, &specs)?);
    }
    Ok(report)
}
