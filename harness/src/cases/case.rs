//! What a validation case is: the declaration each case file makes
//! ([`Case`]) and what running it produces ([`CaseReport`]).
//!
//! A case file declares, in one `pub const CASE: Case`, everything the rest
//! of the harness needs to know about it: its id and title, the scene files
//! it reads, how `cargo test` checks it, which of its rows the README's
//! headline table shows, whether the studies sweep it (and against which
//! reference), whether it is a test problem of the stability study, the
//! study figures drawn from it, and whether the benches time it. Nothing
//! outside the case's file branches on its id.

use crate::plots::{Chart, save_svg};
use crate::row::Row;
use crate::stability::Axis;
use crate::sweep::SweepCase;
use anyhow::Result;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A validation case.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Stable id (docs/cases.md), also the name of its file in `cases/`.
    pub id: &'static str,
    /// One-line description.
    pub title: &'static str,
    /// The scene files it reads, as `scenes/<name>.toml` names.
    pub scenes: &'static [&'static str],
    /// Runs it: every row and the traces.
    pub run: fn() -> Result<CaseReport>,
    /// How `cargo test` checks it (snapshots of what, or rows only).
    pub snapshots: Snapshots,
    /// Its rows shown in the README's headline table and, the first one, in
    /// the summary at the top of the report.
    pub headline: &'static [Headline],
    /// Its step sweep in the studies (work-precision, observed orders), if
    /// it has one: builds the sweep's runs against the case's reference.
    pub sweep: Option<fn() -> Result<SweepCase>>,
    /// The axis of the stability study on which this case's scene is the
    /// test problem, if any.
    pub stability: Option<Axis>,
    /// Figures of the studies drawn from this case's scene.
    pub figures: &'static [StudyFigure],
    /// Whether `cargo bench -p harness` times steps of its scene (a scene of
    /// bodies, not a `[linear_test]`).
    pub bench: bool,
}

impl Case {
    /// A case that takes part in nothing but its own run: no scene, rows
    /// checked by `cargo test` without snapshots, no headline row, no
    /// study, no bench. Case files start from it and set what they use:
    /// `Case { scenes: &["stack"], ..Case::new("stack", "...", run) }`.
    pub const fn new(
        id: &'static str,
        title: &'static str,
        run: fn() -> Result<CaseReport>,
    ) -> Self {
        Self {
            id,
            title,
            scenes: &[],
            run,
            snapshots: Snapshots::RowsOnly,
            headline: &[],
            sweep: None,
            stability: None,
            figures: &[],
            bench: false,
        }
    }
}

/// How `cargo test` checks a case (`harness/tests/snapshots.rs`). Every
/// kind but [`Snapshots::HarnessOnly`] runs the case and asserts that each
/// of its rows passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Snapshots {
    /// And snapshots the sampled traces of each method, one snapshot per
    /// method: `snapshots__<case>__<method>.snap`.
    Traces,
    /// And snapshots the contact events of each of its scenes, one snapshot
    /// per scene: `collision_snapshots__collision_events__<scene>.snap`.
    ContactEvents,
    /// Rows only.
    RowsOnly,
    /// Too heavy for a debug build: only the harness runs it; a reduced run
    /// has its own test (the reason says where).
    HarnessOnly(&'static str),
}

/// A row of the README's headline table: matched by check, method, and the
/// step and variant when given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Headline {
    /// The row's check.
    pub check: &'static str,
    /// The row's method.
    pub method: &'static str,
    /// The row's step (s); `None` matches any (study rows have no single
    /// step).
    pub dt: Option<f64>,
}

impl Headline {
    /// The row `check` of `method`, at any step.
    pub const fn new(check: &'static str, method: &'static str) -> Self {
        Self {
            check,
            method,
            dt: None,
        }
    }

    /// The same, at step `dt` (s) only.
    pub const fn at(self, dt: f64) -> Self {
        Self {
            dt: Some(dt),
            ..self
        }
    }

    /// Whether `row` of case `case` is this headline row.
    pub fn matches(&self, case: &str, row: &Row) -> bool {
        row.case == case
            && row.check == self.check
            && row.method == self.method
            && self.dt.is_none_or(|d| row.dt == d)
    }
}

