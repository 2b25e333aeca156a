//! `cargo run --release -p harness`: runs every case and writes `reports/`.
//! Exits non-zero when a row fails.

use anyhow::{Result, bail};
use clap::{Parser, Subcommand};
use harness::cases::{CASES, Case, CaseRecord, find};
use harness::shard::{Joined, Run, Shard, ShardRecord, Unit};
use harness::study::StudySummary;
use harness::sweep::SweepSettings;
use harness::{report, workspace};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Validation harness of the 2D physics engine.
#[derive(Debug, Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Where `run` writes its report (before or after `run`). A full run
    /// writes the workspace's `reports/` by default (`target/quick-report/`
    /// with `--quick`); a run of selected cases writes nothing unless this
    /// is given, so it never replaces the full report with a partial one.
    #[arg(long, global = true, value_name = "DIR")]
    out: Option<PathBuf>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Lists the cases.
    List,
    /// Runs the selected cases (all when none is named).
    Run {
        /// Case ids, as `list` prints them.
        cases: Vec<String>,
        /// A reduced sweep (for CI and quick checks).
        #[arg(long)]
        quick: bool,
        /// Print every row's reason under it (by default only the rows
        /// whose verdict is not obvious from their numbers show theirs).
        #[arg(long)]
        reasons: bool,
        /// Run only share I of N of the run (`1/2`, `2/2`), into the folder
        /// `--out DIR` (required): the cases, the studies and the benchmark
        /// are split by a fixed rule; `merge` joins the shards' folders into
        /// the report the whole run writes (docs/sharding.md).
        #[arg(long, value_name = "I/N")]
        shard: Option<Shard>,
    },
    /// Joins the folders of `run --shard i/n` (every shard of one run, once)
    /// into the report the whole run writes: into `--out DIR`, or where the
    /// whole run would write (`reports/` for every case, not `--quick`).
    Merge {
        /// The shards' folders, in any order.
        #[arg(required = true, value_name = "DIR")]
        shards: Vec<PathBuf>,
        /// Print every row's reason under it.
        #[arg(long)]
        reasons: bool,
    },
    /// Runs a scene file of your own.
    Simulate(Box<harness::simulate::SimulateArgs>),
    /// Benchmarks this engine's soft step against rapier2d-f64 and Box2D v3
    /// on the many-body scenes, side by side, and writes
    /// `benchmarks.md`/`benchmarks.json` and the charts into the report
    /// folder (`reports/` unless `--out` says), and, writing `reports/`
    /// at the default sizes, the README's speed table (which only this
    /// command rewrites: a full run leaves it, so that timing noise alone
    /// does not change the README).
    Bench {
        /// Benchmark ids (`pyramid_20`, `joint_grid`, ...) to run alone
        /// (every scene when none is named); a selection needs `--out`
        /// (its report is partial) and skips the contact-precision study.
        scenes: Vec<String>,
        /// Full sizes (Box2D's many pyramids, smash, joint grid and ragdoll
        /// rain at their size: many minutes).
        #[arg(long)]
        full: bool,
        /// Also Box2D's SSE2 build, as a row of its own: a second build of
        /// Box2D (the crate `box2d_child/`, into target/), compiled before
        /// the timing (minutes the first time), run as a child process.
        #[arg(long)]
        box2d_sse2: bool,
        /// Also Box2D's double-precision build (boxdd's
        /// `double-precision`: f64 absolute positions, AVX2), built and run
        /// the same way.
        #[arg(long)]
        box2d_double: bool,
        /// Threads of the multi-threaded rows: this engine, rapier2d
        /// (`parallel`) and Box2D (its scheduler) again at this count,
        /// after the one-thread rows (1: the one-thread rows only).
        #[arg(long, value_name = "N", default_value_t = 2,
              value_parser = clap::value_parser!(u8).range(1..=32))]
        threads: u8,
    },
    /// Runs a scene file live in a window: pause, step, drag bodies,
    /// overlays (docs/view.md). Built with `--features view`.
    #[cfg(feature = "view")]
    View(Box<harness::view::ViewArgs>),
    /// Runs a scene file live in a window (docs/view.md): this build has
    /// no view; build it with `--features view`.
    #[cfg(not(feature = "view"))]
    #[command(disable_help_flag = true)]
    View {
        /// Whatever was given.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
}

