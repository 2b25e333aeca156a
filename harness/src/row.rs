//! One validation row: a measured value, what it is compared with, the
//! tolerance and why, and the verdict. Rows are what `reports/summary.json`
//! holds and what the harness's exit code is judged on.

use serde::{Deserialize, Serialize};

/// How `value` is judged against `expected`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Comparison {
    /// `|value − expected| ≤ tolerance`.
    Within,
    /// `value ≥ expected − tolerance` (e.g. a blow-up past a threshold).
    AtLeast,
    /// `value ≤ expected + tolerance` (e.g. an upper energy band).
    AtMost,
}

/// What kind of evidence a row is: what its `expected` and `tolerance`
/// come from. The report and the console count each kind, so "n rows pass"
/// never mixes a check against an independent reference with a check
/// against the code's own numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RowKind {
    /// Against an independent closed form or a high-precision reference
    /// (an exact solution, DOP853 at 1e-12, parry2d, exact arithmetic),
    /// with a tolerance derived from the method, the step or the
    /// reference's precision.
    Validation,
    /// A method failing the way stability theory predicts (growth,
    /// blow-up, the stability limit), checked against that prediction.
    PredictedFailure,
    /// Against the solver's own error estimate (step doubling): evidence
    /// that the error behaves as the method's order says, not that the
    /// value is right to a known bound.
    Consistency,
    /// Against constants recorded from the code itself (hashes, steps,
    /// snapshots): evidence that nothing changed, not that it is right.
    Regression,
    /// Against a bound chosen by hand (a figure quoted from docs/cases.md,
    /// another engine's behaviour, a margin), with its source in `reason`.
    Criterion,
}

impl RowKind {
    /// Every kind, in the order the report counts them.
    pub const ALL: [RowKind; 5] = [
        RowKind::Validation,
        RowKind::PredictedFailure,
        RowKind::Consistency,
        RowKind::Regression,
        RowKind::Criterion,
    ];

    /// The snake_case id written to `summary.json`.
    pub fn id(self) -> &'static str {
        match self {
            RowKind::Validation => "validation",
            RowKind::PredictedFailure => "predicted_failure",
            RowKind::Consistency => "consistency",
            RowKind::Regression => "regression",
            RowKind::Criterion => "criterion",
        }
    }

    /// One line saying what rows of this kind prove.
    pub fn meaning(self) -> &'static str {
        match self {
            RowKind::Validation => "against an independent closed form or high-precision reference",
            RowKind::PredictedFailure => "a method failing as stability theory predicts",
            RowKind::Consistency => "against the solver's own step-doubling error estimate",
            RowKind::Regression => "against constants recorded from the code (hashes, steps)",
            RowKind::Criterion => "against a bound chosen by hand (its source in the reason)",
        }
    }
}

/// The number of rows of each kind, in [`RowKind::ALL`]'s order, with the
/// number of them that pass.
pub fn count_kinds(rows: &[Row]) -> Vec<(RowKind, usize, usize)> {
    RowKind::ALL
        .iter()
        .map(|&k| {
            let of_kind = rows.iter().filter(|r| r.kind == k);
            let n = of_kind.clone().count();
            let passed = of_kind.filter(|r| r.pass).count();
            (k, n, passed)
        })
        .collect()
}

/// A validation row of `reports/summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Case id (`spring`, `projectile`, ...).
    pub case: String,
    /// What is checked (`x_end`, `landing_time`, ...).
    pub check: String,
    /// Method id.
    pub method: String,
    /// What kind of evidence the row is.
    pub kind: RowKind,
    /// What else tells this row from a row of the same case, check, method
    /// and step (e.g. the stability axis); empty when nothing does.
    pub variant: String,
    /// Step (s); for Dormand–Prince the output interval.
    pub dt: f64,
    /// What the engine produced.
    pub value: f64,
    /// What it is compared with.
    pub expected: f64,
    /// Allowed difference, in the unit of the value.
    pub tolerance: f64,
    /// The verdict.
    pub pass: bool,
    /// How the comparison is made.
    pub comparison: Comparison,
    /// Where `expected` and `tolerance` come from.
    pub reason: String,
}

