//! `harness simulate <scene.toml>`: runs a scene file of your own and
//! writes what you ask for.
//!
//! ```text
//! harness simulate scene.toml [--method M] [--dt H] [--until T]
//!     [--trace out.csv] [--svg out.svg] [--gif out.gif] [--html out.html]
//!     [--compare rapier,box2d] [--verbose] [--budget SECONDS]
//!     [--max-samples N] [--frames N] [--threads N]
//! ```
//!
//! - the scene runs with its own `[simulation]` method, step and duration,
//!   each overridable on the command line (a terminal event such as a
//!   landing may end it earlier); a `[linear_test]` scene solves its scalar
//!   ODE instead;
//! - `--trace`: CSV, one row per sample and body: `t, body, x, y, angle,
//!   vx, vy, omega, energy` (s, m, rad, m/s, rad/s, J; `energy` is the
//!   world's total, kinetic plus potential, repeated on each body's row).
//!   Numbers are written in Rust's shortest round-trip form, so they read
//!   back bit for bit. A `[linear_test]` trace has `t, y, exact, error`.
//!   Written by hand (no csv crate): names are quoted when they need it
//!   ([`trace`]);
//! - `--svg`: a filmstrip of six frames; `--gif`: an animation (at most
//!   `--frames`, default 120, ≤ 200); a `[linear_test]` gets its y(t) curve
//!   as SVG and no animation;
//! - `--html`: an interactive replay, one self-contained page
//!   ([`crate::replay`]), with the engines of `--compare` beside the run;
//! - `--compare rapier`, `--compare box2d` or both (`rapier,box2d`): runs
//!   the scene in rapier2d-f64 0.36 and Box2D 3.2 too, whenever their
//!   adapters can represent it ([`compare`]), and prints the largest
//!   difference of each quantity (`--verbose`: and each engine's
//!   configuration);
//! - `--budget SECONDS`: a wall-time limit, checked between steps: the run
//!   stops after the step that spends it, says so (stdout and stderr,
//!   exit code 0), and the outputs cover the part that ran;
//! - on a terminal, a progress bar appears once a run has lasted a second,
//!   redrawn while a slow step goes on ([`crate::progress`]).
//!
//! Memory does not grow with the number of steps: a run keeps only what
//! its outputs need. [`stream`] steps the world and hands each sample (at
//! most `--max-samples`: every k-th step, the first and the last) to its
//! consumers, keeping only what the printed summary needs ([`Run`]: the
//! steps, the first, last and highest energy, the end time, the events);
//! with no output asked, nothing else is kept. `--trace` writes each
//! sample's rows to its temporary file as the run goes ([`trace`]), the
//! overlap warning of a scene without contacts searches the samples as
//! they come ([`contacts_off`]); the pictures and the replay, which draw
//! from the whole run, keep their samples in memory ([`Samples`], at most
//! `--max-samples` of every body), and `--compare` keeps what
//! [`compare`] says. The printed run time leaves out the time spent
//! keeping samples (writing the trace's rows, searching for overlaps).
//! `--verbose` prints the process's peak resident set
//! (`getrusage`), and `harness bench` measures it on the large scenes
//! ([`crate::bench::memory`]).
//!
//! Bad input never panics and never costs the user's work: the scene file
//! is only read, every error (the scene's, with file, field and line, or a
//! command-line value) is reported before the run, and the outputs are
//! written only after the run succeeded, each to a temporary file renamed
//! into place (the trace's is in the destination folder from the start of
//! the run, and removed when the run fails). An output path must end in its format's extension
//! (`--trace` .csv, `--svg` .svg, `--gif` .gif, in any case): `--svg a.png`
//! is refused rather than writing SVG into a `.png`. An output path equal
//! to the scene file is refused, and so
//! is an existing one that is not a regular file (a link, a FIFO, a device:
//! the rename would replace it).
//!
//! Non-finite figures are errors, never numbers: a step whose energy is
//! not a finite number fails the run (exit code 2, nothing written) with a
//! hint naming the fastest body; a `[linear_test]` whose exact solution or
//! error overflows is refused; a picture whose axes cannot be drawn is
//! refused or drawn with a widened view that says so
//! ([`crate::pictures::axis_range`]). A failure of the adaptive method
//! names the force that makes the problem stiff.

pub(crate) mod compare;
mod contacts_off;
mod diagnosis;
mod linear_test;
mod outputs;
mod run_text;
pub mod trace;
mod warnings;

use outputs::{Output, check_outputs, outputs, write_all};
pub use outputs::{refuse_special, write_atomically};
use trace::TraceFile;

