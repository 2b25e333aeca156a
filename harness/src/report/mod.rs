//! Writes what a run found, into the report folder the user asked for:
//!
//! - `README.md`: the summary (each case with its rows, how many pass and
//!   its headline row; each study), where the numbers come from, and how to
//!   read a row;
//! - `cases/<id>.md`: one page per case (`case_page`);
//! - `studies/<name>.md`: one page per study (`studies`);
//! - the charts the cases drew, and `summary.json` (every row).
//!
//! Every table keys each row to where its condition comes from, listed
//! under the table. The console gets the same rows as aligned text
//! ([`console_table`]). [`update_readme`] rewrites the top-level README's
//! headline table from the rows the cases declare.

mod case_page;
pub mod format;
mod studies;
pub mod table;

pub use format::{fmt_dt, fmt_num};

use crate::cases::{CASES, CaseRecord, find};
use crate::row::{Row, RowKind, count_kinds};
use crate::study::{StudyPageLine, StudyResults, StudySummary};
use anyhow::{Context, Result};
use format::{cell, condition, wrap};
use std::fmt::Write as _;
use std::path::Path;

/// The plain-text table of `rows` printed on the console under `title`;
/// the reason under every row when `all_reasons`, else under the rows
/// whose verdict is not obvious from their numbers.
pub fn console_table(title: &str, rows: &[Row], all_reasons: bool) -> String {
    table::console(title, rows, all_reasons)
}

/// The count of each kind of row, one line each, for the console.
pub fn console_kinds(rows: &[&Row]) -> String {
    let owned: Vec<Row> = rows.iter().map(|r| (*r).clone()).collect();
    let mut out = String::from("By kind of evidence:\n");
    for (kind, n, passed) in count_kinds(&owned) {
        let _ = writeln!(
            out,
            "  {:<17} {n:>4} rows, {passed:>4} passed: {}",
            kind.id(),
            kind.meaning()
        );
    }
    out
}

/// The Markdown table counting each kind of row (and how many pass).
fn kinds_table(rows: &[&Row]) -> String {
    let owned: Vec<Row> = rows.iter().map(|r| (*r).clone()).collect();
    let mut out =
        String::from("| kind | rows | passed | what the rows are checked |\n|---|---|---|---|\n");
    for (kind, n, passed) in count_kinds(&owned) {
        let passed = if passed == n {
            passed.to_string()
        } else {
            format!("**{passed}**")
        };
        let _ = writeln!(
            out,
            "| `{}` | {n} | {passed} | {} |",
            kind.id(),
            kind.meaning()
        );
    }
    out
}

/// The sentence that says what the validation rows of `rows` cover: how
/// many, and how many of each case.
pub fn validation_cover(rows: &[&Row]) -> String {
    let validation: Vec<&&Row> = rows
        .iter()
        .filter(|r| r.kind == RowKind::Validation)
        .collect();
    let mut cases: Vec<(&str, usize)> = Vec::new();
    for r in &validation {
        match cases.iter_mut().find(|(c, _)| *c == r.case) {
            Some((_, n)) => *n += 1,
            None => cases.push((&r.case, 1)),
        }
    }
    let by_case: Vec<String> = cases.iter().map(|(c, n)| format!("{c} {n}")).collect();
    let owned: Vec<Row> = rows.iter().map(|r| (*r).clone()).collect();
    let others: Vec<String> = count_kinds(&owned)
        .into_iter()
        .filter(|(k, _, _)| *k != RowKind::Validation)
        .map(|(k, n, _)| format!("{n} {}", k.id()))
        .collect();
    format!(
        "{} of the {} rows are validation rows, checked against an independent closed form or \
         high-precision reference (DOP853, parry2d, exact solutions), in {} cases: {}. The others \
         are {} (what each kind means: reports/README.md).",
        validation.len(),
        rows.len(),
        cases.len(),
        by_case.join(", "),
        others.join(", ")
    )
}

/// Writes a file of the report, creating its folder.
fn write_file(path: &Path, text: &str) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

/// The headline cell of a row: check (and variant), method and step, then
/// value against expected and condition.
fn headline_cell(r: &Row) -> String {
    let variant = if r.variant.is_empty() {
        String::new()
    } else {
        format!(" ({})", r.variant)
    };
    let step = if r.dt.is_finite() && r.dt > 0.0 {
        format!(", h = {} s", fmt_dt(r.dt))
    } else {
        String::new()
    };
    cell(&format!(
        "`{}`{variant} {}{step}: {}, expected {} {}",
        r.check,
        r.method,
        fmt_num(r.value),
        fmt_num(r.expected),
        condition(r)
    ))
}

