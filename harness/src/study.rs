//! The studies of `reports/` beyond the per-case checks: step sweeps and
//! work-precision diagrams, observed orders, stability limits, the long
//! energy run and the trajectory figures, with rapier2d-f64 on the same
//! charts. Run by a full `cargo run --release -p harness` (reduced with
//! `--quick`). Which cases take part is what each declares (`Case::sweep`,
//! `Case::stability`, `Case::figures`).

use crate::cases::{CASES, Case, FigureSection, StudyFigure};
use crate::convergence::{order_rows, tolerance_slope};
use crate::plots;
use crate::row::Row;
use crate::stability::{self, Limit, Problem};
use crate::sweep::{self, Sweep, SweepSettings};
use anyhow::{Context, Result};
use std::path::Path;

/// One run of a sweep, summarised (the cheapest to reach a target error, or
/// the most accurate).
#[derive(Debug, Clone, PartialEq)]
pub struct Cheapest {
    /// Method label.
    pub method: String,
    /// Its step (s).
    pub h: f64,
    /// Its max error over the run (the sweep's unit).
    pub error: f64,
    /// Its wall time (s), the minimum over the timing runs.
    pub cpu_seconds: f64,
}

/// The speed comparison of one sweep that declares a target error: the
/// cheapest run of the engine and of rapier2d-f64 to reach it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedComparison {
    /// Case id.
    pub case: &'static str,
    /// What the error measures, with its unit.
    pub error_label: &'static str,
    /// The error's unit.
    pub unit: &'static str,
    /// The target error (the sweep's unit).
    pub target: f64,
    /// The engine's cheapest run to reach the target.
    pub engine_best: Option<Cheapest>,
    /// rapier2d's cheapest run to reach it, if any.
    pub rapier_best: Option<Cheapest>,
    /// rapier2d's most accurate run in the sweep.
    pub rapier_most_accurate: Option<Cheapest>,
}

/// The sections of the studies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Section {
    /// Error against wall time and evaluations.
    WorkPrecision,
    /// Error against step.
    Convergence,
    /// The largest stable step of each method.
    Stability,
    /// Where methods fail.
    Failures,
    /// Energy over a long run.
    Energy,
    /// Trajectories against references.
    Trajectories,
}

impl From<FigureSection> for Section {
    fn from(s: FigureSection) -> Self {
        match s {
            FigureSection::Failures => Section::Failures,
            FigureSection::Energy => Section::Energy,
            FigureSection::Trajectories => Section::Trajectories,
        }
    }
}

/// A figure the studies wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureFile {
    /// Its section.
    pub section: Section,
    /// The case it was drawn from.
    pub case: &'static str,
    /// Its file name in the report folder.
    pub file: String,
}

/// Everything the studies produced.
#[derive(Debug, Clone, Default)]
pub struct StudyResults {
    /// One sweep per swept case.
    pub sweeps: Vec<Sweep>,
    /// Rows: observed orders, stability limits, energy bands.
    pub rows: Vec<Row>,
    /// The section of each row of `rows`.
    pub row_sections: Vec<Section>,
    /// The measured stability limits.
    pub limits: Vec<Limit>,
    /// Dormand–Prince: slope of log(error) on log(tolerance), per case.
    pub dp_slopes: Vec<(String, f64)>,
    /// Figures written.
    pub figures: Vec<FigureFile>,
    /// The speed comparisons of the sweeps that declare a target error.
    pub speed: Vec<SpeedComparison>,
    /// Wall time of the studies (s).
    pub seconds: f64,
}

/// What the report's pages of the cases and its summary need of the
/// studies once their own pages are written (`report::write_study_pages`):
/// a single run makes it from the [`StudyResults`]; the shard that runs
/// the studies writes it to its folder for `harness merge`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StudySummary {
    /// Rows: observed orders, stability limits, energy bands.
    pub rows: Vec<Row>,
    /// The section of each row of `rows`.
    pub row_sections: Vec<Section>,
    /// Figures written: section, case id, file name.
    pub figures: Vec<(Section, String, String)>,
    /// The study pages written: one line each of the report's table.
    pub pages: Vec<StudyPageLine>,
    /// Wall time of the studies (s).
    pub seconds: f64,
}

/// A study page, as the report's summary table lists it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StudyPageLine {
    /// File name inside `studies/`.
    pub file: String,
    /// Title.
    pub title: String,
    /// One line on what it shows.
    pub summary: String,
    /// Its rows: how many, how many pass.
    pub rows: usize,
    /// How many of them pass.
    pub passed: usize,
}

impl StudyResults {
    /// Adds `rows` of `section`.
    fn add_rows(&mut self, section: Section, rows: impl IntoIterator<Item = Row>) {
        for row in rows {
            self.rows.push(row);
            self.row_sections.push(section);
        }
    }