/// Which section of the studies a figure belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureSection {
    /// Where methods fail (with the stability limits).
    Failures,
    /// Energy over a long run.
    Energy,
    /// A trajectory against its reference and rapier2d-f64.
    Trajectories,
}

/// What drawing a study figure produced: the file written and the rows it
/// checked on the way (an energy band, ...).
#[derive(Debug, Clone, Default)]
pub struct FigureOutput {
    /// The file's name inside the report folder.
    pub file: String,
    /// Rows of the study.
    pub rows: Vec<Row>,
}

impl FigureOutput {
    /// A figure without rows.
    pub fn file(file: impl Into<String>) -> Self {
        Self {
            file: file.into(),
            rows: Vec::new(),
        }
    }
}

/// A figure of the studies drawn from a case.
#[derive(Debug, Clone, Copy)]
pub struct StudyFigure {
    /// Its section.
    pub section: FigureSection,
    /// Draws it into the report folder (`dir`) for case `id`.
    pub write: fn(dir: &Path, id: &str) -> Result<FigureOutput>,
}

/// A trace sampled for snapshots and plots: column names and rows of values
/// (the first column is time, s).
#[derive(Debug, Clone, PartialEq)]
pub struct MethodTrace {
    /// Method id.
    pub method: String,
    /// Step (s).
    pub dt: f64,
    /// Column names, starting with `t`.
    pub columns: Vec<&'static str>,
    /// One row per sample.
    pub samples: Vec<Vec<f64>>,
}

/// A chart a case draws. The case only describes it; the report writer
/// saves it into the report folder the user asked for (a run without a
/// report folder writes nothing).
#[derive(Debug, Clone)]
pub struct CaseFigure {
    /// File name (`.svg`) inside the report folder.
    pub file: String,
    /// What it shows: the image's alternative text.
    pub alt: String,
    /// What to read in it, printed under it.
    pub caption: String,
    /// Panels, `columns` to a row.
    pub panels: Vec<Chart>,
    /// Panels per row.
    pub columns: usize,
    /// Width and height of one panel (px).
    pub panel_size: (u32, u32),
}

impl CaseFigure {
    /// Saves the chart as `dir/<file>`.
    pub fn save(&self, dir: &Path) -> Result<()> {
        save_svg(
            &dir.join(&self.file),
            &self.panels,
            self.columns,
            self.panel_size,
        )
    }
}

/// What a case produces.
#[derive(Debug, Clone, Default)]
pub struct CaseReport {
    /// Validation rows.
    pub rows: Vec<Row>,
    /// One trace per method at the seed step.
    pub traces: Vec<MethodTrace>,
    /// Remarks for the report (methods not applicable, ...).
    pub notes: Vec<String>,
    /// Charts for the report.
    pub figures: Vec<CaseFigure>,
}

/// What the report keeps of a case's run: its rows, notes and the charts
/// it saved (by name). A single run makes it from the [`CaseReport`]; a
/// shard of a run (`harness run --shard i/n`) writes it to its folder and
/// `harness merge` reads it back, so the two write the same report.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    /// Case id.
    pub id: String,
    /// Its rows.
    pub rows: Vec<Row>,
    /// Its remarks for the report.
    pub notes: Vec<String>,
    /// Its charts, saved in the report folder.
    pub figures: Vec<FigureRecord>,
}

/// A chart of a case, saved: file name, alternative text and caption.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FigureRecord {
    /// File name (`.svg`) inside the report folder.
    pub file: String,
    /// The image's alternative text.
    pub alt: String,
    /// What to read in it.
    pub caption: String,
}

impl CaseReport {
    /// The record of case `id`'s report; its charts saved into `dir` when
    /// there is one (a run without a report folder writes nothing).
    pub fn record(self, id: &str, dir: Option<&Path>) -> Result<CaseRecord> {
        if let Some(dir) = dir {
            for figure in &self.figures {
                figure.save(dir)?;
            }
        }
        Ok(CaseRecord {
            id: id.to_string(),
            rows: self.rows,
            notes: self.notes,
            figures: self
                .figures
                .into_iter()
                .map(|f| FigureRecord {
                    file: f.file,
                    alt: f.alt,
                    caption: f.caption,
                })
                .collect(),
        })
    }
}