use crate::pictures::{self, Film, GifOptions};
use crate::progress::{Budget, Ticker};
use crate::report::fmt_num;
use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, ValueEnum};
use engine::time_grid::grid_time;
use engine::{BodyState, EventRecord, MAX_RUN_STEPS, Method, Tolerance, World};
use scene::Scene;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `simulate`.
#[derive(Debug, Clone, Args)]
pub struct SimulateArgs {
    /// The scene file (TOML; see "Write your own scene" in the README).
    pub scene: PathBuf,
    /// Integration method instead of the file's: explicit_euler,
    /// semi_implicit_euler, rk2_midpoint, rk4, velocity_verlet,
    /// implicit_euler or dormand_prince.
    #[arg(long, value_name = "M", value_parser = parse_method)]
    pub method: Option<String>,
    /// Time step in seconds instead of the file's (> 0).
    #[arg(long, value_name = "H", value_parser = parse_seconds, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Run length in seconds instead of the file's duration (> 0).
    #[arg(long, value_name = "T", value_parser = parse_seconds, allow_negative_numbers = true)]
    pub until: Option<f64>,
    /// Write the trace as CSV: t, body, x, y, angle, vx, vy, omega, energy.
    #[arg(long, value_name = "out.csv")]
    pub trace: Option<PathBuf>,
    /// Write a filmstrip of six frames as SVG.
    #[arg(long, value_name = "out.svg")]
    pub svg: Option<PathBuf>,
    /// Write an animation as GIF.
    #[arg(long, value_name = "out.gif")]
    pub gif: Option<PathBuf>,
    /// Write an interactive replay: one self-contained HTML page (play,
    /// pause, step, scrub, speed, zoom, pan, paths, each body's state; the
    /// engines of --compare side by side or overlaid).
    #[arg(long, value_name = "out.html")]
    pub html: Option<PathBuf>,
    /// Frames of the GIF (2 to 200).
    #[arg(long, value_name = "N", default_value_t = 120,
          value_parser = clap::value_parser!(u16).range(2..=200))]
    pub frames: u16,
    /// Most samples kept in the trace, the pictures and the replay: a
    /// longer run keeps every k-th step (and always the first and the
    /// last).
    #[arg(long, value_name = "N", default_value_t = 100_000,
          value_parser = clap::value_parser!(u64).range(2..=100_000_000))]
    pub max_samples: u64,
    /// Wall-time budget in seconds (> 0): the run stops after the step
    /// that spends it, says so, and writes the outputs for the part that
    /// ran. Checked between steps.
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds, allow_negative_numbers = true)]
    pub budget: Option<f64>,
    /// Run the scene in other engines too and print the differences:
    /// rapier, box2d, or both (`--compare rapier,box2d`).
    #[arg(long, value_name = "ENGINE", value_delimiter = ',')]
    pub compare: Vec<CompareWith>,
    /// Print how each engine of --compare is configured, and the run's peak
    /// memory (resident set, getrusage).
    #[arg(long)]
    pub verbose: bool,
    /// Threads of the soft step's parallel stages (1 to 256) instead of
    /// the file's `[simulation] threads`: the trace is the same bits at
    /// every count, only the time changes.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: Option<u16>,
}

/// Engines `--compare` knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CompareWith {
    /// rapier2d-f64 0.36: bent towards ideal rigid-body physics for scenes
    /// without contacts or with exact ones, at its defaults for the soft
    /// step.
    Rapier,
    /// Box2D 3.2 (boxdd 0.6), at its defaults.
    Box2d,
}

/// The method ids `--method` accepts.
pub fn method_ids() -> Vec<&'static str> {
    Method::FIXED_STEP
        .iter()
        .map(Method::id)
        .chain(["dormand_prince"])
        .collect()
}

fn parse_method(text: &str) -> Result<String, String> {
    if Method::from_id(text, Tolerance::uniform(1.0)).is_some() {
        Ok(text.to_owned())
    } else {
        Err(format!(
            "unknown method; expected one of {}",
            method_ids().join(", ")
        ))
    }
}

fn parse_seconds(text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| "not a number of seconds".to_string())?;
    if !value.is_finite() {
        return Err("must be a finite number of seconds".into());
    }
    if value <= 0.0 {
        return Err(format!("must be > 0 s, got {value}"));
    }
    Ok(value)
}

/// Limits of a recorded run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunLimits {
    /// Most samples kept (≥ 2): a longer run keeps every k-th step.
    pub max_samples: u64,
    /// Wall-time budget (s): the run stops after the step that spends it,
    /// keeping what it has. `None`: no limit.
    pub budget: Option<f64>,
}

impl Default for RunLimits {
    /// 100 000 samples, no budget.
    fn default() -> Self {
        Self {
            max_samples: 100_000,
            budget: None,
        }
    }
}