    /// The rows of `section`.
    pub fn rows_of(&self, section: Section) -> Vec<&Row> {
        self.rows
            .iter()
            .zip(&self.row_sections)
            .filter(|(_, s)| **s == section)
            .map(|(r, _)| r)
            .collect()
    }
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

fn cheapest<'a>(
    points: impl Iterator<Item = &'a sweep::SweepPoint>,
    target: f64,
) -> Option<Cheapest> {
    points
        .filter(|p| p.stable && p.max_error <= target && p.cpu_seconds.is_finite())
        .min_by(|a, b| a.cpu_seconds.total_cmp(&b.cpu_seconds))
        .map(Cheapest::from)
}

/// The engine's and rapier2d's cheapest runs of `sweep` to reach `target`.
fn speed_comparison(sweep: &Sweep, target: f64) -> SpeedComparison {
    let rapier = || {
        sweep
            .points
            .iter()
            .filter(|p| p.method.starts_with("rapier2d"))
    };
    let engine = sweep
        .points
        .iter()
        .filter(|p| !p.method.starts_with("rapier2d"));
    SpeedComparison {
        case: sweep.case,
        error_label: sweep.error_label,
        unit: sweep.unit,
        target,
        engine_best: cheapest(engine, target),
        rapier_best: cheapest(rapier(), target),
        rapier_most_accurate: rapier()
            .filter(|p| p.stable)
            .min_by(|a, b| a.max_error.total_cmp(&b.max_error))
            .map(Cheapest::from),
    }
}

/// The stability study's test problems: the cases that declare an axis.
fn stability_problems() -> Result<Vec<Problem<'static>>> {
    CASES
        .iter()
        .filter_map(|c| c.stability.map(|axis| (c, axis)))
        .map(|(c, axis)| {
            let scene = c.scenes.first().with_context(|| {
                format!("case '{}' declares a stability axis but no scene", c.id)
            })?;
            Ok(Problem {
                case: c.id,
                scene,
                axis,
            })
        })
        .collect()
}

/// The study figures the cases declare, section by section (failures,
/// energy, trajectories), in registry order within each.
fn declared_figures() -> Vec<(&'static Case, &'static StudyFigure)> {
    let mut figures: Vec<(&Case, &StudyFigure)> = CASES
        .iter()
        .flat_map(|c| c.figures.iter().map(move |f| (c, f)))
        .collect();
    figures.sort_by_key(|(_, f)| match f.section {
        FigureSection::Failures => 0,
        FigureSection::Energy => 1,
        FigureSection::Trajectories => 2,
    });
    figures
}

/// Runs every study and writes its figures into `dir`.
pub fn run(dir: &Path, settings: SweepSettings) -> Result<StudyResults> {
    let started = std::time::Instant::now();
    let mut out = StudyResults::default();
    let swept: Vec<_> = CASES
        .iter()
        .filter_map(|c| c.sweep.map(|build| (c.id, build)))
        .collect();
    let figures = declared_figures();
    let progress = crate::progress::bar((swept.len() + 1 + figures.len()) as u64, "studies");
    for (id, build) in swept {
        progress.set_message(format!("sweep {id}"));
        let declared = build().with_context(|| format!("sweep of {id}"))?;
        let sweep =
            sweep::run(id, &declared, settings).with_context(|| format!("sweep of {id}"))?;
        out.add_rows(Section::Convergence, order_rows(&sweep));
        out.dp_slopes
            .push((id.to_string(), tolerance_slope(&sweep)));
        for (section, file) in [
            (
                Section::WorkPrecision,
                plots::work_precision::write(dir, &sweep)?,
            ),
            (
                Section::Convergence,
                plots::convergence::write(dir, &sweep)?,
            ),
        ] {
            out.figures.push(FigureFile {
                section,
                case: id,
                file,
            });
        }
        if let Some(target) = declared.speed_target {
            out.speed.push(speed_comparison(&sweep, target));
        }
        out.sweeps.push(sweep);
        progress.inc(1);
    }
    progress.set_message("stability");
    let (limits, rows) = stability::measure_all(&stability_problems()?)?;
    out.limits = limits;
    out.add_rows(Section::Stability, rows);
    progress.inc(1);
    for (case, figure) in figures {
        progress.set_message(format!("figures of {}", case.id));
        let drawn =
            (figure.write)(dir, case.id).with_context(|| format!("a figure of {}", case.id))?;
        out.figures.push(FigureFile {
            section: figure.section.into(),
            case: case.id,
            file: drawn.file,
        });
        out.add_rows(figure.section.into(), drawn.rows);
        progress.inc(1);
    }
    progress.finish_and_clear();
    let json = serde_json::to_string_pretty(&out.sweeps)?;
    std::fs::write(dir.join("sweeps.json"), json + "\n").context("writing sweeps.json")?;
    out.seconds = started.elapsed().as_secs_f64();
    Ok(out)
}
