//! Tables of rows: Markdown for the report pages (every row keyed to where
//! its tolerance comes from, listed under the table) and plain text for the
//! console (columns sized to their contents, the reason under the rows that
//! need one).

use super::format::{cell, condition, fmt_dt, fmt_num, needs_reason, wrap};
use crate::row::Row;
use std::fmt::Write as _;

/// The distinct reasons of `rows`, in order of first appearance, and each
/// row's index into them.
fn reason_keys(rows: &[&Row]) -> (Vec<String>, Vec<usize>) {
    let mut reasons: Vec<String> = Vec::new();
    let keys = rows
        .iter()
        .map(|r| match reasons.iter().position(|x| *x == r.reason) {
            Some(i) => i,
            None => {
                reasons.push(r.reason.clone());
                reasons.len() - 1
            }
        })
        .collect();
    (reasons, keys)
}

/// The Markdown table of `rows` (with a leading `case` column when asked,
/// a `variant` column when a row has one, and each row's kind of
/// evidence), then the list of the reasons its `why` column refers to.
pub fn markdown(rows: &[&Row], with_case: bool) -> String {
    if rows.is_empty() {
        return "No rows.\n".into();
    }
    let with_variant = rows.iter().any(|r| !r.variant.is_empty());
    let (reasons, keys) = reason_keys(rows);
    let mut header = Vec::new();
    if with_case {
        header.push("case");
    }
    header.push("check");
    if with_variant {
        header.push("variant");
    }
    header.extend([
        "method",
        "h (s)",
        "value",
        "expected",
        "condition",
        "kind",
        "pass",
        "why",
    ]);
    let mut out = format!("| {} |\n", header.join(" | "));
    out.push_str(&format!("|{}\n", "---|".repeat(header.len())));
    for (r, key) in rows.iter().zip(keys) {
        let mut cells = Vec::new();
        if with_case {
            cells.push(cell(&r.case));
        }
        cells.push(cell(&r.check));
        if with_variant {
            cells.push(cell(&r.variant));
        }
        cells.extend([
            cell(&r.method),
            fmt_dt(r.dt),
            fmt_num(r.value),
            fmt_num(r.expected),
            condition(r),
            r.kind.id().to_string(),
            if r.pass { "yes" } else { "**NO**" }.to_string(),
            format!("R{}", key + 1),
        ]);
        let _ = writeln!(out, "| {} |", cells.join(" | "));
    }
    out.push_str("\nWhere each condition comes from (the `why` column):\n\n");
    for (i, reason) in reasons.iter().enumerate() {
        out.push_str(&wrap(reason, &format!("- **R{}**: ", i + 1), "  "));
    }
    out
}

/// The plain-text table printed on the console for `title`: columns as
/// wide as their contents (a `case` column when the rows come from several
/// cases); under each row whose verdict is not obvious from its numbers
/// (all rows when `all_reasons`), its reason, indented.
pub fn console(title: &str, rows: &[Row], all_reasons: bool) -> String {
    let with_variant = rows.iter().any(|r| !r.variant.is_empty());
    let with_case = rows.iter().any(|r| r.case != rows[0].case);
    let mut header = if with_case { vec!["case"] } else { vec![] };
    header.push("check");
    if with_variant {
        header.push("variant");
    }
    header.extend(["method", "dt (s)", "value", "expected", "condition", "pass"]);
    // Text columns are left-aligned, numbers right-aligned.
    let numeric: Vec<bool> = header
        .iter()
        .map(|h| matches!(*h, "dt (s)" | "value" | "expected"))
        .collect();
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let mut cells = if with_case {
                vec![r.case.clone()]
            } else {
                vec![]
            };
            cells.push(r.check.clone());
            if with_variant {
                cells.push(r.variant.clone());
            }
            cells.extend([
                r.method.clone(),
                fmt_dt(r.dt),
                fmt_num(r.value),
                fmt_num(r.expected),
                condition(r),
                if r.pass { "ok" } else { "FAIL" }.to_string(),
            ]);
            cells
        })
        .collect();
    let widths: Vec<usize> = (0..header.len())
        .map(|c| {
            table
                .iter()
                .map(|row| row[c].chars().count())
                .chain([header[c].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[String]| -> String {
        let padded: Vec<String> = cells
            .iter()
            .zip(&widths)
            .zip(&numeric)
            .map(|((text, &w), &right)| {
                if right {
                    format!("{text:>w$}")
                } else {
                    format!("{text:<w$}")
                }
            })
            .collect();
        padded.join("  ").trim_end().to_string()
    };
    let mut out = format!("== {title}\n");
    let header: Vec<String> = header.iter().map(|h| h.to_string()).collect();
    let _ = writeln!(out, "{}", line(&header));
    for (r, cells) in rows.iter().zip(&table) {
        let _ = writeln!(out, "{}", line(cells));
        if all_reasons || needs_reason(r) {
            out.push_str(&wrap(&r.reason, "    why: ", "         "));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::row::Comparison;

    fn rows() -> Vec<Row> {
        vec![
            Row::new(
                crate::row::RowKind::Validation,
                "spring",
                "x_end",
                "explicit_euler",
                0.2,
                3.870939e7,
                10.65557611,
                3.870938e7,
                Comparison::Within,
                "tolerance = the error linear stability theory predicts | M(h)^286",
            ),
            Row::new(
                crate::row::RowKind::Validation,
                "spring",
                "order",
                "velocity_verlet",
                0.0000244140625,
                1.999997481,
                2.0,
                0.1,
                Comparison::Within,
                "median of log2(e(h)/e(h/2))",
            )
            .with_variant("a rather long variant name"),
        ]
    }

    #[test]
    fn console_columns_line_up_and_odd_rows_carry_their_reason() {
        let text = console("spring", &rows(), false);
        let lines: Vec<&str> = text.lines().collect();
        // Title, header, row, its reason, row (obvious: no reason).
        assert_eq!(lines.len(), 5, "{text}");
        let column = |l: &str| l.find("method").or_else(|| l.find("explicit_euler"));
        assert_eq!(column(lines[1]), column(lines[2]), "{text}");
        assert_eq!(
            lines[1].find("method"),
            lines[4].find("velocity_verlet"),
            "{text}"
        );
        assert!(lines[3].starts_with("    why: tolerance"), "{text}");
        assert!(lines[4].contains("2.44e-5"), "{text}");
        assert!(console("spring", &rows(), true).contains("why: median"));
    }

    #[test]
    fn rows_of_several_cases_get_a_case_column() {
        let mut r = rows();
        r[1].case = "hoffman".into();
        let text = console("studies", &r, false);
        assert!(text.lines().nth(1).unwrap().starts_with("case "), "{text}");
        assert!(text.contains("\nhoffman "), "{text}");
    }

    #[test]
    fn markdown_keys_every_row_to_its_reason() {
        let r = rows();
        let refs: Vec<&Row> = r.iter().collect();
        let md = markdown(&refs, true);
        assert!(md.contains("| case | check | variant | method |"), "{md}");
        assert!(md.contains("| R1 |") && md.contains("| R2 |"), "{md}");
        assert!(md.contains("| validation | yes | R1 |"), "{md}");
        assert!(md.contains("- **R1**: tolerance"), "{md}");
        // The reason's `|` stays out of the table: it is below it.
        let table_lines = md.lines().take_while(|l| l.starts_with('|'));
        assert!(table_lines.into_iter().all(|l| !l.contains("M(h)")));
    }
}
