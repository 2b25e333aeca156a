//! `cargo run --release -p harness`: runs every case and writes `reports/`.
//! Exits non-zero when a row fails.

use anyhow::{Result, bail};
use clap::{Parser, Subcommand};
use harness::cases::{CASES, CaseReport, find};
use harness::report;
use harness::sweep::SweepSettings;
use std::path::PathBuf;
use std::time::Instant;

/// Validation harness of the 2D physics engine.
#[derive(Debug, Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Where to write the report. A full run writes `reports/` by default; a
    /// run of selected cases writes nothing unless this is given, so it never
    /// replaces the full report with a partial one.
    #[arg(long)]
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
    },
    /// Runs a scene file of your own.
    Simulate(harness::simulate::SimulateArgs),
}

/// Exit codes: 0 every row passed (or the command succeeded), 1 a row
/// failed, 2 the input was refused or the run could not be made (the
/// message names the file, the field and the line when it comes from a
/// scene file). Command-line usage errors are clap's, also 2.
fn main() -> std::process::ExitCode {
    harness::progress::init_tracing();
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
    let mut settings = SweepSettings::FULL;
    let selected: Vec<String> = match cli.command {
        Some(Command::List) => {
            println!("Cases:");
            for c in CASES {
                println!("  {:<16} {}", c.id, c.title);
            }
            println!("Scene files ({}):", harness::scenes::scenes_dir().display());
            for path in harness::scenes::list()? {
                println!("  {}", path.display());
            }
            return Ok(true);
        }
        Some(Command::Simulate(args)) => {
            harness::simulate::run(&args)?;
            return Ok(true);
        }
        Some(Command::Run { cases, quick }) if !cases.is_empty() => {
            settings = if quick {
                SweepSettings::QUICK
            } else {
                settings
            };
            cases
        }
        Some(Command::Run { quick: true, .. }) => {
            settings = SweepSettings::QUICK;
            CASES.iter().map(|c| c.id.to_string()).collect()
        }
        _ => CASES.iter().map(|c| c.id.to_string()).collect(),
    };
    // Read before anything is written, so the commit's state is the code's.
    let provenance = harness::provenance::paragraph(settings.timing_runs);
    let started = Instant::now();
    let mut results: Vec<(&str, CaseReport)> = Vec::new();
    for id in &selected {
        let Some(case) = find(id) else {
            bail!("unknown case '{id}' (see `harness list`)");
        };
        let report = (case.run)()?;
        print!("{}", report::console_table(case.id, &report.rows));
        results.push((case.id, report));
    }
    let full = results.len() == CASES.len();
    // A full run writes reports/; a quick one (reduced timing) writes
    // target/quick-report/ so it never replaces the committed report.
    let quick = settings == SweepSettings::QUICK;
    let default_dir = if quick {
        "target/quick-report"
    } else {
        "reports"
    };
    let out = cli.out.or_else(|| full.then(|| PathBuf::from(default_dir)));
    // The studies (sweeps, orders, stability, energy, trajectories) run with
    // every full run; a run of selected cases checks only those.
    let study = match (&out, full) {
        (Some(dir), true) => Some(harness::study::run(dir, settings)?),
        _ => None,
    };
    if let Some(dir) = &out {
        report::write(dir, &results, study.as_ref(), &provenance)?;
        harness::pictures::write_case_pictures(dir, &results)?;
    }
    // The README's headline table is printed by the harness too (only on a
    // full run, so that a partial run never drops rows from it).
    if full && !quick {
        let mut all: Vec<&harness::row::Row> = results.iter().flat_map(|(_, r)| &r.rows).collect();
        if let Some(study) = &study {
            all.extend(&study.rows);
        }
        report::update_readme(std::path::Path::new("README.md"), &all)?;
    }
    let mut rows: Vec<_> = results.iter().flat_map(|(_, r)| &r.rows).collect();
    if let Some(study) = &study {
        print!("{}", report::console_table("studies", &study.rows));
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
    for r in &failed {
        println!(
            "FAILED: {} {} {} dt={}: {} vs {}",
            r.case, r.check, r.method, r.dt, r.value, r.expected
        );
    }
    Ok(failed.is_empty())
}
