//! Case II, `projectile` (seed §6, docs/cases.md): the box in vacuum at
//! h = 0.01 s. Landing, range and apex come from event location inside the
//! step, so they are not quantized to h.

use super::{
    Case, CaseReport, Headline, MethodTrace, Snapshots, all_methods, dp_global_bound, dp_reason,
    sample_at,
};
use crate::row::{RowKind, RowSink};
use crate::scenes;
use crate::tolerance::{ROUND_OFF_RELATIVE, from_order, from_order_reason};
use anyhow::{Context, Result};
use engine::{Method, Trace};
use references::Projectile;

/// The projectile in vacuum against its closed form.
pub const CASE: Case = Case {
    scenes: &["projectile"],
    snapshots: Snapshots::Traces,
    headline: &[Headline::new("landing_time", "rk4").at(0.01)],
    ..Case::new(
        "projectile",
        "Case II: projectile in vacuum, h = 0.01 s (seed §6)",
        run,
    )
};

/// Time at which the first-order methods' y error is compared with theory (s).
const T_CHECK: f64 = 8.0;

/// Landing time, range, apex height and apex time of a run.
pub(crate) fn events(trace: &Trace) -> Result<[f64; 4]> {
    let landing = trace.event("landing").context("the box never landed")?;
    let apex = trace.event("apex").context("no apex found")?;
    Ok([
        landing.t,
        landing.states[0].position.x,
        apex.states[0].position.y,
        apex.t,
    ])
}

/// Names of the values of [`events`].
pub(crate) const EVENT_CHECKS: [&str; 4] = ["landing_time", "range", "apex_height", "apex_time"];

/// Runs the case.
pub fn run() -> Result<CaseReport> {
    let scene = scenes::load("projectile")?;
    let (dt, duration) = (scene.dt(), scene.duration());
    let exact = Projectile::seed();
    let g = exact.gravity;
    let expected = [
        exact.landing_time(),
        exact.range(),
        exact.apex_height(),
        exact.apex_time(),
    ];
    let mut report = CaseReport::default();
    for method in all_methods() {
        let trace = scenes::world("projectile", method)?.run(duration, dt)?;
        let found = events(&trace)?;
        let mut sink = RowSink {
            case: "projectile",
            method: method.id(),
            dt,
            rows: &mut report.rows,
        };
        if method.is_adaptive() {
            for ((check, value), want) in EVENT_CHECKS.iter().zip(found).zip(expected) {
                let bound = dp_global_bound(trace.stats.steps, want.abs());
                sink.within(RowKind::Validation, check, value, want, bound, dp_reason(trace.stats.steps));
            }
        } else {
            let half = events(&scenes::world("projectile", method)?.run(duration, dt / 2.0)?)?;
            for (((check, value), value_half), want) in
                EVENT_CHECKS.iter().zip(found).zip(half).zip(expected)
            {
                let floor = ROUND_OFF_RELATIVE * want.abs();
                let tol = from_order(value, value_half, method.order(), floor);
                sink.within(
                    RowKind::Consistency,
                    check,
                    value,
                    want,
                    tol,
                    from_order_reason(method.order(), floor),
                );
            }
        }
        let landing = trace.event("landing").context("no landing")?;
        match method {
            Method::ExplicitEuler | Method::SemiImplicitEuler | Method::ImplicitEuler => {
                // Explicit Euler lags the velocity by one step: y errs by
                // +g h t/2; semi-implicit and implicit Euler use the new
                // velocity: -g h t/2 (docs/cases.md).
                let s = sample_at(&trace, T_CHECK)?;
                let sign = if method == Method::ExplicitEuler {
                    1.0
                } else {
                    -1.0
                };
                let predicted = sign * g * dt * s.t / 2.0;
                let error = s.states[0].position.y - exact.position(s.t)[1];
                sink.within(
                    RowKind::Validation,
                    "y_error_t8",
                    error,
                    predicted,
                    ROUND_OFF_RELATIVE * predicted.abs(),
                    "first-order theory: y errs by +g h t/2 (explicit) or -g h t/2 (semi-implicit, implicit); 1e-9 relative",
                );
            }
            _ => {
                let p = exact.position(landing.t);
                let s = landing.states[0].position;
                let error = (s.x - p[0]).hypot(s.y - p[1]);
                sink.within(
                    RowKind::Validation,
                    "position_error_at_landing",
                    error,
                    0.0,
                    1e-9,
                    "order >= 2 methods integrate a parabola exactly; 1e-9 m covers round-off of ~870 steps on |x| <= 400 m",
                );
            }
        }
        report.traces.push(ballistic_trace(method, dt, &trace, |t| {
            let p = exact.position(t);
            Some([p[0], p[1]])
        }));
    }
    Ok(report)
}

/// The sampled trace of a ballistic run: t, x, y, vx, vy, angle, omega and
/// the position error against `reference` (m), when there is one.
pub(crate) fn ballistic_trace(
    method: Method,
    dt: f64,
    trace: &Trace,
    reference: impl Fn(f64) -> Option<[f64; 2]>,
) -> MethodTrace {
    MethodTrace {
        method: method.id().into(),
        dt,
        columns: vec![
            "t",
            "x",
            "y",
            "vx",
            "vy",
            "angle",
            "omega",
            "position_error",
        ],
        samples: trace
            .samples
            .iter()
            .map(|s| {
                let b = &s.states[0];
                let error = reference(s.t).map_or(f64::NAN, |r| {
                    (b.position.x - r[0]).hypot(b.position.y - r[1])
                });
                vec![
                    s.t,
                    b.position.x,
                    b.position.y,
                    b.velocity.x,
                    b.velocity.y,
                    b.angle,
                    b.angular_velocity,
                    error,
                ]
            })
            .collect(),
    }
}
