//! `simulate` on a `[linear_test]` scene: the scalar ODE stepped on the
//! run's grid, keeping at most `--max-samples` samples (a run of 1e8 steps
//! must not hold 1e8 vectors), stopped by `--budget`, and every printed or
//! written figure checked finite.
//!
//! The exact solution is finite over the run ([`scene::LinearTest::check_horizon`],
//! checked on loading for the file's duration and here for `--until`); the
//! method's y is finite (a non-finite y is the engine's blow-up error); the
//! error y − exact can still overflow when y is huge and of the other sign:
//! that is an error of the run, not a number written.

use super::outputs::{outputs, write_all};
use super::{SimulateArgs, duration_text};
use crate::pictures;
use crate::progress::{Budget, Ticker};
use crate::report::fmt_num;
use anyhow::{Context, Result, anyhow, bail};
use engine::error::readable;
use engine::time_grid::grid_time;
use engine::{Integrator, Method};
use scene::Scene;
use std::fmt::Write as _;
use std::time::Instant;

/// Runs a `[linear_test]` scene and writes its outputs.
pub(super) fn run_linear_test(
    scene: &Scene,
    args: &SimulateArgs,
    method: Method,
    (dt, until): (f64, f64),
    header: &str,
) -> Result<()> {
    if args.gif.is_some() {
        bail!(
            "--gif: {} is a [linear_test] scene, with no bodies to animate (use --svg for its y(t) curve)",
            scene.origin()
        );
    }
    if !args.compare.is_empty() {
        bail!(
            "--compare: {} is a [linear_test] scene; only scenes of bodies run in rapier2d",
            scene.origin()
        );
    }
    if method.needs_second_order() {
        bail!(
            "--method {}: needs a (position, velocity) system; a [linear_test] is first order",
            method.id()
        );
    }
    let test = scene
        .linear_test()
        .ok_or_else(|| anyhow!("{}: not a [linear_test] scene", scene.origin()))?;
    test.check_horizon(until).map_err(|reason| {
        let from = if args.until.is_some() {
            "--until"
        } else {
            "simulation.duration"
        };
        anyhow!("{}: {from}: {reason}", scene.origin())
    })?;
    println!("{header}");
    let started = Instant::now();
    let run = solve(&test, method, (dt, until), args)
        .with_context(|| format!("{}: the run failed", scene.origin()))?;
    let mut csv = String::from("t,y,exact,error\n");
    for (t, y) in run.t.iter().zip(&run.y) {
        let exact = test.exact(*t);
        let error = y - exact;
        if !error.is_finite() {
            bail!(
                "{}: at t = {} s the method's y = {} and the exact {} differ by more than f64 holds: the run diverged (use a smaller dt or an implicit method)",
                scene.origin(),
                readable(*t),
                readable(*y),
                readable(exact)
            );
        }
        let _ = writeln!(csv, "{t:?},{y:?},{exact:?},{error:?}");
    }
    let (t_end, y_end) = (run.t[run.t.len() - 1], run.y[run.y.len() - 1]);
    let exact = test.exact(t_end);
    println!(
        "ran {} steps to t = {} s in {}{}\ny = {}, exact {}, error {:.3e}",
        run.steps,
        fmt_num(t_end),
        duration_text(started.elapsed().as_secs_f64()),
        if run.stopped_by_budget {
            " (stopped by --budget)"
        } else {
            ""
        },
        fmt_num(y_end),
        fmt_num(exact),
        y_end - exact
    );
    let mut files = Vec::new();
    let outputs = outputs(args);
    for out in &outputs {
        let bytes = match out.option {
            "--trace" => csv.clone().into_bytes(),
            "--svg" => pictures::svg::linear_test_curve(
                scene.origin(),
                &format!("{}, dt = {} s", method.id(), super::fmt_short(dt)),
                &run.t,
                &run.y,
                |t| test.exact(t),
            )
            .with_context(|| format!("--svg {}", out.path.display()))?
            .into_bytes(),
            _ => continue,
        };
        files.push((out, bytes));
    }
    write_all(None, &files, (run.t.len() as u64, run.stride))
}

/// A sampled scalar run.
struct Run {
    t: Vec<f64>,
    y: Vec<f64>,
    steps: u64,
    stride: u64,
    stopped_by_budget: bool,
}

/// Steps the test from t = 0 to `until` on the grid of
/// [`engine::World::run`] (the same as [`scene::LinearTest::solve`]),
/// keeping every `stride`-th step.
fn solve(
    test: &scene::LinearTest,
    method: Method,
    (dt, until): (f64, f64),
    args: &SimulateArgs,
) -> Result<Run> {
    let steps = engine::step_count(until, dt)?;
    let stride = steps.div_ceil(args.max_samples.max(2) - 1).max(1);
    let mut system = *test;
    let mut integrator = Integrator::new(method)?;
    let mut y = [test.y0];
    let mut t = 0.0;
    let mut run = Run {
        t: vec![0.0],
        y: vec![test.y0],
        steps: 0,
        stride,
        stopped_by_budget: false,
    };
    let mut ticker = Ticker::for_loop(steps, "simulating");
    let budget = Budget::new(args.budget);
    for i in 1..=steps {
        let t_next = grid_time(0.0, until, dt, i, steps);
        while t < t_next {
            let taken = integrator.advance(&mut system, t, &mut y, t_next - t)?;
            // A step that used all the room left lands exactly on t_next.
            t = if taken == t_next - t {
                t_next
            } else {
                t + taken
            };
        }
        ticker.tick();
        run.steps = i;
        let out_of_time = i < steps && budget.exhausted();
        if i % stride == 0 || i == steps || out_of_time {
            run.t.push(t_next);
            run.y.push(y[0]);
        }
        if out_of_time {
            run.stopped_by_budget = true;
            break;
        }
    }
    ticker.finish();
    if run.stopped_by_budget {
        budget.say_stopped(t, run.steps, steps);
    }
    Ok(run)
}