/// What a run did, kept as it goes whatever the outputs: what the printed
/// summary and the warnings need, of a size independent of the number of
/// steps (save the located events, which are few: a landing ends the run).
#[derive(Debug, Clone, Default)]
pub struct Run {
    /// Steps taken.
    pub steps: u64,
    /// Every `stride`-th step was sampled (and the first and the last).
    pub stride: u64,
    /// Samples taken, the initial state included.
    pub samples: u64,
    /// Time of the last sample, where the run ended (s).
    pub end_time: f64,
    /// Total energy at t = 0 (J).
    pub first_energy: f64,
    /// Total energy at the last sample (J).
    pub last_energy: f64,
    /// The largest total energy of the samples after the first (J); −∞
    /// when there is none.
    pub highest_energy: f64,
    /// Events located, in time order.
    pub events: Vec<EventRecord>,
    /// Whether a terminal event (a landing) ended the run.
    pub stopped_by_event: bool,
    /// Whether the wall-time budget ended the run early.
    pub stopped_by_budget: bool,
}

impl Run {
    /// Counts a sample of total energy `energy` (J) taken at `t` (s).
    fn note(&mut self, t: f64, energy: f64) {
        if self.samples == 0 {
            self.first_energy = energy;
            self.highest_energy = f64::NEG_INFINITY;
        } else {
            self.highest_energy = self.highest_energy.max(energy);
        }
        self.samples += 1;
        self.end_time = t;
        self.last_energy = energy;
    }
}

/// Samples of a run held in memory: what the pictures and the replay
/// draw from (at most `--max-samples` of them, every body's state in
/// each), kept only when one of them is asked for.
#[derive(Debug, Clone, Default)]
pub struct Samples {
    /// Sample times (s).
    pub times: Vec<f64>,
    /// Every body's state at each sample.
    pub states: Vec<Vec<BodyState>>,
    /// Total energy at each sample (J).
    pub energies: Vec<f64>,
}

impl Samples {
    /// Keeps the world's current state, of total energy `energy` (J).
    pub fn push(&mut self, world: &World, energy: f64) {
        self.times.push(world.time());
        self.states.push(world.states().to_vec());
        self.energies.push(energy);
    }

    /// Copies the samples into `film`.
    pub fn fill(&self, film: &mut Film) {
        for (t, states) in self.times.iter().zip(&self.states) {
            film.push(*t, states);
        }
    }
}

/// A run with its samples in memory: what [`record`] returns.
#[derive(Debug, Clone, Default)]
pub struct Recorded {
    /// What the run did.
    pub run: Run,
    /// Its samples.
    pub samples: Samples,
}

/// Every how many steps [`record`] keeps a sample of a run of `steps`
/// steps to keep at most `max_samples` (≥ 2), the first and last included.
pub fn stride_for(steps: u64, max_samples: u64) -> u64 {
    (steps.div_ceil(max_samples.max(2) - 1)).max(1)
}

/// Samples a run of `steps` steps takes at `stride`: the initial state,
/// every `stride`-th step and the last (fewer when the run ends early).
pub fn samples_for(steps: u64, stride: u64) -> u64 {
    steps.div_ceil(stride.max(1)) + 1
}

