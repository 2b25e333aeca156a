//! The exact model's rows of the `pendulum` case (`docs/cases.md#pendulum`):
//! the same six pendulums (`scenes/pendulum.toml`), each alone in a world
//! of the exact contact model whose joint is a constraint of the equations
//! of motion (`docs/joints.md`, "Joints under the exact model"), and the
//! acceptance scene `scenes/pendulum_exact.toml` (a rod and a pin from
//! 120°, RK4 at h = 1e-3 s) as `harness simulate` runs it.
//!
//! # What is measured, and where each tolerance comes from
//!
//! - **Period** (RK4, h = 1e-3 s): the mean of ten periods, each between
//!   every second apex event (vy from > 0 to ≤ 0, located inside its step
//!   by the engine's root finder), against T = 4 √(L_eq/g) K(sin(θ0/2)).
//!   Tolerance: [`RICHARDSON_FACTOR`] × the step-doubling estimate of RK4's
//!   own error (the same run at h/2, order 4), plus [`PERIOD_FLOOR`] (the
//!   events' location, 1e-15 of the time, and the closed form's AGM, both
//!   round-off).
//! - **Observed order** of every fixed-step method: the state error at
//!   t = [`ORDER_TIME`] s against the closed form θ(t) (Jacobi's sn, cn),
//!   e = |Δp| + |Δv|/ω (m), at h₀, h₀/2 and h₀/4 ([`order_steps`]), order
//!   log₂(e(h₀/2)/e(h₀/4)), within [`ORDER_TOLERANCE`] of the theory. The
//!   next term of the error expansion moves the observed order by O(h);
//!   the reason prints the order of the coarser pair too, whose distance
//!   to the finer one measures that term.
//! - **Dormand–Prince** at rtol = atol = [`DP_TOLERANCE`]: the largest
//!   state component's error at t = [`ORDER_TIME`] s against
//!   [`dp_global_bound`] (the sum of its accepted steps' local errors, each
//!   at most tol × max|y|).
//! - **Drift**: the largest constraint error the projection removed after
//!   a step ([`engine::World::joint_drift`]) is at most RK4's local
//!   error, O(h⁵): its observed order between [`DRIFT_STEPS`] is at least
//!   5 − [`ORDER_TOLERANCE`];
//!   and the constraint error left after the projection (the joint's
//!   `linear_error` after every step) is round-off, within
//!   [`RESIDUAL_ULPS`] ulps of the largest coordinate.

use super::CaseReport;
use super::pendulum_swing::Spec;
use super::{DP_TOLERANCE, dp_global_bound};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Context, Result, bail};
use engine::prelude::{BodyState, EventSpec, JointDef, Method, Shape, Vector2, World};
use engine::{Anchor, JointKind, Tolerance};
use references::pendulum::{Pendulum, PhysicalPendulum};
use scene::Scene;

/// The step of the period and drift rows (s): the issue's.
pub const H: f64 = 1e-3;
/// Periods averaged by the period rows.
pub const PERIODS: usize = 10;
/// Relative error of a period from its events and the closed form alone:
/// each event time is located to 1e-15 of the time (the engine's root
/// finder) and K(k) by the AGM to a few ulps; 1e-14 covers both.
pub const PERIOD_FLOOR: f64 = 1e-14;
/// Time at which the orders are measured (s): inside the first period of
/// every pendulum of the scene, away from a turning point.
pub const ORDER_TIME: f64 = 2.0;
/// The bound on an observed order's distance to the theory.
pub const ORDER_TOLERANCE: f64 = 0.1;
/// Ulps of the largest coordinate a projected constraint error may keep:
/// C is a difference of coordinates of a few metres, each rounded, and
/// the Newton projection stops when an iteration no longer halves it.
pub const RESIDUAL_ULPS: f64 = 8.0;

/// The coarsest step h₀ (s) of each fixed-step method's order
/// measurement: small enough for the asymptotic range on the 170°
/// pendulums (an error well below the amplitude), large enough that the
/// finest step's error stays far above round-off.
pub fn order_steps(method: Method) -> f64 {
    match method.order() {
        1 => 1e-4,
        2 => 5e-4,
        _ => 5e-3,
    }
}

