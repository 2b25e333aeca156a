//! Case II, `projectile_drag` (seed Table 6.2, docs/cases.md): the projectile with
//! quadratic drag D = 0.003 kg/m. No closed form: the expected values are
//! docs/cases.md's 40-digit reference, and the trajectory reference is an
//! independent DOP853 solve (`references::DragReference`).

use super::projectile::{EVENT_CHECKS, ballistic_trace, events};
use super::{
    Case, CaseReport, FigureOutput, FigureSection, Headline, Snapshots, StudyFigure, all_methods,
    dp_global_bound, dp_reason, sample_at,
};
use crate::plots::trajectories::{error_panel, runs};
use crate::plots::{Chart, REFERENCE_ALT, Series, method_style, save_svg};
use crate::row::{RowKind, RowSink};
use crate::scenes;
use crate::sweep::{SweepCase, rapier_runner, step_world};
use crate::tolerance::{from_order, from_order_reason, half_unit};
use anyhow::Result;
use engine::Method;
use references::drag_reference_values as cases_md;
use references::{DragReference, Projectile};
use std::path::Path;

/// The drag projectile: its rows against docs/cases.md's reference, the sweep
/// against the DOP853 reference (with the speed comparison against
/// rapier2d-f64), seed figures 6.2 and 6.4, and the bench.
pub const CASE: Case = Case {
    scenes: &["projectile_drag"],
    snapshots: Snapshots::Traces,
    headline: &[
        Headline::new("landing_time", "dormand_prince").at(0.01),
        Headline::new("position_error_t5", "rk4").at(0.2),
        Headline::new("order", "rk4"),
    ],
    sweep: Some(sweep),
    figures: &[StudyFigure {
        section: FigureSection::Trajectories,
        write: trajectory,
    }],
    bench: true,
    ..Case::new(
        "projectile_drag",
        "Case II: projectile with quadratic drag (seed Table 6.2)",
        run,
    )
};

/// Accuracy at which the report compares the run time of the engine and of
/// rapier2d-f64 (m of max position error over 0–5 s).
pub const TARGET_ERROR: f64 = 1e-6;

/// End of the swept run (s), where docs/cases.md gives the state.
const SWEEP_UNTIL: f64 = 5.0;

/// Runs the case.
pub fn run() -> Result<CaseReport> {
    let scene = scenes::load("projectile_drag")?;
    let (dt, duration) = (scene.dt(), scene.duration());
    let reference = DragReference::compute()?;
    let expected = [
        cases_md::LANDING_TIME,
        cases_md::RANGE,
        cases_md::APEX_HEIGHT,
        cases_md::APEX_TIME,
    ];
    // docs/cases.md prints 12, 10, 11 and 12 decimals.
    let quoted = [half_unit(12), half_unit(10), half_unit(11), half_unit(12)];
    let state_expected = [
        cases_md::STATE_X,
        cases_md::STATE_Y,
        cases_md::STATE_VX,
        cases_md::STATE_VY,
    ];
    let state_quoted = [half_unit(10), half_unit(11), half_unit(11), half_unit(11)];
    let state_checks = ["x_t5", "y_t5", "vx_t5", "vy_t5"];
    let mut report = CaseReport::default();
    for method in all_methods() {
        let trace = scenes::world("projectile_drag", method)?.run(duration, dt)?;
        let found = events(&trace)?;
        let at5 = sample_at(&trace, cases_md::STATE_TIME)?.states[0];
        let state = [
            at5.position.x,
            at5.position.y,
            at5.velocity.x,
            at5.velocity.y,
        ];
        let mut sink = RowSink {
            case: "projectile_drag",
            method: method.id(),
            dt,
            rows: &mut report.rows,
        };
        let checks = EVENT_CHECKS.iter().chain(&state_checks);
        let values = found.iter().chain(&state);
        let wants = expected.iter().chain(&state_expected);
        let quotes = quoted.iter().chain(&state_quoted);
        if method.is_adaptive() {
            for (((check, &value), &want), &q) in checks.zip(values).zip(wants).zip(quotes) {
                let bound = dp_global_bound(trace.stats.steps, want.abs()) + q;
                sink.within(
                    RowKind::Validation,
                    check,
                    value,
                    want,
                    bound,
                    format!(
                        "{}; + half a unit of docs/cases.md's last digit",
                        dp_reason(trace.stats.steps)
                    ),
                );
            }
        } else {
            let half_trace = scenes::world("projectile_drag", method)?.run(duration, dt / 2.0)?;
            let half_events = events(&half_trace)?;
            let h5 = sample_at(&half_trace, cases_md::STATE_TIME)?.states[0];
            let half_state = [h5.position.x, h5.position.y, h5.velocity.x, h5.velocity.y];
            let halves = half_events.iter().chain(&half_state);
            for ((((check, &value), &value_half), &want), &q) in
                checks.zip(values).zip(halves).zip(wants).zip(quotes)
            {
                let tol = from_order(value, value_half, method.order(), q);
                sink.within(
                    RowKind::Consistency,
                    check,
                    value,
                    want,
                    tol,
                    format!(
                        "{}, i.e. half a unit of docs/cases.md's last digit",
                        from_order_reason(method.order(), q)
                    ),
                );
            }
        }
        if method == Method::Rk4 {
            let coarse = scenes::world("projectile_drag", method)?.run(duration, 0.2)?;
            let s = sample_at(&coarse, cases_md::STATE_TIME)?.states[0];
            let error = (s.position.x - cases_md::STATE_X).hypot(s.position.y - cases_md::STATE_Y);
            let mut coarse_sink = RowSink {
                case: "projectile_drag",
                method: method.id(),
                dt: 0.2,
                rows: &mut report.rows,
            };
            coarse_sink.within(
                RowKind::Validation,
                "position_error_t5",
                error,
                cases_md::RK4_H02_POSITION_ERROR_AT_5_S,
                half_unit(5),
                "docs/cases.md: RK4 at h = 0.2 errs by 4.5e-4 m at t = 5 s (two digits: +/- 5e-6)",
            );
        }
        report.traces.push(ballistic_trace(method, dt, &trace, |t| {
            reference.state_at(t).ok().map(|s| [s[0], s[1]])
        }));
    }
    Ok(report)
}