/// Runs `world` from its current time to `until` (s) in steps of `dt`
/// (s), on the grid of [`World::run`] (times `t0 + i·dt`, the last step
/// shortened to end at `until`), sampling at most `limits.max_samples`
/// times, and keeps no sample: `on_sample(world, energy)` is called at
/// each (the initial state first; `energy` is the world's total, J), and
/// may stream it somewhere or keep what it needs; an error it returns
/// ends the run with that error. After every step, `on_step(i, whole,
/// world)` is called, before the step's sample, with `whole` true when the
/// world stands at exactly `t0 + i·dt` (not after a shortened last step or
/// a terminal event). `ticker` counts the steps. A sampled step whose
/// energy is not a finite number fails the run
/// ([`engine::EngineError::BlowUp`]). When `limits.budget` is spent, the
/// run stops after the current step with what it has
/// (`stopped_by_budget`), and says so on stderr.
pub fn stream(
    world: &mut World,
    until: f64,
    dt: f64,
    limits: &RunLimits,
    mut ticker: Ticker,
    mut on_step: impl FnMut(u64, bool, &World),
    mut on_sample: impl FnMut(&World, f64) -> Result<()>,
) -> Result<Run> {
    let t0 = world.time();
    let span = until - t0;
    let steps = engine::step_count(span, dt)?;
    let last_is_whole = (steps as f64 * dt - span).abs() <= 1e-9 * span;
    let stride = stride_for(steps, limits.max_samples);
    let mut run = Run {
        stride,
        ..Run::default()
    };
    let energy = world.energy();
    run.note(world.time(), energy);
    on_sample(world, energy)?;
    let budget = Budget::new(limits.budget);
    for i in 1..=steps {
        let t = grid_time(t0, until, dt, i, steps);
        let events = world
            .step_to(t)
            .map_err(|e| diagnosis::step_failed(e, i, steps, world.time()))?;
        run.events.extend(events);
        let stopped = world.is_stopped();
        let out_of_time = !stopped && i < steps && budget.exhausted();
        let sampled = i % stride == 0 || i == steps || stopped || out_of_time;
        // A world built from a scene checks the energy of its steps, but
        // not of a step cut short by a terminal event: the energy of every
        // sample (what is printed and written) is checked here too.
        let energy = if sampled { world.energy() } else { 0.0 };
        if !energy.is_finite() {
            let blow_up = engine::EngineError::BlowUp {
                t: world.time(),
                step: i - 1,
                reason: format!("energy {energy} J is not a finite number"),
            };
            return Err(diagnosis::step_failed(blow_up, i, steps, world.time()));
        }
        ticker.tick();
        on_step(i, !stopped && (i < steps || last_is_whole), world);
        run.steps = i;
        if sampled {
            run.note(world.time(), energy);
            on_sample(world, energy)?;
        }
        if stopped {
            run.stopped_by_event = true;
            break;
        }
        if out_of_time {
            run.stopped_by_budget = true;
            break;
        }
    }
    // The bar is cleared before the note, which would otherwise be drawn
    // over.
    ticker.finish();
    if run.stopped_by_budget {
        budget.say_stopped(world.time(), run.steps, steps);
    }
    Ok(run)
}

/// [`stream`], keeping every sample in memory: for the callers that draw
/// or check the whole run (pictures, replays, the fuzzer), whose memory
/// is at most `limits.max_samples` samples of every body.
pub fn record(
    world: &mut World,
    until: f64,
    dt: f64,
    limits: &RunLimits,
    ticker: Ticker,
    on_step: impl FnMut(u64, bool, &World),
) -> Result<Recorded> {
    let mut samples = Samples::default();
    let run = stream(world, until, dt, limits, ticker, on_step, |w, energy| {
        samples.push(w, energy);
        Ok(())
    })?;
    Ok(Recorded { run, samples })
}

/// Step count of the run, with the command-line options named when they
/// make it too long (the file's own values were checked on loading).
fn steps_of(scene: &Scene, args: &SimulateArgs, dt: f64, until: f64) -> Result<u64> {
    engine::step_count(until, dt).map_err(|_| {
        let dt_from = if args.dt.is_some() { "--dt" } else { "simulation.dt" };
        let until_from = if args.until.is_some() {
            "--until"
        } else {
            "simulation.duration"
        };
        anyhow!(
            "{}: a run of {} s ({until_from}) in steps of {} s ({dt_from}) would take {:.3e} steps, more than the {MAX_RUN_STEPS:.0e} allowed: raise {dt_from} or shorten {until_from}",
            scene.origin(),
            fmt_num(until),
            fmt_num(dt),
            until / dt
        )
    })
}

