//! The studies of `reports/` beyond the per-case checks: step sweeps and
//! work-precision diagrams, observed orders, stability limits, the long
//! energy run and the trajectory figures, with rapier2d-f64 on the same
//! charts. Run by a full `cargo run --release -p harness` (reduced with
//! `--quick`).

use crate::convergence::{order_rows, tolerance_slope};
use crate::plots;
use crate::row::Row;
use crate::stability::{self, Limit};
use crate::sweep::{self, SWEPT_CASES, Sweep, SweepSettings};
use anyhow::{Context, Result};
use std::path::Path;

/// Accuracy target of the speed comparison on `projectile_drag` (m).
pub const TARGET_ERROR: f64 = 1e-6;

/// One run of the projectile_drag sweep, summarised (the cheapest to reach
/// [`TARGET_ERROR`], or the most accurate).
#[derive(Debug, Clone, PartialEq)]
pub struct Cheapest {
    /// Method label.
    pub method: String,
    /// Its step (s).
    pub h: f64,
    /// Its max error over the run (m).
    pub error: f64,
    /// Its CPU time (s).
    pub cpu_seconds: f64,
}

/// Everything the studies produced.
#[derive(Debug, Clone, Default)]
pub struct StudyResults {
    /// One sweep per swept case.
    pub sweeps: Vec<Sweep>,
    /// Rows: observed orders, stability limits, energy bands.
    pub rows: Vec<Row>,
    /// The measured stability limits.
    pub limits: Vec<Limit>,
    /// Dormand–Prince: slope of log(error) on log(tolerance), per case.
    pub dp_slopes: Vec<(String, f64)>,
    /// Figures written, as (section, file name).
    pub figures: Vec<(String, String)>,
    /// projectile_drag: the engine's cheapest run to reach the target.
    pub engine_best: Option<Cheapest>,
    /// projectile_drag: rapier2d's cheapest run to reach it, if any.
    pub rapier_best: Option<Cheapest>,
    /// projectile_drag: rapier2d's most accurate run in the sweep.
    pub rapier_most_accurate: Option<Cheapest>,
    /// Wall time of the studies (s).
    pub seconds: f64,
}

impl From<&sweep::SweepPoint> for Cheapest {
    fn from(p: &sweep::SweepPoint) -> Self {
        Self {
            method: p.method.clone(),
            h: p.h,
            error: p.max_error,
            cpu_seconds: p.cpu_seconds,
        }
    }
}

fn cheapest<'a>(points: impl Iterator<Item = &'a sweep::SweepPoint>) -> Option<Cheapest> {
    points
        .filter(|p| p.stable && p.max_error <= TARGET_ERROR && p.cpu_seconds.is_finite())
        .min_by(|a, b| a.cpu_seconds.total_cmp(&b.cpu_seconds))
        .map(Cheapest::from)
}

/// Runs every study and writes its figures into `dir`.
pub fn run(dir: &Path, settings: SweepSettings) -> Result<StudyResults> {
    let started = std::time::Instant::now();
    let mut out = StudyResults::default();
    let progress = crate::progress::bar(SWEPT_CASES.len() as u64 + 3, "studies");
    for id in SWEPT_CASES {
        progress.set_message(format!("sweep {id}"));
        let sweep = sweep::run(id, settings).with_context(|| format!("sweep of {id}"))?;
        out.rows.extend(order_rows(&sweep));
        out.dp_slopes
            .push((id.to_string(), tolerance_slope(&sweep)));
        out.figures.push((
            "work_precision".into(),
            plots::work_precision::write(dir, &sweep)?,
        ));
        out.figures.push((
            "convergence".into(),
            plots::convergence::write(dir, &sweep)?,
        ));
        if id == "projectile_drag" {
            let engine = sweep
                .points
                .iter()
                .filter(|p| !p.method.starts_with("rapier2d"));
            out.engine_best = cheapest(engine);
            let rapier = || {
                sweep
                    .points
                    .iter()
                    .filter(|p| p.method.starts_with("rapier2d"))
            };
            out.rapier_best = cheapest(rapier());
            out.rapier_most_accurate = rapier()
                .filter(|p| p.stable)
                .min_by(|a, b| a.max_error.total_cmp(&b.max_error))
                .map(Cheapest::from);
        }
        out.sweeps.push(sweep);
        progress.inc(1);
    }
    progress.set_message("stability");
    let (limits, rows) = stability::measure_all()?;
    out.limits = limits;
    out.rows.extend(rows);
    out.figures
        .push(("failures".into(), plots::failures::hoffman_euler(dir)?));
    out.figures
        .push(("failures".into(), plots::failures::spring_limits(dir)?));
    progress.inc(1);
    progress.set_message("energy");
    let (file, rows) = plots::energy::write(dir)?;
    out.figures.push(("energy".into(), file));
    out.rows.extend(rows);
    progress.inc(1);
    progress.set_message("trajectories");
    for file in plots::trajectories::write_all(dir)? {
        out.figures.push(("trajectories".into(), file));
    }
    progress.inc(1);
    progress.finish_and_clear();
    let json = serde_json::to_string_pretty(&out.sweeps)?;
    std::fs::write(dir.join("sweeps.json"), json + "\n").context("writing sweeps.json")?;
    out.seconds = started.elapsed().as_secs_f64();
    Ok(out)
}
