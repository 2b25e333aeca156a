//! Step sweeps: every method on every smooth case, halving the step level
//! by level (Dormand–Prince: tightening its tolerance), recording the error
//! against the reference, the wall time (minimum of N runs, release build)
//! and the derivative evaluations (machine-independent).

use crate::cases::all_methods;
use crate::rapier_scene::rapier_problem;
use crate::scenes;
use crate::timing::min_time;
use anyhow::Result;
use engine::time_grid::grid_time;
use engine::{EngineError, Method, Tolerance, World, step_count};
use references::rapier_world::{RapierError, RapierSample, RapierSettings, run_single_body};
use serde::Serialize;

/// One point of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepPoint {
    /// Method id.
    pub method: String,
    /// Step (s) of a fixed-step method; output interval of Dormand–Prince.
    pub h: f64,
    /// Dormand–Prince tolerance; `None` for fixed-step methods.
    pub tolerance: Option<f64>,
    /// |error| at the end of the run, in the case's unit.
    pub error_end: f64,
    /// max |error| over the run.
    pub max_error: f64,
    /// Minimum wall time over the timing runs (s) (the field keeps its
    /// name in `sweeps.json`).
    pub cpu_seconds: f64,
    /// Evaluations of the right-hand side.
    pub evaluations: u64,
    /// Whether the run stayed finite and its error below the case's scale.
    pub stable: bool,
}

/// A whole sweep of one case.
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    /// Case id.
    pub case: &'static str,
    /// What the error measures, with its unit (points hold its maximum over
    /// the run and its value at the end).
    pub error_label: &'static str,
    /// The error's unit (`m`, `rad`, `-`).
    pub unit: &'static str,
    /// The reference the error is measured against.
    pub reference: &'static str,
    /// Size of the solution (same unit): errors above it are "unstable".
    pub scale: f64,
    /// The points, method by method, coarse to fine.
    pub points: Vec<SweepPoint>,
}

/// How much of a sweep to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SweepSettings {
    /// Timing runs per point (the minimum is kept).
    pub timing_runs: usize,
    /// Halvings of the step beyond the first level.
    pub levels: u32,
    /// Halvings of rapier2d's step beyond the first level.
    pub rapier_levels: u32,
}

impl SweepSettings {
    /// The full sweep of the report. Three timing runs (the minimum is
    /// kept): the timings make the work-precision diagrams and the speed
    /// comparison, never a row, and a fine step's runs stop at
    /// [`crate::timing`]'s budget after one or two anyway.
    pub const FULL: SweepSettings = SweepSettings {
        timing_runs: 3,
        levels: 13,
        rapier_levels: 9,
    };
    /// The `--quick` sweep: one timing run, fewer levels.
    pub const QUICK: SweepSettings = SweepSettings {
        timing_runs: 1,
        levels: 13,
        rapier_levels: 5,
    };
}

/// Dormand–Prince tolerances swept, 1e-3 to 1e-12.
pub const DP_TOLERANCES: [f64; 10] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12,
];

/// Errors below this fraction of the scale are at the round-off floor:
/// sweeping further only measures round-off.
pub const ROUND_OFF_FLOOR: f64 = 1e-12;

/// What one observed run returns: (|error| at the end, max |error| over the
/// run, evaluations).
pub type Measured = (f64, f64, u64);

/// Runs a method at a step; `true` asks for the error to be observed.
pub type RunFn = Box<dyn Fn(Method, f64, bool) -> Result<Measured>>;

