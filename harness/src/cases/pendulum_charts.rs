//! The pendulum's two charts (`docs/cases.md#pendulum`):
//!
//! - **work precision**: the period error against the wall time of the
//!   run, for every engine with joints at 1 to 32 substeps, and for the
//!   soft step whose joints follow the substep (1/(4h)), the family whose
//!   error falls as h²: the chart none of the three engines publishes;
//! - **constraint drift against the step**: the largest anchor separation
//!   of a run against dt at 4 substeps, per engine, under the soft rows'
//!   closed-form bound (which the soft step and Box2D share).
//!
//! Every point runs the scene file `scenes/pendulum.toml` (its six
//! pendulums together) in one engine; the error of a panel is that of its
//! pendulum. The wall time is the steps' alone, the minimum over
//! [`REPEATS`] runs; a run that fails (a state no longer finite) leaves
//! its point out, and the caption says so.

use super::joint_common::{Config, Engine, JointScene, SoftRows, crossings, steps};
use super::pendulum_exact;
use super::pendulum_swing::Spec;
use super::{CaseFigure, collision_plots::figure};
use crate::plots::bench::engine_style;
use crate::plots::{Chart, Series, palette};
use anyhow::Result;
use engine::{Method, Tolerance};
use std::time::Instant;

/// Runs per configuration; the time is the minimum.
pub const REPEATS: usize = 3;

/// Substep counts of the work-precision chart.
pub const SUBSTEPS: [usize; 6] = [1, 2, 4, 8, 16, 32];

/// Steps (s) of the drift chart, at 4 substeps.
pub const STEPS: [f64; 8] = [
    1.0 / 480.0,
    1.0 / 240.0,
    1.0 / 120.0,
    1.0 / 60.0,
    1.0 / 30.0,
    1.0 / 20.0,
    1.0 / 15.0,
    1.0 / 10.0,
];

/// Periods of the slowest pendulum in a work-precision run.
const PERIODS: f64 = 20.0;

/// Simulated time of a drift run (s).
const DRIFT_SECONDS: f64 = 20.0;

/// A series of the work-precision chart: its label, style and how each
/// substep count is configured.
struct Family {
    label: &'static str,
    engine: Engine,
    scaled_joints: bool,
    style: crate::plots::Style,
}

fn families() -> [Family; 4] {
    [
        Family {
            label: "soft step, defaults (joints min(60, 1/(4h)) Hz)",
            engine: Engine::SoftStep,
            scaled_joints: false,
            style: engine_style(0),
        },
        Family {
            label: "soft step, joints at 1/(4h) Hz",
            engine: Engine::SoftStep,
            scaled_joints: true,
            style: palette(4),
        },
        Family {
            label: "rapier2d",
            engine: Engine::Rapier,
            scaled_joints: false,
            style: engine_style(1),
        },
        Family {
            label: "Box2D (joints min(60, 1/(4h)) Hz)",
            engine: Engine::Box2d,
            scaled_joints: false,
            style: box2d_style(),
        },
    ]
}

/// Box2D's benchmark style with hollow markers: its points fall on the
/// soft step's (the same rows), which must still show under them.
fn box2d_style() -> crate::plots::Style {
    crate::plots::Style {
        hollow: true,
        ..engine_style(2)
    }
}