/// Exit codes: 0 every row passed (or the command succeeded), 1 a row
/// failed, 2 the input was refused or the run could not be made (the
/// message names the file, the field and the line when it comes from a
/// scene file). Command-line usage errors are clap's, also 2.
/// A closed stdout (`harness simulate s.toml | head`) ends the process as
/// it ends `cat`, by SIGPIPE's default action, instead of a panic in
/// `println!` (Rust starts programs with SIGPIPE ignored).
fn die_quietly_on_a_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to its default before any
    // thread is started has no other effect on the program.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> std::process::ExitCode {
    // First, before any thread starts: SIGINT and SIGTERM then leave no
    // temporary file and no half-written output (`harness::interrupt`).
    harness::interrupt::install();
    die_quietly_on_a_closed_pipe();
    harness::progress::init_tracing();
    // rapier2d is built with `parallel`: its uses outside the benchmark's
    // multi-threaded rows stay on one thread.
    references::serial_rayon();
    match real_main() {
        Ok(true) => std::process::ExitCode::SUCCESS,
        Ok(false) => std::process::ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {}", error_message(&e));
            std::process::ExitCode::from(2)
        }
    }
}

/// The error and its causes joined by ": ", each said once: a cause whose
/// text the message already holds (a scene error quotes its I/O error,
/// which is also its source) is left out.
fn error_message(error: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}

fn real_main() -> Result<bool> {
    let cli = Cli::parse();
    match cli.command {
        Some(Command::List) => {
            refuse_out(cli.out.as_deref(), "list")?;
            list()?;
            Ok(true)
        }
        Some(Command::Simulate(args)) => {
            refuse_out(cli.out.as_deref(), "simulate")?;
            harness::simulate::run(&args)?;
            Ok(true)
        }
        Some(Command::Run {
            cases,
            quick,
            reasons,
            shard: Some(shard),
        }) => run_shard(&cases, quick, reasons, shard, cli.out),
        Some(Command::Run {
            cases,
            quick,
            reasons,
            shard: None,
        }) => run(&cases, quick, reasons, cli.out),
        Some(Command::Merge { shards, reasons }) => merge(&shards, reasons, cli.out),
        Some(Command::Bench {
            scenes,
            full,
            box2d_sse2,
            box2d_double,
            threads,
        }) => {
            if !scenes.is_empty() && cli.out.is_none() {
                bail!(
                    "bench {}: a benchmark of selected scenes writes a partial report; give --out DIR \
                     (the full benchmark writes reports/)",
                    scenes.join(" ")
                );
            }
            let dir = cli.out.unwrap_or_else(workspace::reports_dir);
            let settings = harness::bench::BenchSettings {
                box2d_sse2,
                box2d_double,
                threads: usize::from(threads),
                ..if full {
                    harness::bench::BenchSettings::FULL
                } else {
                    harness::bench::BenchSettings::BENCH
                }
            };
            let readme_too =
                scenes.is_empty() && workspace::same_dir(&dir, &workspace::reports_dir()) && !full;
            println!(
                "bench: writes benchmarks.md, benchmarks.json and the benchmark charts into {}{}.",
                dir.display(),
                if readme_too {
                    ", and the speed table of README.md"
                } else {
                    ""
                }
            );
            // Written aside and moved into place at the end: an interrupted
            // benchmark leaves the folder as it was.
            let staging = harness::interrupt::Staging::new(&dir)?;
            let results = harness::bench::run_selected(staging.dir(), settings, &scenes)?;
            let _hold = staging.commit()?;
            if readme_too {
                harness::bench::report::update_readme(&workspace::readme(), &results)?;
            }
            println!(
                "Benchmark report written to {}.",
                dir.join("benchmarks.md").display()
            );
            Ok(true)
        }
        #[cfg(feature = "view")]
        Some(Command::View(args)) => {
            refuse_out(cli.out.as_deref(), "view")?;
            harness::view::run(&args)?;
            Ok(true)
        }
        #[cfg(not(feature = "view"))]
        Some(Command::View { .. }) => bail!(
            "this harness was built without its live view: \
             cargo run --release -p harness --features view -- view SCENE.toml"
        ),
        None => run(&[], false, false, cli.out),
    }
}

