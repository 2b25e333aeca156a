//! `sensor_gate` (issue 17): a static sensor band detects falling balls at
//! the free-fall times. Four balls of radius r = 0.1 m, dropped from rest
//! with their lowest points d = 0.5, 1, 2 and 3 m above the band's top face,
//! fall through the band (0.2 m thick) to the ground. The sensor must report
//! each ball once entering, when its lowest point reaches the top face, at
//! t = √(2 d / g), and once leaving, when its highest point passes the
//! bottom face, at t = √(2 (d + 0.2 + 2 r) / g), and never push it.
//!
//! When a report can come: the soft step looks for overlaps in its collide
//! stage, at the poses that begin a step, so an overlap that first exists
//! at the end of step n is reported by step n + 1. The time compared is
//! that of the poses that showed it, the reporting step's start. Those
//! poses are the first past the crossing, so they follow it by less than a
//! step; and the substeps' symplectic Euler falls ahead of the exact
//! motion by g t h / 2 in position (x_n = x_0 − g h² n(n+1)/2), reaching a
//! height up to half a substep h early. Window: [t − h/2, t + dt].

use crate::row::RowKind;
use super::soft_step_common::SOFT_STEP;
use super::{Case, CaseReport};
use crate::row::RowSink;
use crate::scenes;
use anyhow::{Context, Result};
use engine::{ContactModel, step_count};

/// The balls through the gate.
pub const CASE: Case = Case {
    scenes: &["sensor_gate"],
    ..Case::new(
        "sensor_gate",
        "Soft step: a sensor band reports falling balls entering and leaving at the free-fall times",
        run,
    )
};

/// Runs `sensor_gate`.
pub fn run() -> Result<CaseReport> {
    let scene = scenes::load("sensor_gate")?;
    let substeps = match scene.contact() {
        Some(ContactModel::SoftStep(s)) => s.substeps,
        _ => anyhow::bail!("sensor_gate: the scene must use the soft step"),
    };
    let mut world = scene.build_world(None)?;
    let dt = scene.dt();
    let h = dt / substeps as f64;
    let g: f64 = 10.0;
    let (radius, band) = (0.1, 0.2);
    let gate = scene.body_id("gate").context("no gate")?;
    let balls: Vec<usize> = (0..4)
        .map(|k| scene.body_id(&format!("ball_{k}")).context("no ball"))
        .collect::<Result<_>>()?;
    let drops: [f64; 4] = [0.5, 1.0, 2.0, 3.0];
    let mut entered: Vec<Vec<f64>> = vec![Vec::new(); balls.len()];
    let mut left: Vec<Vec<f64>> = vec![Vec::new(); balls.len()];
    let mut wrong = 0usize;
    let steps = step_count(scene.duration(), dt)?;
    for _ in 0..steps {
        let start = world.time();
        world.step(dt).context("stepping sensor_gate")?;
        let events = world.step_events()?;
        for (list, out) in [(&events.sensor_began, &mut entered), (&events.sensor_ended, &mut left)] {
            for e in list {
                match balls.iter().position(|&b| b == e.visitor.body) {
                    Some(k) if e.sensor.body == gate => out[k].push(start),
                    _ => wrong += 1,
                }
            }
        }
    }
    let mut report = CaseReport::default();
    let mut rows = RowSink {
        case: "sensor_gate",
        method: SOFT_STEP,
        dt,
        rows: &mut report.rows,
    };
    let window = |exact: f64| (exact - 0.5 * h, exact + dt);
    for (k, &d) in drops.iter().enumerate() {
        for (what, list, fall) in [
            ("enter", &entered[k], d),
            ("leave", &left[k], d + band + 2.0 * radius),
        ] {
            let exact = (2.0 * fall / g).sqrt();
            rows.within(
                RowKind::Criterion,
                &format!("{what}_count_ball_{k}"),
                list.len() as f64,
                1.0,
                0.0,
                format!(
                    "validation (criterion): the sensor reports ball {k} {what}ing once \
                     (exactly one event)"
                ),
            );
            let seen = list.first().copied().unwrap_or(f64::NAN);
            let (lo, hi) = window(exact);
            rows.within(
                RowKind::Validation,
                &format!("{what}_time_ball_{k}"),
                seen,
                0.5 * (lo + hi),
                0.5 * (hi - lo),
                format!(
                    "validation against the closed form √(2·{fall}/g) = {exact:.6} s (the \
                     ball's {} passing the band's {} face after a free fall of {fall} m): the \
                     time of the poses that showed the change, in [t − h/2, t + dt] (a step \
                     late at most, half a substep early at most by symplectic Euler's lead; \
                     see the module docs)",
                    if what == "enter" { "lowest point" } else { "highest point" },
                    if what == "enter" { "top" } else { "bottom" },
                ),
            );
        }
    }
    rows.within(
        RowKind::Criterion,
        "stray_events",
        wrong as f64,
        0.0,
        0.0,
        "criterion: no sensor event names another sensor or visitor (the ground and the \
         gate are both static and never paired)",
    );
    // The balls were not pushed: each lands with the free-fall speed.
    let last = world.states();
    let slowest = balls
        .iter()
        .map(|&b| last[b].position.y)
        .fold(f64::INFINITY, f64::min);
    rows.at_least(
        RowKind::Criterion,
        "landed",
        slowest,
        radius - 0.005,
        0.0,
        "criterion: every ball fell through the sensor and rests on the ground (its centre \
         within 5 mm of r = 0.1 m above it: the soft contact's sink under a ball's weight is \
         under 0.1 mm), so the sensor pushed nothing",
    );
    Ok(report)
}
