//! `filters` (issue 17): Box2D's collision filter rules, on four pairs of
//! 1 m boxes, one dropped from 0.5 m onto the other (`scenes/filters.toml`):
//! a shared negative group never collides, a category outside the other's
//! mask is refused, a shared positive group always collides whatever the
//! masks, default filters collide. A pair that must not collide passes
//! through: its upper box lands on the ground, its centre at 0.5 m like the
//! lower one's; a pair that collides rests stacked, the upper centre at
//! 1.5 m. Both less the soft contacts' static compressions (a fraction of a
//! millimetre, `soft_step_common::point_compression`).

use crate::row::RowKind;
use super::soft_step_common::{SoftRun, inverse_point_mass, point_compression};
use super::{Case, CaseReport};
use anyhow::Result;

/// The four pairs.
pub const CASE: Case = Case {
    scenes: &["filters"],
    ..Case::new(
        "filters",
        "Soft step: pairs whose filters refuse each other pass through; the others rest stacked",
        run,
    )
};

/// Runs `filters`.
pub fn run() -> Result<CaseReport> {
    let run = SoftRun::new("filters")?;
    let (m, g) = (1.0, 10.0);
    let unit = (1.0 / m, 6.0 / m);
    // Two points per contact share its load.
    let on_ground = |load: f64| {
        point_compression(
            0.5 * load,
            inverse_point_mass((0.0, 0.0), 0.0, unit, 0.5),
            run.omega(true),
        )
    };
    let between = point_compression(
        0.5 * m * g,
        inverse_point_mass(unit, 0.5, unit, 0.5),
        run.omega(false),
    );
    let last = run.trace.last().expect("samples");
    let mut report = CaseReport::default();
    let cases = [
        ("never", false, "both in group −1: a shared negative group never collides"),
        (
            "masked",
            false,
            "the lower box's category 2 is outside the upper box's mask 1",
        ),
        (
            "always",
            true,
            "both in group 7 with masks that refuse each other: a shared positive group \
             always collides",
        ),
        ("plain", true, "default filters collide"),
    ];
    let mut found = Vec::new();
    for (name, collide, why) in cases {
        found.push((
            name,
            collide,
            why,
            run.body(&format!("{name}_upper"))?,
            run.body(&format!("{name}_lower"))?,
        ));
    }
    let mut rows = run.sink("filters", &mut report.rows);
    for (name, collide, why, upper, lower) in found {
        let (expected, sink) = if collide {
            let sink = on_ground(2.0 * m * g) + between;
            (1.5 - sink, sink)
        } else {
            let sink = on_ground(m * g);
            (0.5 - sink, sink)
        };
        rows.within(
            RowKind::Validation,
            &format!("{name}_upper_height"),
            last.states[upper].position.y,
            expected,
            sink,
            format!(
                "validation against the closed form ({why}): the upper box {} after 2 s, its \
                 centre at {} m less the static compression of the soft contacts below it, \
                 {sink:.2e} m: {expected:.6} m. Tolerance: that compression again (passing \
                 through and resting differ by 1 m; this checks which happened and that the \
                 box settled)",
                if collide {
                    "rests on the lower one"
                } else {
                    "passed through the lower one and rests on the ground"
                },
                if collide { 1.5 } else { 0.5 },
            ),
        );
        let sink_lower = if collide {
            on_ground(2.0 * m * g)
        } else {
            on_ground(m * g)
        };
        rows.within(
            RowKind::Validation,
            &format!("{name}_lower_height"),
            last.states[lower].position.y,
            0.5 - sink_lower,
            sink_lower,
            format!(
                "validation against the closed form: the lower box rests on the ground, its \
                 centre at 0.5 m less its contact's compression under {} box(es), \
                 {sink_lower:.2e} m (tolerance: that compression again)",
                if collide { 2 } else { 1 }
            ),
        );
    }
    Ok(report)
}