/// What a case declares to be swept (`Case::sweep`): its error against
/// its reference at step `h`, and the same run in rapier2d-f64.
pub struct SweepCase {
    /// What the error measures, with its unit.
    pub error_label: &'static str,
    /// The error's unit (`m`, `rad`, `-`).
    pub unit: &'static str,
    /// The reference the error is measured against.
    pub reference: &'static str,
    /// The coarsest step (s); each level halves it.
    pub h0: f64,
    /// Size of the solution (the error's unit): errors above it are
    /// "unstable".
    pub scale: f64,
    /// The case is a scalar first-order ODE: methods that need a
    /// (position, velocity) system do not apply.
    pub first_order: bool,
    /// An error (the error's unit) at which the report compares the wall
    /// time the engine and rapier2d-f64 need to reach it, if any.
    pub speed_target: Option<f64>,
    /// Runs a method at step `h`: (error at end, max error, evaluations),
    /// or a blow-up.
    pub run: RunFn,
    /// The same observation of a rapier2d-f64 run: (substeps, dt) → error.
    pub rapier: Option<RapierFn>,
}

/// Runs the case's scene in rapier2d-f64 with (substeps, dt) and measures
/// its error like [`RunFn`]; `evaluations` counts force evaluations (one per
/// step: rapier holds external forces over the substeps).
pub type RapierFn = Box<dyn Fn(usize, f64, bool) -> Result<Measured>>;

/// Substep counts of rapier2d swept (its default is 4).
pub const RAPIER_SUBSTEPS: [usize; 3] = [1, 4, 16];

/// The rapier runner of scene `id`, with `error(t, sample)` giving the error
/// of one sample (its unit is the case's).
pub fn rapier_runner(
    id: &str,
    duration: f64,
    error: impl Fn(&RapierSample) -> Result<f64> + 'static,
) -> Result<RapierFn> {
    let (body, forces) = rapier_problem(&scenes::load(id)?)?;
    Ok(Box::new(move |substeps, dt, observe| {
        let settings = RapierSettings { dt, substeps };
        let samples = run_single_body(&body, &forces, &settings, duration)?;
        let last = samples
            .last()
            .ok_or_else(|| anyhow::anyhow!("rapier returned no sample"))?;
        let end = error(last)?;
        let mut max_error: f64 = 0.0;
        if observe {
            for s in &samples {
                max_error = max_error.max(error(s)?);
            }
        }
        Ok((end, max_error, samples.len() as u64 - 1))
    }))
}

/// Steps a world from its current time to `until` on the engine's time grid
/// with step `h` (no sampling, unlike [`World::run`]), calling `observe`
/// after each step.
pub fn step_world(
    world: &mut World,
    until: f64,
    h: f64,
    mut observe: impl FnMut(&World),
) -> Result<()> {
    let t0 = world.time();
    let steps = step_count(until - t0, h)?;
    for i in 1..=steps {
        world.step_to(grid_time(t0, until, h, i, steps))?;
        observe(world);
    }
    Ok(())
}

/// An independent part of a sweep: the points of one of the engine's
/// methods, or of rapier2d at one substep count. A run computes the parts
/// on its workers ([`crate::study::jobs`]); [`run`] computes them in turn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Part {
    /// The engine's method (Dormand–Prince: every tolerance).
    Method(Method),
    /// rapier2d-f64 at this many substeps.
    Rapier(usize),
}

impl Part {
    /// A short name for the log.
    pub fn name(&self) -> String {
        match self {
            Part::Method(m) => m.id().to_string(),
            Part::Rapier(substeps) => format!("rapier2d_{substeps}sub"),
        }
    }
}

/// The parts of `case`'s sweep, in the order of its points.
pub fn parts(case: &SweepCase) -> Vec<Part> {
    let mut parts: Vec<Part> = all_methods()
        .into_iter()
        .filter(|m| !(case.first_order && m.needs_second_order()))
        .map(Part::Method)
        .collect();
    if case.rapier.is_some() {
        parts.extend(RAPIER_SUBSTEPS.map(Part::Rapier));
    }
    parts
}