/// Runs `simulate`.
pub fn run(args: &SimulateArgs) -> Result<()> {
    let started = Instant::now();
    let scene = Scene::load(&args.scene)?;
    tracing::debug!(scene = %scene.origin(), "scene loaded");
    let method = match &args.method {
        Some(id) => Method::from_id(id, scene.tolerance()).ok_or_else(|| {
            anyhow!(
                "--method {id}: unknown method; expected one of {}",
                method_ids().join(", ")
            )
        })?,
        None => scene.method(),
    };
    let dt = args.dt.unwrap_or(scene.dt());
    let until = args.until.unwrap_or(scene.duration());
    let steps = steps_of(&scene, args, dt, until)?;
    let requested = outputs(args);
    check_outputs(&args.scene, &requested)?;
    let header = format!(
        "{}: {}, dt = {} s, until {} s ({steps} steps)",
        scene.origin(),
        method.id(),
        fmt_short(dt),
        fmt_short(until)
    );
    if scene.is_linear_test() {
        return linear_test::run_linear_test(&scene, args, method, (dt, until), &header);
    }
    let mut world = scene.build_world(None)?;
    if let Some(id) = &args.method {
        refuse_method_under_soft_step(&scene, &world, id, method)?;
        world = scene.build_world(Some(method))?;
    }
    if let Some(threads) = args.threads {
        let Some(engine::ContactModel::SoftStep(settings)) = world.contact_model() else {
            bail!(
                "{}: --threads is a setting of the soft-step contact model, which this scene does \
                 not use",
                args.scene.display()
            );
        };
        world.set_contact_model(engine::ContactModel::SoftStep(engine::SoftStepSettings {
            threads: usize::from(threads),
            ..settings
        }))?;
    }
    let mut engines: Vec<CompareWith> = Vec::new();
    for e in &args.compare {
        if !engines.contains(e) {
            engines.push(*e);
        }
    }
    let stride = stride_for(steps, args.max_samples);
    let mut comparison = if engines.is_empty() {
        None
    } else {
        Some(compare::Comparison::prepare(
            &scene,
            &engines,
            (dt, steps, stride),
            world.states(),
            args.html.is_some(),
            args.verbose,
        )?)
    };
    println!("{header}");
    println!("{}", run_text::model_line(&world, dt));
    if let Some(line) = run_text::outlines_line(scene.file()) {
        println!("{line}");
    }
    for warning in warnings::before_run(&scene, dt, args.dt.is_some(), until) {
        eprintln!("{warning}");
    }
    let limits = RunLimits {
        max_samples: args.max_samples,
        budget: args.budget,
    };
    // What the outputs asked keep of the run as it goes: the trace streams
    // its rows to its temporary file, the pictures and the replay keep
    // their samples; with none asked, nothing is kept per step.
    let names = scene.body_names();
    let mut trace = match requested.iter().find(|o| o.option == "--trace") {
        Some(out) => Some((
            out,
            TraceFile::create(out.path, &names)
                .with_context(|| format!("--trace {}", out.path.display()))?,
        )),
        None => None,
    };
    let drawn = args.svg.is_some() || args.gif.is_some() || args.html.is_some();
    let mut samples = drawn.then(Samples::default);
    let mut overlap = contacts_off::OverlapWatch::new(&world, samples_for(steps, stride));
    let ticker = Ticker::for_loop(steps, "simulating");
    let run_started = Instant::now();
    // Time spent keeping samples (the trace's rows, the overlap search),
    // not counted in the run's time.
    let mut keeping = std::time::Duration::ZERO;
    let on_step = |i, whole, w: &World| {
        if let Some(c) = comparison.as_mut() {
            c.observe(i, whole, w);
        }
    };
    let on_sample = |w: &World, energy| {
        let started = Instant::now();
        if let Some(watch) = overlap.as_mut() {
            watch.sample(w);
        }
        if let Some(samples) = samples.as_mut() {
            samples.push(w, energy);
        }
        if let Some((out, file)) = trace.as_mut() {
            file.sample(w.time(), w.states(), energy)
                .with_context(|| format!("--trace {}", out.path.display()))?;
        }
        keeping += started.elapsed();
        Ok(())
    };
    let run = stream(&mut world, until, dt, &limits, ticker, on_step, on_sample).map_err(|e| {
        diagnosis::explain(e, &scene, &world, dt).context(scene.origin().to_owned())
    })?;
    let run_time = run_started.elapsed().saturating_sub(keeping);
    print!("{}", summary(&scene, &world, &run, run_time.as_secs_f64()));
    let references = match comparison {
        Some(c) => {
            let (text, runs) = c.report()?;
            print!("{text}");
            for (message, count) in references::box2d_world::log::repeated() {
                eprintln!("Box2D logged \"{message}\" {count} times in all (printed once)");
            }
            runs
        }
        None => Vec::new(),
    };
    if let Some(warning) = warnings::energy_growth(
        scene.origin(),
        method.id(),
        dt,
        (run.first_energy, run.highest_energy),
    ) {
        eprintln!("{warning}");
    }
    if let Some((t, a, b)) = overlap.as_ref().and_then(contacts_off::OverlapWatch::first) {
        let advice = "add `[contact]` (model = \"soft_step\", the default, or \"exact\") to make them collide";
        let warning = format!(
            "warning: {}: bodies '{}' and '{}' overlap at t = {} s, but contacts are off (the scene has no [contact] table), so they pass through each other; {advice}",
            scene.origin(),
            names[a],
            names[b],
            fmt_short(t)
        );
        eprintln!("{warning}");
    }
    // Everything ran: now build the pictures and the replay in memory,
    // then write them and rename the trace into place.
    let samples = samples.unwrap_or_default();
    let mut files: Vec<(&Output<'_>, Vec<u8>)> = Vec::new();
    for out in &requested {
        let bytes = match out.option {
            "--svg" | "--gif" => {
                let film = film_of(&scene, &world, (&samples, &run.events), method, dt);
                if out.option == "--svg" {
                    pictures::svg::filmstrip(&film, pictures::FILMSTRIP_FRAMES)
                        .map_err(|e| e.context(format!("--svg {}", out.path.display())))?
                        .into_bytes()
                } else {
                    let options = GifOptions {
                        max_frames: usize::from(args.frames),
                        ..GifOptions::default()
                    };
                    pictures::gif::animation(&film, &options)
                        .map_err(|e| e.context(format!("--gif {}", out.path.display())))?
                }
            }
            "--html" => {
                let title = scene_name(&scene);
                let mut replay = crate::replay::Replay::new(
                    &scene,
                    world.bodies(),
                    title,
                    format!("{}, dt = {} s", method.id(), fmt_short(dt)),
                    dt * run.stride as f64,
                );
                replay.runs.push(crate::replay::ReplayRun {
                    label: format!("this engine ({}, dt = {} s)", method.id(), fmt_short(dt)),
                    short: "engine".into(),
                    times: samples.times.clone(),
                    states: samples.states.clone(),
                    energies: Some(samples.energies.clone()),
                    events: crate::replay::ReplayEvent::from_records(&scene, &run.events),
                });
                replay.runs.extend(references.iter().cloned());
                replay
                    .page()
                    .map_err(|e| e.context(format!("--html {}", out.path.display())))?
                    .html
                    .into_bytes()
            }
            _ => continue,
        };
        files.push((out, bytes));
    }
    let trace = trace.map(|(out, file)| (out, file.into_staged()));
    write_all(trace, &files, (run.samples, run.stride))?;
    if args.verbose {
        match crate::bench::memory::own_peak_kib() {
            Ok(kib) => println!(
                "peak memory: {:.0} MB (this process's peak resident set, getrusage)",
                kib as f64 * 1024.0 / 1e6
            ),
            Err(e) => println!("peak memory: not measured ({e})"),
        }
    }
    tracing::info!("simulate done in {:.3} s", started.elapsed().as_secs_f64());
    Ok(())
}

/// Refuses `--method ID` (`method`) on a scene that runs under the soft
/// step (which integrates by itself, by semi-implicit Euler per substep):
/// the fault is the option's, not the file's `[contact]` table.
fn refuse_method_under_soft_step(
    scene: &Scene,
    world: &World,
    id: &str,
    method: Method,
) -> Result<()> {
    let soft = matches!(
        world.contact_model(),
        Some(engine::ContactModel::SoftStep(_))
    );
    if !soft || method == Method::SemiImplicitEuler {
        return Ok(());
    }
    let why = if scene.file().contact.is_some() {
        "its [contact] table asks for the soft-step contact model"
    } else {
        "it has joints, which run under the soft-step contact model"
    };
    let exact = if scene.joint_count() == 0 {
        format!(", or set [contact] model = \"exact\" in the file to integrate it by {id}")
    } else {
        String::new()
    };
    Err(anyhow!(
        "--method {id}: {} runs under the soft step ({why}), which integrates by itself \
         (semi-implicit Euler per substep) and takes no other method: drop --method{exact}",
        scene.origin()
    ))
}

/// `error` and its causes on one line, each said once, joined by ": ".
pub(crate) fn one_line(error: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in error.chain() {
        let part = cause.to_string();
        if text.contains(&part) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&part);
    }
    text
}