/// `--out` is `run`'s: refused elsewhere rather than ignored.
fn refuse_out(out: Option<&Path>, command: &str) -> Result<()> {
    if let Some(dir) = out {
        bail!(
            "--out {}: `{command}` writes no report; --out DIR applies to `run`{}",
            dir.display(),
            if command == "simulate" {
                " (simulate writes where --trace, --svg, --gif and --html say)"
            } else {
                ""
            }
        );
    }
    Ok(())
}

/// `list`: the cases with their scene files, then every scene file.
fn list() -> Result<()> {
    println!("Cases:");
    let width = CASES.iter().map(|c| c.id.len()).max().unwrap_or(0);
    for c in CASES {
        println!("  {:<width$}  {}", c.id, c.title);
        if !c.scenes.is_empty() {
            println!("  {:<width$}  scenes: {}", "", c.scenes.join(", "));
        }
    }
    println!("Scene files ({}):", harness::scenes::scenes_dir().display());
    for path in harness::scenes::list()? {
        println!("  {}", path.display());
    }
    Ok(())
}

/// The cases named, each once, in the order given; every case when none
/// is. An unknown id is refused before anything runs.
fn select(ids: &[String]) -> Result<Vec<&'static Case>> {
    if ids.is_empty() {
        return Ok(CASES.iter().collect());
    }
    let mut selected: Vec<&'static Case> = Vec::new();
    for id in ids {
        let Some(case) = find(id) else {
            let known: Vec<&str> = CASES.iter().map(|c| c.id).collect();
            bail!("unknown case '{id}'; the cases are: {}", known.join(", "));
        };
        if !selected.iter().any(|c| c.id == case.id) {
            selected.push(case);
        }
    }
    Ok(selected)
}

/// Where a run of `selected` cases writes its report when `--out` does not
/// say: a full run into `reports/` (`target/quick-report/` with `--quick`),
/// a partial run nowhere.
fn default_out(full: bool, quick: bool) -> Option<PathBuf> {
    full.then(|| {
        if quick {
            workspace::quick_report_dir()
        } else {
            workspace::reports_dir()
        }
    })
}

/// Runs `cases` in parallel over the cores, each whole on one thread
/// ([`harness::pool`]: the longest expected first); returns their records
/// in the order of `cases`, their charts saved into `dir` when there is
/// one. A case's rows depend on nothing but the case (no state is shared
/// between cases), so they are the bits of a serial run; only the timing
/// notes some cases write (ms per step) see the other threads' load. The
/// first error in the order of `cases` is the one reported.
fn run_cases(cases: &[&'static Case], dir: Option<&Path>) -> Result<Vec<CaseRecord>> {
    let progress = harness::progress::bar(cases.len() as u64, "cases");
    let done = harness::pool::run(case_jobs(cases, dir), |_| progress.inc(1));
    progress.finish_and_clear();
    done.into_iter().map(|d| d.result).collect()
}

/// One job per case of `cases` for the pool of the run, each with its cost
/// estimate ([`harness::shard::cost`]).
fn case_jobs<'a>(
    cases: &[&'static Case],
    dir: Option<&'a Path>,
) -> Vec<harness::pool::Job<'a, CaseRecord>> {
    cases
        .iter()
        .map(|&case| {
            harness::pool::Job::new(
                format!("case {}", case.id),
                harness::shard::cost(&Unit::Case(case.id)),
                move || (case.run)().and_then(|report| report.record(case.id, dir)),
            )
        })
        .collect()
}

/// What a job of a full run returns.
enum Output {
    Case(CaseRecord),
    Study(harness::study::StudyPiece),
    Bench(harness::bench::BenchPiece),
    Picture(Result<harness::pictures::Drawn>),
    Replay(Result<harness::replay_cases::Drawn>),
}