/// The steps (s) of the drift's order: at h = 1e-3 s RK4's drift is 1e-14
/// m and less, within a hundred ulps of round-off; at 5e-3 and 2.5e-3 s it
/// is 3125 and 97 times larger, and still in the asymptotic range.
pub const DRIFT_STEPS: [f64; 2] = [5e-3, 2.5e-3];

/// A world of the exact model integrated by `method`, contacts off, with
/// pendulum `spec` of `scene` alone in it (body 0, its joint to the world
/// re-pointed at it) and an apex event on it.
pub fn exact_world(scene: &Scene, spec: &Spec, method: Method) -> Result<World> {
    let mut world = World::new(method)?;
    if let Some(g) = scene.gravity() {
        world.set_gravity(g)?;
    }
    world.add_body(scene.bodies()[spec.body].clone())?;
    let def = scene
        .joints()
        .nth(spec.joint)
        .with_context(|| format!("{}: no joint {}", scene.origin(), spec.joint))?;
    world.add_joint(JointDef {
        body_a: None,
        body_b: Some(0),
        ..def.clone()
    })?;
    world.add_event(EventSpec::apex(0))?;
    Ok(world)
}

/// The mean period (s) between every second apex time in `apexes`, over
/// the first `periods` periods.
pub fn period_of(apexes: &[f64], periods: usize) -> Result<f64> {
    if apexes.len() < 2 * periods + 1 {
        bail!(
            "{} apex events, fewer than the {} of {periods} periods",
            apexes.len(),
            2 * periods + 1
        );
    }
    Ok((apexes[2 * periods] - apexes[0]) / periods as f64)
}

/// The period of `spec` under the exact model, RK4 at `h` (s), and the
/// largest constraint error projected away and left (m).
fn rk4_period(scene: &Scene, spec: &Spec, h: f64) -> Result<(f64, f64, f64)> {
    let mut world = exact_world(scene, spec, Method::Rk4)?;
    let until = (PERIODS as f64 + 0.75) * spec.closed.period();
    let steps = (until / h).round() as usize;
    let mut apexes = Vec::new();
    let mut residual = 0.0_f64;
    for k in 1..=steps {
        let events = world.step_to(k as f64 * h)?;
        apexes.extend(events.iter().map(|e| e.t));
        residual = residual.max(world.joint(0)?.linear_error);
    }
    let drift = world.joint_drift().unwrap_or(f64::NAN);
    Ok((period_of(&apexes, PERIODS)?, drift, residual))
}

/// The state error e = |Δp| + |Δv|/ω (m) and the largest component error
/// (m or m/s) of `spec` at [`ORDER_TIME`] under `method` at step `h`, with
/// the accepted steps taken.
fn state_error(scene: &Scene, spec: &Spec, method: Method, h: f64) -> Result<(f64, f64, u64)> {
    let mut world = exact_world(scene, spec, method)?;
    world.run(ORDER_TIME, h)?;
    let s: BodyState = world.states()[0];
    let c = &spec.closed;
    let t = world.time();
    let (theta, rate) = (c.angle(t), c.angular_velocity(t));
    let p = Vector2::new(
        spec.pivot[0] + spec.arm * theta.sin(),
        spec.pivot[1] - spec.arm * theta.cos(),
    );
    let v = spec.arm * rate * Vector2::new(theta.cos(), theta.sin());
    let (dp, dv) = (s.position - p, s.velocity - v);
    let largest = dp.x.abs().max(dp.y.abs()).max(dv.x.abs()).max(dv.y.abs());
    Ok((
        dp.norm() + dv.norm() / c.omega(),
        largest,
        world.stats().steps,
    ))
}

/// Adds the exact model's rows of the six pendulums `specs` of `scene`,
/// and of the acceptance scene, to `report`.
pub fn rows(scene: &Scene, specs: &[Spec], report: &mut CaseReport) -> Result<()> {
    let mut notes = Vec::new();
    for spec in specs {
        period_rows(scene, spec, report, &mut notes)?;
        order_rows(scene, spec, report, &mut notes)?;
    }
    acceptance_rows(report, &mut notes)?;
    report.notes.push(format!(
        "Exact model (joints as constraints of the equations of motion, index 1, projected \
         after every step; docs/joints.md): {}",
        notes.join("; ")
    ));
    Ok(())
}