/// The points of `part` of `case`'s sweep.
pub fn run_part(case: &SweepCase, part: Part, settings: SweepSettings) -> Result<Vec<SweepPoint>> {
    let mut points = Vec::new();
    match part {
        Part::Method(method) => {
            let plan: Vec<(Method, f64, Option<f64>)> = if method.is_adaptive() {
                DP_TOLERANCES
                    .iter()
                    .map(|&tol| {
                        (
                            Method::DormandPrince(Tolerance::uniform(tol)),
                            case.h0,
                            Some(tol),
                        )
                    })
                    .collect()
            } else {
                (0..=settings.levels)
                    .map(|k| (method, case.h0 / f64::from(1u32 << k), None))
                    .collect()
            };
            for (m, h, tolerance) in plan {
                let point = measure(case, m, h, tolerance, settings)?;
                let at_floor = point.stable && point.max_error < ROUND_OFF_FLOOR * case.scale;
                points.push(point);
                if at_floor && tolerance.is_none() {
                    break;
                }
            }
        }
        Part::Rapier(substeps) => {
            let Some(rapier) = &case.rapier else {
                return Ok(points);
            };
            for k in 0..=settings.rapier_levels {
                let h = case.h0 / f64::from(1u32 << k);
                let point = measure_with(
                    &format!("rapier2d_{substeps}sub"),
                    case.scale,
                    h,
                    None,
                    settings,
                    |observe| rapier(substeps, h, observe),
                )?;
                let at_floor = point.stable && point.max_error < ROUND_OFF_FLOOR * case.scale;
                points.push(point);
                if at_floor {
                    break;
                }
            }
        }
    }
    Ok(points)
}

/// The sweep of case `id` from its `points` (its parts' in order).
pub fn assemble(id: &'static str, case: &SweepCase, points: Vec<SweepPoint>) -> Sweep {
    Sweep {
        case: id,
        error_label: case.error_label,
        unit: case.unit,
        reference: case.reference,
        scale: case.scale,
        points,
    }
}

/// Runs the sweep of case `id`, as its [`SweepCase`] declares it: its
/// [`parts`] in turn.
pub fn run(id: &'static str, case: &SweepCase, settings: SweepSettings) -> Result<Sweep> {
    let mut points = Vec::new();
    for part in parts(case) {
        points.extend(run_part(case, part, settings)?);
    }
    Ok(assemble(id, case, points))
}

fn measure(
    case: &SweepCase,
    method: Method,
    h: f64,
    tolerance: Option<f64>,
    settings: SweepSettings,
) -> Result<SweepPoint> {
    measure_with(method.id(), case.scale, h, tolerance, settings, |observe| {
        (case.run)(method, h, observe)
    })
}

/// Observes one run (errors, evaluations), then times it without
/// observation. A blow-up is a point marked unstable, not a failure.
fn measure_with(
    label: &str,
    scale: f64,
    h: f64,
    tolerance: Option<f64>,
    settings: SweepSettings,
    run: impl Fn(bool) -> Result<Measured>,
) -> Result<SweepPoint> {
    let (error_end, max_error, evaluations, finite) = match run(true) {
        Ok((e, m, n)) => (e, m, n, e.is_finite()),
        Err(err) if is_blow_up(&err) || is_rapier_blow_up(&err) => {
            (f64::INFINITY, f64::INFINITY, 0, false)
        }
        Err(err) => return Err(err),
    };
    let cpu_seconds = if finite {
        min_time(settings.timing_runs, || run(false).map(|_| ()))?
    } else {
        f64::NAN
    };
    Ok(SweepPoint {
        method: label.into(),
        h,
        tolerance,
        error_end,
        max_error,
        cpu_seconds,
        evaluations,
        stable: finite && max_error < scale,
    })
}

/// Whether rapier2d's run went non-finite (its blow-up).
fn is_rapier_blow_up(err: &anyhow::Error) -> bool {
    matches!(
        err.downcast_ref::<RapierError>(),
        Some(RapierError::NonFinite { .. })
    )
}

/// Whether an error is the engine reporting a blow-up (a result, not a fault).
pub fn is_blow_up(err: &anyhow::Error) -> bool {
    matches!(
        err.downcast_ref::<EngineError>(),
        Some(EngineError::BlowUp { .. })
    )
}