impl Row {
    /// A row judged by `comparison`; the verdict is computed here. A NaN
    /// value never passes.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        kind: RowKind,
        case: &str,
        check: &str,
        method: &str,
        dt: f64,
        value: f64,
        expected: f64,
        tolerance: f64,
        comparison: Comparison,
        reason: impl Into<String>,
    ) -> Self {
        let pass = match comparison {
            Comparison::Within => (value - expected).abs() <= tolerance,
            Comparison::AtLeast => value >= expected - tolerance,
            Comparison::AtMost => value <= expected + tolerance,
        };
        Self {
            case: case.into(),
            check: check.into(),
            method: method.into(),
            kind,
            variant: String::new(),
            dt,
            value,
            expected,
            tolerance,
            pass,
            comparison,
            reason: reason.into(),
        }
    }
}

impl Row {
    /// The same row told apart from its neighbours by `variant`.
    pub fn with_variant(mut self, variant: impl Into<String>) -> Self {
        self.variant = variant.into();
        self
    }
}

/// Collects rows for one case and method at one step.
#[derive(Debug)]
pub struct RowSink<'a> {
    /// Case id.
    pub case: &'a str,
    /// Method id.
    pub method: &'a str,
    /// Step (s).
    pub dt: f64,
    /// Rows so far.
    pub rows: &'a mut Vec<Row>,
}

impl RowSink<'_> {
    /// Adds `|value − expected| ≤ tolerance`.
    pub fn within(
        &mut self,
        kind: RowKind,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        reason: impl Into<String>,
    ) {
        self.push(
            kind,
            check,
            value,
            expected,
            tolerance,
            Comparison::Within,
            reason,
        );
    }

    /// Adds `value ≥ expected − tolerance`.
    pub fn at_least(
        &mut self,
        kind: RowKind,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        reason: impl Into<String>,
    ) {
        self.push(
            kind,
            check,
            value,
            expected,
            tolerance,
            Comparison::AtLeast,
            reason,
        );
    }

    /// Adds `value ≤ expected + tolerance`.
    pub fn at_most(
        &mut self,
        kind: RowKind,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        reason: impl Into<String>,
    ) {
        self.push(
            kind,
            check,
            value,
            expected,
            tolerance,
            Comparison::AtMost,
            reason,
        );
    }

    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        kind: RowKind,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        comparison: Comparison,
        reason: impl Into<String>,
    ) {
        self.rows.push(Row::new(
            kind,
            self.case,
            check,
            self.method,
            self.dt,
            value,
            expected,
            tolerance,
            comparison,
            reason,
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_are_counted_with_their_verdicts_and_serialised_in_snake_case() {
        let row = |kind, value: f64| {
            Row::new(
                kind,
                "c",
                "x",
                "m",
                0.1,
                value,
                0.0,
                1.0,
                Comparison::Within,
                "r",
            )
        };
        let rows = vec![
            row(RowKind::Validation, 0.5),
            row(RowKind::Validation, 2.0),
            row(RowKind::PredictedFailure, 0.0),
        ];
        let counts = count_kinds(&rows);
        assert_eq!(counts[0], (RowKind::Validation, 2, 1));
        assert_eq!(counts[1], (RowKind::PredictedFailure, 1, 1));
        assert!(counts[2..].iter().all(|&(_, n, p)| n == 0 && p == 0));
        let json = serde_json::to_string(&rows[2]).unwrap();
        assert!(json.contains(r#""kind":"predicted_failure""#), "{json}");
        for kind in RowKind::ALL {
            let json = serde_json::to_string(&kind).unwrap();
            assert_eq!(json, format!("\"{}\"", kind.id()));
        }
    }
}