/// Writes the report of `results` (and, after a full run, of `study`) into
/// `dir`: `summary.json`, the pages and the cases' charts. The pages link
/// the pictures of `scenes/` when its index is already there.
///
/// The cases' charts are already there ([`crate::cases::CaseReport::record`]),
/// and so are the pages of the studies ([`write_study_pages`]).
pub fn write(
    dir: &Path,
    results: &[CaseRecord],
    study: Option<&StudySummary>,
    provenance: &str,
) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let pictures = dir.join("scenes").join("README.md").is_file();
    let mut rows: Vec<&Row> = results.iter().flat_map(|r| &r.rows).collect();
    if let Some(study) = study {
        rows.extend(&study.rows);
    }
    let json = serde_json::to_string_pretty(&rows)?;
    write_file(&dir.join("summary.json"), &(json + "\n"))?;
    let passed = rows.iter().filter(|r| r.pass).count();
    let mut md = String::from("# Validation report\n\n");
    md.push_str("Generated by `cargo run --release -p harness`; do not edit by hand.\n\n");
    md.push_str(&wrap(
        &format!(
            "**{passed} of {} rows pass.** Every row compares one number the engine produced \
             with an expected value, under a condition whose source is listed under every table. \
             The rows are of five kinds, by what they are checked against (the `kind` column of \
             every table and of `summary.json`):",
            rows.len()
        ),
        "",
        "",
    ));
    md.push('\n');
    md.push_str(&kinds_table(&rows));
    md.push('\n');
    md.push_str(&wrap(
        "Only `validation` rows show the engine right to a known bound. A method that fails \
         the way theory predicts passes its `predicted_failure` row: the expected value is the \
         failure theory predicts. `consistency` rows show the error behaving as the method's \
         order says; `regression` rows, that nothing changed; `criterion` rows, that a bound \
         chosen by hand holds.",
        "",
        "",
    ));
    md.push('\n');
    md.push_str(&wrap(provenance, "", ""));
    md.push_str("\n## Cases\n\n");
    if dir
        .join(crate::replay_cases::FOLDER)
        .join("README.md")
        .is_file()
    {
        md.push_str(&wrap(
            "Every case with a scene can be watched in the browser: its [replay](replays/README.md) \
             (one self-contained page per case, with rapier2d and Box2D beside the engine where \
             they can run the scene).",
            "",
            "",
        ));
        md.push('\n');
    }
    md.push_str(&wrap(
        "Each case's page has its notes, charts and every row; the headline row is the one the \
         case declares first.",
        "",
        "",
    ));
    md.push('\n');
    md.push_str("| case | rows | passed | headline row |\n|---|---|---|---|\n");
    for report in results {
        let id = report.id.as_str();
        let case = find(id).with_context(|| format!("no case '{id}' in the registry"))?;
        write_file(
            &dir.join("cases").join(format!("{id}.md")),
            &case_page::markdown(
                case,
                report,
                study,
                pictures,
                case.scenes
                    .first()
                    .is_some_and(|s| crate::replay_cases::page_path(dir, s).is_file()),
            ),
        )?;
        let passed = report.rows.iter().filter(|r| r.pass).count();
        let headline = case
            .headline
            .iter()
            .find_map(|h| report.rows.iter().find(|r| h.matches(id, r)))
            .or(report.rows.first())
            .map_or("-".to_string(), headline_cell);
        let passed = if passed == report.rows.len() {
            passed.to_string()
        } else {
            format!("**{passed}**")
        };
        let _ = writeln!(
            md,
            "| [`{id}`](cases/{id}.md) | {} | {passed} | {headline} |",
            report.rows.len(),
        );
    }
    if let Some(study) = study {
        md.push_str("\n## Studies\n\n");
        md.push_str(&wrap(
            &format!(
                "Beyond the per-case checks, across methods and cases ({:.1} s):",
                study.seconds
            ),
            "",
            "",
        ));
        md.push_str("\n| study | rows | passed | what it shows |\n|---|---|---|---|\n");
        for page in &study.pages {
            let passed = page.passed;
            let (rows, passed) = match page.rows {
                0 => ("-".to_string(), "-".to_string()),
                n if n == passed => (n.to_string(), passed.to_string()),
                n => (n.to_string(), format!("**{passed}**")),
            };
            let _ = writeln!(
                md,
                "| [{}](studies/{}) | {rows} | {passed} | {} |",
                page.title, page.file, page.summary
            );
        }
    }
    if dir.join("benchmarks.md").is_file() {
        md.push_str("\n## Benchmarks\n\n");
        md.push_str(&wrap(
            "[`benchmarks.md`](benchmarks.md): this engine's soft step, rapier2d-f64 and Box2D v3 \
             on the same many-body scenes (pyramids of 55 to 5050 boxes, a stack, many pyramids, \
             a tumbler, a smash, a rain of mixed shapes, a grid of circles on revolute joints, a \
             rain of ragdolls), measured side by side in one run: each engine's build \
             (precision, SIMD path, threads, flags), ms per step (minimum, median, maximum), \
             ratios, quality figures (joint separations in the jointed scenes), the targets with \
             their verdicts, the peak memory of the large scenes (`harness bench`), and what a \
             contact model's accuracy costs on the validation contact cases.",
            "",
            "",
        ));
    }
    md.push_str("\n## Reading a row\n\n");
    for item in [
        "`value` is what the engine (or the reference engine named as the method: rapier2d, \
         parry2d) produced; `expected` is what it is compared with; `h (s)` is the step, `-` for \
         a row that has none.",
        "`condition`: `± tol` passes when |value - expected| <= tol; `≥ expected − tol` and \
         `≤ expected + tol` are one-sided bounds (a blow-up past a threshold, a band).",
        "`why` keys the row to where its expected value and tolerance come from, listed under \
         the table.",
        "`variant` tells apart rows of the same check, method and step (e.g. the stability \
         axis).",
    ] {
        md.push_str(&wrap(item, "- ", "  "));
    }
    md.push_str("\n## Files\n\n");
    let mut files = vec![
        "`summary.json`: every row, with `case, check, method, kind, variant, dt, value, \
         expected, tolerance, pass, comparison, reason`.",
    ];
    if study.is_some() {
        files.push("`sweeps.json`: every point of every sweep.");
    }
    if dir.join("benchmarks.json").is_file() {
        files.push(
            "`benchmarks.json`: one row per benchmark scene and engine (`scene, engine, threads, \
             precision, simd, build, bodies, steps, repeats, substeps, ms_per_step_min, \
             ms_per_step_median, ms_per_step_max, ratio_to_engine`, the quality figures, and for \
             this engine's and the linked Box2D's rows `stages`: ms per step in each common \
             stage of a profiled run).",
        );
    }
    if pictures {
        files.push(
            "[`scenes/`](scenes/README.md): a picture and an animation of every case's scene.",
        );
    }
    for item in files {
        md.push_str(&wrap(item, "- ", "  "));
    }
    write_file(&dir.join("README.md"), &md)
}