/// A replay of `scene` run with its own method, step and duration, with
/// every engine of `engines` that can represent it beside it; an engine
/// that cannot is a note on the page, with its reason. `title` heads the
/// page.
pub fn replay_of(
    scene: &Scene,
    engines: &[CompareWith],
    title: String,
) -> Result<crate::replay::Replay> {
    let method = scene.method();
    let (dt, until) = (scene.dt(), scene.duration());
    let mut world = scene.build_world(None)?;
    let limits = RunLimits::default();
    let steps = engine::step_count(until, dt)?;
    let stride = stride_for(steps, limits.max_samples);
    let mut notes = Vec::new();
    let mut comparisons = Vec::new();
    for &engine in engines {
        match compare::Comparison::prepare(
            scene,
            &[engine],
            (dt, steps, stride),
            world.states(),
            true,
            false,
        ) {
            Ok(c) => comparisons.push(c),
            Err(e) => notes.push(format!("Not compared: {e:#}.")),
        }
    }
    let ticker = Ticker::new(indicatif::ProgressBar::hidden(), 1);
    let recorded = record(&mut world, until, dt, &limits, ticker, |i, whole, w| {
        for c in &mut comparisons {
            c.observe(i, whole, w);
        }
    })?;
    let mut replay = crate::replay::Replay::new(
        scene,
        world.bodies(),
        title,
        format!("{}, dt = {} s", method.id(), fmt_short(dt)),
        dt * recorded.run.stride as f64,
    );
    replay.notes = notes;
    replay.runs.push(crate::replay::ReplayRun {
        label: format!("this engine ({}, dt = {} s)", method.id(), fmt_short(dt)),
        short: "engine".into(),
        times: recorded.samples.times,
        states: recorded.samples.states,
        energies: Some(recorded.samples.energies),
        events: crate::replay::ReplayEvent::from_records(scene, &recorded.run.events),
    });
    for c in comparisons {
        let (_, runs) = c.report()?;
        replay.runs.extend(runs);
    }
    Ok(replay)
}

