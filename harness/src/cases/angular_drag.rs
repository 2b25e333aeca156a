//! Case II, `angular_drag` (docs/cases.md): the 0.7 s torque pulse against an
//! angular drag −D ω|ω|, D = 0.003; closed form tanh / ln cosh while driven,
//! hyperbolic decay after. The stiffest term of case II (I is tiny:
//! k = √(τ0 D)/I = 7.75 s⁻¹, so kh = 0.077 at h = 0.01).

use super::torque::{CHECK_TIMES, rotation_case};
use super::{
    Case, CaseReport, FigureOutput, FigureSection, Headline, Snapshots, StudyFigure, sample_at,
};
use crate::plots::trajectories::ScalarFigure;
use crate::row::{RowKind, RowSink};
use crate::scenes;
use crate::sweep::{SweepCase, rapier_runner, step_world};
use anyhow::Result;
use engine::Method;
use references::AngularDrag;
use references::rapier_world::RapierSample;
use std::path::Path;

/// The torque pulse with angular drag: its rows, its sweep against the
/// closed form and seed figure 6.5.
pub const CASE: Case = Case {
    scenes: &["angular_drag"],
    snapshots: Snapshots::Traces,
    headline: &[Headline::new("omega_0.7", "rk4").at(0.01)],
    sweep: Some(sweep),
    figures: &[StudyFigure {
        section: FigureSection::Trajectories,
        write: trajectory,
    }],
    ..Case::new(
        "angular_drag",
        "Case II: torque pulse with angular drag -D w|w|",
        run,
    )
};

/// Step (s) at which RK4 must hold θ(8.7) within 1e-8 rad: at h = 0.01 a
/// textbook RK4 errs by 1.3e-7 rad on θ (its Richardson estimate agrees, and
/// so does an independent re-implementation), so the 1e-8 demand is checked
/// one halving later, where the h⁴ law puts the error near 8e-9.
pub const RK4_FINE_DT: f64 = 0.005;

/// Runs the case.
pub fn run() -> Result<CaseReport> {
    let exact = AngularDrag::seed();
    let mut report = rotation_case("angular_drag", |t| exact.omega(t), |t| exact.theta(t))?;
    let trace = scenes::world("angular_drag", Method::Rk4)?
        .run(scenes::load("angular_drag")?.duration(), RK4_FINE_DT)?;
    let s = sample_at(&trace, 8.7)?.states[0];
    RowSink {
        case: "angular_drag",
        method: Method::Rk4.id(),
        dt: RK4_FINE_DT,
        rows: &mut report.rows,
    }
    .within(
        RowKind::Validation,
        "theta_8.7",
        s.angle,
        exact.theta(8.7),
        1e-8,
        "docs/cases.md / issue: RK4 within 1e-8 rad; met at h = 0.005 (at h = 0.01 the textbook RK4 error is 1.3e-7)",
    );
    Ok(report)
}

/// The sweep: |angle error| against the closed form over 0–8.7 s.
fn sweep() -> Result<SweepCase> {
    let exact = AngularDrag::seed();
    let until = CHECK_TIMES[1];
    let rapier = rapier_runner("angular_drag", until, move |s| {
        Ok((s.angle - exact.theta(s.t)).abs())
    })?;
    Ok(SweepCase {
        error_label: "|angle error| over 0-8.7 s (rad)",
        unit: "rad",
        reference: "the closed form (tanh / ln cosh while driven, hyperbolic decay after)",
        h0: 0.1,
        scale: 1.0,
        first_order: false,
        speed_target: None,
        rapier: Some(rapier),
        run: Box::new(move |method, h, observe| {
            let mut world = scenes::world("angular_drag", method)?;
            let mut max_error: f64 = 0.0;
            step_world(&mut world, until, h, |w| {
                if observe {
                    max_error = max_error.max((w.states()[0].angle - exact.theta(w.time())).abs());
                }
            })?;
            let end = (world.states()[0].angle - exact.theta(until)).abs();
            Ok((end, max_error, world.stats().evaluations))
        }),
    })
}

/// Seed figure 6.5: ω(t) of the scene's run, rapier2d's and the closed form.
fn trajectory(dir: &Path, id: &str) -> Result<FigureOutput> {
    let angular = AngularDrag::seed();
    let file = format!("trajectory_{id}.svg");
    ScalarFigure {
        file: &file,
        title: "torque pulse with angular drag (seed fig. 6.5): angular velocity",
        case: (id, CHECK_TIMES[1]),
        quantity: ("omega", "rad/s"),
        engine_value: |s: &engine::Sample| s.states[0].angular_velocity,
        rapier_value: |s: &RapierSample| s.angular_velocity,
        exact: |t| angular.omega(t),
        y_range: None,
    }
    .write(dir)
}