/// Writes the pages of the studies (`studies/<name>.md`) into `dir` and
/// returns what the rest of the report needs of them.
pub fn write_study_pages(dir: &Path, study: &StudyResults) -> Result<StudySummary> {
    let mut lines = Vec::new();
    for page in studies::pages(study) {
        write_file(&dir.join("studies").join(page.file), &page.markdown)?;
        lines.push(StudyPageLine {
            file: page.file.to_string(),
            title: page.title.to_string(),
            summary: page.summary.to_string(),
            rows: page.rows.len(),
            passed: page.rows.iter().filter(|r| r.pass).count(),
        });
    }
    Ok(StudySummary {
        rows: study.rows.clone(),
        row_sections: study.row_sections.clone(),
        figures: study
            .figures
            .iter()
            .map(|f| (f.section, f.case.to_string(), f.file.clone()))
            .collect(),
        pages: lines,
        seconds: study.seconds,
    })
}

/// Marker lines between which the harness writes the README's headline table.
pub const README_MARKERS: (&str, &str) = ("<!-- headline:start -->", "<!-- headline:end -->");

/// Rewrites the headline table between [`README_MARKERS`] in `readme`, when
/// the file exists and has them: what the validation rows cover
/// ([`validation_cover`]), then the rows each case declares
/// (`Case::headline`), in registry order, with where their conditions come
/// from. Returns whether it did.
pub fn update_readme(readme: &Path, all_rows: &[&Row]) -> Result<bool> {
    let Ok(text) = std::fs::read_to_string(readme) else {
        return Ok(false);
    };
    let (start, end) = README_MARKERS;
    let (Some(a), Some(b)) = (text.find(start), text.find(end)) else {
        return Ok(false);
    };
    let rows: Vec<&Row> = CASES
        .iter()
        .flat_map(|case| {
            case.headline
                .iter()
                .filter_map(move |h| all_rows.iter().find(|r| h.matches(case.id, r)).copied())
        })
        .collect();
    let table = table::markdown(&rows, true);
    let cover = format::wrap(&validation_cover(all_rows), "", "");
    let new = format!("{}{start}\n{cover}\n{table}{}", &text[..a], &text[b..]);
    if new != text {
        crate::simulate::write_atomically(readme, new.as_bytes())?;
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_validation_cover_counts_validation_rows_by_case_and_the_other_kinds() {
        let row = |kind, case: &str| {
            Row::new(
                kind,
                case,
                "x",
                "m",
                0.1,
                0.0,
                0.0,
                1.0,
                crate::row::Comparison::Within,
                "r",
            )
        };
        let rows = [
            row(RowKind::Validation, "spring"),
            row(RowKind::Validation, "spring"),
            row(RowKind::Validation, "pyramid"),
            row(RowKind::Criterion, "pyramid"),
            row(RowKind::Regression, "falling_hinges"),
        ];
        let refs: Vec<&Row> = rows.iter().collect();
        let text = validation_cover(&refs);
        assert!(
            text.starts_with("3 of the 5 rows are validation rows"),
            "{text}"
        );
        assert!(text.contains("in 2 cases: spring 2, pyramid 1."), "{text}");
        assert!(
            text.contains("0 predicted_failure, 0 consistency, 1 regression, 1 criterion"),
            "{text}"
        );
    }
    use crate::cases::CaseFigure;
    use crate::plots::{Chart, Series};
    use crate::row::Comparison;

    /// A report of the parry comparison (a case without a scene, so no
    /// pictures are linked) with made-up rows, a long note and a chart.
    fn written() -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        let long = "a long reason that goes on ".repeat(12);
        let rows = vec![
            Row::new(
                crate::row::RowKind::Validation,
                "collision_parry",
                "verdict_agreement_rate",
                "engine_vs_parry2d",
                0.0,
                1.0,
                1.0,
                0.0,
                Comparison::AtLeast,
                long.clone(),
            ),
            Row::new(
                crate::row::RowKind::Validation,
                "collision_parry",
                "max_depth_difference",
                "engine_vs_parry2d",
                0.0,
                2e-3,
                0.0,
                1e-9,
                Comparison::AtMost,
                "the | pipe stays out of the table",
            ),
        ];
        let report = crate::cases::CaseReport {
            rows,
            notes: vec![long],
            figures: vec![CaseFigure {
                file: "chart.svg".into(),
                alt: "a chart".into(),
                caption: "what to read in it".into(),
                panels: vec![Chart {
                    title: "t".into(),
                    series: vec![Series::new(
                        "s",
                        crate::plots::palette(0),
                        vec![(0.0, 0.0), (1.0, 1.0)],
                    )],
                    ..Chart::default()
                }],
                columns: 1,
                panel_size: (200, 150),
            }],
            ..crate::cases::CaseReport::default()
        };
        let record = report.record("collision_parry", Some(dir.path())).unwrap();
        write(dir.path(), &[record], None, "Provenance.").unwrap();
        dir
    }

    #[test]
    fn the_summary_links_a_page_per_case_and_every_link_resolves() {
        let dir = written();
        let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
        assert!(
            readme.contains("| [`collision_parry`](cases/collision_parry.md) | 2 | **1** |"),
            "{readme}"
        );
        assert!(
            readme.contains("`verdict_agreement_rate` engine_vs_parry2d:"),
            "{readme}"
        );
        let page = std::fs::read_to_string(dir.path().join("cases/collision_parry.md")).unwrap();
        assert!(page.contains("**1 of 2 rows pass.**"), "{page}");
        assert!(page.contains("![a chart](../chart.svg)"), "{page}");
        assert!(page.contains("| **NO** | R2 |"), "{page}");
        assert!(dir.path().join("chart.svg").is_file());
        let broken = crate::links::broken_links(dir.path()).unwrap();
        assert!(broken.is_empty(), "{broken:?}");
    }

    #[test]
    fn prose_lines_stay_short_and_the_json_gains_the_variant() {
        let dir = written();
        for page in ["README.md", "cases/collision_parry.md"] {
            let text = std::fs::read_to_string(dir.path().join(page)).unwrap();
            for line in text.lines().filter(|l| !l.starts_with('|')) {
                assert!(
                    line.chars().count() <= format::TEXT_WIDTH,
                    "{page}: {} characters: {line}",
                    line.chars().count()
                );
            }
        }
        let json = std::fs::read_to_string(dir.path().join("summary.json")).unwrap();
        let rows: serde_json::Value = serde_json::from_str(&json).unwrap();
        let first = &rows[0];
        for field in [
            "case",
            "check",
            "method",
            "variant",
            "dt",
            "value",
            "expected",
            "tolerance",
            "pass",
            "comparison",
            "reason",
        ] {
            assert!(first.get(field).is_some(), "summary.json lacks {field}");
        }
    }
}