fn period_rows(
    scene: &Scene,
    spec: &Spec,
    report: &mut CaseReport,
    notes: &mut Vec<String>,
) -> Result<()> {
    let exact = spec.closed.period();
    let (period, drift, residual) = rk4_period(scene, spec, H)?;
    let (half, half_drift, _) = rk4_period(scene, spec, H / 2.0)?;
    let estimate = richardson_error(period, half, 4).abs() / exact;
    let error = (period - exact) / exact;
    let mut sink = RowSink {
        case: "pendulum",
        method: Method::Rk4.id(),
        dt: H,
        rows: &mut report.rows,
    };
    let name = &spec.name;
    sink.within(
        RowKind::Consistency,
        &format!("exact_period_{name}"),
        error,
        0.0,
        RICHARDSON_FACTOR * estimate + PERIOD_FLOOR,
        format!(
            "measured against a closed form, with a derived bound: the exact model, RK4 at \
             h = 1e-3 s, the mean of {PERIODS} periods between apex events against \
             4 sqrt(L/g) K(sin(theta0/2)) = {exact:.12} s, relative; tolerance \
             {RICHARDSON_FACTOR} x the step-doubling estimate of RK4's own error (h/2 gives \
             {:.3e}, order 4: estimate {estimate:.3e}) + {PERIOD_FLOOR:e} (event times and \
             K to round-off)",
            (half - exact) / exact
        ),
    );
    let (_, coarse_drift, _) = rk4_period(scene, spec, DRIFT_STEPS[0])?;
    let (_, fine_drift, _) = rk4_period(scene, spec, DRIFT_STEPS[1])?;
    let drift_order = (coarse_drift / fine_drift).log2();
    sink.dt = DRIFT_STEPS[1];
    sink.at_least(
        RowKind::Validation,
        &format!("exact_drift_order_{name}"),
        drift_order,
        5.0,
        ORDER_TOLERANCE,
        format!(
            "observed order of a measured drift: the largest constraint error the projection \
             removed after a step, {coarse_drift:.3e} m at h = {:e} s and {fine_drift:.3e} m at \
             {:e} s (at 1e-3 s: {drift:.3e} m; at 5e-4 s: {half_drift:.3e} m, round-off), is \
             at most RK4's local error, O(h^5): its observed order (log2 of their ratio) is at \
             least 5 (more where the local error's leading term has no component across the \
             constraint); tolerance {ORDER_TOLERANCE}, the bound the issue sets on observed \
             orders",
            DRIFT_STEPS[0], DRIFT_STEPS[1]
        ),
    );
    let scale = spec.pivot[0].abs().max(spec.pivot[1].abs()) + spec.arm;
    sink.dt = H;
    sink.at_most(
        RowKind::Validation,
        &format!("exact_residual_{name}"),
        residual,
        0.0,
        RESIDUAL_ULPS * f64::EPSILON * scale,
        format!(
            "round-off bound on a measured error: the joint's constraint error after each \
             step's projection, the largest over the run (m), against {RESIDUAL_ULPS} ulps of \
             the largest coordinate ({scale:.2} m): the projection's Newton iterations stop at \
             the round-off of C"
        ),
    );
    notes.push(format!(
        "{name}: period {error:+.2e} relative at RK4 h = 1e-3 s, drift {drift:.2e} m per step \
         before projection"
    ));
    Ok(())
}

