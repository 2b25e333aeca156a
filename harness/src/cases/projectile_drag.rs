//! Case II, `projectile_drag` (seed Table 6.2, CASES.md): the projectile with
//! quadratic drag D = 0.003 kg/m. No closed form: the expected values are
//! CASES.md's 40-digit reference, and the trajectory reference is an
//! independent DOP853 solve (`references::DragReference`).

use super::projectile::{EVENT_CHECKS, ballistic_trace, events};
use super::{CaseReport, all_methods, dp_global_bound, dp_reason, sample_at};
use crate::row::RowSink;
use crate::scenes;
use crate::tolerance::{from_order, from_order_reason, half_unit};
use anyhow::Result;
use engine::Method;
use references::DragReference;
use references::drag_reference_values as cases_md;

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
    // CASES.md prints 12, 10, 11 and 12 decimals.
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
                    check,
                    value,
                    want,
                    bound,
                    format!(
                        "{}; + half a unit of CASES.md's last digit",
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
                    check,
                    value,
                    want,
                    tol,
                    format!(
                        "{}, i.e. half a unit of CASES.md's last digit",
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
                "position_error_t5",
                error,
                cases_md::RK4_H02_POSITION_ERROR_AT_5_S,
                half_unit(5),
                "CASES.md: RK4 at h = 0.2 errs by 4.5e-4 m at t = 5 s (two digits: +/- 5e-6)",
            );
        }
        report.traces.push(ballistic_trace(method, dt, &trace, |t| {
            reference.state_at(t).ok().map(|s| [s[0], s[1]])
        }));
    }
    Ok(report)
}