/// The mean period of pendulum `p` over a run (s), from its first to its
/// last zero crossing; `None` with fewer than three.
fn mean_period(p: &Spec, run: &super::joint_common::Run) -> Option<f64> {
    let x: Vec<f64> = run
        .samples
        .iter()
        .map(|s| s[p.body].position[0] - p.pivot[0])
        .collect();
    let c = crossings(&x, run.dt);
    (c.len() >= 3).then(|| 2.0 * (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64)
}

/// The work-precision chart.
pub fn work_precision(js: &JointScene, specs: &[Spec]) -> Result<CaseFigure> {
    let slowest = specs.iter().map(|p| p.closed.period()).fold(0.0, f64::max);
    let base = Config::of(&js.scene, Engine::SoftStep)?;
    let n = steps(PERIODS * slowest, base.dt);
    let mut points: Vec<Vec<Vec<(f64, f64)>>> = vec![vec![Vec::new(); 4]; specs.len()];
    let mut failed = Vec::new();
    for (f, family) in families().iter().enumerate() {
        for substeps in SUBSTEPS {
            let h = base.dt / substeps as f64;
            let config = Config {
                engine: family.engine,
                dt: base.dt,
                substeps,
                joint_hertz: family.scaled_joints.then_some(0.25 / h),
            };
            let mut best = f64::INFINITY;
            let mut last = None;
            for _ in 0..REPEATS {
                match js.run(&config, n) {
                    Ok(run) => {
                        best = best.min(run.seconds);
                        last = Some(run);
                    }
                    Err(e) => {
                        failed.push(format!("{} at {substeps} substeps ({e:#})", family.label));
                        break;
                    }
                }
            }
            let Some(run) = last else { continue };
            for (i, p) in specs.iter().enumerate() {
                if let Some(t) = mean_period(p, &run) {
                    points[i][f].push((best, (t / p.closed.period() - 1.0).abs()));
                }
            }
        }
    }
    let exact = exact_points(js, specs, PERIODS * slowest, base.dt, &mut failed)?;
    let panels = specs
        .iter()
        .zip(points)
        .zip(exact)
        .map(|((p, series), exact)| Chart {
            title: p.title(),
            x_label: format!("wall time of the run (s), min of {REPEATS}"),
            y_label: "|mean period / T(θ0) − 1|".into(),
            log_x: true,
            log_y: true,
            series: families()
                .iter()
                .zip(series)
                .map(|(family, pts)| Series::new(family.label, family.style, pts))
                .chain(
                    exact_methods()
                        .iter()
                        .zip(exact)
                        .map(|(m, pts)| Series::new(m.label, m.style, pts)),
                )
                .collect(),
            y_range: None,
        })
        .collect();
    let failures = if failed.is_empty() {
        String::new()
    } else {
        format!(" Runs that failed, left out: {}.", failed.join("; "))
    };
    Ok(figure(
        "pendulum_work_precision.svg",
        "pendulum period error against wall time, per engine, 1 to 32 substeps",
        format!(
            "Work precision of the pendulums: the mean period over {PERIODS:.0} periods of the \
             slowest ({:.0} s of scenes/pendulum.toml, its six pendulums in one run) against the \
             elliptic-integral period at θ0, against the wall time of the run, for 1, 2, 4, 8, \
             16 and 32 substeps of dt = 1/60 s (the points along each curve, left to right). At \
             90° and 170° the error is mostly the energy the joints dissipate, which shortens \
             the period as the amplitude decays. Box2D and the soft step fix their joints at \
             min(60 Hz, 1/(4h)), so beyond 4 substeps their error stops falling as h²; with the \
             joints at 1/(4h) the soft step's does. The exact model (joints as constraints of \
             the equations of motion, docs/joints.md) runs each pendulum in its own world, its \
             time the sum of the six runs', its period from its apex events over the same span: \
             RK4, midpoint and velocity Verlet at h = dt/1 to dt/16 (left to right), \
             Dormand-Prince at rtol = atol = 1e-4 to 1e-12; their errors fall at their orders \
             to 1e-10 and below.{failures}",
            PERIODS * slowest
        ),
        panels,
        3,
    ))
}

/// The points (x, y) of one series.
type Points = Vec<(f64, f64)>;

/// An exact-model series of the work-precision chart.
struct ExactFamily {
    label: &'static str,
    style: crate::plots::Style,
    /// (method, step s) of each point, left to right.
    points: Vec<(Method, f64)>,
}

/// Substep counts whose h = dt/n the exact model's fixed-step methods
/// run at (its steps are whole integrator steps, no substeps).
const EXACT_DIVISIONS: [usize; 5] = [1, 2, 4, 8, 16];

fn exact_methods() -> Vec<ExactFamily> {
    let dt = 1.0 / 60.0;
    let fixed = |m: Method| -> Vec<(Method, f64)> {
        EXACT_DIVISIONS
            .iter()
            .map(|&n| (m, dt / n as f64))
            .collect()
    };
    vec![
        ExactFamily {
            label: "exact model, RK4",
            style: palette(3),
            points: fixed(Method::Rk4),
        },
        ExactFamily {
            label: "exact model, midpoint",
            style: palette(5),
            points: fixed(Method::Midpoint),
        },
        ExactFamily {
            label: "exact model, velocity Verlet",
            style: palette(6),
            points: fixed(Method::VelocityVerlet),
        },
        ExactFamily {
            label: "exact model, Dormand-Prince (tol 1e-4 to 1e-12)",
            style: palette(7),
            points: [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
                .iter()
                .map(|&t| (Method::DormandPrince(Tolerance::uniform(t)), dt))
                .collect(),
        },
    ]
}

/// The exact model's points (wall time, |period error|) per pendulum and
/// family: each pendulum alone in an exact-model world
/// ([`pendulum_exact::exact_world`]) for `seconds`, its mean period over
/// the whole periods between its apex events; the time of a point is the
/// sum over the pendulums of each run's minimum over [`REPEATS`].
fn exact_points(
    js: &JointScene,
    specs: &[Spec],
    seconds: f64,
    sample_dt: f64,
    failed: &mut Vec<String>,
) -> Result<Vec<Vec<Points>>> {
    let families = exact_methods();
    let mut points = vec![vec![Vec::new(); families.len()]; specs.len()];
    for (f, family) in families.iter().enumerate() {
        'point: for &(method, h) in &family.points {
            let mut total = 0.0;
            let mut errors = Vec::new();
            for p in specs {
                let mut best = f64::INFINITY;
                let mut apexes = Vec::new();
                for _ in 0..REPEATS {
                    let mut world = pendulum_exact::exact_world(&js.scene, p, method)?;
                    let dt = if matches!(method, Method::DormandPrince(_)) {
                        sample_dt
                    } else {
                        h
                    };
                    let started = Instant::now();
                    let trace = match world.run(seconds, dt) {
                        Ok(t) => t,
                        Err(e) => {
                            failed.push(format!("{} at h = {h:.5} s ({e:#})", family.label));
                            continue 'point;
                        }
                    };
                    best = best.min(started.elapsed().as_secs_f64());
                    apexes = trace.events.iter().map(|e| e.t).collect();
                }
                total += best;
                let periods = apexes.len().saturating_sub(1) / 2;
                let error = match pendulum_exact::period_of(&apexes, periods.max(1)) {
                    Ok(t) => (t / p.closed.period() - 1.0).abs(),
                    Err(e) => {
                        failed.push(format!("{} at h = {h:.5} s ({e:#})", family.label));
                        continue 'point;
                    }
                };
                errors.push(error);
            }
            for (i, e) in errors.into_iter().enumerate() {
                points[i][f].push((total, e));
            }
        }
    }
    Ok(points)
}

/// The constraint-drift chart.
pub fn drift_against_step(js: &JointScene, specs: &[Spec]) -> Result<CaseFigure> {
    let engines = Engine::ALL;
    let mut points: Vec<Vec<Vec<(f64, f64)>>> = vec![vec![Vec::new(); engines.len()]; specs.len()];
    let mut failed = Vec::new();
    for (e, engine) in engines.iter().enumerate() {
        for dt in STEPS {
            let config = Config {
                engine: *engine,
                dt,
                substeps: 4,
                joint_hertz: None,
            };
            match js.run(&config, steps(DRIFT_SECONDS, dt)) {
                Ok(run) => {
                    let seps = js.largest_separations(&run);
                    for (i, p) in specs.iter().enumerate() {
                        points[i][e].push((dt, seps[p.joint]));
                    }
                }
                Err(e) => failed.push(format!("{} at dt = {dt:.4} s ({e:#})", engine.label())),
            }
        }
    }
    // The exact model: RK4 at h = dt/4 (the soft engines' substep), each
    // pendulum alone; the largest constraint error its projection removed
    // after a step (what the integrator drifts by; after the projection
    // the error is round-off).
    let mut exact: Vec<Vec<(f64, f64)>> = vec![Vec::new(); specs.len()];
    for dt in STEPS {
        for (i, p) in specs.iter().enumerate() {
            let mut world = pendulum_exact::exact_world(&js.scene, p, Method::Rk4)?;
            match world.run(DRIFT_SECONDS, dt / 4.0) {
                Ok(_) => {
                    if let Some(d) = world.joint_drift() {
                        exact[i].push((dt, d));
                    }
                }
                Err(e) => failed.push(format!("exact model, RK4 at dt = {dt:.4} s ({e:#})")),
            }
        }
    }
    let panels = specs
        .iter()
        .zip(points)
        .zip(exact)
        .map(|((p, series), exact)| {
            let g = p.closed.gravity;
            let bound: Vec<(f64, f64)> = STEPS
                .iter()
                .map(|&dt| {
                    let rows = SoftRows::defaults(dt / 4.0);
                    (dt, rows.separation_bound(p.load(g), p.centripetal()))
                })
                .collect();
            let mut all = vec![Series::reference(
                "soft rows' bound (soft step and Box2D)",
                bound,
            )];
            all.extend(
                engines
                    .iter()
                    .enumerate()
                    .zip(series)
                    .map(|((i, engine), pts)| {
                        let style = if *engine == Engine::Box2d {
                            box2d_style()
                        } else {
                            engine_style(i)
                        };
                        Series::new(engine.label(), style, pts)
                    }),
            );
            all.push(Series::new(
                "exact model, RK4 at h = dt/4: drift per step before projection",
                palette(3),
                exact,
            ));
            Chart {
                title: p.title(),
                x_label: "step dt (s), 4 substeps".into(),
                y_label: "largest anchor separation (m)".into(),
                log_x: true,
                log_y: true,
                series: all,
                y_range: None,
            }
        })
        .collect();
    let failures = if failed.is_empty() {
        String::new()
    } else {
        format!(" Runs that failed, left out: {}.", failed.join("; "))
    };
    Ok(figure(
        "pendulum_drift.svg",
        "largest anchor separation against the step, per engine",
        format!(
            "Constraint drift against the step: the largest anchor separation over \
             {DRIFT_SECONDS:.0} s of scenes/pendulum.toml at dt from 1/480 to 1/10 s, 4 substeps, \
             per engine; the pale line is the soft rows' bound (a_load + a_c (1 + 1/(2 a3)))/ω_c² \
             at each step, with the rows at min(60 Hz, 1/(4h)) as in the soft step and Box2D: \
             it grows as h² once 1/(4h) < 60 Hz (dt > 1/60 s). The exact model (each pendulum \
             alone, RK4 at h = dt/4, joints as constraints) is drawn by the largest constraint \
             error its projection removed after a step, RK4's local error, O(h^5); the error \
             left after the projection is round-off.{failures}"
        ),
        panels,
        3,
    ))
}
