//! `cargo run --release -p harness`: runs every case and writes `reports/`.
//! Exits non-zero when a row fails.

use anyhow::{Result, bail};
use clap::{Parser, Subcommand};
use harness::cases::{CASES, CaseReport, find};
use harness::report;
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
    #[arg(long, global = true)]
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

fn main() -> std::process::ExitCode {
    match real_main() {
        Ok(true) => std::process::ExitCode::SUCCESS,
        Ok(false) => std::process::ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::from(2)
        }
    }
}

fn real_main() -> Result<bool> {
    let cli = Cli::parse();
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
        Some(Command::Run { cases, .. }) if !cases.is_empty() => cases,
        _ => CASES.iter().map(|c| c.id.to_string()).collect(),
    };
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
    let provenance = format!(
        "Build profile: {}. Commit: {}.",
        if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        },
        option_env!("HARNESS_COMMIT").unwrap_or("see git log"),
    );
    let full = results.len() == CASES.len();
    let out = cli.out.or_else(|| full.then(|| PathBuf::from("reports")));
    if let Some(dir) = &out {
        report::write(dir, &results, &provenance)?;
    }
    // The README's headline table is printed by the harness too (only on a
    // full run, so that a partial run never drops rows from it).
    if full {
        report::update_readme(std::path::Path::new("README.md"), &results)?;
    }
    let rows: Vec<_> = results.iter().flat_map(|(_, r)| &r.rows).collect();
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