/// The sweep: |position error| against the DOP853 reference over 0–5 s.
fn sweep() -> Result<SweepCase> {
    let reference = std::rc::Rc::new(DragReference::compute()?);
    let for_rapier = reference.clone();
    let rapier = rapier_runner("projectile_drag", SWEEP_UNTIL, move |s| {
        let r = for_rapier.state_at(s.t)?;
        Ok((s.position[0] - r[0]).hypot(s.position[1] - r[1]))
    })?;
    Ok(SweepCase {
        error_label: "|position error| over 0-5 s (m)",
        unit: "m",
        reference: "an independent DOP853 solve (references::DragReference)",
        h0: 0.2,
        scale: 100.0,
        first_order: false,
        speed_target: Some(TARGET_ERROR),
        rapier: Some(rapier),
        run: Box::new(move |method, h, observe| {
            let mut world = scenes::world("projectile_drag", method)?;
            let mut max_error: f64 = 0.0;
            let mut failure = None;
            step_world(&mut world, SWEEP_UNTIL, h, |w| {
                if observe {
                    match reference.state_at(w.time()) {
                        Ok(r) => {
                            let p = w.states()[0].position;
                            max_error = max_error.max((p.x - r[0]).hypot(p.y - r[1]));
                        }
                        Err(e) => failure = Some(e),
                    }
                }
            })?;
            if let Some(e) = failure {
                return Err(e.into());
            }
            let p = world.states()[0].position;
            let r = reference.state_at(SWEEP_UNTIL)?;
            Ok((
                (p.x - r[0]).hypot(p.y - r[1]),
                max_error,
                world.stats().evaluations,
            ))
        }),
    })
}

/// Seed figures 6.2 and 6.4: the path with and without drag, then the
/// position error of the drag run against the DOP853 reference.
fn trajectory(dir: &Path, id: &str) -> Result<FigureOutput> {
    let file = format!("trajectory_{id}.svg");
    let reference = DragReference::compute()?;
    let vacuum = Projectile::seed();
    let until = reference.landing_time();
    let (method, trace, rapier) = runs(id, 5.8)?;
    let dense: Vec<(f64, f64)> = reference.step_points().map(|(_, s)| (s[0], s[1])).collect();
    let parabola: Vec<(f64, f64)> = (0..=200)
        .map(|i| vacuum.position(vacuum.landing_time() * i as f64 / 200.0))
        .map(|p| (p[0], p[1]))
        .collect();
    let engine: Vec<(f64, f64)> = trace
        .samples
        .iter()
        .map(|s| (s.states[0].position.x, s.states[0].position.y))
        .collect();
    let rap: Vec<(f64, f64)> = rapier
        .iter()
        .map(|s| (s.position[0], s.position[1]))
        .collect();
    let path = Chart {
        title: "projectile (seed figs. 6.2, 6.4): path with and without drag".into(),
        x_label: "x (m)".into(),
        y_label: "y (m)".into(),
        series: vec![
            Series::reference("vacuum parabola (closed form)", parabola).styled(REFERENCE_ALT),
            Series::reference("drag reference (DOP853)", dense),
            Series::new(format!("engine {method}"), method_style(&method), engine).line(),
            Series::new("rapier2d (4 substeps)", method_style("rapier2d_4sub"), rap).line(),
        ],
        y_range: Some((0.0, 95.0)),
        ..Chart::default()
    };
    let err_engine: Vec<(f64, f64)> = trace
        .samples
        .iter()
        .filter(|s| s.t <= until)
        .filter_map(|s| {
            let r = reference.state_at(s.t).ok()?;
            Some((
                s.t,
                (s.states[0].position.x - r[0]).hypot(s.states[0].position.y - r[1]),
            ))
        })
        .collect();
    let err_rapier: Vec<(f64, f64)> = rapier
        .iter()
        .filter_map(|s| {
            let r = reference.state_at(s.t).ok()?;
            Some((s.t, (s.position[0] - r[0]).hypot(s.position[1] - r[1])))
        })
        .collect();
    let errors = error_panel(
        "drag projectile: position error against DOP853",
        "m",
        vec![
            Series::new(
                format!("engine {method}"),
                method_style(&method),
                err_engine,
            )
            .line(),
            Series::new(
                "rapier2d (4 substeps)",
                method_style("rapier2d_4sub"),
                err_rapier,
            )
            .line(),
        ],
    );
    save_svg(&dir.join(&file), &[path, errors], 1, (900, 420))?;
    Ok(FigureOutput::file(file))
}
