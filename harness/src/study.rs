//! The studies of `reports/` beyond the per-case checks: step sweeps and
//! work-precision diagrams, observed orders, stability limits, the long
//! energy run and the trajectory figures, with rapier2d-f64 on the same
//! charts. Run by a full `cargo run --release -p harness` (reduced with
//! `--quick`). Which cases take part is what each declares (`Case::sweep`,
//! `Case::stability`, `Case::figures`).

use crate::cases::{CASES, Case, FigureSection, StudyFigure};
use crate::convergence::{order_rows, tolerance_slope};
use crate::plots;
use crate::pool::{Done, Job};
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
    /// The studies' time (s): the sum of their jobs' wall times (the jobs
    /// run on the pool of the run, beside each other and the cases).
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
    /// The studies' time (s): the sum of their jobs' wall times (the jobs
    /// run on the pool of the run, beside each other and the cases).
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

/// What one job of the studies produced (see [`jobs`]).
pub enum StudyPiece {
    /// A part of a swept case's sweep: its points.
    SweepPart {
        /// The case.
        case: &'static str,
        /// The points.
        points: Vec<sweep::SweepPoint>,
    },
    /// The stability limits of one method on every problem.
    Stability {
        /// The limits.
        limits: Vec<Limit>,
        /// Their rows.
        rows: Vec<Row>,
    },
    /// A declared figure and its rows.
    Figure {
        /// The figure.
        figure: FigureFile,
        /// Its rows.
        rows: Vec<Row>,
    },
}

/// Expected wall time of the studies' jobs on one quiet core (s), for the
/// order in which a run starts them ([`crate::pool`]):
/// measured in one full run (2026-12-02, `RUST_LOG=info`, which logs
/// each job's wall and thread CPU time) on the 2-core development machine
/// shared with other work: the larger of the job's CPU time and a quarter
/// of its wall time (the run had about a quarter of a core per worker;
/// rapier2d's own pool thread is not the job's), a sweep's
/// CPU time × 1.5 (on a loaded machine its timing runs stop sooner, at
/// [`crate::timing`]'s budget). Jobs under 0.3 s are left to the default.
const STUDY_COSTS: &[(&str, f64)] = &[
    ("sweep spring implicit_euler", 12.5),
    ("sweep angular_drag implicit_euler", 5.1),
    ("sweep spring rk2_midpoint", 3.9),
    ("sweep spring rapier2d_16sub", 3.7),
    ("sweep spring semi_implicit_euler", 3.6),
    ("sweep spring explicit_euler", 3.2),
    ("sweep spring velocity_verlet", 3.2),
    ("sweep spring rapier2d_4sub", 3.1),
    ("sweep projectile_drag implicit_euler", 2.8),
    ("sweep spring rapier2d_1sub", 2.8),
    ("sweep angular_drag rapier2d_16sub", 1.6),
    ("sweep angular_drag velocity_verlet", 1.3),
    ("sweep projectile_drag velocity_verlet", 1.3),
    ("sweep angular_drag rapier2d_1sub", 1.3),
    ("sweep projectile_drag rk2_midpoint", 1.2),
    ("sweep angular_drag rk2_midpoint", 1.2),
    ("sweep projectile_drag semi_implicit_euler", 1.2),
    ("sweep angular_drag rapier2d_4sub", 1.2),
    ("sweep projectile_drag explicit_euler", 1.2),
    ("sweep angular_drag semi_implicit_euler", 1.1),
    ("sweep angular_drag explicit_euler", 1.1),
    ("sweep projectile_drag rapier2d_16sub", 0.8),
    ("sweep projectile_drag rapier2d_1sub", 0.7),
    ("sweep projectile_drag rapier2d_4sub", 0.6),
    ("sweep spring rk4", 0.6),
];

/// The cost of a study job without an estimate (s).
const DEFAULT_STUDY_COST: f64 = 0.1;

/// The expected cost (s) of the study job `label`.
pub fn job_cost(label: &str) -> f64 {
    crate::pool::estimated_cost(STUDY_COSTS, label, DEFAULT_STUDY_COST)
}

