//! How numbers and text look in the report and on the console: values to
//! ten significant digits, steps compactly, the pass condition of a row in
//! words, prose wrapped to a readable width, Markdown table cells escaped.

use crate::row::{Comparison, Row};

/// Width (characters) at which prose is wrapped in the Markdown pages and
/// on the console.
pub const TEXT_WIDTH: usize = 100;

/// Formats a number for tables: 10 significant digits, or scientific when
/// very large or small.
pub fn fmt_num(v: f64) -> String {
    if v == 0.0 || v.is_nan() || v.is_infinite() {
        return format!("{v}");
    }
    let a = v.abs();
    if (1e-3..1e7).contains(&a) {
        let digits = (9 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.6e}")
    }
}

/// A row's step (s) for tables: as written when short (`0.2`, `0.0021`),
/// else three significant digits (`2.44e-5` for 0.0000244140625); `-` when
/// the row has none (NaN or 0: study rows, comparisons of shapes).
/// `summary.json` keeps every digit.
pub fn fmt_dt(dt: f64) -> String {
    if !dt.is_finite() || dt <= 0.0 {
        return "-".into();
    }
    let plain = dt.to_string();
    if plain.len() <= 7 {
        return plain;
    }
    let sci = format!("{dt:.2e}");
    match sci.split_once('e') {
        Some((mantissa, exponent)) => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exponent}")
        }
        None => sci,
    }
}

/// The condition a row's value must meet, next to its expected value:
/// `± tol`, `≥ expected − tol` or `≤ expected + tol`.
pub fn condition(row: &Row) -> String {
    let tol = fmt_num(row.tolerance);
    match row.comparison {
        Comparison::Within => format!("± {tol}"),
        Comparison::AtLeast => format!("≥ expected − {tol}"),
        Comparison::AtMost => format!("≤ expected + {tol}"),
    }
}

/// Whether a row's verdict is not obvious from its numbers, so its reason
/// should be shown beside it: it failed, or its value lies more than 1 %
/// (of the expected value or of the tolerance, whichever is larger) from
/// what it is compared with — a method failing the way theory predicts, a
/// blow-up past a threshold, a reference engine's documented bias.
pub fn needs_reason(row: &Row) -> bool {
    let gap = (row.value - row.expected).abs();
    let close = gap <= 0.01 * row.expected.abs().max(row.tolerance);
    // A NaN gap is not close.
    !row.pass || !close
}

/// `text` as a Markdown table cell: `|` escaped, line breaks removed.
pub fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// `text` wrapped at [`TEXT_WIDTH`], its first line after `first` and the
/// others after `rest` (a list item: `"- "` and `"  "`). Words longer than
/// a line are kept whole.
pub fn wrap(text: &str, first: &str, rest: &str) -> String {
    let mut out = String::new();
    let mut line = String::from(first);
    let mut empty = true;
    for word in text.split_whitespace() {
        if !empty && line.chars().count() + 1 + word.chars().count() > TEXT_WIDTH {
            out.push_str(line.trim_end());
            out.push('\n');
            line = String::from(rest);
            empty = true;
        }
        if !empty {
            line.push(' ');
        }
        line.push_str(word);
        empty = false;
    }
    out.push_str(line.trim_end());
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(value: f64, expected: f64, tolerance: f64, comparison: Comparison) -> Row {
        Row::new(
            crate::row::RowKind::Validation,
            "c",
            "x",
            "rk4",
            0.1,
            value,
            expected,
            tolerance,
            comparison,
            "why",
        )
    }

    #[test]
    fn steps_are_compact() {
        assert_eq!(fmt_dt(0.2), "0.2");
        assert_eq!(fmt_dt(0.0021), "0.0021");
        assert_eq!(fmt_dt(0.0000244140625), "2.44e-5");
        assert_eq!(fmt_dt(0.00078125), "7.81e-4");
        assert_eq!(fmt_dt(0.025), "0.025");
        assert_eq!(fmt_dt(f64::NAN), "-");
        assert_eq!(fmt_dt(0.0), "-");
    }

    #[test]
    fn conditions_say_which_way() {
        assert_eq!(
            condition(&row(1.0, 1.0, 0.5, Comparison::Within)),
            "± 0.5000000000"
        );
        assert_eq!(
            condition(&row(5e19, 1e19, 0.0, Comparison::AtLeast)),
            "≥ expected − 0"
        );
        assert_eq!(
            condition(&row(0.0, 0.0, 1e-9, Comparison::AtMost)),
            "≤ expected + 1.000000e-9"
        );
    }

    #[test]
    fn a_reason_is_shown_where_the_numbers_look_wrong() {
        // Explicit Euler's x_end: 3.87e7 against 10.66, passing by theory.
        assert!(needs_reason(&row(
            3.87e7,
            10.66,
            3.87e7,
            Comparison::Within
        )));
        // A blow-up past its threshold.
        assert!(needs_reason(&row(5e19, 1e19, 0.0, Comparison::AtLeast)));
        // A failure, however close.
        assert!(needs_reason(&row(
            1.0,
            1.0 + 1e-9,
            1e-10,
            Comparison::Within
        )));
        // Close agreement: obvious.
        assert!(!needs_reason(&row(
            8.6527,
            8.6526,
            1e-3,
            Comparison::Within
        )));
        assert!(!needs_reason(&row(3e-15, 0.0, 1e-9, Comparison::AtMost)));
        // NaN never looks right.
        assert!(needs_reason(&row(f64::NAN, 0.0, 1.0, Comparison::Within)));
    }

    #[test]
    fn wrapping_keeps_every_word_and_the_width() {
        let text = "word ".repeat(60);
        let wrapped = wrap(&text, "- ", "  ");
        assert!(wrapped.lines().all(|l| l.chars().count() <= TEXT_WIDTH));
        assert_eq!(
            wrapped.split_whitespace().filter(|w| *w == "word").count(),
            60
        );
        assert!(wrapped.starts_with("- word"));
        assert!(wrapped.lines().skip(1).all(|l| l.starts_with("  word")));
    }

    #[test]
    fn cells_escape_pipes() {
        assert_eq!(cell("|x error|"), "\\|x error\\|");
    }
}