fn order_rows(
    scene: &Scene,
    spec: &Spec,
    report: &mut CaseReport,
    notes: &mut Vec<String>,
) -> Result<()> {
    let name = &spec.name;
    let mut orders = Vec::new();
    for method in Method::FIXED_STEP {
        let h0 = order_steps(method);
        let e: Vec<f64> = (0..3)
            .map(|i| state_error(scene, spec, method, h0 / f64::from(1 << i)).map(|r| r.0))
            .collect::<Result<_>>()?;
        let (coarse, fine) = ((e[0] / e[1]).log2(), (e[1] / e[2]).log2());
        let mut sink = RowSink {
            case: "pendulum",
            method: method.id(),
            dt: h0 / 4.0,
            rows: &mut report.rows,
        };
        sink.within(
            RowKind::Validation,
            &format!("exact_order_{name}"),
            fine,
            f64::from(method.order()),
            ORDER_TOLERANCE,
            format!(
                "observed order against a closed form: the exact model's state error \
                 |dp| + |dv|/omega at t = {ORDER_TIME} s against theta(t) of Jacobi's sn, cn, \
                 at h = {h0:e}, {:e}, {:e} s: {:.3e}, {:.3e}, {:.3e} m; order log2(e(h/2)/e(h/4)) \
                 (the coarser pair gives {coarse:.3}); tolerance {ORDER_TOLERANCE}, the issue's \
                 bound",
                h0 / 2.0,
                h0 / 4.0,
                e[0],
                e[1],
                e[2]
            ),
        );
        orders.push(format!("{} {fine:.2}", method.id()));
    }
    let dp = Method::DormandPrince(Tolerance::uniform(DP_TOLERANCE));
    let (_, largest, steps) = state_error(scene, spec, dp, 0.1)?;
    let scale =
        spec.pivot[0].abs().max(spec.pivot[1].abs()) + spec.arm * (1.0 + spec.fastest2().sqrt());
    let mut sink = RowSink {
        case: "pendulum",
        method: dp.id(),
        dt: 0.1,
        rows: &mut report.rows,
    };
    sink.at_most(
        RowKind::Consistency,
        &format!("exact_dp_error_{name}"),
        largest,
        0.0,
        dp_global_bound(steps, scale),
        format!(
            "measured against a closed form, with the method's error bound: Dormand-Prince's \
             largest state error at t = {ORDER_TIME} s (m or m/s) against the sum of its \
             {steps} accepted steps' local errors, each <= tol x max|y| (tol = \
             {DP_TOLERANCE:e}, max|y| <= {scale:.2})"
        ),
    );
    notes.push(format!("{name} orders: {}", orders.join(", ")));
    Ok(())
}

/// The acceptance scene, run as `harness simulate` runs it: the world of
/// the file (its method, step and model), to its duration.
fn acceptance_rows(report: &mut CaseReport, notes: &mut Vec<String>) -> Result<()> {
    let scene = crate::scenes::load("pendulum_exact")?;
    let mut world = scene.build_world(None)?;
    let trace = world.run(scene.duration(), scene.dt())?;
    let g = -scene
        .gravity()
        .context("pendulum_exact.toml has no gravity")?
        .y;
    for (body, def) in scene.joints().enumerate() {
        let Some(b) = def.body_b else {
            bail!("joint {body} of pendulum_exact.toml holds no body B")
        };
        let Anchor::World(pivot) = def.anchor_a else {
            bail!("joint {body} of pendulum_exact.toml has a local anchor")
        };
        let start = scene.bodies()[b].state.position - pivot;
        let (arm, amplitude) = (start.norm(), start.x.atan2(-start.y));
        let closed: Pendulum = match (&def.kind, &scene.bodies()[b].shape) {
            (JointKind::Distance(_), _) => Pendulum::new(arm, g, amplitude),
            (JointKind::Revolute(_), Some(Shape::Circle(c))) => {
                PhysicalPendulum::disc(c.radius, arm).pendulum(g, amplitude)
            }
            _ => bail!("joint {body} of pendulum_exact.toml is neither a rod nor a pinned disc"),
        };
        // The apexes of this body: at each, its vy is the root's (~0), the
        // other body's is not.
        let apexes: Vec<f64> = trace
            .events
            .iter()
            .filter(|e| {
                let own = e.states[b].velocity.y.abs();
                e.states
                    .iter()
                    .enumerate()
                    .all(|(i, s)| i == b || own < s.velocity.y.abs())
            })
            .map(|e| e.t)
            .collect();
        let period = period_of(&apexes, PERIODS)?;
        let exact = closed.period();
        let error = (period - exact) / exact;
        let name = &scene.bodies()[b].name;
        let mut sink = RowSink {
            case: "pendulum",
            method: world.method().id(),
            dt: scene.dt(),
            rows: &mut report.rows,
        };
        sink.within(
            RowKind::Criterion,
            &format!("exact_scene_period_{name}"),
            error,
            0.0,
            1e-8,
            format!(
                "acceptance check against a closed form: scenes/pendulum_exact.toml as \
                 `harness simulate` runs it ([contact] model = \"exact\", rk4, h = {} s), the \
                 mean of {PERIODS} periods between its apex events against {exact:.12} s, \
                 relative; tolerance 1e-8, the issue's acceptance bound (the derived bound of \
                 the same pendulum's RK4 error is the exact_period rows')",
                scene.dt()
            ),
        );
        notes.push(format!(
            "pendulum_exact.toml {name}: period {error:+.2e} relative"
        ));
    }
    Ok(())
}