/// The studies as independent jobs, in the order their results are
/// gathered ([`assemble`]): one per part of each swept case's sweep (a
/// method, or rapier2d at a substep count: [`sweep::parts`]), one per
/// method of the stability study, one per declared figure. The figures'
/// jobs write their figures into `dir`.
pub fn jobs(dir: &Path, settings: SweepSettings) -> Result<Vec<Job<'_, StudyPiece>>> {
    let mut jobs = Vec::new();
    for case in CASES {
        let Some(build) = case.sweep else { continue };
        let id = case.id;
        // Each job builds the sweep's runs again (they are not `Send`):
        // cheap beside the sweep itself.
        let declared = build().with_context(|| format!("sweep of {id}"))?;
        for part in sweep::parts(&declared) {
            let label = format!("sweep {id} {}", part.name());
            jobs.push(Job::new(label.clone(), job_cost(&label), move || {
                let declared = build().with_context(|| format!("sweep of {id}"))?;
                let points = sweep::run_part(&declared, part, settings)
                    .with_context(|| format!("sweep of {id}"))?;
                Ok(StudyPiece::SweepPart { case: id, points })
            }));
        }
    }
    let problems = stability_problems()?;
    for method in stability::methods() {
        let label = format!("stability {}", method.id());
        let problems = problems.clone();
        jobs.push(Job::new(label.clone(), job_cost(&label), move || {
            let (limits, rows) = stability::measure_method(method, &problems)?;
            Ok(StudyPiece::Stability { limits, rows })
        }));
    }
    for (case, figure) in declared_figures() {
        let label = format!("figure {} {:?}", case.id, figure.section);
        jobs.push(Job::new(label.clone(), job_cost(&label), move || {
            let drawn =
                (figure.write)(dir, case.id).with_context(|| format!("a figure of {}", case.id))?;
            Ok(StudyPiece::Figure {
                figure: FigureFile {
                    section: figure.section.into(),
                    case: case.id,
                    file: drawn.file,
                },
                rows: drawn.rows,
            })
        }));
    }
    Ok(jobs)
}

/// The sweep of case `id` from its `points`, its rows and figures (into
/// `dir`) into `out`, as a serial run adds them.
fn add_sweep(
    out: &mut StudyResults,
    dir: &Path,
    id: &'static str,
    points: Vec<sweep::SweepPoint>,
) -> Result<()> {
    let build = crate::cases::find(id)
        .and_then(|c| c.sweep)
        .with_context(|| format!("no sweep of {id}"))?;
    let declared = build().with_context(|| format!("sweep of {id}"))?;
    let sweep = sweep::assemble(id, &declared, points);
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
    Ok(())
}

/// The studies' results from their jobs' (in the order of [`jobs`]): the
/// sweeps' rows and figures first, then the stability rows, then the
/// declared figures' (the order of a serial run); writes the sweeps'
/// figures and `sweeps.json` into `dir`. `seconds` is the sum of the jobs'
/// wall times. The first error in that order is the one returned.
pub fn assemble(dir: &Path, done: Vec<Done<StudyPiece>>) -> Result<StudyResults> {
    let mut out = StudyResults::default();
    let mut declared = Vec::new();
    let mut sweeping: Option<(&'static str, Vec<sweep::SweepPoint>)> = None;
    for d in done {
        out.seconds += d.seconds;
        let piece = d.result?;
        // A sweep is complete at the first piece of another kind or case.
        let same = matches!((&piece, &sweeping),
            (StudyPiece::SweepPart { case, .. }, Some((id, _))) if case == id);
        if !same && let Some((id, points)) = sweeping.take() {
            add_sweep(&mut out, dir, id, points)?;
        }
        match piece {
            StudyPiece::SweepPart { case, points } => {
                sweeping
                    .get_or_insert_with(|| (case, Vec::new()))
                    .1
                    .extend(points);
            }
            StudyPiece::Stability { limits, rows } => {
                out.limits.extend(limits);
                out.add_rows(Section::Stability, rows);
            }
            StudyPiece::Figure { figure, rows } => declared.push((figure, rows)),
        }
    }
    if let Some((id, points)) = sweeping.take() {
        add_sweep(&mut out, dir, id, points)?;
    }
    for (figure, rows) in declared {
        out.add_rows(figure.section, rows);
        out.figures.push(figure);
    }
    let json = serde_json::to_string_pretty(&out.sweeps)?;
    std::fs::write(dir.join("sweeps.json"), json + "\n").context("writing sweeps.json")?;
    Ok(out)
}

/// Runs every study and writes its figures into `dir`: [`jobs`] on the
/// worker pool ([`crate::pool`]), then [`assemble`].
pub fn run(dir: &Path, settings: SweepSettings) -> Result<StudyResults> {
    let jobs = jobs(dir, settings)?;
    let progress = crate::progress::bar(jobs.len() as u64, "studies");
    let done = crate::pool::run(jobs, |_| progress.inc(1));
    progress.finish_and_clear();
    assemble(dir, done)
}
