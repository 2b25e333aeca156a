//! `cargo run --release -p harness`: runs every case and writes `reports/`.
//! Exits non-zero when a row fails.

use anyhow::{Context, Result, bail};
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

/// Runs `cases` in parallel over the cores, each whole on one thread;
/// returns their records in the order of `cases`, their charts saved into
/// `dir` when there is one. A case's rows depend on nothing but the case
/// (no state is shared between cases), so they are the bits of a serial
/// run; only the timing notes some cases write (ms per step) see the other
/// threads' load. The first error in the order of `cases` is the one
/// reported.
///
/// The workers are plain threads taking the next case in turn, not rayon's
/// global pool: that pool has one thread ([`references::serial_rayon`], so
/// rapier2d, built with `parallel`, steps serially and gives the bits of a
/// serial run), and a case run on it would run the cases one at a time.
/// Each case runs inside a one-thread rayon pool of its own, so whatever
/// it runs through rayon (rapier2d) stays serial and waits on no other
/// case.
fn run_cases(cases: &[&'static Case], dir: Option<&Path>) -> Result<Vec<CaseRecord>> {
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let progress = harness::progress::bar(cases.len() as u64, "cases");
    let next = AtomicUsize::new(0);
    let records: Vec<Mutex<Option<Result<CaseRecord>>>> =
        cases.iter().map(|_| Mutex::new(None)).collect();
    let run_one = |case: &'static Case| -> Result<CaseRecord> {
        let started = Instant::now();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .context("starting a one-thread pool for a case")?;
        let record = pool
            .install(|| (case.run)())
            .and_then(|report| report.record(case.id, dir))
            .with_context(|| format!("case {}", case.id));
        tracing::info!(
            "case {} in {:.2} s",
            case.id,
            started.elapsed().as_secs_f64()
        );
        progress.inc(1);
        record
    };
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(cases.len().max(1));
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(case) = cases.get(i) else { break };
                    let record = run_one(case);
                    *records[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(record);
                }
            });
        }
    });
    progress.finish_and_clear();
    records
        .into_iter()
        .map(|slot| {
            slot.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .unwrap_or_else(|| Err(anyhow::anyhow!("a case did not run")))
        })
        .collect()
}

/// Runs the studies into `dir` (serially: their sweeps are timed) and
/// writes their pages.
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

/// `run`: the selected cases (in parallel), then, on a full run, the
/// studies and the benchmark (serially); writes the report into `out` (or
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
    let results = run_cases(&selected, stage.as_deref())?;
    for r in &results {
        print!("{}", report::console_table(&r.id, &r.rows, reasons));
    }
    // The studies (sweeps, orders, stability, energy, trajectories) run with
    // every full run that writes a report; a run of selected cases checks
    // only those.
    let study = match (&stage, full) {
        (Some(dir), true) => Some(run_studies(dir, settings)?),
        _ => None,
    };
    // The many-body benchmark runs with a full (not quick) run that writes
    // a report.
    if let (Some(dir), true) = (&stage, full && !quick) {
        run_bench(dir)?;
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
    finish(joined, staging, out, reasons, started)
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
    finish(joined, Some(staging), Some(out), reasons, started)
}

/// The end of a run or a merge: the pictures and replays of the cases'
/// scenes, the report, into place; the README's headline table after a
/// full run into `reports/`; the summary on the console.
fn finish(
    joined: Joined,
    staging: Option<harness::interrupt::Staging>,
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
        let scenes: Vec<(&str, harness::cases::CaseReport)> = results
            .iter()
            .filter_map(|r| find(&r.id)?.scenes.first())
            .map(|scene| (*scene, harness::cases::CaseReport::default()))
            .collect();
        harness::pictures::write_case_pictures(dir, &scenes)?;
        let ids: Vec<&str> = scenes.iter().map(|(id, _)| *id).collect();
        harness::replay_cases::write_case_replays(dir, &ids)?;
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
