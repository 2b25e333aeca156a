//! The page of one case, `cases/<id>.md` in the report folder: what the
//! case is, how many of its rows pass, its notes and charts, its rows keyed
//! to where their conditions come from, and where it appears in the
//! studies.

use super::format::wrap;
use super::table;
use crate::cases::{Case, CaseRecord};
use crate::row::Row;
use crate::study::{Section, StudySummary};
use std::fmt::Write as _;

/// The pages of the studies, in report order, as (name, link from a case
/// page, the sections whose rows and figures they show).
const STUDY_PAGES: [(&str, &str, &[Section]); 5] = [
    (
        "speed against accuracy",
        "../studies/speed.md",
        &[Section::WorkPrecision],
    ),
    (
        "convergence",
        "../studies/convergence.md",
        &[Section::Convergence],
    ),
    (
        "stability",
        "../studies/stability.md",
        &[Section::Stability, Section::Failures],
    ),
    ("energy", "../studies/energy.md", &[Section::Energy]),
    (
        "trajectories",
        "../studies/trajectories.md",
        &[Section::Trajectories],
    ),
];

/// Where case `id` appears in the studies: one list item per study page
/// holding its rows or figures.
fn in_the_studies(id: &str, study: &StudySummary) -> String {
    let mut md = String::new();
    for (name, link, sections) in STUDY_PAGES {
        let rows: Vec<&Row> = study
            .rows
            .iter()
            .zip(&study.row_sections)
            .filter(|(r, s)| r.case == id && sections.contains(s))
            .map(|(r, _)| r)
            .collect();
        let figures: Vec<String> = study
            .figures
            .iter()
            .filter(|(section, case, _)| case == id && sections.contains(section))
            .map(|(_, _, file)| format!("[{file}](../{file})"))
            .collect();
        if rows.is_empty() && figures.is_empty() {
            continue;
        }
        let mut item = format!("[{name}]({link}):");
        if !rows.is_empty() {
            let passed = rows.iter().filter(|r| r.pass).count();
            let _ = write!(item, " {passed} of {} rows pass", rows.len());
            if !figures.is_empty() {
                item.push(';');
            }
        }
        if !figures.is_empty() {
            let _ = write!(item, " figures {}", figures.join(", "));
        }
        md.push_str(&wrap(&item, "- ", "  "));
    }
    md
}

/// Starts section `title` one blank line after what `md` holds.
fn section(md: &mut String, title: &str) {
    let kept = md.trim_end_matches('\n').len();
    md.truncate(kept);
    let _ = write!(md, "\n\n## {title}\n\n");
}

/// The page of `case`, run as `report`, with its place in `study` when
/// the studies ran, linking the pictures of `scenes/` and the replay of
/// `replays/` when there are.
pub fn markdown(
    case: &Case,
    report: &CaseRecord,
    study: Option<&StudySummary>,
    pictures: bool,
    replay: bool,
) -> String {
    let id = case.id;
    let passed = report.rows.iter().filter(|r| r.pass).count();
    let mut md = format!("# `{id}`\n\n[← validation report](../README.md)\n\n");
    md.push_str(&wrap(&format!("{}.", case.title), "", ""));
    md.push('\n');
    let mut facts = format!("**{passed} of {} rows pass.**", report.rows.len());
    if let Some(first) = case.scenes.first() {
        let scenes: Vec<String> = case
            .scenes
            .iter()
            .map(|s| format!("`scenes/{s}.toml`"))
            .collect();
        let _ = write!(facts, " Scene files: {}", scenes.join(", "));
        if pictures {
            let _ = write!(
                facts,
                "; [pictures](../scenes/README.md#{first}) of the first"
            );
        }
        if replay {
            let _ = write!(
                facts,
                "; its [replay](../replays/{first}.html) in the browser"
            );
        }
        facts.push('.');
    }
    md.push_str(&wrap(&facts, "", ""));
    if let Some(study) = study {
        let items = in_the_studies(id, study);
        if !items.is_empty() {
            md.push_str("\nIn the studies:\n\n");
            md.push_str(&items);
        }
    }
    if !report.notes.is_empty() {
        section(&mut md, "Notes");
        for note in &report.notes {
            md.push_str(&wrap(note, "- ", "  "));
        }
    }
    if !report.figures.is_empty() {
        section(&mut md, "Figures");
        for figure in &report.figures {
            let _ = writeln!(md, "![{}](../{})\n", figure.alt, figure.file);
            md.push_str(&wrap(&figure.caption, "", ""));
            md.push('\n');
        }
    }
    section(&mut md, "Rows");
    let rows: Vec<&Row> = report.rows.iter().collect();
    md.push_str(&table::markdown(&rows, false));
    md
}
