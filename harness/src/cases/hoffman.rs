//! The stiff test (seed §4.3, after Hoffman): y' = −1000(y − (t + 2)) + 1,
//! y(0) = 1, exact y = t + 2 − e^(−1000t), over t ∈ [0, 1] at the steps of
//! docs/cases.md, over the scene's duration (the last whole step at or before it). The error e = y − (t + 2) obeys e_{n+1} = R(hλ) e_n exactly
//! for every Runge–Kutta method (the forcing is linear in t), so the
//! engine's error must equal −R(hλ)^n: stable where |R| ≤ 1, blown up
//! where theory says so.

use super::{
    Case, CaseReport, FigureSection, Headline, MethodTrace, Snapshots, StudyFigure, all_methods,
    dp_global_bound, dp_reason,
};
use crate::plots::failures;
use crate::row::{RowKind, RowSink};
use crate::scenes;
use crate::stability::Axis;
use crate::sweep::SweepCase;
use crate::tolerance::ROUND_OFF_RELATIVE;
use anyhow::Context;
use anyhow::Result;
use engine::{integrate_fixed, integrate_to};
use references::Hoffman;
use references::linear_stability::stability_function;

/// Hoffman's stiff test: its rows against linear stability theory, its
/// sweep against the exact solution, the real axis of the stability study
/// and the seed's figures 4.2–4.3.
pub const CASE: Case = Case {
    scenes: &["hoffman"],
    snapshots: Snapshots::Traces,
    headline: &[
        Headline::new("error_end", "explicit_euler").at(0.0021),
        Headline::new("stability_limit", "explicit_euler"),
        Headline::new("stability_limit", "rk4"),
    ],
    sweep: Some(sweep),
    stability: Some(Axis::Real),
    figures: &[StudyFigure {
        section: FigureSection::Failures,
        write: failures::hoffman_euler,
    }],
    ..Case::new(
        "hoffman",
        "Stiff test y' = -1000(y - (t + 2)) + 1 (seed §4.3, after Hoffman)",
        run,
    )
};

/// The steps of docs/cases.md (s): explicit Euler stable at 0.0019 and blown up at
/// 0.0021 and 0.003; RK4 stable at 0.0027 and unstable at 0.0029; implicit
/// Euler stable at 0.01 and 0.1. Every method runs at every step.
pub const STEPS: [f64; 7] = [0.0019, 0.0021, 0.003, 0.0027, 0.0029, 0.01, 0.1];

/// A blow-up, as docs/cases.md counts one: |error| past 1e19 near t = 1.
const BLOW_UP: f64 = 1e19;

/// Runs the case.
pub fn run() -> Result<CaseReport> {
    let exact = Hoffman::seed();
    let ode = scenes::load("hoffman")?
        .linear_test()
        .context("scenes/hoffman.toml must hold a [linear_test]")?;
    let t_end = scenes::load("hoffman")?.duration();
    let mut report = CaseReport::default();
    for method in all_methods() {
        if method.needs_second_order() {
            report.notes.push(format!(
                "{} does not apply to hoffman: it needs a (position, velocity) system and y' = f(t, y) is first order.",
                method.id()
            ));
            continue;
        }
        for h in STEPS {
            let n = (t_end / h + 1e-9).floor() as usize;
            let mut system = ode;
            let solution = integrate_fixed(&mut system, method, 0.0, &[ode.y0], h, n)?;
            let t_last = solution.t[n];
            let error = solution.y[n][0] - exact.exact(t_last);
            let mut sink = RowSink {
                case: "hoffman",
                method: method.id(),
                dt: h,
                rows: &mut report.rows,
            };
            match stability_function(method, h * exact.lambda) {
                Some(r) => {
                    // y_n − (t_n + 2) = (y0 − 2) R^n and y(t) − (t + 2) =
                    // (y0 − 2) e^(λt), so the error is (y0 − 2)(R^n − e^(λt)).
                    let predicted =
                        (exact.y0 - 2.0) * (r.powi(n as i32) - (exact.lambda * t_last).exp());
                    let scale = predicted.abs().max(1.0);
                    let theory_stable = r.abs() <= 1.0;
                    // Where |R(hλ)| > 1 the rows check a failure theory
                    // predicts; elsewhere the method's error against the
                    // closed form.
                    let kind = if theory_stable {
                        RowKind::Validation
                    } else {
                        RowKind::PredictedFailure
                    };
                    sink.within(
                        kind,
                        "error_end",
                        error,
                        predicted,
                        ROUND_OFF_RELATIVE * scale,
                        "linear stability theory: e_n = R(h lambda)^n e_0 exactly; 1e-9 x max(1, |e|) round-off",
                    );
                    let stable = error.abs() <= 1.0;
                    sink.within(
                        kind,
                        "stable",
                        f64::from(u8::from(stable)),
                        f64::from(u8::from(theory_stable)),
                        0.0,
                        format!("1 when |error| <= 1 at t = {t_last:.4}; expected |R(h lambda)| = {:.6} <= 1", r.abs()),
                    );
                    if !theory_stable && error.abs() > 1.0 && predicted.abs() > BLOW_UP {
                        sink.at_least(
                            RowKind::PredictedFailure,
                            "blown_up",
                            error.abs(),
                            BLOW_UP,
                            0.0,
                            "docs/cases.md: a blow-up is |error| > 1e19 near t = 1",
                        );
                    }
                }
                None => {
                    let bound = dp_global_bound(solution.stats.steps, 3.0);
                    sink.within(
                        RowKind::Validation,
                        "error_end",
                        error,
                        0.0,
                        bound,
                        dp_reason(solution.stats.steps),
                    );
                }
            }
            report.traces.push(MethodTrace {
                method: method.id().into(),
                dt: h,
                columns: vec!["t", "y", "error"],
                samples: solution
                    .t
                    .iter()
                    .zip(&solution.y)
                    .map(|(&t, y)| vec![t, y[0], y[0] - exact.exact(t)])
                    .collect(),
            });
        }
    }
    Ok(report)
}

/// The sweep: |y error| against the exact solution over the scene's
/// duration; methods that need a (position, velocity) system do not apply.
fn sweep() -> Result<SweepCase> {
    let exact = Hoffman::seed();
    let scene = scenes::load("hoffman")?;
    let duration = scene.duration();
    let ode = scene
        .linear_test()
        .context("scenes/hoffman.toml must hold a [linear_test]")?;
    Ok(SweepCase {
        error_label: "|y error| over 0-1 s (-)",
        unit: "-",
        reference: "the exact solution t + 2 - e^(-1000 t)",
        h0: 0.1,
        scale: 1.0,
        first_order: true,
        speed_target: None,
        rapier: None,
        run: Box::new(move |method, h, _observe| {
            let mut system = ode;
            let solution = integrate_to(&mut system, method, 0.0, &[ode.y0], duration, h)?;
            let errors = solution
                .t
                .iter()
                .zip(&solution.y)
                .map(|(&t, y)| (y[0] - exact.exact(t)).abs());
            let max_error = errors.fold(0.0, f64::max);
            let last = solution.y.len() - 1;
            let end = (solution.y[last][0] - exact.exact(duration)).abs();
            Ok((end, max_error, solution.stats.evaluations))
        }),
    })
}