/// The pictures and replays of the cases' scenes, drawn as jobs of a run
/// ([`run_everything`]) for [`finish`] to write.
struct Drawings {
    pictures: Vec<Result<harness::pictures::Drawn>>,
    replays: Vec<Result<harness::replay_cases::Drawn>>,
}

/// The scenes drawn for the cases `ids`: each case's first scene file (the
/// parry comparison has none).
fn drawn_scenes<'a>(ids: impl IntoIterator<Item = &'a str>) -> Vec<&'static str> {
    ids.into_iter()
        .filter_map(|id| find(id)?.scenes.first().copied())
        .collect()
}

/// The results of the jobs of one kind from a run's `done`, those that
/// `pick` takes (errors stay with their job).
fn take<T>(
    done: &mut Vec<harness::pool::Done<Output>>,
    count: usize,
    pick: impl Fn(Output) -> Option<T>,
) -> Vec<harness::pool::Done<T>> {
    done.drain(..count)
        .map(|d| harness::pool::Done {
            result: d.result.and_then(|o| {
                pick(o).ok_or_else(|| anyhow::anyhow!("a job returned another kind's result"))
            }),
            seconds: d.seconds,
        })
        .collect()
}

/// A full run's cases, studies and (unless `quick`) short benchmark, all
/// on one pool ([`harness::pool`]): the longest job first, so that both
/// workers end together, instead of the studies and the benchmark one
/// after the other after the cases. Writes the studies' pages and the
/// benchmark's report into `dir`.
fn run_everything(
    cases: &[&'static Case],
    dir: &Path,
    settings: SweepSettings,
    quick: bool,
) -> Result<(Vec<CaseRecord>, StudySummary, Drawings)> {
    let started = Instant::now();
    let bench_settings = harness::bench::BenchSettings::DEFAULT;
    let contenders = if quick {
        None
    } else {
        Some(harness::bench::measure::Contenders::for_settings(
            &bench_settings,
        )?)
    };
    let mut jobs: Vec<harness::pool::Job<Output>> = case_jobs(cases, Some(dir))
        .into_iter()
        .map(|j| j.map(Output::Case))
        .collect();
    let study_jobs = harness::study::jobs(dir, settings)?;
    let studies = study_jobs.len();
    jobs.extend(study_jobs.into_iter().map(|j| j.map(Output::Study)));
    if let Some(contenders) = &contenders {
        jobs.extend(
            harness::bench::jobs(bench_settings, contenders)
                .into_iter()
                .map(|j| j.map(Output::Bench)),
        );
    }
    let bench_jobs = jobs.len() - cases.len() - studies;
    // The pictures and replays time nothing: on the pool too.
    let scenes = drawn_scenes(cases.iter().map(|c| c.id));
    let replayed = harness::replay_cases::with_scene(&scenes);
    jobs.extend(
        harness::pictures::drawing_jobs(&scenes)
            .into_iter()
            .map(|j| j.map(Output::Picture)),
    );
    jobs.extend(
        harness::replay_cases::jobs(&replayed)
            .into_iter()
            .map(|j| j.map(Output::Replay)),
    );
    let progress = harness::progress::bar(jobs.len() as u64, "cases, studies, benchmark, pictures");
    let mut done = harness::pool::run(jobs, |_| progress.inc(1));
    progress.finish_and_clear();
    let records = take(&mut done, cases.len(), |o| match o {
        Output::Case(r) => Some(r),
        _ => None,
    });
    let pieces = take(&mut done, studies, |o| match o {
        Output::Study(p) => Some(p),
        _ => None,
    });
    let bench = take(&mut done, bench_jobs, |o| match o {
        Output::Bench(p) => Some(p),
        _ => None,
    });
    let mut drawings = Drawings {
        pictures: Vec::new(),
        replays: Vec::new(),
    };
    for (i, d) in done.into_iter().enumerate() {
        match d.result? {
            Output::Picture(p) if i < scenes.len() => drawings.pictures.push(p),
            Output::Replay(r) if i >= scenes.len() => drawings.replays.push(r),
            _ => bail!("a drawing job returned another kind's result"),
        }
    }
    let records: Vec<CaseRecord> = records
        .into_iter()
        .map(|d| d.result)
        .collect::<Result<_>>()?;
    let study = harness::study::assemble(dir, pieces)?;
    let summary = report::write_study_pages(dir, &study)?;
    tracing::info!("studies: {:.2} s of jobs", study.seconds);
    if let Some(contenders) = &contenders {
        let seconds: f64 = bench.iter().map(|d| d.seconds).sum();
        let measured = harness::bench::gather(bench)?;
        harness::bench::write(dir, bench_settings, contenders, measured)?;
        tracing::info!("benchmark: {seconds:.2} s of jobs");
    }
    tracing::info!(
        "cases, studies and benchmark in {:.2} s",
        started.elapsed().as_secs_f64()
    );
    Ok((records, summary, drawings))
}

/// Runs the studies into `dir` (their jobs on the pool,
/// [`harness::study::run`]) and writes their pages.
fn run_studies(dir: &Path, settings: SweepSettings) -> Result<StudySummary> {
    let started = Instant::now();
    let study = harness::study::run(dir, settings)?;
    let summary = report::write_study_pages(dir, &study)?;
    tracing::info!("studies in {:.2} s", started.elapsed().as_secs_f64());
    Ok(summary)
}

/// The many-body benchmark into `dir`, at the short settings of
/// `BenchSettings::DEFAULT` (the benchmark proper, at Box2D's step counts
/// and 10 repeats, is `harness bench`, which rewrites benchmarks.md and the
/// README's table after). Run alone, after the parallel cases: its timings
/// share the machine with nothing of this process.
fn run_bench(dir: &Path) -> Result<()> {
    let started = Instant::now();
    harness::bench::run(dir, harness::bench::BenchSettings::DEFAULT)?;
    tracing::info!("benchmark in {:.2} s", started.elapsed().as_secs_f64());
    Ok(())
}

/// `run`: the selected cases and, on a full run, the studies and the
/// benchmark, in parallel ([`run_everything`]); writes the report into `out` (or
/// the default folder of a full run) and, after a full run into
/// `reports/`, the README's headline table.
fn run(ids: &[String], quick: bool, reasons: bool, out: Option<PathBuf>) -> Result<bool> {
    let settings = if quick {
        SweepSettings::QUICK
    } else {
        SweepSettings::FULL
    };
    let selected = select(ids)?;
    let full = selected.len() == CASES.len();
    let out = out.or_else(|| default_out(full, quick));
    announce(out.as_deref(), full, quick);
    // Read before anything is written, so the commit's state is the code's.
    let provenance = harness::provenance::paragraph(settings.timing_runs);
    // The report is written into a staging folder next to `out`, moved
    // into place once complete (a signal or an error before then removes
    // it): an interrupted run leaves `out` as it was.
    let staging = match &out {
        Some(dir) => Some(harness::interrupt::Staging::new(dir)?),
        None => None,
    };
    let stage = staging.as_ref().map(|s| s.dir().to_path_buf());
    let started = Instant::now();
    // The studies (sweeps, orders, stability, energy, trajectories) run with
    // every full run that writes a report, and the many-body benchmark
    // with a full run that is not `--quick`, on the cases' pool; a run of
    // selected cases checks only those.
    let (results, study, drawings) = match (&stage, full) {
        (Some(dir), true) => {
            let (results, study, drawings) = run_everything(&selected, dir, settings, quick)?;
            (results, Some(study), Some(drawings))
        }
        _ => (run_cases(&selected, stage.as_deref())?, None, None),
    };
    for r in &results {
        print!("{}", report::console_table(&r.id, &r.rows, reasons));
    }
    let joined = Joined {
        run: Run {
            selection: selected.iter().map(|c| c.id.to_string()).collect(),
            full,
            quick,
            provenance,
        },
        cases: results,
        studies: study,
    };
    finish(joined, staging, drawings, out, reasons, started)
}

/// Prints where the report goes.
fn announce(out: Option<&Path>, full: bool, quick: bool) {
    if let Some(dir) = out {
        let readme_too = full && !quick && workspace::same_dir(dir, &workspace::reports_dir());
        println!(
            "run: writes the report into {}{} at the end (its files are replaced; \
             an interrupted run leaves it as it was).",
            dir.display(),
            if readme_too {
                ", and the headline table of README.md"
            } else {
                ""
            }
        );
    }
}

/// `run --shard i/n`: the units of the run that fall to shard `shard`
/// (`harness::shard::assign`), their files and `shard.cbor` into `out`.
fn run_shard(
    ids: &[String],
    quick: bool,
    reasons: bool,
    shard: Shard,
    out: Option<PathBuf>,
) -> Result<bool> {
    let Some(out) = out else {
        bail!(
            "run --shard {shard}: a shard writes its part into a folder of its own; give --out DIR \
             (then `harness merge DIR...` writes the report)"
        );
    };
    if workspace::same_dir(&out, &workspace::reports_dir()) {
        bail!(
            "run --shard {shard} --out {}: a shard's folder is not a report; give another folder \
             and merge the shards into reports/",
            out.display()
        );
    }
    let settings = if quick {
        SweepSettings::QUICK
    } else {
        SweepSettings::FULL
    };
    let selected = select(ids)?;
    let full = selected.len() == CASES.len();
    let ids: Vec<&'static str> = selected.iter().map(|c| c.id).collect();
    let mine = harness::shard::assign(&harness::shard::units(&ids, full, quick), shard);
    let cases: Vec<&'static Case> = mine
        .iter()
        .filter_map(|u| match u {
            Unit::Case(id) => find(id),
            _ => None,
        })
        .collect();
    let studies = mine.contains(&Unit::Studies);
    let bench = mine.contains(&Unit::Bench);
    println!(
        "run --shard {shard}: {} of the {} cases{}{}, into {} (merge every shard's folder with \
         `harness merge`).",
        cases.len(),
        selected.len(),
        if studies { ", the studies" } else { "" },
        if bench { ", the benchmark" } else { "" },
        out.display()
    );
    let provenance = harness::provenance::paragraph(settings.timing_runs);
    let staging = harness::interrupt::Staging::new(&out)?;
    let stage = staging.dir().to_path_buf();
    let started = Instant::now();
    let results = run_cases(&cases, Some(&stage))?;
    for r in &results {
        print!("{}", report::console_table(&r.id, &r.rows, reasons));
    }
    let study = if studies {
        Some(run_studies(&stage, settings)?)
    } else {
        None
    };
    if bench {
        run_bench(&stage)?;
    }
    if let Some(study) = &study {
        print!("{}", report::console_table("studies", &study.rows, reasons));
    }
    let mut rows: Vec<&harness::row::Row> = results.iter().flat_map(|r| &r.rows).collect();
    if let Some(study) = &study {
        rows.extend(&study.rows);
    }
    let failed = rows.iter().filter(|r| !r.pass).count();
    let run = Run {
        selection: ids.iter().map(|s| s.to_string()).collect(),
        full,
        quick,
        provenance,
    };
    let record = ShardRecord::new(shard, run, results.clone(), study.clone(), bench);
    record.write(&stage)?;
    drop(staging.commit()?);
    println!(
        "\nshard {shard}: {} rows, {} passed, {failed} failed ({:.1} s). Written to {}.",
        rows.len(),
        rows.len() - failed,
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(failed == 0)
}

/// `merge DIR...`: the shards of one run joined into its report.
fn merge(dirs: &[PathBuf], reasons: bool, out: Option<PathBuf>) -> Result<bool> {
    let started = Instant::now();
    let mut records = Vec::new();
    for dir in dirs {
        records.push((dir.display().to_string(), ShardRecord::read(dir)?));
    }
    let joined = harness::shard::join(records)?;
    let Some(out) = out.or_else(|| default_out(joined.run.full, joined.run.quick)) else {
        bail!(
            "merge: these shards are of a run of selected cases, whose report goes nowhere by \
             default; give --out DIR"
        );
    };
    announce(Some(&out), joined.run.full, joined.run.quick);
    let staging = harness::interrupt::Staging::new(&out)?;
    for dir in dirs {
        harness::shard::copy_files(dir, staging.dir())?;
    }
    for r in &joined.cases {
        print!("{}", report::console_table(&r.id, &r.rows, reasons));
    }
    finish(joined, Some(staging), None, Some(out), reasons, started)
}

/// The end of a run or a merge: the pictures and replays of the cases'
/// scenes, the report, into place; the README's headline table after a
/// full run into `reports/`; the summary on the console.
fn finish(
    joined: Joined,
    staging: Option<harness::interrupt::Staging>,
    drawings: Option<Drawings>,
    out: Option<PathBuf>,
    reasons: bool,
    started: Instant,
) -> Result<bool> {
    let into_reports = out
        .as_deref()
        .is_some_and(|d| workspace::same_dir(d, &workspace::reports_dir()));
    let readme_too = joined.run.full && !joined.run.quick && into_reports;
    let results = &joined.cases;
    let study = joined.studies.as_ref();
    if let Some(staging) = &staging {
        let dir = staging.dir();
        // The pictures index has one section per scene drawn: each case's
        // first scene file (the parry comparison has none).
        let ids = drawn_scenes(results.iter().map(|r| r.id.as_str()));
        match drawings {
            Some(Drawings { pictures, replays }) => {
                harness::pictures::write_drawn(dir, &ids, pictures)?;
                let replayed = harness::replay_cases::with_scene(&ids);
                harness::replay_cases::write_drawn(dir, &replayed, replays)?;
            }
            None => {
                let scenes: Vec<(&str, harness::cases::CaseReport)> = ids
                    .iter()
                    .map(|id| (*id, harness::cases::CaseReport::default()))
                    .collect();
                harness::pictures::write_case_pictures(dir, &scenes)?;
                harness::replay_cases::write_case_replays(dir, &ids)?;
            }
        }
        // After the pictures, so that the pages can link them.
        report::write(dir, results, study, &joined.run.provenance)?;
    }
    // Into place; a signal waits until the README is written too.
    let _hold = staging.map(|s| s.commit()).transpose()?;
    if let Some(dir) = &out {
        let broken = harness::links::broken_links(dir)?;
        if !broken.is_empty() {
            bail!(
                "the report in {} has broken links:\n  {}",
                dir.display(),
                broken.join("\n  ")
            );
        }
    }
    // The README's headline table is printed by the harness too: only by a
    // full run writing the committed report, so that neither a partial run
    // nor a report written elsewhere changes it.
    // The README's speed table is `bench`'s alone: rewriting it on every
    // run would change a tracked file by timing noise only.
    if readme_too {
        let mut all: Vec<&harness::row::Row> = results.iter().flat_map(|r| &r.rows).collect();
        if let Some(study) = study {
            all.extend(&study.rows);
        }
        report::update_readme(&workspace::readme(), &all)?;
    }
    drop(_hold);
    let mut rows: Vec<_> = results.iter().flat_map(|r| &r.rows).collect();
    if let Some(study) = study {
        print!("{}", report::console_table("studies", &study.rows, reasons));
        rows.extend(&study.rows);
    }
    let failed: Vec<_> = rows.iter().filter(|r| !r.pass).collect();
    println!(
        "\n{} rows, {} passed, {} failed ({:.1} s).{}",
        rows.len(),
        rows.len() - failed.len(),
        failed.len(),
        started.elapsed().as_secs_f64(),
        out.map_or(String::new(), |d| format!(
            " Report written to {}.",
            d.display()
        ))
    );
    print!("{}", report::console_kinds(&rows));
    if !reasons {
        println!(
            "Rows whose verdict is not obvious from their numbers show their reason (why:); \
             --reasons shows every row's."
        );
    }
    for r in &failed {
        println!(
            "FAILED: {} {}{} {} dt = {} s: {} vs {} {}",
            r.case,
            r.check,
            if r.variant.is_empty() {
                String::new()
            } else {
                format!(" ({})", r.variant)
            },
            r.method,
            report::fmt_dt(r.dt),
            report::fmt_num(r.value),
            report::fmt_num(r.expected),
            report::format::condition(r)
        );
    }
    Ok(failed.is_empty())
}