/// The scene file's name (without its folders).
fn scene_name(scene: &Scene) -> String {
    Path::new(scene.origin()).file_name().map_or_else(
        || scene.origin().to_owned(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// A number as short as it reads back (Rust's shortest round trip) when
/// that is at most 10 characters, else to 6 significant digits: `0.01`,
/// `5.85` for 5.8500000000000005.
pub fn fmt_short(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() <= 10 {
        return plain;
    }
    let rounded: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    let again = format!("{rounded}");
    if again.len() <= 12 {
        again
    } else {
        format!("{v:.5e}")
    }
}

fn film_of(
    scene: &Scene,
    world: &World,
    (samples, events): (&Samples, &[EventRecord]),
    method: Method,
    dt: f64,
) -> Film {
    let name = scene_name(scene);
    let mut film = Film::new(
        scene,
        world.bodies(),
        name,
        format!("{}, dt = {} s", method.id(), fmt_short(dt)),
    );
    samples.fill(&mut film);
    film.mark_events(scene, events);
    film
}

/// A duration for people: ms below a second.
fn duration_text(seconds: f64) -> String {
    if seconds < 1.0 {
        format!("{:.1} ms", seconds * 1e3)
    } else {
        format!("{seconds:.2} s")
    }
}

/// What the run did: steps, events, final states, energy (10 significant
/// digits; the CSV has every digit).
fn summary(scene: &Scene, world: &World, rec: &Run, seconds: f64) -> String {
    let mut out = String::new();
    let end = rec.end_time;
    let ended_by = match (rec.stopped_by_event, rec.events.last()) {
        (true, Some(e)) => format!(" (ended by the {} event)", e.name),
        _ if rec.stopped_by_budget => " (stopped by --budget: the outputs cover this part)".into(),
        _ => String::new(),
    };
    let _ = writeln!(
        out,
        "ran {} steps to t = {} s in {}{ended_by}",
        rec.steps,
        fmt_num(end),
        duration_text(seconds),
    );
    let names = scene.body_names();
    if !rec.events.is_empty() {
        let _ = writeln!(out, "events:");
        for e in &rec.events {
            let _ = write!(out, "  {:<8} t = {} s", e.name, fmt_num(e.t));
            if let Some(id) = event_body(scene, &e.name) {
                let p = e.states[id].position;
                let _ = write!(
                    out,
                    ", {} at x = {} m, y = {} m",
                    names[id],
                    fmt_num(p.x),
                    fmt_num(p.y)
                );
            }
            out.push('\n');
        }
    }
    if world.bodies().len() > run_text::LISTED_BODIES {
        out.push_str(&run_text::pile_summary(world, &names, fmt_num));
    } else {
        let _ = writeln!(out, "final state:");
    }
    let listed = if world.bodies().len() > run_text::LISTED_BODIES {
        0
    } else {
        world.bodies().len()
    };
    for (body, (name, s)) in world
        .bodies()
        .iter()
        .zip(names.iter().zip(world.states()))
        .take(listed)
    {
        let _ = write!(
            out,
            "  {name}: x = {} m, y = {} m, vx = {} m/s, vy = {} m/s",
            fmt_num(s.position.x),
            fmt_num(s.position.y),
            fmt_num(s.velocity.x),
            fmt_num(s.velocity.y)
        );
        if body.rotates() {
            let _ = write!(
                out,
                ", angle = {} rad, omega = {} rad/s",
                fmt_num(s.angle),
                fmt_num(s.angular_velocity)
            );
        }
        out.push('\n');
    }
    if rec.samples > 0 {
        let (e0, e1) = (rec.first_energy, rec.last_energy);
        // Each energy is finite (the world reports a non-finite one as a
        // blow-up); their difference may still overflow.
        let change = (e1 - e0) / e0.abs();
        let relative = if e0 != 0.0 && change.is_finite() {
            format!(" (relative change {change:.3e})")
        } else {
            String::new()
        };
        let _ = writeln!(
            out,
            "energy: {} J at t = 0, {} J at the end{relative}",
            fmt_num(e0),
            fmt_num(e1)
        );
    }
    out
}

fn event_body(scene: &Scene, name: &str) -> Option<usize> {
    use scene::format::EventEntry;
    scene.file().events.iter().find_map(|e| match e {
        EventEntry::Landing { body, .. } if name == "landing" => scene.body_id(body),
        EventEntry::Apex { body } if name == "apex" => scene.body_id(body),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seconds_must_be_finite_and_positive() {
        assert_eq!(parse_seconds("0.01"), Ok(0.01));
        for bad in ["0", "-1", "nan", "inf", "-inf", "abc", ""] {
            assert!(parse_seconds(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn methods_are_the_engine_ids() {
        assert_eq!(parse_method("rk4"), Ok("rk4".into()));
        let err = parse_method("rk5").unwrap_err();
        assert!(err.contains("dormand_prince"), "{err}");
    }

    #[test]
    fn a_recorded_run_keeps_at_most_max_samples() {
        let scene = Scene::parse_str(
            "inline.toml",
            "[simulation]\ndt = 0.001\nduration = 1.0\n[[bodies]]\nname = \"p\"\nmass = 1.0\nvelocity = [1.0, 0.0]\n",
        )
        .unwrap();
        let mut world = scene.build_world(None).unwrap();
        let limits = RunLimits {
            max_samples: 11,
            ..RunLimits::default()
        };
        let mut whole = 0;
        let rec = record(
            &mut world,
            1.0,
            0.001,
            &limits,
            Ticker::new(indicatif::ProgressBar::hidden(), 1),
            |_, w, _| whole += u64::from(w),
        )
        .unwrap();
        assert_eq!(rec.run.steps, 1000);
        assert_eq!(rec.run.stride, 100);
        assert_eq!(rec.samples.times.len(), 11);
        assert_eq!(rec.run.samples, 11);
        assert_eq!(samples_for(1000, 100), 11);
        assert_eq!(*rec.samples.times.last().unwrap(), 1.0);
        assert_eq!(rec.run.end_time, 1.0);
        assert_eq!(whole, 1000);
        let mut csv = Vec::from(trace::HEADER);
        let rows = trace::TraceRows::new(&["p"]);
        for ((t, states), e) in rec
            .samples
            .times
            .iter()
            .zip(&rec.samples.states)
            .zip(&rec.samples.energies)
        {
            rows.write(&mut csv, *t, states, *e).unwrap();
        }
        let csv = String::from_utf8(csv).unwrap();
        assert_eq!(csv.lines().count(), 12);
        assert!(csv.lines().nth(11).unwrap().starts_with("1.0,p,"), "{csv}");
    }

    #[test]
    fn a_streamed_run_notes_its_energies_without_keeping_samples() {
        // A free particle under gravity from rest: its energy is constant
        // up to rounding, so first, last and highest agree with the
        // recorded samples' to the bit (the same values, taken once).
        let scene = Scene::parse_str(
            "inline.toml",
            "[simulation]\ndt = 0.01\nduration = 1.0\ngravity = [0.0, -9.81]\n[[bodies]]\nname = \"p\"\nmass = 1.0\nposition = [0.0, 5.0]\n",
        )
        .unwrap();
        let limits = RunLimits {
            max_samples: 7,
            ..RunLimits::default()
        };
        let ticker = || Ticker::new(indicatif::ProgressBar::hidden(), 1);
        let mut world = scene.build_world(None).unwrap();
        let rec = record(&mut world, 1.0, 0.01, &limits, ticker(), |_, _, _| {}).unwrap();
        let mut world = scene.build_world(None).unwrap();
        let mut seen = 0;
        let run = stream(
            &mut world,
            1.0,
            0.01,
            &limits,
            ticker(),
            |_, _, _| {},
            |_, _| {
                seen += 1;
                Ok(())
            },
        )
        .unwrap();
        let e = &rec.samples.energies;
        assert_eq!(run.samples, e.len() as u64);
        assert_eq!(seen, e.len());
        assert_eq!(run.first_energy, e[0]);
        assert_eq!(run.last_energy, *e.last().unwrap());
        assert_eq!(
            run.highest_energy,
            e[1..].iter().copied().fold(f64::NEG_INFINITY, f64::max)
        );
        assert_eq!(run.end_time, *rec.samples.times.last().unwrap());
        // An error of the sample's consumer (a full disk) ends the run.
        let mut world = scene.build_world(None).unwrap();
        let failed = stream(
            &mut world,
            1.0,
            0.01,
            &limits,
            ticker(),
            |_, _, _| {},
            |w, _| {
                if w.time() > 0.5 {
                    bail!("disk full")
                } else {
                    Ok(())
                }
            },
        );
        assert!(failed.unwrap_err().to_string().contains("disk full"));
        assert!(world.time() < 0.6, "the run went on after the error");
    }
}
